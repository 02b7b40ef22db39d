"""Shared pieces of the figures: colours per mode family, line styles per whirl, label placement
without overprinting, and the damping axis scaled to the lightly damped modes.

* :func:`spread_labels` -- positions for text labels as close as possible (least squares) to where
  they belong, at least one line height apart and inside the axis (exact: isotonic regression).
* :func:`damping_split` -- where to break a damping axis so that the lightly damped modes fill the
  main panel and the heavily damped ones (flap modes in operation, 10-60 %) go to a small panel.
* :func:`label_ends` -- write the names of lines at their ends, spread apart.

Everything here works on a :class:`matplotlib.figure.Figure` laid out with fixed axes positions,
so the size of an axis in points is known before drawing.
"""

from __future__ import annotations

import math

import numpy as np

#: one colour per mode family (red is kept for instability marks)
FAMILY_COLOURS = {"flap": "tab:blue", "edge": "tab:orange", "torsion": "tab:purple",
                  "tower_fa": "tab:brown", "tower_ss": "tab:olive", "tower_torsion": "tab:pink",
                  "tower_wall": "tab:green", "drivetrain": "tab:gray", "other": "tab:cyan"}
#: readable family names for legends
FAMILY_NAMES = {"flap": "flap", "edge": "edge", "torsion": "torsion", "tower_fa": "tower fore-aft",
                "tower_ss": "tower side-side", "tower_torsion": "tower torsion",
                "tower_wall": "tower wall",
                "drivetrain": "drivetrain", "other": "other"}
#: one line style per whirl
WHIRL_STYLES = {"collective": "-", "BW": "--", "FW": "-.", "none": ":"}
WHIRL_NAMES = {"collective": "collective", "BW": "backward whirl (BW)", "FW": "forward whirl (FW)",
               "none": "fixed frame (tower, drivetrain)"}
UNSTABLE_COLOUR = "tab:red"
LABEL_FONTSIZE = 7.5
MIN_FONTSIZE = 5.0
#: vertical distance between label centres, in multiples of the font size
LINE_SPACING = 1.2


def _isotonic(y: np.ndarray) -> np.ndarray:
    """Least-squares non-decreasing fit of ``y`` (pool-adjacent-violators)."""
    vals: list[float] = []
    sizes: list[int] = []
    for v in y:
        vals.append(float(v))
        sizes.append(1)
        while len(vals) > 1 and vals[-2] > vals[-1]:
            n = sizes[-2] + sizes[-1]
            m = (vals[-2] * sizes[-2] + vals[-1] * sizes[-1]) / n
            vals[-2:] = [m]
            sizes[-2:] = [n]
    return np.repeat(vals, sizes)


def spread_labels(y, gap: float, lo: float = -math.inf, hi: float = math.inf) -> np.ndarray:
    """Label positions closest to ``y`` with neighbours at least ``gap`` apart, within ``[lo, hi]``.

    Minimises ``sum (p_i - y_i)^2`` subject to ``p_(k+1) - p_k >= gap`` in the order of ``y``
    (ties keep their input order) and ``lo <= p <= hi``.  With ``z_k = p_k - k gap`` this is an
    isotonic regression of ``y_k - k gap`` with bounds, whose solution is the unbounded one
    clipped.  When ``n`` labels cannot fit (``(n - 1) gap > hi - lo``) the gap shrinks to fit.

    Parameters
    ----------
    y : wanted positions (any unit, e.g. data units of the axis).
    gap : minimum distance between neighbouring labels (same unit).
    lo, hi : bounds of the positions.

    Returns
    -------
    positions in the input order.
    """
    y = np.asarray(y, float).ravel()
    n = y.size
    if n == 0:
        return y.copy()
    if not np.all(np.isfinite(y)):
        raise ValueError("label positions must be finite")
    if n > 1 and math.isfinite(hi - lo) and (n - 1) * gap > hi - lo:
        gap = (hi - lo) / (n - 1)
    order = np.argsort(y, kind="stable")
    k = np.arange(n) * gap
    z = _isotonic(y[order] - k)
    z = np.clip(z, lo, hi - k[-1]) if lo <= hi - k[-1] else np.full(n, lo)
    out = np.empty(n)
    out[order] = z + k
    return out


def axis_height_pt(ax) -> float:
    """Height of an axis in points (fixed-position layouts)."""
    fig = ax.figure
    return float(ax.get_position().height * fig.get_figheight() * 72.0)


