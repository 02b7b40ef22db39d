"""Structural and aerodynamic matrices of the typical section, and its static divergence.

The state is ``q = [h (m, positive DOWN: Theodorsen's sign), alpha (rad, nose-up)]``.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy import linalg

from windflutter.aero.theodorsen import theodorsen
from windflutter.section.model import TWO_PI, TypicalSection

#: a circulation function: reduced frequencies (array) -> C(k) (complex array), vectorised,
#: e.g. :func:`~windflutter.aero.theodorsen.theodorsen` or ``jones``
CirculationFunction = Callable[[np.ndarray], np.ndarray]


def structural_matrices(sec: TypicalSection) -> tuple[np.ndarray, np.ndarray]:
    """Structural mass (kg/m, kg m/m, kg m^2/m) and stiffness (N/m^2, N) matrices of ``q``."""
    M = np.array([[sec.mass, sec.static_moment], [sec.static_moment, sec.inertia]])
    K = np.diag([sec.plunge_stiffness, sec.pitch_stiffness])
    return M, K


def natural_frequencies(sec: TypicalSection) -> np.ndarray:
    """Coupled in-vacuo natural frequencies (rad/s), ascending."""
    M, K = structural_matrices(sec)
    return np.sqrt(np.sort(linalg.eigvalsh(K, M)))


def aero_parts(sec: TypicalSection, U: float):
    """Pieces of the aero force ``F = [A2 s^2 + A1 s + qc C w (r1 s + r0)] q`` (h down).

    Returns ``A2, A1, qc, w, r1, r0`` at airspeed ``U`` (m/s), with ``qc = Cla rho U b``;
    ``w`` the force distribution (on h, alpha) of the circulatory lift and ``r1 s + r0`` the
    3/4-chord downwash operator.
    """
    b, a, rho = sec.semi_chord, sec.elastic_axis, sec.air_density
    c = math.cos(sec.plunge_angle)
    T = np.diag([c, 1.0])
    pr = math.pi * rho * b * b
    if sec.scale_apparent_mass:
        pr *= sec.lift_slope / TWO_PI
    A2 = pr * np.array([[-1.0, b * a], [b * a, -b * b * (0.125 + a * a)]])
    A1 = pr * np.array([[0.0, -U], [0.0, -U * b * (0.5 - a)]])
    A2 = T @ A2 @ T
    A1 = T @ A1 @ T
    w = np.array([-c, b * (a + 0.5)])
    r1 = np.array([c, b * (0.5 - a)])
    r0 = np.array([0.0, U])
    qc = sec.lift_slope * rho * U * b
    return A2, A1, qc, w, r1, r0


def c_scalar(c_func: CirculationFunction, k: float) -> complex:
    """The circulation function ``c_func`` (default :func:`~windflutter.aero.theodorsen.theodorsen`)
    at one reduced frequency ``k``, as a Python complex."""
    return complex(np.asarray(c_func(k)))


def aero_matrices(
    sec: TypicalSection, U: float, k: float | None = None, C: complex | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Aerodynamic matrices with C frozen: ``F_aero = (Ma s^2 + Da s + Ka) q`` (h down).

    Parameters
    ----------
    sec
        The section.
    U
        Airspeed (m/s).
    k
        Reduced frequency for ``C(k)``; ignored if ``C`` is given.  Default 0 (quasi-steady).
    C
        Value of Theodorsen's function to use (e.g. 1 for quasi-steady aerodynamics).

    Returns
    -------
    Ma (kg/m), Da (kg/(m s)), Ka (N/m^2 ...) as complex 2x2 arrays.  The coupled system is
    ``(M_s - Ma) s^2 + (-Da) s + (K_s - Ka)``.
    """
    if C is None:
        C = c_scalar(theodorsen, 0.0 if k is None else k)
    A2, A1, qc, w, r1, r0 = aero_parts(sec, U)
    Ma = A2.astype(complex)
    Da = A1 + qc * C * np.outer(w, r1)
    Ka = qc * C * np.outer(w, r0)
    return Ma, Da.astype(complex), Ka.astype(complex)


def companion_parts(sec: TypicalSection, U: float) -> tuple[np.ndarray, np.ndarray]:
    """First-order companion matrix of the coupled system at ``U`` (m/s) split as ``base + C dC``.

    The state is ``[q, q']``; C enters linearly (circulatory terms), so p-k iterations only
    rescale ``dC``, and a state space with aerodynamic lag states starts from ``C`` at its
    high-frequency value.
    """
    M, K = structural_matrices(sec)
    A2, A1, qc, w, r1, r0 = aero_parts(sec, U)
    Minv = np.linalg.inv(M - A2)
    base = np.zeros((4, 4), dtype=complex)
    base[:2, 2:] = np.eye(2)
    base[2:, :2] = -Minv @ K
    base[2:, 2:] = Minv @ A1
    dC = np.zeros((4, 4), dtype=complex)
    dC[2:, :2] = qc * Minv @ np.outer(w, r0)
    dC[2:, 2:] = qc * Minv @ np.outer(w, r1)
    return base, dC


def divergence_speed(sec: TypicalSection) -> float | None:
    """Closed-form static divergence speed ``sqrt(K_a / (Cla rho b^2 (a + 1/2)))`` (m/s).

    None if ``a <= -1/2`` (elastic axis at or ahead of the aerodynamic centre).
    """
    e = sec.elastic_axis + 0.5
    if e <= 0:
        return None
    return math.sqrt(sec.pitch_stiffness / (sec.lift_slope * sec.air_density * sec.semi_chord**2 * e))


def divergence_speed_numerical(sec: TypicalSection) -> float | None:
    """Divergence speed (m/s) from the static eigenproblem ``K_s x = U^2 Khat x`` (``Ka = U^2 Khat``).

    Uses C(0) = 1.  Returns the smallest positive real ``U``, or None.
    """
    _, K = structural_matrices(sec)
    _, _, Khat = aero_matrices(sec, 1.0, C=1.0)
    mu = linalg.eigvals(K, Khat.real)
    mu = mu[np.isfinite(mu)]
    mu = mu[(np.abs(mu.imag) <= 1e-9 * np.abs(mu)) & (mu.real > 0)]
    if mu.size == 0:
        return None
    return float(math.sqrt(mu.real.min()))
