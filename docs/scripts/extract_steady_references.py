"""Write the steady-state reference extracts bundled in src/windflutter/data (run once, by hand).

From the reference-data snapshot (shared/data, see its SOURCES.md):
* iea22mw/steady_state/iea-22-280-rwt-steady-states-{hawc2,openfast}.yaml (IEAWindTask37/IEA-22-280-RWT,
  outputs/01_steady_states, Apache-2.0) -> iea22mw/steady_states_hawc2_openfast.csv: per case the
  configuration and integrated outputs, and the last value (blade tip, grid 1.0) of the distributed
  deflections in the blade-root pitching system;
* iea15mw/steady_state/IEA-15-240-RWT_tabular_Rotor_Performance.csv (IEAWindTask37/IEA-15-240-RWT,
  Documentation/IEA-15-240-RWT_tabular.xlsx, sheet "Rotor Performance", Apache-2.0): copied unchanged.

Values are written with Python repr (no rounding).  Usage: python extract_steady_references.py SHARED_DATA OUT_DATA
"""

import csv
import shutil
import sys
from pathlib import Path

import yaml

FIELDS = ["source", "wind_speed", "rotor_speed_rpm", "pitch_deg", "mechanical_power_W", "rotor_thrust_N",
          "rotor_torque_Nm", "tip_deflection_x_m", "tip_deflection_y_m", "tip_deflection_z_m", "tip_rotation_z_deg"]


def main(shared: Path, out: Path) -> None:
    rows = []
    for code in ("hawc2", "openfast"):
        cases = yaml.safe_load((shared / f"iea22mw/steady_state/iea-22-280-rwt-steady-states-{code}.yaml").read_text())
        for c in cases["cases"]:
            cf, integ, dist = c["configuration"], c["outputs"]["integrated"], c["outputs"]["distributed"]
            tip = {k: dist[f"blade_translation_deflection_{k}_pitching"]["values"][-1] for k in "xyz"}
            rows.append([code, cf["wind_speed"], cf["rotor_speed"], cf["pitch"], integ["mechanical_power"],
                         integ["rotor_thrust"], integ["rotor_torque"], tip["x"], tip["y"], tip["z"],
                         dist["blade_rotation_deflection_z_pitching"]["values"][-1]])
    with open(out / "iea22mw/steady_states_hawc2_openfast.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FIELDS)
        w.writerows([[r[0]] + [repr(float(v)) for v in r[1:]] for r in rows])
    shutil.copyfile(shared / "iea15mw/steady_state/IEA-15-240-RWT_tabular_Rotor_Performance.csv",
                    out / "iea15mw/IEA-15-240-RWT_tabular_Rotor_Performance.csv")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]))
