"""The 3-D shell blade's torsion against its sections (docs/mesh.md, "Two extractions").

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/shell_torsion_vs_sections.py [iea22mw|nrel5mw|tube]

The shell blade (default mesh; ``tube``: the straight elliptical aluminium tube blade of
tests/mesh/test_shell_section.py, 48 x 40, skin on the ellipse) clamped at the root, its tip ring tied
to a node on the reference axis (the tip rib's diaphragm left out) and loaded by a torque of 100 kN m
about the last span direction.  The twist of every station ring (least-squares rigid motion of its
nodes, the rotation about the local span direction) gives the shell's twist rate; printed beside it,
``(T / GJ) / rate`` for the GJ of each extraction (``segment``, ``section``; 40 stations, 9 for the tube):
1 where the extraction's section carries the shell's torsion, above 1 where the shell is stiffer.
"""

from __future__ import annotations

import dataclasses
import sys
import warnings
from pathlib import Path

import numpy as np

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.shell_beam import shell_beam_table, station_planes
from windflutter.mesh.turbine import build_model
from windflutter.model import load_turbine
from windflutter.structure.assembly import assemble
from windflutter.structure.equivalent_beam import ring_rigid_motion
from windflutter.structure.fem import RigidLink
from windflutter.structure.prestress import static_solve

TORQUE = 1e5  # N m


def turbine_and_mesh(name: str):
    if name != "tube":
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return load_turbine(name), MeshSettings(model="shell", part="blade"), 40
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "mesh"))
    from synthetic import synthetic_turbine, tube_blade  # noqa: PLC0415

    mesh = MeshSettings(model="shell", part="blade", n_chord=48, n_span=40, reference_surface="outer")
    return synthetic_turbine(tube_blade(40.0, 2.0, 0.4, 0.01)), mesh, 9


def station_twist(fe, sec):
    """(span positions (m), twist of every station (rad)) under the tip torque."""
    P0, st, on = station_planes(fe, sec)
    ns = len(P0) - 1
    X = np.asarray(fe.nodes, float)
    tip = np.flatnonzero(on & (st == ns))
    fe2 = dataclasses.replace(fe, diaphragms=[], nodes=np.vstack([X, P0[-1]]),
                              rigid_links=list(fe.rigid_links) + [RigidLink(independent=fe.n_nodes, dependent=tip)])
    t_end = (P0[-1] - P0[-2]) / np.linalg.norm(P0[-1] - P0[-2])
    F = np.zeros(fe2.n_dof)
    F[6 * fe.n_nodes + 3: 6 * fe.n_nodes + 6] = TORQUE * t_end
    u = static_solve(assemble(fe2), F).reshape(-1, 6)[:, :3]
    twist = []
    for k in range(ns + 1):
        ring = np.flatnonzero(on & (st == k))
        t = P0[min(k + 1, ns)] - P0[max(k - 1, 0)]
        twist.append(ring_rigid_motion(X[ring], u[ring], P0[k])[3:] @ (t / np.linalg.norm(t)))
    return np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(P0, axis=0), axis=1))], np.array(twist)


def main(name: str = "iea22mw") -> None:
    turbine, mesh, n_stations = turbine_and_mesh(name)
    fe, sec = build_model(turbine, mesh)
    x, twist = station_twist(fe, sec)
    gj = {}
    for ex in ("segment", "section"):
        tab = shell_beam_table(turbine, n_stations, mesh, extraction=ex)
        gj[ex] = (tab.s, np.array([1.0 / np.linalg.inv(K)[3, 3] for K in tab.beam.stiffness]))
    ns = len(x) - 1
    print(f"{name}: tip torque {TORQUE:g} N m; (T/GJ)/rate: 1 = the extraction's GJ carries the shell's torsion")
    for j in range(4, ns - 4, max(1, ns // 12)):
        rate = (twist[j + 1] - twist[j - 1]) / (x[j + 1] - x[j - 1])
        s = x[j] / x[-1]
        ratios = [TORQUE / np.interp(s, *gj[ex]) / rate for ex in ("segment", "section")]
        print(f"  r/R {s:.2f}: shell twist rate {rate:.3e} rad/m; segment {ratios[0]:.3f}, section {ratios[1]:.3f}")


if __name__ == "__main__":
    main(*sys.argv[1:2])
