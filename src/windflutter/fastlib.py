"""The optional fast extra (``kvxopt``: CHOLMOD, UMFPACK, AMD), loaded with BLAS kernels its bundled
OpenBLAS would not pick, and CHOLMOD's block solve on its factors (bottom layer: imports only the
standard library, and NumPy inside the block solve).

Why
---
kvxopt 1.3.3 bundles its own OpenBLAS, 0.3.15 (2021), beside NumPy's and SciPy's.  OpenBLAS picks
its kernels once, when it is loaded, from the processor's model number, and 0.3.15 does not know
the processors released after it: on a Xeon of model 207 (2023, AVX-512) it falls back to its
generic ``Prescott`` kernels (SSE3), while NumPy's OpenBLAS 0.3.31 on the same machine picks
``SkylakeX``.  CHOLMOD's supernodal factorizations and block solves run on those kernels: measured
on the NREL 5 MW shell blade (one wind speed, 34 factorizations and 31 block solves, one process),
0.39 s a factorization with ``Prescott`` against 0.15 s with ``SkylakeX``, and 0.36 against 0.24 s
a block solve; the whole 10 m/s sweep 72 s against 57 s ([performance_rounds.md](../../docs/notes/
performance_rounds.md) §25).

What it does
------------
:func:`import_kvxopt` imports kvxopt with ``OPENBLAS_CORETYPE`` (OpenBLAS's own variable, read at
load) set to the kernel family the processor's instruction sets allow -- ``SkylakeX`` with the
AVX-512 subsets those kernels use, ``Haswell`` with AVX2 and FMA, nothing otherwise -- and then
restores the variable, so that only kvxopt's OpenBLAS is affected (NumPy's and SciPy's, loaded
before or after it, detect for themselves).  A user's own ``OPENBLAS_CORETYPE`` is left alone, and so is
every processor whose flags cannot be read (not Linux, not x86-64): there OpenBLAS detects as usual.
The kernels change how fast, not what is computed (up to round-off).

Block solves
------------
kvxopt solves a block of right-hand sides column by column (its dense ``cholmod.solve``) or through
CHOLMOD's sparse right-hand-side solve (``cholmod.spsolve``), each streaming the whole factor once
per column or few columns: 40 columns on the NREL 5 MW shell blade (26k DOF, 5.8 M factor entries)
took 0.26 s.  CHOLMOD's own ``cholmod_l_solve`` on a dense block runs the supernodal triangular
solves with level-3 BLAS over all columns at once: 0.07 s for the same 40, the same numbers to the
last bit.  No wheel on PyPI exposes it for a factor that kvxopt made (scikit-sparse: no wheels;
cholespy: its own factor on the reference BLAS), so :func:`cholmod_block_solve` calls it through
``ctypes`` in the CHOLMOD library kvxopt itself loads, on kvxopt's factor (its capsule), with a
``cholmod_common`` of its own.  CHOLMOD checks the factor's integer and numeric types against the
call; anything unexpected (another kvxopt build, another capsule, no CHOLMOD library mapped) makes it
return ``None`` and the caller falls back to kvxopt's solve.
"""

from __future__ import annotations

import atexit
import contextlib
import ctypes
import functools
import os
import platform
from collections.abc import Iterable

__all__ = ["CORETYPE_VAR", "coretype_for", "cpu_flags", "import_kvxopt", "cholmod_block_solve"]

#: OpenBLAS's variable naming the kernel family to use instead of its own detection.
CORETYPE_VAR = "OPENBLAS_CORETYPE"
#: Kernel families by the instruction sets they need, best first (names as OpenBLAS spells them).
_FAMILIES: tuple[tuple[str, frozenset[str]], ...] = (
    ("SkylakeX", frozenset({"avx512f", "avx512cd", "avx512bw", "avx512dq", "avx512vl", "avx2", "fma"})),
    ("Haswell", frozenset({"avx2", "fma"})),
)
_CPUINFO = "/proc/cpuinfo"


