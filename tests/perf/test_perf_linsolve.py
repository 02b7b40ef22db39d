"""Sparse LU abstraction: backends agree to round-off on complex systems; errors are clear."""

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.errors import InputError, ModelError
from windflutter.solve import linsolve
from windflutter.solve.linsolve import Factorizer, as_operator, available_backends, factorize
from testproblems import tube_qep

HAVE_UMF = "umfpack" in available_backends()


@pytest.fixture(scope="module")
def Q():
    """Complex, non-symmetric shell-like Q(s) = s^2 M + s D + K near a structural frequency."""
    p = tube_qep(8, 12, seed=3)
    s = 0.01 + 0.7j
    return (s * s * p.M + s * p.D + p.K).tocsc()


def _rhs(n, k=None, seed=0):
    rng = np.random.default_rng(seed)
    shape = (n,) if k is None else (n, k)
    return rng.standard_normal(shape) + 1j * rng.standard_normal(shape)


@pytest.mark.parametrize("backend", available_backends())
@pytest.mark.parametrize("trans", ["N", "T", "H"])
def test_backend_solves_complex_system(Q, backend, trans):
    # Independent reference: dense LAPACK solve. Tolerance: relative residual at round-off
    # level times a modest condition-number allowance (cond(Q) ~ 1e3 here).
    A = Q.toarray()
    Aop = {"N": A, "T": A.T, "H": A.conj().T}[trans]
    b = _rhs(Q.shape[0], 3)
    x = factorize(Q, backend).solve(b, trans=trans)
    x_ref = np.linalg.solve(Aop, b)
    assert np.linalg.norm(x - x_ref) / np.linalg.norm(x_ref) < 1e-11


@pytest.mark.skipif(not HAVE_UMF, reason="kvxopt not installed")
def test_umfpack_and_superlu_agree_to_roundoff(Q):
    b = _rhs(Q.shape[0], seed=1)
    x1 = factorize(Q, "superlu").solve(b)
    x2 = factorize(Q, "umfpack").solve(b)
    assert x1.shape == x2.shape == b.shape
    # both are backward stable: difference bounded by cond * eps ~ 1e3 * 1e-16
    assert np.linalg.norm(x1 - x2) / np.linalg.norm(x1) < 1e-12


@pytest.mark.parametrize("backend", available_backends())
def test_real_factor_complex_rhs(backend):
    p = tube_qep(4, 3)
    f = factorize(p.Ks, backend)
    assert f.dtype == np.float64
    b = _rhs(p.n)
    x = f.solve(b)
    assert np.iscomplexobj(x)
    assert np.linalg.norm(p.Ks @ x - b) / np.linalg.norm(b) < 1e-10


@pytest.mark.skipif(not HAVE_UMF, reason="kvxopt not installed")
def test_factorizer_reuses_symbolic_analysis():
    p = tube_qep(4, 5)
    fz = Factorizer("umfpack")
    b = _rhs(p.n)
    for s in (0.3j, 0.5j, 0.1 + 0.9j):
        Q = (s * s * p.M + s * p.D + p.K).tocsc()
        x = fz.factorize(Q).solve(b)
        assert np.linalg.norm(Q @ x - b) / np.linalg.norm(b) < 1e-11
    # same pattern three times -> one symbolic analysis, three numeric factorizations
    assert (fz.n_symbolic, fz.n_numeric) == (1, 3)
    # a different pattern triggers a new analysis
    fz.factorize(p.Ks + sp.eye(p.n, format="csc"))
    assert fz.n_symbolic == 2


def test_auto_choice_and_env_override(monkeypatch):
    monkeypatch.delenv("WINDFLUTTER_LU_BACKEND", raising=False)
    assert linsolve.default_backend() == "superlu"  # fastest measured (bench_linsolve.py)
    if HAVE_UMF:
        monkeypatch.setenv("WINDFLUTTER_LU_BACKEND", "umfpack")
        assert factorize(sp.eye(3, format="csc")).backend == "umfpack"
    monkeypatch.setenv("WINDFLUTTER_LU_BACKEND", "mumps")
    with pytest.raises(InputError, match="WINDFLUTTER_LU_BACKEND"):
        linsolve.default_backend()


@pytest.mark.parametrize("ordering", ["auto", "symmetric", "COLAMD", "MMD_AT_PLUS_A"])
def test_superlu_orderings_agree(Q, ordering):
    b = _rhs(Q.shape[0], seed=2)
    x_ref = np.linalg.solve(Q.toarray(), b)
    f = factorize(Q, "superlu", ordering=ordering, blas_threads=1)
    assert np.linalg.norm(f.solve(b) - x_ref) / np.linalg.norm(x_ref) < 1e-11


def test_structural_symmetry_picks_ordering(Q):
    assert linsolve.is_structurally_symmetric(Q)
    assert factorize(Q, "superlu").ordering == "symmetric"
    U = sp.csc_matrix(np.triu(np.ones((4, 4))) + 3 * np.eye(4))
    assert not linsolve.is_structurally_symmetric(U)
    assert factorize(U, "superlu").ordering == "COLAMD"
    with pytest.raises(InputError, match="ordering"):
        factorize(U, "superlu", ordering="metis")


def test_bad_input_and_singular():
    with pytest.raises(InputError, match="backend"):
        factorize(sp.eye(3), "pardiso")
    with pytest.raises(InputError, match="A.shape"):
        factorize(sp.random(3, 4, density=0.5))
    A = sp.csc_matrix(np.array([[1.0, 2.0], [2.0, 4.0]]))
    for be in available_backends():
        with pytest.raises(ModelError, match="singular"):
            factorize(A, be).solve(np.ones(2))
    with pytest.raises(InputError, match="b.shape"):
        factorize(sp.eye(3)).solve(np.ones(4))


def test_as_operator(Q):
    op = as_operator(factorize(Q))
    b = _rhs(Q.shape[0])
    assert np.allclose(Q @ (op @ b), b, atol=1e-10)
