"""The tip response of ``windflutter simulate --confirm-onset`` at each rotor speed (PNG, Agg)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed; must precede pyplot
import matplotlib.pyplot as plt  # noqa: E402

from windflutter.errors import InputError  # noqa: E402
from windflutter.post.vg_plots import save_figure  # noqa: E402

__all__ = ["check_png", "plot_onset_check"]


def check_png(path) -> Path:
    """``path`` as a Path if it names a PNG in an existing folder, else InputError."""
    p = Path(path)
    if p.suffix.lower() != ".png":
        raise InputError("--plot", str(path), "a .png file name")
    if not p.parent.exists():
        raise InputError("--plot", str(path), "a file in an existing folder")
    return p


def plot_onset_check(res, path) -> Path:
    """One panel per rotor speed: the tip translation relative to its steady position (mm), with
    the identified growth rate and the eigenvalue's in the title."""
    p = check_png(path)
    n = len(res.checks)
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(7, 2.4 * n + 0.6), squeeze=False)
    for ax, c in zip(axes[:, 0], res.checks):
        for k, name in enumerate(("x (downwind)", "y", "z")):
            ax.plot(c.t, 1e3 * c.tip[:, k], lw=0.8, label=name)
        ax.set_ylabel("tip (mm)")
        ax.set_title(f"{c.factor:.2f} x onset = {c.rpm:.2f} RPM: sigma simulated {c.sigma_sim:+.4f} 1/s, "
                     f"eigenvalue {c.sigma_eig:+.4f} 1/s", fontsize=9)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8, loc="upper right")
    axes[-1, 0].set_xlabel("time (s)")
    what = "the whole turbine, blade 1's tip in its frame" if res.part == "turbine" else "rotor on a clamped hub"
    fig.suptitle(f"{res.mode} onset {res.onset_rpm:.2f} RPM at {res.wind_speed:g} m/s ({what})", fontsize=10)
    fig.tight_layout()
    save_figure(fig, p)
    return p
