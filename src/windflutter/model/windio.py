"""windIO turbine readers (ontology v1.x and v2.x) -> :class:`~windflutter.model.turbine.Turbine`.

Public entry point: :func:`load_turbine` (a path or a bundled name).  Steps:

1. YAML parsing with YAML-1.2 numbers (``5e-05`` is a float, see :mod:`.yamlio`).
2. Version detection: ``windIO_version: '2.x'`` -> v2; no version key -> v1 (``outer_shape_bem``,
   ``internal_structure_2d_fem``, ``nacelle``).
3. Validation.  v2: the windIO 2.1.1 JSON schema (``windIO.validate`` machinery, non-restrictive:
   extra keys allowed) - every violation is reported as :class:`InputError` with its path in the
   file.  v1: windIO 2.x ships no v1 schema, so v1 files get the structural checks of our own
   readers (required keys, types, array lengths, ranges) - the same checks also run on v2 files.
4. Conversion to SI/radians.  v2 files give twist, cone, tilt, polar angles and control angles in
   degrees and rotor speeds in rpm; v1 files give radians and rad/s (see docs/turbine_input.md).
5. Supplementary data (hub/nacelle masses, operating curve...) from a ``windflutter:`` block in the
   file or a sibling ``<stem>.windflutter.yaml`` (see :mod:`.supplement`).
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.model.checks import Reader, join
from windflutter.model.turbine import (
    Airfoil,
    BeamProperties,
    Blade,
    ControlSettings,
    Hub,
    IsotropicMaterial,
    Layer,
    Layup,
    Nacelle,
    OrthotropicMaterial,
    Polar,
    Tower,
    TowerLayer,
    Turbine,
    Web,
)
from windflutter.model.yamlio import load_yaml_file

DEG = np.pi / 180.0
RPM = np.pi / 30.0


# ------------------------------------------------------------------------------------ validation
@functools.lru_cache(maxsize=1)
def _v2_validator():
    """jsonschema validator for the windIO 2.x turbine schema (cached: building it is slow)."""
    import jsonschema
    import windIO
    from windIO.validator import registry  # the $ref registry windIO uses for its own validate()

    schema = windIO.load_yaml(Path(windIO.__file__).parent / "schemas" / "turbine" / "turbine_schema.yaml")
    cls = jsonschema.validators.validator_for(schema)
    return cls(schema, registry=registry)


def validate_windio_v2(data: dict, source: str | None = None) -> None:
    """Validate against the windIO 2.1.1 turbine schema (extra keys allowed).

    Raises
    ------
    InputError
        For the first violation (the one deepest in the file among the best matches), with its
        dotted path, offending value and the schema's message.
    """
    import jsonschema

    validator = _v2_validator()
    # the 'windflutter' supplement block is our extension (the schema forbids unknown top-level keys)
    data = {k: v for k, v in data.items() if k != "windflutter"}
    errors = list(validator.iter_errors(data))
    if not errors:
        return
    err = max(errors, key=jsonschema.exceptions.relevance)
    # descend into oneOf/anyOf contexts: take the alternative (schema branch) with the fewest
    # errors - the one the user most likely meant - and its deepest error
    while err.context:
        branches: dict = {}
        for c in err.context:
            branches.setdefault(c.schema_path[0] if c.schema_path else 0, []).append(c)
        fewest = min(branches.values(), key=len)
        err = max(fewest, key=lambda c: len(c.absolute_path))
    path = _json_path(err.absolute_path)
    raise InputError(path or "<top level>", err.instance, f"windIO schema: {err.message}", source)


def _json_path(parts) -> str:
    out = ""
    for p in parts:
        out = join(out, p)
    return out


def windio_major_version(data: dict) -> int:
    """1 for windIO 1.x files (no ``windIO_version`` key), 2 for 2.x."""
    v = data.get("windIO_version")
    if v is None:
        return 1
    try:
        return int(str(v).split(".")[0])
    except ValueError:
        raise InputError("windIO_version", v, "a version string such as '2.0'") from None


# ----------------------------------------------------------------------------------- entry point
def load_turbine(path_or_name: str | Path, validate: bool = True) -> Turbine:
    """Read a turbine: a windIO v1/v2 file, a windflutter seed file, or a bundled name.

    Parameters
    ----------
    path_or_name : a file path, or one of the bundled names (see
        :func:`windflutter.model.bundled.bundled_turbines`), e.g. ``"nrel5mw"``, ``"iea15mw"``,
        ``"iea15mw_v1"``, ``"seed5mw"``, ``"seed20mw"``.
    validate : run the windIO schema validation (v2 files; ~0.5-1 s for large files).

    Raises
    ------
    InputError
        Missing file, YAML syntax error, schema violation or inconsistent data; the message names
        the path inside the file.
    """
    from windflutter.model.bundled import resolve_turbine_path
    from windflutter.model.supplement import apply_supplement, find_supplement

    path = resolve_turbine_path(path_or_name)
    data = load_yaml_file(path)
    source = str(path)
    turbine, raw = read_windio_dict(data, source=source, validate=validate)
    supp, supp_source = find_supplement(data, path)
    turbine = apply_supplement(turbine, raw, supp, base_dir=path.parent, source=supp_source or source)
    _check_rigid_body_inertias(turbine, supp_source or source)
    return turbine


def _check_rigid_body_inertias(turbine: Turbine, source: str | None) -> None:
    """Hub and nacelle inertia tensors must be symmetric positive semi-definite.

    A tensor that is not (e.g. a yaw inertia written into the Iyz slot of the 6-vector) would
    make the whole-turbine mass matrix indefinite; refuse it here, naming the field.
    """
    for name, body in (("hub", turbine.hub), ("nacelle", turbine.nacelle)):
        J = np.asarray(body.inertia, dtype=float)
        if J.shape != (3, 3) or not np.all(np.isfinite(J)):
            raise InputError(f"{name}.inertia", J.tolist(), "a finite 3x3 inertia tensor (kg m^2)", source)
        ev = np.linalg.eigvalsh(0.5 * (J + J.T))
        if ev.min() < -1e-9 * max(abs(ev).max(), 1.0):
            raise InputError(
                f"{name}.inertia", J.tolist(),
                "a positive semi-definite inertia tensor (Ixx, Iyy, Izz, Ixy, Ixz, Iyz order; "
                "products of inertia must not exceed the moments)", source,
            )


def read_windio_dict(data: dict, source: str | None = None, validate: bool = True) -> tuple[Turbine, dict]:
    """Convert a parsed windIO dict to a :class:`Turbine` (without supplement); also returns the
    dict (for the supplement step)."""
    major = windio_major_version(data)
    if major >= 2:
        if validate:
            validate_windio_v2(data, source)
        return _read(data, _V2, Reader(source), f"{data.get('windIO_version')}"), data
    return _read(data, _V1, Reader(source), "1.x"), data


# ------------------------------------------------------------------------- version differences
class _Keys:
    """Where things live in each ontology version and which angle units are used."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


