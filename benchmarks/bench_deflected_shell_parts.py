"""The two parts of a deflected shell point that the 19th session of issue 33 changed, each against its
baseline in the same run, on the NREL 5 MW shell blade at the default mesh (26k DOF, 4600 elements):

* **block solves** with the blade's CHOLMOD factor: kvxopt's sparse right-hand-side solve (the
  baseline, ``cholmod.spsolve``) against CHOLMOD's one-call dense block solve
  (``windflutter.fastlib.cholmod_block_solve``); 1, 40, 60 and 100 columns; the largest difference of
  the solutions (expected: none);
* **the deflected blade's assembly** on a carried mesh (10 m/s, 18 RPM): pyfe3d's elements computed
  again on the carried nodes (the baseline, ``deflected_shell_blade(..., reassemble=True)``) against
  the undeformed elements turned with their rotations (the default); the whole
  ``deflected_shell_blade`` call, and the two routes' assembled stiffness differing at the order of the
  strains (``docs/steady_state.md``, "Shell blades", item 2).

    python benchmarks/bench_deflected_shell_parts.py [--quick]
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import header, maxrss_mb, table  # noqa: E402


def _best(fn, repeat: int) -> tuple[object, float]:
    """``fn()``'s result and its best wall time of ``repeat`` calls (the machine's speed varies)."""
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best


def block_solves(rb, repeat: int) -> list[dict]:
    import numpy as np

    from windflutter.fastlib import cholmod_block_solve
    from windflutter.structure.linalg import SPDFactor

    K = rb.struct.Kr.tocsc()
    f = SPDFactor(K)
    if f.backend != "cholmod":
        print("CHOLMOD (kvxopt) not available: no block-solve rows")
        return []
    rng = np.random.default_rng(0)
    rows = []
    for k in (1, 40, 60, 100):
        B = rng.standard_normal((K.shape[0], k))
        base, t_base = _best(lambda B=B: np.array(f._matrix(f._cm.spsolve(f._F, f._sparse(f._matrix(B))))), repeat)
        new, t_new = _best(lambda B=B: cholmod_block_solve(f._F, B), repeat)
        rows.append(dict(case=f"block solve, {k} columns", dof=K.shape[0], baseline_s=t_base, new_s=t_new,
                         ratio=t_new / t_base, max_diff=float(np.abs(np.asarray(new).reshape(base.shape) - base).max())))
    return rows


def deflected_assembly(om, repeat: int) -> list[dict]:
    import numpy as np

    from windflutter.system.deflected_shell import deflected_shell_blade
    from windflutter.units import RPM

    V, rpm = 10.0, 18.0
    pitch = om.operating_point(V)[1]
    rb = om.blade(pitch)
    st = om.steady(rb, V, rpm * RPM)
    rb.shell_blocks()  # computed once per process in a run: not part of a point
    base, t_base = _best(lambda: deflected_shell_blade(rb, st, rpm * RPM, reassemble=True), repeat)
    new, t_new = _best(lambda: deflected_shell_blade(rb, st, rpm * RPM), repeat)
    Kb, Kn = base.blade.struct.K, new.blade.struct.K
    return [dict(case="deflected_shell_blade (10 m/s, 18 RPM)", dof=rb.fe.n_dof, baseline_s=t_base, new_s=t_new,
                 ratio=t_new / t_base, max_diff=float(abs(Kn - Kb).max() / abs(Kb).max()))]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="one repetition instead of three")
    args = ap.parse_args(argv)
    import windflutter
    from windflutter.operating import campbell_model

    header("bench_deflected_shell_parts: NREL 5 MW shell blade, default mesh")
    repeat = 1 if args.quick else 3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        om = campbell_model(windflutter.load_turbine("nrel5mw"), windflutter.analysis_config(model="shell"))
        rows = block_solves(om.blade(0.0), repeat) + deflected_assembly(om, repeat)
    table(rows, ["case", "dof", "baseline_s", "new_s", "ratio", "max_diff"])
    print("baseline: kvxopt's spsolve / pyfe3d's elements on the carried nodes; new: CHOLMOD's one-call block solve /"
          " the undeformed elements turned; max_diff: largest difference of the solutions (block solves) or of the"
          " stiffness entries relative to the largest (assembly: the two routes differ at the order of the strains)")
    print(f"peak RSS {maxrss_mb():.0f} MB; best of {repeat} calls each")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
