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


def test_two_notes_and_a_stop_keep_both_rotor_speeds_for_the_summary():
    """The NREL 5 MW beam map (`make run`) at 4 m/s carries two validity notes (the Mach number, the BEM's
    propeller-brake state), at 22 m/s a note and the steady state's stop; a cut at 500 characters took the
    second note's "[from X RPM]", and the run's summary line of that kind was lost.  The notes are kept whole
    and the command's summary (cli.warn.gather_notes) prints both kinds, with their rotor speeds."""
    import io

    from windflutter.analysers import MAX_REASON, point_reason
    from windflutter.cli import warn

    mach = ("at V = 4.0 m/s the blade's relative Mach number exceeds 0.5 at high rotor speed: the incompressible strips "
            "(Theodorsen, low-Mach polars) underestimate the lift slope there by more than 15 % (Prandtl-Glauert); "
            "onsets in that range are indicative [from 27.00 RPM]")
    momentum = ("at V = 4.0 m/s the BEM induction leaves momentum theory at high rotor speed (axial induction reaches 1 or "
                "tangential induction falls below -0.1: the propeller-brake state); onsets in that range depend on the "
                "induction model (compare with solver.induction: false) [from 14.00 RPM]")
    assert len(f"{mach}; {momentum}") > 500  # the former cut fell inside the second note
    stop = "the steady state at V = 4 m/s did not converge in 60 iterations; " * 40 + "[from 34.00 RPM]"
    reason = point_reason([mach, momentum], stop)
    assert len(reason) <= MAX_REASON and reason.startswith(f"{mach}; {momentum}; the steady state")
    out = io.StringIO()
    with warn.one_line_warnings("test", stream=out):
        warn.gather_notes([reason])
    lines = out.getvalue().splitlines()
    assert len(lines) == 2
    assert any("Mach number" in s and "4 m/s from 27.0 RPM" in s for s in lines)
    assert any("momentum theory" in s and "4 m/s from 14.0 RPM" in s for s in lines)