_V2 = _Keys(
    major=2,
    blade_shape="outer_shape",
    blade_struct="structure",
    tower_shape="outer_shape",
    tower_struct="structure",
    nacelle="drivetrain",
    angle=DEG,  # twist, cone, tilt, polar alpha, fibre orientation, control angles
    speed=RPM,  # control rotor speeds
    rthick_key="rthick",
)
_V1 = _Keys(
    major=1,
    blade_shape="outer_shape_bem",
    blade_struct="internal_structure_2d_fem",
    tower_shape="outer_shape_bem",
    tower_struct="internal_structure_2d_fem",
    nacelle="nacelle",
    angle=1.0,
    speed=1.0,
    rthick_key="relative_thickness",
)


def _read(data: dict, k: _Keys, r: Reader, version: str) -> Turbine:
    asm = r.mapping(data, "", "assembly")
    comps = r.mapping(data, "", "components")
    materials, ply_t = _materials(data, r, k)
    airfoils = _airfoils(data, r, k)
    blade = _blade(r.mapping(comps, "components", "blade"), r, k, airfoils, materials)
    tower = _tower(r.mapping(comps, "components", "tower"), r, k, materials)
    hub = _hub(r.mapping(comps, "components", "hub"), r, k, data)
    nac = _nacelle(comps, r, k, tower)
    control = _control(data.get("control"), r, k)
    orient = str(asm.get("rotor_orientation", "upwind")).lower()
    rated_speed = control.max_rotor_speed
    ctrl = data.get("control") or {}
    if "rated_rotor_speed" in ctrl:
        rated_speed = r.number(ctrl, "control", "rated_rotor_speed", positive=True) * k.speed
    return Turbine(
        name=str(data.get("name", Path(r.source or "turbine").stem)),
        n_blades=int(r.number(asm, "assembly", "number_of_blades", positive=True)),
        hub_height=r.number(asm, "assembly", "hub_height", positive=True),
        rotor_diameter=r.number(asm, "assembly", "rotor_diameter", positive=True),
        rated_power=r.number(asm, "assembly", "rated_power", positive=True),
        rated_rotor_speed=float(rated_speed),
        blade=blade,
        tower=tower,
        hub=hub,
        nacelle=nac,
        airfoils=airfoils,
        materials=materials,
        ply_thickness=ply_t,
        control=control,
        rotor_orientation="downwind" if orient.startswith("down") else "upwind",
        source=r.source or "",
        windio_version=version,
    )


