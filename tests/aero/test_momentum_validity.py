"""The BEM induction says when it leaves momentum theory (aero/induction.py, MOMENTUM_LIMITS).

Reference: momentum theory with Buhl's turbulent-wake relation holds up to an axial induction of 1
(C_T = 2); a strip with tangential induction well below zero drives the flow (propeller).  The NREL
5 MW at fixed pitch 0 at 4 m/s: at its operating 7 RPM (tip-speed ratio 11.5) the induction is inside
(a <= 0.66), at 16 RPM (tip-speed ratio 26) the rotor is in the propeller-brake state (power
coefficient -0.8, a at the limit, a' down to -0.3).  At the NREL 5 MW's first overspeed crossing of
the default analysis (8 m/s, 16.35 RPM, tip-speed ratio 13.5) it is still inside (a <= 0.77)."""

import warnings

import numpy as np
import pytest

from windflutter.aero.induction import sections_induction
from windflutter.errors import ValidityWarning
from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.turbine import build_model, rotor_geometry


@pytest.fixture(scope="module")
def blade(nrel5mw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, sec = build_model(nrel5mw, MeshSettings(model="beam", part="rotor_blade", n_span=20))
    return sec, rotor_geometry(nrel5mw)


@pytest.mark.parametrize("wind, rpm, outside", [(4.0, 7.0, False), (8.0, 16.35, False), (11.4, 12.1, False),
                                                (25.0, 12.1, False), (4.0, 16.0, True), (4.0, 40.0, True)])
def test_propeller_brake_state_is_reported(blade, wind, rpm, outside):
    sec, geom = blade
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        res = sections_induction(sec, geom, wind, rpm * np.pi / 30, n_blades=3)
    hits = [w for w in got if issubclass(w.category, ValidityWarning)]
    assert bool(hits) == outside, [str(w.message) for w in hits]
    if outside:
        assert f"V = {wind:.1f} m/s" in str(hits[0].message) and "solver.induction" in str(hits[0].message)
        assert res.cp < 0  # the rotor takes power: the propeller-brake state, not a turbine
    else:
        assert res.cp > 0


def test_a_drag_only_root_strip_is_not_the_propeller_state(nrel5mw):
    """The shell model's strips follow its elements (100 on the NREL 5 MW), the innermost on the root
    cylinder (cl = 0, cd ~ 0.5), where the drag swirls the flow against the rotation: a' ~ -0.19 at the
    operating point, 10-25 m/s.  That is not the propeller-brake state: no warning at the operating
    point; the propeller state at fixed pitch far above it is still reported on the same strips."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, sec = build_model(nrel5mw, MeshSettings(model="beam", part="rotor_blade", n_span=100))
    geom = rotor_geometry(nrel5mw)
    for wind, rpm, outside in [(11.4, 12.1, False), (4.0, 16.0, True)]:
        with warnings.catch_warnings(record=True) as got:
            warnings.simplefilter("always")
            res = sections_induction(sec, geom, wind, rpm * np.pi / 30, n_blades=3)
        hits = [w for w in got if issubclass(w.category, ValidityWarning)]
        assert bool(hits) == outside, (wind, rpm, [str(w.message) for w in hits])
        if not outside:  # the case: a drag-only strip beyond the tangential limit
            drag = res.converged & (np.abs(res.cl) < res.cd)
            assert np.any(res.ap[drag] < -0.1), (res.ap[drag], res.cl[drag])
