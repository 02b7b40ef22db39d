"""`windflutter stability TURBINE.yaml`: flutter and divergence onset rotor speed per wind speed."""

from __future__ import annotations

import argparse
import json
import math

from windflutter.config import AERO_DISTRIBUTIONS, AERO_VARIANTS, REDUCTIONS, SEARCH_METHODS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("stability", help="flutter/divergence onset (RPM) of a turbine per wind speed")
    p.add_argument("turbine", help="windIO turbine file or bundled name (e.g. nrel5mw)")
    p.add_argument("--wind-speeds", type=float, nargs="+", default=[10.0], metavar="V",
                   help="wind speeds (m/s), default 10")
    p.add_argument("--aero", choices=AERO_VARIANTS, default="potential")
    p.add_argument("--method", choices=SEARCH_METHODS, default="pk")
    p.add_argument("--model", choices=("shell", "beam"), default="beam")
    p.add_argument("--physics", choices=("full", "thesis"), default="full",
                   help="full: with centrifugal prestress K_sigma; thesis: without (as the seed)")
    p.add_argument("--rpm", type=float, nargs=3, default=[2.0, 40.0, 2.0], metavar=("MIN", "MAX", "STEP"),
                   help="rotor-speed grid (RPM), default 2 40 2")
    p.add_argument("--air-density", type=float, default=1.225)
    p.add_argument("--n-span", type=int, default=None, help="blade elements / strips along the span")
    p.add_argument("--part", choices=("turbine", "rotor"), default="turbine",
                   help="whole turbine, or the rotor alone with the hub clamped")
    p.add_argument("--reduction", choices=REDUCTIONS, default="mta",
                   help="modal basis with aero static-correction vectors (mta, default), structural "
                        "modes only (modal), or full order (none)")
    p.add_argument("--basis-modes", type=int, default=30, metavar="N",
                   help="structural modes per reference rotor speed in the basis (default 30)")
    p.add_argument("--n-tracked", type=int, default=None, metavar="N",
                   help="modes tracked by the p-k search (default: every mode up to 1.25 x first torsion)")
    p.add_argument("--aero-distribution", choices=AERO_DISTRIBUTIONS, default="spline",
                   help="shell models: rigid-section spline (default) or the seed's skin quads")
    p.add_argument("--steady-loads", action="store_true",
                   help="quasi-steady damping of the mean lift/drag/moment (edgewise aero damping; default: off, as the thesis)")
    p.add_argument("--induction", action="store_true",
                   help="steady BEM axial/tangential induction in the inflow (default: none, as the thesis)")
    p.add_argument("--plot", default=None, help="write the Campbell diagram of the first wind speed here")
    p.add_argument("--json", action="store_true", help="print a JSON object")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from windflutter.errors import InputError
    from windflutter.model.windio import load_turbine
    from windflutter.stability.turbine import TurbineOptions, TurbineStability

    for v in args.wind_speeds:
        if not (math.isfinite(v) and v >= 0):
            raise InputError("--wind-speeds", v, "non-negative wind speeds (m/s)")
    mesh = {"part": args.part}
    if args.n_span is not None:
        mesh["n_span"] = args.n_span
    opts = TurbineOptions(model=args.model, aero=args.aero, method=args.method, physics=args.physics,
                          air_density=args.air_density, rpm_min=args.rpm[0], rpm_max=args.rpm[1],
                          rpm_step=args.rpm[2], reduction=args.reduction, n_modes=args.basis_modes,
                          n_tracked=args.n_tracked, aero_distribution=args.aero_distribution,
                          induction=args.induction, steady_loads=args.steady_loads, mesh=mesh)
    turbine = load_turbine(args.turbine)
    ts = TurbineStability(turbine, opts)
    points = [ts.analyse_operating_point(v) for v in args.wind_speeds]
    if args.plot:
        from windflutter.post.stability_plots import campbell

        campbell(points[0]).savefig(args.plot, dpi=110)
    if args.json:
        print(json.dumps({"points": [p.as_dict() for p in points]}))
        return 0
    print(f"{turbine.name}: {args.model} model, {args.aero} aero, {args.method} search, {args.physics} physics")
    print(f"{'V (m/s)':>8} {'pitch':>6} {'flutter RPM':>12} {'f (Hz)':>7} {'divergence RPM':>15}  mode")
    for p in points:
        fr = "-" if p.flutter_rpm is None else f"{p.flutter_rpm:.2f}"
        ff = "-" if p.flutter_frequency_hz is None else f"{p.flutter_frequency_hz:.3f}"
        dv = "-" if p.divergence_rpm is None else f"{p.divergence_rpm:.2f}"
        print(f"{p.wind_speed:8.2f} {p.pitch_deg:6.2f} {fr:>12} {ff:>7} {dv:>15}  {p.flutter_mode or ''}")
    return 0
