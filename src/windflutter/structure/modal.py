"""Modal analysis: sparse shift-invert Lanczos (ARPACK via scipy ``eigsh``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import ConvergenceError, InputError
from windflutter.structure.assembly import Structural
from windflutter.threads import blas_limit


@dataclass
class Modes:
    """Normal modes of a (constrained) structure.

    Attributes
    ----------
    freq : (n,) natural frequencies (Hz), ascending.
    omega2 : (n,) eigenvalues omega^2 (rad^2/s^2); may be slightly negative for a prestressed
        structure close to buckling.
    q : (nq, n) mode shapes in reduced coordinates, unit modal mass (q^T Mr q = 1).
    shapes : (n_dof, n) mode shapes in the full numbering (``T q``).
    participation : (n, 6) participation factors for unit rigid motions (3 translations, 3
        rotations about ``center``) of the support: ``Gamma = phi^T M R`` (unit modal mass).
    effective_mass : (n, 6) effective masses ``Gamma^2`` (kg for translations, kg m^2 for rotations).
    total_mass : (6,) rigid-body mass/inertia ``R^T M R`` of the whole model for comparison.
    center : (3,) reference point for the rotational participation (m).
    """

    freq: np.ndarray
    omega2: np.ndarray
    q: np.ndarray
    shapes: np.ndarray
    participation: np.ndarray
    effective_mass: np.ndarray
    total_mass: np.ndarray
    center: np.ndarray

    @property
    def n(self) -> int:
        return int(self.freq.size)


def _single_thread_blas():
    """Context manager limiting BLAS to one thread (:func:`windflutter.threads.blas_limit`)."""
    return blas_limit(1)


def _default_shift(Kr: sp.spmatrix, Mr: sp.spmatrix) -> float:
    """A small negative shift (rad^2/s^2) keeping K - sigma M positive definite."""
    dk = np.abs(Kr.diagonal())
    dm = np.abs(Mr.diagonal())
    ok = dm > 0
    scale = float(np.median(dk[ok] / dm[ok])) if np.any(ok) else 1.0
    return -1e-6 * min(scale, 1.0e6)


def modes(
    struct: Structural,
    n: int = 20,
    K_extra: sp.spmatrix | None = None,
    shift: float | None = None,
    center: np.ndarray | None = None,
    tol: float = 0.0,
) -> Modes:
    """Lowest natural modes of ``(K + K_extra) phi = omega^2 M phi``.

    Parameters
    ----------
    struct : assembled structure.
    n : number of modes (clipped to nq - 1).
    K_extra : optional extra stiffness in the FULL numbering (n_dof x n_dof), e.g. a geometric
        stiffness from :func:`windflutter.structure.prestress.geometric_stiffness` or spin
        softening; it is reduced with ``T`` here.
    shift : shift sigma (rad^2/s^2) of the shift-invert transformation; modes nearest to it are
        returned.  Default: a small negative number (lowest modes).
    center : reference point (m) for rotational participation factors; default the origin.
    tol : ARPACK relative tolerance (0 = machine precision).

    Returns
    -------
    Modes
    """
    if not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError("n", n, "a positive integer number of modes")
    Kr = struct.Kr
    if K_extra is not None:
        if K_extra.shape != (struct.n_dof, struct.n_dof):
            raise InputError("K_extra", K_extra.shape, f"a ({struct.n_dof}, {struct.n_dof}) full-numbering matrix")
        Kr = (Kr + struct.reduce(sp.csr_matrix(K_extra))).tocsr()
    Mr = struct.Mr
    nq = struct.nq
    sigma = _default_shift(Kr, Mr) if shift is None else float(shift)
    if nq <= max(n + 2, 12) or nq < 200:
        from scipy.linalg import eigh

        # M may be singular (massless DOFs): solve M q = mu (K - sigma M) q, omega^2 = sigma + 1/mu
        mu, Q = eigh(Mr.toarray(), (Kr - sigma * Mr).toarray())
        pos = mu > 1e-14 * max(np.abs(mu).max(), 1e-300)
        mu, Q = mu[pos], Q[:, pos]
        order = np.argsort(-mu)[: min(n, mu.size)]
        w, Q = sigma + 1.0 / mu[order], Q[:, order]
        order = np.argsort(w)
        w, Q = w[order], Q[:, order]
    else:
        k = min(n, nq - 2)
        from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor

        A = (Kr - sigma * Mr).tocsc()
        try:
            OPinv = SPDFactor(A).operator()
        except NotPositiveDefinite:  # shift above the lowest eigenvalue: general LU
            lu = spla.splu(A)
            OPinv = spla.LinearOperator(A.shape, matvec=lu.solve, dtype=float)
        try:
            # ARPACK's Lanczos work is level-2 BLAS on tall vectors: multi-threaded BLAS only adds
            # overhead (3x slower measured on a loaded 2-core machine), so run it single-threaded.
            with _single_thread_blas():
                w, Q = spla.eigsh(Kr, k=k, M=Mr, sigma=sigma, which="LM", OPinv=OPinv, tol=tol)
        except spla.ArpackNoConvergence as exc:  # pragma: no cover - rare
            raise ConvergenceError(f"eigsh did not converge for {k} modes: {exc}") from exc
        order = np.argsort(w)
        w, Q = w[order], Q[:, order]
    # unit modal mass and a deterministic sign (largest component positive)
    mm = np.einsum("ij,ij->j", Q, Mr @ Q)
    Q = Q / np.sqrt(np.abs(mm))[None, :]
    imax = np.argmax(np.abs(Q), axis=0)
    Q = Q * np.sign(Q[imax, np.arange(Q.shape[1])])[None, :]
    shapes = struct.expand(Q)
    c = np.zeros(3) if center is None else np.asarray(center, dtype=float)
    R = struct.rigid_body_vectors(c)
    MR = struct.M @ R
    gamma = shapes.T @ MR
    total = np.einsum("ij,ij->j", R, MR)
    freq = np.sqrt(np.abs(w)) * np.sign(w) / (2.0 * np.pi)
    return Modes(freq=freq, omega2=w, q=Q, shapes=shapes, participation=gamma, effective_mass=gamma**2,
                 total_mass=total, center=c)
