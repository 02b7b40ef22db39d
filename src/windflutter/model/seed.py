"""The seed thesis's turbines as windIO-2-style files (Castillo Capponi, TU Delft MSc 2010).

This module holds the thesis tables as data and writes ``data/seed/seed5mw.yaml`` and
``data/seed/seed20mw.yaml`` (run ``python -m windflutter.model.seed`` to regenerate; a test checks
that the bundled files match).  Every gap the thesis leaves is filled with a stated choice
(``NOTES_*``); see ``docs/turbine_input.md``.

Airfoil shapes and polars for both turbines are the NREL 5 MW ones (DU/NACA "A17" set) taken from
the bundled WISDEM windIO NREL-5MW file: the thesis's 20 MW airfoils (XDU00W401, XDU00W350,
XDU97W300, DU91W2250, XDU93W210, NACA64618) are the same families as the 5 MW's DU40/35/30/25/21
and NACA64 (thesis table 4.5), so their A17 data are used under the thesis's names.
"""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import yaml

from windflutter.model.airfoil_geom import arc_at_chord_x
from windflutter.model.bundled import DATA_DIR
from windflutter.model.airfoil_geom import orient_contour as _orient_contour
from windflutter.model.operating import read_openfast_steady_csv
from windflutter.model.yamlio import load_yaml_file
from windflutter.units import RPM

# ============================================================================ 20 MW (thesis ch. 5)
# Table 5.4 / 5.5: radial position from the blade root (m)
R20 = [0.000, 2.771, 7.390, 12.009, 16.628, 21.247, 25.880, 30.499, 35.118, 42.053, 55.924, 69.781, 83.651,
       97.508, 111.379, 125.250, 132.171, 135.639, 139.106, 142.119]
CHORD20 = [9.000, 9.000, 9.000, 9.312, 9.999, 10.686, 11.000, 10.992, 10.969, 10.903, 10.659, 10.256, 9.685,
           8.936, 8.000, 3.028, 0.525, 0.120, 0.120, 0.120]
SHELL_T20 = [0.080, 0.080, 0.080, 0.070, 0.051, 0.041, 0.041, 0.041, 0.042, 0.042, 0.043, 0.045, 0.047, 0.048,
             0.050, 0.050, 0.041, 0.032, 0.023, 0.015]
WEB_T20 = [0.000, 0.000, 0.010, 0.010, 0.010, 0.010, 0.010, 0.010, 0.011, 0.011, 0.013, 0.015, 0.018, 0.020,
           0.021, 0.022, 0.019, 0.016, 0.013, 0.010]
SPAR_T20 = [0.000, 0.000, 0.010, 0.018, 0.024, 0.027, 0.027, 0.027, 0.026, 0.026, 0.024, 0.022, 0.019, 0.017,
            0.014, 0.012, 0.011, 0.011, 0.010, 0.010]
TWIST20 = [13.308, 13.308, 13.308, 13.308, 13.308, 13.308, 12.265, 10.252, 8.919, 8.335, 7.559, 7.116, 6.773,
           6.300, 5.464, 3.542, 2.157, 1.412, 0.655, 0.000]
DIST20 = [0.500, 0.500, 0.500, 0.460, 0.420, 0.390] + [0.375] * 14
AF20 = ["Cylinder1"] * 3 + ["Cylinder2"] * 2 + ["XDU00W401"] * 3 + ["XDU00W350"] * 2 + [
    "XDU97W300", "DU91W2250", "XDU93W210"] + ["NACA64618"] * 7
# thesis airfoil name -> NREL A17 data in the WISDEM NREL-5MW windIO file
AF_DATA = {"Cylinder1": "Cylinder1", "Cylinder2": "Cylinder2", "XDU00W401": "DU40_A17", "XDU00W350": "DU35_A17",
           "XDU97W300": "DU30_A17", "DU91W2250": "DU25_A17", "XDU93W210": "DU21_A17", "NACA64618": "NACA64_A17",
           "DU40_A17": "DU40_A17", "DU35_A17": "DU35_A17", "DU30_A17": "DU30_A17", "DU25_A17": "DU25_A17",
           "DU21_A17": "DU21_A17", "NACA64_A17": "NACA64_A17"}
