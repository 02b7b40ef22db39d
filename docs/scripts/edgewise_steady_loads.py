"""Spanwise steady aerodynamic loads of the deflected IEA 22 MW rotor against HAWC2 and OpenFAST.

For docs/notes/edgewise_damping.md sec. 3: the edgewise damping depends on the steady state through the
strips' Cl0, W and phi; the IEA 22 MW reference steady states (IEAWindTask37/IEA-22-280-RWT,
outputs/01_steady_states, Apache-2.0; ``/work/shared/data/iea22mw/steady_state``) give the axial and
tangential aerodynamic force per unit blade length along the span.  Our side is the set-up of
``tests/steady/test_steady_references.py`` (one beam blade, 30 elements, each code's rotor speed
and pitch, wind along the shaft).  This script reads the shared data directly (it is not a test).

Run: ``PYTHONPATH=src python docs/scripts/edgewise_steady_loads.py [wind speeds]``.
"""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import yaml

from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry
from windflutter.model.windio import load_turbine
from windflutter.steady import steady_state
from windflutter.structure.assembly import assemble

SHARED = "/work/shared/data/iea22mw/steady_state/iea-22-280-rwt-steady-states-{}.yaml"


def reference(code: str, V: float):
    with open(SHARED.format(code)) as f:
        cases = yaml.safe_load(f)["cases"]
    c = min(cases, key=lambda c: abs(c["configuration"]["wind_speed"] - V))
    d = c["outputs"]["distributed"]
    # the references' tangential force is positive against the rotation: turned to ours (driving +)
    return c["configuration"], {k: (np.asarray(d[k]["grid"], float), sgn * np.asarray(d[k]["values"], float))
                                for k, sgn in (("aero_force_axial", 1.0), ("aero_force_tangential", -1.0))}


def ours(turbine, V, rpm, pitch_deg, n_span=30):
    fe, sec = build_model(turbine, MeshSettings(model="beam", part="blade", n_span=n_span,
                                                pitch=math.radians(pitch_deg)))
    g = dataclasses.replace(rotor_geometry(turbine), wind_direction=rotor_geometry(turbine).shaft_axis)
    s = steady_state(fe, assemble(fe), sec, g, V, rpm * math.pi / 30, n_blades=turbine.n_blades)
    n = np.asarray(g.shaft_axis, float) / np.linalg.norm(g.shaft_axis)
    r = np.asarray(s.sections.origin, float) - np.asarray(g.hub_center, float)
    t = np.cross(n, r)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    w = np.asarray(sec.width, float)
    F = s.strip_loads[:, :3] / w[:, None]
    # span fraction of each strip (undeformed arc length from the root)
    z = np.cumsum(w) - 0.5 * w
    return s, z / w.sum(), F @ n, np.sum(F * t, 1)


def main(speeds):
    turbine = load_turbine("iea22mw", validate=False)
    for V in speeds:
        cfg, ref = reference("hawc2", V)
        cfo, refo = reference("openfast", V)
        s, x, fa, ft = ours(turbine, V, cfg["rotor_speed"], cfg["pitch"])
        print(f"V = {V} m/s (HAWC2 {cfg['rotor_speed']:.3f} rpm, pitch {cfg['pitch']:.3f} deg; OpenFAST "
              f"{cfo['rotor_speed']:.3f} rpm, {cfo['pitch']:.3f} deg; ours at HAWC2's)")
        print("  span   fa ours  HAWC2  OpenFAST |  ft ours  HAWC2  OpenFAST  (N/m, ft + driving)")
        for xi in (0.3, 0.5, 0.7, 0.8, 0.9, 0.95):
            row = [np.interp(xi, x, fa), np.interp(xi, *ref["aero_force_axial"]), np.interp(xi, *refo["aero_force_axial"]),
                   np.interp(xi, x, ft), np.interp(xi, *ref["aero_force_tangential"]),
                   np.interp(xi, *refo["aero_force_tangential"])]
            print(f"  {xi:4.2f} " + " ".join(f"{v:8.0f}" for v in row))
        # integrated over the outer half (the edge mode's region)
        out = {}
        for name, (gx, gv), (ox, ov), mine in (("axial", ref["aero_force_axial"], refo["aero_force_axial"], fa),
                                                ("tangential", ref["aero_force_tangential"],
                                                 refo["aero_force_tangential"], ft)):
            xx = np.linspace(0.5, 1.0, 201)
            out[name] = [np.trapezoid(np.interp(xx, x, mine), xx), np.trapezoid(np.interp(xx, gx, gv), xx),
                         np.trapezoid(np.interp(xx, ox, ov), xx)]
        print("  outer half (0.5-1 span) mean: axial ours/HAWC2/OpenFAST "
              + "/".join(f"{2 * v:.0f}" for v in out["axial"]) + " N/m; tangential "
              + "/".join(f"{2 * v:.0f}" for v in out["tangential"]) + " N/m")


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [6.0, 9.0, 12.0])
