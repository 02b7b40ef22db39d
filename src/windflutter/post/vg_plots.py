"""V-g / V-f plots of typical-section results and the simple-model onset curve (PNG, Agg)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed; must precede pyplot
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from windflutter.errors import InputError  # noqa: E402

__all__ = ["plot_vg", "plot_simple_model"]


def _check_out(path: str | Path) -> Path:
    p = Path(path)
    if p.suffix.lower() != ".png":
        raise InputError("--plot", str(path), "a file name ending in .png")
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError("--plot", str(path), f"a writable location ({exc.strerror})") from None
    return p


def save_figure(fig, p: Path) -> None:
    """Write ``fig`` to ``p`` (110 dpi) and close it; an unwritable path is an InputError of ``--plot``."""
    try:
        fig.savefig(p, dpi=110)
    except OSError as exc:
        raise InputError("--plot", str(p), f"a writable file ({exc.strerror})") from None
    finally:
        plt.close(fig)


def damping_curve(curves, m: int) -> np.ndarray:
    """The damping plotted for mode ``m``, with the turbine figures' sign (positive: damped,
    flutter where it crosses zero downwards): the damping ratio zeta for p-k / p; for the
    k method the equivalent damping ratio ``-g / 2`` (the structural damping ``g`` a harmonic
    motion needs is ``-2 zeta`` for small damping)."""
    return -0.5 * np.asarray(curves.damping[m]) if curves.damping_kind == "g" else np.asarray(curves.damping[m])


def vg_figure(result, title: str | None = None):
    """V-g (top) and V-f (bottom) curves of a :class:`~windflutter.section.SectionResult`
    (a pyplot figure; the caller closes it).  Frequencies in Hz; damping by :func:`damping_curve`;
    the flutter and divergence speeds marked."""
    c = result.curves
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 7))
    n_modes = c.frequency.shape[0]
    for m in range(n_modes):
        speed = c.speed[m] if np.ndim(c.speed) == 2 else c.speed
        ax1.plot(speed, damping_curve(c, m), label=f"mode {m + 1}")
        ax2.plot(speed, c.frequency[m] / (2 * math.pi), label=f"mode {m + 1}")
    ax1.axhline(0.0, color="k", lw=0.8)
    ax1.set_ylabel("-g/2 (k method: equivalent damping ratio, > 0 damped)" if c.damping_kind == "g"
                   else "damping ratio ζ (> 0 damped)")
    ax2.set_ylabel("frequency (Hz)")
    ax2.set_xlabel("airspeed U (m/s)")
    for ax in (ax1, ax2):
        if result.flutter_speed is not None:
            ax.axvline(result.flutter_speed, color="r", ls="--", lw=1,
                       label=f"flutter {result.flutter_speed:.4g} m/s")
        if result.divergence_speed is not None:
            ax.axvline(result.divergence_speed, color="m", ls=":", lw=1,
                       label=f"divergence {result.divergence_speed:.4g} m/s")
        ax.grid(True, alpha=0.3)
    ax1.legend(fontsize=8)
    xmax = result.max_speed if math.isfinite(result.max_speed) else None
    if result.flutter_speed is not None:
        xmax = min(xmax or np.inf, 2.0 * result.flutter_speed)
    if xmax:
        ax1.set_xlim(0, xmax)
        if c.damping_kind == "g":
            # k-method curves extend to huge speeds at small k: keep the y range readable
            ax1.set_ylim(-0.5, 0.5)
    fig.suptitle(title or f"Typical section, {result.method} method")
    fig.tight_layout()
    return fig


def plot_vg(result, path: str | Path, title: str | None = None) -> Path:
    """Write :func:`vg_figure` of a section result as a PNG; returns the path."""
    p = _check_out(path)
    save_figure(vg_figure(result, title), p)
    return p


def plot_simple_model(results: Sequence, path: str | Path, extra: Sequence | None = None) -> Path:
    """First unstable rotor speed vs wind speed, one panel per turbine.

    ``results`` are :class:`~windflutter.frozen.simple_model.SimpleModelResult`; ``extra``
    optional second results per turbine (e.g. frozen-k beside p-k), drawn dashed.  The range
    reported by the thesis (fig. 4.7) is shaded.
    """
    p = _check_out(path)
    n = len(results)
    fig, axes = plt.subplots(1, n, figsize=(5.5 * n, 4.2), squeeze=False)
    for i, res in enumerate(results):
        ax = axes[0, i]
        rs = res.turbine
        sets = [res] + ([extra[i]] if extra else [])
        colours = ("tab:blue", "tab:orange")
        for j, r in enumerate(sets):
            ws = [pt.wind_speed for pt in r.points]
            name = "frozen k (thesis)" if r.frozen_k else "p-k (k matched)"
            ax.plot(ws, r.first_unstable_rpm, "o-" if j == 0 else "s--", ms=3, color=colours[j],
                    label=f"first unstable, {name}")
            flut = np.array([pt.flutter_rpm for pt in r.points])
            if np.any(np.isfinite(flut)):
                ax.plot(ws, flut, "x:", ms=4, lw=0.8, color=colours[j],
                        label=f"flutter onset, {name}")
            div = np.array([pt.divergence_rpm for pt in r.points])
            if j == 0 and np.any(np.isfinite(div)):
                ax.plot(ws, div, "-", lw=3, alpha=0.3, color="gray", label="divergence (static)")
        if rs.reported_rpm:
            lo, hi = rs.reported_rpm
            ax.axhspan(lo, hi, color="orange", alpha=0.3, label=f"thesis fig. 4.7: {lo}-{hi} RPM")
        ax.set_title(f"{rs.label}: section at r = {rs.radius} m")
        ax.set_xlabel("wind speed [m/s]")
        ax.set_ylabel("rotor speed [RPM]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Seed simple model (Castillo Capponi 2010, ch. 4.1.8)")
    fig.tight_layout()
    save_figure(fig, p)
    return p
