"""The operating-point Campbell figure: frequency and damping ratio of every mode vs wind speed.

One colour per mode family, one line style per whirl (:mod:`windflutter.post.figstyle`), a line
per mode track; the 1P/3P/6P/9P excitation lines from the operating rotor speed; the names at
the line ends spread apart (no overprinting); the damping axis scaled to the lightly damped
modes with the heavily damped ones (flap modes in operation) on a small panel above a break;
a zero-damping line with the negative region shaded; the least damped mode marked (star) and
unstable points marked (red crosses); the legend grouped (families, whirls, marks) below the
axes.  The drivetrain's rigid-body root is not drawn (it is no vibration mode).

Drawn from the Campbell dataset alone (:func:`windflutter.post.campbell_data.campbell_dataset`),
so a stored diagram can be re-plotted.  Matplotlib's object interface (no pyplot state).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from windflutter.errors import InputError
from windflutter.post import figstyle as fs
from windflutter.post.campbell_data import as_campbell_dataset, least_damped, present, track_style_keys

HARMONICS = (1, 3, 6, 9)
#: axes rectangles (left, bottom, width, height; figure fraction) of the 11 x 8.5 in figure
_FIG = (11.0, 8.5)
_LEFT, _WIDTH = 0.075, 0.66
_FREQ = (0.585, 0.355)
_HIGH = (0.455, 0.095)
_LOW = (0.165, 0.285)


def _tracks(ds):
    """Per drawn track: (index, name, family, whirl); rigid-body-only tracks left out."""
    pres = present(ds)
    rigid = ds["rigid_body"].values == 1
    out = []
    for t, (name, fam, whirl) in enumerate(track_style_keys(ds)):
        if pres[:, t].any() and not np.all(rigid[pres[:, t], t]):
            out.append((t, name, fam, whirl))
    return out


def _draw_lines(ax, v, y, tracks, unstable_t, **kw):
    for t, _, fam, whirl in tracks:
        ax.plot(v, y[:, t], ls=fs.WHIRL_STYLES.get(whirl, "-"), color=fs.FAMILY_COLOURS.get(fam, "k"),
                marker="o", ms=2.5, lw=2.4 if t in unstable_t else 1.3, **kw)


def _harmonic_lines(ax, v, rpm, fmax, harmonics):
    for n in harmonics:
        f = n * rpm / 60.0
        ax.plot(v, f, color="0.55", lw=0.8, ls=(0, (4, 3)), zorder=0)
        inside = np.where(f <= fmax)[0]
        if inside.size == 0:
            continue
        j = inside[-1]
        if j == len(v) - 1:
            xy, dy, va = (v[j], f[j]), 2, "bottom"
        else:  # where the line leaves the top of the axis: the name inside, under the edge
            x = np.interp(fmax, [f[j], f[j + 1]], [v[j], v[j + 1]])
            xy, dy, va = (x, fmax), -2, "top"
        ax.annotate(f"{n}P", xy, xytext=(-3, dy), textcoords="offset points", ha="right", va=va,
                    fontsize=7.5, color="0.35")


def _end_labels(ax, v, y, tracks, top=None, bottom=None):
    """Names at the line ends: lines reaching the last wind speed in the right margin, the others
    at their last point (spread apart per column).  ``top`` / ``bottom``: only lines whose end
    value lies in that range."""
    ends: dict[int, list] = {}
    for t, name, fam, _ in tracks:
        rows = np.where(np.isfinite(y[:, t]))[0]
        if rows.size == 0:
            continue
        r, val = rows[-1], y[rows[-1], t]
        if (top is not None and val > top) or (bottom is not None and val < bottom):
            continue
        ends.setdefault(int(r), []).append((val, name, fs.FAMILY_COLOURS.get(fam, "k")))
    texts = []
    last = len(v) - 1
    for r, items in ends.items():
        ys, names, cols = zip(*items)
        texts += fs.label_ends(ax, v[r], ys, names, cols, x_text=1.012 if r == last else None)
    return texts


def _legend(fig, tracks, harmonics):
    fams = list(dict.fromkeys(f for _, _, f, _ in tracks))
    whirls = [w for w in fs.WHIRL_STYLES if any(w == x for _, _, _, x in tracks)]
    groups = [
        ("mode family", [Line2D([], [], color=fs.FAMILY_COLOURS.get(f, "k"), lw=2) for f in fams],
         [fs.FAMILY_NAMES.get(f, f) for f in fams]),
        ("whirl", [Line2D([], [], color="k", ls=fs.WHIRL_STYLES[w], lw=1.3) for w in whirls],
         [fs.WHIRL_NAMES[w] for w in whirls]),
        ("marks", [Line2D([], [], color="0.55", ls=(0, (4, 3)), lw=0.8),
                   Line2D([], [], ls="", marker="*", ms=11, mfc="gold", mec="k"),
                   Line2D([], [], ls="", marker="x", ms=7, mew=2, color=fs.UNSTABLE_COLOUR)],
         [" / ".join(f"{n}P" for n in harmonics) + " (rotor speed multiples)", "least damped mode",
          "negative damping (unstable)"]),
    ]
    x = 0.02
    for title, handles, labels in groups:
        leg = fig.legend(handles, labels, title=title, loc="lower left", bbox_to_anchor=(x, 0.005),
                         fontsize=7.5, title_fontsize=8, ncols=2 if len(labels) > 4 else 1, frameon=True)
        x += leg.get_window_extent().width / (fig.dpi * fig.get_figwidth()) + 0.015


def campbell_figure(campbell, harmonics=HARMONICS, max_hz: float | None = None, title: str | None = None) -> Figure:
    """The Campbell figure (see the module docstring).

    Parameters
    ----------
    campbell : a :class:`~windflutter.system.campbell.CampbellResult` or its dataset.
    harmonics : rotor-speed multiples drawn (1P, 3P, ...).
    max_hz : upper frequency limit (Hz); default 8 % above the highest mode.
    title : figure title; default names the turbine and the part.
    """
    ds = as_campbell_dataset(campbell)
    v = ds["wind_speed"].values
    f = np.where(present(ds), ds["frequency"].values, np.nan)
    z = np.where(present(ds), ds["damping_ratio"].values, np.nan)
    tracks = _tracks(ds)
    drawn = [t for t, *_ in tracks]
    unstable_t = {t for t in drawn if np.nanmin(z[:, t]) < 0}
    fig = Figure(figsize=_FIG)
    axf = fig.add_axes((_LEFT, _FREQ[0], _WIDTH, _FREQ[1]))
    fmax = max_hz or (1.08 * float(np.nanmax(f[:, drawn])) if drawn else 1.0)
    _draw_lines(axf, v, f, tracks, unstable_t)
    _harmonic_lines(axf, v, ds["rotor_speed"].values, fmax, harmonics)
    axf.set_ylim(0, fmax)
    axf.set_ylabel("frequency (Hz)")
    axf.set_title(title or f"Campbell diagram — {ds.attrs.get('turbine', '')} ({ds.attrs.get('part', '')}, "
                  f"{ds.attrs.get('frame', 'ground-fixed')} frame)", fontsize=10)
    lo, cut, top = fs.damping_split(z[:, drawn] if drawn else z)
    axes_z = _damping_axes(fig, v, 100 * z, tracks, unstable_t, 100 * lo, 100 * cut, None if top is None else 100 * top)
    for ax in (axf, *axes_z):
        pad = 0.02 * np.ptp(v) if v.size > 1 else 1.0
        ax.set_xlim(v[0] - pad, v[-1] + pad)
        ax.grid(alpha=0.3)
    axes_z[-1].set_xlabel("wind speed (m/s)")
    for ax in (axf, *axes_z[:-1]):
        ax.tick_params(labelbottom=False)
    _mark_least_damped(ds, axf, axes_z, cut)
    _end_labels(axf, v, f, tracks)
    _end_labels(axes_z[-1], v, 100 * z, tracks, top=100 * cut)
    if len(axes_z) > 1:
        _end_labels(axes_z[0], v, 100 * z, tracks, bottom=100 * cut)
    _legend(fig, tracks, harmonics)
    return fig


def _damping_axes(fig, v, zp, tracks, unstable_t, lo, cut, top):
    """The damping panel(s) in %: the main one ``[lo, cut]`` and, if ``top``, a small one above."""
    rect = (_LEFT, _LOW[0], _WIDTH, _HIGH[0] + _HIGH[1] - _LOW[0])
    axes = fs.damping_panels(fig, rect, lo, cut, top, lambda ax: _draw_lines(ax, v, zp, tracks, unstable_t),
                             high_share=0.22)
    bad = np.where(np.nan_to_num(zp, nan=1.0) < 0)
    if bad[0].size:
        axes[-1].plot(v[bad[0]], zp[bad], "x", ms=8, mew=2, color=fs.UNSTABLE_COLOUR, zorder=7)  # over the star
    axes[-1].set_ylabel("damping ratio ζ (%)")
    return axes


def _mark_least_damped(ds, axf, axes_z, cut):
    ld = least_damped(ds)
    if ld is None:
        return
    star = dict(marker="*", ms=14, mfc="gold", mec="k", ls="", zorder=6)
    axf.plot([ld["wind_speed"]], [ld["frequency_hz"]], **star)
    z = ld["damping_ratio"]
    ax = axes_z[-1] if z <= cut or len(axes_z) == 1 else axes_z[0]
    ax.plot([ld["wind_speed"]], [100 * z], **star)
    word = "UNSTABLE" if z < 0 else "least damped"
    axes_z[0].set_title(f"{word}: {ld['name']}, ζ = {100 * z:.2f} % at {ld['wind_speed']:g} m/s "
                        f"({ld['frequency_hz']:.3f} Hz, {ld['rotor_speed_rpm']:.2f} RPM)", fontsize=9,
                        color=fs.UNSTABLE_COLOUR if z < 0 else "k")


PLOT_FORMATS = (".png", ".pdf", ".svg")


def save_campbell_plot(campbell, path, dpi: int = 110, field: str = "--plot", **kw) -> Path:
    """Draw :func:`campbell_figure` (``kw`` passed on) and write it to ``path`` (.png, .pdf, .svg).

    Raises
    ------
    InputError
        another file type, a folder, or a location that cannot be written (``field`` names the
        option).
    """
    p = Path(path)
    if p.suffix.lower() not in PLOT_FORMATS:
        raise InputError(field, str(path), f"a file name ending in {', '.join(PLOT_FORMATS)}")
    if p.is_dir():
        raise InputError(field, str(path), "a file name, not a folder")
    fig = campbell_figure(campbell, **kw)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(p, dpi=dpi)
    except OSError as exc:
        raise InputError(field, str(path), f"a writable file ({exc.strerror})") from None
    finally:
        fig.clear()
    return p