def label_ends(ax, x, y, texts, colours, *, x_text=None, fontsize: float = LABEL_FONTSIZE,
               leader: bool = True) -> list:
    """Write ``texts`` at the right of the points ``(x, y)`` (data units), spread apart vertically.

    ``x_text``: the x of the text column in axes fraction (e.g. 1.01: the right margin); None: at
    the points themselves, 4 pt to their right (all points of one call should share their x).
    The y limits must be final.  When the labels do not fit the axis height at ``fontsize``, the
    type shrinks to fit (down to :data:`MIN_FONTSIZE`).  Returns the Text artists.
    """
    y = np.asarray(y, float)
    if y.size == 0:
        return []
    y0, y1 = ax.get_ylim()
    h = axis_height_pt(ax)
    fontsize = max(min(fontsize, h / (LINE_SPACING * y.size)), MIN_FONTSIZE)  # smaller type when crowded
    gap = LINE_SPACING * fontsize / h * (y1 - y0)
    pos = spread_labels(np.clip(y, y0, y1), gap, y0 + 0.5 * gap, y1 - 0.5 * gap)
    out = []
    for xi, yi, pi, t, c in zip(np.broadcast_to(x, y.shape), y, pos, texts, colours):
        if x_text is None:
            kw = dict(xytext=(4, 0), textcoords="offset points", xy=(xi, pi))
        else:
            kw = dict(xy=(xi, yi), xytext=(x_text, pi), textcoords=("axes fraction", "data"))
            if leader:
                kw["arrowprops"] = dict(arrowstyle="-", color=c, lw=0.5, alpha=0.6, shrinkA=0, shrinkB=1)
        out.append(ax.annotate(t, fontsize=fontsize, color=c, va="center", ha="left",
                               annotation_clip=False, **kw))
    return out


def damping_split(z, light: float = 0.10, floor: float = 0.02):
    """Limits of a damping axis (same unit as ``z``, a damping ratio, not %): ``(lo, cut, top)``.

    The main panel spans ``[lo, cut]``: the lines whose median damping is below ``light`` (10 %:
    edge, tower, drivetrain modes; not the aerodynamically damped flap modes), with 15 % head
    room, at least ``floor`` (2 %), at most ``light``; ``lo`` shows the zero line with some
    negative room (more when a mode is unstable).  ``top`` is the upper limit of a second panel
    for what lies above ``cut``; None when nothing does (no second panel needed).

    Parameters
    ----------
    z : (n_x, n_lines) damping ratios, NaN where a line is absent.
    """
    z = np.asarray(z, float)
    if z.ndim == 1:
        z = z[:, None]
    fin = z[np.isfinite(z)]
    if fin.size == 0:
        return -0.2 * floor, floor, None
    with np.errstate(all="ignore"):
        med = np.nanmedian(np.where(np.isfinite(z), z, np.nan), axis=0)
    lightly = z[:, np.isfinite(med) & (med < light)]
    peak = float(np.nanmax(lightly)) if lightly.size and np.any(np.isfinite(lightly)) else floor
    cut = min(max(1.15 * peak, floor), light)
    zmin = float(fin.min())
    lo = min(-0.08 * cut, 1.15 * zmin - 0.03 * cut)
    top = float(fin.max())
    return lo, cut, (1.06 * top if top > cut else None)


def damping_panels(fig, rect, lo: float, cut: float, top: float | None, draw, high_share: float = 0.25) -> list:
    """The damping axis in ``rect`` (left, bottom, width, height; figure fraction): one panel
    ``[lo, cut]``, or, when ``top`` is given, a main panel ``[lo, cut]`` under a small one
    ``[cut, top]`` (``high_share`` of the height) with break marks between them.  ``draw(ax)``
    plots the lines into a panel (called for each).  The zero line is drawn and the negative
    region shaded.  Returns the axes, top first."""
    left, bottom, width, height = rect
    axes = []
    if top is not None:
        hh = high_share * height
        axh = fig.add_axes((left, bottom + height - hh, width, hh))
        draw(axh)
        axh.set_ylim(cut, top)
        axh.spines["bottom"].set_visible(False)
        axh.tick_params(bottom=False, labelbottom=False)
        axh.text(0.005, 0.95, "heavily damped (axis broken)", transform=axh.transAxes, fontsize=7,
                 va="top", color="0.35")
        axes.append(axh)
        height -= hh + 0.012
    axl = fig.add_axes((left, bottom, width, height))
    draw(axl)
    axl.set_ylim(lo, cut)
    axl.axhline(0.0, color="k", lw=1.0)
    axl.axhspan(lo, 0.0, color=UNSTABLE_COLOUR, alpha=0.08, lw=0)
    if top is not None:
        axl.spines["top"].set_visible(False)
        for ax, y in ((axes[0], 0.0), (axl, 1.0)):  # the break marks, 6 pt tall
            d = 3.0 / axis_height_pt(ax)
            ax.plot([-0.006, 0.006], [y - d, y + d], transform=ax.transAxes, color="k", lw=1, clip_on=False)
    axes.append(axl)
    return axes
