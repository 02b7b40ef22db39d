"""`windflutter sensitivity TURBINE`: which blade property, at which station, buys damping -- the
derivative of each named mode's frequency and damping ratio with respect to the blade's section
properties per station and global parameters (:func:`windflutter.api.sensitivity`), printed as a
ranked table, optionally written as NetCDF and plotted; with ``--model shell``, with respect to the ply
thickness of each layup region (:func:`windflutter.api.shell_sensitivity`).
"""

from __future__ import annotations

import argparse

from windflutter.cli.options import PLOT_EXTENSIONS, SOLVER_FLAGS, Flag, add_flags, config_overrides, flag_error
from windflutter.errors import InputError

FLAGS = (
    Flag("--wind-speeds", "wind_speeds", nargs="+", metavar="V",
         help="wind speeds (m/s); default: the operating curve's within 3-25 m/s"),
    Flag("--aero", "aero", help="aerodynamic variant (default viscous: the airfoil polars)"),
    Flag("--model", "model.type", help="structural model: beam (default; section properties per element) or shell "
         "(the ply thickness of each layup region: spar caps, TE/LE reinforcement, webs, panels, skin)"),
    Flag("--max-hz", "campbell.max_hz", metavar="F", help="modes up to this frequency (Hz; default 1.25 x the "
         "first blade torsion frequency)"),
) + SOLVER_FLAGS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("sensitivity", help="design sensitivities: what to change to raise a mode's damping",
                       description="The derivative of the frequency and damping ratio of each named mode at each "
                                   "wind speed with respect to the blade's section properties per station (flap, "
                                   "edge, torsion and axial stiffness, mass, mass and elastic centre, structural "
                                   "damping) and global parameters (tower and drivetrain stiffness, nacelle "
                                   "mass, air density); first-order eigenvalue perturbation about the point's "
                                   "steady state (held fixed); with --model shell, the ply thickness of each "
                                   "layup region.")
    p.add_argument("turbine", help="turbine file (windIO, OpenFAST .fst, HAWC2 .htc) or bundled name")
    add_flags(p, FLAGS)
    p.add_argument("--modes", nargs="+", default=None, metavar="NAME",
                   help="modes to analyse by name, e.g. '1st edge BW' (quoted); default every mode")
    p.add_argument("--regions", nargs="+", default=None, metavar="NAME",
                   help="with --model shell: the layup regions by name (quoted, e.g. 'spar caps'); default all")
    p.add_argument("--total", action="store_true", help="also the derivatives with the steady state's own change "
                   "included (its sensitivity: whole blade, each r/R segment of the table, global parameters; "
                   "~15 s per wind speed)")
    p.add_argument("--onset", action="store_true", help="instead: the derivative of the first instability's onset "
                   "rotor speed at one wind speed (the operating curve's pitch held, the rotor speed raised; implicit "
                   "function theorem): of the mode of --modes (one) near --rpm, default the first flutter onset of "
                   "method p's rotor-speed search")
    p.add_argument("--rpm", type=float, default=None, metavar="R", help="with --onset: a rotor speed (RPM) near the "
                   "onset of the --modes mode")
    p.add_argument("--top", type=int, default=12, metavar="N", help="lines of the ranked table (default 12)")
    p.add_argument("--out", default=None, metavar="FILE", help="write the sensitivities as NetCDF (.nc)")
    p.add_argument("--plot", default=None, metavar="FILE", help="plot the spanwise sensitivity of the least "
                   "damped mode's damping (" + ", ".join(PLOT_EXTENSIONS) + ")")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from windflutter.api import sensitivity  # noqa: PLC0415
    from windflutter.config import load_config  # noqa: PLC0415
    from windflutter.files import check_output_file, prepare_output_file  # noqa: PLC0415
    from windflutter.sensitivity.results import segment_table, sentence, spanwise_figure, total_table  # noqa: PLC0415

    try:
        config = load_config(None, config_overrides(args, FLAGS))
    except InputError as exc:
        raise flag_error(exc, args, FLAGS, {}) from None
    if args.top < 1:
        raise InputError("--top", args.top, "a positive number of lines")
    for flag, exts in (("--out", (".nc",)), ("--plot", PLOT_EXTENSIONS)):
        path = getattr(args, flag.lstrip("-"))
        if path is not None:  # before the analysis
            check_output_file(path, flag, exts)
    winds = config.wind_speeds if args.wind_speeds is not None else None
    if config.model.type == "shell":
        return run_shell(args, config, winds)
    if args.regions is not None:
        raise InputError("--regions", " ".join(args.regions), "--model shell with it (the layup regions of a shell "
                         "blade)")
    if args.onset or args.rpm is not None:
        return run_onset(args, config, winds)
    ds = sensitivity(args.turbine, winds, modes=args.modes, total=args.total, config=config)
    if args.out:
        out = ds.copy()
        out["defined"] = out["defined"].astype("int8")  # NetCDF has no boolean
        out.to_netcdf(prepare_output_file(args.out))
    if args.plot:
        spanwise_figure(ds).savefig(prepare_output_file(args.plot), dpi=config.output.dpi)
    rows = segment_table(ds, modes=args.modes)
    print(f"{ds.attrs.get('title', '')}: {len(ds['mode'])} modes, {len(ds['wind_speed'])} wind speeds; "
          "steady state held fixed; largest damping changes first" +
          ("" if args.modes else " of the 3 least damped modes at each wind speed"))
    for r in rows[:args.top]:
        print("  " + sentence(r))
    lines = total_table(ds, modes=args.modes)
    if lines:
        print("with the steady state's own change (whole blade and r/R segments), largest first:")
        for line in lines[:args.top]:
            print("  " + line)
    return 0


