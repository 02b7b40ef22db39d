"""The analysis configuration of ``windflutter run``: what to compute, how, and what to write.

An analysis config is a small YAML file.  Every field has a documented default (the bundled
``data/analysis_default.yaml`` lists them all, with comments); a user file only states what it
changes.  Validation is strict: an unknown key, a value of the wrong kind or out of range raises
:class:`~windflutter.errors.InputError` naming the dotted field (``rotor_speed.max_rpm``), the
value and what was expected.  The full reference is ``docs/config_reference.md``.

Units at this edge follow the engineer's habits: wind speed m/s, rotor speed RPM, frequencies
Hz, angles degrees.  :class:`AnalysisConfig` keeps them as given; the workflow converts to SI.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
from dataclasses import asdict, dataclass, field, fields
from importlib import resources
from pathlib import Path
from typing import Any

import yaml

from windflutter.errors import InputError

AERO_VARIANTS = ("potential", "viscous")
SEARCH_METHODS = ("thesis", "pk")
MODEL_TYPES = ("shell", "beam", "section")
DAMPING_MODELS = ("none", "stiffness", "rayleigh", "modal")
PLOT_FORMATS = ("png", "svg", "pdf")
REDUCTIONS = ("mta", "modal", "none")
AERO_DISTRIBUTIONS = ("spline", "skin")
# keys of earlier versions: a clear message instead of "unknown key"
_RENAMED_SOLVER_KEYS = {
    "n_modes": "renamed: solver.n_eig (eigenvalues per eigen-solve); the projection basis is solver.basis_modes",
    "shift_hz": "removed: the p-k search shifts each eigen-solve to the tracked mode's own frequency",
}


@dataclass(frozen=True)
class RotorSpeedConfig:
    """Rotor-speed range searched for the onset, and the Campbell sweep grid (RPM).

    Attributes
    ----------
    min_rpm, max_rpm : search range (RPM); the onset is looked for in ``(min_rpm, max_rpm]``.
    n_points : number of rotor speeds of the Campbell / damping sweep (evenly spaced,
        ``min_rpm .. max_rpm``).
    tolerance_rpm : onset located to this rotor-speed tolerance (RPM).
    full_sweep : sweep every rotor speed of the grid (Campbell and damping data beyond the
        first instability); ``False`` (default) stops at the first grid speed past both the
        flutter and the divergence onsets -- the same onsets, about half the work on the
        NREL 5 MW, whose onsets lie at 22-24 RPM of the 2-40 RPM grid.
    """

    min_rpm: float = 2.0
    max_rpm: float = 40.0
    n_points: int = 20
    tolerance_rpm: float = 0.01
    full_sweep: bool = False


@dataclass(frozen=True)
class ModelConfig:
    """Which structural model to build.

    Attributes
    ----------
    type : ``shell`` (the thesis's composite-shell FE model), ``beam`` (Timoshenko beams with
        6x6 sections) or ``section`` (the seed's 2-DOF typical section at 75 % span).
    mesh_density : multiplier on the default number of elements along span and chord (-).
    n_aero_sections : aerodynamic strips per blade.
    """

    type: str = "beam"
    mesh_density: float = 1.0
    n_aero_sections: int = 30


@dataclass(frozen=True)
class DampingConfig:
    """Structural damping.

    Attributes
    ----------
    model : ``none``, ``stiffness`` (D = beta K with beta = 2 zeta / omega_ref),
        ``rayleigh`` (alpha M + beta K, zeta at ``reference_hz`` and 10x it) or ``modal``
        (the same ratio in every structural mode).
    ratio : damping ratio zeta (-).  The default 0 is conservative: the computed onset is
        the onset of the undamped structure.
    reference_hz : reference frequency of the stiffness / Rayleigh models (Hz).
    """

    model: str = "none"
    ratio: float = 0.0
    reference_hz: float = 1.0


@dataclass(frozen=True)
class SolverConfig:
    """Eigen-solver, model-reduction and search options.

    Attributes
    ----------
    backend : ``windflutter`` (the built-in solver) or ``"package.module:factory"``, a
        user-supplied analyser factory ``factory(turbine, config) -> analyse`` (see
        ``docs/workflow.md``).
    reduction : ``mta`` (structural modes plus aerodynamic static-correction vectors, the
        default: within 0.02 % of full order on the NREL 5 MW), ``modal`` (structural modes
        only) or ``none`` (full order, the reference; slow on shell models).
    basis_modes : structural modes per reference rotor speed in the projection basis.
    correction_tol : ``mta`` only: relative cut-off of the aerodynamic correction directions
        (kept when carrying more than ``sqrt(correction_tol)`` of the largest one's amplitude;
        1e-8, the default, is safe; 1e-4 halves the NREL 5 MW basis with the same onsets but
        puts the seed 20 MW's 2-5 % low).
    n_eig : eigenvalues computed per eigen-solve (near each tracked mode's frequency).
    n_tracked : modes followed across rotor speed by the p-k search and shown in the
        Campbell diagram; ``null`` (default) tracks every mode up to 1.25 x the first blade
        torsion frequency (the classical flutter partner of the flap modes).
    aero_distribution : how the strip forces reach a shell model: ``spline`` (rigid-section
        fit of the skin nodes, the default) or ``skin`` (the seed's bilinear skin quads, 2x2
        Gauss); beam models map directly (``spline``).
    geometric_stiffness : include the centrifugal stress stiffness K_sigma (full physics);
        ``false`` reproduces the thesis.
    induction : account for axial and tangential induction (steady BEM, frozen in the
        stability problem) in the inflow; ``false`` is the thesis's ``V, Omega r``.
    steady_loads : add the quasi-steady damping of the mean lift, drag and moment (the airfoil
        polars at each strip's steady angle of attack): the edgewise aerodynamic damping of the
        blades; ``false`` is the thesis's model.
    """

    backend: str = "windflutter"
    reduction: str = "mta"
    basis_modes: int = 30
    correction_tol: float = 1e-8
    n_eig: int = 20
    n_tracked: int | None = None
    aero_distribution: str = "spline"
    geometric_stiffness: bool = True
    induction: bool = False
    steady_loads: bool = False


@dataclass(frozen=True)
class OperatingConfig:
    """Reference rotor speeds for margins.  ``null`` takes the value from the turbine.

    Attributes
    ----------
    rated_rpm : rated rotor speed (RPM).
    overspeed_factor : overspeed = ``overspeed_factor * rated_rpm`` unless ``overspeed_rpm``
        is given.  The default 1.2 is a common design overspeed, not a standard's value; set it
        to your turbine's.
    overspeed_rpm : explicit overspeed (RPM).
    """

    rated_rpm: float | None = None
    overspeed_factor: float = 1.2
    overspeed_rpm: float | None = None


@dataclass(frozen=True)
class OutputConfig:
    """What the run writes into its output folder.

    Attributes
    ----------
    plots : write the figures.
    report : write ``report.html`` (figures embedded).
    formats : figure file formats.
    dpi : raster resolution of the figures.
    mode_shapes : store the flutter mode shape and the aero-work diagnostic per point.
    animations : write the flutter mode of every point with flutter as a VTK time series
        (``OUTDIR/animations/*.pvd``, one cycle, openable in ParaView) when the analyser gives
        the full mode and its FE model.
    animation_frames : frames per cycle (>= 16 recommended for a smooth loop).
    """

    plots: bool = True
    report: bool = True
    formats: tuple[str, ...] = ("png",)
    dpi: int = 110
    mode_shapes: bool = True
    animations: bool = True
    animation_frames: int = 24


@dataclass(frozen=True)
class AnalysisConfig:
    """Everything ``windflutter run`` needs besides the turbine.

    Attributes
    ----------
    wind_speeds : wind speeds (m/s), strictly increasing.
    aero : aerodynamic variants, each of ``potential`` (2 pi, no drag) and ``viscous`` (fitted
        polar slopes and drag).
    method : search methods, each of ``thesis`` (the seed's 8 reduced frequencies) and ``pk``
        (p-k with onset root-finding).
    air_density : kg/m^3.
    title : free text shown in the report.
    """

    wind_speeds: tuple[float, ...] = (4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 22.0, 25.0)
    aero: tuple[str, ...] = ("potential", "viscous")
    method: tuple[str, ...] = ("pk",)
    air_density: float = 1.225
    title: str = ""
    rotor_speed: RotorSpeedConfig = field(default_factory=RotorSpeedConfig)
    model: ModelConfig = field(default_factory=ModelConfig)
    damping: DampingConfig = field(default_factory=DampingConfig)
    solver: SolverConfig = field(default_factory=SolverConfig)
    operating: OperatingConfig = field(default_factory=OperatingConfig)
    output: OutputConfig = field(default_factory=OutputConfig)

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
        return yaml.safe_dump(self.to_dict(), sort_keys=False)

    def fingerprint(self, exclude_output: bool = True) -> str:
        """Hash of the settings that change results (output options excluded by default).

        ``--resume`` refuses to continue a run whose fingerprint differs.
        """
        d = self.to_dict()
        if exclude_output:
            d.pop("output", None)
            d.pop("title", None)
        return hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]


# --------------------------------------------------------------------------------------------
# validation
# --------------------------------------------------------------------------------------------
def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _number(name: str, v: Any, src: str | None, *, positive: bool = False,
            nonneg: bool = False, unit: str = "") -> float:
    u = f" ({unit})" if unit else ""
    if not _is_number(v) or not math.isfinite(float(v)):
        kind = "a positive" if positive else "a non-negative" if nonneg else "a finite"
        raise InputError(name, v, f"{kind} number{u}", src)
    v = float(v)
    if positive and v <= 0:
        raise InputError(name, v, f"a positive number{u}", src)
    if nonneg and v < 0:
        raise InputError(name, v, f"a non-negative number{u}", src)
    return v


def _integer(name: str, v: Any, src: str | None, minimum: int = 1) -> int:
    if isinstance(v, bool) or not (isinstance(v, int) or (isinstance(v, float) and v.is_integer())):
        raise InputError(name, v, f"an integer >= {minimum}", src)
    if int(v) < minimum:
        raise InputError(name, v, f"an integer >= {minimum}", src)
    return int(v)


def _boolean(name: str, v: Any, src: str | None) -> bool:
    if not isinstance(v, bool):
        raise InputError(name, v, "true or false", src)
    return v


def _choice(name: str, v: Any, choices: tuple[str, ...], src: str | None) -> str:
    if not isinstance(v, str) or v.lower() not in choices:
        raise InputError(name, v, "one of " + ", ".join(choices), src)
    return v.lower()


def _choices(name: str, v: Any, choices: tuple[str, ...], src: str | None) -> tuple[str, ...]:
    items = [v] if isinstance(v, str) else v
    if not isinstance(items, (list, tuple)) or not items:
        raise InputError(name, v, "a non-empty list of " + ", ".join(choices), src)
    out = tuple(_choice(f"{name}[{i}]", x, choices, src) for i, x in enumerate(items))
    if len(set(out)) != len(out):
        raise InputError(name, v, "a list without repeated entries", src)
    return out


def _optional_number(name: str, v: Any, src: str | None, unit: str) -> float | None:
    return None if v is None else _number(name, v, src, positive=True, unit=unit)


def _wind_speeds(v: Any, src: str | None) -> tuple[float, ...]:
    name = "wind_speeds"
    if isinstance(v, dict):
        _check_keys(name, v, {"start", "stop", "step"}, src)
        for k in ("start", "stop", "step"):
            if k not in v:
                raise InputError(f"{name}.{k}", None, "a number (m/s); start, stop and step are all required", src)
        start = _number(f"{name}.start", v["start"], src, nonneg=True, unit="m/s")
        stop = _number(f"{name}.stop", v["stop"], src, nonneg=True, unit="m/s")
        step = _number(f"{name}.step", v["step"], src, positive=True, unit="m/s")
        if stop < start:
            raise InputError(f"{name}.stop", stop, f"a wind speed >= start = {start} m/s", src)
        n = int(math.floor((stop - start) / step + 1e-9)) + 1
        vals = [start + i * step for i in range(n)]
        if n > 10000:
            raise InputError(f"{name}.step", step, "a step giving at most 10000 wind speeds", src)
        return tuple(round(x, 10) for x in vals)
    if _is_number(v):
        v = [v]
    if not isinstance(v, (list, tuple)) or not v:
        raise InputError(name, v, "a non-empty list of wind speeds (m/s) or {start, stop, step}", src)
    vals = []
    for i, x in enumerate(v):
        if not _is_number(x) or not math.isfinite(float(x)) or float(x) <= 0:
            raise InputError(f"{name}[{i}]", x, "a positive wind speed (m/s)", src)
        vals.append(float(x))
    for i in range(1, len(vals)):
        if vals[i] <= vals[i - 1]:
            raise InputError(f"{name}[{i}]", vals[i], f"strictly increasing wind speeds (> {vals[i - 1]} m/s)", src)
    return tuple(vals)


def _check_keys(prefix: str, d: dict, allowed: set[str], src: str | None) -> None:
    for k in d:
        if k not in allowed:
            name = f"{prefix}.{k}" if prefix else str(k)
            raise InputError(name, d[k], "a known key (unknown key; allowed: " + ", ".join(sorted(allowed)) + ")", src)


def _section(prefix: str, d: Any, cls: type, src: str | None) -> dict:
    if d is None:
        return {}
    if not isinstance(d, dict):
        raise InputError(prefix, d, "a mapping of " + ", ".join(f.name for f in fields(cls)), src)
    _check_keys(prefix, d, {f.name for f in fields(cls)}, src)
    return d


def config_from_dict(data: dict | None, source: str | None = None,
                     base: AnalysisConfig | None = None) -> AnalysisConfig:
    """Validate a (possibly partial) nested dict and merge it over ``base`` (defaults).

    Raises
    ------
    InputError
        naming the first bad field.
    """
    base = base or AnalysisConfig()
    src = source
    if data is None:
        data = {}
    if not isinstance(data, dict):
        raise InputError("(top level)", data, "a mapping of analysis settings", src)
    _check_keys("", data, {f.name for f in fields(AnalysisConfig)}, src)

    top: dict[str, Any] = {}
    if "wind_speeds" in data:
        top["wind_speeds"] = _wind_speeds(data["wind_speeds"], src)
    if "aero" in data:
        top["aero"] = _choices("aero", data["aero"], AERO_VARIANTS, src)
    if "method" in data:
        top["method"] = _choices("method", data["method"], SEARCH_METHODS, src)
    if "air_density" in data:
        top["air_density"] = _number("air_density", data["air_density"], src, positive=True, unit="kg/m^3")
    if "title" in data:
        if not isinstance(data["title"], str):
            raise InputError("title", data["title"], "a string", src)
        top["title"] = data["title"]

    # rotor speed
    d = _section("rotor_speed", data.get("rotor_speed"), RotorSpeedConfig, src)
    r = asdict(base.rotor_speed)
    for k in ("min_rpm", "max_rpm"):
        if k in d:
            r[k] = _number(f"rotor_speed.{k}", d[k], src, nonneg=True, unit="RPM")
    if "n_points" in d:
        r["n_points"] = _integer("rotor_speed.n_points", d["n_points"], src, 2)
    if "tolerance_rpm" in d:
        r["tolerance_rpm"] = _number("rotor_speed.tolerance_rpm", d["tolerance_rpm"], src, positive=True, unit="RPM")
    if "full_sweep" in d:
        r["full_sweep"] = _boolean("rotor_speed.full_sweep", d["full_sweep"], src)
    if r["max_rpm"] <= r["min_rpm"]:
        bad = "max_rpm" if "max_rpm" in d or "min_rpm" not in d else "min_rpm"
        exp = (f"a rotor speed above min_rpm = {r['min_rpm']} RPM" if bad == "max_rpm"
               else f"a rotor speed below max_rpm = {r['max_rpm']} RPM")
        raise InputError(f"rotor_speed.{bad}", r[bad], exp + " (range reversed or empty)", src)

    # model
    d = _section("model", data.get("model"), ModelConfig, src)
    m = asdict(base.model)
    if "type" in d:
        m["type"] = _choice("model.type", d["type"], MODEL_TYPES, src)
    if "mesh_density" in d:
        m["mesh_density"] = _number("model.mesh_density", d["mesh_density"], src, positive=True)
    if "n_aero_sections" in d:
        m["n_aero_sections"] = _integer("model.n_aero_sections", d["n_aero_sections"], src, 2)

    # damping
    d = _section("damping", data.get("damping"), DampingConfig, src)
    dm = asdict(base.damping)
    if "model" in d:
        dm["model"] = _choice("damping.model", d["model"], DAMPING_MODELS, src)
    if "ratio" in d:
        dm["ratio"] = _number("damping.ratio", d["ratio"], src, nonneg=True)
        if dm["ratio"] >= 1:
            raise InputError("damping.ratio", dm["ratio"], "a damping ratio in [0, 1)", src)
    if "reference_hz" in d:
        dm["reference_hz"] = _number("damping.reference_hz", d["reference_hz"], src, positive=True, unit="Hz")
    if dm["model"] != "none" and dm["ratio"] == 0 and "ratio" in d:
        pass  # allowed: explicit zero
    if dm["model"] == "none" and "ratio" in d and dm["ratio"] > 0 and "model" in d:
        raise InputError("damping.model", "none", "stiffness, rayleigh or modal when damping.ratio > 0", src)
    if dm["model"] == "none" and dm["ratio"] > 0:
        dm["model"] = "modal"

    # solver
    d = data.get("solver")
    if isinstance(d, dict):
        for k, why in _RENAMED_SOLVER_KEYS.items():
            if k in d:
                raise InputError(f"solver.{k}", d[k], f"a current key ({why})", src)
    d = _section("solver", d, SolverConfig, src)
    s = asdict(base.solver)
    if "backend" in d:
        b = d["backend"]
        if not isinstance(b, str) or not (b == "windflutter" or (":" in b and all(b.split(":", 1)))):
            raise InputError("solver.backend", b, "'windflutter' or 'package.module:factory'", src)
        s["backend"] = b
    if "reduction" in d:
        s["reduction"] = _choice("solver.reduction", d["reduction"], REDUCTIONS, src)
    if "aero_distribution" in d:
        s["aero_distribution"] = _choice("solver.aero_distribution", d["aero_distribution"],
                                         AERO_DISTRIBUTIONS, src)
    if "basis_modes" in d:
        s["basis_modes"] = _integer("solver.basis_modes", d["basis_modes"], src, 1)
    if "correction_tol" in d:
        s["correction_tol"] = _number("solver.correction_tol", d["correction_tol"], src, positive=True, unit="-")
        if not s["correction_tol"] < 1.0:
            raise InputError("solver.correction_tol", d["correction_tol"], "a relative cut-off in (0, 1), e.g. 1e-8", src)
    if "n_eig" in d:
        s["n_eig"] = _integer("solver.n_eig", d["n_eig"], src, 2)
    if "n_tracked" in d:
        s["n_tracked"] = None if d["n_tracked"] is None else _integer("solver.n_tracked", d["n_tracked"], src, 1)
    for k in ("geometric_stiffness", "induction", "steady_loads"):
        if k in d:
            s[k] = _boolean(f"solver.{k}", d[k], src)
    if s["reduction"] != "none" and s["n_tracked"] is not None and s["n_tracked"] > s["basis_modes"]:
        raise InputError("solver.n_tracked", s["n_tracked"],
                         f"at most solver.basis_modes = {s['basis_modes']} with reduction {s['reduction']}", src)
    if dm["model"] == "modal" and dm["ratio"] > 0 and s["reduction"] == "none":
        raise InputError("damping.model", "modal", "stiffness or rayleigh with solver.reduction none "
                         "(modal damping is applied in the modal basis)", src)
    if s["aero_distribution"] == "skin" and m["type"] != "shell":
        raise InputError("solver.aero_distribution", "skin", "spline unless model.type is shell "
                         "(skin quads need a shell model)", src)

    # operating
    d = _section("operating", data.get("operating"), OperatingConfig, src)
    o = asdict(base.operating)
    if "rated_rpm" in d:
        o["rated_rpm"] = _optional_number("operating.rated_rpm", d["rated_rpm"], src, "RPM")
    if "overspeed_rpm" in d:
        o["overspeed_rpm"] = _optional_number("operating.overspeed_rpm", d["overspeed_rpm"], src, "RPM")
    if "overspeed_factor" in d:
        o["overspeed_factor"] = _number("operating.overspeed_factor", d["overspeed_factor"], src, positive=True)
        if o["overspeed_factor"] < 1:
            raise InputError("operating.overspeed_factor", o["overspeed_factor"], "a factor >= 1", src)

    # output
    d = _section("output", data.get("output"), OutputConfig, src)
    out = asdict(base.output)
    for k in ("plots", "report", "mode_shapes", "animations"):
        if k in d:
            out[k] = _boolean(f"output.{k}", d[k], src)
    if "formats" in d:
        out["formats"] = _choices("output.formats", d["formats"], PLOT_FORMATS, src)
    if "dpi" in d:
        out["dpi"] = _integer("output.dpi", d["dpi"], src, 20)
    if "animation_frames" in d:
        out["animation_frames"] = _integer("output.animation_frames", d["animation_frames"], src, 4)
    out["formats"] = tuple(out["formats"])

    kw = {f.name: getattr(base, f.name) for f in fields(AnalysisConfig)}
    kw.update(top)
    kw.update(rotor_speed=RotorSpeedConfig(**r), model=ModelConfig(**m), damping=DampingConfig(**dm),
              solver=SolverConfig(**s), operating=OperatingConfig(**o), output=OutputConfig(**out))
    for k in ("wind_speeds", "aero", "method"):
        kw[k] = tuple(kw[k])
    return AnalysisConfig(**kw)


def default_config_text() -> str:
    """The bundled, commented default analysis (``data/analysis_default.yaml``)."""
    return resources.files("windflutter").joinpath("data/analysis_default.yaml").read_text()


def default_config() -> AnalysisConfig:
    """The default analysis, read from the bundled YAML (so file and dataclass agree)."""
    return config_from_dict(yaml.safe_load(default_config_text()), "analysis_default.yaml")


def load_config(path: str | Path | None = None, overrides: dict | None = None) -> AnalysisConfig:
    """Read an analysis YAML over the defaults; ``None`` gives the defaults.

    Parameters
    ----------
    path : YAML file, or ``None``.
    overrides : nested dict applied after the file (e.g. from the command line).

    Raises
    ------
    InputError
        unreadable file, bad YAML, unknown key or bad value (naming the field).
    """
    cfg = default_config()
    if path is not None:
        p = Path(path)
        if not p.is_file():
            raise InputError("config", str(path), "an existing analysis YAML file")
        try:
            data = yaml.safe_load(p.read_text())
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            where = f"line {mark.line + 1}" if mark is not None else "?"
            raise InputError("config", str(path), f"valid YAML (parse error at {where})") from None
        cfg = config_from_dict(data, p.name, base=cfg)
    if overrides:
        cfg = config_from_dict(copy.deepcopy(overrides), "command line", base=cfg)
    return cfg
