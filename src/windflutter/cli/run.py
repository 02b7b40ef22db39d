"""``windflutter run TURBINE [-c ANALYSIS.yaml] [-o OUTDIR] [--resume] [--quiet] [--workers N]
[--scheduler ADDRESS]``.

Runs the whole analysis of a turbine (every wind speed, aerodynamic variant and search method of
the analysis config), stores results point by point in ``OUTDIR/results.nc``, draws the figures
and writes ``OUTDIR/report.html``; the last lines printed say where they are.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from windflutter.cli.options import (RUN_FLAGS, SOLVER_FLAGS, TIP_MACH_FLAG, Flag, add_flags, config_overrides,
                                     flag_error, rpm_flag)
from windflutter.config import load_config
from windflutter.errors import InputError

#: flags that override the config file (validated as part of the config)
FLAGS = (
    Flag("--wind-speeds", "wind_speeds", nargs="+", metavar="V", help="override the config's wind speeds (m/s)"),
    Flag("--aero", "aero", nargs="+", help="override the aerodynamic variants"),
    Flag("--method", "method", nargs="+", help="override the search methods"),
    Flag("--model", "model.type", help="override the model type"),
    rpm_flag(),
    TIP_MACH_FLAG,
) + SOLVER_FLAGS + RUN_FLAGS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="full stability analysis of a turbine: results, figures, HTML report",
        description="Flutter and divergence onset of a turbine over its wind speeds; results are "
                    "stored one operating point at a time, so an interrupted run can be resumed.  "
                    "The flags below the config file override its fields (same names, same checks).",
    )
    p.add_argument("turbine", metavar="TURBINE",
                   help="turbine file (windIO YAML) or bundled name (e.g. nrel5mw, iea15mw)")
    p.add_argument("-c", "--config", metavar="ANALYSIS.yaml",
                   help="analysis config (defaults: see docs/config_reference.md)")
    p.add_argument("-o", "--outdir", metavar="OUTDIR", default=None,
                   help="output folder (default: out/<turbine file name without suffix>, or out/<bundled name>)")
    p.add_argument("--resume", action="store_true",
                   help="continue an interrupted run in OUTDIR, keeping its finished points (same config, "
                        "turbine and windflutter version)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bars")
    p.add_argument("--workers", metavar="N", default=None,
                   help="operating points in parallel on N local processes (default: the usable "
                        "cores; 1 = serial, with progress inside each point)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="run the operating points on a Dask cluster, e.g. tcp://host:8786 "
                        "(its workers need windflutter installed; --workers is then ignored)")
    add_flags(p, FLAGS)
    p.add_argument("--print-default-config", action="store_true",
                   help="print the default analysis YAML and exit")
    p.set_defaults(func=run)


def read_config(args: argparse.Namespace):
    """The analysis config: defaults, then the ``-c`` file, then the flags (one validator)."""
    try:
        return load_config(args.config, config_overrides(args, FLAGS))
    except InputError as exc:
        from windflutter.cli.options import RPM_PATHS  # noqa: PLC0415

        raise flag_error(exc, args, FLAGS, RPM_PATHS) from None


def parse_workers(value: str | None) -> int | None:
    """``--workers`` as a positive int (``None``: the default, the usable cores)."""
    if value is None:
        return None
    try:
        n = int(str(value).strip())
    except ValueError:
        n = 0
    if n < 1 or str(value).strip() != str(n):
        raise InputError("--workers", value, "a positive integer number of processes (1 = serial)")
    return n


def load_turbine_for(arg: str, backend: str):
    """The turbine object handed to the analyser.

    The built-in solver gets ``windflutter.model.load_turbine(arg)``; a plug-in analyser
    (``solver.backend: NAME``) gets the argument string as given and loads what it needs itself.
    """
    if backend != "windflutter":
        return arg
    try:
        from windflutter.model import load_turbine  # noqa: PLC0415
    except ImportError:
        raise InputError("TURBINE", arg, "a turbine this version can read (no turbine reader is "
                         "installed: windflutter.model.load_turbine is missing)") from None
    return load_turbine(arg)


def _check_outdir(outdir: str | Path, field: str, resume: bool) -> None:
    """The output folder (and, with ``--resume``, its record) before anything is computed."""
    from windflutter.post import runfolder  # noqa: PLC0415

    runfolder.check_run_folder(outdir, field)
    if resume:
        runfolder.read_run_record(outdir)


def run(args: argparse.Namespace) -> int:
    if args.print_default_config:
        from windflutter.config import default_config_text  # noqa: PLC0415

        sys.stdout.write(default_config_text())
        return 0
    workers = parse_workers(args.workers)  # None: the usable cores (workflow.run resolves it)
    config = read_config(args)
    field = "-o" if args.outdir is not None else "OUTDIR (default out/<turbine file name>)"
    if args.outdir is not None:  # checked before the turbine is read
        _check_outdir(args.outdir, field, args.resume)
    if args.scheduler is not None:
        from windflutter.parallel import check_scheduler_address  # noqa: PLC0415

        check_scheduler_address(args.scheduler, "--scheduler")
    from windflutter.cli.warn import curve_rpm, gather_notes, operating_rotor_speed  # noqa: PLC0415
    from windflutter.workflow import RunInterrupted, run as run_workflow  # noqa: PLC0415

    turbine = load_turbine_for(args.turbine, config.solver.backend)
    if args.outdir is not None:
        outdir = Path(args.outdir)
    else:
        from windflutter.api import run_folder_name  # noqa: PLC0415

        outdir = Path("out") / run_folder_name(args.turbine)  # the file's stem or the bundled name
        _check_outdir(outdir, field, args.resume)
    try:
        ds = run_workflow(turbine, config, outdir, resume=args.resume, progress=not args.quiet,
                          workers=workers, scheduler=args.scheduler)
    except InputError as exc:
        if exc.field in ("scheduler", "workers"):  # name the flag the user typed
            raise InputError(f"--{exc.field}", exc.value, exc.expected) from None
        if exc.field == "outdir":
            raise InputError(field, exc.value, exc.expected) from None
        raise
    except RunInterrupted as exc:
        print(f"windflutter run: interrupted; {exc.done} of {exc.total} points stored in "
              f"{exc.outdir}; continue with: windflutter run {args.turbine}"
              + (f" -c {args.config}" if args.config else "") + f" -o {exc.outdir} --resume",
              file=sys.stderr)
        return 130
    if "reason" in ds:  # the points' range warnings: one line per kind (a worker process prints none)
        gather_notes(ds["reason"].values)
    operating_rotor_speed(curve_rpm(turbine))
    status = [str(s) for s in ds["status"].values] if "status" in ds else []
    n_failed = sum(s != "ok" for s in status)
    print(f"windflutter run: {len(status)} operating points, {n_failed} failed")
    if n_failed:
        for i in range(len(status)):
            if status[i] != "ok":
                print(f"  failed: V = {float(ds['wind_speed'][i]):g} m/s, {ds['aero'].values[i]}, "
                      f"{ds['method'].values[i]}: {ds['reason'].values[i]}")
    _print_headline(ds, outdir)
    print(f"results: {outdir / 'results.nc'}")
    report = outdir / "report.html"
    if report.is_file():
        print(f"report: {report.resolve()}")
    if status and n_failed == len(status):
        print("windflutter run: every operating point failed (see the reasons above)", file=sys.stderr)
        return 1
    return 0


def _print_headline(ds, outdir) -> None:
    """The verdict: first instability (mode, RPM, margin) and least damped mode in operation."""
    from windflutter.post import store  # noqa: PLC0415
    from windflutter.post.verdict import headline  # noqa: PLC0415

    camp = store.open_campbell(outdir) if (outdir / "campbell.nc").is_file() else None
    try:
        print(headline(ds, camp))
    except Exception as exc:  # the verdict must not cost the run its exit code
        print(f"(no verdict: {type(exc).__name__}: {exc})")
