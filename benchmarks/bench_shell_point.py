"""One wind speed of the NREL 5 MW shell stability map (method p): refined vs cold blade modes.

Issue 17's target: the 12-wind-speed shell map in under 3 minutes on 2 cores.  A shell point pays,
at every rotor speed of its sweep and every trial of its root searches, the fixed-interface modes of
the 7,866-DOF blade.  Baseline measured in the same run: those modes from scratch at every rotor speed
(shift-invert Lanczos, ``BladeBasis.restart`` before each); new: refined by subspace iteration
from the last speed's (``solve.symmetric.refine_modes``, the default).  Printed: wall time,
model evaluations, blade DOF, basis size and the onsets of both (they must agree to well inside the
search's 0.01 RPM).  ``--quick``: 8 m/s up to 16 RPM (no onset; the time per rotor speed).

    python benchmarks/bench_shell_point.py [--quick] [--wind 10]
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, maxrss_mb, table  # noqa: E402

from windflutter.solve.linsolve import blas_limit  # noqa: E402


def run(turbine, wind: float, max_rpm: float, cold: bool) -> dict:
    import windflutter
    from windflutter.system.blade_basis import BladeBasis

    orig = BladeBasis._sparse_modes
    count = {"n": 0}

    def sparse_modes(self, *a, **k):
        count["n"] += 1
        if cold:
            self.restart()
        return orig(self, *a, **k)

    BladeBasis._sparse_modes = sparse_modes
    try:
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            p = windflutter.stability(turbine, [wind], model="shell", rotor_speed={"max_rpm": max_rpm})[0]
        wall = time.perf_counter() - t0
    finally:
        BladeBasis._sparse_modes = orig
    return dict(wall=wall, evaluations=count["n"], flutter=p.flutter_rpm, mode=p.flutter_mode,
                divergence=p.divergence_rpm, rss=maxrss_mb())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--wind", type=float, default=None)
    args = ap.parse_args(argv)
    import windflutter

    wind = args.wind if args.wind is not None else (8.0 if args.quick else 10.0)
    max_rpm = 16.0 if args.quick else 40.0
    turbine = windflutter.load_turbine("nrel5mw")
    header("bench_shell_point: NREL 5 MW shell, method p, one wind speed", wind=wind, max_rpm=max_rpm)
    rows = []
    with blas_limit(1):
        for case, cold in (("cold Lanczos every speed [baseline]", True), ("refined from the last speed", False)):
            r = run(turbine, wind, max_rpm, cold)
            rows.append(dict(case=case, **r))
    base = rows[0]
    for r in rows:
        r["speedup"] = base["wall"] / r["wall"]
        r["d_flutter"] = (abs(r["flutter"] - base["flutter"])
                          if r["flutter"] is not None and base["flutter"] is not None else None)
        r["d_divergence"] = (abs(r["divergence"] - base["divergence"])
                             if r["divergence"] is not None and base["divergence"] is not None else None)
    table(rows, ["case", "wall", "evaluations", "speedup", "flutter", "d_flutter", "divergence", "d_divergence",
                 "mode", "rss"])
    print("times in s; onsets and differences in RPM; rss: peak RSS of this process (MB)")
    same = all((r["flutter"] is None) == (base["flutter"] is None) for r in rows)
    close = all((r["d_flutter"] or 0) < 1e-3 and (r["d_divergence"] or 0) < 1e-3 for r in rows)
    return 0 if same and close else 1


if __name__ == "__main__":
    sys.exit(main())
