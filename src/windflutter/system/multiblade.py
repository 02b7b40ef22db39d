"""Multi-blade coordinates: an isotropic N-bladed rotor on a ground-fixed support, time-invariant.

Coordinates of the coupled system (before the transformation)

    ``q = [x_F, eta_0, ..., eta_{N-1}]``,   aerodynamic states ``z = [z_0, ..., z_{N-1}]``

``x_F``: ground-fixed coordinates (support structure, rotor azimuth ``phi`` relative to the
nacelle, generator); ``eta_b``: blade ``b``'s fixed-interface coordinates in its own rotating
frame.  The hub motion the rotor sees is ``h_R = L x_F`` (6: translation, rotation incl.
``phi`` about the shaft).  Blade ``b`` at azimuth ``psi_b = psi + 2 pi b / N`` sees it in its own
components, ``h_b = Q_b h_R`` with ``Q_b = blockdiag(R_b^T, R_b^T)`` and ``R_b`` the rotation by
``psi_b`` about the shaft, so its coordinates are ``y_b = J_b(psi) q`` and, with
``dQ_b/dt = -Omega S6 Q_b`` (``S6 = blockdiag([n], [n])``), the blade's equations

    ``Mb y'' + Cb y' + Kb y = Fb z_b``,  ``z_b' = Az z_b + Bq y_b + Bv y_b'``

contribute by virtual work (``delta y_b = J_b delta q``)
``J^T Mb J``, ``J^T (2 Mb J' + Cb J)``, ``J^T (Mb J'' + Cb J' + Kb J)`` to the periodic mass,
damping and stiffness.  The Coleman transformation of the blade coordinates and states

    ``eta_b = eta_0 + sum_k (eta_kc cos k psi_b + eta_ks sin k psi_b) [+ eta_N/2 (-1)^b]``

``q = T(psi) q_B`` gives ``M_B = T^-1 M T``, ``C_B = T^-1 (2 M T' + C T)``,
``K_B = T^-1 (M T'' + C T' + K T)`` (Bir 2008, NREL/CP-500-42553) and, for the
states, ``A_B = Tz^-1 (Az Tz - Tz')``.  For an isotropic rotor with N >= 3 all of them are constant:
:func:`multiblade_system` forms them at one azimuth; the tests check another azimuth and the
Floquet exponents of the periodic system computed by time integration.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.errors import InputError


def axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """(3, 3) rotation by ``angle`` (rad) about the unit ``axis`` (Rodrigues)."""
    n = np.asarray(axis, float)
    S = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    return np.eye(3) + np.sin(angle) * S + (1.0 - np.cos(angle)) * (S @ S)


def coleman_matrix(n_blades: int, psi: float):
    """``(C, dC/dpsi, d2C/dpsi2)``, each (N, N): blade b's row of the multi-blade transformation.

    Columns: collective; cosine and sine of harmonics k = 1 .. (N-1)//2; for even N the
    alternating (reactionless) ``(-1)^b``.
    """
    N = int(n_blades)
    if N < 1:
        raise InputError("n_blades", n_blades, "at least 1")
    psib = psi + 2.0 * np.pi * np.arange(N) / N
    cols, d1, d2 = [np.ones(N)], [np.zeros(N)], [np.zeros(N)]
    for k in range(1, (N - 1) // 2 + 1):
        c, s = np.cos(k * psib), np.sin(k * psib)
        cols += [c, s]
        d1 += [-k * s, k * c]
        d2 += [-k * k * c, -k * k * s]
    if N % 2 == 0:
        alt = (-1.0) ** np.arange(N)
        cols.append(alt)
        d1.append(np.zeros(N))
        d2.append(np.zeros(N))
    return np.stack(cols, 1), np.stack(d1, 1), np.stack(d2, 1)


@dataclass
class FixedFrame:
    """The ground-fixed part: matrices over ``x_F`` and the hub-motion map ``L`` (6, nF).

    ``M``, ``C``, ``K`` (nF, nF) SI; ``labels`` name each coordinate (``"support:<i>"``,
    ``"azimuth"``, ``"generator"``).
    """

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    L: np.ndarray
    labels: list = field(default_factory=list)

    @property
    def size(self) -> int:
        return int(self.M.shape[0])


@dataclass
class BladeSystem:
    """One blade's equations in its coordinates ``y = (h (6), eta (m))`` at the operating point.

    ``M``, ``C``, ``K`` (6 + m, 6 + m): structure, rotating-frame terms and the aerodynamic
    ``-Ma, -Da, -Ka`` (transport velocity included); aero states ``z`` (nz):
    ``M y'' + C y' + K y = F z``, ``z' = Az z + Bq y + Bv y'``; ``nz = 0`` without states.
    """

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    F: np.ndarray | None = None
    Az: np.ndarray | None = None
    Bq: np.ndarray | None = None
    Bv: np.ndarray | None = None

    def __post_init__(self):
        n = self.M.shape[0]
        if self.F is None:
            self.F = np.zeros((n, 0))
            self.Az = np.zeros((0, 0))
            self.Bq = np.zeros((0, n))
            self.Bv = np.zeros((0, n))

    @property
    def n_eta(self) -> int:
        return int(self.M.shape[0]) - 6

    @property
    def n_states(self) -> int:
        return int(self.Az.shape[0])


@dataclass
class PeriodicSystem:
    """The coupled system at one azimuth: ``M q'' + C q' + K q = F z``, ``z' = A z + Bq q + Bv q'``."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    F: np.ndarray
    A: np.ndarray
    Bq: np.ndarray
    Bv: np.ndarray


