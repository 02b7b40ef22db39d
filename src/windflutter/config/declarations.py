"""The declarations of the analysis config: choices, bounds and one dataclass per section, each
field with its :class:`~windflutter.schema.Spec` (see :mod:`windflutter.config`)."""

from __future__ import annotations

import functools
import hashlib
import json
import math
from dataclasses import Field, asdict, dataclass, fields
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

from windflutter.aero_types import HIGH_THRUST
from windflutter.backends import check_backend_name
from windflutter.exporters import check_export_format
from windflutter.errors import InputError
from windflutter.files import dump_yaml
from windflutter.schema import Spec, check_keys, document_settings, is_number, section, setting

AERO_VARIANTS = ("potential", "viscous")
SEARCH_METHODS = ("p", "pk", "thesis")
MODEL_TYPES = ("shell", "beam", "section")
MODEL_PARTS = ("turbine", "rotor")
TIP_CLOSURES = ("rib", "rigid", "open")
REFERENCE_SURFACES = ("midsurface", "outer")
SHELL_SHEAR_MODELS = ("mitc4", "one-point")
#: beam blades: elements along the span unless told
BEAM_SPAN_ELEMENTS = 30
#: shell blades without an element length: the target length along the span is the blade length over
#: this (the convergence study of tests/mesh/test_mesh_convergence.py: the error of the Campbell
#: frequencies is set by the elements per blade length, alike on blades of 61.5 m and 138 m)
SHELL_SPAN_ELEMENTS = 100
DAMPING_MODELS = ("file", "none", "stiffness", "rayleigh", "modal")
DRIVETRAINS = ("flexible", "rigid", "locked")
CIRCULATIONS = ("jones", "rfa", "quasi_steady")
STRUCTURES = ("auto", "undeformed", "deflected")
PLOT_FORMATS = ("png", "svg", "pdf")
REDUCTIONS = ("mta", "modal", "none")
AERO_DISTRIBUTIONS = ("spline", "skin")

#: bounds of the sizes and ranges (the reasons are in docs/config_reference.md, "Bounds")
MAX_RPM = 1000.0            # RPM; a utility-scale rotor runs at 5-20 RPM, small turbines < 500
MAX_WIND_SPEED = 100.0      # m/s; 70 m/s is the IEC class I 50-year gust
MAX_WIND_SPEEDS = 1000      # wind speeds of a run (each one a point per case)
MAX_GRID_POINTS = 1000      # rotor speeds of the sweep
MAX_BLADE_ELEMENTS = 1000   # blade elements (= strips) along the span after mesh_density
MAX_MODES = 500             # basis_modes, n_eig, n_tracked
MAX_AIR_DENSITY = 2.0       # kg/m^3; dry air at -50 degC and 1050 hPa is 1.64

# keys of earlier versions: a clear message instead of "unknown key"
RENAMED = {"solver": {
    "steady_loads": "renamed: solver.mean_loads (the mean-load terms, now on by default)",
    "n_modes": "renamed: solver.n_eig (eigenvalues per eigen-solve); the projection basis is solver.basis_modes",
    "shift_hz": "removed: the p-k search shifts each eigen-solve to the tracked mode's own frequency",
}}


