"""The co-rotational beam linearized about a large deflection, against geometrically exact references.

References that share nothing with the element (structure/corotational.py):
- the elastica of a cantilever under a dead tip force (closed form in elliptic integrals, Bisshopp &
  Drucker 1945, *Q. Appl. Math.* 3:272);
- the lateral-torsional buckling load of a cantilever with a tip force at the centroid,
  ``P_cr = 4.0126 sqrt(EI_lat GJ) / L^2`` (Timoshenko & Gere 1961, *Theory of Elastic Stability*,
  sec. 6.5: 4.013);
- a discrete Kirchhoff rod (kirchhoff_chain.py: rigid links, joint rotations through the matrix
  logarithm, Newton on its potential, its Hessian and lumped mass), for the frequencies of the
  linearized vibrations about bent and bent-and-twisted equilibria.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp
from kirchhoff_chain import Chain
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation
from scipy.special import ellipeinc, ellipkinc
from test_beam import cantilever

from windflutter.errors import InputError
from windflutter.structure import assemble, geometric_stiffness, static_solve
from windflutter.structure.corotational import (BeamConfiguration, beam_tangent, chained_configuration,
                                                 deformed_model, displaced, linear_configuration,
                                                 reference_configuration, solve_equilibrium)
from windflutter.structure.fem import BeamSection
from windflutter.structure.prestress import buckling_factors

L, EI_F, EI_E, GJ, M_L, I_P, I_F, I_E = 10.0, 1e6, 4e6, 5e5, 10.0, 0.5, 0.02, 0.08


def blade_like(ne=20, EA=1e10):
    """Cantilever along x: flap (z) weak, edge (y) four times stiffer, torsion GJ; nearly
    inextensible and shear-rigid, like the Kirchhoff rod."""
    sec = BeamSection.from_properties(EA=EA, EIy=EI_F, EIz=EI_E, GJ=GJ, mass_per_length=M_L, Ixx_mass=I_P,
                                      Iyy_mass=I_F, Izz_mass=I_E)
    return cantilever(ne=ne, L=L, section=sec)


def tip_load(fe, P, arm=(0.0, 0.0, 0.0)):
    """``external`` of a dead force ``P`` at the tip node through a rigid ``arm`` (reference axes) fixed
    to it: force P and moment ``(R a) x P``; stiffness the minus Hessian of ``-P . R a``."""
    tip = fe.n_nodes - 1
    P, arm = np.asarray(P, float), np.asarray(arm, float)

    def external(config, factor):
        f = np.zeros(fe.n_dof)
        b = config.R[tip] @ arm
        Pf = factor * P
        f[6 * tip:6 * tip + 3], f[6 * tip + 3:6 * tip + 6] = Pf, np.cross(b, Pf)
        K = np.zeros((fe.n_dof, fe.n_dof))
        K[6 * tip + 3:6 * tip + 6, 6 * tip + 3:6 * tip + 6] = 0.5 * (np.outer(Pf, b) + np.outer(b, Pf)) - (Pf @ b) * np.eye(3)
        return f, sp.csr_matrix(K)

    return external


def frequencies(K, M, T, k=8):
    Kr, Mr = (np.asarray((T.T @ A @ T).todense()) for A in (K, M))
    w2 = sla.eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T), eigvals_only=True, subset_by_index=[0, k - 1])
    return np.sqrt(np.abs(w2)) / (2 * np.pi)


def elastica_tip(alpha):
    """Tip (x/L, z/L) of a cantilever under a dead tip force normal to it, ``alpha = P L^2 / EI``:
    ``kL = K(p) - F(phi1, p)``, ``sin phi1 = 1 / (sqrt 2 p)``, ``z/L = 1 - 2 (E(p) - E(phi1, p)) / kL``,
    ``x/L = sqrt(2 (2 p^2 - 1)) / kL``."""
    kL = np.sqrt(alpha)

    def phi1(p):
        return np.arcsin(1.0 / (np.sqrt(2.0) * p))

    p = brentq(lambda p: ellipkinc(np.pi / 2, p * p) - ellipkinc(phi1(p), p * p) - kL, 1 / np.sqrt(2) + 1e-12, 1 - 1e-12)
    z = 1.0 - 2.0 / kL * (ellipeinc(np.pi / 2, p * p) - ellipeinc(phi1(p), p * p))
    return np.sqrt(2.0 * (2.0 * p * p - 1.0)) / kL, z


def chain(n=60):
    return Chain(L, n, (GJ, EI_F, EI_E), M_L, (I_P, I_F, I_E))


# -- the element at rest and for small motions -------------------------------------------------------
def test_reference_configuration_is_the_linear_element():
    """At the undeformed configuration without stress: K_mat is the linear element's stiffness, no
    geometric part, no internal force (oblique axis and twisted section frame).  The derivatives are
    central differences: 1e-7 relative."""
    fe = cantilever(ne=6, axis=(1.0, 2.0, -0.5), orient=(0.0, 0.3, 1.0),
                    section=BeamSection.from_properties(EA=1e9, EIy=1e6, EIz=4e6, GJ=5e5, mass_per_length=10.0))
    K = assemble(fe).K.toarray()
    t = beam_tangent(fe, reference_configuration(fe))
    assert np.abs(t.K_mat.toarray() - K).max() <= 1e-7 * np.abs(K).max()
    assert np.abs(t.K_geo.toarray()).max() <= 1e-7 * np.abs(K).max()
    assert np.abs(t.f_int).max() <= 1e-7 * np.abs(K).max() * 1e-4


def test_axial_initial_stress_is_the_hermite_matrix():
    """With an axial force alone, the initial-stress matrix of all resultants (``moments=True``) is the
    element's Hermite ``N int (v'^2 + w'^2)`` (string term of the chord plus the bowing term): 1e-6."""
    fe = cantilever(ne=8, axis=(1.0, 2.0, -0.5), orient=(0.0, 0.0, 1.0))
    st = assemble(fe)
    F = np.zeros(st.n_dof)
    F[6 * 8:6 * 8 + 3] = 1e5 * np.array([1.0, 2.0, -0.5]) / np.linalg.norm([1.0, 2.0, -0.5])
    u = static_solve(st, F)
    K0, K1 = geometric_stiffness(fe, u).toarray(), geometric_stiffness(fe, u, moments=True).toarray()
    assert np.abs(K1 - K0).max() <= 1e-6 * np.abs(K0).max()


