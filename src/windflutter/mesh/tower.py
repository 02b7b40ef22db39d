"""Tower meshes: tapered circular shell of quads, or 2-node beams with thin-walled tube sections."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from windflutter.errors import InputError
from windflutter.mesh.loft import quad_grid
from windflutter.structure.fem import BeamSection, IsotropicMaterial, Ply, ShellProperty


@dataclass
class TowerMesh:
    """Tower nodes/elements (global frame).

    ``ring_nodes`` (n_lev, n_circ) for shells, (n_lev, 1) for beams; the top ring is ``ring_nodes[-1]``
    and the base ring ``ring_nodes[0]``.
    """

    nodes: np.ndarray
    ring_nodes: np.ndarray
    conn: np.ndarray  # (ne, 4) shells or (ne, 2) beams
    prop: np.ndarray
    properties: list  # ShellProperty or BeamSection
    matdir: np.ndarray  # shells: material axis; beams: section y reference vector
    s: np.ndarray  # level positions (-)


def tower_material(tower, materials: dict) -> IsotropicMaterial:
    """The wall material (first layer), density scaled by the outfitting factor."""
    if not tower.layers:
        raise InputError("tower.layers", (), "at least one wall layer")
    name = tower.layers[0].material
    m = materials.get(name)
    if not isinstance(m, IsotropicMaterial):
        raise InputError("tower.layers[0].material", name, "an isotropic material defined in the materials list")
    return replace(m, rho=m.rho * float(tower.outfitting_factor))


def tower_levels(tower, n_axial: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(s, z, outer diameter, wall thickness) at ``n_axial + 1`` uniform levels."""
    s = np.linspace(0.0, 1.0, n_axial + 1)
    z = np.interp(s, tower.s, tower.z)
    d = np.interp(s, tower.s, tower.outer_diameter)
    t = np.interp(s, tower.s, tower.wall_thickness)
    if np.any(d <= 0) or np.any(t <= 0) or np.any(2 * t >= d):
        raise InputError("tower", "diameter/thickness", "positive diameter and 0 < wall thickness < radius")
    return s, z, d, t


def tube_section(E: float, G: float, rho: float, d_out: float, t: float) -> BeamSection:
    """Thin/thick-walled circular tube (exact annulus formulas), shear factor 0.5 (thin tube)."""
    ro, ri = 0.5 * d_out, 0.5 * d_out - t
    A = np.pi * (ro**2 - ri**2)
    I = np.pi / 4 * (ro**4 - ri**4)
    return BeamSection.from_properties(
        EA=E * A, EIy=E * I, EIz=E * I, GJ=G * 2 * I, mass_per_length=rho * A,
        GAy=0.5 * G * A, GAz=0.5 * G * A, Ixx_mass=rho * 2 * I, Iyy_mass=rho * I, Izz_mass=rho * I,
    )


def tower_shell_mesh(tower, materials: dict, n_circ: int, n_axial: int, offset: int = 0) -> TowerMesh:
    """Tapered shell tower: rings of ``n_circ`` nodes on the wall mid-surface, outward normals.

    Element thickness is the mean of its two levels (a stepped wall, as towers are built).
    """
    mat = tower_material(tower, materials)
    s, z, d, t = tower_levels(tower, n_axial)
    r = 0.5 * (d - t)
    th = -2 * np.pi * np.arange(n_circ) / n_circ  # clockwise about z -> outward quad normals
    nodes = np.stack([r[:, None] * np.cos(th)[None, :], r[:, None] * np.sin(th)[None, :], np.repeat(z[:, None], n_circ, 1)], -1)
    conn = quad_grid(len(s), n_circ, offset=offset)
    te = 0.5 * (t[:-1] + t[1:])
    props = [ShellProperty(plies=(Ply(mat, float(ti), 0.0),), name=f"tower_{k}") for k, ti in enumerate(te)]
    prop = np.repeat(np.arange(n_axial), n_circ)
    # material axis: the tower axis (structure/shell.py handles an axis equal to the element x axis)
    matdir = np.tile([0.0, 0.0, 1.0], (n_axial * n_circ, 1))
    ring = offset + np.arange(len(s) * n_circ).reshape(len(s), n_circ)
    return TowerMesh(nodes.reshape(-1, 3), ring, conn, prop, props, matdir, s)


def tower_beam_mesh(tower, materials: dict, n_axial: int, offset: int = 0) -> TowerMesh:
    """Tower as 2-node beams on the axis; element section from the mean diameter/thickness."""
    mat = tower_material(tower, materials)
    s, z, d, t = tower_levels(tower, n_axial)
    nodes = np.column_stack([np.zeros_like(z), np.zeros_like(z), z])
    conn = offset + np.column_stack([np.arange(n_axial), np.arange(1, n_axial + 1)])
    dm, tm = 0.5 * (d[:-1] + d[1:]), 0.5 * (t[:-1] + t[1:])
    E, G, rho = mat.E, mat.G, mat.rho
    secs = [tube_section(E, G, rho, a, b) for a, b in zip(dm, tm)]
    orient = np.tile([1.0, 0.0, 0.0], (n_axial, 1))
    ring = offset + np.arange(len(s)).reshape(-1, 1)
    return TowerMesh(nodes, ring, conn, np.arange(n_axial), secs, orient, s)
