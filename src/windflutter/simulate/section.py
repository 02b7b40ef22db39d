"""The 2-DOF typical section in the time domain: the structure of
:class:`~windflutter.section.model.TypicalSection` under the nonlinear strip force law
(:mod:`windflutter.simulate.strips`) with its lag states, integrated by generalized-alpha.

Coordinates ``q = (h, alpha)``: plunge of the elastic axis UP (m) and pitch nose-up (rad); the
section's mass centre lies ``x_alpha b`` aft of the elastic axis, so its kinetic energy has the
cross term ``-S h' alpha'``.  Flat-plate polar ``Cl = Cla alpha`` (``TypicalSection.lift_slope``),
the air along the chord at rest.  The apparent mass (Theodorsen) is linear and joins the mass.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.strip import apparent_mass
from windflutter.aero.unsteady import circulation as make_circulation
from windflutter.errors import InputError
from windflutter.simulate.identify import Identification, identify
from windflutter.simulate.integrator import Trajectory, integrate, step_for_frequency
from windflutter.simulate.strips import StripGeometry, flat_plate, strip_forces
from windflutter.section.model import TypicalSection

__all__ = ["SectionDynamics", "SectionRun", "simulate_section"]


class SectionDynamics:
    """:class:`~windflutter.simulate.integrator.Dynamics` of a typical section at airspeed ``U``."""

    def __init__(self, sec: TypicalSection, U: float, circ):
        if sec.plunge_angle != 0.0:
            raise InputError("plunge_angle", sec.plunge_angle, "0 (the plunge along the lift) in the time domain")
        self.sec, self.U, self.circ = sec, float(U), circ
        b = np.array([sec.semi_chord])
        a = np.array([sec.elastic_axis])
        self.geo = StripGeometry(b=b, a=a, rho=sec.air_density)
        scale = sec.lift_slope / (2 * np.pi) if sec.scale_apparent_mass else 1.0
        Ma, Da = apparent_mass(b, a, np.array([U]), sec.air_density, scale)
        Ms = np.array([[sec.mass, -sec.static_moment], [-sec.static_moment, sec.inertia]])
        self.mass = Ms - Ma[0, :2, :2]
        self.Da = Da[0, :2, :2]
        self.K = np.diag([sec.plunge_stiffness, sec.pitch_stiffness])
        self.coefficients = flat_plate(sec.lift_slope)
        self.n_lag = circ.n_lag

    def forces(self, t, q, v, z):
        F, M, zdot, _ = strip_forces(self.geo, self.circ, self.coefficients, np.array([[self.U, 0.0]]),
                                     np.array([[0.0, v[0]]]), q[1:2], v[1:2], z.reshape(1, -1))
        f = self.K @ q - self.Da @ v - np.array([F[0, 1], M[0]])
        return f, zdot.reshape(-1)

    def outputs(self, t, q, v, z):
        return np.array([q[0], q[1]])


@dataclass
class SectionRun:
    """A section's free response (``trajectory.y``: h (m), alpha (rad)) and its identified modes."""

    speed: float
    trajectory: Trajectory
    identification: Identification


def simulate_section(sec: TypicalSection, U: float, duration: float | None = None, kick=(0.0, 0.01),
                     circulation="rfa", n_lag: int = 4, rho_inf: float = 1.0,
                     points_per_period: float = 60.0) -> SectionRun:
    """Free response of ``sec`` at airspeed ``U`` (m/s) released from ``kick = (h (m), alpha (rad))``.

    ``circulation``: the lag realisation of :func:`windflutter.aero.unsteady.circulation`
    (``"rfa"``: the fit the p-method uses; ``"jones"``).  The step gives ``points_per_period``
    steps in the period of the highest natural frequency; ``duration`` defaults to 40 periods of
    the lowest.  ``rho_inf = 1`` (trapezoidal) adds no numerical damping, so the sign of the
    growth rate is the system's.
    """
    if not (np.isfinite(U) and U > 0):
        raise InputError("U", U, "a positive airspeed (m/s)")
    circ = make_circulation(circulation, n_lag)
    model = SectionDynamics(sec, U, circ)
    w = np.sqrt(np.linalg.eigvals(np.linalg.solve(model.mass, model.K)).real)
    dt = step_for_frequency(w.max() / (2 * np.pi), points_per_period)
    duration = 40 * 2 * np.pi / w.min() if duration is None else duration
    q0 = np.asarray(kick, float)
    z0 = np.full(circ.n_lag, q0[1])  # at rest in the kicked pitch: the lags have settled on it
    tr = integrate(model, q0, np.zeros(2), z0, dt, duration, rho_inf=rho_inf)
    return SectionRun(speed=float(U), trajectory=tr, identification=identify(tr.t, tr.y, order=4 + circ.n_lag))
