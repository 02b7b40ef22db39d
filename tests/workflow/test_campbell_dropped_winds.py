"""The run's operating-point Campbell says which asked wind speeds it leaves out (issue 34 item 6)."""

import pytest

from windflutter.analysers import operating_campbell
from windflutter.api import analysis_config, load_turbine
from windflutter.errors import InputError, InputWarning


def test_campbell_names_the_wind_speeds_outside_the_operating_curve():
    tb = load_turbine("nrel5mw")
    cfg = analysis_config(wind_speeds=[8.0, 30.0], **{"model.n_aero_sections": 8, "campbell.max_hz": 1.5})
    with pytest.warns(InputWarning, match=r"wind speeds 30 m/s left out"):
        res = operating_campbell(tb, cfg)
    assert [p.wind_speed for p in res.points] == [8.0]


def test_campbell_without_an_operating_curve_names_the_supplement_key():
    from dataclasses import replace

    from windflutter.operating import operating_campbell as service

    tb = replace(load_turbine("nrel5mw"), operating_curve=None)
    with pytest.raises(InputError, match="windflutter.operating_curve"):
        service(tb, analysis_config())
