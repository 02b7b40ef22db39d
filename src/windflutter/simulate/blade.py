"""A blade of a turbine on a rigid hub spinning at a constant rotor speed, in the time domain.

The blade model of ``MeshSettings(part="blade", model="beam")`` (clamped at the root), in the
frame spinning with the rotor: co-rotational beams (:mod:`windflutter.simulate.beam`),
centrifugal and Coriolis loads of the current configuration (:mod:`windflutter.simulate.inertia`).
It starts from its own static equilibrium under those loads (plus, with aerodynamics, the
strip loads), is kicked by an impulse, and its response is recorded at a few nodes.

Frequencies and damping identified from the response are corrected for the scheme's own period
error and numerical damping at each identified frequency
(:func:`windflutter.simulate.integrator.algorithmic_damping`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.unsteady import circulation as make_circulation
from windflutter.aero_types import RotorGeometry
from windflutter.errors import InputError
from windflutter.mesh.settings import MeshSettings
from windflutter.simulate.beam import SpinningBeams, spin_equilibrium
from windflutter.simulate.identify import Identification, IdentifiedMode, identify
from windflutter.simulate.inertia import SpinningMass
from windflutter.simulate.integrator import Trajectory, algorithmic_damping, integrate, step_for_frequency
from windflutter.simulate.rotor_aero import BladeAero
from windflutter.steady import SteadyOptions, steady_state
from windflutter.structure.assembly import assemble
from windflutter.structure.corotational import beam_tangent, deformed_model
from windflutter.units import DEG, RPM

__all__ = ["BladeRun", "blade_in_vacuum", "blade_in_wind", "corrected_modes", "blade_model", "wind_setup",
           "wind_blade_dynamics"]


@dataclass
class BladeRun:
    """The response (``trajectory.y``: displacements of the recorded nodes, 6 per node), the
    recorded nodes, the identification and the modes corrected for the scheme."""

    rpm: float
    nodes: np.ndarray
    trajectory: Trajectory
    identification: Identification
    modes: tuple


def corrected_modes(ident: Identification, dt: float, rho_inf: float) -> tuple:
    """The oscillatory modes of ``ident`` with frequency and damping corrected for the
    generalized-alpha scheme at step ``dt`` (frequency times its period ratio, damping minus the
    damping it adds), ascending frequency."""
    out = []
    for m in ident.modes:
        if m.frequency_hz <= 0:
            continue
        wh = 2 * np.pi * m.frequency_hz * dt
        zn, ratio = algorithmic_damping(wh, rho_inf)
        f = m.frequency_hz * ratio
        zeta = m.zeta - zn
        lam = complex(-zeta * 2 * np.pi * f / np.sqrt(max(1 - zeta**2, 1e-12)), 2 * np.pi * f)
        out.append(IdentifiedMode(lam=lam, frequency_hz=f, zeta=zeta, share=m.share, sigma_spread=m.sigma_spread,
                                  frequency_spread_hz=m.frequency_spread_hz))
    return tuple(sorted(out, key=lambda m: m.frequency_hz))


def blade_model(turbine, n_span: int = 30):
    """``(fe, struct, sections, apex, axis)`` of one beam blade clamped at the root."""
    from windflutter.mesh.turbine import build_model, rotor_geometry  # noqa: PLC0415

    fe, sections = build_model(turbine, MeshSettings(part="blade", model="beam", n_span=n_span))
    geo = rotor_geometry(turbine)
    axis = np.asarray(geo.shaft_axis, float)
    return fe, assemble(fe), sections, np.asarray(geo.hub_center, float), axis / np.linalg.norm(axis)


def _kick(dyn, fe, nodes, amplitude):
    """``(q0, v0)``: released from the static deflection (beam tangent at the base) under unit
    forces at the recorded nodes (largest translation ``amplitude``, m) plus that under unit
    moments (largest rotation ``amplitude / 2``, rad), with the velocity of unit impulses at the
    same nodes (largest translational velocity ``amplitude`` m/s) for the higher modes."""

    T = dyn.T
    K = np.asarray((T.T @ beam_tangent(fe, dyn.base, elements=dyn.el).K @ T).todense())
    out = []
    for part, scale in ((slice(0, 3), 1.0), (slice(3, 6), 0.5)):
        f = np.zeros((fe.n_dof // 6, 6))
        f[nodes, part] = 1.0
        q = np.linalg.solve(K, T.T @ f.reshape(-1))
        out.append(q * (scale * amplitude / np.abs((T @ q).reshape(-1, 6)[:, part]).max()))
    imp = np.zeros((fe.n_dof // 6, 6))
    imp[nodes] = [1.0, 1.0, 1.0, 0.3, 0.3, 0.3]
    v0 = np.linalg.solve(dyn.mass, T.T @ imp.reshape(-1))
    v0 *= amplitude / np.abs((T @ v0).reshape(-1, 6)[:, :3]).max()
    return out[0] + out[1], v0


def blade_in_vacuum(turbine, rpm: float, duration: float = 8.0, n_span: int = 30, f_max_hz: float = 8.0,
                    points_per_period: float = 30.0, rho_inf: float = 0.9, amplitude: float = 1e-3,
                    n_record: int = 6, progress=None) -> BladeRun:
    """Free vibration of a blade spinning at ``rpm`` (rev/min) in vacuum, kicked by impulses at
    ``n_record`` nodes along the span (:func:`_kick`, size ``amplitude``); the time step
    from ``f_max_hz``, the highest frequency retained (``points_per_period`` steps per period)."""

    if not (np.isfinite(rpm) and rpm >= 0):
        raise InputError("rpm", rpm, "a non-negative rotor speed (rev/min)")
    fe, struct, _, apex, axis = blade_model(turbine, n_span)
    inertia = SpinningMass(fe, fe.node_groups["rotor"], rpm * RPM, axis, apex)
    base = spin_equilibrium(fe, struct.T, inertia)
    M = assemble(deformed_model(fe, base)).M
    nodes = np.unique(np.linspace(1, fe.n_nodes - 1, n_record).astype(int))

    def outputs(cfg, u, ud):
        return u.reshape(-1, 6)[nodes].reshape(-1)

    dyn = SpinningBeams(fe, struct.T, M, base, inertia, outputs=outputs)
    dt = step_for_frequency(f_max_hz, points_per_period)
    q0, v0 = _kick(dyn, fe, nodes, amplitude)
    tr = integrate(dyn, q0, v0, np.zeros(0), dt, duration, rho_inf=rho_inf, progress=progress)
    y = tr.y / np.maximum(np.abs(tr.y).max(axis=0), 1e-300)  # every channel on one scale
    ident = identify(tr.t, y, sv_tol=1e-7)
    return BladeRun(rpm=float(rpm), nodes=nodes, trajectory=tr, identification=ident,
                    modes=corrected_modes(ident, dt, rho_inf))


def blade_in_wind(turbine, wind_speed: float, rpm: float, duration: float = 20.0, pitch_deg: float | None = None,
                  n_span: int = 30, f_max_hz: float = 8.0, points_per_period: float = 30.0, rho_inf: float = 0.9,
                  amplitude: float = 1e-3, n_record: int = 6, circulation: str = "jones", air_density: float = 1.225,
                  progress=None, dynamic_stall: bool = False) -> BladeRun:
    """Free response of one blade on a rigid hub spinning at ``rpm`` in the wind ``wind_speed``
    (m/s, along the shaft as in method p), strip aerodynamics with lag states and the steady
    state's BEM induction frozen (:mod:`windflutter.simulate.rotor_aero`).  The blade starts at its
    own equilibrium (found from the co-rotational steady state) and is kicked as in
    :func:`blade_in_vacuum`.  ``pitch_deg`` defaults to the operating curve's at the wind speed;
    ``dynamic_stall``: Oye's separation-point state per strip (:mod:`windflutter.simulate.strips`)."""

    dyn = wind_blade_dynamics(turbine, wind_speed, rpm, pitch_deg, n_span, circulation, air_density, dynamic_stall)
    fe, aero, base = dyn.fe, dyn.external, dyn.base
    nodes = np.unique(np.linspace(1, fe.n_nodes - 1, n_record).astype(int))
    dyn.set_outputs(lambda cfg, u, ud: u.reshape(-1, 6)[nodes].reshape(-1))
    dt = step_for_frequency(f_max_hz, points_per_period)
    q0, v0 = _kick(dyn, fe, nodes, amplitude)
    tr = integrate(dyn, q0, v0, aero.steady_lags(base), dt, duration, rho_inf=rho_inf, progress=progress)
    y = tr.y / np.maximum(np.abs(tr.y).max(axis=0), 1e-300)
    ident = identify(tr.t, y, sv_tol=1e-7)
    return BladeRun(rpm=float(rpm), nodes=nodes, trajectory=tr, identification=ident,
                    modes=corrected_modes(ident, dt, rho_inf))


