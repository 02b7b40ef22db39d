"""The run loop with the toy analyser (an analytic typical section): storage, failures,
interrupt + resume, report."""

from __future__ import annotations

import re

import numpy as np
import pytest

import toy_analyser
from helpers import assert_same_results
from windflutter.errors import InputError
from windflutter.post import store
from windflutter.workflow import PointResult, RunInterrupted, plan_points, run


def test_plan_points_order(toy_config):
    cfg = toy_config()
    pts = plan_points(cfg)
    assert [p.index for p in pts] == list(range(8))
    assert [(p.aero, p.wind_speed) for p in pts[:5]] == [("potential", 4.0), ("potential", 10.0),
                                                        ("potential", 16.0), ("potential", 25.0),
                                                        ("viscous", 4.0)]
    assert pts[0].sweep_rpm == tuple(np.linspace(2, 26, 9))


def test_run_stores_every_point_with_units(toy_config, tmp_path):
    cfg = toy_config()
    ds = run(None, cfg, tmp_path, progress=False)
    assert ds.sizes["point"] == 8 and ds.attrs["complete"] == 1
    assert len(list((tmp_path / "points").glob("p*.nc"))) == 8
    back = store.open_results(tmp_path)
    np.testing.assert_array_equal(back["flutter_rpm"].values, ds["flutter_rpm"].values)
    # the toy's onset is independent of the case set-up: check a physical property instead of
    # a stored number -- the section flutters at one relative speed U_F, so
    # (Omega_F r)^2 + V^2 is the same at every wind speed (to the 0.01 RPM search tolerance)
    pot = ds.where(ds["aero"] == "potential", drop=True)
    u_f = np.hypot(pot["wind_speed"], pot["flutter_rpm"] * np.pi / 30 * toy_analyser.RADIUS).values
    assert np.ptp(u_f) < 2 * 0.01 * np.pi / 30 * toy_analyser.RADIUS + 1e-9
    # divergence: closed form sqrt(K_a / (2 pi rho b^2 (a + 1/2)))
    u_d = np.hypot(pot["wind_speed"], pot["divergence_rpm"] * np.pi / 30 * toy_analyser.RADIUS).values
    np.testing.assert_allclose(u_d, toy_analyser.divergence_speed(), rtol=1e-12)
    for name in ("flutter_rpm", "divergence_rpm", "frequency", "damping_ratio", "rotor_speed"):
        assert back[name].attrs["units"]
    for key in ("windflutter_version", "numpy_version", "config_yaml", "config_fingerprint",
                "solver_n_eig", "solver_reduction", "rated_rpm", "overspeed_rpm"):
        assert key in back.attrs
    assert back.attrs["overspeed_rpm"] == pytest.approx(1.2 * 12.1)
    assert "operating_rpm" in back


def test_failed_point_is_recorded_and_run_continues(toy_config, tmp_path, monkeypatch):
    monkeypatch.setenv("TOY_FAIL_WIND", "10")
    ds = run(None, toy_config(aero=["potential"]), tmp_path, progress=False)
    status = list(ds["status"].values)
    assert status == ["ok", "failed", "ok", "ok"]
    assert "ConvergenceError" in ds["reason"].values[1] and "10.0 m/s" in ds["reason"].values[1]
    assert np.isnan(ds["flutter_rpm"].values[1]) and np.isfinite(ds["flutter_rpm"].values[2])


class InterruptAfter:
    """Wraps the toy: Ctrl-C (KeyboardInterrupt) arrives during the n-th call."""

    def __init__(self, n):
        self.toy = toy_analyser.ToyAnalyser()
        self.n = n
        self.calls = 0

    def describe(self):
        return self.toy.describe()

    def __call__(self, point, progress=None):
        self.calls += 1
        if self.calls == self.n:
            raise KeyboardInterrupt
        return self.toy(point, progress)


