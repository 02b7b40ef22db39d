"""Reading and checking an analysis config: the declared fields applied recursively, then the rules
between fields (the ``_rule_*`` functions), the bundled defaults and YAML files (see
:mod:`windflutter.config`)."""

from __future__ import annotations

import copy
import functools
import math
import warnings
from dataclasses import fields, replace
from importlib import resources
from pathlib import Path
from typing import Any

from windflutter.config.declarations import (
    RENAMED, MAX_BLADE_ELEMENTS, MAX_GRID_POINTS, MAX_RPM, SHELL_SPAN_ELEMENTS, BEAM_SPAN_ELEMENTS,
    AnalysisConfig,
    field_spec)
from windflutter.errors import InputError, InputWarning
from windflutter.files import load_yaml, parse_yaml
from windflutter.schema import Spec, check_keys


# --------------------------------------------------------------------------------------------
# validation: the declarations, then the rules between fields
# --------------------------------------------------------------------------------------------
def _merge(cls: type, data: Any, base: Any, prefix: str, src: str | None, given: set[str]) -> Any:
    """``base`` with the declared fields of ``data`` checked and applied (recursively)."""
    if data is None:
        return base
    name = prefix.rstrip(".") or "(top level)"
    if not isinstance(data, dict):
        what = "analysis settings" if not prefix else ", ".join(f.name for f in fields(cls))
        raise InputError(name, data, f"a mapping of {what}", src)
    check_keys(prefix, data, {f.name for f in fields(cls)}, src, RENAMED.get(prefix.rstrip(".")))
    kw = {}
    for f in fields(cls):
        if f.name not in data:
            continue
        dotted = prefix + f.name
        if "section" in f.metadata:
            kw[f.name] = _merge(f.metadata["section"], data[f.name], getattr(base, f.name), dotted + ".", src, given)
        else:
            kw[f.name] = f.metadata["spec"].check(data[f.name], dotted, src)
            given.add(dotted)
    return replace(base, **kw)


def _rule_rotor_range(c: AnalysisConfig, given: set[str], src: str | None) -> AnalysisConfig:
    r = c.rotor_speed
    if r.max_rpm <= r.min_rpm:
        bad = "max_rpm" if "rotor_speed.max_rpm" in given or "rotor_speed.min_rpm" not in given else "min_rpm"
        exp = (f"a rotor speed above min_rpm = {r.min_rpm:g} RPM" if bad == "max_rpm"
               else f"a rotor speed below max_rpm = {r.max_rpm:g} RPM")
        raise InputError(f"rotor_speed.{bad}", getattr(r, bad), exp + " (range reversed or empty)", src)
    step = (r.max_rpm - r.min_rpm) / (r.n_points - 1)
    if r.tolerance_rpm > step:
        raise InputError("rotor_speed.tolerance_rpm", r.tolerance_rpm,
                         f"a tolerance at most the sweep step {step:.4g} RPM", src)
    return c


def _rule_damping(c: AnalysisConfig, given: set[str], src: str | None) -> AnalysisConfig:
    d = c.damping
    if d.model == "none" and d.ratio > 0:
        if "damping.model" in given:
            raise InputError("damping.model", "none", "stiffness, rayleigh or modal when damping.ratio > 0", src)
        c = replace(c, damping=replace(d, model="modal"))
    if c.damping.model == "modal" and c.damping.ratio > 0 and c.solver.reduction == "none":
        raise InputError("damping.model", "modal", "stiffness or rayleigh with solver.reduction none "
                         "(modal damping is applied in the modal basis)", src)
    return c


def _rule_solver(c: AnalysisConfig, given: set[str], src: str | None) -> AnalysisConfig:
    s = c.solver
    if s.reduction != "none" and s.n_tracked is not None and s.n_tracked > s.basis_modes:
        raise InputError("solver.n_tracked", s.n_tracked,
                         f"at most solver.basis_modes = {s.basis_modes} with reduction {s.reduction}", src)
    if s.aero_distribution == "skin" and c.model.type != "shell":
        raise InputError("solver.aero_distribution", "skin", "spline unless model.type is shell "
                         "(skin quads need a shell model)", src)
    if s.structure == "deflected" and not s.deflection:
        raise InputError("solver.structure", s.structure, "undeformed or auto unless solver.deflection is true "
                         "(there is no deflected shape to linearize about)", src)
    return c


def _rule_mesh(c: AnalysisConfig, given: set[str], src: str | None) -> AnalysisConfig:
    m = c.model
    if m.element_length is not None and m.type != "shell":
        raise InputError("model.element_length", m.element_length, f"null with model.type {m.type} (the "
                         "element length sets the shell blade's mesh; beams take n_aero_sections)", src)
    if m.n_aero_sections is None and m.element_length is not None:
        return c  # the counts follow from the blade's size: checked when the mesh is built
    n0 = m.n_aero_sections or (SHELL_SPAN_ELEMENTS if m.type == "shell" else BEAM_SPAN_ELEMENTS)
    n_span = round(n0 * m.mesh_density)
    if not 4 <= n_span <= MAX_BLADE_ELEMENTS:
        bad = "mesh_density" if "model.mesh_density" in given or m.n_aero_sections is None else "n_aero_sections"
        raise InputError(f"model.{bad}", getattr(m, bad), f"n_aero_sections x mesh_density in [4, "
                         f"{MAX_BLADE_ELEMENTS}] blade elements (it gives {n_span})", src)
    return c


