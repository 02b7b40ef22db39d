"""Symmetric structural pencils ``K phi = w^2 M phi``: one positive-definite solve with a fallback,
and the refinement of their lowest modes from a nearby pencil's.

``spd_operator`` is the factorization every structural eigen-solve uses (CHOLMOD where the matrix is
positive definite and the ``fast`` extra is installed, else the project's LU); ``refine_modes`` is a
block Rayleigh-Ritz iteration (the current Ritz block and its inverse-iteration residuals) that
follows the lowest modes of a slowly changing pencil -- a rotating blade from one rotor speed or wind
speed to the next -- with one or two block solves where a Lanczos solve from scratch takes hundreds
of single ones.
SciPy has no subspace iteration; its ``lobpcg`` with the exact inverse as preconditioner, tried first,
did not converge the highest wanted modes in 50 iterations on the NREL 5 MW shell blade.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import InputError
from windflutter.solve.linsolve import as_operator, default_backend, factorize
from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor
from windflutter.structure.modal import m_orthonormalize, symmetric_eigs

__all__ = ["spd_operator", "factor_with_inertia", "refine_modes"]


def spd_operator(A, backend: str = "auto") -> spla.LinearOperator:
    """``B -> A^-1 B`` (vectors or (n, k) blocks) for a symmetric structural matrix ``A``: a Cholesky
    factor (CHOLMOD, :class:`~windflutter.structure.linalg.SPDFactor`, the ``fast`` extra) when
    ``backend`` is ``auto`` and ``A`` is positive definite (a constrained structure at shift 0: the
    standstill NREL 5 MW shell blade's 8k DOF factorize in 0.1 s against SuperLU's 1.7 s, a solve
    4 ms against 16 ms), else the LU of :func:`~windflutter.solve.linsolve.factorize` (CHOLMOD
    missing, or a rotating blade past its static stability)."""
    return factor_with_inertia(A, backend)[0]


def factor_with_inertia(A, backend: str = "auto") -> tuple[spla.LinearOperator, int | None]:
    """:func:`spd_operator`'s ``A^-1`` and the number of negative eigenvalues of ``A`` (Sylvester's law of
    inertia on the factorization ``P A P^T = L D L^T``): 0 where the Cholesky factor exists, the count of
    negative pivots where the LU pivoted on the diagonal alone (row and column permutations equal), None
    where it is not known (another LU, or pivots off the diagonal).

    A shell blade under its steady stress can lose definiteness in a local mode of the mesh (a skin
    panel's short-wave buckling, ``w^2 ~ -1e5 1/s^2``) far from the lowest modes that a structural margin
    computed on the blade's basis sees: the count tells it at no cost beyond the factorization."""
    A = sp.csc_matrix(A)
    if backend == "auto":
        try:  # CHOLMOD only: without it (ImportError) the LU below is the one factorization
            F = SPDFactor(A, backend="cholmod")
        except (ImportError, NotPositiveDefinite):
            pass
        else:
            if F.backend == "cholmod":
                return spla.LinearOperator(A.shape, matvec=F.solve, matmat=F.solve, dtype=float), 0
        if default_backend() == "superlu":
            # an indefinite symmetric matrix (a blade past a local static instability): SuperLU on the
            # minimum-degree ordering of A + A^T, pivoting off the diagonal only below 1e-3 of the
            # column's largest entry; the default symmetric mode's threshold 0.1 pivoted off it on the
            # IEA 22 MW shell blade and took 7.6 s with 3.5x the fill, this 0.9 s
            try:
                lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=1e-3,
                               options=dict(SymmetricMode=True))
            except RuntimeError:  # singular: the general LU below reports it
                pass
            else:
                negative = int(np.count_nonzero(lu.U.diagonal() < 0)) \
                    if np.array_equal(lu.perm_r, lu.perm_c) else None
                return spla.LinearOperator(A.shape, matvec=lu.solve, matmat=lu.solve, dtype=float), negative
    return as_operator(factorize(A, backend)), None


