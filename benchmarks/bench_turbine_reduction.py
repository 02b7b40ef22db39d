"""NREL 5 MW: flutter/divergence onset of the full-order model vs the modally reduced one.

Uses the solver's own switch ``TurbineOptions.n_modes`` (None = full constrained model, solved by
sparse shift-invert Arnoldi in every p-k iteration; an integer = Galerkin projection on the union
of that many structural modes at 0 RPM and at the top of the range); "+ aero MTA" uses
``windflutter.solve.aero_reduction.MTAAeroelasticModel`` (the same basis plus static-correction
vectors for the aero loads of the modes, quasi-steady, at the analysed wind speed). Beam model of the bundled
NREL 5 MW (672 DOF after constraints), potential flow, p-k search, full physics, one wind speed.
Baseline: the full-order run. Target of issue 7: reduced onset within 0.5 % of full order.
``--quick``: reduced models only (the full-order p-k sweep takes minutes).
Usage: python benchmarks/bench_turbine_reduction.py [--quick] [--wind 10] [--rpm 20 34 2]
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, isolated, table  # noqa: E402


def load():
    from windflutter.model import load_turbine

    t = load_turbine("nrel5mw")
    I = np.asarray(t.nacelle.inertia)
    if not (np.allclose(I, I.T) and np.linalg.eigvalsh(0.5 * (I + I.T)).min() >= -1e-9 * abs(I).max()):
        # reader issue seen at the time of writing: non-symmetric nacelle tensor; use the yaw
        # inertia of Jonkman et al. 2009 (NacYIner = 2,607,890 kg m^2) as tests/mesh does
        t = dataclasses.replace(t, nacelle=dataclasses.replace(t.nacelle, inertia=np.diag([0.0, 0.0, 2607890.0])))
    return t


def case(n_modes, wind, rpm, mta=False):
    import windflutter.frozen.turbine as tmod
    from windflutter.frozen.turbine import TurbineOptions, TurbineStability

    if mta:  # runs in a forked child: the swap does not leak into other cases
        from windflutter.solve.aero_reduction import MTAAeroelasticModel

        tmod.AeroelasticModel = lambda **kw: MTAAeroelasticModel(**kw, mta_wind_speeds=(wind,))

    o = TurbineOptions(model="beam", aero="potential", method="pk", n_modes=n_modes,
                       min_rpm=rpm[0], max_rpm=rpm[1], rpm_step=rpm[2])
    ts = TurbineStability(load(), o)
    t0 = time.perf_counter()
    _, _, am = ts.model(ts.pitch_at(wind))
    t_build = time.perf_counter() - t0
    t0 = time.perf_counter()
    s = ts.analyse_operating_point(wind)
    return dict(size=am.size, t_build=t_build, t_search=time.perf_counter() - t0,
                flutter_rpm=s.flutter_rpm, flutter_hz=s.flutter_frequency_hz, mode=s.flutter_mode,
                divergence_rpm=s.divergence_rpm)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--wind", type=float, default=10.0)
    ap.add_argument("--rpm", type=float, nargs=3, default=[20.0, 34.0, 2.0])
    a = ap.parse_args()
    header("bench_turbine_reduction: NREL 5 MW beam model, full vs reduced onset",
           case=f"V = {a.wind} m/s, potential, p-k, full physics, rpm grid {a.rpm}")
    cases = [("reduced, 30 modes/speed", 30, False), ("reduced, 15 modes/speed + aero MTA", 15, True),
             ("reduced, 30 modes/speed + aero MTA", 30, True)]
    if not (QUICK or a.quick):
        cases = [("full order [baseline]", None, False)] + cases
    rows = []
    for label, nm, mta in cases:
        try:
            r, wall, rss = isolated(case, nm, a.wind, tuple(a.rpm), mta)
        except RuntimeError as exc:
            print(f"  {label}: FAILED\n{exc}")
            continue
        r.update(case=label, peak_rss_MB=rss)
        rows.append(r)
        print(f"  done: {label}: flutter {r['flutter_rpm']}, divergence {r['divergence_rpm']}, "
              f"{r['t_search']:.1f} s", flush=True)
    if not rows:
        return 1
    base = rows[0]
    for r in rows:
        r["search_ratio"] = r["t_search"] / base["t_search"]
        for k in ("flutter_rpm", "divergence_rpm"):
            if r[k] is not None and base[k] is not None:
                r[f"d_{k[:4]}_%"] = 100.0 * (r[k] - base[k]) / base[k]
    table(rows, ["case", "size", "t_build", "t_search", "search_ratio", "flutter_rpm", "d_flut_%",
                 "divergence_rpm", "d_dive_%", "flutter_hz", "mode", "peak_rss_MB"])
    print("d_*_%: onset difference to the first row (%); target |d| < 0.5 %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
