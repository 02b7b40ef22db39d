"""The roots the searches follow: the system protocol, one p-k root (Newton refinement and the
frozen-frequency p-k iteration), the static divergence distance.

* :class:`FrequencyDomainSystem` -- what a system at one parameter value provides (documented
  methods, a cache it owns); :class:`PencilSystem` builds one from a ``matrices(omega)`` function.
* :func:`newton_mode` / :func:`pk_mode` -- the p-k root of one mode; :func:`static_min_eig` -- the
  signed distance of the static stiffness from singularity; :func:`structural_eig`.
* :class:`Onset` -- what a search returns.
"""

from __future__ import annotations

import warnings
from typing import Callable, Protocol
import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from windflutter.errors import ModelError
from windflutter.solve.linsolve import factorize
from windflutter.solve.qep import qep_pencil, solve_qep
from windflutter.structure.modal import symmetric_eigs
from windflutter.linalg_tools import mac, mac_matrix

#: the seed's reduced frequencies (ch. 3.3.2, step 3)
THESIS_K = (0.001, 0.1429, 0.2857, 0.4286, 0.5714, 0.7143, 0.8571, 1.0)

#: reduced frequency ``k = omega b / U`` (at 75 % span) below which a root is static: a crossing
#: of the imaginary axis there is divergence, never flutter.  It is the seed's lowest, quasi-steady
#: reduced frequency (:data:`THESIS_K`).  On the bundled NREL 5 MW at 10 m/s and 24 RPM (U = 114
#: m/s, b = 1.47 m at 75 % span) it is 0.077 rad/s = 0.012 Hz, far below any structural mode (first
#: tower mode 0.32 Hz); the root of the seed's search that crosses there has 0.010 rad/s.
STATIC_K = THESIS_K[0]


def static_frequency(system, static_k: float = STATIC_K) -> float:
    """The frequency (rad/s) below which a root of ``system`` is static: ``static_k U75 / b75``
    (0 for a stand-in system without a reference flow)."""
    if not hasattr(system, "reference"):
        return 0.0
    U, b = system.reference(0.75)
    return float(static_k * U / b) if b > 0 else 0.0


class FrequencyDomainSystem(Protocol):
    """What the p-k and the seed's 8-k searches need of a system at one parameter value (a
    :class:`~windflutter.solve.aeroelastic.OperatingSystem` is one).

    Attributes
    ----------
    size : number of coordinates of the working basis.
    eig_cache : dict owned by the system: frozen-frequency eigen-solves keyed by ``(omega, n_eig)``
        (identical frequencies of symmetric blades share solves).

    Methods
    -------
    matrices(omega) : ``(Mt, Dt, Kt)`` with the aerodynamics frozen at frequency ``omega`` (rad/s).
    newton_pencil(lam, omega) : ``T(lam)`` at ``omega`` and the map ``x -> T'(lam) x``.
    structural_pencil() : ``(K, M)`` of the structure alone (with the rotor terms) at this point.
    reference(fraction) : ``(U, b)`` of the strip nearest ``fraction`` of the span (the seed's k).
    """

    size: int
    eig_cache: dict

    def matrices(self, omega: float): ...

    def newton_pencil(self, lam: complex, omega: float): ...

    def structural_pencil(self): ...

    def reference(self, fraction: float = 0.75): ...


class PencilSystem:
    """A :class:`FrequencyDomainSystem` from a function ``matrices(omega) -> (M, D, K)`` and the
    structural pencil ``(K, M)`` (test problems, stand-ins, small models)."""

    def __init__(self, matrices: Callable, K, M, reference: tuple[float, float] = (1.0, 1.0)):
        self._matrices, self._K, self._M, self._ref = matrices, K, M, reference
        self.eig_cache: dict = {}

    @property
    def size(self) -> int:
        return int(self._M.shape[0])

    def matrices(self, omega: float):
        return self._matrices(omega)

    def newton_pencil(self, lam: complex, omega: float):
        return qep_pencil(*self._matrices(omega), lam)

    def structural_pencil(self):
        return self._K, self._M

    def reference(self, fraction: float = 0.75):
        return self._ref


def qep(M, D, K, n_eig, shift=0.0):
    return solve_qep(M, D, K, shift=shift, n_eig=min(n_eig, 2 * M.shape[0]))


# ---------------------------------------------------------------------------- p-k
def excluded_roots(vals: np.ndarray, vecs: np.ndarray, exclude) -> np.ndarray:
    """Mask of the roots that are already taken by other tracked modes.

    A root is taken when it is close in value (5 %) *and* in shape (MAC > 0.9) to one of the
    ``exclude`` pairs ``(lambda, x)``: the value alone would also exclude the other copy of a
    repeated root (identical blades), which has an independent shape.
    """
    out = np.zeros(vals.shape, bool)
    for lam_x, x_x in exclude:
        close = np.abs(vals - lam_x) <= 0.05 * max(abs(lam_x), 1.0)
        if np.any(close):
            m = mac_matrix(x_x[:, None], vecs)[0]
            out |= close & (m > 0.9)
    return out


