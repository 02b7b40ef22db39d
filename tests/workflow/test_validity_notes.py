"""A point whose sweep leaves the aerodynamic model's range keeps the note (its ``reason``, shown
beside ``ok`` in the report): the NREL 5 MW rotor at 4 m/s and fixed pitch, the seed's p-k sweep
to 40 RPM, passes the propeller-brake state of the BEM (a = 1 above about 12 RPM:
tests/aero/test_momentum_validity.py); at 11.4 m/s it stays inside up to 40 RPM."""

import warnings

from windflutter.config import config_from_dict
from windflutter.errors import ValidityWarning
from windflutter.workflow import make_analyser, plan_points


def test_validity_note_is_kept_with_the_point(nrel5mw):
    cfg = config_from_dict({"wind_speeds": [4.0, 11.4], "method": ["pk"], "aero": ["potential"],
                            "model": {"type": "beam", "n_aero_sections": 12, "part": "rotor"},
                            "rotor_speed": {"min_rpm": 4, "max_rpm": 40, "n_points": 10},
                            "campbell": {"enabled": False}, "output": {"mode_shapes": False}})
    analyse = make_analyser(nrel5mw, cfg)
    low, rated = plan_points(cfg)
    with warnings.catch_warnings(record=True) as shown:
        warnings.simplefilter("default")
        r_low = analyse(low)
        r_rated = analyse(rated)
    assert r_low.status == "ok" and "V = 4.0 m/s" in r_low.reason and "momentum theory" in r_low.reason
    # with the lowest rotor speed of the sweep where it was found: above the operating 7.1 RPM
    # (inside the range there), at or below the sweep's end
    import re

    rpm = float(re.search(r"\[from ([0-9.]+) RPM\]", r_low.reason).group(1))
    assert r_low.sweep_rpm[0] < rpm <= r_low.sweep_rpm[-1] + 1e-9
    assert r_rated.reason == ""
    # still shown to the user, once for the point
    assert sum(issubclass(w.category, ValidityWarning) for w in shown) == 1
