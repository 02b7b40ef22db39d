"""windIO blade: airfoils and polars, outer shape, airfoil stack and the 6x6 beam properties.

Shared by both ontology versions; :class:`~windflutter.model.windio_common.Keys` says where each
version keeps a block and which units it uses.  Every array is checked at the file's own
stations (:mod:`windflutter.model.plausibility`) before anything is interpolated.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.model import plausibility as pl
from windflutter.model.airfoil_geom import orient_contour
from windflutter.model.beamprops import beamdyn_mass_matrix, beamdyn_to_section, repair_precomp_inertia
from windflutter.model.checks import Reader, join
from windflutter.model.turbine import Airfoil, BeamProperties, Blade, BladeDamping, Polar
from windflutter.model.v1arcs import contour_at
from windflutter.model.windio_common import Keys, ref_axis, shape_and_axis
from windflutter.model.windio_layup import layup_v1, layup_v2


# ------------------------------------------------------------------------------------- airfoils
def airfoils(data: dict, r: Reader, k: Keys, notes: pl.Notes) -> dict[str, Airfoil]:
    """``airfoils[]``: name, relative thickness, contour (reordered TE -> suction -> LE), polars."""
    out: dict[str, Airfoil] = {}
    for i, a in enumerate(r.seq(data, "", "airfoils")):
        p = f"airfoils[{i}]"
        name = r.string(a, p, "name")
        rt_key = "rthick" if "rthick" in a else "relative_thickness"
        rthick = r.number(a, p, rt_key, positive=True)
        pl.relative_thickness(rthick, join(p, rt_key), notes)
        ac = r.number(a, p, "aerodynamic_center", default=0.25)
        coords = r.mapping(a, p, "coordinates")
        x = r.array(r.get(coords, join(p, "coordinates"), "x"), join(p, "coordinates.x"), min_len=3)
        y = r.array(r.get(coords, join(p, "coordinates"), "y"), join(p, "coordinates.y"), min_len=3)
        if x.size != y.size:
            raise InputError(join(p, "coordinates.y"), f"{y.size} values", f"{x.size} (as many as x)", r.source)
        x, y = orient_contour(x, y)
        polars, res = [], []
        for j, pol in enumerate(r.seq(a, p, "polars", default=[])):
            pp = f"{p}.polars[{j}]"
            sets = [(pol, pp, ("c_l", "c_d", "c_m"))]  # v1
            if "re_sets" in pol:  # v2
                sets = [(rs, f"{pp}.re_sets[{m}]", ("cl", "cd", "cm")) for m, rs in enumerate(r.seq(pol, pp, "re_sets"))]
            for d, q, keys in sets:
                polars.append(_polar(d, r, q, keys, k, name, rthick, notes))
                res.append(float(d["re"]) if isinstance(d.get("re"), (int, float)) else np.nan)
        out[name] = Airfoil(name=name, x=x, y=y, relative_thickness=rthick, aerodynamic_center=ac,
                            polars=tuple(polars), reynolds=np.asarray(res, dtype=float))
    return out


def _polar(d: dict, r: Reader, p: str, keys: tuple[str, str, str], k: Keys, name: str, rthick: float,
           notes: pl.Notes) -> Polar:
    arrays = []
    alpha = None
    for key in keys:
        g, v = _angle_grid(r, d, p, key)
        if alpha is None:
            alpha = g
        elif g.size != alpha.size or np.max(np.abs(g - alpha)) > 1e-6:
            v = np.interp(alpha, g, v)
        arrays.append(v)
    alpha_si = np.asarray(alpha) * k.angle
    pl.polar(alpha_si, arrays[0], arrays[1], rthick, p, "deg" if k.angle != 1.0 else "rad", notes,
             alpha_field=join(p, f"{keys[0]}.grid"))
    return Polar(alpha=alpha_si, cl=arrays[0], cd=arrays[1], cm=arrays[2], name=name, relative_thickness=rthick)


def _angle_grid(r: Reader, d: dict, p: str, key: str) -> tuple[np.ndarray, np.ndarray]:
    dd = r.mapping(d, p, key)
    q = join(p, key)
    g = r.array(r.get(dd, q, "grid"), join(q, "grid"), min_len=2, increasing=True)
    v = r.array(r.get(dd, q, "values"), join(q, "values"), min_len=2)
    if g.size != v.size:
        raise InputError(join(q, "values"), f"{v.size} values", f"{g.size} values", r.source)
    # drop duplicated angles (e.g. -180 and 180 listed twice in some files)
    keep = np.concatenate([[True], np.diff(g) > 0])
    return g[keep], v[keep]


# ---------------------------------------------------------------------------------------- blade
def blade(b: dict, r: Reader, k: Keys, foils: dict, materials: dict, notes: pl.Notes) -> Blade:
    """``components.blade``: shape on the union of the axis, chord and twist grids, airfoil
    stack, layup (if any) and 6x6 properties (if any)."""
    shape_p, shape, ra_p, ra = shape_and_axis(b, r, k, "blade", k.blade_shape)
    s_ax, xyz_ax, arc_ax = ref_axis(ra, r, ra_p)
    if arc_ax[-1] <= 0:
        raise InputError(ra_p, "zero length", "a reference axis of positive length", r.source)
    for c, what in (("z", None), ("x", "prebend"), ("y", "sweep")):
        g, v = r.grid_values(ra, ra_p, c)
        if what is None:
            pl.span_axis(g, v, join(ra_p, "z.values"), notes)
        else:
            pl.offsets(g, v, float(arc_ax[-1]), what, join(ra_p, f"{c}.values"), notes)

    cg, cv = r.grid_values(shape, shape_p, "chord", positive=True)
    tg, tv = r.grid_values(shape, shape_p, "twist")
    tv = tv * k.angle
    pl.chord_twist(cg, cv, tg, tv, float(arc_ax[-1]), join(shape_p, "chord.values"), join(shape_p, "twist.values"),
                   notes)
    if k.major >= 2:
        og, ov = r.grid_values(shape, shape_p, "section_offset_y")
    else:
        pg, pv = r.grid_values(shape, shape_p, "pitch_axis")
        pl.pitch_axis(pg, pv, join(shape_p, "pitch_axis.values"), notes)
    s = np.unique(np.concatenate([s_ax, cg, tg]))
    chord = np.interp(s, cg, cv)
    if k.major >= 2:
        offset = np.interp(s, og, ov)
        pitch_axis = offset / chord
        pl.pitch_axis(og, ov / np.interp(og, cg, cv), join(shape_p, "section_offset_y.values"), notes)
    else:
        pitch_axis = np.interp(s, pg, pv)
        offset = pitch_axis * chord
    xyz = np.stack([np.interp(s, s_ax, xyz_ax[:, j]) for j in range(3)], axis=1)
    arc = np.interp(s, s_ax, arc_ax)
    pos_a, names = _airfoil_stack(shape, r, k, shape_p, foils)
    if "rthick" in shape:
        rg, rv = r.grid_values(shape, shape_p, "rthick", positive=True)
        rthick = np.interp(s, rg, rv)
    else:
        rthick = np.interp(s, pos_a, np.array([foils[n].relative_thickness for n in names]))
    layup = _layup(b, r, k, materials, foils, pos_a, names, s, rthick, chord, pitch_axis)
    twist = np.interp(s, tg, tv)
    beam, damping = blade_beam(b, r, k, float(arc[-1]), s, twist, notes)
    return Blade(
        s=s, ref_axis=xyz, arc_length=arc, chord=chord, twist=twist, pitch_axis=pitch_axis,
        section_offset_y=offset, relative_thickness=rthick, airfoil_positions=pos_a,
        airfoil_names=tuple(names), layup=layup, beam=beam, damping=damping,
    )


def _airfoil_stack(shape: dict, r: Reader, k: Keys, shape_p: str, foils: dict) -> tuple[np.ndarray, list[str]]:
    if k.major >= 2:
        names, pos = [], []
        for i, a in enumerate(r.seq(shape, shape_p, "airfoils")):
            q = f"{shape_p}.airfoils[{i}]"
            names.append(r.string(a, q, "name"))
            pos.append(r.number(a, q, "spanwise_position"))
        pos_a = r.array(pos, join(shape_p, "airfoils[].spanwise_position"), increasing=True, unit_interval=True)
    else:
        ap = r.mapping(shape, shape_p, "airfoil_position")
        q = join(shape_p, "airfoil_position")
        pos_a = r.array(r.get(ap, q, "grid"), join(q, "grid"), increasing=True, unit_interval=True)
        names = list(r.seq(ap, q, "labels"))
        if len(names) != pos_a.size:
            raise InputError(join(q, "labels"), f"{len(names)} labels", f"{pos_a.size} labels (one per grid point)",
                             r.source)
    for i, nm in enumerate(names):
        if nm not in foils:
            raise InputError(f"{shape_p} airfoil[{i}]", nm, f"one of the airfoils defined: {sorted(foils)}", r.source)
    return pos_a, names


def _layup(b, r, k, materials, foils, pos_a, names, s, rthick, chord, pitch_axis):
    struct = r.mapping(b, "components.blade", k.blade_struct, default=None)
    if struct is None:
        return None

    sp = f"components.blade.{k.blade_struct}"

    def geom(sq: float):
        x, y = contour_at(sq, pos_a, tuple(names), foils, float(np.interp(sq, s, rthick)))
        return x, y, float(np.interp(sq, s, chord)), float(np.interp(sq, s, pitch_axis))

    return (layup_v2 if k.major >= 2 else layup_v1)(struct, r, sp, materials, geom)


# ------------------------------------------------------------------------- blade beam properties
_UPPER = [(i, j) for i in range(6) for j in range(i, 6)]


def blade_beam(b: dict, r: Reader, k: Keys, length: float, s_blade: np.ndarray, twist_blade: np.ndarray,
               notes: pl.Notes) -> tuple[BeamProperties | None, BladeDamping | None]:
    """6x6 blade properties from the file (v2 ``structure.elastic_properties``, v1
    ``elastic_properties_mb.six_x_six``), checked at the file's stations and converted to the
    BeamSection convention; and the blade's ``structural_damping: mu`` if given."""
    got = _v2_six_by_six(b, r, k, notes) if k.major >= 2 else _v1_six_by_six(b, r, notes)
    if got is None:
        return None, None
    g, K, M, kp, src, mu, mu_field = got
    pl.section_matrices(K, None, g, kp, notes)
    twist = np.interp(g, s_blade, twist_blade)
    Ks, Ms = beamdyn_to_section(K, M)
    damping = None
    if mu is not None:
        damping = BladeDamping.from_beamdyn_mu(mu, source=f"{src} structural_damping.mu")
        pl.damping_mu(mu, mu_field, notes)
    return BeamProperties(s=g, stiffness=Ks, mass=Ms, twist=twist, length=float(length), source=src), damping


