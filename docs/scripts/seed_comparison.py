"""Stability maps for the comparison with the seed thesis (docs/seed_comparison.md).

Rotor alone (hub clamped, ``part="rotor"``), beam model, default strips, p-k search, no
structural damping; flutter and divergence onset (RPM) per wind speed, pitch from each turbine's
operating curve.

* NREL 5 MW: potential / viscous x thesis physics (no K_sigma) / full physics;
* the seed's 20 MW (``seed20mw``) and the IEA 15 MW (``iea15mw``): potential and viscous, full
  physics.

Usage::

    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR [--turbines nrel5mw ...]
    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR --plot-only

writes ``OUTDIR/maps.csv`` (one row per turbine, variant and wind speed; appended as it goes, so
a run can be split by turbine), ``OUTDIR/maps.md`` (the same as a markdown table) and
``OUTDIR/<turbine>_flutter.png`` / ``OUTDIR/<turbine>_divergence.png``.
"""

from __future__ import annotations

import argparse
import csv
import math
import time
from pathlib import Path

# per turbine: wind speeds (m/s), rotor-speed grid (RPM: min, max, step), variants (aero, physics)
CASES = {
    "nrel5mw": dict(wind=(4, 6, 8, 10, 12, 15, 20, 25), rpm=(8.0, 36.0, 2.0),
                    variants=(("potential", "thesis"), ("potential", "full"),
                              ("viscous", "thesis"), ("viscous", "full"))),
    "seed20mw": dict(wind=(4, 7, 10, 13, 18, 25), rpm=(2.0, 20.0, 1.5),
                     variants=(("potential", "full"), ("viscous", "full"))),
    "iea15mw": dict(wind=(4, 7, 10, 13, 18, 25), rpm=(2.0, 20.0, 1.5),
                    variants=(("potential", "full"), ("viscous", "full"))),
}
RATED_RPM = {"nrel5mw": 12.1, "seed20mw": 6.31, "iea15mw": 7.56}
FIELDS = ("turbine", "aero", "physics", "wind_speed", "pitch_deg", "flutter_rpm", "flutter_hz",
          "flutter_mode", "divergence_rpm", "seconds")


def run_case(name: str, out_csv: Path) -> None:
    """Analyse every variant and wind speed of one turbine, appending rows to ``out_csv``."""
    from windflutter.model.windio import load_turbine
    from windflutter.stability.turbine import TurbineOptions, TurbineStability

    case = CASES[name]
    turbine = load_turbine(name)
    new = not out_csv.exists()
    with out_csv.open("a", newline="") as fh:
        w = csv.DictWriter(fh, FIELDS)
        if new:
            w.writeheader()
        for aero, physics in case["variants"]:
            lo, hi, step = case["rpm"]
            opts = TurbineOptions(model="beam", aero=aero, physics=physics, method="pk",
                                  rpm_min=lo, rpm_max=hi, rpm_step=step, mesh={"part": "rotor"})
            ts = TurbineStability(turbine, opts)
            for v in case["wind"]:
                t0 = time.time()
                p = ts.analyse_operating_point(float(v))
                f = (lambda x: "" if x is None else f"{x:.3f}")
                w.writerow(dict(turbine=name, aero=aero, physics=physics, wind_speed=v,
                                pitch_deg=f"{p.pitch_deg:.2f}", flutter_rpm=f(p.flutter_rpm),
                                flutter_hz=f(p.flutter_frequency_hz), flutter_mode=p.flutter_mode or "",
                                divergence_rpm=f(p.divergence_rpm), seconds=f"{time.time() - t0:.0f}"))
                fh.flush()
                print(name, aero, physics, v, p.flutter_rpm, p.divergence_rpm, flush=True)


def read_rows(out_csv: Path) -> list[dict]:
    with out_csv.open() as fh:
        return list(csv.DictReader(fh))


def write_markdown(rows: list[dict], path: Path) -> None:
    head = "| turbine | aero | physics | V (m/s) | pitch (deg) | flutter (RPM) | f (Hz) | divergence (RPM) | flutter mode |"
    lines = [head, "|" + "---|" * 9]
    for r in rows:
        lines.append(f"| {r['turbine']} | {r['aero']} | {r['physics']} | {r['wind_speed']} | {r['pitch_deg']} | "
                     f"{r['flutter_rpm'] or '-'} | {r['flutter_hz'] or '-'} | {r['divergence_rpm'] or '-'} | "
                     f"{r['flutter_mode']} |")
    path.write_text("\n".join(lines) + "\n")


def plot(rows: list[dict], outdir: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {("potential", "full"): ("C0", "-o"), ("potential", "thesis"): ("C0", "--s"),
              ("viscous", "full"): ("C3", "-o"), ("viscous", "thesis"): ("C3", "--s")}
    for name in sorted({r["turbine"] for r in rows}):
        for key, title in (("flutter_rpm", "flutter"), ("divergence_rpm", "divergence")):
            fig, ax = plt.subplots(figsize=(5.2, 3.6))
            for (aero, physics), (color, fmt) in styles.items():
                sel = [r for r in rows if r["turbine"] == name and r["aero"] == aero and r["physics"] == physics]
                pts = [(float(r["wind_speed"]), float(r[key])) for r in sel if r[key]]
                if pts:
                    x, y = zip(*pts)
                    ax.plot(x, y, fmt, color=color, ms=4, label=f"{aero}, {physics} physics")
            ax.axhline(RATED_RPM[name], color="k", lw=0.8, ls=":", label=f"rated {RATED_RPM[name]} RPM")
            if name == "nrel5mw" and key == "flutter_rpm":
                ax.plot([10.0], [19.1], "k*", ms=9, label="AIAA 2008-1302: 19.1 RPM")
            ax.set_xlabel("wind speed (m/s)")
            ax.set_ylabel("rotor speed (RPM)")
            ax.set_title(f"{name}: {title} onset (rotor alone, beam, p-k)", fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(outdir / f"{name}_{title}.png", dpi=90)
            plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir")
    ap.add_argument("--turbines", nargs="+", choices=sorted(CASES), default=list(CASES))
    ap.add_argument("--plot-only", action="store_true", help="only redo maps.md and the PNGs from maps.csv")
    a = ap.parse_args(argv)
    out = Path(a.outdir)
    out.mkdir(parents=True, exist_ok=True)
    csv_path = out / "maps.csv"
    if not a.plot_only:
        for name in a.turbines:
            run_case(name, csv_path)
    rows = read_rows(csv_path)
    write_markdown(rows, out / "maps.md")
    plot(rows, out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
