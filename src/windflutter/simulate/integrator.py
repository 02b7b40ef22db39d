"""Generalized-alpha time integration (Chung & Hulbert 1993) of a nonlinear second-order system
with first-order states, by Newton iterations on the nonlinear residual.

The system (SI, any consistent units)::

    M q'' + f(t, q, q', z) = 0        n second-order coordinates q (structure)
    z' = g(t, q, q', z)               m first-order states z (aerodynamic lags)

``M`` constant, or ``M(t)`` when the model has ``mass_at(t)`` (a hub turning with the rotor);
the inertial term of a step is then interpolated as the products, ``(1 - am) M(t_{n+1})
a_{n+1} + am M(t_n) a_n``.  One step from ``t_n`` to ``t_{n+1} = t_n + h`` (Chung & Hulbert, J. Appl. Mech.
60:371, 1993; the first-order states as in Jansen, Whiting & Hulbert, CMAME 190:305, 2000, with
the same weights, which keeps second order and unconditional stability for ``rho_inf <= 1``)::

    M a_{n+1-am} + f(t_{n+1-af}, q_{n+1-af}, v_{n+1-af}, z_{n+1-af}) = 0
    zdot_{n+1-am} = g(t_{n+1-af}, ...)
    x_{n+1-a} = (1 - a) x_{n+1} + a x_n
    q_{n+1} = q_n + h v_n + h^2 ((1/2 - beta) a_n + beta a_{n+1})
    v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_{n+1}),   z_{n+1} = z_n + h ((1 - gamma) zdot_n + gamma zdot_{n+1})

with ``am = (2 rho - 1) / (rho + 1)``, ``af = rho / (rho + 1)``, ``gamma = 1/2 - am + af``,
``beta = (1 - am + af)^2 / 4`` from the spectral radius at infinite frequency ``rho_inf``
(1: the trapezoidal rule, no numerical damping; smaller: high frequencies damped).

The unknowns of a step are ``(a_{n+1}, zdot_{n+1})``; the residual is exact (the model's
nonlinear forces), the iteration matrix is the model's Jacobian if it gives one, else central
differences of its forces, kept over steps (modified Newton) and rebuilt when an iteration
converges slowly.  The converged step does not depend on the iteration matrix.

:func:`algorithmic_damping` gives the scheme's own damping ratio and frequency error for an
undamped oscillator at ``omega h`` (the amplification matrix's eigenvalues).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np
import scipy.linalg as la

from windflutter.errors import InputError, ModelError

__all__ = ["Dynamics", "AlphaScheme", "Trajectory", "integrate", "fd_jacobian", "algorithmic_damping", "step_for_frequency"]


class Dynamics(Protocol):
    """What :func:`integrate` needs of a model."""

    mass: np.ndarray  #: (n, n) constant mass matrix (or, with ``mass_at(t)``, the one at t = 0)

    def forces(self, t: float, q: np.ndarray, v: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(f (n,), g (m,))`` of the module docstring."""

    def outputs(self, t: float, q: np.ndarray, v: np.ndarray, z: np.ndarray) -> np.ndarray:
        """(k,) recorded channels."""


@dataclass(frozen=True)
class AlphaScheme:
    """The generalized-alpha parameters of a spectral radius at infinity ``rho_inf`` in [0, 1]."""

    rho_inf: float = 0.9

    def __post_init__(self):
        r = self.rho_inf
        if isinstance(r, bool) or not isinstance(r, (int, float)) or not 0.0 <= r <= 1.0:
            raise InputError("rho_inf", r, "a spectral radius in [0, 1]")

    @property
    def am(self) -> float:
        return (2.0 * self.rho_inf - 1.0) / (self.rho_inf + 1.0)

    @property
    def af(self) -> float:
        return self.rho_inf / (self.rho_inf + 1.0)

    @property
    def gamma(self) -> float:
        return 0.5 - self.am + self.af

    @property
    def beta(self) -> float:
        return 0.25 * (1.0 - self.am + self.af) ** 2


def algorithmic_damping(omega_h: float, rho_inf: float = 0.9, zeta: float = 0.0) -> tuple[float, float]:
    """``(zeta_computed, period_ratio)``: the damping ratio of the scheme's response of
    ``q'' + 2 zeta omega q' + omega^2 q = 0`` at ``omega h`` (``zeta = 0``: the damping the
    scheme adds) and its period over the exact damped period (from the eigenvalues of the
    amplification matrix)."""
    s = AlphaScheme(rho_inf)
    w2, c = omega_h**2, 2.0 * zeta * omega_h  # h = 1, omega = omega_h
    am, af, g, b = s.am, s.af, s.gamma, s.beta
    # a1 from (1-am) a1 + am a0 + c v_af + w2 q_af = 0 with q1, v1 of the Newmark update
    A = np.zeros((3, 3))
    for j, e in enumerate(np.eye(3)):
        q0, v0, a0 = e
        qp, vp = q0 + v0 + (0.5 - b) * a0, v0 + (1 - g) * a0
        rhs = am * a0 + w2 * ((1 - af) * qp + af * q0) + c * ((1 - af) * vp + af * v0)
        a1 = -rhs / ((1 - am) + (1 - af) * (w2 * b + c * g))
        A[:, j] = [qp + b * a1, vp + g * a1, a1]
    lam = np.linalg.eigvals(A)
    lam = lam[np.argmax(np.abs(lam.imag))]
    s_ = np.log(lam)  # per step (h = 1)
    wd = omega_h * np.sqrt(1.0 - zeta**2)
    return float(-s_.real / abs(s_)), float(wd / abs(s_.imag))


