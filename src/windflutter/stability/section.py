"""Typical-section (2-DOF plunge/pitch) flutter and divergence with Theodorsen aerodynamics.

Model (Theodorsen 1935; Bisplinghoff, Ashley & Halfman 1955 ch. 5; Hodges & Pierce 2011 ch. 5)::

    m h'' + S a'' + K_h h     = -L
    S h'' + I a'' + K_a alpha =  M_ea

with the plunge ``h`` positive DOWN inside this module (Theodorsen's convention), pitch ``alpha``
nose-up about the elastic axis at ``a b`` aft of mid-chord, ``S`` the static moment (CG aft of
EA positive) and, for harmonic motion, METHOD.md section 3::

    L    = pi rho b^2 (h'' + U alpha' - b a alpha'')
         + Cla rho U b C(k) [h' + U alpha + b(1/2 - a) alpha']
    M_ea = pi rho b^2 [b a h'' - U b (1/2 - a) alpha' - b^2 (1/8 + a^2) alpha'']
         + Cla rho U b^2 (a + 1/2) C(k) [h' + U alpha + b(1/2 - a) alpha']

(``Cla`` = lift slope, 2 pi for the flat plate; only the circulatory part is scaled).  The
public results report the flutter mode with ``h`` positive along the lift (up), as in the
project's conventions.

An optional ``plunge_angle`` (rad) is the angle between the plunge DOF and the lift direction:
the aerodynamics sees the plunge ``h cos(plunge_angle)`` and the lift acts on the plunge DOF with
the same factor (used by the seed's rotor "simple model", thesis eq. 4.3).

Solvers
-------
* :func:`k_method` -- V-g method: artificial structural damping ``g`` for harmonic motion,
  eigenproblem in ``(1 + i g)/omega^2`` for each k, flutter where ``g`` of a branch crosses 0.
* :func:`pk_method` -- p-k: for each speed and each mode, k is iterated to the mode's own
  frequency ``k = omega b / U`` until converged; flutter where the tracked mode's real part
  ``sigma`` crosses 0 (bracket on a speed grid + Brent root-finding).
* :func:`p_method` -- exact eigenvalues of the state-space model built with a Roger
  rational-function approximation of C(k) (aero lag states); same bracket + root-find.
* :func:`divergence_speed` -- closed form ``sqrt(K_a / (Cla rho b^2 (a + 1/2)))`` and
  :func:`divergence_speed_numerical` from the static eigenproblem ``K_s x = U^2 K_aero x``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import linalg, optimize, special

from windflutter.aero.theodorsen import RogerRFA, theodorsen, theodorsen_rfa
from windflutter.errors import ConvergenceError, InputError

__all__ = [
    "TypicalSection",
    "StabilityCurves",
    "SectionResult",
    "section_from_config",
    "structural_matrices",
    "aero_matrices",
    "k_method",
    "pk_method",
    "p_method",
    "analyse",
    "divergence_speed",
    "divergence_speed_numerical",
    "pk_eigen",
    "rfa_state_matrix",
    "natural_frequencies",
]

TWO_PI = 2.0 * math.pi


# --------------------------------------------------------------------------------------------
# Input
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TypicalSection:
    """A 2-DOF typical section, dimensional form (SI, per unit span).

    Attributes
    ----------
    semi_chord
        b (m).
    elastic_axis
        a, elastic axis aft of mid-chord in semi-chords (-).
    mass
        m (kg/m).
    static_moment
        S = m x_alpha b (kg m / m), CG aft of the elastic axis positive.
    inertia
        I_alpha about the elastic axis (kg m^2 / m).
    plunge_stiffness
        K_h (N/m^2).
    pitch_stiffness
        K_alpha (N m / rad / m = N).
    air_density
        rho (kg/m^3).
    lift_slope
        Cla (1/rad), replaces 2 pi in the circulatory terms.
    plunge_angle
        Angle (rad) between the plunge DOF and the lift direction (0 for the classic section).
    scale_apparent_mass
        If True the non-circulatory (apparent-mass) terms are scaled by ``Cla / 2 pi`` too, as
        in the seed thesis's "viscous" variant (METHOD.md section 3); default False.
    """

    semi_chord: float
    elastic_axis: float
    mass: float
    static_moment: float
    inertia: float
    plunge_stiffness: float
    pitch_stiffness: float
    air_density: float = 1.225
    lift_slope: float = TWO_PI
    plunge_angle: float = 0.0
    scale_apparent_mass: bool = False

    def __post_init__(self) -> None:
        _check_positive("semi_chord", self.semi_chord)
        _check_finite("elastic_axis", self.elastic_axis)
        _check_positive("mass", self.mass)
        _check_finite("static_moment", self.static_moment)
        _check_positive("inertia", self.inertia)
        _check_positive("plunge_stiffness", self.plunge_stiffness)
        _check_positive("pitch_stiffness", self.pitch_stiffness)
        _check_positive("air_density", self.air_density)
        _check_positive("lift_slope", self.lift_slope)
        _check_finite("plunge_angle", self.plunge_angle)
        if self.mass * self.inertia <= self.static_moment**2:
            raise InputError(
                "inertia",
                self.inertia,
                f"I_alpha > S^2/m = {self.static_moment**2 / self.mass:.6g} kg m^2/m "
                "(r_alpha^2 > x_alpha^2: positive-definite mass matrix)",
            )

    # nondimensional views ---------------------------------------------------------------
    @property
    def mass_ratio(self) -> float:
        """mu = m / (pi rho b^2)."""
        return self.mass / (math.pi * self.air_density * self.semi_chord**2)

    @property
    def x_alpha(self) -> float:
        """x_alpha = S / (m b)."""
        return self.static_moment / (self.mass * self.semi_chord)

    @property
    def r_alpha_squared(self) -> float:
        """r_alpha^2 = I / (m b^2)."""
        return self.inertia / (self.mass * self.semi_chord**2)

    @property
    def omega_h(self) -> float:
        """Uncoupled plunge frequency sqrt(K_h/m) (rad/s)."""
        return math.sqrt(self.plunge_stiffness / self.mass)

    @property
    def omega_alpha(self) -> float:
        """Uncoupled pitch frequency sqrt(K_alpha/I) (rad/s)."""
        return math.sqrt(self.pitch_stiffness / self.inertia)

    @classmethod
    def from_nondimensional(
        cls,
        semi_chord: float,
        elastic_axis: float,
        mass_ratio: float,
        x_alpha: float,
        r_alpha_squared: float,
        omega_h: float,
        omega_alpha: float,
        air_density: float = 1.225,
        lift_slope: float = TWO_PI,
        plunge_angle: float = 0.0,
    ) -> "TypicalSection":
        """Build from mu, x_alpha, r_alpha^2, omega_h, omega_alpha (rad/s) and b, rho."""
        _check_positive("semi_chord", semi_chord)
        _check_positive("air_density", air_density)
        _check_positive("mass_ratio", mass_ratio)
        _check_finite("x_alpha", x_alpha)
        _check_positive("r_alpha_squared", r_alpha_squared)
        _check_positive("omega_h", omega_h)
        _check_positive("omega_alpha", omega_alpha)
        if r_alpha_squared <= x_alpha**2:
            raise InputError(
                "r_alpha_squared",
                r_alpha_squared,
                f"r_alpha^2 > x_alpha^2 = {x_alpha**2:.6g} (positive-definite mass matrix)",
            )
        m = mass_ratio * math.pi * air_density * semi_chord**2
        inertia = m * r_alpha_squared * semi_chord**2
        return cls(
            semi_chord=semi_chord,
            elastic_axis=elastic_axis,
            mass=m,
            static_moment=m * x_alpha * semi_chord,
            inertia=inertia,
            plunge_stiffness=m * omega_h**2,
            pitch_stiffness=inertia * omega_alpha**2,
            air_density=air_density,
            lift_slope=lift_slope,
            plunge_angle=plunge_angle,
        )


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


def _check_finite(name: str, v: Any, source: str | None = None) -> None:
    if not _is_number(v) or not math.isfinite(float(v)):
        raise InputError(name, v, "a finite number", source)


def _check_positive(name: str, v: Any, source: str | None = None) -> None:
    if not _is_number(v) or not math.isfinite(float(v)) or float(v) <= 0.0:
        raise InputError(name, v, "a positive finite number", source)


_COMMON_KEYS = {"semi_chord", "elastic_axis", "air_density", "lift_slope"}
_DIM_KEYS = ("mass", "static_moment", "inertia", "plunge_stiffness", "pitch_stiffness")
_NONDIM_KEYS = ("mass_ratio", "x_alpha", "r_alpha_squared", "omega_h", "omega_alpha")
_UNITS = {
    "semi_chord": "m",
    "elastic_axis": "semi-chords aft of mid-chord",
    "air_density": "kg/m^3",
    "lift_slope": "1/rad",
    "mass": "kg/m",
    "static_moment": "kg m/m",
    "inertia": "kg m^2/m",
    "plunge_stiffness": "N/m^2",
    "pitch_stiffness": "N",
    "mass_ratio": "-",
    "x_alpha": "semi-chords",
    "r_alpha_squared": "-",
    "omega_h": "rad/s",
    "omega_alpha": "rad/s",
}


def section_from_config(config: Any, source: str | None = None) -> TypicalSection:
    """Validate a config mapping (the ``windflutter section`` YAML) and build the section.

    Raises
    ------
    InputError
        Naming the field for: not a mapping, unknown key, missing key, non-numeric / NaN /
        infinite value, non-positive mass, stiffness, ..., r_alpha^2 <= x_alpha^2, and a mix of
        the dimensional and nondimensional forms.
    """
    if not isinstance(config, Mapping):
        raise InputError("<config>", config, "a mapping of section parameters", source)
    allowed = _COMMON_KEYS | set(_DIM_KEYS) | set(_NONDIM_KEYS)
    for key in config:
        if key not in allowed:
            raise InputError(str(key), config[key], "a known key: " + ", ".join(sorted(allowed)),
                             source)
    for key, val in config.items():
        if not _is_number(val) or not math.isfinite(float(val)):
            raise InputError(key, val, f"a finite number ({_UNITS[key]})", source)
    dim = [k for k in _DIM_KEYS if k in config]
    nondim = [k for k in _NONDIM_KEYS if k in config]
    if dim and nondim:
        raise InputError(
            nondim[0], config[nondim[0]],
            f"either the dimensional keys ({', '.join(_DIM_KEYS)}) or the nondimensional keys "
            f"({', '.join(_NONDIM_KEYS)}), not both (found {dim[0]!r} too)", source)
    for key in ("semi_chord", "elastic_axis"):
        if key not in config:
            raise InputError(key, None, f"a number ({_UNITS[key]}); the key is missing", source)
    common = {
        "semi_chord": float(config["semi_chord"]),
        "elastic_axis": float(config["elastic_axis"]),
        "air_density": float(config.get("air_density", 1.225)),
        "lift_slope": float(config.get("lift_slope", TWO_PI)),
    }
    try:
        if nondim:
            required = _NONDIM_KEYS
            for key in required:
                if key not in config:
                    raise InputError(key, None, f"a number ({_UNITS[key]}); the key is missing")
            if float(config["mass_ratio"]) <= 0:
                raise InputError("mass_ratio", config["mass_ratio"], "a positive number (-)")
            return TypicalSection.from_nondimensional(
                mass_ratio=float(config["mass_ratio"]),
                x_alpha=float(config["x_alpha"]),
                r_alpha_squared=float(config["r_alpha_squared"]),
                omega_h=float(config["omega_h"]),
                omega_alpha=float(config["omega_alpha"]),
                **common,
            )
        for key in _DIM_KEYS:
            if key not in config and key != "static_moment":
                raise InputError(
                    key, None,
                    f"a positive number ({_UNITS[key]}); the key is missing "
                    "(give mass, inertia, plunge_stiffness, pitch_stiffness [, static_moment] "
                    "or mass_ratio, x_alpha, r_alpha_squared, omega_h, omega_alpha)")
        if float(config["mass"]) <= 0:
            raise InputError("mass", config["mass"], "a positive number (kg/m)")
        return TypicalSection(
            mass=float(config["mass"]),
            static_moment=float(config.get("static_moment", 0.0)),
            inertia=float(config["inertia"]),
            plunge_stiffness=float(config["plunge_stiffness"]),
            pitch_stiffness=float(config["pitch_stiffness"]),
            **common,
        )
    except InputError as exc:
        if source and exc.source is None:
            raise InputError(exc.field, exc.value, exc.expected, source) from None
        raise


# --------------------------------------------------------------------------------------------
# Matrices
# --------------------------------------------------------------------------------------------
def structural_matrices(sec: TypicalSection) -> tuple[np.ndarray, np.ndarray]:
    """Structural mass and stiffness matrices for ``q = [h (down, m), alpha (rad)]``."""
    M = np.array([[sec.mass, sec.static_moment], [sec.static_moment, sec.inertia]])
    K = np.diag([sec.plunge_stiffness, sec.pitch_stiffness])
    return M, K


def _aero_parts(sec: TypicalSection, U: float):
    """Pieces of the aero force ``F = [A2 s^2 + A1 s + qc C w (r1 s + r0)] q`` (h down).

    Returns ``A2, A1, qc, w, r1, r0`` with ``qc = Cla rho U b``; ``w`` the force distribution
    (on h, alpha) of the circulatory lift and ``r1 s + r0`` the 3/4-chord downwash operator.
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
        C = complex(theodorsen(0.0 if k is None else k))
    A2, A1, qc, w, r1, r0 = _aero_parts(sec, U)
    Ma = A2.astype(complex)
    Da = A1 + qc * C * np.outer(w, r1)
    Ka = qc * C * np.outer(w, r0)
    return Ma, Da.astype(complex), Ka.astype(complex)


