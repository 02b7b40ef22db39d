"""Flutter and divergence of a whole turbine, one wind speed at a time.

For a wind speed ``V`` the blade pitch comes from the turbine's operating curve; the FE model
(beam or shell, built by :func:`windflutter.mesh.turbine.build_model` at that pitch) is coupled
with the rotating-frame terms (G, Kr and -- full physics -- the centrifugal prestress Ksigma) and
the Theodorsen strips; the rotor speed is then increased over ``min_rpm .. max_rpm`` and the
first flutter and divergence onsets are located (:mod:`windflutter.frozen.search`).

Public API
----------
* :class:`TurbineOptions` -- model, aero variant, search method, physics, ranges.
* :class:`TurbineStability` -- holds the turbine and caches the FE models per pitch;
  :meth:`TurbineStability.analyse_operating_point` analyses one wind speed.
* :func:`analyse_operating_point` / :func:`stability_map` -- one-call wrappers.
* :func:`options_from_config` -- the options of a ``windflutter run`` analysis config (the
  per-point adapter is :class:`windflutter.workflow.TurbinePointAnalyser`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from windflutter.aero.skin import skin_distribution
from windflutter.aero.strip import AeroOptions
from windflutter.config import AERO_DISTRIBUTIONS, AERO_VARIANTS, DAMPING_MODELS, REDUCTIONS, SEARCH_METHODS
from windflutter.errors import InputError, check_choice
from windflutter.frozen.pk_roots import structural_eig
from windflutter.frozen.search import pk_search, thesis_search
from windflutter.frozen.tracking import has_torsion, mode_names
from windflutter.linalg_tools import mac_matrix
from windflutter.mesh import turbine as mesh_turbine
from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model as build_blade  # the blade alone (never a test's edited model)
from windflutter.results import PointSummary
from windflutter.rotor.rotating import rotor_terms
from windflutter.solve.aero_reduction import MTAAeroelasticModel
from windflutter.solve.aeroelastic import AeroelasticModel, StructuralMatrices
from windflutter.solve.skin_model import SkinAeroelasticModel
from windflutter.structure.assembly import assemble
from windflutter.structure.damping import damping_matrix, rayleigh_coefficients
from windflutter.system.damping import blade_mu, shell_modal_damping, turbine_damping_matrix
from windflutter.system.identity import MIXED_SHARE
from windflutter.system.reference import blade_reference
from windflutter.units import RPM


@dataclass(frozen=True)
class TurbineOptions:
    """How to analyse a turbine.

    Parameters
    ----------
    model : ``"beam"`` or ``"shell"``.
    aero : ``"potential"`` or ``"viscous"``.
    method : ``"pk"`` (p-k + root-finding) or ``"thesis"`` (the seed's 8-k search).
    geometric_stiffness : with the centrifugal prestress Ksigma (True) or without (False, as the seed).
    rigid_sections : the rotating-frame terms of beam sections and lumped masses as rigid bodies
        (mass-centre offsets, rotary inertia) with the initial stress of every beam stress
        resultant (True), or the seed's translational terms with the axial force's initial stress
        (False, the default here; ``solver.rigid_sections`` of the analysis config is True).  Only
        True gives results independent of where a beam's reference axis lies in its sections
        (:func:`windflutter.rotor.rotating.rotor_terms`).
    air_density : kg/m^3.
    min_rpm, max_rpm, rpm_step : rotor-speed grid (RPM) of the search / Campbell sweep.
    tolerance_rpm : onset tolerance of the p-k root-finding (RPM).
    full_sweep : p-k: sweep the whole grid (Campbell data beyond the instabilities); ``False``
        stops at the first grid speed past both the flutter and the divergence onsets (same
        onsets, less work).
    reduction : ``"mta"`` (modal basis + aerodynamic static-correction vectors, the default:
        NREL 5 MW whole turbine, beam, 10 m/s: 21.985 / 23.597 RPM flutter / divergence vs
        21.99 / 23.60 at full order), ``"modal"`` (structural modes only: 23.60 / 25.73 RPM with
        30 modes, non-conservative on whole turbines) or ``"none"`` (full order, the reference).
    basis_modes : structural modes per reference speed in the projection basis; ``None`` means
        full order (the same as ``reduction="none"``).
    mta_wind_speeds : wind speeds (m/s) whose aero loads build the correction vectors of
        ``reduction="mta"`` (fixed, so results do not depend on the order of the points).
    correction_tol : relative cut-off of those correction directions
        (:class:`~windflutter.solve.aero_reduction.MTAAeroelasticModel`); 1e-8 (default) is safe,
        1e-4 halves the basis but was 2-5 % low on the seed 20 MW.
    n_tracked : modes followed by the p-k search; ``None`` (default) tracks every mode up to
        1.25 x the frequency of the first blade-torsion mode (the classical flutter partner of
        the flap modes); a fixed count may miss it (a whole 3-bladed turbine has ~20 modes below
        the first torsion).
    n_eig : eigenvalues per eigen-solve (near the p-k frequency).
    apparent_mass_scaling : viscous only, scale apparent-mass terms by Cl_alpha / 2 pi.
    aero_distribution : ``"spline"`` (strip motion from a rigid-section fit of its skin nodes;
        the only choice for beams) or ``"skin"`` (the seed's skin quads, shell models only;
        ``docs/aero_distribution.md``).
    mean_loads : add the quasi-steady damping of the mean lift, drag and moment (polars at the
        strips' steady angles of attack; :class:`~windflutter.aero.strip.AeroOptions`): the
        edgewise aerodynamic damping; ``False`` is the thesis's model.
    induction : steady BEM axial/tangential induction in the inflow (frozen in the stability
        problem); ``False`` is the thesis's ``V, Omega r``.  high_thrust : its thrust--induction
        relation (:mod:`windflutter.aero.momentum`).
    damping : ``"file"`` (the turbine files' blade ``mu`` and tower ratios,
        :mod:`windflutter.system.damping`), ``"none"``, ``"stiffness"``, ``"rayleigh"`` or ``"modal"``; ``damping_ratio`` at
        ``damping_reference_hz`` (Rayleigh: and at 10x it; modal: in every non-rotating
        structural mode of the basis).
    mesh : extra :class:`~windflutter.mesh.settings.MeshSettings` fields (dict).
    """

    model: str = "beam"
    aero: str = "potential"
    method: str = "pk"
    geometric_stiffness: bool = True
    rigid_sections: bool = False
    air_density: float = 1.225
    min_rpm: float = 2.0
    max_rpm: float = 40.0
    rpm_step: float = 2.0
    tolerance_rpm: float = 0.01
    full_sweep: bool = False
    reduction: str = "mta"
    basis_modes: int = 30
    mta_wind_speeds: tuple[float, ...] = (4.0, 25.0)
    correction_tol: float = 1e-8
    n_tracked: int | None = None
    n_eig: int = 20
    apparent_mass_scaling: bool = False
    aero_distribution: str = "spline"
    induction: bool = False
    high_thrust: str = "buhl"
    mean_loads: bool = False
    damping: str = "none"
    damping_ratio: float = 0.0
    damping_reference_hz: float = 1.0
    mesh: dict = field(default_factory=dict)

    def __post_init__(self):
        for name, choices in (("model", ("beam", "shell")), ("aero", AERO_VARIANTS), ("method", SEARCH_METHODS),
                              ("damping", DAMPING_MODELS),
                              ("reduction", REDUCTIONS), ("aero_distribution", AERO_DISTRIBUTIONS)):
            check_choice(name, getattr(self, name), choices)
        if self.basis_modes is None:  # full order
            object.__setattr__(self, "reduction", "none")
            object.__setattr__(self, "basis_modes", 30)
        if self.aero_distribution == "skin" and self.model != "shell":
            raise InputError("aero_distribution", "skin", "'spline' for a beam model (skin quads need shells)")
        if not (0 <= self.min_rpm < self.max_rpm):
            raise InputError("min_rpm", self.min_rpm, f"0 <= min_rpm < max_rpm = {self.max_rpm}")
        if not self.rpm_step > 0:
            raise InputError("rpm_step", self.rpm_step, "a positive step (RPM)")
        if not self.tolerance_rpm > 0:
            raise InputError("tolerance_rpm", self.tolerance_rpm, "a positive tolerance (RPM)")
        if not self.air_density > 0:
            raise InputError("air_density", self.air_density, "a positive density (kg/m^3)")
        if not (isinstance(self.basis_modes, (int, np.integer)) and self.basis_modes >= 1):
            raise InputError("basis_modes", self.basis_modes, "a positive number of modes")
        if self.n_tracked is not None and not (isinstance(self.n_tracked, (int, np.integer))
                                               and self.n_tracked >= 1):
            raise InputError("n_tracked", self.n_tracked, "a positive number of modes, or None (auto)")
        if not (0.0 < self.correction_tol < 1.0):
            raise InputError("correction_tol", self.correction_tol, "a relative cut-off in (0, 1), e.g. 1e-8")
        if not (isinstance(self.n_eig, (int, np.integer)) and self.n_eig >= 2):
            raise InputError("n_eig", self.n_eig, "at least 2 eigenvalues per solve")
        if self.damping == "modal" and self.reduction == "none":
            raise InputError("damping", "modal", "'stiffness' or 'rayleigh' with reduction 'none' "
                             "(modal damping lives in the modal basis)")

    def grid(self) -> np.ndarray:
        """Rotor-speed grid (RPM)."""
        n = max(int(math.ceil((self.max_rpm - self.min_rpm) / self.rpm_step - 1e-9)), 1)
        return np.linspace(self.min_rpm, self.max_rpm, n + 1)


class TurbineStability:
    """A turbine ready for stability analysis; FE models are cached per blade pitch."""

    def __init__(self, turbine, options: TurbineOptions | None = None):
        self.turbine = turbine
        self.options = options or TurbineOptions()
        if hasattr(turbine, "require"):  # refuse data the files lack (airfoil polars, masses) by name
            turbine.require(self.options.mesh.get("part", "turbine"), aerodynamics=True)
        self._models: dict[float, tuple] = {}

    # -- model -----------------------------------------------------------------------------
    def reference(self):
        """The blade's structural identities (:func:`windflutter.system.reference.structural_reference`:
        its standstill modes, named), from the blade alone meshed as this model's blades, cached:
        the names of method p, for the tracked modes of the frozen-azimuth searches."""
        if getattr(self, "_reference", None) is None:
            _, st, sections = self._blade0()
            self._reference = blade_reference(st, sections)
        return self._reference

    def _blade0(self):
        """The blade alone, clamped at the hub, at pitch 0, meshed as this model's blades:
        ``(fe, struct, sections)``, cached."""
        if getattr(self, "_blade_zero", None) is None:
            settings = MeshSettings(**{"model": self.options.model, **self.options.mesh, "part": "rotor_blade",
                                       "pitch": 0.0})
            fe, sections = build_blade(self.turbine, settings)
            self._blade_zero = (fe, assemble(fe), sections)
        return self._blade_zero

    def _shell_blade_damping(self, fe):
        """The files' per-direction damping of the shell blades of the model ``fe`` -- method p's
        (:func:`windflutter.system.damping.shell_modal_damping` on the clamped pitch-0 blade, built
        once) placed on each blade by its rigid motion (pitch, azimuth, cone, tilt); None for beam
        blades or without coefficients."""
        mu = blade_mu(self.turbine)
        if mu is None or not len(fe.shell_conn) or "blade0" not in fe.node_groups:
            return None
        if getattr(self, "_shell_damping0", None) is None:
            fe0, st0, sec0 = self._blade0()
            self._shell_damping0 = shell_modal_damping(fe0, st0, sec0, mu)
        fe0 = self._blade0()[0]
        src = fe0.node_groups["blade0"]
        nodes = np.asarray(fe.nodes, float)
        targets = [(ids, nodes[ids]) for k in range(int(self.turbine.n_blades))
                   if (ids := fe.node_groups.get(f"blade{k}")) is not None]
        return self._shell_damping0.placed(src, np.asarray(fe0.nodes, float)[src], targets, fe.n_nodes)

    def pitch_at(self, wind_speed: float) -> float:
        """Blade pitch (rad) from the operating curve (0 without one)."""
        oc = self.turbine.operating_curve
        if oc is None:
            return 0.0
        oc.warn_outside(float(wind_speed))
        return float(oc.pitch_at(wind_speed))

    def model(self, pitch: float):
        """(fe, sections, AeroelasticModel) at blade pitch ``pitch`` (rad), cached."""
        key = round(float(pitch), 6)
        if key in self._models:
            return self._models[key]

        o = self.options
        settings = MeshSettings(**{"model": o.model, **o.mesh, "pitch": float(pitch)})
        fe, sections = mesh_turbine.build_model(self.turbine, settings)  # module access: tests patch it
        st = assemble(fe)
        geom = mesh_turbine.rotor_geometry(self.turbine)
        terms = rotor_terms(fe, st, geom, prestress=bool(o.geometric_stiffness), rigid_sections=bool(o.rigid_sections))
        sm = StructuralMatrices.from_structural(st)
        sm.D = self._damping(st)
        aero = AeroOptions(model=o.aero, apparent_mass_scaling=o.apparent_mass_scaling, steady_loads=o.mean_loads)
        kw = dict(structure=sm, sections=sections, rotor=terms, rotor_geometry=geom, aero=aero,
                  air_density=o.air_density, n_modes=None if o.reduction == "none" else o.basis_modes,
                  omega_ref=(0.0, o.max_rpm * RPM), pitch=0.0)
        if o.induction:
            kw["induction"], kw["high_thrust"] = True, o.high_thrust
        skin = None
        if o.aero_distribution == "skin":

            # the seed's skin quads as sub-strips (same strip aerodynamics, own motion rows)
            skin = skin_distribution(fe, sections)
            sections = kw["sections"] = skin.sections
        if o.reduction == "mta":

            am = MTAAeroelasticModel(**kw, mta_wind_speeds=tuple(o.mta_wind_speeds), mta_tol=o.correction_tol)
        elif skin is not None:

            am = SkinAeroelasticModel(**kw, parent=skin.parent)
        else:
            am = AeroelasticModel(**kw)
        if o.damping == "modal" and o.damping_ratio > 0:
            am.add_modal_damping(o.damping_ratio)
        Db = self._shell_blade_damping(fe) if o.damping == "file" else None
        if Db is not None:  # low-rank: added in the working basis (turbine_damping_matrix has the rest)
            am.add_low_rank_damping(Db.U, Db.c)
        self._models[key] = (fe, sections, am)
        return self._models[key]

    def _damping(self, st):
        o = self.options
        if o.damping == "file":

            return turbine_damping_matrix(self.turbine, st)
        if o.damping in ("none", "modal") or o.damping_ratio == 0.0:
            return None  # modal damping is added in the modal basis (AeroelasticModel)

        if o.damping == "stiffness":
            beta = o.damping_ratio / (math.pi * o.damping_reference_hz)
            return damping_matrix(st, "rayleigh", alpha=0.0, beta=beta)
        a, b = rayleigh_coefficients(o.damping_reference_hz, 10 * o.damping_reference_hz, o.damping_ratio)
        return damping_matrix(st, "rayleigh", alpha=a, beta=b)

    # -- analysis --------------------------------------------------------------------------
    def analyse_operating_point(self, wind_speed: float, rpm_grid=None) -> PointSummary:
        """Flutter/divergence onset over the rotor-speed grid at one wind speed (m/s)."""
        if not (np.isfinite(wind_speed) and wind_speed >= 0):
            raise InputError("wind_speed", wind_speed, "a non-negative wind speed (m/s)")
        o = self.options
        pitch = self.pitch_at(wind_speed)
        fe, sections, am = self.model(pitch)
        grid = o.grid() if rpm_grid is None else np.asarray(rpm_grid, float)
        if grid[0] <= 0 and wind_speed == 0:
            grid = grid[grid > 0]

        def system_at(rpm):
            return am.at(wind_speed, rpm * RPM)

        sys_ref = system_at(grid[0])
        M = am.structure.M
        ref = self.reference()
        named = None
        if o.method == "pk":  # only p-k tracks
            shapes = structural_shapes(sys_ref)
            named = structural_names(sys_ref, fe, M, sections, ref, shapes)
            # (the count by the frequency-order names of the seed's labels: the tracked set, and so the
            # onsets, as before the identities)
            n_track = o.n_tracked if o.n_tracked is not None else \
                auto_tracked(sys_ref, fe, M, sections, named=structural_names(sys_ref, fe, M, sections, None, shapes))
            on = pk_search(system_at, grid, n_track=min(n_track, am.size), n_eig=o.n_eig, xtol=o.tolerance_rpm,
                           stop_at_onset=not o.full_sweep)
        else:
            on = thesis_search(system_at, grid, n_eig=o.n_eig)
        labels, mode = self._names(on, system_at, fe, M, sections, named, ref)
        if mode is not None and on.divergence is not None and on.flutter > on.divergence:
            # reported like a V-g plot shows it, but the stability limit is the divergence: beyond
            # it the linearization about the undeformed rotor describes no equilibrium
            mode = f"{mode} (above divergence)"
        lam = on.eigenvalues
        with np.errstate(invalid="ignore", divide="ignore"):
            zeta = -lam.real / np.abs(lam)
        return PointSummary(
            wind_speed=float(wind_speed), pitch_deg=float(np.degrees(pitch)),
            flutter_rpm=on.flutter, divergence_rpm=on.divergence,
            flutter_frequency_hz=None if on.flutter_frequency is None else on.flutter_frequency / (2 * math.pi),
            flutter_mode=mode, sweep_rpm=on.params, damped_frequency_hz=np.abs(lam.imag) / (2 * math.pi),
            damping_ratio=zeta, mode_labels=labels, onset=on)


    @staticmethod
    def _names(on, system_at, fe, M, sections, named, reference=None):
        """Names of the tracked modes and of the flutter mode (:mod:`~windflutter.frozen.tracking`).

        A tracked mode is named as the structural mode (``Ks(Omega), M`` at the first rotor speed,
        no aerodynamics) it is closest to by MAC: the aerodynamic coupling there can already make
        a torsion mode's strips move more in flap than in twist.  The flutter mode is named ``"grew
        from -> at onset"``: the tracked mode it grew from and, where it differs, the identity of its
        shape at the onset (the blade's identities ``reference``, as method p names its modes);
        without a tracked mode (the thesis search), its identity at the onset."""
        labels = []
        if on.vectors0 is not None and named is not None:
            # a mode without a free root at the first grid point (lost there) has no shape yet
            _, V, struct_names = named
            have = [i for i, x in enumerate(on.vectors0) if x is not None]
            labels = ["lost"] * len(on.vectors0)
            if have:  # one structural mode each (the blade copies span near-degenerate subspaces)
                from scipy.optimize import linear_sum_assignment

                C = mac_matrix(np.stack([np.asarray(on.vectors0[i]) for i in have], axis=1), V)
                rows, cols = linear_sum_assignment(-C)
                for r, c in zip(rows, cols):
                    labels[have[r]] = struct_names[c]
        mode = None
        if on.flutter is None:
            return labels, mode
        onset = None
        if on.flutter_vector is not None and reference is not None:  # its identity at the onset
            onset = onset_identity(system_at(on.flutter), np.asarray(on.flutter_vector), fe, M, sections, reference)
        if on.flutter_mode is not None and on.flutter_mode < len(labels) and labels[on.flutter_mode] != "lost":
            start = labels[on.flutter_mode]
            mode = start if onset is None or onset == start else f"{start} -> {onset}"
        else:
            mode = onset
        return labels, mode


def onset_identity(system, x: np.ndarray, fe, M, sections, reference) -> str:
    """The name of the mode ``x`` (working basis) of ``system`` as method p names a lightly damped
    mode (:func:`windflutter.system.identity.participations`): its strain energy ``omega_k^2
    |a_k|^2`` over the structural modes of ``system`` without aerodynamics (``a_k = v_k^T M x``,
    mass-normalized), summed per identity (:func:`structural_names` with the blade's ``reference``),
    the largest -- and ``" + "`` the second where the largest has less than ``MIXED_SHARE``."""
    shapes = structural_shapes(system)
    w2, V, _ = shapes
    _, Mw = system.structural_pencil()
    Mw = Mw.toarray() if hasattr(Mw, "toarray") else np.asarray(Mw)
    a = V.T @ (0.5 * (Mw + Mw.T)) @ x
    _, _, names = structural_names(system, fe, M, sections, reference, shapes)
    energy: dict = {}
    for name, e in zip(names, np.maximum(w2, 0.0) * np.abs(a) ** 2):
        energy[name] = energy.get(name, 0.0) + float(e)
    ranked = sorted(energy, key=energy.get, reverse=True)
    total = max(sum(energy.values()), 1e-300)
    if len(ranked) > 1 and energy[ranked[0]] < MIXED_SHARE * total:  # mixed, as method p names it
        return f"{ranked[0]} + {ranked[1]}"
    return ranked[0]


def structural_shapes(system):
    """``(w^2, V, X)``: the modes of ``Ks(Omega), M`` of ``system`` in its working basis (``V``,
    mass-normalized) and expanded to the full numbering (``X``), to be named once or twice."""
    w2, V = structural_eig(system)
    return w2, V, np.stack([system.expand(V[:, i]) for i in range(V.shape[1])], axis=1)


def structural_names(system, fe, M, sections, reference=None, shapes=None):
    """``(f (Hz), V, names)``: the modes of ``Ks(Omega), M`` of ``system`` (working basis) and their
    names (:func:`~windflutter.frozen.tracking.mode_names`, by the blade's identities
    ``reference`` when given); ``shapes``: :func:`structural_shapes` of ``system``, if known."""
    w2, V, X = shapes if shapes is not None else structural_shapes(system)
    f = np.sqrt(np.maximum(w2, 0.0)) / (2 * math.pi)
    return f, V, mode_names(fe, M, X, f, sections, reference)


def auto_tracked(system, fe, M, sections, factor: float = 1.25, named=None) -> int:
    """Number of modes to track: every structural mode up to ``factor`` x the first torsion.

    Classical flutter of a blade couples a flap mode with a torsion mode; a whole turbine has
    tower, drivetrain and three of each blade mode below the first torsion, so a fixed count is
    fragile.  The modes of ``Ks(Omega) , M`` at the first rotor speed of the sweep are labelled
    (:func:`~windflutter.frozen.tracking.mode_names`); without a torsion-dominated mode all
    modes of the basis are tracked.  ``named``: :func:`structural_names` of ``system``, if known.
    """
    f, _, names = named if named is not None else structural_names(system, fe, M, sections)
    for i, name in enumerate(names):
        if has_torsion(name):
            return int(np.count_nonzero(f <= factor * f[i]))
    return len(f)


def analyse_operating_point(turbine, wind_speed: float, options: TurbineOptions | None = None) -> PointSummary:
    """One wind speed; see :meth:`TurbineStability.analyse_operating_point`."""
    return TurbineStability(turbine, options).analyse_operating_point(wind_speed)


def stability_map(turbine, wind_speeds, options: TurbineOptions | None = None) -> list[PointSummary]:
    """Onsets at every wind speed (m/s), sharing the cached FE models."""
    ts = TurbineStability(turbine, options)
    return [ts.analyse_operating_point(float(v)) for v in wind_speeds]


def options_from_config(config, aero: str, method: str) -> TurbineOptions:
    """:class:`TurbineOptions` from a workflow :class:`~windflutter.config.AnalysisConfig`."""
    r = config.rotor_speed
    step = (r.max_rpm - r.min_rpm) / max(r.n_points - 1, 1)
    mtype = config.model.type
    if mtype not in ("beam", "shell"):
        raise InputError("model.type", mtype, "'beam' or 'shell' for the turbine solver")
    mesh = {}
    if mtype == "beam":
        mesh["n_span"] = max(2, int(config.model.n_aero_sections or 30))
    s = config.solver
    return TurbineOptions(model=mtype, aero=aero, method=method,
                          geometric_stiffness=s.geometric_stiffness, rigid_sections=s.rigid_sections,
                          air_density=config.air_density, min_rpm=r.min_rpm, max_rpm=r.max_rpm, rpm_step=step,
                          tolerance_rpm=r.tolerance_rpm, full_sweep=r.full_sweep, reduction=s.reduction,
                          basis_modes=s.basis_modes, correction_tol=s.correction_tol,
                          n_tracked=s.n_tracked, n_eig=s.n_eig, aero_distribution=s.aero_distribution,
                          induction=s.induction, high_thrust=s.high_thrust, mean_loads=s.mean_loads,
                          damping=config.damping.model,
                          damping_ratio=config.damping.ratio,
                          damping_reference_hz=config.damping.reference_hz, mesh=mesh)


__all__ = ["TurbineOptions", "TurbineStability", "PointSummary", "analyse_operating_point", "stability_map",
           "auto_tracked", "options_from_config", "replace"]
