"""Issue 15's bar: no false alarm in operation on the IEA 15 MW and IEA 22 MW (slow, ~4 min).

Reference: HAWCStab2 and OpenFAST linearizations of both turbines find every mode damped along the
operating curve (the IEA 15 MW's HAWCStab2 Campbell is in ``tests/data/iea15mw_hawcstab2``).  With the
defaults of ``windflutter stability`` (method p: the whole turbine in multi-blade coordinates, the
blades linearized about their deflected shape, the files' structural damping, Jones lag states), at 6
and 10 m/s the first instability of the overspeed search must lie at or above 1.2 x rated rotor
speed, and the overspeed instabilities must still be found below 2 x rated (a search that finds
nothing would pass the first check trivially).  The bar is the issue's, not a measured value; the
IEA 22 MW at 10 m/s meets it by a small margin (1.205 x, docs/notes/no_false_alarm.md).
"""

from __future__ import annotations

import pytest

import windflutter
from windflutter.units import RPM

CASES = [("iea15mw", 6.0), ("iea15mw", 10.0), ("iea22mw", 6.0), ("iea22mw", 10.0)]


@pytest.mark.slow
@pytest.mark.parametrize("name, wind", CASES)
def test_first_instability_above_1p2_rated(name, wind):
    tb = windflutter.load_turbine(name)
    rated = tb.operating_curve.rated_rotor_speed / RPM
    (p,) = windflutter.stability(tb, [wind])
    onsets = [r for r in (p.flutter_rpm, p.divergence_rpm) if r is not None]
    assert onsets, "no overspeed instability found up to the sweep's end"
    first = min(onsets)
    print(f"{name} {wind} m/s: first instability {first:.2f} RPM = {first / rated:.3f} x rated ({p.flutter_mode})")
    assert first >= 1.2 * rated
    assert first < 2.0 * rated