def test_interrupt_keeps_points_and_resume_equals_uninterrupted(toy_config, tmp_path):
    cfg = toy_config(wind_speeds=[4, 10, 16, 25], aero=["potential"])
    ref = run(None, cfg, tmp_path / "ref", progress=False)
    with pytest.raises(RunInterrupted) as ei:
        run(None, cfg, tmp_path / "cut", progress=False, analyser=InterruptAfter(3))
    assert ei.value.done == 2 and ei.value.total == 4
    partial = store.open_results(tmp_path / "cut")
    assert partial.sizes["point"] == 2 and partial.attrs["complete"] == 0
    counter = InterruptAfter(10**6)
    res = run(None, cfg, tmp_path / "cut", resume=True, progress=False, analyser=counter)
    assert counter.calls == 2                     # only the missing points were computed
    assert_same_results(res, ref)
    assert_same_results(store.open_results(tmp_path / "cut"), store.open_results(tmp_path / "ref"))


def test_resume_refuses_a_different_config(toy_config, tmp_path):
    run(None, toy_config(wind_speeds=[4, 10], aero=["potential"]), tmp_path, progress=False)
    with pytest.raises(InputError, match="--resume"):
        run(None, toy_config(wind_speeds=[4, 12], aero=["potential"]), tmp_path, resume=True, progress=False)


def test_fresh_run_discards_old_points(toy_config, tmp_path):
    run(None, toy_config(wind_speeds=[4, 10, 16], aero=["potential"]), tmp_path, progress=False)
    ds = run(None, toy_config(wind_speeds=[4], aero=["potential"]), tmp_path, progress=False)
    assert ds.sizes["point"] == 1
    assert len(list((tmp_path / "points").glob("p*.nc"))) == 1


def test_bad_analyser_return_is_a_failed_point(toy_config, tmp_path):
    ds = run(None, toy_config(wind_speeds=[4], aero=["potential"]), tmp_path, progress=False,
             analyser=lambda point: {"flutter_rpm": 3})
    assert ds["status"].values[0] == "failed" and "PointResult" in ds["reason"].values[0]


def test_report_contains_every_figure(toy_config, tmp_path, monkeypatch):
    from windflutter.post import plots

    monkeypatch.setenv("TOY_FAIL_WIND", "16")
    cfg = toy_config(wind_speeds=[4, 16, 25], aero=["potential"], method=["pk", "thesis"],
                     output={"plots": True, "report": True, "dpi": 30})
    ds = run(None, cfg, tmp_path, progress=False)
    html = (tmp_path / "report.html").read_text()
    names = list(plots.all_figures(ds))
    expected = ["stability_map"] + [f"{kind}_potential_{m}" for m in ("pk", "thesis")
                                    for kind in ("campbell", "damping", "flutter_mode", "aero_work")]
    assert sorted(names) == sorted(expected)
    for name in names:
        assert f"data-figure='{name}'" in html
        assert (tmp_path / "figures" / f"{name}.png").is_file()
    assert len(re.findall(r"src='data:image/png;base64,[A-Za-z0-9+/=]{200,}'", html)) == len(names)
    assert "http" not in html.replace("http-equiv", "")       # self-contained: nothing fetched
    assert "failed" in html and "margin to rated" in html
    assert "ConvergenceError" in html


def test_progress_bars_draw(toy_config, tmp_path):
    import io

    buf = io.StringIO()
    run(None, toy_config(wind_speeds=[4, 10], aero=["potential"]), tmp_path, progress=True, stream=buf)
    out = buf.getvalue()
    assert "2/2" in out and "run" in out


def test_flutter_mode_animation_series(toy_config, tmp_path):
    import xml.etree.ElementTree as ET

    import meshio

    cfg = toy_config(wind_speeds=[10], aero=["potential"],
                     output={"animations": True, "animation_frames": 16})
    ds = run(None, cfg, tmp_path, progress=False)
    pvd = tmp_path / "animations" / "flutter_p0000.pvd"
    assert pvd.is_file()
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    assert len(sets) == 16
    frames = [meshio.read(pvd.parent / d.get("file")) for d in sets]
    times = [float(d.get("timestep")) for d in sets]
    # one period of the flutter frequency, 16 equal steps
    np.testing.assert_allclose(np.diff(times), 1 / 16 / float(ds["flutter_frequency"][0]), rtol=1e-6)
    x = np.array([f.points[-1, 0] for f in frames])       # tip flap motion over the cycle
    assert x.max() > 0 > x.min()                            # it oscillates about the rest position
