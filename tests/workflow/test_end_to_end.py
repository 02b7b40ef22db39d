"""`windflutter run` end to end on the bundled NREL 5 MW with the real solver.

CI runs a reduced version (beam model, coarse strips, one wind speed, one aero variant); the
full default analysis is marked slow (`make test-slow`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from windflutter.cli import main

RATED_RPM = 12.1  # NREL 5 MW rated rotor speed (Jonkman et al. 2009, NREL/TP-500-38060)


def _run(tmp_path, cfg_text: str, extra=()):
    cfg = tmp_path / "analysis.yaml"
    cfg.write_text(cfg_text)
    out = tmp_path / "out"
    rc = main(["run", "nrel5mw", "-c", str(cfg), "-o", str(out), "-q", *extra])
    assert rc == 0
    return out


def test_run_nrel5mw_reduced(tmp_path):
    out = _run(tmp_path, """
wind_speeds: [10]
aero: [potential]
rotor_speed: {min_rpm: 4, max_rpm: 32, n_points: 8}
model: {type: beam, n_aero_sections: 16}
output: {dpi: 40}
""")
    ds = xr.open_dataset(out / "results.nc")
    assert ds.sizes["point"] == 1
    assert str(ds.status.values[0]) == "ok"
    onsets = [float(ds.flutter_rpm.values[0]), float(ds.divergence_rpm.values[0])]
    finite = [v for v in onsets if math.isfinite(v)]
    # the blade goes unstable somewhere in the range, and only above rated speed: an onset at or
    # below rated would mean a sign or frame error in the rotor/aero terms.  (The flap-torsion
    # flutter of the published NREL 5 MW studies lies near 2 x rated; with the blade linearized
    # about its deflected shape, the default, the 1st edge BW loses its damping first at fixed-pitch
    # overspeed, near 1.2-1.4 x rated: docs/notes/edgewise_damping.md sec. 8, not verified by another code.)
    assert finite, "no instability found up to 32 RPM"
    assert min(finite) > RATED_RPM
    html = (out / "report.html").read_text()
    assert html.count("data:image/png;base64") >= 3
    assert list((out / "figures").glob("*.png"))


@pytest.mark.slow
def test_run_nrel5mw_default_analysis(tmp_path):
    out = _run(tmp_path, "title: NREL 5 MW default\n")
    ds = xr.open_dataset(out / "results.nc")
    assert np.all(ds.status.values == "ok")
    div = ds.divergence_rpm.values
    assert np.all(div[np.isfinite(div)] > RATED_RPM)
