"""Mutated turbine files for tests/model/test_fuzz_turbine_files.py (issue 16's hostile cases and
more): each case is one change to a bundled turbine (windIO v2/v1 dict, YAML text, OpenFAST deck,
HAWC2 model) and what must come of it - an InputError whose message names the field (and the
station where one applies), or an InputWarning for data that are merely unusual."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class Case:
    id: str
    base: str  # windio2 | windio1 | yaml | openfast15 | openfast5 | hawc2
    mutate: Callable
    error: str | None = None  # text the InputError message must contain
    warn: str | None = None  # text an InputWarning (and Turbine.warnings) must contain


# ------------------------------------------------------------------------------------- helpers
def _blade(d):
    return d["components"]["blade"]


def _ep(d):
    return _blade(d)["structure"]["elastic_properties"]


def _scale(seq, f):
    return [x * f for x in seq]


def _set(lst, i, v):
    lst[i] = v


def _sub(path: Path, old: str, new: str, count: int = 1) -> None:
    """Replace ``old`` by ``new`` in a file (the text must be there: a mutation that did not
    happen would make the case pass for nothing)."""
    text = path.read_text()
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, count))


def _lines(path: Path, fn: Callable[[list[str]], list[str]]) -> None:
    path.write_text("\n".join(fn(path.read_text().splitlines())) + "\n")


def _polar(d, name):
    a = next(a for a in d["airfoils"] if a["name"] == name)
    return a["polars"][0]["re_sets"][0]


def _entry(block: dict, key: str, f=None, i=None, v=None):
    """Scale column ``key`` of a windIO 6x6 block by ``f``, or set its entry ``i`` to ``v``
    (a missing column is added as zeros)."""
    if key not in block:
        block[key] = [0.0] * len(block["grid"])
    if i is None:
        block[key] = _scale(block[key], f)
    else:
        block[key][i] = v


def _k(d, key, f=None, i=None, v=None):
    _entry(_ep(d)["stiffness_matrix"], key, f, i, v)


def _all_k(d, f):
    K = _ep(d)["stiffness_matrix"]
    for key in K:
        if key.startswith("K"):
            K[key] = _scale(K[key], f)


def _inertia(d, key, f=None, i=None, v=None):
    _entry(_ep(d)["inertia_matrix"], key, f, i, v)


# -------------------------------------------------------------------- windIO v2 (NREL 5 MW file)
# (d, supp): the windIO dict and its windflutter supplement (the file's own 6x6 is used: the
# supplement's BeamDyn blade_beam is dropped for these cases)
W2 = [
    Case("K66-negative-station-17", "windio2", lambda d, s: _k(d, "K66", i=17, v=-5e8), error="K66 (torsion GJ) at station 17"),
    Case("K44-zero", "windio2", lambda d, s: _k(d, "K44", i=30, v=0.0), error="K44 (edgewise EI) at station 30"),
    Case("K55-negative", "windio2", lambda d, s: _k(d, "K55", i=3, v=-1.0), error="K55 (flapwise EI) at station 3"),
    Case("K33-negative", "windio2", lambda d, s: _k(d, "K33", i=10, v=-2e9), error="K33 (EA) at station 10"),
    Case("K11-negative", "windio2", lambda d, s: _k(d, "K11", i=5, v=-1e6), error="K11 (shear, flapwise) at station 5"),
    Case("K45-exceeds-EIs", "windio2", lambda d, s: _k(d, "K45", i=20, v=1e12), error="positive definite"),
    Case("K-not-finite", "windio2", lambda d, s: _k(d, "K66", i=2, v=float("nan")), error="stiffness_matrix.K66[2]"),
    Case("stiffness-x1e-12", "windio2", lambda d, s: _all_k(d, 1e-12), error="first flapwise frequency estimate"),
    Case("stiffness-x1e12", "windio2", lambda d, s: _all_k(d, 1e12), error="first flapwise frequency estimate"),
    Case("mass-x1e6", "windio2", lambda d, s: _inertia(d, "mass", 1e6), error="mass / chord^2"),
    Case("mass-x1e-9", "windio2", lambda d, s: _inertia(d, "mass", 1e-9), error="mass / chord^2"),
    Case("mass-negative-station-3", "windio2", lambda d, s: _inertia(d, "mass", i=3, v=-10.0), error="inertia_matrix.mass[3]"),
    Case("i-edge-negative", "windio2", lambda d, s: _inertia(d, "i_edge", i=12, v=-100.0), error="inertia_matrix at station 12"),
    Case("i-cp-too-large", "windio2", lambda d, s: _inertia(d, "i_cp", i=8, v=1e6), error="inertia_matrix at station 8"),
    Case("mu-negative", "windio2", lambda d, s: _ep(d)["structural_damping"].update(mu=[-1e-3] * 6), error="structural_damping.mu"),
    Case("mu-5s", "windio2", lambda d, s: _ep(d)["structural_damping"].update(mu=[5.0] * 6), error="structural_damping.mu"),
    Case("chord-x1e6", "windio2", lambda d, s: _blade(d)["outer_shape"]["chord"].update(
        values=_scale(_blade(d)["outer_shape"]["chord"]["values"], 1e6)), error="outer_shape.chord.values"),
    Case("chord-40m-station-9", "windio2", lambda d, s: _set(_blade(d)["outer_shape"]["chord"]["values"], 9, 40.0),
         error="outer_shape.chord.values[9]"),
    Case("twist-1e6-deg", "windio2", lambda d, s: _set(_blade(d)["outer_shape"]["twist"]["values"], 4, 1e6),
         error="outer_shape.twist.values[4]"),
    Case("prebend-100m", "windio2", lambda d, s: _set(_blade(d)["reference_axis"]["x"]["values"], -1, -100.0),
         error="reference_axis.x.values"),
    Case("sweep-80m", "windio2", lambda d, s: _set(_blade(d)["reference_axis"]["y"]["values"], -1, 80.0),
         error="reference_axis.y.values"),
    Case("folded-span-axis", "windio2", lambda d, s: _set(_blade(d)["reference_axis"]["z"]["values"], 20, 1.0),
         error="reference_axis.z.values[20]"),
    Case("blade-61.5km", "windio2", lambda d, s: _blade(d)["reference_axis"]["z"].update(
        values=_scale(_blade(d)["reference_axis"]["z"]["values"], 1000.0)), error="rotor_diameter"),
    Case("rotor-diameter-x100", "windio2", lambda d, s: d["assembly"].update(rotor_diameter=12600.0), error="rotor_diameter"),
    Case("hub-height-1e4", "windio2", lambda d, s: d["assembly"].update(hub_height=1e4), error="hub_height"),
    Case("tower-300m-at-90m", "windio2", lambda d, s: s["tower"].update(height=300.0), error="hub_height"),
    Case("pitch-axis-10-chords", "windio2", lambda d, s: _blade(d)["outer_shape"]["section_offset_y"].update(
        values=_scale(_blade(d)["outer_shape"]["chord"]["values"], 10.0)), error="section_offset_y.values"),
    Case("precone-1e6-deg", "windio2", lambda d, s: s.update(precone_deg=1e6), error="hub.precone"),
    Case("tilt-80-deg", "windio2", lambda d, s: s["nacelle"].update(shaft_tilt_deg=80.0), error="nacelle.shaft_tilt"),
    Case("nacelle-mass-1e30", "windio2", lambda d, s: s["nacelle"].update(mass=1e30), error="nacelle.mass"),
    Case("hub-mass-1e25", "windio2", lambda d, s: s["hub"].update(mass=1e25), error="hub.mass"),
    Case("nacelle-inertia-1e30", "windio2", lambda d, s: s["nacelle"].update(yaw_inertia=1e30), error="radius of gyration"),
    Case("polar-radians-in-degree-file", "windio2", lambda d, s: [_polar(d, "DU25_A17")[k].update(
        grid=_scale(_polar(d, "DU25_A17")[k]["grid"], np.pi / 180)) for k in ("cl", "cd", "cm")], error="look like radians"),
    Case("lift-sign-flipped", "windio2", lambda d, s: _polar(d, "DU25_A17")["cl"].update(
        values=_scale(_polar(d, "DU25_A17")["cl"]["values"], -1.0)), error="lift slope"),
    Case("lift-zero", "windio2", lambda d, s: _polar(d, "DU21_A17")["cl"].update(
        values=[0.0] * len(_polar(d, "DU21_A17")["cl"]["values"])), error="lift slope"),
    Case("lift-x1e6", "windio2", lambda d, s: _polar(d, "NACA64_A17")["cl"].update(
        values=_scale(_polar(d, "NACA64_A17")["cl"]["values"], 1e6)), error="Cl at alpha"),
    Case("negative-drag", "windio2", lambda d, s: _set(_polar(d, "DU30_A17")["cd"]["values"], 60, -0.01), error="Cd at alpha"),
    Case("drag-x100", "windio2", lambda d, s: _polar(d, "DU35_A17")["cd"].update(
        values=_scale(_polar(d, "DU35_A17")["cd"]["values"], 100.0)), error="Cd at alpha"),
    Case("rthick-in-percent", "windio2", lambda d, s: d["airfoils"][5].update(rthick=25.0), error="airfoils[5].rthick"),
    Case("E-x1e-12", "windio2", lambda d, s: d["materials"][0].update(E=3.44e-3), error="materials[0].E"),
    Case("rho-1e9", "windio2", lambda d, s: d["materials"][1].update(rho=1e9), error="materials[1].rho"),
    Case("windio-version-9.9", "windio2", lambda d, s: d.update(windIO_version="9.9"), error="windIO_version"),
    Case("windio-version-text", "windio2", lambda d, s: d.update(windIO_version="two"), error="windIO_version"),
    Case("tower-wall-thicker-than-radius", "windio2", lambda d, s: s["tower"].update(wall_thickness=[4.0, 4.0]),
         error="tower"),
    # unusual but possible: a warning, kept on the turbine
    Case("chord-25-percent-of-blade", "windio2", lambda d, s: _set(_blade(d)["outer_shape"]["chord"]["values"], 9, 15.0),
         warn="of the blade length"),
    Case("twist-60-deg", "windio2", lambda d, s: _set(_blade(d)["outer_shape"]["twist"]["values"], 0, 60.0), warn="unusually large"),
    Case("prebend-20-percent", "windio2", lambda d, s: _set(_blade(d)["reference_axis"]["x"]["values"], -1, -12.0),
         warn="prebend"),
    Case("precone-20-deg", "windio2", lambda d, s: s.update(precone_deg=20.0), warn="hub.precone"),
    Case("nacelle-mass-x20", "windio2", lambda d, s: s["nacelle"].update(mass=4.8e6), warn="nacelle.mass"),
    Case("lift-slope-x0.3", "windio2", lambda d, s: _polar(d, "DU25_A17")["cl"].update(
        values=_scale(_polar(d, "DU25_A17")["cl"]["values"], 0.3)), warn="lift slope"),
    Case("drag-x2", "windio2", lambda d, s: _polar(d, "DU40_A17")["cd"].update(
        values=_scale(_polar(d, "DU40_A17")["cd"]["values"], 2.0)), warn="unusually high"),
    Case("mu-0.08s", "windio2", lambda d, s: _ep(d)["structural_damping"].update(mu=[0.08] * 6), warn="damping ratio"),
    Case("rotor-diameter-x1.1", "windio2", lambda d, s: d["assembly"].update(rotor_diameter=138.6), warn="rotor_diameter"),
]

# ---------------------------------------------------------------------- windIO v1 (IEA 15 MW file)
W1 = [
    Case("v1-six-x-six-K66-negative", "windio1", lambda d, s: _set(
        _blade(d)["elastic_properties_mb"]["six_x_six"]["stiff_matrix"]["values"][10], 20, -1e8),
        error="K66 (torsion GJ) at station 10"),
    Case("v1-inertia-not-psd", "windio1", lambda d, s: _set(
        _blade(d)["elastic_properties_mb"]["six_x_six"]["inertia_matrix"]["values"][4], 15, -500.0),
        error="inertia_matrix at station 4"),
    Case("v1-polar-degrees-in-radian-file", "windio1", lambda d, s: [d["airfoils"][3]["polars"][0][k].update(
        grid=_scale(d["airfoils"][3]["polars"][0][k]["grid"], 180 / np.pi)) for k in ("c_l", "c_d", "c_m")],
        error="look like degrees"),
    Case("v1-twist-100-rad", "windio1", lambda d, s: _set(_blade(d)["outer_shape_bem"]["twist"]["values"], 2, 100.0),
         error="outer_shape_bem.twist.values[2]"),
]

# ------------------------------------------------------------------------------------- YAML text
YAML_OK = "windIO_version: '2.0'\nname: x\nassembly: {number_of_blades: 3}\n"
Y = [
    Case("duplicate-top-key", "yaml", lambda p: p.write_text(YAML_OK + "name: y\n"), error="unique keys"),
    Case("duplicate-nested-key", "yaml", lambda p: p.write_text(YAML_OK.replace("{number_of_blades: 3}",
         "{number_of_blades: 3, number_of_blades: 2}")), error="key 'number_of_blades'"),
    Case("non-utf8", "yaml", lambda p: p.write_bytes(YAML_OK.encode() + b"# \xff\xfe latin-1 \xe9\n"), error="UTF-8"),
    Case("nested-5000-deep", "yaml", lambda p: p.write_text("a: " + "[" * 5000 + "]" * 5000 + "\n"), error="YAML"),
    Case("top-level-list", "yaml", lambda p: p.write_text("- 1\n- 2\n"), error="top level"),
    Case("empty-file", "yaml", lambda p: p.write_text(""), error="top level"),
    Case("yaml-syntax", "yaml", lambda p: p.write_text("a: [1, 2\nb: 3\n"), error="YAML syntax"),
    Case("huge-file", "yaml", lambda p: (p.write_text("a: 1\n"), open(p, "r+b").truncate(65 * 2**20)), error="MiB"),
    Case("v2-schema-string-number", "yaml", lambda p: p.write_text(YAML_OK.replace("3}", "'3'}")), error="windIO schema"),
]


# ------------------------------------------------------------------------- OpenFAST / HAWC2 text
def _setkey(path: Path, key: str, value: str) -> None:
    """Set the value of the ``value  key  - ...`` line of an OpenFAST file."""
    def fn(lines):
        for i, ln in enumerate(lines):
            tok = ln.split()
            if len(tok) > 1 and tok[1] == key:
                lines[i] = f"{value}   {key}   - mutated"
                return lines
        raise AssertionError((path, key))
    _lines(path, fn)


def _bd_entry(path: Path, station: int, row: int, col: int, value: float | None = None, block: str = "K",
              drop: bool = False) -> None:
    """Change (or drop) one entry of a BeamDyn blade file's station block (0-based indices)."""
    def fn(lines):
        start = next(i for i, ln in enumerate(lines) if "DISTRIBUTED PROPERTIES" in ln.upper())
        num = [i for i in range(start + 1, len(lines)) if lines[i].split()]
        i = num[13 * station + 1 + row + (6 if block == "M" else 0)]
        tok = lines[i].split()
        if drop:
            del tok[col]
        else:
            tok[col] = f"{value:.6e}"
        lines[i] = "  ".join(tok)
        return lines
    _lines(path, fn)


