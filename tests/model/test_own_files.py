"""A user's own turbine files run, or say exactly what is missing (issue 34).

* hub and nacelle masses the files do not give: ``DEFAULT_MASS_PER_D3 x rotor_diameter^3`` with one
  warning each naming the assumption; the constants are the geometric means of the bundled
  reference turbines (checked here against those turbines, so the stated factor stays true);
* no blade structural damping in the files: one warning;
* an OpenFAST deck without its supplement: method p refuses it in one line naming the supplement
  key ``windflutter.operating_curve`` and the file it goes in.
"""

from __future__ import annotations

import math
import shutil
import warnings
from pathlib import Path

import pytest

from windflutter.model import load_turbine
from windflutter.model.consistency import DEFAULT_MASS_PER_D3

DATA = Path(__file__).resolve().parents[2] / "src" / "windflutter" / "data"


def test_default_masses_are_the_reference_turbines_geometric_means():
    ratios = {"hub": [], "nacelle": []}
    for name in ("nrel5mw", "iea10mw", "iea15mw", "iea22mw"):
        t = load_turbine(name)
        D3 = t.rotor_diameter ** 3
        ratios["hub"].append(t.hub.mass / D3)
        ratios["nacelle"].append(t.nacelle.mass / D3)
    for part, factor in (("hub", 3.1), ("nacelle", 2.0)):
        g = math.exp(sum(math.log(r) for r in ratios[part]) / len(ratios[part]))
        assert DEFAULT_MASS_PER_D3[part] == pytest.approx(g, rel=0.01)  # rounded to 2 digits
        assert max(max(r / g, g / r) for r in ratios[part]) <= factor


@pytest.fixture(scope="module")
def raw_iea10(tmp_path_factory):
    f = tmp_path_factory.mktemp("raw") / "IEA-10-198-RWT.yaml"
    shutil.copy(DATA / "turbines" / "IEA-10-198-RWT.yaml", f)
    with pytest.warns(Warning) as caught:
        t = load_turbine(f, validate=False)
    return t, [str(w.message) for w in caught]


def test_missing_masses_assumed_with_one_warning_each(raw_iea10):
    t, warned = raw_iea10
    for part, body in (("hub", t.hub), ("nacelle", t.nacelle)):
        assert body.mass == pytest.approx(DEFAULT_MASS_PER_D3[part] * t.rotor_diameter ** 3, rel=1e-12)
        hits = [w for w in warned if f"{part}.mass: not in the files" in w]
        assert len(hits) == 1 and "assumed" in hits[0] and "rotor_diameter^3" in hits[0], warned
    assert "hub.mass" not in t.missing and "nacelle.mass" not in t.missing
    t.require("turbine", aerodynamics=True)  # nothing refused


def test_zero_structural_damping_warns_once(raw_iea10):
    t, warned = raw_iea10
    hits = [w for w in warned if "blade structural damping: zero" in w]
    assert len(hits) == 1 and "structural_damping.mu" in hits[0]
    assert any("blade structural damping" in w for w in t.warnings)


def test_bundled_damped_turbine_gives_no_damping_warning():
    for name in ("nrel5mw", "iea15mw"):
        assert not [w for w in load_turbine(name).warnings if "structural damping" in w]


def test_deck_without_supplement_names_the_key(tmp_path, capsys):
    from windflutter.cli import main

    for f in (DATA / "nrel5mw").iterdir():
        if f.is_file() and not f.name.endswith(".windflutter.yaml"):
            shutil.copy(f, tmp_path / f.name)
    shutil.copytree(DATA / "nrel5mw" / "Airfoils", tmp_path / "Airfoils")
    rc = main(["stability", str(tmp_path / "NREL-5MW_Onshore.fst"), "--wind-speeds", "10"])
    err = [ln for ln in capsys.readouterr().err.splitlines() if "error" in ln]
    assert rc == 2 and len(err) == 1, err
    assert "windflutter.operating_curve" in err[0] and "NREL-5MW_Onshore.windflutter.yaml" in err[0]


def test_wind_speed_outside_the_operating_curve_warns():
    """Above cut-out (or below cut-in) the curve's end point is used, and said so once per point."""
    import numpy as np

    from windflutter.errors import ValidityWarning
    from windflutter.model.turbine import OperatingCurve
    from windflutter.frozen.turbine import TurbineStability

    oc = OperatingCurve(wind_speed=np.array([3.0, 11.4, 25.0]), rotor_speed=np.array([0.72, 1.27, 1.27]),
                        pitch=np.radians([0.0, 0.0, 23.0]), source="test table")
    with pytest.warns(ValidityWarning, match=r"V = 30 m/s is outside the operating curve \(3-25 m/s, test table\).*"
                      r"25 m/s \(12.13 RPM, 23.00 deg\)"):
        oc.warn_outside(30.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        oc.warn_outside(25.0)
        oc.warn_outside(3.0)

    class Stub:
        operating_curve = oc

    ts = TurbineStability.__new__(TurbineStability)
    ts.turbine = Stub()
    with pytest.warns(ValidityWarning, match="V = 2 m/s is outside"):
        assert ts.pitch_at(2.0) == 0.0


def test_rated_rotor_speed_is_the_operating_curves_where_the_file_s_is_not_reached(tmp_path):
    """One rated rotor speed per turbine: the IEA 22 MW's windIO control gives 7.162 RPM (its overview
    table's "Maximum rotor speed"), the HAWCStab2 operating curve of its supplement runs at 7.0611 RPM above
    rated (the last row of ``iea_22mw_rwt_hawc2.opt``, read here with numpy): the analyses run at the
    curve's, so the margins to rated and overspeed refer to it, and a note says why.  An explicit
    ``rated_rotor_speed_rpm`` in the supplement is kept; a file and curve that agree (IEA 15 MW, 7.56 and
    7.559987 RPM) keep the file's."""
    import numpy as np

    from windflutter.units import RPM

    opt = np.loadtxt(DATA / "iea22mw" / "iea_22mw_rwt_hawc2.opt", skiprows=1)
    t = load_turbine("iea22mw")
    assert t.rated_rotor_speed / RPM == pytest.approx(opt[:, 2].max(), rel=1e-12)
    assert any("7.162 RPM is not reached" in n for n in t.notes)
    assert load_turbine("iea15mw").rated_rotor_speed / RPM == 7.56
    src = DATA / "turbines"
    shutil.copy(src / "IEA-22-280-RWT.yaml", tmp_path)
    supp = (src / "IEA-22-280-RWT.windflutter.yaml").read_text()
    supp = supp.replace("../iea22mw/iea_22mw_rwt_hawc2.opt", str(DATA / "iea22mw" / "iea_22mw_rwt_hawc2.opt"))
    (tmp_path / "IEA-22-280-RWT.windflutter.yaml").write_text(supp.replace("windflutter:\n", "windflutter:\n  rated_rotor_speed_rpm: 7.162\n", 1))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert load_turbine(str(tmp_path / "IEA-22-280-RWT.yaml")).rated_rotor_speed / RPM == pytest.approx(7.162)
