"""The quasi-steady limit of the state-space operator against finite differences of the NONLINEAR
quasi-steady strip force, attached and stalled, for in-plane, out-of-plane and pitch motion.

The reference force is written here from rigid-body kinematics of a 2-D section (x downstream, z
up, pitch about +y nose-up) and shares nothing with the operator but the polar table."""

from __future__ import annotations

import numpy as np
import pytest
from aero_helpers import one_strip, stall_polar

from windflutter.aero.flow import OperatingPoint
from windflutter.aero.linearization import polar_linearization
from windflutter.aero.operators import StateSpaceAero
from windflutter.aero.sections import Polar
from windflutter.aero.unsteady import UnsteadyOptions

RHO, U, B, A = 1.225, 55.0, 0.9, -0.25


def qs_force(polar: Polar, alpha0: float, x: np.ndarray) -> np.ndarray:
    """Nonlinear quasi-steady (lift, moment, drag) per unit span of a section at pitch
    ``alpha0 + x[0]`` moving with plunge rate x[1] (up), pitch rate x[2], edgewise rate x[3]
    (downstream): the relative wind at the 3/4-chord point sets the angle of attack, the dynamic
    pressure and the lift/drag directions; forces act at the quarter chord."""
    pitch, hd, ad, sd = x
    theta = alpha0 + pitch
    t = np.array([np.cos(theta), -np.sin(theta)])  # chord LE -> TE in (x, z)
    d34, d14 = B * (0.5 - A), B * (A + 0.5)

    def rot_vel(r):  # omega x r for omega = ad along +y, in (x, z)
        return ad * np.array([r[1], -r[0]])

    v34 = np.array([sd, hd]) + rot_vel(d34 * t)
    W = np.array([U, 0.0]) - v34
    Wn = np.hypot(*W)
    w_hat = W / Wn
    n_hat = np.array([-w_hat[1], w_hat[0]])
    aoa = np.arctan2(W[1], W[0]) + theta
    cl, cd, cm = (np.interp(aoa, polar.alpha, c) for c in (polar.cl, polar.cd, polar.cm))
    q, c = 0.5 * RHO * Wn**2, 2 * B
    F = q * c * (cl * n_hat + cd * w_hat)
    r = -d14 * t
    My = r[1] * F[0] - r[0] * F[1] + q * c * c * cm
    return np.array([F[1], My, F[0]])


def jacobian(polar, alpha0, step=(1e-6, 1e-4, 1e-4, 1e-4)):
    cols = []
    for i, h in enumerate(step):
        e = np.zeros(4)
        e[i] = h
        cols.append((qs_force(polar, alpha0, e) - qs_force(polar, alpha0, -e)) / (2 * h))
    return np.stack(cols, axis=1)  # d(L, M, D) / d(alpha, h', alpha', s')


@pytest.mark.parametrize("alpha0_deg", [5.0, 17.0, 23.0])
@pytest.mark.parametrize("lift_direction", ["effective", "instantaneous"])
def test_quasi_steady_operator_is_the_linearised_nonlinear_force(alpha0_deg, lift_direction):
    # Quasi-steady circulation (C = 1, no states), no apparent mass: Ka and Da must be the
    # Jacobian of the nonlinear force.  alpha0 sits mid-segment of the 2-deg table, so the
    # operator's centred slope over +-1 deg is the table's slope there (exact), and the
    # reference differences stay inside the segment.  Tolerance 1e-6 relative to the largest
    # entry of each column: the O(step^2) error of the central differences (~1e-9).
    pol = stall_polar()
    alpha0 = np.radians(alpha0_deg)
    sec = one_strip(B, A, alpha0, pol, width=1.0)
    o = UnsteadyOptions(circulation="quasi_steady", apparent_mass=0.0, lift_direction=lift_direction)
    op = StateSpaceAero(sec, OperatingPoint(U, 0.0, RHO, None), o)
    assert op.flow.alpha[0] == pytest.approx(alpha0, rel=1e-12)
    assert op.n_states == 0
    ss = op.state_space()
    Ka, Da = ss.Ka[0], ss.Da[0]
    got = np.stack([Ka[:, 1], Da[:, 0], Da[:, 1], Da[:, 2]], axis=1)  # same columns as jacobian
    ref = jacobian(pol, alpha0)
    for j in range(4):
        scale = np.abs(ref[:, j]).max()
        assert np.allclose(got[:, j], ref[:, j], rtol=0, atol=1e-6 * scale), (j, got[:, j], ref[:, j])
    assert np.all(np.abs(ss.Ka[0][:, [0, 2]]) == 0) and np.all(ss.Ma[0] == 0)  # no h, s stiffness
    lin = op.linearization
    if alpha0_deg > 14:
        assert lin.dcl[0] < 0  # stalled: negative lift slope is kept (it drives stall vibrations)
        assert ref[0, 1] > 0  # ... and makes the plunge damping force positive (negative damping)