def _table_col(path: Path, header: str, col: int, fn_row: Callable[[int, float], float], rows: int) -> None:
    """Apply ``fn_row(k, value)`` to column ``col`` of the ``rows`` numeric rows below ``header``."""
    def fn(lines):
        i0 = next(i for i, ln in enumerate(lines) if header in ln.split())
        k, i = 0, i0 + 1
        while k < rows:
            tok = lines[i].split()
            try:
                v = float(tok[col])
            except (ValueError, IndexError):
                i += 1
                continue
            tok[col] = f"{fn_row(k, v):.8e}"
            lines[i] = "  ".join(tok)
            k, i = k + 1, i + 1
        return lines
    _lines(path, fn)


B15 = "IEA-15-240-RWT/IEA-15-240-RWT_BeamDyn_blade.dat"
M15 = "IEA-15-240-RWT/IEA-15-240-RWT_BeamDyn.dat"
E15 = "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat"
T15 = "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn_tower.dat"
F15 = "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile.fst"
A15 = "IEA-15-240-RWT/IEA-15-240-RWT_AeroDyn15_blade.dat"

OF15 = [  # the IEA 15 MW structural deck (fast to read); d = the deck folder
    Case("beamdyn-main-without-kp_zr", "openfast15", lambda d: _sub(d / M15, "kp_zr", "kp_z"), error="kp_zr"),
    Case("beamdyn-kp_total-1e9", "openfast15", lambda d: _setkey(d / M15, "kp_total", "1000000000"), error="kp_total"),
    Case("beamdyn-kp-folded", "openfast15", lambda d: _table_col(d / M15, "kp_zr", 2, lambda k, v: 1.0 if k == 7 else v, 50),
         error="kp_zr of key point 8"),
    Case("beamdyn-station_total-too-many", "openfast15", lambda d: _setkey(d / B15, "station_total", "40"),
         error="station_total"),
    Case("beamdyn-station_total-1e9", "openfast15", lambda d: _setkey(d / B15, "station_total", "1000000000"),
         error="station_total"),
    Case("beamdyn-K66-negative-station-5", "openfast15", lambda d: _bd_entry(d / B15, 5, 5, 5, -1e9),
         error="K66 (torsion GJ) at station 5"),
    Case("beamdyn-K55-zero-station-9", "openfast15", lambda d: _bd_entry(d / B15, 9, 4, 4, 0.0),
         error="K55 (flapwise EI) at station 9"),
    Case("beamdyn-mass-not-psd", "openfast15", lambda d: _bd_entry(d / B15, 3, 3, 3, -10.0, block="M"),
         error="mass matrix at station 3"),
    Case("beamdyn-row-with-5-numbers", "openfast15", lambda d: _bd_entry(d / B15, 2, 1, 0, drop=True, block="M"),
         error="station 3 mass row 2"),
    Case("beamdyn-mu-negative", "openfast15", lambda d: _sub(d / B15, "0.00299005", "-0.00299005"), error="mu1..mu6"),
    Case("beamdyn-eta-not-increasing", "openfast15", lambda d: _sub(d / B15, "\t 0.010000 ", "\t 0.000000 "),
         error="station eta values"),
    Case("beamdyn-non-utf8", "openfast15", lambda d: (d / B15).write_bytes((d / B15).read_bytes() + b"\xff\xfe"),
         error="UTF-8"),
    Case("elastodyn-no-TipRad", "openfast15", lambda d: _sub(d / E15, "TipRad", "TipRadius"), error="TipRad"),
    Case("elastodyn-TipRad-text", "openfast15", lambda d: _setkey(d / E15, "TipRad", "big"), error="TipRad"),
    Case("elastodyn-HubRad-over-TipRad", "openfast15", lambda d: _setkey(d / E15, "HubRad", "200.0"), error="HubRad"),
    Case("elastodyn-NumBl-0", "openfast15", lambda d: _setkey(d / E15, "NumBl", "0"), error="NumBl"),
    Case("elastodyn-TipRad-1000", "openfast15", lambda d: _setkey(d / E15, "TipRad", "1000.0"), error="rotor_diameter"),
    Case("elastodyn-NacMass-1e30", "openfast15", lambda d: (_setkey(d / E15, "NacMass", "1e30"),
                                                              _setkey(d / E15, "NacYIner", "1e33")), error="nacelle.mass"),
    Case("elastodyn-PreCone-1e6", "openfast15", lambda d: _setkey(d / E15, "PreCone(1)", "1e6"), error="hub.precone"),
    Case("elastodyn-NacYIner-too-small", "openfast15", lambda d: _setkey(d / E15, "NacYIner", "1000.0"), error="NacYIner"),
    Case("elastodyn-TowerHt-below-base", "openfast15", lambda d: _setkey(d / E15, "TowerHt", "10.0"), error="TowerHt"),
    Case("elastodyn-TwrFile-missing", "openfast15", lambda d: (d / T15).unlink(), error="TwrFile"),
    Case("elastodyn-tower-mass-negative", "openfast15", lambda d: _table_col(
        d / T15, "HtFract", 1, lambda k, v: -v if k == 4 else v, 20), error="TMassDen at station 4"),
    Case("elastodyn-tower-EI-x1e-12", "openfast15", lambda d: [_table_col(d / T15, "HtFract", c, lambda k, v: v * 1e-12, 20)
                                                               for c in (2, 3)], error="TMassDen/TwFAStif at station 0"),
    Case("elastodyn-NTwInpSt-1e9", "openfast15", lambda d: _setkey(d / T15, "NTwInpSt", "1000000000"), error="NTwInpSt"),
    Case("elastodyn-tower-damping-150pc", "openfast15", lambda d: _setkey(d / T15, "TwrFADmp(1)", "150"),
         error="TwrFADmp"),
    Case("fst-CompElast-3", "openfast15", lambda d: _setkey(d / F15, "CompElast", "3"), error="CompElast"),
    Case("fst-CompAero-1", "openfast15", lambda d: _setkey(d / F15, "CompAero", "1"), error="CompAero"),
    Case("fst-EDFile-missing", "openfast15", lambda d: (d / E15).unlink(), error="EDFile"),
    Case("fst-no-CompElast", "openfast15", lambda d: _sub(d / F15, "CompElast", "CompElastic"), error="CompElast"),
    Case("aerodyn-blade-chord-negative", "openfast15", lambda d: _table_col(
        d / A15, "BlSpn", 5, lambda k, v: -v if k == 10 else v, 50), error="BlChord at node 11"),
    Case("aerodyn-blade-twist-1e6", "openfast15", lambda d: _table_col(
        d / A15, "BlSpn", 4, lambda k, v: 1e6 if k == 3 else v, 50), error="BlTwist[3]"),
    Case("aerodyn-span-folded", "openfast15", lambda d: _table_col(
        d / A15, "BlSpn", 0, lambda k, v: 1.0 if k == 12 else v, 50), error="BlSpn"),
    Case("aerodyn-chord-35pc-of-blade", "openfast15", lambda d: _table_col(
        d / A15, "BlSpn", 5, lambda k, v: 30.0 if k == 10 else v, 50), warn="of the blade length"),
]

