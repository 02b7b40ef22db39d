"""The operating-point model of a whole turbine in the ground-fixed frame (multi-blade coordinates).

:class:`OperationalModel` builds, once per turbine and options, the parts of
:mod:`windflutter.system`: the blade substructure (per blade pitch), the support, the hub rigid
body and the drivetrain.  At an operating point (wind speed, rotor speed, pitch) it

1. finds the steady state of the blade (:func:`windflutter.steady.steady_state`: BEM induction,
   deflection and elastic twist under centrifugal and aerodynamic loads, the geometric stiffness of
   the total steady stress) -- or the seed's undeformed state (``deflection=False``);
2. forms the blade's rotating-frame matrices on a fixed-interface basis (its modes at that state
   plus static corrections for the aerodynamic load shapes) and the strip aerodynamics about the
   steady state (:func:`windflutter.aero.operators.make_operator`, transport velocity included,
   :mod:`windflutter.system.blade_aero`);
3. couples ``N`` blades with the ground-fixed part in multi-blade coordinates
   (:func:`windflutter.system.multiblade.multiblade_system`): a time-invariant first-order system
   whose eigenvalues are the damped modes of the turbine.

Assumptions (the same as HAWCStab2's): an isotropic rotor in axisymmetric steady inflow (the wind
along the shaft: no tilt, shear, yaw or gravity in the steady state), linearized about it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.aero.flow import OperatingPoint
from windflutter.aero.operators import make_operator
from windflutter.aero.sections import RotorGeometry
from windflutter.errors import InputError
from windflutter.mesh.parts import hub_mass
from windflutter.mesh.settings import MeshSettings
from windflutter.steady import SteadyOptions, steady_state
from windflutter.steady.geometry import pitching_frames
from windflutter.structure.assembly import assemble
from windflutter.structure.modal import m_orthonormalize, symmetric_eigs
from windflutter.structure.shell import shell_element_blocks, turned_blocks
from windflutter.system.blade import RotorBlade, link_geometric_stiffness
from windflutter.system.blade_aero import (balanced_projection, blade_system, project_blade_aero, quasi_steady_blocks,
                                           reduced_blade_system)
from windflutter.system.blade_basis import BladeBasis
from windflutter.system.damping import (blade_damping_matrix, blade_mu, shell_modal_damping, support_modal_damping,
                                        tower_ratios)
from windflutter.system.deflected import deflected_blade
from windflutter.system.deflected_shell import deflected_shell_blade
from windflutter.system.reference import structural_reference, tower_wall_waves
from windflutter.system.multiblade import FixedFrame, MultiBladeSystem, axis_rotation, multiblade_system
from windflutter.system.operational_options import OperationalOptions, missing_curve_error  # noqa: F401  (re-exported)
from windflutter.system.pitch import pitch_rotation, rotate_blade
from windflutter.system.support import Drivetrain, fixed_frame, rigid_body_mass, support_model
from windflutter.units import RPM

#: supports with more free DOFs than this (shell towers) are reduced to SUPPORT_AUTO_MODES modes
#: plus the six hub-load corrections unless ``support_modes`` says otherwise
SUPPORT_FULL_ORDER_LIMIT = 400
SUPPORT_AUTO_MODES = 30

#: relative change of the steady state's strip motions and loads at which its iteration stops: the
#: linearization needs the state to a few digits (1e-5 moves the NREL 5 MW onsets by < 1e-4 RPM)
STEADY_TOL = 1e-5

@dataclass
class PointSystem:
    """The model at one operating point: the multi-blade system and what is needed to read its modes.

    wind_speed (m/s), omega (rad/s), pitch (rad); ``mbc`` the time-invariant system; ``blade``
    the substructure; ``Phi`` (nq_blade, m) its fixed-interface basis; ``support`` the support
    model (None for ``part="rotor"``); ``steady`` the steady state (or None); ``labels`` of the
    ground-fixed coordinates; ``blade_structure`` the blade's structural ``(M, K)`` (rotating-frame
    and steady-stress terms, no aerodynamics) in its coordinates and ``blade_damping`` its structural
    ``C`` (file damping and Coriolis); ``fixed`` the ground-fixed part (:class:`FixedFrame`), so that
    the system without aerodynamics can be formed at the same steady state (a decay-rate audit:
    ``docs/scripts/whirl_split_audit.py``).
    """

    wind_speed: float
    omega: float
    pitch: float
    mbc: MultiBladeSystem
    blade: RotorBlade
    Phi: np.ndarray | None
    support: object
    steady: object
    n_blades: int
    labels: list
    blade_system: object = None
    blade_structure: tuple | None = None
    #: negative eigenvalues of the blade's full-order structural stiffness (its basis's factorization:
    #: a local mode of a shell mesh can be far from the basis's lowest modes); 0 definite, None not known
    blade_negative: int | None = None
    blade_damping: np.ndarray | None = field(default=None, repr=False)
    fixed: FixedFrame | None = field(default=None, repr=False)
    #: (3, ns, m) flap, edge, torsion strip motion of each basis vector (filled when modes are read)
    basis_components: np.ndarray | None = field(default=None, repr=False)
    #: (3, 3) the blade's pitching frame (columns x flapwise, y edgewise, z the pitch axis; undeformed
    #: axes turned with the pitch: steady.geometry.pitching_frames), the axes of ModeRecord.tip
    tip_frame: np.ndarray | None = field(default=None, repr=False)
    #: (3, m) the tip flap, edge (m) and torsion (rad) of each basis vector in ``tip_frame`` (filled
    #: when modes are read)
    tip_basis: np.ndarray | None = field(default=None, repr=False)
    #: the turbine's own structural modes that name the modes (:mod:`windflutter.system.identity`)
    reference: object = field(default=None, repr=False)
    #: the blade's full-numbering initial-stress matrix of the steady state and the hub-link term it was
    #: linearized with (what :meth:`OperationalModel.assemble_point` takes)
    ksigma: object = field(default=None, repr=False)
    klink: np.ndarray | None = field(default=None, repr=False)
    #: the reduction of the blade's aerodynamic states in ``blade_system`` and ``mbc``
    #: (:class:`~windflutter.system.blade_aero.AeroStateProjection`), None: every state
    aero_projection: object = field(default=None, repr=False)


def lowest_elastic(K: np.ndarray, M: np.ndarray) -> float:
    """Smallest finite eigenvalue (real part) of ``K x = w M x`` on a blade's elastic coordinates
    (the six hub coordinates held), ``inf`` if there is none."""
    import scipy.linalg as sla

    e = slice(6, None)
    w = sla.eigvals(K[e, e], M[e, e])
    w = w[np.isfinite(w)]
    return float(np.min(w.real)) if w.size else float("inf")


def structural_margin(ps: PointSystem) -> float:
    """Smallest eigenvalue (1/s^2) of the blade's structural static stiffness over its mass at the
    point ``ps`` -- rotating-frame and steady-stress terms, no aerodynamics, hub clamped (its reduced
    ``blade_structure``).  Negative: the FE structure under its steady stress is statically unstable
    on its own (e.g. a local buckling of shell elements).  ``-inf`` where the reduced structure is
    positive but the full-order stiffness is not (``ps.blade_negative``: a local mode far from the
    basis's lowest modes, whose eigenvalue is not computed)."""
    M, K = ps.blade_structure
    low = lowest_elastic(K, M)
    if low > 0 and ps.blade_negative:
        return float("-inf")
    return low


class OperationalModel:
    """A turbine ready for operating-point (Campbell) analyses; parts cached."""

    def __init__(self, turbine, options: OperationalOptions | None = None):
        self.turbine = turbine
        self.options = options or OperationalOptions()
        g = turbine
        axis = g.nacelle.shaft_axis()
        # axisymmetric inflow: the wind along the shaft (HAWCStab2's steady state)
        self.rotor = RotorGeometry(hub_center=g.rotor_apex, shaft_axis=axis, wind_direction=axis)
        self.n_blades = int(g.n_blades)
        if self.n_blades < 3:
            raise InputError("assembly.number_of_blades", self.n_blades, "3 or more blades (isotropic rotor)")
        self._blades: dict = {}
        self._support = None
        self._last_steady: dict = {}
        self._rotor_mass: np.ndarray | None = None  # :meth:`with_rotor_mass`
        o = self.options
        self._basis = BladeBasis(o.basis_modes, corrections=o.corrections, correction_tol=o.correction_tol)

    # -- parts -------------------------------------------------------------------------------
    def _mesh(self, part: str, pitch: float = 0.0):
        return MeshSettings(**{"model": self.options.model, **self.options.mesh, "part": part, "pitch": float(pitch)})

    def blade(self, pitch: float) -> RotorBlade:
        """The fixed-interface blade at collective ``pitch`` (rad), cached: the pitch-0 model meshed and
        assembled once and turned about the pitch axis (:mod:`windflutter.system.pitch`)."""
        key = round(float(pitch), 8)
        if key not in self._blades:
            fe, st, sec = self._blade0()
            mu = blade_mu(self.turbine) if self.options.damping == "file" else None
            shell = len(fe.shell_conn) > 0
            if shell and getattr(self, "_shell_damping0", False) is False:  # built once, turned with the pitch
                self._shell_damping0 = shell_modal_damping(fe, st, sec, mu)
            R, blocks = None, None
            if shell and self.options.structure == "deflected":  # the elements the deflected blade turns
                blocks = self._shell_blocks0()
            if key != 0.0:
                R, root = pitch_rotation(self.turbine, pitch)
                fe, st, sec = rotate_blade(fe, st, sec, R, root, self.rotor.hub_center, self.rotor.shaft_axis)
                if blocks is not None:
                    Re = np.broadcast_to(R, (len(fe.shell_conn), 3, 3))
                    blocks = tuple(turned_blocks(B, Re) for B in blocks)
            if shell:
                D = self._shell_damping0
                D = D.rotated(R) if D is not None and R is not None else D
            else:
                D = blade_damping_matrix(fe, mu, K=st.K)
            self._blades[key] = RotorBlade(fe, st, sec, self.rotor.hub_center, self.rotor.shaft_axis, damping=D,
                                           shell_blocks=blocks)
        return self._blades[key]

    def keep_blades(self, pitches=()) -> None:
        """Drop the cached pitched blades except those at ``pitches`` (rad) and the pitch-0 blade (the
        reference's), and the steady-state warm starts (kept per blade, wind speed and pitch): a
        Campbell above rated turns the blade to a new pitch at every wind speed, and a shell blade is
        hundreds of MB (:func:`windflutter.system.campbell.campbell`'s workers keep one)."""
        keep = {0.0} | {round(float(p), 8) for p in pitches}
        self._blades = {k: b for k, b in self._blades.items() if k in keep}
        self._last_steady = {}

    def _shell_blocks0(self):
        """The pitch-0 shell blade's element blocks (:func:`~windflutter.structure.shell.
        shell_element_blocks`), computed once: a pitched blade's are these turned by the pitch."""
        if getattr(self, "_blocks_zero", None) is None:
            self._blocks_zero = shell_element_blocks(self._blade0()[0])
        return self._blocks_zero

    def _blade0(self):
        """The pitch-0 blade model ``(fe, struct, sections)``, built once."""
        if getattr(self, "_blade_zero", None) is None:
            from windflutter.mesh.turbine import build_model

            fe, sec = build_model(self.turbine, self._mesh("rotor_blade", 0.0))
            self._blade_zero = (fe, assemble(fe), sec)
        return self._blade_zero

    def variant(self, turbine, options: OperationalOptions | None = None) -> "OperationalModel":
        """A model of ``turbine`` (a changed copy of this one's: support, nacelle, drivetrain) that
        shares this model's cached blade parts and identities -- the blade's data must be unchanged
        (design sensitivities, :mod:`windflutter.sensitivity`)."""
        out = OperationalModel(turbine, options or self.options)
        out._blades, out._blade_zero = self._blades, getattr(self, "_blade_zero", None)
        out._blocks_zero = getattr(self, "_blocks_zero", None)
        out._reference = getattr(self, "_reference", None)
        return out

    def reference(self):
        """The structural identities of this model (:func:`windflutter.system.identity.
        structural_reference`: the blade's standstill modes, the support's own modes), cached."""
        if getattr(self, "_reference", None) is None:

            self._reference = structural_reference(self.blade(0.0), self.support())
        return self._reference

    def support(self):
        """The support model (None for the rotor on a fixed nacelle), cached."""
        if self.options.part == "rotor":
            return None
        if self._support is None:
            from windflutter.mesh.turbine import build_model

            fe, _ = build_model(self.turbine, self._mesh("support"))
            st = assemble(fe)
            basis = None
            n_sup = self.options.support_modes
            if n_sup is None and st.nq > SUPPORT_FULL_ORDER_LIMIT:
                n_sup = SUPPORT_AUTO_MODES  # shell towers: a modal basis, beam towers stay at full order
            if n_sup is not None:
                basis = _support_basis(st, n_sup)
            sm = support_model(fe, st, basis=basis)
            if self.options.damping == "file":
                sm.D = self._support_damping(sm)
            self._support = sm
        return self._support

    def _support_damping(self, sm):
        """The files' tower modal ratios on the turbine's tower modes (support + rotor lumped at the hub)."""
        fa, ss = tower_ratios(self.turbine)
        if self.options.tower_damping is not None:
            fa = ss = np.array([float(self.options.tower_damping)])
        Mr = sm.H.T @ (self.rotor_rigid_mass() if self._rotor_mass is None else self._rotor_mass) @ sm.H
        md = np.asarray(sm.struct.M.diagonal())

        def direction(v):
            u = np.asarray(sm.expand @ v)
            e = (md * u**2).reshape(-1, 6).sum(axis=0)
            return e[0], e[1]

        D = support_modal_damping(sm.K, sm.M, Mr, fa, ss, direction, wall=lambda V: tower_wall_waves(sm, V) >= 0)
        return np.zeros_like(sm.K) if D is None else D

    def with_rotor_mass(self, rotor_mass: np.ndarray) -> "OperationalModel":
        """A :meth:`variant` of this model (same turbine) whose support damping -- the files' tower modal
        ratios, set on the tower modes with the rotor lumped at the hub -- is set with the rotor
        rigid-body mass ``rotor_mass`` (6, 6) (:meth:`rotor_rigid_mass` of a changed blade): the
        support of a rotor of changed blade mass (design sensitivities)."""
        out = self.variant(self.turbine, self.options)
        out._rotor_mass = np.asarray(rotor_mass, float)
        return out

    def rotor_rigid_mass(self, pitch: float = 0.0, blade: RotorBlade | None = None) -> np.ndarray:
        """(6, 6) rigid-body mass of the whole rotor (hub + blades) at the apex, ground-fixed axes:
        ``sum_b Q_b^T (Gamma^T M Gamma) Q_b`` over the blade azimuths plus the hub; ``blade``: that
        blade (at pitch 0) in place of this model's."""
        rb = self.blade(pitch) if blade is None else blade
        G = rb.Gamma
        Mb = G.T @ (rb.struct.M @ G)
        out = self.hub_mass().copy()
        for b in range(self.n_blades):
            R = axis_rotation(self.rotor.shaft_axis, 2 * np.pi * b / self.n_blades)
            Q = np.zeros((6, 6))
            Q[:3, :3] = Q[3:, 3:] = R.T
            out += Q.T @ Mb @ Q
        return out

    def hub_mass(self) -> np.ndarray:
        hm = hub_mass(self.turbine, 0)
        return rigid_body_mass(hm.mass, hm.inertia, hm.offset)

    def drivetrain(self) -> Drivetrain:
        return Drivetrain.from_turbine(self.turbine, mode=self.options.drivetrain)

    def describe(self) -> dict:
        """The modelling assumptions, for reports and result attributes (plain strings / numbers)."""
        o = self.options
        a = o.aero
        if a is None:
            aero = "none"
        elif hasattr(a, "circulation"):
            aero = (f"unsteady strips ({a.circulation} lag states), "
                    f"{'polar tables, local slopes' if a.polar == 'table' else 'flat plate'}"
                    f"{', mean-load terms' if a.mean_loads else ''}{', dynamic stall' if a.dynamic_stall else ''}")
        else:
            aero = f"quasi-steady Theodorsen strips ({getattr(a, 'model', '?')})"

        mu = blade_mu(self.turbine) if o.damping == "file" else None
        fa, ss = tower_ratios(self.turbine) if o.damping == "file" else (np.zeros(0), np.zeros(0))
        if o.damping == "file" and o.tower_damping is not None:
            fa = ss = np.array([float(o.tower_damping)])
        steady = "undeformed"
        if o.deflection:
            beam = "co-rotational beam" if o.corotational and o.model == "beam" else "linear structure, second-order loads"
            steady = f"deflected (BEM, centrifugal + aero loads; {beam})"
        model = o.model
        if o.model == "shell":
            model = f"shell (blade tips: {self._mesh('rotor_blade').tip_closure})"
        return {"frame": "ground-fixed (multi-blade coordinates)", "model": model, "part": o.part,
                "drivetrain": o.drivetrain, "aerodynamics": aero,
                "steady_state": steady,
                "structure": (("linearized about the deflected shape (shell carried to it, membrane stress of "
                               "its loads)" if o.model == "shell" else
                               "linearized about the deflected shape (co-rotational beam, all stress resultants)")
                              if o.structure == "deflected" else "undeformed axis, axial-force geometric stiffness"),
                "induction": f"steady BEM ({o.high_thrust} thrust-induction relation)" if o.induction else "none",
                "blade_damping": "none" if mu is None else (
                    "modal, each fixed-interface mode by its direction shares of " if o.model == "shell" else
                    "") + "stiffness-proportional mu " + ", ".join(f"{x:.3g}" for x in mu),
                "tower_damping": ("modal: fore-aft " + ", ".join(f"{100 * x:.2g} %" for x in fa) + "; side-side "
                                  + ", ".join(f"{100 * x:.2g} %" for x in ss)) if (fa.size or ss.size) else "none",
                "blade_basis": "full order" if o.basis_modes is None else f"{o.basis_modes} fixed-interface modes"
                               + (" + aero corrections" if o.corrections else ""),
                "inflow": "axisymmetric along the shaft (no tilt, shear, yaw, gravity)"}

    # -- operating point ---------------------------------------------------------------------
    def operating_point(self, wind_speed: float) -> tuple[float, float]:
        """(rotor speed rad/s, pitch rad) of the turbine's operating curve at ``wind_speed``."""
        oc = self.turbine.operating_curve
        if oc is None:
            raise missing_curve_error(self.turbine)
        oc.warn_outside(float(wind_speed))
        return float(oc.rotor_speed_at(wind_speed)), float(oc.pitch_at(wind_speed))

    def steady(self, rb: RotorBlade, wind_speed: float, omega: float):
        """The blade's steady state at (V m/s, Omega rad/s), or None without aerodynamics."""
        o = self.options
        if o.aero is None or wind_speed <= 0 or not rb.sections.n_sections:
            return None

        key = (id(rb), round(float(wind_speed), 9))
        prev = self._last_steady.get(key)
        initial = None if prev is None else prev.u * (omega / prev.omega) ** 2 if prev.omega > 0 else prev.u
        own_stress = o.structure == "deflected" and len(rb.fe.shell_conn) > 0  # deflected_shell_blade's stress
        so = SteadyOptions(deflection=o.deflection, corotational=bool(o.corotational), tol=STEADY_TOL,
                           bem={"high_thrust": o.high_thrust}, stress=not own_stress)
        st = steady_state(rb.fe, rb.struct, rb.sections, self.rotor, wind_speed, omega, n_blades=self.n_blades,
                          air_density=o.air_density, options=so, initial=initial)
        self._last_steady[key] = st  # a warm start for the next rotor speed at this wind speed and pitch
        return st

    def at(self, wind_speed: float, rpm: float | None = None, pitch: float | None = None) -> PointSystem:
        """The multi-blade system at ``wind_speed`` (m/s); rotor speed (RPM) and pitch (rad) from
        the operating curve unless given."""
        if not (np.isfinite(wind_speed) and wind_speed >= 0):
            raise InputError("wind_speed", wind_speed, "a non-negative wind speed (m/s)")
        om_c, pi_c = self.operating_point(wind_speed) if (rpm is None or pitch is None) else (0.0, 0.0)
        omega = om_c if rpm is None else float(rpm) * RPM
        pitch = pi_c if pitch is None else float(pitch)
        rb = self.blade(pitch)
        tip_frame = pitching_frames(rb.sections, self.rotor)[0] if rb.sections.n_sections else None
        st = self.steady(rb, wind_speed, omega)
        if self.options.structure == "deflected":  # the blade rebuilt and linearized about its deflected shape

            mu = blade_mu(self.turbine) if self.options.damping == "file" else None
            build = deflected_shell_blade if len(rb.fe.shell_conn) else deflected_blade
            d = build(rb, st, omega, mu=mu)
            rb, st, ksig, klink = d.blade, d.steady, d.ksigma, d.klink
        else:
            ksig, klink = self._prestress(rb, st, omega)
        return self.assemble_point(rb, st, ksig, klink, wind_speed, omega, pitch, tip_frame=tip_frame)

    def assemble_point(self, rb: RotorBlade, st, ksig, klink, wind_speed: float, omega: float, pitch: float, *,
                       tip_frame=None, Phi=None, aero_projection=None) -> PointSystem:
        """The :class:`PointSystem` of the blade ``rb`` linearized about the steady state ``st`` (its
        full-numbering initial-stress matrix ``ksig`` and hub-link term ``klink``) on this model's
        support, hub and drivetrain: the second half of :meth:`at`.  ``Phi``: the blade basis to use
        (None: computed at the point); ``aero_projection`` the reduction of the blade's aerodynamic
        states to use (None: the options' ``aero_state_tol`` at the point).  Design sensitivities
        (:mod:`windflutter.sensitivity`) call it with a blade or a support of changed data, the steady
        state held fixed and the nominal point's basis and projection (the same coordinates)."""
        blocks, strip_P = self._aero_blocks(rb, st, wind_speed, omega)
        negative = None
        if Phi is None:
            Phi = self.blade_basis(rb, omega, ksig, blocks, strip_P)
            negative = self._basis.negative
        bm = rb.matrices(Phi, ksigma_full=ksig, klink=klink)
        M, C, K = bm.at(omega, ksigma=bm.Ks1)
        aero = None
        if blocks is not None:
            B = rb.basis_full(Phi)
            aero = project_blade_aero(blocks, strip_P @ B, strip_P @ (rb.St @ B), omega)
        blade = blade_system(M, C, K, aero)
        tol = self.options.aero_state_tol
        if blade.n_states and (aero_projection is not None or tol is not None):
            aero_projection = aero_projection or balanced_projection(blade, tol)
            blade = reduced_blade_system(blade, aero_projection)
        ff = fixed_frame(self.support(), self.hub_mass(), self.rotor.shaft_axis, self.drivetrain())
        mbc = multiblade_system(ff, blade, self.n_blades, omega, self.rotor.shaft_axis)
        return PointSystem(wind_speed=float(wind_speed), omega=omega, pitch=pitch, mbc=mbc, blade=rb, Phi=Phi,
                           support=self.support(), steady=st, n_blades=self.n_blades, labels=ff.labels,
                           blade_system=blade, blade_structure=(M, K), blade_negative=negative, blade_damping=C,
                           fixed=ff, tip_frame=tip_frame, reference=self.reference(), ksigma=ksig, klink=klink,
                           aero_projection=aero_projection)

    # -- pieces ------------------------------------------------------------------------------
    def _prestress(self, rb: RotorBlade, st, omega: float):
        """Full-numbering Ksigma and the hub-link term of the steady stress (NOT per unit speed)."""
        if st is None:
            Kg1, Kl1, _ = rb.unit_prestress()
            return Kg1 * omega**2, Kl1 * omega**2

        return st.Ksigma, link_geometric_stiffness(rb.fe, st.f_internal - st.load, rb.hub_node)

    def _aero_blocks(self, rb: RotorBlade, st, wind_speed: float, omega: float):
        """(StripBlocks, section map P) of the blade's strips about the steady state, or (None, None)."""
        o = self.options
        if o.aero is None or not rb.sections.n_sections:
            return None, None

        if st is not None:
            sections, op = self._linearized_strips(rb, st), st.operating_point(self.rotor)
            if not o.induction:
                op = OperatingPoint(wind_speed, omega, o.air_density, self.rotor, 0.0)
        else:
            sections, op = rb.sections, OperatingPoint(wind_speed, omega, o.air_density, self.rotor, 0.0)
        oper = make_operator(sections, op, o.aero)
        if not oper.time_domain:
            return quasi_steady_blocks(oper), oper.P
        return oper.state_space(), oper.P

    def _linearized_strips(self, rb: RotorBlade, st):
        """The strips the linear aerodynamics act on: the deflected ones when the structure is linearized
        about the deflected shape; with the undeformed structure, the undeformed strips turned by the
        steady elastic twist only (the deflected chord direction projected on the plane normal to the
        undeformed span), so that the steady angle of attack has the elastic twist while the lift,
        drag and pitch axes stay those of the structure's flap, edge and torsion motion (bent strips
        on a straight structure would mix them: on the IEA 22 MW, 20 m of tip deflection tilt the
        span by ~15 degrees)."""
        if getattr(self.options, "structure", "undeformed") == "deflected":
            return st.sections
        from dataclasses import replace

        es = np.asarray(rb.sections.e_span, float)
        ec = np.asarray(st.sections.e_chord, float)
        ec = ec - np.sum(ec * es, axis=1, keepdims=True) * es
        ec /= np.linalg.norm(ec, axis=1, keepdims=True)
        return replace(rb.sections, e_chord=ec)

    def blade_basis(self, rb: RotorBlade, omega: float, ksig, blocks, strip_P):
        """Fixed-interface basis (nq, m) of the blade at this point (:class:`~windflutter.system.
        blade_basis.BladeBasis`); None for full order."""
        return self._basis(rb, omega, ksig, blocks, strip_P)

    def restart_modes(self) -> None:
        """Start the next shell-blade modes afresh (:meth:`BladeBasis.restart`): called at
        the start of each wind speed of a stability map, so that its onsets do not depend on which
        points a worker ran before (they differ by about 1e-7 RPM otherwise): a shell blade's from its
        clamped modes at rest (:func:`~windflutter.system.blade_basis.clamped_modes`, kept with the
        blade since its modal damping was built on them), which a sweep's first point refines in a few
        block solves instead of a Lanczos run from scratch."""
        self._basis.restart(self._blade0()[1] if self.options.model == "shell" else None)


def _support_basis(st, n_modes: int) -> np.ndarray:
    """Support modes (rotor-less, so the basis does not depend on the operating point) plus the six
    static responses to hub loads, M-orthonormal.  The Lanczos start is fixed: with ARPACK's random
    one every model had a basis of its own (a rotation of a shell tower's degenerate wall pairs), so
    the same point's reduced matrices differed from run to run (by 3e-3 of their largest entry on the
    NREL 5 MW shell turbine; its modes only to round-off)."""
    import scipy.sparse.linalg as spla

    K, M = st.Kr.tocsc(), st.Mr.tocsc()
    n = min(n_modes, K.shape[0] - 2)
    _, V = symmetric_eigs(K, M, n, shift=0.0, v0=np.ones(K.shape[0]))
    hub = int(st.fe.node_groups["hub"][0])
    H = np.asarray(st.T[6 * hub: 6 * hub + 6].todense()).T
    X = spla.splu(K).solve(H)
    X -= V @ (V.T @ (M @ X))  # the part the modes miss, at unit mass-norm
    X /= np.sqrt(np.maximum(np.einsum("ij,ij->j", X, M @ X), 1e-300))
    return m_orthonormalize(np.hstack([V, X]), M, tol=1e-10, largest_first=False)
