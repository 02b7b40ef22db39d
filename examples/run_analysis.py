"""A scripted `windflutter run`, then its results read back with xarray.

Runs the whole analysis of a turbine with an analysis config (default: analysis_nrel5mw.yaml
beside this script) into an output folder -- results.nc, report.html, figures/ -- exactly as
``windflutter run nrel5mw -c examples/analysis_nrel5mw.yaml`` does, then opens ``results.nc`` with
xarray and prints one line per operating point.

    python examples/run_analysis.py                                  # about a minute on 2 cores
    python examples/run_analysis.py --wind-speeds 8 15 --set model.n_aero_sections=12 --outdir out/quick
    python examples/run_analysis.py --results out/nrel5mw/results.nc  # only read an earlier run
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import yaml

import windflutter
from windflutter.api import run_folder_name

HERE = Path(__file__).resolve().parent


def parse(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--turbine", default="nrel5mw", help="turbine file or bundled name")
    p.add_argument("--config", default=str(HERE / "analysis_nrel5mw.yaml"), help="analysis YAML")
    p.add_argument("--outdir", default=None, help="output folder (default out/<turbine>)")
    p.add_argument("--wind-speeds", nargs="+", type=float, default=None, metavar="V",
                   help="override the config's wind speeds (m/s)")
    p.add_argument("--set", action="append", default=[], metavar="FIELD=VALUE",
                   help="override any config field, e.g. --set model.n_aero_sections=12 (repeatable)")
    p.add_argument("--quick", action="store_true", help="no figures, report or animations (results.nc only)")
    p.add_argument("--results", default=None, help="read this results.nc only (no run)")
    return p.parse_args(argv)


def run(args: argparse.Namespace) -> Path:
    """The analysis; returns the path of its results.nc."""
    overrides: dict = {}
    if args.wind_speeds is not None:
        overrides["wind_speeds"] = args.wind_speeds
    for item in args.set:  # dotted config fields; the values are YAML (numbers, lists, true/false)
        field, _, text = item.partition("=")
        overrides[field.strip()] = yaml.safe_load(text)
    if args.quick:
        overrides["output"] = {"plots": False, "report": False, "animations": False}
    outdir = Path(args.outdir) if args.outdir else Path("out") / run_folder_name(args.turbine)
    windflutter.run(args.turbine, args.config, outdir, progress=False, **overrides)
    return outdir / "results.nc"


def summarise(path: str | Path) -> None:
    """One line per operating point of a results.nc (units from the file's attributes)."""
    import xarray as xr

    with xr.open_dataset(path) as ds:
        unit = ds["flutter_rpm"].attrs.get("units", "")
        print(f"{ds.attrs.get('title', '')}: {ds.sizes['point']} operating points")
        for i in range(ds.sizes["point"]):
            p = ds.isel(point=i)
            fl, dv = float(p["flutter_rpm"]), float(p["divergence_rpm"])
            flutter = "-" if math.isnan(fl) else f"{fl:.2f} {unit} ({p['flutter_mode'].item()}, " \
                                                   f"{float(p['flutter_frequency']):.3f} Hz)"
            diverge = "-" if math.isnan(dv) else f"{dv:.2f} {unit}"
            print(f"  V = {float(p['wind_speed']):5.1f} m/s {p['aero'].item()}/{p['method'].item()}: "
                  f"flutter {flutter}; divergence {diverge}; {p['status'].item()}")


def main(argv=None) -> int:
    args = parse(argv)
    path = Path(args.results) if args.results else run(args)
    summarise(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
