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


@pytest.mark.parametrize("backend", BACKENDS)
def test_block_solve_equals_column_by_column(backend):
    """A block of right-hand sides (CHOLMOD: its sparse right-hand-side solve, which works on blocks of
    columns) gives what the columns solved one at a time give."""
    K = _tube(spc=True).Kr.tocsc()
    f = SPDFactor(K, backend=backend)
    B = np.random.default_rng(1).standard_normal((K.shape[0], 7))
    B[:, 3] = 0.0  # a zero column (the sparse right-hand side drops it entirely)
    X = f.solve(B)
    cols = np.column_stack([f.solve(B[:, k]) for k in range(B.shape[1])])
    assert X.shape == B.shape
    assert np.abs(X - cols).max() <= 1e-12 * np.abs(cols).max()
    assert np.all(X[:, 3] == 0.0)


def test_indefinite_symmetric_operator_solves():
    """``spd_operator`` on a symmetric indefinite matrix (a shift between the tube's first two
    eigenvalues: one negative pivot) falls back from CHOLMOD to an LU and still solves, checked by the
    residual and against a dense solve."""
    import scipy.linalg as sla

    from windflutter.solve.symmetric import spd_operator

    st = _tube(spc=True)
    K, M = st.Kr.toarray(), st.Mr.toarray()
    w2 = sla.eigh(K, M, eigvals_only=True, subset_by_index=[0, 2])
    A = K - 0.5 * (w2[0] + w2[2]) * M  # between distinct eigenvalues (the tube's come in pairs)
    B = np.random.default_rng(2).standard_normal((K.shape[0], 5))
    X = spd_operator(st.Kr - 0.5 * (w2[0] + w2[2]) * st.Mr) @ B
    ref = np.linalg.solve(A, B)
    assert np.abs(X - ref).max() <= 1e-8 * np.abs(ref).max()
