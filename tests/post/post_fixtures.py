"""Builders of the post-processing tests: small synthetic Campbell results (built from the
system's own record classes, every number chosen here), a small synthetic run dataset, and the
checks several test files share."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr

DATA = Path(__file__).parent / "data"
RATED_RPM = 12.1
#: every unit string the files use, each a valid UDUNITS-2 unit (checked with cf_units 3.3 when
#: this list was written; the checker test re-checks whatever the files carry)
UDUNITS_OK = {"1", "m/s", "rpm", "Hz", "s", "m", "rad", "J", "W", "N", "degree", "s-1"}
CSV_FIELDS = ("wind_speed", "rotor_speed_rpm", "pitch_deg", "name", "family", "order", "whirl",
              "frequency_hz", "damped_frequency_hz", "damping_ratio", "share", "mixed", "heavily_damped",
              "participation_1", "participation_1_share", "participation_2", "participation_2_share")


def _mode(f_hz: float, zeta: float, name: str, family: str, whirl: str, order: int = 1, rigid: bool = False):
    from windflutter.system.modes import ModeRecord

    w = 2 * math.pi * f_hz
    lam = complex(-zeta * w, w * math.sqrt(1 - zeta**2))
    return ModeRecord(lam, family, whirl, order=order, name=name, rigid=rigid)


def synthetic_campbell(edge_bw_zeta=(0.012, 0.008, 0.010), shuffle: bool = False):
    """Three wind speeds, five tracks: tower fore-aft, 1st edge BW / FW, 1st flap collective
    (heavily damped) and a 2nd flap BW present at the first two speeds only; the edge BW damping
    as given (negative: an instability in operation).  ``shuffle``: points out of wind order."""
    from windflutter.system.campbell import CampbellPoint, CampbellResult, Track

    ws, rpm, pitch = [5.0, 11.0, 18.0], [7.5, 12.1, 12.1], [0.0, 2.5, 14.0]
    pts = []
    for i in range(3):
        modes = [_mode(0.32, 0.02 + 0.01 * i, "1st tower fore-aft", "tower_fa", "none"),
                 _mode(0.90 - 0.02 * i, edge_bw_zeta[i], "1st edge BW", "edge", "BW"),
                 _mode(0.70 + 0.05 * i, 0.35 - 0.05 * i, "1st flap collective", "flap", "collective"),
                 _mode(1.20 + 0.01 * i, 0.011, "1st edge FW", "edge", "FW")]
        if i < 2:
            modes.append(_mode(1.6, 0.09, "2nd flap BW", "flap", "BW", order=2))
        modes.sort(key=lambda m: m.frequency_hz)
        pts.append(CampbellPoint(ws[i], rpm[i], pitch[i], modes, power=1e6 * (i + 1), thrust=3e5, tip_deflection=2.0))
    names = ["1st tower fore-aft", "1st edge BW", "1st flap collective", "1st edge FW", "2nd flap BW"]
    tracks = [Track(index=[next(k for k, m in enumerate(p.modes) if m.name == n) if any(m.name == n for m in p.modes)
                           else -1 for p in pts], names=[n]) for n in names]
    if shuffle:
        order = [2, 0, 1]
        pts = [pts[i] for i in order]
        for t in tracks:
            t.index = [t.index[i] for i in order]
    return CampbellResult("synthetic 3-bladed", "turbine", pts, tracks,
                          assumptions={"aerodynamics": "unsteady strips", "drivetrain": "flexible"})


def synthetic_run(flutter_rpm=(20.0, 19.0), labels=("flap-edge b1 r/R=1.00", "edge b2 r/R=1.00")):
    """A run dataset of two points (potential, pk) built with the store's own functions."""
    from windflutter.post import store
    from windflutter.workflow import OperatingPoint, PointResult

    pts = {}
    for i, (v, fr) in enumerate(zip((10.0, 20.0), flutter_rpm)):
        rpm = np.array([4.0, 12.0, 20.0, 24.0])
        freq = np.array([[0.7, 1.0], [0.72, 1.02], [0.75, 1.05], [0.76, 1.07]])
        zeta = np.array([[0.3, 0.02], [0.3, 0.01], [0.3, 0.0], [0.3, -0.01]])
        res = PointResult(flutter_rpm=fr, flutter_frequency_hz=1.05, divergence_rpm=np.nan,
                          flutter_mode="edge b2 r/R=1.00 -> flap-edge b2 r/R=1.00", sweep_rpm=rpm,
                          damped_frequency_hz=freq, damping_ratio=zeta, mode_labels=list(labels))
        pts[i] = store.point_dataset(OperatingPoint(i, v, "potential", "pk", 4.0, 24.0, 0.01, tuple(rpm)), res)
    return store.combine(pts, {"rated_rpm": RATED_RPM, "overspeed_rpm": 1.2 * RATED_RPM, "turbine": "synthetic",
                               "solver_geometric_stiffness": 1, "model_type": "beam", "model_part": "turbine",
                               "config_yaml": "solver:\n  geometric_stiffness: true\n  n_eig: 20\n"
                                              "operating:\n  rated_rpm: 12.100000000000001\n"})


def json_rows(result):
    """The rows the CSV export must hold, taken from the result's JSON (the CLI's --json)."""
    return [{"wind_speed": p["wind_speed"], "rotor_speed_rpm": p["rotor_speed_rpm"], "pitch_deg": p["pitch_deg"],
             **{k: m[k] for k in CSV_FIELDS[3:]}} for p in result.as_dict()["points"] for m in p["modes"]]


def assert_cf_rules(path):
    """The CF-1.8 rules the windflutter files rely on (sections 2.2, 2.5.1, 2.6.1, 3.1, 5)."""
    with xr.open_dataset(path, decode_cf=False) as ds:
        assert ds.attrs["Conventions"] == "CF-1.8"
        for name, var in ds.variables.items():
            assert var.attrs.get("long_name"), f"{name}: no long_name"
            assert var.dtype.kind != "i" or var.dtype.itemsize <= 4, f"{name}: {var.dtype} (CF-1.8 has no int64)"
            units = var.attrs.get("units")
            assert units is None or units in UDUNITS_OK, f"{name}: units {units!r}"
            if name in ds.dims:  # a coordinate variable: numeric, strictly monotonic, no fill value
                assert var.dtype.kind in "fiu", f"{name}: a coordinate variable of {var.dtype}"
                assert "_FillValue" not in var.attrs, name
                assert np.all(np.diff(var.values) > 0), f"{name}: not strictly increasing"
