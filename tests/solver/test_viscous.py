"""The viscous strip model: polar fits (Cl_alpha, Cd_alpha), the drag term and the apparent-mass
scaling, each against an independent reference (exact synthetic polars, finite differences of
the tables, hand-derived quasi-steady forces, a fixed-wing strip with known force directions).

See docs/notes/seed_comparison.md for why the viscous onset of the NREL 5 MW lies below the potential
one here and above it in the seed.
"""

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.aero.polars import fit_polar
from windflutter.aero.sections import AeroSections, Polar, RotorGeometry
from windflutter.aero.strip import AeroOptions, OperatingPoint, StripAero, aero_matrices, section_matrices
from windflutter.errors import InputError


def _synthetic_polar(cla=5.9, a0_deg=-2.0, stall_deg=9.0, cd0=0.007, cda=0.03):
    """Linear lift up to stall (then a drop), drag linear in alpha above the zero-lift angle."""
    a = np.radians(np.arange(-30.0, 30.5, 0.5))
    a0, ast = np.radians(a0_deg), np.radians(stall_deg)
    cl = cla * (a - a0)
    cl = np.where(a > ast, cla * (ast - a0) - 2.0 * (a - ast), cl)  # stall: slope -2 /rad
    cl = np.where(a < -ast + 2 * a0, cla * (-ast + a0) + 2.0 * (-ast + 2 * a0 - a), cl)
    cd = np.where(a >= a0, cd0 + cda * (a - a0), cd0 - 0.01 * (a - a0))
    cd = cd + np.where(np.abs(a - a0) > ast - a0, 0.5 * (np.abs(a - a0) - (ast - a0)), 0.0)
    return Polar(a, cl, cd, np.zeros_like(a), name="synthetic")


def test_fit_recovers_exact_slopes_of_a_linear_polar():
    # independent reference: the slopes the polar was generated with (exact, up to round-off)
    f = fit_polar(_synthetic_polar())
    assert f.cl_alpha == pytest.approx(5.9, rel=1e-10)
    assert f.cd_alpha == pytest.approx(0.03, rel=1e-8)
    assert np.degrees(f.alpha_zero_lift) == pytest.approx(-2.0, abs=1e-9)
    # the attached range stops before stall (9 deg) and inside the 12-deg limit around alpha_0
    assert np.degrees(f.alpha_max) <= 9.0 + 1e-9
    assert np.degrees(f.alpha_min) >= -14.0 - 1e-9


def test_fit_is_in_radians_not_degrees():
    # the same polar tabulated on a finer grid gives the same slope per radian (a degree/radian
    # mix-up would be off by 57x)
    p = _synthetic_polar(cla=6.0)
    fine = Polar(np.linspace(p.alpha[0], p.alpha[-1], 481), *(np.interp(np.linspace(p.alpha[0], p.alpha[-1], 481),
                                                                       p.alpha, c) for c in (p.cl, p.cd, p.cm)))
    assert fit_polar(fine).cl_alpha == pytest.approx(6.0, rel=1e-6)


@pytest.fixture(scope="module")
def nrel_airfoils():
    from windflutter.model.windio import load_turbine

    return load_turbine("nrel5mw").airfoils


@pytest.mark.parametrize("name", ["DU35_A17", "DU30_A17", "DU25_A17", "DU21_A17", "NACA64_A17"])
def test_nrel_fit_vs_finite_difference_of_the_table(nrel_airfoils, name):
    """Cl_alpha of the AeroDyn tables vs a direct central difference at the zero-lift angle.

    The least-squares line over the attached range (+-7..13 deg) includes the gentle curvature of
    the lift curve, so it is within 10 % of the point slope (observed 5-9 %), not equal; a
    unit error or a range reaching into stall would be far outside.  The tables' own slope is
    above 2 pi (thick airfoils; the reason why the viscous onset lies below the potential one).
    """
    p = nrel_airfoils[name].polar
    f = fit_polar(p)
    h = np.radians(2.0)
    fd = (np.interp(f.alpha_zero_lift + h, p.alpha, p.cl) - np.interp(f.alpha_zero_lift - h, p.alpha, p.cl)) / (2 * h)
    assert fd > 2 * np.pi
    assert f.cl_alpha == pytest.approx(fd, rel=0.10)
    # drag: a least-squares slope over sorted abscissae is a positively weighted mean of the
    # slopes between neighbouring points, so it must lie within the table's own local slopes on
    # the fitted positive range (alpha_0 .. alpha_max); Cd is bucket-shaped, so that is all a
    # straight line can promise.  And drag varies far less than lift.
    sel = (p.alpha >= f.alpha_zero_lift) & (p.alpha <= f.alpha_max)
    local = np.diff(p.cd[sel]) / np.diff(p.alpha[sel])
    assert local.min() <= f.cd_alpha <= local.max()
    assert 0 < f.cd_alpha < 0.01 * f.cl_alpha


