"""Beam element verification against Euler-Bernoulli / Saint-Venant closed forms."""

import numpy as np
import pytest

from windflutter.errors import InputError, ModelError
from windflutter.structure import assemble, modes
from windflutter.structure.fem import BeamSection, FEModel

BETA_L = np.array([1.87510407, 4.69409113, 7.85475744])  # cantilever roots of 1 + cos cosh = 0


def cantilever(ne=20, L=10.0, section=None, orient=(0.0, 1.0, 0.0), axis=(1.0, 0.0, 0.0)):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    x = np.linspace(0, L, ne + 1)[:, None] * axis[None, :]
    if section is None:
        section = BeamSection.from_properties(EA=1e9, EIy=1e6, EIz=1e6, GJ=5e5, mass_per_length=10.0, Ixx_mass=0.5)
    return FEModel(nodes=x, beam_conn=np.c_[np.arange(ne), np.arange(1, ne + 1)],
                   beam_section=np.zeros(ne, int), beam_orient=np.tile(orient, (ne, 1)),
                   beam_sections=[section], spc={0: (0, 1, 2, 3, 4, 5)})


def test_cantilever_bending_and_torsion_frequencies():
    # oblique axis to exercise the frame rotation
    fe = cantilever(ne=20, axis=(1.0, 2.0, -0.5), orient=(0.0, 0.0, 1.0))
    md = modes(assemble(fe), n=10)
    L, EI, m, GJ, Ip = 10.0, 1e6, 10.0, 5e5, 0.5
    f_b = BETA_L**2 / L**2 * np.sqrt(EI / m) / (2 * np.pi)
    f_t = np.array([1, 3]) / (4 * L) * np.sqrt(GJ / Ip)
    f = md.freq
    # bending pairs (EIy = EIz): Hermite consistent mass + exact stiffness converge as h^4;
    # with 20 elements the 3rd mode is within 1e-4 (shear-rigid section: GA = 1e3 EA)
    for k, fb in enumerate(f_b):
        assert np.sum(np.abs(f - fb) / fb < 1e-4) == 2
    # torsion: linear twist interpolation with consistent mass over-estimates the frequency by
    # (k h)^2 / 24 (k = wave number, h = element length): 2.6e-4 and 2.3e-3; allow 1.5x that
    for n_half, ft in zip((1, 3), f_t):
        kh = n_half * np.pi / 2 / 20
        assert 0 < np.min(np.abs(f - ft)) / ft < 1.5 * kh**2 / 24


def test_static_tip_load_exact():
    # exact element stiffness: tip deflection PL^3/3EI (+ tiny shear term with GA = 1e3 EA)
    fe = cantilever(ne=3)
    st = assemble(fe)
    from windflutter.structure import static_solve

    F = np.zeros(st.n_dof)
    F[6 * 3 + 2] = 1000.0
    u = static_solve(st, F)
    assert u[6 * 3 + 2] == pytest.approx(1000.0 * 10.0**3 / (3 * 1e6), rel=1e-6)
    assert u[6 * 3 + 4] == pytest.approx(-1000.0 * 10.0**2 / (2 * 1e6), rel=1e-6)


def test_unconstrained_model_raises():
    fe = cantilever(ne=4)
    fe.spc = {}
    with pytest.raises(ModelError, match="not sufficiently constrained"):
        assemble(fe)
    # a pinned support only (rotation about x free: torsional mechanism)
    fe.spc = {0: (0, 1, 2, 4, 5)}
    with pytest.raises(ModelError):
        assemble(fe)


def test_bad_orientation_raises():
    fe = cantilever(ne=4, orient=(1.0, 0.0, 0.0))
    with pytest.raises(InputError, match="beam_orient"):
        assemble(fe)


def coupled_bt_freqs(EI, GJ, m, Ixx, cy, L, n=3):
    """Exact coupled bending-torsion frequencies (Hz) of a uniform clamped-free beam with the
    mass centre at cy from the (shear-centre) reference axis, shear-rigid Euler-Bernoulli bending.

    EI w'''' = omega^2 m (w + cy theta),  -GJ theta'' = omega^2 (Ixx theta + m cy w)
    (Ixx about the reference axis).  Transfer matrix expm(A L) of the 6-state system; clamped
    root, free tip: det of the 3x3 tip-condition block; roots bracketed on a fine grid.
    """
    from scipy.linalg import expm

    def det(om):
        A = np.zeros((6, 6))
        A[0, 1] = A[1, 2] = A[2, 3] = A[4, 5] = 1.0
        A[3, 0], A[3, 4] = om**2 * m / EI, om**2 * m * cy / EI
        A[5, 4], A[5, 0] = -om**2 * Ixx / GJ, -om**2 * m * cy / GJ
        P = expm(A * L)
        return np.linalg.det(P[np.ix_([2, 3, 5], [2, 3, 5])])

    grid = np.linspace(0.1, 2 * np.pi * 40.0, 500)  # first three roots lie below 40 Hz
    d = np.array([det(o) for o in grid])
    roots = []
    for k in np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0][:n]:
        from scipy.optimize import brentq

        roots.append(brentq(det, grid[k], grid[k + 1], xtol=1e-12) / (2 * np.pi))
    return np.array(roots)


