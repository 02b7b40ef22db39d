"""Sparse LU backends on a complex shell-like system: SuperLU (baseline) vs kvxopt UMFPACK.

The matrix is Q(s) = s^2 M + s D + K of the synthetic clamped tube of
``benchmarks/testproblems.py::tube_qep`` (4-node quads, 6 DOF/node: the sparsity of a CQUAD4
shell model) with complex element-local aero-like coupling, at a shift s near a structural
frequency. Full size: 40 x 104 free nodes = 24,960 DOF (the thesis's NREL 5 MW model has
26,136). ``--quick``: 3,600 DOF.

Each case runs in its own forked process so its peak RSS is its own. Ratios are to the first
case (SciPy splu defaults), measured in the same run.
Usage: python benchmarks/bench_linsolve.py [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, isolated, table  # noqa: E402

from windflutter.solve.linsolve import Factorizer, available_backends  # noqa: E402
from testproblems import tube_qep  # noqa: E402

N_SOLVES = 60  # a shift-invert Arnoldi run for 20 eigenvalues applies the inverse ~40-120 times


def build(n_around, n_along):
    p = tube_qep(n_around, n_along, seed=1)
    s = 0.01 + 0.8j
    Q = (s * s * p.M + s * p.D + p.K).tocsc()
    return Q


CASES = [
    # (label, backend, ordering, blas_threads); the first is the baseline: SciPy's splu defaults
    # as the QEP solver of issue 5 calls it (COLAMD, library-default BLAS threads)
    ("superlu COLAMD, default BLAS threads", "superlu", "COLAMD", None),
    ("superlu COLAMD, 1 BLAS thread", "superlu", "COLAMD", 1),
    ("superlu symmetric, 1 BLAS thread [default]", "superlu", "symmetric", 1),
    ("umfpack (kvxopt)", "umfpack", "auto", 1),
]


def case(backend: str, ordering: str, blas_threads, n_around: int, n_along: int) -> dict:
    Q = build(n_around, n_along)
    rng = np.random.default_rng(0)
    b = rng.standard_normal(Q.shape[0]) + 1j * rng.standard_normal(Q.shape[0])
    fz = Factorizer(backend, ordering=ordering, blas_threads=blas_threads)
    t0 = time.perf_counter()
    f = fz.factorize(Q)
    t_fact = time.perf_counter() - t0
    t0 = time.perf_counter()
    x = f.solve(b)
    t_solve1 = time.perf_counter() - t0
    t0 = time.perf_counter()
    for _ in range(N_SOLVES):
        f.solve(b)
    t_solves = time.perf_counter() - t0
    # refactorization of a new matrix with the same pattern (next shift / k / rotor speed)
    Q2 = (Q * (1.0 + 0.01j)).tocsc()
    t0 = time.perf_counter()
    fz.factorize(Q2)
    t_refact = time.perf_counter() - t0
    lu_nnz = (f._lu.L.nnz + f._lu.U.nnz) if backend == "superlu" else ""
    res = float(np.linalg.norm(Q @ x - b) / np.linalg.norm(b))
    return dict(t_fact=t_fact, t_refact=t_refact, t_solve=t_solve1,
                t_arnoldi=t_fact + t_solves, residual=res, lu_nnz=lu_nnz, x=x)


def main() -> int:
    na, nl = (20, 30) if QUICK else (40, 104)
    Q = build(na, nl)
    header("bench_linsolve: complex sparse LU", model=f"tube {na}x{nl}: n = {Q.shape[0]} DOF, "
           f"nnz(Q) = {Q.nnz}", backends=available_backends(),
           note=f"t_arnoldi = factor + {N_SOLVES} solves (typical shift-invert Arnoldi use)")
    del Q
    rows = []
    for label, be, ordering, threads in CASES:
        if be not in available_backends():
            print(f"(skipping {label}: not installed)")
            continue
        r, wall, rss = isolated(case, be, ordering, threads, na, nl, blas_threads=threads)
        r["case"] = label
        r["peak_rss_MB"] = rss
        rows.append(r)
        print(f"  done: {label}: factor {r['t_fact']:.2f} s", flush=True)
    base = rows[0]
    for r in rows:
        r["fact_ratio"] = r["t_fact"] / base["t_fact"]
        r["arnoldi_ratio"] = r["t_arnoldi"] / base["t_arnoldi"]
        r["rel_diff_x"] = float(np.linalg.norm(r["x"] - base["x"]) / np.linalg.norm(base["x"]))
    table(rows, ["case", "t_fact", "t_refact", "t_solve", "t_arnoldi", "fact_ratio",
                 "arnoldi_ratio", "lu_nnz", "residual", "rel_diff_x", "peak_rss_MB"])
    print("times in s; t_refact: same pattern, new values (UMFPACK reuses its symbolic analysis); "
          "rel_diff_x: |x - x_superlu| / |x_superlu|")
    if len(rows) > 1:
        worst = max(r["rel_diff_x"] for r in rows)
        print(f"backends agree to {worst:.1e} (relative)")
        if worst > 1e-8:
            print("WARNING: backends disagree beyond round-off")
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