def step_for_frequency(f_max_hz: float, points_per_period: float = 40.0) -> float:
    """The time step (s) giving ``points_per_period`` steps in a period of the highest retained
    frequency ``f_max_hz``."""
    if not (np.isfinite(f_max_hz) and f_max_hz > 0):
        raise InputError("f_max", f_max_hz, "a positive highest retained frequency (Hz)")
    if not (np.isfinite(points_per_period) and points_per_period >= 4):
        raise InputError("points_per_period", points_per_period, "at least 4 steps per period")
    return 1.0 / (points_per_period * f_max_hz)


@dataclass
class Trajectory:
    """The recorded response: times ``t`` (nt,), channels ``y`` (nt, k), the final state, the
    Newton iterations per step and whether the run was cut short (Ctrl-C: what was done is kept)."""

    t: np.ndarray
    y: np.ndarray
    q: np.ndarray
    v: np.ndarray
    z: np.ndarray
    iterations: np.ndarray
    interrupted: bool = False
    wall_time: float = 0.0
    info: dict = field(default_factory=dict)


def fd_jacobian(model, t, q, v, z, step: float = 1e-6):
    """Central-difference Jacobians of ``(f, g)`` in ``(q, v, z)``."""
    n, m = q.size, z.size
    out = []
    for which, x in (("q", q), ("v", v), ("z", z)):
        J = np.zeros((n + m, x.size))
        for j in range(x.size):
            d = step * max(1.0, abs(x[j]))
            xp, xm = x.copy(), x.copy()
            xp[j] += d
            xm[j] -= d
            args_p = {"q": q, "v": v, "z": z, which: xp}
            args_m = {"q": q, "v": v, "z": z, which: xm}
            fp, gp = model.forces(t, args_p["q"], args_p["v"], args_p["z"])
            fm, gm = model.forces(t, args_m["q"], args_m["v"], args_m["z"])
            J[:, j] = np.concatenate([fp - fm, gp - gm]) / (2.0 * d)
        out.append(J)
    return out


class _Stepper:
    """The iteration matrix of a step size and its LU factors."""

    def __init__(self, model, scheme: AlphaScheme, h: float, fd_step: float):
        self.model, self.s, self.h, self.fd_step = model, scheme, h, fd_step
        self.M = np.atleast_2d(np.asarray(model.mass, float))
        self.mass_at = getattr(model, "mass_at", None)
        self.lu = None

    def inertia(self, t, a):
        """``M(t) a``: the model's own product when its mass depends on time."""
        if self.mass_at is None:
            return self.M @ a
        prod = getattr(self.model, "inertia", None)
        return prod(t, a) if prod is not None else self.mass_at(t) @ a

    def build(self, t, q, v, z):
        jac = getattr(self.model, "jacobian", None)
        Jq, Jv, Jz = jac(t, q, v, z) if jac is not None else fd_jacobian(self.model, t, q, v, z, self.fd_step)
        if self.mass_at is not None:
            self.M = np.atleast_2d(np.asarray(self.mass_at(t), float))
        s, h = self.s, self.h
        n, m = q.size, z.size
        ca, cz = s.beta * h * h, s.gamma * h  # dq/da, dv/da (= dz/dzdot)
        A = np.zeros((n + m, n + m))
        A[:n, :n] = (1 - s.am) * self.M
        A[n:, n:] = (1 - s.am) * np.eye(m)
        # d(f, -g)/d(a, zdot) through the interpolated state
        A[:n, :n] += (1 - s.af) * (ca * Jq[:n] + cz * Jv[:n])
        A[:n, n:] += (1 - s.af) * cz * Jz[:n]
        A[n:, :n] -= (1 - s.af) * (ca * Jq[n:] + cz * Jv[n:])
        A[n:, n:] -= (1 - s.af) * cz * Jz[n:]
        self.lu = la.lu_factor(A)

    def solve(self, r):
        return la.lu_solve(self.lu, r)


