"""OpenFAST deck reader: ``.fst`` -> ElastoDyn main (+ tower file), blade from BeamDyn (6x6) or
the ElastoDyn blade file, AeroDyn 15 blade and airfoil polars -> :class:`Turbine`.

What each file gives (and the defaults for the rest) is tabulated in ``docs/turbine_input.md``.
In short:

* ``.fst``: ``CompElast`` (1 ElastoDyn blades, 2 BeamDyn), ``CompAero`` (2 AeroDyn 15; 0 none:
  the AeroDyn blade geometry is still read when ``AeroFile`` exists, but no polars - modes only),
  ``EDFile``, ``BDBldFile(1)``, ``AeroFile``.
* ElastoDyn main: blade count, tip/hub radius, precone, hub/nacelle masses and inertias, nacelle
  CG, overhang, tilt, ``Twr2Shft``, tower top/base heights, drivetrain (``GBRatio``, ``GenIner``,
  ``DTTorSpr``, ``DTTorDmp``); tower file: mass and EI -> an equivalent steel tube
  (:mod:`.tower_tube`), tower modal damping.
* Blade structure: BeamDyn key points (reference axis, structural twist), 6x6 per station and
  ``mu``; or ElastoDyn mass/EI (no torsion: stability analyses are refused) and its modal damping.
* AeroDyn: span, chord, aerodynamic twist, airfoil per node; AirfoilInfo tables (all Reynolds
  numbers) and shape coordinates (for t/c).  The chordwise position of the reference axis is the
  ElastoDyn ``PitchAxis`` column when the blade file has one, else it follows from AeroDyn's AC
  offsets ``BlCrvAC``/``BlSwpAC`` with the aerodynamic centre at a quarter chord.
* Not in a deck: the operating curve, rated power and rated speed (a sibling
  ``<stem>.windflutter.yaml`` supplement gives them, as for windIO files).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model import plausibility as pl
from windflutter.model.aerodyn import AeroDynBlade, read_aerodyn_blade, read_aerodyn_main, read_airfoil
from windflutter.model.beamdyn import read_beamdyn_blade, read_beamdyn_main
from windflutter.model.consistency import finish_turbine
from windflutter.model.elastodyn import (
    ElastoDynMain,
    read_elastodyn_blade,
    read_elastodyn_blade_table,
    read_elastodyn_main,
    read_elastodyn_tower_table,
)
from windflutter.model.fastfile import FastFile
from windflutter.model.supplement import apply_supplement, find_supplement
from windflutter.model.tower_tube import STEEL, equivalent_tube
from windflutter.model.turbine import Airfoil, Blade, BladeDamping, Hub, Nacelle, Turbine


def load_openfast(path: Path, validate: bool = True) -> Turbine:
    """Read an OpenFAST deck (``.fst``) and its sibling supplement, if any.

    Parameters
    ----------
    path : the ``.fst`` file.
    validate : unused (OpenFAST decks have no schema; the plausibility checks always run).
    """
    fst = FastFile(path, "OpenFAST main (.fst) file")
    notes = pl.Notes(fst.source)
    elast = fst.integer("CompElast", lo=1, hi=3)
    aero = fst.integer("CompAero", lo=0, hi=3)
    if elast == 3 or aero in (1, 3):
        what = "CompElast" if elast == 3 else "CompAero"
        fst.error(what, elast if elast == 3 else aero,
                  "CompElast 1 (ElastoDyn) or 2 (BeamDyn) and CompAero 0 or 2 (AeroDyn 15)")
    ed = read_elastodyn_main(fst.file("EDFile"), need_blade_file=(elast == 1))
    files = [fst.source, ed.source, str(ed.tower_file)]
    geometry, foils, afiles = _aerodynamics(fst, aero, notes)
    files += afiles
    blade, b_files, missing = _blade(fst, elast, ed, geometry, notes)
    keys = list(foils)
    names = tuple(keys[i - 1] if len(keys) > 1 else keys[0] for i in geometry.af_id)
    tc = np.array([foils[n].relative_thickness for n in names])
    blade = dataclasses.replace(blade, airfoil_names=names, relative_thickness=np.interp(blade.s, blade.airfoil_positions, tc))
    files += b_files
    tower, tower_mat, t_files = _tower(ed, notes)
    files += t_files
    missing += [] if aero == 2 else ["airfoil polars"]
    hub = Hub(mass=ed.hub_mass, inertia=np.diag([ed.hub_inertia, 0.0, 0.0]), diameter=2 * ed.hub_radius,
              precone=ed.precone, cg_offset=ed.hub_cm)
    nac = Nacelle(mass=ed.nacelle_mass, inertia=np.diag([0.0, 0.0, _yaw_about_cg(ed, notes)]), cg=ed.nacelle_cg,
                  overhang=ed.overhang, shaft_tilt=ed.shaft_tilt, tower_to_shaft=ed.tower_to_shaft,
                  generator_inertia=ed.generator_inertia, gear_ratio=ed.gear_ratio,
                  drivetrain_torsional_stiffness=ed.dt_stiffness, drivetrain_torsional_damping=ed.dt_damping,
                  yaw_bearing_mass=ed.yaw_bearing_mass)
    for key in ed.ignored:
        notes.warn(key, "non-zero, but tip brakes and platforms are not part of windflutter's model: ignored",
                   source=ed.source)
    t = Turbine(
        name=Path(fst.source).stem, n_blades=ed.n_blades, hub_height=float(nac.rotor_apex(tower.top_z)[2]),
        rotor_diameter=2 * ed.tip_radius, rated_power=float("nan"), rated_rotor_speed=float("nan"),
        blade=blade, tower=tower, hub=hub, nacelle=nac, airfoils=foils, materials={tower_mat.name: tower_mat},
        source=fst.source, source_format="OpenFAST", warnings=tuple(notes.items), missing=tuple(missing),
        notes=("hub_height: the rotor apex height from TowerHt, Twr2Shft, OverHang and ShftTilt",
               "operating curve, rated power and speed: not in an OpenFAST deck (a supplement may give them)"),
    )
    supp, supp_source = find_supplement(None, Path(fst.source))
    t = apply_supplement(t, None, supp, base_dir=Path(fst.source).parent, source=supp_source or fst.source)
    return finish_turbine(t, tuple(files) + ((supp_source,) if supp_source else ()))


def _yaw_about_cg(ed: ElastoDynMain, notes: pl.Notes) -> float:
    """``NacYIner`` is about the yaw (tower) axis; windflutter's nacelle inertia is about the
    nacelle CG: subtract ``NacMass (NacCMxn^2 + NacCMyn^2)`` (parallel axes).  The NREL 5 MW gives
    2.60789e6 - 240000 x 1.9^2 = 1.74149e6 kg m^2, the value of its HAWC2 model."""
    arm2 = float(ed.nacelle_cg[0] ** 2 + ed.nacelle_cg[1] ** 2)
    izz = ed.nacelle_yaw_inertia - ed.nacelle_mass * arm2
    if izz < -1e-9 * max(ed.nacelle_yaw_inertia, 1.0):
        raise InputError("NacYIner", ed.nacelle_yaw_inertia, f"a yaw inertia of at least NacMass (NacCMxn^2 + "
                         f"NacCMyn^2) = {ed.nacelle_mass * arm2:.6g} kg m^2 (it is about the yaw axis)", ed.source)
    return max(izz, 0.0)


# ---------------------------------------------------------------------------------- aerodynamics
def _aerodynamics(fst: FastFile, aero: int, notes: pl.Notes) -> tuple[AeroDynBlade, dict[str, Airfoil], list[str]]:
    """AeroDyn blade nodes and the airfoils (with polars when ``CompAero = 2``)."""
    af = fst.file("AeroFile", required=(aero == 2))
    if af is None:
        fst.error("AeroFile", fst.string("AeroFile", ""), "an AeroDyn 15 file with the blade's chord and twist "
                  "(windflutter's strips need them even for modes; with CompAero = 0 the file is read for the "
                  "geometry only)")
    ad = read_aerodyn_main(af, need_airfoils=(aero == 2))
    geom = read_aerodyn_blade(ad.blade_file, notes)
    files = [ad.source, geom.source]
    n_af = len(ad.airfoil_files)
    if n_af and geom.af_id.max() > n_af:
        raise InputError("BlAFID", int(geom.af_id.max()), f"airfoil numbers up to NumAFfiles = {n_af}", geom.source)
    foils: dict[str, Airfoil] = {}
    for j, p in enumerate(ad.airfoil_files):
        name = _unique(p.stem, foils)
        if aero == 2:
            foils[name] = read_airfoil(p, ad.columns, notes, name=name)
            files.append(str(p))
        else:
            foils[name] = Airfoil(name=name, x=np.zeros(0), y=np.zeros(0), relative_thickness=float("nan"))
    if not foils:  # CompAero 0 with no airfoil list: one anonymous airfoil without polars
        foils["no_airfoil_data"] = Airfoil(name="no_airfoil_data", x=np.zeros(0), y=np.zeros(0),
                                           relative_thickness=float("nan"))
    return geom, foils, files


def _unique(name: str, taken: dict) -> str:
    out, k = name, 2
    while out in taken:
        out, k = f"{name}_{k}", k + 1
    return out


# ----------------------------------------------------------------------------------------- blade
def _blade(fst: FastFile, elast: int, ed: ElastoDynMain, geom: AeroDynBlade, notes: pl.Notes):
    """The blade: reference axis and 6x6 (BeamDyn or ElastoDyn), AeroDyn chord/twist/airfoils."""
    files, missing = [], []
    length = ed.tip_radius - ed.hub_radius
    table = None
    if ed.blade_file is not None:
        table = read_elastodyn_blade_table(ed.blade_file, notes=notes.for_file(str(ed.blade_file)))
        files.append(str(ed.blade_file))
    if elast == 2:
        bd_main = read_beamdyn_main(fst.file("BDBldFile(1)" if fst.has("BDBldFile(1)") else "BDBldFile1"))
        if bd_main.blade_file is None:
            raise InputError("BldFile", None, "an existing BeamDyn blade file", bd_main.source)
        beam, damping = read_beamdyn_blade(bd_main.blade_file, bd_main.twist_by_eta, bd_main.length,
                                           notes=notes.for_file(str(bd_main.blade_file)))
        files += [bd_main.source, str(bd_main.blade_file)]
        eta_kp, kp = bd_main.eta, bd_main.kp - bd_main.kp[0]
        length = bd_main.length
    else:
        beam, damping = read_elastodyn_blade(ed.blade_file, length, notes=notes.for_file(str(ed.blade_file)))
        eta_kp, kp = np.array([0.0, 1.0]), np.array([[0.0, 0.0, 0.0], [0.0, 0.0, length]])
        missing.append("blade torsion")
    if table is not None:
        damping = (damping or BladeDamping()).merged(table.damping) if elast == 2 else damping
    s_aero = (geom.span - geom.span[0]) / (geom.span[-1] - geom.span[0])
    s = np.unique(np.concatenate([s_aero, eta_kp]))
    xyz = np.stack([np.interp(s, eta_kp, kp[:, j]) for j in range(3)], axis=1)
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xyz, axis=0), axis=1))])
    chord = np.interp(s, s_aero, geom.chord)
    twist = np.interp(s, s_aero, geom.twist)
    pa = _pitch_axis(s, s_aero, geom, table, eta_kp, kp, notes)
    names = tuple("" for _ in geom.af_id)  # set by the caller from the AeroDyn airfoil list
    blade = Blade(s=s, ref_axis=xyz, arc_length=arc, chord=chord, twist=twist, pitch_axis=pa,
                  section_offset_y=pa * chord, relative_thickness=np.full(s.size, np.nan),
                  airfoil_positions=s_aero, airfoil_names=names, beam=beam, damping=damping)
    return blade, files, missing


def _pitch_axis(s, s_aero, geom: AeroDynBlade, table, eta_kp, kp, notes: pl.Notes) -> np.ndarray:
    """ElastoDyn ``PitchAxis`` if given; else from the AC offsets (AC at a quarter chord): the
    offset of the AC from the reference axis projected on the chord (towards the TE)."""
    from_ed = None
    if table is not None and table.pitch_axis is not None:
        from_ed = np.interp(s, table.frac, table.pitch_axis)
    ac = geom.ac_offset
    if ac is None:
        return from_ed if from_ed is not None else np.full(s.size, 0.25)
    off = ac - np.stack([np.interp(s_aero, eta_kp, kp[:, j]) for j in range(2)], axis=1)
    d = off[:, 0] * np.sin(geom.twist) + off[:, 1] * np.cos(geom.twist)
    from_ac = np.interp(s, s_aero, 0.25 - d / geom.chord)
    pl.pitch_axis(s_aero, 0.25 - d / geom.chord, "pitch axis from BlCrvAC/BlSwpAC", notes.for_file(geom.source))
    if from_ed is None:
        return from_ac
    worst = float(np.max(np.abs(from_ac - from_ed)))
    if worst > 0.05:
        notes.warn("ElastoDyn PitchAxis vs AeroDyn BlCrvAC/BlSwpAC", f"the reference axis differs by up to "
                   f"{worst:.3f} chords (AC at a quarter chord assumed); using PitchAxis", source=geom.source)
    return from_ed


# ----------------------------------------------------------------------------------------- tower
def _tower(ed: ElastoDynMain, notes: pl.Notes):
    """ElastoDyn tower table -> equivalent steel tube (fore-aft EI; side-to-side must agree)."""
    tt = read_elastodyn_tower_table(ed.tower_file, notes=notes.for_file(str(ed.tower_file)))
    rel = np.max(np.abs(tt.ei_side_side - tt.ei_fore_aft) / tt.ei_fore_aft)
    if rel > 0.01:
        notes.warn("TwSSStif vs TwFAStif", f"differ by up to {rel:.1%}; the tubular tower uses their mean",
                   source=str(ed.tower_file))
    z = ed.tower_base + tt.frac * (ed.tower_top - ed.tower_base)
    tower, mat = equivalent_tube(z, tt.mass, 0.5 * (tt.ei_fore_aft + tt.ei_side_side), STEEL["E"], STEEL["G"],
                                 STEEL["rho"], "TMassDen/TwFAStif", str(ed.tower_file), damping=tt.damping,
                                 material_name="tower_steel_elastodyn")
    return tower, mat, [str(ed.tower_file)]
