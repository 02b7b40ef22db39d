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


@pytest.mark.skipif("cholmod" not in BACKENDS, reason="the fast extra (kvxopt) is not installed")
def test_factors_of_one_pattern_share_the_analysis_and_never_solve_wrong():
    """Two matrices of one pattern (a sweep's structural operators) share CHOLMOD's symbolic analysis:
    the second factorization writes into the first's factor, which then factorizes its own matrix anew
    when it solves again -- each factor solves its own matrix to round-off, before and after; a matrix
    of another pattern gets an analysis of its own."""
    import scipy.sparse as sp

    from windflutter.structure import linalg

    K = _tube(spc=True).Kr.tocsc()
    rng = np.random.default_rng(1)
    K2 = (K + sp.diags(K.diagonal() * rng.random(K.shape[0]))).tocsc()  # same pattern, other numbers
    b = rng.standard_normal(K.shape[0])
    f1 = SPDFactor(K, backend="cholmod")
    x1 = f1.solve(b)
    f2 = SPDFactor(K2, backend="cholmod")
    entry = next(e for e in linalg._SYMBOLIC if e.factor is f2._F)  # the cached analysis f2 used
    assert entry.owner() is f2 and f1._F is None  # shared with f1, which is stale now
    assert entry.matrix is not None  # the pattern's kvxopt matrix, its numbers rewritten for f2
    for f, A in ((f1, K), (f2, K2), (f1, K), (f2, K2)):
        assert np.abs(A @ f.solve(b) - b).max() < 1e-8 * np.abs(b).max()
    assert np.allclose(f1.solve(b), x1, rtol=1e-12, atol=0)
    assert f1._F is not entry.factor and f2._F is entry.factor  # the stale one has its own analysis now
    K3 = K[:-6, :-6].tocsc()  # another pattern
    f3 = SPDFactor(K3, backend="cholmod")
    assert f3._F is not entry.factor and f2._F is entry.factor
    assert np.abs(K3 @ f3.solve(b[:-6]) - b[:-6]).max() < 1e-8 * np.abs(b).max()
