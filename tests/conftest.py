"""Session-wide test set-up: the BLAS-thread policy (:mod:`windflutter.threads`).

pytest imports this file before any test module, so importing windflutter here puts the policy
in place before the tests load NumPy or SciPy (and limits a BLAS library that a plugin loaded
earlier): one BLAS thread per process unless
``WINDFLUTTER_BLAS_THREADS`` says otherwise (measured: 756 s with OpenBLAS's default threads
against 189 s with one, on 2 cores). Subprocesses started by the tests inherit it through the
thread variables the policy sets.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from windflutter import threads
from windflutter.errors import InputError

#: folders whose modules the spawned Dask workers must import (the toy analyser plug-in; the synthetic
#: test problems of benchmarks/testproblems.py, which are not part of the package)
WORKER_PATH = (Path(__file__).parent / "workflow", Path(__file__).parents[1] / "benchmarks")


def pytest_report_header(config):
    try:
        n = threads.configured_threads()
    except InputError:
        n = threads.DEFAULT_THREADS  # what the policy applied, with a warning
    counts = sorted(set(threads.blas_thread_counts().values()))
    setting = "unset" if not os.environ.get(threads.ENV_VAR) else repr(os.environ[threads.ENV_VAR])
    return (f"windflutter BLAS threads: {'library default' if n is None else n} per process "
            f"({threads.ENV_VAR} {setting}; loaded BLAS libraries now at {counts or 'none loaded yet'})")


@pytest.fixture(scope="session")
def nrel5mw():
    """The bundled NREL 5 MW, read and validated once per session (about 0.5 s a read). The
    turbine dataclasses are frozen; tests that change one make a copy (``dataclasses.replace``)."""
    from windflutter.model import load_turbine

    return load_turbine("nrel5mw")


@pytest.fixture
def dask_cluster():
    """A Dask ``LocalCluster`` (2 worker processes, 1 thread each) for one test, spawned with
    :data:`WORKER_PATH` on ``PYTHONPATH`` so its workers can import the test plug-ins.

    Function scope on purpose: an idle cluster costs about 0.18 CPU-seconds per second (its
    heartbeats, measured on the 2-core test machine), so a cluster kept for a module or the
    session costs more than starting one for each of the two tests that need it."""
    distributed = pytest.importorskip("distributed")
    old = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join([str(p) for p in WORKER_PATH] + ([old] if old else []))
    try:  # the workers are spawned now: the variable is put back at once
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None)
    finally:
        if old is None:
            os.environ.pop("PYTHONPATH", None)
        else:
            os.environ["PYTHONPATH"] = old
    with cluster:
        yield cluster