def _wind_speeds(v: Any, name: str, src: str | None) -> tuple[float, ...]:
    """A list of positive, strictly increasing wind speeds, or ``{start, stop, step}``.

    The number of speeds of a range is computed (and bounded) before the list is built.
    """
    one = Spec("float", lower=0.0, lower_open=True, upper=MAX_WIND_SPEED, unit="m/s")
    if isinstance(v, dict):
        check_keys(f"{name}.", v, ("start", "stop", "step"), src)
        for k in ("start", "stop", "step"):
            if k not in v:
                raise InputError(f"{name}.{k}", None, "a number (m/s); start, stop and step are all required", src)
        start, stop = (one.check(v[k], f"{name}.{k}", src) for k in ("start", "stop"))
        step = Spec("float", lower=0.0, lower_open=True, upper=MAX_WIND_SPEED, unit="m/s").check(
            v["step"], f"{name}.step", src)
        if stop < start:
            raise InputError(f"{name}.stop", stop, f"a wind speed >= start = {start:g} m/s", src)
        n = (stop - start) / step
        if not n < MAX_WIND_SPEEDS:
            raise InputError(f"{name}.step", step, f"a step giving at most {MAX_WIND_SPEEDS} wind speeds "
                             f"(this one gives {n + 1:.3g})", src)
        count = int(math.floor(n + 1e-9)) + 1
        return tuple(round(start + i * step, 10) for i in range(count))
    if is_number(v):
        v = [v]
    if not isinstance(v, (list, tuple)) or not v or len(v) > MAX_WIND_SPEEDS:
        raise InputError(name, v, f"a list of 1 to {MAX_WIND_SPEEDS} wind speeds (m/s) or {{start, stop, step}}", src)
    vals = []
    for i, x in enumerate(v):
        if not (is_number(x) and one._in_bounds(x) and math.isfinite(x)):
            raise InputError(f"{name}[{i}]", x, f"a positive wind speed up to {MAX_WIND_SPEED:g} m/s", src)
        vals.append(float(x))
        if i and vals[i] <= vals[i - 1]:
            raise InputError(f"{name}[{i}]", vals[i], f"strictly increasing wind speeds (> {vals[i - 1]:g} m/s)", src)
    return tuple(vals)


def _backend(v: Any, name: str, src: str | None) -> str:
    return check_backend_name(v, name, src)


def _exports(v: Any, name: str, src: str | None) -> tuple[str, ...]:
    """Names of registered export formats (:mod:`windflutter.exporters`), without repeats."""
    items = [v] if isinstance(v, str) else v
    if not isinstance(items, (list, tuple)):
        raise InputError(name, v, "a list of export format names", src)
    out = tuple(check_export_format(x, name, src) for x in items)
    if len(set(out)) != len(out):
        raise InputError(name, v, "a list without repeated entries", src)
    return out


# --------------------------------------------------------------------------------------------
# the declarations
# --------------------------------------------------------------------------------------------
_RPM = dict(unit="RPM")


@dataclass(frozen=True)
class RotorSpeedConfig:
    """Rotor-speed range searched for the onset, and the Campbell sweep grid (RPM)."""

    min_rpm: float = setting(2.0, "float", "lower end of the rotor-speed search", lower=0.0, upper=MAX_RPM,
                         upper_open=True, **_RPM)
    max_rpm: float = setting(40.0, "float", "upper end of the search; the onset is looked for in (min_rpm, max_rpm]",
                         lower=0.0, lower_open=True, upper=MAX_RPM, **_RPM)
    max_tip_mach: float | None = setting(0.5, "float", "method p: the search also ends where the blade tip's speed "
                                     "relative to the wind, sqrt((rotor speed x tip radius)^2 + V^2), reaches this "
                                     "Mach number (340 m/s): above 0.5 the incompressible strips are outside their "
                                     "range (docs/induction.md); null: max_rpm alone", lower=0.05, upper=3.0,
                                     nullable=True, unit="-")
    n_points: int = setting(20, "int", "rotor speeds of the sweep (evenly spaced, ends included): the Campbell "
                        "diagram and the brackets of the onset search", lower=2, upper=MAX_GRID_POINTS)
    tolerance_rpm: float = setting(0.01, "float", "onset located to this rotor-speed tolerance; at most the sweep step",
                               lower=1e-6, upper=10.0, **_RPM)
    full_sweep: bool = setting(False, "bool", "sweep the whole grid (Campbell and damping beyond the first "
                           "instability); false stops at the first grid speed past both onsets (same onsets)")


