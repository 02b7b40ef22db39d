"""Strip aerodynamics of a spinning blade in the time domain, with frozen BEM induction.

Each strip of the blade's :class:`~windflutter.aero_types.AeroSections` is carried by the beam's
current configuration as in :func:`windflutter.steady.exact.configuration_deflection` (strip ``j``
carried rigidly by each node ``n`` it is tied to with the motion map's weight ``w_jn``:
``x_j = sum_n w_jn (x_n + R_n (p_j - X_n))``, ``R_j = exp(sum_n w_jn log R_n)``).  In the frame spinning with the rotor, the air reaches it
at::

    V_air = V w + u_ind - Omega n x (x_j - apex)

with ``u_ind = -a (V w . n) n - a' Omega n x (x_j0 - apex)`` the induced velocity of the steady
state's BEM (``a, a'`` and the steady strip position ``x_j0``), FROZEN: held at its steady value
during the run (no dynamic inflow).  The strip's current axes: chord ``t = R_j e_chord``, normal
``n_j = R_j (e_chord x e_span)`` (suction side), span ``s = R_j e_span`` (the nose-up axis).  The
relative wind, the elastic-axis velocity and the pitch rate (angular velocity about ``s``) are
resolved in ``(t, n_j)`` -- the spanwise component dropped, as in
:func:`windflutter.aero.flow.section_flow` -- and the nonlinear strip law
(:func:`windflutter.simulate.strips.strip_forces`) with its lag states gives the loads; per unit
span times the strip width, moved to the nodes by the virtual work of the same kinematics at the
CURRENT configuration: node ``n`` gets ``w_jn F_j`` and the moment ``w_jn (R_n (p_j - X_n) x F_j +
M_j)``, the lever arm turned with the node (:meth:`BladeAero.nodal_loads`).  The arms of the steady
configuration would leave out ``(dtheta x arm) x F_j``, first order in the motion times the steady
load: a non-conservative nodal moment whose stiffness, on the IEA 22 MW at 10 m/s with 10 blade
elements, put the 1st edge frequency 1 % above method p's (docs/notes/iea22mw_edge_gap.md).  The
velocities are carried by the steady configuration's motion map (second order).  The polar
is the strips' table, linearly interpolated (:func:`windflutter.aero.strip.mean_coefficients`).
The apparent mass (Theodorsen's, on the plunge along ``n_j`` and the pitch) joins the mass
matrix; its velocity terms are evaluated with the current relative speed.  With ``dynamic_stall``
each strip has one more state, Oye's separation point (:mod:`windflutter.simulate.strips`), on the
Kirchhoff decomposition of its polar (:class:`StallCurves`).
"""

from __future__ import annotations

import numpy as np

from windflutter.aero.linearization import kirchhoff_curves
from windflutter.aero.strip import apparent_mass, mean_coefficients
from windflutter.aero.unsteady import SEPARATION_TIME, Circulation
from windflutter.errors import InputError
from windflutter.simulate.inertia import cross
from windflutter.simulate.strips import StripGeometry, strip_forces
from windflutter.steady.exact import deformed_motion_map
from windflutter.steady.geometry import rotation_matrices, rotation_vectors

__all__ = ["BladeAero"]


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


class PolarTable:
    """The strips' polar tables interpolated all at once: the same linear interpolation with end
    values outside the table as :func:`windflutter.aero.strip.mean_coefficients` (one
    ``np.interp`` per strip and coefficient there), vectorized over the strips."""

    def __init__(self, sections):
        idx = np.asarray(sections.airfoil, dtype=np.int64)
        polars = [sections.polars[int(k)] for k in idx]
        grids = [np.asarray(p.alpha, float) for p in polars]
        if any(np.any(np.diff(g) <= 0) for g in grids):
            raise InputError("polar.alpha", "not increasing", "strictly increasing polar angles")
        sizes = np.array([len(g) for g in grids])
        self.start = np.concatenate([[0], np.cumsum(sizes)[:-1]])
        self.stop = self.start + sizes - 1
        self.grid = np.concatenate(grids)
        self.values = np.stack([np.concatenate([np.asarray(getattr(p, c), float) for p in polars])
                                for c in ("cl", "cd", "cm")])
        self.first, self.last = self.grid[self.start], self.grid[self.stop]
        # each strip's grid shifted past the previous one's: one sorted key for searchsorted
        self.shift = np.repeat(np.arange(len(grids)) * (2.0 * np.ptp(self.grid) + 1.0), sizes)
        self.key = self.grid + self.shift
        self.offset = self.shift[self.start]

    def __call__(self, alpha):
        a = np.clip(np.asarray(alpha, float), self.first, self.last)
        i = np.searchsorted(self.key, a + self.offset, side="right") - 1
        i = np.clip(i, self.start, self.stop - 1)
        x0, x1 = self.grid[i], self.grid[i + 1]
        w = (a - x0) / (x1 - x0)
        v = self.values[:, i] * (1.0 - w) + self.values[:, i + 1] * w
        return v[0], v[1], v[2]