def _rule_operating(c: AnalysisConfig, given: set[str], src: str | None) -> AnalysisConfig:
    o = c.operating
    if o.rated_rpm is not None and o.overspeed_rpm is not None and o.overspeed_rpm < o.rated_rpm:
        raise InputError("operating.overspeed_rpm", o.overspeed_rpm,
                         f"an overspeed at least operating.rated_rpm = {o.rated_rpm:g} RPM", src)
    return c


#: air density (kg/m^3) of wind-turbine sites: sea level to 3000 m, -30 to +45 degC; outside it a
#: run is computed (the density is allowed up to MAX_AIR_DENSITY) with one warning
AIR_DENSITY_USUAL = (0.7, 1.5)


def _rule_air_density(c: AnalysisConfig, given: set[str], src: str | None) -> AnalysisConfig:
    lo, hi = AIR_DENSITY_USUAL
    if not lo <= c.air_density <= hi:
        where = f"{src}: " if src else ""
        warnings.warn(f"{where}air_density = {c.air_density:g} kg/m^3 is outside the {lo:g}-{hi:g} kg/m^3 of "
                      "wind-turbine sites (sea level to 3000 m, -30 to +45 degC); the aerodynamic forces scale "
                      "with it", InputWarning, stacklevel=4)
    return c


RULES = (_rule_rotor_range, _rule_damping, _rule_solver, _rule_mesh, _rule_operating, _rule_air_density)


def config_from_dict(data: dict | None, source: str | None = None,
                     base: AnalysisConfig | None = None) -> AnalysisConfig:
    """Validate a (possibly partial) nested dict and merge it over ``base`` (defaults).

    Raises
    ------
    InputError
        naming the first bad field.
    """
    given: set[str] = set()
    cfg = _merge(AnalysisConfig, {} if data is None else data, base or AnalysisConfig(), "", source, given)
    for rule in RULES:
        cfg = rule(cfg, given, source)
    _VALIDATED[cfg] = None
    while len(_VALIDATED) > 64:
        del _VALIDATED[next(iter(_VALIDATED))]
    return cfg


#: the configs :func:`config_from_dict` returned (validated; a config is immutable and hashable, and
#: an equal config is equally valid), so that :func:`check_config` does not check them again
_VALIDATED: dict[AnalysisConfig, None] = {}


def check_config(config: AnalysisConfig, source: str = "config") -> AnalysisConfig:
    """``config`` validated as if it had been read from a file: for configs built in Python
    (``AnalysisConfig(...)``, ``dataclasses.replace``), which the dataclasses do not check.
    Returns the equal, validated config."""
    if not isinstance(config, AnalysisConfig):
        raise InputError("config", type(config).__name__, "an AnalysisConfig", source)
    try:
        if config in _VALIDATED:
            return config
    except TypeError:  # a field set to a list or dict in Python: unhashable, checked below
        pass
    return config_from_dict(config.to_dict(), source)


def n_points_for_step(min_rpm: Any, max_rpm: Any, step: Any, name: str = "rotor_speed.step") -> int:
    """Grid points of ``min_rpm .. max_rpm`` in steps of ``step`` (the last step may be shorter),
    checked against :data:`MAX_GRID_POINTS` before any grid is built (``name`` names ``step``)."""
    lo = field_spec("rotor_speed.min_rpm").check(min_rpm, "rotor_speed.min_rpm")
    hi = field_spec("rotor_speed.max_rpm").check(max_rpm, "rotor_speed.max_rpm")
    st = Spec("float", lower=0.0, lower_open=True, upper=MAX_RPM, unit="RPM").check(step, name)
    n = max(hi - lo, 0.0) / st
    if not n < MAX_GRID_POINTS:
        raise InputError(name, step, f"a step giving at most {MAX_GRID_POINTS} rotor speeds (this one "
                         f"gives {n + 1:.3g})")
    return max(int(math.ceil(n - 1e-9)), 1) + 1


def default_config_text() -> str:
    """The bundled, commented default analysis (``data/analysis_default.yaml``)."""
    return resources.files("windflutter").joinpath("data/analysis_default.yaml").read_text(encoding="utf-8")


@functools.lru_cache(maxsize=1)
def bundled_config() -> AnalysisConfig:
    """The bundled YAML (``data/analysis_default.yaml``), read and validated: equal to
    :func:`default_config` (a test keeps the two from drifting apart)."""
    return config_from_dict(parse_yaml(default_config_text(), "config", "analysis_default.yaml"),
                            "analysis_default.yaml")


@functools.lru_cache(maxsize=1)
def default_config() -> AnalysisConfig:
    """The default analysis: the declared defaults, which the bundled, commented YAML lists
    (:func:`bundled_config`; the test suite checks that the two agree and that the defaults pass
    every field check and rule, so a run does not parse and check the file again; made once: the
    config is immutable)."""
    cfg = AnalysisConfig()
    _VALIDATED[cfg] = None
    return cfg


def load_config(path: str | Path | None = None, overrides: dict | None = None,
                overrides_source: str = "command line") -> AnalysisConfig:
    """Read an analysis YAML over the defaults; ``None`` gives the defaults.

    Parameters
    ----------
    path : YAML file, or ``None``.
    overrides : nested dict applied after the file (e.g. from the command line).
    overrides_source : how messages name where ``overrides`` came from.

    Raises
    ------
    InputError
        unreadable or non-UTF-8 file, bad YAML (duplicate key, too deep), unknown key or bad
        value (naming the field).
    """
    cfg = default_config()
    if path is not None:
        data = load_yaml(path, "config", what="analysis YAML file")
        cfg = config_from_dict(data, Path(path).name, base=cfg)
    if overrides:
        cfg = config_from_dict(copy.deepcopy(overrides), overrides_source, base=cfg)
    return cfg
