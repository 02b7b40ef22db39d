"""Design sensitivities (issue 31): the cost of all sensitivities of one operating point.

Target: all sensitivities of one point (every mode up to the Campbell's frequency limit; the eight
blade properties at every element of the blade and the four global parameters) cost at most 2x the
Campbell at that point (the point system and its named modes).  Baseline measured in the same run:
the finite-difference re-analyses the sensitivities replace -- two re-analyses per parameter (one
blade property over one element; the cost per element x the number of elements and properties,
plus the global parameters), extrapolated from a measured few.  Also timed: the total derivatives of
the whole-blade and global parameters and of the blade properties per r/R segment (the steady state's own sensitivity
included, windflutter.sensitivity.steady).

    python benchmarks/bench_sensitivity.py [--quick] [--turbine nrel5mw] [--wind 15]
"""

from __future__ import annotations

import argparse
import os
import time

from windflutter.config import config_from_dict
from windflutter.model import load_turbine
from windflutter.operating import campbell_model
from windflutter.sensitivity import finite_difference as fd
from windflutter.sensitivity.parameters import BLADE_PROPERTIES, GLOBAL_PARAMETERS
from windflutter.system.modes import state_eig
from windflutter.sensitivity.point import point_sensitivities
from windflutter.sensitivity.results import SEGMENTS
from windflutter.sensitivity.steady import HELD_EXACTLY, point_totals, segment_totals
from windflutter.solve.linsolve import blas_limit
from windflutter.system.modes import point_modes


def best(fn, repeat: int):
    """(result, the fastest of ``repeat`` wall times in s)."""
    out, dt = None, float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        dt = min(dt, time.perf_counter() - t0)
    return out, dt


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--turbine", default="nrel5mw")
    ap.add_argument("--wind", type=float, default=15.0)
    args = ap.parse_args(argv)
    quick = args.quick or os.environ.get("WINDFLUTTER_BENCH_QUICK") == "1"
    repeat = 1 if quick else 3
    tb = load_turbine(args.turbine)
    with blas_limit(1):
        om = campbell_model(tb, config_from_dict({}))
        max_hz = om.reference().default_max_hz()
        om.at(args.wind)  # warm: the model's parts (blade, support, identities) are built once per turbine

        def campbell_point():  # its one eigen-solve with left vectors, shared with the sensitivities
            ps = om.at(args.wind)
            eig = state_eig(ps.mbc)
            return ps, eig, point_modes(ps, max_hz, eig=eig)

        (ps, eig, modes), t_point = best(campbell_point, repeat)
        models = {}
        point_sensitivities(om, ps, modes, models=models, eig=eig)  # warm: the changed turbines' supports, per run
        res, t_sens = best(lambda: point_sensitivities(om, ps, modes, models=models, eig=eig), repeat)
        n_el = len(res.station)
        n_par = len(BLADE_PROPERTIES) * n_el + len(GLOBAL_PARAMETERS)
        totals, t_total = best(lambda: point_totals(om, ps, res), 1)
        n_tot = len([n for n in totals if n not in HELD_EXACTLY])
        segs, t_seg = best(lambda: segment_totals(om, ps, res, SEGMENTS), 1)
        _, t_fd = best(lambda: fd.frozen_blade(om, ps, res.names, "edge_stiffness", 1e-3, [n_el // 2], max_hz), 1)
        print(f"{args.turbine} at {args.wind:g} m/s: {len(modes)} modes up to {max_hz:.2f} Hz, "
              f"{ps.mbc.M.shape[0]} DOF + {ps.mbc.A.shape[0]} aero states, {n_el} blade elements")
        print(f"  Campbell point (point system + named modes): {t_point:.2f} s")
        print(f"  all sensitivities ({len(BLADE_PROPERTIES)} blade properties x {n_el} elements + "
              f"{len(GLOBAL_PARAMETERS)} global = {n_par} parameters): {t_sens:.2f} s "
              f"= {t_sens / t_point:.2f}x the Campbell point")
        print(f"  total derivatives (the steady state's own change; {n_tot} whole-blade and global parameters, "
              f"{len(totals) - n_tot} equal to the held ones): {t_total:.2f} s = {t_total / t_point:.2f}x the "
              f"Campbell point, {t_total / max(n_tot, 1):.2f} s per parameter")
        print(f"  total derivatives per r/R segment ({len(segs)} blade properties x {len(SEGMENTS) - 1} segments): "
              f"{t_seg:.2f} s = {t_seg / t_point:.2f}x the Campbell point")
        print(f"  baseline: finite differences, {t_fd:.2f} s per parameter (two re-analyses) -> "
              f"{t_fd * n_par:.0f} s for all ({t_fd * n_par / t_sens:.0f}x the sensitivities)")
        both, every = (t_sens + t_total) / t_point, (t_sens + t_total + t_seg) / t_point
        print(f"  target: sensitivities <= 2x the Campbell point -> steady state held: "
              f"{'met' if t_sens <= 2 * t_point else 'NOT met'}; with the whole-blade and global totals "
              f"({both:.2f}x): {'met' if both <= 2 else 'NOT met'}; with the segment totals too ({every:.2f}x): "
              f"{'met' if every <= 2 else 'NOT met'}")
        print(f"  machine load (1-min average) {os.getloadavg()[0]:.2f} on {os.cpu_count()} CPUs")


if __name__ == "__main__":
    main()
