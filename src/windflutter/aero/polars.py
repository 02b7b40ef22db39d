"""Linear fits of airfoil polars over the attached-flow range (seed ch. 3.2, viscous model).

The attached-flow range of a polar is found as the contiguous interval of angles of attack
around the zero-lift angle where the local lift slope stays above half of the slope at zero
lift and below the stall peaks, limited to ``max_range`` on either side.  Over that range
``Cl`` is fitted by a least-squares straight line (slope ``Cl_alpha``, 1/rad); ``Cd`` by a
straight line over the positive part of the range (zero lift .. positive end, where operating
blade sections work), slope ``Cd_alpha`` (1/rad).  Polars without a lift slope (cylinders) give ``Cl_alpha = 0``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.aero.sections import Polar
from windflutter.errors import InputError


@dataclass(frozen=True)
class PolarFit:
    """Linear fit of one polar.

    Attributes
    ----------
    cl_alpha, cd_alpha : slopes (1/rad).  alpha_zero_lift : zero-lift angle (rad).
    alpha_min, alpha_max : attached-flow range used (rad).  n_points : points in the fit.
    name : airfoil name.
    cm_alpha : slope of the quarter-chord pitching moment over the same range as ``cl_alpha``
        (1/rad, nose-up positive); 0 without a lift slope.
    """

    cl_alpha: float
    cd_alpha: float
    alpha_zero_lift: float
    alpha_min: float
    alpha_max: float
    n_points: int
    name: str = ""
    cm_alpha: float = 0.0

    @property
    def ac_shift(self) -> float:
        """Aerodynamic centre aft of the quarter chord, fraction of chord: ``-Cm_alpha / Cl_alpha``
        (0 without a lift slope)."""
        return -self.cm_alpha / self.cl_alpha if self.cl_alpha > 0 else 0.0


def fit_polar(polar: Polar, max_range: float = np.radians(12.0), slope_fraction: float = 0.5) -> PolarFit:
    """Fit ``Cl = Cl_alpha (alpha - alpha_0)`` and ``Cd`` linearly over the attached-flow range.

    Parameters
    ----------
    polar : the airfoil polar (alpha in rad).
    max_range : largest distance from the zero-lift angle kept on either side (rad).
    slope_fraction : the range ends where the local lift slope drops below this fraction of the
        slope at zero lift (onset of separation).
    """
    a = np.asarray(polar.alpha, float)
    cl = np.asarray(polar.cl, float)
    cd = np.asarray(polar.cd, float)
    if a.ndim != 1 or a.size < 2 or cl.shape != a.shape or cd.shape != a.shape:
        raise InputError(f"polar[{polar.name}]", a.shape, "alpha, cl, cd arrays of equal length >= 2")
    if np.any(np.diff(a) <= 0):
        raise InputError(f"polar[{polar.name}].alpha", "not increasing", "increasing angles of attack (rad)")
    if np.ptp(cl) < 1e-3:
        # no lift at any angle (a cylinder, often given by two points only, e.g. the IEA 15 MW
        # root "circular" polar): no lift or drag slope
        return PolarFit(0.0, 0.0, 0.0, float(a.min()), float(a.max()), int(a.size), polar.name)
    if a.size < 3:
        raise InputError(f"polar[{polar.name}]", a.shape, "at least 3 points for a lift slope")
    # candidate window around small angles, where attached flow lives
    win = np.abs(a) <= np.radians(20.0)
    if win.sum() < 3 or np.ptp(cl[win]) < 1e-3:
        return PolarFit(0.0, 0.0, 0.0, float(a[win].min()) if win.any() else 0.0,
                        float(a[win].max()) if win.any() else 0.0, int(win.sum()), polar.name)
    # zero-lift angle: first upward zero crossing of Cl inside the window
    aw, clw = a[win], cl[win]
    cross = np.where((clw[:-1] <= 0) & (clw[1:] > 0))[0]
    if cross.size:
        i = cross[np.argmin(np.abs(aw[cross]))]
        a0 = aw[i] - clw[i] * (aw[i + 1] - aw[i]) / (clw[i + 1] - clw[i])
    else:
        a0 = aw[np.argmin(np.abs(clw))]
    slope = np.gradient(cl, a)
    i0 = int(np.argmin(np.abs(a - a0)))
    s0 = np.median(slope[max(i0 - 1, 0): i0 + 2])
    if s0 <= 0:
        return PolarFit(0.0, 0.0, float(a0), float(a0), float(a0), 0, polar.name)
    ok = (slope >= slope_fraction * s0) & (np.abs(a - a0) <= max_range)
    lo = hi = i0
    while lo - 1 >= 0 and ok[lo - 1]:
        lo -= 1
    while hi + 1 < a.size and ok[hi + 1]:
        hi += 1
    if hi - lo < 2:
        lo, hi = max(i0 - 1, 0), min(i0 + 1, a.size - 1)
    sel = slice(lo, hi + 1)
    A = np.vstack([a[sel], np.ones(hi - lo + 1)]).T
    cla = float(np.linalg.lstsq(A, cl[sel], rcond=None)[0][0])
    # drag: fitted on the positive side of the attached range (alpha0 .. alpha_max), where an
    # operating blade section works; over the whole range the bucket-shaped Cd would give a
    # slope set by the range's asymmetry only
    pos = np.arange(lo, hi + 1)[a[lo:hi + 1] >= a0]
    if pos.size >= 2:
        Ap = np.vstack([a[pos], np.ones(pos.size)]).T
        cda = float(np.linalg.lstsq(Ap, cd[pos], rcond=None)[0][0])
    else:
        cda = float(np.linalg.lstsq(A, cd[sel], rcond=None)[0][0])
    cm = np.asarray(polar.cm, float)
    cma = float(np.linalg.lstsq(A, cm[sel], rcond=None)[0][0]) if cm.shape == a.shape else 0.0
    return PolarFit(cla, cda, float(a0), float(a[lo]), float(a[hi]), hi - lo + 1, polar.name, cma)

