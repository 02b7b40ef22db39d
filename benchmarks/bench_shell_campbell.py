"""The shell Campbell diagram (method p) of issue 33: deflected against undeformed, times, sizes, memory.

Issue 33's target: the IEA 22 MW shell Campbell at 23 wind speeds in at most 90 s on 2 cores, the
blades linearized about their deflected shape, peak memory under 4 GB; the undeformed shell
(``solver.structure: undeformed``) is the same-run baseline.  Both at the defaults of
``windflutter campbell TURBINE --model shell`` (the default mesh: the blade length / 100 along the span,
40 around, midsurface skin; 30 fixed-interface blade modes + aerodynamic corrections).  Each case runs
in a forked child with one BLAS thread, so its peak RSS (``resource.getrusage``) is its own.
``--cold``: also the deflected run with the blade modes from shift-invert Lanczos at every wind speed
(``BladeBasis.restart`` before each: the path before the refinement, and the reference of
``tests/system/test_fast_blade_modes.py``); the largest frequency and damping differences of its modes
from the default run's are printed.

    python benchmarks/bench_shell_campbell.py [--quick] [--turbine iea22mw] [--winds 23] [--cold]
                                             [--only deflected|undeformed] [--workers 2]

``--workers N`` (default 2; 1: none): also the deflected run with its points in N worker processes
(``campbell(..., workers=N)``); its CPU time and memory include the workers' (the memory as the parent's
peak + N x the largest worker's, a bound on the total); the largest differences of its modes from the
one-process run's are printed.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, isolated, table  # noqa: E402


def run_case(turbine: str, winds: list, structure: str, cold: bool, workers: int = 1) -> dict:
    """One Campbell run (in the child): wall time of the model build and of the points, sizes, modes;
    with ``workers`` > 1 the points in that many worker processes (their CPU time and peak RSS as well)."""
    from windflutter.config import config_from_dict
    from windflutter.model import load_turbine
    from windflutter.methods import operational_options
    from windflutter.system.blade_basis import BladeBasis
    from windflutter.system.campbell import campbell
    from windflutter.system.operational import OperationalModel

    warnings.simplefilter("ignore")
    tb = load_turbine(turbine)
    cfg = config_from_dict({"model": {"type": "shell"}, "solver": {"structure": structure}})
    if cold:
        orig = BladeBasis._sparse_modes

        def from_scratch(self, *a, **k):
            self.restart()
            return orig(self, *a, **k)

        BladeBasis._sparse_modes = from_scratch
    t0 = time.perf_counter()
    om = OperationalModel(tb, operational_options(cfg, "viscous"))
    rb = om.blade(0.0)
    om.support(), om.reference()
    t1 = time.perf_counter()
    work = _count_work()
    c1 = _cpu()
    res = campbell(tb, winds, model=om, max_hz=2.5, workers=workers)
    t2, c2 = time.perf_counter(), _cpu()
    work = dict(work, cpu=c2 - c1 + _children_cpu(), workers=workers, worker_rss_mb=_children_rss_mb())  # the points' own (the sizes below evaluate one more)
    ps = om.at(float(winds[0]))
    modes = [[(complex(m.eigenvalue), bool(m.rigid)) for m in p.modes] for p in res.points]
    return dict(build=t1 - t0, points=t2 - t1, wall=t2 - t0, blade_dof=rb.struct.nq,
                basis=None if ps.Phi is None else ps.Phi.shape[1], states=ps.mbc.A.shape[0], modes=modes,
                unstable=len(res.unstable()), **work)


def _cpu() -> float:
    """CPU time (user + system, s) of this process: on a loaded machine a better measure of the work
    than the wall time."""
    import resource

    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def _children_cpu() -> float:
    """CPU time (s) of this process's ended children (the Campbell's worker processes)."""
    import resource

    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _children_rss_mb() -> float:
    """The largest peak RSS (MB) among this process's ended children (0 without)."""
    import resource

    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024


def _count_work() -> dict:
    """Count, from here on in this process, the work of the points: operating points evaluated
    (``OperationalModel.at``), sparse factorizations (CHOLMOD's numeric ones and SuperLU's), the columns
    solved with them, and dense eigen-solves (``scipy.linalg.eig``).  Returns the dict that the
    counters fill."""
    import scipy.linalg as sla
    import scipy.sparse.linalg as spla
    from kvxopt import cholmod

    from windflutter.structure import linalg
    from windflutter.system.operational import OperationalModel

    work = dict(evaluations=0, factorizations=0, columns=0, eigs=0)

    def counted(fn, key):
        def wrapped(*a, **k):
            work[key] += 1
            return fn(*a, **k)
        return wrapped

    at, numeric, solve, splu, eig = OperationalModel.at, cholmod.numeric, linalg.SPDFactor.solve, spla.splu, sla.eig

    def spd_solve(self, b):
        b = np.asarray(b)
        work["columns"] += 1 if b.ndim == 1 else b.shape[1]
        return solve(self, b)

    def lu(*a, **k):
        work["factorizations"] += 1
        f = splu(*a, **k)
        lu_solve = f.solve

        class Counted:  # SuperLU objects are read-only: count their solved columns through a wrapper
            def __getattr__(self, name):
                return getattr(f, name)

            def solve(self, b, *args, **kw):
                work["columns"] += 1 if np.ndim(b) == 1 else np.shape(b)[1]
                return lu_solve(b, *args, **kw)
        return Counted()

    OperationalModel.at = counted(at, "evaluations")
    cholmod.numeric = counted(numeric, "factorizations")
    linalg.SPDFactor.solve = spd_solve
    spla.splu = lu
    sla.eig = counted(eig, "eigs")
    return work


