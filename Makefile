# windflutter — two commands on a fresh machine: `make run` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python
PIP     = $(VENV)/bin/pip
STAMP   = $(VENV)/.installed
OUT    ?= out

.PHONY: run test test-fast test-slow test-nastran bench clean venv

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip
	$(PIP) install --quiet -e '.[test,fast,dist]'
	touch $(STAMP)

venv: $(STAMP)

## make run: set up and run the main analysis on the bundled NREL 5 MW turbine
run: $(STAMP)
	$(VENV)/bin/windflutter run nrel5mw -o $(OUT)/nrel5mw

## make test: set up and run the test suite (slow end-to-end runs use reduced models)
test: $(STAMP)
	$(PY) -m pytest -q -m "not slow and not nastran" $(PYTEST_ARGS)

## the long end-to-end runs at full model size
test-slow: $(STAMP)
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

bench: $(STAMP)
	$(PY) benchmarks/run_all.py

clean:
	rm -rf $(VENV) $(VENV_NASTRAN) $(OUT) .pytest_cache
