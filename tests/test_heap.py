"""windflutter.heap: freed arrays stay in the process for the next operating point (glibc only).

The check is the allocator's own account (``mallinfo2``): a 64 MB array is an ``mmap`` of its own
under glibc's defaults, returned to the system at ``free``; with :func:`keep_freed_memory` it comes
from the heap, and the heap keeps it after ``free`` for the next one.  Run in fresh interpreters, so the
setting of one case does not leak into the other or into the test session."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

SCRIPT = """
import ctypes, sys
import numpy as np
from windflutter.heap import keep_freed_memory

class Mallinfo2(ctypes.Structure):
    _fields_ = [(k, ctypes.c_size_t) for k in ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks",
                                               "fsmblks", "uordblks", "fordblks", "keepcost")]

info = ctypes.CDLL(None).mallinfo2
info.restype = Mallinfo2
applied = keep_freed_memory() if sys.argv[1] == "keep" else None
a = np.ones(8_000_000)  # 64 MB
mapped = info().hblkhd  # bytes in mmap'ed chunks
del a
print(applied, mapped, info().fordblks)  # and the free bytes the heap keeps
"""
SIZE = 64e6


def _run(mode: str, **env) -> tuple[str, int, int]:
    e = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_") and k != "GLIBC_TUNABLES"}
    out = subprocess.run([sys.executable, "-c", SCRIPT, mode], capture_output=True, text=True, check=True,
                         env={**e, **env}).stdout.split()
    return out[0], int(out[1]), int(out[2])


def _has_mallinfo2() -> bool:  # glibc 2.33 or later
    try:
        import ctypes
        return hasattr(ctypes.CDLL(None), "mallinfo2")
    except OSError:
        return False


glibc = pytest.mark.skipif(not sys.platform.startswith("linux") or not _has_mallinfo2(),
                           reason="glibc's mallopt")


@glibc
def test_freed_arrays_are_reused():
    applied, mapped, kept = _run("keep")
    _, mapped0, kept0 = _run("default")
    assert applied == "True"
    assert mapped0 >= SIZE and kept0 < SIZE  # the premise: by default mapped, and unmapped at free
    assert mapped < SIZE and kept >= SIZE, (mapped, kept)  # kept: from the heap, and kept there


@glibc
def test_user_tunables_decide():
    applied = _run("keep", MALLOC_TRIM_THRESHOLD_="131072")[0]
    assert applied == "False"
