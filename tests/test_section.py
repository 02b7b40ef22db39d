"""Typical-section flutter and divergence: published cases, method agreement, limits, input."""

import math

import numpy as np
import pytest

from windflutter.aero.theodorsen import jones, jones_rfa, theodorsen
from windflutter.errors import InputError
from windflutter.section import (
    TypicalSection,
    aero_matrices,
    divergence_speed,
    divergence_speed_numerical,
    k_method,
    natural_frequencies,
    p_method,
    pk_eigen,
    pk_method,
    rfa_state_matrix,
    section_from_config,
    structural_matrices,
)

# Lee, Price & Wong, "Nonlinear aeroelastic analysis of airfoils: bifurcation and chaos",
# Prog. Aerosp. Sci. 35 (1999) 205-334 (and Lee, Jiang & Wong, J. Fluids Struct. 13 (1999)):
# mu = 100, a_h = -1/2, x_alpha = 1/4, r_alpha = 1/2, omega_bar = 0.2, no structural damping,
# Wagner function with R.T. Jones' coefficients: linear flutter speed U* = U/(b w_a) = 6.2851.
LEE = dict(semi_chord=1.0, elastic_axis=-0.5, mass_ratio=100.0, x_alpha=0.25,
           r_alpha_squared=0.25, omega_h=0.2, omega_alpha=1.0)
LEE_U_STAR = 6.2851

# Hodges & Pierce (2011) sec. 5.5 example section: mu = 20, a = -1/5, e = -1/10 (x_alpha = 1/10),
# r^2 = 6/25, sigma = omega_h/omega_a = 2/5.
HP = dict(semi_chord=1.0, elastic_axis=-0.2, mass_ratio=20.0, x_alpha=0.1,
          r_alpha_squared=6 / 25, omega_h=0.4, omega_alpha=1.0)


def _sec(**kw):
    return TypicalSection.from_nondimensional(**kw)


def bah_flutter(mu, a, xa, r2, sig, cfun=theodorsen):
    """INDEPENDENT reference: the classical flutter determinant in Theodorsen's coefficients
    (Bisplinghoff, Ashley & Halfman 1955, sec. 9-6; L_h = 1 - 2iC/k, L_a = 1/2 - i(1+2C)/k
    - 2C/k^2, M_h = 1/2, M_a = 3/8 - i/k), solved as a quadratic in X = (w_a/w)^2 (1 + i g),
    with g = 0 located by bisection in k.  Returns U/(b w_a), w/w_a."""

    def roots(k):
        C = complex(np.asarray(cfun(k)))
        Lh = 1 - 2j * C / k
        La = 0.5 - 1j * (1 + 2 * C) / k - 2 * C / k**2
        Mh, Ma = 0.5, 3 / 8 - 1j / k
        e = a + 0.5
        A11, B11 = mu + Lh, -mu * sig**2
        A22, B22 = mu * r2 + Ma - (La + Mh) * e + Lh * e**2, -mu * r2
        off = (mu * xa + La - Lh * e) * (mu * xa + Mh - Lh * e)
        return np.roots([B11 * B22, A11 * B22 + B11 * A22, A11 * A22 - off])

    ks = np.geomspace(3.0, 0.02, 3000)
    g_prev = None
    for k in ks:
        X = roots(k)
        g = np.sort(X.imag / X.real)
        if g_prev is not None and g_prev[1] < 0 <= g[1]:
            lo, hi = k, k_prev
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                gm = np.sort(roots(mid).imag / roots(mid).real)[1]
                lo, hi = (mid, hi) if gm >= 0 else (lo, mid)
            X = roots(0.5 * (lo + hi))
            j = np.argmax(X.imag / X.real)
            w = 1 / math.sqrt(X[j].real)
            return w / (0.5 * (lo + hi)), w
        g_prev, k_prev = g, k
    return None, None


def test_lee_price_wong_published_flutter_speed():
    sec = _sec(**LEE)
    # p-method on the state space with Jones' 2-pole C(k) = the paper's model
    rp = p_method(sec, rfa=jones_rfa())
    # p-k with the same rational C(k)
    rpk = pk_method(sec, c_func=jones)
    # published value has 5 significant digits: relative rounding 8e-6 -> tolerance 2e-5
    assert rp.flutter_speed == pytest.approx(LEE_U_STAR, rel=2e-5)
    assert rpk.flutter_speed == pytest.approx(LEE_U_STAR, rel=2e-5)


