"""windIO materials, tower, hub, nacelle/drivetrain and control blocks (both ontology versions)."""

from __future__ import annotations

from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.model import plausibility as pl
from windflutter.model.checks import Reader, join
from windflutter.model.turbine import ControlSettings, Hub, IsotropicMaterial, Nacelle, OrthotropicMaterial, Tower, TowerLayer
from windflutter.model.windio_common import Keys, inertia6, ref_axis, shape_and_axis
from windflutter.units import DEG, RPM


# ------------------------------------------------------------------------------------ materials
def materials(data: dict, r: Reader, k: Keys, notes: pl.Notes) -> tuple[dict, dict]:
    """``materials[]`` -> name -> material, and name -> ply thickness (m) where given."""
    mats: dict = {}
    ply: dict = {}
    for i, m in enumerate(r.seq(data, "", "materials")):
        p = f"materials[{i}]"
        name = r.string(m, p, "name")
        orth = int(r.number(m, p, "orth", default=0))
        rho = r.number(m, p, "rho", positive=True)
        if orth:
            E = r.array(r.get(m, p, "E"), join(p, "E"), min_len=2, positive=True)
            G = r.array(r.get(m, p, "G"), join(p, "G"), min_len=1, positive=True)
            nu = r.array(r.get(m, p, "nu"), join(p, "nu"), min_len=1)
            G = np.resize(G, 3) if G.size < 3 else G
            mats[name] = OrthotropicMaterial(
                E1=E[0], E2=E[1], nu12=float(nu[0]), G12=G[0], G13=G[1], G23=G[2], rho=rho, name=name
            )
            pl.material(name, float(E.max()), rho, p, notes)
        else:
            E = _scalar_or_first(r, m, p, "E")
            nu = _scalar_or_first(r, m, p, "nu", positive=False)
            if not -1.0 < nu <= 0.5:
                raise InputError(join(p, "nu"), nu, "a Poisson ratio in (-1, 0.5]", r.source)
            mats[name] = IsotropicMaterial(E=E, nu=nu, rho=rho, name=name)
            pl.material(name, E, rho, p, notes)
        if "ply_t" in m:
            ply[name] = r.number(m, p, "ply_t", positive=True)
    return mats, ply


def _scalar_or_first(r: Reader, m: dict, p: str, key: str, positive: bool = True) -> float:
    v = r.get(m, p, key)
    if isinstance(v, list):
        v = r.array(v, join(p, key))[0]
    return r.as_number(v, join(p, key), positive=positive)


# ---------------------------------------------------------------------------------------- tower
def tower(t: dict, r: Reader, k: Keys, materials: dict) -> Tower:
    shape_p, shape, ra_p, ra = shape_and_axis(t, r, k, "tower", k.tower_shape)
    s_ax, xyz, _ = ref_axis(ra, r, ra_p)
    dg, dv = r.grid_values(shape, shape_p, "outer_diameter", positive=True)
    st_p = f"components.tower.{k.tower_struct}"
    st = r.mapping(t, "components.tower", k.tower_struct)
    lays = r.seq(st, st_p, "layers")
    grids = [s_ax, dg]
    raw = []
    for i, lay in enumerate(lays):
        q = f"{st_p}.layers[{i}]"
        mat = r.string(lay, q, "material")
        if mat not in materials:
            raise InputError(join(q, "material"), mat, f"a defined material ({sorted(materials)})", r.source)
        tg, tv = r.grid_values(lay, q, "thickness", nonneg=True)
        grids.append(tg)
        raw.append((r.string(lay, q, "name", default=f"layer{i}"), mat, tg, tv))
    s = np.unique(np.concatenate(grids))
    z = np.interp(s, s_ax, xyz[:, 2])
    if np.any(np.diff(z) <= 0):
        raise InputError(join(ra_p, "z.values"), "non-increasing", "tower heights increasing from base to top",
                         r.source)
    d = np.interp(s, dg, dv)
    layers = tuple(TowerLayer(name=n, material=m, thickness=np.interp(s, tg, tv)) for n, m, tg, tv in raw)
    wall = np.sum([lay.thickness for lay in layers], axis=0)
    if np.any(2 * wall >= d):
        i = int(np.argmax(2 * wall >= d))
        raise InputError(f"{st_p}.layers", float(wall[i]), f"a wall thinner than the radius ({d[i] / 2:.3f} m)",
                         r.source)
    of = r.number(st, st_p, "outfitting_factor", default=1.0, positive=True)
    return Tower(s=s, z=z, outer_diameter=d, layers=layers, outfitting_factor=of)


# ---------------------------------------------------------------------------------- hub/nacelle
def hub(h: dict, r: Reader, k: Keys, data: dict) -> Hub:
    p = "components.hub"
    key = "elastic_properties" if "elastic_properties" in h else "elastic_properties_mb"
    mass, inertia, _ = lumped(h.get(key), r, join(p, key))
    return Hub(
        mass=float(mass), inertia=inertia, diameter=r.number(h, p, "diameter", positive=True),
        precone=r.number(h, p, "cone_angle") * k.angle, cg_offset=0.0,
    )


