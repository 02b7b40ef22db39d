"""The full-order QEP path (shift-invert Arnoldi) with each sparse LU of ``linsolve`` against the
dense companion solve, plus reproducibility and symbolic reuse.

Reference: ``solve_qep_dense`` (LAPACK on the 2n companion form, no factorization, no Krylov
space) of a 288-DOF clamped tube with Rayleigh damping, gyroscopic and complex element-local
coupling (``benchmarks/testproblems.py::tube_qep``). Tolerance 1e-9 relative: both are
backward-stable on a well-conditioned problem; only round-off (~1e-13 here) separates them, while
a wrong operator or a wrong shift handling would give O(1) errors.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla

from windflutter.errors import InputError
from windflutter.solve import qep
from windflutter.solve.linsolve import available_backends
from testproblems import tube_qep

SHIFT = 0.05 + 0.8j
N_EIG = 12


@pytest.fixture(scope="module")
def problem():
    p = tube_qep(8, 6, coupling=0.02, gyro=0.05, seed=3)
    ref = qep.solve_qep_dense(p.M, p.D, p.K, shift=SHIFT, n_eig=N_EIG)
    return p, ref


# (None, None): the defaults qep.LU_BACKEND / qep.LU_ORDERING
CASES = [(None, None)] + [(b, o) for b in available_backends()
                          for o in (("COLAMD", "symmetric") if b == "superlu" else ("auto",))]


@pytest.mark.parametrize("backend,ordering", CASES)
def test_sparse_equals_dense_for_every_lu(problem, backend, ordering):
    p, ref = problem
    e = qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT, n_eig=N_EIG, lu_backend=backend,
                             lu_ordering=ordering)
    np.testing.assert_allclose(e.values, ref.values, rtol=1e-9)
    for lam, x in zip(e.values, e.vectors.T):
        assert qep.qep_residual(p.M, p.D, p.K, lam, x) < 1e-10
    # (no MAC check: the tube's axisymmetry gives double eigenvalues, whose vectors are any
    # basis of a 2-D space; the residual above is the shape check)


def test_independent_of_call_history(problem):
    p, _ = problem
    a = qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT, n_eig=N_EIG)
    # an unrelated ARPACK call advances ARPACK's internal random start vector
    spla.eigs(p.K.astype(complex), k=3, sigma=0.0)
    b = qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT, n_eig=N_EIG)
    assert np.array_equal(a.values, b.values) and np.array_equal(a.vectors, b.vectors)


@pytest.mark.skipif("umfpack" not in available_backends(), reason="kvxopt not installed")
def test_umfpack_symbolic_analysis_is_reused(problem):
    p, _ = problem
    fz = qep._factorizer("umfpack", "auto")
    n0 = fz.n_symbolic
    for s in (SHIFT, 0.9j, 0.02 + 1.1j):      # same pattern, new values (p-k iterations)
        qep.solve_qep_sparse(p.M, p.D, p.K, shift=s, n_eig=6, lu_backend="umfpack")
    assert fz.n_symbolic - n0 <= 1 and fz.n_numeric >= 3


def test_bad_lu_backend_is_an_input_error(problem):
    p, _ = problem
    with pytest.raises(InputError, match="lu_backend"):
        qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT, n_eig=4, lu_backend="mumps")


def test_warm_start_gives_the_same_eigenvalues(problem):
    p, ref = problem
    near = qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT * 0.98, n_eig=N_EIG)
    e = qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT, n_eig=N_EIG, v0=qep.warm_start_vector(near))
    np.testing.assert_allclose(e.values, ref.values, rtol=1e-9)   # same tolerance as above
    with pytest.raises(InputError, match="v0"):
        qep.solve_qep_sparse(p.M, p.D, p.K, shift=SHIFT, n_eig=4, v0=np.zeros(3))
