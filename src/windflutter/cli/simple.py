"""`windflutter simple [--turbine nrel5mw|seed20mw|both] [--frozen-k] [--plot FILE.png] [--json]`.

The seed's "simple model" (thesis ch. 4.1.8): a 2-DOF section at 75 % radius with rotor inflow;
prints the first unstable rotor speed for wind speeds 4-25 m/s.  By default the reduced
frequency is matched to each mode (p-k); ``--frozen-k`` reproduces the thesis's assumption of a
fixed structural frequency (0.20 Hz / 0.11 Hz).  The plot shows both.
"""

from __future__ import annotations

import argparse
import json
import math



def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simple", help="the seed's simple model: first unstable rotor speed vs wind speed",
                       description=__doc__.split("\n\n", 1)[1] if __doc__ else None)
    p.add_argument("--turbine", choices=("nrel5mw", "seed20mw", "both"), default="both")
    p.add_argument("--frozen-k", action="store_true",
                   help="freeze k at the thesis's structural frequency instead of p-k")
    p.add_argument("--plot", metavar="FILE.png", help="write the onset curves (both methods) to a PNG")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from windflutter.frozen.simple_model import load_simple_models, run_simple_model

    if args.plot is not None:
        from windflutter.files import check_output_file  # noqa: PLC0415

        check_output_file(args.plot, "--plot", (".png",))
    models = load_simple_models()
    names = ["nrel5mw", "seed20mw"] if args.turbine == "both" else [args.turbine]
    main = [run_simple_model(models[n], frozen_k=args.frozen_k) for n in names]
    other = None
    if args.plot:
        from windflutter.post.vg_plots import plot_simple_model

        other = [run_simple_model(models[n], frozen_k=not args.frozen_k) for n in names]
        plot_simple_model(main, args.plot, extra=other)
    if args.json:
        print(json.dumps({"turbines": [r.to_dict() for r in main]}))
        return 0
    for r in main:
        rs = r.turbine
        method = (f"frozen k (f = {rs.frozen_frequency_hz} Hz)" if r.frozen_k
                  else "p-k (k matched to each mode)")
        print(f"{rs.label}: section at r = {rs.radius} m, chord {rs.chord} m, a = {rs.elastic_axis}; {method}")
        if rs.reported_rpm:
            print(f"  thesis fig. 4.7: {rs.reported_rpm[0]}-{rs.reported_rpm[1]} RPM")
        print("  V [m/s]  first unstable [RPM]  kind        flutter [RPM]  f_flutter [Hz]  k       divergence [RPM]")
        for p in r.points:
            def f(x: float, w: int = 8, d: int = 2) -> str:
                return f"{x:{w}.{d}f}" if math.isfinite(x) else f"{'-':>{w}}"
            print(f"  {p.wind_speed:6.1f}   {f(p.first_unstable_rpm, 12)}          {p.kind:<10}  "
                  f"{f(p.flutter_rpm, 12)}  {f(p.flutter_frequency / (2 * math.pi), 12, 3)}  "
                  f"{f(p.reduced_frequency, 6, 4)}  {f(p.divergence_rpm, 12)}")
    if args.plot:
        print(f"plot: {args.plot}")
    return 0