@dataclass(frozen=True)
class ModelConfig:
    """Which structural model to build."""

    type: str = setting("beam", "choice", "shell (the thesis's composite shells), beam (Timoshenko beams with 6x6 "
                    "sections, much faster) or section (the seed's 2-DOF section: windflutter simple)",
                    choices=MODEL_TYPES)
    part: str = setting("turbine", "choice", "turbine (tower, nacelle, hub and blades) or rotor (blades and hub on a "
                    "fixed nacelle, no tower; the shaft as model.drivetrain says: method p free by default, locked = "
                    "hub clamped; pk and thesis always hub clamped)", choices=MODEL_PARTS)
    mesh_density: float = setting(1.0, "float", "multiplier on the element counts (blade elements along the span "
                              "n_aero_sections x density, or the shell's element length / density; shells also "
                              "around each section and on the tower)",
                              lower=0.1, upper=4.0, unit="-")
    n_aero_sections: int | None = setting(None, "int", "blade elements along the span, one aerodynamic strip each (at "
                                      "mesh_density 1); null: 30 for beams, for shells from the element length",
                                      lower=4, upper=MAX_BLADE_ELEMENTS, nullable=True)
    element_length: float | None = setting(None, "float", "shell models, when n_aero_sections is null: target length "
                                       "of the blade's skin elements along the span (the elements around a "
                                       "section follow, at least 40); null: the blade length / 100, the default "
                                       "chosen by the mesh convergence study (docs/mesh.md)", lower=0.0,
                                       lower_open=True, upper=100.0, nullable=True, unit="m")
    reference_surface: str = setting("midsurface", "choice", "shell models: the skin's reference surface -- "
                                 "midsurface (the laminate midsurface, inside the outer mould line by half the "
                                 "laminate: the walls the layup describes) or outer (the seed's: on the outer "
                                 "mould line, half of each laminate outside the airfoil)",
                                 choices=REFERENCE_SURFACES)
    tip_closure: str = setting("rib", "choice", "shell models: how each blade's end section is closed -- rib (a thin "
                           "rib: the section keeps its shape in its plane, warping free), rigid (a rigid section) or "
                           "open (the skin's free edge, windflutter's mesh until Dec 2026; docs/mesh.md)", choices=TIP_CLOSURES)
    shell_shear: str = setting("mitc4", "choice", "shell models: the elements' transverse shear -- mitc4 (assumed "
                           "covariant shear strains, Dvorkin and Bathe 1984: no spurious mode) or one-point (pyfe3d's "
                           "Quad4 as it is, windflutter's element before Dec 2026: its hourglass mode turns unstable "
                           "under compressive steady stress; docs/mesh.md)", choices=SHELL_SHEAR_MODELS)
    drivetrain: str = setting("flexible", "choice", "method p: flexible (shaft spring and generator inertia of the "
                          "turbine file), rigid (one rotor azimuth freedom) or locked (the rotor locked to the "
                          "nacelle, as the seed's model; pk and thesis always lock it)", choices=DRIVETRAINS)


@dataclass(frozen=True)
class DampingConfig:
    """Structural damping."""

    model: str = setting("file", "choice", "file (the turbine files' structural damping: blade mu per direction, "
                     "tower modal ratios; none where a file gives none), none, stiffness (D = beta K), rayleigh "
                     "(alpha M + beta K) or modal (the ratio in every structural mode of the basis; needs "
                     "solver.reduction mta or modal)", choices=DAMPING_MODELS)
    ratio: float = setting(0.0, "float", "damping ratio; 0 gives the onset of the undamped structure (conservative); "
                       "> 0 with model none switches the model to modal", lower=0.0, upper=1.0, upper_open=True,
                       unit="-")
    reference_hz: float = setting(1.0, "float", "reference frequency of stiffness / Rayleigh damping (Rayleigh: and "
                              "10 x it)", lower=1e-3, upper=1000.0, unit="Hz")
    tower_ratio: float | None = setting(None, "float", "model file, method p: the modal damping ratio of every tower "
                                    "mode in place of the files' (e.g. to match another code's tower model); null: "
                                    "the files'", lower=0.0, upper=1.0, upper_open=True, nullable=True, unit="-")


