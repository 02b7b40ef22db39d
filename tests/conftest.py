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

from windflutter import threads
from windflutter.errors import InputError


def pytest_report_header(config):
    try:
        n = threads.configured_threads()
    except InputError:
        n = threads.DEFAULT_THREADS  # what the policy applied, with a warning
    counts = sorted(set(threads.blas_thread_counts().values()))
    setting = "unset" if not os.environ.get(threads.ENV_VAR) else repr(os.environ[threads.ENV_VAR])
    return (f"windflutter BLAS threads: {'library default' if n is None else n} per process "
            f"({threads.ENV_VAR} {setting}; loaded BLAS libraries now at {counts or 'none loaded yet'})")
