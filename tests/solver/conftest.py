"""Fixtures shared by the solver tests."""

import pytest

from windflutter.frozen.turbine import TurbineOptions, TurbineStability

#: The rotor-alone reference case: NREL 5 MW rotor (hub clamped), beam model with 8 elements and
#: strips per blade, 10 m/s, potential flow, rotor speeds 16-32 RPM in steps of 2. The same
#: settings as ``N_SPAN`` and ``GRID`` of test_turbine_whole.py, which compares whole-turbine
#: variants with it (checked there).
ROTOR_ALONE = dict(model="beam", mesh={"n_span": 8, "part": "rotor"}, min_rpm=16.0, max_rpm=32.0, rpm_step=2.0)


@pytest.fixture(scope="session")
def rotor_alone(nrel5mw):
    """Onsets of the rotor-alone reference case (one analysis for test_turbine.py and
    test_turbine_whole.py)."""
    return TurbineStability(nrel5mw, TurbineOptions(**ROTOR_ALONE)).analyse_operating_point(10.0)