class StallCurves:
    """``(f_st, Cl_fs, Cl_att)`` of every strip at its angle (:func:`kirchhoff_curves` of its
    polar, one call per airfoil); zeros for a polar without lift slope (as method p: no lag)."""

    def __init__(self, sections):
        self.idx = np.asarray(sections.airfoil, dtype=np.int64)
        self.groups = [(self.idx == k, kirchhoff_curves(sections.polars[int(k)])) for k in np.unique(self.idx)]

    def __call__(self, alpha):
        out = np.zeros((3, self.idx.size))
        for sel, curves in self.groups:
            if curves is not None:
                out[:, sel] = curves(alpha[sel])
        return out[0], out[1], out[2]


class BladeAero:
    """The strip loads of a blade (module docstring).

    Parameters
    ----------
    fe, sections : the beam blade and its undeformed strips.  base : the configuration whose
        deformed motion map carries the loads and velocities.
    wind_speed (m/s), omega (rad/s), axis (unit), apex (3,), wind_direction (unit), rho.
    induction : ``(a, a')`` per strip (frozen).  x_steady : (ns, 3) strip points of the steady state.
    circ : the lag realisation.  apparent : factor on the apparent mass (1 = flat plate).
    dynamic_stall : Oye's separation-point state per strip (polar tables needed), ``separation_time``
        its ``T_f`` (units of ``b / |W|``, method p's 6).  ``n_lag``: the states per strip (the
        circulation's lags, plus the separation point last).
    """

    def __init__(self, fe, sections, base, wind_speed, omega, axis, apex, wind_direction, rho, induction, x_steady,
                 circ: Circulation, apparent: float = 1.0, dynamic_stall: bool = False, separation_time: float = SEPARATION_TIME):
        self.fe, self.sections, self.circ = fe, sections, circ
        ns = sections.n_sections
        self._table = PolarTable(sections) if sections.polars else None
        if dynamic_stall and self._table is None:
            raise InputError("dynamic_stall", True, "polar tables for the separation point")
        if not (np.isfinite(separation_time) and separation_time > 0):
            raise InputError("separation_time", separation_time, "a positive T_f (semi-chords)")
        self.stall = StallCurves(sections) if dynamic_stall else None
        self.separation_time = float(separation_time)
        self.ns, self.n_lag = ns, circ.n_lag + (1 if dynamic_stall else 0)
        self.width = np.asarray(sections.width, float)
        b = 0.5 * np.asarray(sections.chord, float)
        self.geo = StripGeometry(b=b, a=np.asarray(sections.elastic_axis, float), rho=float(rho))
        self.c0 = _unit(np.asarray(sections.e_chord, float))
        self.s0 = _unit(np.asarray(sections.e_span, float))
        self.n0 = _unit(np.cross(self.c0, self.s0))
        self.Omega = float(omega) * np.asarray(axis, float)
        self.apex = np.asarray(apex, float)
        a, ap = (np.broadcast_to(np.asarray(x, float), (ns,)) for x in induction)
        w = float(wind_speed) * np.asarray(wind_direction, float)
        ax = np.asarray(axis, float)
        self.wind = w[None, :] - (a * float(w @ ax))[:, None] * ax[None, :] \
            - ap[:, None] * np.cross(self.Omega, np.asarray(x_steady, float) - self.apex)
        self.W = deformed_motion_map(sections.motion_map, base.R).tocsr()
        self.apparent = float(apparent)
        mm = sections.motion_map.tocoo()
        pairs = np.unique(np.stack([mm.row // 6, mm.col // 6], axis=1), axis=0)
        first = sections.motion_map.tocsr()[6 * pairs[:, 0], :].toarray()  # the ux rows: ux weights
        self.pj, self.pn = pairs[:, 0], pairs[:, 1]
        self.pw = first[np.arange(len(pairs)), 6 * pairs[:, 1]]
        self.arm = np.asarray(sections.origin, float)[self.pj] - np.asarray(fe.nodes, float)[self.pn]
        self._mass_parts(base)

    def strips(self, config):
        """(origin (ns, 3), R (ns, 3, 3)) of the strips carried by the configuration."""
        R = np.asarray(config.R, float)
        carried = np.asarray(config.x, float)[self.pn] + np.einsum("kab,kb->ka", R[self.pn], self.arm)
        origin = np.zeros((self.ns, 3))
        np.add.at(origin, self.pj, self.pw[:, None] * carried)
        theta = np.zeros((self.ns, 3))
        np.add.at(theta, self.pj, self.pw[:, None] * rotation_vectors(R[self.pn]))
        return origin, rotation_matrices(theta)

    def _mass_parts(self, base):
        """Apparent mass on the nodal DOFs at the base configuration (full numbering)."""
        origin, Rs = self.strips(base)
        n = np.einsum("jab,jb->ja", Rs, self.n0)
        s = np.einsum("jab,jb->ja", Rs, self.s0)
        V = np.linalg.norm(self.air(origin), axis=1)
        Ma, _ = apparent_mass(self.geo.b, self.geo.a, V, self.geo.rho, self.apparent)
        ns = self.ns
        rows = np.zeros((2 * ns, 6 * ns))
        j = np.arange(ns)
        for k in range(3):
            rows[2 * j, 6 * j + k] = n[:, k]
            rows[2 * j + 1, 6 * j + 3 + k] = s[:, k]
        H = rows @ self.W  # (h, alpha) of every strip from the nodal DOFs
        blocks = np.zeros((2 * ns, 2 * ns))
        for jj in range(ns):
            blocks[2 * jj:2 * jj + 2, 2 * jj:2 * jj + 2] = self.width[jj] * Ma[jj, :2, :2]
        self.mass_added = -np.asarray(H.T @ blocks @ H)  # Ma < 0: the air adds mass

    def air(self, x):
        """(ns, 3) air velocity at strip points ``x`` in the spinning frame (m/s)."""
        return self.wind - cross(self.Omega, x - self.apex)

    def steady_lags(self, config):
        """(ns * n_lag,) lag states settled at the configuration at rest (``z_j = alpha34``)."""
        _, _, _, aE = self._evaluate(config, np.zeros(self.fe.n_dof), None, settled=True)
        z = np.repeat(aE[:, None], self.n_lag, axis=1)
        if self.stall is not None:
            z[:, -1] = self.stall(aE)[0]
        return z.reshape(-1)

    def _evaluate(self, config, udot, z, settled=False):
        origin, Rs = self.strips(config)
        t = np.einsum("jab,jb->ja", Rs, self.c0)
        n = np.einsum("jab,jb->ja", Rs, self.n0)
        s = np.einsum("jab,jb->ja", Rs, self.s0)
        vs = (self.W @ udot).reshape(-1, 6)
        W3 = self.air(origin)
        V2 = np.stack([np.sum(W3 * t, 1), np.sum(W3 * n, 1)], axis=1)
        v2 = np.stack([np.sum(vs[:, :3] * t, 1), np.sum(vs[:, :3] * n, 1)], axis=1)
        adot = np.sum(vs[:, 3:] * s, axis=1)
        if settled:  # z = alpha34 at rest (= alpha_E), the separation point at its steady value there
            phi = np.arctan2(V2[:, 1], V2[:, 0])
            z = np.repeat(phi[:, None], self.n_lag, axis=1)
            if self.stall is not None:
                z[:, -1] = self.stall(self.circ.A0 * phi)[0]
        F, M, zdot, aE = strip_forces(self.geo, self.circ, self._coefficients, V2, v2, np.zeros(self.ns), adot, z,
                                      stall=self.stall, separation_time=self.separation_time)
        _, Da = apparent_mass(self.geo.b, self.geo.a, np.hypot(V2[:, 0], V2[:, 1]), self.geo.rho, self.apparent)
        F = F.copy()
        F[:, 1] += Da[:, 0, 1] * adot
        M = M + Da[:, 1, 1] * adot
        loads = np.zeros((self.ns, 6))
        loads[:, :3] = (F[:, :1] * t + F[:, 1:2] * n) * self.width[:, None]
        loads[:, 3:] = (M * self.width)[:, None] * s
        return loads, zdot, origin, aE

    def nodal_loads(self, config, loads):
        """(n_dof,) nodal loads of the strip loads ``loads`` (ns, 6: force and moment at each strip
        point, global axes) by the virtual work of the strips' kinematics at ``config``
        (:meth:`strips`): ``x_j = sum_n w_jn (x_n + R_n a_jn)``, ``theta_j = sum_n w_jn theta_n``
        to first order, so node ``n`` gets ``w_jn F_j`` and ``w_jn (R_n a_jn x F_j + M_j)``."""
        F, Mj = loads[self.pj, :3], loads[self.pj, 3:]
        arm = np.einsum("kab,kb->ka", np.asarray(config.R, float)[self.pn], self.arm)
        out = np.zeros((self.fe.n_dof // 6, 6))
        np.add.at(out, self.pn, self.pw[:, None] * np.concatenate([F, cross(arm, F) + Mj], axis=1))
        return out.reshape(-1)

    def _coefficients(self, alpha):
        if self._table is None:
            return mean_coefficients(self.sections, alpha)
        return self._table(alpha)

    def __call__(self, t, config, xdot, omega, z):
        """``(f (n_dof,), zdot)``: nodal aerodynamic loads and lag-state rates (the callback of
        :class:`~windflutter.simulate.beam.SpinningBeams`)."""
        ud = np.zeros((self.fe.n_dof // 6, 6))
        ud[:, :3], ud[:, 3:] = xdot, omega
        loads, zdot, _, _ = self._evaluate(config, ud.reshape(-1), z.reshape(self.ns, self.n_lag))
        return self.nodal_loads(config, loads), zdot.reshape(-1)

    def static_loads(self, config):
        """(n_dof,) nodal loads at rest with settled lags."""
        loads, _, _, _ = self._evaluate(config, np.zeros(self.fe.n_dof), None, settled=True)
        return self.nodal_loads(config, loads)