def coretype_for(flags: Iterable[str]) -> str | None:
    """The OpenBLAS kernel family for a processor with these instruction-set ``flags`` (as
    ``/proc/cpuinfo`` lists them), or ``None`` (leave OpenBLAS's detection alone).

    >>> coretype_for({"sse4_2", "avx", "avx2", "fma"})
    'Haswell'
    >>> coretype_for({"sse4_2", "avx"}) is None
    True
    """
    have = set(flags)
    return next((name for name, need in _FAMILIES if need <= have), None)


def cpu_flags(path: str = _CPUINFO) -> frozenset[str]:
    """The instruction-set flags of the first processor in ``path`` (Linux's ``/proc/cpuinfo``);
    empty when they cannot be read (another system, another architecture)."""
    if platform.system() != "Linux" or platform.machine().lower() not in ("x86_64", "amd64"):
        return frozenset()
    try:
        with open(path, encoding="ascii", errors="replace") as fh:
            for line in fh:
                key, _, value = line.partition(":")
                if key.strip() == "flags":
                    return frozenset(value.split())
    except OSError:
        return frozenset()
    return frozenset()


@contextlib.contextmanager
def _coretype_scope():
    """``OPENBLAS_CORETYPE`` set for the block from :func:`cpu_flags` (unless the user set it)."""
    core = None if CORETYPE_VAR in os.environ else coretype_for(cpu_flags())
    if core is None:
        yield None
        return
    os.environ[CORETYPE_VAR] = core
    try:
        yield core
    finally:
        os.environ.pop(CORETYPE_VAR, None)


@functools.cache
def import_kvxopt():
    """kvxopt with the extension modules windflutter uses (``amd``, ``cholmod``, ``umfpack``)
    loaded, its OpenBLAS on the processor's kernels (module doc); ``None`` when kvxopt is not
    installed or does not load.  Every windflutter import of kvxopt goes through here: the first
    import loads its OpenBLAS, and only that one reads the variable -- so the answer is kept for the
    process (every factorization asks; reading the flags again would be 40 us of nothing)."""
    with _coretype_scope():
        try:
            import kvxopt
            from kvxopt import amd, cholmod, umfpack  # noqa: F401
        except Exception:  # noqa: BLE001 - not installed, or a build that does not load here
            return None
    return kvxopt


#: kvxopt's capsule name of a real symmetric CHOLMOD factor (``cholmod.symbolic`` / ``numeric``)
FACTOR_CAPSULE = b"CHOLMOD SYM D FACTOR L"
_CHOLMOD_A, _CHOLMOD_REAL, _CHOLMOD_DOUBLE = 0, 1, 0  # sys A x = b; xtype real; dtype double
_COMMON_BYTES = 1 << 16  # room for a cholmod_common (about 2-3 kB in CHOLMOD 2-5)


class _Dense(ctypes.Structure):
    """CHOLMOD's ``cholmod_dense`` (the same layout in CHOLMOD 2 to 5)."""

    _fields_ = [("nrow", ctypes.c_size_t), ("ncol", ctypes.c_size_t), ("nzmax", ctypes.c_size_t),
                ("d", ctypes.c_size_t), ("x", ctypes.c_void_p), ("z", ctypes.c_void_p),
                ("xtype", ctypes.c_int), ("dtype", ctypes.c_int)]


def _loaded_library(stem: str) -> str | None:
    """The path of the shared library ``stem*`` this process has loaded (Linux: /proc/self/maps)."""
    try:
        with open("/proc/self/maps", encoding="ascii", errors="replace") as fh:
            for line in fh:
                path = line.rsplit(" ", 1)[-1].strip()
                if os.path.basename(path).startswith(stem):
                    return path
    except OSError:
        return None
    return None


