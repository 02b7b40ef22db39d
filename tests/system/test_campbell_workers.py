"""The Campbell's points evaluated in worker processes (issue 33): the same names, frequencies and
damping as the serial run (system/campbell.py, ``workers``), on the NREL 5 MW with a coarse shell blade
linearized about its deflected shape (the case whose points are worth a process: a shell blade basis,
iterative, warm-started from the worker's own previous point)."""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.system.campbell import campbell, campbell_workers
from windflutter.system.operational import OperationalModel, OperationalOptions

SHELL = OperationalOptions(model="shell", structure="deflected", mesh={"n_span": 6, "n_chord": 12})
WINDS = [5.0, 8.0, 11.0, 14.0, 20.0]


def _table(res):
    return [(p.wind_speed, p.rotor_speed_rpm, p.pitch_deg,
             [(m.name, m.frequency_hz, m.damping_ratio) for m in p.modes]) for p in res.points]


def test_two_workers_give_the_serial_campbell(nrel5mw_turbine):
    """Names identical point by point, tracks identical; frequencies to 2.3e-6 relative and damping
    ratios to 1.5e-6 (absolute): the blade basis is iterative (converged to 1e-6) and its warm start in
    a worker is the worker's own previous point, not the curve's previous one (docs/notes/
    performance_rounds.md, sections 11 and 12).  Above rated (14, 20 m/s) every point has its own pitch:
    the workers keep one pitched blade each (OperationalModel.keep_blades)."""
    serial = campbell(nrel5mw_turbine, WINDS, SHELL, max_hz=2.0, workers=1)
    seen = []
    pooled = campbell(nrel5mw_turbine, WINDS, SHELL, max_hz=2.0, workers=2,
                      progress=lambda f, text: seen.append(f))
    assert seen[0] == 0.0 and seen[-1] == 1.0 and len(seen) == len(WINDS) + 1
    a, b = _table(serial), _table(pooled)
    assert len(a) == len(b) and sum(len(p[3]) for p in a) > 3 * len(WINDS)
    for (v, rpm, pitch, ma), (w, rpm2, pitch2, mb) in zip(a, b):
        assert (v, rpm, pitch) == (w, rpm2, pitch2)
        assert [m[0] for m in ma] == [m[0] for m in mb], v
        np.testing.assert_allclose([m[1] for m in mb], [m[1] for m in ma], rtol=2.3e-6, atol=0)
        np.testing.assert_allclose([m[2] for m in mb], [m[2] for m in ma], rtol=0, atol=1.5e-6)
    assert [(t.name, t.index) for t in serial.tracks] == [(t.name, t.index) for t in pooled.tracks]
    assert [p.power for p in serial.points] == pytest.approx([p.power for p in pooled.points], rel=1e-6)


def test_refined_steps_middles_in_the_workers(nrel5mw_turbine, monkeypatch):
    """Every step ambiguous (JUMP patched to 0 in this process, where the names are checked): each
    step's middle is evaluated by a worker and carries the names as in the serial run (same
    tolerances as above); the middles are not reported."""
    from windflutter.system import campbell as campbell_module

    monkeypatch.setattr(campbell_module, "JUMP", 0.0)
    winds = [8.0, 12.0, 16.0]
    serial = campbell(nrel5mw_turbine, winds, SHELL, max_hz=2.0, workers=1)
    pooled = campbell(nrel5mw_turbine, winds, SHELL, max_hz=2.0, workers=2)
    assert [p.wind_speed for p in pooled.points] == winds
    for pa, pb in zip(serial.points, pooled.points):
        assert [m.name for m in pa.modes] == [m.name for m in pb.modes]
        np.testing.assert_allclose([m.frequency_hz for m in pb.modes], [m.frequency_hz for m in pa.modes],
                                   rtol=2.3e-6, atol=0)
        np.testing.assert_allclose([m.damping_ratio for m in pb.modes], [m.damping_ratio for m in pa.modes],
                                   rtol=0, atol=1.5e-6)


def test_workers_default_and_refusal(nrel5mw_turbine):
    """``workers=None``: the cores (at most one per point) for a shell model, 1 for a beam model; a
    non-positive count is refused naming the field."""
    beam = OperationalModel(nrel5mw_turbine, OperationalOptions())
    shell = OperationalModel(nrel5mw_turbine, SHELL)
    assert campbell_workers(beam, 20) == 1 and campbell_workers(beam, 20, 3) == 3
    assert 1 <= campbell_workers(shell, 20) and campbell_workers(shell, 1) == 1
    with pytest.raises(InputError, match="workers"):
        campbell_workers(shell, 20, 0)
    import windflutter

    with pytest.raises(InputError, match="workers"):  # refused before the turbine is read
        windflutter.campbell("no-such-turbine", [8.0], workers=0)


@pytest.mark.parametrize("error", ["model", "input"])
def test_a_points_own_error_in_a_worker_is_raised_as_in_the_serial_run(nrel5mw_turbine, monkeypatch, error):
    """A point that fails in a worker (no steady state: a ModelError; an InputError) is raised in the
    parent as the same one-line error of the same type, not as an unexpected RuntimeError carrying a
    traceback.  (The workers are forked: the patched ``OperationalModel.at`` is theirs too.)"""
    from windflutter.errors import ModelError

    real = OperationalModel.at

    def at(self, wind_speed, *args, **kwargs):
        if wind_speed == 11.0:
            raise (ModelError("no steady state at V = 11 m/s") if error == "model"
                   else InputError("wind_speed", 11.0, "a wind speed with a steady state"))
        return real(self, wind_speed, *args, **kwargs)

    monkeypatch.setattr(OperationalModel, "at", at)
    with pytest.raises(ModelError if error == "model" else InputError) as exc:
        campbell(nrel5mw_turbine, [8.0, 11.0], OperationalOptions(), max_hz=1.0, workers=2)
    assert ("no steady state at V = 11 m/s" if error == "model" else "wind_speed = 11.0") in str(exc.value)
    assert "Traceback" not in str(exc.value)