def dense(A) -> np.ndarray:
    return A.toarray() if hasattr(A, "toarray") else np.asarray(A)


def solve_near_singular(T, b):
    """``T^-1 b`` for a ``T`` that is near-singular by design (inverse iteration); None if singular.

    Dense: LAPACK LU without the condition-number warning of ``solve``; sparse (full-order
    models): the project's sparse LU (:func:`windflutter.solve.linsolve.factorize`).
    """
    if sp.issparse(T):
        try:
            return factorize(T.tocsc()).solve(b)
        except ModelError:
            return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)
        lu = sla.lu_factor(T, check_finite=False)
    return sla.lu_solve(lu, b, check_finite=False)


def pencil(system: FrequencyDomainSystem, lam, w):
    """``T(lam)`` at frequency ``w`` and ``x -> T'(lam) x``."""
    return system.newton_pencil(lam, w)


def newton_mode(system, lam0: complex, x0: np.ndarray, tol: float = 1e-8, maxiter: int = 12):
    """The p-k root near ``(lam0, x0)`` by nonlinear inverse iteration (Ruhe 1973).

    ``x <- T(lam)^-1 T'(lam) x``, ``lam <- lam - c^H x / c^H T(lam)^-1 T'(lam) x`` with
    ``T(lam) = lam^2 Mt(w) + lam Dt(w) + Kt(w)``, ``T' = 2 lam Mt + Dt`` and Theodorsen frozen
    at ``w = Im(lam)`` of the current iterate, so the fixed point is the p-k root (the frozen-
    frequency eigenvalue whose imaginary part is that frequency).  Quadratic in ``lam`` at fixed
    ``w``; the frequency coupling converges like the plain p-k iteration (the aero terms vary
    slowly with ``w``).  One LU of the n x n ``T`` per step (dense for projected models, sparse
    at full order), against a shift-invert Arnoldi solve per p-k step (NREL 5 MW whole turbine,
    n = 169: ~1 ms against ~15 ms).

    Returns ``(lam, x, converged)``: converged when the step in ``lam`` is below
    ``tol |lam|`` -- or, as in :func:`pk_mode`, after 4 steps for a heavily damped root
    (damping ratio > 0.3, far from any onset; its frequency coupling converges slowly).  The
    caller checks that the root is the tracked mode (shape, sign of Im).
    """
    lam = complex(lam0)
    x = np.asarray(x0, dtype=complex)
    c = x.conj() / np.vdot(x, x).real  # normalisation c^H x = 1
    for it in range(maxiter):
        T, Tp = pencil(system, lam, max(lam.imag, 0.0))
        y = solve_near_singular(T, Tp(x))
        cy = np.nan if y is None else c @ y
        if not (np.isfinite(cy) and cy != 0):
            return lam, x, False
        step = (c @ x) / cy
        lam, x = lam - step, y / cy
        if abs(step) <= tol * max(abs(lam), 1.0) or (it >= 3 and -lam.real > 0.3 * abs(lam)):
            return lam, x, True
    return lam, x, False


def _pick_root(system, w: float, x, exclude, n_eig: int):
    """The frozen-frequency root at ``w`` (rad/s) of best shape match to ``x`` (the nearest to
    ``i w`` without a shape), never one of ``exclude``; None when no root is free."""
    cache = system.eig_cache  # identical frequencies (symmetric blades) share solves
    key = (w, n_eig)
    if key not in cache:
        M, D, K = system.matrices(w)
        cache[key] = qep(M, D, K, n_eig, shift=1j * w)
    e = cache[key]
    vals, vecs = e.values, e.vectors
    phys = vals.imag >= -1e-9 * max(1.0, abs(w))
    if exclude:
        phys &= ~excluded_roots(vals, vecs, exclude)
    if not np.any(phys):
        return None
    vals, vecs = vals[phys], vecs[:, phys]
    if x is not None:
        m = mac_matrix(x[:, None], vecs)[0]
        score = m - 0.05 * np.abs(vals - 1j * w) / max(abs(w), 1.0)
    else:
        score = -np.abs(vals - 1j * w)
    i = int(np.argmax(score))
    return vals[i], vecs[:, i]


def _upper(lam: complex) -> bool:
    """A root of the upper half plane (the conjugates are not modes)."""
    return lam.imag >= -1e-9 * max(1.0, abs(lam))


def _refine_from_estimate(system, w: float, x0, lam0: complex, n_eig: int, near: float | None):
    """``(lambda, x)`` from the estimate ``lam0`` of the mode of shape ``x0`` by Newton
    (:func:`newton_mode`), or from the best-shape root at ``w`` refined by Newton; None when
    neither converges onto that mode (see :func:`pk_mode`)."""
    lam, x, ok = newton_mode(system, lam0, x0)
    if ok and _upper(lam) and (mac(x, x0) >= 0.8 or (near is not None and abs(lam - lam0) <= near * abs(lam0))):
        return lam, x
    # the Newton root is not the tracked one: choose the root of best shape at w by one
    # frozen-frequency solve, and refine that one by Newton (it starts on an eigenpair)
    got = _pick_root(system, w, x0, (), n_eig)
    if got is not None:
        lam, x, ok = newton_mode(system, got[0], got[1])
        if ok and _upper(lam) and mac(x, got[1]) >= 0.9:
            return lam, x
    return None


