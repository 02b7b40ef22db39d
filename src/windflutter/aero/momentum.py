"""The thrust--induction relation of the BEM: the axial induction ``a`` of an annulus whose blade
elements carry the thrust ``C_T = 4 F k (1 - a)^2`` (``k = sigma' cn / (4 F sin^2 phi)``, see
:mod:`windflutter.aero.induction`).

Three relations, chosen by name (``high_thrust``; the same name in the config,
``solver.high_thrust``):

* ``"buhl"`` (default; OpenFAST AeroDyn's): momentum ``C_T = 4 F a (1 - a)`` up to ``a = 0.4``,
  Buhl's (2005, NREL/TP-500-36834) empirical turbulent-wake thrust above,
  ``C_T = 8/9 + (4F - 40/9) a + (50/9 - 4F) a^2``, equal to momentum in value and slope at 0.4;
* ``"madsen"`` (HAWC2's and HAWCStab2's): ``a = k3 C_T^3 + k2 C_T^2 + k1 C_T`` of the tip-loss
  corrected local thrust coefficient ``C_T / F`` at every load, with ``k3 = 0.0883``,
  ``k2 = 0.0586``, ``k1 = 0.2460`` (Madsen, Larsen, Pirrung, Li and Zahle 2020, *Wind Energ.
  Sci.* 5:1-27, "Implementation of the blade element momentum model on a polar grid and its
  aeroelastic load impact"); within 1.6 % of momentum's ``a`` at small loads and within 2 % of
  Buhl's up to ``C_T = 0.85``, it gives less induction above (``C_T = 1``: 0.393 against Buhl's
  0.446), where a rotor at low wind and high tip-speed ratio works;
* ``"momentum"``: momentum everywhere (no turbulent-wake correction; ``a -> 1`` as ``C_T -> 1``).

Units: dimensionless.
"""

from __future__ import annotations

import numpy as np

from windflutter.aero_types import HIGH_THRUST
from windflutter.errors import InputError

__all__ = ["HIGH_THRUST", "high_thrust_model", "buhl_axial", "madsen_axial", "axial_from_k"]

_A_SWITCH = 0.4  # momentum / Buhl switch (a); k = a / (1 - a) = 2/3 there
#: Madsen et al. (2020): a = k1 C_T + k2 C_T^2 + k3 C_T^3
MADSEN = (0.2460, 0.0586, 0.0883)


def high_thrust_model(value) -> str:
    """The relation's name from ``value``: one of :data:`HIGH_THRUST`, or True (``"buhl"``) and
    False (``"momentum"``) as the earlier on/off switch."""
    if isinstance(value, (bool, np.bool_)):
        return "buhl" if value else "momentum"
    if isinstance(value, str) and value in HIGH_THRUST:
        return value
    raise InputError("high_thrust", value, "one of " + ", ".join(HIGH_THRUST) + " (or true / false)")


def buhl_axial(k, F) -> np.ndarray:
    """Axial induction in Buhl's high-thrust region, from ``k = sigma' cn / (4 F sin^2 phi)``.

    Equating the blade-element thrust ``4 F k (1 - a)^2`` with Buhl's
    ``8/9 + (4F - 40/9) a + (50/9 - 4F) a^2`` gives a quadratic in ``a``; its physical root,
    written without the cancellation of the textbook ``(g1 - sqrt(g2)) / g3`` form, is
    ``a = (2 F k - 4/9) / (g1 + sqrt(g2))``, ``g1 = 2 F k + F - 10/9``,
    ``g2 = 2 F k - F (4/3 - F)`` (no special case where ``g3 = 2 F k + 2 F - 25/9`` vanishes).
    """
    k = np.asarray(k, float)
    F = np.asarray(F, float)
    g1 = 2.0 * F * k + F - 10.0 / 9.0
    g2 = np.maximum(2.0 * F * k - F * (4.0 / 3.0 - F), 0.0)
    return (2.0 * F * k - 4.0 / 9.0) / (g1 + np.sqrt(g2))


def madsen_axial(k, iterations: int = 40, tol: float = 1e-14) -> np.ndarray:
    """Axial induction of Madsen's relation, the root of ``h(a) = a - P(4 k (1 - a)^2)`` with
    ``P`` the cubic of :data:`MADSEN` (``4 k (1 - a)^2`` is the tip-loss corrected ``C_T / F``).

    For ``k > 0``, ``h`` is increasing and concave on ``[0, 1]`` (``P`` is increasing and convex
    for ``C_T > 0``) with ``h(0) < 0 < h(1)``: Newton's method from ``a = 0`` climbs to the root
    monotonically, without overshoot.  ``k <= 0`` (no thrust or a negative one) takes momentum's
    ``k / (1 + k)``, which ``P`` equals to first order there (slopes 1 and 0.984).
    """
    k = np.asarray(k, float)
    k1, k2, k3 = MADSEN
    pos = k > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(pos, 0.0, k / (1.0 + k))
    kp = np.where(pos, k, 0.0)
    x = np.zeros_like(kp)
    for _ in range(iterations):
        c = 4.0 * kp * (1.0 - x) ** 2
        h = x - c * (k1 + c * (k2 + c * k3))
        dh = 1.0 + (k1 + c * (2.0 * k2 + 3.0 * c * k3)) * 8.0 * kp * (1.0 - x)
        step = -h / dh
        x = np.minimum(x + step, 1.0)
        if not np.any(np.abs(step[pos]) > tol):
            break
    return np.where(pos, x, a)


def axial_from_k(k, F, high_thrust="buhl") -> np.ndarray:
    """Axial induction ``a`` (-) of the windmill state for ``k = sigma' cn / (4 F sin^2 phi)`` and
    the loss factor ``F`` by the relation ``high_thrust`` (module docstring; True / False are
    ``"buhl"`` / ``"momentum"``)."""
    model = high_thrust_model(high_thrust)
    k = np.asarray(k, float)
    if model == "madsen":
        return madsen_axial(k)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = k / (1.0 + k)
        if model == "buhl":
            hi = k > _A_SWITCH / (1.0 - _A_SWITCH)
            if np.any(hi):
                a = np.where(hi, buhl_axial(np.where(hi, k, 1.0), np.broadcast_to(F, k.shape)), a)
    return a