def test_flutter_against_independent_determinant():
    for case in (HP, LEE):
        sec = _sec(**case)
        u_ref, w_ref = bah_flutter(case["mass_ratio"], case["elastic_axis"], case["x_alpha"],
                                   case["r_alpha_squared"], case["omega_h"])
        r = pk_method(sec)
        # same physics, two independent formulations: agreement limited by the bisection (1e-9)
        assert r.flutter_speed == pytest.approx(u_ref, rel=1e-7)
        assert r.flutter_frequency == pytest.approx(w_ref, rel=1e-7)
    # recorded values (docs/typical_section.md): HP 2.18391, LEE exact Theodorsen 6.25662
    assert pk_method(_sec(**HP)).flutter_speed == pytest.approx(2.18391, abs=1e-5)


def test_k_pk_p_agree_at_flutter():
    for case in (HP, LEE):
        sec = _sec(**case)
        rk, rpk, rp = k_method(sec), pk_method(sec), p_method(sec)
        # k and p-k are both exact at neutral stability: agree to root-finding tolerance
        assert rk.flutter_speed == pytest.approx(rpk.flutter_speed, rel=1e-7)
        assert rk.flutter_frequency == pytest.approx(rpk.flutter_frequency, rel=1e-7)
        assert rk.reduced_frequency == pytest.approx(rpk.reduced_frequency, rel=1e-7)
        # p-method with the 4-pole Roger RFA: issue 2 requires 1 %; we get ~0.04 %
        assert rp.flutter_speed == pytest.approx(rpk.flutter_speed, rel=1e-2)
        assert rp.flutter_speed == pytest.approx(rpk.flutter_speed, rel=2e-3)
        assert rp.flutter_frequency == pytest.approx(rpk.flutter_frequency, rel=2e-3)
        # flutter modes agree (normalised identically)
        assert np.allclose(rk.flutter_mode, rpk.flutter_mode, atol=1e-6)


def test_p_method_state_space_matches_pk_for_rational_c():
    # with the SAME rational C(k) both are exact at sigma = 0: checks the lag-state realisation
    sec = _sec(**HP)
    rp = p_method(sec, rfa=jones_rfa())
    rpk = pk_method(sec, c_func=jones)
    assert rp.flutter_speed == pytest.approx(rpk.flutter_speed, rel=1e-8)


def test_flutter_mode_solves_flutter_equation():
    sec = _sec(**HP)
    r = pk_method(sec)
    w, U = r.flutter_frequency, r.flutter_speed
    M, K = structural_matrices(sec)
    Ma, Da, Ka = aero_matrices(sec, U, k=r.reduced_frequency)
    s = 1j * w
    Z = (M - Ma) * s**2 - Da * s + (K - Ka)
    v = np.array([-r.flutter_mode[0], r.flutter_mode[1]])  # back to h positive down
    assert np.linalg.norm(Z @ v) < 1e-8 * np.linalg.norm(Z) * np.linalg.norm(v)


def test_bracket_and_root_find_not_stepping():
    # a coarse speed grid must give the same flutter speed as a fine one
    sec = _sec(**HP)
    fine = pk_method(sec).flutter_speed
    coarse = pk_method(sec, speeds=np.array([0.5, 1.5, 2.5, 3.5])).flutter_speed
    assert coarse == pytest.approx(fine, rel=1e-9)


def test_divergence_closed_form_and_numerical():
    sec = _sec(**HP)
    # U_D/(b w_a) = sqrt(mu r^2 / (2 (a + 1/2))) = sqrt(8) for the HP section
    assert divergence_speed(sec) == pytest.approx(math.sqrt(8.0), rel=1e-12)
    assert divergence_speed_numerical(sec) == pytest.approx(math.sqrt(8.0), rel=1e-10)
    # lift slope replaces 2 pi: U_D scales with (2 pi / Cla)^(1/2)
    sec2 = TypicalSection.from_nondimensional(**HP, lift_slope=5.7)
    assert divergence_speed(sec2) == pytest.approx(math.sqrt(8.0 * 2 * math.pi / 5.7), rel=1e-12)
    assert divergence_speed_numerical(sec2) == pytest.approx(divergence_speed(sec2), rel=1e-10)
    # no divergence with the elastic axis at or ahead of the quarter chord
    for a in (-0.5, -0.7):
        s = TypicalSection.from_nondimensional(**{**HP, "elastic_axis": a})
        assert divergence_speed(s) is None and divergence_speed_numerical(s) is None


