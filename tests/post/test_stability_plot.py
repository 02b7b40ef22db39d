"""``windflutter stability --plot``: the first wind speed's search drawn by the run's rotor-speed
Campbell figure (issue 29: one Campbell plotter for the sweep of a point), through the one
conversion of a search's summary into the run's result (``results.point_result``)."""

from __future__ import annotations

import numpy as np

from windflutter import methods
from windflutter.cli import main
from windflutter.model import windio
from windflutter.results import Onset, PointSummary, point_result


def summary(v: float = 10.0) -> PointSummary:
    rpm = np.array([10.0, 12.0, 14.0])
    f = np.array([[0.7, 1.1], [0.72, 1.08], [0.74, 1.05]])
    z = np.array([[0.02, 0.01], [0.01, 0.0], [0.0, -0.01]])
    return PointSummary(wind_speed=v, pitch_deg=1.5, flutter_rpm=12.0, flutter_frequency_hz=1.08,
                        flutter_mode="1st edge BW", divergence_rpm=None, sweep_rpm=rpm, damped_frequency_hz=f,
                        damping_ratio=z, mode_labels=["1st flap BW", "1st edge BW"], onset=Onset(method="p"))


def test_point_result_carries_the_summary_and_none_becomes_nan():
    s = summary()
    r = point_result(s, info={"n_dof": 6}, reason="why")
    assert r.flutter_rpm == 12.0 and np.isnan(r.divergence_rpm) and r.flutter_mode == "1st edge BW"
    assert np.array_equal(r.damped_frequency_hz, s.damped_frequency_hz) and r.mode_labels == s.mode_labels
    assert r.info == {"pitch_deg": 1.5, "n_dof": 6} and r.reason == "why"


def test_stability_plot_draws_the_first_point(monkeypatch, tmp_path, capsys):
    class Search:
        def analyse_operating_point(self, v, rpm_grid=None):
            return summary(v)

    monkeypatch.setattr(windio, "load_turbine", lambda name: type("T", (), {"name": "toy", "operating": None})())
    monkeypatch.setattr(methods, "stability_analysis", lambda *a, **k: Search())
    monkeypatch.setattr("windflutter.cli.warn.curve_rpm", lambda t: None)
    monkeypatch.setattr("windflutter.cli.warn.operating_rotor_speed", lambda rpm: None)
    out = tmp_path / "campbell.png"
    assert main(["stability", "nrel5mw", "--wind-speeds", "10", "12", "--plot", str(out), "--json"]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000
    assert '"flutter_rpm": 12.0' in capsys.readouterr().out


def test_real_roots_are_not_drawn_as_zero_frequency_and_divergence_is_a_line():
    # past static divergence (and for overdamped roots) a root is real: its damped frequency is 0.
    # The Campbell figure draws oscillations: that point is left out of its track (no line down to
    # the axis), and the divergence onset is drawn like the flutter onset.
    from windflutter.post import plots, store
    from windflutter.workflow import OperatingPoint

    s = summary()
    s.damped_frequency_hz = np.array([[0.7, 1.1], [0.72, 1.08], [0.74, 0.0]])
    s.divergence_rpm = 13.5
    res = point_result(s)
    ds = store.combine({0: store.point_dataset(OperatingPoint(0, 10.0, "viscous", "p", 10.0, 14.0, 0.01,
                                                              tuple(s.sweep_rpm)), res)}, {"turbine": "toy"})
    fig = plots.campbell(ds, 0)
    ax = fig.axes[0]
    tracks = [ln.get_ydata() for ln in ax.lines if len(ln.get_ydata()) == 3 and ln.get_linestyle() == "-"]
    edge = next(y for y in tracks if np.isclose(y[0], 1.1))
    assert np.isnan(edge[2]) and np.allclose(edge[:2], [1.1, 1.08])
    assert any("divergence 13.50 RPM" in t for t in ax.get_legend_handles_labels()[1])
    # the mask itself: the sweep's real roots only
    f = plots.oscillating(np.array([[1.0, 0.0], [2.0, 1e-9]]))
    assert np.isnan(f[:, 1]).all() and np.array_equal(f[:, 0], [1.0, 2.0])


def test_heavily_damped_points_have_no_line_and_no_label():
    # a heavily damped mode's damped frequency moves fast with the rotor speed and means little (the
    # NREL 5 MW's aerodynamically damped flap modes, 80-90 % at overspeed, rose from 0.5 to 3 Hz across
    # the diagram): its points are open circles, lines join lightly damped neighbours only, and a
    # track is labelled at its last lightly damped point (none: no label)
    from windflutter.post import plots, store
    from windflutter.system.campbell import HEAVILY_DAMPED
    from windflutter.workflow import OperatingPoint

    s = summary()
    s.damping_ratio = np.array([[0.02, 0.01], [0.5, 0.0], [0.8, -0.01]])
    res = point_result(s)
    ds = store.combine({0: store.point_dataset(OperatingPoint(0, 10.0, "viscous", "p", 10.0, 14.0, 0.01,
                                                              tuple(s.sweep_rpm)), res)}, {"turbine": "toy"})
    ax = plots.campbell(ds, 0).axes[0]
    tracks = [ln.get_ydata() for ln in ax.lines if len(ln.get_ydata()) == 3 and ln.get_linestyle() == "-"]
    flap = next(y for y in tracks if np.isclose(y[0], 0.7))
    assert np.isnan(flap[1:]).all() and 0.5 > HEAVILY_DAMPED
    edge = next(y for y in tracks if np.isclose(y[0], 1.1))
    assert np.isfinite(edge).all()
    texts = [t.get_text() for t in ax.texts]
    assert "1st edge BW" in texts and "1st flap BW" in texts  # the flap's label at its first, light point
    s.damping_ratio[0, 0] = 0.9  # heavily damped everywhere: no label
    res = point_result(s)
    ds = store.combine({0: store.point_dataset(OperatingPoint(0, 10.0, "viscous", "p", 10.0, 14.0, 0.01,
                                                              tuple(s.sweep_rpm)), res)}, {"turbine": "toy"})
    assert "1st flap BW" not in [t.get_text() for t in plots.campbell(ds, 0).axes[0].texts]
