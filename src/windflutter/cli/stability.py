"""`windflutter stability TURBINE`: flutter and divergence onset rotor speed per wind speed.

The flags are analysis-config fields (:mod:`windflutter.cli.options`): they are applied as
overrides to the default analysis config and validated by the same code as ``windflutter run
-c ANALYSIS.yaml`` (``--wind-speeds 0``, ``--rpm 2 inf 2`` or ``--n-tracked`` above
``--basis-modes`` are refused alike); the solver options then come from the config exactly as
for a run's points (:func:`windflutter.workflow.turbine_options`).
"""

from __future__ import annotations

import argparse
import json

from windflutter.cli.options import (PLOT_EXTENSIONS, RPM_PATHS, SOLVER_FLAGS, TIP_MACH_FLAG, Flag, add_flags,
                                     config_overrides, flag_error, rpm_flag)
from windflutter.errors import InputError

FLAGS = (
    Flag("--wind-speeds", "wind_speeds", nargs="+", metavar="V", default=[10.0], help="wind speeds (m/s)"),
    Flag("--aero", "aero", help="aerodynamic variant (default viscous: the airfoil polars)"),
    Flag("--method", "method", help="search method (default p: whole turbine in multi-blade coordinates with "
         "aerodynamic states; pk, thesis: the seed's model)"),
    Flag("--model", "model.type", help="structural model (shell or beam)"),
    rpm_flag(default=[2.0, 40.0, 2.0]),
    TIP_MACH_FLAG,
) + SOLVER_FLAGS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("stability", help="flutter/divergence onset (RPM) of a turbine per wind speed",
                       description="Flutter and divergence onset of a turbine at each wind speed.  The "
                                   "flags set analysis-config fields (docs/config_reference.md) and are "
                                   "checked as a config is.")
    p.add_argument("turbine", help="windIO turbine file or bundled name (e.g. nrel5mw)")
    add_flags(p, FLAGS)
    p.add_argument("--plot", default=None, metavar="FILE",
                   help="write the Campbell diagram of the first wind speed here (" + ", ".join(PLOT_EXTENSIONS) + ")")
    p.add_argument("--json", action="store_true", help="print a JSON object")
    p.set_defaults(func=run)


def options_from_args(args: argparse.Namespace):
    """``(AnalysisConfig, options)`` of the command line (errors name the flag): the options of the
    solver :func:`windflutter.methods.stability_analysis` builds for the case."""
    from windflutter.config import load_config  # noqa: PLC0415
    from windflutter.methods import case_options  # noqa: PLC0415

    try:
        config = load_config(None, config_overrides(args, FLAGS))
        aero, method = config.aero[0], config.method[0]
        return config, case_options(config, aero, method)
    except InputError as exc:
        raise flag_error(exc, args, FLAGS, RPM_PATHS) from None


def run(args: argparse.Namespace) -> int:
    from windflutter.cli.warn import curve_rpm, operating_rotor_speed
    from windflutter.files import check_output_file, prepare_output_file
    from windflutter.model.windio import load_turbine
    from windflutter.methods import stability_analysis

    config, opts = options_from_args(args)
    if args.plot is not None:  # before the analysis
        check_output_file(args.plot, "--plot", PLOT_EXTENSIONS)
    turbine = load_turbine(args.turbine)
    operating_rotor_speed(curve_rpm(turbine))  # range warnings say: inside the operating range or overspeed
    ts = stability_analysis(turbine, config, config.aero[0], config.method[0])
    points = [ts.analyse_operating_point(v) for v in config.wind_speeds]
    if args.plot:  # the run's rotor-speed Campbell figure (post.plots.campbell) of the first wind speed
        from windflutter.post.plots import campbell
        from windflutter.post.store import point_dataset
        from windflutter.results import OperatingPoint, point_result

        p0, r = points[0], config.rotor_speed
        op = OperatingPoint(0, p0.wind_speed, config.aero[0], config.method[0], r.min_rpm, r.max_rpm, r.tolerance_rpm,
                            tuple(float(x) for x in p0.sweep_rpm))
        campbell(point_dataset(op, point_result(p0)), 0).savefig(prepare_output_file(args.plot), dpi=config.output.dpi)
    if args.json:
        print(json.dumps({"points": [p.as_dict() for p in points]}))
        return 0
    s = config.solver
    physics = {(True, True): "full", (False, False): "thesis"}.get(
        (bool(s.geometric_stiffness), bool(s.rigid_sections)),
        f"geometric stiffness {'on' if s.geometric_stiffness else 'off'}, rigid sections "
        f"{'on' if s.rigid_sections else 'off'}")
    print(f"{turbine.name}: {config.model.type} model, {config.aero[0]} aero, {config.method[0]} search, "
          f"{physics} physics")
    # "-": none up to where the sweep ended ("searched to": max_rpm, the tip-Mach bound, or a stop)
    print(f"{'V (m/s)':>8} {'pitch':>6} {'flutter RPM':>12} {'f (Hz)':>7} {'divergence RPM':>15} "
          f"{'searched to':>12}  mode")
    for p in points:
        fr = "-" if p.flutter_rpm is None else f"{p.flutter_rpm:.2f}"
        ff = "-" if p.flutter_frequency_hz is None else f"{p.flutter_frequency_hz:.3f}"
        dv = "-" if p.divergence_rpm is None else f"{p.divergence_rpm:.2f}"
        end = f"{max(p.sweep_rpm):.2f}" if len(p.sweep_rpm) else "-"
        print(f"{p.wind_speed:8.2f} {p.pitch_deg:6.2f} {fr:>12} {ff:>7} {dv:>15} {end:>12}  {p.flutter_mode or ''}")
    return 0
