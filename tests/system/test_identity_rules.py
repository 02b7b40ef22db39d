"""Rules of the naming (system/identity.py) on stand-in participations: the rigid rotation keeps
its rigid-body name whatever its share (so that it is never reported as an instability)."""

from __future__ import annotations

import numpy as np

from windflutter.system.identity import RIGID_HZ, Identity, assign, rigid_rotation

IDS = [Identity("flap", 1, "collective"), Identity("rigid", 0), Identity("edge", 1, "BW")]


def test_a_heavily_damped_rotor_speed_root_is_the_rigid_rotation():
    """The IEA 22 MW shell at 8 m/s: its 0.004 Hz root, -79 % damped, is 60 % 1st flap collective
    and 30 % rigid rotation by its energy -- the assignment gives the flap to the flap mode and the
    rigid rotation to the root, below the naming's floor of a heavily damped mode (half its largest
    share); it is still the rigid rotation."""
    S = np.array([[0.6, 0.3, 0.1],    # the rotor-speed root
                  [0.9, 0.0, 0.1],    # the 1st flap collective
                  [0.0, 0.0, 1.0]])
    f = np.array([0.004, 0.6, 0.45])
    got = assign(S)
    assert rigid_rotation(IDS, S, f, got) == {0: 1}


def test_no_rigid_rotation_above_its_frequency_or_without_its_share():
    S = np.array([[0.6, 0.3, 0.1], [0.9, 0.0, 0.1], [0.0, 0.0, 1.0]])
    assert rigid_rotation(IDS, S, np.array([RIGID_HZ * 1.1, 0.6, 0.45]), assign(S)) == {}
    S0 = S.copy()
    S0[0] = [0.6, 0.0, 0.4]  # no rigid rotation in it
    assert rigid_rotation(IDS, S0, np.array([0.004, 0.6, 0.45]), assign(S0)) == {}