def test_state_space_static_gain_is_the_quasi_steady_stiffness():
    # With lag states (Jones, 2 poles; and with the separation lag of dynamic stall) the
    # response to a constant pitch is the quasi-steady one: H(0) = Ka_qs (1e-12).
    pol = stall_polar()
    sec = one_strip(B, A, np.radians(17.0), pol)
    opp = OperatingPoint(U, 0.0, RHO, None)
    qs = StateSpaceAero(sec, opp, UnsteadyOptions(circulation="quasi_steady", apparent_mass=0.0)).state_space()
    for o in (UnsteadyOptions(apparent_mass=0.0), UnsteadyOptions(apparent_mass=0.0, dynamic_stall=True),
              UnsteadyOptions(apparent_mass=0.0, circulation="rfa", n_lag=3, lift_direction="instantaneous")):
        ss = StateSpaceAero(sec, opp, o).state_space()
        assert ss.n_states == o.n_lag * (o.circulation == "rfa") + 2 * (o.circulation == "jones") + o.dynamic_stall
        H0 = ss.transfer(0.0)[0]
        assert np.abs(H0 - qs.Ka[0]).max() < 1e-12 * np.abs(qs.Ka[0]).max()


def test_dynamic_stall_state_lags_the_separation_point():
    # The separation state of Oye's model relaxes with tau = T_f b / U (Hansen et al. 2004):
    # its eigenvalue in Az is -U / (T_f b); and the lift it carries is the Kirchhoff
    # decomposition's dCl/df, so the total quasi-steady lift slope is the polar's (checked by
    # the static gain above).  In attached flow (f = 1, f' = 0) the state does not couple.
    pol = stall_polar()
    opp = OperatingPoint(U, 0.0, RHO, None)
    o = UnsteadyOptions(dynamic_stall=True, separation_time=4.0)
    st = StateSpaceAero(one_strip(B, A, np.radians(17.0), pol), opp, o)
    assert st.state_space().Az[0, 2, 2] == pytest.approx(-U / (4.0 * B), rel=1e-14)
    sep = st.linearization.separation
    assert 0 < sep.f[0] < 1 and sep.df[0] < 0  # separating further as alpha grows
    att = StateSpaceAero(one_strip(B, A, np.radians(1.0), pol), opp, o)
    s_att = att.linearization.separation
    assert s_att.f[0] == pytest.approx(1.0) and s_att.df[0] == 0.0
    assert np.all(att.state_space().Bq[0, 2] == 0) and np.all(att.state_space().Az[0, 2, :2] == 0)


def test_flat_plate_needs_no_polar_and_table_needs_one():
    from windflutter.errors import InputError

    sec = one_strip(B, A, 0.0, None)
    op = StateSpaceAero(sec, OperatingPoint(U, 0.0, RHO, None), UnsteadyOptions(polar="flat_plate"))
    assert op.n_states == 2
    with pytest.raises(InputError, match="polars"):
        StateSpaceAero(sec, OperatingPoint(U, 0.0, RHO, None), UnsteadyOptions())
    with pytest.raises(InputError, match="lift_direction"):
        UnsteadyOptions(lift_direction="sideways")
    with pytest.raises(InputError, match="circulation"):
        UnsteadyOptions(circulation="wagner")
    with pytest.raises(InputError, match="n_lag"):
        UnsteadyOptions(circulation="rfa", n_lag=0)
    with pytest.raises(InputError, match="dynamic_stall"):
        UnsteadyOptions(polar="flat_plate", dynamic_stall=True)
    assert polar_linearization(one_strip(B, A, 0.0, stall_polar()), np.zeros(1)).cl[0] == pytest.approx(
        np.interp(0.0, stall_polar().alpha, stall_polar().cl))
