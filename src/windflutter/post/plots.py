"""Figures of a run, drawn from the results dataset alone (so any stored run can be re-plotted).

* :func:`stability_map` — flutter and divergence onset rotor speed vs wind speed, per case, with
  the turbine's operating rotor-speed curve and the rated and overspeed lines;
* :func:`campbell` — frequency vs rotor speed of the tracked modes, coloured by damping ratio,
  with the 1P/3P/6P excitation lines and mode labels;
* :func:`damping_plot` — V-g / V-f style: damping ratio and frequency of each mode vs rotor speed;
* :func:`flutter_mode` — the flutter mode's flap / edge / torsion amplitude and phase along span;
* :func:`aero_work_plot` — aerodynamic work per cycle per station, split into plunge / pitch /
  edgewise (:mod:`windflutter.post.aerowork`).

Matplotlib's object interface is used (``Figure``, no pyplot state), so nothing here depends on
a display or a global backend.  Rotor speeds in RPM, frequencies in Hz (user units).
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.colors import TwoSlopeNorm
from matplotlib.figure import Figure

from windflutter.post import figstyle as fs
from windflutter.system.campbell import HEAVILY_DAMPED
from windflutter.post.fmt import field_label
from windflutter.post.store import flutter_shape

CASE_STYLES = {("potential", "pk"): "C0", ("viscous", "pk"): "C1",
               ("potential", "thesis"): "C2", ("viscous", "thesis"): "C3"}
COMPONENT_STYLE = {"flap": "C0", "edge": "C1", "torsion": "C3"}


def cases(ds: xr.Dataset) -> list[tuple[str, str]]:
    """The (aero, method) cases present, in point order."""
    out: list[tuple[str, str]] = []
    if "point" not in ds.dims or ds.sizes["point"] == 0:
        return out
    for a, m in zip(ds["aero"].values, ds["method"].values):
        if (str(a), str(m)) not in out:
            out.append((str(a), str(m)))
    return out


def case_points(ds: xr.Dataset, case: tuple[str, str]) -> xr.Dataset:
    sel = (ds["aero"] == case[0]) & (ds["method"] == case[1])
    return ds.isel(point=np.where(sel.values)[0])


def critical_point(ds: xr.Dataset, case: tuple[str, str]) -> int | None:
    """Index (into ``ds.point``) of the case's lowest flutter onset; else its first ok point."""
    sel = np.where(((ds["aero"] == case[0]) & (ds["method"] == case[1])).values)[0]
    if sel.size == 0:
        return None
    f = ds["flutter_rpm"].values[sel]
    if np.any(np.isfinite(f)):
        return int(sel[np.nanargmin(f)])
    ok = [i for i in sel if str(ds["status"].values[i]) == "ok"]
    return int(ok[0]) if ok else None


def _case_name(case: tuple[str, str]) -> str:
    return f"{case[0]}, {case[1]}"


def _reference_lines(ax, ds: xr.Dataset, vertical: bool = False) -> None:
    """The rated and overspeed rotor speeds of the run as lines (horizontal: RPM on the y axis)."""
    line = ax.axvline if vertical else ax.axhline
    for key, color, ls, what in (("rated_rpm", "k", "-.", "rated"), ("overspeed_rpm", "0.4", ":", "overspeed")):
        v = ds.attrs.get(key)
        if v is not None and np.isfinite(v):
            line(v, color=color, lw=1.0, ls=ls, label=f"{what} {v:.1f} RPM")


