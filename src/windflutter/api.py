"""windflutter's Python API: the commands of the CLI as functions.

The functions are re-exported by the package (``import windflutter``; the import stays light: this
module is loaded on first use) ::

    import windflutter

    turbine = windflutter.load_turbine("nrel5mw")             # or a windIO / .fst / .htc file
    f = windflutter.modes(turbine, part="blade", n=4)           # natural frequencies (Hz)
    res = windflutter.campbell(turbine, [6.0, 11.0, 18.0])      # -> CampbellResult
    pts = windflutter.stability(turbine, [11.0], model="beam")  # -> one PointSummary per wind speed
    ds = windflutter.run(turbine, "analysis.yaml", outdir="out/nrel5mw")   # results.nc, report.html
    sens = windflutter.api.sensitivity(turbine, [15.0], modes=["1st edge BW"])  # design sensitivities

Every entry point validates its input as the CLI does and raises
:class:`~windflutter.errors.InputError` naming the keyword (or config field), the value and what
was expected:

* ``modes`` checks each keyword with the :class:`~windflutter.schema.Spec` the ``windflutter
  modes`` flag of the same name uses (:data:`MODES_OPTIONS`, :data:`MESH_OPTIONS`);
* ``stability``, ``campbell`` and ``run`` take **analysis-config overrides** as keywords -- the
  top-level keys of the analysis YAML (``aero="potential"``, ``air_density=1.1``,
  ``solver={"reduction": "modal"}``), dotted field names (``**{"solver.basis_modes": 20}``) and,
  as on the command line, ``model="shell"`` for ``model.type`` -- merged over the defaults (or a
  ``config=``) by :func:`windflutter.config.config_from_dict`, the validator of a config file.

Units as at the CLI: wind speed m/s, rotor speed RPM, angles in degrees, frequencies Hz.
"""

from __future__ import annotations

import inspect
from pathlib import Path
from typing import Any

from windflutter.config import AnalysisConfig, check_config, config_from_dict, load_config
# the modes/mesh options: declared with the config, re-exported here (the API's names)
from windflutter.config.commands import DEFAULT_MODEL, MESH_DEFAULTS, MESH_OPTIONS, MODES_OPTIONS, SHELL_ONLY
from windflutter.errors import InputError
from windflutter.mesh.settings import MeshSettings
from windflutter.model.turbine import Turbine
from windflutter import operating
from windflutter import methods  # module access: tests patch methods.stability_analysis
from windflutter.operating import campbell_model
from windflutter.parallel import check_workers
from windflutter.post.runfolder import run_folder_name
from windflutter.sensitivity import onset as onset_
from windflutter.sensitivity.results import as_dataset, sensitivities
from windflutter.sensitivity import shell_results
from windflutter.simulate import onset as simulate_onset, run as simulate_run
from windflutter.system.campbell import default_wind_speeds
from windflutter.system.operational import missing_curve_error

# --------------------------------------------------------------------------------------------
# turbines and configs
# --------------------------------------------------------------------------------------------
def load_turbine(path_or_name: str | Path, validate: bool = True):
    """A turbine from a file or a bundled name.

    Parameters
    ----------
    path_or_name : a windIO (v1/v2) YAML file, an OpenFAST ``.fst`` deck, a HAWC2 ``.htc`` model, a
        seed-thesis file, or a bundled name (``"nrel5mw"``, ``"iea15mw"``, ... ;
        :func:`windflutter.model.bundled_turbines`).
    validate : schema validation where the format has one (windIO v2).

    Returns
    -------
    windflutter.model.Turbine

    Raises
    ------
    InputError
        missing or unreadable file, schema error, implausible data (naming file, field, station).
    """
    from windflutter.model import load_turbine as _load  # noqa: PLC0415

    if not isinstance(path_or_name, (str, Path)):
        raise InputError("turbine", type(path_or_name).__name__, "a turbine file path or a bundled name")
    return _load(path_or_name, validate=validate)