# Table 5.6 (GPa, -, kg/m^3)
MAT20 = {"shell": (10.37e9, 10.37e9, 4.5e9, 0.3, 643.3), "web": (10.37e9, 10.37e9, 4.5e9, 0.3, 676.7),
         "spar": (27.1e9, 27.1e9, 4.5e9, 0.3, 1700.0)}
SPAR_WIDTH20 = 0.15  # fig. 5.3: box-spar width as a fraction of chord

NOTES_20 = [
    "Castillo Capponi (2010) ch. 5, tables 5.1-5.6, figs 5.1-5.3; 20 MW design from T. Ashuri's MDO work.",
    "Radial positions of tables 5.4/5.5 are from the blade root; blade length 142.119 m. Table 5.1 lists 'rotor "
    "diameter 142.11 m', which equals the blade length; with the 6 m hub the rotor diameter is 2 x (3 + 142.119) = "
    "290.24 m (tip speed at 6.31 rpm: 95.9 m/s), used here.",
    "Blade section (fig. 5.3): box spar of width 0.15 c centred at 'Distance(1)' of table 5.5 (used as pitch axis): "
    "two webs at Distance(1) -/+ 0.075 c; spar caps (table 5.4 spar thickness, 'spar' material) on suction and "
    "pressure side between the webs, on top of the full-contour shell (table 5.4 shell thickness).",
    "Webs start where table 5.4 first gives a web thickness (7.39 m); the cylindrical root has no webs.",
    "Materials table 5.6 as orthotropic with E1 = E2 = E3, G12 = G13 = G23; isotropic tower steel E 210 GPa, "
    "G 80.8 GPa (nu = E/2G - 1 = 0.2995), effective density 8500 kg/m^3 (table 5.2).",
    "Tower (fig. 5.1): 157.1 m, outer diameter 16.0 -> 7.96 m and wall 0.0986 -> 0.0528 m, linear in height.",
    "Hub/nacelle (table 5.3, fig. 5.2): hub 264,371 kg, 2.16e6 kg m^2 about the shaft, 10.0 m upwind of the yaw "
    "axis along the shaft; nacelle 936,800 kg, 8.286e7 kg m^2 about the yaw axis, CG 3.8 m downwind of the yaw "
    "axis and 3.5 m below the shaft. Fig. 5.2's 161.9 m is read as the shaft height on the yaw axis (as 89.56 m in "
    "fig. 4.2 for the 5 MW), so tower top -> shaft = 4.8 m.",
    "Not in the thesis (choices): shaft tilt 5 deg and precone 2.5 deg (as the 5 MW); airfoil data = NREL A17 set.",
    "Operating curve (fig. 5.5 is not legible in the text): NREL 5 MW steady-state curve with rotor speed scaled "
    "by 6.31/12.1 (same shape, same rated wind speed 11.4 m/s) and the same pitch schedule.",
]

# ============================================================================= 5 MW (thesis ch. 4)
# Table 4.4: radial position from the blade root (m), twist (deg), chord (m), airfoil number
R5 = [0.000, 4.100, 6.833, 10.250, 14.350, 18.450, 22.550, 26.650, 30.750, 34.850, 38.950, 43.050, 47.150, 51.250,
      54.667, 57.400, 61.500]
TWIST5 = [13.308, 13.308, 13.308, 13.308, 11.480, 10.162, 9.011, 7.795, 6.544, 5.361, 4.188, 3.125, 2.319, 1.526,
          0.863, 0.370, 0.106]
CHORD5 = [3.542, 3.854, 4.167, 4.557, 4.652, 4.458, 4.249, 4.007, 3.748, 3.502, 3.256, 3.010, 2.764, 2.518, 2.313,
          2.086, 1.419]
AFNUM5 = [1, 1, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8, 8, 8, 8, 8, 8]
# Table 4.5
AFNAMES5 = {1: "Cylinder1", 2: "Cylinder2", 3: "DU40_A17", 4: "DU35_A17", 5: "DU30_A17", 6: "DU25_A17",
            7: "DU21_A17", 8: "NACA64_A17"}
# Table A.1 (MPa, -, kg/m^3): E11, E22, G12, nu12, rho
MAT5 = {"UDOB": (38887e6, 9000e6, 3600e6, 0.249, 1869.0), "UD45R": (24800e6, 11500e6, 4861e6, 0.416, 1826.0),
        "R4545": (11700e6, 11700e6, 9770e6, 0.501, 1782.0), "SKINFOAM": (256e6, 256e6, 22e6, 0.3, 200.0),
        "WEBPS": (25e6, 25e6, 12e6, 0.3, 45.0)}
