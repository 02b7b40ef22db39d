"""A small analytic analyser for the workflow tests: a 2-DOF Theodorsen typical section at a
fixed radius of a toy rotor, solved by p-k.  Not a turbine model; it only has to be a correct,
fast, deterministic stand-in for the stability solver.

Plug-in use: ``solver.backend: toy`` with this folder on ``PYTHONPATH`` (the entry point
of ``windflutter_test_plugins-0.dist-info`` here publishes it in ``windflutter.backends``).
Environment knobs (test control only): ``TOY_DELAY`` (s of sleep per point, to give a kill
time to land), ``TOY_FAIL_WIND`` (comma-separated wind speeds whose points raise
ConvergenceError).

Section (h positive down, alpha nose-up, Theodorsen 1935 / Hodges & Pierce ch. 5 forms)::

    L   = pi rho b^2 (h'' + U a' - b a a'') + cla rho U b C(k) [h' + U alpha + b(1/2 - a) alpha']
    M_ea = pi rho b^2 [b a h'' - U b (1/2 - a) alpha' - b^2 (1/8 + a^2) alpha'']
           + cla rho U b^2 (a + 1/2) C(k) [h' + U alpha + b(1/2 - a) alpha']

Generalised forces conjugate to (h, alpha): Q = (-L, M_ea).
"""

from __future__ import annotations

import math
import os
import time

import numpy as np

from windflutter.aero.theodorsen import theodorsen
from windflutter.errors import ConvergenceError
from windflutter.post.aerowork import normalise_mode, section_work
from windflutter.workflow import OperatingPoint, PointResult

RHO = 1.225
B = 1.35            # semi-chord (m)
A_EA = -0.2         # elastic axis aft of mid-chord (semi-chords)
MU = 20.0           # mass ratio m / (pi rho b^2)
X_ALPHA = 0.1       # CG aft of EA (semi-chords)
R2_ALPHA = 0.25     # radius of gyration squared (b^2)
OMEGA_H = 8.0       # rad/s
OMEGA_A = 30.0      # rad/s
RADIUS = 47.7       # m, the section's radius
R_TIP = 63.0        # m


def section_matrices():
    m = MU * math.pi * RHO * B**2
    S = m * X_ALPHA * B
    I = m * R2_ALPHA * B**2
    M = np.array([[m, S], [S, I]])
    K = np.diag([m * OMEGA_H**2, I * OMEGA_A**2])
    return M, K


def aero_coefficients(U: float, k: float, cla: float = 2 * math.pi):
    """A2, A1, A0 (complex 2x2) with Q = (s^2 A2 + s A1 + A0) q, C frozen at k."""
    C = complex(theodorsen(k)) * cla / (2 * math.pi)
    p, b, a = math.pi * RHO, B, A_EA
    circ = 2 * p * U * b * C          # 2 pi rho U b C  (x cla/2pi)
    A2 = np.array([[-p * b**2, p * b**3 * a],
                   [p * b**3 * a, -p * b**4 * (0.125 + a**2)]], complex)
    A1 = np.array([[-circ, -(p * b**2 * U + circ * b * (0.5 - a))],
                   [circ * b * (a + 0.5), -p * b**3 * U * (0.5 - a) + circ * b**2 * (a + 0.5) * (0.5 - a)]], complex)
    A0 = np.array([[0.0, -circ * U],
                   [0.0, circ * b * (a + 0.5) * U]], complex)
    return A2, A1, A0


def harmonic_aero(U: float, omega: float, cla: float = 2 * math.pi) -> np.ndarray:
    """A(i omega) such that Q_hat = A q_hat for harmonic motion."""
    A2, A1, A0 = aero_coefficients(U, omega * B / U, cla)
    s = 1j * omega
    return s * s * A2 + s * A1 + A0


def qep_eigs(U: float, k: float, cla: float):
    M, K = section_matrices()
    A2, A1, A0 = aero_coefficients(U, k, cla)
    Mt, Dt, Kt = M - A2, -A1, K - A0
    n = 2
    Z, I = np.zeros((n, n)), np.eye(n)
    Ainv = np.linalg.solve(Mt, np.hstack([Kt, Dt]))
    L = np.block([[Z, I], [-Ainv[:, :n], -Ainv[:, n:]]])
    lam, V = np.linalg.eig(L)
    return lam, V[:n]


def pk_mode(U: float, omega0: float, cla: float, tol: float = 1e-10, maxit: int = 200):
    """p-k iteration for the branch starting near omega0: (lambda, q).

    Solves ``w = |Im lambda(k = w b / U)|`` for the branch nearest ``w``; the plain fixed-point
    step is accelerated by the secant through the last two residuals (same fixed point and
    stopping rule, a third of the eigen-solves)."""
    w, w_old, f_old = omega0, None, None
    for _ in range(maxit):
        lam, V = qep_eigs(U, max(w, 1e-9) * B / U, cla)
        cand = np.where(lam.imag > -1e-12)[0]
        j = cand[np.argmin(np.abs(lam[cand].imag - w))]
        f = abs(lam[j].imag) - w
        if abs(f) < tol * max(1.0, w):
            return lam[j], V[:, j]
        step = f if f_old is None or f == f_old else -f * (w - w_old) / (f - f_old)
        w_old, f_old, w = w, f, w + step
    raise ConvergenceError(f"p-k did not converge at U = {U:.3f} m/s")


