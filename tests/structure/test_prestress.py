"""Prestress verification: Euler column, tube in tension (shell membrane KG), rotating cantilever."""

import numpy as np
import pytest
from scipy.optimize import brentq
from shellmodels import iso, tube
from test_beam import cantilever

from windflutter.structure import assemble, centrifugal_load, geometric_stiffness, modes, spin_softening, static_solve
from windflutter.structure.fem import BeamSection
from windflutter.structure.prestress import buckling_factors

EI, M_L = 1e6, 10.0


def pinned_column(ne=20, L=10.0):
    fe = cantilever(ne=ne, L=L, section=BeamSection.from_properties(EA=1e10, EIy=EI, EIz=EI, GJ=5e5,
                                                                   mass_per_length=M_L, Ixx_mass=0.5))
    fe.spc = {0: (0, 1, 2, 3), ne: (1, 2)}
    return fe


def test_euler_column_buckling_and_frequency_drop():
    ne, L, P = 20, 10.0, 1.0e4
    fe = pinned_column(ne, L)
    st = assemble(fe)
    F = np.zeros(st.n_dof)
    F[6 * ne] = -P  # compression
    Kg = geometric_stiffness(fe, static_solve(st, F))
    lam, _ = buckling_factors(st, Kg, n=2)
    P_cr = np.pi**2 * EI / L**2  # Euler, pinned-pinned
    # Hermite geometric stiffness: O(h^4) convergence, 20 elements -> < 1e-5; two planes (pair)
    np.testing.assert_allclose(lam * P, [P_cr, P_cr], rtol=1e-4)
    # frequency drop of a SS beam under compression: omega^2 = omega0^2 (1 - P / P_cr) (exact)
    P2 = 0.5 * P_cr
    F[6 * ne] = -P2
    Kg2 = geometric_stiffness(fe, static_solve(st, F))
    f = modes(st, n=2, K_extra=Kg2).freq
    f0 = np.pi / 2 / L**2 * np.sqrt(EI / M_L)
    np.testing.assert_allclose(f, f0 * np.sqrt(1 - P2 / P_cr), rtol=1e-4)


def cantilever_tension_freq(EI, m, T, L):
    """Lowest frequency (Hz) of a clamped-free EB beam under constant axial tension T (dead load).

    EI w'''' - T w'' = m omega^2 w; free end: w'' = 0, EI w''' - T w' = 0.  Roots of the 4x4
    determinant with w = C1 cosh(a x) + C2 sinh(a x) + C3 cos(b x) + C4 sin(b x).
    """

    def det(om):
        disc = np.sqrt(T**2 + 4 * EI * m * om**2)
        a, b = np.sqrt((T + disc) / (2 * EI)), np.sqrt((disc - T) / (2 * EI))
        ch, sh, c, s = np.cosh(a * L), np.sinh(a * L), np.cos(b * L), np.sin(b * L)
        Mx = np.array([
            [1, 0, 1, 0],
            [0, a, 0, b],
            [a**2 * ch, a**2 * sh, -b**2 * c, -b**2 * s],
            [EI * a**3 * sh - T * a * sh, EI * a**3 * ch - T * a * ch, EI * b**3 * s + T * b * s, -EI * b**3 * c - T * b * c],
        ])
        return np.linalg.det(Mx) / ch

    om0 = 1.8751**2 / L**2 * np.sqrt(EI / m)
    grid = np.linspace(0.5 * om0, 4 * om0, 400)
    d = np.array([det(o) for o in grid])
    k = np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0][0]
    return brentq(det, grid[k], grid[k + 1], xtol=1e-12) / (2 * np.pi)


def test_tension_reference_reduces_to_cantilever():
    # the analytic reference itself: T -> 0 gives 1.8751^2 sqrt(EI/m)/(2 pi L^2)
    f = cantilever_tension_freq(1e6, 10.0, 1e-6, 10.0)
    assert f == pytest.approx(1.87510407**2 / 100 * np.sqrt(1e5) / (2 * np.pi), rel=1e-7)


def test_beam_cantilever_in_tension():
    ne, L, T = 20, 10.0, 5.0 * EI / 10.0**2
    fe = cantilever(ne=ne, L=L, section=BeamSection.from_properties(EA=1e10, EIy=EI, EIz=EI, GJ=5e5,
                                                                   mass_per_length=M_L, Ixx_mass=0.5))
    st = assemble(fe)
    F = np.zeros(st.n_dof)
    F[6 * ne] = T
    f = modes(st, n=1, K_extra=geometric_stiffness(fe, static_solve(st, F))).freq[0]
    assert f == pytest.approx(cantilever_tension_freq(EI, M_L, T, L), rel=1e-4)