def as_turbine(turbine: Any, backend: str = "windflutter"):
    """``turbine`` itself if it is a :class:`~windflutter.model.Turbine`, else read with
    :func:`load_turbine`; for a plug-in back-end (``solver.backend``) a path or name is passed on
    unread, as ``windflutter run`` does."""
    if isinstance(turbine, Turbine):
        return turbine
    if not isinstance(turbine, (str, Path)):
        raise InputError("turbine", type(turbine).__name__, "a Turbine (windflutter.load_turbine), a turbine "
                         "file path or a bundled name")
    return str(turbine) if backend != "windflutter" else load_turbine(turbine)


def _nest(options: dict[str, Any]) -> dict[str, Any]:
    """Keyword overrides -> the nested dict of a config file (dotted keys split, ``model="shell"``
    read as ``model.type``)."""
    out: dict[str, Any] = {}
    for key, value in options.items():
        if key == "model" and isinstance(value, str):
            key = "model.type"
        *head, last = str(key).split(".")
        d = out
        for k in head:
            if not isinstance(d.setdefault(k, {}), dict):
                raise InputError(key, value, f"no {key!r} together with a non-section {k!r}")
            d = d[k]
        if isinstance(value, dict) and isinstance(d.get(last), dict):
            d[last] = {**d[last], **value}
        else:
            d[last] = value
    return out


def analysis_config(config: Any = None, **options):
    """An analysis config: ``config`` (``None``: the defaults; a YAML file path; a dict as in a
    file; an :class:`~windflutter.config.AnalysisConfig`) with the keyword overrides ``options``
    (module docstring) merged over it, validated as a config file is
    (:func:`windflutter.config.config_from_dict`).

    Raises
    ------
    InputError
        an unknown key or a bad value, naming the dotted field.
    """
    return _config(config, options, "keyword arguments")


def _config(config: Any, options: dict[str, Any], source: str):
    import copy  # noqa: PLC0415

    overrides = _nest(options)
    if config is None or isinstance(config, (str, Path)):
        return load_config(config, overrides, overrides_source=source)
    if isinstance(config, AnalysisConfig):
        base = check_config(config)
    elif isinstance(config, dict):
        base = config_from_dict(copy.deepcopy(config), "config dict", base=load_config(None))
    else:
        raise InputError("config", type(config).__name__, "None, an analysis YAML file, a dict or an AnalysisConfig")
    return config_from_dict(copy.deepcopy(overrides), source, base=base) if overrides else base


def _one(config, field: str, what: str) -> str:
    values = getattr(config, field)
    if len(values) != 1:
        raise InputError(field, list(values), f"one {what} (run() analyses several)")
    return values[0]


# --------------------------------------------------------------------------------------------
# structure
# --------------------------------------------------------------------------------------------
def mesh_settings(values: dict[str, Any], name=lambda key: key):
    """:class:`~windflutter.mesh.settings.MeshSettings` from checked :data:`MESH_OPTIONS` values
    (angles in degrees); the shell-only options are refused with the beam model (``name(key)``:
    how an error names an option, e.g. its CLI flag)."""
    import math  # noqa: PLC0415

    v = {**MESH_DEFAULTS, **{k: x for k, x in values.items() if x is not None}}
    if v["model"] != "shell":
        for key in SHELL_ONLY:
            if v[key] is not None:
                raise InputError(name(key), v[key], f"no value with the {v['model']} model ({name(key)} is a "
                                 f"shell-model option and the default model is {DEFAULT_MODEL}: add {name('model')} "
                                 "shell)")
    kw = dict(model=v["model"], part=v["part"], pitch=math.radians(v["pitch"]), azimuth=math.radians(v["azimuth"]),
              tower_model=v["tower_model"] or "shell")
    kw.update({k: v[k] for k in ("n_chord", "n_span", "tip_closure", "element_length", "reference_surface",
                                 "shell_shear") if v[k] is not None})
    return MeshSettings(**kw)