A5 = "Airfoils/DU25_A17.dat"
OF5 = [  # the NREL 5 MW deck with AeroDyn airfoil tables
    Case("airfoil-lift-sign-flipped", "openfast5", lambda d: _table_col(d / A5, "NumAlf", 1, lambda k, v: -v, 140),
         error="lift slope"),
    Case("airfoil-alpha-in-radians", "openfast5", lambda d: _table_col(d / A5, "NumAlf", 0, lambda k, v: np.radians(v), 140),
         error="look like radians"),
    Case("airfoil-negative-drag", "openfast5", lambda d: _table_col(d / A5, "NumAlf", 2, lambda k, v: -0.01 if k == 70 else v,
                                                                    140), error="Cd at alpha"),
    Case("airfoil-NumAlf-too-many", "openfast5", lambda d: _setkey(d / A5, "NumAlf", "200"), error="NumAlf = 200"),
    Case("airfoil-file-missing", "openfast5", lambda d: (d / A5).unlink(), error="AFNames[6]"),
    Case("aerodyn-BlAFID-99", "openfast5", lambda d: _table_col(d / "NRELOffshrBsline5MW_AeroDyn_blade.dat", "BlSpn", 6,
                                                                lambda k, v: 99 if k == 5 else v, 19), error="BlAFID"),
    Case("elastodyn-main-non-utf8", "openfast5", lambda d: (d / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat").write_bytes(
        b"\xff" + (d / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat").read_bytes()), error="UTF-8"),
    Case("blade-mass-factor-in-supplement-1e6", "openfast5", lambda d: _sub(d / "NREL-5MW_Onshore.windflutter.yaml",
         "blade_mass_factor: 1.04536", "blade_mass_factor: 1.0e6"), error="mass / chord^2"),
]

ST = "data/NREL_5MW_st.txt"
HT = "htc/NREL_5MW.htc"


def _st_col(d: Path, set_header: str, col: int, fn_row, rows: int = 49):
    """Apply fn_row(k, v) to column ``col`` of the rows after the subset header ``set_header``."""
    def fn(lines):
        i0 = next(i for i, ln in enumerate(lines) if ln.strip().startswith(set_header))
        for k in range(rows):
            tok = lines[i0 + 1 + k].split()
            tok[col] = f"{fn_row(k, float(tok[col])):.6e}"
            lines[i0 + 1 + k] = "\t".join(tok)
        return lines
    _lines(d / ST, fn)


def _st_truncate(d: Path, set_header: str, row: int, keep: int):
    def fn(lines):
        i0 = next(i for i, ln in enumerate(lines) if ln.strip().startswith(set_header))
        lines[i0 + 1 + row] = "\t".join(lines[i0 + 1 + row].split()[:keep])
        return lines
    _lines(d / ST, fn)


H = [  # the NREL 5 MW HAWC2 model; d = the hawc2 folder
    Case("st-E-negative-station-7", "hawc2", lambda d: _st_col(d, "$1\t 49", 8, lambda k, v: -v if k == 7 else v),
         error="column E at station 7"),
    Case("st-m-x1e6", "hawc2", lambda d: _st_col(d, "$1\t 49", 1, lambda k, v: v * 1e6), error="mass / chord^2"),
    Case("st-I_x-x1e-12", "hawc2", lambda d: _st_col(d, "$1\t 49", 10, lambda k, v: v * 1e-12),
         error="first flapwise frequency estimate"),
    Case("st-short-rows", "hawc2", lambda d: _st_truncate(d, "$1\t 49", 3, 10), error="st set 5 1 row 4"),
    Case("st-set-missing", "hawc2", lambda d: _sub(d / HT, "set 5 1 ;", "set 9 1 ;"), error="st set 9 1"),
    Case("htc-unbalanced-blocks", "hawc2", lambda d: _sub(d / HT, "end c2_def ;", "", 1), error="end"),
    Case("htc-nested-40-deep", "hawc2", lambda d: _sub(d / HT, "begin simulation ;", "begin simulation ;\n"
         + "".join(f"begin b{i} ;\n" for i in range(40)) + "".join(f"end b{i} ;\n" for i in reversed(range(40)))),
         error="nested blocks"),
    Case("htc-aero-link-unknown-body", "hawc2", lambda d: _sub(d / HT, "link 1 mbdy_c2_def blade1", "link 1 mbdy_c2_def bladeX"),
         error="aero.link"),
    Case("htc-blade-not-connected", "hawc2", lambda d: _sub(d / HT, "mbdy2 blade1 1 ;", "mbdy2 blade2 1 ;"),
         error="orientation"),
    Case("htc-downwind-shaft", "hawc2", lambda d: _sub(d / HT, "mbdy2_eulerang 90.0 0.0 0.0 ;", "mbdy2_eulerang -90.0 0.0 0.0 ;"),
         error="upwind rotor"),
    Case("htc-cone-60-deg", "hawc2", lambda d: _sub(d / HT, "mbdy2_eulerang 2.5 0.0 0.0 ;  2.5 deg cone",
         "mbdy2_eulerang 60.0 0.0 0.0 ;"), error="hub.precone"),
    Case("htc-c2-z-folded", "hawc2", lambda d: _sub(d / HT, " 30.750 ", " 3.750 "), error="c2_def z"),
    Case("htc-non-utf8", "hawc2", lambda d: (d / HT).write_bytes((d / HT).read_bytes() + b"\n; \xe9\xff\n"), error="UTF-8"),
    Case("htc-continue-missing", "hawc2", lambda d: _sub(d / HT, "begin aero ;", "continue_in_file ./nothere.htc ;\nbegin aero ;"),
         error="HAWC2 htc file"),
    Case("pc-lift-sign-flipped", "hawc2", lambda d: _pc_col(d, "DU25", 1, lambda v: -v), error="lift slope"),
    Case("pc-alpha-in-radians", "hawc2", lambda d: _pc_col(d, "DU21", 0, np.radians), error="look like radians"),
    Case("ae-chord-x1e6", "hawc2", lambda d: _ae_col(d, 1, lambda v: v * 1e6), error="chord"),
    Case("ae-set-missing", "hawc2", lambda d: _sub(d / HT, "ae_sets 1 1 1 ;", "ae_sets 4 4 4 ;"), error="ae_sets"),
]


def _pc_col(d: Path, name: str, col: int, f):
    def fn(lines):
        i0 = next(i for i, ln in enumerate(lines) if name in ln and len(ln.split()) > 3)
        n = int(lines[i0].split()[1])
        for k in range(n):
            tok = lines[i0 + 1 + k].split()
            tok[col] = f"{f(float(tok[col])):.6f}"
            lines[i0 + 1 + k] = "  ".join(tok)
        return lines
    _lines(d / "data" / "NREL_5MW_pc.txt", fn)


def _ae_col(d: Path, col: int, f):
    def fn(lines):
        for k in range(2, 21):
            tok = lines[k].split()
            tok[col] = f"{f(float(tok[col])):.6f}"
            lines[k] = "  ".join(tok)
        return lines
    _lines(d / "data" / "NREL_5MW_ae.txt", fn)


ALL = W2 + W1 + Y + OF15 + OF5 + H
