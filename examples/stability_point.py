"""The flutter and divergence onset of a turbine above one operating point, and its margins.

At the given wind speed the rotor speed is raised from the operating point (rotor speed and pitch
from the turbine's operating curve) until a mode loses its damping (flutter) or the blades' static
stiffness vanishes (divergence).  The same as ``windflutter stability nrel5mw --wind-speeds 11.4``.

    python examples/stability_point.py                            # NREL 5 MW at rated wind speed
    python examples/stability_point.py --wind-speed 20 --model shell
    python examples/stability_point.py --config examples/analysis_nrel5mw.yaml
    python examples/stability_point.py --rpm 2 30 4 --set model.n_aero_sections=8   # a coarse, quick look
"""

from __future__ import annotations

import argparse
import json
import math

import yaml

import windflutter
from windflutter.config import n_points_for_step


def parse(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--turbine", default="nrel5mw", help="turbine file or bundled name")
    p.add_argument("--wind-speed", type=float, default=11.4, metavar="V", help="wind speed (m/s)")
    p.add_argument("--config", default=None, help="an analysis YAML as the base (e.g. examples/analysis_nrel5mw.yaml)")
    p.add_argument("--model", default=None, help="beam (the default) or shell")
    p.add_argument("--rpm", nargs=3, type=float, default=None, metavar=("MIN", "MAX", "STEP"),
                   help="rotor-speed search grid (RPM; default 2 to 40 in steps of 2)")
    p.add_argument("--set", action="append", default=[], metavar="FIELD=VALUE",
                   help="any config field, e.g. --set model.n_aero_sections=12 (YAML value; repeatable)")
    p.add_argument("--json", action="store_true", help='print {"points": [...]} as windflutter stability --json')
    return p.parse_args(argv)


def options(args: argparse.Namespace) -> dict:
    """The analysis-config overrides of the command line (checked by windflutter like a config file)."""
    out: dict = {}
    if args.model is not None:
        out["model.type"] = args.model
    if args.rpm is not None:
        lo, hi, step = args.rpm
        out["rotor_speed"] = {"min_rpm": lo, "max_rpm": hi, "n_points": n_points_for_step(lo, hi, step, "--rpm STEP")}
    for item in args.set:  # dotted config fields; the values are YAML (numbers, lists, true/false)
        field, _, text = item.partition("=")
        out[field.strip()] = yaml.safe_load(text)
    return out


def main(argv=None) -> int:
    args = parse(argv)
    turbine = windflutter.load_turbine(args.turbine)
    config = windflutter.analysis_config(args.config, **options(args))  # validated like a config file
    (point,) = windflutter.stability(turbine, [args.wind_speed], config=config)
    if args.json:
        print(json.dumps({"points": [point.as_dict()]}))
        return 0
    rated = turbine.rated_rotor_speed * 30.0 / math.pi if turbine.rated_rotor_speed else None
    print(f"{turbine.name} at V = {point.wind_speed:g} m/s (pitch {point.pitch_deg:.2f} deg), "
          f"{config.model.type} model, {config.aero[0]} aerodynamics")
    if point.flutter_rpm is not None:
        margin = f", {point.flutter_rpm / rated:.2f} x rated {rated:.2f} RPM" if rated else ""
        print(f"  flutter:    {point.flutter_rpm:.2f} RPM, {point.flutter_frequency_hz:.3f} Hz, "
              f"{point.flutter_mode}{margin}")
    else:
        print("  flutter:    none in the searched range")
    print(f"  divergence: {'none in the searched range' if point.divergence_rpm is None else f'{point.divergence_rpm:.2f} RPM'}")
    print(f"  first instability: {point.first_instability or 'none'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
