"""Benchmark of the structural core: assembly and 20 lowest modes of a ~30k-DOF shell model.

Model: clamped thin circular steel tube (R = 0.5 m, L = 10 m, t = 10 mm) meshed with pyfe3d
Quad4 shells, 50 nodes around x 100 elements along = 5050 nodes = 30,300 DOF.
Baselines measured in the same run: the same model at 1/4 size (scaling exponent), and scipy's
default ``eigsh`` shift-invert path (its own general LU) instead of our symmetric-mode SuperLU.

Targets (issue 3, on 2 cores): assembly < 5 s, 20 modes < 10 s.
Run: ``.venv/bin/python benchmarks/bench_structure.py`` (``--quick`` for the small size only).
"""

from __future__ import annotations

import sys
import time

import numpy as np
import scipy.sparse.linalg as spla

from windflutter.structure import assemble, modes
from windflutter.structure.fem import FEModel, IsotropicMaterial, Ply, ShellProperty


def tube_model(nc: int, nl: int, R: float = 0.5, L: float = 10.0, t: float = 0.01) -> FEModel:
    th = np.linspace(0, 2 * np.pi, nc, endpoint=False)
    X, TH = np.meshgrid(np.linspace(0, L, nl + 1), th, indexing="ij")
    nodes = np.c_[X.ravel(), R * np.cos(TH.ravel()), R * np.sin(TH.ravel())]
    idx = np.arange(X.size).reshape(nl + 1, nc)
    nxt = np.roll(idx, -1, axis=1)
    conn = np.c_[idx[:-1].ravel(), idx[1:].ravel(), nxt[1:].ravel(), nxt[:-1].ravel()]
    prop = ShellProperty(plies=(Ply(IsotropicMaterial(210e9, 0.3, 7850.0), t, 0.0),))
    return FEModel(nodes=nodes, shell_conn=conn, shell_prop=np.zeros(len(conn), int),
                   shell_matdir=np.tile([1.0, 0, 0], (len(conn), 1)), shell_properties=[prop],
                   spc={int(k): (0, 1, 2, 3, 4, 5) for k in idx[0]})


def run(nc: int, nl: int, alt: bool = False) -> dict:
    fe = tube_model(nc, nl)
    t0 = time.perf_counter()
    st = assemble(fe, check=False)
    t_asm = time.perf_counter() - t0
    t0 = time.perf_counter()
    from windflutter.structure import check_constrained

    check_constrained(st)
    t_chk = time.perf_counter() - t0
    t0 = time.perf_counter()
    md = modes(st, n=20)
    t_modes = time.perf_counter() - t0
    out = dict(n_dof=st.n_dof, nq=st.nq, n_elem=len(fe.shell_conn), t_asm=t_asm, t_check=t_chk,
               t_modes=t_modes, f1=md.freq[0], f20=md.freq[-1])
    if alt:
        t0 = time.perf_counter()
        w, _ = spla.eigsh(st.Kr, k=20, M=st.Mr, sigma=-1e-3)
        out["t_modes_scipy_default"] = time.perf_counter() - t0
        out["max_rel_diff_vs_scipy_default"] = float(np.max(np.abs(np.sort(w) - md.omega2) / md.omega2))
    return out


def main() -> None:
    quick = "--quick" in sys.argv
    small = run(25, 25)
    print(f"small : {small['n_dof']:6d} DOF ({small['n_elem']} quads): assemble {small['t_asm']:.2f} s, "
          f"rigid-body check {small['t_check']:.2f} s, 20 modes {small['t_modes']:.2f} s")
    if quick:
        return
    big = run(50, 100, alt=True)
    print(f"large : {big['n_dof']:6d} DOF ({big['n_elem']} quads): assemble {big['t_asm']:.2f} s (target < 5 s), "
          f"rigid-body check {big['t_check']:.2f} s, 20 modes {big['t_modes']:.2f} s (target < 10 s)")
    print(f"        f1 = {big['f1']:.3f} Hz, f20 = {big['f20']:.3f} Hz")
    r = big["n_dof"] / small["n_dof"]
    print(f"scaling: DOF x{r:.1f} -> assembly x{big['t_asm'] / small['t_asm']:.1f}, "
          f"modes x{big['t_modes'] / small['t_modes']:.1f}")
    print(f"alternative: scipy default eigsh (general LU) {big['t_modes_scipy_default']:.2f} s "
          f"= {big['t_modes_scipy_default'] / big['t_modes']:.2f} x ours; "
          f"max rel. diff of omega^2 {big['max_rel_diff_vs_scipy_default']:.1e}")


if __name__ == "__main__":
    main()
