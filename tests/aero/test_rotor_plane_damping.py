"""Quasi-steady rotor-plane damping of the state-space strips against the blade-element formula.

Independent reference (written here, nothing shared with the operator): a blade element in the
rotor plane with the relative wind ``W = W_n n - W_t t`` (``n`` downwind along the shaft, ``t``
the direction of rotation; ``W_n = V (1 - a)``, ``W_t = Omega r (1 + a')``), inflow angle
``phi = atan(W_n / W_t)`` from the rotor plane, ``alpha = phi - beta`` and the forces per unit span

    F_n = q c (Cl cos(phi) + Cd sin(phi)),      F_t = q c (Cl sin(phi) - Cd cos(phi)),   q = rho W^2 / 2.

A section velocity ``(x_n', x_t')`` changes ``W_n -> W_n - x_n'``, ``W_t -> W_t + x_t'``; with
``dW/dW_n = sin(phi)``, ``dW/dW_t = cos(phi)``, ``dphi/dW_n = cos(phi)/W``, ``dphi/dW_t = -sin(phi)/W``
the damping matrix ``F = -C x'`` is, with ``k = rho c W / 2`` and the polar slopes ``Cl'``, ``Cd'``::

    C_tt = k [Cd (1 + cos^2) + Cl' sin^2 - (Cl + Cd') sin cos]      (in-plane: the Cl0 term REDUCES it)
    C_nn = k [Cl' cos^2 + Cd (1 + sin^2) + (Cl + Cd') sin cos]
    C_nt = -k [Cl (1 + cos^2) + (Cd - Cl') sin cos - Cd' sin^2]     (out-of-plane force per in-plane velocity)
    C_tn = k [Cl (1 + sin^2) + (Cl' - Cd) sin cos - Cd' cos^2]      (in-plane force per out-of-plane velocity)

(``sin``, ``cos`` of ``phi``).  The transport velocity of the rotating frame, ``Omega n x u`` for a
displacement ``u`` of the section, is ``Omega u_r t`` for a radial displacement (nothing for ``u``
along ``n``; a spanwise velocity for ``u`` along ``t``), so it adds the stiffness
``F = -Omega C[:, t] u_r`` to the strips (the operating-point model's
:func:`~windflutter.system.blade_aero.project_blade_aero`).  ``C_tt`` is the in-plane damping formula of Hansen (2007, Wind
Energy 10:551, "Aeroelastic instability problems for wind turbines") and of the edgewise-damping
audit (docs/notes/edgewise_damping.md).  Without the mean-load terms the operator keeps only the slope
terms (``Cl = Cd = 0`` in the formula).

Set-up: four strips on one blade along +z, shaft and wind along +x, rotor speed about +x (the
blade moves towards -y), induction factors given, chords turned towards feather so that the
steady angles of attack sit at chosen points of a piecewise-linear polar (attached, near the
peak, stalled with a negative lift slope), each more than 1 deg from a table node, where the
operator's centred slope (+-1 deg) is the exact segment slope.  The operator is the state-space
strip law in its quasi-steady limit (``C = 1``, no apparent mass): the formula above is exact
for it, so the tolerance is round-off (1e-10 of each matrix's largest entry).
"""

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.system.blade import axis_skew_translations
from windflutter.system.blade_aero import project_blade_aero

from windflutter.aero.flow import OperatingPoint
from windflutter.aero.operators import StateSpaceAero
from windflutter.aero.sections import AeroSections, Polar, RotorGeometry
from windflutter.aero.unsteady import UnsteadyOptions

RHO, V, OMEGA = 1.225, 10.0, 0.75
RADII = np.array([20.0, 45.0, 70.0, 95.0])
CHORD = np.array([5.0, 4.0, 3.0, 2.0])
A_AX = np.array([0.30, 0.32, 0.28, 0.22])
A_TAN = np.array([0.020, 0.008, 0.004, 0.002])
ALPHA = np.radians([6.0, 2.0, 14.0, 22.0])  # attached, attached, just past the peak, stalled

#: nodes every 4 deg from -8 to 32 deg; values of a typical thick airfoil with stall at 12 deg
POLAR_DEG = np.arange(-8.0, 33.0, 4.0)
POLAR = Polar(np.radians(POLAR_DEG),
              np.interp(POLAR_DEG, [-8, 0, 12, 16, 24, 32], [-0.5, 0.45, 1.55, 1.35, 1.1, 1.05]),
              np.interp(POLAR_DEG, [-8, 0, 8, 12, 16, 24, 32], [0.02, 0.008, 0.012, 0.03, 0.09, 0.25, 0.42]),
              np.interp(POLAR_DEG, [-8, 0, 12, 32], [-0.02, -0.09, -0.11, -0.16]), name="thick")