def test_two_point_cylinder_polar_has_no_slopes():
    # the IEA 15 MW root "circular" polar has two points and no lift
    cyl = Polar(np.array([-np.pi, np.pi]), np.zeros(2), np.full(2, 0.6), np.zeros(2), name="circular")
    f = fit_polar(cyl)
    assert (f.cl_alpha, f.cd_alpha) == (0.0, 0.0)
    with pytest.raises(InputError):
        fit_polar(Polar(np.array([-0.1, 0.1]), np.array([-0.6, 0.6]), np.zeros(2), np.zeros(2), name="two"))


RHO, B, A, U, CLA, CDA = 1.2, 0.8, -0.3, 40.0, 6.7, 0.025


def test_quasi_steady_drag_row_matches_hand_derivation():
    """C(k) = 1: alpha_eff = alpha - h'/U + b (1/2 - a) alpha'/U (h up, three-quarter-chord
    downwash) and D = 1/2 rho U^2 (2 b) Cd_alpha alpha_eff, along e3; no apparent-mass drag and
    no dependence on the edgewise motion s (the seed's eq. 3.51 has none either)."""
    Ma, Da, Ka = (x[0] for x in section_matrices(np.array([B]), np.array([A]), np.array([U]), np.array([1.0 + 0j]),
                                                 RHO, CLA, CDA))
    q = RHO * U**2 * B  # 1/2 rho U^2 c
    assert Ka[2] == pytest.approx(np.array([0.0, q * CDA, 0.0]), abs=1e-12)
    assert Da[2] == pytest.approx(np.array([-q * CDA / U, q * CDA * B * (0.5 - A) / U, 0.0]), abs=1e-12)
    assert np.all(Ma[2] == 0)
    # the lift row of the same derivation with Cl_alpha (and the flat-plate apparent mass)
    assert Ka[0, 1] == pytest.approx(q * CLA, rel=1e-14)
    assert Da[0, 0] == pytest.approx(-q * CLA / U, rel=1e-14)
    assert np.all(Ma[:, 2] == 0) and np.all(Da[:, 2] == 0) and np.all(Ka[:, 2] == 0)


def test_drag_scales_lift_row_with_theodorsen_lag():
    # unsteady: the drag row is the circulatory lift row times Cd_alpha / Cl_alpha
    C = np.array([0.7 - 0.15j])
    Ma, Da, Ka = section_matrices(np.array([B]), np.array([A]), np.array([U]), C, RHO, CLA, CDA)
    M0, D0, K0 = section_matrices(np.array([B]), np.array([A]), np.array([U]), C, RHO, CLA, CDA, am_scale=0.0)
    assert Da[0, 2] == pytest.approx(D0[0, 0] * CDA / CLA, rel=1e-14)
    assert Ka[0, 2] == pytest.approx(K0[0, 0] * CDA / CLA, rel=1e-14)


def test_apparent_mass_scaling_only_touches_noncirculatory_terms():
    args = (np.array([B]), np.array([A]), np.array([U]), np.array([0.8 - 0.1j]), RHO, CLA, CDA)
    s = CLA / (2 * np.pi)
    M1, D1, K1 = section_matrices(*args)
    Ms, Ds, Ks = section_matrices(*args, am_scale=s)
    Mc, Dc, Kc = section_matrices(*args, am_scale=0.0)  # circulatory part alone
    assert np.allclose(Ms, s * M1, rtol=1e-14)
    assert np.allclose(Ks, K1, rtol=1e-14)
    assert np.allclose(Ds - Dc, s * (D1 - Dc), rtol=1e-13, atol=1e-12)