def lumped(ep, r: Reader, p: str) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, 3x3 inertia, CG) of an ``elastic_properties(_mb)`` block (windIO v2 ``mass``,
    ``inertia``, ``location``; v1 ``system_mass``, ``system_inertia``, ``system_center_mass``);
    NaN where absent."""
    mass, inertia, cg = np.nan, np.full((3, 3), np.nan), np.full(3, np.nan)
    if not isinstance(ep, dict):
        return mass, inertia, cg
    keys = {k: (k if k in ep else alt) for k, alt in (("mass", "system_mass"), ("inertia", "system_inertia"),
                                                      ("location", "system_center_mass"))}
    if keys["mass"] in ep:
        mass = r.number(ep, p, keys["mass"], positive=True)
    if keys["inertia"] in ep:
        inertia = inertia6(r.array(ep[keys["inertia"]], join(p, keys["inertia"]), min_len=6)[:6])
    if keys["location"] in ep:
        cg = r.array(ep[keys["location"]], join(p, keys["location"]), min_len=3)[:3]
    return mass, inertia, cg


def nacelle(comps: dict, r: Reader, k: Keys, tower: Tower) -> Nacelle:
    if k.major >= 2:
        p = "components.drivetrain"
        dt = r.mapping(comps, "components", "drivetrain")
        shape = r.mapping(dt, p, "outer_shape")
        sp = join(p, "outer_shape")
        gear = (dt.get("gearbox") or {}).get("gear_ratio", 1.0)
        ep = dt.get("elastic_properties")
        ep_p = join(p, "elastic_properties")
    else:
        p = "components.nacelle"
        nac = r.mapping(comps, "components", "nacelle")
        shape = r.mapping(nac, p, "drivetrain")
        sp = join(p, "drivetrain")
        dt = shape
        gear = shape.get("gear_ratio", 1.0)
        ep = shape.get("elastic_properties_mb")
        ep_p = join(sp, "elastic_properties_mb")
    tilt = r.number(shape, sp, "uptilt") * k.angle
    overhang_h = r.number(shape, sp, "overhang")  # horizontal distance tower axis -> hub (m)
    dz = r.number(shape, sp, "distance_tt_hub")  # vertical distance tower top -> hub centre (m)
    # Along-shaft overhang (OpenFAST sign: negative upwind); Twr2Shft from the apex height.
    overhang = -overhang_h / np.cos(tilt)
    tower_to_shaft = dz - overhang_h * np.tan(tilt)
    mass, inertia, cg = lumped(ep, r, ep_p)
    if not isinstance(gear, (int, float)):
        gear = 1.0
    return Nacelle(
        mass=float(mass), inertia=inertia, cg=cg, overhang=float(overhang), shaft_tilt=float(tilt),
        tower_to_shaft=float(tower_to_shaft), gear_ratio=float(gear),
    )


# -------------------------------------------------------------------------------------- control
#: control fields that must be positive when given (a negative maximum rotor speed, cut-in or TSR
#: is not a controller); the minimum rotor speed may be zero, the pitch limits negative
_POSITIVE = ("cut_in", "cut_out", "max_tip_speed", "max_pitch_rate", "tsr", "max_rotor_speed")


def control(c: Any, r: Reader, k: Keys, radius: float | None = None, notes: pl.Notes | None = None) -> ControlSettings:
    """The ``control`` block (windIO 1 nested keys or the 2.1 flat keys), SI.  Signs are checked
    here (an :class:`InputError` names the key and the file's value); with the rotor ``radius``
    (m) and ``notes`` the limits are checked against each other and for plausibility
    (:func:`windflutter.model.plausibility.control_limits`)."""
    if not isinstance(c, dict):
        return ControlSettings()
    p = "control"
    sup = c.get("supervisory") or {}
    pit = c.get("pitch") or {}
    tq = c.get("torque") or {}
    where: dict[str, tuple[str, float]] = {}  # field -> (key in the file, value as written)

    def num(field_, d, q, key, scale=1.0, default=np.nan):
        if not isinstance(d, dict) or key not in d:
            return default
        raw = r.number(d, q, key, positive=field_ in _POSITIVE, nonneg=field_ == "min_rotor_speed")
        where[field_] = (join(q, key), raw)
        return raw * scale

    kw = dict(
        cut_in=num("cut_in", sup, f"{p}.supervisory", "Vin"),
        cut_out=num("cut_out", sup, f"{p}.supervisory", "Vout"),
        max_tip_speed=num("max_tip_speed", sup, f"{p}.supervisory", "maxTS"),
        min_pitch=num("min_pitch", pit, f"{p}.pitch", "min_pitch", k.angle, 0.0),
        max_pitch=num("max_pitch", pit, f"{p}.pitch", "max_pitch", k.angle),
        max_pitch_rate=num("max_pitch_rate", pit, f"{p}.pitch", "max_pitch_rate", k.angle),
        tsr=num("tsr", tq, f"{p}.torque", "tsr"),
        min_rotor_speed=num("min_rotor_speed", tq, f"{p}.torque", "VS_minspd", k.speed),
        max_rotor_speed=num("max_rotor_speed", tq, f"{p}.torque", "VS_maxspd", k.speed),
    )
    if isinstance(tq, dict) and "max_torque_rate" in tq:  # not used; a negative rate is no controller
        r.number(tq, f"{p}.torque", "max_torque_rate", positive=True)
    # windIO 2.1 flat control keys (rpm / deg)
    flat = {"min_rotor_speed": ("min_rotor_speed", RPM), "max_rotor_speed": ("max_rotor_speed", RPM),
            "min_pitch_limit": ("min_pitch", DEG), "max_pitch_limit": ("max_pitch", DEG),
            "max_pitch_rate": ("max_pitch_rate", DEG), "optimal_tsr": ("tsr", 1.0)}
    for key, (field_, scale) in flat.items():
        if key in c and not isinstance(c[key], dict):
            kw[field_] = num(field_, c, p, key, scale)
    out = ControlSettings(**kw)
    if radius is not None and notes is not None:
        pl.control_limits(out, where, radius, notes)
    return out
