"""NetCDF store: one point per file, atomic writes, values survive a reopen."""

from __future__ import annotations

import os

import numpy as np
import pytest
import xarray as xr

from windflutter.post import store
from windflutter.workflow import OperatingPoint, PointResult


def _point(i, v=8.0):
    return OperatingPoint(i, v, "potential", "pk", 2.0, 30.0, 0.01, (2.0, 16.0, 30.0))


def _result(rng, ns=5):
    return PointResult(
        flutter_rpm=17.25, flutter_frequency_hz=1.75, flutter_mode="1st torsion", divergence_rpm=np.nan,
        sweep_rpm=np.array([2.0, 16.0, 30.0]), damped_frequency_hz=rng.random((3, 4)), damping_ratio=rng.random((3, 4)) - 0.5,
        mode_labels=["1st flap", "1st edge", "2nd flap", "1st torsion"], station_radius=np.linspace(5, 60, ns),
        flutter_shape=rng.random((ns, 3)) + 1j * rng.random((ns, 3)), aero_work=rng.random((ns, 3)) - 0.5,
        info={"iterations": 7, "converged": True, "pitch_deg": 1.5})


def test_point_roundtrip_same_values(tmp_path):
    rng = np.random.default_rng(1)
    res = _result(rng)
    ds = store.point_dataset(_point(3), res, {"config_fingerprint": "abc"})
    path = store.write_point(tmp_path, ds)
    assert path.name == "p0003.nc"
    back = store.read_points(tmp_path)[3]
    xr.testing.assert_identical(back.drop_vars("mode_label"), ds.drop_vars("mode_label"))
    assert list(back["mode_label"].values[0]) == res.mode_labels
    shape = store.flutter_shape(back).values[0]
    np.testing.assert_array_equal(shape, res.flutter_shape)      # bit-exact (float64 on disk)
    assert back.attrs["info_iterations"] == 7 and back.attrs["config_fingerprint"] == "abc"
    for name in ("flutter_rpm", "frequency", "damping_ratio", "aero_work", "station_radius"):
        assert "units" in back[name].attrs and "long_name" in back[name].attrs
    assert back["flutter_rpm"].attrs["units"] == "rpm" and back["frequency"].attrs["units"] == "Hz"


def test_combine_pads_points_of_different_sizes(tmp_path):
    rng = np.random.default_rng(2)
    a = store.point_dataset(_point(0, 4.0), _result(rng, ns=5))
    b = store.point_dataset(_point(1, 6.0), PointResult(status="failed", reason="ConvergenceError: no"))
    c = store.point_dataset(_point(2, 8.0), _result(rng, ns=7))
    ds = store.combine({2: c, 0: a, 1: b})
    assert list(ds["point"].values) == [0, 1, 2]
    assert ds.sizes["station"] == 7 and ds.sizes["mode"] == 4
    assert np.isnan(ds["station_radius"].values[0, 5:]).all()
    assert np.isnan(ds["frequency"].values[1]).all()
    assert list(ds["status"].values) == ["ok", "failed", "ok"]
    assert ds["reason"].values[1] == "ConvergenceError: no"
    store.atomic_write_netcdf(ds, tmp_path / "r.nc")
    back = store.open_results(tmp_path / "r.nc")
    for name in ds.data_vars:
        if ds[name].dtype.kind in "fi":
            np.testing.assert_array_equal(back[name].values, ds[name].values)
        else:
            assert [str(x) for x in back[name].values.ravel()] == [str(x) for x in ds[name].values.ravel()]


def test_atomic_write_keeps_old_file_on_failure(tmp_path, monkeypatch):
    ds = xr.Dataset({"x": ("a", [1.0, 2.0])})
    path = store.atomic_write_netcdf(ds, tmp_path / "f.nc")

    def boom(*args, **kw):
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", boom)
    with pytest.raises(OSError):
        store.atomic_write_netcdf(xr.Dataset({"x": ("a", [9.0])}), path)
    monkeypatch.undo()
    assert [p.name for p in tmp_path.iterdir()] == ["f.nc"]   # no temporary left behind
    np.testing.assert_array_equal(store.open_results(path)["x"].values, [1.0, 2.0])


def test_clean_temporaries(tmp_path):
    (tmp_path / "points").mkdir()
    (tmp_path / "points" / ".p0001.abc.nc.tmp").write_bytes(b"half")
    (tmp_path / ".results.x.nc.tmp").write_bytes(b"half")
    assert store.clean_temporaries(tmp_path) == 2
    assert store.read_points(tmp_path) == {}
    assert os.listdir(tmp_path / "points") == []
