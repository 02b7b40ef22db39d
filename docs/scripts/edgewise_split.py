"""The IEA 15 MW whirling 1st edge modes against HAWCStab2's mode shapes (docs/edgewise_damping.md sec. 9).

At a wind speed on HAWCStab2's operating curve, in HAWCStab2's configuration (the blade described
about its half chord, HAWC2's thrust-induction relation, tower damping 0.1 %), prints for our 1st edge
BW and FW modes, per model variant: damping ratio, decay rate, the whirling flap over edge tip amplitude
(magnitude and phase) and the tower top's side-side motion and yaw over the edge amplitude; then HAWCStab2's
(its amplitude file, tests/data/iea15mw_hawcstab2/modes.csv).

    python docs/scripts/edgewise_split.py [WIND]
"""

from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
from reference_axis import moved_reference  # noqa: E402

from windflutter.aero.unsteady import UnsteadyOptions  # noqa: E402
from windflutter.model import load_turbine  # noqa: E402
from windflutter.system.modes import point_modes  # noqa: E402
from windflutter.system.operational import OperationalModel, OperationalOptions  # noqa: E402

DATA = ROOT / "tests" / "data" / "iea15mw_hawcstab2"
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


def operating_point(wind: float) -> tuple[float, float]:
    op = np.loadtxt(DATA / "operation_1_25_windspeed.opt", skiprows=1)
    i = int(np.argmin(np.abs(op[:, 0] - wind)))
    return float(op[i, 2]), float(op[i, 1])


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
    for r in csv.DictReader(open(DATA / "modes.csv")):
        if float(r["wind_speed"]) == wind and r["blade_label"] in ("BW edge", "FW edge") and float(r["frequency_hz"]) < 1.0:
            z, f = float(r["damping_pct"]) / 100.0, float(r["frequency_hz"])
            w = r["blade_label"].split()[0].lower()
            print(f"HAWCStab2 {r['blade_label']}: zeta {100 * z:.2f} % sigma {z * 2 * math.pi * f / math.sqrt(1 - z * z):.4f} "
                  f"1/s flap/edge {float(r[w + '_flap']) / float(r[w + '_edge']):.3f} "
                  f"tower SS/edge {float(r['twr_x']) / float(r[w + '_edge']):.4f} "
                  f"yaw/edge {float(r['twr_yaw']) / float(r[w + '_edge']):.2e} rad/m (phases: the .amp file)")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 10.0)