@dataclass(frozen=True)
class SolverConfig:
    """Eigen-solver, model-reduction and search options."""

    backend: str = setting("windflutter", "custom", "windflutter (the built-in solver) or the name of a plug-in "
                       "analyser registered in the entry-point group windflutter.backends", parse=_backend)
    reduction: str = setting("mta", "choice", "mta (structural modes + aerodynamic static-correction vectors), modal "
                         "(structural modes only) or none (full order, the reference)", choices=REDUCTIONS)
    basis_modes: int = setting(30, "int", "structural modes per reference rotor speed in the projection basis",
                           lower=1, upper=MAX_MODES)
    correction_tol: float = setting(1e-8, "float", "mta only: relative cut-off of the aerodynamic correction "
                                "directions (kept above sqrt(tol) of the largest)", lower=1e-16, upper=1.0,
                                upper_open=True, unit="-")
    n_eig: int = setting(20, "int", "eigenvalues per eigen-solve (near each tracked mode's frequency)",
                     lower=2, upper=MAX_MODES)
    n_tracked: int | None = setting(None, "int", "modes followed across rotor speed by the p-k search; null: every "
                                "mode up to 1.25 x the first blade-torsion frequency; <= basis_modes when reduced",
                                lower=1, upper=MAX_MODES, nullable=True)
    aero_distribution: str = setting("spline", "choice", "shell models: spline (rigid-section fit of the skin nodes) "
                                 "or skin (the seed's skin quads); beams need spline", choices=AERO_DISTRIBUTIONS)
    geometric_stiffness: bool = setting(True, "bool", "centrifugal stress stiffness K_sigma (full physics); false "
                                    "reproduces the thesis")
    rigid_sections: bool = setting(True, "bool", "pk and thesis searches: the centrifugal, Coriolis and spin-softening "
                               "terms of beam sections as rigid bodies (mass-centre offsets, rotary inertia) with "
                               "the initial stress of every stress resultant (full physics; independent of where "
                               "the 6x6 reference axis lies); false: the thesis's translational terms and axial "
                               "initial stress.  Method p always has the full terms")
    induction: bool = setting(True, "bool", "axial and tangential induction from a steady BEM solution, frozen in "
                          "the stability problem; false is the thesis's inflow V, Omega r")
    high_thrust: str = setting("buhl", "choice", "the BEM's thrust-induction relation: buhl (momentum to "
                           "a = 0.4, Buhl's turbulent-wake thrust above; OpenFAST AeroDyn's), madsen (HAWC2's and "
                           "HAWCStab2's cubic a(CT), Madsen et al. 2020) or momentum (no high-thrust correction)",
                           choices=HIGH_THRUST)
    mean_loads: bool = setting(True, "bool", "the mean-load terms: the quasi-steady force of the mean lift, drag "
                           "and moment (polars at each strip's steady angle of attack) under section motion -- "
                           "the edgewise aerodynamic damping; false is the thesis's model")
    deflection: bool = setting(True, "bool", "method p: linearize about the deflected steady state (BEM, centrifugal "
                           "and aerodynamic loads, elastic twist); false: the undeformed blade (pk and thesis "
                           "always)")
    corotational: bool = setting(True, "bool", "method p, beam blades: the deflected steady state on the "
                             "co-rotational beam (exact for any reference line of the sections); false: the "
                             "linear structure with second-order load corrections (shell blades always)")
    structure: str = setting("auto", "choice", "method p: the blade structure the stability problem is linearized "
                         "about: deflected (beam blades: the co-rotational beam re-equilibrated under the steady "
                         "loads, the geometric stiffness of every steady stress resultant; shell blades: the "
                         "shell carried to its deflected steady shape, its elements turned with it, with the membrane "
                         "stress of the deformed blade's loads), undeformed (the straight axis turned by the "
                         "elastic twist, the geometric stiffness of the undeformed blade's stress) or auto "
                         "(deflected with solver.deflection, undeformed otherwise)",
                         choices=STRUCTURES)
    circulation: str = setting("jones", "choice", "method p: the rational approximation of Theodorsen's C(k) behind "
                           "the aerodynamic lag states: jones (R.T. Jones, 2 states per strip), rfa (Roger fit "
                           "with n_lag poles) or quasi_steady (C = 1, no states)", choices=CIRCULATIONS)
    n_lag: int = setting(4, "int", "method p, circulation rfa: lag poles of the Roger fit", lower=1, upper=8)
    dynamic_stall: bool = setting(False, "bool", "method p: the separation-point lag of Oye's dynamic-stall model "
                              "(one more state per strip)")
    aero_state_tol: float | None = setting(1e-7, "float", "method p: each blade's aerodynamic lag states reduced by "
                                       "balanced truncation -- Hankel singular values below this fraction of the "
                                       "largest dropped, their static part kept; null: every state (the reference)",
                                       lower=1e-14, upper=1.0, upper_open=True, nullable=True, unit="-")