def test_shell_tube_in_tension_full_membrane_kg():
    """Thin tube (shells) in axial tension: stiffening ratio vs beam theory.

    pyfe3d's plate-only KG (out-of-plane gradient only) would give roughly half the increase of
    omega^2 for the walls that bend in their own plane; the full membrane KG must match theory.
    """
    R, L, t, E, nu, rho = 0.25, 10.0, 0.005, 210e9, 0.3, 7850.0
    nc = 24
    fe, idx = tube(nc, 40, R, L, iso(E, nu, rho, t))
    fe.spc = {int(k): (0, 1, 2, 3, 4, 5) for k in idx[0]}
    st = assemble(fe)
    I, A = np.pi * R**3 * t, 2 * np.pi * R * t
    T = 5.0 * E * I / L**2
    F = np.zeros(st.n_dof)
    F[6 * idx[-1]] = T / nc
    Kg = geometric_stiffness(fe, static_solve(st, F))
    f0 = modes(st, n=1).freq[0]
    f1 = modes(st, n=1, K_extra=Kg).freq[0]
    ref = cantilever_tension_freq(E * I, rho * A, T, L) / cantilever_tension_freq(E * I, rho * A, 1e-9 * T, L)
    assert ref > 1.3  # a large, easily detected stiffening
    # ratio f(T)/f(0): shell vs beam theory, the shell's own -0.7 % baseline (shear, mesh) cancels
    assert f1 / f0 == pytest.approx(ref, rel=0.005)
    # a plate-type KG (element-normal translation only, like pyfe3d's) misses the stiffening of
    # the walls bending in their own plane: clearly outside the tolerance
    import scipy.sparse as sp

    from windflutter.structure.shell import shell_membrane_kg

    r, c, v = shell_membrane_kg(fe, static_solve(st, F), directions="normal")
    Kn = sp.coo_matrix((v, (r, c)), shape=Kg.shape).tocsr()
    f_plate = modes(st, n=1, K_extra=Kn).freq[0]
    assert (f_plate / f0 - 1) < 0.8 * (ref - 1)


# Wright, Smith, Thresher & Wang (1982), J. Appl. Mech. 49:197-202, and Banerjee (2000), J. Sound
# Vib. 233(5):857-875, Table 1: first flapwise frequency omega sqrt(m L^4 / EI) of a uniform
# cantilever rotating about an axis through its root (no hub) at Omega sqrt(m L^4 / EI) = 0..12.
# (Checked independently here with a Chebyshev collocation solution: 3.51602, 3.68165, 4.13732,
# 4.79728, 7.36037, 13.17015.)
WRIGHT_FLAP = {0: 3.5160, 1: 3.6817, 2: 4.1373, 3: 4.7973, 6: 7.3604, 12: 13.1702}


@pytest.mark.parametrize("om_bar", [1, 3, 6, 12])
def test_rotating_cantilever_southwell(om_bar):
    ne, L = 40, 10.0
    fe = cantilever(ne=ne, L=L, section=BeamSection.from_properties(EA=1e12, EIy=EI, EIz=EI, GJ=5e5,
                                                                   mass_per_length=M_L, Ixx_mass=0.5))
    st = assemble(fe)
    scale = np.sqrt(EI / (M_L * L**4))
    Om = np.array([0.0, 0.0, om_bar * scale])  # axis z through the root; beam along x
    F = centrifugal_load(fe, st, Om, center=(0.0, 0.0, 0.0))
    K_sigma = geometric_stiffness(fe, static_solve(st, F))
    md = modes(st, n=4, K_extra=K_sigma + spin_softening(st, Om))
    # flap = motion along z (parallel to Omega): no spin softening, only centrifugal stiffening
    flap = md.freq[np.argmax(np.abs(md.shapes[2::6, :]).sum(0) > np.abs(md.shapes[1::6, :]).sum(0))]
    lag_mask = np.abs(md.shapes[1::6, :]).sum(0) > np.abs(md.shapes[2::6, :]).sum(0)
    lag = md.freq[np.nonzero(lag_mask)[0][0]]
    # 40 Hermite elements; piecewise-constant axial force per element: observed < 2e-4, allow 1e-3
    assert 2 * np.pi * flap / scale == pytest.approx(WRIGHT_FLAP[om_bar], rel=1e-3)
    # lead-lag (in the rotation plane) with equal stiffness: omega_lag^2 = omega_flap^2 - Omega^2
    # exactly (spin softening); both from the same model -> tight tolerance
    assert (2 * np.pi * lag) ** 2 == pytest.approx((2 * np.pi * flap) ** 2 - Om[2] ** 2, rel=2e-4)
