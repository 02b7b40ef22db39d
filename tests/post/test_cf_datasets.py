"""CF-1.8 validity of results.nc and campbell.nc, the Campbell dataset's cells, the run store's
eigenvalues and mode identity across points.

The CF rules the files rely on are checked here directly (every run); the IOOS compliance
checker, when installed, is run on top (``test_files_pass_the_cf_checker``)."""

from __future__ import annotations

import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from post_fixtures import assert_cf_rules, synthetic_campbell, synthetic_run

from windflutter.errors import InputError
from windflutter.post import store
from windflutter.post.campbell_data import campbell_dataset

def _write_both(tmp_path):
    run = tmp_path / "results.nc"
    store.atomic_write_netcdf(synthetic_run(), run)
    camp = store.write_campbell(tmp_path, synthetic_campbell())
    return run, camp


def test_results_and_campbell_files_follow_the_cf_rules(tmp_path):
    run, camp = _write_both(tmp_path)
    assert_cf_rules(run)
    assert_cf_rules(camp)
    # the flutter shape is split by unit: translations in m, torsion in rad
    back = store.open_results(run)
    assert back["flutter_translation_real"].attrs["units"] == "m"
    assert back["flutter_torsion_real"].attrs["units"] == "rad"
    assert list(back["translation_name"].values) == ["flap", "edge"]


def _checker():
    """The IOOS checker's command: its console script beside this Python's (the test extras install
    it; the package has no ``__main__``), else one named by WINDFLUTTER_CF_CHECKER or on the PATH."""
    beside = Path(sys.executable).parent / "compliance-checker"
    if importlib.util.find_spec("compliance_checker") is not None and beside.exists():
        return [str(beside)]
    exe = os.environ.get("WINDFLUTTER_CF_CHECKER") or shutil.which("compliance-checker")
    return [exe] if exe else None


@pytest.mark.slow  # ~12 s: the checker loads its CF tables for each file
@pytest.mark.skipif(_checker() is None, reason="IOOS compliance-checker not installed "
                    "(pip install compliance-checker, or WINDFLUTTER_CF_CHECKER=path)")
def test_files_pass_the_cf_checker(tmp_path):
    run, camp = _write_both(tmp_path)
    for path in (run, camp):
        out = tmp_path / f"{path.stem}.json"
        subprocess.run([*_checker(), "--test", "cf:1.8", "--format", "json", "-o", str(out), str(path)],
                       capture_output=True, timeout=120, check=False)
        rep = json.loads(out.read_text())["cf:1.8"]
        errors = [m for p in rep["high_priorities"] for m in p["msgs"]]   # the checker's "Errors"
        assert not errors, (path.name, errors)


def test_campbell_dataset_cells_are_the_modes():
    res = synthetic_campbell(shuffle=True)
    ds = campbell_dataset(res)
    np.testing.assert_array_equal(ds["wind_speed"].values, [5.0, 11.0, 18.0])   # sorted
    n_modes = sum(len(p.modes) for p in res.points)
    assert int(np.isfinite(ds["frequency"].values).sum()) == n_modes             # each mode once
    for p in res.points:
        i = int(np.where(ds["wind_speed"].values == p.wind_speed)[0][0])
        assert ds["rotor_speed"].values[i] == p.rotor_speed_rpm
        for t, tr in enumerate(res.tracks):
            k = tr.index[res.points.index(p)]
            if k < 0:
                assert ds["mode_name"].values[i, t] == "" and math.isnan(ds["damping_ratio"].values[i, t])
                continue
            m = p.modes[k]
            lam = ds["eigenvalue_real"].values[i, t] + 1j * ds["eigenvalue_imag"].values[i, t]
            assert lam == m.eigenvalue
            assert ds["damping_ratio"].values[i, t] == m.damping_ratio
            assert ds["mode_name"].values[i, t] == m.name and ds["whirl"].values[i, t] == m.whirl
    assert list(ds["track_name"].values) == [t.name for t in res.tracks]
    assert ds.attrs["assumption_drivetrain"] == "flexible"


def test_campbell_dataset_refuses_repeated_wind_speeds_and_lost_modes():
    res = synthetic_campbell()
    res.points[1].wind_speed = 5.0
    with pytest.raises(InputError, match="wind_speeds"):
        campbell_dataset(res)
    res = synthetic_campbell()
    res.tracks[0].index[0] = -1
    with pytest.raises(InputError, match="tracks at point 0"):
        campbell_dataset(res)


def test_stored_campbell_reads_back(tmp_path, stable_campbell):
    ds = campbell_dataset(stable_campbell)
    back = store.open_campbell(store.write_campbell(tmp_path, stable_campbell).parent)
    xr.testing.assert_equal(back, ds)
    with pytest.raises(InputError, match="campbell"):
        store.open_campbell(tmp_path / "nothing")


def test_run_store_eigenvalues_and_mode_identity_across_points():
    from windflutter.workflow import OperatingPoint, PointResult

    rpm = np.array([5.0, 10.0])
    f = np.array([[0.5, 1.5, 2.5], [0.6, 1.4, 2.6]])
    z = np.array([[0.02, 0.3, 0.01], [0.01, 0.2, -0.02]])
    order = ([0, 1, 2], [2, 0, 1])   # the second point lists its modes in another order
    labels = ["1st flap", "1st edge", "1st torsion"]
    pts = {}
    for i, perm in enumerate(order):
        res = PointResult(sweep_rpm=rpm, damped_frequency_hz=f[:, perm], damping_ratio=z[:, perm],
                          mode_labels=[labels[j] for j in perm], flutter_rpm=np.nan, divergence_rpm=np.nan)
        pts[i] = store.point_dataset(OperatingPoint(i, 8.0 + i, "potential", "pk", 5.0, 10.0, 0.1, tuple(rpm)), res)
    ds = store.combine(pts)
    assert list(ds["mode_name"].values) == labels
    for i in range(2):   # the same mode at the same slot at every point
        assert list(ds["mode_label"].values[i]) == labels
        np.testing.assert_array_equal(ds["damped_frequency"].values[i], f)
        # the undamped frequency of a damped oscillator: f_n = f_d / sqrt(1 - zeta^2)
        np.testing.assert_allclose(ds["frequency"].values[i], f / np.sqrt(1 - z**2), rtol=1e-14)
    # eigenvalues: Im = 2 pi f_d (the damped frequency), |lambda| = 2 pi f_n, zeta = -Re/|lambda|
    lam = ds["eigenvalue_real"].values + 1j * ds["eigenvalue_imag"].values
    np.testing.assert_allclose(lam.imag / (2 * np.pi), ds["damped_frequency"].values, rtol=1e-14)
    np.testing.assert_allclose(np.abs(lam) / (2 * np.pi), ds["frequency"].values, rtol=1e-14)
    np.testing.assert_allclose(-lam.real / np.abs(lam), ds["damping_ratio"].values, rtol=1e-12)
    assert "undamped" in ds["frequency"].attrs["long_name"] and "damped" in ds["damped_frequency"].attrs["long_name"]