def _no_unknown(function: str, unknown: dict[str, Any], known) -> None:
    """An unknown keyword is an InputError naming it (not Python's TypeError)."""
    if unknown:
        key = next(iter(unknown))
        raise InputError(key, unknown[key], f"a keyword of windflutter.{function}: {', '.join(sorted(known))}")


def modes(turbine, *, rpm: float = 0.0, n: int = 10, part: str = "turbine", model: str = DEFAULT_MODEL,
          pitch: float = 0.0, azimuth: float = 0.0, n_chord: int | None = None, n_span: int | None = None,
          tower_model: str | None = None, tip_closure: str | None = None, **unknown):
    """Natural frequencies and labelled modes: ``windflutter modes``.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`, a turbine file or a bundled name.
    rpm : rotor speed (RPM); > 0 adds centrifugal stiffening and spin softening.
    n : number of modes.
    part : ``"turbine"``, ``"blade"`` (root clamped), ``"tower"`` (rotor-nacelle lumped) or
        ``"rotor"`` (hub clamped).
    model : ``"beam"`` (the default) or ``"shell"``.
    pitch, azimuth : blade pitch and rotor azimuth of blade 0 (deg).
    n_chord, tower_model, tip_closure : shell model only: elements around a section, the tower as shell
        or beam, the blade tips' closure (``"rib"``, ``"rigid"`` or ``"open"``).
    n_span : blade elements along the span.

    Returns
    -------
    windflutter.mesh.analysis.ModesResult
        ``.frequencies_hz`` (ascending), ``.labels``, and the model they come from.
    """
    from windflutter.mesh.analysis import turbine_modes  # noqa: PLC0415

    given = dict(rpm=rpm, n=n, part=part, model=model, pitch=pitch, azimuth=azimuth, n_chord=n_chord, n_span=n_span,
                 tower_model=tower_model, tip_closure=tip_closure)
    _no_unknown("modes", unknown, given)
    specs = {**MODES_OPTIONS, **MESH_OPTIONS}
    values = {k: (None if v is None else specs[k].check(v, k)) for k, v in given.items()}
    settings = mesh_settings(values)  # every option checked before the turbine is read
    return turbine_modes(as_turbine(turbine), settings, n_modes=values["n"], rpm=values["rpm"])


# --------------------------------------------------------------------------------------------
# aeroelastic analyses
# --------------------------------------------------------------------------------------------
def stability(turbine, wind_speeds, *, config: Any = None, **options) -> list:
    """Flutter and divergence onset above the operating point at each wind speed: ``windflutter
    stability``.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`, a turbine file or a bundled name.
    wind_speeds : m/s, one or a list (the config's ``wind_speeds`` field).
    config : base analysis config (see :func:`analysis_config`); one ``aero`` and one ``method``.
    **options : analysis-config overrides (module docstring), e.g. ``model="shell"``,
        ``rotor_speed={"max_rpm": 30}``, ``method="pk"``.

    Returns
    -------
    list of windflutter.results.PointSummary
        per wind speed: ``flutter_rpm``, ``flutter_frequency_hz``, ``flutter_mode``,
        ``divergence_rpm``, ``pitch_deg``, the sweep; ``.as_dict()`` is the CLI's ``--json`` point.
    """
    cfg = _config(config, {**options, "wind_speeds": wind_speeds}, "windflutter.stability() keywords")
    aero, method = _one(cfg, "aero", "aerodynamic variant"), _one(cfg, "method", "search method")
    methods.case_options(cfg, aero, method)  # the solver's options checked before the turbine is read
    solver = methods.stability_analysis(as_turbine(turbine), cfg, aero, method)
    return [solver.analyse_operating_point(v) for v in cfg.wind_speeds]


