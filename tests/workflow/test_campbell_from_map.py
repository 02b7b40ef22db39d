"""The run's operating-point Campbell reads the stability map's operating points (issue 33 item 2, the
shell map's time): each wind speed's sweep starts at the operating point, which the Campbell used to
evaluate again (11 shell points, 35-40 s of a 5.4 min NREL 5 MW shell run).  Checked: the Campbell from
prepared points equals the one that evaluates its points itself (names, frequencies, damping, tracks),
prepared points are not evaluated again, the missing ones and a refined step's middle are, and a run
hands its map's points over."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from windflutter.overspeed import OperationalStability, SearchSettings
from windflutter.system import campbell as campbell_module
from windflutter.system.campbell import campbell
from windflutter.system.operational import OperationalModel, OperationalOptions

SHELL = OperationalOptions(model="shell", structure="deflected", mesh={"n_span": 6, "n_chord": 12})
WINDS = [6.0, 11.0, 16.0]


def _solver(turbine, options):
    """A stability solver whose model's reference (and so its support) is computed, as a run's
    analyser shares it before it is copied to the workers (``share_campbell_model``)."""
    st = OperationalStability(turbine, options, SearchSettings(max_rpm=40.0))
    st.model.reference()
    return st


def _prepared(solver, winds):
    """``{V: point}`` as a run's workers keep them: a copy of ``solver`` (another process's, in a
    run) sweeps the operating point and one rotor speed above it at each wind speed."""
    st = pickle.loads(pickle.dumps(solver))
    st.keep_operating = True
    out = {}
    for v in winds:
        op = st.model.operating_point(v)[0] * 30 / np.pi
        st.analyse_operating_point(v, rpm_grid=[op + 1.0])
        out[v] = campbell_module.campbell_point(*st.operating)
    return out


def _counted(monkeypatch):
    """The rotor speeds (RPM) of the points the Campbell's own model evaluates."""
    seen = []
    orig = OperationalModel.at

    def at(self, wind_speed, rpm=None, pitch=None):
        seen.append(float(wind_speed))
        return orig(self, wind_speed, rpm, pitch)

    monkeypatch.setattr(OperationalModel, "at", at)
    return seen


def _same(a, b):
    """Names and tracks identical; frequencies to 2.3e-6 relative and damping ratios to 1.5e-6 absolute:
    the shell blade's basis is iterative (converged to 1e-6), started from scratch at each wind speed
    of a map and from the previous point along the Campbell (test_campbell_workers.py)."""
    assert [p.wind_speed for p in a.points] == [p.wind_speed for p in b.points]
    assert sum(len(p.modes) for p in a.points) > 3 * len(a.points)
    for pa, pb in zip(a.points, b.points):
        assert pa.rotor_speed_rpm == pytest.approx(pb.rotor_speed_rpm, rel=1e-12)
        assert pa.pitch_deg == pytest.approx(pb.pitch_deg, abs=1e-12)
        assert [m.name for m in pa.modes] == [m.name for m in pb.modes], pa.wind_speed
        np.testing.assert_allclose([m.frequency_hz for m in pb.modes], [m.frequency_hz for m in pa.modes],
                                   rtol=2.3e-6, atol=0)
        np.testing.assert_allclose([m.damping_ratio for m in pb.modes], [m.damping_ratio for m in pa.modes],
                                   rtol=0, atol=1.5e-6)
        assert pa.power == pytest.approx(pb.power, rel=1e-6)
    assert [(t.name, t.index) for t in a.tracks] == [(t.name, t.index) for t in b.tracks]


def test_prepared_points_give_the_campbell_without_evaluating_them(nrel5mw, monkeypatch):
    solver = _solver(nrel5mw, SHELL)
    own = campbell(nrel5mw, WINDS, max_hz=2.0, workers=1, model=OperationalModel(nrel5mw, SHELL))
    prepared = _prepared(solver, WINDS)
    seen = _counted(monkeypatch)
    got = campbell(nrel5mw, WINDS, max_hz=2.0, workers=1, model=solver.model, prepared=prepared)
    assert not set(seen) & set(WINDS)  # every point read; evaluated: a refined step's middle (8.5 m/s)
    _same(own, got)


def test_missing_wind_speeds_and_middles_are_evaluated(nrel5mw, monkeypatch):
    """One wind speed not prepared (a resumed run's stored point) and every step ambiguous (``JUMP``
    0): the missing point and the two middles are evaluated, the prepared ones are not."""
    monkeypatch.setattr(campbell_module, "JUMP", 0.0)
    own = campbell(nrel5mw, WINDS, max_hz=2.0, workers=1, model=OperationalModel(nrel5mw, SHELL))
    solver = _solver(nrel5mw, SHELL)
    prepared = _prepared(solver, [WINDS[0], WINDS[2]])
    seen = _counted(monkeypatch)
    got = campbell(nrel5mw, WINDS, max_hz=2.0, workers=1, model=solver.model, prepared=prepared)
    assert sorted(seen) == sorted([WINDS[1], 0.5 * (WINDS[0] + WINDS[1]), 0.5 * (WINDS[1] + WINDS[2])])
    _same(own, got)


def test_a_run_hands_its_operating_points_to_the_campbell(nrel5mw, tmp_path, monkeypatch):
    """``windflutter run`` (beam, in this process): its Campbell evaluates no point of its own and
    equals ``windflutter campbell``'s with the same config."""
    import windflutter
    from windflutter import workflow

    cfg = windflutter.analysis_config(wind_speeds=[8.0, 12.0], model={"n_aero_sections": 12},
                                      rotor_speed={"min_rpm": 4, "max_rpm": 16, "n_points": 4},
                                      output={"plots": False, "report": False, "animations": False})
    alone = windflutter.campbell(nrel5mw, [8.0, 12.0], config=cfg)
    got, orig = [], workflow.operating_campbell

    def operating_campbell(*args, **kw):
        assert sorted(kw["prepared"]) == [8.0, 12.0]
        got.append(orig(*args, **kw))
        return got[-1]

    monkeypatch.setattr(workflow, "operating_campbell", operating_campbell)
    seen = _counted(monkeypatch)
    windflutter.run(nrel5mw, cfg, tmp_path / "out", progress=False, workers=1)
    assert len(got) == 1 and len(seen) > 2  # the map's sweeps evaluated their points ...
    n_map = len(seen)
    _same(alone, got[0])  # ... and the Campbell none (the beam's basis is exact: equal to round-off)
    assert len(seen) == n_map
