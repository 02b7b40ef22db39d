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

from windflutter.config import AERO_VARIANTS, MODEL_TYPES, SEARCH_METHODS, load_config
from windflutter.errors import InputError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "run",
        help="full stability analysis of a turbine: results, figures, HTML report",
        description="Flutter and divergence onset of a turbine over its wind speeds; results are "
                    "stored one operating point at a time, so an interrupted run can be resumed.",
    )
    p.add_argument("turbine", metavar="TURBINE",
                   help="turbine file (windIO YAML) or bundled name (e.g. nrel5mw, iea15mw)")
    p.add_argument("-c", "--config", metavar="ANALYSIS.yaml",
                   help="analysis config (defaults: see docs/config_reference.md)")
    p.add_argument("-o", "--outdir", metavar="OUTDIR", default=None,
                   help="output folder (default: out/<turbine name>)")
    p.add_argument("--resume", action="store_true",
                   help="continue an interrupted run in OUTDIR, keeping its finished points")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bars")
    p.add_argument("--workers", metavar="N", default=None,
                   help="operating points in parallel on N local processes (default: the usable "
                        "cores; 1 = serial, with progress inside each point)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="run the operating points on a Dask cluster, e.g. tcp://host:8786 "
                        "(its workers need windflutter installed; --workers is then ignored)")
    p.add_argument("--wind-speeds", nargs="+", type=float, metavar="V",
                   help="override the config's wind speeds (m/s)")
    p.add_argument("--aero", nargs="+", choices=AERO_VARIANTS, help="override the aero variants")
    p.add_argument("--method", nargs="+", choices=SEARCH_METHODS, help="override the search methods")
    p.add_argument("--model", choices=MODEL_TYPES, help="override the model type")
    p.add_argument("--print-default-config", action="store_true",
                   help="print the default analysis YAML and exit")
    p.set_defaults(func=run)


def _overrides(args: argparse.Namespace) -> dict:
    o: dict = {}
    if args.wind_speeds:
        o["wind_speeds"] = list(args.wind_speeds)
    if args.aero:
        o["aero"] = list(args.aero)
    if args.method:
        o["method"] = list(args.method)
    if args.model:
        o["model"] = {"type": args.model}
    return o


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
    (``solver.backend: module:factory``) gets the argument string as given and loads what it
    needs itself.
    """
    if backend != "windflutter":
        return arg
    try:
        from windflutter.model import load_turbine  # noqa: PLC0415
    except ImportError:
        raise InputError("TURBINE", arg, "a turbine this version can read (no turbine reader is "
                         "installed: windflutter.model.load_turbine is missing)") from None
    return load_turbine(arg)


def run(args: argparse.Namespace) -> int:
    from windflutter.workflow import RunInterrupted, run as run_workflow  # noqa: PLC0415

    if args.print_default_config:
        from windflutter.config import default_config_text  # noqa: PLC0415

        sys.stdout.write(default_config_text())
        return 0
    workers = parse_workers(args.workers)  # None: the usable cores (workflow.run resolves it)
    config = load_config(args.config, _overrides(args))
    turbine = load_turbine_for(args.turbine, config.solver.backend)
    name = Path(str(getattr(turbine, "name", args.turbine))).stem.replace(" ", "_") or "turbine"
    outdir = Path(args.outdir) if args.outdir else Path("out") / name
    try:
        ds = run_workflow(turbine, config, outdir, resume=args.resume, progress=not args.quiet,
                          workers=workers, scheduler=args.scheduler)
    except InputError as exc:
        if exc.field in ("scheduler", "workers"):  # name the flag the user typed
            raise InputError(f"--{exc.field}", exc.value, exc.expected) from None
        raise
    except RunInterrupted as exc:
        print(f"windflutter run: interrupted; {exc.done} of {exc.total} points stored in "
              f"{exc.outdir}; continue with: windflutter run {args.turbine}"
              + (f" -c {args.config}" if args.config else "") + f" -o {exc.outdir} --resume",
              file=sys.stderr)
        return 130
    status = [str(s) for s in ds["status"].values] if "status" in ds else []
    n_failed = sum(s != "ok" for s in status)
    print(f"windflutter run: {len(status)} operating points, {n_failed} failed")
    if n_failed:
        for i in range(len(status)):
            if status[i] != "ok":
                print(f"  failed: V = {float(ds['wind_speed'][i]):g} m/s, {ds['aero'].values[i]}, "
                      f"{ds['method'].values[i]}: {ds['reason'].values[i]}")
    print(f"results: {outdir / 'results.nc'}")
    report = outdir / "report.html"
    if report.is_file():
        print(f"report: {report.resolve()}")
    if status and n_failed == len(status):
        print("windflutter run: every operating point failed (see the reasons above)", file=sys.stderr)
        return 1
    return 0
