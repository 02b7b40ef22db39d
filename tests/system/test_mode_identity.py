"""Mode identity (issue 32): every mode named by its participation in the turbine's own structural
modes and keeping its name along the operating curve (:mod:`windflutter.system.identity`).

Independent of the naming code: the criteria are those an engineer reads a Campbell diagram by
(``identity_checks``), the blade's own family counts come from its standstill modes, and a name's
frequency must be continuous along the wind speeds.  Before the identities, per-point names passed
322 of 414 checks on the IEA 22 MW (78 %: no 1st torsion at 9-25 m/s, "7th flap" below 4 Hz)."""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.api import campbell, load_turbine
from windflutter.system.operational import OperationalModel

from identity_checks import blade_counts_below, identity_checks


def _check(name: str, winds, limit_hz: float, share: float):
    res = campbell(name, [float(v) for v in winds], max_hz=limit_hz + 0.8)
    ref = OperationalModel(load_turbine(name)).reference()
    ok, n, missing, jumps, impossible = identity_checks(res, blade_counts_below(ref, limit_hz), limit_hz)
    report = "\n".join([f"{ok}/{n}", *missing, *jumps, *impossible])
    assert ok >= share * n and not impossible, report
    for p in res.points:  # a name once per point
        names = [m.identity for m in p.modes if m.identity is not None]
        assert len(names) == len(set(names)), p.wind_speed
    return res, ok, n


def test_nrel5mw_every_family_named_and_continuous_along_the_curve():
    """NREL 5 MW whole turbine, 3-25 m/s every 2 m/s: every family present at every wind speed, no
    jump, no impossible ordinal below 5.5 Hz (measured 216/216 at 12 wind speeds; 414/414 at 23)."""
    _check("nrel5mw", np.arange(3.0, 25.1, 2.0), 5.5, 1.0)


@pytest.mark.slow
@pytest.mark.parametrize("name,share", [("iea22mw", 1.0), ("iea15mw", 0.95), ("nrel5mw", 1.0)])
def test_whole_turbines_every_family_named_3_to_25(name, share):
    """The three whole turbines at every wind speed 3-25 m/s, below 4.3 Hz.  Measured: IEA 22 MW
    414/414, NREL 5 MW 414/414, IEA 15 MW 406/414 -- the 1st torsion BW/FW/collective at 24-25 m/s
    and the 2nd edge BW at 25 m/s, where these modes mix with the 3rd edge and 3rd flap (named as
    mixed); required 95 % there, as the project's shared checker."""
    _check(name, np.arange(3.0, 25.1, 1.0), 4.3, share)