def pk_mode(system, omega0: float, x0: np.ndarray | None, tol: float = 1e-6, maxiter: int = 40,
            n_eig: int = 20, exclude=(), lam0: complex | None = None, near: float | None = None):
    """p-k iteration for one mode: solve with Theodorsen frozen at the mode's own frequency.

    Parameters
    ----------
    system : OperatingSystem (``matrices(omega)``).
    omega0 : starting frequency (rad/s).
    x0 : shape to follow (working basis) or None (the root nearest ``i omega0``).
    exclude : ``(lambda, x)`` pairs of roots taken by other tracked modes; never selected.
    lam0 : estimate of the root (e.g. the mode's value at the previous parameter): with ``x0``
        and a small working basis, the root is first refined locally by :func:`newton_mode`
        and accepted when it converges onto a free root of that shape (MAC >= 0.8 to ``x0``,
        ``Im >= 0``); otherwise one frozen-frequency eigen-solve at ``omega0`` picks the root of
        best shape among the ``n_eig`` nearest ``i omega0`` and Newton refines that one; only if
        that fails too (and always with ``exclude``) the plain p-k iteration of frozen-frequency
        eigen-solves below runs.
    near : for a member of a cluster of near-repeated roots (:func:`_clusters`), whose shape
        may rotate inside the cluster: the Newton root is also accepted when it lies within
        ``near |lam0|`` of ``lam0``, whatever its MAC.

    Returns (lambda, x).  A mode whose frequency falls to zero is returned with the aero at k=0.
    """
    w = max(float(omega0), 0.0)
    if lam0 is not None and x0 is not None and not exclude:
        got = _refine_from_estimate(system, w, x0, lam0, n_eig, near)
        if got is not None:
            return got
    lam, x = None, x0
    for it in range(maxiter):
        got = _pick_root(system, w, x, exclude, n_eig)
        if got is None:
            return complex(np.nan, np.nan), None
        lam, x_new = got
        w_new = max(lam.imag, 0.0)
        if abs(w_new - w) / max(abs(w_new), 1.0) <= tol:
            return lam, x_new
        if it >= 4 and -lam.real > 0.3 * abs(lam):
            # heavily damped (zeta > 0.3): far from any onset; its frequency may wander between
            # close roots, so stop refining it
            return lam, x_new
        if it >= maxiter // 3:  # under-relax an oscillating iteration (heavily damped modes)
            w_new = 0.5 * (w + w_new)
        w, x = w_new, x_new
    # not converged: return the last iterate (typically a heavily damped mode whose frequency
    # keeps jumping between close roots; it does not decide the onset)
    return lam, x


#: above this many DOFs :func:`static_min_eig` uses one LU and Arnoldi instead of the spectrum
STATIC_DENSE_LIMIT = 300


def static_min_eig(system) -> float:
    """Signed distance of the static stiffness from singularity (divergence when it crosses 0).

    ``sign(det Kt(k=0)) * min |mu|`` over the eigenvalues of ``Kt x = mu M x``: continuous, and
    it changes sign exactly when a real eigenvalue crosses zero (complex pairs never flip the
    sign of the determinant).  Up to :data:`STATIC_DENSE_LIMIT` DOFs from the whole dense
    spectrum; above (full-order models), from one LU of ``Kt``: the sign of its determinant
    from the LU and ``min |mu|`` by Arnoldi on ``Kt^-1 M`` (its largest eigenvalue is
    ``1 / min |mu|``), the whole spectrum only if that does not converge.
    """
    M, D, K = system.matrices(0.0)
    Kd, Md = dense(K).real, dense(M).real
    sM, _ = np.linalg.slogdet(Md)
    if Kd.shape[0] > STATIC_DENSE_LIMIT:
        lu, piv = sla.lu_factor(Kd, check_finite=False)
        d = np.diag(lu)
        if not np.all(d != 0):
            return 0.0
        sK = np.prod(np.sign(d)) * (-1.0) ** np.count_nonzero(piv != np.arange(piv.size))
        op = spla.LinearOperator(Kd.shape, matvec=lambda v: sla.lu_solve((lu, piv), Md @ v, check_finite=False),
                                 dtype=float)
        try:
            nu = spla.eigs(op, k=1, which="LM", v0=np.ones(Kd.shape[0]), return_eigenvectors=False)
            return float(sK * sM / np.abs(nu[0]))
        except spla.ArpackNoConvergence:
            pass
    mu = sla.eig(Kd, Md, right=False)
    mu = mu[np.isfinite(mu)]
    sK, _ = np.linalg.slogdet(Kd)
    return float(sK * sM * np.min(np.abs(mu)))


def structural_eig(system: FrequencyDomainSystem):
    """Eigenpairs ``(w^2, V)`` of the structural pencil ``(Ks(Omega), M)`` of ``system``, dense."""
    K, M = (dense(A) for A in system.structural_pencil())
    return symmetric_eigs(K, M)
