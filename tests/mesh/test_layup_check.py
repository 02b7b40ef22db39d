"""Layup vs file 6x6 check (mesh/layup_check.py): is the shell model's blade the beam model's blade?

References: analytic thin-walled box (principal EI about the centroid), the files' own 6x6 tables
(computed upstream by other cross-section codes from the same layup for the IEA turbines; the
Jonkman 2009 blade for the WISDEM NREL 5 MW, whose layup is a different, carbon-capped blade).
"""

from __future__ import annotations

import dataclasses
import functools
import json
import warnings

import numpy as np
import pytest

from windflutter.errors import InputWarning
from windflutter.mesh.layup_check import (
    MASS_TOLERANCE,
    STIFFNESS_TOLERANCE,
    check_layup_against_6x6,
    main,
    principal_bending,
    span_weights,
    weighted_median,
)
from windflutter.model.section import thin_wall_properties

E, G, RHO = 7.0e10, 2.7e10, 2700.0


@functools.lru_cache(maxsize=None)
def _load(name: str):
    from windflutter.model.windio import load_turbine

    return load_turbine(name)


def _box(b, h, m):
    """Closed rectangular midline b (chordwise z) x h (flapwise y), m segments a side, from the
    trailing-edge upper corner round the suction side first (first point repeated at the end)."""
    corners = np.array([[h / 2, b / 2], [h / 2, -b / 2], [-h / 2, -b / 2], [-h / 2, b / 2], [h / 2, b / 2]])
    u = np.linspace(0.0, 1.0, m + 1)[:-1]
    sides = [c0 + u[:, None] * (c1 - c0) for c0, c1 in zip(corners[:-1], corners[1:])]
    return np.vstack(sides + [corners[-1:]])


def test_principal_bending_is_independent_of_reference_point_and_frame():
    """Thin box b x h, wall t: I_flap = t h^2 b / 2 + t h^3 / 6, I_edge = t b^2 h / 2 + t b^3 / 6
    (about the centroid).  The same box shifted 0.4 m / 0.1 m off the reference axis and turned
    by 17 deg gives coupled 6x6 tables whose condensed principal values are the analytic ones to
    1e-9 (exact integrals on a straight-sided midline); the raw K55 of the shifted box differs by
    the parallel-axis term, so the condensation is what makes a diagonal elastic-axis table and a
    coupled pitch-axis table comparable."""
    b, h, t, m = 2.0, 0.6, 0.01, 16
    poly = _box(b, h, m)
    ang = np.radians(17.0)
    R = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
    moved = poly @ R.T + [0.1, 0.4]
    ns = poly.shape[0] - 1
    args = (np.full(ns, E * t), np.full(ns, G * t), np.full(ns, RHO * t))
    K0, _ = thin_wall_properties(poly, *args)
    K1, _ = thin_wall_properties(moved, *args)
    i_flap, i_edge = t * h**2 * b / 2 + t * h**3 / 6, t * b**2 * h / 2 + t * b**3 / 6
    for K in (K0, K1):
        lo, hi = principal_bending(K[None])
        assert lo[0] == pytest.approx(E * i_flap, rel=1e-9)
        assert hi[0] == pytest.approx(E * i_edge, rel=1e-9)
    assert abs(K1[5, 5] / K0[5, 5] - 1) > 0.1  # the uncondensed value would not compare


def test_weighted_median_and_span_weights():
    w = span_weights(np.array([0.0, 0.1, 0.2, 1.0]))
    np.testing.assert_allclose(w, [0.05, 0.1, 0.45, 0.4])
    # the station at 0.2 carries 45 %: with 0.05 + 0.1 below it the median is its value
    assert weighted_median(np.array([5.0, 1.0, 2.0, 9.0]), w) == 2.0
    assert weighted_median(np.array([1.0, 2.0]), np.array([1.0, 1.0])) == 1.5  # exact tie
    assert weighted_median(np.array([np.nan, 3.0]), np.array([1.0, 1.0])) == 3.0
    assert np.isnan(weighted_median(np.array([np.nan]), np.array([1.0])))


