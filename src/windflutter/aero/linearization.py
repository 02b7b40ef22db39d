"""Steady linearization data of the strips: polar values and LOCAL slopes at each steady angle.

The mean-load and state-space operators (:mod:`windflutter.aero.unsteady`) linearize each strip's
force about its steady state.  They need, per strip ``j`` at its steady angle of attack
``alpha0_j`` (rad, :func:`windflutter.aero.flow.section_flow`):

* the polar values ``Cl0, Cd0, Cm0`` (``Cm`` about the quarter chord, nose-up positive);
* the local slopes ``dCl/dalpha, dCd/dalpha, dCm/dalpha`` (1/rad) -- not one straight line over
  the attached range (that is :func:`windflutter.aero.polars.fit_polar`, the seed's viscous
  model), but the slope of the table where the strip works;
* the aerodynamic centre implied by them, ``x_ac = -dCm/dCl`` (fraction of chord aft of the
  quarter chord);
* optionally the steady separation point of the Kirchhoff/Oye decomposition (dynamic stall).

Differentiation
---------------
The tables are piecewise linear (``np.interp``, end values held outside the table).  The slope
at ``alpha0`` is the centred difference over ``+-delta`` (default 1 deg)::

    dC/dalpha (alpha0) = (C(alpha0 + delta) - C(alpha0 - delta)) / (2 delta)

which is the mean of the table's segment slopes over ``[alpha0 - delta, alpha0 + delta]``
(the derivative of the table smoothed by a box of width ``2 delta``): exact on a straight
polar, second-order accurate (``O(delta^2 C''')``) on a smooth one, and insensitive to a kink or
a noisy point of the table, which a one-segment slope would pick up.  A point within ``delta``
of a table end gets the one-sided slope of the remaining part (the held end value has slope 0).

In stall the local lift slope is small or NEGATIVE and the drag slope large: that is the
physics (it is what makes stall-induced edgewise vibrations possible), not an error, and it is
passed on unchanged.  ``x_ac`` is reported as NaN where ``|dCl/dalpha| < 1e-3`` (the moment
slope is then not a lift acting somewhere; the operators use ``dCm/dalpha`` directly and never
divide by the lift slope).

Separation point (dynamic stall option)
---------------------------------------
Kirchhoff's flat-plate relation, as used by Oye (1991) and Hansen, Gaunaa & Madsen (2004,
Risoe-R-1354) and OpenFAST's AeroDyn (UA theory, "separation function")::

    Cl = Cl_a (alpha - alpha_z) ((1 + sqrt f) / 2)^2   ->   f = (2 sqrt(Cl / (Cl_a (alpha - alpha_z))) - 1)^2

clipped to ``[0, 1]`` (1 near ``alpha_z``, 0 once the root drops below 1/2), with ``Cl_a`` and the
zero-lift angle ``alpha_z`` from the attached-range fit (:func:`~windflutter.aero.polars.fit_polar`).
The fully separated lift is ``Cl_fs = (Cl - Cl_a (alpha - alpha_z) f) / (1 - f)`` (``Cl / 2`` where
``f = 1``), so that ``Cl = f Cl_a (alpha - alpha_z) + (1 - f) Cl_fs`` holds at every angle.  The
operators need ``f``, ``df/dalpha`` and ``dCl/df = Cl_a (alpha - alpha_z) - Cl_fs`` at ``alpha0``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.polars import fit_polar
from windflutter.aero.sections import AeroSections, Polar
from windflutter.errors import InputError

__all__ = ["Separation", "StripLinearization", "polar_linearization", "flat_plate_linearization",
           "centred_slope", "kirchhoff_separation", "kirchhoff_curves"]

#: Default half-width of the centred difference of the polar tables (rad): 1 degree.
SLOPE_STEP = np.radians(1.0)


@dataclass(frozen=True)
class Separation:
    """Steady separation state of each strip (Kirchhoff decomposition of its polar), arrays (ns,).

    f : separation point ``f_st(alpha0)`` (-, 1 attached, 0 fully separated).
    df : ``d f_st / d alpha`` at ``alpha0`` (1/rad).
    dcl_df : ``dCl/df = Cl_a (alpha0 - alpha_z) - Cl_fs(alpha0)`` (-): the lift change when the
        separation point moves by one chord fraction at fixed angle.
    """

    f: np.ndarray
    df: np.ndarray
    dcl_df: np.ndarray


@dataclass(frozen=True)
class StripLinearization:
    """Steady strip state and local polar slopes at the steady angles of attack (arrays (ns,)).

    alpha : steady angle of attack (rad).  cl, cd, cm : polar values there (-; cm about the
    quarter chord, nose-up positive).  dcl, dcd, dcm : local slopes (1/rad), see the module
    docstring.  separation : the Kirchhoff separation state for dynamic stall, or None.
    """

    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    cm: np.ndarray
    dcl: np.ndarray
    dcd: np.ndarray
    dcm: np.ndarray
    separation: Separation | None = None

    @property
    def n_sections(self) -> int:
        return int(np.shape(self.alpha)[0])

    @property
    def aerodynamic_centre(self) -> np.ndarray:
        """``x_ac = -dCm/dCl`` (fraction of chord aft of the quarter chord); NaN where
        ``|dCl/dalpha| < 1e-3`` (stall peak, cylinder)."""
        ok = np.abs(self.dcl) >= 1e-3
        return np.where(ok, -self.dcm / np.where(ok, self.dcl, 1.0), np.nan)

    def take(self, idx) -> "StripLinearization":
        """The linearization of the strips ``idx`` (e.g. a parent map of sub-strips)."""
        sep = None if self.separation is None else Separation(*(np.asarray(x)[idx] for x in (
            self.separation.f, self.separation.df, self.separation.dcl_df)))
        return StripLinearization(*(np.asarray(getattr(self, n))[idx] for n in (
            "alpha", "cl", "cd", "cm", "dcl", "dcd", "dcm")), separation=sep)


def centred_slope(x: np.ndarray, y: np.ndarray, at: np.ndarray, delta: float = SLOPE_STEP) -> np.ndarray:
    """Centred-difference slope ``(y(at + delta) - y(at - delta)) / (2 delta)`` of the linearly
    interpolated table ``(x, y)`` (x increasing), vectorized over ``at``."""
    if not (np.isfinite(delta) and delta > 0):
        raise InputError("slope_step", delta, "a positive angle step (rad)")
    at = np.asarray(at, float)
    return (np.interp(at + delta, x, y) - np.interp(at - delta, x, y)) / (2.0 * delta)


def _check_polar(p: Polar, k: int) -> tuple[np.ndarray, ...]:
    a = np.asarray(p.alpha, float)
    cols = [np.asarray(c, float) for c in (p.cl, p.cd, p.cm)]
    if a.ndim != 1 or a.size < 2 or any(c.shape != a.shape for c in cols):
        raise InputError(f"polars[{k}] ({p.name})", a.shape, "alpha, cl, cd, cm arrays of equal length >= 2")
    if np.any(np.diff(a) <= 0) or not all(np.all(np.isfinite(c)) for c in [a, *cols]):
        raise InputError(f"polars[{k}].alpha ({p.name})", "not increasing or not finite",
                         "finite, increasing angles of attack (rad) and finite coefficients")
    return (a, *cols)


def kirchhoff_curves(polar: Polar):
    """``curves(alpha) -> (f_st, Cl_fs, Cl_att)`` of one polar at angles ``alpha`` (rad): the steady
    separation point, the fully separated lift and the attached (inviscid) lift ``Cl_a (alpha -
    alpha_z)`` of the Kirchhoff decomposition (module docstring), so that ``Cl = f_st Cl_att + (1 -
    f_st) Cl_fs``; None for a polar without lift slope (cylinder: nothing separates)."""
    fit = fit_polar(polar)
    a, cl = np.asarray(polar.alpha, float), np.asarray(polar.cl, float)
    if fit.cl_alpha <= 0:
        return None

    def curves(x):
        x = np.asarray(x, float)
        c = np.interp(x, a, cl)
        inv = fit.cl_alpha * (x - fit.alpha_zero_lift)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(np.abs(inv) > 1e-9, c / np.where(np.abs(inv) > 1e-9, inv, 1.0), 1.0)
        f = np.clip(2.0 * np.sqrt(np.clip(ratio, 0.0, None)) - 1.0, 0.0, 1.0) ** 2
        one = f >= 1.0 - 1e-12
        fs = np.where(one, 0.5 * c, (c - inv * f) / np.where(one, 1.0, 1.0 - f))
        return f, fs, inv

    return curves


def kirchhoff_separation(polar: Polar, alpha: np.ndarray, delta: float = SLOPE_STEP) -> Separation:
    """Steady separation state of one polar at angles ``alpha`` (rad), see the module docstring."""
    alpha = np.asarray(alpha, float)
    curves = kirchhoff_curves(polar)
    if curves is None:  # no lift slope (cylinder): nothing separates, no lift lag
        z = np.zeros_like(alpha)
        return Separation(f=z, df=z, dcl_df=z)
    f, fs, inv = curves(alpha)
    df = (curves(alpha + delta)[0] - curves(alpha - delta)[0]) / (2.0 * delta)
    return Separation(f=f, df=df, dcl_df=inv - fs)


def polar_linearization(sections: AeroSections, alpha: np.ndarray, delta: float = SLOPE_STEP,
                        separation: bool = False) -> StripLinearization:
    """Polar values and local slopes of every strip at its steady angle ``alpha`` (rad, (ns,)).

    Parameters
    ----------
    sections : the strips (``airfoil`` indexes ``polars``).
    alpha : steady angles of attack (rad), e.g. ``section_flow(sections, op).alpha``.
    delta : half-width of the centred difference (rad), 1 deg by default.
    separation : also compute the Kirchhoff separation state (for dynamic stall).
    """
    if not sections.polars:
        raise InputError("sections.polars", "[]", "airfoil polars for the steady linearization "
                         "(or the flat-plate linearization)")
    idx = np.asarray(sections.airfoil, dtype=np.int64)
    alpha = np.asarray(alpha, float)
    ns = sections.n_sections
    if alpha.shape != (ns,) or not np.all(np.isfinite(alpha)):
        raise InputError("alpha", alpha.shape, f"{ns} finite steady angles of attack (rad)")
    if idx.size and (idx.min() < 0 or idx.max() >= len(sections.polars)):
        raise InputError("sections.airfoil", int(idx.max()), f"indices into {len(sections.polars)} polars")
    out = np.zeros((6, ns))
    sep = np.zeros((3, ns)) if separation else None
    for k in np.unique(idx):  # one pass per airfoil, vectorized over its strips
        sel = idx == k
        a, *cols = _check_polar(sections.polars[int(k)], int(k))
        for row, c in enumerate(cols):
            out[row, sel] = np.interp(alpha[sel], a, c)
            out[3 + row, sel] = centred_slope(a, c, alpha[sel], delta)
        if separation:
            s = kirchhoff_separation(sections.polars[int(k)], alpha[sel], delta)
            sep[:, sel] = (s.f, s.df, s.dcl_df)
    return StripLinearization(alpha, *out, separation=None if sep is None else Separation(*sep))


def flat_plate_linearization(alpha: np.ndarray) -> StripLinearization:
    """The thin flat plate of potential flow: ``Cl = 2 pi alpha``, ``Cd = Cm = 0`` (quarter chord)
    -- the linearization of the "potential" variant (no polars needed, no stall)."""
    alpha = np.asarray(alpha, float)
    z = np.zeros_like(alpha)
    return StripLinearization(alpha, 2 * np.pi * alpha, z, z, np.full_like(alpha, 2 * np.pi), z, z)
