"""Modal reduction of the coupled aeroelastic quadratic eigenproblem.

The full-order problem is ``(lam^2 M + lam D + K) x = 0`` with complex, sparse n x n matrices
``M = Ms - Ma``, ``D = Ds + G - Da``, ``K = Ks - Kr + Ksigma - Ka`` (``docs/stability.md``, "Pipeline
(modules)", coupled system).
Flutter lives in the lowest few structural modes, so the problem is projected (Galerkin) onto a
real basis ``Phi`` (n x m, m << n) of

1. the lowest *structural* modes of the rotating, prestressed structure -- the real symmetric
   pencil ``(Ks - Kr + Ksigma, Ms)`` at the rotor speed of interest (:func:`structural_modes`);
2. optionally *static-correction* (residual-flexibility, "modal truncation augmentation")
   vectors ``K^{-1} f`` for the aerodynamic load shapes ``f`` the modes do not represent
   (:func:`static_correction_modes`);

giving ``(lam^2 Mr + lam Dr + Kr) y = 0`` with ``Mr = Phi^T M Phi`` etc. (:func:`project`), a
dense 2m companion problem solved by LAPACK (:func:`solve_dense_qep`), and mode shapes
``x = Phi y`` (:func:`expand`). As the rotor speed changes, the basis can be recomputed, taken
from the nearest precomputed speed, or built once for a speed range as the orthonormalised union
of the bases at its ends (:func:`interpolate_basis`, :func:`union_basis`). The full-order solve
stays the reference; ``tests/perf/test_perf_reduction.py`` checks that the reduced eigenvalues
converge to it as the basis grows.

References
----------
* Craig, R.R. and Kurdila, A.J., *Fundamentals of Structural Dynamics*, 2nd ed., Wiley 2006,
  ch. 14 (mode-displacement and mode-acceleration / static correction).
* Dickens, J.M., Nakagawa, J.M. and Wittbrodt, M.J., "A critique of mode acceleration and modal
  truncation augmentation methods for modal response analysis", Computers & Structures 62(6),
  1997 (MTA vectors as used here).
* Castillo Capponi, P., TU Delft MSc thesis 2010, ch. 6.2 (model reduction recommended).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.linalg_tools import mac_matrix as mac  # the column-by-column MAC (solve.reduction.mac)
from windflutter.solve.linsolve import factorize
from windflutter.solve.symmetric import spd_operator
from windflutter.structure.modal import m_orthonormalize, mass_normalize, symmetric_eigs

__all__ = [
    "ModalBasis",
    "ReducedQEP",
    "structural_modes",
    "m_orthonormalize",
    "static_correction_modes",
    "augment",
    "union_basis",
    "interpolate_basis",
    "mac",
    "project",
    "reduce_qep",
    "solve_dense_qep",
    "expand",
    "reduced_eigs",
]


@dataclass
class ModalBasis:
    """A real, mass-orthonormal reduction basis.

    Attributes
    ----------
    Phi
        ``(n, m)`` real array, ``Phi^T Ms Phi = I``.
    omega
        ``(m,)`` natural circular frequencies (rad/s) of the columns that are structural modes;
        ``nan`` for static-correction vectors.
    rotor_speed
        Rotor speed (rad/s) the basis was computed at, or ``None``.
    """

    Phi: np.ndarray
    omega: np.ndarray
    rotor_speed: float | None = None
    meta: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return self.Phi.shape[0]

    @property
    def m(self) -> int:
        return self.Phi.shape[1]

    @property
    def n_modes(self) -> int:
        """Number of columns that are structural eigenmodes (the rest are corrections)."""
        return int(np.count_nonzero(np.isfinite(self.omega)))


def _check_square(name: str, A, n: int | None = None) -> int:
    if not (sp.issparse(A) or isinstance(A, np.ndarray)) or A.ndim != 2 or A.shape[0] != A.shape[1]:
        raise InputError(name, getattr(A, "shape", type(A).__name__), "a square (n, n) matrix")
    if n is not None and A.shape[0] != n:
        raise InputError(f"{name}.shape", A.shape, f"({n}, {n}) to match the other matrices")
    return A.shape[0]


def structural_modes(
    M, K, n_modes: int, *, shift: float = 0.0, rotor_speed: float | None = None,
    dense_below: int = 600, backend: str = "auto",
) -> ModalBasis:
    """Lowest real eigenmodes of the symmetric pencil ``K phi = w^2 M phi``.

    Parameters
    ----------
    M, K
        Real symmetric mass (kg) and stiffness (N/m) matrices, n x n sparse or dense; ``K`` is
        the stiffness of the rotating, prestressed structure (``Ks - Kr + Ksigma``).
    n_modes
        Number of modes (``1 <= n_modes < n``).
    shift
        Spectral shift ``w0^2`` (rad^2/s^2) for the shift-invert Lanczos; 0 works for a
        constrained structure. Use a small negative value if ``K`` may be singular.
    rotor_speed
        Stored in the result (rad/s), for interpolation across speeds.
    dense_below
        Use dense LAPACK ``eigh`` when ``n`` is below this size.
    backend
        LU backend for the shift-invert (see :mod:`windflutter.solve.linsolve`).

    Returns
    -------
    ModalBasis
        Mass-normalised modes sorted by frequency; ``omega = sqrt(max(w^2, 0))`` (rad/s).
    """
    n = _check_square("K", K)
    _check_square("M", M, n)
    if not (1 <= int(n_modes) < n):
        raise InputError("n_modes", n_modes, f"an integer in [1, {n - 1}]")
    n_modes = int(n_modes)
    if np.iscomplexobj(M) or np.iscomplexobj(K):
        raise InputError("K", "complex matrix", "real symmetric structural M and K (no aero terms)")
    if n < dense_below:
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        w2, V = symmetric_eigs(Kd, Md, n_modes)
    else:
        Ms = sp.csc_matrix(M)
        Ks = sp.csc_matrix(K)
        f = spd_operator(Ks - shift * Ms, backend)
        # fixed start vector: ARPACK's default one comes from a per-process random state that
        # advances with every call, so results would depend on what ran before in the process
        v0 = np.random.default_rng(20100).standard_normal(n)
        w2, V = symmetric_eigs(Ks, Ms, n_modes, shift=shift, opinv=f, v0=v0)
    V = mass_normalize(V, M)  # eigh/eigsh already M-orthonormalise; again for safety, and a deterministic sign
    return ModalBasis(Phi=V, omega=np.sqrt(np.maximum(w2, 0.0)), rotor_speed=rotor_speed)


def static_correction_modes(
    K, M, Phi: np.ndarray, loads: np.ndarray, *, tol: float = 1e-8, backend: str = "auto"
) -> np.ndarray:
    """Static-correction (modal truncation augmentation) vectors for given load shapes.

    For each load shape ``f`` the static response ``K^{-1} f`` is computed, its part already
    represented by ``Phi`` is removed by mass-orthogonal projection
    (``x - Phi Phi^T M x``), and the remainders are mass-orthonormalised.

    Parameters
    ----------
    K, M
        Real stiffness (N/m) and mass (kg) matrices; ``K`` must be nonsingular.
    Phi
        ``(n, m)`` M-orthonormal basis.
    loads
        ``(n, r)`` load shapes (N); complex shapes contribute their real and imaginary parts.
        For aerodynamic coupling use, e.g., ``Ka @ Phi`` and ``Da @ Phi`` (the aero forces the
        retained modes generate) or the section load distributions.
    tol
        Relative cut-off for dependent vectors (see :func:`m_orthonormalize`).

    Returns
    -------
    numpy.ndarray
        ``(n, c)`` real, M-orthonormal and M-orthogonal to ``Phi`` (``c <= 2 r``).
    """
    loads = np.asarray(loads)
    if loads.ndim == 1:
        loads = loads[:, None]
    if loads.shape[0] != Phi.shape[0]:
        raise InputError("loads.shape", loads.shape, f"({Phi.shape[0]}, r)")
    F = np.hstack([loads.real, loads.imag]) if np.iscomplexobj(loads) else loads.astype(float)
    F = F[:, np.linalg.norm(F, axis=0) > 0]
    if F.shape[1] == 0:
        return np.zeros((Phi.shape[0], 0))
    X = factorize(sp.csc_matrix(K), backend).solve(F)
    X = np.real(X)
    for _ in range(2):  # two passes of M-orthogonal deflation (re-orthogonalisation)
        X = X - Phi @ (Phi.T @ (M @ X))
    # scale columns to unit mass-norm first so the relative cut-off treats them alike;
    # a column whose remainder is at round-off level of its static response carries nothing new
    nrm = np.sqrt(np.abs(np.einsum("ij,ij->j", X, M @ X)))
    X = X[:, nrm > 1e-10 * max(nrm.max(), np.finfo(float).tiny)]
    if X.shape[1] == 0:
        return X
    X = X / np.sqrt(np.abs(np.einsum("ij,ij->j", X, M @ X)))
    C = m_orthonormalize(X, M, tol=tol)
    C = C - Phi @ (Phi.T @ (M @ C))
    return m_orthonormalize(C, M, tol=tol)


def augment(basis: ModalBasis, K, M, loads: np.ndarray, *, tol: float = 1e-8) -> ModalBasis:
    """Append static-correction vectors for ``loads`` to ``basis`` (modes keep their order)."""
    C = static_correction_modes(K, M, basis.Phi, loads, tol=tol)
    return ModalBasis(
        Phi=np.hstack([basis.Phi, C]),
        omega=np.concatenate([basis.omega, np.full(C.shape[1], np.nan)]),
        rotor_speed=basis.rotor_speed,
        meta={**basis.meta, "n_correction": C.shape[1]},
    )


def union_basis(bases: Sequence[ModalBasis], M, *, tol: float = 1e-8) -> ModalBasis:
    """One M-orthonormal basis spanning all ``bases`` (e.g. computed at several rotor speeds).

    Nearly parallel directions (the same mode at neighbouring speeds) are merged by the Gram
    cut-off ``tol``, so the union grows only by what the speeds add.
    """
    if len(bases) == 0:
        raise InputError("bases", bases, "at least one ModalBasis")
    Phi = m_orthonormalize(np.hstack([b.Phi for b in bases]), M, tol=tol)
    return ModalBasis(Phi=Phi, omega=np.full(Phi.shape[1], np.nan), rotor_speed=None,
                      meta={"union_of": [b.rotor_speed for b in bases]})


def interpolate_basis(
    bases: Sequence[ModalBasis], speed: float, M, *, method: str = "union", tol: float = 1e-8
) -> ModalBasis:
    """Reduction basis at rotor speed ``speed`` from bases precomputed at other speeds.

    Parameters
    ----------
    bases
        Bases with ``rotor_speed`` set (rad/s), any order.
    speed
        Rotor speed wanted (rad/s); outside the range the end basis is used.
    method
        ``"nearest"``: the basis of the closest speed.
        ``"union"``: M-orthonormalised union of the two bracketing bases (robust: the subspace
        contains both end subspaces; ``m`` up to doubles).
        ``"linear"``: columns of the two bracketing bases matched by MAC, signs aligned,
        blended linearly in speed and re-orthonormalised (keeps ``m``; mode order may change
        when frequencies cross).
    """
    if method not in ("nearest", "union", "linear"):
        raise InputError("method", method, "'nearest', 'union' or 'linear'")
    if len(bases) == 0 or any(b.rotor_speed is None for b in bases):
        raise InputError("bases", "missing rotor_speed", "bases computed with rotor_speed set")
    bases = sorted(bases, key=lambda b: b.rotor_speed)
    speeds = np.array([b.rotor_speed for b in bases], dtype=float)
    if method == "nearest" or len(bases) == 1 or speed <= speeds[0] or speed >= speeds[-1]:
        b = bases[int(np.argmin(np.abs(speeds - speed)))]
        return ModalBasis(b.Phi, b.omega, b.rotor_speed, dict(b.meta))
    j = int(np.searchsorted(speeds, speed))  # speeds[j-1] < speed <= speeds[j]
    a, b = bases[j - 1], bases[j]
    if method == "union":
        u = union_basis([a, b], M, tol=tol)
        u.rotor_speed = float(speed)
        return u
    # linear: match b's columns to a's by MAC (greedy on the largest values)
    if a.Phi.shape != b.Phi.shape:
        raise InputError("bases", "different sizes", "bases of equal shape for method='linear'")
    C = mac(a.Phi, b.Phi)
    perm = -np.ones(a.m, dtype=int)
    Cw = C.copy()
    for _ in range(a.m):
        i, k = np.unravel_index(np.argmax(Cw), Cw.shape)
        perm[i] = k
        Cw[i, :] = -1.0
        Cw[:, k] = -1.0
    Pb = b.Phi[:, perm]
    sgn = np.sign(np.einsum("ij,ij->j", a.Phi, M @ Pb))
    sgn[sgn == 0] = 1.0
    Pb = Pb * sgn
    t = (speed - a.rotor_speed) / (b.rotor_speed - a.rotor_speed)
    V = (1.0 - t) * a.Phi + t * Pb
    # Gram-Schmidt in mode order (Cholesky of the Gram matrix) keeps the columns mode-like
    G = V.T @ (M @ V)
    L = np.linalg.cholesky(0.5 * (G + G.T))
    Phi = sla.solve_triangular(L, V.T, lower=True).T
    om = (1.0 - t) * a.omega + t * b.omega[perm]
    return ModalBasis(Phi=Phi, omega=om, rotor_speed=float(speed), meta={"interpolated": True})


def project(Phi: np.ndarray, A) -> np.ndarray:
    """Galerkin projection ``Phi^T A Phi`` (dense ``m x m``; complex if ``A`` is)."""
    if A is None:
        return np.zeros((Phi.shape[1], Phi.shape[1]))
    return Phi.T @ np.asarray(A @ Phi)


@dataclass
class ReducedQEP:
    """Reduced problem ``(lam^2 Mr + lam Dr + Kr) y = 0``, full shape ``x = Phi y``."""

    Mr: np.ndarray
    Dr: np.ndarray
    Kr: np.ndarray
    Phi: np.ndarray

    @property
    def m(self) -> int:
        return self.Mr.shape[0]


def reduce_qep(M, D, K, Phi: np.ndarray) -> ReducedQEP:
    """Project the full matrices (n x n, sparse or dense, real or complex) onto ``Phi``."""
    n = _check_square("M", M)
    _check_square("K", K, n)
    if D is not None:
        _check_square("D", D, n)
    Phi = np.asarray(Phi, dtype=float)
    if Phi.ndim != 2 or Phi.shape[0] != n:
        raise InputError("Phi.shape", Phi.shape, f"({n}, m)")
    return ReducedQEP(project(Phi, M), project(Phi, D), project(Phi, K), Phi)


def solve_dense_qep(
    M: np.ndarray, D: np.ndarray, K: np.ndarray, n_eig: int | None = None,
    *, target: complex | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """All (or selected) eigenpairs of a small dense QEP via its 2m companion linearisation.

    ``[[0, I], [-K, -D]] z = lam [[I, 0], [0, M]] z`` with ``z = [y; lam y]``, solved by LAPACK
    (QZ, :func:`scipy.linalg.eig`). Infinite eigenvalues (singular ``M``) are dropped.

    Parameters
    ----------
    M, D, K
        ``(m, m)`` arrays, real or complex; ``D`` may be ``None``.
    n_eig
        Number of eigenpairs returned (default: all finite ones).
    target
        Return those closest to ``target`` (rad/s); default: smallest modulus first.

    Returns
    -------
    lam : (k,) complex
        Eigenvalues ``sigma + i omega`` (rad/s).
    Y : (m, k) complex
        Eigenvectors, unit 2-norm.
    """
    M = np.atleast_2d(np.asarray(M))
    m = M.shape[0]
    K = np.atleast_2d(np.asarray(K))
    D = np.zeros_like(M) if D is None else np.atleast_2d(np.asarray(D))
    dt = np.result_type(M, D, K, np.complex128)
    I = np.eye(m, dtype=dt)
    Z = np.zeros((m, m), dtype=dt)
    A = np.block([[Z, I], [-K.astype(dt), -D.astype(dt)]])
    B = np.block([[I, Z], [Z, M.astype(dt)]])
    lam, V = sla.eig(A, B)
    ok = np.isfinite(lam)
    lam, V = lam[ok], V[:, ok]
    # y from whichever half of z = [y; lam y] is better conditioned
    top, bot = V[:m], V[m:]
    use_bot = np.abs(lam) > 1.0
    Y = np.where(use_bot[None, :], bot / np.where(use_bot, lam, 1.0)[None, :], top)
    Y = Y / np.linalg.norm(Y, axis=0)
    key = np.abs(lam) if target is None else np.abs(lam - target)
    order = np.argsort(key, kind="stable")
    if n_eig is not None:
        order = order[: int(n_eig)]
    return lam[order], Y[:, order]


def expand(Phi: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Full-order mode shapes ``X = Phi Y`` (n x k)."""
    return Phi @ Y


def reduced_eigs(
    M, D, K, basis: ModalBasis | np.ndarray, n_eig: int | None = None,
    *, target: complex | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Project, solve and expand in one call: eigenpairs of the full QEP approximated on a basis.

    Parameters
    ----------
    M, D, K
        Full-order matrices (n x n; sparse or dense; complex allowed).
    basis
        :class:`ModalBasis` or ``(n, m)`` real array.
    n_eig, target
        See :func:`solve_dense_qep`.

    Returns
    -------
    lam : (k,) complex
        Eigenvalues (rad/s).
    X : (n, k) complex
        Full-order mode shapes ``Phi y``.
    """
    Phi = basis.Phi if isinstance(basis, ModalBasis) else np.asarray(basis)
    r = reduce_qep(M, D, K, Phi)
    lam, Y = solve_dense_qep(r.Mr, r.Dr, r.Kr, n_eig, target=target)
    return lam, expand(Phi, Y)