def run_onset(args: argparse.Namespace, config, winds) -> int:
    """``--onset``: the onset rotor speed's derivatives (:func:`windflutter.api.onset_sensitivity`),
    ranked by the onset shift of each parameter's unit change; ``--out``: a NetCDF dataset."""
    from windflutter.api import onset_sensitivity  # noqa: PLC0415
    from windflutter.files import prepare_output_file  # noqa: PLC0415
    from windflutter.sensitivity.onset import onset_dataset, onset_lines  # noqa: PLC0415

    if not args.onset:
        raise InputError("--rpm", args.rpm, "--onset with it (a rotor speed near the onset)")
    if winds is None or len(winds) != 1:
        raise InputError("--wind-speeds", "none" if winds is None else " ".join(f"{v:g}" for v in winds),
                         "one wind speed with --onset")
    if args.modes is not None and len(args.modes) != 1:
        raise InputError("--modes", " ".join(args.modes), "one mode name with --onset")
    if args.rpm is not None and not args.rpm > 0:
        raise InputError("--rpm", args.rpm, "a positive rotor speed (RPM)")
    if args.plot:
        raise InputError("--plot", args.plot, "no plot with --onset (the table and --out)")
    if (args.modes is None) != (args.rpm is None):
        raise InputError("--rpm" if args.rpm is None else "--modes", "missing", "--modes NAME and --rpm R together "
                         "with --onset, or neither (method p's first flutter onset)")
    mode = args.modes[0] if args.modes else None
    res = onset_sensitivity(args.turbine, float(winds[0]), mode=mode, rpm=args.rpm, total=args.total, config=config)
    if args.out:
        onset_dataset(res).to_netcdf(prepare_output_file(args.out))
    for line in onset_lines(res)[:args.top + 1]:
        print(line)
    return 0


def run_shell(args: argparse.Namespace, config, winds) -> int:
    """``--model shell``: the layup regions' ply-thickness derivatives
    (:func:`windflutter.api.shell_sensitivity`), ranked; ``--out``: a NetCDF dataset."""
    from windflutter.api import shell_sensitivity  # noqa: PLC0415
    from windflutter.files import prepare_output_file  # noqa: PLC0415
    from windflutter.sensitivity.shell_results import shell_table  # noqa: PLC0415

    for flag, given in (("--onset", args.onset), ("--total", args.total), ("--rpm", args.rpm is not None),
                        ("--plot", args.plot is not None)):
        if given:
            raise InputError(flag, "given", "not with --model shell (the layup regions' table and --out; the "
                             "shell's steady state is held)")
    ds = shell_sensitivity(args.turbine, winds, modes=args.modes, regions=args.regions, config=config)
    if args.out:
        out = ds.copy()
        out["defined"] = out["defined"].astype("int8")  # NetCDF has no boolean
        out.to_netcdf(prepare_output_file(args.out))
    print(f"{ds.attrs.get('title', '')}: {len(ds['mode'])} modes, {len(ds['wind_speed'])} wind speeds, "
          f"{len(ds['region'])} layup regions; steady state and blade basis held; largest damping changes first" +
          ("" if args.modes else " of the 3 least damped modes at each wind speed"))
    for line in shell_table(ds, modes=args.modes)[:args.top]:
        print("  " + line)
    return 0