# Table A.2: ("Radius" in m as printed, total thickness in mm) per layer group.  "Radius" is measured
# from the rotor axis with the blade root at ROOT_RADIUS5 = 2.0 m: the skins TRIAX-1/TRIAX-3 run from
# 2.0 to 63.5 m, i.e. exactly the 61.5 m blade (read from the blade root instead, they would start
# 2 m outboard of the root and end 2 m beyond the tip, and the 100 mm root build-up would cover the
# first 2.3 m instead of 0.3 m: +8 t of blade mass).
ROOT_RADIUS5 = 2.0
TRIAX1 = [(2.0, 2.82), (63.5, 2.82)]
TRIAX2 = [(2.0, 100.0), (2.3, 100.0), (2.8, 26.0), (3.6, 26.0), (11.0, 0.94)]
UD_CAP = [(3.5, 0.47), (9.0, 49.26), (14.0, 96.33), (19.0, 94.05), (24.0, 87.37), (29.0, 80.94), (34.0, 71.77),
          (39.0, 58.37), (44.0, 46.45), (49.0, 25.81), (54.0, 9.99), (60.0, 0.47)]
UD_TE = [(3.5, 0.47), (7.5, 15.0), (11.0, 21.0), (14.0, 13.6), (47.0, 0.47)]
SKINFOAM = [(3.5, 1.0), (7.5, 40.0), (43.0, 40.0), (57.0, 6.0), (60.0, 6.0)]
TRIAX3 = [(2.0, 2.82), (63.5, 2.82)]
WEB_FACE_MM = 2 * 0.94  # "2 * R4545" per face; R4545 ply thickness not given: 0.94 mm assumed (as the triax)
WEB_CORE_MM = 50.0  # "50 mm WEBPS"
WEB_SPAN5 = (3.5, 60.0)  # table A.2 radius: webs where the UD spar cap exists (choice)

NOTES_5 = [
    "Castillo Capponi (2010) ch. 4 and appendix A: NREL 5 MW (Jonkman et al. 2009, NREL/TP-500-38060) with the "
    "UpWind WMC5MW laminate lay-out (thesis ref. [53]).",
    "Aero (table 4.4/4.5): chord, twist, airfoil per station; positions from the blade root (61.5 m blade). Pitch "
    "axis is not in the thesis: NREL ElastoDyn PitchAxis (from the WISDEM windIO NREL-5MW section_offset_y).",
    "Layup (tables A.1/A.2): 'Radius' read from the rotor axis with the blade root at r = 2.0 m (the skins TRIAX-1/3 "
    "run from 2.0 to 63.5 m = the 61.5 m blade), i.e. blade-root distance = Radius - 2.0 m; layer thickness linear "
    "between the listed radii, zero outside. Chordwise extents (spar caps, TE UD, sandwich "
    "panels, webs) are not in the thesis text: taken from the anchors of the WISDEM windIO NREL-5MW file.",
    "Stack per region (outer -> inner): TRIAX-1 (3 x UD45R, 2.82 mm), TRIAX-2 root build-up (UD45R), spar cap UD "
    "(UDOB) / TE UD (UDOB) / SKINFOAM panels (LE and TE), TRIAX-3 (3 x UD45R, 2.82 mm). Webs: 2 x R4545 + 50 mm "
    "WEBPS + 2 x R4545; R4545 ply thickness 0.94 mm assumed; webs from Radius 3.5 m to 60 m (where the spar cap "
    "is), i.e. 1.5 to 58 m from the blade root.",
    "Orthotropic materials: G13 = G23 = G12 and E3 = E22 assumed (only E11, E22, G12, nu12, rho in table A.1).",
    "Tower (fig. 4.1, table 4.2): 87.6 m, D 6.0 -> 3.87 m, wall 0.0351 -> 0.0247 m linear; E 210 GPa, G 80.8 GPa, "
    "effective density 8500 kg/m^3.",
    "Hub/nacelle (table 4.3, fig. 4.2): hub 56,780 kg, 115,926 kg m^2; nacelle 240,000 kg, 2,607,890 kg m^2; nacelle "
    "CG 1.9 m downwind of the yaw axis, 0.21 m below the shaft; shaft 89.56 m at the yaw axis; overhang 5.01 m.",
    "Operating curve (fig. 4.4): NREL 5MW OpenFAST steady-state table (onshore, flexible, DISCON).",
]