def test_tangent_is_the_hessian_of_the_strain_energy():
    """At a strongly deformed, unbalanced configuration (rotations ~0.1 rad, stretch): the tangent and
    the internal forces against second and first differences of the total strain energy
    ``sum 1/2 d^T K_loc d`` over all DOFs at once, rotations composed with SciPy's exponential (step
    1e-5; 1e-6 of the largest entry)."""
    from windflutter.structure.corotational import _Elements

    fe = blade_like(ne=3, EA=1e8)
    el = _Elements(fe)
    cfg = linear_configuration(fe, 0.05 * np.random.default_rng(1).normal(size=fe.n_dof))
    t = beam_tangent(fe, cfg)

    def energy(du):  # du (..., n_dof): every perturbation at once
        du = du.reshape(du.shape[:-1] + (-1, 6))
        x = cfg.x + du[..., :3]
        R = Rotation.from_rotvec(du[..., 3:].reshape(-1, 3)).as_matrix().reshape(du.shape[:-1] + (3, 3)) @ cfg.R
        a, b = el.conn[:, 0], el.conn[:, 1]
        d = el.deformation(x[..., b, :] - x[..., a, :], R[..., a, :, :], R[..., b, :, :])[0]
        return 0.5 * np.einsum("...ei,eij,...ej->...", d, el.K_loc, d)

    n, h = fe.n_dof, 1e-5
    E = np.eye(n) * h
    g = (energy(E) - energy(-E)) / (2 * h)
    assert np.abs(g - t.f_int).max() <= 1e-6 * np.abs(g).max()
    Ei, Ej = E[:, None, :], E[None, :, :]
    H = (energy(Ei + Ej) - energy(Ei - Ej) - energy(-Ei + Ej) + energy(-Ei - Ej)) / (4 * h * h)
    K = t.K.toarray()
    assert np.abs(H - K).max() <= 1e-6 * np.abs(K).max()


