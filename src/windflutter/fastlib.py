"""The optional fast extra (``kvxopt``: CHOLMOD, UMFPACK, AMD), loaded with BLAS kernels its bundled
OpenBLAS would not pick (bottom layer: imports only the standard library).

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
"""

from __future__ import annotations

import contextlib
import functools
import os
import platform
from collections.abc import Iterable

__all__ = ["CORETYPE_VAR", "coretype_for", "cpu_flags", "import_kvxopt"]

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
