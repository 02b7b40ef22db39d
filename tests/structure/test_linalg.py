"""Both SPD factorisation backends (CHOLMOD via optional kvxopt, SuperLU fallback)."""

import numpy as np
import pytest
from shellmodels import iso, tube

from windflutter.structure import assemble
from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor

BACKENDS = ["superlu"]
try:
    import kvxopt  # noqa: F401

    BACKENDS.append("cholmod")
except ImportError:  # pragma: no cover - the optional extra is not installed
    pass


def _tube(spc: bool):
    fe, idx = tube(12, 6, 0.25, 1.5, iso(210e9, 0.3, 7850.0, 0.005))
    if spc:
        fe.spc = {int(k): (0, 1, 2, 3, 4, 5) for k in idx[0]}
    return assemble(fe, check=False)


@pytest.mark.parametrize("backend", BACKENDS)
def test_spd_factor_solves_and_traces_pivots(backend):
    st = _tube(spc=True)
    K = st.Kr.tocsc()
    f = SPDFactor(K, backend=backend)
    assert f.backend == backend
    b = np.random.default_rng(0).standard_normal((K.shape[0], 2))
    x = f.solve(b)
    assert np.abs(K @ x - b).max() < 1e-8 * np.abs(b).max()
    assert sorted(f.pivot_dofs) == list(range(K.shape[0]))  # a permutation
    ratio = K.diagonal()[f.pivot_dofs] / f.pivots
    assert 1.0 <= ratio.max() < 1e8  # constrained elastic tube: far below the 1e10 threshold


@pytest.mark.parametrize("backend", BACKENDS)
def test_spd_factor_flags_free_structure(backend):
    st = _tube(spc=False)
    K = st.Kr.tocsc()
    try:
        f = SPDFactor(K, backend=backend)
    except NotPositiveDefinite:
        return
    ratio = K.diagonal()[f.pivot_dofs] / f.pivots
    assert ratio.max() > 1e10 or np.any(f.pivots <= 0)