def _strips():
    """Strips at RADII with the chord turned so that alpha (with the induction) is ALPHA."""
    phi = np.arctan2(V * (1 - A_AX), OMEGA * RADII * (1 + A_TAN))
    beta = phi - ALPHA  # chord angle from the rotor plane, + towards feather
    # LE towards the motion (-y): chord LE->TE along +y, trailing edge downwind (+x) for beta > 0
    e_chord = np.column_stack([np.sin(beta), np.cos(beta), np.zeros_like(beta)])
    ns = RADII.size
    sec = AeroSections(blade=np.zeros(ns, dtype=np.int64), radius=RADII, width=np.ones(ns), chord=CHORD,
                       elastic_axis=np.array([-0.3, -0.2, 0.0, 0.1]),
                       origin=np.column_stack([np.zeros(ns), np.zeros(ns), RADII]), e_chord=e_chord,
                       e_span=np.tile([0.0, 0.0, 1.0], (ns, 1)), airfoil=np.zeros(ns, dtype=np.int64),
                       polars=[POLAR], twist=beta, motion_map=sp.identity(6 * ns, format="csr"))
    rotor = RotorGeometry(hub_center=np.zeros(3), shaft_axis=np.array([1.0, 0.0, 0.0]),
                          wind_direction=np.array([1.0, 0.0, 0.0]))
    return sec, OperatingPoint(V, OMEGA, RHO, rotor, induction=(A_AX, A_TAN)), phi


def _slopes():
    """Exact segment slopes of the polar at ALPHA (1/rad) and its values there."""
    a = POLAR.alpha
    seg = np.searchsorted(a, ALPHA) - 1
    dcl = (POLAR.cl[seg + 1] - POLAR.cl[seg]) / (a[seg + 1] - a[seg])
    dcd = (POLAR.cd[seg + 1] - POLAR.cd[seg]) / (a[seg + 1] - a[seg])
    return np.interp(ALPHA, a, POLAR.cl), np.interp(ALPHA, a, POLAR.cd), dcl, dcd


def blade_element_damping(phi, mean_loads=True):
    """(ns, 2, 2) damping matrices [[C_nn, C_nt], [C_tn, C_tt]] (N s/m per m) of the module docstring."""
    cl, cd, dcl, dcd = _slopes()
    if not mean_loads:
        cl, cd = np.zeros_like(cl), np.zeros_like(cd)
    W = np.hypot(V * (1 - A_AX), OMEGA * RADII * (1 + A_TAN))
    k = 0.5 * RHO * CHORD * W
    s, c = np.sin(phi), np.cos(phi)
    C = np.empty((RADII.size, 2, 2))
    C[:, 1, 1] = k * (cd * (1 + c**2) + dcl * s**2 - (cl + dcd) * s * c)
    C[:, 0, 0] = k * (dcl * c**2 + cd * (1 + s**2) + (cl + dcd) * s * c)
    C[:, 0, 1] = -k * (cl * (1 + c**2) + (cd - dcl) * s * c - dcd * s**2)
    C[:, 1, 0] = k * (cl * (1 + s**2) + (dcl - cd) * s * c - dcd * c**2)
    return C


def operator_damping(sec, op, mean_loads=True):
    """The operator's quasi-steady damping on the strips' (n, t) translations: (ns, 2, 2)."""
    oper = StateSpaceAero(sec, op, UnsteadyOptions(circulation="quasi_steady", apparent_mass=0.0,
                                                   mean_loads=mean_loads))
    ss = oper.state_space()
    assert ss.n_states == 0
    ns = sec.n_sections
    n_hat, t_hat = np.array([1.0, 0.0, 0.0]), np.array([0.0, -1.0, 0.0])  # t: direction of rotation
    C = np.empty((ns, 2, 2))
    Da = sp.block_diag(list(ss.Da), format="csr")
    for col, d in enumerate((n_hat, t_hat)):
        v = np.zeros((ns, 6))
        v[:, :3] = d
        f = (oper.P.T @ (Da @ (oper.P @ v.ravel()))).reshape(ns, 6)[:, :3]  # strip forces, global
        C[:, 0, col] = -f @ n_hat
        C[:, 1, col] = -f @ t_hat
    return C, oper


