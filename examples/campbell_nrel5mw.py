"""The operating-point Campbell diagram of the bundled NREL 5 MW at three wind speeds.

Prints, per wind speed, the rotor speed, the pitch and the frequency and damping ratio of every
mode of the whole turbine (ground-fixed frame, multi-blade coordinates), then the least damped
mode in operation.  The same as ``windflutter campbell nrel5mw --wind-speeds 6 11.4 18``.

    python examples/campbell_nrel5mw.py                      # about 10 s on a laptop core
    python examples/campbell_nrel5mw.py --turbine iea15mw --wind-speeds 7 10.6 20
    python examples/campbell_nrel5mw.py --n-span 8           # a coarse blade: faster, less exact
"""

from __future__ import annotations

import argparse
import json

import windflutter


def parse(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--turbine", default="nrel5mw", help="turbine file or bundled name")
    p.add_argument("--wind-speeds", nargs="+", type=float, default=[6.0, 11.4, 18.0], metavar="V",
                   help="wind speeds (m/s)")
    p.add_argument("--n-span", type=int, default=None, help="blade elements along the span (default 30)")
    p.add_argument("--json", action="store_true", help="print the result as JSON (as windflutter campbell --json)")
    return p.parse_args(argv)


def main(argv=None) -> int:
    args = parse(argv)
    turbine = windflutter.load_turbine(args.turbine)
    options = {} if args.n_span is None else {"model": {"n_aero_sections": args.n_span}}
    result = windflutter.campbell(turbine, args.wind_speeds, **options)
    if args.json:
        print(json.dumps(result.as_dict()))
        return 0
    for point in result.points:
        print(f"V = {point.wind_speed:5.1f} m/s   {point.rotor_speed_rpm:5.2f} RPM   pitch {point.pitch_deg:5.2f} deg")
        for mode in point.modes:
            print(f"    {mode.name:26s} {mode.frequency_hz:7.3f} Hz   damping ratio {100 * mode.damping_ratio:6.2f} %")
    point, mode = result.least_damped()
    print(f"least damped mode: {mode.name} at {point.wind_speed:g} m/s, {mode.frequency_hz:.3f} Hz, "
          f"damping ratio {100 * mode.damping_ratio:.2f} %")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
