"""The issue-7 targets on the bundled NREL 5 MW turbine, measured on this machine.

Targets (2 cores): shell model (>= 26k DOF) built and assembled < 10 s; one coupled 20-mode
eigen-solve < 2 s; the full map (12 wind speeds, potential + viscous) < 60 s with reduction;
peak memory < 4 GB; 1 vs 2 workers.

Cases, each in its own forked process (BLAS 1 thread; peak RSS = that process's):
A. beam model build + assemble [baseline of B];
B. the seed-size shell model (MeshSettings(model="shell", **SEED_MESH): 40 x 30 skin quads per blade,
   3-element webs, 20 x 22 tower shells; the default until Dec 2026) build + assemble;
C. shell, full order (``reduction="none"``): one coupled eigen-solve, 20 eigenvalues nearest
   i*omega at V = 10 m/s, 12.1 RPM (sparse shift-invert Arnoldi) [baseline of D];
D. shell, reduced (``reduction="mta"``, 30 modes per reference speed, the ``windflutter run``
   default): one-off basis, then the same 20-eigenvalue solve (dense companion of the basis);
E0. one map point (10 m/s, potential), beam model with the ``windflutter run`` defaults but
   the former p-k tracking: Arnoldi eigen-solves only (``NEWTON_LIMIT = 0``), no clusters of
   near-repeated roots (``CLUSTER_REL = 0``), the whole rotor-speed grid [baseline of E];
E. the same point with the defaults (Newton refinement, clusters, sweep stopped past the onsets);
G. the full map of the issue: 12 wind speeds x potential + viscous = 24 points, ``windflutter
   run`` defaults (beam, mta, 2-40 RPM in 20 points, 0.01 RPM), no plots, serial [baseline of H];
H. the same map on 2 local workers (``windflutter.workflow.run(workers=2)``).
Every case prints the 1-min load average when it started (the machine is shared).
Usage: python benchmarks/bench_targets.py [--quick] [--only A,B,C,D,E0,E,G,H]
``--quick``: a coarse shell (12 x 10 skin quads, 1-element webs, 8 x 6 tower) for B-D.
"""

from __future__ import annotations

import math
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, isolated, maxrss_mb, table  # noqa: E402
from windflutter.mesh.settings import SEED_MESH  # noqa: E402

RPM = math.pi / 30
V_SOLVE, RPM_SOLVE, F_SOLVE_HZ = 10.0, 12.1, 0.7   # operating point and shift of the single solve
SHELL_MESH = dict(n_chord=12, n_span=10, n_web=1, n_tower_circ=8, n_tower_axial=6) if QUICK else dict(SEED_MESH)


def _turbine():
    from windflutter.model import load_turbine

    return load_turbine("nrel5mw")


def case_build(model: str) -> dict:
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model
    from windflutter.structure.assembly import assemble

    tb = _turbine()
    t0 = time.perf_counter()
    fe, sections = build_model(tb, MeshSettings(model=model, **(SHELL_MESH if model == "shell" else {})))
    t_build = time.perf_counter() - t0
    t0 = time.perf_counter()
    st = assemble(fe)
    t_asm = time.perf_counter() - t0
    return dict(n_dof=6 * len(fe.nodes), nq=int(st.T.shape[1]), t_build=t_build, t_asm=t_asm,
                t=t_build + t_asm, nnz_K=int(st.K.nnz) if hasattr(st, "K") else -1)


def case_solve(reduction: str) -> dict:
    import windflutter.frozen.turbine as tmod
    from windflutter.solve import qep

    tb = _turbine()
    ts = tmod.TurbineStability(tb, tmod.TurbineOptions(model="shell", reduction=reduction, basis_modes=30,
                                                       mesh=SHELL_MESH, max_rpm=40.0))
    t0 = time.perf_counter()
    fe, sections, am = ts.model(0.0)
    t_model = time.perf_counter() - t0
    sys_ = am.at(V_SOLVE, RPM_SOLVE * RPM)
    w = 2 * math.pi * F_SOLVE_HZ
    t0 = time.perf_counter()
    M, D, K = sys_.matrices(w)
    t_mat = time.perf_counter() - t0
    t0 = time.perf_counter()
    e = qep.solve_qep(M, D, K, shift=1j * w, n_eig=20)
    t_solve = time.perf_counter() - t0
    return dict(n_dof=6 * len(fe.nodes), nq=int(am.size), t_model=t_model, t_mat=t_mat, t=t_solve,
                lam=np.sort_complex(e.values))


class _Counter:
    """Wraps ``qep.solve_qep`` in this (benchmark) process to count the eigen-solves."""

    def __init__(self, fn):
        self.fn, self.n, self.t = fn, 0, 0.0

    def __call__(self, *a, **kw):
        t0 = time.perf_counter()
        try:
            return self.fn(*a, **kw)
        finally:
            self.n += 1
            self.t += time.perf_counter() - t0


