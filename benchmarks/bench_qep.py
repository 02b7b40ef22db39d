"""Full-order shift-invert QEP solve (20 eigenvalues) with each sparse LU of ``linsolve``.

Matrix: the synthetic clamped tube of ``benchmarks/testproblems.py::tube_qep`` (4-node quads,
6 DOF/node: the sparsity of a CQUAD4 shell model), 40 x 104 free nodes = 24,960 complex DOF
(``--quick``: 12 x 20 = 1,440), with Rayleigh damping, gyroscopic and complex element-local
aero-like coupling; shift ``i omega`` near the lowest structural frequencies, as in a p-k step.

Cases (each in its own forked process, BLAS limited to 1 thread; times in s; peak RSS of that
process):
1. the solver before this change: a bare ``scipy.sparse.linalg.splu(Q)`` (COLAMD) and ARPACK's
   random start vector -- the baseline, re-implemented here;
2. ``qep.solve_qep_sparse`` with ``lu_backend="superlu"``, ``lu_ordering="COLAMD"``;
3. the same with SuperLU's symmetric mode (``lu_ordering="symmetric"``);
4. ``lu_backend="umfpack"`` (kvxopt), if installed;
5. case 2 or 4 run twice in one process: the second solve reuses the symbolic analysis;
6. warm start (``--warm``): operator applications (= LU solves, independent of the load) of a
   solve at shift ``i w (1 + d)`` from the fixed start vector vs from
   ``qep.warm_start_vector`` of the solve at ``i w``, on a 20 x 40 tube (4,800 DOF).
Each prints the time, the ratio to case 1 of the same run, the worst relative eigenvalue
difference to case 1 over the 20 eigenvalues, and the load average.
Usage: python benchmarks/bench_qep.py [--quick]
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, isolated, table  # noqa: E402

from windflutter.solve.linsolve import available_backends  # noqa: E402
from testproblems import tube_qep  # noqa: E402

SIZE = (12, 20) if QUICK else (40, 104)
N_EIG = 20
SHIFT = 0.8j


def _problem():
    p = tube_qep(*SIZE, coupling=0.02, gyro=0.05, seed=0)
    return p.M, p.D, p.K


def _baseline(M, D, K):
    """The committed solver before issue 7: bare splu, ARPACK's default start vector."""
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    n = K.shape[0]
    s = SHIFT
    Q = sp.csc_matrix((s * s) * M + s * D + K, dtype=complex)
    lu = spla.splu(Q)
    DsM, Mr = (D + s * M).tocsr(), M.tocsr()

    def mv(z):
        z = np.asarray(z).ravel()
        y1 = -lu.solve(Mr @ z[n:] + DsM @ z[:n])
        return np.concatenate([y1, z[:n] + s * y1])

    op = spla.LinearOperator((2 * n, 2 * n), matvec=mv, dtype=complex)
    nu, _ = spla.eigs(op, k=N_EIG, which="LM")
    lam = s + 1.0 / nu
    return lam[np.argsort(np.abs(lam - s))]


def case(kind: str, backend: str = "", ordering: str = "", repeat: int = 1) -> dict:
    M, D, K = _problem()
    from windflutter.solve import qep

    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        if kind == "baseline":
            lam = _baseline(M, D, K)
        else:
            lam = qep.solve_qep_sparse(M, D, K, shift=SHIFT, n_eig=N_EIG, lu_backend=backend,
                                       lu_ordering=ordering).values
        times.append(time.perf_counter() - t0)
    return dict(n=K.shape[0], nnz=K.nnz, t=times[0], t_again=times[-1] if repeat > 1 else float("nan"),
                lam=lam)


def warm_start_counts() -> None:
    import scipy.sparse.linalg as spla

    from windflutter.solve import qep

    p = tube_qep(20, 40, coupling=0.02 * (8 / 40) ** 2, gyro=0.05, seed=0)
    M, D, K = p.M, p.D, p.K
    eigs, count = spla.eigs, [0]

    def counting_eigs(op, **kw):  # this process only: count the operator applications
        def mv(x):
            count[0] += 1
            return op.matvec(x)
        return eigs(spla.LinearOperator(op.shape, matvec=mv, dtype=op.dtype), **kw)

    qep.spla.eigs = counting_eigs
    try:
        w = 0.8
        e0 = qep.solve_qep_sparse(M, D, K, shift=1j * w, n_eig=N_EIG)
        print(f"warm start, {K.shape[0]} DOF, {N_EIG} eigenvalues near i*{w}:")
        for d in (0.001, 0.01, 0.05):
            s = 1j * w * (1 + d)
            count[0] = 0
            cold = qep.solve_qep_sparse(M, D, K, shift=s, n_eig=N_EIG)
            n_cold = count[0]
            count[0] = 0
            warm = qep.solve_qep_sparse(M, D, K, shift=s, n_eig=N_EIG, v0=qep.warm_start_vector(e0))
            diff = np.max(np.abs(np.sort_complex(cold.values) - np.sort_complex(warm.values)) / np.abs(cold.values))
            print(f"  step {d:.1%}: fixed v0 {n_cold} applications, warm {count[0]} "
                  f"({count[0] / n_cold:.2f}); max rel. eigenvalue difference {diff:.1e}")
    finally:
        qep.spla.eigs = eigs


def main() -> int:
    if "--warm" in sys.argv:
        warm_start_counts()
        return 0
    header("bench_qep: 20 eigenvalues of a complex shell-like QEP, full order, LU backends",
           size=SIZE, shift=SHIFT)
    cases = [("bare splu COLAMD + random v0 (before) [baseline]", ("baseline",)),
             ("solve_qep_sparse, superlu COLAMD", ("qep", "superlu", "COLAMD", 2)),
             ("solve_qep_sparse, superlu symmetric", ("qep", "superlu", "symmetric"))]
    if "umfpack" in available_backends():
        cases.append(("solve_qep_sparse, umfpack (kvxopt)", ("qep", "umfpack", "auto", 2)))
    rows = []
    for label, args in cases:
        load = os.getloadavg()[0]
        out, wall, rss = isolated(case, *args)
        rows.append(dict(case=label, n_dof=out["n"], t=out["t"], t_again=out["t_again"], rss=rss,
                         load=load, lam=out["lam"]))
        print(f"  {label}: {out['t']:.2f} s (load {load:.1f})", flush=True)
    base = rows[0]
    ok = True
    for r in rows:
        r["ratio"] = r["t"] / base["t"]
        err = np.abs(np.sort_complex(r["lam"]) - np.sort_complex(base["lam"])) / np.abs(base["lam"])
        r["max_rel_diff"] = float(err.max())
        ok &= r["max_rel_diff"] < 1e-8
    table(rows, ["case", "n_dof", "t", "t_again", "ratio", "max_rel_diff", "rss", "load"])
    print("t: first solve (s); t_again: a second solve in the same process (symbolic reuse); "
          "ratio: t / baseline t; rss: peak RSS of the case's process (MB); load: 1-min load "
          "average when the case started")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