def test_geometry_puts_alpha_where_intended():
    # the reference's rotor-plane angles are the operator's: alpha = phi - beta with beta
    # towards feather, induction in the inflow
    sec, op, phi = _strips()
    _, oper = operator_damping(sec, op)
    np.testing.assert_allclose(oper.flow.alpha, ALPHA, atol=1e-12)
    np.testing.assert_allclose(oper.flow.phi, phi, atol=1e-12)
    cl, cd, dcl, dcd = _slopes()
    lin = oper.linearization
    np.testing.assert_allclose(lin.dcl, dcl, rtol=1e-10)
    np.testing.assert_allclose(lin.dcd, dcd, rtol=1e-10)
    assert dcl[3] < 0  # the stalled strip has a falling lift curve


@pytest.mark.parametrize("mean_loads", [True, False])
def test_rotor_plane_damping_equals_blade_element_formula(mean_loads):
    sec, op, phi = _strips()
    C_op, _ = operator_damping(sec, op, mean_loads)
    C_ref = blade_element_damping(phi, mean_loads)
    for j in range(sec.n_sections):
        np.testing.assert_allclose(C_op[j], C_ref[j], atol=1e-10 * np.abs(C_ref[j]).max(), rtol=0,
                                   err_msg=f"strip {j}, alpha {np.degrees(ALPHA[j]):.0f} deg")


def test_in_plane_damping_of_an_outer_strip_is_cut_by_the_mean_lift():
    # The physics the formula states, on the operator: at the outer attached strip (phi ~ 5 deg,
    # Cl0 ~ 0.6) the mean lift's share -Cl0 sin(phi) cos(phi) takes away more in-plane damping than
    # the drag and lift slope give, so C_tt with the mean loads is below the slope-only value --
    # the reason the edgewise aerodynamic damping of a large blade comes from its flap content.
    sec, op, phi = _strips()
    with_ml, _ = operator_damping(sec, op, True)
    without, _ = operator_damping(sec, op, False)
    j = 1  # alpha 2 deg, r = 45 m
    cl, cd, dcl, dcd = _slopes()
    W = np.hypot(V * (1 - A_AX[j]), OMEGA * RADII[j] * (1 + A_TAN[j]))
    expected = 0.5 * RHO * CHORD[j] * W * (cd[j] * (1 + np.cos(phi[j]) ** 2) - cl[j] * np.sin(phi[j]) * np.cos(phi[j]))
    assert expected < 0
    assert with_ml[j, 1, 1] - without[j, 1, 1] == pytest.approx(expected, rel=1e-10)


def test_transport_velocity_is_omega_times_the_tangential_damping_of_a_radial_displacement():
    # the rotating-frame transport term of the turbine assembly (system.blade_aero), on these
    # strips with their own 6 DOFs as the coordinates (blade along +z: radial = z)
    sec, op, phi = _strips()
    C, oper = operator_damping(sec, op)
    ss = oper.state_space()
    ns = sec.n_sections
    R = oper.P.toarray()
    Rt = (oper.P @ axis_skew_translations(ns, np.array([1.0, 0.0, 0.0]))).toarray()
    blocks = ss  # StripBlocks is the operator's StripStateSpace
    _, _, Ka, *_ = project_blade_aero(blocks, R, Rt, OMEGA)
    _, _, Ka0, *_ = project_blade_aero(blocks, R, Rt, 0.0)
    K_tr = Ka - Ka0  # the aerodynamic force (added to the structure's right-hand side) per displacement
    n_hat, t_hat = np.array([1.0, 0.0, 0.0]), np.array([0.0, -1.0, 0.0])
    for j in range(ns):
        rows = slice(6 * j, 6 * j + 3)
        f_r = K_tr[rows, 6 * j + 2]  # unit radial (z) displacement of strip j
        scale = OMEGA * np.abs(C[j]).max()
        assert f_r @ n_hat == pytest.approx(-OMEGA * C[j, 0, 1], abs=1e-10 * scale)
        assert f_r @ t_hat == pytest.approx(-OMEGA * C[j, 1, 1], abs=1e-10 * scale)
        # a displacement along the shaft or the direction of rotation adds no aerodynamic force
        np.testing.assert_allclose(K_tr[rows, 6 * j: 6 * j + 2], 0.0, atol=1e-10 * scale)
    assert np.abs(K_tr[:, 3::6]).max() == 0.0  # rotations carry no transport term