# ---------------------------------------------------------------------------------------- helpers
def _gv(grid, values) -> dict:
    return {"grid": [float(g) for g in grid], "values": [float(v) for v in values]}


def _orth(name: str, E1, E2, G12, nu, rho, ply_t=None) -> dict:
    m = {"name": name, "orth": 1, "rho": rho, "E": [E1, E2, E2], "G": [G12, G12, G12], "nu": [nu, nu, nu]}
    if ply_t:
        m["ply_t"] = ply_t
    return m


def _template() -> dict:
    return load_yaml_file(DATA_DIR / "turbines" / "NREL-5MW.yaml")


def _airfoil_entries(tmpl: dict, names: list[str]) -> list[dict]:
    src = {a["name"]: a for a in tmpl["airfoils"]}
    out = []
    for nm in dict.fromkeys(names):
        a = copy.deepcopy(src[AF_DATA[nm]])
        a["name"] = nm
        out.append(a)
    return out


def _contour(tmpl: dict, name: str) -> tuple[np.ndarray, np.ndarray]:
    a = {a["name"]: a for a in tmpl["airfoils"]}[AF_DATA[name]]
    return _orient_contour(np.asarray(a["coordinates"]["x"], float), np.asarray(a["coordinates"]["y"], float))


def _piecewise(table, L) -> tuple[list, list, float, float]:
    r = np.array([min(t[0], L) for t in table])
    v = np.array([t[1] for t in table]) * 1e-3
    # clipping can create duplicate positions at the tip: keep the first
    keep = np.concatenate([[True], np.diff(r) > 1e-9])
    r, v = r[keep], v[keep]
    return list(r / L), list(v), float(r[0] / L), float(r[-1] / L)


def _blade_component(tmpl: dict, s, r, chord, twist_deg, offset_y, names: list[str], structure: dict) -> dict:
    """windIO-2 blade: straight reference axis ``r`` (m) at span fractions ``s``, one airfoil per
    station (``names``; relative thickness from the template's A17 data, 1 for cylinders)."""
    af = {a["name"]: a for a in tmpl["airfoils"]}
    rthick = [1.0 if nm.startswith("Cyl") else float(af[AF_DATA[nm]]["rthick"]) for nm in names]
    return {
        "reference_axis": {"x": _gv([0, 1], [0, 0]), "y": _gv([0, 1], [0, 0]), "z": _gv(s, r)},
        "outer_shape": {
            "chord": _gv(s, chord), "twist": _gv(s, twist_deg), "section_offset_y": _gv(s, offset_y),
            "rthick": _gv(s, rthick),
            "airfoils": [{"name": nm, "spanwise_position": float(si), "configuration": ["default"], "weight": [1.0]}
                         for nm, si in zip(names, s)],
        },
        "structure": structure,
    }


def _tower(height, d_bot, d_top, t_bot, t_top, n=11) -> dict:
    s = np.linspace(0.0, 1.0, n)
    return {
        "reference_axis": {"x": _gv([0, 1], [0, 0]), "y": _gv([0, 1], [0, 0]), "z": _gv(s, s * height)},
        "outer_shape": {"outer_diameter": _gv(s, d_bot + (d_top - d_bot) * s), "cd": _gv([0, 1], [0.5, 0.5])},
        "structure": {"outfitting_factor": 1.0,
                      "layers": [{"name": "tower_wall", "material": "tower_steel",
                                  "thickness": _gv(s, t_bot + (t_top - t_bot) * s)}]},
    }


TOWER_STEEL = {"name": "tower_steel", "orth": 0, "rho": 8500.0, "E": 2.10e11, "G": 8.08e10,
               "nu": round(2.10e11 / (2 * 8.08e10) - 1.0, 6)}


def _base(name: str, tmpl: dict) -> dict:
    return {"windIO_version": "2.0", "name": name, "comments": "", "assembly": {}, "components": {}, "airfoils": [],
            "materials": [], "control": {}}


