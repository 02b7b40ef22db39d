"""Element-stack congruence ``B^T A B``: the three-operand einsum against batched matmul.

The beam element, its co-rotational tangent and the rigid-section spin terms form ``B[e]^T A[e] B[e]``
for every element; until 2 Dec 2026 with ``einsum("eki,ekl,elj->eij", ...)``, whose unoptimized loop
is slow.  Baseline measured in the same run: that einsum, on stacks of beam-element shapes (6 x 12
shape functions, 12 x 12 rotations), then the NREL 5 MW beam blade's ``spin_terms`` (30 elements) with
each.  Prints times per call and the largest difference.

    python benchmarks/bench_congruence.py [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, table  # noqa: E402


def _einsum(B, A):
    return np.einsum("eki,ekl,elj->eij", B, A, B)


def per_call(fn, *args, n=50) -> float:
    fn(*args)
    t0 = time.perf_counter()
    for _ in range(n):
        out = fn(*args)
    return (time.perf_counter() - t0) / n, out


def main() -> int:
    import windflutter.rotor.spin as spin
    from windflutter.linalg_tools import congruence
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model
    from windflutter.model import load_turbine

    header("bench_congruence: B^T A B on element stacks, einsum [baseline] vs batched matmul")
    rng = np.random.default_rng(0)
    rows = []
    for e in ((30,) if QUICK else (30, 300)):
        for k, i in ((6, 12), (12, 12)):
            B, A = rng.standard_normal((e, k, i)), rng.standard_normal((e, k, k))
            t0, r0 = per_call(_einsum, B, A)
            t1, r1 = per_call(congruence, B, A)
            rows.append(dict(case=f"{e} x ({k}x{i})", einsum_ms=1e3 * t0, matmul_ms=1e3 * t1, speedup=t0 / t1,
                             max_diff=float(np.abs(r0 - r1).max() / np.abs(r0).max())))
    fe, _ = build_model(load_turbine("nrel5mw"), MeshSettings(model="beam", part="rotor_blade"))
    nodes, axis, apex = np.arange(fe.n_nodes), np.array([1.0, 0.0, 0.0]), np.zeros(3)
    t1, r1 = per_call(spin.spin_terms, fe, None, nodes, axis, apex, n=10)
    spin.congruence = _einsum
    try:
        t0, r0 = per_call(spin.spin_terms, fe, None, nodes, axis, apex, n=10)
    finally:
        spin.congruence = congruence
    diff = max(float(abs(a - b).max() / max(abs(a).max(), 1e-300)) for a, b in zip(r0[:2], r1[:2]))
    rows.append(dict(case=f"spin_terms, NREL 5 MW blade ({len(fe.beam_conn)} el.)", einsum_ms=1e3 * t0,
                     matmul_ms=1e3 * t1, speedup=t0 / t1, max_diff=diff))
    table(rows, ["case", "einsum_ms", "matmul_ms", "speedup", "max_diff"])
    print("times in ms per call; max_diff relative to the largest entry")
    return 0 if all(r["max_diff"] < 1e-12 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
