"""The incompressible strips' range (aero/compressibility.py): a point whose sweep takes the blade's fastest
strip above Mach 0.5 keeps a note from the rotor speed where it happens; method p's search ends at the tips'
Mach 0.5 by default (``rotor_speed.max_tip_mach``, overspeed.py), checked against the strips' own speeds.

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
                            "rotor_speed": {"min_rpm": 4, "max_rpm": 32, "n_points": 8, "max_tip_mach": None},
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


def _solver(turbine, **rotor_speed):
    from windflutter.methods import stability_analysis

    cfg = config_from_dict({"model": {"type": "beam", "part": "rotor"}, "rotor_speed": rotor_speed})
    return stability_analysis(turbine, cfg, cfg.aero[0], cfg.method[0])


@pytest.mark.parametrize("wind", [4.0, 25.0])
def test_method_p_search_ends_before_the_strips_reach_mach_half(nrel5mw, wind):
    """Method p's default search ends where the tip's speed relative to the wind, ``sqrt((Omega R)^2 +
    V^2)``, reaches Mach 0.5 (``rotor_speed.max_tip_mach``): the strips' own relative speeds (the BEM's
    steady state, with induction, at the 30 strips' centres inside the tip) stay below Mach 0.5 there
    and pass it within 10 % above (measured: the fastest strip 4-6 % slower than ``Omega R``: its
    centre 1 m inside the tip, the tangential induction negative at overspeed).  Fails with a bound
    made on the diameter, without the wind or in the wrong unit."""
    ts = _solver(nrel5mw)
    grid = ts.grid(wind)
    top = math.sqrt((MACH_LIMIT * SPEED_OF_SOUND) ** 2 - wind**2) / 63.0 * 30 / math.pi
    assert grid[-1] == pytest.approx(top, abs=1e-9), grid
    steps = np.diff(grid)
    assert 1.0 <= steps[0] <= 3.0 and 1.0 <= steps[-1] <= 3.0 and np.allclose(steps[1:-1], 2.0), grid
    m = ts.model
    rb = m.blade(ts.pitch_at(wind))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        w = [float(np.max(m.steady(rb, wind, f * top * math.pi / 30).bem.W)) for f in (1.0, 1.1)]
    limit = MACH_LIMIT * SPEED_OF_SOUND
    assert w[0] < limit < w[1], (w, limit)


def test_without_the_bound_the_search_reaches_max_rpm(nrel5mw):
    grid = _solver(nrel5mw, max_rpm=30.0, n_points=15, max_tip_mach=None).grid(11.4)
    assert grid[-1] == pytest.approx(30.0) and np.allclose(np.diff(grid[1:]), 2.0), grid
    grid = _solver(nrel5mw, max_rpm=20.0).grid(11.4)  # max_rpm below the bound
    assert grid[-1] == pytest.approx(20.0), grid


@pytest.mark.parametrize("value, expected", [("none", None), ("0.6", 0.6)])
def test_max_tip_mach_flag_reaches_the_config(value, expected):
    from windflutter.cli import build_parser
    from windflutter.cli.stability import options_from_args
    from windflutter.methods import search_settings

    args = build_parser().parse_args(["stability", "nrel5mw", "--max-tip-mach", value])
    config, _ = options_from_args(args)
    assert config.rotor_speed.max_tip_mach == expected and search_settings(config).max_tip_mach == expected


def test_a_bad_max_tip_mach_names_the_flag():
    from windflutter.cli import build_parser
    from windflutter.cli.stability import options_from_args
    from windflutter.errors import InputError

    args = build_parser().parse_args(["stability", "nrel5mw", "--max-tip-mach", "0"])
    with pytest.raises(InputError) as e:
        options_from_args(args)
    assert e.value.field == "--max-tip-mach" and "0.05" in str(e.value), str(e.value)
