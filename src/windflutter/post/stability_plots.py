"""Stability map and Campbell diagram from :class:`~windflutter.results.PointSummary`."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def stability_map(points, label: str = "", ax=None):
    """Flutter (solid) and divergence (dashed) onset rotor speed (RPM) vs wind speed (m/s)."""
    fig = None
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
    V = np.array([p.wind_speed for p in points])
    fl = np.array([np.nan if p.flutter_rpm is None else p.flutter_rpm for p in points])
    dv = np.array([np.nan if p.divergence_rpm is None else p.divergence_rpm for p in points])
    ax.plot(V, fl, "o-", label=f"flutter {label}".strip())
    ax.plot(V, dv, "s--", label=f"divergence {label}".strip())
    ax.set_xlabel("wind speed (m/s)")
    ax.set_ylabel("onset rotor speed (RPM)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return fig or ax.figure


def campbell(point):
    """Frequency (Hz) and damping ratio of the tracked modes vs rotor speed (RPM) at one wind speed."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    r = np.asarray(point.sweep_rpm)
    f = np.asarray(point.damped_frequency_hz)
    z = np.asarray(point.damping_ratio)
    labels = point.mode_labels or [f"mode {i + 1}" for i in range(f.shape[1])]
    for i in range(f.shape[1]):
        a1.plot(r, f[:, i], label=labels[i] if i < len(labels) else None)
        a2.plot(r, z[:, i])
    for k in (1, 3, 6, 9):  # rotor-speed harmonics
        a1.plot(r, k * r / 60.0, "k:", lw=0.7)
    if point.flutter_rpm is not None:
        for a in (a1, a2):
            a.axvline(point.flutter_rpm, color="r", lw=0.8)
    a2.axhline(0.0, color="k", lw=0.8)
    a1.set_ylabel("frequency (Hz)")
    a2.set_ylabel("damping ratio (-)")
    a2.set_xlabel("rotor speed (RPM)")
    a1.set_title(f"V = {point.wind_speed:g} m/s")
    a1.legend(fontsize=6, ncol=2)
    for a in (a1, a2):
        a.grid(True, alpha=0.3)
    return fig
