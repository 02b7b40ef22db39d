"""The seed's rotor simple model (thesis ch. 4.1.8)."""

import math
from importlib import resources

import numpy as np
import pytest

from windflutter.section import divergence_speed, pk_eigen, natural_frequencies
from windflutter.frozen.simple_model import (
    RPM,
    first_unstable,
    inflow,
    load_simple_models,
    run_simple_model,
    section_at,
)


@pytest.fixture(scope="module")
def models():
    return load_simple_models()


def test_data_matches_thesis_table(models):
    # Castillo Capponi (2010), table of sec. 4.1.8
    m5, m20 = models["nrel5mw"], models["seed20mw"]
    assert (m5.chord, m5.mass, m5.inertia, m5.plunge_stiffness, m5.pitch_stiffness, m5.radius) == (
        2.7, 138.9, 27.7, 2.7e3, 3.5e5, 47.7)
    assert (m20.chord, m20.mass, m20.inertia, m20.plunge_stiffness, m20.pitch_stiffness,
            m20.radius) == (8.0, 709.8, 149.8, 8.5e3, 2.4e6, 109.5)
    assert (m5.frozen_frequency_hz, m20.frozen_frequency_hz) == (0.20, 0.11)
    # NREL 5 MW control curve: fine pitch below rated, 23.01 deg at 25 m/s (OpenFAST steady state)
    assert m5.pitch(8.0) == 0.0
    assert math.degrees(m5.pitch(25.0)) == pytest.approx(23.0136)


def test_inflow_geometry():
    U, phi = inflow(10.0, 1.0, 47.7)
    assert U == pytest.approx(math.sqrt(100 + 47.7**2))
    assert phi == pytest.approx(math.atan(10 / 47.7))
    assert inflow(0.0, 2.0, 10.0) == (20.0, 0.0)


def test_section_at_rotor_point(models):
    rs = models["nrel5mw"]
    om = 30 * RPM
    sec, U = section_at(rs, 20.0, om)
    assert sec.semi_chord == 1.35
    assert U == pytest.approx(math.hypot(20.0, om * 47.7))
    expect = math.atan2(20.0, om * 47.7) - math.radians(2.503) - rs.pitch(20.0)
    assert sec.plunge_angle == pytest.approx(expect)


def test_onset_is_a_neutral_point(models):
    rs = models["nrel5mw"]
    pt = first_unstable(rs, 10.0, frozen_k=True)
    assert pt.kind == "flutter"
    om = pt.flutter_rpm * RPM
    # the reported k is the frozen one: 2 pi f b / U
    sec, U = section_at(rs, 10.0, om)
    assert pt.reduced_frequency == pytest.approx(2 * math.pi * 0.20 * 1.35 / U, rel=1e-9)
    # independent check: follow the flutter mode on a fine rotor-speed grid (0.01 RPM) and find
    # where its real part changes sign
    w_frozen = 2 * math.pi * 0.20
    rpms = np.arange(pt.flutter_rpm - 0.5, pt.flutter_rpm + 0.5, 0.01)
    lam = 1j * pt.flutter_frequency
    sig = []
    for r in rpms:
        s, u = section_at(rs, 10.0, r * RPM)
        lam, _, _ = pk_eigen(s, u, lam, frozen_omega=w_frozen)
        sig.append(lam.real)
    sig = np.array(sig)
    i = np.where((sig[:-1] < 0) & (sig[1:] >= 0))[0][0]
    # the root lies within the 0.01 RPM grid cell found by the scan
    assert rpms[i] - 1e-9 <= pt.flutter_rpm <= rpms[i + 1] + 1e-9


def test_pk_onset_uses_matched_k_and_divergence(models):
    rs = models["nrel5mw"]
    pt = first_unstable(rs, 10.0, frozen_k=False)
    sec, U = section_at(rs, 10.0, 10 * RPM)
    ud = divergence_speed(sec)
    assert pt.divergence_rpm == pytest.approx(math.sqrt(ud**2 - 100.0) / 47.7 / RPM, rel=1e-12)
    assert pt.first_unstable_rpm <= pt.divergence_rpm
    if pt.kind == "flutter":  # k must then be the mode's own reduced frequency
        s, u = section_at(rs, 10.0, pt.flutter_rpm * RPM)
        assert pt.reduced_frequency == pytest.approx(pt.flutter_frequency * 1.35 / u, rel=1e-6)


def test_weak_wind_speed_dependence(models):
    # Omega r >> V, and pitch only enters through cos(plunge angle): the onset barely moves
    # with wind speed (the thesis's 5 MW curve spans 36.4-36.6 RPM for the same reason)
    for name in ("nrel5mw", "seed20mw"):
        res = run_simple_model(models[name], np.array([4.0, 12.0, 25.0]), frozen_k=True)
        r = res.first_unstable_rpm
        assert np.all(np.isfinite(r))
        assert (r.max() - r.min()) / r.mean() < 0.03


def test_zero_plunge_angle_limit(models):
    # with the plunge-lift angle set to zero the rotor section is a plain typical section at U
    rs = models["seed20mw"]
    sec, U = section_at(rs, 10.0, 20 * RPM, with_angle=False)
    w = natural_frequencies(sec)
    assert sec.plunge_angle == 0.0 and w[0] == pytest.approx(math.sqrt(8.5e3 / 709.8))


def test_bad_simple_model_file_is_named(tmp_path):
    from windflutter.errors import InputError

    good = (resources.files("windflutter") / "data" / "seed_simple_model" / "simple_model.yaml").read_text()
    path = tmp_path / "m.yaml"
    path.write_text(good.replace("    chord: 2.7 ", "    chrd: 2.7 "))
    with pytest.raises(InputError, match=r"turbines\.nrel5mw\.chord"):
        load_simple_models(str(path))
    path.write_text(good.replace("mass: 138.9", "mass: heavy"))
    with pytest.raises(InputError, match=r"turbines\.nrel5mw\.mass"):
        load_simple_models(str(path))
    path.write_text("turbines: [1, 2\n")
    with pytest.raises(InputError, match="YAML"):
        load_simple_models(str(path))
    with pytest.raises(InputError, match="path"):
        load_simple_models(str(tmp_path / "missing.yaml"))
