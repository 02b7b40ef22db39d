"""Composite layup -> per-element laminates (``ShellProperty``), vectorised over elements.

Each element takes the layers that cover its centre (span position ``s`` and contour arc
position), with the layer thickness and fibre angle interpolated at its span position.
Identical laminates (thicknesses equal to 1 micrometre, angles to 1e-4 rad) share one property.
Plies are stored bottom (inside) to top (outside), i.e. the windIO outer-to-inner layer list
reversed, so that with outward element normals the outer layers are on top.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np

from windflutter.structure.fem import Material, Ply, ShellProperty

THICKNESS_QUANTUM = 1e-6  # m: laminates closer than this in every ply are merged
ANGLE_QUANTUM = 1e-4  # rad


def arc_covers(arc: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """True where the contour position ``arc`` lies in ``[start, end)``.

    ``end < start`` means the interval wraps through the trailing edge (1 -> 0).  A layer from 0
    to 1 covers everything.
    """
    arc = np.asarray(arc, dtype=float)
    start = np.asarray(start, dtype=float)
    end = np.asarray(end, dtype=float)
    direct = (arc >= start) & (arc < end)
    wrapped = (arc >= start) | (arc < end)
    full = (end - start) >= 1.0 - 1e-9
    return np.where(full, True, np.where(end >= start, direct, wrapped))


def element_center_arc(arc_nodes: np.ndarray, conn_j: np.ndarray) -> np.ndarray:
    """Centre arc of skin elements from the chordwise node indices of their two edges.

    Parameters
    ----------
    arc_nodes : (n_chord,) arc of the chordwise grid points (same at all stations).
    conn_j : (ne, 2) chordwise indices (j, j+1 mod n) of each element.
    """
    a = arc_nodes[conn_j[:, 0]]
    b = arc_nodes[conn_j[:, 1]]
    b = np.where(b <= a, b + 1.0, b)
    return np.mod(0.5 * (a + b), 1.0)


def layer_tables(layers: Sequence, s_elem: np.ndarray, arc_elem: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
    """Thickness and angle of every layer at every element.

    Parameters
    ----------
    layers : objects with ``thickness_at(s)``, ``arcs_at(s)`` and ``orientation_at(s)``
        (:class:`windflutter.model.turbine.Layer`).
    s_elem : (ne,) span position of the element centres (-).
    arc_elem : (ne,) contour position of the element centres, or None for web elements (a web
        layer covers the whole web height).

    Returns
    -------
    thickness : (ne, nl) m, 0 where the layer is absent.
    angle : (ne, nl) rad.
    """
    ne, nl = len(s_elem), len(layers)
    T = np.zeros((ne, nl))
    A = np.zeros((ne, nl))
    for k, lay in enumerate(layers):
        t = np.asarray(lay.thickness_at(s_elem), dtype=float)
        if arc_elem is not None:
            a0, a1 = lay.arcs_at(s_elem)
            t = np.where(arc_covers(arc_elem, a0, a1), t, 0.0)
        T[:, k] = np.maximum(t, 0.0)
        A[:, k] = lay.orientation_at(s_elem)
    return T, A


def group_laminates(
    T: np.ndarray,
    A: np.ndarray,
    materials: Sequence[Material],
    name_prefix: str = "laminate",
) -> tuple[np.ndarray, list[ShellProperty]]:
    """Merge identical rows of (thickness, angle) tables into shared laminates.

    Parameters
    ----------
    T, A : (ne, nl) layer thickness (m) and fibre angle (rad) per element, layers outer -> inner.
    materials : (nl,) material of each layer.

    Returns
    -------
    index : (ne,) property index per element.
    properties : list of :class:`ShellProperty` (plies inner -> outer).
    """
    qt = np.round(T / THICKNESS_QUANTUM).astype(np.int64)
    qa = np.where(qt > 0, np.round(A / ANGLE_QUANTUM), 0).astype(np.int64)
    keys = np.concatenate([qt, qa], axis=1)
    uniq, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    props = []
    for u, i0 in enumerate(first):
        plies = tuple(
            Ply(material=materials[k], thickness=float(T[i0, k]), angle=float(A[i0, k]))
            for k in range(T.shape[1] - 1, -1, -1)
            if qt[i0, k] > 0
        )
        props.append(ShellProperty(plies=plies, name=f"{name_prefix}_{u}"))
    return inverse.reshape(-1).astype(np.int64), props
