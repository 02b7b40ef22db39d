"""`windflutter wing CONFIG.yaml [--json]`: flutter and divergence of a uniform cantilever wing."""

from __future__ import annotations

import argparse
import json

from windflutter.config import MAX_BLADE_ELEMENTS, MAX_GRID_POINTS, MAX_MODES, field_spec
from windflutter.errors import InputError
from windflutter.schema import Spec


def _positive(upper: float, unit: str) -> Spec:
    return Spec("float", lower=0.0, lower_open=True, upper=upper, unit=unit)


#: lift slope (1/rad) of a wing or section file: thin-airfoil theory gives 2 pi, real airfoils 5-7,
#: a low-aspect-ratio wing less; below 0.1 (1/60 of 2 pi) the aerodynamic forces vanish and no onset
#: can be found (a slope of 1e-300 gave all-null results without a word), above 20 it is no airfoil
LIFT_SLOPE = Spec("float", lower=0.1, upper=20.0, unit="1/rad")

#: physical ranges and sizes of the wing file's fields (WingConfig checks kinds and consistency)
BOUNDS = {
    "span": _positive(1e4, "m"), "chord": _positive(1e3, "m"),
    "bending_stiffness": _positive(1e13, "N m^2"), "torsion_stiffness": _positive(1e13, "N m^2"),
    "mass": _positive(1e6, "kg/m"), "inertia": _positive(1e7, "kg m^2/m"),
    "air_density": field_spec("air_density"), "lift_slope": LIFT_SLOPE,
    "n_elements": Spec("int", lower=1, upper=MAX_BLADE_ELEMENTS), "n_modes": Spec("int", lower=2, upper=MAX_MODES),
    "speed_min": _positive(1e4, "m/s"), "speed_max": _positive(1e4, "m/s"), "speed_step": _positive(1e4, "m/s"),
}


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("wing", help="flutter/divergence of a straight cantilever wing (beam + strip theory)")
    p.add_argument("config", help="YAML file: span, chord, elastic_axis, mass_axis, bending_stiffness, "
                                   "torsion_stiffness, mass, inertia, air_density[, lift_slope, n_elements, "
                                   "basis_modes (or n_modes)]")
    p.add_argument("--method", choices=("pk", "thesis"), default="pk", help="search method (default pk)")
    p.add_argument("--json", action="store_true", help="print a JSON object")
    p.set_defaults(func=run)


def _vocabulary(data, source: str):
    """The wing file's ``basis_modes`` (the name of the analysis config, preferred) or its older
    ``n_modes`` for :class:`~windflutter.frozen.wing.WingConfig`'s ``n_modes``."""
    if isinstance(data, dict) and "basis_modes" in data:
        if "n_modes" in data:
            raise InputError("n_modes", data["n_modes"], "basis_modes or n_modes (the same setting), not both",
                             source)
        data = {("n_modes" if k == "basis_modes" else k): v for k, v in data.items()}
    return data


def check_bounds(cfg, source: str, names: dict[str, str] | None = None) -> None:
    """Every field of a :class:`~windflutter.frozen.wing.WingConfig` in its physical range and
    the speed grid at most :data:`~windflutter.config.MAX_GRID_POINTS` long, before any work
    (``names``: the file's name of a field where it differs)."""
    for name, spec in BOUNDS.items():
        spec.check(getattr(cfg, name), (names or {}).get(name, name), source)
    n = (cfg.speed_max - cfg.speed_min) / cfg.speed_step
    if not n < MAX_GRID_POINTS:
        raise InputError("speed_step", cfg.speed_step, f"a step giving at most {MAX_GRID_POINTS} speeds "
                         f"(this one gives {n + 1:.3g})", source)


def run(args: argparse.Namespace) -> int:
    from windflutter.files import load_yaml
    from windflutter.frozen.wing import WingConfig, analyse_wing

    data = load_yaml(args.config, "config", what="wing YAML file")
    names = {"n_modes": "basis_modes"} if isinstance(data, dict) and "basis_modes" in data else {}
    try:
        cfg = WingConfig.from_dict(_vocabulary(data if data is not None else {}, str(args.config)),
                                   source=str(args.config))
    except InputError as exc:
        if exc.field in names:
            raise InputError(names[exc.field], exc.value, exc.expected, exc.source) from None
        raise
    check_bounds(cfg, str(args.config), names)
    res = analyse_wing(cfg, method=args.method)
    out = {k: (None if v is None else float(v)) for k, v in res.as_dict().items()}
    if args.json:
        print(json.dumps(out))
    else:
        fs = "none in range" if out["flutter_speed"] is None else f"{out['flutter_speed']:.2f} m/s"
        ff = "" if out["flutter_frequency"] is None else f" at {out['flutter_frequency']:.2f} rad/s"
        ds = "none in range" if out["divergence_speed"] is None else f"{out['divergence_speed']:.2f} m/s"
        print(f"flutter speed: {fs}{ff}\ndivergence speed: {ds}")
    return 0