# ------------------------------------------------------------------------------------ materials
def _materials(data: dict, r: Reader, k: _Keys) -> tuple[dict, dict]:
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
        else:
            E = _scalar_or_first(r, m, p, "E")
            nu = _scalar_or_first(r, m, p, "nu", positive=False)
            if not -1.0 < nu <= 0.5:
                raise InputError(join(p, "nu"), nu, "a Poisson ratio in (-1, 0.5]", r.source)
            mats[name] = IsotropicMaterial(E=E, nu=nu, rho=rho, name=name)
        if "ply_t" in m:
            ply[name] = r.number(m, p, "ply_t", positive=True)
    return mats, ply


def _scalar_or_first(r: Reader, m: dict, p: str, key: str, positive: bool = True) -> float:
    v = r.get(m, p, key)
    if isinstance(v, list):
        v = r.array(v, join(p, key))[0]
    return r.as_number(v, join(p, key), positive=positive)


# ------------------------------------------------------------------------------------- airfoils
def _airfoils(data: dict, r: Reader, k: _Keys) -> dict[str, Airfoil]:
    out: dict[str, Airfoil] = {}
    for i, a in enumerate(r.seq(data, "", "airfoils")):
        p = f"airfoils[{i}]"
        name = r.string(a, p, "name")
        rt_key = "rthick" if "rthick" in a else "relative_thickness"
        rthick = r.number(a, p, rt_key, positive=True)
        ac = r.number(a, p, "aerodynamic_center", default=0.25)
        coords = r.mapping(a, p, "coordinates")
        x = r.array(r.get(coords, join(p, "coordinates"), "x"), join(p, "coordinates.x"), min_len=3)
        y = r.array(r.get(coords, join(p, "coordinates"), "y"), join(p, "coordinates.y"), min_len=3)
        if x.size != y.size:
            raise InputError(join(p, "coordinates.y"), f"{y.size} values", f"{x.size} (as many as x)", r.source)
        x, y = _orient_contour(x, y)
        polars, res = [], []
        for j, pol in enumerate(r.seq(a, p, "polars", default=[])):
            pp = f"{p}.polars[{j}]"
            if "re_sets" in pol:  # v2
                for m, rs in enumerate(r.seq(pol, pp, "re_sets")):
                    q = f"{pp}.re_sets[{m}]"
                    polars.append(_polar(rs, r, q, ("cl", "cd", "cm"), k.angle, name, rthick))
                    res.append(float(rs.get("re", np.nan)) if isinstance(rs.get("re"), (int, float)) else np.nan)
            else:  # v1
                polars.append(_polar(pol, r, pp, ("c_l", "c_d", "c_m"), k.angle, name, rthick))
                res.append(float(pol.get("re", np.nan)) if isinstance(pol.get("re"), (int, float)) else np.nan)
        out[name] = Airfoil(
            name=name, x=x, y=y, relative_thickness=rthick, aerodynamic_center=ac, polars=tuple(polars),
            reynolds=np.asarray(res, dtype=float),
        )
    return out


