"""Airfoil contour helpers: nondimensional arc length and chordwise stations on the contour.

Contours are ordered TE -> suction side -> LE -> pressure side -> TE (as normalised by the
readers), coordinates normalised by chord, x from the leading edge.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError


def nd_arc(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Nondimensional arc length (0 at the first point, 1 at the last) along the contour."""
    seg = np.hypot(np.diff(x), np.diff(y))
    s = np.concatenate([[0.0], np.cumsum(seg)])
    return s / s[-1]


def le_index(x: np.ndarray) -> int:
    """Index of the leading-edge point (minimum x)."""
    return int(np.argmin(x))


def arc_at_chord_x(x: np.ndarray, y: np.ndarray, xc: float | np.ndarray, side: str) -> np.ndarray:
    """Nondimensional arc position where the contour crosses chordwise position ``xc`` (x/c) on
    the ``"suction"`` (first half) or ``"pressure"`` side.

    ``xc`` is clipped to the airfoil's x range.
    """
    s = nd_arc(x, y)
    i = le_index(x)
    if side == "suction":
        xs, ss = x[: i + 1][::-1], s[: i + 1][::-1]  # LE -> TE, x increasing
    elif side == "pressure":
        xs, ss = x[i:], s[i:]
    else:
        raise InputError("side", side, "'suction' or 'pressure'")
    order = np.argsort(xs, kind="stable")
    xs, ss = xs[order], ss[order]
    xq = np.clip(np.asarray(xc, dtype=float), xs[0], xs[-1])
    return np.interp(xq, xs, ss)


def perimeter(x: np.ndarray, y: np.ndarray) -> float:
    """Contour length normalised by chord (-)."""
    return float(np.sum(np.hypot(np.diff(x), np.diff(y))))


def orient_contour(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Order a contour TE -> suction side (y > 0) -> LE -> pressure side -> TE.

    windIO fixes nondimensional arc 0 at the trailing edge, increasing over the suction side, but
    some files (e.g. the NREL 5 MW DU airfoils in WISDEM's examples) list the pressure side first.
    A contour traversed TE -> upper -> LE -> lower -> TE encloses positive signed area
    (counter-clockwise), so the arrays are reversed when the signed area is negative.
    """
    area = 0.5 * np.sum(x[:-1] * y[1:] - x[1:] * y[:-1])
    if area < 0:
        return x[::-1].copy(), y[::-1].copy()
    return x, y


def thickness_ratio(x: np.ndarray, y: np.ndarray) -> float:
    """Largest thickness of a normalised contour (t/c), from its two sides sampled at equal x."""
    i = le_index(x)
    xs, ys = x[: i + 1][::-1], y[: i + 1][::-1]
    xp, yp = x[i:], y[i:]
    if xs.size < 2 or xp.size < 2:
        return float(np.ptp(y))
    xg = np.linspace(max(xs.min(), xp.min()), min(xs.max(), xp.max()), 201)
    o_s, o_p = np.argsort(xs, kind="stable"), np.argsort(xp, kind="stable")
    return float(np.max(np.interp(xg, xs[o_s], ys[o_s]) - np.interp(xg, xp[o_p], yp[o_p])))