def test_chained_configuration_is_a_first_order_displacement():
    """The length-keeping update agrees with the plain one to first order (difference O(u^2))."""
    fe = blade_like(ne=5)
    u = np.random.default_rng(2).normal(size=fe.n_dof)
    diffs = []
    for s in (1e-3, 1e-4):
        a, b = chained_configuration(fe, s * u), linear_configuration(fe, s * u)
        diffs.append(np.abs(a.x - b.x).max() + np.abs(a.R - b.R).max())
    assert diffs[1] < 0.02 * diffs[0]  # quadratic: 1e-2 for a tenfold smaller u


def test_bad_configuration_is_an_input_error():
    fe = blade_like(ne=4)
    with pytest.raises(InputError, match="configuration"):
        beam_tangent(fe, BeamConfiguration(x=np.zeros((3, 3)), R=np.zeros((3, 3, 3))))
    with pytest.raises(InputError, match="resultants"):
        beam_tangent(fe, reference_configuration(fe), resultants=np.zeros((2, 12)))


# -- the initial-stress matrix of bending -------------------------------------------------------------
def test_lateral_torsional_buckling_of_a_cantilever():
    """A narrow cantilever (EI_lateral 1e-3 of EI in the load plane) under a tip force at the centroid
    buckles sideways in bending and torsion at ``4.0126 sqrt(EI_lat GJ) / L^2`` (Timoshenko & Gere).
    Linear buckling with the initial-stress matrix of the bending moments (``moments=True``):
    measured +0.15 % with 20 elements, Richardson (10, 20) within 2e-5; tolerances 0.3 % and 1e-4.
    The axial-force matrix alone finds no buckling (the test can fail)."""
    out = []
    for ne in (10, 20):
        fe = cantilever(ne=ne, L=L, section=BeamSection.from_properties(EA=1e11, EIy=1e9, EIz=EI_F, GJ=GJ,
                                                                       mass_per_length=M_L, Ixx_mass=I_P))
        st = assemble(fe)
        F = np.zeros(st.n_dof)
        F[6 * ne + 2] = 1.0
        u = static_solve(st, F)
        lam, _ = buckling_factors(st, geometric_stiffness(fe, u, moments=True), n=1)
        out.append(lam[0] * L**2 / np.sqrt(EI_F * GJ))
        if ne == 10:
            assert buckling_factors(st, geometric_stiffness(fe, u), n=1)[0].size == 0
    assert out[1] == pytest.approx(4.0126, rel=3e-3)
    assert out[1] + (out[1] - out[0]) / 3.0 == pytest.approx(4.0126, rel=1e-4)


# -- large deflection -------------------------------------------------------------------------------
def test_the_rod_reference_is_the_elastica_and_the_straight_cantilever():
    """The reference itself: its tip under PL^2/EI = 1 and 2 against the elliptic-integral elastica
    (measured 4e-5 and 6e-5 of L with 60 links, O(h^2); tolerance 1e-4); its frequencies at rest
    against the Euler-Bernoulli cantilever (1.8751^2 sqrt(EI/m) / (2 pi L^2), flap and edge) and the
    torsion rod (sqrt(GJ / I_p) / 4L), without bending rotary inertia: measured 8e-5, tolerance 2e-4."""
    for alpha in (1.0, 2.0):
        x, z = elastica_tip(alpha)
        tip = chain().solve((0.0, 0.0, alpha * EI_F / L**2), steps=3).tip() / L
        assert abs(tip[0] - x) < 1e-4 and abs(tip[2] - z) < 1e-4
    f = Chain(L, 60, (GJ, EI_F, EI_E), M_L, (I_P, 0.0, 0.0)).frequencies(6)
    fb = 1.87510407**2 / L**2 * np.sqrt(EI_F / M_L) / (2 * np.pi)
    np.testing.assert_allclose(f[[0, 1, 4]], [fb, 2 * fb, np.sqrt(GJ / I_P) / (4 * L)], rtol=2e-4)