def stability_map(ds: xr.Dataset) -> Figure:
    """Onset rotor speed (RPM) vs wind speed (m/s)."""
    fig = Figure(figsize=(9.5, 4.8), layout="constrained")
    ax = fig.add_subplot()
    for case in cases(ds):
        c = case_points(ds, case)
        col = CASE_STYLES.get(case, None)
        v = c["wind_speed"].values
        ax.plot(v, c["flutter_rpm"].values, "o-", color=col, label=f"flutter ({_case_name(case)})")
        if np.any(np.isfinite(c["divergence_rpm"].values)):
            ax.plot(v, c["divergence_rpm"].values, "s--", color=col, mfc="none",
                    label=f"divergence ({_case_name(case)})")
        failed = np.array([str(s) != "ok" for s in c["status"].values])
        if failed.any():
            lab = "failed point" if "failed point" not in ax.get_legend_handles_labels()[1] else None
            ax.plot(v[failed], np.zeros(failed.sum()), "x", color="r", ms=9, clip_on=False, label=lab)
    if "operating_rpm" in ds:
        ax.plot(ds["operating_wind_speed"].values, ds["operating_rpm"].values, "-", color="k",
                lw=2, label="operating rotor speed")
    _reference_lines(ax, ds)
    ax.set_xlabel("wind speed (m/s)")
    ax.set_ylabel("rotor speed (RPM)")
    ax.set_title(f"Stability map — {ds.attrs.get('turbine', '')}")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    fig.legend(fontsize=8, loc="outside right upper")  # outside the axes: covers no data
    return fig


def _sweep(ds: xr.Dataset, i: int):
    p = ds.isel(point=i)
    rpm = p["rotor_speed"].values
    ok = np.isfinite(rpm)
    freq = p["damped_frequency" if "damped_frequency" in p else "frequency"].values[ok]  # (before issue 29: "frequency")
    zeta = p["damping_ratio"].values[ok]
    labels = [str(x) for x in p["mode_label"].values] if "mode_label" in p else []
    keep = [j for j in range(freq.shape[1]) if np.any(np.isfinite(freq[:, j]))]
    names = [field_label(labels[j]) if j < len(labels) and labels[j] else f"mode {j + 1}" for j in keep]
    return rpm[ok], freq[:, keep], zeta[:, keep], names


def flutter_column(ds: xr.Dataset, i: int, rpm: np.ndarray, zeta: np.ndarray) -> int | None:
    """The column of :func:`_sweep` that flutters at point ``i``: the least damped mode at the
    first sweep speed at or past the flutter onset (None without flutter)."""
    fr = float(ds["flutter_rpm"].values[i])
    if not np.isfinite(fr) or zeta.size == 0:
        return None
    past = np.where(rpm >= fr - 1e-9)[0]
    row = zeta[past[0] if past.size else -1]
    return int(np.nanargmin(row)) if np.any(np.isfinite(row)) else None


def _point_title(ds: xr.Dataset, i: int) -> str:
    return (f"V = {float(ds['wind_speed'].values[i]):.4g} m/s, {ds['aero'].values[i]}, "
            f"{ds['method'].values[i]}")


#: fixed layout of the sweep figures: axes from 8 % to 72 % of the width, names to the right
_SWEEP_FIG = (9.5, 6.2)
_SWEEP_X = (0.085, 0.64)


#: a root whose damped frequency is below this fraction of the sweep's highest is real (no
#: oscillation: an overdamped or, past divergence, a statically unstable root)
REAL_ROOT = 1e-4


def oscillating(freq: np.ndarray) -> np.ndarray:
    """``freq`` (Hz) with the real roots (:data:`REAL_ROOT`) made NaN: a Campbell diagram draws the
    frequencies of oscillations; a real root drawn at 0 Hz would join its track with a line to the
    axis (static divergence has its own line)."""
    top = float(np.nanmax(freq)) if freq.size and np.any(np.isfinite(freq)) else 0.0
    with np.errstate(invalid="ignore"):
        return np.where(freq > REAL_ROOT * top, freq, np.nan)