def refine_modes(K, M, solve, start: np.ndarray, n_modes: int, *, tol: float = 1e-4, max_iter: int = 6):
    """Lowest ``n_modes`` of ``K phi = w^2 M phi`` by block Rayleigh-Ritz from ``start``.

    For a pencil that changed little since ``start`` was its block of lowest modes (the next rotor
    speed of a sweep, the next wind speed of a Campbell diagram), a few block solves reach what a
    shift-invert Lanczos from scratch does with hundreds of single ones.  Each iteration solves
    ``Y = K^-1 M X`` for the current Ritz block ``X`` (one block solve: it also gives the Ritz
    pairs' residuals ``R = X - w^2 Y``) and takes the ``p`` lowest Ritz pairs of ``span[X, R]``
    (a two-block Krylov space; Knyazev's LOBPCG without its third block, Knyazev 2001, SIAM J. Sci.
    Comput. 23(2)).  The residuals, each scaled to unit M-norm, keep the directions of every
    column at the same precision; plain subspace iteration (``X <- K^-1 M X``, Bathe 2014, sec.
    11.6) converges the highest wanted mode by the ratio ``w_n^2 / w_(p+1)^2`` per iteration only,
    slow in the dense band of panel modes (10-20 Hz) of a large shell blade: on the IEA 22 MW shell
    blade from one wind speed to the next, 7 block solves became 3, the returned residuals 20x
    smaller (docs/notes/performance_rounds.md, "The deflected shell Campbell at the converged
    mesh").  On convergence the last residuals, already computed, give one more Rayleigh-Ritz
    step for free (its Ritz values are no larger, so no further from the eigenvalues, than those of
    the block that passed the test).

    Parameters
    ----------
    K, M : real symmetric stiffness (N/m) and mass (kg), (n, n) sparse or dense, ``K`` definite.
    solve : ``B -> K^-1 B`` for (n, p) blocks (one factorization of ``K``).
    start : (n, p) start block, ``p > n_modes`` (the extra columns guard the convergence of the
        highest wanted mode).
    n_modes : modes wanted.
    tol : convergence of every wanted Ritz vector ``x``: ``||x - w^2 K^-1 M x||_M <= tol`` with
        ``||x||_M = 1`` (the sine of its angle to its inverse-iterate; its eigenvalue is then right
        to about ``tol^2``).
    max_iter : block solves before giving up.

    Returns
    -------
    (w2 (p,), X (n, p)) the M-orthonormal Ritz pairs sorted by ``w2`` (rad^2/s^2), or None when
    they did not converge in ``max_iter`` block solves (a cold start is then needed).
    """
    X = np.asarray(start, float)
    if X.ndim != 2 or not (n_modes < X.shape[1] < X.shape[0]):
        raise InputError("start", getattr(X, "shape", None), f"an (n, p) block with {n_modes} < p < n")
    p = X.shape[1]
    K, M = _csr(K), _csr(M)
    try:
        w2, X, KX, MX = _ritz(X, np.asarray(K @ X), np.asarray(M @ X), p)
        for _ in range(max_iter):
            R = X - np.asarray(solve(MX)) * w2
            MR = np.asarray(M @ R)
            eta = np.sqrt(np.abs(np.einsum("ij,ij->j", R, MR)))
            done = bool(np.all(eta[:n_modes] <= tol))
            for _ in range(2):  # the new directions, M-orthogonal to X (twice: rounding)
                C = X.T @ MR
                R, MR = R - X @ C, MR - MX @ C
            nr = np.sqrt(np.abs(np.einsum("ij,ij->j", R, MR)))
            keep = nr > 1e-12 * max(float(eta.max()), 1e-300)
            if np.any(keep):
                R, MR = R[:, keep] / nr[keep], MR[:, keep] / nr[keep]
                Z = m_orthonormalize(R, M, tol=1e-12, gram=R.T @ MR)
                w2, X, KX, MX = _ritz(np.hstack([X, Z]), np.hstack([KX, np.asarray(K @ Z)]),
                                      np.hstack([MX, np.asarray(M @ Z)]), p)
            if done:
                return w2, X
    except (np.linalg.LinAlgError, ValueError):  # lost rank: start again from scratch
        return None
    return None


def _csr(A):
    return A.tocsr() if sp.issparse(A) else np.asarray(A)


def _ritz(Q: np.ndarray, KQ: np.ndarray, MQ: np.ndarray, p: int):
    """The ``p`` lowest Ritz pairs of the pencil on ``span(Q)`` (``KQ = K Q``, ``MQ = M Q``):
    ``(w2 (p,), X (n, p), K X, M X)``, ``X`` M-orthonormal."""
    w2, U = symmetric_eigs(Q.T @ KQ, Q.T @ MQ, p)
    return w2, Q @ U, KQ @ U, MQ @ U
