"""`windflutter wing CONFIG.yaml [--json]`: flutter and divergence of a uniform cantilever wing."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import yaml

from windflutter.errors import InputError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("wing", help="flutter/divergence of a straight cantilever wing (beam + strip theory)")
    p.add_argument("config", help="YAML file: span, chord, elastic_axis, mass_axis, bending_stiffness, "
                                   "torsion_stiffness, mass, inertia, air_density[, lift_slope, n_elements]")
    p.add_argument("--method", choices=("pk", "thesis"), default="pk", help="search method (default pk)")
    p.add_argument("--json", action="store_true", help="print a JSON object")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from windflutter.stability.wing import WingConfig, analyse_wing

    path = Path(args.config)
    if not path.is_file():
        raise InputError("config", str(path), "an existing YAML file")
    try:
        data = yaml.safe_load(path.read_text())
    except yaml.YAMLError as exc:
        raise InputError("config", str(path), f"valid YAML ({str(exc).splitlines()[0]})") from None
    cfg = WingConfig.from_dict(data if data is not None else {}, source=str(path))
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