def natural_frequencies(sec: TypicalSection) -> np.ndarray:
    """Coupled in-vacuo natural frequencies (rad/s), ascending."""
    M, K = structural_matrices(sec)
    return np.sqrt(np.sort(linalg.eigvalsh(K, M)))


def _quad_eig(M: np.ndarray, D: np.ndarray, K: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenpairs of ``(lam^2 M + lam D + K) x = 0`` via the first-order companion form."""
    n = M.shape[0]
    Minv = np.linalg.inv(M)
    A = np.zeros((2 * n, 2 * n), dtype=complex)
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -Minv @ K
    A[n:, n:] = -Minv @ D
    lam, V = np.linalg.eig(A)
    return lam, V[:n, :]


# --------------------------------------------------------------------------------------------
# Results
# --------------------------------------------------------------------------------------------
@dataclass
class StabilityCurves:
    """V-g / V-f curves.

    Attributes
    ----------
    speed
        Airspeeds (m/s), shape (n,).
    frequency
        Modal frequencies (rad/s), shape (n_modes, n).
    damping
        k-method: required structural damping g; p-k / p: damping ratio zeta = -sigma/|lambda|
        (shape (n_modes, n)).  Flutter where a curve crosses 0 (g upward / zeta downward).
    damping_kind
        ``"g"`` or ``"zeta"``.
    """

    speed: np.ndarray
    frequency: np.ndarray
    damping: np.ndarray
    damping_kind: str


@dataclass
class SectionResult:
    """Result of a typical-section stability analysis.

    ``flutter_speed`` (m/s), ``flutter_frequency`` (rad/s), ``reduced_frequency`` (omega b/U) are
    None if no flutter was found up to the largest speed analysed.  ``flutter_mode`` is the
    complex eigenvector ``[h (m, positive along the lift), alpha (rad, nose-up)]`` scaled so that
    its largest component in ``[h/b, alpha]`` is 1.  ``divergence_speed`` is the closed form
    (None if ``a <= -1/2``), ``divergence_speed_numerical`` from the static eigenproblem.
    """

    method: str
    flutter_speed: float | None
    flutter_frequency: float | None
    reduced_frequency: float | None
    flutter_mode: np.ndarray | None
    divergence_speed: float | None
    divergence_speed_numerical: float | None
    curves: StabilityCurves
    max_speed: float = float("nan")
    extra: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """JSON-friendly summary (the ``windflutter section --json`` object; NaN -> None)."""
        def fin(x: float | None) -> float | None:
            return None if x is None or not math.isfinite(x) else float(x)

        return {
            "method": self.method,
            "flutter_speed": self.flutter_speed,
            "flutter_frequency": self.flutter_frequency,
            "flutter_frequency_hz": (None if self.flutter_frequency is None
                                     else self.flutter_frequency / TWO_PI),
            "reduced_frequency": self.reduced_frequency,
            "divergence_speed": self.divergence_speed,
            "divergence_speed_numerical": self.divergence_speed_numerical,
            "flutter_mode": (None if self.flutter_mode is None else
                             {"h_re": float(self.flutter_mode[0].real),
                              "h_im": float(self.flutter_mode[0].imag),
                              "alpha_re": float(self.flutter_mode[1].real),
                              "alpha_im": float(self.flutter_mode[1].imag)}),
            "max_speed_analysed": fin(self.max_speed),
        }


def _normalise_mode(sec: TypicalSection, v: np.ndarray) -> np.ndarray:
    """h down -> h up; scale so the largest of |h/b|, |alpha| is 1 (real)."""
    out = np.array([-v[0], v[1]], dtype=complex)
    scaled = np.array([out[0] / sec.semi_chord, out[1]])
    j = int(np.argmax(np.abs(scaled)))
    return out / scaled[j]


# --------------------------------------------------------------------------------------------
# Divergence
# --------------------------------------------------------------------------------------------
def divergence_speed(sec: TypicalSection) -> float | None:
    """Closed-form static divergence speed ``sqrt(K_a / (Cla rho b^2 (a + 1/2)))`` (m/s).

    None if ``a <= -1/2`` (elastic axis at or ahead of the aerodynamic centre).
    """
    e = sec.elastic_axis + 0.5
    if e <= 0:
        return None
    return math.sqrt(sec.pitch_stiffness / (sec.lift_slope * sec.air_density * sec.semi_chord**2 * e))


def divergence_speed_numerical(sec: TypicalSection) -> float | None:
    """Divergence speed from the static eigenproblem ``K_s x = U^2 Khat x`` (``Ka = U^2 Khat``).

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


# --------------------------------------------------------------------------------------------
# p-k
# --------------------------------------------------------------------------------------------
def _companion_parts(sec: TypicalSection, U: float) -> tuple[np.ndarray, np.ndarray]:
    """First-order companion matrix of the coupled system split as ``base + C * dC``.

    The state is ``[q, q']``; C enters linearly (circulatory terms), so p-k iterations only
    rescale ``dC``.
    """
    M, K = structural_matrices(sec)
    A2, A1, qc, w, r1, r0 = _aero_parts(sec, U)
    Minv = np.linalg.inv(M - A2)
    base = np.zeros((4, 4), dtype=complex)
    base[:2, 2:] = np.eye(2)
    base[2:, :2] = -Minv @ K
    base[2:, 2:] = Minv @ A1
    dC = np.zeros((4, 4), dtype=complex)
    dC[2:, :2] = qc * Minv @ np.outer(w, r0)
    dC[2:, 2:] = qc * Minv @ np.outer(w, r1)
    return base, dC


def _c_scalar(c_func: Callable, k: float) -> complex:
    """C(k) for one k; exact Theodorsen evaluated directly (hot loop of p-k / k-method)."""
    if c_func is theodorsen and 1e-12 < k < 1e8:
        h1 = special.hankel2(1, k)
        return complex(h1 / (h1 + 1j * special.hankel2(0, k)))
    return complex(np.asarray(c_func(k)))


def pk_eigen(
    sec: TypicalSection,
    U: float,
    lam_guess: complex,
    *,
    frozen_omega: float | None = None,
    c_func: Callable[[np.ndarray], np.ndarray] = theodorsen,
    tol: float = 1e-10,
    max_iter: int = 200,
    mode_index: int | None = None,
) -> tuple[complex, np.ndarray, float]:
    """p-k eigenvalue of one mode at speed U: iterate ``k = |Im lam| b / U`` to convergence.

    Parameters
    ----------
    sec, U
        Section and airspeed (m/s, > 0).
    lam_guess
        Starting eigenvalue (rad/s); the mode followed is the eigenvalue (Im >= 0) nearest to the
        current estimate.
    frozen_omega
        If given, k is frozen at ``frozen_omega b / U`` (the seed's assumption); no iteration.
    c_func
        Circulation function (default exact Theodorsen; e.g. ``lambda k: 1`` for quasi-steady).
    mode_index
        If given and both roots of the eigenproblem (at the mode's k) are oscillatory, the mode
        is the ``mode_index``-th root in ascending frequency (the usual p-k root ordering,
        robust near frequency coalescence); otherwise the root nearest the estimate.

    Returns
    -------
    lam, eigenvector (h down), k
    """
    b = sec.semi_chord
    base, dC = _companion_parts(sec, U)
    n = 2

    def solve(omega: float, ref: complex) -> tuple[complex, np.ndarray, float]:
        k = omega * b / U
        lams, V = np.linalg.eig(base + _c_scalar(c_func, k) * dC)
        cand = np.where(lams.imag >= -1e-12 * np.abs(lams))[0]
        if mode_index is not None and cand.size == n and np.all(
                lams[cand].imag > 1e-9 * np.abs(lams[cand])):
            j = cand[np.argsort(lams[cand].imag)[mode_index]]
        else:
            j = cand[np.argmin(np.abs(lams[cand] - ref))]
        return lams[j], V[:n, j], k

    lam = complex(lam_guess)
    if frozen_omega is not None:
        return solve(frozen_omega, lam)
    # Fixed point omega -> |Im lam(omega)| accelerated by the secant method on
    # F(omega) = |Im lam(omega)| - omega (falls back to plain/relaxed fixed-point steps).
    omega = abs(lam.imag)
    lam, vec, k = solve(omega, lam)
    F0 = abs(lam.imag) - omega
    w0 = omega
    omega = abs(lam.imag)
    for it in range(max_iter):
        lam_new, vec_new, k = solve(omega, lam)
        F1 = abs(lam_new.imag) - omega
        lam, vec = lam_new, vec_new
        if abs(F1) <= tol * max(1.0, omega):
            return lam, vec, abs(lam.imag) * b / U
        denom = F1 - F0
        step = -F1 * (omega - w0) / denom if denom != 0 else F1
        w_fp = abs(lam.imag) if it < 30 else omega + 0.5 * F1
        w_new = omega + step
        # accept the secant step only if it stays positive and not wildly far from the fixed point
        if not (np.isfinite(w_new) and w_new >= 0 and abs(w_new - w_fp) <= 2 * abs(F1) + 1e-300):
            w_new = w_fp
        w0, F0, omega = omega, F1, w_new
        if it >= 15 and abs(lam.imag) < 0.05 * abs(lam):
            break
    if abs(lam.imag) < 0.05 * abs(lam):
        # a (nearly) non-oscillatory, overdamped root: k is ~0 and its exact value is immaterial
        # (such roots are never reported as flutter)
        return lam, vec, abs(lam.imag) * b / U
    raise ConvergenceError(f"p-k iteration did not converge at U = {U:.6g} m/s (lambda ~ {lam:.6g})")


def _pk_track(sec_at: Callable[[float], tuple[TypicalSection, float]], params: np.ndarray,
              lam0: np.ndarray, **kw) -> tuple[np.ndarray, list[list[np.ndarray]]]:
    """Follow each mode of ``lam0`` along a parameter path; returns lam (n_modes, n)."""
    lam = np.full((len(lam0), len(params)), np.nan + 0j)
    vecs: list[list[np.ndarray]] = [[] for _ in lam0]
    for i, x in enumerate(params):
        sec, U = sec_at(x)
        try:
            for m in range(len(lam0)):
                guess = lam0[m] if i == 0 else (lam[m, i - 1] if i < 2 else
                                                 2 * lam[m, i - 1] - lam[m, i - 2])
                l, v, _ = pk_eigen(sec, U, guess, mode_index=m, **kw)
                lam[m, i] = l
                vecs[m].append(v)
        except ConvergenceError:
            if i < 2:
                raise
            # typically beyond divergence (real root pair): stop the curves here
            return lam[:, :i], vecs
    return lam, vecs


def locate_pk_onset(
    sec_at: Callable[[float], tuple[TypicalSection, float]],
    params: np.ndarray,
    lam0: np.ndarray,
    *,
    omega_min_ratio: float = 1e-3,
    xtol: float = 1e-10,
    max_depth: int = 5,
    **kw,
) -> dict:
    """Track p-k modes along a parameter path and locate the first flutter crossing.

    ``sec_at(x)`` returns ``(section, U)`` for the path parameter ``x`` (the airspeed for a plain
    section, the rotor speed for the rotor model).  Flutter is bracketed on the grid (a mode's
    ``sigma`` goes from < 0 to >= 0 while oscillating) and refined by Brent's method on the
    tracked mode's ``sigma``.  A root is accepted only if ``|sigma| <= 1e-6 |lambda|`` there;
    otherwise (e.g. the p-k root ordering swapped inside the cell, making ``sigma``
    discontinuous) the cell is subdivided and re-tracked, up to ``max_depth`` times.  Returns a
    dict with the curves and, if found, ``x``, ``lam_f``, ``vec``, ``k``, ``U``, ``mode``.
    """
    lam, _ = _pk_track(sec_at, params, lam0, **kw)
    params = params[: lam.shape[1]]
    scale = float(np.max(np.abs(lam0.imag))) if np.max(np.abs(lam0.imag)) > 0 else 1.0
    omega_min = omega_min_ratio * scale
    out = {"params": params, "lam": lam, "x": None, "n_tracked": lam.shape[1]}

    def in_cell(xs: np.ndarray, lams: np.ndarray, depth: int):
        """First confirmed root in the cells of ``xs`` (modes ``lams`` tracked on ``xs``)."""
        sig, om = lams.real, np.abs(lams.imag)
        for i in range(len(xs) - 1):
            modes = [m for m in range(lams.shape[0])
                     if sig[m, i] < 0 <= sig[m, i + 1] and om[m, i] > omega_min
                     and om[m, i + 1] > omega_min]
            if not modes:
                continue
            best = None
            for m in modes:
                start = lams[m, i]

                def f(x: float, start=start, m=m) -> float:
                    sec, U = sec_at(x)
                    return pk_eigen(sec, U, start, mode_index=m, **kw)[0].real

                a, b_ = xs[i], xs[i + 1]
                try:
                    fa, fb = f(a), f(b_)
                    if not (fa < 0 <= fb):
                        continue
                    xr = optimize.brentq(f, a, b_, xtol=xtol, rtol=4 * np.finfo(float).eps)
                    sec, U = sec_at(xr)
                    l, v, k = pk_eigen(sec, U, start, mode_index=m, **kw)
                except ConvergenceError:
                    continue
                if abs(l.real) <= 1e-6 * abs(l) + 1e-12 and (best is None or xr < best[0]):
                    best = (xr, m, l, v, k, U)
            if best is not None:
                return best
            if depth < max_depth:  # unconfirmed: subdivide this cell and look again
                sub = np.linspace(xs[i], xs[i + 1], 7)
                try:
                    sub_lam, _ = _pk_track(sec_at, sub, lams[:, i], **kw)
                except ConvergenceError:
                    continue
                found = in_cell(sub[: sub_lam.shape[1]], sub_lam, depth + 1)
                if found is not None:
                    return found
        return None

    found = in_cell(params, lam, 0)
    if found is not None:
        xr, m, l, v, k, U = found
        out.update(x=xr, lam_f=l, vec=v, k=k, U=U, mode=m)
    return out


def _default_speeds(sec: TypicalSection, n: int = 160) -> np.ndarray:
    """Speed grid (m/s) from ~0 to ``4 sqrt(mu) b omega_max`` (flutter of practical sections
    lies well inside: U_F/(b omega_alpha) is of order sqrt(mu)), capped at 3x divergence."""
    wmax = float(natural_frequencies(sec).max())
    umax = 4.0 * math.sqrt(max(sec.mass_ratio, 1.0)) * sec.semi_chord * wmax
    ud = divergence_speed(sec)
    if ud is not None:
        umax = min(umax, 3.0 * ud) if ud > 0.05 * umax else umax
    return np.linspace(umax / n, umax, n)


def pk_method(
    sec: TypicalSection,
    speeds: np.ndarray | None = None,
    *,
    c_func: Callable[[np.ndarray], np.ndarray] = theodorsen,
) -> SectionResult:
    """p-k flutter analysis of a typical section (see module docstring)."""
    speeds = _default_speeds(sec) if speeds is None else _check_speeds(speeds)
    lam0 = 1j * natural_frequencies(sec)
    res = locate_pk_onset(lambda U: (sec, U), speeds, lam0, c_func=c_func)
    lam = res["lam"]
    curves = StabilityCurves(
        speed=speeds[: lam.shape[1]],
        frequency=np.abs(lam.imag),
        damping=-lam.real / np.maximum(np.abs(lam), 1e-300),
        damping_kind="zeta",
    )
    return _result("pk", sec, res, curves, speeds)


def _result(method: str, sec: TypicalSection, res: dict, curves: StabilityCurves,
            speeds: np.ndarray) -> SectionResult:
    if res.get("x") is None:
        uf = wf = kf = None
        mode = None
    else:
        uf = float(res["U"])
        wf = float(abs(res["lam_f"].imag))
        kf = wf * sec.semi_chord / uf
        mode = _normalise_mode(sec, res["vec"])
    return SectionResult(
        method=method,
        flutter_speed=uf,
        flutter_frequency=wf,
        reduced_frequency=kf,
        flutter_mode=mode,
        divergence_speed=divergence_speed(sec),
        divergence_speed_numerical=divergence_speed_numerical(sec),
        curves=curves,
        max_speed=float(speeds[-1]),
    )


def _check_speeds(speeds: Any) -> np.ndarray:
    s = np.asarray(speeds, dtype=float)
    if s.ndim != 1 or s.size < 2 or np.any(~np.isfinite(s)) or np.any(s <= 0) or np.any(np.diff(s) <= 0):
        raise InputError("speeds", speeds, "an increasing array of >= 2 positive speeds (m/s)")
    return s


# --------------------------------------------------------------------------------------------
# k-method
# --------------------------------------------------------------------------------------------
def _k_eig(sec: TypicalSection, k: float, Minv_K: np.ndarray, M: np.ndarray,
           c_func: Callable = theodorsen) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues Z = (1 + i g)/omega^2 of ``K^-1 A(k)`` and eigenvectors."""
    b = sec.semi_chord
    Ma, Da1, Ka1 = aero_matrices(sec, 1.0, C=_c_scalar(c_func, k))
    A = (M - Ma) + 1j * (b / k) * Da1 + (b / k) ** 2 * Ka1
    Z, V = np.linalg.eig(Minv_K @ A)
    return Z, V


def k_method(
    sec: TypicalSection,
    k_values: np.ndarray | None = None,
    *,
    c_func: Callable[[np.ndarray], np.ndarray] = theodorsen,
) -> SectionResult:
    """k (V-g) method.  Branches are followed from high to low k by nearest-eigenvalue matching.

    Flutter: a branch's ``g = Im Z / Re Z`` crosses 0 from below as k decreases (U increases);
    the crossing is refined by Brent's method in k.  U = omega b / k with omega = 1/sqrt(Re Z).
    """
    if k_values is None:
        k_values = np.geomspace(5.0, 1e-3, 400)
    k_values = np.asarray(k_values, dtype=float)
    M, K = structural_matrices(sec)
    Kinv = np.linalg.inv(K)
    nk = k_values.size
    Z = np.zeros((2, nk), dtype=complex)
    for i, k in enumerate(k_values):
        z, _ = _k_eig(sec, k, Kinv, M, c_func)
        if i == 0:
            z = np.sort_complex(z)
        else:
            # nearest matching to the previous (linearly extrapolated) values
            ref = Z[:, i - 1] if i < 2 else 2 * Z[:, i - 1] - Z[:, i - 2]
            if abs(z[0] - ref[0]) + abs(z[1] - ref[1]) > abs(z[1] - ref[0]) + abs(z[0] - ref[1]):
                z = z[::-1]
        Z[:, i] = z
    with np.errstate(invalid="ignore", divide="ignore"):
        omega = np.where(Z.real > 0, 1.0 / np.sqrt(np.abs(Z.real)), np.nan)
        g = Z.imag / Z.real
        U = omega * sec.semi_chord / k_values[None, :]
    best = None
    for m in range(2):
        for i in range(nk - 1):
            if (Z.real[m, i] > 0 and Z.real[m, i + 1] > 0 and np.isfinite(g[m, i])
                    and np.isfinite(g[m, i + 1]) and g[m, i] < 0 <= g[m, i + 1]):
                ref = Z[m, i]

                def gfun(k: float, ref=ref) -> float:
                    # Im Z has the sign of g while Re Z > 0 and no poles: safer for Brent
                    z, _ = _k_eig(sec, k, Kinv, M, c_func)
                    return z[np.argmin(np.abs(z - ref))].imag

                kr = optimize.brentq(gfun, k_values[i + 1], k_values[i], xtol=1e-13)
                z, V = _k_eig(sec, kr, Kinv, M, c_func)
                j = int(np.argmin(np.abs(z - ref)))
                if z[j].real <= 0:
                    continue
                w = 1.0 / math.sqrt(z[j].real)
                uf = w * sec.semi_chord / kr
                if best is None or uf < best[0]:
                    best = (uf, w, kr, V[:, j])
                break
    curves = StabilityCurves(
        speed=U,  # per-branch speeds (n_modes, nk): the k-method has no common speed grid
        frequency=omega,
        damping=g,
        damping_kind="g",
    )
    if best is None:
        res = SectionResult("k", None, None, None, None, divergence_speed(sec),
                            divergence_speed_numerical(sec), curves,
                            max_speed=float(np.nanmax(U)))
    else:
        uf, w, kr, v = best
        res = SectionResult("k", float(uf), float(w), float(kr), _normalise_mode(sec, v),
                            divergence_speed(sec), divergence_speed_numerical(sec), curves,
                            max_speed=float(np.nanmax(U)))
    return res


# --------------------------------------------------------------------------------------------
# p-method on the Roger RFA state space
# --------------------------------------------------------------------------------------------
def rfa_state_matrix(sec: TypicalSection, U: float, rfa: RogerRFA) -> np.ndarray:
    """State matrix for states ``[q, q', y_1..y_n]`` (h down) with C(s) from a Roger RFA.

    ``C(sbar) ~ A0 + sum c_j sbar/(sbar + beta_j)``, ``sbar = s b / U``.  With the 3/4-chord
    downwash ``w34 = r1 q' + r0 q`` and lag states ``y_j' = -beta_j (U/b) y_j + w34``::

        C w34 = (A0 + sum c_j) w34 - sum c_j beta_j (U/b) y_j
    """
    if np.ndim(rfa.A0) != 0 or abs(float(rfa.A1)) > 0 or abs(float(rfa.A2)) > 0:
        raise InputError("rfa", rfa, "a scalar Roger fit of C(k) without polynomial s terms")
    M, K = structural_matrices(sec)
    A2, A1, qc, w, r1, r0 = _aero_parts(sec, U)
    b = sec.semi_chord
    nl = len(rfa.poles)
    c_inf = float(rfa.A0) + float(np.sum(rfa.lags))
    Meff = M - A2
    Minv = np.linalg.inv(Meff)
    n = 2
    A = np.zeros((2 * n + nl, 2 * n + nl))
    A[:n, n:2 * n] = np.eye(n)
    Kq = -K + qc * c_inf * np.outer(w, r0)
    Dq = A1 + qc * c_inf * np.outer(w, r1)
    A[n:2 * n, :n] = Minv @ Kq
    A[n:2 * n, n:2 * n] = Minv @ Dq
    for j, (beta, cj) in enumerate(zip(rfa.poles, rfa.lags)):
        A[n:2 * n, 2 * n + j] = Minv @ (-qc * float(cj) * beta * (U / b) * w)
        A[2 * n + j, :n] = r0
        A[2 * n + j, n:2 * n] = r1
        A[2 * n + j, 2 * n + j] = -beta * U / b
    return A


def p_method(
    sec: TypicalSection,
    speeds: np.ndarray | None = None,
    *,
    rfa: RogerRFA | None = None,
) -> SectionResult:
    """p-method: eigenvalues of the RFA state space; flutter where the largest real part of the
    oscillatory eigenvalues crosses 0 (bracket on the grid, then Brent)."""
    speeds = _default_speeds(sec) if speeds is None else _check_speeds(speeds)
    rfa = theodorsen_rfa() if rfa is None else rfa
    wscale = float(natural_frequencies(sec).max())
    nm = 2

    def modes(U: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        lam, V = np.linalg.eig(rfa_state_matrix(sec, U, rfa))
        osc = np.where(lam.imag > 1e-6 * wscale)[0]
        return lam, V, osc

    lam_grid = np.full((nm, speeds.size), np.nan + 0j)
    sig_max = np.full(speeds.size, np.nan)
    prev = 1j * natural_frequencies(sec)
    for i, U in enumerate(speeds):
        lam, _, osc = modes(U)
        lo = lam[osc]
        # follow the two structural modes by nearest match (aero lag roots are real)
        for m in range(nm):
            if lo.size:
                j = int(np.argmin(np.abs(lo - prev[m])))
                lam_grid[m, i] = lo[j]
        prev = lam_grid[:, i].copy()
        sig_max[i] = lo.real.max() if lo.size else -np.inf

    def f(U: float) -> float:
        lam, _, osc = modes(U)
        return float(lam[osc].real.max()) if osc.size else -1e300

    res: dict = {"x": None}
    idx = np.where((sig_max[:-1] < 0) & (sig_max[1:] >= 0))[0]
    if idx.size:
        i = int(idx[0])
        uf = optimize.brentq(f, speeds[i], speeds[i + 1], xtol=1e-12 * speeds[i + 1])
        lam, V, osc = modes(uf)
        j = osc[np.argmax(lam[osc].real)]
        res = {"x": uf, "U": uf, "lam_f": lam[j], "vec": V[:2, j]}
    curves = StabilityCurves(
        speed=speeds,
        frequency=np.abs(lam_grid.imag),
        damping=-lam_grid.real / np.maximum(np.abs(lam_grid), 1e-300),
        damping_kind="zeta",
    )
    return _result("p", sec, res, curves, speeds)


def analyse(sec: TypicalSection, method: str = "pk", speeds: np.ndarray | None = None) -> SectionResult:
    """Run one of ``"k"``, ``"pk"``, ``"p"``."""
    if method == "k":
        return k_method(sec)
    if method == "pk":
        return pk_method(sec, speeds)
    if method == "p":
        return p_method(sec, speeds)
    raise InputError("method", method, "one of 'k', 'pk', 'p'")