def test_fixed_wing_strip_force_directions():
    """A strip with chord along the wind (+x), span +y: a nose-up pitch gives lift along +z and
    drag along +x (downstream), of the hand-computed quasi-steady sizes (width 2 m)."""
    sec = AeroSections(blade=np.array([0]), radius=np.array([1.0]), width=np.array([2.0]),
                       chord=np.array([2 * B]), elastic_axis=np.array([A]), origin=np.zeros((1, 3)),
                       e_chord=np.array([[1.0, 0, 0]]), e_span=np.array([[0, 1.0, 0]]), airfoil=np.array([0]),
                       polars=[], twist=np.zeros(1), motion_map=sp.identity(6, format="csr"))
    op = OperatingPoint(U, 0.0, RHO, RotorGeometry(np.zeros(3), np.array([0, 0, 1.0]), np.array([1.0, 0, 0])))
    Ma, Da, Ka = aero_matrices(sec, op, 0.0, AeroOptions("viscous", lift_slope=CLA, drag_slope=CDA))
    K = Ka.toarray()
    theta = 4  # rotation about +y: the trailing edge (+x) goes down, i.e. nose up
    q = RHO * U**2 * B * 2.0
    assert K[0, theta].real == pytest.approx(q * CDA, rel=1e-12)   # drag along +x (downwind)
    assert K[2, theta].real == pytest.approx(q * CLA, rel=1e-12)   # lift along +z
    # pitching moment about -y? nose-up moment about +y from lift ahead of the elastic axis
    assert K[4, theta].real == pytest.approx(q * CLA * B * (A + 0.5), rel=1e-12)


def test_cm_slope_and_aerodynamic_centre_of_a_linear_polar():
    p = _synthetic_polar(cla=5.9)
    p = Polar(p.alpha, p.cl, p.cd, -0.05 - 0.2 * (p.alpha - np.radians(-2.0)), name="synthetic")
    f = fit_polar(p)
    assert f.cm_alpha == pytest.approx(-0.2, rel=1e-10)
    assert f.ac_shift == pytest.approx(0.2 / 5.9, rel=1e-10)  # a.c. aft of c/4: x_ac = 1/4 - Cm_a/Cl_a


def test_ac_shift_moves_the_circulatory_lift():
    """Lift acting at x_ac = c/4 + dx: moment arm about the elastic axis (x_ea = (1 + a) b from the
    leading edge) is x_ea - x_ac = b (a + 1/2) - 2 b dx.  With the a.c. on the elastic axis the
    circulatory moment vanishes (only the apparent-mass moment is left)."""
    args = (np.array([B]), np.array([A]), np.array([U]), np.array([0.8 - 0.1j]), RHO, CLA, CDA)
    dx = 0.03
    M0, D0, K0 = (x[0] for x in section_matrices(*args))
    M1, D1, K1 = (x[0] for x in section_matrices(*args, ac_shift=dx))
    arm0, arm1 = B * (A + 0.5), B * (A + 0.5) - 2 * B * dx
    assert K1[1, 1] == pytest.approx(K0[1, 1] * arm1 / arm0, rel=1e-13)
    assert np.allclose(K1[[0, 2]], K0[[0, 2]]) and np.allclose(M1, M0)
    Mn, Dn, Kn = (x[0] for x in section_matrices(*args, ac_shift=(A + 0.5) / 2))
    Mc, Dc, Kc = (x[0] for x in section_matrices(*args[:5], 0.0, CDA))  # apparent mass alone
    assert Kn[1] == pytest.approx(np.zeros(3), abs=1e-12)
    assert Dn[1] == pytest.approx(Dc[1], abs=1e-12)


@pytest.mark.parametrize("model, am_scaling", [("potential", False), ("viscous", True)])
def test_projected_aero_equals_the_assembled_matrices_projected(model, am_scaling):
    # StripAero.projected uses that the circulatory terms are rank one per strip (one downwash,
    # one lift): it must equal Phi^T A(omega) Phi of the assembled sparse matrices (no such
    # structure used) to round-off, on several rotating strips of different size, slope and flow
    rng = np.random.default_rng(7)
    ns = 5
    pol = _synthetic_polar()
    sec = AeroSections(blade=np.zeros(ns, int), radius=np.linspace(10.0, 60.0, ns), width=np.full(ns, 12.0),
                       chord=np.linspace(4.0, 1.5, ns), elastic_axis=np.linspace(-0.3, 0.1, ns),
                       origin=np.stack([np.zeros(ns), np.zeros(ns), np.linspace(10.0, 60.0, ns)], axis=1),
                       e_chord=np.tile([1.0, 0, 0], (ns, 1)), e_span=np.tile([0, 0, 1.0], (ns, 1)),
                       airfoil=np.zeros(ns, int), polars=[pol], twist=np.linspace(0.2, 0.0, ns),
                       motion_map=sp.identity(6 * ns, format="csr"))
    rot = RotorGeometry(np.zeros(3), np.array([1.0, 0, 0]), np.array([0, 0, 1.0]))
    op = OperatingPoint(9.0, 1.2, RHO, rot)
    strip = StripAero(sec, op, AeroOptions(model, apparent_mass_scaling=am_scaling))
    Phi = rng.standard_normal((6 * ns, 7))
    f = strip.projected(Phi)
    for omega in (0.0, 3.1, 40.0):
        for A, B in zip(f(omega), strip.matrices(omega)):
            ref = Phi.T @ (B @ Phi)
            assert np.abs(A - ref).max() < 1e-12 * np.abs(ref).max()