@pytest.fixture(scope="module")
def bent():
    """Flap tip force PL^2/EI_flap = 1.5 (tip slope 0.6 rad): the FE equilibrium (20 elements) and the
    rod (60 links)."""
    fe = blade_like()
    P = np.array([0.0, 0.0, 1.5 * EI_F / L**2])
    eq = solve_equilibrium(fe, assemble(fe).T, tip_load(fe, P))
    return fe, P, eq, chain().solve(P, steps=3)


def test_co_rotational_equilibrium_is_the_elastica(bent):
    """Newton on the co-rotational beam reaches the elastica's tip to 2e-5 L (measured 5e-7)."""
    fe, _, eq, _ = bent
    x, z = elastica_tip(1.5)
    assert np.abs(eq.config.x[-1] / L - [x, 0.0, z]).max() < 2e-5


def test_frequencies_about_the_bent_cantilever(bent):
    """Linearized vibrations about the bent equilibrium: the 8 lowest frequencies (flap in the bending
    plane; edge bending coupled with torsion by the deflection out of it) against the Kirchhoff rod.
    Measured within 9e-4 (20 elements; the rod's own discretization error 4e-4); tolerance 0.3 %.
    The linearization on the undeformed axis (axial prestress only, ``structure="undeformed"``) is
    2-17 % off; a stress-free beam built in the bent shape (the curvature coupling without the
    initial stress) matches the rod made stress-free in its bent shape (1.4e-3; tolerance 0.3 %) and
    is itself up to 12 % off the loaded one: the bending stress cancels part of the curvature
    coupling."""
    fe, P, eq, rod = bent
    st = assemble(fe)
    fe_d = deformed_model(fe, eq.config)
    st_d = assemble(fe_d)
    f = frequencies(eq.tangent.K - eq.K_ext, st_d.M, st.T)
    ref = rod.frequencies(8)
    np.testing.assert_allclose(f, ref, rtol=3e-3)
    u = static_solve(st, np.asarray(tip_load(fe, P)(reference_configuration(fe), 1.0)[0]))
    f_und = frequencies(st.K + geometric_stiffness(fe, u), st.M, st.T)
    assert np.abs(f_und / ref - 1).max() > 0.05
    f_free = frequencies(st_d.K, st_d.M, st_d.T)
    ref_free = Chain(L, rod.n, rod.C, rod.m, rod.J).solve(P, steps=3).freeze_shape().frequencies(8)
    np.testing.assert_allclose(f_free, ref_free, rtol=3e-3)
    assert np.abs(f_free / ref - 1).max() > 0.05


def test_frequencies_about_a_bent_and_twisted_cantilever():
    """The tip force through an arm of 0.05 L along the chord (y) bends and twists the beam (tip twist
    0.09 rad from the steady torsion moment P a): all resultants are non-zero.  Frequencies against
    the rod (the same load, its arm fixed to the last link): measured 6.5e-4, tolerance 0.3 % (the
    undeformed linearization: 15 %); the arm's end point: 1e-5 L, tolerance 2e-4 L."""
    fe = blade_like()
    P, arm = np.array([0.0, 0.0, 1.0 * EI_F / L**2]), np.array([0.0, 0.05 * L, 0.0])
    eq = solve_equilibrium(fe, assemble(fe).T, tip_load(fe, P, arm), load_steps=2)
    rod = chain().solve(P, arm=arm, steps=3)
    tip = eq.config.x[-1] + eq.config.R[-1] @ arm
    assert np.abs(tip - rod.tip()).max() < 2e-4 * L
    f = frequencies(eq.tangent.K - eq.K_ext, assemble(deformed_model(fe, eq.config)).M, assemble(fe).T)
    np.testing.assert_allclose(f, rod.frequencies(8), rtol=3e-3)
