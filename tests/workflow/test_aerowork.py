"""Aero-work diagnostic: W = pi Im(x^H f) against a time-domain integral, and its physics on a
Theodorsen typical section (zero at the flutter speed, negative below, positive above)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import toy_analyser as toy
from windflutter.post.aerowork import (
    harmonic_force,
    normalise_mode,
    section_work,
    to_section_dofs,
    total_work,
    work_per_dof,
)


def _time_domain_work(x_hat, f_hat, omega, n=4096):
    """int_0^T f(t) . xdot(t) dt by the trapezoid rule over one period (exact to rounding for
    trigonometric polynomials of degree < n)."""
    t = np.arange(n) * (2 * np.pi / omega) / n
    e = np.exp(1j * omega * t)
    f = np.real(f_hat[:, None] * e)
    xdot = np.real(1j * omega * x_hat[:, None] * e)
    return np.sum(f * xdot, axis=1) * (2 * np.pi / omega) / n


def test_formula_matches_time_integral():
    rng = np.random.default_rng(7)
    n, omega = 5, 3.7
    x = rng.normal(size=n) + 1j * rng.normal(size=n)
    Ma, Da, Ka = (rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n)) for _ in range(3))
    f = harmonic_force(x, omega, Ma, Da, Ka)
    np.testing.assert_allclose(f, (-omega**2 * Ma + 1j * omega * Da + Ka) @ x)
    per_dof = _time_domain_work(x, f, omega)
    # agreement to rounding: the quadrature is exact for these harmonics
    np.testing.assert_allclose(work_per_dof(x, f), per_dof, rtol=1e-10, atol=1e-10 * np.abs(per_dof).max())
    assert total_work(x, -omega**2 * Ma + 1j * omega * Da + Ka) == pytest.approx(per_dof.sum(), rel=1e-10)


def test_conservative_forces_do_no_work():
    # a real symmetric stiffness/mass-like A and a pure viscous damper: zero and -pi omega c |x|^2
    rng = np.random.default_rng(3)
    x = rng.normal(size=4) + 1j * rng.normal(size=4)
    S = rng.normal(size=(4, 4))
    assert abs(total_work(x, S + S.T)) < 1e-12 * np.linalg.norm(S) * np.vdot(x, x).real
    c, omega = 2.5, 1.3
    # f = -c xdot  ->  W = -pi omega c |x|^2 (energy taken out each cycle)
    assert total_work(x, -1j * omega * c * np.eye(4)) == pytest.approx(-np.pi * omega * c * np.vdot(x, x).real)


def test_section_projection_is_work_conjugate():
    rng = np.random.default_rng(5)
    ns = 4
    e1 = np.tile([0.0, 0.0, 1.0], (ns, 1))
    e2 = np.tile([0.0, 1.0, 0.0], (ns, 1))
    e3 = np.tile([1.0, 0.0, 0.0], (ns, 1))
    u6 = rng.normal(size=(ns, 6)) + 1j * rng.normal(size=(ns, 6))
    # forces only along the three section DOF directions -> the 6-DOF work equals the 3-DOF work
    f3 = rng.normal(size=(ns, 3)) + 1j * rng.normal(size=(ns, 3))
    f6 = np.zeros((ns, 6), complex)
    f6[:, 2], f6[:, 4], f6[:, 0] = f3[:, 0], f3[:, 1], f3[:, 2]
    w3 = section_work(to_section_dofs(u6, e1, e2, e3), to_section_dofs(f6, e1, e2, e3))
    assert w3.sum() == pytest.approx(work_per_dof(u6, f6).sum(), rel=1e-12)


def _flutter_branch(U):
    """The p-k torsion branch of the toy section at relative speed U: (lambda, q)."""
    return toy.pk_mode(U, toy.OMEGA_A, 2 * math.pi)


def test_typical_section_work_changes_sign_at_flutter():
    U_f = brentq(lambda U: _flutter_branch(U)[0].real, 20.0, 200.0, xtol=1e-10)
    M, _ = toy.section_matrices()
    vals = {}
    for s in (0.9, 1.0, 1.1):
        lam, q = _flutter_branch(s * U_f)
        q = normalise_mode(q)
        omega = lam.imag
        A = toy.harmonic_aero(s * U_f, omega)
        W = total_work(q, A)
        # scale: kinetic-energy amplitude x 2 pi; W / E is the energy gained per cycle (-)
        E = np.pi * omega**2 * np.vdot(q, M @ q).real
        # per-DOF split adds up to the total
        w_dof = work_per_dof(q, A @ q)
        assert w_dof.sum() == pytest.approx(W, rel=1e-9, abs=1e-12 * E)
        vals[s] = (W / E, lam.real / omega)
    # at the onset the undamped section's flutter mode takes no net energy from the air; the
    # tolerance is set by the onset tolerance (xtol on U) times dW/dU, far below 1e-6
    assert abs(vals[1.0][0]) < 1e-6
    assert vals[0.9][0] < -1e-3 and vals[1.1][0] > 1e-3          # sign follows the stability
    assert np.sign(vals[0.9][0]) == np.sign(vals[0.9][1]) and np.sign(vals[1.1][0]) == np.sign(vals[1.1][1])


def test_normalise_mode():
    q = np.array([0.5j, -2.0 + 0j, 1.0])
    n = normalise_mode(q)
    assert n[1] == 1.0 and abs(n[0]) == pytest.approx(0.25)
    assert normalise_mode(q, np.array([True, False, False]))[0] == 1.0
