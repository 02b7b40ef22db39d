"""The ``windflutter section`` YAML mapping -> :class:`TypicalSection`, every field checked."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from windflutter.errors import InputError
from windflutter.section.model import TWO_PI, TypicalSection, is_number

_COMMON_KEYS = {"semi_chord", "elastic_axis", "air_density", "lift_slope"}
_DIM_KEYS = ("mass", "static_moment", "inertia", "plunge_stiffness", "pitch_stiffness")
_NONDIM_KEYS = ("mass_ratio", "x_alpha", "r_alpha_squared", "omega_h", "omega_alpha")
_UNITS = {
    "semi_chord": "m",
    "elastic_axis": "semi-chords aft of mid-chord",
    "air_density": "kg/m^3",
    "lift_slope": "1/rad",
    "mass": "kg/m",
    "static_moment": "kg m/m",
    "inertia": "kg m^2/m",
    "plunge_stiffness": "N/m^2",
    "pitch_stiffness": "N",
    "mass_ratio": "-",
    "x_alpha": "semi-chords",
    "r_alpha_squared": "-",
    "omega_h": "rad/s",
    "omega_alpha": "rad/s",
}


def section_from_config(config: Any, source: str | None = None) -> TypicalSection:
    """Validate a config mapping (the ``windflutter section`` YAML) and build the section.

    Raises
    ------
    InputError
        Naming the field for: not a mapping, unknown key, missing key, non-numeric / NaN /
        infinite value, non-positive mass, stiffness, ..., r_alpha^2 <= x_alpha^2, and a mix of
        the dimensional and nondimensional forms.
    """
    nondim = _check_keys(config, source)
    common = {
        "semi_chord": float(config["semi_chord"]),
        "elastic_axis": float(config["elastic_axis"]),
        "air_density": float(config.get("air_density", 1.225)),
        "lift_slope": float(config.get("lift_slope", TWO_PI)),
    }
    try:
        return _nondimensional(config, common) if nondim else _dimensional(config, common)
    except InputError as exc:
        if source and exc.source is None:
            raise InputError(exc.field, exc.value, exc.expected, source) from None
        raise


def _check_keys(config: Any, source: str | None) -> bool:
    """Keys known, values finite numbers, one form only, b and a given; True: nondimensional."""
    if not isinstance(config, Mapping):
        raise InputError("<config>", config, "a mapping of section parameters", source)
    allowed = _COMMON_KEYS | set(_DIM_KEYS) | set(_NONDIM_KEYS)
    for key in config:
        if key not in allowed:
            raise InputError(str(key), config[key], "a known key: " + ", ".join(sorted(allowed)),
                             source)
    for key, val in config.items():
        if not is_number(val) or not math.isfinite(float(val)):
            raise InputError(key, val, f"a finite number ({_UNITS[key]})", source)
    dim = [k for k in _DIM_KEYS if k in config]
    nondim = [k for k in _NONDIM_KEYS if k in config]
    if dim and nondim:
        raise InputError(
            nondim[0], config[nondim[0]],
            f"either the dimensional keys ({', '.join(_DIM_KEYS)}) or the nondimensional keys "
            f"({', '.join(_NONDIM_KEYS)}), not both (found {dim[0]!r} too)", source)
    for key in ("semi_chord", "elastic_axis"):
        if key not in config:
            raise InputError(key, None, f"a number ({_UNITS[key]}); the key is missing", source)
    return bool(nondim)


def _nondimensional(config: Mapping, common: dict[str, float]) -> TypicalSection:
    for key in _NONDIM_KEYS:
        if key not in config:
            raise InputError(key, None, f"a number ({_UNITS[key]}); the key is missing")
    if float(config["mass_ratio"]) <= 0:
        raise InputError("mass_ratio", config["mass_ratio"], "a positive number (-)")
    return TypicalSection.from_nondimensional(
        mass_ratio=float(config["mass_ratio"]),
        x_alpha=float(config["x_alpha"]),
        r_alpha_squared=float(config["r_alpha_squared"]),
        omega_h=float(config["omega_h"]),
        omega_alpha=float(config["omega_alpha"]),
        **common,
    )


def _dimensional(config: Mapping, common: dict[str, float]) -> TypicalSection:
    for key in _DIM_KEYS:
        if key not in config and key != "static_moment":
            raise InputError(
                key, None,
                f"a positive number ({_UNITS[key]}); the key is missing "
                "(give mass, inertia, plunge_stiffness, pitch_stiffness [, static_moment] "
                "or mass_ratio, x_alpha, r_alpha_squared, omega_h, omega_alpha)")
    if float(config["mass"]) <= 0:
        raise InputError("mass", config["mass"], "a positive number (kg/m)")
    return TypicalSection(
        mass=float(config["mass"]),
        static_moment=float(config.get("static_moment", 0.0)),
        inertia=float(config["inertia"]),
        plunge_stiffness=float(config["plunge_stiffness"]),
        pitch_stiffness=float(config["pitch_stiffness"]),
        **common,
    )
