"""Supplementary turbine data that windIO files do not carry (or carry incompletely).

windIO files rarely give lumped hub/nacelle masses (WISDEM computes them from components) and
never an operating curve.  windflutter reads them from a ``windflutter:`` block, either inside the
turbine file (extra top-level keys are allowed by the windIO schema) or in a sibling file
``<stem>.windflutter.yaml`` (looked up next to the turbine file, then one folder up, so the
``windIO_v1/`` copies share the supplement of their v2 originals).  Values in the supplement
override those in the windIO file.  User-facing units: degrees and rpm, with suffixes.

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
    drivetrain_torsional_stiffness: 8.67637e8
    yaw_bearing_mass: 0.0
  precone_deg: 2.5
  rated_rotor_speed_rpm: 12.1
  operating_curve: {file: ../nrel5mw/NREL5MW_Oper_Onshore_Flexible_Discon.csv, format: openfast_csv}
  # or: {wind_speed: [...], rotor_speed_rpm: [...], pitch_deg: [...]}
  blade_beam: {file: ../nrel5mw/NRELOffshrBsline5MW_BeamDyn_Blade.dat, format: beamdyn,
               main: ../nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat}
```
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
import numpy as np

from windflutter.errors import InputError
from windflutter.model.checks import Reader
from windflutter.model.operating import (
    curve_from_control,
    curve_from_inline,
    read_hawc2_opt,
    read_openfast_steady_csv,
)
from windflutter.model.turbine import Hub, Nacelle, Turbine
from windflutter.model.yamlio import load_yaml_file

DEG = np.pi / 180.0
RPM = np.pi / 30.0


def find_supplement(data: dict, path: Path) -> tuple[dict | None, str | None]:
    """The ``windflutter`` block for a turbine file (inline first, then sibling files)."""
    if isinstance(data.get("windflutter"), dict):
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


def apply_supplement(turbine: Turbine, raw: dict, supp: dict | None, base_dir: Path, source: str) -> Turbine:
    """Merge the supplement into the turbine and check that the lumped masses are known."""
    r = Reader(source)
    notes = list(turbine.notes)
    hub, nac = turbine.hub, turbine.nacelle
    rated = turbine.rated_rotor_speed
    curve = turbine.operating_curve
    blade = turbine.blade
    if supp:
        p = "windflutter"
        fdir = Path(source).parent if Path(source).is_file() else base_dir
        notes += [str(n) for n in r.seq(supp, p, "notes", default=[])]
        h = r.mapping(supp, p, "hub", default={})
        if h:
            q = f"{p}.hub"
            inertia = _overridden_inertia(r, h, q, hub.inertia, "inertia_shaft", 0)
            hub = dataclasses.replace(
                hub,
                mass=r.number(h, q, "mass", default=hub.mass, positive=True),
                inertia=inertia,
                cg_offset=r.number(h, q, "cg_offset", default=hub.cg_offset),
                diameter=r.number(h, q, "diameter", default=hub.diameter, positive=True),
            )
        if "precone_deg" in supp:
            hub = dataclasses.replace(hub, precone=r.number(supp, p, "precone_deg") * DEG)
        n = r.mapping(supp, p, "nacelle", default={})
        if n:
            q = f"{p}.nacelle"
            inertia = _overridden_inertia(r, n, q, nac.inertia, "yaw_inertia", 2)
            cg = nac.cg
            if "cg" in n:
                cg = r.array(n["cg"], f"{q}.cg", min_len=3)[:3]
            nac = dataclasses.replace(
                nac,
                mass=r.number(n, q, "mass", default=nac.mass, positive=True),
                inertia=inertia,
                cg=cg,
                overhang=r.number(n, q, "overhang", default=nac.overhang),
                shaft_tilt=r.number(n, q, "shaft_tilt_deg", default=nac.shaft_tilt / DEG) * DEG,
                tower_to_shaft=r.number(n, q, "tower_to_shaft", default=nac.tower_to_shaft),
                generator_inertia=r.number(n, q, "generator_inertia", default=nac.generator_inertia, nonneg=True),
                gear_ratio=r.number(n, q, "gear_ratio", default=nac.gear_ratio, positive=True),
                drivetrain_torsional_stiffness=(
                    r.number(n, q, "drivetrain_torsional_stiffness", positive=True)
                    if "drivetrain_torsional_stiffness" in n else nac.drivetrain_torsional_stiffness),
                yaw_bearing_mass=r.number(n, q, "yaw_bearing_mass", default=nac.yaw_bearing_mass, nonneg=True),
            )
        if "rated_rotor_speed_rpm" in supp:
            rated = r.number(supp, p, "rated_rotor_speed_rpm", positive=True) * RPM
        oc = r.mapping(supp, p, "operating_curve", default=None)
        if oc is not None:
            curve = _curve(oc, r, f"{p}.operating_curve", fdir)
        tw = r.mapping(supp, p, "tower", default=None)
        if tw is not None:
            turbine = _tower_override(turbine, tw, r, f"{p}.tower")
        bb = r.mapping(supp, p, "blade_beam", default=None)
        if bb is not None:
            blade = dataclasses.replace(blade, beam=_beam(bb, r, f"{p}.blade_beam", fdir, blade.length))
    if curve is None:
        curve = curve_from_control(turbine.control, 0.5 * turbine.rotor_diameter)
    if not np.isfinite(rated) and curve is not None:
        rated = curve.rated_rotor_speed
    # lumped masses must be known: never build a model with a silently missing nacelle
    for field_, val in (("hub.mass", hub.mass), ("nacelle.mass", nac.mass)):
        if not np.isfinite(val):
            raise InputError(
                f"components.{field_}", None,
                "a lumped mass: the windIO file has none; add a 'windflutter:' block (see docs/turbine_input.md)",
                turbine.source,
            )
    if not np.all(np.isfinite(nac.cg)):
        nac = dataclasses.replace(nac, cg=np.zeros(3))
        notes.append("nacelle CG not given: placed at the tower top")
    if not np.all(np.isfinite(nac.inertia)):
        nac = dataclasses.replace(nac, inertia=np.zeros((3, 3)))
        notes.append("nacelle inertia not given: zero (point mass)")
    if not np.all(np.isfinite(hub.inertia)):
        hub = dataclasses.replace(hub, inertia=np.zeros((3, 3)))
        notes.append("hub inertia not given: zero (point mass)")
    from_layup = blade.beam == "layup"
    if from_layup:
        blade = dataclasses.replace(blade, beam=None)
    out = dataclasses.replace(turbine, hub=hub, nacelle=nac, rated_rotor_speed=float(rated),
                              operating_curve=curve, blade=blade, notes=tuple(notes))
    if from_layup:
        from windflutter.model.section import layup_beam_sections

        out = dataclasses.replace(out, blade=dataclasses.replace(out.blade, beam=layup_beam_sections(out)),
                                  notes=out.notes + ("blade 6x6: thin-walled sections of the layup (model/section.py)",))
    return out


def _tower_override(turbine: Turbine, tw: dict, r: Reader, q: str) -> Turbine:
    """Replace the tower by a linear-taper tube: ``{height, base_z, outer_diameter: [base, top],
    wall_thickness: [base, top], n_stations, material: {name, E, G, rho}}``."""
    from windflutter.model.turbine import IsotropicMaterial, Tower, TowerLayer

    h = r.number(tw, q, "height", positive=True)
    z0 = r.number(tw, q, "base_z", default=0.0)
    d = r.array(r.get(tw, q, "outer_diameter"), f"{q}.outer_diameter", min_len=2, positive=True)
    t = r.array(r.get(tw, q, "wall_thickness"), f"{q}.wall_thickness", min_len=2, positive=True)
    n = int(r.number(tw, q, "n_stations", default=11, positive=True))
    m = r.mapping(tw, q, "material")
    E = r.number(m, f"{q}.material", "E", positive=True)
    G = r.number(m, f"{q}.material", "G", positive=True)
    name = r.string(m, f"{q}.material", "name", default="tower_material")
    mat = IsotropicMaterial(E=E, nu=E / (2 * G) - 1.0, rho=r.number(m, f"{q}.material", "rho", positive=True),
                            name=name)
    s = np.linspace(0.0, 1.0, n)
    tower = Tower(s=s, z=z0 + h * s, outer_diameter=d[0] + (d[-1] - d[0]) * s,
                  layers=(TowerLayer(name="wall", material=name, thickness=t[0] + (t[-1] - t[0]) * s),),
                  outfitting_factor=1.0)
    return dataclasses.replace(turbine, tower=tower, materials={**turbine.materials, name: mat})


def _overridden_inertia(r, d: dict, q: str, base, axis_key: str, axis: int) -> np.ndarray:
    """Inertia tensor after a supplement block ``d``: a full ``inertia`` 6-vector replaces
    ``base``, then ``axis_key`` (e.g. ``yaw_inertia``) sets the one diagonal term ``axis``."""
    inertia = np.array(base, dtype=float)
    if "inertia" in d:
        inertia = _inertia6(r, d, q)
    if axis_key in d:
        if not np.all(np.isfinite(inertia)):
            inertia = np.zeros((3, 3))
        inertia[axis, axis] = r.number(d, q, axis_key, nonneg=True)
    return inertia


def _inertia6(r: Reader, d: dict, q: str) -> np.ndarray:
    v = r.array(d["inertia"], f"{q}.inertia", min_len=3)
    v = np.concatenate([v, np.zeros(max(0, 6 - v.size))])[:6]
    ixx, iyy, izz, ixy, ixz, iyz = v
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def _file(d: dict, r: Reader, q: str, fdir: Path, key: str = "file") -> Path:
    f = Path(r.string(d, q, key))
    f = f if f.is_absolute() else fdir / f
    if not f.is_file():
        raise InputError(f"{q}.{key}", str(f), "an existing file", r.source)
    return f


def _curve(oc: dict, r: Reader, q: str, fdir: Path):
    if "file" not in oc:
        return curve_from_inline(oc, r.source or "")
    f = _file(oc, r, q, fdir)
    fmt = r.string(oc, q, "format", default="openfast_csv")
    if fmt == "openfast_csv":
        return read_openfast_steady_csv(f)
    if fmt == "hawc2_opt":
        return read_hawc2_opt(f)
    raise InputError(f"{q}.format", fmt, "'openfast_csv' or 'hawc2_opt'", r.source)


def _beam(bb: dict, r: Reader, q: str, fdir: Path, length: float):
    from windflutter.model.beamprops import read_beamdyn_blade, read_elastodyn_blade

    fmt = r.string(bb, q, "format", default="beamdyn")
    if fmt == "layup":
        return "layup"  # computed after the supplement is applied (needs the final turbine)
    f = _file(bb, r, q, fdir)
    factor = r.number(bb, q, "mass_factor", default=1.0, positive=True)
    if fmt == "beamdyn":
        tw = None
        if "main" in bb:
            tw = _beamdyn_twist(_file(bb, r, q, fdir, "main"))
        bp = read_beamdyn_blade(f, tw, length)
    elif fmt == "elastodyn":
        bp = read_elastodyn_blade(f, length)
    else:
        raise InputError(f"{q}.format", fmt, "'beamdyn', 'elastodyn' or 'layup'", r.source)
    if factor != 1.0:
        bp = dataclasses.replace(bp, mass=bp.mass * factor, source=f"{bp.source} x mass_factor {factor}")
    return bp


def _beamdyn_twist(main: Path) -> tuple[np.ndarray, np.ndarray]:
    """Key-point twist (deg) vs nondimensional position from a BeamDyn main file."""
    lines = main.read_text().splitlines()
    i0 = next(i for i, ln in enumerate(lines) if "kp_zr" in ln) + 2
    rows = []
    for ln in lines[i0:]:
        tok = ln.split()
        try:
            rows.append([float(t) for t in tok[:4]])
        except (ValueError, IndexError):
            break
        if len(tok) < 4:
            break
    a = np.array(rows)
    z = a[:, 2]
    return (z - z[0]) / (z[-1] - z[0]), a[:, 3]

