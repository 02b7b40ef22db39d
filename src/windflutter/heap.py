"""Keep freed memory in the process: glibc's ``malloc`` thresholds for the long shell runs (bottom
layer: the standard library only).

An operating point of a shell model allocates and frees arrays of tens to hundreds of megabytes
(sparse factors, blocks of 40-70 columns on 26,000 DOF, the 1084-state eigen-solve).  By default
glibc serves each from a fresh ``mmap`` and returns it at ``free``, so every point maps, zeroes and
unmaps the same memory again: on the NREL 5 MW shell map 1.7 M minor page faults for two wind
speeds and 9 % of the CPU in the kernel.  :func:`keep_freed_memory` raises the ``mmap`` threshold
to 512 MiB and the heap's trim threshold to 2 GiB (``mallopt``), so those arrays come from the heap
and stay there for the next point.  Measured (docs/notes/performance_rounds.md, the 12th session's
round): the NREL 5 MW shell at 10 and 22 m/s 86.4 s CPU against 91.5 s (page faults 216 k against
1.67 M, peak RSS 2.02 GB against 1.91 GB); the IEA 22 MW shell Campbell 103 s against 109 s in one
process, peak memory 2.71 / 3.05 GB against 2.73 / 3.04 GB.  Results are bit for bit the same.

Applied by the command line (:func:`windflutter.cli.main`) and in every worker process
(:mod:`windflutter.parallel`); not by ``import windflutter`` (a library should not change the
allocator of the program that imports it).  Left alone where it does not apply: not glibc (macOS,
Windows, musl), or the user set ``MALLOC_MMAP_THRESHOLD_`` / ``MALLOC_TRIM_THRESHOLD_`` (glibc's own
environment tunables, which then decide).
"""

from __future__ import annotations

import ctypes
import functools
import os
import sys

__all__ = ["MMAP_THRESHOLD", "TRIM_THRESHOLD", "keep_freed_memory"]

#: allocations from this size (bytes) are served by ``mmap`` and unmapped at ``free``
MMAP_THRESHOLD = 512 * 2**20
#: free memory at the top of the heap beyond this (bytes) is returned to the system
TRIM_THRESHOLD = 2**31 - 1
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3  # glibc's malloc.h
_USER_TUNABLES = ("MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "GLIBC_TUNABLES")


@functools.cache
def keep_freed_memory() -> bool:
    """Set the thresholds once per process; True where they are (now or before) set."""
    if not sys.platform.startswith("linux") or any(os.environ.get(v) for v in _USER_TUNABLES):
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):  # no C library symbols, or not glibc (musl has no mallopt)
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD) == 1 and mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD) == 1
