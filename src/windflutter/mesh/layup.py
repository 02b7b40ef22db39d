"""Composite layup -> per-element laminates (``ShellProperty``), vectorised over elements.

Each element takes the layers that overlap it, each with its thickness at the element's span
position times the overlapped fraction of the element (smeared at layer edges; layer edges that
are key arcs of the mesh coincide with element edges and are exact), and its fibre angle.
Identical laminates (thicknesses equal to 1 micrometre, angles to 1e-4 rad) share one property.
Plies are stored bottom (inside) to top (outside), i.e. the windIO outer-to-inner layer list
reversed, so that with outward element normals the outer layers are on top.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
from scipy.integrate import trapezoid  # numpy < 2 (pyNastran env) has no np.trapezoid

from windflutter.structure.fem import Material, Ply, ShellProperty

THICKNESS_QUANTUM = 1e-6  # m: laminates closer than this in every ply are merged
ANGLE_QUANTUM = 1e-4  # rad
SPAN_SAMPLES = 11  # points averaging a layer's thickness over an element's span interval


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


def arc_overlap_fraction(e0: np.ndarray, e1: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Fraction of the element arc interval ``[e0, e1]`` (``e1 > e0``, may exceed 1 at the
    trailing edge) covered by the layer ``[start, end)`` (wrapping through 1 -> 0 if
    ``end < start``; 0 -> 1 covers everything)."""
    e0, e1 = np.asarray(e0, dtype=float), np.asarray(e1, dtype=float)
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    full = (end - start) >= 1.0 - 1e-9
    endw = np.where(end < start, end + 1.0, end)
    tot = np.zeros(np.broadcast(e0, start).shape)
    for k in (-1.0, 0.0, 1.0):
        tot += np.clip(np.minimum(e1, endw + k) - np.maximum(e0, start + k), 0.0, None)
    return np.where(full, 1.0, np.clip(tot / np.maximum(e1 - e0, 1e-300), 0.0, 1.0))


def layer_tables(
    layers: Sequence,
    s_lo: np.ndarray,
    s_hi: np.ndarray,
    arc_lo: np.ndarray | None = None,
    arc_hi: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Thickness and angle of every layer at every element, smeared over the element.

    An element spanning ``[s_lo, s_hi]`` along the span and ``[arc_lo, arc_hi]`` around the
    contour gets each layer's mean thickness over the covered span interval times the
    covered fractions of its span and arc intervals, so layer mass and membrane stiffness are
    conserved when layer edges fall inside elements (mesh-independent to first order).

    Parameters
    ----------
    layers : objects with ``thickness_at(s)``, ``arcs_at(s)``, ``orientation_at(s)``,
        ``s_start``, ``s_end`` (:class:`windflutter.model.turbine.Layer`).
    s_lo, s_hi : (ne,) span interval of each element (-).
    arc_lo, arc_hi : (ne,) contour interval (``arc_hi > arc_lo``), or None for web elements (a
        web layer covers the whole web height).

    Returns
    -------
    thickness : (ne, nl) m, 0 where the layer is absent.
    angle : (ne, nl) rad.
    """
    s_lo, s_hi = np.asarray(s_lo, dtype=float), np.asarray(s_hi, dtype=float)
    ne, nl = len(s_lo), len(layers)
    T = np.zeros((ne, nl))
    A = np.zeros((ne, nl))
    sc = 0.5 * (s_lo + s_hi)
    for k, lay in enumerate(layers):
        a = np.maximum(s_lo, lay.s_start)
        b = np.minimum(s_hi, lay.s_end)
        frac = np.clip((b - a) / np.maximum(s_hi - s_lo, 1e-300), 0.0, 1.0)
        # mean thickness over the covered interval (11-point trapezoid: layer tables can change
        # steeply within an element, e.g. the end of a root build-up)
        u = np.linspace(0.0, 1.0, SPAN_SAMPLES)
        ss = np.where(frac > 0, a, sc)[:, None] + np.where(frac > 0, b - a, 0.0)[:, None] * u[None, :]
        tt = np.asarray(lay.thickness_at(ss), dtype=float)
        t = trapezoid(tt, u, axis=1) * frac
        if arc_lo is not None:
            a0, a1 = lay.arcs_at(sc)
            t = t * arc_overlap_fraction(arc_lo, arc_hi, a0, a1)
        T[:, k] = np.maximum(t, 0.0)
        A[:, k] = lay.orientation_at(sc)
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
