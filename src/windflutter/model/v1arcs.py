"""Resolve parametric windIO 1.x layup definitions to nondimensional contour arcs.

windIO 1.x (WISDEM ``internal_structure_2d_fem``) may define a layer or web by geometry instead
of explicit ``start_nd_arc``/``end_nd_arc``:

* ``offset_y_pa`` + ``rotation: {fixed: twist}`` (+ ``width``, ``side``): a plane normal to the
  chord at ``x/c = pitch_axis + offset_y_pa / chord`` (offset in metres, positive towards the
  trailing edge).  A web spans between the plane's suction- and pressure-side intersections; a
  layer of ``width`` metres is centred on the intersection on its ``side``.
* ``midpoint_nd_arc: {fixed: LE}`` + ``width``: centred on the leading edge.
* ``start_nd_arc: {fixed: TE}`` + ``width`` (or ``end_nd_arc: {fixed: TE}``): from the trailing edge.
* ``start_nd_arc: {fixed: <layer>}`` = that layer's end; ``end_nd_arc: {fixed: <layer>}`` = its start.

The contour at a span station is the airfoil stack blended to the local relative thickness
(shape interpolation at equal chordwise x on each side); arc positions are fractions of that
contour's length from the trailing edge over the suction side (windIO convention).  These are
geometric reconstructions, not WISDEM's own implementation: for the NREL 5 MW the result agrees
with the WISDEM v2 file's resolved anchors within ~0.01 of the contour (tests/model).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from windflutter.errors import InputError
from windflutter.model.airfoil_geom import arc_at_chord_x, le_index, nd_arc, perimeter
from windflutter.model.turbine import Airfoil

_NX = 160


def _side_tables(af: Airfoil) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(x, y_suction(x), y_pressure(x)) on a cosine-spaced x grid from LE to TE."""
    i = le_index(af.x)
    xs, ys = af.x[: i + 1][::-1], af.y[: i + 1][::-1]
    xp, yp = af.x[i:], af.y[i:]
    x0, x1 = af.x[i], max(af.x.max(), 1e-6)
    xg = x0 + (x1 - x0) * 0.5 * (1 - np.cos(np.linspace(0, np.pi, _NX)))
    o_s, o_p = np.argsort(xs, kind="stable"), np.argsort(xp, kind="stable")
    return xg, np.interp(xg, xs[o_s], ys[o_s]), np.interp(xg, xp[o_p], yp[o_p])


