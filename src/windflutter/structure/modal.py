"""Modal analysis: the one structural eigen-solver of the package and its normalisations.

* :func:`symmetric_eigs` -- the lowest eigenpairs of a symmetric pencil ``K v = w^2 M v``, in this
  argument order everywhere: dense LAPACK ``eigh`` for dense matrices (the full spectrum, or the
  lowest ``n``; optionally inverted so that ``M`` may be singular), shift-invert Lanczos (ARPACK
  ``eigsh``) for sparse ones;
* :func:`mass_normalize` -- unit modal mass and a deterministic sign;
* :func:`m_orthonormalize` -- a mass-orthonormal basis of a span, dependent directions dropped;
* :func:`modes` -- the natural modes of an assembled :class:`Structural` with participation factors.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.errors import ConvergenceError, InputError
from windflutter.structure.assembly import Structural
from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor
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


def symmetric_eigs(K, M, n: int | None = None, *, shift: float = 0.0, opinv=None, v0=None, tol: float = 0.0,
                   vectors: bool = True, inverted: bool = False):
    """The lowest eigenpairs ``(w2, V)`` of the real symmetric pencil ``K v = w2 M v``, ``w2`` ascending.

    Parameters
    ----------
    K, M : stiffness and mass, both dense arrays (LAPACK ``eigh`` of their symmetric parts) or both
        sparse (shift-invert Lanczos, ARPACK ``eigsh``).
    n : number of pairs; None: the whole spectrum (dense only).
    shift : the Lanczos shift (rad^2/s^2; pairs nearest to it), and of the inverted dense form.
    opinv : the shift-invert operator ``(K - shift M)^-1`` (a LinearOperator or a callable); None:
        ARPACK factorises with SuperLU.
    v0 : the Lanczos start vector (None: ARPACK's random one, which depends on what ran before).
    tol : ARPACK relative tolerance (0: machine precision).
    vectors : False: the eigenvalues only (``V`` is None).
    inverted : dense only: solve ``M v = mu (K - shift M) v``, ``w2 = shift + 1/mu``, keeping the
        ``n`` largest finite ``mu`` (``M`` may be singular: massless DOFs).

    Raises
    ------
    ConvergenceError
        ARPACK did not converge.
    """
    if not sp.issparse(K):
        Kd = np.asarray(K)
        Md = np.asarray(M)
        if inverted:
            mu, Q = sla.eigh(Md, Kd - shift * Md)
            pos = mu > 1e-14 * max(np.abs(mu).max(), 1e-300)
            mu, Q = mu[pos], Q[:, pos]
            order = np.argsort(-mu)[: mu.size if n is None else min(n, mu.size)]
            w2, V = shift + 1.0 / mu[order], Q[:, order]
            order = np.argsort(w2)
            return w2[order], (V[:, order] if vectors else None)
        Kd, Md = 0.5 * (Kd + Kd.T), 0.5 * (Md + Md.T)
        subset = None if n is None or n >= Kd.shape[0] else [0, int(n) - 1]
        if not vectors:
            return sla.eigh(Kd, Md, eigvals_only=True, subset_by_index=subset), None
        return sla.eigh(Kd, Md, subset_by_index=subset)
    if n is None:
        raise InputError("n", n, "a number of modes for a sparse pencil")
    try:
        out = spla.eigsh(K, k=int(n), M=M, sigma=shift, which="LM", OPinv=opinv, v0=v0, tol=tol,
                         return_eigenvectors=vectors)
    except spla.ArpackNoConvergence as exc:  # pragma: no cover - rare
        raise ConvergenceError(f"structural modes: ARPACK did not converge for {n} modes ({exc})") from exc
    w2, V = out if vectors else (out, None)
    order = np.argsort(w2)
    return w2[order], (V[:, order] if vectors else None)


def mass_normalize(V: np.ndarray, M) -> np.ndarray:
    """``V`` scaled to unit modal mass (``|v^T M v| = 1``), each column's largest-magnitude component
    positive (a deterministic sign, for interpolation and MAC)."""
    V = np.asarray(V, dtype=float)
    mm = np.einsum("ij,ij->j", V, M @ V)
    V = V / np.sqrt(np.abs(mm))[None, :]
    imax = np.argmax(np.abs(V), axis=0)
    return V * np.sign(V[imax, np.arange(V.shape[1])])[None, :]


def m_orthonormalize(V: np.ndarray, M, *, tol: float = 1e-8, largest_first: bool = True,
                     gram: np.ndarray | None = None) -> np.ndarray:
    """Mass-orthonormal basis of ``span(V)``, dropping (numerically) dependent directions.

    Uses the eigen-decomposition of the Gram matrix ``G = V^T M V``: directions whose eigenvalue
    is below ``tol * max eigenvalue`` are discarded. The column order of an already M-orthonormal
    ``V`` is *not* preserved (the Gram directions in descending, or with ``largest_first=False``
    ascending, eigenvalue); use :func:`windflutter.solve.reduction.augment` to append to a basis.

    Parameters
    ----------
    V : ``(n, r)`` real array.
    M : ``(n, n)`` symmetric positive definite mass matrix (dense or sparse).
    tol : relative eigenvalue cut-off of the Gram matrix (a direction is kept if it carries more
        than ``sqrt(tol)`` of the largest direction's mass-norm).
    gram : ``V^T M V`` when the caller has it (else computed as ``V.T @ (M @ V)``).
    """
    V = np.asarray(V, dtype=float)
    if V.ndim != 2:
        raise InputError("V", V.shape, "a 2-D (n, r) array")
    G = V.T @ (M @ V) if gram is None else np.asarray(gram)
    G = 0.5 * (G + G.T)
    g, U = np.linalg.eigh(G)
    keep = g > tol * max(g.max(), np.finfo(float).tiny)
    g, U = g[keep], U[:, keep]
    if largest_first:
        g, U = g[::-1], U[:, ::-1]
    return V @ (U / np.sqrt(g))


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
        w, Q = symmetric_eigs(Kr.toarray(), Mr.toarray(), n, shift=sigma, inverted=True)
    else:
        A = (Kr - sigma * Mr).tocsc()
        try:
            OPinv = SPDFactor(A).operator()
        except NotPositiveDefinite:  # shift above the lowest eigenvalue: general LU
            lu = spla.splu(A)
            OPinv = spla.LinearOperator(A.shape, matvec=lu.solve, dtype=float)
        # ARPACK's Lanczos work is level-2 BLAS on tall vectors: multi-threaded BLAS only adds
        # overhead (3x slower measured on a loaded 2-core machine), so run it single-threaded.
        with _single_thread_blas():
            w, Q = symmetric_eigs(Kr, Mr, min(n, nq - 2), shift=sigma, opinv=OPinv, tol=tol)
    Q = mass_normalize(Q, Mr)  # unit modal mass and a deterministic sign (largest component positive)
    shapes = struct.expand(Q)
    c = np.zeros(3) if center is None else np.asarray(center, dtype=float)
    R = struct.rigid_body_vectors(c)
    MR = struct.M @ R
    gamma = shapes.T @ MR
    total = np.einsum("ij,ij->j", R, MR)
    freq = np.sqrt(np.abs(w)) * np.sign(w) / (2.0 * np.pi)
    return Modes(freq=freq, omega2=w, q=Q, shapes=shapes, participation=gamma, effective_mass=gamma**2,
                 total_mass=total, center=c)


#: modes whose squared frequencies are this close (relative) share one eigen-space: an axisymmetric
#: tower's fore-aft and side-side pair, whose eigenvectors the solver returns in any rotation
DEGENERATE = 1e-6


def degenerate_groups(w2: np.ndarray) -> list[range]:
    """The groups of two or more consecutive modes (squared frequencies ``w2``, ascending) that share
    one eigen-space (:data:`DEGENERATE`), each a range of indices."""
    w2 = np.asarray(w2, dtype=float)
    out, i = [], 0
    while i < w2.size:
        j = i + 1
        while j < w2.size and abs(w2[j] - w2[i]) <= DEGENERATE * max(abs(w2[i]), 1e-12):
            j += 1
        if j - i > 1:
            out.append(range(i, j))
        i = j
    return out


def split_directions(w2: np.ndarray, V: np.ndarray, direction_energy) -> np.ndarray:
    """``V`` with each group of degenerate modes (:data:`DEGENERATE`) turned within its eigen-space onto
    the directions of extreme fore-aft energy (the eigenvectors of that quadratic form in the group's
    basis, by polarization of ``direction_energy``): the pair of an axisymmetric tower becomes one
    fore-aft and one side-side mode whatever rotation the solver returned (it decided which of the
    files' two tower ratios each got, :mod:`windflutter.system.damping`, and which name,
    :mod:`windflutter.system.identity`).
    The eigen-space, hence the modal damping of a non-degenerate set, is unchanged."""
    V = np.array(V, copy=True)
    for group in degenerate_groups(w2):
        G = V[:, group]
        k = len(group)
        Q = np.zeros((k, k))
        for a in range(k):
            Q[a, a] = direction_energy(G[:, a])[0]
            for b in range(a + 1, k):
                Q[a, b] = Q[b, a] = 0.25 * (direction_energy(G[:, a] + G[:, b])[0]
                                            - direction_energy(G[:, a] - G[:, b])[0])
        V[:, group] = G @ symmetric_eigs(Q, np.eye(k))[1][:, ::-1]  # the most fore-aft first
    return V
