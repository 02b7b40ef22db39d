"""First-order eigenvalue perturbation of the multi-blade system of an operating point.

The point's system (:class:`~windflutter.system.multiblade.MultiBladeSystem`) is

    ``M q'' + C q' + K q = F z``,   ``z' = A z + Bq q + Bv q'``

and its modes the eigenpairs of the state matrix ``S`` of ``x = [q, q', z]``
(:meth:`~windflutter.system.multiblade.MultiBladeSystem.state_matrix`, the matrix
:func:`windflutter.system.modes.point_modes` solves).  With the right eigenvector ``x`` and the left
one ``y`` (``y^H S = lambda y^H``) of a simple eigenvalue,

    ``dlambda = y^H dS x / y^H x``.

Written with the blocks of ``S`` (``S_2 = M^-1 [-K, -C, F]``, ``x = [q, lambda q, z]``, and
``M^-1 (-K q - lambda C q + F z) = lambda^2 q`` on the eigenvector), with ``w = M^-H y_2``:

    ``y^H dS x = -w^H (lambda^2 dM + lambda dC + dK) q + w^H dF z + y_3^H (dBq q + lambda dBv q + dA z)``.

The multi-blade matrices are sums over the blades of ``J_b^T (blade matrix) J_b`` terms and the
Coleman transformation (:mod:`windflutter.system.multiblade`), so a change of the blade's own
``(M_b, C_b, K_b)`` enters as ``sum_b l_b^T (dM_b r_M,b + dC_b r_C,b + dK_b r_K,b)`` with vectors
``l_b``, ``r_*,b`` in the blade's coordinates (:func:`blade_vectors`); those are expanded to the
blade's nodes once per mode, and every element's derivative is a 12 x 12 product.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from windflutter.system.modes import state_eig
from windflutter.system.multiblade import blade_frame, coleman_matrix


@dataclass
class ModeVectors:
    """One mode's eigenvalue and the vectors of its perturbation.

    ``lam`` the eigenvalue; ``x`` right, ``y`` left eigenvector of the state matrix; ``norm`` =
    ``y^H x``; ``q``, ``z`` the structural and aerodynamic-state parts of ``x``; ``w = M^-H y_2``;
    ``y3`` the state part of ``y``; ``gap`` the distance to the nearest other eigenvalue relative to
    ``|lambda|``; ``condition`` = ``|x| |y| / |y^H x|`` (the eigenvalue's condition number).
    """

    lam: complex
    x: np.ndarray
    y: np.ndarray
    norm: complex
    q: np.ndarray
    z: np.ndarray
    w: np.ndarray
    y3: np.ndarray
    gap: float
    condition: float
    neighbour: "ModeVectors | None" = None


def mode_vectors(mbc, eigenvalues, eig: tuple | None = None) -> list[ModeVectors]:
    """:class:`ModeVectors` of the eigenvalues ``eigenvalues`` (those of the point's named modes)
    of ``mbc``'s state matrix: one dense eigen-solve with left and right vectors, as
    :func:`~windflutter.system.modes.point_modes`' (the same matrix, so the same eigenvalues).
    Each carries its nearest other eigenvalue's vectors as ``neighbour`` (:func:`pair_vectors`).
    ``eig``: that eigen-solve already done (:func:`~windflutter.system.modes.state_eig` of ``mbc``)."""
    lam, Y, X = state_eig(mbc) if eig is None else eig
    n = mbc.M.shape[0]
    lu = sla.lu_factor(mbc.M)

    def vectors(i: int, gap: float) -> ModeVectors:
        x, y = X[:, i], Y[:, i]
        nrm = complex(np.vdot(y, x))
        y2 = y[n:2 * n]
        w = sla.lu_solve(lu, y2.real, trans=1) + 1j * sla.lu_solve(lu, y2.imag, trans=1)  # M^H w = y_2 (M real)
        return ModeVectors(lam=complex(lam[i]), x=x, y=y, norm=nrm, q=x[:n], z=x[2 * n:], w=w, y3=y[2 * n:],
                           gap=gap, condition=float(np.linalg.norm(x) * np.linalg.norm(y) / max(abs(nrm), 1e-300)))

    out = []
    for target in np.atleast_1d(np.asarray(eigenvalues, complex)):
        i = int(np.argmin(np.abs(lam - target)))
        dist = np.abs(lam - lam[i])
        dist[i] = np.inf
        j = int(np.argmin(dist))
        mv = vectors(i, float(dist[j] / max(abs(lam[i]), 1e-300)))
        if np.isfinite(dist[j]):
            mv.neighbour = vectors(j, mv.gap)
        out.append(mv)
    return out


def pair_vectors(mv: ModeVectors) -> tuple[ModeVectors, ModeVectors]:
    """The cross terms of a mode ``i`` and its neighbour ``j``: vectors whose derivatives
    (:func:`system_derivative`, :mod:`windflutter.sensitivity.point`) are
    ``kappa_ji = y_j^H dS x_i / y_j^H x_j`` and ``kappa_ij = y_i^H dS x_j / y_i^H x_i``, the
    coupling of the pair by the change (the eigenvector derivative's term towards the other is
    ``kappa_ji / (lambda_i - lambda_j)``)."""
    nb = mv.neighbour
    ji = dataclasses.replace(mv, w=nb.w, y3=nb.y3, norm=nb.norm)
    ij = dataclasses.replace(nb, w=mv.w, y3=mv.y3, norm=mv.norm)
    return ji, ij


def pair_ratio(mv: ModeVectors, kappa_ji, kappa_ij, step: float):
    """``2 sqrt(|kappa_ij kappa_ji|) step / |lambda_i - lambda_j|``: how strongly a change ``step`` of
    a parameter (whose pair couplings are ``kappa_ji``, ``kappa_ij``, :func:`pair_vectors`) couples
    the mode to its nearest eigenvalue, over half their distance.  Two eigenvalues a coupling
    ``kappa`` mixes move as ``sqrt((Delta/2)^2 + kappa_ij kappa_ji dp^2)``: linear in ``dp`` -- the
    first-order derivative meaningful -- only while this is well below 1."""
    dist = abs(mv.lam - mv.neighbour.lam) if mv.neighbour is not None else np.inf
    return 2.0 * np.sqrt(np.abs(np.asarray(kappa_ji) * np.asarray(kappa_ij))) * step / max(dist, 1e-300)


def system_derivative(mv: ModeVectors, dM=None, dC=None, dK=None, dF=None, dA=None, dBq=None, dBv=None) -> complex:
    """``dlambda`` of the mode ``mv`` for changes of the multi-blade matrices (module docstring);
    any of them None: unchanged."""
    lam, q, z = mv.lam, mv.q, mv.z
    r = np.zeros_like(q)
    for D, f in ((dM, lam**2), (dC, lam), (dK, 1.0)):
        if D is not None:
            r = r + f * (D @ q)
    t = -np.vdot(mv.w, r)
    if dF is not None and z.size:
        t += np.vdot(mv.w, dF @ z)
    if z.size:
        s = np.zeros_like(z)
        if dBq is not None:
            s = s + dBq @ q
        if dBv is not None:
            s = s + lam * (dBv @ q)
        if dA is not None:
            s = s + dA @ z
        t += np.vdot(mv.y3, s)
    return complex(t / mv.norm)


def mbc_derivative(mv: ModeVectors, plus, minus, h: float) -> complex:
    """``dlambda/dp`` from two multi-blade systems at ``p = +h`` and ``-h`` (central differences of
    the assembled matrices; the eigenvectors are the nominal point's)."""
    d = {k: (getattr(plus, k) - getattr(minus, k)) / (2.0 * h) for k in ("M", "C", "K", "F", "A", "Bq", "Bv")}
    return system_derivative(mv, d["M"], d["C"], d["K"], d["F"], d["A"], d["Bq"], d["Bv"])


@dataclass
class BladeVectors:
    """Per blade ``b`` the left vector ``l[b]`` and the right vectors ``rM[b]``, ``rC[b]``, ``rK[b]``
    (each (N, 6 + m), blade coordinates ``y = (h, eta)``): ``y^H dS x = -sum_b l_b^T (dM_b rM_b +
    dC_b rC_b + dK_b rK_b)`` for a change of the blade's structural matrices."""

    l: np.ndarray
    rM: np.ndarray
    rC: np.ndarray
    rK: np.ndarray


def _jacobians(L: np.ndarray, nF: int, m: int, N: int, b: int, omega: float, axis) -> tuple:
    """Blade ``b``'s ``y_b = J q`` of the periodic coordinates at azimuth 0 and its time derivatives
    (:func:`windflutter.system.multiblade.periodic_system`'s)."""
    Q, S6 = blade_frame(axis, 2.0 * np.pi * b / N)
    nq = nF + N * m
    J, J1, J2 = np.zeros((6 + m, nq)), np.zeros((6 + m, nq)), np.zeros((6 + m, nq))
    QL = Q @ L
    J[:6, :nF] = QL
    J1[:6, :nF] = -omega * S6 @ QL
    J2[:6, :nF] = omega**2 * S6 @ S6 @ QL
    J[6:, nF + b * m: nF + (b + 1) * m] = np.eye(m)
    return J, J1, J2


def blade_jacobians(mbc, L: np.ndarray, omega: float, axis) -> list[tuple]:
    """``[(J, J', J'')]`` of every blade (:func:`_jacobians`), for :func:`blade_vectors`."""
    return [_jacobians(L, mbc.n_fixed, mbc.n_eta, mbc.n_blades, b, omega, axis) for b in range(mbc.n_blades)]


def blade_vectors(mv: ModeVectors, mbc, jacobians: list[tuple], omega: float) -> BladeVectors:
    """:class:`BladeVectors` of the mode ``mv`` of ``mbc`` (the blades' :func:`blade_jacobians` at
    rotor speed ``omega``): the Coleman transformation at azimuth 0 and the blade Jacobians, as
    :func:`~windflutter.system.multiblade.multiblade_system` forms them."""
    nF, m, N = mbc.n_fixed, mbc.n_eta, mbc.n_blades
    Cm, C1, C2 = coleman_matrix(N, 0.0)

    def apply(C, v):  # kron(C, I_m) on the blade coordinates, 0 on the ground-fixed ones
        out = np.zeros_like(v)
        out[nF:] = (C @ v[nF:].reshape(N, m)).ravel()
        return out

    a = np.concatenate([mv.w[:nF], (np.linalg.inv(Cm).T @ mv.w[nF:].reshape(N, m)).ravel()])  # a^H = w^H T^-1
    lam = mv.lam
    u0 = apply(Cm, mv.q)
    u0[:nF] = mv.q[:nF]
    u1, u2 = omega * apply(C1, mv.q), omega**2 * apply(C2, mv.q)
    ls, rM, rC, rK = [], [], [], []
    for J, J1, J2 in jacobians:
        ls.append(J @ a.conj())
        rM.append(J @ (lam**2 * u0 + 2 * lam * u1 + u2) + 2 * J1 @ (lam * u0 + u1) + J2 @ u0)
        rC.append(J @ (lam * u0 + u1) + J1 @ u0)
        rK.append(J @ u0)
    return BladeVectors(l=np.array(ls), rM=np.array(rM), rC=np.array(rC), rK=np.array(rK))


def frequency_damping(lam: complex, dlam):
    """``(df_Hz, dzeta)`` of the undamped frequency ``|lambda| / 2 pi`` and the damping ratio
    ``-Re lambda / |lambda|`` for eigenvalue changes ``dlam`` (array)."""
    dlam = np.asarray(dlam, complex)
    a = abs(lam)
    da = np.real(np.conj(lam) * dlam) / a
    dzeta = -(np.real(dlam) * a - lam.real * da) / a**2
    return da / (2.0 * np.pi), dzeta