def campbell(turbine, wind_speeds=None, *, max_hz: float | None = None, config: Any = None, progress=None,
             workers: int | None = None, **options):
    """The operating-point Campbell diagram: ``windflutter campbell``.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`, a turbine file or a bundled name.
    wind_speeds : m/s; default the operating curve's within 3-25 m/s (a ``config``'s wind speeds
        are not used).
    max_hz : modes up to this frequency (Hz; the config's ``campbell.max_hz``); default 1.25 x the
        blade's 1st torsion frequency (:func:`windflutter.operating.operating_campbell`).
    config : base analysis config (see :func:`analysis_config`); one ``aero``.
    progress : optional ``progress(fraction, text)``.
    workers : processes evaluating the operating points (``windflutter campbell --workers``); default
        the usable cores for a shell model (a point takes seconds), 1 for a beam model.
    **options : analysis-config overrides (module docstring), e.g. ``model="shell"``,
        ``aero="potential"``, ``model={"part": "rotor"}``.

    Returns
    -------
    windflutter.system.campbell.CampbellResult
        ``.points`` (per wind speed: rotor speed, pitch, modes with frequency and damping),
        ``.least_damped()``, ``.unstable()``, ``.as_dict()`` (the CLI's ``--json``).
    """
    extra = {} if wind_speeds is None else {"wind_speeds": wind_speeds}
    if max_hz is not None:
        extra["campbell.max_hz"] = max_hz
    cfg = _config(config, {**options, **extra}, "windflutter.campbell() keywords")
    methods.operational_options(cfg, _one(cfg, "aero", "aerodynamic variant"))  # checked before the turbine is read
    winds = cfg.wind_speeds if wind_speeds is not None else None
    if workers is not None:
        check_workers(workers)  # before the turbine is read
    return operating.operating_campbell(as_turbine(turbine), cfg, winds, progress=progress, workers=workers)


def _operating_study(turbine, wind_speeds, max_hz, config, options: dict[str, Any], function: str):
    """``(turbine, model, wind speeds, max_hz)`` of a study along the operating curve (the
    sensitivities): the config from ``config`` and the keywords, checked before the turbine is read;
    the wind speeds given or the curve's; the Campbell's frequency limit."""
    extra = {} if wind_speeds is None else {"wind_speeds": wind_speeds}
    if max_hz is not None:
        extra["campbell.max_hz"] = max_hz
    cfg = _config(config, {**options, **extra}, f"windflutter.{function}() keywords")
    methods.operational_options(cfg, _one(cfg, "aero", "aerodynamic variant"))  # checked before the turbine is read
    t = as_turbine(turbine)
    if getattr(t, "operating_curve", None) is None:
        raise missing_curve_error(t)
    om = campbell_model(t, cfg)
    winds = cfg.wind_speeds if wind_speeds is not None else default_wind_speeds(t)
    return t, om, winds, operating.campbell_max_hz(cfg, om)


def sensitivity(turbine, wind_speeds=None, *, modes=None, blade_properties=None, global_parameters=None,
                total: bool = False, max_hz: float | None = None, config: Any = None, progress=None, **options):
    """Design sensitivities: the derivative of each named mode's frequency and damping ratio with
    respect to the blade's section properties (per beam element) and global parameters, at each wind
    speed -- ``windflutter sensitivity`` (:mod:`windflutter.sensitivity`, docs/sensitivity.md).

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`, a turbine file or a bundled name (beam blades).
    wind_speeds : m/s; default the operating curve's within 3-25 m/s.
    modes : identity names to keep (``["1st edge BW"]``); default every mode up to ``max_hz``.
    blade_properties, global_parameters : names (:data:`~windflutter.sensitivity.parameters.
        BLADE_PROPERTIES`, ``GLOBAL_PARAMETERS``); default all.
    total : also the whole-blade and global parameters' derivatives with the steady state's own change
        (its sensitivity, :mod:`windflutter.sensitivity.steady`; the blade basis held), which the
        per-element sensitivities hold fixed: ``dfrequency_total``, ``ddamping_total``.
    max_hz, config, progress, **options : as :func:`campbell`.

    Returns
    -------
    xarray.Dataset
        ``frequency``, ``damping_ratio`` (mode x wind_speed); ``dfrequency``, ``ddamping`` (mode x
        wind_speed x parameter x station); ``dfrequency_global``, ``ddamping_global``; ``defined``.
    """

    t, om, winds, hz = _operating_study(turbine, wind_speeds, max_hz, config, options, "sensitivity")
    if om.options.model != "beam":
        raise InputError("model.type", om.options.model, "beam (a shell blade's sensitivities, to the ply thickness "
                         "of its layup regions: windflutter.api.shell_sensitivity)")
    pts = sensitivities(om, winds, hz, modes=modes, blade_properties=blade_properties,
                        global_parameters=global_parameters, progress=progress, total=bool(total))
    return as_dataset(pts, str(getattr(t, "name", "")), om.describe())


