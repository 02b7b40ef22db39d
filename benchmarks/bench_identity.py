"""Mode identity (issue 32): what naming every mode by its structural participation costs.

The IEA 22 MW whole turbine at 23 wind speeds (``windflutter campbell iea22mw``'s analysis): the
whole Campbell, and inside it the time spent naming (``system.modes.identify_modes``: the point's
own blade modes, the participations, the assignment) and, once per model, the reference (the
blade's standstill modes and the support's).  Baseline measured in the same run: the same analysis
with the naming's time taken out (eigenvalues, mode shapes, signatures and tip amplitudes kept).
Target: the naming adds at most 15 %.

    python benchmarks/bench_identity.py [--quick] [--turbine iea22mw]
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import windflutter.system.modes as modes
import windflutter.system.operational as operational
from windflutter.api import analysis_config, load_turbine
from windflutter.operating import campbell_model, operating_campbell
from windflutter.system.campbell import default_wind_speeds
from windflutter.threads import blas_limit


def _timer(fn, box):
    def wrapped(*a, **k):
        t0 = time.perf_counter()
        try:
            return fn(*a, **k)
        finally:
            box[0] += time.perf_counter() - t0
    return wrapped


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--turbine", default="iea22mw")
    args = ap.parse_args(argv)
    quick = args.quick or os.environ.get("WINDFLUTTER_BENCH_QUICK") == "1"
    tb = load_turbine(args.turbine)
    winds = default_wind_speeds(tb)
    if len(winds) < 23:
        winds = np.linspace(winds[0], winds[-1], 23)
    if quick:
        winds = winds[:: max(1, len(winds) // 4)]
    cfg = analysis_config()
    naming, reference = [0.0], [0.0]
    modes.identify_modes = _timer(modes.identify_modes, naming)
    # timed where the model looks it up (patching it in its own module would not reach the model)
    operational.structural_reference = _timer(operational.structural_reference, reference)
    with blas_limit(1):
        t0 = time.perf_counter()
        om = campbell_model(tb, cfg)
        res = operating_campbell(tb, cfg, [float(v) for v in winds], model=om)
        total = time.perf_counter() - t0
    n_modes = sum(len(p.modes) for p in res.points)
    extra = naming[0] + reference[0]
    base = total - extra
    print(f"{args.turbine}: {len(winds)} wind speeds, {n_modes} modes named, one BLAS thread")
    print(f"  Campbell with identities  {total:7.2f} s")
    print(f"  of which naming           {naming[0]:7.2f} s  ({1e3 * naming[0] / max(n_modes, 1):.2f} ms per mode)")
    print(f"  of which reference        {reference[0]:7.2f} s  (once per model)")
    print(f"  baseline (without them)   {base:7.2f} s")
    print(f"  identity overhead         {100 * extra / base:6.1f} %   (target <= 15 %)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
