"""The generalized-alpha integrator and the matrix-pencil identification against closed forms:
the damped oscillator's exact decay, a linear system with a first-order state against its
matrix exponential, the pendulum's amplitude-dependent period (elliptic integral), and
identification of synthetic damped sinusoids."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.special import ellipk

from windflutter.errors import InputError
from windflutter.simulate.identify import dominant, identify
from windflutter.simulate.integrator import algorithmic_damping, integrate, step_for_frequency


class Linear:
    """M q'' + C q' + K q + Fz z = 0, z' = Gq q + Gv q' + Gz z (all constant)."""

    def __init__(self, M, C, K, Fz=None, Gq=None, Gv=None, Gz=None):
        self.mass, self.C, self.K = (np.atleast_2d(np.asarray(x, float)) for x in (M, C, K))
        n = self.K.shape[0]
        m = 0 if Gz is None else np.atleast_2d(Gz).shape[0]
        self.Fz = np.zeros((n, m)) if Fz is None else np.atleast_2d(Fz)
        self.Gq = np.zeros((m, n)) if Gq is None else np.atleast_2d(Gq)
        self.Gv = np.zeros((m, n)) if Gv is None else np.atleast_2d(Gv)
        self.Gz = np.zeros((m, m)) if Gz is None else np.atleast_2d(Gz)

    def forces(self, t, q, v, z):
        return self.C @ v + self.K @ q + self.Fz @ z, self.Gq @ q + self.Gv @ v + self.Gz @ z

    def outputs(self, t, q, v, z):
        return np.concatenate([q, z])


def sdof_exact(t, w, zeta, x0):
    wd = w * np.sqrt(1 - zeta**2)
    return x0 * np.exp(-zeta * w * t) * (np.cos(wd * t) + zeta * w / wd * np.sin(wd * t))


@pytest.mark.parametrize("rho", [1.0, 0.8])
def test_damped_oscillator_second_order_convergence(rho):
    """Error against the exact decay over 5 periods falls as h^2 (ratio 4 per halving, 3-5
    allowed) and stays below the trapezoidal rule's phase error, (w h)^2 / 12 per radian: 1.0e-2
    rad after 5 periods at 100 steps per period (bound 1.2e-2 of the amplitude)."""
    w, zeta = 2 * np.pi, 0.02
    errs = []
    for n_per in (100, 200):
        model = Linear([[1.0]], [[2 * zeta * w]], [[w * w]])
        tr = integrate(model, [1.0], [0.0], [], dt=1.0 / n_per, duration=5.0, rho_inf=rho)
        errs.append(np.abs(tr.y[:, 0] - sdof_exact(tr.t, w, zeta, 1.0)).max())
    assert errs[0] < 1.2e-2
    assert 3.0 < errs[0] / errs[1] < 5.0


def test_identified_damping_is_the_scheme_s_exact_one():
    """The damping identified from the simulated SDOF equals the scheme's exact discrete one
    (eigenvalues of its amplification matrix) to 1e-6 and the frequency to 1e-6 relative; at 12
    steps per period and rho_inf = 0.5 that differs from the physical damping (a check that can
    fail); at 40 steps per period and rho_inf = 0.9 it is within 1 % of the physical one (measured 0.4 %)."""
    w, zeta, rho, n_per = 2 * np.pi * 1.3, 0.01, 0.5, 12
    dt = 1.0 / (1.3 * n_per)
    model = Linear([[2.0]], [[2 * 2.0 * zeta * w]], [[2.0 * w * w]])
    tr = integrate(model, [1e-3], [0.0], [], dt=dt, duration=8.0, rho_inf=rho)
    zc, pr = algorithmic_damping(w * dt, rho, zeta)
    assert zc - zeta > 1e-3
    m = dominant(identify(tr.t, tr.y[:, 0]))
    assert m.zeta == pytest.approx(zc, abs=1e-6)
    assert m.frequency_hz * pr / (1.3 * np.sqrt(1 - zeta**2)) == pytest.approx(1.0, abs=1e-6)
    assert algorithmic_damping(w * dt, 1.0)[0] == pytest.approx(0.0, abs=1e-12)
    assert algorithmic_damping(2 * np.pi / 40, 0.9, zeta)[0] == pytest.approx(zeta, rel=1e-2)