@dataclass(frozen=True)
class CampbellConfig:
    """The operating-point Campbell analysis of ``windflutter run`` (method p)."""

    enabled: bool = setting(True, "bool", "add the operating-point Campbell diagram (every mode along the operating "
                        "curve, ground-fixed frame) to the run")
    max_hz: float | None = setting(None, "float", "modes up to this frequency; null: 1.25 x the first blade torsion "
                               "frequency", lower=0.01, upper=100.0, nullable=True, unit="Hz")


@dataclass(frozen=True)
class OperatingConfig:
    """Reference rotor speeds for margins; ``null`` takes the value from the turbine."""

    rated_rpm: float | None = setting(None, "float", "rated rotor speed for the margins; null: the turbine's",
                                  lower=0.0, lower_open=True, upper=MAX_RPM, nullable=True, **_RPM)
    overspeed_factor: float = setting(1.2, "float", "overspeed = factor x rated unless overspeed_rpm is given (1.2 "
                                  "is a common design overspeed, not a standard's value)", lower=1.0, upper=3.0,
                                  unit="-")
    overspeed_rpm: float | None = setting(None, "float", "explicit overspeed; at least the rated rotor speed",
                                      lower=0.0, lower_open=True, upper=MAX_RPM, nullable=True, **_RPM)


@dataclass(frozen=True)
class OutputConfig:
    """What the run writes into its output folder."""

    plots: bool = setting(True, "bool", "write OUTDIR/figures/*")
    report: bool = setting(True, "bool", "write OUTDIR/report.html (figures embedded)")
    formats: tuple[str, ...] = setting(("png",), "choices", "figure formats", choices=PLOT_FORMATS)
    dpi: int = setting(110, "int", "raster resolution of the figures", lower=20, upper=1200)
    exports: tuple[str, ...] = setting((), "custom", "export formats of the operating-point Campbell, each written to "
                                   "OUTDIR/campbell.<suffix>: csv, cmb, amp, figure, netcdf or a plug-in's "
                                   "(entry-point group windflutter.exporters)", parse=_exports)
    mode_shapes: bool = setting(True, "bool", "store the flutter mode shape and the aero-work diagnostic per point")
    animations: bool = setting(True, "bool", "write the flutter mode of every point with flutter as a VTK time "
                           "series (OUTDIR/animations/*.pvd, ParaView)")
    animation_frames: int = setting(24, "int", "frames per cycle of the animations (>= 16 for a smooth loop)",
                                lower=4, upper=360)


