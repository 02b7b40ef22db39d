"""The whole turbine in the time domain: N co-rotational beam blades on a hub carried by the
support (tower, nacelle) and the drivetrain.

Formulation (a floating frame per blade).  Each blade is the clamped blade of
:mod:`windflutter.simulate.blade` in ITS OWN frame, which turns with the rotor and is carried by
the hub: origin ``apex + d``, orientation ``E(theta) A_b(t)`` with ``A_b(t)`` the rotation by
``psi_b = Omega t + 2 pi b / N`` about the shaft ``n`` and ``(d, theta)`` the small motion of the
hub (the support's hub node, with the azimuth perturbation ``phi`` about the shaft in
``theta``).  In blade ``b``'s frame a material point at ``rho`` (from the apex) accelerates as::

    a = A_b^T d'' + rho'' + 2 w x rho' + w x (w x rho) + w' x rho,
    w = Omega n + dw,   dw = A_b^T theta',   w' = A_b^T theta'' - Omega n x dw

(first order in the hub's rotation; the blade's own motion is kept whole: co-rotational beams,
:mod:`windflutter.simulate.beam`).  The terms in the hub's accelerations couple the mass: the
blade's nodal velocities are ``T_b q_b' + Gamma V_b`` with ``V_b = Q_b(t) L x_F'`` the hub's
velocity in the blade frame (``Q_b = diag(A_b^T, A_b^T)``, ``L`` the hub motion of the ground
coordinates ``x_F``, ``Gamma`` the rigid-body map about the apex at the base configuration), so
the mass matrix turns with the rotor (``M(t)``, :func:`windflutter.simulate.integrator.integrate`).
The rest -- centrifugal, Coriolis, gyroscopic and Euler loads of the current ``w`` and blade
configuration -- are nonlinear loads (:class:`~windflutter.simulate.inertia.SpinningMass` with the
frame's spin).  The blades act on the hub with the resultant of their inertial and aerodynamic
loads about the apex at their current configuration (the internal forces are self-equilibrated),
turned to the ground.

Ground coordinates ``x_F``: the support's FE coordinates (tower beams, nacelle mass, hub node;
linear: its displacements are millimetres, its static deflection under the mean rotor loads is
the state it starts from, so those loads are subtracted), the rotor azimuth ``phi`` and the
generator angle (shaft spring and damper between them, the generator inertia on the low-speed
side, its absolute rotation including the nacelle's roll about the shaft); the hub as a rigid
body at the apex moving with ``L x_F`` (no gyroscopic term of its own spin, as in method p); the
generator torque held at the steady aerodynamic torque (no controller).

The aerodynamics of each blade (:class:`~windflutter.simulate.rotor_aero.BladeAero`) see the
hub's motion: the strips move with ``T_b q_b' + Gamma V_b`` and the free wind turns with the hub
(``-A_b^T theta x V``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.linalg_tools import skew
from windflutter.simulate.beam import left_jacobian
from windflutter.simulate.inertia import cross
from windflutter.structure.corotational import beam_elements, beam_internal_forces, displaced

__all__ = ["BladePart", "GroundPart", "TurbineDynamics", "axis_turn", "rigid_map"]


def axis_turn(n: np.ndarray, angle: float) -> np.ndarray:
    """(3, 3) rotation by ``angle`` (rad) about the unit axis ``n`` (Rodrigues)."""
    S = skew(np.asarray(n, float))
    return np.eye(3) + np.sin(angle) * S + (1.0 - np.cos(angle)) * (S @ S)


def rigid_map(x: np.ndarray, apex: np.ndarray) -> np.ndarray:
    """(6 n, 6) nodal displacements (translation, rotation) of a rigid motion ``(d, theta)`` about
    ``apex`` for nodes at ``x`` (n, 3)."""
    r = np.asarray(x, float) - np.asarray(apex, float)
    G = np.zeros((len(r), 6, 6))
    G[:, :3, :3] = np.eye(3)
    G[:, :3, 3:] = -skew(r)
    G[:, 3:, 3:] = np.eye(3)
    return G.reshape(-1, 6)


@dataclass
class BladePart:
    """One blade model (the same for every blade, each in its own frame).

    fe, T (n_dof, nq), M (n_dof, n_dof) full-numbering mass (structure + apparent mass) at the base
    configuration ``base``; ``inertia`` its :class:`SpinningMass`; ``aero`` a
    :class:`BladeAero` or None; ``wind_axial`` (ns, 3) the part of the aerodynamic inflow that
    turns with the hub (free wind and axial induction) and ``wind_rest`` the rest; ``damping`` the
    structural damping matrix (full numbering) on the blade's own velocities, or None."""

    fe: object
    T: object
    M: np.ndarray
    base: object
    inertia: object
    aero: object = None
    wind_axial: np.ndarray | None = None
    wind_rest: np.ndarray | None = None
    #: (n_dof, n_dof) structural damping on the blade's velocities relative to its frame, or None
    damping: object = None


