"""The IEA 15 MW whirling 1st edge modes against HAWCStab2's mode shapes (docs/notes/edgewise_damping.md sec. 9).

At a wind speed on HAWCStab2's operating curve, in HAWCStab2's configuration (the blade described
about its half chord, HAWC2's thrust-induction relation, tower damping 0.1 %), prints for our 1st edge
BW and FW modes, per model variant: damping ratio, decay rate, the whirling flap over edge tip amplitude
(magnitude and phase) and the tower top's side-side motion and yaw over the edge amplitude; then HAWCStab2's
(its amplitude file, tests/data/iea15mw_hawcstab2/modes.csv).  With ``--shapes``: for the defaults
at each wind speed, the two modes' tower-top motion (side-side, fore-aft, yaw) and tip flap over
their edge, magnitude and phase, beside HAWCStab2's read in its convention (docs/campbell.md,
"HAWCStab2's phases": FW parts conjugated, edge reversed, blade 1 273 deg away; in the FW mode one
phase, the eigenvector's clock, is fitted on the side-side motion).

    python docs/scripts/edgewise_split.py [WIND]
    python docs/scripts/edgewise_split.py --shapes [WIND ...]
"""

from __future__ import annotations

import cmath
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "system"))
from hawcstab2_reference import hawcstab2_1st_edge_whirl, operating_point  # noqa: E402
from reference_axis import moved_reference  # noqa: E402

from windflutter.aero.unsteady import UnsteadyOptions  # noqa: E402
from windflutter.model import load_turbine  # noqa: E402
from windflutter.system.modes import point_modes  # noqa: E402
from windflutter.system.operational import OperationalModel, OperationalOptions  # noqa: E402

VARIANTS = {
    "defaults": {},
    "lift direction instantaneous": {"aero": UnsteadyOptions(lift_direction="instantaneous")},
    "quasi-steady circulation": {"aero": UnsteadyOptions(circulation="quasi_steady")},
    "separation-point lag": {"aero": UnsteadyOptions(dynamic_stall=True)},
    "no mean-load terms": {"aero": UnsteadyOptions(mean_loads=False)},
    "no induction": {"induction": False},
    "no blade structural damping": {"damping": "none"},
    "drivetrain rigid": {"drivetrain": "rigid"},
    "tower damping 1 %": {"tower_damping": 0.01},
}


def main(wind: float) -> None:
    tb = moved_reference(load_turbine("iea15mw", validate=False), 0.5)
    rpm, pitch = operating_point(wind)
    for name, kw in VARIANTS.items():
        kw = {"tower_damping": 0.001, **kw}
        om = OperationalModel(tb, OperationalOptions(mesh={"n_span": 20}, structure="deflected",
                                                     high_thrust="madsen", **kw))
        out = []
        for m in point_modes(om.at(wind, rpm=rpm, pitch=math.radians(pitch)), max_hz=1.0):
            if m.name not in ("1st edge BW", "1st edge FW"):
                continue
            c, w = m.multiblade_components(), m.whirl.lower()
            e, f = c[f"{w}_edge"], c[f"{w}_flap"]
            out.append(f"{m.whirl} zeta {100 * m.damping_ratio:.2f} % sigma {-m.eigenvalue.real:.4f} 1/s "
                       f"flap/edge {abs(f / e):.3f} ({math.degrees(np.angle(f / e)):+.0f} deg) "
                       f"tower SS/edge {abs(c['tower_ss'] / e):.4f} yaw/edge {abs(c['tower_yaw'] / e):.2e} rad/m")
        print(f"{name:30s}", " | ".join(out), flush=True)
    for whirl in ("BW", "FW"):
        r = hawcstab2_1st_edge_whirl(wind, whirl)
        z, f, w = float(r["damping_pct"]) / 100.0, float(r["frequency_hz"]), whirl.lower()
        print(f"HAWCStab2 {r['blade_label']}: zeta {100 * z:.2f} % sigma {z * 2 * math.pi * f / math.sqrt(1 - z * z):.4f} "
              f"1/s flap/edge {float(r[w + '_flap']) / float(r[w + '_edge']):.3f} "
              f"tower SS/edge {float(r['twr_x']) / float(r[w + '_edge']):.4f} "
              f"yaw/edge {float(r['twr_yaw']) / float(r[w + '_edge']):.2e} rad/m (phases: the .amp file)")


AZIMUTH = math.radians(273.0)  # blade 1's azimuth origin in HAWCStab2's file relative to ours


def shapes(winds: list[float]) -> None:
    """Ours against HAWCStab2's, component by component, in HAWCStab2's convention."""
    tb = moved_reference(load_turbine("iea15mw", validate=False), 0.5)
    om = OperationalModel(tb, OperationalOptions(mesh={"n_span": 20}, structure="deflected", high_thrust="madsen",
                                                 tower_damping=0.001))
    keys = (("tower_ss", "twr_x"), ("tower_fa", "twr_y"), ("tower_yaw", "twr_yaw"))
    for wind in winds:
        rpm, pitch = operating_point(wind)
        for m in point_modes(om.at(wind, rpm=rpm, pitch=math.radians(pitch)), max_hz=1.0):
            if m.name not in ("1st edge BW", "1st edge FW"):
                continue
            c, w = m.multiblade_components(), m.whirl.lower()
            r = hawcstab2_1st_edge_whirl(wind, m.whirl)
            h = {k: float(r[k]) * cmath.exp(1j * math.radians(float(r[k + "_ph"]))) for k in r if k + "_ph" in r}
            e = -c[f"{w}_edge"] * cmath.exp(-1j * AZIMUTH if w == "bw" else 1j * AZIMUTH)  # ours, as HAWCStab2 writes it
            if w == "bw":
                ours = {kh: c[ko] / e for ko, kh in keys}
                ours["flap"] = c["bw_flap"] * cmath.exp(-1j * AZIMUTH) / e
            else:  # conjugated part: the ground-fixed ones turn with twice the eigenvector's clock
                ours = {kh: c[ko] / np.conj(e) for ko, kh in keys}
                clock = cmath.phase((h["twr_x"] / h["fw_edge"]) / ours["twr_x"])
                ours = {k: v * cmath.exp(1j * clock) for k, v in ours.items()}
                ours["flap"] = np.conj(c["fw_flap"] * cmath.exp(1j * AZIMUTH) / e)
            ref = {kh: h[kh] / h[f"{w}_edge"] for _, kh in keys}
            ref["flap"] = h[f"{w}_flap"] / h[f"{w}_edge"]
            print(f"{wind:4.0f} m/s {m.name}: " + "  ".join(
                f"{k} {abs(ref[k]):.2e}@{math.degrees(cmath.phase(ref[k])):+.0f} / {abs(ours[k]):.2e}@{math.degrees(cmath.phase(ours[k])):+.0f}"
                for k in ref) + ("  (side-side phase fitted)" if w == "fw" else ""), flush=True)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--shapes"]:
        shapes([float(a) for a in sys.argv[2:]] or [5.0, 10.0, 15.0])
    else:
        main(float(sys.argv[1]) if len(sys.argv) > 1 else 10.0)