def blade_frame(axis, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """``(Q, S6)`` (6, 6) of a blade turned by ``angle`` (rad) about the shaft ``axis``: ``Q`` takes a
    hub motion (translation, rotation) into the blade's frame, ``S6`` is the cross product with the
    axis on both halves (the frame's rate of turn per unit rotor speed)."""
    R = axis_rotation(axis, angle)
    Q = np.zeros((6, 6))
    Q[:3, :3] = Q[3:, 3:] = R.T
    n = np.asarray(axis, float)
    S = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    S6 = np.zeros((6, 6))
    S6[:3, :3] = S6[3:, 3:] = S
    return Q, S6


def _blade_jacobians(fixed: FixedFrame, n_eta: int, n_blades: int, b: int, psi: float, omega: float, axis):
    """``(J, J', J'')`` (6 + m, nq) of blade ``b``: ``y_b = J q``."""
    nF = fixed.size
    nq = nF + n_blades * n_eta
    Q, S6 = blade_frame(axis, psi + 2.0 * np.pi * b / n_blades)
    J = np.zeros((6 + n_eta, nq))
    J1 = np.zeros_like(J)
    J2 = np.zeros_like(J)
    QL = Q @ fixed.L
    J[:6, :nF] = QL
    J1[:6, :nF] = -omega * S6 @ QL
    J2[:6, :nF] = omega**2 * S6 @ S6 @ QL
    J[6:, nF + b * n_eta: nF + (b + 1) * n_eta] = np.eye(n_eta)
    return J, J1, J2


def periodic_system(fixed: FixedFrame, blade: BladeSystem, n_blades: int, omega: float, axis,
                    psi: float = 0.0) -> PeriodicSystem:
    """The coupled equations of the ground-fixed part and ``n_blades`` identical blades at azimuth
    ``psi`` (rad) of blade 0, rotor speed ``omega`` (rad/s) about the unit ``axis``."""
    nF, m, nz = fixed.size, blade.n_eta, blade.n_states
    nq = nF + n_blades * m
    M = np.zeros((nq, nq))
    C = np.zeros((nq, nq))
    K = np.zeros((nq, nq))
    M[:nF, :nF] += fixed.M
    C[:nF, :nF] += fixed.C
    K[:nF, :nF] += fixed.K
    F = np.zeros((nq, n_blades * nz))
    Bq = np.zeros((n_blades * nz, nq))
    Bv = np.zeros((n_blades * nz, nq))
    A = np.kron(np.eye(n_blades), blade.Az) if nz else np.zeros((0, 0))
    for b in range(n_blades):
        J, J1, J2 = _blade_jacobians(fixed, m, n_blades, b, psi, omega, axis)
        MJ = blade.M @ J
        M += J.T @ MJ
        C += J.T @ (2.0 * blade.M @ J1 + blade.C @ J)
        K += J.T @ (blade.M @ J2 + blade.C @ J1 + blade.K @ J)
        if nz:
            rows = slice(b * nz, (b + 1) * nz)
            F[:, rows] = J.T @ blade.F
            Bq[rows] = blade.Bq @ J + blade.Bv @ J1
            Bv[rows] = blade.Bv @ J
    return PeriodicSystem(M=M, C=C, K=K, F=F, A=A, Bq=Bq, Bv=Bv)


def _transform(nF: int, m: int, n_blades: int, psi: float, omega: float):
    """``(T, T', T'')`` of the coordinates ``q = T q_B``."""
    Cm, C1, C2 = coleman_matrix(n_blades, psi)
    nq = nF + n_blades * m
    T = np.zeros((nq, nq))
    T1 = np.zeros_like(T)
    T2 = np.zeros_like(T)
    T[:nF, :nF] = np.eye(nF)
    I = np.eye(m)
    T[nF:, nF:] = np.kron(Cm, I)
    T1[nF:, nF:] = omega * np.kron(C1, I)
    T2[nF:, nF:] = omega**2 * np.kron(C2, I)
    return T, T1, T2


@dataclass
class MultiBladeSystem(PeriodicSystem):
    """The time-invariant system in multi-blade coordinates (ground-fixed frame).

    ``M q'' + C q' + K q = F z``, ``z' = A z + Bq q + Bv q'`` over ``q_B = [x_F, eta_B]`` with
    ``eta_B`` ordered coordinate-major: ``[eta_0 (m), eta_1c (m), eta_1s (m), ...]``.
    """

    n_fixed: int = 0
    n_eta: int = 0
    n_blades: int = 0

    def state_matrix(self) -> np.ndarray:
        """First-order ``x' = S x`` with ``x = [q, q', z]``."""
        n, nz = self.M.shape[0], self.A.shape[0]
        Minv_K = np.linalg.solve(self.M, np.hstack([self.K, self.C, self.F]))
        S = np.zeros((2 * n + nz, 2 * n + nz))
        S[:n, n:2 * n] = np.eye(n)
        S[n:2 * n, :n] = -Minv_K[:, :n]
        S[n:2 * n, n:2 * n] = -Minv_K[:, n:2 * n]
        S[n:2 * n, 2 * n:] = Minv_K[:, 2 * n:]
        if nz:
            S[2 * n:, :n] = self.Bq
            S[2 * n:, n:2 * n] = self.Bv
            S[2 * n:, 2 * n:] = self.A
        return S


def multiblade_system(fixed: FixedFrame, blade: BladeSystem, n_blades: int, omega: float, axis,
                      psi: float = 0.0) -> MultiBladeSystem:
    """The system of :func:`periodic_system` in multi-blade coordinates (constant for N >= 3)."""
    P = periodic_system(fixed, blade, n_blades, omega, axis, psi)
    nF, m, nz = fixed.size, blade.n_eta, blade.n_states
    T, T1, T2 = _transform(nF, m, n_blades, psi, omega)
    Ti = np.linalg.inv(T)
    # multi-blade coordinate-major order: [x_F, eta_0, eta_1c, ...]; kron(C, I) already is
    MB = Ti @ P.M @ T
    CB = Ti @ (2.0 * P.M @ T1 + P.C @ T)
    KB = Ti @ (P.M @ T2 + P.C @ T1 + P.K @ T)
    if nz:
        Cm, C1, _ = coleman_matrix(n_blades, psi)
        Tz = np.kron(Cm, np.eye(nz))
        Tz1 = omega * np.kron(C1, np.eye(nz))
        Tzi = np.linalg.inv(Tz)
        FB = Ti @ P.F @ Tz
        AB = Tzi @ (P.A @ Tz - Tz1)
        BqB = Tzi @ (P.Bv @ T1 + P.Bq @ T)
        BvB = Tzi @ (P.Bv @ T)
    else:
        FB, AB = np.zeros((MB.shape[0], 0)), np.zeros((0, 0))
        BqB = BvB = np.zeros((0, MB.shape[0]))
    return MultiBladeSystem(M=MB, C=CB, K=KB, F=FB, A=AB, Bq=BqB, Bv=BvB, n_fixed=nF, n_eta=m, n_blades=n_blades)