def test_coupled_bending_torsion_cg_offset():
    L, EI, GJ, m, cy = 10.0, 1e6, 5e5, 10.0, 0.15
    Ixx = 0.5 + m * cy**2  # about the reference axis
    # Izz_mass >= m cy^2 keeps the section mass positive semi-definite (rotation about z moves
    # the offset mass axially)
    sec = BeamSection.from_properties(EA=1e10, EIy=EI, EIz=1e3 * EI, GJ=GJ, mass_per_length=m, Ixx_mass=Ixx,
                                      Izz_mass=m * cy**2, cg=(cy, 0.0))
    md = modes(assemble(cantilever(ne=40, section=sec)), n=4)
    ref = coupled_bt_freqs(EI, GJ, m, Ixx, cy, L, n=3)
    # the uncoupled values (1.77, 11.09, 25.0 Hz) move by 1-10 %; 40 elements: torsion-like modes
    # carry the O(h^2) twist-interpolation error (~1e-4); allow 1e-3
    np.testing.assert_allclose(md.freq[:3], ref, rtol=1e-3)
    unc = np.array([1.8751**2 / L**2 * np.sqrt(EI / m), 4.6941**2 / L**2 * np.sqrt(EI / m)]) / (2 * np.pi)
    assert np.max(np.abs(ref[:2] / unc - 1)) > 5e-3  # coupling is visible (test can fail)


def test_bend_twist_coupled_section_static():
    """6x6 section with bending(kappa_y)-twist coupling g: tip load and tip torque vs closed form."""
    L, EIy, GJ, g = 10.0, 1e6, 5e5, 3e5
    C = np.diag([1e10, 1e9, 1e9, GJ, EIy, 1e6])
    C[3, 4] = C[4, 3] = g
    sec = BeamSection(stiffness=C, mass=np.diag([10.0, 10, 10, 0.5, 0.1, 0.1]))
    fe = cantilever(ne=5, section=sec)
    st = assemble(fe)
    from windflutter.structure import static_solve

    S = np.linalg.inv(np.array([[GJ, g], [g, EIy]]))  # compliance of (twist rate, kappa_y)
    tip = 6 * 5
    Fz, Tq = 1e3, 2e3
    F = np.zeros((st.n_dof, 2))
    F[tip + 2, 0] = Fz
    F[tip + 3, 1] = Tq
    u = static_solve(st, F)
    # tip force: My(x) = -Fz (L - x); w'' = -kappa_y; twist rate = S01 My
    # + shear deflection Fz L / GAz
    assert u[tip + 2, 0] == pytest.approx(S[1, 1] * Fz * L**3 / 3 + Fz * L / C[2, 2], rel=1e-8)
    assert u[tip + 3, 0] == pytest.approx(-S[0, 1] * Fz * L**2 / 2, rel=1e-6)
    # tip torque: twist = S00 T L, kappa_y = S10 T -> theta_y(L) = S10 T L, w(L) = -S10 T L^2 / 2
    assert u[tip + 3, 1] == pytest.approx(S[0, 0] * Tq * L, rel=1e-6)
    assert u[tip + 2, 1] == pytest.approx(-S[1, 0] * Tq * L**2 / 2, rel=1e-6)
    assert abs(u[tip + 3, 0]) > 1e-3 * abs(u[tip + 2, 0]) / L  # coupling present


def test_beam_mesh_convergence_order():
    # bending with Hermite mass + exact stiffness: observed order ~4 (errors of mode 3)
    L, EI, m = 10.0, 1e6, 10.0
    f3 = BETA_L[2] ** 2 / L**2 * np.sqrt(EI / m) / (2 * np.pi)
    errs = []
    for ne in (4, 8, 16):
        fe = cantilever(ne=ne)
        fe.beam_sections = [BeamSection.from_properties(EA=1e9, EIy=EI, EIz=100 * EI, GJ=1e9, mass_per_length=m,
                                                        Ixx_mass=0.5)]
        f = modes(assemble(fe), n=4).freq
        errs.append(np.min(np.abs(f - f3)) / f3)
    p = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(p > 3.5), (errs, p)


def test_tension_centre_offset_coupling():
    """EA acting at y = e from the reference axis: C = [[EA, -EA e], [-EA e, EIz_c + EA e^2]] on
    (axial strain, kappa_z).  An axial tip force P at the reference axis bends the beam:
    kappa_z = P e / EIz_c, v(L) = P e L^2 / (2 EIz_c), u(L) = P L (1/EA + e^2/EIz_c)."""
    L, EA, EIz, e, P = 10.0, 1e8, 1e6, 0.2, 1e4
    C = np.diag([EA, 1e9, 1e9, 5e5, 1e6, EIz + EA * e**2])
    C[0, 5] = C[5, 0] = -EA * e
    fe = cantilever(ne=4, section=BeamSection(stiffness=C, mass=np.diag([10.0, 10, 10, 0.5, 0.1, 0.1])))
    st = assemble(fe)
    from windflutter.structure import static_solve

    F = np.zeros(st.n_dof)
    F[6 * 4] = P
    u = static_solve(st, F).reshape(-1, 6)
    assert u[4, 1] == pytest.approx(P * e * L**2 / (2 * EIz), rel=1e-8)
    assert u[4, 5] == pytest.approx(P * e * L / EIz, rel=1e-8)
    assert u[4, 0] == pytest.approx(P * L * (1 / EA + e**2 / EIz), rel=1e-8)
