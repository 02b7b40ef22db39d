"""Self-contained HTML report of a run: one file, figures embedded as base64 PNG, no scripts.

Sections: summary and margins (lowest flutter and divergence onset per case against the rated and
overspeed rotor speeds), inputs (the analysis config), model size and versions, the per-point
results table (failed points with their reason), and every figure of
:func:`windflutter.post.plots.all_figures`, each tagged ``data-figure="<name>"``.
"""

from __future__ import annotations

import base64
import html
import io
import math

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from windflutter.post.plots import case_points, cases

_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:2em auto;max-width:1100px;
color:#222;line-height:1.45;padding:0 1em}
h1{font-size:1.6em;margin-bottom:0.2em}h2{border-bottom:1px solid #ccc;padding-bottom:0.2em;margin-top:1.6em}
table{border-collapse:collapse;font-size:0.9em;margin:0.6em 0}th,td{border:1px solid #ccc;padding:3px 8px;
text-align:right}th{background:#f3f3f3}td.l,th.l{text-align:left}tr.failed td{background:#fde8e8}
.warn{color:#a00;font-weight:bold}.ok{color:#070}figure{margin:1em 0}figure img{max-width:100%;
border:1px solid #eee}figcaption{font-size:0.85em;color:#555}pre{background:#f7f7f7;padding:0.8em;
overflow:auto;font-size:0.85em}
"""

_CAPTIONS = {
    "stability_map": "Stability map: lowest rotor speed with flutter (solid) and divergence (dashed) "
                     "vs wind speed, with the operating rotor-speed curve and the rated and overspeed lines.",
    "campbell": "Campbell diagram at the critical wind speed: frequencies of the tracked modes vs rotor "
                "speed, coloured by damping ratio (red: negative damping), with 1P/3P/6P lines.",
    "damping": "Damping ratio and frequency of each tracked mode vs rotor speed (V-g / V-f style).",
    "flutter_mode": "Flutter mode at onset: flap, edge and torsion amplitude and phase along the span.",
    "aero_work": "Aerodynamic work per cycle on the flutter mode, per span station, split into plunge, "
                 "pitch and edgewise motion (positive: the air feeds the mode).",
}


def figure_png_base64(fig: Figure, dpi: int = 110) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def _b64(data: bytes | None, fig: Figure, dpi: int) -> str:
    if data is None:
        return figure_png_base64(fig, dpi)
    return base64.b64encode(data).decode("ascii")


def _fmt(x, nd=2) -> str:
    try:
        x = float(x)
    except (TypeError, ValueError):
        return html.escape(str(x))
    return "—" if not math.isfinite(x) else f"{x:.{nd}f}"


def margins(ds: xr.Dataset) -> list[dict]:
    """Per case: lowest flutter / divergence onset (RPM), where, and margins to rated/overspeed (%)."""
    rated = ds.attrs.get("rated_rpm")
    over = ds.attrs.get("overspeed_rpm")
    rows = []
    for case in cases(ds):
        c = case_points(ds, case)
        row = {"case": f"{case[0]}, {case[1]}"}
        for kind in ("flutter", "divergence"):
            vals = c[f"{kind}_rpm"].values
            if np.any(np.isfinite(vals)):
                j = int(np.nanargmin(vals))
                row[f"{kind}_rpm"] = float(vals[j])
                row[f"{kind}_wind"] = float(c["wind_speed"].values[j])
            else:
                row[f"{kind}_rpm"] = float("nan")
                row[f"{kind}_wind"] = float("nan")
        onset = np.nanmin([row["flutter_rpm"], row["divergence_rpm"]]) if np.any(
            np.isfinite([row["flutter_rpm"], row["divergence_rpm"]])) else float("nan")
        row["onset_rpm"] = onset
        row["margin_rated_pct"] = 100 * (onset / rated - 1) if rated else float("nan")
        row["margin_overspeed_pct"] = 100 * (onset / over - 1) if over else float("nan")
        row["n_failed"] = int(sum(str(s) != "ok" for s in c["status"].values))
        rows.append(row)
    return rows


def build_report(ds: xr.Dataset, figs: dict[str, Figure], dpi: int = 110,
                 png: dict[str, bytes] | None = None) -> str:
    """The report as one HTML string (every figure of ``figs`` embedded).

    ``png``: figures already rendered as PNG bytes (name -> bytes), used instead of redrawing.
    """
    png = png or {}
    a = ds.attrs
    e = html.escape
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
             f"<title>{e(str(a.get('title', 'windflutter report')))}</title><style>{_CSS}</style></head><body>"]
    parts.append(f"<h1>{e(str(a.get('title', 'windflutter stability analysis')))}</h1>")
    parts.append(f"<p>windflutter {e(str(a.get('windflutter_version', '?')))} · turbine "
                 f"<b>{e(str(a.get('turbine', '?')))}</b> · finished {e(str(a.get('finished_utc', 'not finished')))}"
                 f" · {a.get('n_points_done', '?')} of {a.get('n_points_planned', '?')} operating points</p>")

    # summary and margins
    parts.append("<h2>Summary: margins</h2>")
    rated, over = a.get("rated_rpm"), a.get("overspeed_rpm")
    parts.append(f"<p>Rated rotor speed <b>{_fmt(rated)} RPM</b>, overspeed <b>{_fmt(over)} RPM</b>. "
                 "Margin = onset / reference − 1; negative means the instability lies inside the "
                 "operating range.</p>")
    parts.append("<table><tr><th class='l'>case</th><th>lowest flutter (RPM)</th><th>at V (m/s)</th>"
                 "<th>lowest divergence (RPM)</th><th>at V (m/s)</th><th>margin to rated</th>"
                 "<th>margin to overspeed</th><th>failed points</th></tr>")
    for r in margins(ds):
        def pct(x):
            if not math.isfinite(x):
                return "—"
            cls = "warn" if x < 0 else "ok"
            return f"<span class='{cls}'>{x:+.1f} %</span>"
        parts.append(f"<tr><td class='l'>{e(r['case'])}</td><td>{_fmt(r['flutter_rpm'])}</td>"
                     f"<td>{_fmt(r['flutter_wind'], 1)}</td><td>{_fmt(r['divergence_rpm'])}</td>"
                     f"<td>{_fmt(r['divergence_wind'], 1)}</td><td>{pct(r['margin_rated_pct'])}</td>"
                     f"<td>{pct(r['margin_overspeed_pct'])}</td><td>{r['n_failed']}</td></tr>")
    parts.append("</table>")

    # figures
    parts.append("<h2>Figures</h2>")
    for name, fig in figs.items():
        key = next((k for k in _CAPTIONS if name == k or name.startswith(k + "_")), None)
        cap = _CAPTIONS.get(key, name)
        tag = name[len(key) + 1:].replace("_", ", ") if key and name != key else ""
        parts.append(f"<figure data-figure='{e(name)}'><img alt='{e(name)}' "
                     f"src='data:image/png;base64,{_b64(png.get(name), fig, dpi)}'>"
                     f"<figcaption><b>{e(name)}</b>{' (' + e(tag) + ')' if tag else ''}: {e(cap)}</figcaption></figure>")

    # per-point table
    parts.append("<h2>Results per operating point</h2><table><tr><th>#</th><th>V (m/s)</th>"
                 "<th class='l'>aero</th><th class='l'>method</th><th>flutter (RPM)</th><th>f (Hz)</th>"
                 "<th class='l'>mode</th><th>divergence (RPM)</th><th class='l'>status</th><th>time (s)</th></tr>")
    if "point" in ds.dims:
        for i in range(ds.sizes["point"]):
            st = str(ds["status"].values[i])
            reason = str(ds["reason"].values[i])
            cls = " class='failed'" if st != "ok" else ""
            parts.append(f"<tr{cls}><td>{int(ds['point'].values[i])}</td><td>{_fmt(ds['wind_speed'].values[i], 1)}</td>"
                         f"<td class='l'>{e(str(ds['aero'].values[i]))}</td><td class='l'>{e(str(ds['method'].values[i]))}</td>"
                         f"<td>{_fmt(ds['flutter_rpm'].values[i])}</td><td>{_fmt(ds['flutter_frequency'].values[i], 3)}</td>"
                         f"<td class='l'>{e(str(ds['flutter_mode'].values[i]))}</td><td>{_fmt(ds['divergence_rpm'].values[i])}</td>"
                         f"<td class='l'>{e(st + (': ' + reason if reason else ''))}</td><td>{_fmt(ds['elapsed'].values[i], 1)}</td></tr>")
    parts.append("</table>")

    # model, inputs, versions
    parts.append("<h2>Model</h2><table>")
    skip = {"config_yaml", "title", "Conventions", "source"}
    model_keys = [k for k in a if not k.endswith("_version") and k not in skip
                  and not k.startswith(("solver_", "damping_", "model_"))]
    for k in model_keys:
        parts.append(f"<tr><th class='l'>{e(k)}</th><td class='l'>{e(str(a[k]))}</td></tr>")
    parts.append("</table><h2>Solver settings</h2><table>")
    for k in a:
        if k.startswith(("solver_", "damping_", "model_")):
            parts.append(f"<tr><th class='l'>{e(k)}</th><td class='l'>{e(str(a[k]))}</td></tr>")
    parts.append("</table><h2>Inputs: analysis config</h2>")
    parts.append(f"<pre>{e(str(a.get('config_yaml', '')))}</pre>")
    parts.append("<h2>Versions</h2><table>")
    for k in a:
        if k.endswith("_version"):
            parts.append(f"<tr><th class='l'>{e(k)}</th><td class='l'>{e(str(a[k]))}</td></tr>")
    parts.append("</table></body></html>")
    return "\n".join(parts)
