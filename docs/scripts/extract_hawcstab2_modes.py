"""Extract the IEA 15 MW HAWCStab2 Campbell modes with their amplitude labels into one small CSV.

Reads the DLR-AE/CampbellViewer files (Apache-2.0; /work/shared/data/iea15mw/hawcstab2_campbell/):
``aeroelastic_entire_turbine.cmb`` (frequencies, damping ratios) and ``.amp`` (per mode the modal
magnitudes of the tower top (x, y, yaw), the shaft (x, y, torsion) and blade 1 in multi-blade
components: symmetric / BW / FW edge, flap and torsion).  Writes, per wind speed and mode, the
frequency (Hz), damping ratio (%), the magnitudes, the label of the largest blade component
(``Sym|BW|FW`` + ``edge|flap|tors``) -- the numbers HAWCStab2 users read to name a mode -- and the
phases (deg, columns ``<dof>_ph``; their convention: docs/campbell.md, "HAWCStab2's phases").

    python docs/scripts/extract_hawcstab2_modes.py SRC_DIR tests/data/iea15mw_hawcstab2/modes.csv
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

COLS = ("twr_x", "twr_y", "twr_yaw", "sft_x", "sft_y", "sft_tor", "sym_edge", "bw_edge", "fw_edge",
        "sym_flap", "bw_flap", "fw_flap", "sym_tors", "bw_tors", "fw_tors")


def main(src: str, out: str) -> None:
    src = Path(src)
    cmb = np.loadtxt(src / "aeroelastic_entire_turbine.cmb", comments="#")
    amp = np.loadtxt(src / "aeroelastic_entire_turbine.amp", comments="#")
    lines = ["wind_speed,mode,frequency_hz,damping_pct,blade_label," + ",".join(COLS)
             + "," + ",".join(c + "_ph" for c in COLS)]
    for row_c, row_a in zip(cmb, amp):
        v = row_c[0]
        f, z = row_c[1:61], row_c[61:121]
        mag = row_a[1:].reshape(60, 30)[:, 0::2]
        phase = row_a[1:].reshape(60, 30)[:, 1::2]
        for k in range(60):
            blade = mag[k, 6:15]
            i = int(np.argmax(blade))
            label = ("Sym", "BW", "FW")[i % 3] + " " + ("edge", "flap", "tors")[i // 3]
            lines.append(f"{v:g},{k + 1},{f[k]:.6g},{z[k]:.6g},{label}," + ",".join(f"{x:.4g}" for x in mag[k])
                         + "," + ",".join(f"{x:.1f}" for x in phase[k]))
    Path(out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:3])