def campbell(ds: xr.Dataset, i: int, harmonics=(1, 3, 6)) -> Figure:
    """Campbell diagram of point ``i``: frequency vs rotor speed coloured by damping ratio; real
    roots are not drawn (:func:`oscillating`), heavily damped points (above
    :data:`~windflutter.system.campbell.HEAVILY_DAMPED`) are small open circles without lines or labels,
    the flutter and divergence onsets are lines."""
    fig = Figure(figsize=_SWEEP_FIG)
    ax = fig.add_axes((_SWEEP_X[0], 0.2, _SWEEP_X[1], 0.72))
    rpm, freq, zeta, labels = _sweep(ds, i)
    jf = flutter_column(ds, i, rpm, zeta)
    freq = oscillating(freq)
    # colour scale: +-10 % damping at most, so that the region near zero stays readable
    zmax = float(np.nanpercentile(np.abs(zeta), 95)) if zeta.size and np.any(np.isfinite(zeta)) else 0.05
    zmax = min(max(zmax, 1e-3), 0.1)
    norm = TwoSlopeNorm(vcenter=0.0, vmin=-zmax, vmax=zmax)
    sc = None
    heavy = np.abs(zeta) > HEAVILY_DAMPED  # NaN: False
    for j in range(freq.shape[1]):
        bold = j == jf
        # lines join lightly damped neighbours only: a heavily damped mode's damped frequency moves
        # fast with the rotor speed and means little, and its line would cross the diagram
        light = np.where(heavy[:, j], np.nan, freq[:, j])
        ax.plot(rpm, light, "-", color="k" if bold else "0.7", lw=2.2 if bold else 1, zorder=1)
        ax.scatter(rpm[heavy[:, j]], freq[heavy[:, j], j], s=14, facecolors="none", edgecolors="0.6", linewidths=0.6,
                   zorder=2)
        sc = ax.scatter(rpm[~heavy[:, j]], freq[~heavy[:, j], j], c=np.clip(zeta[~heavy[:, j], j], -zmax, zmax),
                        cmap="RdBu", norm=norm, s=26, zorder=2, edgecolors="k", linewidths=0.3)
    fmax = float(np.nanmax(freq)) * 1.15 if np.any(np.isfinite(freq)) else 1.0
    for n in harmonics:
        ax.plot(rpm, n * rpm / 60.0, "--", color="0.3", lw=0.8)
        xe = min(rpm[-1], fmax * 60.0 / n)
        ax.annotate(f"{n}P", (xe, n * xe / 60.0), fontsize=8, color="0.3", xytext=(-2, 2), ha="right",
                    textcoords="offset points")
    _reference_lines(ax, ds, vertical=True)
    fr = ds["flutter_rpm"].values[i]
    if np.isfinite(fr):
        ax.axvline(fr, color="r", lw=1.2, label=f"flutter {fr:.2f} RPM")
    dv = ds["divergence_rpm"].values[i]
    if np.isfinite(dv):
        ax.axvline(dv, color="m", lw=1.2, ls="--", label=f"divergence {dv:.2f} RPM")
    ax.set_ylim(0, fmax)
    ax.set_xlim(rpm[0], rpm[-1] if rpm.size else 1)
    if freq.size:  # a track is labelled at its last lightly damped point
        lit = np.where(heavy, np.nan, freq)
        last = np.array([f[np.isfinite(f)][-1] if np.any(np.isfinite(f)) else np.nan for f in lit.T])
        ok = np.isfinite(last)
        fs.label_ends(ax, rpm[-1], last[ok], [labels[j] for j in np.where(ok)[0]],
                      ["k" if j == jf else "0.25" for j in np.where(ok)[0]], x_text=1.012)
    if sc is not None:
        cax = fig.add_axes((_SWEEP_X[0] + _SWEEP_X[1] + 0.2, 0.2, 0.018, 0.72))
        fig.colorbar(sc, cax=cax, extend="both", label="damping ratio ζ (−)  [red: unstable]")
    ax.set_xlabel("rotor speed (RPM)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title(f"Campbell diagram — {_point_title(ds, i)}", fontsize=10)
    ax.grid(alpha=0.3)
    _legend_below(fig, ax)
    return fig


def _legend_below(fig, ax) -> None:
    h, lab = ax.get_legend_handles_labels()
    if h:
        fig.legend(h, lab, loc="lower left", bbox_to_anchor=(_SWEEP_X[0], 0.0), ncols=min(len(h), 4), fontsize=8)


def damping_plot(ds: xr.Dataset, i: int) -> Figure:
    """V-g / V-f style: damping ratio (top, axis scaled to the lightly damped modes, the heavily
    damped ones above a break) and frequency (bottom) of each mode vs rotor speed; names at the
    line ends; the flutter mode bold."""
    fig = Figure(figsize=(_SWEEP_FIG[0], 7.5))
    rpm, freq, zeta, labels = _sweep(ds, i)
    jf = flutter_column(ds, i, rpm, zeta)
    cols = [f"C{j % 10}" for j in range(freq.shape[1])]

    def draw(ax, y):
        for j in range(y.shape[1]):
            ax.plot(rpm, y[:, j], "o-", ms=2.5, lw=2.6 if j == jf else 1.0, color="k" if j == jf else cols[j],
                    zorder=3 if j == jf else 2)

    lo, cut, top = fs.damping_split(zeta)
    axz = fs.damping_panels(fig, (_SWEEP_X[0], 0.5, _SWEEP_X[1], 0.44), lo, cut, top, lambda ax: draw(ax, zeta))
    axf = fig.add_axes((_SWEEP_X[0], 0.13, _SWEEP_X[1], 0.33))
    draw(axf, freq)
    fr = ds["flutter_rpm"].values[i]
    for ax in (*axz, axf):
        _reference_lines(ax, ds, vertical=True)
        if np.isfinite(fr):
            ax.axvline(fr, color="r", lw=1.2, label=f"flutter {fr:.2f} RPM")
        ax.set_xlim(rpm[0], rpm[-1] if rpm.size else 1)
        ax.grid(alpha=0.3)
    colours = ["k" if j == jf else cols[j] for j in range(freq.shape[1])]
    for ax, y, rng in ((axz[-1], zeta, (lo, cut)), (axf, freq, axf.get_ylim())) + (
            ((axz[0], zeta, (cut, np.inf)),) if len(axz) > 1 else ()):
        last = np.array([c[np.isfinite(c)][-1] if np.any(np.isfinite(c)) else np.nan for c in y.T])
        sel = np.where(np.isfinite(last) & (last >= rng[0]) & (last <= rng[1]))[0]
        fs.label_ends(ax, rpm[-1], last[sel], [labels[j] for j in sel], [colours[j] for j in sel], x_text=1.012)
    axz[-1].set_ylabel("damping ratio ζ (−)")
    axz[-1].tick_params(labelbottom=False)
    axf.set_ylabel("frequency (Hz)")
    axf.set_xlabel("rotor speed (RPM)")
    axz[0].set_title(f"Damping and frequency vs rotor speed — {_point_title(ds, i)}", fontsize=10)
    _legend_below(fig, axf)
    return fig


def flutter_mode(ds: xr.Dataset, i: int) -> Figure:
    """Flap, edge (m, normalised) and torsion (rad) amplitude and phase along span at onset."""
    fig = Figure(figsize=(7.5, 6.0), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    p = ds.isel(point=i)
    r = p["station_radius"].values
    ok = np.isfinite(r)
    shape = flutter_shape(ds).values[i][ok]
    r = r[ok]
    ref = shape.ravel()[np.nanargmax(np.abs(shape.ravel()))] if shape.size else 1.0
    shape = shape / (ref if abs(ref) > 0 else 1.0)
    axt = ax1.twinx()
    for c, name in enumerate(("flap", "edge", "torsion")):
        ax = axt if name == "torsion" else ax1
        ax.plot(r, np.abs(shape[:, c]), "-o", ms=3, color=COMPONENT_STYLE[name], label=name)
        amp = np.abs(shape[:, c])
        phase = np.degrees(np.angle(shape[:, c]))
        phase[amp < 1e-3 * max(np.nanmax(np.abs(shape)), 1e-300)] = np.nan
        ax2.plot(r, phase, "-o", ms=3, color=COMPONENT_STYLE[name], label=name)
    ax1.set_ylabel("flap, edge amplitude (−, normalised)")
    axt.set_ylabel("torsion amplitude (rad per unit)", color=COMPONENT_STYLE["torsion"])
    h1, l1 = ax1.get_legend_handles_labels()
    h2, l2 = axt.get_legend_handles_labels()
    ax1.legend(h1 + h2, l1 + l2, fontsize=8, loc="upper left")
    ax2.set_ylabel("phase (deg)")
    ax2.set_xlabel("radius (m)")
    ax2.set_ylim(-185, 185)
    ax2.set_yticks([-180, -90, 0, 90, 180])
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    f = float(p["flutter_frequency"].values)
    ax1.set_title(f"Flutter mode '{field_label(p['flutter_mode'].values)}' at {float(p['flutter_rpm'].values):.2f} RPM, "
                  f"{f:.3f} Hz — {_point_title(ds, i)}", fontsize=9)
    return fig


def aero_work_plot(ds: xr.Dataset, i: int) -> Figure:
    """Aerodynamic work per cycle on the flutter mode, per station and section DOF."""
    fig = Figure(figsize=(7.5, 4.2), layout="constrained")
    ax = fig.add_subplot()
    p = ds.isel(point=i)
    r = p["station_radius"].values
    ok = np.isfinite(r)
    w = p["aero_work"].values[ok]
    r = r[ok]
    width = 0.8 * (np.min(np.diff(r)) if r.size > 1 else 1.0) / 3
    for c, name in enumerate(("plunge", "pitch", "edgewise")):
        ax.bar(r + (c - 1) * width, w[:, c], width=width, label=name)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("radius (m)")
    ax.set_ylabel("aero work per cycle (J, mode normalised)")
    ax.set_title(f"Aero work on the flutter mode (> 0 feeds the mode), total "
                 f"{float(np.nansum(w)):.3g} J — {_point_title(ds, i)}", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def all_figures(ds: xr.Dataset, operating=None) -> dict[str, Figure]:
    """Every figure of a run, by name (``stability_map``, ``campbell_<aero>_<method>``, ...);
    with ``operating`` (the run's operating-point Campbell result or dataset) also
    ``operating_campbell`` (:func:`windflutter.post.campbell_plots.campbell_figure`)."""
    figs: dict[str, Figure] = {}
    if operating is not None:
        from windflutter.post.campbell_plots import campbell_figure  # noqa: PLC0415

        figs["operating_campbell"] = campbell_figure(operating)
    if "point" not in ds.dims or ds.sizes["point"] == 0:
        return figs
    figs["stability_map"] = stability_map(ds)
    for case in cases(ds):
        i = critical_point(ds, case)
        if i is None:
            continue
        tag = f"{case[0]}_{case[1]}"
        if "rotor_speed" in ds and np.any(np.isfinite(ds["rotor_speed"].values[i])):
            figs[f"campbell_{tag}"] = campbell(ds, i)
            figs[f"damping_{tag}"] = damping_plot(ds, i)
        if (("flutter_torsion_real" in ds or "flutter_shape_real" in ds) and "station_radius" in ds
                and np.any(np.isfinite(flutter_shape(ds).values[i]))):
            figs[f"flutter_mode_{tag}"] = flutter_mode(ds, i)
        if "aero_work" in ds and np.any(np.isfinite(ds["aero_work"].values[i])):
            figs[f"aero_work_{tag}"] = aero_work_plot(ds, i)
    return figs


def render_png(figs: dict[str, Figure], dpi: int = 110) -> dict[str, bytes]:
    """Each figure rendered once as PNG bytes (shared by the files and the report)."""
    out = {}
    for name, fig in figs.items():
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi)
        out[name] = buf.getvalue()
    return out


def save_figures(figs: dict[str, Figure], folder: str | Path, formats=("png",), dpi: int = 110,
                 png: dict[str, bytes] | None = None) -> dict[str, Path]:
    """Save figures as ``folder/<name>.<fmt>``; return name -> path of the first format.

    ``png``: already rendered PNG bytes (from :func:`render_png`) to write instead of redrawing.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    out = {}
    for name, fig in figs.items():
        for k, fmt in enumerate(formats):
            path = folder / f"{name}.{fmt}"
            if fmt == "png" and png is not None and name in png:
                path.write_bytes(png[name])
            else:
                fig.savefig(path, dpi=dpi)
            if k == 0:
                out[name] = path
    return out


def close_figures(figs: dict[str, Figure]) -> None:
    for fig in figs.values():
        fig.clear()
