"""A straight cantilever wing (``windflutter wing``'s model, e.g. Goland's) in the time domain.

The wing's data and discretisation are the eigen-solver's (:func:`windflutter.frozen.wing.
build_wing`: beam elements along the span, one strip per element at its mid-point moving with
the mean of its two nodes); everything else is this package's own:

* the structure: the co-rotational beam (:class:`~windflutter.simulate.beam.SpinningBeams`,
  not spinning): its internal forces at the current configuration, the consistent mass;
* the air: the nonlinear strip force law (:func:`windflutter.simulate.strips.strip_forces`) with
  the lag states of C(s) (the 4-pole Roger fit by default), flat plate ``Cl = Cla alpha_E``, the
  free stream along the chord; each strip's plunge, chordwise motion and pitch are the mean of
  its nodes' translations and rotation vector about the span (the wing's rotations stay
  milliradians); Theodorsen's apparent mass, linear by definition, joins the mass matrix and its
  damping term the loads;
* generalized-alpha with Newton iterations (:func:`windflutter.simulate.integrator.integrate`),
  and the matrix pencil on the tip's and mid-span's plunge and pitch.

No matrix of the eigen-solver (stiffness, aerodynamic or modal) is used.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.strip import apparent_mass
from windflutter.aero.unsteady import circulation as make_circulation
from windflutter.errors import InputError
from windflutter.simulate.beam import SpinningBeams, left_jacobian
from windflutter.simulate.blade import corrected_modes
from windflutter.simulate.identify import Identification, identify
from windflutter.simulate.inertia import SpinningMass
from windflutter.simulate.integrator import Trajectory, integrate, step_for_frequency
from windflutter.simulate.strips import StripGeometry, flat_plate, strip_forces
from windflutter.structure.assembly import assemble
from windflutter.structure.corotational import reference_configuration

__all__ = ["WingDynamics", "WingRun", "simulate_wing"]


class WingDynamics:
    """:class:`~windflutter.simulate.integrator.Dynamics` of a wing (``fe``, ``sections`` of
    :func:`~windflutter.frozen.wing.build_wing`) at airspeed ``U`` (m/s) (module docstring)."""

    def __init__(self, fe, sections, U: float, air_density: float, lift_slope: float, circ):

        st = assemble(fe)
        base = reference_configuration(fe)
        nodes = np.arange(fe.n_nodes)
        inertia = SpinningMass(fe, nodes, 0.0, np.array([0.0, 0.0, 1.0]), np.zeros(3))
        self.beams = SpinningBeams(fe, st.T, st.M, base, inertia)
        self.T = self.beams.T
        self.U, self.circ, self.n_lag = float(U), circ, circ.n_lag
        s = sections
        self.ns = len(s.radius)
        self.width = np.asarray(s.width, float)
        e_c = np.asarray(s.e_chord, float)
        e_s = np.asarray(s.e_span, float)
        e_n = np.cross(e_c, e_s)  # the section's normal (up); nose-up pitch is about +e_span
        P = s.motion_map.tocsr()  # (6 ns, n_dof): the strips' mean translation and rotation
        rows = np.arange(self.ns)
        tr = [P[6 * rows + k] for k in range(6)]
        self.S_chord = sum(tr[k].multiply(e_c[:, [k]]) for k in range(3)).tocsr() @ self.T
        self.S_plunge = sum(tr[k].multiply(e_n[:, [k]]) for k in range(3)).tocsr() @ self.T
        self.S_pitch = sum(tr[3 + k].multiply(e_s[:, [k]]) for k in range(3)).tocsr() @ self.T
        self.geo = StripGeometry(b=0.5 * np.asarray(s.chord, float), a=np.asarray(s.elastic_axis, float),
                                 rho=float(air_density))
        self.coefficients = flat_plate(lift_slope)
        Ma, Da = apparent_mass(self.geo.b, self.geo.a, np.full(self.ns, self.U), self.geo.rho)
        H = [self.S_plunge.toarray(), self.S_pitch.toarray()]  # (ns, nq) each: h (up) and alpha
        Mad = np.zeros_like(self.beams.mass)
        self.Dad = np.zeros_like(self.beams.mass)
        for i in range(2):
            for j in range(2):
                Mad += H[i].T @ ((self.width * Ma[:, i, j])[:, None] * H[j])
                self.Dad += H[i].T @ ((self.width * Da[:, i, j])[:, None] * H[j])
        self.mass = self.beams.mass - Mad
        self.atol = self.beams.atol
        self.n_states = self.ns * self.n_lag
        self._pm = None  # the strips' pitch from the nodes' rotation vectors (full numbering), when first needed

    def forces(self, t, q, v, z):
        f, _ = self.beams.forces(t, q, v, np.zeros(0))
        v_ea = np.stack([self.S_chord @ v, self.S_plunge @ v], axis=1)
        alpha, alpha_dot = self.S_pitch @ q, self.S_pitch @ v
        V_air = np.tile([self.U, 0.0], (self.ns, 1))
        F, M, zdot, _ = strip_forces(self.geo, self.circ, self.coefficients, V_air, v_ea, alpha, alpha_dot,
                                     z.reshape(self.ns, -1))
        w = self.width
        # virtual work of the strip loads on the strips' motion, the moments through the rotation
        # vector's left Jacobian like the beam's own (SpinningBeams.forces)
        load = self.S_chord.T @ (w * F[:, 0]) + self.S_plunge.T @ (w * F[:, 1])
        mom = np.asarray(self.T.T @ self._pitch_moment(q, w * M)).reshape(-1)
        f = f - load - mom - self.Dad @ v
        return f, zdot.reshape(-1)

    def _pitch_moment(self, q, m_strip):
        """Nodal moments (full numbering) of the strips' pitch moments, turned by the left Jacobian."""
        n = self.beams.fe.n_nodes
        full = np.zeros((n, 6))
        u = np.asarray(self.T @ q).reshape(-1, 6)
        Pm = self._pitch_map_full()
        full[:, 3:] = (Pm.T @ m_strip).reshape(n, 3)
        full[:, 3:] = np.einsum("nji,nj->ni", left_jacobian(u[:, 3:]), full[:, 3:])
        return full.reshape(-1)

    def _pitch_map_full(self):
        if self._pm is None:
            # (ns, 3 n): the strip's pitch from the nodes' rotation vectors (full numbering)
            S = (self.S_pitch @ self.T.T).tocsr()
            n = self.beams.fe.n_nodes
            cols = np.arange(6 * n).reshape(n, 6)[:, 3:].reshape(-1)
            self._pm = S[:, cols]
        return self._pm

    def outputs(self, t, q, v, z):
        u = np.asarray(self.T @ q).reshape(-1, 6)
        n = u.shape[0]
        rec = [n - 1, n // 2]
        return np.concatenate([u[rec, 2], u[rec, 4]])


@dataclass
class WingRun:
    """A wing's free response (``trajectory.y``: tip and mid-span plunge (m) and pitch (rad)) and
    its identified modes (corrected for the scheme)."""

    speed: float
    trajectory: Trajectory
    identification: Identification
    modes: tuple


def simulate_wing(fe, sections, U: float, duration: float, *, air_density: float = 1.225,
                  lift_slope: float = 2 * np.pi, circulation: str = "rfa", n_lag: int = 4, f_max_hz: float = 60.0,
                  points_per_period: float = 30.0, rho_inf: float = 0.8, kick: float = 1e-4,
                  f_kick_hz: float = 10.0) -> WingRun:
    """Free response of the wing (``fe``, ``sections``: :func:`~windflutter.frozen.wing.build_wing`)
    at airspeed ``U`` (m/s), started from rest in the undeflected shape with the velocity of a
    bent and twisted wing (tip plunge ``kick`` x span, tip pitch ``kick`` rad, at
    ``f_kick_hz``: no initial load, so no initial acceleration of the stiff in-plane and
    axial motions) and the modes identified from it.
    ``f_max_hz`` sets the step (``points_per_period`` steps in its period); the scheme's
    ``rho_inf`` damps the much higher beam modes."""

    if not (np.isfinite(U) and U > 0):
        raise InputError("U", U, "a positive airspeed (m/s)")
    circ = make_circulation(circulation, n_lag)
    dyn = WingDynamics(fe, sections, U, air_density, lift_slope, circ)
    x = np.asarray(fe.nodes, float)
    span = float(np.ptp(x[:, 1]))
    s = (x[:, 1] - x[:, 1].min()) / span
    w = 2 * np.pi * f_kick_hz
    u = np.zeros((fe.n_nodes, 6))
    u[:, 2] = w * kick * span * s**2  # plunge rate (up)
    u[:, 3] = w * 2 * kick * s  # its slope's: the rotation about +x of a bend along +y
    u[:, 4] = w * kick * s  # nose-up twist rate about the span (+y)
    v0 = np.linalg.lstsq(dyn.T.toarray(), u.reshape(-1), rcond=None)[0]
    dt = step_for_frequency(f_max_hz, points_per_period)
    q0 = np.zeros_like(v0)
    tr = integrate(dyn, q0, v0, np.zeros(dyn.n_states), dt, duration, rho_inf=rho_inf, tol=1e-9)
    ident = identify(tr.t, tr.y / np.abs(tr.y).max(axis=0))
    return WingRun(speed=float(U), trajectory=tr, identification=ident, modes=corrected_modes(ident, dt, rho_inf))