# ------------------------------------------------------------------------------------------ 20 MW
def seed20mw_dict() -> dict:
    """The 20 MW turbine of the thesis as a windIO-2-style dict (see ``NOTES_20``)."""
    tmpl = _template()
    L = R20[-1]
    s = np.array(R20) / L
    chord = np.array(CHORD20)
    pa = np.array(DIST20)
    d = _base("Seed 20MW (Castillo Capponi 2010, ch. 5)", tmpl)
    d["comments"] = " | ".join(NOTES_20)
    hub_d, hub_h = 6.0, 161.9
    d["assembly"] = {"turbine_class": "I", "turbulence_class": "B", "drivetrain": "Geared",
                     "rotor_orientation": "Upwind", "number_of_blades": 3, "hub_height": hub_h,
                     "rotor_diameter": round(2 * (hub_d / 2 + L), 4), "rated_power": 20.0e6}
    # airfoil-dependent arcs of the box spar
    a_ss0, a_ss1, a_ps0, a_ps1 = [], [], [], []
    for j, nm in enumerate(AF20):
        x, y = _contour(tmpl, nm)
        x_fore, x_aft = pa[j] - SPAR_WIDTH20 / 2, pa[j] + SPAR_WIDTH20 / 2
        a_ss0.append(float(arc_at_chord_x(x, y, x_aft, "suction")))  # suction side: arc grows TE -> LE
        a_ss1.append(float(arc_at_chord_x(x, y, x_fore, "suction")))
        a_ps0.append(float(arc_at_chord_x(x, y, x_fore, "pressure")))
        a_ps1.append(float(arc_at_chord_x(x, y, x_aft, "pressure")))
    web_start = R20[2] / L
    anchors = [
        {"name": "TE", "start_nd_arc": _gv([0, 1], [0, 0]), "end_nd_arc": _gv([0, 1], [1, 1])},
        {"name": "spar_ss", "start_nd_arc": _gv(s, a_ss0), "end_nd_arc": _gv(s, a_ss1)},
        {"name": "spar_ps", "start_nd_arc": _gv(s, a_ps0), "end_nd_arc": _gv(s, a_ps1)},
        # fore web joins the fore edges of the caps, aft web the aft edges
        {"name": "web_fore", "start_nd_arc": _gv(s, a_ss1), "end_nd_arc": _gv(s, a_ps0)},
        {"name": "web_aft", "start_nd_arc": _gv(s, a_ss0), "end_nd_arc": _gv(s, a_ps1)},
    ]

    def ref(nm, h):
        return {"anchor": {"name": nm, "handle": h}}

    webs = []
    for w in ("web_fore", "web_aft"):
        webs.append({"name": w, "start_nd_arc": ref(w, "start_nd_arc"), "end_nd_arc": ref(w, "end_nd_arc"),
                     "start_nd_grid": web_start, "end_nd_grid": 1.0,
                     "anchors": [{"name": f"{w}_shell_attachment", "start_nd_arc": _gv([0, 1], [0, 0]),
                                  "end_nd_arc": _gv([0, 1], [1, 1])}]})
    layers = [
        {"name": "shell", "material": "shell", "thickness": _gv(s, SHELL_T20), "fiber_orientation": _gv([0, 1], [0, 0]),
         "start_nd_arc": ref("TE", "start_nd_arc"), "end_nd_arc": ref("TE", "end_nd_arc")},
        {"name": "spar_cap_ss", "material": "spar", "thickness": _gv(s, SPAR_T20),
         "fiber_orientation": _gv([0, 1], [0, 0]),
         "start_nd_arc": ref("spar_ss", "start_nd_arc"), "end_nd_arc": ref("spar_ss", "end_nd_arc")},
        {"name": "spar_cap_ps", "material": "spar", "thickness": _gv(s, SPAR_T20),
         "fiber_orientation": _gv([0, 1], [0, 0]),
         "start_nd_arc": ref("spar_ps", "start_nd_arc"), "end_nd_arc": ref("spar_ps", "end_nd_arc")},
    ]
    for w in ("web_fore", "web_aft"):
        layers.append({"name": f"{w}_layer", "material": "web", "web": w, "thickness": _gv(s, WEB_T20),
                       "fiber_orientation": _gv([0, 1], [0, 0]), "start_nd_grid": web_start, "end_nd_grid": 1.0,
                       "start_nd_arc": ref(f"{w}_shell_attachment", "start_nd_arc"),
                       "end_nd_arc": ref(f"{w}_shell_attachment", "end_nd_arc")})
    # the stack needs increasing positions: one entry per station
    d["components"]["blade"] = _blade_component(tmpl, s, R20, chord, TWIST20, pa * chord, AF20,
                                                {"anchors": anchors, "webs": webs, "layers": layers})
    d["components"]["hub"] = {"diameter": hub_d, "cone_angle": 2.5, "cd": 0.5}
    tilt = np.radians(5.0)
    overhang_shaft, twr2shft = 10.0, hub_h - 157.1
    d["components"]["drivetrain"] = {"outer_shape": {
        "uptilt": 5.0, "overhang": round(overhang_shaft * np.cos(tilt), 6),
        "distance_tt_hub": round(twr2shft + overhang_shaft * np.sin(tilt), 6)}}
    d["components"]["tower"] = _tower(157.1, 16.0, 7.96, 0.0986, 0.0528)
    d["airfoils"] = _airfoil_entries(tmpl, AF20)
    d["materials"] = [_orth(k, *v) for k, v in MAT20.items()] + [dict(TOWER_STEEL)]
    rpm_max = 6.31
    d["control"] = {"supervisory": {"Vin": 4.0, "Vout": 25.0,
                                    "maxTS": round(rpm_max * RPM * (hub_d / 2 + L), 3)},
                    "pitch": {"min_pitch": 0.0, "max_pitch": 90.0, "max_pitch_rate": 8.0},
                    "torque": {"tsr": 7.0, "VS_minspd": round(6.9 * rpm_max / 12.1, 4), "VS_maxspd": rpm_max}}
    v, w, p = _nrel_curve()
    d["windflutter"] = {
        "notes": NOTES_20,
        "hub": {"mass": 264371.0, "inertia_shaft": 2.16e6, "cg_offset": 0.0},
        "nacelle": {"mass": 936800.0, "yaw_inertia": 82860699.0, "cg": [3.8, 0.0, round(twr2shft - 3.5, 6)],
                    "overhang": -overhang_shaft, "shaft_tilt_deg": 5.0, "tower_to_shaft": round(twr2shft, 6)},
        "rated_rotor_speed_rpm": rpm_max,
        "operating_curve": {"wind_speed": v.tolist(), "rotor_speed_rpm": (w * rpm_max / 12.1).round(5).tolist(),
                            "pitch_deg": p.tolist(),
                            "source": "NREL 5MW steady states (OpenFAST, DISCON) with rotor speed x 6.31/12.1"},
    }
    return d


