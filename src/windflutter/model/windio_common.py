"""What the windIO ontology versions put where, and small helpers shared by the windIO readers."""

from __future__ import annotations

from typing import Any

import numpy as np

from windflutter.model.checks import Reader, join
from windflutter.units import DEG, RPM


class Keys:
    """Where things live in one ontology version and which angle/speed units it uses."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


V2 = Keys(major=2, blade_shape="outer_shape", blade_struct="structure", tower_shape="outer_shape",
          tower_struct="structure", nacelle="drivetrain", rthick_key="rthick",
          angle=DEG,  # twist, cone, tilt, polar alpha, fibre orientation, control angles
          speed=RPM)  # control rotor speeds
V1 = Keys(**{**V2.__dict__, "major": 1, "blade_shape": "outer_shape_bem", "blade_struct": "internal_structure_2d_fem",
             "tower_shape": "outer_shape_bem", "tower_struct": "internal_structure_2d_fem", "nacelle": "nacelle",
             "rthick_key": "relative_thickness", "angle": 1.0, "speed": 1.0})  # radians and rad/s


def ref_axis(d: dict, r: Reader, p: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reference axis ``(s, xyz (n, 3), arc length)`` interpolated on the union of the x, y, z grids."""
    comps = [r.grid_values(d, p, c) for c in ("x", "y", "z")]
    s = np.unique(np.concatenate([g for g, _ in comps]))
    xyz = np.stack([np.interp(s, g, v) for g, v in comps], axis=1)
    seg = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    return s, xyz, arc


def shape_and_axis(comp: dict, r: Reader, k: Keys, name: str, shape_key: str) -> tuple[str, dict, str, dict]:
    """A component's outer-shape block and reference axis with their paths: v2 keeps the axis
    beside the shape (``components.NAME.reference_axis``), v1 inside it."""
    cp = f"components.{name}"
    shape_p = f"{cp}.{shape_key}"
    shape = r.mapping(comp, cp, shape_key)
    if k.major >= 2:
        return shape_p, shape, f"{cp}.reference_axis", r.mapping(comp, cp, "reference_axis")
    return shape_p, shape, join(shape_p, "reference_axis"), r.mapping(shape, shape_p, "reference_axis")


def inertia6(v: np.ndarray) -> np.ndarray:
    """windIO 6-vector (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) -> symmetric 3x3 (kg m^2)."""
    ixx, iyy, izz, ixy, ixz, iyz = v
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)


def explicit(d: Any) -> bool:
    """True for an explicit ``{grid, values}`` mapping."""
    return isinstance(d, dict) and "grid" in d and "values" in d