def test_first_order_state_against_matrix_exponential():
    """A 2-DOF system with a lag state coupled both ways (like an aerodynamic lag) against the
    exact solution expm(A t) x0 of its first-order form: error below 1e-4 of the amplitude."""
    M = np.array([[2.0, 0.3], [0.3, 1.0]])
    C = np.array([[0.1, 0.0], [0.0, 0.05]])
    K = np.array([[40.0, -5.0], [-5.0, 90.0]])
    Fz = np.array([[3.0], [-1.0]])
    Gq, Gv, Gz = np.array([[1.0, 0.5]]), np.array([[0.2, 0.0]]), np.array([[-4.0]])
    model = Linear(M, C, K, Fz, Gq, Gv, Gz)
    Mi = np.linalg.inv(M)
    A = np.zeros((5, 5))
    A[:2, 2:4] = np.eye(2)
    A[2:4, :2], A[2:4, 2:4], A[2:4, 4:] = -Mi @ K, -Mi @ C, -Mi @ Fz
    A[4:, :2], A[4:, 2:4], A[4:, 4:] = Gq, Gv, Gz
    x0 = np.array([0.01, -0.02, 0.0, 0.05, 0.003])
    tr = integrate(model, x0[:2], x0[2:4], x0[4:], dt=2e-3, duration=3.0, rho_inf=0.9)
    exact = np.array([expm(A * t) @ x0 for t in tr.t[::50]])
    err = np.abs(tr.y[::50] - exact[:, [0, 1, 4]]).max() / np.abs(exact).max()
    assert err < 1e-4


class Pendulum:
    mass = np.eye(1)

    def __init__(self, w0):
        self.w0 = w0

    def forces(self, t, q, v, z):
        return self.w0**2 * np.sin(q), np.zeros(0)

    def outputs(self, t, q, v, z):
        return q


def test_pendulum_period_against_elliptic_integral():
    """Nonlinear residual: the pendulum released at 1 rad, period 4 K(sin^2 0.5) / w0 (1.0663 x
    the linear one), from the zero crossings of the response, within 2e-4."""
    w0, th0 = 2.0, 1.0
    T = 4 * ellipk(np.sin(th0 / 2) ** 2) / w0
    tr = integrate(Pendulum(w0), [th0], [0.0], [], dt=T / 400, duration=6 * T, rho_inf=1.0)
    y = tr.y[:, 0]
    i = np.where((y[:-1] > 0) & (y[1:] <= 0))[0]
    tc = tr.t[i] + (tr.t[i + 1] - tr.t[i]) * y[i] / (y[i] - y[i + 1])
    assert np.mean(np.diff(tc)) / T == pytest.approx(1.0, abs=2e-4)
    assert T * w0 / (2 * np.pi) > 1.06  # the check sees the nonlinearity
    assert tr.iterations.max() > 1


def test_identify_two_modes_with_noise():
    """Two damped sinusoids (0.8 Hz, 2 %; 2.3 Hz, -0.5 %: growing) in 2 channels with 0.1 % noise:
    both found, zeta within 1e-3, frequency within 1e-3 relative, small half-record spread."""
    rng = np.random.default_rng(0)
    t = np.arange(0, 20, 0.02)
    modes = [(0.8, 0.02, 1.0, 0.3), (2.3, -0.005, 0.4, 1.0)]
    y = np.zeros((len(t), 2))
    for f, z, a1, a2 in modes:
        w = 2 * np.pi * f
        s = -z * w
        wd = w * np.sqrt(1 - z * z)
        y[:, 0] += a1 * np.exp(s * t) * np.cos(wd * t + 0.3)
        y[:, 1] += a2 * np.exp(s * t) * np.sin(wd * t)
    y += 1e-3 * np.abs(y).max() * rng.standard_normal(y.shape)
    ident = identify(t, y, order=4)
    assert ident.residual < 5e-3
    for f, z, *_ in modes:
        m = dominant(ident, f)
        assert m.zeta == pytest.approx(z, abs=1e-3)
        assert m.frequency_hz == pytest.approx(f * np.sqrt(1 - z * z), rel=1e-3)
        assert m.sigma_spread < 0.02
    pure = identify(t, rng.standard_normal(len(t)), order=4)
    assert pure.residual > 0.5  # noise alone is not a mode: the confidence measure says so


def test_bad_input():
    with pytest.raises(InputError):
        step_for_frequency(-1.0)
    with pytest.raises(InputError):
        identify(np.arange(5.0), np.ones(5))
    with pytest.raises(InputError):
        integrate(Pendulum(1.0), [0.1], [0.0], [], dt=0.0, duration=1.0)


class Interrupted(Pendulum):
    """Ctrl-C arrives during the 50th force evaluation."""

    calls = 0

    def forces(self, t, q, v, z):
        self.calls += 1
        if self.calls == 50:
            raise KeyboardInterrupt
        return super().forces(t, q, v, z)


def test_ctrl_c_keeps_the_partial_record():
    tr = integrate(Interrupted(2.0), [0.1], [0.0], [], dt=0.01, duration=10.0)
    assert tr.interrupted and 5 < len(tr.t) < 50 and len(tr.y) == len(tr.t)
