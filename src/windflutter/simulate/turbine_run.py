"""Set up, kick, run and identify the whole turbine in the time domain
(:mod:`windflutter.simulate.turbine`: the formulation).

* Ground part (:func:`ground_part`): the support FE model (``MeshSettings(part="support")``:
  tower beams, nacelle mass, hub node) in its constrained coordinates, the hub rigid body at the
  apex (the turbine's hub mass), the drivetrain from the nacelle data (shaft stiffness and
  damping, generator inertia times the gear ratio squared; ``flexible``: azimuth and generator
  coordinates, ``rigid`` when the shaft is rigid or the generator has no inertia).
* Blades: the beam blade at the pitch, its co-rotational equilibrium spinning (in the wind with
  the frozen-induction strips, :func:`windflutter.simulate.blade.blade_in_wind`'s setup).
* Kick: blade 1 released from its static deflection under unit forces and moments at the
  recorded nodes, the tower top from its static deflection under unit fore-aft and side-side hub
  forces; no initial velocity (no net angular momentum about the shaft: the free generator's
  rigid-body mode is not started).
* Identification: the hub's translations and rotations and the blades' recorded displacements
  in multi-blade coordinates (collective, cosine, sine: ground-fixed, so a whirling pair shows
  at its BW and FW frequencies, like method p's modes), each channel scaled to unit peak, by the
  matrix pencil; frequencies and damping corrected for the scheme.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.unsteady import circulation as make_circulation
from windflutter.errors import InputError
from windflutter.mesh.parts import hub_mass
from windflutter.mesh.settings import MeshSettings
from windflutter.simulate.beam import spin_equilibrium
from windflutter.simulate.blade import blade_model, corrected_modes, wind_setup
from windflutter.simulate.identify import Identification, identify
from windflutter.simulate.inertia import SpinningMass
from windflutter.simulate.integrator import Trajectory, integrate, step_for_frequency
from windflutter.simulate.mode_kick import mode_kick
from windflutter.simulate.rotor_aero import BladeAero
from windflutter.simulate.turbine import BladePart, GroundPart, TurbineDynamics, axis_turn, check_blades, rigid_map
from windflutter.structure.assembly import assemble
from windflutter.structure.corotational import beam_tangent, deformed_model
from windflutter.system.damping import blade_damping_matrix, blade_mu, support_modal_damping, tower_ratios
from windflutter.units import RPM

__all__ = ["TurbineRun", "ground_part", "turbine_dynamics", "simulate_turbine", "multiblade_channels", "kick",
           "KICK_LOADS"]


@dataclass
class TurbineRun:
    """The response of the whole turbine: ``trajectory.y`` (hub 6, then per blade the recorded
    nodes' 6 displacements), the multi-blade channels identified, and the modes corrected for the
    scheme (ascending frequency)."""

    rpm: float
    wind_speed: float
    nodes: np.ndarray
    trajectory: Trajectory
    identification: Identification
    modes: tuple
    #: ``--kick MODE``: method p's mode the run started in (a ModeRecord: its name and eigenvalue), else None
    kicked: object = None

    def nearest(self, lam: complex):
        """The identified mode nearest the eigenvalue ``lam`` (1/s) in the complex plane."""
        return min(self.modes, key=lambda m: abs(m.lam - complex(lam)))


def ground_part(turbine, axis, drivetrain: str = "flexible", rotor_mass: np.ndarray | None = None) -> GroundPart:
    """The support, hub rigid body and drivetrain (module docstring).  ``rotor_mass``: the rotor's
    (6, 6) rigid-body mass at the apex (blades and hub): given, the support gets the files' tower
    modal damping on the tower modes with the rotor lumped at the hub
    (:func:`windflutter.system.damping.support_modal_damping`, the damping's definition)."""
    from windflutter.mesh.turbine import build_model  # noqa: PLC0415

    fe, _ = build_model(turbine, MeshSettings(part="support", model="beam"))
    st = assemble(fe)
    T = st.T.tocsr()
    Ms = np.asarray((T.T @ st.M @ T).todense())
    Ks = np.asarray((T.T @ st.K @ T).todense())
    hub = int(fe.node_groups["hub"][0])
    H = np.asarray(T[6 * hub: 6 * hub + 6].todense())
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    nac = turbine.nacelle
    k = float(nac.drivetrain_torsional_stiffness)
    c = float(getattr(nac, "drivetrain_torsional_damping", 0.0) or 0.0)
    Jg = float(nac.gear_ratio) ** 2 * float(nac.generator_inertia)
    if drivetrain not in ("flexible", "rigid"):
        raise InputError("drivetrain", drivetrain, "flexible or rigid")
    flexible = drivetrain == "flexible" and np.isfinite(k) and Jg > 0
    ns = Ms.shape[0]
    nd = 2 if flexible else 1
    nF = ns + nd
    L = np.zeros((6, nF))
    L[:, :ns] = H
    L[3:, ns] = n  # the azimuth about the shaft
    Mh = _hub_rigid_mass(turbine)
    M = np.zeros((nF, nF))
    K = np.zeros((nF, nF))
    C = np.zeros((nF, nF))
    M[:ns, :ns], K[:ns, :ns] = Ms, Ks
    if rotor_mass is not None:
        C[:ns, :ns] = _tower_damping(turbine, st, Ms, Ks, H.T @ rotor_mass @ H)
    M += L.T @ Mh @ L
    gen = np.zeros(nF)  # the generator's absolute rotation: the nacelle's about the shaft + its own
    gen[:ns] = n @ H[3:]
    gen[nF - 1] = 1.0
    M += Jg * np.outer(gen, gen)
    labels = tuple(f"support:{i}" for i in range(ns)) + (("azimuth", "generator") if flexible else ("azimuth",))
    if flexible:
        d = np.zeros(nF)
        d[ns], d[ns + 1] = 1.0, -1.0
        K += k * np.outer(d, d)
        C += c * np.outer(d, d)
    return GroundPart(M=M, C=C, K=K, L=L, labels=labels)


def _hub_rigid_mass(turbine) -> np.ndarray:
    """(6, 6) the hub's rigid-body mass at the apex (the turbine's hub mass and inertia)."""

    hm = hub_mass(turbine, 0)
    cg = skew3(np.asarray(hm.offset, float))
    Mh = np.zeros((6, 6))
    Mh[:3, :3] = hm.mass * np.eye(3)
    Mh[:3, 3:], Mh[3:, :3] = -hm.mass * cg, hm.mass * cg
    Mh[3:, 3:] = np.asarray(hm.inertia, float) - hm.mass * cg @ cg
    return Mh


def _tower_damping(turbine, st, Ms, Ks, Mr):
    """The files' tower modal ratios on the support's modes with the rotor lumped at the hub."""

    fa, ss = tower_ratios(turbine)
    md = np.asarray(st.M.diagonal())
    T = st.T

    def direction(v):
        e = (md * np.asarray(T @ v) ** 2).reshape(-1, 6).sum(axis=0)
        return e[0], e[1]

    D = support_modal_damping(Ks, Ms, Mr, fa, ss, direction)
    return np.zeros_like(Ks) if D is None else D


def skew3(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _blade_part(turbine, rpm, wind_speed, pitch_deg, n_span, circulation, air_density, damping="none",
                dynamic_stall=False):
    """The blade at its spinning equilibrium (in the wind: with the strips), and its pitch (deg)."""

    omega = rpm * RPM
    if wind_speed == 0.0:
        if pitch_deg not in (None, 0.0):
            raise InputError("pitch", pitch_deg, "0 in vacuum (the blade model at pitch 0)")
        fe, struct, _, apex, axis = blade_model(turbine, n_span)
        inertia = SpinningMass(fe, fe.node_groups["rotor"], omega, axis, apex)
        base = spin_equilibrium(fe, struct.T, inertia)
        M = np.asarray(assemble(deformed_model(fe, base)).M.todense())
        return BladePart(fe=fe, T=struct.T, M=M, base=base, inertia=inertia,
                         damping=_blade_damping(turbine, deformed_model(fe, base), damping)), apex, axis

    fe, struct, sections, apex, axis, st = wind_setup(turbine, wind_speed, rpm, pitch_deg, n_span, air_density)
    inertia = SpinningMass(fe, fe.node_groups["rotor"], omega, axis, apex)
    aero = BladeAero(fe, sections, st.configuration, wind_speed, omega, axis, apex, axis, air_density,
                     (st.bem.a, st.bem.ap), st.sections.origin, make_circulation(circulation),
                     dynamic_stall=dynamic_stall)
    base = spin_equilibrium(fe, struct.T, inertia, start=st.configuration, external=aero.static_loads)
    M = np.asarray(assemble(deformed_model(fe, base)).M.todense()) + np.asarray(aero.mass_added)
    a = np.broadcast_to(np.asarray(st.bem.a, float), (aero.ns,))
    axial = (1.0 - a)[:, None] * (float(wind_speed) * axis)[None, :]
    return BladePart(fe=fe, T=struct.T, M=M, base=base, inertia=inertia, aero=aero, wind_axial=axial,
                     wind_rest=aero.wind - axial, damping=_blade_damping(turbine, deformed_model(fe, base), damping)), \
        apex, axis


def _blade_damping(turbine, fe, damping):
    """The files' blade damping (stiffness-proportional per direction,
    :func:`windflutter.system.damping.blade_damping_matrix`) of the blade ``fe`` at its steady
    (deflected) configuration, or None for ``damping="none"``: built on the deflected elements,
    the damping acts on their deformation rates and not on the rigid rotation of a deflected
    element (the undeformed blade's matrix would damp that motion of the bent blade)."""
    if damping not in ("none", "file"):
        raise InputError("damping", damping, "none or file (the turbine files' structural damping)")
    if damping == "none":
        return None

    C = blade_damping_matrix(fe, blade_mu(turbine))
    return None if C is None else C.tocsr()


def turbine_dynamics(turbine, rpm: float, wind_speed: float = 0.0, pitch_deg: float | None = None,
                     n_span: int = 30, n_record: int = 3, circulation: str = "jones", air_density: float = 1.225,
                     drivetrain: str = "flexible", damping: str = "none", dynamic_stall: bool = False) -> TurbineDynamics:
    """The :class:`TurbineDynamics` of ``turbine`` at ``rpm`` in ``wind_speed`` (0: vacuum),
    recording ``n_record`` blade nodes (the tip last); the mean rotor load on the hub at the
    start is the support's preload.  ``damping``: ``none`` or ``file`` (the turbine files' blade
    and tower damping, defined as method p's); ``dynamic_stall``: Oye's separation point per strip."""
    N = check_blades(turbine.n_blades)
    blade, apex, axis = _blade_part(turbine, float(rpm), float(wind_speed), pitch_deg, int(n_span), circulation,
                                    air_density, damping, dynamic_stall)
    rotor = None
    if damping == "file":  # the rotor's rigid-body mass at the apex: the blades turned to their azimuths + hub


        G = rigid_map(np.asarray(blade.fe.nodes, float), apex)  # the undeformed blade's structural mass
        Mb = G.T @ np.asarray(assemble(blade.fe).M.todense()) @ G
        rotor = _hub_rigid_mass(turbine)
        for k in range(N):
            Q = np.kron(np.eye(2), axis_turn(axis, 2 * np.pi * k / N))
            rotor = rotor + Q @ Mb @ Q.T
    ground = ground_part(turbine, axis, drivetrain, rotor)
    nn = blade.fe.n_nodes
    record = np.unique(np.linspace(nn - 1, 1, n_record).round().astype(int))
    dyn = TurbineDynamics(blade, ground, N, float(rpm) * RPM, axis, apex, record=record)
    dyn.preload = dyn.hub_load(0.0)
    return dyn


#: the kick's nodal load on blade 1 (force x, y, z, moment x, y, z; the blade's axes at azimuth 0:
#: x about downwind (flap), y in the rotor plane (edge), z along the blade)
KICK_LOADS = (1.0, 1.0, 1.0, 0.3, 0.3, 0.3)


def kick(dyn: TurbineDynamics, amplitude: float = 1e-2, tower_amplitude: float = 2e-3,
         loads=KICK_LOADS, blades=None) -> np.ndarray:
    """Initial displacements (module docstring): blade 1's static deflection under ``loads`` at
    the recorded nodes, largest translation ``amplitude`` (m) -- or every blade's, times its
    weight in ``blades`` (N,) (e.g. ``cos(2 pi b / N)``: a cyclic kick); the tower top's under unit
    fore-aft and side-side hub forces, ``tower_amplitude`` (m; 0: none)."""

    b = dyn.b
    T = dyn.T
    K = np.asarray((T.T @ beam_tangent(b.fe, b.base, elements=dyn.el).K @ T).todense())
    f = np.zeros((b.fe.n_dof // 6, 6))
    f[dyn.record] = np.asarray(loads, float)
    qb = np.linalg.solve(K, T.T @ f.reshape(-1))
    qb *= amplitude / np.abs((T @ qb).reshape(-1, 6)[:, :3]).max()
    ns = dyn.g.labels.index("azimuth")
    Ks = dyn.g.K[:ns, :ns]
    H = dyn.g.L[:, :ns]
    xs = np.linalg.solve(Ks, H[:3].T @ np.array([1.0, 1.0, 0.0]))
    xs *= float(tower_amplitude) / np.abs(H[:3] @ xs).max()
    q0 = np.zeros(dyn.nF + dyn.N * dyn.nq)
    q0[:ns] = xs
    weights = np.eye(dyn.N)[0] if blades is None else np.asarray(blades, float)
    if weights.shape != (dyn.N,):
        raise InputError("kick blades", weights.tolist(), f"{dyn.N} weights, one per blade")
    for k, w in enumerate(weights):
        q0[dyn.nF + k * dyn.nq: dyn.nF + (k + 1) * dyn.nq] = w * qb
    return q0


def multiblade_channels(dyn: TurbineDynamics, t: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(nt, k): the hub's 6 displacements and the recorded blade displacements in multi-blade
    coordinates (collective, cosine, sine of the azimuth ``Omega t + 2 pi b / N``)."""
    N, nr = dyn.N, 6 * len(dyn.record)
    hub = y[:, :6]
    ub = y[:, 6:].reshape(len(t), N, nr)
    psi = dyn.omega * np.asarray(t)[:, None] + 2 * np.pi * np.arange(N)[None, :] / N
    a0 = ub.mean(axis=1)
    a1 = (2.0 / N) * np.einsum("tb,tbk->tk", np.cos(psi), ub)
    b1 = (2.0 / N) * np.einsum("tb,tbk->tk", np.sin(psi), ub)
    return np.hstack([hub, a0, a1, b1])


def scaled_channels(dyn: TurbineDynamics, t, y, floor: float = 1e-4) -> np.ndarray:
    """The :func:`multiblade_channels` each scaled to unit peak, without those whose peak is below
    ``floor`` of the largest of their kind (hub translations, hub rotations, blade translations,
    blade rotations): a channel the kick left still holds only round-off, which the scaling would
    make as large as the response."""
    ch = multiblade_channels(dyn, t, y)
    peak = np.abs(ch).max(axis=0)
    kind = np.zeros(ch.shape[1], dtype=int)
    kind[3:6] = 1
    rest = np.arange(ch.shape[1] - 6) % 6
    kind[6:] = np.where(rest < 3, 2, 3)
    keep = np.zeros(ch.shape[1], bool)
    for k in range(4):
        sel = kind == k
        if np.any(sel) and peak[sel].max() > 0:
            keep |= sel & (peak >= floor * peak[sel].max())
    return ch[:, keep] / peak[keep]


def simulate_turbine(turbine, rpm: float, wind_speed: float = 0.0, *, duration: float = 30.0,
                     pitch_deg: float | None = None, n_span: int = 30, f_max_hz: float = 8.0,
                     points_per_period: float = 30.0, rho_inf: float = 0.9, amplitude: float = 1e-2,
                     circulation: str = "jones", air_density: float = 1.225, drivetrain: str = "flexible",
                     sv_tol: float = 1e-7, tol: float = 1e-7, kick_loads=KICK_LOADS, tower_kick: float = 2e-3,
                     kick_blades=None, damping: str = "none", kick_mode: str | None = None,
                     progress=None, dynamic_stall: bool = False) -> TurbineRun:
    """Free response of the whole turbine (module docstring) and its identified modes.

    ``amplitude``, ``kick_loads`` and ``kick_blades``: the blades' kick (:func:`kick`);
    ``tower_kick`` the tower top's (m).  ``kick_mode``: instead, start in method p's mode of that
    name at the point, its largest translation ``amplitude``
    (:func:`windflutter.simulate.mode_kick.mode_kick`).  ``damping``: ``none`` or ``file`` (:func:`turbine_dynamics`).
    ``tol``: the Newton iteration's relative increment (1e-7 of the largest
    displacement: a force error far below what the identification resolves).  Other parameters
    as :func:`windflutter.simulate.run.simulate`."""

    if not (np.isfinite(rpm) and rpm >= 0):
        raise InputError("rpm", rpm, "a non-negative rotor speed (rev/min)")
    if wind_speed > 0 and rpm <= 0:
        raise InputError("rpm", rpm, "a positive rotor speed in the wind")
    dyn = turbine_dynamics(turbine, rpm, wind_speed, pitch_deg, n_span, circulation=circulation,
                           air_density=air_density, drivetrain=drivetrain, damping=damping,
                           dynamic_stall=dynamic_stall)
    mode = None
    if kick_mode is None:
        q0 = kick(dyn, amplitude, tower_kick, kick_loads, kick_blades)
        v0 = np.zeros_like(q0)
    else:

        q0, v0, mode = mode_kick(dyn, turbine, kick_mode, wind_speed, pitch_deg, n_span, amplitude, damping,
                                 max_hz=max(f_max_hz, 1.0))
    z0 = np.tile(dyn.steady_lags(), dyn.N)
    dt = step_for_frequency(f_max_hz, points_per_period)
    tr = integrate(dyn, q0, v0, z0, dt, duration, rho_inf=rho_inf, tol=tol, progress=progress)
    ident = identify(tr.t, scaled_channels(dyn, tr.t, tr.y), sv_tol=sv_tol)
    return TurbineRun(rpm=float(rpm), wind_speed=float(wind_speed), nodes=dyn.record, trajectory=tr,
                      identification=ident, modes=corrected_modes(ident, dt, rho_inf), kicked=mode)
