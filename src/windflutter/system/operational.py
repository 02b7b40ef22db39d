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
import scipy.linalg as sla

from windflutter.aero.sections import RotorGeometry
from windflutter.errors import InputError
from windflutter.system.blade import RotorBlade
from windflutter.system.blade_aero import StripBlocks, blade_system, project_blade_aero
from windflutter.system.multiblade import MultiBladeSystem, multiblade_system
from windflutter.system.support import Drivetrain, fixed_frame, rigid_body_mass, support_model
from windflutter.units import RPM

PARTS = ("turbine", "rotor")
DRIVETRAINS = ("flexible", "rigid", "locked")


@dataclass(frozen=True)
class OperationalOptions:
    """How the operating-point model is built.

    Parameters
    ----------
    model : ``"beam"`` or ``"shell"`` blades (and tower).
    part : ``"turbine"`` (rotor on the flexible tower) or ``"rotor"`` (rotor on a fixed nacelle,
        drivetrain free: HAWCStab2's / OpenFAST's rotor-only analysis).
    mesh : extra :class:`~windflutter.mesh.settings.MeshSettings` fields.
    blade_modes : fixed-interface blade modes in the basis; ``None``: full order.
    corrections : add static corrections (modal truncation augmentation) of the aerodynamic loads
        of the retained modes to the blade basis; ``correction_tol`` is their relative cut-off.
    support_modes : support modes (+ 6 hub-load corrections); ``None``: its full constrained
        coordinates (beam towers).
    drivetrain : ``"flexible"`` (shaft spring, generator inertia), ``"rigid"`` or ``"locked"``.
    aero : the strip operator's options (:class:`~windflutter.aero.unsteady.UnsteadyOptions` for
        the state-space model; :class:`~windflutter.aero.strip.AeroOptions` for the thesis's
        quasi-steady strips), ``None`` for no aerodynamics.
    deflection : linearize about the deflected steady state (False: the undeformed blade).
    induction : steady BEM induction in the inflow.
    damping : ``"file"`` (the turbine files' structural damping) or ``"none"``.
    air_density : kg/m^3.
    """

    model: str = "beam"
    part: str = "turbine"
    mesh: dict = field(default_factory=dict)
    blade_modes: int | None = 20
    corrections: bool = False
    correction_tol: float = 1e-6
    support_modes: int | None = None
    drivetrain: str = "flexible"
    aero: object = "default"
    deflection: bool = True
    induction: bool = True
    damping: str = "file"
    air_density: float = 1.225

    def __post_init__(self):
        from windflutter.errors import check_choice

        check_choice("model", self.model, ("beam", "shell"))
        check_choice("part", self.part, PARTS)
        check_choice("drivetrain", self.drivetrain, DRIVETRAINS)
        check_choice("damping", self.damping, ("file", "none"))
        if self.aero == "default":
            from windflutter.aero.unsteady import UnsteadyOptions

            object.__setattr__(self, "aero", UnsteadyOptions())
        for name in ("blade_modes", "support_modes"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, (int, np.integer)) and v >= 1):
                raise InputError(name, v, "a positive number of modes, or None (full order)")
        if not (np.isfinite(self.air_density) and self.air_density > 0):
            raise InputError("air_density", self.air_density, "a positive density (kg/m^3)")


