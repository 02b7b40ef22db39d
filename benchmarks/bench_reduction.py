"""Full-order vs modally reduced eigen-solve of a complex shell-like QEP.

Model: the synthetic clamped tube of ``benchmarks/testproblems.py::tube_qep`` (40 x 104
free nodes = 24,960 DOF, ``--quick``: 12 x 20 = 1,440 DOF) with Rayleigh damping, gyroscopic
coupling and complex element-local aero-like coupling.

Cases (each in its own forked process with BLAS limited to 1 thread -- see bench_linsolve.py for
what multi-threaded BLAS does on a busy machine; times in s, peak RSS of that process):
1. full order, ``windflutter.solve.qep.solve_qep_sparse`` with ``lu_ordering="COLAMD"`` (the
   ordering of SciPy's ``splu`` defaults, used before issue 7) -- the baseline; 20 eigenvalues
   nearest the shift 0 (smallest modulus, as the thesis);
2. the same solver with its default LU (``linsolve`` SuperLU symmetric mode, 1 BLAS thread);
3. reduced: 40 structural modes (one-off: shift-invert Lanczos) + projection + dense 2m
   companion eigen-solve (the per-point cost);
4. reduced with static-correction (MTA) vectors for the coupling loads.
Accuracy: worst relative eigenvalue difference to case 1 over the 10 smallest-modulus
eigenvalues.
Usage: python benchmarks/bench_reduction.py [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, isolated, table  # noqa: E402


from windflutter.solve import reduction as R  # noqa: E402
from testproblems import tube_qep  # noqa: E402

N_EIG = 20
N_CMP = 10
SIZE = (12, 20) if QUICK else (40, 104)


# The coupling of tube_qep is element-local and does not soften with the tube's length, while the
# lowest structural stiffness falls ~ 1/length^2 (the tests' 8-ring tube: 0.02). Scaling it by
# (8 / n_along)^2 keeps the coupling a perturbation of the lowest modes of the same relative size
# as in the tests, as aerodynamics is for a blade's lowest modes; unscaled, the 104-ring tube's
# lowest eigenvalues are coupling-dominated and no structural basis captures them (measured:
# 25-30 % error with 20-40 modes, with or without MTA vectors).
COUPLING = 0.02 * (8.0 / SIZE[1]) ** 2


def _problem():
    return tube_qep(*SIZE, coupling=COUPLING, gyro=0.05, seed=0)


def _full_eigs(M, D, K, fast_lu: bool):
    from windflutter.solve import qep

    # the LU ordering before issue 7 (COLAMD) vs the default now (SuperLU symmetric mode)
    return qep.solve_qep_sparse(M, D, K, shift=0.0, n_eig=N_EIG,
                                lu_ordering=None if fast_lu else "COLAMD").values


def case_full(fast_lu: bool) -> dict:
    p = _problem()
    M, D, K = p.M, p.D, p.K
    t0 = time.perf_counter()
    lam = _full_eigs(M, D, K, fast_lu)
    return dict(t_oneoff=0.0, t_point=time.perf_counter() - t0, m="", lam=lam)


def case_reduced(n_modes: int, mta: bool) -> dict:
    p = _problem()
    M, D, K = p.M, p.D, p.K
    t0 = time.perf_counter()
    b = R.structural_modes(p.Ms, p.Ks, n_modes)
    if mta:
        b = R.augment(b, p.Ks, p.Ms, np.hstack([p.Ka @ b.Phi, p.Da @ b.Phi]))
    t_oneoff = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = R.reduce_qep(M, D, K, b.Phi)
    lam, Y = R.solve_dense_qep(r.Mr, r.Dr, r.Kr, N_EIG)
    R.expand(b.Phi, Y)
    return dict(t_oneoff=t_oneoff, t_point=time.perf_counter() - t0, m=b.m, lam=lam)


def main() -> int:
    p = _problem()
    header("bench_reduction: full-order vs reduced eigen-solve",
           model=f"tube {SIZE[0]}x{SIZE[1]}: n = {p.n} DOF, nnz(K) = {p.K.nnz}, coupling {COUPLING:.3g}",
           note=f"{N_EIG} eigenvalues nearest 0; accuracy over the {N_CMP} smallest")
    del p
    cases = [("full, qep.solve_qep_sparse, COLAMD (as before) [baseline]", case_full, (False,)),
             ("full, qep.solve_qep_sparse default LU (symmetric mode)", case_full, (True,)),
             ("reduced, 20 modes", case_reduced, (20, False)),
             ("reduced, 40 modes", case_reduced, (40, False)),
             ("reduced, 20 modes + MTA", case_reduced, (20, True))]
    rows = []
    for label, fn, args in cases:
        try:
            r, wall, rss = isolated(fn, *args)
        except RuntimeError as exc:
            print(f"  {label}: FAILED\n{exc}")
            continue
        r.update(case=label, peak_rss_MB=rss)
        rows.append(r)
        print(f"  done: {label}: {r['t_oneoff'] + r['t_point']:.2f} s", flush=True)
    base = rows[0]
    ref = np.sort_complex(base["lam"][np.argsort(np.abs(base["lam"]))[:N_CMP]])
    for r in rows:
        r["point_ratio"] = r["t_point"] / base["t_point"]
        r["max_rel_err"] = max(float(np.min(np.abs(r["lam"] - x)) / abs(x)) for x in ref)
    table(rows, ["case", "m", "t_oneoff", "t_point", "point_ratio", "max_rel_err", "peak_rss_MB"])
    print("t_oneoff: basis (structural modes [+ MTA]) once per rotor speed/range; t_point: per "
          "eigen-solve; point_ratio = t_point / baseline t_point")
    return 0


if __name__ == "__main__":
    sys.exit(main())
