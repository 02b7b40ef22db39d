"""Supplementary turbine data that a turbine file does not carry (or carries incompletely).

windIO files rarely give lumped hub/nacelle masses (WISDEM computes them from components) and
never an operating curve; OpenFAST decks and HAWC2 models have no operating curve either (it is
a result of their controllers).  windflutter reads such data from a ``windflutter:`` block,
either inside a windIO file (extra top-level keys are allowed by the windIO schema) or in a
sibling file ``<stem>.windflutter.yaml`` (looked up next to the turbine file, then one folder up,
so the ``windIO_v1/`` copies share the supplement of their v2 originals).  It works for every
format.  Values in the supplement override those of the turbine file.  User-facing units:
degrees, rpm and percent, with suffixes.

```yaml
windflutter:
  notes: ["where the numbers come from"]
  hub: {mass: 56780, inertia_shaft: 115926, cg_offset: 0.0}     # kg, kg m^2, m
  nacelle:
    mass: 240000                  # kg
    yaw_inertia: 2.60789e6        # kg m^2 (or inertia: [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] about the CG)
    cg: [1.9, 0.0, 1.75]          # m from the tower top, global axes
    overhang: -5.0191             # m along the shaft, OpenFAST sign (negative = upwind)
    shaft_tilt_deg: 5.0
    tower_to_shaft: 1.96256       # m
    generator_inertia: 534.116    # kg m^2 about the HSS
    gear_ratio: 97
    drivetrain_torsional_stiffness: 8.67637e8   # N m/rad
    drivetrain_torsional_damping: 6.215e6       # N m s/rad
    yaw_bearing_mass: 0.0
  precone_deg: 2.5
  rated_rotor_speed_rpm: 12.1
  rated_power_kw: 5000
  blade_mass_factor: 1.04536      # scales the blade's 6x6 mass (whatever file gave it)
  operating_curve: {file: ../nrel5mw/NREL5MW_Oper_Onshore_Flexible_Discon.csv, format: openfast_csv}
  # or: {wind_speed: [...], rotor_speed_rpm: [...], pitch_deg: [...]}
  blade_beam: {file: ../nrel5mw/NRELOffshrBsline5MW_BeamDyn_Blade.dat, format: beamdyn,
               main: ../nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat}
  blade_damping: {mu: [1e-3, 1e-3, 1e-3, 1.4e-3, 2.2e-3, 2.2e-3],   # BeamDyn mu1..mu6 (s)
                  flap_percent: [0.477, 0.477], edge_percent: [0.477], source: "..."}
  tower_damping: {fore_aft_percent: [1, 1], side_side_percent: [1, 1], source: "..."}
```
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model import plausibility as pl
from windflutter.model.beamdyn import read_beamdyn_blade, read_beamdyn_main
from windflutter.model.checks import Reader
from windflutter.model.elastodyn import read_elastodyn_blade
from windflutter.model.operating import (
    curve_from_control,
    curve_from_inline,
    read_hawc2_opt,
    read_openfast_steady_csv,
)
from windflutter.model.section import layup_beam_sections
from windflutter.model.turbine import BeamProperties, BladeDamping, IsotropicMaterial, Tower, TowerDamping, TowerLayer, Turbine
from windflutter.model.windio_common import inertia6
from windflutter.model.yamlio import load_yaml_file
from windflutter.units import DEG, PERCENT, RPM


def find_supplement(data: dict | None, path: Path) -> tuple[dict | None, str | None]:
    """The ``windflutter`` block for a turbine file (inline first, then sibling files)."""
    if isinstance(data, dict) and isinstance(data.get("windflutter"), dict):
        return data["windflutter"], str(path)
    for folder in (path.parent, path.parent.parent):
        cand = folder / f"{path.stem}.windflutter.yaml"
        if cand.is_file():
            d = load_yaml_file(cand)
            block = d.get("windflutter", d)
            if not isinstance(block, dict):
                raise InputError("windflutter", block, "a mapping", str(cand))
            return block, str(cand)
    return None, None


def apply_supplement(turbine: Turbine, raw: dict | None, supp: dict | None, base_dir: Path, source: str) -> Turbine:
    """Merge the supplement into the turbine; an operating curve from the control block when
    neither gives a table.  (Missing masses are recorded later, by
    :func:`windflutter.model.consistency.finish_turbine`.)"""
    files: list[str] = []
    if supp:
        r = Reader(source)
        notes = pl.Notes(source)
        fdir = Path(source).parent if Path(source).is_file() else base_dir
        turbine = _rotor_parts(turbine, supp, r)
        turbine = _curves_and_tables(turbine, supp, r, fdir, files, notes)
        turbine = _damping(turbine, supp, r, notes)
        turbine = dataclasses.replace(
            turbine, notes=turbine.notes + tuple(str(n) for n in r.seq(supp, "windflutter", "notes", default=[])),
            warnings=turbine.warnings + tuple(notes.items), input_files=turbine.input_files + tuple(files))
    if turbine.operating_curve is None:
        curve = curve_from_control(turbine.control, 0.5 * turbine.rotor_diameter)
        turbine = dataclasses.replace(turbine, operating_curve=curve)
    if not np.isfinite(turbine.rated_rotor_speed) and turbine.operating_curve is not None:
        turbine = dataclasses.replace(turbine, rated_rotor_speed=turbine.operating_curve.rated_rotor_speed)
    if turbine.blade.beam == "layup":
        t0 = dataclasses.replace(turbine, blade=dataclasses.replace(turbine.blade, beam=None))
        turbine = dataclasses.replace(t0, blade=dataclasses.replace(t0.blade, beam=layup_beam_sections(t0)),
                                      notes=t0.notes + ("blade 6x6: thin-walled sections of the layup (model/section.py)",))
    return turbine


def _rotor_parts(turbine: Turbine, supp: dict, r: Reader) -> Turbine:
    """``hub``, ``precone_deg``, ``nacelle``, ``rated_rotor_speed_rpm``, ``rated_power_kw``."""
    p = "windflutter"
    hub, nac, rated, power = turbine.hub, turbine.nacelle, turbine.rated_rotor_speed, turbine.rated_power
    h = r.mapping(supp, p, "hub", default={})
    if h:
        q = f"{p}.hub"
        hub = dataclasses.replace(
            hub, mass=r.number(h, q, "mass", default=hub.mass, positive=True),
            inertia=_overridden_inertia(r, h, q, hub.inertia, "inertia_shaft", 0),
            cg_offset=r.number(h, q, "cg_offset", default=hub.cg_offset),
            diameter=r.number(h, q, "diameter", default=hub.diameter, positive=True))
    if "precone_deg" in supp:
        hub = dataclasses.replace(hub, precone=r.number(supp, p, "precone_deg") * DEG)
    n = r.mapping(supp, p, "nacelle", default={})
    if n:
        nac = _nacelle(nac, n, r, f"{p}.nacelle")
    if "rated_rotor_speed_rpm" in supp:
        rated = r.number(supp, p, "rated_rotor_speed_rpm", positive=True) * RPM
    if "rated_power_kw" in supp:
        power = r.number(supp, p, "rated_power_kw", positive=True) * 1e3
    return dataclasses.replace(turbine, hub=hub, nacelle=nac, rated_rotor_speed=float(rated), rated_power=power)


def _nacelle(nac, n: dict, r: Reader, q: str):
    cg = r.array(n["cg"], f"{q}.cg", min_len=3)[:3] if "cg" in n else nac.cg
    kdt = nac.drivetrain_torsional_stiffness
    if "drivetrain_torsional_stiffness" in n:
        kdt = r.number(n, q, "drivetrain_torsional_stiffness", positive=True)
    return dataclasses.replace(
        nac,
        mass=r.number(n, q, "mass", default=nac.mass, positive=True),
        inertia=_overridden_inertia(r, n, q, nac.inertia, "yaw_inertia", 2),
        cg=cg,
        overhang=r.number(n, q, "overhang", default=nac.overhang),
        shaft_tilt=r.number(n, q, "shaft_tilt_deg", default=nac.shaft_tilt / DEG) * DEG,
        tower_to_shaft=r.number(n, q, "tower_to_shaft", default=nac.tower_to_shaft),
        generator_inertia=r.number(n, q, "generator_inertia", default=nac.generator_inertia, nonneg=True),
        gear_ratio=r.number(n, q, "gear_ratio", default=nac.gear_ratio, positive=True),
        drivetrain_torsional_stiffness=kdt,
        drivetrain_torsional_damping=r.number(n, q, "drivetrain_torsional_damping",
                                              default=nac.drivetrain_torsional_damping, nonneg=True),
        yaw_bearing_mass=r.number(n, q, "yaw_bearing_mass", default=nac.yaw_bearing_mass, nonneg=True),
    )


def _curves_and_tables(turbine: Turbine, supp: dict, r: Reader, fdir: Path, files: list, notes: pl.Notes) -> Turbine:
    """``operating_curve``, ``tower`` (linear-taper tube) and ``blade_beam`` (external 6x6)."""
    p = "windflutter"
    oc = r.mapping(supp, p, "operating_curve", default=None)
    if oc is not None:
        turbine = dataclasses.replace(turbine, operating_curve=_curve(oc, r, f"{p}.operating_curve", fdir, files))
        if "rated_rotor_speed_rpm" not in supp:
            turbine = _rated_from_curve(turbine)
    tw = r.mapping(supp, p, "tower", default=None)
    if tw is not None:
        turbine = _tower_override(turbine, tw, r, f"{p}.tower")
    bb = r.mapping(supp, p, "blade_beam", default=None)
    if bb is not None:
        beam, damping = _beam(bb, r, f"{p}.blade_beam", fdir, turbine.blade.length, files, notes)
        blade = dataclasses.replace(turbine.blade, beam=beam)
        if damping is not None:
            blade = dataclasses.replace(blade, damping=(blade.damping or BladeDamping()).merged(damping))
        turbine = dataclasses.replace(turbine, blade=blade)
    if "blade_mass_factor" in supp:
        f = r.number(supp, p, "blade_mass_factor", positive=True)
        bp = turbine.blade.beam
        if not isinstance(bp, BeamProperties):
            raise InputError(f"{p}.blade_mass_factor", f, "a blade with 6x6 beam properties to scale", r.source)
        bp = dataclasses.replace(bp, mass=bp.mass * f, source=f"{bp.source} x mass_factor {f}")
        turbine = dataclasses.replace(turbine, blade=dataclasses.replace(turbine.blade, beam=bp))
    return turbine


#: a turbine file's rated rotor speed and its operating curve's maximum differing by more than this
#: fraction: the curve's is the rated speed (the file's is then a controller limit the curve never reaches)
RATED_MISMATCH = 0.005


def _rated_from_curve(turbine: Turbine) -> Turbine:
    """The rated rotor speed of a turbine given an operating curve by its supplement: the curve's
    maximum, the speed every analysis runs at above rated, where the turbine file's value differs from
    it by more than :data:`RATED_MISMATCH` (the IEA 22 MW: windIO's control maximum 7.162 RPM, its
    HAWCStab2 operating curve 7.061 RPM), so that the margins "to rated" and "to overspeed" refer to
    the rotor speed the turbine is analysed at; a note says so.  An explicit
    ``rated_rotor_speed_rpm`` is kept."""
    curve, rated = turbine.operating_curve, turbine.rated_rotor_speed
    top = curve.rated_rotor_speed
    if np.isfinite(rated) and abs(top - rated) <= RATED_MISMATCH * rated:
        return turbine
    note = (f"rated rotor speed {top / RPM:.4g} RPM: the operating curve's above rated"
            + (f" (the turbine file's {rated / RPM:.4g} RPM is not reached on it)" if np.isfinite(rated) else ""))
    return dataclasses.replace(turbine, rated_rotor_speed=float(top), notes=turbine.notes + (note,))


def _damping(turbine: Turbine, supp: dict, r: Reader, notes: pl.Notes) -> Turbine:
    """``blade_damping {mu (BeamDyn order, s), flap_percent, edge_percent, source}`` and
    ``tower_damping {fore_aft_percent, side_side_percent, source}``."""
    p = "windflutter"
    bd = r.mapping(supp, p, "blade_damping", default=None)
    if bd is not None:
        q = f"{p}.blade_damping"
        src = r.string(bd, q, "source", default=f"{r.source}: {q}")
        mu = r.array(bd["mu"], f"{q}.mu", min_len=6, nonneg=True)[:6] if "mu" in bd else None
        if mu is not None:
            pl.damping_mu(mu, f"{q}.mu", notes)
        kw = {}
        for key, n in (("flap_percent", 2), ("edge_percent", 1)):
            if key in bd:
                v = np.resize(r.array(bd[key], f"{q}.{key}", nonneg=True), n) * PERCENT
                pl.modal_ratios(v, f"{q}.{key}", notes)
                kw[key.replace("_percent", "_ratio")] = v
        new = BladeDamping.from_beamdyn_mu(mu, source=src, **kw) if mu is not None else BladeDamping(source=src, **kw)
        blade = dataclasses.replace(turbine.blade, damping=(turbine.blade.damping or BladeDamping()).merged(new))
        turbine = dataclasses.replace(turbine, blade=blade)
    td = r.mapping(supp, p, "tower_damping", default=None)
    if td is not None:
        q = f"{p}.tower_damping"
        kw = {}
        for key in ("fore_aft_percent", "side_side_percent"):
            if key in td:
                v = np.resize(r.array(td[key], f"{q}.{key}", nonneg=True), 2) * PERCENT
                pl.modal_ratios(v, f"{q}.{key}", notes)
                kw[key.replace("_percent", "_ratio")] = v
        damping = TowerDamping(source=r.string(td, q, "source", default=f"{r.source}: {q}"), **kw)
        turbine = dataclasses.replace(turbine, tower=dataclasses.replace(turbine.tower, damping=damping))
    return turbine


def _tower_override(turbine: Turbine, tw: dict, r: Reader, q: str) -> Turbine:
    """Replace the tower by a linear-taper tube: ``{height, base_z, outer_diameter: [base, top],
    wall_thickness: [base, top], n_stations, material: {name, E, G, rho}}``."""
    h = r.number(tw, q, "height", positive=True)
    z0 = r.number(tw, q, "base_z", default=0.0)
    d = r.array(r.get(tw, q, "outer_diameter"), f"{q}.outer_diameter", min_len=2, positive=True)
    t = r.array(r.get(tw, q, "wall_thickness"), f"{q}.wall_thickness", min_len=2, positive=True)
    n = int(r.number(tw, q, "n_stations", default=11, positive=True))
    pl.bounded_count(n, f"{q}.n_stations", r.source, limit=1000)
    m = r.mapping(tw, q, "material")
    E = r.number(m, f"{q}.material", "E", positive=True)
    G = r.number(m, f"{q}.material", "G", positive=True)
    name = r.string(m, f"{q}.material", "name", default="tower_material")
    mat = IsotropicMaterial(E=E, nu=E / (2 * G) - 1.0, rho=r.number(m, f"{q}.material", "rho", positive=True),
                            name=name)
    if np.any(2 * t[[0, -1]] >= d[[0, -1]]):
        raise InputError(f"{q}.wall_thickness", t.tolist(), f"walls thinner than the radius ({(d / 2).tolist()} m)",
                         r.source)
    s = np.linspace(0.0, 1.0, n)
    tower = Tower(s=s, z=z0 + h * s, outer_diameter=d[0] + (d[-1] - d[0]) * s,
                  layers=(TowerLayer(name="wall", material=name, thickness=t[0] + (t[-1] - t[0]) * s),),
                  outfitting_factor=1.0, damping=turbine.tower.damping)
    return dataclasses.replace(turbine, tower=tower, materials={**turbine.materials, name: mat})


def _overridden_inertia(r, d: dict, q: str, base, axis_key: str, axis: int) -> np.ndarray:
    """Inertia tensor after a supplement block ``d``: a full ``inertia`` 6-vector replaces
    ``base``, then ``axis_key`` (e.g. ``yaw_inertia``) sets the one diagonal term ``axis``."""
    inertia = np.array(base, dtype=float)
    if "inertia" in d:
        v = r.array(d["inertia"], f"{q}.inertia", min_len=3)
        inertia = inertia6(np.concatenate([v, np.zeros(max(0, 6 - v.size))])[:6])
    if axis_key in d:
        if not np.all(np.isfinite(inertia)):
            inertia = np.zeros((3, 3))
        inertia[axis, axis] = r.number(d, q, axis_key, nonneg=True)
    return inertia


def _file(d: dict, r: Reader, q: str, fdir: Path, key: str = "file") -> Path:
    f = Path(r.string(d, q, key))
    f = f if f.is_absolute() else fdir / f
    if not f.is_file():
        raise InputError(f"{q}.{key}", str(f), "an existing file", r.source)
    return f


def _curve(oc: dict, r: Reader, q: str, fdir: Path, files: list):
    if "file" not in oc:
        return curve_from_inline(oc, r.source or "")
    f = _file(oc, r, q, fdir)
    files.append(str(f))
    fmt = r.string(oc, q, "format", default="openfast_csv")
    if fmt == "openfast_csv":
        return read_openfast_steady_csv(f)
    if fmt == "hawc2_opt":
        return read_hawc2_opt(f)
    raise InputError(f"{q}.format", fmt, "'openfast_csv' or 'hawc2_opt'", r.source)


def _beam(bb: dict, r: Reader, q: str, fdir: Path, length: float, files: list, notes: pl.Notes):
    """External 6x6 (``beamdyn`` / ``elastodyn`` file, or ``layup``) and the file's damping."""
    fmt = r.string(bb, q, "format", default="beamdyn")
    if fmt == "layup":
        return "layup", None  # computed after the supplement is applied (needs the final turbine)
    f = _file(bb, r, q, fdir)
    files.append(str(f))
    factor = r.number(bb, q, "mass_factor", default=1.0, positive=True)
    if fmt == "beamdyn":
        twist = None
        if "main" in bb:
            main = _file(bb, r, q, fdir, "main")
            files.append(str(main))
            twist = read_beamdyn_main(main).twist_by_eta
        bp, damping = read_beamdyn_blade(f, twist, length, notes=notes)
    elif fmt == "elastodyn":
        bp, damping = read_elastodyn_blade(f, length, notes=notes)
    else:
        raise InputError(f"{q}.format", fmt, "'beamdyn', 'elastodyn' or 'layup'", r.source)
    if factor != 1.0:
        bp = dataclasses.replace(bp, mass=bp.mass * factor, source=f"{bp.source} x mass_factor {factor}")
    return bp, damping