def onset_sensitivity(turbine, wind_speed: float, *, mode: str | None = None, rpm: float | None = None,
                      blade_properties=None, global_parameters=None, total: bool = False,
                      max_hz: float | None = None, config: Any = None, **options):
    """The derivative of an instability's onset rotor speed with respect to the design parameters,
    by the implicit function theorem (:mod:`windflutter.sensitivity.onset`): at ``wind_speed`` (m/s),
    the operating curve's pitch held and the rotor speed raised.

    ``mode`` (identity name) and ``rpm`` (RPM, near the onset): default the first flutter onset of
    method p's search (:func:`stability`, which costs a rotor-speed sweep).  The onset is refined by
    the secant method.  ``total``: with the steady state's own change (else held at the onset).
    Other keywords as :func:`sensitivity`.

    Returns
    -------
    windflutter.sensitivity.onset.OnsetSensitivity
        ``rpm`` the onset, ``drpm[parameter]`` RPM per unit of the parameter (blade properties
        over the whole blade; relative ones per +100 %, offsets per m).
    """

    if max_hz is not None:
        options["campbell.max_hz"] = max_hz
    cfg = _config(config, {**options, "wind_speeds": [wind_speed]}, "windflutter.onset_sensitivity() keywords")
    t = as_turbine(turbine)
    if mode is None or rpm is None:
        found = stability(t, [wind_speed], config=cfg, method="p")[0]
        if found.flutter_rpm is None:
            raise InputError("wind_speed", wind_speed, "a wind speed where method p finds a flutter onset "
                             "(none up to the config's maximum rotor speed)")
        mode = mode or str(found.flutter_mode).split(" + ")[0]
        rpm = float(found.flutter_rpm) if rpm is None else rpm
    om = campbell_model(t, cfg)
    _, pitch = om.operating_point(float(wind_speed))
    hz = operating.campbell_max_hz(cfg, om)
    r0 = onset_.onset(lambda r: om.at(float(wind_speed), rpm=r, pitch=pitch), mode, float(rpm) - 0.1,
                      float(rpm) + 0.1, hz)
    return onset_.onset_sensitivity(om, float(wind_speed), mode, r0, pitch, hz, blade_properties=blade_properties,
                                    global_parameters=global_parameters, total=bool(total))


def shell_sensitivity(turbine, wind_speeds=None, *, modes=None, regions=None, max_hz: float | None = None,
                      config: Any = None, progress=None, **options):
    """Design sensitivities of a shell blade: the derivative of each named mode's frequency and damping
    ratio with respect to the ply thickness of each layup region (spar caps, TE/LE reinforcement,
    webs, panels, skin; relative), the steady state and the blade basis held --
    ``windflutter sensitivity --model shell`` (:mod:`windflutter.sensitivity.shell_results`).

    ``regions``: ``{name: layer names}``, or names of the default regions (default all of them: the
    layup's layers grouped by name, :func:`~windflutter.sensitivity.shell_results.default_regions`); the model is
    the shell one whatever ``config`` says; other keywords as :func:`sensitivity`.

    Returns
    -------
    xarray.Dataset
        ``frequency``, ``damping_ratio`` (mode x wind_speed); ``dfrequency_region``,
        ``ddamping_region``, ``defined`` (mode x wind_speed x region); ``region_layers``.
    """
    t, om, winds, hz = _operating_study(turbine, wind_speeds, max_hz, config, {**options, "model.type": "shell"},
                                        "shell_sensitivity")
    regs = shell_results.chosen_regions(t, regions)
    pts = shell_results.shell_sensitivities(om, winds, hz, modes=modes, regions=regs, progress=progress)
    return shell_results.shell_dataset(pts, regs, str(getattr(t, "name", "")), om.describe())


