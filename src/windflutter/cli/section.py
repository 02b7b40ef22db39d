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

from windflutter.cli.wing import LIFT_SLOPE
from windflutter.config import field_spec
from windflutter.schema import Spec, is_number


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


def _positive(upper: float, unit: str) -> Spec:
    return Spec("float", lower=0.0, lower_open=True, upper=upper, unit=unit)


#: physical ranges of the section file's numbers (the section checks kinds and consistency)
BOUNDS = {
    "semi_chord": _positive(1e3, "m"), "elastic_axis": Spec("float", lower=-1.0, upper=1.0, unit="semi-chords"),
    "air_density": field_spec("air_density"), "lift_slope": LIFT_SLOPE,
    "mass": _positive(1e7, "kg/m"), "static_moment": Spec("float", lower=-1e7, upper=1e7, unit="kg m/m"),
    "inertia": _positive(1e8, "kg m^2/m"), "plunge_stiffness": _positive(1e13, "N/m^2"),
    "pitch_stiffness": _positive(1e13, "N"), "mass_ratio": _positive(1e6, "-"),
    "x_alpha": Spec("float", lower=-10.0, upper=10.0, unit="semi-chords"), "r_alpha_squared": _positive(100.0, "-"),
    "omega_h": _positive(1e4, "rad/s"), "omega_alpha": _positive(1e4, "rad/s"),
}


def load_yaml(path: str) -> Any:
    """Read a section YAML file; any problem becomes an :class:`InputError` naming the file and
    every number is checked in its physical range (:data:`BOUNDS`)."""
    from windflutter.files import load_yaml as load  # noqa: PLC0415

    data = load(path, "CONFIG", what="section YAML file")
    if isinstance(data, dict):
        for key, spec in BOUNDS.items():
            if key in data and is_number(data[key]):
                spec.check(data[key], key, str(path))
    return data


def _fmt(x: float | None, unit: str, digits: int = 6) -> str:
    return "none" if x is None else f"{x:.{digits}g} {unit}"


def run(args: argparse.Namespace) -> int:
    from windflutter.section import analyse, section_from_config

    cfg = load_yaml(args.config)
    sec = section_from_config(cfg, source=args.config)
    if args.plot is not None:
        from windflutter.files import check_output_file  # noqa: PLC0415

        check_output_file(args.plot, "--plot", (".png",))
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
