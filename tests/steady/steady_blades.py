"""Synthetic straight blades for the steady-state tests, built here without the mesh package.

A uniform beam along +z from ``r0`` to ``r0 + L`` (hub centre at the origin, shaft and wind along
+x, so the blade turns towards -y), root clamped; its section axes: local y = global x (flapwise),
local z = global y (edgewise, the chord direction at zero blade angle).  The strips sit at the
element midpoints with the chord turned by the blade angle ``theta`` towards feather,
``e_chord = cos(theta) y + sin(theta) x``; each strip's motion is the mean of the rigid transfers
from its two end nodes (this file's own motion map).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.aero.sections import AeroSections, Polar, RotorGeometry
from windflutter.structure.fem import BeamSection, FEModel

ROTOR = RotorGeometry(hub_center=np.zeros(3), shaft_axis=np.array([1.0, 0.0, 0.0]),
                      wind_direction=np.array([1.0, 0.0, 0.0]))


def constant_polar(cl: float, cd: float, cm: float) -> Polar:
    a = np.radians(np.linspace(-180.0, 180.0, 37))
    return Polar(a, np.full(a.size, cl), np.full(a.size, cd), np.full(a.size, cm), name="constant")


def linear_polar(cd: float = 0.01, cm: float = -0.05) -> Polar:
    a = np.radians(np.linspace(-180.0, 180.0, 721))
    return Polar(a, 2 * np.pi * np.clip(a, -0.3, 0.3), np.full(a.size, cd), np.full(a.size, cm), name="linear")


@dataclass
class Blade:
    fe: FEModel
    sections: AeroSections
    L: float
    r0: float
    EA: float
    EI_flap: float
    EI_edge: float
    GJ: float
    m: float


def straight_blade(n: int = 40, L: float = 50.0, r0: float = 5.0, chord: float = 2.0, a: float = -0.5,
                   theta: float = 0.0, EA: float = 1e10, EI_flap: float = 1e9, EI_edge: float = 4e9, GJ: float = 5e8,
                   m: float = 200.0, inertia=(20.0, 5.0, 15.0), polar: Polar | None = None,
                   axes_with_chord: bool = False) -> Blade:
    """The blade of the module docstring; ``inertia`` = (polar, about local y, about local z) (kg m);
    ``axes_with_chord``: the section axes turned with the chord (local y normal to it)."""
    z = r0 + np.linspace(0.0, L, n + 1)
    nodes = np.column_stack([np.zeros(n + 1), np.zeros(n + 1), z])
    orient = [np.cos(theta), -np.sin(theta), 0.0] if axes_with_chord else [1.0, 0.0, 0.0]
    K = np.diag([EA, 1e3 * EA, 1e3 * EA, GJ, EI_edge, EI_flap])  # bending about local y moves along local z
    M = np.diag([m, m, m, *inertia])
    fe = FEModel(nodes=nodes, beam_conn=np.column_stack([np.arange(n), np.arange(1, n + 1)]),
                 beam_section=np.zeros(n, dtype=np.int64), beam_orient=np.tile(orient, (n, 1)),
                 beam_sections=[BeamSection(stiffness=K, mass=M)], spc={0: (0, 1, 2, 3, 4, 5)},
                 node_groups={"rotor": np.arange(n + 1), "blade0": np.arange(n + 1)})
    mid = 0.5 * (nodes[1:] + nodes[:-1])
    rows, cols, vals = [], [], []
    for j in range(n):
        for k in (j, j + 1):
            W = np.eye(6)
            d = mid[j] - nodes[k]
            W[:3, 3:] = -np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])
            r, c = np.nonzero(W)
            rows.append(6 * j + r)
            cols.append(6 * k + c)
            vals.append(0.5 * W[r, c])
    mm = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(6 * n, 6 * (n + 1)))
    e_chord = np.tile([np.sin(theta), np.cos(theta), 0.0], (n, 1))
    sec = AeroSections(blade=np.zeros(n, dtype=np.int64), radius=mid[:, 2].copy(), width=np.full(n, L / n),
                       chord=np.full(n, chord), elastic_axis=np.full(n, a), origin=mid, e_chord=e_chord,
                       e_span=np.tile([0.0, 0.0, 1.0], (n, 1)), airfoil=np.zeros(n, dtype=np.int64),
                       polars=[polar or constant_polar(1.0, 0.1, 0.0)], twist=np.full(n, theta), motion_map=mm)
    return Blade(fe=fe, sections=sec, L=L, r0=r0, EA=EA, EI_flap=EI_flap, EI_edge=EI_edge, GJ=GJ, m=m)