@dataclass
class GroundPart:
    """The ground-fixed coordinates ``x_F``: mass, damping, stiffness (nF, nF) and the hub motion
    ``L`` (6, nF) (translation, rotation, ground axes, the azimuth included)."""

    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    L: np.ndarray
    labels: tuple


class TurbineDynamics:
    """:class:`~windflutter.simulate.integrator.Dynamics` of the turbine (module docstring).

    Coordinates ``[x_F, q_1, ..., q_N]``; states ``[z_1, ..., z_N]`` (the blades' lag states).
    ``outputs(...)``: the support's hub-node 6 displacements (ground; the azimuth left out) then,
    per blade, the 6 displacements of each node in ``record`` (blade frame).
    """

    def __init__(self, blade: BladePart, ground: GroundPart, n_blades: int, omega: float, axis, apex,
                 record=(), hub_preload: np.ndarray | None = None):
        self.b, self.g = blade, ground
        self.N = int(n_blades)
        self.omega = float(omega)
        self.n = np.asarray(axis, float) / np.linalg.norm(axis)
        self.apex = np.asarray(apex, float)
        self.el = beam_elements(blade.fe)
        self.T = sp.csr_matrix(blade.T)
        self.TT = self.T.T.tocsr()
        self.nF, self.nq = ground.M.shape[0], self.T.shape[1]
        self.n_lag = 0 if blade.aero is None else blade.aero.ns * blade.aero.n_lag
        self.n_states = self.N * self.n_lag
        self.Gam = rigid_map(blade.base.x, self.apex)
        MT = np.asarray(blade.M @ self.T.toarray())
        self.Mbb = self.T.T @ MT
        self.Mbb = 0.5 * (self.Mbb + self.Mbb.T)
        self.G = MT.T @ self.Gam  # (nq, 6): blade mass coupled to the hub's rigid motion
        self.MGG = self.Gam.T @ blade.M @ self.Gam
        self.record = np.asarray(record, dtype=int)
        self.preload = np.zeros(6) if hub_preload is None else np.asarray(hub_preload, float)
        self.atol = 1e-12 * max(float(np.ptp(np.asarray(blade.fe.nodes, float), axis=0).max()), 1.0)
        self.mass = self.mass_at(0.0)
        #: the iteration matrix follows the turning mass: renewed at every step (a small Schur complement)
        self.renew_interval = 0.0 if self.omega > 0 else np.inf
        self._lin = None
        self.evaluations = 0

    # -- kinematics --------------------------------------------------------------------------
    def turns(self, t: float) -> list:
        """The blades' frame rotations ``A_b(t)`` (3, 3)."""
        return [axis_turn(self.n, self.omega * t + 2 * np.pi * k / self.N) for k in range(self.N)]

    def _QL(self, A):
        """(6, nF): the hub motion in a blade's frame, ``Q_b L``."""
        L = self.g.L
        return np.vstack([A.T @ L[:3], A.T @ L[3:]])

    def split(self, q):
        return q[:self.nF], [q[self.nF + k * self.nq: self.nF + (k + 1) * self.nq] for k in range(self.N)]

    # -- mass --------------------------------------------------------------------------------
    def mass_at(self, t: float) -> np.ndarray:
        nF, nq = self.nF, self.nq
        M = np.zeros((nF + self.N * nq, nF + self.N * nq))
        M[:nF, :nF] = self.g.M
        for k, A in enumerate(self.turns(t)):
            QL = self._QL(A)
            s = slice(nF + k * nq, nF + (k + 1) * nq)
            M[:nF, :nF] += QL.T @ self.MGG @ QL
            M[s, s] = self.Mbb
            M[s, :nF] = self.G @ QL
            M[:nF, s] = M[s, :nF].T
        return M

    def inertia(self, t: float, a: np.ndarray) -> np.ndarray:
        """``M(t) a`` without forming ``M(t)``."""
        aF, ab = self.split(a)
        outF = self.g.M @ aF
        out = [outF]
        for A, a_k in zip(self.turns(t), ab):
            QL = self._QL(A)
            Vh = QL @ aF
            outF = outF + QL.T @ (self.MGG @ Vh + self.G.T @ a_k)
            out.append(self.Mbb @ a_k + self.G @ Vh)
        out[0] = outF
        return np.concatenate(out)

    # -- forces ------------------------------------------------------------------------------
    def blade_forces(self, hub, hub_dot, q, v, z, t=0.0):
        """One blade: ``(rows (nq,), hub load (6,), zdot)`` given the hub's motion ``hub,
        hub_dot`` (6,) in the BLADE's frame; the load on the hub (force, moment about the apex) in
        the blade's frame too."""
        bl = self.b
        u = np.asarray(self.T @ q).reshape(-1, 6)
        ud = np.asarray(self.T @ v).reshape(-1, 6)
        Jl = left_jacobian(u[:, 3:])
        om_rel = np.einsum("nij,nj->ni", Jl, ud[:, 3:])
        cfg = displaced(bl.base, u.reshape(-1))
        dw = hub_dot[3:]
        Om = self.omega * self.n
        loads = bl.inertia.loads(cfg.x, cfg.R, ud[:, :3], om_rel, frame_spin=Om + dw,
                                 frame_alpha=-cross(Om, dw))
        zdot = np.zeros(0)
        rel = cfg.x - self.apex
        if bl.aero is not None:
            x_tot = ud[:, :3] + hub_dot[:3] + cross(dw, rel)
            bl.aero.wind = bl.wind_axial - cross(hub[3:], bl.wind_axial) + bl.wind_rest
            fa, zdot = bl.aero(t, cfg, x_tot, om_rel + dw, z)
            loads = loads + np.asarray(fa).reshape(-1, 6)
        f = beam_internal_forces(bl.fe, cfg, self.el).reshape(-1, 6) - loads
        if bl.damping is not None:
            f = f + (bl.damping @ ud.reshape(-1)).reshape(-1, 6)
        load = np.concatenate([loads[:, :3].sum(axis=0), (loads[:, 3:] + cross(rel, loads[:, :3])).sum(axis=0)])
        f[:, 3:] = np.einsum("nji,nj->ni", Jl, f[:, 3:])
        return self.TT @ f.reshape(-1), load, np.asarray(zdot, float).reshape(-1)

    def forces(self, t, q, v, z):
        self.evaluations += 1
        xF, qb = self.split(q)
        vF, vb = self.split(v)
        hub, hub_dot = self.g.L @ xF, self.g.L @ vF
        rows, zd = [], []
        load = -self.preload.copy()
        for k, A in enumerate(self.turns(t)):
            zk = z[k * self.n_lag: (k + 1) * self.n_lag]
            r, h, g = self.blade_forces(_turn6(A.T, hub), _turn6(A.T, hub_dot), qb[k], vb[k], zk, t)
            rows.append(r)
            load += _turn6(A, h)
            zd.append(g)
        fF = self.g.K @ xF + self.g.C @ vF - self.g.L.T @ load
        return np.concatenate([fF] + rows), np.concatenate(zd) if zd else np.zeros(0)

    def steady_lags(self) -> np.ndarray:
        return self.b.aero.steady_lags(self.b.base) if self.b.aero is not None else np.zeros(0)

    def hub_load(self, t=0.0):
        """(6,) the rotor's load on the hub at the base state (ground axes, about the apex)."""
        zero6, zq = np.zeros(6), np.zeros(self.nq)
        return sum(_turn6(A, self.blade_forces(zero6, zero6, zq, zq, self.steady_lags(), t)[1]) for A in self.turns(t))

    # -- iteration matrix --------------------------------------------------------------------
    def linearization(self, step: float = 1e-7):
        """Central differences of one blade's rows, lag rates and hub load (its own frame) in its
        coordinates, lag states and the hub's motion, at the base state (the same for every
        blade; computed once): ``{"q", "v", "z", "hp", "hv"} -> ((nq + m + 6), k)`` (rows: the
        blade's equations, the lag rates, the hub load)."""
        if getattr(self, "_lin", None) is not None:
            return self._lin
        base = {"hp": np.zeros(6), "hv": np.zeros(6), "q": np.zeros(self.nq), "v": np.zeros(self.nq),
                "z": self.steady_lags()}

        def f(x):
            r, h, g = self.blade_forces(x["hp"], x["hv"], x["q"], x["v"], x["z"])
            return np.concatenate([r, g, h])

        out = {}
        for key in base:
            J = np.zeros((self.nq + self.n_lag + 6, base[key].size))
            for j in range(base[key].size):
                x = {k: v.copy() for k, v in base.items()}
                d = step * max(1.0, abs(x[key][j]))
                x[key][j] += d
                fp = f(x)
                x[key][j] -= 2 * d
                J[:, j] = (fp - f(x)) / (2 * d)
            out[key] = J
        self._lin = out
        return out

    def iteration_solver(self, t, scheme, h):
        """``solve(r)`` of the step's iteration matrix at ``t`` by its structure: identical blade
        blocks (constant, factored once) coupled to the ground coordinates through the hub's six
        motions in each blade's frame, a Schur complement on the ground coordinates (turning with
        the rotor, factored at every call)."""
        import scipy.linalg as la  # noqa: PLC0415

        J = self.linearization()
        nq, m, nF, N = self.nq, self.n_lag, self.nF, self.N
        am, af = scheme.am, scheme.af
        ca, cz = scheme.beta * h * h, scheme.gamma * h
        key = (h, am, af)
        if getattr(self, "_blocks_key", None) != key:
            nb = nq + m
            Abb = np.zeros((nb, nb))  # unknowns (a_b, zd_b), rows (blade equations, lag equations)
            Abb[:nq, :nq] = (1 - am) * self.Mbb
            Abb[nq:, nq:] = (1 - am) * np.eye(m)
            sign = np.ones(nb)
            sign[nq:] = -1.0  # the lag rows are (1 - am) zd - g
            Abb[:, :nq] += sign[:, None] * (1 - af) * (ca * J["q"][:nb] + cz * J["v"][:nb])
            Abb[:, nq:] += sign[:, None] * (1 - af) * cz * J["z"][:nb]
            # d rows / d hub acceleration (blade frame)
            Cb = sign[:, None] * (1 - af) * (ca * J["hp"][:nb] + cz * J["hv"][:nb])
            Cb[:nq] += (1 - am) * self.G
            D = np.hstack([(1 - am) * self.G.T - (1 - af) * (ca * J["q"][nb:] + cz * J["v"][nb:]),
                           -(1 - af) * cz * J["z"][nb:]])  # d hub rows (blade frame) / d (a_b, zd_b)
            Y = (1 - am) * self.MGG - (1 - af) * (ca * J["hp"][nb:] + cz * J["hv"][nb:])
            lu = la.lu_factor(Abb)
            X = la.lu_solve(lu, Cb)
            self._blocks = (lu, X, D, Y - D @ X)
            self._blocks_key = key
        lu, X, D, W = self._blocks
        turns = self.turns(t)
        QLs = [self._QL(A) for A in turns]
        S = (1 - am) * self.g.M + (1 - af) * (ca * self.g.K + cz * self.g.C)
        for QL in QLs:
            S += QL.T @ W @ QL
        S_lu = la.lu_factor(S)
        n = nF + N * nq

        def solve(r):
            rF = r[:nF].copy()
            ys = []
            for k, QL in enumerate(QLs):
                rb = np.concatenate([r[nF + k * nq: nF + (k + 1) * nq], r[n + k * m: n + (k + 1) * m]])
                y = la.lu_solve(lu, rb)
                ys.append(y)
                rF -= QL.T @ (D @ y)
            xF = la.lu_solve(S_lu, rF)
            out = np.zeros_like(r)
            out[:nF] = xF
            for k, (QL, y) in enumerate(zip(QLs, ys)):
                x = y - X @ (QL @ xF)
                out[nF + k * nq: nF + (k + 1) * nq] = x[:nq]
                out[n + k * m: n + (k + 1) * m] = x[nq:]
            return out

        return solve

    def outputs(self, t, q, v, z):
        xF, qb = self.split(q)
        ns = self.g.labels.index("azimuth")
        out = [self.g.L[:, :ns] @ xF[:ns]]
        for k in range(self.N):
            u = np.asarray(self.T @ qb[k]).reshape(-1, 6)
            out.append(u[self.record].reshape(-1))
        return np.concatenate(out)


def _turn6(A, h):
    """(6,) a force-moment (or motion) pair turned by ``A``."""
    return np.concatenate([A @ h[:3], A @ h[3:]])


def check_blades(n_blades) -> int:
    if isinstance(n_blades, bool) or not isinstance(n_blades, (int, np.integer)) or n_blades < 3:
        raise InputError("assembly.number_of_blades", n_blades, "3 or more blades (an isotropic rotor)")
    return int(n_blades)
