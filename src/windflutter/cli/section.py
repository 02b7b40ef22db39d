"""`windflutter section CONFIG.yaml [--method k|pk|p] [--json] [--plot FILE.png]`.

Flutter and divergence of a 2-DOF typical section with Theodorsen aerodynamics.  The YAML
config (SI units) holds ``semi_chord``, ``elastic_axis``, optional ``air_density`` (1.225) and
``lift_slope`` (2 pi), and the structure either dimensional (``mass``, ``static_moment``,
``inertia``, ``plunge_stiffness``, ``pitch_stiffness``) or nondimensional (``mass_ratio``,
``x_alpha``, ``r_alpha_squared``, ``omega_h``, ``omega_alpha``).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

import yaml

from windflutter.errors import InputError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "section",
        help="typical-section (plunge/pitch) flutter and divergence, Theodorsen aerodynamics",
        description=__doc__.split("\n\n", 1)[1] if __doc__ else None,
    )
    p.add_argument("config", metavar="CONFIG.yaml", help="section parameters (YAML, SI units)")
    p.add_argument("--method", choices=("k", "pk", "p"), default="pk",
                   help="k (V-g), pk (p-k, default) or p (state space with Roger RFA)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--plot", metavar="FILE.png", help="write V-g / V-f curves to this PNG")
    p.set_defaults(func=run)


def load_yaml(path: str) -> Any:
    """Read a YAML file; any problem becomes an :class:`InputError` naming the file."""
    p = Path(path)
    if not p.is_file():
        raise InputError("CONFIG", path, "an existing YAML file")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError("CONFIG", path, f"a readable UTF-8 YAML file ({exc})") from None
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as exc:
        where = ""
        mark = getattr(exc, "problem_mark", None)
        if mark is not None:
            where = f" at line {mark.line + 1}, column {mark.column + 1}"
        problem = getattr(exc, "problem", None) or type(exc).__name__
        raise InputError("CONFIG", path, f"valid YAML ({problem}{where})") from None


def _fmt(x: float | None, unit: str, digits: int = 6) -> str:
    return "none" if x is None else f"{x:.{digits}g} {unit}"


def run(args: argparse.Namespace) -> int:
    from windflutter.stability.section import analyse, section_from_config

    cfg = load_yaml(args.config)
    sec = section_from_config(cfg, source=args.config)
    if args.plot and not str(args.plot).lower().endswith(".png"):
        raise InputError("--plot", args.plot, "a file name ending in .png")
    res = analyse(sec, args.method)
    if args.plot:
        from windflutter.post.vg_plots import plot_vg

        plot_vg(res, args.plot, title=f"{Path(args.config).name}: {args.method} method")
    if args.json:
        print(json.dumps(res.to_dict()))
    else:
        print(f"typical section {args.config} ({args.method} method)")
        print(f"  mu = {sec.mass_ratio:.6g}, x_alpha = {sec.x_alpha:.6g}, "
              f"r_alpha^2 = {sec.r_alpha_squared:.6g}, a = {sec.elastic_axis:.6g}, "
              f"omega_h = {sec.omega_h:.6g} rad/s, omega_alpha = {sec.omega_alpha:.6g} rad/s")
        print(f"  flutter speed       : {_fmt(res.flutter_speed, 'm/s')}"
              + ("" if res.flutter_speed is not None
                 else f" (none up to {res.max_speed:.4g} m/s)"))
        if res.flutter_frequency is not None:
            print(f"  flutter frequency   : {res.flutter_frequency:.6g} rad/s "
                  f"({res.flutter_frequency / (2 * math.pi):.6g} Hz)")
            print(f"  reduced frequency   : {res.reduced_frequency:.6g}")
        print(f"  divergence speed    : {_fmt(res.divergence_speed, 'm/s')}")
        if args.plot:
            print(f"  plot                : {args.plot}")
    return 0