@dataclass(frozen=True)
class AnalysisConfig:
    """Everything ``windflutter run`` needs besides the turbine."""

    wind_speeds: tuple[float, ...] = setting(
        (4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 22.0, 25.0), "custom",
        f"a list of positive, strictly increasing wind speeds up to {MAX_WIND_SPEED:g} m/s, or {{start, stop, "
        f"step}} (inclusive); at most {MAX_WIND_SPEEDS}", parse=_wind_speeds, unit="m/s")
    aero: tuple[str, ...] = setting(("viscous",), "choices", "aerodynamic variants: viscous (the airfoil polars: "
                                "method p their local slopes at the steady angle of attack, pk / thesis the seed's "
                                "fitted slopes and drag) and/or potential (2 pi, no drag)", choices=AERO_VARIANTS)
    method: tuple[str, ...] = setting(("p",), "choices", "search methods: p (eigenvalues of the whole turbine in "
                                  "multi-blade coordinates with aerodynamic states: valid at any damping), pk "
                                  "(the seed's model: p-k with onset root-finding) and/or thesis (the seed's 8 "
                                  "reduced frequencies)", choices=SEARCH_METHODS)
    air_density: float = setting(1.225, "float", "air density", lower=0.0, lower_open=True, upper=MAX_AIR_DENSITY,
                             unit="kg/m^3")
    title: str = setting("", "str", "free text shown in the report", max_len=500)
    rotor_speed: RotorSpeedConfig = section(RotorSpeedConfig)
    model: ModelConfig = section(ModelConfig)
    damping: DampingConfig = section(DampingConfig)
    solver: SolverConfig = section(SolverConfig)
    campbell: CampbellConfig = section(CampbellConfig)
    operating: OperatingConfig = section(OperatingConfig)
    output: OutputConfig = section(OutputConfig)

    # -- derived -----------------------------------------------------------------------------
    @property
    def cases(self) -> list[tuple[str, str]]:
        """``(aero, method)`` combinations, in config order."""
        return [(a, m) for a in self.aero for m in self.method]

    def sweep_rpm(self) -> list[float]:
        """The Campbell sweep grid (RPM)."""
        r = self.rotor_speed
        if r.n_points == 1:
            return [r.max_rpm]
        step = (r.max_rpm - r.min_rpm) / (r.n_points - 1)
        return [r.min_rpm + i * step for i in range(r.n_points)]

    def to_dict(self) -> dict[str, Any]:
        """Plain nested dict (YAML/JSON-ready; tuples become lists)."""
        return json.loads(json.dumps(asdict(self)))

    def to_yaml(self) -> str:
        """YAML text that :func:`load_config` reads back equal."""
        return dump_yaml(self.to_dict())

    def fingerprint(self, exclude_output: bool = True) -> str:
        """Hash of the settings that change results (output options excluded by default).

        The run's own fingerprint (:func:`windflutter.workflow.run_fingerprint`) adds the
        turbine's content and the package version; ``--resume`` refuses any difference.
        """
        d = self.to_dict()
        if exclude_output:
            d.pop("output", None)
            d.pop("title", None)
        return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]


def declared_fields(cls: type = AnalysisConfig, prefix: str = "") -> tuple[tuple[str, Field, Spec], ...]:
    """``(dotted name, dataclass field, spec)`` of every declared setting, in declaration order
    (computed once per section: the declarations do not change)."""
    return _declared(cls, prefix)


@functools.lru_cache(maxsize=None)
def _declared(cls: type, prefix: str) -> tuple[tuple[str, Field, Spec], ...]:
    out: list[tuple[str, Field, Spec]] = []
    for f in fields(cls):
        if "section" in f.metadata:
            out.extend(_declared(f.metadata["section"], f"{prefix}{f.name}."))
        else:
            out.append((f"{prefix}{f.name}", f, f.metadata["spec"]))
    return tuple(out)


@functools.lru_cache(maxsize=1)
def field_specs() -> Mapping[str, Spec]:
    """Every config field's :class:`~windflutter.schema.Spec` by dotted name (read-only)."""
    return MappingProxyType({name: spec for name, _, spec in declared_fields()})


def field_spec(dotted: str) -> Spec:
    """The :class:`~windflutter.schema.Spec` of a dotted config field, e.g. ``solver.basis_modes``."""
    return field_specs()[dotted]


for _cls in (RotorSpeedConfig, ModelConfig, DampingConfig, SolverConfig, CampbellConfig, OperatingConfig, OutputConfig,
             AnalysisConfig):
    document_settings(_cls)