def _nrel_curve() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """NREL 5 MW steady-state table at integer wind speeds 3..25 m/s plus rated 11.4 (rpm, deg)."""
    c = read_openfast_steady_csv(DATA_DIR / "nrel5mw" / "NREL5MW_Oper_Onshore_Flexible_Discon.csv")
    v = np.unique(np.concatenate([np.arange(3.0, 25.01, 1.0), [11.4]]))
    w = np.round(c.rotor_speed_at(v) / RPM, 4)
    p = np.round(np.degrees(c.pitch_at(v)), 4)
    return v, w, p


# ------------------------------------------------------------------------------------------- 5 MW
def seed5mw_dict() -> dict:
    """The NREL 5 MW as modelled in the thesis (ch. 4, appendix A) as a windIO-2-style dict."""
    tmpl = _template()
    L = 61.5
    s = np.array(R5) / L
    chord = np.array(CHORD5)
    tb = tmpl["components"]["blade"]
    og = tb["outer_shape"]["section_offset_y"]
    cg = tb["outer_shape"]["chord"]
    pa_t = np.interp(s, og["grid"], og["values"]) / np.interp(s, cg["grid"], cg["values"])
    names = [AFNAMES5[i] for i in AFNUM5]
    d = _base("Seed NREL 5MW (Castillo Capponi 2010, ch. 4 + appendix A)", tmpl)
    d["comments"] = " | ".join(NOTES_5)
    d["assembly"] = {"turbine_class": "I", "turbulence_class": "B", "drivetrain": "Geared",
                     "rotor_orientation": "Upwind", "number_of_blades": 3, "hub_height": 90.0,
                     "rotor_diameter": 126.0, "rated_power": 5.0e6}
    # chordwise anchors from the WISDEM NREL-5MW file (resolved to explicit arcs)
    st = tb["structure"]
    tanch = {a["name"]: a for a in st["anchors"]}

    def arcs(nm):
        a = tanch[nm]
        return (_gv(a["start_nd_arc"]["grid"], a["start_nd_arc"]["values"]),
                _gv(a["end_nd_arc"]["grid"], a["end_nd_arc"]["values"]))

    cap_ss, cap_ps = arcs("Spar_Cap_SS"), arcs("Spar_Cap_PS")
    te_ss_end = _gv(tanch["TE_reinforcement_SS"]["end_nd_arc"]["grid"],
                    tanch["TE_reinforcement_SS"]["end_nd_arc"]["values"])
    te_ps_start = _gv(tanch["TE_reinforcement_PS"]["start_nd_arc"]["grid"],
                      tanch["TE_reinforcement_PS"]["start_nd_arc"]["values"])
    web_f, web_a = arcs("Web_fore"), arcs("Web_aft")
    anchors = [
        {"name": "TE", "start_nd_arc": _gv([0, 1], [0, 0]), "end_nd_arc": _gv([0, 1], [1, 1])},
        {"name": "spar_cap_ss", "start_nd_arc": cap_ss[0], "end_nd_arc": cap_ss[1]},
        {"name": "spar_cap_ps", "start_nd_arc": cap_ps[0], "end_nd_arc": cap_ps[1]},
        {"name": "te_ud_ss", "start_nd_arc": _gv([0, 1], [0, 0]), "end_nd_arc": te_ss_end},
        {"name": "te_ud_ps", "start_nd_arc": te_ps_start, "end_nd_arc": _gv([0, 1], [1, 1])},
        {"name": "te_panel_ss", "start_nd_arc": te_ss_end, "end_nd_arc": cap_ss[0]},
        {"name": "le_panel", "start_nd_arc": cap_ss[1], "end_nd_arc": cap_ps[0]},
        {"name": "te_panel_ps", "start_nd_arc": cap_ps[1], "end_nd_arc": te_ps_start},
        {"name": "web_fore", "start_nd_arc": web_f[0], "end_nd_arc": web_f[1]},
        {"name": "web_aft", "start_nd_arc": web_a[0], "end_nd_arc": web_a[1]},
    ]

    def ref(nm, h):
        return {"anchor": {"name": nm, "handle": h}}

    def layer(name, mat, table, anchor, web=None):
        g, v, s0, s1 = _piecewise([(r - ROOT_RADIUS5, t) for r, t in table], L)
        lay = {"name": name, "material": mat, "thickness": _gv(g, v), "fiber_orientation": _gv([0, 1], [0, 0]),
               "start_nd_grid": s0, "end_nd_grid": s1,
               "start_nd_arc": ref(anchor, "start_nd_arc"), "end_nd_arc": ref(anchor, "end_nd_arc")}
        if web:
            lay["web"] = web
        return lay

    ws0, ws1 = (WEB_SPAN5[0] - ROOT_RADIUS5) / L, (WEB_SPAN5[1] - ROOT_RADIUS5) / L
    webs = [{"name": w, "start_nd_arc": ref(w, "start_nd_arc"), "end_nd_arc": ref(w, "end_nd_arc"),
             "start_nd_grid": ws0, "end_nd_grid": ws1,
             "anchors": [{"name": f"{w}_shell_attachment", "start_nd_arc": _gv([0, 1], [0, 0]),
                          "end_nd_arc": _gv([0, 1], [1, 1])}]} for w in ("web_fore", "web_aft")]
    layers = [
        layer("triax_1_outer", "UD45R", TRIAX1, "TE"),
        layer("triax_2_root", "UD45R", TRIAX2, "TE"),
        layer("ud_spar_cap_ss", "UDOB", UD_CAP, "spar_cap_ss"),
        layer("ud_spar_cap_ps", "UDOB", UD_CAP, "spar_cap_ps"),
        layer("ud_te_ss", "UDOB", UD_TE, "te_ud_ss"),
        layer("ud_te_ps", "UDOB", UD_TE, "te_ud_ps"),
        layer("skinfoam_te_ss", "SKINFOAM", SKINFOAM, "te_panel_ss"),
        layer("skinfoam_le", "SKINFOAM", SKINFOAM, "le_panel"),
        layer("skinfoam_te_ps", "SKINFOAM", SKINFOAM, "te_panel_ps"),
        layer("triax_3_inner", "UD45R", TRIAX3, "TE"),
    ]
    for w in ("web_fore", "web_aft"):
        span = [(WEB_SPAN5[0], 0.0), (WEB_SPAN5[1], 0.0)]
        for nm, mat, t in ((f"{w}_r4545_a", "R4545", WEB_FACE_MM), (f"{w}_webps", "WEBPS", WEB_CORE_MM),
                           (f"{w}_r4545_b", "R4545", WEB_FACE_MM)):
            layers.append(layer(nm, mat, [(r, t) for r, _ in span], f"{w}_shell_attachment", web=w))
    d["components"]["blade"] = _blade_component(tmpl, s, R5, chord, TWIST5, pa_t * chord, names,
                                                {"anchors": anchors, "webs": webs, "layers": layers})
    d["components"]["hub"] = {"diameter": 3.0, "cone_angle": 2.5, "cd": 0.5}
    tilt = np.radians(5.0)
    overhang_shaft, twr2shft = 5.01, 89.56 - 87.6
    d["components"]["drivetrain"] = {"outer_shape": {
        "uptilt": 5.0, "overhang": round(overhang_shaft * np.cos(tilt), 6),
        "distance_tt_hub": round(twr2shft + overhang_shaft * np.sin(tilt), 6)}}
    d["components"]["tower"] = _tower(87.6, 6.0, 3.87, 0.0351, 0.0247)
    d["airfoils"] = _airfoil_entries(tmpl, names)
    ply = {"UDOB": 0.47e-3, "UD45R": 0.94e-3, "R4545": 0.94e-3}
    d["materials"] = [_orth(k, *v, ply_t=ply.get(k)) for k, v in MAT5.items()] + [dict(TOWER_STEEL)]
    d["control"] = {"supervisory": {"Vin": 3.0, "Vout": 25.0, "maxTS": 80.0},
                    "pitch": {"min_pitch": 0.0, "max_pitch": 90.0, "max_pitch_rate": 8.0},
                    "torque": {"tsr": 7.55, "VS_minspd": 6.9, "VS_maxspd": 12.1}}
    d["windflutter"] = {
        "notes": NOTES_5,
        "hub": {"mass": 56780.0, "inertia_shaft": 115926.0, "cg_offset": 0.0},
        "nacelle": {"mass": 240000.0, "yaw_inertia": 2607890.0, "cg": [1.9, 0.0, round(twr2shft - 0.21, 6)],
                    "overhang": -overhang_shaft, "shaft_tilt_deg": 5.0, "tower_to_shaft": round(twr2shft, 6),
                    "gear_ratio": 97.0},
        "rated_rotor_speed_rpm": 12.1,
        "operating_curve": {"file": "../nrel5mw/NREL5MW_Oper_Onshore_Flexible_Discon.csv", "format": "openfast_csv"},
    }
    return d


