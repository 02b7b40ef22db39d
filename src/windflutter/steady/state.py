"""The deflected steady state of a rotor: static equilibrium under centrifugal and BEM aerodynamic loads.

For a rotor model whose hub (or blade root) is clamped -- typically one blade built with its
global geometry -- in an axisymmetric steady inflow (no gravity, shear or yaw), a fixed-point
iteration finds the deflected blade and the loads on it:

1. the strips take the geometry of the current displacement ``u``
   (:func:`windflutter.steady.geometry.deflection`: the linear strip motions composed into
   moderate rotations along the span -- translation, shortening of the bent span, finite
   rotation of the chord and span directions, among them the elastic twist);
2. BEM induction on those strips (:func:`windflutter.aero.induction.sections_induction`, the
   coned form: every strip sees the wind in its own plane);
3. strip loads from ``Cl, Cd, Cm`` at the induced angle of attack, at the elastic-axis point
   (:func:`windflutter.steady.loads.strip_loads`), plus the pure moments that give the linear
   structure the section moments of the deformed configuration
   (:func:`windflutter.steady.loads.second_order_moments`);
4. the static solution ``(K + K_sigma,cf - Omega^2 K_r) u = F_cf + motion_map^T (loads)`` with
   the centrifugal loads ``F_cf`` of the rigidly spinning sections
   (:func:`windflutter.rotor.spin.spin_terms`), the geometric stiffness ``K_sigma,cf``
   of their linear static stress and the spin softening ``K_r`` of the same rigid sections
   (the centrifugal force on the displaced mass is ``F_cf + Omega^2 K_r u``); one
   factorization per call;
5. Aitken-relaxed update of ``u``; stop when the strip motions and strip loads change by less
   than ``tol`` (relative to their largest values).

The result is linearized about with the geometric stiffness of the *total* steady stress
(``K_sigma`` of ``u``: centrifugal and aerodynamic; beams: axial force, shells: membrane
resultants), the deflected strips and their induced inflow.  Not in it: the follower-load
stiffness of the aerodynamic loads (their change with the blade motion belongs to the
aerodynamic operator), and the bending-moment terms of the geometric stiffness (used here in
step 3 as loads, not as a matrix).

With ``SteadyOptions(deflection=False)`` the undeformed linearization of the seed is returned:
``u`` the linear centrifugal displacement and ``K_sigma`` of its stress, both exactly as the
prestress of :func:`windflutter.rotor.rotating.rotor_terms`; BEM and loads on the undeformed
strips (with ``cone=False`` the BEM of ``AeroelasticModel(induction=True)``).

Units: SI (m, rad, s, N, N m, W); angles in rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.aero.induction import BEMResult, sections_induction
from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.aero.strip import OperatingPoint, SectionFlow
from windflutter.errors import InputError, ModelError
from windflutter.rotor.rotating import centrifugal_load, rotating_nodes
from windflutter.rotor.spin import spin_terms
from windflutter.steady import exact as ex
from windflutter.steady.fixedpoint import aitken, strip_change
from windflutter.steady.geometry import (Deflection, deflected_sections, deflection, pitching_frames, strip_motion,
                                         tip_motion)
from windflutter.steady.loads import (StripLoads, nodal_loads, rotor_totals, second_order_moments,
                                      strip_loads)
from windflutter.structure.corotational import beam_tangent, chained_configuration, internal_forces
from windflutter.structure.linalg import NotPositiveDefinite, SPDFactor
from windflutter.structure.prestress import axial_geometric_stiffness, geometric_stiffness, static_solve

__all__ = ["SteadyOptions", "SteadyState", "steady_state"]


@dataclass(frozen=True)
class SteadyOptions:
    """How to find the steady state.

    Parameters
    ----------
    deflection : iterate to the deflected state (True) or return the undeformed linearization
        of the seed (False).
    cone : coned BEM (each strip sees the normal wind projected on its own plane); False: the
        rotor-plane BEM of ``AeroelasticModel(induction=True)``.
    second_order : add the deformed-configuration moments of the aerodynamic loads.
    finite_rotations : moderate-rotation kinematics of the strips (rotations composed along the
        span: shortening of the bent span, bending of the twisted sections); False: linear
        (``p + u``, ``exp(theta)``), see :mod:`windflutter.steady.geometry`.
    tol : relative change of strip motions and loads at which the iteration stops (-).
    max_iterations : bound on the iterations.
    relaxation : initial relaxation factor of the displacement update (then Aitken's).
    max_deflection : a strip translation beyond this fraction of the rotor radius is taken as
        divergence (no steady state).
    corotational : beam-only models (default): the equilibrium of the co-rotational beam
        (:mod:`windflutter.steady.exact`, exact for any reference line of the sections), started
        from the linear one; False (and always for shells): the linear structure with
        second-order load corrections.  The state's ``f_internal`` and ``Ksigma`` are then the
        co-rotational beams' internal forces and axial forces.
    rotating_group : node group of the rotating part (centrifugal load, spin softening).
    strict : raise :class:`~windflutter.errors.ModelError` when the iteration does not converge
        (default); False returns the last iterate with ``converged=False``.
    stress : compute the state's ``Ksigma`` (default); False leaves it None, for a caller that
        linearizes about the deflected shape with a stress stiffness of its own (the deflected shell
        blade: the linear structure's, 0.18 s a point on the NREL 5 MW shell blade, went unused).
    bem : extra keywords for :func:`~windflutter.aero.induction.sections_induction`
        (``tip_loss``, ``hub_loss``, ``high_thrust``, ``xtol``).
    """

    deflection: bool = True
    cone: bool = True
    second_order: bool = True
    finite_rotations: bool = True
    tol: float = 1e-6
    max_iterations: int = 60
    relaxation: float = 1.0
    max_deflection: float = 0.5
    corotational: bool = True
    rotating_group: str = "rotor"
    strict: bool = True
    stress: bool = True
    bem: dict | None = None

    def __post_init__(self):
        for name in ("deflection", "cone", "second_order", "finite_rotations", "corotational", "strict"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise InputError(f"steady.{name}", getattr(self, name), "true or false")
        if not (np.isfinite(self.tol) and 0 < self.tol < 1):
            raise InputError("steady.tol", self.tol, "a relative tolerance in (0, 1)")
        if not (isinstance(self.max_iterations, (int, np.integer)) and self.max_iterations >= 1):
            raise InputError("steady.max_iterations", self.max_iterations, "a positive integer")
        if not (np.isfinite(self.relaxation) and 0 < self.relaxation <= 1.5):
            raise InputError("steady.relaxation", self.relaxation, "a factor in (0, 1.5]")
        if not (np.isfinite(self.max_deflection) and self.max_deflection > 0):
            raise InputError("steady.max_deflection", self.max_deflection, "a positive fraction of the rotor radius")


@dataclass(frozen=True)
class SteadyState:
    """The steady state of the rotor at one operating point.

    Attributes
    ----------
    u : (n_dof,) static displacement (m, rad), full numbering.
    sections : the deflected strips (the input strips with ``deflection=False``).
    bem : BEM state on them (a, a', phi, alpha, cl, cd, ...).
    flow : induced section flow on them; ``cl, cd, cm`` : (ns,) polar coefficients at ``flow.alpha``.
    strip_loads : (ns, 6) aerodynamic force (N) and moment (N m) per strip at its elastic-axis
        point, global axes (without the second-order moments).
    load_aero, load_centrifugal : (n_dof,) nodal loads (N, N m); ``load`` is their sum.
    Ksigma : (n_dof, n_dof) CSR geometric stiffness of the total steady stress (full numbering);
        None when not asked for (``SteadyOptions.stress``).
    thrust (N), torque (N m), power (W) : rotor totals for ``n_blades`` blades.
    iterations : fixed-point iterations (0 without deflection).  converged : bool.
    residual : last relative change of the strip motions / loads.
    tip_deflection : (nb, 3) tip translation (m) of each blade present in its pitching frame:
        flapwise (downwind), edgewise (towards the trailing edge), along the blade.
    tip_rotation : (nb, 3) tip rotation (rad) in the same axes; ``[:, 2]`` is the elastic twist
        (negative towards feather).
    frames : (nb, 3, 3) the blade frames (columns x, y, z, global).
    wind_speed (m/s), omega (rad/s), air_density (kg/m^3), pitch (rad) : the operating point.
    configuration : the co-rotational beam's equilibrium
        (:class:`~windflutter.structure.corotational.BeamConfiguration`) when it gave the state,
        else None; ``u`` is then its node translations and rotation vectors, ``load_aero`` the
        nodal loads of that equilibrium (lever arms of the deformed blade).
    f_internal : (n_dof,) the structure's internal nodal forces (N, N m) at the state: ``K u``, or
        the co-rotational beams' ``f_int``; ``f_internal - load`` is the reaction of the supports
        and links (the hub links' geometric stiffness, :func:`~windflutter.system.blade.
        link_geometric_stiffness`).  ``Ksigma`` is the axial-force geometric stiffness of the same
        stress, on the undeformed geometry.
    """

    u: np.ndarray
    sections: AeroSections
    bem: BEMResult
    flow: SectionFlow
    cl: np.ndarray
    cd: np.ndarray
    cm: np.ndarray
    strip_loads: np.ndarray
    load_aero: np.ndarray
    load_centrifugal: np.ndarray
    Ksigma: sp.csr_matrix | None
    thrust: float
    torque: float
    power: float
    iterations: int
    converged: bool
    residual: float
    tip_deflection: np.ndarray
    tip_rotation: np.ndarray
    frames: np.ndarray
    wind_speed: float
    omega: float
    air_density: float
    pitch: float
    configuration: object = None
    f_internal: np.ndarray | None = None

    @property
    def load(self) -> np.ndarray:
        """Total static load (N, N m), full numbering: centrifugal + aerodynamic."""
        return self.load_centrifugal + self.load_aero

    @property
    def tip_flap(self) -> float:
        """Flapwise tip deflection of blade 0 (m, downwind positive)."""
        return float(self.tip_deflection[0, 0])

    @property
    def tip_edge(self) -> float:
        """Edgewise tip deflection of blade 0 (m, towards the trailing edge positive)."""
        return float(self.tip_deflection[0, 1])

    @property
    def tip_twist(self) -> float:
        """Elastic tip twist of blade 0 (rad, negative towards feather)."""
        return float(self.tip_rotation[0, 2])

    def operating_point(self, rotor: RotorGeometry) -> OperatingPoint:
        """The :class:`~windflutter.aero.strip.OperatingPoint` of this state (with its induction),
        for the strip aerodynamics on :attr:`sections`."""
        return OperatingPoint(self.wind_speed, self.omega, self.air_density, rotor, self.pitch,
                              induction=(self.bem.a, self.bem.ap))


def _check_inputs(fe, struct, sections, rotor, wind_speed, omega, n_blades, air_density, pitch):
    checks = (
        ("rotor_geometry", rotor, rotor is not None, "a RotorGeometry (hub centre, shaft axis, wind direction)"),
        ("wind_speed", wind_speed, np.isfinite(wind_speed) and wind_speed >= 0, "a non-negative speed (m/s)"),
        ("omega", omega, np.isfinite(omega), "a finite rotor speed (rad/s)"),
        ("n_blades", n_blades, isinstance(n_blades, (int, np.integer)) and n_blades >= 1,
         "a positive number of blades"),
        ("air_density", air_density, np.isfinite(air_density) and air_density > 0, "a positive density (kg/m^3)"),
        ("pitch", pitch, np.isfinite(pitch), "a finite extra pitch (rad)"),
        ("sections", 0, sections is not None and sections.n_sections > 0, "aerodynamic strips (a model with blades)"),
    )
    for field, value, ok, expected in checks:
        if not ok:
            raise InputError(field, value, expected)
    if sections.motion_map.shape != (6 * sections.n_sections, fe.n_dof) or struct.n_dof != fe.n_dof:
        raise InputError("sections.motion_map", sections.motion_map.shape,
                         f"({6 * sections.n_sections}, {fe.n_dof}): strips of this FE model")


def _unit_centrifugal(fe, struct, axis: np.ndarray, hub: np.ndarray, group: str, seed: bool):
    """``(f1, u1, K1)`` at 1 rad/s: the centrifugal load (N), its linear static displacement (m, rad)
    and the reduced static operator's centrifugal part ``K_sigma(u1) - K_r`` (None for the seed's
    load), kept on ``struct`` beside its cached reduced matrices (a sweep over rotor speed needs them
    at every speed: a factorization and the geometric stiffness, 0.1 s a speed on the NREL 5 MW shell
    blade)."""
    cache = struct.__dict__.setdefault("_unit_centrifugal", {})
    key = (tuple(np.round(axis, 12)), tuple(np.round(hub, 9)), group, bool(seed))
    hit = cache.get(key)
    if hit is not None and hit[0] is fe:
        return hit[1]
    nodes = rotating_nodes(fe, group)
    if seed:
        f1, K1 = centrifugal_load(struct.M, fe, nodes, axis, hub), None
        u1 = static_solve(struct, f1)
    else:
        _, Kr1, f1 = spin_terms(fe, struct.M, nodes, axis, hub)
        u1 = static_solve(struct, f1)
        K1 = struct.reduce(sp.csr_matrix(geometric_stiffness(fe, u1, constraint_forces=struct.K @ u1 - f1) - Kr1))
    cache[key] = (fe, (f1, u1, K1))
    return f1, u1, K1


class _Static:
    """The centrifugal load and the static operator ``K + K_sigma,cf - Omega^2 K_r`` of the rotating
    structure, factorized once.

    ``seed=True``: the centrifugal load and prestress of :func:`windflutter.rotor.rotating.rotor_terms`
    (``Omega^2 S^T M_tt S R``, the seed's); else the rigid-section centrifugal loads of
    :func:`windflutter.rotor.spin.spin_terms` (beam sections and lumped masses as rigid bodies:
    their offsets and rotary inertia) and the matching spin softening.
    """

    def __init__(self, fe, struct, rotor: RotorGeometry, omega: float, group: str, seed: bool):
        axis = np.asarray(rotor.shaft_axis, float)
        axis = axis / np.linalg.norm(axis)
        hub = np.asarray(rotor.hub_center, float)
        self.struct = struct
        if omega == 0:
            self.f_cf, self.u_cf, K_cf1 = np.zeros(fe.n_dof), np.zeros(fe.n_dof), None
        else:  # all linear in omega^2: the unit-speed terms are computed once per structure
            f1, u1, K_cf1 = _unit_centrifugal(fe, struct, axis, hub, group, seed)
            self.f_cf, self.u_cf = omega**2 * f1, omega**2 * u1  # u_cf: the linear centrifugal prestress
        self._fac = None
        if not seed:
            K = struct.Kr if K_cf1 is None else struct.Kr + omega**2 * K_cf1
            K = sp.csc_matrix(K)

            try:
                self._fac = SPDFactor(K)
            except NotPositiveDefinite:
                raise ModelError(f"the rotating structure has no stable static equilibrium at {omega:.4g} rad/s: "
                                 "K + K_sigma - Omega^2 K_r is not positive definite (spin softening beyond the "
                                 "stiffness; check the rotor speed and the model's constraints)") from None

    def solve(self, f: np.ndarray) -> np.ndarray:
        return self.struct.expand(self._fac.solve(self.struct.reduce_vector(f)))


@dataclass
class _Aero:
    """Everything the aerodynamics gives at one displacement."""

    defl: Deflection
    sections: AeroSections
    bem: BEMResult
    loads: StripLoads
    extra: np.ndarray


def _aero_at(u, sections, rotor, V, omega, n_blades, rho, pitch, options: SteadyOptions, deflected: bool,
             xtol: float = 1e-12, defl: Deflection | None = None) -> _Aero:
    """Strip geometry, BEM and strip loads at the displacement ``u`` (undeformed strips unless
    ``deflected``); ``xtol``: the BEM's bisection tolerance (rad) unless ``options.bem`` sets one.
    With ``defl`` (an exact deflection: :mod:`windflutter.steady.exact`) ``u`` is not used and no
    second-order moments are added (the co-rotational beam holds them)."""
    exact = defl is not None
    if not exact:
        defl = deflection(sections, strip_motion(sections, u), options.finite_rotations and deflected)
    sec = deflected_sections(sections, rotor, defl) if deflected else sections
    kw = {"xtol": xtol, **(options.bem or {})}
    bem = sections_induction(sec, rotor, V, omega, n_blades=n_blades, pitch=pitch, air_density=rho,
                             cone=options.cone, **kw)
    sl = strip_loads(sec, OperatingPoint(V, omega, rho, rotor, pitch, induction=(bem.a, bem.ap)))
    extra = np.zeros_like(sl.loads)
    if deflected and options.second_order and not exact:
        extra = second_order_moments(sections, defl, sl.loads)
    return _Aero(defl=defl, sections=sec, bem=bem, loads=sl, extra=extra)


def _iterate(static: _Static, sections, rotor, V, omega, n_blades, rho, pitch, options: SteadyOptions, u0=None):
    """Aitken-relaxed fixed point ``u = S^-1 (F_cf + F_aero(u))`` from ``u0`` (default: the centrifugal
    displacement); (u, aero, iterations, residual, converged)."""
    radius = float(np.max(sections.radius)) + float(np.max(sections.width))
    u = static.u_cf if u0 is None else np.asarray(u0, float)
    aero = _aero_at(u, sections, rotor, V, omega, n_blades, rho, pitch, options, True)
    r_prev, w, res = None, options.relaxation, 1.0
    for it in range(1, options.max_iterations + 1):
        u_new = static.solve(static.f_cf + nodal_loads(sections, aero.loads.loads + aero.extra))
        r = u_new - u
        w = aitken(w, r, r_prev)
        u, r_prev = u + w * r, r
        # the inflow angles need not be exact while the geometry still moves: BEM bisection to a
        # thousandth of the last relative change (1e-5 .. 1e-12 rad; about 1e-9 rad at the end)
        new = _aero_at(u, sections, rotor, V, omega, n_blades, rho, pitch, options, True,
                       xtol=float(np.clip(1e-3 * res, 1e-12, 1e-5)))
        if np.abs(new.defl.shift).max() > options.max_deflection * radius:
            raise ModelError(f"no steady state at V = {V:.4g} m/s, Omega = {omega:.4g} rad/s: the blade deflection "
                             f"grows beyond {options.max_deflection:g} x the rotor radius after {it} iterations "
                             "(static aeroelastic divergence or an unstable rotating structure)")
        res = strip_change(new, aero, sections)
        aero = new
        if res <= options.tol:
            return u, aero, it, res, True
    if not options.strict:
        return u, aero, options.max_iterations, res, False
    raise ModelError(f"the steady state at V = {V:.4g} m/s, Omega = {omega:.4g} rad/s did not converge in "
                     f"{options.max_iterations} iterations (last relative change {res:.3g} > tol {options.tol:g}): "
                     "no steady state found there (API: SteadyOptions max_iterations, relaxation)")


def steady_state(fe, struct, sections: AeroSections, rotor_geometry: RotorGeometry, wind_speed: float,
                 omega: float, *, n_blades: int, air_density: float = 1.225, pitch: float = 0.0,
                 options: SteadyOptions | None = None, initial=None) -> SteadyState:
    """Deflected steady state of a clamped rotor (or blade) at one operating point (module docstring).

    Parameters
    ----------
    fe, struct : the FE model and its assembly (:func:`~windflutter.structure.assembly.assemble`),
        with the rotating nodes in ``fe.node_groups[options.rotating_group]`` and its hub or blade
        roots clamped.
    sections : its undeformed strips (from :func:`~windflutter.mesh.turbine.build_model`).
    rotor_geometry : hub centre, shaft axis, wind direction.
    wind_speed : free wind (m/s).  omega : rotor speed (rad/s) about the shaft axis.
    n_blades : blades of the rotor (the loads of the blades present are scaled to it).
    air_density : kg/m^3.  pitch : extra pitch of the aerodynamics on top of the model's
        ``e_chord`` (rad, as ``OperatingPoint.pitch``); build the model with its pitch
        (``MeshSettings.pitch``) so that the structure is turned too.
    options : :class:`SteadyOptions`.
    initial : optional displacement (n_dof,) to start the iteration from, e.g. the steady state of
        a nearby operating point (the same state is reached, in fewer iterations).

    Returns
    -------
    SteadyState

    Raises
    ------
    InputError for bad arguments; ModelError when there is no steady state (divergence, no
    convergence within ``options.max_iterations``, an unstable rotating structure).
    """
    options = options or SteadyOptions()
    V, om, rho, pitch = float(wind_speed), float(omega), float(air_density), float(pitch)
    _check_inputs(fe, struct, sections, rotor_geometry, V, om, n_blades, rho, pitch)
    static = _Static(fe, struct, rotor_geometry, om, options.rotating_group, seed=not options.deflection)
    config = None
    if options.deflection:
        u, aero, iterations, residual, converged = _iterate(static, sections, rotor_geometry, V, om, n_blades, rho,
                                                            pitch, options, u0=initial)
    else:
        u, iterations, residual, converged = static.u_cf, 0, 0.0, True
        aero = _aero_at(u, sections, rotor_geometry, V, om, n_blades, rho, pitch, options, False)
    load_aero, f_cf = nodal_loads(sections, aero.loads.loads), static.f_cf
    if options.deflection and converged and options.corotational and len(fe.shell_conn) == 0:
        config, aero, load_aero, f_cf, it, residual, converged = _exact(
            fe, struct, sections, rotor_geometry, u, (V, om, n_blades, rho, pitch), options)
        iterations += it
        u = ex.configuration_displacement(fe, config)
    f_internal, Ksigma = _stress(fe, struct, u, config, load_aero + f_cf, options.stress)
    frames = pitching_frames(sections, rotor_geometry)
    tip_d, tip_r = tip_motion(sections, aero.defl, frames)
    thrust, torque, power = rotor_totals(aero.sections, rotor_geometry, aero.loads.loads, om, n_blades)
    return SteadyState(
        u=u, sections=aero.sections, bem=aero.bem, flow=aero.loads.flow, cl=aero.loads.cl, cd=aero.loads.cd,
        cm=aero.loads.cm, strip_loads=aero.loads.loads, load_aero=load_aero,
        load_centrifugal=f_cf, Ksigma=Ksigma, f_internal=f_internal, thrust=thrust, torque=torque,
        power=power, iterations=iterations, converged=converged, residual=residual, tip_deflection=tip_d,
        tip_rotation=tip_r, frames=frames, wind_speed=V, omega=om, air_density=rho, pitch=pitch,
        configuration=config)


def _stress(fe, struct, u, config, load, stiffness: bool = True):
    """(internal nodal forces (n_dof,), axial-force geometric stiffness Ksigma) of the steady state:
    ``K u`` and the linear elements' axial forces for the linear structure; for a co-rotational
    equilibrium ``config`` its beams' internal forces and axial forces (the linear ones of its
    large-rotation ``u`` would not be its stress).  ``load`` (n_dof,): the state's nodal loads (the
    shell ribs' term of the geometric stiffness takes the constraint forces ``K u - load``).
    ``stiffness`` False: the linear structure's Ksigma is None (not computed)."""
    if config is None:
        f = struct.K @ u
        return f, (geometric_stiffness(fe, u, constraint_forces=f - load) if stiffness else None)

    tan = beam_tangent(fe, config)
    return internal_forces(fe, config, tan), axial_geometric_stiffness(fe, tan.resultants[:, 6])


def _exact(fe, struct, sections, rotor, u, point, options: SteadyOptions):
    """The co-rotational steady state from the linear one ``u`` (:mod:`windflutter.steady.exact`):
    (config, aero, nodal aero loads, nodal centrifugal loads, iterations, residual, converged)."""
    V, om, n_blades, rho, pitch = point
    cf = ex.centrifugal_loads(fe, om, np.asarray(rotor.hub_center, float), np.asarray(rotor.shaft_axis, float),
                              options.rotating_group)

    def aero_at(defl, xtol):
        return _aero_at(None, sections, rotor, V, om, n_blades, rho, pitch, options, True, xtol=xtol, defl=defl)

    try:
        config, aero, f_aero, it, res, ok = ex.iterate_corotational(
            fe, struct, sections, chained_configuration(fe, u), aero_at, cf, options.tol, options.max_iterations)
    except ModelError as err:
        raise ModelError(f"no co-rotational steady state at V = {V:.4g} m/s, Omega = {om:.4g} rad/s: {err}") from None
    if not ok and options.strict:
        raise ModelError(f"the co-rotational steady state at V = {V:.4g} m/s, Omega = {om:.4g} rad/s did not converge "
                         f"in {options.max_iterations} iterations (last relative change {res:.3g} > tol {options.tol:g}): "
                         "no steady state found there (solver.corotational false: the linear structure's; API: "
                         "SteadyOptions max_iterations)")
    return config, aero, f_aero, cf(config)[0], it, res, ok