def integrate(model, q0, v0, z0, dt: float, duration: float, rho_inf: float = 0.9, tol: float = 1e-9,
              max_iterations: int = 25, progress: Callable | None = None, fd_step: float = 1e-6,
              atol: float = 0.0) -> Trajectory:
    """Integrate ``model`` (:class:`Dynamics`) from ``(q0, v0, z0)`` over ``duration`` with step ``dt``.

    Parameters
    ----------
    tol : a step has converged when the largest increment of ``q`` is below ``tol`` times the
        largest ``|q|`` seen so far (and the same for ``z``), or below ``atol`` (the round-off
        floor of the model's forces, in the units of ``q``; a model may give it as ``atol``).
    progress : ``progress(step, n_steps, t)`` called about every 2 s of wall time.
    fd_step : relative step of the finite-difference Jacobian (when the model has none).

    Ctrl-C during the run returns what was integrated so far (``interrupted=True``).
    Raises :class:`~windflutter.errors.ModelError` when a step does not converge.
    """
    if not (np.isfinite(dt) and dt > 0):
        raise InputError("dt", dt, "a positive time step (s)")
    if not (np.isfinite(duration) and duration > 0):
        raise InputError("duration", duration, "a positive duration (s)")
    s = AlphaScheme(rho_inf)
    atol = max(float(atol), float(getattr(model, "atol", 0.0)))
    q, v, z = (np.array(x, float).reshape(-1) for x in (q0, v0, z0))
    n = q.size
    stepper = _Stepper(model, s, dt, fd_step)
    stepper.built = 0.0
    #: a mass that turns with time: the iteration matrix renewed at the model's interval (s)
    renew = float(getattr(model, "renew_interval", np.inf))
    #: ``model.iteration_solver(t, scheme, h) -> solve(r)``: the model's own solution of the
    #: iteration matrix (structured: a turning hub coupled to identical blades)
    custom, solve = getattr(model, "iteration_solver", None), None
    f, g = model.forces(0.0, q, v, z)
    a = -np.linalg.solve(stepper.M if stepper.mass_at is None else stepper.mass_at(0.0), f)
    Ma = stepper.inertia(0.0, a)
    zd = np.asarray(g, float).copy()
    n_steps = int(round(duration / dt))
    ys = [np.asarray(model.outputs(0.0, q, v, z), float)]
    ts, its = [0.0], []
    qscale = max(float(np.abs(q).max(initial=0.0)), dt * float(np.abs(v).max(initial=0.0)), 1e-300)
    zscale = max(float(np.abs(z).max(initial=0.0)), 1e-300)
    t0 = last = time.monotonic()
    interrupted = False
    h, ca, cz = dt, s.beta * dt * dt, s.gamma * dt
    try:
        for k in range(n_steps):
            t = k * h
            qp = q + h * v + h * h * (0.5 - s.beta) * a
            vp = v + h * (1 - s.gamma) * a
            zp = z + h * (1 - s.gamma) * zd
            a1, zd1 = a.copy(), zd.copy()
            ta = t + (1 - s.af) * h
            for it in range(1, max_iterations + 1):
                q1, v1, z1 = qp + ca * a1, vp + cz * a1, zp + cz * zd1
                qa, va, za = (1 - s.af) * q1 + s.af * q, (1 - s.af) * v1 + s.af * v, (1 - s.af) * z1 + s.af * z
                fa, ga = model.forces(ta, qa, va, za)
                Ma1 = stepper.inertia(t + h, a1)
                r = np.concatenate([(1 - s.am) * Ma1 + s.am * Ma + fa,
                                    (1 - s.am) * zd1 + s.am * zd - ga])
                if custom is not None:  # the model solves its own iteration matrix
                    if solve is None or (it > 6 and it % 6 == 1) or (it == 1 and t - stepper.built >= renew):
                        solve, stepper.built = custom(ta, s, h), t
                    dx = -solve(r)
                else:
                    if stepper.lu is None or (it > 6 and it % 6 == 1) or (it == 1 and t - stepper.built >= renew):
                        stepper.build(ta, qa, va, za)
                        stepper.built = t
                    dx = -stepper.solve(r)
                a1 += dx[:n]
                zd1 += dx[n:]
                dq = ca * float(np.abs(dx[:n]).max(initial=0.0))
                dz = cz * float(np.abs(dx[n:]).max(initial=0.0))
                if dq <= max(tol * qscale, atol) and dz <= max(tol * zscale, atol):
                    break
            else:
                raise ModelError(f"the time step at t = {t:.4g} s did not converge in {max_iterations} Newton "
                                 "iterations: reduce the time step or the kick")
            q, v, z = qp + ca * a1, vp + cz * a1, zp + cz * zd1
            a, zd, Ma = a1, zd1, stepper.inertia(t + h, a1)
            qscale = max(qscale, float(np.abs(q).max(initial=0.0)))
            zscale = max(zscale, float(np.abs(z).max(initial=0.0)))
            ts.append(t + h)
            ys.append(np.asarray(model.outputs(t + h, q, v, z), float))
            its.append(it)
            now = time.monotonic()
            if progress is not None and (now - last > 2.0 or k == n_steps - 1):
                progress(k + 1, n_steps, t + h)
                last = now
    except KeyboardInterrupt:
        interrupted = True
    return Trajectory(t=np.asarray(ts), y=np.asarray(ys).reshape(len(ts), -1), q=q, v=v, z=z,
                      iterations=np.asarray(its, dtype=int), interrupted=interrupted,
                      wall_time=time.monotonic() - t0, info={"dt": dt, "rho_inf": rho_inf})