def contour_at(
    s: float,
    positions: np.ndarray,
    names: tuple[str, ...],
    airfoils: dict[str, Airfoil],
    rthick: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Blended contour (TE -> suction -> LE -> pressure -> TE) at span position ``s``."""
    j = int(np.clip(np.searchsorted(positions, s, side="right") - 1, 0, len(positions) - 1))
    k = min(j + 1, len(positions) - 1)
    a, b = airfoils[names[j]], airfoils[names[k]]
    if a.name == b.name or j == k:
        w = 0.0
    else:
        ta, tb = a.relative_thickness, b.relative_thickness
        if rthick is not None and abs(tb - ta) > 1e-6:
            w = float(np.clip((rthick - ta) / (tb - ta), 0.0, 1.0))
        else:
            w = float(np.clip((s - positions[j]) / max(positions[k] - positions[j], 1e-12), 0.0, 1.0))
    xa, sa, pa = _side_tables(a)
    if w == 0.0:
        xg, ys, yp = xa, sa, pa
    else:
        xb, sb, pb = _side_tables(b)
        xg = xa  # both grids run LE -> TE with the same spacing on [0, 1]
        ys = (1 - w) * sa + w * np.interp(xg, xb, sb)
        yp = (1 - w) * pa + w * np.interp(xg, xb, pb)
    x = np.concatenate([xg[::-1], xg[1:]])
    y = np.concatenate([ys[::-1], yp[1:]])
    return x, y


Geometry = Callable[[float], tuple[np.ndarray, np.ndarray, float, float]]  # s -> (x, y, chord, pitch_axis)


def _val(r, d: dict, path: str, key: str, s: float, default=None) -> float:
    if key not in d:
        if default is None:
            raise InputError(f"{path}.{key}", "<missing>", "a required key", r.source)
        return default
    g, v = r.grid_values(d, path, key)
    return float(np.interp(s, g, v))


def resolve_web(w: dict, r, path: str, geom: Geometry, s_grid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Suction/pressure attachment arcs of a v1 web defined by ``offset_y_pa`` (+ fixed twist)."""
    if "offset_y_pa" not in w:
        raise InputError(path, sorted(w), "start_nd_arc/end_nd_arc or offset_y_pa for a web", r.source)
    _check_rotation(w, r, path)
    a0, a1 = np.empty_like(s_grid), np.empty_like(s_grid)
    for i, s in enumerate(s_grid):
        x, y, chord, pa = geom(s)
        xc = pa + _val(r, w, path, "offset_y_pa", s) / chord
        a0[i] = arc_at_chord_x(x, y, xc, "suction")
        a1[i] = arc_at_chord_x(x, y, xc, "pressure")
    return a0, a1


def _check_rotation(d: dict, r, path: str) -> None:
    rot = d.get("rotation")
    if rot is None:
        return
    if isinstance(rot, dict) and rot.get("fixed") == "twist":
        return
    if isinstance(rot, dict) and "values" in rot:
        # an explicit plane rotation equal to minus the twist is the same as 'fixed: twist' (IEA v1 files
        # write it out); other rotations are not supported
        return
    raise InputError(f"{path}.rotation", rot, "'fixed: twist' (planes normal to the chord)", r.source)


def resolve_layer(
    lay: dict,
    r,
    path: str,
    geom: Geometry,
    s_grid: np.ndarray,
    resolved: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]],
) -> tuple[np.ndarray, np.ndarray]:
    """(start_arc, end_arc) on ``s_grid`` for a parametric v1 shell layer."""
    n = s_grid.size
    start, end = np.full(n, np.nan), np.full(n, np.nan)

    def other(name: str, handle: int) -> np.ndarray:
        if name not in resolved:
            raise InputError(path, name, f"a layer defined before this one ({sorted(resolved)})", r.source)
        g, a, b = resolved[name]
        return np.interp(s_grid, g, (a, b)[handle])

    sp, ep = lay.get("start_nd_arc"), lay.get("end_nd_arc")
    fixed_s = sp.get("fixed") if isinstance(sp, dict) else None
    fixed_e = ep.get("fixed") if isinstance(ep, dict) else None
    side = lay.get("side")
    for i, s in enumerate(s_grid):
        x, y, chord, pa = geom(s)
        per = perimeter(x, y) * chord
        width = _val(r, lay, path, "width", s, default=np.nan) / per if "width" in lay else np.nan
        if "offset_y_pa" in lay and "width" in lay:
            _check_rotation(lay, r, path)
            if side not in ("suction", "pressure"):
                raise InputError(f"{path}.side", side, "'suction' or 'pressure'", r.source)
            xc = pa + _val(r, lay, path, "offset_y_pa", s) / chord
            mid = float(arc_at_chord_x(x, y, xc, side))
            start[i], end[i] = mid - 0.5 * width, mid + 0.5 * width
        elif isinstance(lay.get("midpoint_nd_arc"), dict) and "width" in lay:
            fx = lay["midpoint_nd_arc"].get("fixed")
            if fx != "LE":
                raise InputError(f"{path}.midpoint_nd_arc.fixed", fx, "'LE'", r.source)
            mid = float(nd_arc(x, y)[le_index(x)])
            start[i], end[i] = mid - 0.5 * width, mid + 0.5 * width
        elif fixed_s == "TE" and "width" in lay:
            start[i], end[i] = 0.0, width
        elif fixed_e == "TE" and "width" in lay:
            start[i], end[i] = 1.0 - width, 1.0
    if fixed_s not in (None, "TE"):
        start = other(fixed_s, 1)
    if fixed_e not in (None, "TE"):
        end = other(fixed_e, 0)
    if fixed_s == "TE" and "width" not in lay:
        start = np.zeros(n)
    if fixed_e == "TE" and "width" not in lay:
        end = np.ones(n)
    if np.isnan(start).any() or np.isnan(end).any():
        raise InputError(path, sorted(lay), "a layer extent: explicit arcs, offset_y_pa + width + side, "
                         "midpoint_nd_arc + width, or arcs fixed to TE / other layers", r.source)
    return np.clip(start, 0.0, 1.0), np.clip(end, 0.0, 1.0)
