"""windIO blade layups: v2 anchors (resolved recursively) and v1 explicit or parametric extents.

Arcs are nondimensional contour positions (windIO convention, see
:class:`~windflutter.model.turbine.Web`).  Parametric v1 definitions are resolved on the blended
airfoil contour by :mod:`windflutter.model.v1arcs`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from windflutter.errors import InputError, InputWarning
from windflutter.model.airfoil_geom import perimeter
from windflutter.model.checks import Reader, join
from windflutter.model.turbine import Layer, Layup, Web
from windflutter.model.v1arcs import resolve_layer, resolve_web
from windflutter.model.windio_common import explicit
from windflutter.units import DEG


# ----------------------------------------------------------------------------- layup, v2 anchors
def _anchors(st: dict, r: Reader, sp: str) -> dict[str, tuple[dict, str]]:
    """Every anchor (structure-level and per web) by name, with its path."""
    anchors: dict[str, tuple[dict, str]] = {}
    for i, a in enumerate(r.seq(st, sp, "anchors", default=[])):
        anchors[r.string(a, f"{sp}.anchors[{i}]", "name")] = (a, f"{sp}.anchors[{i}]")
    for i, w in enumerate(r.seq(st, sp, "webs", default=[])):
        for j, a in enumerate(r.seq(w, f"{sp}.webs[{i}]", "anchors", default=[])):
            q = f"{sp}.webs[{i}].anchors[{j}]"
            anchors[r.string(a, q, "name")] = (a, q)
    return anchors


def layup_v2(st: dict, r: Reader, sp: str, materials: dict, geom=None) -> Layup:
    """windIO 2.x layup: webs and layers whose arcs are explicit or anchor references (followed
    recursively; ``width``-defined placeholder handles recomputed from the contour)."""
    anchors = _anchors(st, r, sp)

    def resolve(spec: Any, path: str, depth: int = 0) -> tuple[np.ndarray, np.ndarray]:
        if depth > 10:
            raise InputError(path, "anchor cycle", "anchors that resolve to arc positions", r.source)
        if isinstance(spec, dict) and "anchor" in spec:
            ref = r.mapping(spec, path, "anchor")
            nm = r.string(ref, join(path, "anchor"), "name")
            handle = r.string(ref, join(path, "anchor"), "handle")
            if nm not in anchors:
                raise InputError(join(path, "anchor.name"), nm, f"a defined anchor ({sorted(anchors)})", r.source)
            a, ap = anchors[nm]
            if geom is not None and _width_placeholder(a, handle):
                return _from_width(a, ap, handle, depth)
            if handle not in a:
                # IEA-10 v2 has a handle that names another anchor: follow it with the same handle
                if handle in anchors:
                    key = "start_nd_arc" if "start" in path.rsplit(".", 1)[-1] else "end_nd_arc"
                    return resolve({"anchor": {"name": handle, "handle": key}}, path, depth + 1)
                raise InputError(join(path, "anchor.handle"), handle, f"a key of anchor {nm!r} ({sorted(a)})",
                                 r.source)
            return resolve(a[handle], join(ap, handle), depth + 1)
        if isinstance(spec, dict) and "values" in spec:
            g, v = r.grid_values(spec, path)
            return g, v
        raise InputError(path, spec if not isinstance(spec, dict) else sorted(spec), "arc positions "
                         "({grid, values}) or an anchor reference with resolved positions", r.source)

    def _from_width(a: dict, ap: str, handle: str, depth: int) -> tuple[np.ndarray, np.ndarray]:
        # the other end of the anchor, then +/- width (m) converted with the local contour length
        other = "start_nd_arc" if handle == "end_nd_arc" else "end_nd_arc"
        go, ao = resolve(a[other], join(ap, other), depth + 1)
        gw, wv = r.grid_values(a, ap, "width", nonneg=True)
        g = np.unique(np.concatenate([go, gw, np.linspace(0.0, 1.0, 41)]))

        per = np.array([perimeter(*geom(sq)[:2]) * geom(sq)[2] for sq in g])
        wnd = np.interp(g, gw, wv) / per
        base = np.interp(g, go, ao)
        return g, np.clip(base + wnd if handle == "end_nd_arc" else base - wnd, 0.0, 1.0)

    webs = _webs_v2(st, r, sp, resolve)
    web_names = {w.name for w in webs}
    layers = []
    for i, lay in enumerate(r.seq(st, sp, "layers")):
        q = f"{sp}.layers[{i}]"
        name, mat, tg, tv, fo, web = layer_fields(lay, q, r, materials, web_names)
        if web is None:
            g1, a1 = resolve(r.get(lay, q, "start_nd_arc"), join(q, "start_nd_arc"))
            g2, a2 = resolve(r.get(lay, q, "end_nd_arc"), join(q, "end_nd_arc"))
        else:
            g1 = g2 = np.array([0.0, 1.0])
            a1, a2 = np.zeros(2), np.ones(2)
        s = np.unique(np.concatenate([tg, g1, g2] + ([fo[0]] if fo is not None else [])))
        orient = np.interp(s, fo[0], fo[1]) * DEG if fo is not None else np.zeros_like(s)
        t_s, a0_s, a1_s = collapse_inverted(q, name, s, np.interp(s, tg, tv), np.interp(s, g1, a1),
                                             np.interp(s, g2, a2), r.source)
        layers.append(Layer(
            name=name, material=mat, s=s, thickness=t_s, orientation=orient,
            start_arc=a0_s, end_arc=a1_s, web=web,
            s_start=r.number(lay, q, "start_nd_grid", default=float(tg[0])),
            s_end=r.number(lay, q, "end_nd_grid", default=float(tg[-1])),
        ))
    return Layup(webs=tuple(webs), layers=tuple(layers))


def _webs_v2(st: dict, r: Reader, sp: str, resolve) -> list[Web]:
    webs = []
    for i, w in enumerate(r.seq(st, sp, "webs", default=[])):
        q = f"{sp}.webs[{i}]"
        g1, a1 = resolve(r.get(w, q, "start_nd_arc"), join(q, "start_nd_arc"))
        g2, a2 = resolve(r.get(w, q, "end_nd_arc"), join(q, "end_nd_arc"))
        s = np.unique(np.concatenate([g1, g2]))
        webs.append(Web(name=r.string(w, q, "name"), s=s, start_arc=np.interp(s, g1, a1), end_arc=np.interp(s, g2, a2),
                        s_start=r.number(w, q, "start_nd_grid", default=float(s[0])),
                        s_end=r.number(w, q, "end_nd_grid", default=float(s[-1]))))
    return webs


# ------------------------------------------------------------------------------------- layup, v1
def layup_v1(st: dict, r: Reader, sp: str, materials: dict, geom) -> Layup:
    """windIO 1.x layup.  Explicit ``start_nd_arc``/``end_nd_arc`` are used as given; layers with
    neither (and no ``width``) cover the whole contour; parametric definitions (``offset_y_pa``,
    ``width``, ``midpoint_nd_arc``, arcs fixed to TE or to other layers) are resolved on the blade
    geometry by :mod:`windflutter.model.v1arcs`."""
    uniform = np.linspace(0.0, 1.0, 41)
    webs = []
    for i, w in enumerate(r.seq(st, sp, "webs", default=[])):
        q = f"{sp}.webs[{i}]"
        name = r.string(w, q, "name")
        if explicit(w.get("start_nd_arc")) and explicit(w.get("end_nd_arc")):
            g1, a1 = r.grid_values(w, q, "start_nd_arc", nonneg=True)
            g2, a2 = r.grid_values(w, q, "end_nd_arc", nonneg=True)
            s = np.unique(np.concatenate([g1, g2]))
            a1, a2 = np.interp(s, g1, a1), np.interp(s, g2, a2)
        else:
            s = uniform
            a1, a2 = resolve_web(w, r, q, geom, s)
        webs.append(Web(name=name, s=s, start_arc=a1, end_arc=a2, s_start=float(s[0]), s_end=float(s[-1])))
    web_names = {w.name for w in webs}
    layers = []
    resolved: dict = {}
    for i, lay in enumerate(r.seq(st, sp, "layers")):
        q = f"{sp}.layers[{i}]"
        name, mat, tg, tv, fo, web = layer_fields(lay, q, r, materials, web_names)
        if web is not None:
            g1 = g2 = np.array([0.0, 1.0])
            a1, a2 = np.zeros(2), np.ones(2)
        elif explicit(lay.get("start_nd_arc")) and explicit(lay.get("end_nd_arc")):
            g1, a1 = r.grid_values(lay, q, "start_nd_arc", nonneg=True)
            g2, a2 = r.grid_values(lay, q, "end_nd_arc", nonneg=True)
        elif not any(k in lay for k in ("start_nd_arc", "end_nd_arc", "width", "midpoint_nd_arc", "offset_y_pa")):
            g1 = g2 = np.array([0.0, 1.0])
            a1, a2 = np.zeros(2), np.ones(2)
        else:
            extra = [uniform, tg]
            if "width" in lay:
                extra.append(r.grid_values(lay, q, "width")[0])
            g1 = g2 = np.unique(np.concatenate(extra))
            a1, a2 = resolve_layer(lay, r, q, geom, g1, resolved)
        if web is None:
            sg = np.unique(np.concatenate([g1, g2]))
            resolved[name] = (sg, np.interp(sg, g1, a1), np.interp(sg, g2, a2))
        s = np.unique(np.concatenate([tg, g1, g2] + ([fo[0]] if fo is not None else [])))
        orient = np.interp(s, fo[0], fo[1]) if fo is not None else np.zeros_like(s)  # v1: rad
        t_s, a0_s, a1_s = collapse_inverted(q, name, s, np.interp(s, tg, tv), np.interp(s, g1, a1),
                                             np.interp(s, g2, a2), r.source)
        layers.append(Layer(
            name=name, material=mat, s=s, thickness=t_s, orientation=orient,
            start_arc=a0_s, end_arc=a1_s, web=web,
            s_start=float(tg[0]), s_end=float(tg[-1]),
        ))
    return Layup(webs=tuple(webs), layers=tuple(layers))


INVERTED_MAX = 0.5  # end_arc < start_arc by less than this (wrapped width > 0.5): inverted, not wrapping


def collapse_inverted(q: str, name: str, s: np.ndarray, t: np.ndarray, a0: np.ndarray, a1: np.ndarray,
                       source: str | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Outer-shell layer arcs with ``end_arc < start_arc`` by less than :data:`INVERTED_MAX`.

    ``end < start`` means a layer wrapping through the trailing edge; a panel whose two
    bounding division points have crossed (e.g. WISDEM's IEA 10 MW ``DP15_DP13_*`` and
    ``DP04_DP02_*`` beyond 80 % span, where the leading-edge band reaches past the spar-cap edge:
    end - start down to -0.11) would then wrap around almost the whole contour (90-99 % of it
    instead of nothing).  Such stations get zero width (both arcs at their midpoint; linear
    interpolation to a neighbouring valid station then never inverts), with an
    :class:`~windflutter.errors.InputWarning` naming the layer and the span range.  WISDEM's own
    6x6 of the IEA 10 MW has no such mass there (mass per length at 90 % span: ours 2.0x the
    file's before, 1.0x after)."""
    import warnings

    inv = (a1 < a0) & (a0 - a1 < INVERTED_MAX) & (t > 0)
    if not inv.any():
        return t, a0, a1
    worst = float(np.max((a0 - a1)[inv]))
    mid = 0.5 * (a0 + a1)
    a0, a1 = np.where(inv, mid, a0), np.where(inv, mid, a1)
    where = f"{source}: " if source else ""
    warnings.warn(f"{where}{q} ({name}): end_nd_arc < start_nd_arc (by up to {worst:.3f}) at span "
                  f"{float(s[inv].min()):.3f}-{float(s[inv].max()):.3f} (crossed division points, not a "
                  "trailing-edge wrap); the layer is given zero width there", InputWarning, stacklevel=2)
    return t, a0, a1


