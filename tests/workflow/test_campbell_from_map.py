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
        out[v] = campbell_module.campbell_point(*st.operating, max_hz=2.0)  # the Campbell's limit below
    return out


def _counted(monkeypatch):
    """The wind speeds of the points evaluated in this process (``OperationalModel.at``) from now on."""
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


def test_prepared_points_are_read_the_rest_evaluated(nrel5mw, monkeypatch):
    """Two wind speeds prepared, one not (a resumed run's stored point), every step ambiguous (``JUMP``
    0): the missing point and the two middles are evaluated, the prepared ones are not, and the
    Campbell is the one the same model gives evaluating every point."""
    monkeypatch.setattr(campbell_module, "JUMP", 0.0)
    own = campbell(nrel5mw, WINDS, max_hz=2.0, workers=1, model=OperationalModel(nrel5mw, SHELL))
    solver = _solver(nrel5mw, SHELL)
    prepared = _prepared(solver, [WINDS[0], WINDS[2]])
    seen = _counted(monkeypatch)
    got = campbell(nrel5mw, WINDS, max_hz=2.0, workers=1, model=solver.model, prepared=prepared)
    assert sorted(seen) == sorted([WINDS[1], 0.5 * (WINDS[0] + WINDS[1]), 0.5 * (WINDS[1] + WINDS[2])])
    _same(own, got)


def _run(nrel5mw, tmp_path, monkeypatch, model: dict, workers: int):
    """``(campbell, own, evaluated)`` of ``windflutter run``: the Campbell it wrote, the one the same
    model gives evaluating every point itself, and the evaluations in this process during the run.
    Modes up to 2 Hz: above, a shell tower's degenerate wall pairs (3rd and 4th tower wall n=2 at
    the same frequency) may take their two ordinals in either order from bases equal to 1e-6."""
    import windflutter
    from windflutter import workflow

    cfg = windflutter.analysis_config(wind_speeds=[8.0, 12.0], model=model,
                                      rotor_speed={"min_rpm": 4, "max_rpm": 16, "n_points": 4}, campbell={"max_hz": 2.0},
                                      output={"plots": False, "report": False, "animations": False})
    got, orig = {}, workflow.operating_campbell
    seen = _counted(monkeypatch)

    def operating_campbell(turbine, config, analyser=None, progress=False, workers=1, prepared=None):
        assert sorted(prepared) == [8.0, 12.0]
        got["run"] = orig(turbine, config, analyser, progress, workers=workers, prepared=prepared)
        got["evaluated"] = list(seen)
        got["own"] = orig(turbine, config, analyser, progress, workers=1)  # the same model, every point its own
        return got["run"]

    monkeypatch.setattr(workflow, "operating_campbell", operating_campbell)
    windflutter.run(nrel5mw, cfg, tmp_path / "out", progress=False, workers=workers)
    return got["run"], got["own"], got["evaluated"]


@pytest.mark.slow  # the default suite runs the 2-worker shell case below and the reduced run end to end
def test_a_run_hands_its_operating_points_to_the_campbell(nrel5mw, tmp_path, monkeypatch):
    """``windflutter run`` (beam, in this process): its Campbell evaluates no point of its own (the
    evaluations seen are the map's) and equals the one its model gives evaluating them."""
    run, own, seen = _run(nrel5mw, tmp_path, monkeypatch, {"n_aero_sections": 12}, workers=1)
    assert len(seen) > 2
    _same(own, run)


@pytest.mark.parametrize("model", [pytest.param({"n_aero_sections": 12}, marks=pytest.mark.slow),
                                   {"type": "shell", "n_aero_sections": 12, "mesh_density": 0.5}])
def test_a_run_on_workers_hands_its_operating_points_to_the_campbell(nrel5mw, tmp_path, monkeypatch, model):
    """The same on two worker processes (nothing evaluated here): their analysers are copies of this
    one, which shared the Campbell case's model first (``share_campbell_model``), so the points they
    assembled are named through this process's support basis.  (A shell tower's wall modes come in
    degenerate pairs: with ARPACK's random start for the support basis, and without the sharing, the
    shell case failed here -- its drivetrain root named "5th tower fore-aft + 8th tower wall n=3".)"""
    run, own, seen = _run(nrel5mw, tmp_path, monkeypatch, model, workers=2)
    assert seen == []
    _same(own, run)


def test_a_model_that_cannot_be_built_is_left_to_the_workers(nrel5mw, monkeypatch):
    """``share_campbell_model`` on a model whose build fails (here its reference): no error before the
    run (each worker's point then fails with the reason, as before) and no operating point kept."""
    import windflutter
    from windflutter.analysers import TurbinePointAnalyser
    from windflutter.errors import ModelError

    def fail(self):
        raise ModelError("no model")

    monkeypatch.setattr(OperationalModel, "reference", fail)
    an = TurbinePointAnalyser(nrel5mw, windflutter.analysis_config(wind_speeds=[8.0]))
    an.share_campbell_model()
    assert an._campbell is None and not an._cases