#: the 12 wind speeds of the map (m/s): cut-in to cut-out, denser around rated (11.4 m/s)
MAP12 = [3.0, 5.0, 7.0, 9.0, 11.0, 12.0, 13.0, 15.0, 17.0, 19.0, 21.0, 25.0]


def case_map(workers: int, winds=None, aero=("potential", "viscous"), former: bool = False) -> dict:
    import windflutter.frozen.search as search
    from windflutter.config import load_config
    from windflutter.workflow import run

    over = {"wind_speeds": list(winds or MAP12), "aero": list(aero),
            "output": {"plots": False, "report": False, "animations": False, "mode_shapes": False}}
    if former:  # this forked child only
        search.NEWTON_LIMIT, search.CLUSTER_REL = 0, 0.0
        over["rotor_speed"] = {"full_sweep": True}
    cfg = load_config(None, over)
    counter = None
    if workers == 1:
        counter = search.solve_qep = _Counter(search.solve_qep)  # this forked child only
    tb = _turbine()
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        ds = run(tb, cfg, tmp, progress=False, workers=workers)
        wall = time.perf_counter() - t0
    out = dict(n_points=int(ds.sizes["point"]), t=wall, status=list(map(str, ds["status"].values)),
               onsets=[float(x) for x in np.r_[ds["flutter_rpm"].values, ds["divergence_rpm"].values]],
               n_dof=int(ds.attrs.get("n_dof", -1)), nq=int(ds.attrs.get("n_reduced_dof", -1)),
               point_elapsed=[round(float(x), 2) for x in ds["elapsed"].values])
    if counter is not None:
        out.update(n_arnoldi_solves=counter.n, t_arnoldi_solves=counter.t)
    return out


CASES = {
    "A": ("beam build + assemble [baseline of B]", case_build, ("beam",)),
    "B": ("shell build + assemble", case_build, ("shell",)),
    "C": ("shell full order, one 20-eig solve [baseline of D]", case_solve, ("none",)),
    "D": ("shell reduced (mta, 30 modes), one 20-eig solve", case_solve, ("mta",)),
    "E0": ("one map point, former p-k (Arnoldi only, no clusters, whole grid) [baseline of E]", case_map,
           (1, [10.0], ("potential",), True)),
    "E": ("the same point, default p-k", case_map, (1, [10.0], ("potential",))),
    "G": ("full map 12 winds x 2 aero, run defaults, serial [baseline of H]", case_map, (1,)),
    "H": ("the same map on 2 local workers", case_map, (2,)),
}
BASELINE = {"B": "A", "D": "C", "E": "E0", "H": "G"}


def main() -> int:
    only = None
    if "--only" in sys.argv:
        only = sys.argv[sys.argv.index("--only") + 1].split(",")
    header("bench_targets: issue-7 targets on the NREL 5 MW", shell_mesh=SHELL_MESH or "default",
           solve=f"V={V_SOLVE} m/s, {RPM_SOLVE} RPM, shift i*2pi*{F_SOLVE_HZ} Hz, 20 eigenvalues",
           map_winds=MAP12)
    rows = {}
    for key, (label, fn, args) in CASES.items():
        if only and key not in only:
            continue
        load = os.getloadavg()
        try:
            out, wall, rss = isolated(fn, *args)
        except RuntimeError as exc:
            print(f"  {key} {label}: FAILED\n{exc}", flush=True)
            continue
        out.update(case=f"{key}. {label}", rss=rss, load=f"{load[0]:.1f}/{load[1]:.1f}")
        rows[key] = out
        extra = {k: v for k, v in out.items() if k not in ("lam", "case")}
        print(f"  {key} {label}: {extra}", flush=True)
    for key, base in BASELINE.items():
        if key in rows and base in rows:
            rows[key]["ratio"] = rows[key]["t"] / rows[base]["t"]
    if "C" in rows and "D" in rows:
        a, b = rows["C"]["lam"], rows["D"]["lam"]
        print("  D vs C eigenvalues (sorted):")
        for x, y in zip(a, b):
            print(f"    full {x:.5f}   reduced {y:.5f}")
    if "G" in rows and "H" in rows:
        same = np.array_equal(rows["G"]["onsets"], rows["H"]["onsets"], equal_nan=True)
        print(f"  H onsets identical to G: {same}")
    if "E0" in rows and "E" in rows:
        d = np.max(np.abs(np.subtract(rows["E"]["onsets"], rows["E0"]["onsets"])))
        print(f"  E onsets vs E0: largest difference {d:.2e} RPM (tolerance 0.01 RPM)")
    table(list(rows.values()), ["case", "n_dof", "nq", "t", "ratio", "rss", "load"])
    print("t: the timed step (s) -- B: build + assemble; C, D: one eigen-solve (model set-up in "
          "t_model above); E0, E, G, H: wall time of the run; rss: peak RSS of the case's process (MB); "
          f"load: 1/5-min load average at the start; parent rss {maxrss_mb():.0f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
