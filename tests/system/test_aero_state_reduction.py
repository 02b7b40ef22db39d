"""Each blade's aerodynamic lag states reduced by balanced truncation (``solver.aero_state_tol``).

References independent of the reduction's code: Glover's bound (Glover 1984, Int. J. Control 39(6)):
the truncated system's transfer function is within twice the sum of the dropped Hankel singular
values of the full one at every frequency -- evaluated here on a frequency grid from the full
state-space matrices; and the full-order model itself (``aero_state_tol: null``), whose modes and
static margin the reduced one must reproduce.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.overspeed import blade_static_margin
from windflutter.system.blade_aero import VELOCITY_WEIGHT, balanced_projection, reduced_blade_system
from windflutter.system.modes import point_modes
from windflutter.system.operational import OperationalModel, OperationalOptions

WIND, RPM = 10.0, 16.0  # NREL 5 MW above its operating 11.2 RPM: lightly damped edge modes (0.2-0.7 %)


def _model(turbine, tol):
    return OperationalModel(turbine, OperationalOptions(mesh={"n_span": 20}, structure="deflected",
                                                        aero_state_tol=tol))


@pytest.fixture(scope="module")
def points(nrel5mw_turbine):
    """The same NREL 5 MW beam point (20 strips, 40 lag states a blade) full order and reduced."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        full = _model(nrel5mw_turbine, None).at(WIND, rpm=RPM, pitch=0.0)
        red = _model(nrel5mw_turbine, 1e-7).at(WIND, rpm=RPM, pitch=0.0)
    return full, red


def _transfer(bs, w: float, static=None) -> np.ndarray:
    """``F (iw I - Az)^-1 [Bq, VELOCITY_WEIGHT Bv]`` (+ ``static`` on the displacement inputs)."""
    B = np.hstack([bs.Bq, VELOCITY_WEIGHT * bs.Bv])
    H = bs.F @ np.linalg.solve(1j * w * np.eye(bs.Az.shape[0]) - bs.Az, B)
    if static is not None:
        H[:, :bs.Bq.shape[1]] -= static
    return H


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_truncation_error_within_glovers_bound(points, tol):
    """At 0.001-1000 rad/s the reduced blade's aerodynamic transfer function, with the static part
    added to the stiffness taken back out, is within Glover's bound of the full one (2 x the dropped
    Hankel values; the static correction at most doubles it: 4 x), and its static value is the full
    one's to round-off.  A wrong left/right pairing or scaling of the projection fails both."""
    bs = points[0].blade_system
    proj = balanced_projection(bs, tol)
    red = reduced_blade_system(bs, proj)
    assert 0 < proj.n_states < bs.n_states
    dropped = 2.0 * proj.hsv[proj.n_states:].sum()
    static = red.K - bs.K  # the dropped states' static part, added to the stiffness
    for w in np.logspace(-3, 3, 61):
        err = np.linalg.norm(_transfer(bs, w) - _transfer(red, w, static), 2)
        assert err <= 2.0 * dropped * (1 + 1e-9) + 1e-12 * np.abs(_transfer(bs, w)).max(), (w, err, dropped)
    # static aerodynamic stiffness -F Az^-1 Bq of the full subsystem, to round-off
    K0 = bs.K + bs.F @ np.linalg.solve(bs.Az, bs.Bq)
    K1 = red.K + red.F @ np.linalg.solve(red.Az, red.Bq)
    assert np.abs(K1 - K0).max() <= 1e-10 * np.abs(K0).max()


def test_reduced_point_has_the_full_order_modes_and_margin(points):
    """The default cut-off (1e-7) on a 20-strip beam blade (18 of 40 states kept): the same names to
    2.5 Hz; the modes below 10 % damping at the same frequency (1e-5) and damping ratio (1e-4 points;
    measured 1e-6 and 2.4e-5 points), the heavily damped flap modes (18-91 %) within 1e-3 and 0.01
    points (measured 2.2e-4 and 6.8e-3 points on the 77-91 % ones, whose frequency is ill-conditioned);
    the blade's static margin (the divergence search's) to 1e-9.  On the NREL 5 MW shell at 10 m/s,
    19.4 RPM (40 of 200 states) the modes below 5 % damping agree to 1e-5 points."""
    full, red = points
    assert red.blade_system.n_states < full.blade_system.n_states
    assert red.aero_projection is not None and full.aero_projection is None
    mf, mr = (point_modes(p, max_hz=2.5) for p in (full, red))
    assert [m.name for m in mr] == [m.name for m in mf] and len(mf) >= 10
    light = [a.damping_ratio < 0.1 for a in mf]
    assert sum(light) >= 5 and not all(light)
    for a, b, lt in zip(mf, mr, light):
        assert b.frequency_hz == pytest.approx(a.frequency_hz, rel=1e-5 if lt else 1e-3), a.name
        assert abs(b.damping_ratio - a.damping_ratio) < (1e-6 if lt else 1e-4), (a.name, a.damping_ratio, b.damping_ratio)
    assert blade_static_margin(red) == pytest.approx(blade_static_margin(full), rel=1e-9)


def test_a_changed_point_reuses_the_points_projection(points, nrel5mw_turbine):
    """Design sensitivities difference two points in the same coordinates: ``assemble_point`` with the
    point's own projection (and basis) gives back its multi-blade system."""
    red = points[1]
    om = _model(nrel5mw_turbine, 1e-7)
    again = om.assemble_point(red.blade, red.steady, red.ksigma, red.klink, WIND, red.omega, red.pitch,
                              Phi=red.Phi, aero_projection=red.aero_projection)
    for k in ("M", "C", "K", "F", "A", "Bq", "Bv"):
        a, b = getattr(red.mbc, k), getattr(again.mbc, k)
        assert a.shape == b.shape and np.allclose(a, b, rtol=0, atol=1e-12 * max(np.abs(a).max(), 1)), k


def test_the_cut_off_is_checked_and_reaches_the_model():
    from windflutter import analysis_config
    from windflutter.methods import operational_options

    cfg = analysis_config()
    assert cfg.solver.aero_state_tol == 1e-7
    assert operational_options(cfg, "viscous").aero_state_tol == 1e-7
    off = analysis_config(solver={"aero_state_tol": None})
    assert operational_options(off, "viscous").aero_state_tol is None
    for bad in (0.0, 1.0, float("nan")):
        with pytest.raises(InputError, match="aero_state_tol"):
            OperationalOptions(aero_state_tol=bad)
    with pytest.raises(InputError, match="aero_state_tol"):
        analysis_config(solver={"aero_state_tol": 2.0})


def test_strips_without_states_are_left_as_they_are(nrel5mw_turbine, points):
    """Quasi-steady strips (C = 1) have no lag states: nothing to reduce, no projection kept; a cut-off
    outside (0, 1) is refused by name."""
    from windflutter.aero.unsteady import UnsteadyOptions

    om = OperationalModel(nrel5mw_turbine, OperationalOptions(mesh={"n_span": 10}, aero_state_tol=1e-7,
                                                              aero=UnsteadyOptions(circulation="quasi_steady")))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ps = om.at(WIND, rpm=RPM, pitch=0.0)
    assert ps.blade_system.n_states == 0 and ps.aero_projection is None
    with pytest.raises(InputError, match="aero_state_tol"):
        balanced_projection(points[0].blade_system, 0.0)
