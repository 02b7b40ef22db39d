"""`windflutter campbell TURBINE`: the operating-point Campbell diagram -- frequency and damping of
every mode of the whole turbine (ground-fixed frame, multi-blade coordinates) along its operating
curve, with mode names in the field's terms.

The flags are analysis-config fields (:mod:`windflutter.cli.options`), checked as a config is;
the command parses, calls :func:`windflutter.api.campbell` (the operating-point service,
:mod:`windflutter.operating`) and prints or exports.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from windflutter.cli.options import PLOT_EXTENSIONS, SOLVER_FLAGS, Flag, add_flags, config_overrides, flag_error
from windflutter.errors import InputError

FLAGS = (
    Flag("--wind-speeds", "wind_speeds", nargs="+", metavar="V",
         help="wind speeds (m/s); default: the operating curve's within 3-25 m/s"),
    Flag("--aero", "aero", help="aerodynamic variant (default viscous: the airfoil polars)"),
    Flag("--model", "model.type", help="structural model (beam or shell)"),
    Flag("--max-hz", "campbell.max_hz", metavar="F", help="modes up to this frequency (Hz; default 1.25 x the "
         "first blade torsion frequency)"),
) + SOLVER_FLAGS


_FORMATS_HELP = ("csv (.csv), cmb (.cmb), amp (.amp), figure (.png, .pdf, .svg), netcdf (.nc) and the formats "
                 "plug-ins register in the entry-point group windflutter.exporters")
#: the old export flags: aliases of --export with a fixed format
ALIASES = (("--csv", "csv"), ("--cmb", "cmb"), ("--amp", "amp"), ("--plot", "figure"))


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("campbell", help="frequency and damping of every mode along the operating curve",
                       description="The operating-point Campbell diagram of a turbine: at each wind speed of "
                                   "its operating curve (rotor speed and pitch from the curve) the frequency "
                                   "and aeroelastic damping of every mode of the whole turbine in the "
                                   "ground-fixed frame, named (1st edge BW, 1st tower fore-aft, ...).")
    p.add_argument("turbine", help="turbine file (windIO, OpenFAST .fst, HAWC2 .htc) or bundled name")
    add_flags(p, FLAGS)
    p.add_argument("--workers", metavar="N", default=None,
                   help="operating points evaluated in N local processes (default: the usable cores for "
                        "--model shell, whose points take seconds; 1 for a beam model; 1 = serial)")
    p.add_argument("--json", action="store_true", help="print the result as one JSON object")
    p.add_argument("--export", action="append", default=None, metavar="FILE",
                   help="write the result to FILE in the format of its suffix (repeatable): " + _FORMATS_HELP)
    p.add_argument("--format", default=None, metavar="NAME",
                   help="the format of every --export (default: from the suffix; needed for .txt and for "
                        "plug-in formats without a suffix)")
    p.add_argument("--csv", default=None, metavar="FILE", help="= --export FILE --format csv: one row per wind "
                   "speed and mode")
    p.add_argument("--cmb", default=None, metavar="FILE", help="= --export FILE --format cmb: a HAWCStab2-style "
                   ".cmb text file")
    p.add_argument("--amp", default=None, metavar="FILE", help="= --export FILE --format amp: a HAWCStab2-style "
                   ".amp text file (each mode's tower-top and blade-tip amplitudes, the .cmb's modes in its order)")
    p.add_argument("--plot", default=None, metavar="FILE",
                   help="= --export FILE --format figure: the Campbell figure (" + ", ".join(PLOT_EXTENSIONS) + ")")
    p.set_defaults(func=run)


def _config(args: argparse.Namespace):
    from windflutter.config import load_config  # noqa: PLC0415
    from windflutter.methods import operational_options  # noqa: PLC0415

    try:
        config = load_config(None, config_overrides(args, FLAGS))
        return config, operational_options(config, config.aero[0])
    except InputError as exc:
        raise flag_error(exc, args, FLAGS, {}) from None


def _exports(args: argparse.Namespace) -> list[tuple[object, str, str]]:
    """``(exporter, path, flag)`` of every requested file, each checked before the analysis."""
    from windflutter.exporters import check_export_format, exporter_for  # noqa: PLC0415
    from windflutter.files import check_output_file  # noqa: PLC0415

    plan = []
    if args.format is not None:
        check_export_format(args.format, "--format")
    for flag, fmt in ALIASES:
        path = getattr(args, flag.lstrip("-"))
        if path is not None:
            plan.append((exporter_for(path, fmt, flag), path, flag))
    for path in args.export or ():
        plan.append((exporter_for(path, args.format, "--export"), path, "--export"))
    for exporter, path, flag in plan:
        check_output_file(path, flag, exporter.suffixes or (Path(path).suffix.lower(),))
    return plan


def run(args: argparse.Namespace) -> int:
    from windflutter.api import campbell  # noqa: PLC0415
    from windflutter.files import prepare_output_file  # noqa: PLC0415

    from windflutter.cli.run import parse_workers  # noqa: PLC0415

    config, _ = _config(args)
    workers = parse_workers(args.workers)
    plan = _exports(args)
    winds = config.wind_speeds if args.wind_speeds is not None else None
    res = campbell(args.turbine, winds, config=config, workers=workers)
    for exporter, path, flag in plan:
        exporter.write(res, prepare_output_file(path), field=flag, dpi=config.output.dpi)
    if args.json:
        print(json.dumps(res.as_dict()))
        return 0
    _print_table(res)
    return 0


def _print_table(res) -> None:
    print(f"{res.turbine}: {res.part}, {res.frame} frame; {res.assumptions.get('aerodynamics', '')}")
    for p in res.points:
        print(f"V = {p.wind_speed:5.2f} m/s  {p.rotor_speed_rpm:6.2f} RPM  pitch {p.pitch_deg:6.2f} deg")
        for m in p.modes:
            print(f"   {m.name:26s} {m.frequency_hz:7.4f} Hz   zeta {100 * m.damping_ratio:7.2f} %")
    worst = res.least_damped()
    if worst is not None:
        p, m = worst
        print(f"least damped mode in operation: {m.name}, zeta {100 * m.damping_ratio:.2f} % at {p.wind_speed:g} m/s")
    bad = res.unstable()
    if bad:
        print(f"UNSTABLE: {bad[0][1].name} at {bad[0][0].wind_speed:g} m/s (zeta {100 * bad[0][1].damping_ratio:.2f} %)")
        return
    local = sorted({p.wind_speed for p, _ in res.structure_unstable()})
    # the blade structure unstable on its own: what and why is the ValidityWarning's line
    # (system.campbell.warn_indefinite_blade, which fires at those points), not repeated here
    print("every mode damped in operation" if not local else
          "every oscillating mode damped in operation, but the blade's FE structure alone is statically unstable "
          f"at {', '.join(f'{v:g}' for v in local)} m/s (a local buckling without aerodynamics, see the warning)")