def _mu(ep: dict, r: Reader, p: str) -> np.ndarray | None:
    sd = ep.get("structural_damping") if isinstance(ep, dict) else None
    if sd is None:
        return None
    q = join(p, "structural_damping")
    return r.array(r.get(sd, q, "mu"), join(q, "mu"), min_len=6, nonneg=True)[:6]


def _v2_six_by_six(b: dict, r: Reader, k: Keys, notes: pl.Notes):
    st = b.get(k.blade_struct) or {}
    ep = st.get("elastic_properties")
    p = f"components.blade.{k.blade_struct}.elastic_properties"
    if not ep:
        return None
    K_d, I_d = r.mapping(ep, p, "stiffness_matrix"), r.mapping(ep, p, "inertia_matrix")
    kp, ip = join(p, "stiffness_matrix"), join(p, "inertia_matrix")
    gk = r.array(r.get(K_d, kp, "grid"), join(kp, "grid"), min_len=2, increasing=True, unit_interval=True)
    pl.bounded_count(gk.size, join(kp, "grid"), r.source)
    K = np.zeros((gk.size, 6, 6))
    for i, j in _UPPER:
        key = f"K{i + 1}{j + 1}"
        if key in K_d:
            K[:, i, j] = K[:, j, i] = _column(r, K_d, kp, key, gk.size)
    gi = r.array(r.get(I_d, ip, "grid"), join(ip, "grid"), min_len=2, increasing=True, unit_interval=True)

    def col(key, default=None):
        if key not in I_d and default is not None:
            return np.full(gi.size, default)
        return _column(r, I_d, ip, key, gi.size)

    mass = col("mass")
    if (mass <= 0).any():
        i = int(np.argmax(mass <= 0))
        raise InputError(f"{join(ip, 'mass')}[{i}] (span {gi[i]:.4f})", float(mass[i]),
                         "a positive mass per length (kg/m)", r.source)
    M = beamdyn_mass_matrix(mass, col("cm_x", 0.0), col("cm_y", 0.0), col("i_edge"), col("i_flap"),
                            col("i_plr", np.nan), col("i_cp", 0.0))
    M = repair_precomp_inertia(M, ip, r.source)
    pl.section_matrices(None, M, gi, ip, notes)  # mass at its own stations, before it is interpolated
    if gi.size != gk.size or np.max(np.abs(gi - gk)) > 1e-9:
        M = _resample(M, gi, gk)
    return (gk, K, M, kp, "windIO v2 structure.elastic_properties", _mu(ep, r, p),
            join(p, "structural_damping.mu"))