def test_nrel5mw_layup_is_another_blade(nrel5mw):
    """The WISDEM NREL 5 MW layup (carbon caps) against its Jonkman 2009 (BeamDyn) 6x6: flap EI
    +76 % and GJ +52 % (span medians; measured), mass -11 % and edge EI +8 % within tolerance.
    Independent evidence that these medians describe the blade: beam models of the two property
    sets give flap 1 0.888 vs 0.668 Hz (ratio 1.33; the medians predict sqrt(1.76 / 0.89) = 1.40)
    and torsion 1 7.00 vs 5.46 Hz (1.28; predicted 1.31), docs/mesh.md."""
    res = check_layup_against_6x6(nrel5mw)
    assert res.applicable and res.disagrees
    assert res.s.size == 49 and res.radius[-1] == pytest.approx(61.5, rel=1e-3)
    assert {q.name for q in res.disagreeing} == {"EI_flap", "GJ"}
    assert res.quantity("EI_flap").median > 0.5 and res.quantity("GJ").median > 0.3
    assert abs(res.quantity("mass").median) < MASS_TOLERANCE
    msg = res.warning
    assert "\n" not in msg and "flap EI +" in msg and "GJ +" in msg and "NREL-5MW.yaml" in msg
    table = res.table().splitlines()
    assert len(table) == 2 + 49 + 1 and "*" in table[20]
    assert res.store_attributes()["layup_vs_6x6"] == msg


@pytest.mark.parametrize("name", ["iea15mw", pytest.param("iea22mw", marks=pytest.mark.slow), "iea10mw"])
def test_iea_layups_are_their_blades(name):
    """IEA 15 / 22 / 10 MW: each file's 6x6 was computed upstream from its own layup, so the check
    must not warn.  Measured span medians (mass, flap EI, edge EI, GJ): IEA 15 +2/+5/0/-6 %,
    IEA 22 +1/0/+2/-3 %, IEA 10 -1/-6/-2/+21 %.  IEA 10 MW's GJ is beyond 25 % at 16 of its 30
    stations (-27..-33 % at 17-21 % span, +27..+60 % at 45-90 %) -- reported in docs/verification.md, under the blade-level tolerance.
    IEA 22 MW is *slow* (its 0.7 MB file takes 5 s to read)."""
    res = check_layup_against_6x6(_load(name))
    assert res.applicable and not res.disagrees and res.warning is None
    for q in res.quantities:
        if q.tolerance is not None:
            assert abs(q.median) < (0.22 if q.name == "GJ" else 0.08), (name, q.summary())
    assert "agree" in res.store_attributes()["layup_vs_6x6"]


def test_check_can_fail_on_a_scaled_table():
    """IEA 15 MW with its 6x6 stiffness scaled by 0.7 (layup/file +43 %) is flagged on every
    judged stiffness and not on mass; scaled by 0.9 (+11 %) it passes; the mass table x 1.3 is
    flagged on mass alone."""
    t = _load("iea15mw")
    bp = t.blade.beam

    def scaled(k=1.0, m=1.0):
        nb = dataclasses.replace(bp, stiffness=bp.stiffness * k, mass=bp.mass * m)
        return check_layup_against_6x6(dataclasses.replace(t, blade=dataclasses.replace(t.blade, beam=nb)))

    soft = scaled(k=0.7)
    assert {q.name for q in soft.disagreeing} == {"EI_flap", "EI_edge", "GJ"}
    assert soft.quantity("EI_flap").median > STIFFNESS_TOLERANCE
    assert not scaled(k=0.9).disagrees
    assert {q.name for q in scaled(m=1.3).disagreeing} == {"mass"}


def test_seed_turbines_and_build_model_warning(nrel5mw):
    """seed5mw / seed20mw have only their layup (the blade is the layup): nothing to compare, no
    warning.  build_model emits the NREL 5 MW warning once for its shell blade (not for a second
    shell build of the same blade, nor for a copy of the turbine, nor for the beam model)."""
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model

    st = MeshSettings(model="shell", part="blade", n_chord=12, n_span=4)
    for name in ("seed5mw", "seed20mw"):
        t = _load(name)
        res = check_layup_against_6x6(t)
        assert not res.applicable and res.warning is None and "no 6x6" in res.reason
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            build_model(t, st)
        assert not [x for x in w if issubclass(x.category, InputWarning)]
    # a fresh blade object: the session's nrel5mw blade may have been warned about already
    t = dataclasses.replace(nrel5mw, name="NREL 5MW (copy for the warning test)",
                            blade=dataclasses.replace(nrel5mw.blade))
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        build_model(t, dataclasses.replace(st, model="beam"))
        build_model(t, st)
        build_model(t, st)
        build_model(dataclasses.replace(t, hub_height=91.0), st)
    hits = [str(x.message) for x in w if issubclass(x.category, InputWarning) and "6x6" in str(x.message)]
    assert len(hits) == 1 and "copy for the warning test" in hits[0]


def test_command_line_table_and_json(capsys):
    assert main(["seed5mw"]) == 0
    assert "not compared" in capsys.readouterr().out
    assert main(["seed20mw", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert not d["applicable"] and d["warning"] is None and d["quantities"] == {}
    d = check_layup_against_6x6(_load("iea15mw")).to_dict()
    json.dumps(d)  # plain Python
    assert d["applicable"] and not d["disagrees"] and len(d["quantities"]["GJ"]["relative"]) == len(d["s"])