# ------------------------------------------------------------------------------------------ write
class _Dumper(yaml.SafeDumper):
    pass


def _repr_list(dumper, data):
    flow = all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in data) or (
        all(isinstance(x, str) for x in data) and len(data) <= 3)
    return dumper.represent_sequence("tag:yaml.org,2002:seq", data, flow_style=flow)


_Dumper.add_representer(list, _repr_list)
_Dumper.add_multi_representer(np.floating, lambda dumper, x: dumper.represent_float(float(x)))
_Dumper.add_multi_representer(np.integer, lambda dumper, x: dumper.represent_int(int(x)))


def dump_yaml(d: dict) -> str:
    """YAML text with numeric lists in flow style (floats always carry a '.', so PyYAML 1.1
    readers also see numbers)."""
    return yaml.dump(d, Dumper=_Dumper, sort_keys=False, width=1000)


def write_seed_files(out_dir: Path | None = None) -> list[Path]:
    out = Path(out_dir) if out_dir else DATA_DIR / "seed"
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, fn in (("seed5mw", seed5mw_dict), ("seed20mw", seed20mw_dict)):
        p = out / f"{name}.yaml"
        header = (f"# {name}: generated by windflutter.model.seed ({fn.__name__}); do not edit by hand.\n"
                  "# Source: Castillo Capponi, 'A Finite Element Approach for Aeroelastic Instability Prediction of\n"
                  "# Wind Turbines', MSc thesis, TU Delft 2010. Airfoil data: NREL 5MW A17 set (WISDEM windIO file,\n"
                  "# Apache-2.0; Jonkman et al. 2009, NREL/TP-500-38060). See the 'windflutter.notes' block.\n")
        p.write_text(header + dump_yaml(fn()))
        paths.append(p)
    return paths


if __name__ == "__main__":  # pragma: no cover
    for p in write_seed_files():
        print(p)