@pytest.mark.parametrize("model", ["viscous", "potential"])
def test_mean_load_damping_is_the_linearised_quasi_steady_force(model):
    # Independent reference: central finite differences of the *nonlinear* quasi-steady force
    # of a strip moving with (h', s') across / along the wind -- relative wind (U - s', -h'),
    # lift Cl(alpha) perpendicular to it, drag Cd(alpha) along it, dynamic pressure from its
    # magnitude, moment arm x lift + q c^2 Cm -- with the tabulated polar (linear lift and drag
    # here, so Cl_alpha / Cd_alpha of the fit are the table's).  At k = 0 (C = 1) the h and s
    # columns of Da must be its derivatives: Theodorsen's circulatory terms (the change of
    # angle of attack) plus the mean-load terms of steady_loads.  Potential flow: its 2 pi
    # slope and no drag for the angle-of-attack part, the polar's mean loads for the rest.
    # Tolerance 1e-7 relative: the O(dv^2) error of the differences (dv = 1e-3 m/s).
    alpha0 = np.radians(4.0)
    pol = _synthetic_polar(cla=5.9, a0_deg=-2.0, cd0=0.007, cda=0.03)
    pol = Polar(pol.alpha, pol.cl, pol.cd, np.full_like(pol.alpha, -0.08), name="cm")
    chord_dir = np.array([[np.cos(alpha0), 0.0, -np.sin(alpha0)]])  # trailing edge low: nose up
    sec = AeroSections(blade=np.array([0]), radius=np.array([1.0]), width=np.array([2.0]),
                       chord=np.array([2 * B]), elastic_axis=np.array([A]), origin=np.zeros((1, 3)),
                       e_chord=chord_dir, e_span=np.array([[0, 1.0, 0]]), airfoil=np.array([0]),
                       polars=[pol], twist=np.zeros(1), motion_map=sp.identity(6, format="csr"))
    op = OperatingPoint(U, 0.0, RHO, RotorGeometry(np.zeros(3), np.array([0, 0, 1.0]), np.array([1.0, 0, 0])))
    strip = StripAero(sec, op, AeroOptions(model, steady_loads=True))
    assert strip.flow.alpha[0] == pytest.approx(alpha0, rel=1e-12)
    Da = strip.matrices(0.0)[1].toarray().real / 2.0  # per unit span
    cla = 5.9 if model == "viscous" else 2 * np.pi
    cda = 0.03 if model == "viscous" else 0.0
    c, arm = 2 * B, B * (A + 0.5)

    def force(hd, sd):
        Wl, Wd = -hd, U - sd  # relative wind on (e1 = lift, e3 = drag) axes
        W = np.hypot(Wl, Wd)
        w_hat, n_hat = np.array([Wl, Wd]) / W, np.array([Wd, -Wl]) / W
        da = np.arctan2(-hd, U - sd)  # change of the angle of attack
        cl0, cd0, cm0 = (np.interp(alpha0, pol.alpha, t) for t in (pol.cl, pol.cd, pol.cm))
        cl, cd = cl0 + cla * da, cd0 + cda * da  # the model's slopes for the alpha part
        q = 0.5 * RHO * W**2
        F = q * c * (cl * n_hat + cd * w_hat)
        return np.array([F[0], arm * F[0] + q * c**2 * cm0, F[1]])  # lift, moment, drag

    dv = 1e-3
    for col, dof in ((0, 2), (1, 0)):  # h' (global uz) and s' (global ux)
        e = np.zeros(2)
        e[col] = dv
        fd = (force(*e) - force(*(-e))) / (2 * dv)
        got = Da[[2, 4, 0], dof]  # lift (z), moment (about y), drag (x) rows
        assert np.allclose(got, fd, rtol=1e-7, atol=1e-7 * np.abs(fd).max())