def _orient_contour(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Order the contour TE -> suction side (y > 0) -> LE -> pressure side -> TE.

    windIO fixes nondimensional arc 0 at the trailing edge, increasing over the suction side, but
    some files (e.g. the NREL 5 MW DU airfoils in WISDEM's examples) list the pressure side first.
    A contour traversed TE -> upper -> LE -> lower -> TE encloses positive signed area
    (counter-clockwise), so the arrays are reversed when the signed area is negative.
    """
    area = 0.5 * np.sum(x[:-1] * y[1:] - x[1:] * y[:-1])
    if area < 0:
        return x[::-1].copy(), y[::-1].copy()
    return x, y


def _polar(d: dict, r: Reader, p: str, keys: tuple[str, str, str], angle: float, name: str, rthick: float) -> Polar:
    arrays = []
    alpha = None
    for key in keys:
        g, v = r.grid_values_angle(d, p, key) if hasattr(r, "grid_values_angle") else _angle_grid(r, d, p, key)
        if alpha is None:
            alpha = g
        elif g.size != alpha.size or np.max(np.abs(g - alpha)) > 1e-6:
            v = np.interp(alpha, g, v)
        arrays.append(v)
    alpha = np.asarray(alpha) * angle
    return Polar(alpha=alpha, cl=arrays[0], cd=arrays[1], cm=arrays[2], name=name, relative_thickness=rthick)


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
def _ref_axis(d: dict, r: Reader, p: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reference axis (x, y, z) interpolated on the union of the three grids."""
    comps = []
    for c in ("x", "y", "z"):
        comps.append(r.grid_values(d, p, c))
    s = np.unique(np.concatenate([g for g, _ in comps]))
    xyz = np.stack([np.interp(s, g, v) for g, v in comps], axis=1)
    seg = np.linalg.norm(np.diff(xyz, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    return s, xyz, arc


def _blade(b: dict, r: Reader, k: _Keys, airfoils: dict, materials: dict) -> Blade:
    shape_p = f"components.blade.{k.blade_shape}"
    shape = r.mapping(b, "components.blade", k.blade_shape)
    if k.major >= 2:
        ra_p = "components.blade.reference_axis"
        ra = r.mapping(b, "components.blade", "reference_axis")
    else:
        ra_p = join(shape_p, "reference_axis")
        ra = r.mapping(shape, shape_p, "reference_axis")
    s_ax, xyz_ax, arc_ax = _ref_axis(ra, r, ra_p)
    if arc_ax[-1] <= 0:
        raise InputError(ra_p, "zero length", "a reference axis of positive length", r.source)

    cg, cv = r.grid_values(shape, shape_p, "chord", positive=True)
    tg, tv = r.grid_values(shape, shape_p, "twist")
    tv = tv * k.angle
    if k.major >= 2:
        og, ov = r.grid_values(shape, shape_p, "section_offset_y")
    else:
        pg, pv = r.grid_values(shape, shape_p, "pitch_axis")
    # common grid: union of the axis, chord and twist grids
    s = np.unique(np.concatenate([s_ax, cg, tg]))
    chord = np.interp(s, cg, cv)
    if k.major >= 2:
        offset = np.interp(s, og, ov)
        pitch_axis = offset / chord
    else:
        pitch_axis = np.interp(s, pg, pv)
        offset = pitch_axis * chord
    xyz = np.stack([np.interp(s, s_ax, xyz_ax[:, j]) for j in range(3)], axis=1)
    arc = np.interp(s, s_ax, arc_ax)

    # airfoil stack
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
        if nm not in airfoils:
            raise InputError(f"{shape_p} airfoil[{i}]", nm, f"one of the airfoils defined: {sorted(airfoils)}", r.source)

    rt_key = "rthick"
    if rt_key in shape:
        rg, rv = r.grid_values(shape, shape_p, rt_key, positive=True)
        rthick = np.interp(s, rg, rv)
    else:
        at = np.array([airfoils[n].relative_thickness for n in names])
        rthick = np.interp(s, pos_a, at)

    struct = r.mapping(b, "components.blade", k.blade_struct, default=None)
    layup = None
    if struct is not None:
        sp = f"components.blade.{k.blade_struct}"
        from windflutter.model.v1arcs import contour_at

        def geom(sq: float):
            x, y = contour_at(sq, pos_a, tuple(names), airfoils, float(np.interp(sq, s, rthick)))
            return x, y, float(np.interp(sq, s, chord)), float(np.interp(sq, s, pitch_axis))

        if k.major >= 2:
            layup = _layup_v2(struct, r, sp, materials, geom)
        else:
            layup = _layup_v1(struct, r, sp, materials, geom)

    beam = _blade_beam(b, r, k, arc[-1], s, tv_s := np.interp(s, tg, tv))
    return Blade(
        s=s, ref_axis=xyz, arc_length=arc, chord=chord, twist=tv_s, pitch_axis=pitch_axis,
        section_offset_y=offset, relative_thickness=rthick, airfoil_positions=pos_a,
        airfoil_names=tuple(names), layup=layup, beam=beam,
    )


# ----------------------------------------------------------------------------- layup, v2 anchors
def _layup_v2(st: dict, r: Reader, sp: str, materials: dict, geom=None) -> Layup:
    anchors: dict[str, tuple[dict, str]] = {}
    for i, a in enumerate(r.seq(st, sp, "anchors", default=[])):
        anchors[r.string(a, f"{sp}.anchors[{i}]", "name")] = (a, f"{sp}.anchors[{i}]")
    webs_in = r.seq(st, sp, "webs", default=[])
    for i, w in enumerate(webs_in):
        for j, a in enumerate(r.seq(w, f"{sp}.webs[{i}]", "anchors", default=[])):
            q = f"{sp}.webs[{i}].anchors[{j}]"
            anchors[r.string(a, q, "name")] = (a, q)

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
        from windflutter.model.airfoil_geom import perimeter

        per = np.array([perimeter(*geom(sq)[:2]) * geom(sq)[2] for sq in g])
        wnd = np.interp(g, gw, wv) / per
        base = np.interp(g, go, ao)
        return g, np.clip(base + wnd if handle == "end_nd_arc" else base - wnd, 0.0, 1.0)

    webs = []
    for i, w in enumerate(webs_in):
        q = f"{sp}.webs[{i}]"
        name = r.string(w, q, "name")
        g1, a1 = resolve(r.get(w, q, "start_nd_arc"), join(q, "start_nd_arc"))
        g2, a2 = resolve(r.get(w, q, "end_nd_arc"), join(q, "end_nd_arc"))
        s = np.unique(np.concatenate([g1, g2]))
        s0 = r.number(w, q, "start_nd_grid", default=float(s[0]))
        s1 = r.number(w, q, "end_nd_grid", default=float(s[-1]))
        webs.append(Web(name=name, s=s, start_arc=np.interp(s, g1, a1), end_arc=np.interp(s, g2, a2),
                        s_start=s0, s_end=s1))
    web_names = {w.name for w in webs}

    layers = []
    for i, lay in enumerate(r.seq(st, sp, "layers")):
        q = f"{sp}.layers[{i}]"
        name, mat, tg, tv, fo, web = _layer_fields(lay, q, r, materials, web_names)
        if web is None:
            g1, a1 = resolve(r.get(lay, q, "start_nd_arc"), join(q, "start_nd_arc"))
            g2, a2 = resolve(r.get(lay, q, "end_nd_arc"), join(q, "end_nd_arc"))
        else:
            g1 = g2 = np.array([0.0, 1.0])
            a1, a2 = np.zeros(2), np.ones(2)
        s = np.unique(np.concatenate([tg, g1, g2] + ([fo[0]] if fo is not None else [])))
        orient = np.interp(s, fo[0], fo[1]) * DEG if fo is not None else np.zeros_like(s)
        t_s, a0_s, a1_s = _collapse_inverted(q, name, s, np.interp(s, tg, tv), np.interp(s, g1, a1),
                                             np.interp(s, g2, a2), r.source)
        layers.append(Layer(
            name=name, material=mat, s=s, thickness=t_s, orientation=orient,
            start_arc=a0_s, end_arc=a1_s, web=web,
            s_start=r.number(lay, q, "start_nd_grid", default=float(tg[0])),
            s_end=r.number(lay, q, "end_nd_grid", default=float(tg[-1])),
        ))
    return Layup(webs=tuple(webs), layers=tuple(layers))


# ------------------------------------------------------------------------------------- layup, v1
def _layup_v1(st: dict, r: Reader, sp: str, materials: dict, geom) -> Layup:
    """windIO 1.x layup.  Explicit ``start_nd_arc``/``end_nd_arc`` are used as given; layers with
    neither (and no ``width``) cover the whole contour; parametric definitions (``offset_y_pa``,
    ``width``, ``midpoint_nd_arc``, arcs fixed to TE or to other layers) are resolved on the blade
    geometry by :mod:`windflutter.model.v1arcs`."""
    from windflutter.model.v1arcs import resolve_layer, resolve_web

    uniform = np.linspace(0.0, 1.0, 41)
    webs = []
    for i, w in enumerate(r.seq(st, sp, "webs", default=[])):
        q = f"{sp}.webs[{i}]"
        name = r.string(w, q, "name")
        if _explicit(w.get("start_nd_arc")) and _explicit(w.get("end_nd_arc")):
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
        name, mat, tg, tv, fo, web = _layer_fields(lay, q, r, materials, web_names)
        if web is not None:
            g1 = g2 = np.array([0.0, 1.0])
            a1, a2 = np.zeros(2), np.ones(2)
        elif _explicit(lay.get("start_nd_arc")) and _explicit(lay.get("end_nd_arc")):
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
        t_s, a0_s, a1_s = _collapse_inverted(q, name, s, np.interp(s, tg, tv), np.interp(s, g1, a1),
                                             np.interp(s, g2, a2), r.source)
        layers.append(Layer(
            name=name, material=mat, s=s, thickness=t_s, orientation=orient,
            start_arc=a0_s, end_arc=a1_s, web=web,
            s_start=float(tg[0]), s_end=float(tg[-1]),
        ))
    return Layup(webs=tuple(webs), layers=tuple(layers))


INVERTED_MAX = 0.5  # end_arc < start_arc by less than this (wrapped width > 0.5): inverted, not wrapping


def _collapse_inverted(q: str, name: str, s: np.ndarray, t: np.ndarray, a0: np.ndarray, a1: np.ndarray,
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

    from windflutter.errors import InputWarning

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
    if not _explicit(h):
        return False
    v = np.asarray(h["values"], dtype=float) if all(isinstance(x, (int, float)) for x in h["values"]) else None
    other = "start_nd_arc" if handle == "end_nd_arc" else "end_nd_arc"
    return v is not None and np.ptp(v) == 0.0 and v[0] in (0.0, 1.0) and other in a


def _explicit(d: Any) -> bool:
    return isinstance(d, dict) and "grid" in d and "values" in d


# ------------------------------------------------------------------------- blade beam properties
_UPPER = [(i, j) for i in range(6) for j in range(i, 6)]


def _blade_beam(b: dict, r: Reader, k: _Keys, length: float, s_blade: np.ndarray, twist_blade: np.ndarray):
    """6x6 blade properties from the file (v2 ``structure.elastic_properties``, v1
    ``elastic_properties_mb.six_x_six``), converted to the BeamSection convention."""
    from windflutter.model.beamprops import (
        beamdyn_mass_matrix, beamdyn_to_section, check_section_mass, repair_precomp_inertia,
    )

    if k.major >= 2:
        st = b.get(k.blade_struct) or {}
        ep = st.get("elastic_properties")
        p = f"components.blade.{k.blade_struct}.elastic_properties"
        if not ep:
            return None
        K_d = r.mapping(ep, p, "stiffness_matrix")
        I_d = r.mapping(ep, p, "inertia_matrix")
        kp, ip = join(p, "stiffness_matrix"), join(p, "inertia_matrix")
        gk = r.array(r.get(K_d, kp, "grid"), join(kp, "grid"), min_len=2, increasing=True, unit_interval=True)
        K = np.zeros((gk.size, 6, 6))
        for i, j in _UPPER:
            key = f"K{i + 1}{j + 1}"
            if key in K_d:
                v = r.array(K_d[key], join(kp, key))
                if v.size != gk.size:
                    raise InputError(join(kp, key), f"{v.size} values", f"{gk.size} values", r.source)
                K[:, i, j] = v
                K[:, j, i] = v
        gi = r.array(r.get(I_d, ip, "grid"), join(ip, "grid"), min_len=2, increasing=True, unit_interval=True)

        def col(key, default=None):
            if key not in I_d:
                if default is None:
                    raise InputError(join(ip, key), "<missing>", "a required key", r.source)
                return np.full(gi.size, default)
            v = r.array(I_d[key], join(ip, key))
            if v.size != gi.size:
                raise InputError(join(ip, key), f"{v.size} values", f"{gi.size} values", r.source)
            return v

        mass = col("mass")
        if (mass <= 0).any():
            raise InputError(join(ip, "mass"), float(mass.min()), "positive mass per length (kg/m)", r.source)
        M = beamdyn_mass_matrix(mass, col("cm_x", 0.0), col("cm_y", 0.0), col("i_edge"), col("i_flap"),
                                col("i_plr", np.nan), col("i_cp", 0.0))
        M = repair_precomp_inertia(M, ip, r.source)
        check_section_mass(M, gi, ip, r.source)
        if gi.size != gk.size or np.max(np.abs(gi - gk)) > 1e-9:
            M = np.stack([np.stack([np.interp(gk, gi, M[:, a, c]) for c in range(6)], -1) for a in range(6)], 1)
        g = gk
        src = "windIO v2 structure.elastic_properties"
    else:
        ep = (b.get("elastic_properties_mb") or {}).get("six_x_six")
        p = "components.blade.elastic_properties_mb.six_x_six"
        if not ep:
            return None
        kg, kv = r.grid_values(ep, p, "stiff_matrix", values_ndim=2)
        ig, iv = r.grid_values(ep, p, "inertia_matrix", values_ndim=2)
        if kv.shape[1] != 21 or iv.shape[1] != 21:
            raise InputError(p, f"{kv.shape[1]}/{iv.shape[1]} entries per station",
                             "21 upper-triangle entries per station", r.source)
        K = _from_upper(kv)
        M = repair_precomp_inertia(_from_upper(iv), join(p, "inertia_matrix"), r.source)
        check_section_mass(M, ig, join(p, "inertia_matrix"), r.source)
        if ig.size != kg.size or np.max(np.abs(ig - kg)) > 1e-9:
            M = np.stack([np.stack([np.interp(kg, ig, M[:, a, c]) for c in range(6)], -1) for a in range(6)], 1)
        g = kg
        src = "windIO v1 elastic_properties_mb.six_x_six"
    twist = np.interp(g, s_blade, twist_blade)
    Ks, Ms = beamdyn_to_section(K, M)
    return BeamProperties(s=g, stiffness=Ks, mass=Ms, twist=twist, length=float(length), source=src)


def _from_upper(v: np.ndarray) -> np.ndarray:
    A = np.zeros((v.shape[0], 6, 6))
    for n, (i, j) in enumerate(_UPPER):
        A[:, i, j] = v[:, n]
        A[:, j, i] = v[:, n]
    return A


# ---------------------------------------------------------------------------------------- tower
def _tower(t: dict, r: Reader, k: _Keys, materials: dict) -> Tower:
    shape_p = f"components.tower.{k.tower_shape}"
    shape = r.mapping(t, "components.tower", k.tower_shape)
    if k.major >= 2:
        ra_p, ra = "components.tower.reference_axis", r.mapping(t, "components.tower", "reference_axis")
    else:
        ra_p, ra = join(shape_p, "reference_axis"), r.mapping(shape, shape_p, "reference_axis")
    s_ax, xyz, _ = _ref_axis(ra, r, ra_p)
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
def _hub(h: dict, r: Reader, k: _Keys, data: dict) -> Hub:
    p = "components.hub"
    mass = np.nan
    inertia = np.full((3, 3), np.nan)
    ep = h.get("elastic_properties") or h.get("elastic_properties_mb")
    if isinstance(ep, dict):
        q = join(p, "elastic_properties" if "elastic_properties" in h else "elastic_properties_mb")
        mkey = "mass" if "mass" in ep else "system_mass"
        if mkey in ep:
            mass = r.number(ep, q, mkey, positive=True)
        ikey = "inertia" if "inertia" in ep else "system_inertia"
        if ikey in ep:
            inertia = _inertia6(r.array(ep[ikey], join(q, ikey), min_len=6)[:6])
    return Hub(
        mass=float(mass), inertia=inertia, diameter=r.number(h, p, "diameter", positive=True),
        precone=r.number(h, p, "cone_angle") * k.angle, cg_offset=0.0,
    )


def _layer_fields(lay: dict, q: str, r: Reader, materials: dict, web_names: set):
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


def _inertia6(v: np.ndarray) -> np.ndarray:
    """windIO 6-vector (Ixx, Iyy, Izz, Ixy, Ixz, Iyz) -> symmetric 3x3."""
    ixx, iyy, izz, ixy, ixz, iyz = v
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]], dtype=float)


def _nacelle(comps: dict, r: Reader, k: _Keys, tower: Tower) -> Nacelle:
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
    mass = np.nan
    inertia = np.full((3, 3), np.nan)
    cg = np.full(3, np.nan)
    if isinstance(ep, dict):
        mkey = "mass" if "mass" in ep else "system_mass"
        if mkey in ep:
            mass = r.number(ep, ep_p, mkey, positive=True)
        ikey = "inertia" if "inertia" in ep else "system_inertia"
        if ikey in ep:
            inertia = _inertia6(r.array(ep[ikey], join(ep_p, ikey), min_len=6)[:6])
        ckey = "location" if "location" in ep else "system_center_mass"
        if ckey in ep:
            cg = r.array(ep[ckey], join(ep_p, ckey), min_len=3)[:3]
    if not isinstance(gear, (int, float)):
        gear = 1.0
    return Nacelle(
        mass=float(mass), inertia=inertia, cg=cg, overhang=float(overhang), shaft_tilt=float(tilt),
        tower_to_shaft=float(tower_to_shaft), gear_ratio=float(gear),
    )


# -------------------------------------------------------------------------------------- control
def _control(c: Any, r: Reader, k: _Keys) -> ControlSettings:
    if not isinstance(c, dict):
        return ControlSettings()
    p = "control"
    sup = c.get("supervisory") or {}
    pit = c.get("pitch") or {}
    tq = c.get("torque") or {}

    def num(d, q, key, scale=1.0, default=np.nan):
        if key not in d:
            return default
        return r.number(d, q, key) * scale

    kw = dict(
        cut_in=num(sup, f"{p}.supervisory", "Vin"),
        cut_out=num(sup, f"{p}.supervisory", "Vout"),
        max_tip_speed=num(sup, f"{p}.supervisory", "maxTS"),
        min_pitch=num(pit, f"{p}.pitch", "min_pitch", k.angle, 0.0),
        max_pitch=num(pit, f"{p}.pitch", "max_pitch", k.angle),
        max_pitch_rate=num(pit, f"{p}.pitch", "max_pitch_rate", k.angle),
        tsr=num(tq, f"{p}.torque", "tsr"),
        min_rotor_speed=num(tq, f"{p}.torque", "VS_minspd", k.speed),
        max_rotor_speed=num(tq, f"{p}.torque", "VS_maxspd", k.speed),
    )
    # windIO 2.1 flat control keys (rpm / deg)
    flat = {"min_rotor_speed": ("min_rotor_speed", RPM), "max_rotor_speed": ("max_rotor_speed", RPM),
            "min_pitch_limit": ("min_pitch", DEG), "max_pitch_limit": ("max_pitch", DEG),
            "max_pitch_rate": ("max_pitch_rate", DEG), "optimal_tsr": ("tsr", 1.0)}
    for key, (field_, scale) in flat.items():
        if key in c and not isinstance(c[key], dict):
            kw[field_] = r.number(c, p, key) * scale
    return ControlSettings(**kw)