def wind_blade_dynamics(turbine, wind_speed: float, rpm: float, pitch_deg: float | None = None, n_span: int = 30,
                        circulation: str = "jones", air_density: float = 1.225,
                        dynamic_stall: bool = False) -> SpinningBeams:
    """The equations of :func:`blade_in_wind` (one blade on a rigid hub in the wind, strips with lag
    states, frozen BEM induction) about the blade's own equilibrium: a :class:`SpinningBeams` whose
    ``external`` is the :class:`BladeAero` and whose ``base`` the equilibrium."""
    if not (np.isfinite(wind_speed) and wind_speed > 0):
        raise InputError("wind_speed", wind_speed, "a positive wind speed (m/s)")
    if not (np.isfinite(rpm) and rpm > 0):
        raise InputError("rpm", rpm, "a positive rotor speed (rev/min)")
    fe, struct, sections, apex, axis, st = wind_setup(turbine, wind_speed, rpm, pitch_deg, n_span, air_density)
    omega = rpm * RPM
    inertia = SpinningMass(fe, fe.node_groups["rotor"], omega, axis, apex)
    aero = BladeAero(fe, sections, st.configuration, wind_speed, omega, axis, apex, axis, air_density,
                     (st.bem.a, st.bem.ap), st.sections.origin, make_circulation(circulation),
                     dynamic_stall=dynamic_stall)
    base = spin_equilibrium(fe, struct.T, inertia, start=st.configuration, external=aero.static_loads)
    M = assemble(deformed_model(fe, base)).M + aero.mass_added
    return SpinningBeams(fe, struct.T, M, base, inertia, external=aero, n_states=aero.ns * aero.n_lag)


