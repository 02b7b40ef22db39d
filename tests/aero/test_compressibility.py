"""The incompressible strips' range (aero/compressibility.py): a point whose sweep takes the blade's fastest
strip above Mach 0.5 keeps a note from the rotor speed where it happens.

Independent reference: the rotor's geometry.  The fastest strip moves at about ``Omega R`` (its radius a
little inside the tip radius R, its inflow ``sqrt((Omega r (1 + a'))^2 + (V (1 - a))^2)``), so on a grid
of 4 RPM the note must start at the first grid speed whose tip speed ``Omega R`` passes 0.5 x 340 m/s: for
the NREL 5 MW (R = 63 m, IEA/NREL definition: rotor diameter 126 m) 28 RPM (tip 184.7 m/s; at 24 RPM
158.3 m/s, below by 7 %, more than the strip's offset from the tip and its induction can bridge)."""

import math
import re
import warnings

import numpy as np
import pytest

from windflutter.aero.compressibility import MACH_LIMIT, SPEED_OF_SOUND, warn_compressible
from windflutter.config import config_from_dict
from windflutter.errors import ValidityWarning
from windflutter.workflow import make_analyser, plan_points


def test_one_note_above_the_limit_with_its_rotor_speed():
    limit = MACH_LIMIT * SPEED_OF_SOUND
    with warnings.catch_warnings(record=True) as shown:
        warnings.simplefilter("always")
        warn_compressible(np.array([50.0, 0.99 * limit, np.nan]), 10.0, 2.0)
        assert not shown
        warn_compressible(np.array([50.0, 1.01 * limit]), 10.0, 3.0)
    (w,) = shown
    assert issubclass(w.category, ValidityWarning) and "Mach" in str(w.message)
    assert w.message.rotor_speed_rpm == pytest.approx(3.0 * 30 / math.pi) and w.message.wind_speed == 10.0


def test_the_note_starts_where_the_tip_passes_mach_half(nrel5mw):
    cfg = config_from_dict({"wind_speeds": [11.4], "model": {"type": "beam", "n_aero_sections": 12, "part": "rotor"},
                            "rotor_speed": {"min_rpm": 4, "max_rpm": 32, "n_points": 8},
                            "campbell": {"enabled": False}, "output": {"mode_shapes": False}})
    (point,) = plan_points(cfg)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = make_analyser(nrel5mw, cfg)(point)
    R = 63.0
    grid = np.asarray(r.sweep_rpm)
    above = grid[grid * math.pi / 30 * R >= MACH_LIMIT * SPEED_OF_SOUND]
    assert above.size, "the sweep must pass the limit for the test to mean something"
    note = re.search(r"Mach number exceeds[^\[]*\[from ([0-9.]+) RPM\]", r.reason)
    assert note and float(note.group(1)) == pytest.approx(above[0], abs=0.005), (r.reason, grid)