def _v1_six_by_six(b: dict, r: Reader, notes: pl.Notes):
    epm = b.get("elastic_properties_mb") or {}
    ep = epm.get("six_x_six")
    p = "components.blade.elastic_properties_mb.six_x_six"
    if not ep:
        return None
    kg, kv = r.grid_values(ep, p, "stiff_matrix", values_ndim=2)
    ig, iv = r.grid_values(ep, p, "inertia_matrix", values_ndim=2)
    pl.bounded_count(kg.size, join(p, "stiff_matrix.grid"), r.source)
    if kv.shape[1] != 21 or iv.shape[1] != 21:
        raise InputError(p, f"{kv.shape[1]}/{iv.shape[1]} entries per station",
                         "21 upper-triangle entries per station", r.source)
    K = _from_upper(kv)
    M = repair_precomp_inertia(_from_upper(iv), join(p, "inertia_matrix"), r.source)
    pl.section_matrices(None, M, ig, join(p, "inertia_matrix"), notes)
    if ig.size != kg.size or np.max(np.abs(ig - kg)) > 1e-9:
        M = _resample(M, ig, kg)
    mp = p if "structural_damping" in ep else "components.blade.elastic_properties_mb"
    mu = _mu(ep if mp == p else epm, r, mp)
    return (kg, K, M, join(p, "stiff_matrix"), "windIO v1 elastic_properties_mb.six_x_six", mu,
            join(mp, "structural_damping.mu"))


def _column(r: Reader, d: dict, p: str, key: str, n: int) -> np.ndarray:
    if key not in d:
        raise InputError(join(p, key), "<missing>", "a required key", r.source)
    v = r.array(d[key], join(p, key))
    if v.size != n:
        raise InputError(join(p, key), f"{v.size} values", f"{n} values (one per grid point)", r.source)
    return v


def _resample(M: np.ndarray, g_from: np.ndarray, g_to: np.ndarray) -> np.ndarray:
    """(n, 6, 6) tables linearly resampled from one span grid to another."""
    flat = M.reshape(M.shape[0], 36)
    return np.stack([np.interp(g_to, g_from, flat[:, j]) for j in range(36)], axis=-1).reshape(-1, 6, 6)


def _from_upper(v: np.ndarray) -> np.ndarray:
    A = np.zeros((v.shape[0], 6, 6))
    for n, (i, j) in enumerate(_UPPER):
        A[:, i, j] = v[:, n]
        A[:, j, i] = v[:, n]
    return A