def _difference(a, b):
    """Largest relative frequency and absolute damping-ratio difference of the elastic modes, each mode
    of ``a`` paired with the nearest eigenvalue of ``b`` (an assignment: modes of nearly equal
    frequency and different damping can swap ranks)."""
    from scipy.optimize import linear_sum_assignment

    df = dz = 0.0
    for p, q in zip(a, b):
        la = np.array([x for x, rigid in p if not rigid])
        lb = np.array([x for x, _ in q])
        if not la.size:
            continue
        r, c = linear_sum_assignment(np.abs(la[:, None] - lb[None, :]) / np.abs(la)[:, None])
        fa, fb = np.abs(la[r]), np.abs(lb[c])
        df = max(df, float(np.max(np.abs(fb / fa - 1))))
        dz = max(dz, float(np.max(np.abs(lb[c].real / fb - la[r].real / fa))))
    return df, dz


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="4 wind speeds")
    ap.add_argument("--turbine", default="iea22mw")
    ap.add_argument("--winds", type=int, default=23, help="wind speeds along 3-25 m/s (default 23)")
    ap.add_argument("--cold", action="store_true", help="also the deflected run with modes from scratch")
    ap.add_argument("--only", choices=("deflected", "undeformed"), default=None)
    ap.add_argument("--workers", type=int, default=2, help="processes of the parallel deflected row (default 2; 1: no such row)")
    args = ap.parse_args(argv)
    from windflutter.model import load_turbine
    from windflutter.system.campbell import default_wind_speeds

    ws = default_wind_speeds(load_turbine(args.turbine))
    n = 4 if args.quick else args.winds
    winds = [float(v) for v in np.linspace(ws[0], ws[-1], n)]
    header(f"bench_shell_campbell: {args.turbine} shell Campbell, {n} wind speeds {winds[0]:g}-{winds[-1]:g} m/s")
    cases = [("undeformed [baseline]", "undeformed", False), ("deflected (default)", "deflected", False)]
    if args.only:
        cases = [c for c in cases if c[1] == args.only]
    if args.workers > 1 and args.only != "undeformed":
        cases.append((f"deflected, {args.workers} workers", "deflected", False))
    if args.cold:
        cases.append(("deflected, Lanczos at every point", "deflected", True))
    rows, runs = [], {}
    for label, structure, cold in cases:
        nw = args.workers if "workers" in label else 1
        out, dt, rss = isolated(run_case, args.turbine, winds, structure, cold, nw)
        rss = rss + nw * out["worker_rss_mb"] if nw > 1 else rss  # all processes: bounded by the largest worker
        runs[label] = out
        rows.append(dict(case=label, wall=out["wall"], build=out["build"], points=out["points"],
                         per_point=out["points"] / n, blade_dof=out["blade_dof"], basis=out["basis"],
                         states=out["states"], rss_mb=rss, unstable=out["unstable"], load=os.getloadavg()[0],
                         **{k: out[k] for k in ("cpu", "evaluations", "factorizations", "columns", "eigs", "workers")}))
        print(f"  {label}: {out['wall']:.1f} s, peak RSS {rss:.0f} MB (load avg {os.getloadavg()[0]:.2f})", flush=True)
    base = rows[0]["wall"]
    for r in rows:
        r["ratio"] = r["wall"] / base
    table(rows, ["case", "workers", "wall", "build", "points", "per_point", "ratio", "blade_dof", "basis", "states", "rss_mb",
                 "unstable", "cpu", "evaluations", "factorizations", "columns", "eigs", "load"])
    print("times in s (wall = build + points); ratio: to the first row; basis: blade basis vectors (modes + "
          "corrections); states: first-order MBC system; rss_mb: peak RSS of the case's process; cpu: CPU time of the points "
          "(s, workers included); with workers rss_mb is the parent's + workers x the largest worker's (a bound on the total); the work of the points: evaluations (operating points, with the middles of ambiguous steps), sparse factorizations, "
          "columns solved with them, dense eigen-solves; load: 1-min load average at the case's end")
    pooled = f"deflected, {args.workers} workers"
    if pooled in runs and "deflected (default)" in runs:
        df, dz = _difference(runs[pooled]["modes"], runs["deflected (default)"]["modes"])
        print(f"one process vs {args.workers} workers: max rel. frequency difference {df:.2e}, max damping-ratio "
              f"difference {dz:.2e} (elastic modes)")
    if args.cold and "deflected (default)" in runs:
        df, dz = _difference(runs["deflected, Lanczos at every point"]["modes"], runs["deflected (default)"]["modes"])
        print(f"default vs Lanczos at every point: max rel. frequency difference {df:.2e}, max damping-ratio "
              f"difference {dz:.2e} (elastic modes)")
    for target in ([r for r in rows if r["case"].startswith("deflected")] if n == 23 else []):
        t = target["wall"]
        print(f"issue 33 target ({target['case']}): 23 wind speeds deflected <= 90 s -> {'met' if t <= 90 else 'NOT met'} ({t:.0f} s); "
              f"peak memory < 4 GB -> {'met' if target['rss_mb'] < 4096 else 'NOT met'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
