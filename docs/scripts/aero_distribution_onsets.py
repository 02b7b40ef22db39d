"""Onsets of the NREL 5 MW rotor (shell, hub clamped) with the two aero distributions.

Reproduces the onset table of ``docs/aero_distribution.md``: for each layup (``nrel5mw``, the
windIO/WISDEM blade; ``seed5mw``, the thesis's UpWind layup) and each distribution (``spline``,
``skin``), the p-k flutter and divergence onsets at 10 m/s, potential flow, full physics.

Usage::

    python docs/scripts/aero_distribution_onsets.py [OUT.md] [--mesh 24x16]

About 2-4 minutes per case on one core.
"""

from __future__ import annotations

import argparse
import time

from windflutter.model import load_turbine
from windflutter.frozen.turbine import TurbineOptions, TurbineStability


def onset(turbine: str, distribution: str, n_chord: int, n_span: int, wind: float = 10.0) -> dict:
    """Flutter/divergence onset (RPM) of the rotor alone at ``wind`` m/s."""
    # the table was made with the plain 30-mode basis (reduction "modal"), kept here to reproduce it
    opts = TurbineOptions(model="shell", rpm_min=4, rpm_max=40, rpm_step=2, n_modes=30, n_tracked=18,
                          reduction="modal",
                          aero_distribution=distribution,
                          mesh={"part": "rotor", "n_chord": n_chord, "n_span": n_span})
    t0 = time.perf_counter()
    p = TurbineStability(load_turbine(turbine), opts).analyse_operating_point(wind)
    return {"turbine": turbine, "distribution": distribution, "mesh": f"{n_chord}x{n_span}",
            "flutter_rpm": p.flutter_rpm, "flutter_hz": p.flutter_frequency_hz, "mode": p.flutter_mode,
            "divergence_rpm": p.divergence_rpm, "seconds": time.perf_counter() - t0}


def _fmt(v, f="{:.2f}"):
    return "-" if v is None else f.format(v)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", nargs="?", default=None, help="markdown table file (default: print)")
    ap.add_argument("--mesh", default="24x16", help="elements around x along the blade")
    ap.add_argument("--turbines", nargs="+", default=["nrel5mw", "seed5mw"])
    a = ap.parse_args()
    nc, ns = (int(x) for x in a.mesh.split("x"))
    rows = ["| layup | mesh | distribution | flutter RPM | f (Hz) | mode | divergence RPM |",
            "|---|---|---|---|---|---|---|"]
    for t in a.turbines:
        for dist in ("spline", "skin"):
            r = onset(t, dist, nc, ns)
            rows.append(f"| `{t}` | {r['mesh']} | {dist} | {_fmt(r['flutter_rpm'])} | {_fmt(r['flutter_hz'], '{:.3f}')} "
                        f"| {r['mode'] or '-'} | {_fmt(r['divergence_rpm'])} |")
            print(rows[-1], f"({r['seconds']:.0f} s)", flush=True)
    text = "\n".join(rows) + "\n"
    if a.out:
        with open(a.out, "w") as fh:
            fh.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