# --------------------------------------------------------------------------------------------
# the time domain: a second implementation
# --------------------------------------------------------------------------------------------
def simulate(turbine, rpm: float, wind_speed: float = 0.0, **options):
    """A nonlinear time-domain run of the whole turbine (``part="turbine"``, the default) or of one
    blade on a rigid hub (``part="blade"``) and the frequency and damping of its modes identified
    from the response: ``windflutter simulate`` (what is included:
    :mod:`windflutter.simulate.run`; keywords as :func:`windflutter.simulate.run.simulate`).

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`, a turbine file or a bundled name.
    rpm : rotor speed (RPM).  wind_speed : m/s (0: in vacuum).

    Returns
    -------
    windflutter.simulate.turbine_run.TurbineRun (or windflutter.simulate.blade.BladeRun)
    """
    known = [k for k in inspect.signature(simulate_run.simulate).parameters if k not in ("turbine", "rpm", "wind_speed")]
    _no_unknown("simulate", {k: v for k, v in options.items() if k not in known}, known)
    return simulate_run.simulate(as_turbine(turbine), rpm, wind_speed, **options)


def confirm_onset(turbine, wind_speed: float, **options):
    """Method p's first instability at ``wind_speed`` (m/s) -- of the whole turbine (``part=
    "turbine"``, the default) or of the rotor on a clamped hub (``part="rotor"``) -- simulated in
    the time domain at 0.97 and 1.03 x its rotor speed: ``windflutter simulate --confirm-onset``
    (keywords as :func:`windflutter.simulate.onset.confirm_onset`)."""
    known = [k for k in inspect.signature(simulate_onset.confirm_onset).parameters if k not in ("turbine", "wind_speed")]
    _no_unknown("confirm_onset", {k: v for k, v in options.items() if k not in known}, known)
    return simulate_onset.confirm_onset(as_turbine(turbine), wind_speed, **options)


# --------------------------------------------------------------------------------------------
# the whole analysis
# --------------------------------------------------------------------------------------------
def run(turbine, config: Any = None, outdir: str | Path | None = None, *, resume: bool = False,
        progress: bool = True, workers: int | None = 1, scheduler: Any = None, **options):
    """The whole analysis: ``windflutter run`` (results.nc, figures, report.html in ``outdir``).

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`, a turbine file or a bundled name.
    config : the analysis (see :func:`analysis_config`: ``None`` for the defaults, a YAML file...).
    outdir : output folder; default ``out/<name>`` (:func:`windflutter.post.runfolder.run_folder_name`), as
        ``windflutter run``.
    resume, progress, workers, scheduler : as :func:`windflutter.workflow.run` (``workers=1``:
        serial, in this process).
    **options : analysis-config overrides (module docstring), e.g. ``wind_speeds=[8, 12]``.

    Returns
    -------
    xarray.Dataset
        the results, also in ``outdir/results.nc``.
    """
    from windflutter.workflow import run as run_workflow  # noqa: PLC0415

    cfg = _config(config, options, "windflutter.run() keywords")
    folder = Path(outdir) if outdir is not None else Path("out") / run_folder_name(turbine)
    tb = as_turbine(turbine, cfg.solver.backend)
    return run_workflow(tb, cfg, folder, resume=resume, progress=progress, workers=workers, scheduler=scheduler)


__all__ = ["load_turbine", "analysis_config", "modes", "stability", "campbell", "sensitivity", "onset_sensitivity",
           "shell_sensitivity", "simulate", "confirm_onset", "run", "run_folder_name",
           "mesh_settings", "as_turbine", "MESH_OPTIONS", "MODES_OPTIONS", "DEFAULT_MODEL"]