def wind_setup(turbine, wind_speed, rpm, pitch_deg, n_span, air_density):
    """The blade model at the pitch and its co-rotational steady state (BEM induction)."""
    from windflutter.mesh.turbine import build_model  # noqa: PLC0415

    if pitch_deg is None:
        oc = turbine.operating_curve
        if oc is None:
            raise InputError("pitch", None, "a pitch angle (the turbine has no operating curve)")
        pitch = float(oc.pitch_at(wind_speed))
    else:
        pitch = float(pitch_deg) * DEG
    fe, sections = build_model(turbine, MeshSettings(part="blade", model="beam", n_span=n_span, pitch=pitch))
    struct = assemble(fe)
    axis = np.asarray(turbine.nacelle.shaft_axis(), float)
    axis = axis / np.linalg.norm(axis)
    apex = np.asarray(turbine.rotor_apex, float)
    rotor = RotorGeometry(hub_center=apex, shaft_axis=axis, wind_direction=axis)
    st = steady_state(fe, struct, sections, rotor, wind_speed, rpm * RPM, n_blades=int(turbine.n_blades),
                      air_density=air_density, options=SteadyOptions(corotational=True))
    if st.configuration is None:
        raise InputError("steady state", "not co-rotational", "the co-rotational steady state of a beam blade")
    return fe, struct, sections, apex, axis, st
