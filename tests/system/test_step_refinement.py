"""Step refinement of the names along a sweep (issue 32, item 2): where a named mode's natural frequency
jumps across a step, the names are carried through the step's middle -- along the wind speeds (the
Campbell, system/campbell.py) and along the rotor speed (the overspeed sweep, overspeed.py).
The physics of the names is tested in test_mode_identity.py and test_hawcstab2_identity.py; here the
rule that triggers a refinement and the wiring of both sweeps, with stand-in modes."""

from __future__ import annotations

from collections import OrderedDict
from types import SimpleNamespace

import numpy as np
import pytest

from windflutter.system import campbell as campbell_module
from windflutter.system.campbell import JUMP, ambiguous
from windflutter.system.identity import Identity
from windflutter.system.modes import ModeRecord


def _mode(identity, f, zeta=0.02):
    w = 2 * np.pi * f  # undamped natural frequency f (Hz)
    rec = ModeRecord(eigenvalue=complex(-zeta * w, w * np.sqrt(1 - zeta**2)), family=identity.family,
                     whirl=identity.whirl)
    rec.identity = identity
    return rec


EDGE = Identity("edge", 1, "BW")
FLAP = Identity("flap", 1, "BW")


def test_a_step_is_ambiguous_when_a_lightly_damped_name_jumps():
    """A name whose frequency moves by more than JUMP (12 %) between two points, both damped below
    30 %, makes the step ambiguous; a smaller move, a heavily damped mode or a new name does not."""
    before = [_mode(EDGE, 1.0), _mode(FLAP, 2.0, 0.5)]
    assert not ambiguous(before, [_mode(EDGE, 1.0 + 0.9 * JUMP)])
    assert ambiguous(before, [_mode(EDGE, 1.0 + 1.1 * JUMP)])
    assert ambiguous(before, [_mode(EDGE, 1.0 - 1.1 * JUMP)])
    assert not ambiguous(before, [_mode(FLAP, 3.0, 0.5)])  # heavily damped: its natural frequency moves
    assert not ambiguous(before, [_mode(Identity("torsion", 1, "BW"), 5.0)])


def test_the_rigid_body_root_does_not_make_a_step_ambiguous():
    """The drivetrain's free rotation (family ``rigid``) at a few mHz: its frequency doubling between
    two points is the remainder of a zero one moving, not a swapped name -- no refinement; the same
    jump of an elastic name still refines."""
    rigid = Identity("rigid", 0, "none")
    before = [_mode(rigid, 0.005), _mode(EDGE, 1.0)]
    after = [_mode(rigid, 0.010), _mode(EDGE, 1.0)]
    for m in before + after:
        m.rigid = m.family == "rigid"
    assert not ambiguous(before, after)
    assert ambiguous(before, [after[0], _mode(EDGE, 1.0 + 1.1 * JUMP)])


def _recording_point_modes(calls, jump_at, eigs=None):
    """A point_modes stand-in: the modes at the point ``ps`` (its ``x``), whose 1st edge BW is
    misnamed (a mode at 1.5 Hz carries it) where a step longer than 1.5 crosses ``jump_at``; records
    (x, previous x), and in ``eigs`` (x, the eigen-solution passed)."""
    def point_modes(ps, max_hz, previous=None, eig=None):
        src = None if previous is None else previous[0].x
        calls.append((ps.x, src))
        if eigs is not None:
            eigs.append((ps.x, eig))
        f = 1.5 if src is not None and src <= jump_at < ps.x and ps.x - src > 1.5 else 1.0
        rec = _mode(EDGE, f)
        rec.x = ps.x
        return [rec]
    return point_modes


def test_campbell_refines_an_ambiguous_wind_step_through_its_middle(monkeypatch):
    """Along the wind speeds: the step 10 -> 12 m/s is ambiguous (the name jumps past 10.5 m/s), so
    the point at 12 m/s is named again, continuing a point at 11 m/s (its middle) that is not reported."""
    calls, eigs = [], []
    monkeypatch.setattr(campbell_module, "point_modes", _recording_point_modes(calls, 10.5, eigs))
    mbc = SimpleNamespace(state_matrix=lambda: np.diag([-1.0, -2.0]))
    model = SimpleNamespace(at=lambda v: SimpleNamespace(x=v, omega=1.0, pitch=0.0, steady=None, mbc=mbc),
                            options=SimpleNamespace(part="turbine"), describe=lambda: {})
    monkeypatch.setattr(campbell_module, "track_modes", lambda pts: [])
    res = campbell_module.campbell(None, [8.0, 10.0, 12.0], model=model)
    assert [p.wind_speed for p in res.points] == [8.0, 10.0, 12.0]
    assert (11.0, 10.0) in calls and (12.0, 11.0) in calls
    assert all(src is None or x - src <= 2.0 for x, src in calls)
    assert res.points[-1].modes[0].frequency_hz == pytest.approx(1.0)  # named through the middle
    # the reported point's eigen-solution is solved once and passed to both of its namings
    at12 = [e for x, e in eigs if x == 12.0]
    assert len(at12) == 2 and at12[0] is not None and at12[0] is at12[1]


def test_overspeed_sweep_refines_an_ambiguous_rotor_speed_step_through_its_middle(monkeypatch):
    """Along the rotor speed: the same for the overspeed sweep's step 12 -> 14 RPM."""
    from windflutter import overspeed

    calls = []
    monkeypatch.setattr(overspeed, "point_modes", _recording_point_modes(calls, 13.0))
    st = overspeed.OperationalStability.__new__(overspeed.OperationalStability)
    st.model = SimpleNamespace(at=lambda v, rpm, pitch: SimpleNamespace(x=rpm))
    st._points = OrderedDict()
    st.max_hz = lambda pitch: 5.0
    _, before = st._modes(10.0, 12.0, 0.0)
    _, modes = st._continued(10.0, 0.0, (12.0, before), 14.0)
    assert (13.0, 12.0) in calls and (14.0, 13.0) in calls
    assert modes[0].frequency_hz == pytest.approx(1.0)
    assert st._modes(10.0, 14.0, 0.0)[1] is modes  # the cached point carries the refined names
    _, modes = st._continued(10.0, 0.0, (14.0, modes), 16.0)  # no jump: no refinement
    assert (15.0, 14.0) not in calls
