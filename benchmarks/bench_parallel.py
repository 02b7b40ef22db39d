"""Independent operating points: serial (baseline) vs 2 local worker processes vs Dask.

Each task is ``benchmarks/testproblems.py::demo_point``: build a shell-like tube model, compute
its structural modes at the task's rotor speed, reduce and solve the coupled QEP -- the shape of
one operating point of a stability map. 8 tasks (``--quick``: 4 smaller ones). Results of all
modes are compared bit for bit with the serial run. The Dask case starts a
``distributed.LocalCluster`` with 2 single-threaded worker processes (its start-up time is
reported separately); skip it with ``--no-dask``.
Usage: python benchmarks/bench_parallel.py [--quick] [--no-dask]
"""

from __future__ import annotations

import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, maxrss_mb, table  # noqa: E402

from windflutter.parallel import run_tasks  # noqa: E402
from testproblems import demo_point  # noqa: E402

N_TASKS = 4 if QUICK else 8
TASK = dict(n_around=10, n_along=12, n_modes=20, n_eig=10, repeat=1) if QUICK else \
    dict(n_around=16, n_along=30, n_modes=30, n_eig=10, repeat=2)


def children_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0


def main() -> int:
    tasks = [dict(TASK, speed=0.25 * i) for i in range(N_TASKS)]
    header("bench_parallel: operating points in parallel",
           model=f"{N_TASKS} tasks, each a tube {TASK['n_around']}x{TASK['n_along']} "
                 f"({6 * TASK['n_around'] * TASK['n_along']} DOF), {TASK['n_modes']} modes, "
                 f"solved {TASK['repeat']}x")
    rows = []

    def run(label, **kw):
        t0 = time.perf_counter()
        res = run_tasks(demo_point, tasks, **kw)
        wall = time.perf_counter() - t0
        ok = all(r.ok for r in res)
        rows.append(dict(case=label, wall=wall, task_sum=sum(r.elapsed for r in res), ok=ok,
                         res=res, rss_self=maxrss_mb(), rss_children=children_rss_mb()))
        print(f"  done: {label}: {wall:.2f} s", flush=True)

    run("serial, workers=1 [baseline]", workers=1)
    run("local pool, workers=2", workers=2)
    if "--no-dask" not in sys.argv:
        try:
            from distributed import LocalCluster

            t0 = time.perf_counter()
            with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster:
                t_start = time.perf_counter() - t0
                print(f"  LocalCluster start-up: {t_start:.2f} s (not included below)")
                run("dask LocalCluster, 2 workers", scheduler=cluster)
        except ImportError:
            print("  (dask.distributed not installed: Dask case skipped)")
    base = rows[0]
    for r in rows:
        r["speedup"] = base["wall"] / r["wall"]
        r["identical"] = all(np.array_equal(a.value["eigenvalues"], b.value["eigenvalues"])
                             for a, b in zip(base["res"], r["res"]))
    table(rows, ["case", "wall", "task_sum", "speedup", "identical", "ok", "rss_self",
                 "rss_children"])
    print("wall / task_sum in s (task_sum: time inside the tasks); speedup = serial wall / wall; "
          "rss_*: peak RSS (MB) of this process / of the largest finished child process")
    return 0 if all(r["identical"] and r["ok"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
