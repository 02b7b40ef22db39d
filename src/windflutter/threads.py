"""One BLAS-thread policy for the whole process (bottom layer: imports only the standard library,
:mod:`windflutter.errors` and, lazily, ``threadpoolctl``).

NumPy and SciPy bundle a multi-threaded OpenBLAS (two copies: one in ``numpy.libs``, one in
``scipy.libs``). On a machine whose cores are already busy, its spin-waiting threads compete with
the other work: measured on a 2-core machine, the test suite took 756 s with OpenBLAS's default
threads and 189 s with one thread, ``windflutter stability nrel5mw --wind-speeds 10`` 43.6 s
against 10.4 s with the same onsets to 1e-10 RPM (issue 13; ``docs/performance.md``, "The
biggest effect: BLAS threads on a busy machine").
windflutter's matrices are sparse or small and dense, so one thread per process loses nothing that
running operating points in parallel (``windflutter run --workers N``) does not win back.

The policy
----------
``WINDFLUTTER_BLAS_THREADS`` (environment variable) chooses the number of BLAS threads:

* unset or empty: **1** (:data:`DEFAULT_THREADS`);
* a positive integer ``N``: ``N`` threads;
* ``auto``: windflutter leaves BLAS alone (the library's own default, or whatever
  ``OPENBLAS_NUM_THREADS``/``OMP_NUM_THREADS``/``MKL_NUM_THREADS`` say).

:func:`apply_policy` applies it to the whole process in two ways, because a BLAS library reads
its thread count once, when it is loaded:

1. it sets the thread variables of :data:`BLAS_ENV_VARS` in ``os.environ``, so a BLAS library
   loaded later (SciPy's copy is loaded only with ``scipy.linalg``) and every child process
   (subprocesses, ``spawn`` workers) start with ``N`` threads;
2. it limits the BLAS libraries already loaded with ``threadpoolctl``.

``import windflutter`` applies it (the package ``__init__``), which is before windflutter's first
BLAS call, so the command line, the Python API and the test session all run under it; the CLI's
:func:`windflutter.cli.main` applies it again around each command (:func:`policy_scope`), so an
in-process call leaves the caller's process as it found it. A bad value gives one
:class:`~windflutter.errors.InputWarning` line and the default. To opt out, set
``WINDFLUTTER_BLAS_THREADS=auto`` (or a number) *before* importing windflutter.

Independently of the process policy, sparse factorizations (:mod:`windflutter.solve.linsolve`),
dense modal solves and parallel workers (:mod:`windflutter.parallel`) limit BLAS to their own
``blas_threads`` argument (default 1) around each call with :func:`blas_limit`, so that serial
and parallel runs stay bit-identical whatever the process policy is.
"""

from __future__ import annotations

import contextlib
import os
import warnings
from collections.abc import Mapping
from typing import Any

from windflutter.errors import InputError, InputWarning

__all__ = [
    "ENV_VAR", "DEFAULT_THREADS", "BLAS_ENV_VARS", "configured_threads", "apply_policy", "policy_scope",
    "set_process_threads", "blas_limit", "blas_thread_counts",
]

#: The environment variable of the policy.
ENV_VAR = "WINDFLUTTER_BLAS_THREADS"
#: BLAS threads per process when :data:`ENV_VAR` is not set.
DEFAULT_THREADS = 1
#: The variables the common BLAS builds read when they are loaded (OpenBLAS with pthreads or
#: OpenMP, MKL, BLIS, Apple Accelerate).
BLAS_ENV_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
                 "VECLIB_MAXIMUM_THREADS")
_AUTO = "auto"
_EXPECTED = (f"a positive integer number of BLAS threads per process, or '{_AUTO}' (the BLAS library's "
             f"own default); unset means {DEFAULT_THREADS}")


def configured_threads(environ: Mapping[str, str] | None = None) -> int | None:
    """BLAS threads per process that the policy asks for: an int, or ``None`` for ``auto``.

    Parameters
    ----------
    environ
        Where to read :data:`ENV_VAR` (default ``os.environ``).

    Raises
    ------
    InputError
        The variable is neither empty, a positive integer nor ``auto``.
    """
    raw = (os.environ if environ is None else environ).get(ENV_VAR, "")
    text = raw.strip().lower()
    if not text:
        return DEFAULT_THREADS
    if text == _AUTO:
        return None
    if text.isdigit() and int(text) >= 1:
        return int(text)
    raise InputError(ENV_VAR, raw, _EXPECTED)


def set_process_threads(n_threads: int | None) -> None:
    """Run BLAS with ``n_threads`` threads in this process and in its future children.

    Sets every variable of :data:`BLAS_ENV_VARS` (for BLAS libraries loaded later and for child
    processes) and limits the loaded BLAS libraries with ``threadpoolctl``. ``None`` does
    nothing (the BLAS library's own default stays).
    """
    if n_threads is None:
        return
    n = int(n_threads)
    if n < 1:
        raise InputError("n_threads", n_threads, "a positive integer number of BLAS threads")
    _limit_now(n)  # persists: the returned limiter is not restored
    _CONTROLLER.clear()  # libraries may have been loaded since the cached controller was made


