"""Shell mesh of one blade in its root frame: lofted skin of quads plus shear webs sharing skin nodes.

The chordwise grid is split at *key arcs* (web attachment points and layer boundaries such as
spar-cap edges), each segment keeping the same number of elements at every station, so that
the quad topology is one structured grid, webs attach exactly at skin nodes and layer
boundaries follow element edges (seed, Castillo Capponi 2010, sec. 4.1.6: quad-only mesh,
parametric in the number of elements per section).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError, check_choice
from windflutter.mesh import loft as lf
from windflutter.mesh.layup import group_laminates, layer_tables
from windflutter.config.declarations import REFERENCE_SURFACES
from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.shell_layup import (  # noqa: F401  (fill_web_keys: importable here)
    arc_interval, choose_key_arcs, extend_to_blade_ends, fill_uncovered, fill_web_keys, layer_material)
from windflutter.structure.fem import ShellProperty



@dataclass
class BladeShellMesh:
    """One blade's shell mesh in the blade root frame (see :mod:`windflutter.mesh.loft`).

    Attributes
    ----------
    nodes : (n, 3) m, blade root frame.
    conn : (ne, 4) quads, outward normals on the skin.
    prop : (ne,) index into ``properties``.
    matdir : (ne, 3) material axis (span direction of the element), blade frame.
    properties : laminates.
    region : (ne,) index into ``region_names``.
    region_names : e.g. ``["skin", "web:Web_fore", ...]``.
    eta : (n_st,) station span positions (-).
    station_nodes : (n_st, n_chord) skin node index of station i, chordwise point j.
    arc : (n_st, n_chord) contour arc of each skin node.
    ref_axis : (n_st, 3) reference-axis points (m).
    chord, twist, pitch_axis : (n_st,) section data at the stations.
    """

    nodes: np.ndarray
    conn: np.ndarray
    prop: np.ndarray
    matdir: np.ndarray
    properties: list[ShellProperty]
    region: np.ndarray
    region_names: list[str]
    eta: np.ndarray
    station_nodes: np.ndarray
    arc: np.ndarray
    ref_axis: np.ndarray
    chord: np.ndarray
    twist: np.ndarray
    pitch_axis: np.ndarray


@dataclass(frozen=True)
class _BladeOnly:
    """What :meth:`MeshSettings.resolved` reads of a turbine: its blade and airfoils."""

    blade: object
    airfoils: dict


def station_positions(n_span: int, clustering: float = 0.0) -> np.ndarray:
    """Span positions of ``n_span + 1`` stations on [0, 1]: uniform blended with cosine spacing."""
    u = np.linspace(0.0, 1.0, n_span + 1)
    c = 0.5 * (1.0 - np.cos(np.pi * u))
    return (1.0 - clustering) * u + clustering * c


def _oriented_stack(blade, airfoils) -> tuple[np.ndarray, list[np.ndarray]]:
    pos = np.asarray(blade.airfoil_positions, dtype=float)
    shapes = []
    for name in blade.airfoil_names:
        af = airfoils.get(name)
        if af is None:
            raise InputError("blade.airfoils", name, "an airfoil defined in the airfoils list")
        if len(af.x) < 8:
            raise InputError(f"airfoils[{name}].coordinates", len(af.x), "at least 8 points for the shell loft")
        shapes.append(lf.orient_airfoil(np.column_stack([af.x, af.y]), name))
    return pos, shapes


def blade_shell_mesh(blade, airfoils: dict, materials: dict, settings: MeshSettings,
                     reference_surface: str | None = None) -> BladeShellMesh:
    """Loft and mesh one blade (skin + webs) with laminates from its layup.

    Parameters
    ----------
    blade : :class:`windflutter.model.turbine.Blade` with a layup.
    airfoils : name -> :class:`windflutter.model.turbine.Airfoil`.
    materials : name -> FE material.
    settings : element counts (or the element length they follow from) and the reference surface.
    reference_surface : overrides ``settings.reference_surface``: where the skin elements' reference
        (mid-)surface lies: ``"outer"`` on
        the outer mould line (the seed's model: half of each laminate outside the airfoil), or
        ``"midsurface"`` (the default) moved inwards in the section plane by half the local laminate thickness
        (capped at a quarter of the local airfoil thickness), the wall midline of the thin-walled
        beam sections (:mod:`windflutter.model.section`); the webs then end on the moved skin.
    """
    reference_surface = reference_surface or settings.reference_surface
    check_choice("mesh.reference_surface", reference_surface, REFERENCE_SURFACES)
    if settings.n_span is None or settings.n_chord is None:
        settings = settings.resolved(_BladeOnly(blade, airfoils))
    if blade.layup is None or not blade.layup.layers:
        raise InputError("blade.layup", None, "a composite layup (layers and webs) for the shell model")
    eta = station_positions(settings.n_span, settings.span_clustering)
    layup = blade.layup
    shell_layers = extend_to_blade_ends(layup.shell_layers)
    webs, web_rows = _present_webs(layup, eta)
    keys, key_arr, counts = _key_arcs(webs, web_rows, shell_layers, eta, settings.n_chord)
    key_index = {name: int(np.sum(counts[: i + 1])) for i, (name, _) in enumerate(keys)}
    st = _lofted_stations(blade, airfoils, eta, key_arr, counts)
    parts = _skin_part(st, shell_layers, materials, settings.n_chord, reference_surface)
    for w in webs:
        _add_web(parts, w, layup.web_layers(w.name), web_rows[w.name], key_index, st.eta, settings.n_web, materials)

    all_nodes = np.vstack(parts.nodes)
    conn = np.vstack(parts.conns)
    all_nodes, conn, station_nodes = _compact(all_nodes, conn, parts.station_nodes)
    return BladeShellMesh(
        nodes=all_nodes,
        conn=conn,
        prop=np.concatenate(parts.prop),
        matdir=_span_directions(all_nodes, conn),
        properties=parts.properties,
        region=np.concatenate(parts.region),
        region_names=parts.region_names,
        eta=eta,
        station_nodes=station_nodes,
        arc=st.arc,
        ref_axis=st.ref,
        chord=st.chord,
        twist=st.twist,
        pitch_axis=st.pitch_axis,
    )


def _present_webs(layup, eta: np.ndarray) -> tuple[list, dict[str, np.ndarray]]:
    """The webs that get elements, and the rows of elements of each.

    Parameters
    ----------
    layup : the blade's layup.
    eta : (n_st,) station span positions (-).

    Returns
    -------
    webs : the layup's webs with layers and non-zero thickness on at least one row, in layup
        order.
    web_rows : web name -> indices of the element rows (between stations i and i+1) whose two
        bounding stations both have web thickness (m) > 0.
    """
    # a web exists where its layers have thickness (windIO files give attachment arcs along the
    # whole span, also where the web is absent and may coincide with another web's)
    web_t = {w.name: sum(lay.thickness_at(eta) for lay in layup.web_layers(w.name)) * ((eta >= w.s_start - 1e-9) & (eta <= w.s_end + 1e-9))
             for w in layup.webs if layup.web_layers(w.name)}
    webs = [w for w in layup.webs if w.name in web_t and np.any(web_t[w.name] > 0)]
    # web elements on the rows whose two bounding stations both have web thickness
    web_rows = {w.name: np.where((web_t[w.name][:-1] > 0) & (web_t[w.name][1:] > 0))[0] for w in webs}
    webs = [w for w in webs if web_rows[w.name].size]
    return webs, web_rows


def _key_arcs(webs: list, web_rows: dict, shell_layers: list, eta: np.ndarray, n_chord: int):
    """Key arcs of the chordwise grid (webs first, then layer boundaries) and its segment counts.

    Parameters
    ----------
    webs, web_rows : from :func:`_present_webs`.
    shell_layers : the skin layers (extended to the blade ends).
    eta : (n_st,) station span positions (-).
    n_chord : chordwise elements (-).

    Returns
    -------
    keys : (name, (n_st,) arc (-)) of the kept key arcs, sorted by mean arc.
    key_arr : (n_st, nk + 1) segment start arcs (-) at every station, the first column 0.
    counts : (nk + 1,) elements in each segment (sum ``n_chord``).

    Raises InputError if a web's attachment arc could not be kept as a key.
    """
    n_st = len(eta)
    raw = []
    for w in webs:
        rows = web_rows[w.name]
        on = np.zeros(n_st, dtype=bool)
        on[np.unique(np.concatenate([rows, rows + 1]))] = True
        raw.append((f"{w.name}.start", np.interp(eta, w.s, w.start_arc), on))
        raw.append((f"{w.name}.end", np.interp(eta, w.s, w.end_arc), on))
    curves: list[tuple[str, np.ndarray]] = fill_web_keys(raw, eta)
    n_web_keys = len(curves)
    for lay in shell_layers:
        if np.max(lay.thickness) <= 0:
            continue
        a0, a1 = lay.arcs_at(eta)
        curves.append((f"{lay.name}.start", np.mod(a0, 1.0)))
        curves.append((f"{lay.name}.end", np.mod(a1, 1.0)))
    max_keys = max(n_web_keys, n_chord // 3 - 1)
    keys = choose_key_arcs(curves, max_keys, n_web_keys)
    web_keys = {name for name, _ in keys}
    for w in webs:
        for h in ("start", "end"):
            if f"{w.name}.{h}" not in web_keys:
                raise InputError(f"blade.layup.webs[{w.name}]", h, "web attachment arcs inside (0, 1), distinct from other webs")
    key_arr = np.column_stack([np.zeros(n_st)] + [c for _, c in keys])  # (n_st, nk+1)
    seg_len = np.diff(np.column_stack([key_arr, np.ones(n_st)]), axis=1).mean(axis=0)
    counts = lf.distribute_counts(seg_len, n_chord)
    return keys, key_arr, counts


@dataclass
class _Stations:
    """Lofted stations of the blade (see :func:`_lofted_stations`).

    Attributes
    ----------
    eta : (n_st,) span positions (-).  arc : (n_st, nc) contour arc of each skin point (-).
    sec : (n_st, nc, 2) unit airfoil coordinates (-).  ref : (n_st, 3) reference axis (m).
    chord (m), twist (rad), pitch_axis (-) : (n_st,) section data.
    skin : (n_st, nc, 3) skin points on the outer mould line, blade root frame (m).
    """

    eta: np.ndarray
    arc: np.ndarray
    sec: np.ndarray
    ref: np.ndarray
    chord: np.ndarray
    twist: np.ndarray
    pitch_axis: np.ndarray
    skin: np.ndarray


def _lofted_stations(blade, airfoils: dict, eta: np.ndarray, key_arr: np.ndarray, counts: np.ndarray) -> _Stations:
    """Airfoil blend at each station on its own arc grid, lofted to the blade root frame.

    Parameters
    ----------
    blade, airfoils : as :func:`blade_shell_mesh`.
    eta : (n_st,) station span positions (-).
    key_arr, counts : segment start arcs (-) and element counts from :func:`_key_arcs`.
    """
    n_st = len(eta)
    pos, shapes = _oriented_stack(blade, airfoils)
    arc = np.stack([lf.segmented_grid(key_arr[i], counts) for i in range(n_st)])
    tc_target = blade.at("relative_thickness", eta)
    j, w = lf.stack_weights(pos, [lf.relative_thickness(x) for x in shapes], eta, tc_target)
    sec = np.stack([_blend_to_thickness(shapes[j[i]], shapes[j[i] + 1], arc[i], w[i], tc_target[i]) for i in range(n_st)])
    ref = np.column_stack([np.interp(eta, blade.s, blade.ref_axis[:, c]) for c in range(3)])
    chord = blade.at("chord", eta)
    twist = blade.at("twist", eta)
    pa = blade.at("pitch_axis", eta)
    skin = lf.loft(sec, chord, twist, pa, ref)  # (n_st, n_chord, 3)
    return _Stations(eta=eta, arc=arc, sec=sec, ref=ref, chord=chord, twist=twist, pitch_axis=pa, skin=skin)


@dataclass
class _MeshParts:
    """Nodes and element regions collected while meshing (skin first, then one region per web).

    Attributes
    ----------
    skin : (n_st, nc, 3) skin nodes on the elements' reference surface (m).
    station_nodes : (n_st, nc) node index of each skin point.
    nodes : (k, 3) node blocks (m), numbered consecutively.  next_id : next free node index.
    conns, prop, region : per region (ne_r, 4) quads, (ne_r,) laminate and region indices.
    properties : laminates.  region_names : one per region.
    """

    skin: np.ndarray
    station_nodes: np.ndarray
    nodes: list
    next_id: int
    conns: list
    prop: list
    properties: list
    region: list
    region_names: list


def _skin_part(st: _Stations, shell_layers: list, materials: dict, nc: int, reference_surface: str) -> _MeshParts:
    """Skin quads and their laminates; with ``"midsurface"`` the skin nodes moved inwards.

    Parameters
    ----------
    st : lofted stations.  shell_layers : skin layers.  materials : name -> FE material.
    nc : chordwise elements (-).  reference_surface : ``"outer"`` or ``"midsurface"``.

    Returns
    -------
    The mesh parts holding the skin region only.
    """
    eta, skin = st.eta, st.skin
    n_st = len(eta)
    nodes = [skin.reshape(-1, 3)]
    station_nodes = np.arange(n_st * nc).reshape(n_st, nc)
    conn_skin = lf.quad_grid(n_st, nc)
    ii = np.repeat(np.arange(n_st - 1), nc)
    jj = np.tile(np.arange(nc), n_st - 1)
    a_lo, a_hi = arc_interval(st.arc, ii, jj)
    T, A = layer_tables(shell_layers, eta[ii], eta[ii + 1], a_lo, a_hi)
    mats = [layer_material(materials, lay.material, lay.name) for lay in shell_layers]
    T, A = fill_uncovered(T, A, n_st - 1, nc)
    prop_skin, props = group_laminates(T, A, mats, "skin")
    if reference_surface == "midsurface":
        e_c, e_n = lf.chord_frame(st.twist)
        off = midsurface_offsets(st.sec, T.sum(axis=1).reshape(n_st - 1, nc), st.chord)  # (n_st, nc, 2)
        skin = skin + off[:, :, 0:1] * e_c[:, None, :] + off[:, :, 1:2] * e_n[:, None, :]
        nodes = [skin.reshape(-1, 3)]
    return _MeshParts(skin=skin, station_nodes=station_nodes, nodes=nodes, next_id=n_st * nc, conns=[conn_skin],
                      prop=[prop_skin], properties=props, region=[np.zeros(len(conn_skin), dtype=np.int64)],
                      region_names=["skin"])


def _add_web(parts: _MeshParts, w, wl: list, on: np.ndarray, key_index: dict, eta: np.ndarray, nw: int,
             materials: dict) -> None:
    """Append one web to ``parts``: its interior nodes and, on its rows, its quads and laminates.

    Parameters
    ----------
    parts : mesh parts (modified in place).  w : the web.  wl : its layers.
    on : indices of the element rows the web has (see :func:`_present_webs`).
    key_index : key-arc name -> chordwise skin point index.  eta : (n_st,) span positions (-).
    nw : elements across the web (-).  materials : name -> FE material.
    """
    skin, station_nodes = parts.skin, parts.station_nodes
    n_st = len(eta)
    js, je = key_index[f"{w.name}.start"], key_index[f"{w.name}.end"]
    a = skin[:, js, :]
    b = skin[:, je, :]
    t = np.linspace(0.0, 1.0, nw + 1)[1:-1]
    inner = a[:, None, :] + t[None, :, None] * (b - a)[:, None, :]  # (n_st, nw-1, 3)
    cols = np.empty((n_st, nw + 1), dtype=np.int64)
    cols[:, 0] = station_nodes[:, js]
    cols[:, -1] = station_nodes[:, je]
    if nw > 1:
        cols[:, 1:-1] = parts.next_id + np.arange(n_st * (nw - 1)).reshape(n_st, nw - 1)
        parts.nodes.append(inner.reshape(-1, 3))
        parts.next_id += n_st * (nw - 1)
    if on.size == 0:
        return
    i = np.repeat(on, nw)
    k = np.tile(np.arange(nw), on.size)
    cw = np.stack([cols[i, k], cols[i + 1, k], cols[i + 1, k + 1], cols[i, k + 1]], axis=1)
    Tw, Aw = layer_tables(wl, np.repeat(eta[on], nw), np.repeat(eta[on + 1], nw))
    if np.any(Tw.sum(axis=1) <= 0):
        raise InputError(f"blade.layup.webs[{w.name}]", "zero thickness", "web layers over the web's extent")
    pw, props_w = group_laminates(Tw, Aw, [layer_material(materials, lay.material, lay.name) for lay in wl], f"web_{w.name}")
    parts.conns.append(cw)
    parts.prop.append(pw + len(parts.properties))
    parts.properties = parts.properties + props_w
    parts.region.append(np.full(len(cw), len(parts.region_names), dtype=np.int64))
    parts.region_names.append(f"web:{w.name}")


def _span_directions(nodes: np.ndarray, conn: np.ndarray) -> np.ndarray:
    """(ne, 3) unit material axis of every quad: its span direction (-), blade frame.

    Every quad is (station i, station i+1, station i+1, station i), so the span edge is
    ``p1 + p2 - p0 - p3``.  (No nudge needed: structure/shell.py computes the material angle
    itself, exact when the material axis is the element x axis.)
    """
    p = nodes[conn]
    matdir = p[:, 1] + p[:, 2] - p[:, 0] - p[:, 3]
    matdir /= np.linalg.norm(matdir, axis=1, keepdims=True)
    return matdir


def midsurface_offsets(sec: np.ndarray, t_elem: np.ndarray, chord: np.ndarray) -> np.ndarray:
    """In-plane offsets (m) moving skin nodes from the outer mould line to the laminate midsurface.

    Parameters
    ----------
    sec : (n_st, nc, 2) unit airfoil coordinates of the stations (chordwise, flapwise), ordered
        TE -> suction side -> LE -> pressure side (counter-clockwise).
    t_elem : (n_st - 1, nc) total laminate thickness of each skin element (m); element (i, j)
        lies between stations i, i+1 and chordwise points j, j+1.
    chord : (n_st,) chord (m).

    Returns
    -------
    (n_st, nc, 2) offsets in the (chord, flapwise-normal) frame of each station: the inward
    normal of the contour times half the node's laminate thickness (mean of its neighbouring
    elements), capped at a quarter of the local airfoil thickness (where the skins meet at the
    trailing edge), as the thin-walled sections of :mod:`windflutter.model.section` do.
    """
    rows = np.vstack([t_elem[:1], t_elem, t_elem[-1:]])
    t_st = 0.5 * (rows[:-1] + rows[1:])  # (n_st, nc): mean over the elements above and below
    t_node = 0.5 * (t_st + np.roll(t_st, 1, axis=1))  # node j between elements j-1 and j
    tang = np.roll(sec, -1, axis=1) - np.roll(sec, 1, axis=1)
    tang /= np.maximum(np.linalg.norm(tang, axis=2, keepdims=True), 1e-30)
    inward = np.stack([-tang[:, :, 1], tang[:, :, 0]], axis=2)  # counter-clockwise contour
    h = np.empty(t_node.shape)
    for i, xy in enumerate(sec):  # local airfoil thickness at each node's chordwise position
        i_le = int(np.argmin(xy[:, 0]))
        up, lo = xy[: i_le + 1], xy[i_le:]
        ou, ol = np.argsort(up[:, 0]), np.argsort(lo[:, 0])
        h[i] = np.interp(xy[:, 0], up[ou, 0], up[ou, 1]) - np.interp(xy[:, 0], lo[ol, 0], lo[ol, 1])
    off = np.minimum(0.5 * t_node, 0.25 * np.abs(h) * np.asarray(chord)[:, None])
    return inward * off[:, :, None]


def _blend_to_thickness(a: np.ndarray, b: np.ndarray, arc: np.ndarray, w0: float, tc: float) -> np.ndarray:
    """Blend ``(1-w) a + w b`` resampled at ``arc``; if the two differ in thickness, ``w`` is
    refined by bisection so that the blended section's t/c equals ``tc`` (the blend's thickness
    is not linear in ``w`` when the thickest points are at different chord positions)."""
    ra, rb = lf.resample_airfoil(a, arc), lf.resample_airfoil(b, arc)
    ta, tb = lf.relative_thickness(ra), lf.relative_thickness(rb)
    if abs(tb - ta) < 1e-4 or not (min(ta, tb) <= tc <= max(ta, tb)):
        return (1 - w0) * ra + w0 * rb
    lo, hi = 0.0, 1.0
    for _ in range(30):
        w = 0.5 * (lo + hi)
        t = lf.relative_thickness((1 - w) * ra + w * rb)
        if (t - tc) * (tb - ta) < 0:
            lo = w
        else:
            hi = w
    w = 0.5 * (lo + hi)
    return (1 - w) * ra + w * rb


def _compact(nodes: np.ndarray, conn: np.ndarray, station_nodes: np.ndarray):
    """Drop nodes no element uses; renumber."""
    used = np.zeros(len(nodes), dtype=bool)
    used[conn.ravel()] = True
    new = -np.ones(len(nodes), dtype=np.int64)
    new[used] = np.arange(used.sum())
    return nodes[used], new[conn], new[station_nodes]
