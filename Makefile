# windflutter — two commands on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python
PIP     = $(VENV)/bin/pip
OUT    ?= out
# what each target installs: `run` the package alone (its dependencies: NumPy, SciPy, matplotlib, xarray,
# netCDF4, pyfe3d, windIO, ...); `test` also the test, fast-solver and Dask extras, so that no test is skipped
STAMP_RUN  = $(VENV)/.installed-run
STAMP_TEST = $(VENV)/.installed-test

.PHONY: run test test-slow test-nastran bench clean venv

$(PY):
	$(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip

$(STAMP_RUN): pyproject.toml | $(PY)
	$(PIP) install --quiet -e .
	touch $@

$(STAMP_TEST): pyproject.toml | $(PY)
	$(PIP) install --quiet -e '.[test,fast,dist]'
	touch $@ $(STAMP_RUN)

venv: $(STAMP_RUN)

## make run: set up (the package only) and run the main analysis on the bundled NREL 5 MW turbine
run: $(STAMP_RUN)
	$(VENV)/bin/windflutter run nrel5mw -o $(OUT)/nrel5mw

## make test: set up with the test extras and run the test suite (slow end-to-end runs use reduced models)
## (two test processes, whole test files per process, one BLAS thread each: TEST_WORKERS=0 runs serially)
TEST_WORKERS ?= 2
test: $(STAMP_TEST)
	$(PY) -m pytest -q -m "not slow and not nastran" -n $(TEST_WORKERS) --dist loadfile $(PYTEST_ARGS)

## the long end-to-end runs at full model size
test-slow: $(STAMP_TEST)
	$(PY) -m pytest -q -m slow $(PYTEST_ARGS)

## NASTRAN BDF tests in a separate environment (pyNastran 1.4.1 pins numpy < 2)
## WINDFLUTTER_REQUIRE_NASTRAN=1 turns a missing pyNastran into an error instead of a skip
VENV_NASTRAN  = .venv-nastran
STAMP_NASTRAN = $(VENV_NASTRAN)/.installed
$(STAMP_NASTRAN): pyproject.toml
	test -x $(VENV_NASTRAN)/bin/python || $(PYTHON) -m venv $(VENV_NASTRAN)
	$(VENV_NASTRAN)/bin/pip install --quiet --upgrade pip
	$(VENV_NASTRAN)/bin/pip install --quiet -e '.[test,nastran]'
	$(VENV_NASTRAN)/bin/python -c "import pyNastran, numpy; assert int(numpy.__version__.split('.')[0]) < 2"
	touch $(STAMP_NASTRAN)

test-nastran: $(STAMP_NASTRAN)
	WINDFLUTTER_REQUIRE_NASTRAN=1 $(VENV_NASTRAN)/bin/python -m pytest -q -m nastran $(PYTEST_ARGS)

bench: $(STAMP_TEST)
	$(PY) benchmarks/run_all.py

clean:
	rm -rf $(VENV) $(VENV_NASTRAN) $(OUT) .pytest_cache