def _limit_now(n: int):
    """Set the variables of :data:`BLAS_ENV_VARS` to ``n`` and limit the loaded BLAS libraries;
    return the ``threadpoolctl`` limiter (it can restore the previous limits) or ``None``."""
    os.environ.update({var: str(n) for var in BLAS_ENV_VARS})
    ctl = _new_controller()
    return None if ctl is None else ctl.limit(limits=n, user_api="blas")


_WARNED: dict = {}  # the warnings registry of the bad-value warning (shown once per process)


def _checked_threads(strict: bool) -> int | None:
    """:func:`configured_threads`; with ``strict=False`` a bad value gives an
    :class:`~windflutter.errors.InputWarning` (once per process) and :data:`DEFAULT_THREADS`."""
    try:
        return configured_threads()
    except InputError as exc:
        if strict:
            raise
        # one line ("ENV_VAR:0: InputWarning: ..."), shown once however often the policy is applied
        warnings.warn_explicit(f"{exc}; using {DEFAULT_THREADS}", InputWarning, filename=ENV_VAR, lineno=0,
                               module=__name__, registry=_WARNED)
        return DEFAULT_THREADS


def apply_policy(*, strict: bool = False) -> int | None:
    """Apply the process-wide BLAS-thread policy of :data:`ENV_VAR`; return the thread count
    (``None``: ``auto``, nothing changed).

    Parameters
    ----------
    strict
        ``True``: a bad :data:`ENV_VAR` raises :class:`InputError`. ``False`` (the default, used
        at import time, where an exception would break every ``import windflutter``): an
        :class:`~windflutter.errors.InputWarning` and :data:`DEFAULT_THREADS`. The thread count
        changes how fast, not what is computed (up to round-off), so a bad value is not worth
        refusing to run.
    """
    n = _checked_threads(strict)
    set_process_threads(n)
    return n


@contextlib.contextmanager
def policy_scope(*, strict: bool = False):
    """Apply the policy of :data:`ENV_VAR` for a ``with`` block and undo it afterwards (the BLAS
    limits and the variables of :data:`BLAS_ENV_VARS`): the CLI's :func:`~windflutter.cli.main`
    runs every command in one, so an in-process call leaves the caller's process as it was.

    Yields
    ------
    int or None
        The thread count applied (``None``: ``auto``).

    Raises
    ------
    InputError
        With ``strict=True``, a bad :data:`ENV_VAR`, before anything is changed (else as
        :func:`apply_policy`).
    """
    n = _checked_threads(strict)
    saved = {var: os.environ.get(var) for var in BLAS_ENV_VARS}
    limiter = None if n is None else _limit_now(n)
    try:
        yield n
    finally:
        if limiter is not None:
            limiter.restore_original_limits()
        for var, value in saved.items():
            if value is None:
                os.environ.pop(var, None)
            else:
                os.environ[var] = value


# --- scoped limits ------------------------------------------------------------------------
_CONTROLLER: dict[str, Any] = {}


def _new_controller():
    try:
        from threadpoolctl import ThreadpoolController
    except ImportError:  # pragma: no cover - threadpoolctl is a dependency
        return None
    return ThreadpoolController()


def _controller():
    """One cached ``threadpoolctl`` controller (making one scans the loaded libraries, ~3 ms;
    reusing it makes a limit ~20 us, cheap enough around every solve). Rebuilt while it has no
    BLAS library yet (made before NumPy was loaded)."""
    ctl = _CONTROLLER.get("blas")
    if ctl is None or not ctl.select(user_api="blas").lib_controllers:
        ctl = _new_controller()
        if ctl is None:  # pragma: no cover - threadpoolctl is a dependency
            return None
        _CONTROLLER["blas"] = ctl
    return ctl


def blas_limit(n_threads: int | None):
    """Context manager limiting BLAS to ``n_threads`` threads (no-op for ``None``).

    Examples
    --------
    >>> import numpy as np
    >>> with blas_limit(1):
    ...     x = np.linalg.solve(np.eye(3), np.ones(3))
    """
    if n_threads is None:
        return contextlib.nullcontext()
    ctl = _controller()
    if ctl is None:  # pragma: no cover - threadpoolctl is a dependency
        return contextlib.nullcontext()
    return ctl.limit(limits=int(n_threads), user_api="blas")


def blas_thread_counts() -> dict[str, int]:
    """Threads of every loaded BLAS library now: ``{library file: threads}`` (for diagnostics
    and tests)."""
    try:
        from threadpoolctl import threadpool_info
    except ImportError:  # pragma: no cover - threadpoolctl is a dependency
        return {}
    return {d["filepath"]: int(d["num_threads"]) for d in threadpool_info() if d.get("user_api") == "blas"}