def test_divergence_from_dynamic_eigenproblem():
    # a real eigenvalue of the RFA state space crosses zero exactly at U_D (C(0)=1 exactly)
    sec = _sec(**HP)
    from windflutter.aero.theodorsen import theodorsen_rfa

    rfa = theodorsen_rfa()
    ud = divergence_speed(sec)

    def max_real_root(U):
        lam = np.linalg.eigvals(rfa_state_matrix(sec, U, rfa))
        real = lam[np.abs(lam.imag) < 1e-9]
        return real.real.max()

    assert max_real_root(ud * 0.999) < 0 < max_real_root(ud * 1.001)


def test_no_aero_gives_structural_frequencies():
    sec = TypicalSection(semi_chord=0.5, elastic_axis=-0.3, mass=10.0, static_moment=0.4,
                         inertia=0.3, plunge_stiffness=4000.0, pitch_stiffness=900.0,
                         air_density=1e-12)
    # closed form: det(K - w^2 M) = 0 -> quadratic in w^2
    m, S, I, kh, ka = 10.0, 0.4, 0.3, 4000.0, 900.0
    A, B, C = m * I - S * S, -(kh * I + ka * m), kh * ka
    w2 = np.sort(np.roots([A, B, C]).real)
    assert np.allclose(natural_frequencies(sec), np.sqrt(w2), rtol=1e-12)
    for mode, w in enumerate(np.sqrt(w2)):
        lam, _, _ = pk_eigen(sec, 50.0, 1j * w)
        assert lam.imag == pytest.approx(w, rel=1e-9) and abs(lam.real) < 1e-9 * w
    # uncoupled (S = 0) frequencies are sqrt(K/M)
    s0 = TypicalSection(0.5, -0.3, 10.0, 0.0, 0.3, 4000.0, 900.0, air_density=1e-12)
    assert np.allclose(natural_frequencies(s0), [20.0, math.sqrt(3000.0)])


def test_quasi_steady_vs_exact():
    sec = _sec(**LEE)
    qs = pk_method(sec, c_func=lambda k: 1.0)
    ex = pk_method(sec)
    u_ref, _ = bah_flutter(100.0, -0.5, 0.25, 0.25, 0.2, cfun=lambda k: 1.0)
    # quasi-steady p-k vs the independent determinant with C = 1
    assert qs.flutter_speed == pytest.approx(u_ref, rel=1e-7)
    # without the circulatory lag the flutter speed here is ~24 % lower (4.77 vs 6.26)
    assert qs.flutter_speed < 0.85 * ex.flutter_speed
    assert ex.flutter_speed == pytest.approx(6.25662, abs=1e-5)


def test_dimensional_nondimensional_roundtrip():
    sec = TypicalSection(semi_chord=1.35, elastic_axis=-0.25, mass=138.9, static_moment=5.0,
                         inertia=27.7, plunge_stiffness=2.7e3, pitch_stiffness=3.5e5)
    back = TypicalSection.from_nondimensional(
        semi_chord=1.35, elastic_axis=-0.25, mass_ratio=sec.mass_ratio, x_alpha=sec.x_alpha,
        r_alpha_squared=sec.r_alpha_squared, omega_h=sec.omega_h, omega_alpha=sec.omega_alpha)
    for f in ("mass", "static_moment", "inertia", "plunge_stiffness", "pitch_stiffness"):
        assert getattr(back, f) == pytest.approx(getattr(sec, f), rel=1e-12)


GOOD_DIM = dict(semi_chord=1.0, elastic_axis=-0.2, mass=50.0, static_moment=5.0, inertia=10.0,
                plunge_stiffness=1e4, pitch_stiffness=1e5)


