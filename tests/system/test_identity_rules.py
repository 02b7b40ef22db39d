"""Rules of the naming (system/identity.py) on stand-in participations: the rigid rotation keeps
its rigid-body name whatever its share (so that it is never reported as an instability)."""

from __future__ import annotations

import numpy as np

from windflutter.system.identity import Identity, assign, name_record
from windflutter.system.modes import ModeRecord

IDS = [Identity("flap", 1, "collective"), Identity("rigid", 0), Identity("edge", 1, "BW")]


def _named(S: np.ndarray, heavy: bool = True) -> list[ModeRecord]:
    got = assign(S)
    recs = [ModeRecord(eigenvalue=complex(-1.0, 1.0), family="other", whirl="none") for _ in S]
    for i, rec in enumerate(recs):
        name_record(rec, IDS, S[i], int(got[i]), heavy=heavy)
    return recs


def test_a_heavily_damped_rotor_speed_root_is_the_rigid_rotation():
    """The IEA 22 MW shell at 8 m/s: its 0.004 Hz root, -79 % damped, is 60 % 1st flap collective
    and 30 % rigid rotation by its energy -- the assignment gives the flap to the flap mode and the
    rigid rotation to the root, below the naming's floor of a heavily damped mode (half its largest
    share); it is still the rigid rotation."""
    S = np.array([[0.6, 0.3, 0.1],    # the rotor-speed root
                  [0.9, 0.0, 0.1],    # the 1st flap collective
                  [0.0, 0.0, 1.0]])
    root = _named(S)[0]
    assert root.rigid and root.family == "rigid" and root.share == 0.3


def test_no_rigid_rotation_without_its_share():
    """A mode without any rigid rotation in it (participations give it none above RIGID_HZ) is not
    the rigid rotation, even where the assignment leaves it that identity."""
    S = np.array([[0.6, 0.0, 0.4], [0.9, 0.0, 0.1], [0.0, 0.0, 1.0]])
    assert not any(r.rigid for r in _named(S))


def test_a_round_off_share_is_no_second_participation():
    """A mode carried by one identity alone (an uncoupled tower wall mode: its other shares 1e-25, which
    identity by round-off) reports no second participation; a real one, however small, is kept."""
    S = np.array([[1.0, 1e-25, 0.0], [0.0, 1.0, 0.0], [1e-25, 0.0, 1.0]])
    assert [r.participation for r in _named(S, heavy=False)] == [[("1st flap collective", 1.0)],
                                                                 [("drivetrain rigid-body", 1.0)],
                                                                 [("1st edge BW", 1.0)]]
    S = np.array([[0.999, 1e-6, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    assert _named(S, heavy=False)[0].participation[1] == ("drivetrain rigid-body", 1e-6)
