"""NREL 5 MW stability map (several wind speeds) with the reduced model: serial vs 2 workers.

Each wind speed is one task of ``windflutter.parallel.run_tasks``; the task callable holds one
``TurbineStability`` (beam model, potential flow, p-k, full physics, rotor speeds 20-34 RPM) whose
model uses ``MTAAeroelasticModel`` (15 modes per reference speed + aero static-correction
vectors at the two end wind speeds of the map, §5 of docs/notes/performance_rounds.md). The callable is sent to each worker once, so each
worker builds the model once per pitch. Baseline: the serial run; results compared bit for bit.
``--quick``: 2 wind speeds.
Usage: python benchmarks/bench_turbine_map.py [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, maxrss_mb, table  # noqa: E402

from windflutter.parallel import run_tasks  # noqa: E402

WINDS = [6.0, 10.0] if QUICK else [5.0, 7.0, 9.0, 11.0]


class MapPoint:
    """Callable task: onsets at one wind speed (m/s) -> dict."""

    def __init__(self, turbine):
        self.turbine = turbine
        self._ts = None

    def __call__(self, wind):
        import windflutter.frozen.turbine as tmod
        from windflutter.solve.aero_reduction import MTAAeroelasticModel

        if self._ts is None:
            self._ts = tmod.TurbineStability(self.turbine, tmod.TurbineOptions(
                model="beam", aero="potential", method="pk", n_modes=15, min_rpm=20, max_rpm=34,
                rpm_step=2))
        orig = tmod.AeroelasticModel
        # load shapes at fixed wind speeds (the ends of the map), not at the analysed one: the
        # model is cached per pitch, so the basis must not depend on which point comes first
        ends = (min(WINDS), max(WINDS))
        tmod.AeroelasticModel = lambda **kw: MTAAeroelasticModel(**kw, mta_wind_speeds=ends)
        try:
            s = self._ts.analyse_operating_point(wind)
        finally:
            tmod.AeroelasticModel = orig
        return s.as_dict()


def main() -> int:
    from bench_turbine_reduction import load

    turbine = load()
    header("bench_turbine_map: NREL 5 MW beam, reduced (15 modes + aero MTA), map over wind speed",
           winds=WINDS)
    rows = []
    for label, workers in (("serial [baseline]", 1), ("local pool, workers=2", 2)):
        t0 = time.perf_counter()
        res = run_tasks(MapPoint(turbine), WINDS, workers=workers)
        wall = time.perf_counter() - t0
        rows.append(dict(case=label, wall=wall, task_sum=sum(r.elapsed for r in res),
                         ok=all(r.ok for r in res), res=res, rss=maxrss_mb()))
        for r in res:
            print(f"  {label}: V={WINDS[r.index]}: " + (str(r.value) if r.ok else r.error), flush=True)
    base = rows[0]
    for r in rows:
        r["speedup"] = base["wall"] / r["wall"]
        r["identical"] = [a.value for a in base["res"]] == [b.value for b in r["res"]]
    table(rows, ["case", "wall", "task_sum", "speedup", "identical", "ok", "rss"])
    print("times in s; rss: peak RSS of this process (MB)")
    return 0 if all(r["ok"] and r["identical"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