@pytest.mark.parametrize(
    "change,field",
    [
        ({"colour": "red"}, "colour"),
        ({"mass": None}, "mass"),
        ({"mass": -1.0}, "mass"),
        ({"mass": 0.0}, "mass"),
        ({"inertia": 0.4}, "inertia"),  # I m = 20 < S^2 = 25: r^2 <= x_alpha^2
        ({"semi_chord": float("nan")}, "semi_chord"),
        ({"pitch_stiffness": "stiff"}, "pitch_stiffness"),
        ({"pitch_stiffness": True}, "pitch_stiffness"),
        ({"mass_ratio": 20.0}, "mass_ratio"),  # mixed forms
        ({"air_density": 0.0}, "air_density"),
    ],
)
def test_config_errors_name_the_field(change, field):
    cfg = dict(GOOD_DIM)
    for k, v in change.items():
        if v is None:
            cfg.pop(k)
        else:
            cfg[k] = v
    with pytest.raises(InputError) as exc:
        section_from_config(cfg, source="x.yaml")
    assert exc.value.field == field
    assert field in str(exc.value) and "x.yaml" in str(exc.value)


def test_config_nondimensional_errors():
    good = dict(HP)
    assert section_from_config(good).mass_ratio == pytest.approx(20.0)
    with pytest.raises(InputError) as exc:
        section_from_config({**good, "r_alpha_squared": 0.01})
    assert exc.value.field == "r_alpha_squared"
    bad = dict(good)
    bad.pop("omega_h")
    with pytest.raises(InputError) as exc:
        section_from_config(bad)
    assert exc.value.field == "omega_h"
    with pytest.raises(InputError):
        section_from_config({**good, "mass_ratio": -3.0})
    with pytest.raises(InputError):
        section_from_config([1, 2, 3])


# Regression: frequency coalescence and p-k root-order swap within one grid cell (found by a
# randomised k vs p-k comparison); the bracket must be subdivided, not root-found on the jump.
SWAP = dict(semi_chord=1.0, elastic_axis=-0.3049935571944805, mass_ratio=158.091632056407,
            x_alpha=0.2843858799545832, r_alpha_squared=0.36141555579513257,
            omega_h=0.30866723271899754, omega_alpha=1.0)


@pytest.mark.parametrize("seed", [0, 1])
def test_k_and_pk_agree_on_random_sections(seed):
    rng = np.random.default_rng(seed)
    cases = [SWAP]
    for _ in range(3):
        xa = rng.uniform(-0.1, 0.4)
        cases.append(dict(semi_chord=1.0, elastic_axis=rng.uniform(-0.45, 0.3),
                          mass_ratio=rng.uniform(5, 200), x_alpha=xa,
                          r_alpha_squared=rng.uniform(max(1.2 * xa**2, 0.05), 0.6),
                          omega_h=rng.uniform(0.1, 1.5), omega_alpha=1.0))
    for case in cases:
        sec = _sec(**case)
        rk, rpk = k_method(sec), pk_method(sec)
        if rpk.flutter_speed is None:
            # p-k grid stops at 3 U_D: k may only find flutter beyond it
            assert rk.flutter_speed is None or rk.flutter_speed > rpk.max_speed
            continue
        assert rk.flutter_speed == pytest.approx(rpk.flutter_speed, rel=1e-7)


def test_apparent_mass_scaling_option():
    base = dict(semi_chord=0.5, elastic_axis=-0.3, mass=10.0, static_moment=0.4, inertia=0.3,
                plunge_stiffness=4000.0, pitch_stiffness=900.0, lift_slope=5.7)
    plain = TypicalSection(**base)
    scaled = TypicalSection(**base, scale_apparent_mass=True)
    Ma0, Da0, Ka0 = aero_matrices(plain, 30.0, C=1.0)
    Ma1, Da1, Ka1 = aero_matrices(scaled, 30.0, C=1.0)
    # apparent mass scales by Cla/2pi; stiffness (circulatory only) is unchanged
    assert np.allclose(Ma1, Ma0 * 5.7 / (2 * math.pi), rtol=1e-14)
    assert np.allclose(Ka1, Ka0, rtol=1e-14)
    # with Cla = 2 pi the option changes nothing
    b2 = {**base, "lift_slope": 2 * math.pi}
    assert np.allclose(aero_matrices(TypicalSection(**b2, scale_apparent_mass=True), 30.0, k=0.3)[1],
                       aero_matrices(TypicalSection(**b2), 30.0, k=0.3)[1], rtol=1e-14)
