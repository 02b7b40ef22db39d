"""Shared helpers for windflutter benchmarks: timing, peak memory, isolated runs, tables.

Peak memory is measured two ways:
* ``tracemalloc`` peak: Python-level and NumPy allocations only (NumPy reports to tracemalloc),
  NOT the C allocations inside SuperLU / UMFPACK / ARPACK;
* ``ru_maxrss`` of a forked child that runs only the measured case: the whole process peak
  (includes the interpreter and imported libraries, ~100-200 MB), the honest number for the
  "< 4 GB" target.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import platform
import resource
import sys
import time
import traceback
import tracemalloc
from typing import Any, Callable

QUICK = os.environ.get("WINDFLUTTER_BENCH_QUICK", "") not in ("", "0") or "--quick" in sys.argv


def maxrss_mb() -> float:
    """Peak resident set size of this process so far (MB; Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def timed(fn: Callable, *args, **kw) -> tuple[Any, float, float]:
    """Run ``fn`` once: (result, wall seconds, tracemalloc peak MB)."""
    tracemalloc.start()
    t0 = time.perf_counter()
    try:
        out = fn(*args, **kw)
    finally:
        dt = time.perf_counter() - t0
        _, peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    return out, dt, peak / 2**20


def _child(conn, fn, args, kw, blas_threads):
    try:
        if blas_threads is not None:
            from threadpoolctl import threadpool_limits

            threadpool_limits(limits=blas_threads, user_api="blas")
        t0 = time.perf_counter()
        out = fn(*args, **kw)
        dt = time.perf_counter() - t0
        conn.send(("ok", out, dt, maxrss_mb()))
    except BaseException:  # noqa: BLE001
        conn.send(("error", traceback.format_exc(), 0.0, maxrss_mb()))
    finally:
        conn.close()


def isolated(fn: Callable, *args, blas_threads: int | None = 1, **kw) -> tuple[Any, float, float]:
    """Run ``fn`` in a forked child: (result, wall seconds, child's peak RSS MB).

    ``blas_threads``: BLAS thread limit in the child (default 1: on a shared or busy machine
    multi-threaded OpenBLAS makes timings erratic by 10-50x, see docs/performance.md; ``None``
    keeps the library default). The result must be picklable.
    """
    try:
        ctx = mp.get_context("fork")
    except ValueError:  # pragma: no cover
        out, dt, _ = timed(fn, *args, **kw)
        return out, dt, maxrss_mb()
    a, b = ctx.Pipe(duplex=False)
    p = ctx.Process(target=_child, args=(b, fn, args, kw, blas_threads))
    p.start()
    b.close()
    status, out, dt, rss = a.recv()
    p.join()
    if status != "ok":
        raise RuntimeError(f"benchmark case failed in child:\n{out}")
    return out, dt, rss


def header(title: str, **info) -> None:
    print(f"\n=== {title} ===")
    print(f"python {platform.python_version()}, {os.cpu_count()} cores "
          f"(usable {len(os.sched_getaffinity(0))}), load avg {os.getloadavg()[0]:.2f}"
          + (", QUICK mode" if QUICK else ""))
    print(machine_speed())
    for k, v in info.items():
        print(f"{k}: {v}")


def machine_speed() -> str:
    """This machine's speed in two numbers that the project's time splits between: the interpreter
    (a fixed pure-Python loop) and dense BLAS on one thread (a 1000 x 1000 product), so that times
    measured in different sessions -- on machines that differ by up to 1.8x -- can be compared
    (performance_rounds.md section 25).  About 0.5 s."""
    import numpy as np

    from windflutter.threads import blas_limit

    t0 = time.perf_counter()
    s = 0
    for i in range(2_000_000):
        s += i * i
    loop = time.perf_counter() - t0
    a = np.random.default_rng(0).standard_normal((1000, 1000))
    with blas_limit(1):
        a @ a
        t0 = time.perf_counter()
        for _ in range(3):
            a @ a
        gemm = time.perf_counter() - t0
    return (f"machine: Python loop {1e3 * loop:.0f} ms (2e6 iterations), one-thread dgemm "
            f"{3 * 2e9 / gemm / 1e9:.0f} GFLOP/s, CPU {_cpu_model()}")


def _cpu_model() -> str:
    try:
        with open("/proc/cpuinfo") as fh:
            first = fh.read().split("\n\n")[0]
        info = {k.strip(): v.strip() for k, _, v in (line.partition(":") for line in first.splitlines())}
        return f"{info['model name']} (family {info['cpu family']} model {info['model']})"
    except (OSError, KeyError):
        return platform.processor() or "?"


def table(rows: list[dict], cols: list[str]) -> None:
    """Print rows as an aligned text table (floats with 3 significant digits)."""
    def fmt(v):
        if isinstance(v, float):
            return f"{v:.3g}"
        return str(v)

    cells = [[fmt(r.get(c, "")) for c in cols] for r in rows]
    w = [max(len(c), *(len(x[i]) for x in cells)) for i, c in enumerate(cols)]
    print("  ".join(c.ljust(w[i]) for i, c in enumerate(cols)))
    print("  ".join("-" * w[i] for i in range(len(cols))))
    for x in cells:
        print("  ".join(x[i].ljust(w[i]) for i in range(len(cols))))


def nrel5mw_solver(model: str, **config):
    """Method p's stability solver of the bundled NREL 5 MW (``model`` beam or shell) with the config
    sections ``config`` changed (``windflutter.analysis_config`` keywords), for :func:`map_rows`."""
    import windflutter
    from windflutter import methods

    t = windflutter.load_turbine("nrel5mw")
    cfg = windflutter.analysis_config(model=model, **config)
    return methods.stability_analysis(t, cfg, cfg.aero[0], "p")


def map_rows(solver, winds, **label) -> list[dict]:
    """Method p's onsets (``solver.analyse_operating_point``) at each wind speed of ``winds``, with
    the CPU and wall time of each and the full operating points it evaluated (``OperationalModel.at``
    counted: sweep points, refined steps' middles, root-search trials); ``label``: columns added to
    every row.  Meant for a benchmark case's child process (:func:`isolated`): the count patches
    ``OperationalModel.at`` for the rest of the process."""
    import warnings

    from windflutter.system import operational

    count = {"n": 0}
    orig = operational.OperationalModel.at

    def at(self, *a, **k):
        count["n"] += 1
        return orig(self, *a, **k)

    operational.OperationalModel.at = at
    rows = []
    for V in winds:
        count["n"] = 0
        c0, t0 = time.process_time(), time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            p = solver.analyse_operating_point(V)
        rows.append(dict(**label, wind=V, cpu=time.process_time() - c0, wall=time.perf_counter() - t0,
                         evaluations=count["n"], end=float(max(p.sweep_rpm)), flutter=p.flutter_rpm,
                         mode=p.flutter_mode, freq=p.flutter_frequency_hz, divergence=p.divergence_rpm))
    return rows


def pair_table(base: list[dict], new: list[dict], cols: list[str]) -> tuple[float, float]:
    """Print the :func:`map_rows` of a baseline and a new case side by side, wind speed by wind speed
    (onsets to 1e-4 RPM); returns their CPU sums ``(new, base)``."""
    exact = ("flutter", "divergence")
    table([{k: (f"{v:.4f}" if k in exact and v is not None else v) for k, v in r.items()} for pair in zip(base, new)
           for r in pair], cols)
    return sum(r["cpu"] for r in new), sum(r["cpu"] for r in base)


def map_arguments(argv, doc: str, winds: list[float]) -> tuple[str, list[float]]:
    """``(model, wind speeds)`` of a map benchmark's command line: ``--wind V ...`` (default ``winds``)
    and ``--beam`` (the beam model instead of the shell)."""
    import argparse

    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--wind", type=float, nargs="+", default=list(winds))
    ap.add_argument("--beam", action="store_true", help="the beam model instead of the shell")
    args = ap.parse_args(argv)
    return ("beam" if args.beam else "shell"), args.wind
