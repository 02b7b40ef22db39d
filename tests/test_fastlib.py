"""kvxopt's bundled OpenBLAS loaded on the processor's kernels (``windflutter.fastlib``).

The reference is OpenBLAS's own report of the kernels it loaded (``threadpoolctl``'s
``architecture``), read in a fresh interpreter where kvxopt is loaded for the first time.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from windflutter import fastlib

AVX512 = {"sse4_2", "avx", "avx2", "fma", "avx512f", "avx512cd", "avx512bw", "avx512dq", "avx512vl"}


def test_kernel_family_by_instruction_sets():
    assert fastlib.coretype_for(AVX512) == "SkylakeX"
    assert fastlib.coretype_for(AVX512 - {"avx512bw"}) == "Haswell"  # AVX-512F alone (Knights Landing): not SkylakeX
    assert fastlib.coretype_for({"sse4_2", "avx", "avx2", "fma"}) == "Haswell"
    assert fastlib.coretype_for({"sse4_2", "avx", "avx2"}) is None  # no FMA: OpenBLAS's own choice
    assert fastlib.coretype_for(set()) is None


def test_cpu_flags_read_from_the_first_processor(tmp_path, monkeypatch):
    monkeypatch.setattr(fastlib.platform, "system", lambda: "Linux")
    monkeypatch.setattr(fastlib.platform, "machine", lambda: "x86_64")
    info = tmp_path / "cpuinfo"
    info.write_text("processor\t: 0\nmodel\t\t: 207\nflags\t\t: fpu sse4_2 avx2 fma\n\n"
                    "processor\t: 1\nflags\t\t: fpu\n")
    assert fastlib.cpu_flags(str(info)) == {"fpu", "sse4_2", "avx2", "fma"}
    assert fastlib.cpu_flags(str(tmp_path / "missing")) == frozenset()
    monkeypatch.setattr(fastlib.platform, "machine", lambda: "aarch64")
    assert fastlib.cpu_flags(str(info)) == frozenset()  # another architecture: OpenBLAS detects


def test_the_variable_is_set_only_while_kvxopt_loads_and_a_users_own_is_kept(monkeypatch):
    monkeypatch.setattr(fastlib, "cpu_flags", lambda: frozenset(AVX512))
    monkeypatch.delenv(fastlib.CORETYPE_VAR, raising=False)
    with fastlib._coretype_scope() as core:
        assert core == os.environ[fastlib.CORETYPE_VAR] == "SkylakeX"
    assert fastlib.CORETYPE_VAR not in os.environ
    monkeypatch.setenv(fastlib.CORETYPE_VAR, "Sandybridge")
    with fastlib._coretype_scope() as core:
        assert core is None and os.environ[fastlib.CORETYPE_VAR] == "Sandybridge"
    assert os.environ[fastlib.CORETYPE_VAR] == "Sandybridge"


_PROBE = """
import json, os
from windflutter.fastlib import import_kvxopt
import threadpoolctl
kvx = import_kvxopt()
libs = [d for d in threadpoolctl.threadpool_info() if 'kvxopt' in d.get('filepath', '')
        and d.get('internal_api') == 'openblas']
print(json.dumps({'loaded': kvx is not None, 'arch': [d.get('architecture') for d in libs],
                  'env': os.environ.get('OPENBLAS_CORETYPE')}))
"""


def _probe(env_extra: dict[str, str]) -> dict:
    env = {k: v for k, v in os.environ.items() if k != fastlib.CORETYPE_VAR}
    env.update(env_extra)
    out = subprocess.run([sys.executable, "-c", _PROBE], env=env, capture_output=True, text=True, timeout=120,
                         check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_kvxopts_openblas_runs_the_processors_kernels():
    """In a fresh process: kvxopt's OpenBLAS reports the family :func:`coretype_for` chose (on a
    processor its 0.3.15 does not know it reports ``Prescott`` without this), the variable is gone
    afterwards, and a user's own ``OPENBLAS_CORETYPE`` wins."""
    pytest.importorskip("kvxopt")
    core = fastlib.coretype_for(fastlib.cpu_flags())
    if core is None:
        pytest.skip("no AVX2/FMA flags readable here: OpenBLAS's own detection is used")
    seen = _probe({})
    if not seen["arch"]:
        pytest.skip("kvxopt here does not bundle an OpenBLAS that threadpoolctl can read")
    assert seen["loaded"] and seen["env"] is None
    assert set(seen["arch"]) == {core}
    assert set(_probe({fastlib.CORETYPE_VAR: "Haswell"})["arch"]) == {"Haswell"}


def _spd(n: int, seed: int):
    """A sparse SPD matrix (a 2D Laplacian-like band plus a random symmetric coupling and a shift)."""
    import numpy as np
    import scipy.sparse as sp

    rng = np.random.default_rng(seed)
    A = sp.random(n, n, density=8.0 / n, random_state=rng)
    A = A + A.T + sp.diags(np.full(n, 20.0)) + sp.diags(np.full(n - 1, -1.0), 1) + sp.diags(np.full(n - 1, -1.0), -1)
    return sp.csc_matrix(A)


def test_cholmod_block_solve_against_scipy_and_kvxopt():
    """CHOLMOD's one-call block solve on kvxopt's factor: ``A X = B`` against SciPy's LU solve (a
    second implementation sharing nothing: 1e-12 of ``X``) and kvxopt's own column solves (the same
    algorithm: to round-off, measured bit for bit); through ``SPDFactor`` the same."""
    import numpy as np
    import scipy.sparse.linalg as spla

    from windflutter.structure.linalg import SPDFactor

    if fastlib.import_kvxopt() is None or fastlib._cholmod_library() is None:
        pytest.skip("kvxopt's CHOLMOD is not available here")
    A = _spd(800, 1)
    B = np.random.default_rng(2).standard_normal((800, 7))
    f = SPDFactor(A, backend="cholmod")
    X = fastlib.cholmod_block_solve(f._F, B)
    assert X is not None and X.shape == B.shape and X.flags.owndata
    ref = spla.splu(A).solve(B)
    assert np.abs(X - ref).max() <= 1e-12 * np.abs(ref).max()
    cols = np.column_stack([f.solve(B[:, j]) for j in range(B.shape[1])])
    assert np.abs(X - cols).max() <= 1e-14 * np.abs(cols).max()
    assert np.array_equal(f.solve(B), X)
    assert np.array_equal(fastlib.cholmod_block_solve(f._F, np.ascontiguousarray(B)), X)  # C order taken too


def test_cholmod_block_solve_declines_what_is_not_a_kvxopt_factor():
    """Anything but kvxopt's real symmetric factor capsule gives None (the caller's fallback), never
    a call into CHOLMOD with it."""
    import numpy as np

    B = np.ones((5, 2))
    assert fastlib.cholmod_block_solve(object(), B) is None
    assert fastlib.cholmod_block_solve(None, B) is None
