"""A point whose sweep leaves the aerodynamic model's range keeps the note (its ``reason``, shown
beside ``ok`` in the report): the NREL 5 MW at 4 m/s and fixed pitch passes the propeller-brake
state of the BEM above about 12 RPM (tests/aero/test_momentum_validity.py), at 11.4 m/s it stays
inside up to 20 RPM (a <= 0.6 there)."""

import warnings

from windflutter.config import config_from_dict
from windflutter.errors import ValidityWarning
from windflutter.workflow import make_analyser, plan_points


def test_validity_note_is_kept_with_the_point(nrel5mw):
    cfg = config_from_dict({"wind_speeds": [4.0, 11.4], "model": {"type": "beam", "n_aero_sections": 8, "part": "rotor"},
                            "rotor_speed": {"min_rpm": 4, "max_rpm": 20, "n_points": 5},
                            "campbell": {"enabled": False}, "output": {"mode_shapes": False}})
    analyse = make_analyser(nrel5mw, cfg)
    low, rated = plan_points(cfg)
    with warnings.catch_warnings(record=True) as shown:
        warnings.simplefilter("default")
        r_low = analyse(low)
        r_rated = analyse(rated)
    assert r_low.status == "ok" and "V = 4.0 m/s" in r_low.reason and "momentum theory" in r_low.reason
    assert r_rated.reason == ""
    # still shown to the user, once for the point
    assert sum(issubclass(w.category, ValidityWarning) for w in shown) == 1
