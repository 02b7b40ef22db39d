"""``windflutter run`` on shell blades: the operating-point Campbell read from the map's points vs evaluated again.

Issue 33's NREL 5 MW shell run (11 wind speeds, 2 workers) spent 35-40 s of its 5.4 min evaluating the
Campbell's operating points -- the points each overspeed sweep starts from -- in two freshly started
workers.  Now the map's analysers keep them (``PointResult.operating_system``) and the Campbell reads them
(``system/campbell.py::PreparedPoints``).  Baseline, measured in the same run: the same run with the
analysers keeping nothing (``TurbinePointAnalyser.share_campbell_model`` and the keeping switched off), so
the Campbell evaluates its points in its own workers as before.  Printed: wall and CPU time (workers
included), operating points, and the largest differences between the two Campbells (names must agree).

    python benchmarks/bench_run_campbell.py [--quick] [--workers 2]

Default: the NREL 5 MW with the default shell mesh at 3 wind speeds, overspeed sweeps to 16 RPM (a few
points each; the whole map's numbers are in docs/notes/performance_rounds.md §17).  ``--quick``: a coarse
shell (mesh density 0.3).
"""

from __future__ import annotations

import argparse
import resource
import sys
import tempfile
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, table  # noqa: E402


def _cpu() -> float:
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def run(turbine, cfg, workers: int, prepared: bool):
    """``(CampbellResult, wall s, CPU s)`` of ``windflutter.run``; ``prepared`` False: the baseline."""
    import windflutter
    from windflutter import workflow
    from windflutter.analysers import TurbinePointAnalyser

    got, orig = {}, workflow.operating_campbell
    saved = TurbinePointAnalyser.__init__

    def init(self, *a, **k):  # the baseline: no Campbell case kept or shared
        saved(self, *a, **k)
        self._campbell = None

    def operating_campbell(*a, **k):
        got["c"] = orig(*a, **k)
        return got["c"]

    workflow.operating_campbell = operating_campbell
    if not prepared:
        TurbinePointAnalyser.__init__ = init
    try:
        with tempfile.TemporaryDirectory() as out, warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t0, c0 = time.perf_counter(), _cpu()
            windflutter.run(turbine, cfg, out, progress=False, workers=workers)
            return got["c"], time.perf_counter() - t0, _cpu() - c0
    finally:
        workflow.operating_campbell = orig
        TurbinePointAnalyser.__init__ = saved


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args(argv)
    import numpy as np

    import windflutter
    from windflutter.solve.linsolve import blas_limit

    model = {"type": "shell", **({"mesh_density": 0.3} if args.quick else {})}
    winds = [8.0, 12.0, 20.0]
    cfg = windflutter.analysis_config(wind_speeds=winds, model=model, rotor_speed={"max_rpm": 16.0},
                                      output={"plots": False, "report": False, "animations": False})
    turbine = windflutter.load_turbine("nrel5mw")
    header("bench_run_campbell: windflutter run, NREL 5 MW shell, the Campbell from the map's points",
           wind_speeds=winds, workers=args.workers, mesh="mesh density 0.3" if args.quick else "default")
    rows, camps = [], []
    with blas_limit(1):
        for case, prepared in (("Campbell evaluates its points [baseline]", False), ("Campbell from the map", True)):
            c, wall, cpu = run(turbine, cfg, args.workers, prepared)
            camps.append(c)
            rows.append(dict(case=case, wall=wall, cpu=cpu, campbell_points=len(c.points),
                             modes=sum(len(p.modes) for p in c.points)))
    for r in rows:
        r["speedup"] = rows[0]["wall"] / r["wall"]
    table(rows, ["case", "wall", "cpu", "speedup", "campbell_points", "modes"])
    a, b = camps
    names = all(sorted(m.name for m in p.modes) == sorted(m.name for m in q.modes) for p, q in zip(a.points, b.points))
    swaps = [(p.wind_speed, m.name, n.name, round(m.frequency_hz, 4)) for p, q in zip(a.points, b.points)
             for m, n in zip(p.modes, q.modes) if m.name != n.name]
    if swaps:  # a degenerate pair's two ordinals (a shell tower's wall modes: the same frequency) either way round
        print("names in the other order (V, baseline, new, Hz):", swaps)
    df = max(abs(m.frequency_hz / n.frequency_hz - 1) for p, q in zip(a.points, b.points) for m, n in zip(p.modes, q.modes))
    dz = max(abs(m.damping_ratio - n.damping_ratio) for p, q in zip(a.points, b.points) for m, n in zip(p.modes, q.modes))
    print(f"times in s (cpu: this process and its workers); the same names at every point: {names}; largest relative frequency "
          f"difference {df:.2e}, damping-ratio difference {dz:.2e} (the shell basis's tolerance: ~1e-5)")
    return 0 if names and df < 1e-4 and np.isfinite(dz) and dz < 1e-4 else 1


if __name__ == "__main__":
    sys.exit(main())
