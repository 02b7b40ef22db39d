"""Results of a typical-section analysis, and the speed grid and crossing helpers all methods share."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.section.matrices import (
    divergence_speed,
    divergence_speed_numerical,
    natural_frequencies,
)
from windflutter.section.model import TWO_PI, TypicalSection


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

    @classmethod
    def from_roots(cls, speed: np.ndarray, lam: np.ndarray) -> "StabilityCurves":
        """Curves of the roots ``lam`` (rad/s, (n_modes, n)) at ``speed``: frequency ``|Im|``, zeta."""
        return cls(
            speed=speed,
            frequency=np.abs(lam.imag),
            damping=-lam.real / np.maximum(np.abs(lam), 1e-300),
            damping_kind="zeta",
        )


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


def normalise_mode(sec: TypicalSection, v: np.ndarray) -> np.ndarray:
    """h down -> h up; scale so the largest of |h/b|, |alpha| is 1 (real)."""
    out = np.array([-v[0], v[1]], dtype=complex)
    scaled = np.array([out[0] / sec.semi_chord, out[1]])
    j = int(np.argmax(np.abs(scaled)))
    return out / scaled[j]


def section_result(method: str, sec: TypicalSection, curves: StabilityCurves, max_speed: float,
                   flutter: tuple[float, float, float, np.ndarray] | None) -> SectionResult:
    """The result of ``method``; ``flutter`` is ``(U (m/s), omega (rad/s), k, vector (h down))``
    of the flutter point, or None; divergence is added here."""
    uf = wf = kf = mode = None
    if flutter is not None:
        uf, wf, kf = (float(x) for x in flutter[:3])
        mode = normalise_mode(sec, flutter[3])
    return SectionResult(
        method=method,
        flutter_speed=uf,
        flutter_frequency=wf,
        reduced_frequency=kf,
        flutter_mode=mode,
        divergence_speed=divergence_speed(sec),
        divergence_speed_numerical=divergence_speed_numerical(sec),
        curves=curves,
        max_speed=float(max_speed),
    )


def default_speeds(sec: TypicalSection, n: int = 160) -> np.ndarray:
    """Speed grid (m/s) from ~0 to ``4 sqrt(mu) b omega_max`` (flutter of practical sections
    lies well inside: U_F/(b omega_alpha) is of order sqrt(mu)), capped at 3x divergence."""
    wmax = float(natural_frequencies(sec).max())
    umax = 4.0 * math.sqrt(max(sec.mass_ratio, 1.0)) * sec.semi_chord * wmax
    ud = divergence_speed(sec)
    if ud is not None:
        umax = min(umax, 3.0 * ud) if ud > 0.05 * umax else umax
    return np.linspace(umax / n, umax, n)


def check_speeds(speeds: Any) -> np.ndarray:
    """``speeds`` (m/s) as an increasing array of >= 2 positive values, else :class:`InputError`."""
    s = np.asarray(speeds, dtype=float)
    if s.ndim != 1 or s.size < 2 or np.any(~np.isfinite(s)) or np.any(s <= 0) or np.any(np.diff(s) <= 0):
        raise InputError("speeds", speeds, "an increasing array of >= 2 positive speeds (m/s)")
    return s


def extrapolate(history: np.ndarray, i: int) -> np.ndarray:
    """Linear prediction of column ``i`` of ``history`` from the two before it (one: constant)."""
    return history[:, i - 1] if i < 2 else 2 * history[:, i - 1] - history[:, i - 2]
