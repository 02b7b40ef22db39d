"""k (V-g) method of the typical section: artificial structural damping for harmonic motion.

For each reduced frequency k the eigenproblem ``K^-1 A(k) q = Z q``, ``Z = (1 + i g)/omega^2``;
branches followed from high to low k by nearest matching; flutter where a branch's
``g = Im Z / Re Z`` crosses 0 from below (U = omega b / k increasing), refined by Brent's method.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy import optimize

from windflutter.aero.theodorsen import theodorsen
from windflutter.section.matrices import (
    CirculationFunction,
    aero_matrices,
    c_scalar,
    structural_matrices,
)
from windflutter.section.model import TypicalSection
from windflutter.section.results import (
    SectionResult,
    StabilityCurves,
    extrapolate,
    section_result,
)


def _k_eig(sec: TypicalSection, k: float, Kinv: np.ndarray, M: np.ndarray,
           C: complex) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues Z = (1 + i g)/omega^2 (s^2) of ``K^-1 A(k)`` and eigenvectors; ``C = C(k)``."""
    b = sec.semi_chord
    Ma, Da1, Ka1 = aero_matrices(sec, 1.0, C=C)
    A = (M - Ma) + 1j * (b / k) * Da1 + (b / k) ** 2 * Ka1
    Z, V = np.linalg.eig(Kinv @ A)
    return Z, V


def _k_branches(eig: Callable[..., tuple[np.ndarray, np.ndarray]], k_values: np.ndarray,
                C: np.ndarray) -> np.ndarray:
    """Z of the two branches (2, nk), followed along ``k_values`` (``C`` = C(k) there) by
    nearest matching to the linearly extrapolated previous values."""
    Z = np.zeros((2, k_values.size), dtype=complex)
    for i, k in enumerate(k_values):
        z, _ = eig(k, complex(C[i]))
        if i == 0:
            z = np.sort_complex(z)
        else:
            ref = extrapolate(Z, i)
            if abs(z[0] - ref[0]) + abs(z[1] - ref[1]) > abs(z[1] - ref[0]) + abs(z[0] - ref[1]):
                z = z[::-1]
        Z[:, i] = z
    return Z


def _k_flutter(eig: Callable[..., tuple[np.ndarray, np.ndarray]], k_values: np.ndarray,
               Z: np.ndarray, g: np.ndarray, b: float):
    """Lowest-speed crossing ``(U, omega, k, vector)`` of g through 0 over the branches, or None."""
    best = None
    for m in range(2):
        for i in range(k_values.size - 1):
            if not (Z.real[m, i] > 0 and Z.real[m, i + 1] > 0 and np.isfinite(g[m, i])
                    and np.isfinite(g[m, i + 1]) and g[m, i] < 0 <= g[m, i + 1]):
                continue
            ref = Z[m, i]

            def gfun(k: float, ref=ref) -> float:
                # Im Z has the sign of g while Re Z > 0 and no poles: safer for Brent
                z, _ = eig(k)
                return z[np.argmin(np.abs(z - ref))].imag

            kr = optimize.brentq(gfun, k_values[i + 1], k_values[i], xtol=1e-13)
            z, V = eig(kr)
            j = int(np.argmin(np.abs(z - ref)))
            if z[j].real <= 0:
                continue
            w = 1.0 / math.sqrt(z[j].real)
            uf = w * b / kr
            if best is None or uf < best[0]:
                best = (uf, w, kr, V[:, j])
            break
    return best


def k_method(sec: TypicalSection, k_values: np.ndarray | None = None, *,
             c_func: CirculationFunction = theodorsen) -> SectionResult:
    """k (V-g) method on ``k_values`` (descending; default 400 from 5 to 1e-3, geometric).

    Flutter: a branch's ``g = Im Z / Re Z`` crosses 0 from below as k decreases (U increases);
    the crossing is refined by Brent's method in k.  U = omega b / k with omega = 1/sqrt(Re Z).
    """
    if k_values is None:
        k_values = np.geomspace(5.0, 1e-3, 400)
    k_values = np.asarray(k_values, dtype=float)
    M, K = structural_matrices(sec)
    Kinv = np.linalg.inv(K)

    def eig(k: float, C: complex | None = None) -> tuple[np.ndarray, np.ndarray]:
        return _k_eig(sec, k, Kinv, M, c_scalar(c_func, k) if C is None else C)

    # C on the whole grid in one vectorised call (the same values as one k at a time)
    Z = _k_branches(eig, k_values, np.broadcast_to(np.asarray(c_func(k_values)), k_values.shape))
    with np.errstate(invalid="ignore", divide="ignore"):
        omega = np.where(Z.real > 0, 1.0 / np.sqrt(np.abs(Z.real)), np.nan)
        g = Z.imag / Z.real
        U = omega * sec.semi_chord / k_values[None, :]
    # per-branch speeds (n_modes, nk): the k-method has no common speed grid
    curves = StabilityCurves(speed=U, frequency=omega, damping=g, damping_kind="g")
    flutter = _k_flutter(eig, k_values, Z, g, sec.semi_chord)
    return section_result("k", sec, curves, float(np.nanmax(U)), flutter)