@functools.cache
def _cholmod_library():
    """``(library, common)``: the CHOLMOD that kvxopt's ``cholmod`` module loaded, with a started
    ``cholmod_common`` of windflutter's (finished at exit), or None when it cannot be had."""
    if import_kvxopt() is None or platform.system() != "Linux":
        return None
    path = _loaded_library("libcholmod")  # kvxopt's cholmod module is loaded: its CHOLMOD is mapped, unless
    if path is None:                      # linked into the module (then no other copy may take its factors)
        return None
    try:
        lib = ctypes.CDLL(path)
        version = (ctypes.c_int * 3)()
        lib.cholmod_l_version.argtypes = [ctypes.c_void_p]
        if not 2 <= lib.cholmod_l_version(version) // 1000 <= 5:  # CHOLMOD's major * 1000 + minor
            return None
        lib.cholmod_l_start.argtypes = [ctypes.c_void_p]
        lib.cholmod_l_finish.argtypes = [ctypes.c_void_p]
        lib.cholmod_l_solve.restype = ctypes.POINTER(_Dense)
        lib.cholmod_l_solve.argtypes = [ctypes.c_int, ctypes.c_void_p, ctypes.POINTER(_Dense), ctypes.c_void_p]
        lib.cholmod_l_free_dense.argtypes = [ctypes.POINTER(ctypes.POINTER(_Dense)), ctypes.c_void_p]
        common = ctypes.create_string_buffer(_COMMON_BYTES)
        if lib.cholmod_l_start(common) != 1:
            return None
    except (OSError, AttributeError, TypeError):  # no such library or symbol
        return None
    atexit.register(lib.cholmod_l_finish, common)
    return lib, common


@functools.cache
def _capsule_api():
    """``(PyCapsule_GetName, PyCapsule_GetPointer)`` as prototypes of their own (setting the types on
    ``ctypes.pythonapi``'s shared function objects would change them for every other user)."""
    api = ctypes.pythonapi
    name = ctypes.PYFUNCTYPE(ctypes.c_char_p, ctypes.py_object)(("PyCapsule_GetName", api))
    get = ctypes.PYFUNCTYPE(ctypes.c_void_p, ctypes.py_object, ctypes.c_char_p)(("PyCapsule_GetPointer", api))
    return name, get


def _factor_pointer(factor) -> int | None:
    """The ``cholmod_factor *`` in kvxopt's factor capsule, or None for anything else."""
    if type(factor).__name__ != "PyCapsule":
        return None
    name, get = _capsule_api()
    if name(factor) != FACTOR_CAPSULE:
        return None
    return get(factor, FACTOR_CAPSULE)


def cholmod_block_solve(factor, b):
    """``A^-1 B`` for the (n, k) real block ``b`` (a NumPy array) with kvxopt's CHOLMOD ``factor`` of
    ``A`` in one ``cholmod_l_solve`` call (module doc, "Block solves"); ``None`` when that call is not
    available here or fails (the caller solves another way)."""
    import numpy as np

    found = _cholmod_library()
    ptr = _factor_pointer(factor) if found is not None else None
    if ptr is None:
        return None
    lib, common = found
    B = np.asfortranarray(b, dtype=float)
    if B.ndim != 2 or not B.size:
        return None
    n, k = B.shape
    dense = _Dense(n, k, n * k, n, B.ctypes.data, None, _CHOLMOD_REAL, _CHOLMOD_DOUBLE)
    X = lib.cholmod_l_solve(_CHOLMOD_A, ptr, ctypes.byref(dense), common)
    if not X:  # CHOLMOD refused (e.g. the factor's integer type is not this call's)
        return None
    try:
        x = X.contents
        if (x.nrow, x.ncol, x.xtype) != (n, k, _CHOLMOD_REAL) or x.d < n:
            return None
        data = ctypes.cast(x.x, ctypes.POINTER(ctypes.c_double))
        return np.ctypeslib.as_array(data, shape=(k, x.d))[:, :n].T.copy()
    finally:
        lib.cholmod_l_free_dense(ctypes.byref(X), common)