def modes_at(U: float, cla: float):
    return [pk_mode(U, w0, cla) for w0 in (OMEGA_H, OMEGA_A)]


def relative_speed(V: float, rpm: float) -> float:
    return math.hypot(V, rpm * math.pi / 30 * RADIUS)


def divergence_speed() -> float:
    _, K = section_matrices()
    return math.sqrt(K[1, 1] / (2 * math.pi * RHO * B**2 * (0.5 + A_EA)))


class ToyAnalyser:
    def __init__(self, turbine=None, config=None):
        self.turbine = turbine
        self.delay = float(os.environ.get("TOY_DELAY", "0") or 0)
        fail = os.environ.get("TOY_FAIL_WIND", "")
        self.fail = {float(x) for x in fail.split(",") if x.strip()}

    def fe_model(self, point):
        """A stick of beams through the stations (for the animation)."""
        from windflutter.structure.fem import BeamSection, FEModel

        r = np.linspace(0.3, 1.0, 8) * R_TIP
        nodes = np.stack([np.zeros_like(r), np.zeros_like(r), r], axis=1)
        n = r.size
        return FEModel(nodes=nodes, beam_conn=np.stack([np.arange(n - 1), np.arange(1, n)], axis=1),
                       beam_section=np.zeros(n - 1, int), beam_orient=np.tile([1.0, 0.0, 0.0], (n - 1, 1)),
                       beam_sections=[BeamSection(stiffness=np.eye(6), mass=np.eye(6))])

    def describe(self) -> dict:
        v = np.arange(3.0, 25.01, 1.0)
        rpm = np.minimum(6.9 + (12.1 - 6.9) * (v - 3) / (11.4 - 3), 12.1)
        return {"turbine": "toy section", "model_type": "typical section", "n_dof": 2,
                "operating_wind_speed": v, "operating_rpm": rpm,
                "operating_pitch_deg": np.where(v > 11.4, (v - 11.4) * 1.5, 0.0), "rated_rpm": 12.1}

    def __call__(self, point: OperatingPoint, progress=None) -> PointResult:
        if point.wind_speed in self.fail:
            raise ConvergenceError(f"toy: forced failure at {point.wind_speed} m/s")
        cla = 2 * math.pi if point.aero == "potential" else 0.9 * 2 * math.pi
        V = point.wind_speed
        sweep = np.asarray(point.sweep_rpm, float)
        freq = np.zeros((sweep.size, 2))
        zeta = np.zeros((sweep.size, 2))
        for i, rpm in enumerate(sweep):
            for j, (lam, _) in enumerate(modes_at(relative_speed(V, rpm), cla)):
                freq[i, j] = abs(lam.imag) / (2 * math.pi)
                zeta[i, j] = -lam.real / abs(lam)
            if progress:
                progress(0.8 * (i + 1) / sweep.size)
            if self.delay:
                time.sleep(self.delay / sweep.size)

        def min_damping(rpm):
            return min(-lam.real / abs(lam) for lam, _ in modes_at(relative_speed(V, rpm), cla))

        res = PointResult(sweep_rpm=sweep, damped_frequency_hz=freq, damping_ratio=zeta,
                          mode_labels=["plunge (flap)", "pitch (torsion)"])
        neg = np.where(zeta.min(axis=1) < 0)[0]
        if neg.size:
            hi = sweep[neg[0]]
            lo = sweep[neg[0] - 1] if neg[0] > 0 else point.min_rpm
            while hi - lo > point.tolerance_rpm:
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if min_damping(mid) < 0 else (mid, hi)
            rpm_f = 0.5 * (lo + hi)
            U = relative_speed(V, rpm_f)
            modes = modes_at(U, cla)
            j = int(np.argmin([-lam.real / abs(lam) for lam, _ in modes]))
            lam, q = modes[j]
            res.flutter_rpm = rpm_f
            res.flutter_frequency_hz = abs(lam.imag) / (2 * math.pi)
            res.flutter_mode = res.mode_labels[j]
            q = normalise_mode(q)
            r = np.linspace(0.3, 1.0, 8) * R_TIP
            scale = (r / RADIUS) ** 2
            res.station_radius = r
            res.flutter_shape = np.stack([scale * q[0], 0 * scale, scale * q[1]], axis=1)
            Ah = harmonic_aero(U, abs(lam.imag), cla)
            w = np.full(r.size, (r[1] - r[0]))
            motion = np.stack([scale * q[0], scale * q[1], 0 * scale], axis=1)
            force = np.stack([(Ah @ np.array([mh, ma]))for mh, ma in motion[:, :2]])
            force = np.column_stack([force * w[:, None], np.zeros(r.size)])
            res.aero_work = section_work(motion, force)
            # the same mode on a stick model along z (flap = x translation, torsion = rz)
            u = np.zeros((r.size, 6), complex)
            u[:, 0] = scale * q[0]
            u[:, 5] = scale * q[1]
            res.flutter_dof_vector = u.ravel()
        Ud = divergence_speed()
        if Ud > V:
            rpm_d = math.sqrt(Ud**2 - V**2) / RADIUS * 30 / math.pi
            if point.min_rpm < rpm_d <= point.max_rpm:
                res.divergence_rpm = rpm_d
        res.info = {"radius_m": RADIUS}
        if progress:
            progress(1.0)
        return res


def factory(turbine, config):
    return ToyAnalyser(turbine, config)