def _width_placeholder(a: dict, handle: str) -> bool:
    """True when a v2 anchor defines ``handle`` through ``width`` but the file carries only a
    constant 0/1 placeholder for it (WISDEM's IEA-10 file: the TE bands would otherwise cover the
    whole contour)."""
    w = a.get("width")
    if not isinstance(w, dict) or handle not in (w.get("defines") or []):
        return False
    h = a.get(handle)
    if not explicit(h):
        return False
    v = np.asarray(h["values"], dtype=float) if all(isinstance(x, (int, float)) for x in h["values"]) else None
    other = "start_nd_arc" if handle == "end_nd_arc" else "end_nd_arc"
    return v is not None and np.ptp(v) == 0.0 and v[0] in (0.0, 1.0) and other in a



def layer_fields(lay: dict, q: str, r: Reader, materials: dict, web_names: set):
    """Fields every layup layer has (v1 and v2): name, material (checked), thickness grid and
    values, fibre orientation (or None) and web name (checked, or None)."""
    name = r.string(lay, q, "name")
    mat = r.string(lay, q, "material")
    if mat not in materials:
        raise InputError(join(q, "material"), mat, f"a defined material ({sorted(materials)})", r.source)
    tg, tv = r.grid_values(lay, q, "thickness", nonneg=True)
    fo = r.grid_values(lay, q, "fiber_orientation", default=None)
    web = lay.get("web")
    if web is not None and web not in web_names:
        raise InputError(join(q, "web"), web, f"a defined web ({sorted(web_names)})", r.source)
    return name, mat, tg, tv, fo, web