@dataclass
class PointSystem:
    """The model at one operating point: the multi-blade system and what is needed to read its modes.

    wind_speed (m/s), omega (rad/s), pitch (rad); ``mbc`` the time-invariant system; ``blade``
    the substructure; ``Phi`` (nq_blade, m) its fixed-interface basis; ``support`` the support
    model (None for ``part="rotor"``); ``steady`` the steady state (or None); ``labels`` of the
    ground-fixed coordinates.
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

    # -- parts -------------------------------------------------------------------------------
    def _mesh(self, part: str, pitch: float = 0.0):
        from windflutter.mesh.settings import MeshSettings

        return MeshSettings(**{"model": self.options.model, **self.options.mesh, "part": part, "pitch": float(pitch)})

    def blade(self, pitch: float) -> RotorBlade:
        """The fixed-interface blade at collective ``pitch`` (rad), cached."""
        key = round(float(pitch), 8)
        if key not in self._blades:
            from windflutter.mesh.turbine import build_model
            from windflutter.structure.assembly import assemble
            from windflutter.system.damping import blade_damping_matrix, blade_mu

            fe, sec = build_model(self.turbine, self._mesh("rotor_blade", pitch))
            mu = blade_mu(self.turbine) if self.options.damping == "file" else None
            self._blades[key] = RotorBlade(fe, assemble(fe), sec, self.rotor.hub_center, self.rotor.shaft_axis,
                                           damping=blade_damping_matrix(fe, mu))
        return self._blades[key]

    def support(self):
        """The support model (None for the rotor on a fixed nacelle), cached."""
        if self.options.part == "rotor":
            return None
        if self._support is None:
            from windflutter.mesh.turbine import build_model
            from windflutter.structure.assembly import assemble
            from windflutter.system.damping import stiffness_proportional, tower_ratio

            fe, _ = build_model(self.turbine, self._mesh("support"))
            st = assemble(fe)
            basis = None
            if self.options.support_modes is not None:
                basis = _support_basis(st, self.options.support_modes)
            sm = support_model(fe, st, basis=basis)
            zeta = tower_ratio(self.turbine) if self.options.damping == "file" else 0.0
            D = stiffness_proportional(sm.K, sm.M, zeta)
            if D is not None:
                sm.D = D
            self._support = sm
        return self._support

    def hub_mass(self) -> np.ndarray:
        from windflutter.mesh.parts import hub_mass

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
        from windflutter.system.damping import blade_mu, tower_ratio

        mu = blade_mu(self.turbine) if o.damping == "file" else None
        zt = tower_ratio(self.turbine) if o.damping == "file" else 0.0
        return {"frame": "ground-fixed (multi-blade coordinates)", "model": o.model, "part": o.part,
                "drivetrain": o.drivetrain, "aerodynamics": aero,
                "steady_state": "deflected (BEM, centrifugal + aero loads)" if o.deflection else "undeformed",
                "induction": "steady BEM" if o.induction else "none",
                "blade_damping": "none" if mu is None else "stiffness-proportional mu " + ", ".join(f"{x:.3g}" for x in mu),
                "tower_damping": f"{100 * zt:.2g} % (stiffness-proportional)" if zt > 0 else "none",
                "blade_basis": "full order" if o.blade_modes is None else f"{o.blade_modes} fixed-interface modes"
                               + (" + aero corrections" if o.corrections else ""),
                "inflow": "axisymmetric along the shaft (no tilt, shear, yaw, gravity)"}

    # -- operating point ---------------------------------------------------------------------
    def operating_point(self, wind_speed: float) -> tuple[float, float]:
        """(rotor speed rad/s, pitch rad) of the turbine's operating curve at ``wind_speed``."""
        oc = self.turbine.operating_curve
        if oc is None:
            raise InputError("operating curve", None, "a turbine with an operating curve (rotor speed, pitch)")
        return float(oc.rotor_speed_at(wind_speed)), float(oc.pitch_at(wind_speed))

    def steady(self, rb: RotorBlade, wind_speed: float, omega: float):
        """The blade's steady state at (V m/s, Omega rad/s), or None without aerodynamics."""
        o = self.options
        if o.aero is None or wind_speed <= 0 or not rb.sections.n_sections:
            return None
        from windflutter.steady import SteadyOptions, steady_state

        return steady_state(rb.fe, rb.struct, rb.sections, self.rotor, wind_speed, omega, n_blades=self.n_blades,
                            air_density=o.air_density, options=SteadyOptions(deflection=o.deflection))

    def at(self, wind_speed: float, rpm: float | None = None, pitch: float | None = None) -> PointSystem:
        """The multi-blade system at ``wind_speed`` (m/s); rotor speed (RPM) and pitch (rad) from
        the operating curve unless given."""
        if not (np.isfinite(wind_speed) and wind_speed >= 0):
            raise InputError("wind_speed", wind_speed, "a non-negative wind speed (m/s)")
        om_c, pi_c = self.operating_point(wind_speed) if (rpm is None or pitch is None) else (0.0, 0.0)
        omega = om_c if rpm is None else float(rpm) * RPM
        pitch = pi_c if pitch is None else float(pitch)
        rb = self.blade(pitch)
        st = self.steady(rb, wind_speed, omega)
        ksig, klink = self._prestress(rb, st, omega)
        blocks, strip_P = self._aero_blocks(rb, st, wind_speed, omega)
        Phi = self._blade_basis(rb, omega, ksig, klink, blocks, strip_P)
        bm = rb.matrices(Phi, ksigma_full=ksig, klink=klink)
        M, C, K = bm.at(omega, ksigma=bm.Ks1)
        aero = None
        if blocks is not None:
            B = rb.basis_full(Phi)
            aero = project_blade_aero(blocks, strip_P @ B, strip_P @ (rb.St @ B), omega)
        blade = blade_system(M, C, K, aero)
        ff = fixed_frame(self.support(), self.hub_mass(), self.rotor.shaft_axis, self.drivetrain())
        mbc = multiblade_system(ff, blade, self.n_blades, omega, self.rotor.shaft_axis)
        return PointSystem(wind_speed=float(wind_speed), omega=omega, pitch=pitch, mbc=mbc, blade=rb, Phi=Phi,
                           support=self.support(), steady=st, n_blades=self.n_blades, labels=ff.labels)

    # -- pieces ------------------------------------------------------------------------------
    def _prestress(self, rb: RotorBlade, st, omega: float):
        """Full-numbering Ksigma and the hub-link term of the steady stress (NOT per unit speed)."""
        if st is None:
            Kg1, Kl1, _ = rb.unit_prestress()
            return Kg1 * omega**2, Kl1 * omega**2
        from windflutter.system.blade import link_geometric_stiffness

        return st.Ksigma, link_geometric_stiffness(rb.fe, rb.struct, st.u, st.load, rb.hub_node)

    def _aero_blocks(self, rb: RotorBlade, st, wind_speed: float, omega: float):
        """(StripBlocks, section map P) of the blade's strips about the steady state, or (None, None)."""
        o = self.options
        if o.aero is None or not rb.sections.n_sections:
            return None, None
        from windflutter.aero.flow import OperatingPoint
        from windflutter.aero.operators import make_operator

        if st is not None:
            sections, op = st.sections, st.operating_point(self.rotor)
            if not o.induction:
                op = OperatingPoint(wind_speed, omega, o.air_density, self.rotor, 0.0)
        else:
            sections, op = rb.sections, OperatingPoint(wind_speed, omega, o.air_density, self.rotor, 0.0)
        oper = make_operator(sections, op, o.aero)
        if not oper.time_domain:
            from windflutter.system.blade_aero import quasi_steady_blocks

            return quasi_steady_blocks(oper), oper.P
        ss = oper.state_space()
        return StripBlocks(Ma=ss.Ma, Da=ss.Da, Ka=ss.Ka, Cz=ss.Cz, Az=ss.Az, Bq=ss.Bq, Bv=ss.Bv), oper.P

    def _blade_basis(self, rb: RotorBlade, omega: float, ksig, klink, blocks, strip_P):
        """Fixed-interface basis (nq, m): modes of the prestressed rotating blade, plus static
        corrections for the strip load shapes; None for full order."""
        n = self.options.blade_modes
        st = rb.struct
        if n is None or n >= st.nq:
            return None
        T = st.T
        K = (st.Kr + T.T @ (ksig - omega**2 * rb.Kr1) @ T).toarray()
        M = st.Mr.toarray()
        K = 0.5 * (K + K.T)
        w2, V = sla.eigh(K, 0.5 * (M + M.T), subset_by_index=[0, n - 1])
        if not (self.options.corrections and blocks is not None):
            return V
        # static responses to the strip loads the retained modes generate (modal truncation
        # augmentation): Ka and Da blocks acting on the modes' section motion
        R = np.asarray((strip_P @ (T @ V)))  # (3 ns, n)
        ns = blocks.n_sections
        Rs = R.reshape(ns, 3, -1)
        loads = np.concatenate([np.einsum("jab,jbk->jak", blocks.Ka, Rs), np.einsum("jab,jbk->jak", blocks.Da, Rs)],
                               axis=2).reshape(3 * ns, -1)
        F = np.asarray(T.T @ (strip_P.T @ loads))
        X = np.linalg.solve(K, F)
        X -= V @ (V.T @ (M @ X))
        G = X.T @ M @ X
        w, U = np.linalg.eigh(0.5 * (G + G.T))
        keep = w > self.options.correction_tol * w.max()
        C = X @ (U[:, keep] / np.sqrt(w[keep]))
        return np.hstack([V, C])


def _support_basis(st, n_modes: int) -> np.ndarray:
    """Support modes (rotor-less, so the basis does not depend on the operating point) plus the six
    static responses to hub loads, M-orthonormal."""
    import scipy.sparse.linalg as spla

    K, M = st.Kr.tocsc(), st.Mr.tocsc()
    n = min(n_modes, K.shape[0] - 2)
    w2, V = spla.eigsh(K, k=n, M=M, sigma=0.0, which="LM")
    hub = int(st.fe.node_groups["hub"][0])
    H = np.asarray(st.T[6 * hub: 6 * hub + 6].todense()).T
    X = spla.splu(K).solve(H)
    B = np.hstack([V, X])
    G = B.T @ (M @ B)
    w, U = np.linalg.eigh(0.5 * (G + G.T))
    keep = w > 1e-10 * w.max()
    return B @ (U[:, keep] / np.sqrt(w[keep]))
