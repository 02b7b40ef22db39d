"""Self-contained HTML report of a run: one file, figures embedded as base64 PNG, no scripts.

It opens with the verdict (first instability: mode, frequency, rotor speed, margins to rated and
overspeed; the least damped mode in operation) and a box of the modelling assumptions
(:mod:`windflutter.post.verdict`), then the margins table per case (naming the flutter mode and
its frequency), the operating-point Campbell diagram with the least damped mode per wind speed
(when the run has one), every figure of :func:`windflutter.post.plots.all_figures` (each tagged
``data-figure="<name>"``), the per-point results (failed points with their reason), the model
with units, the settings, the analysis config and the versions.  Sections are tagged
``data-section="<name>"``.
"""

from __future__ import annotations

import base64
import html
import io
import xarray as xr
from matplotlib.figure import Figure

from windflutter.post import fmt
from windflutter.post import report_parts as rp
from windflutter.post.campbell_data import as_campbell_dataset
from windflutter.post.verdict import verdict

_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:2em auto;max-width:1100px;
color:#222;line-height:1.45;padding:0 1em}
h1{font-size:1.6em;margin-bottom:0.2em}h2{border-bottom:1px solid #ccc;padding-bottom:0.2em;margin-top:1.6em}
table{border-collapse:collapse;font-size:0.9em;margin:0.6em 0}th,td{border:1px solid #ccc;padding:3px 8px;
text-align:right}th{background:#f3f3f3}td.l,th.l{text-align:left}tr.failed td{background:#fde8e8}
.warn{color:#a00;font-weight:bold}
section.verdict{border:2px solid #999;border-radius:6px;padding:0.2em 1em;margin:1em 0}
section.verdict.bad{border-color:#c00;background:#fff3f3}section.verdict.good{border-color:#2a7;background:#f3fbf6}
section.verdict h2{border:none;margin-top:0.4em}section.assumptions{background:#f7f7fb;border:1px solid #ccd;
border-radius:6px;padding:0.2em 1em}table.kv{display:inline-table;vertical-align:top;margin-right:1.5em}
caption{font-weight:bold;text-align:left;padding:0.2em 0}.ok{color:#070}figure{margin:1em 0}figure img{max-width:100%;
border:1px solid #eee}figcaption{font-size:0.85em;color:#555}pre{background:#f7f7f7;padding:0.8em;
overflow:auto;font-size:0.85em}
"""

_CAPTIONS = {
    "stability_map": "Stability map: lowest rotor speed with flutter (solid) and divergence (dashed) "
                     "vs wind speed, with the operating rotor-speed curve and the rated and overspeed lines.",
    "campbell": "Campbell diagram of the overspeed search at the critical wind speed: frequencies of the "
                "tracked modes vs rotor speed, coloured by damping ratio (red: negative damping), with "
                "1P/3P/6P lines; the flutter mode drawn bold.",
    "damping": "Damping ratio and frequency of each tracked mode vs rotor speed (V-g / V-f style), the "
               "damping axis scaled to the lightly damped modes (heavily damped ones above the break), "
               "the flutter mode drawn bold.",
    "flutter_mode": "Flutter mode at onset: flap, edge and torsion amplitude and phase along the span.",
    "operating_campbell": "Operating-point Campbell diagram: frequency and damping ratio of every mode vs wind speed.",
    "aero_work": "Aerodynamic work per cycle on the flutter mode, per span station, split into plunge, "
                 "pitch and edgewise motion (positive: the air feeds the mode).",
}


def figure_png_base64(fig: Figure, dpi: int = 110) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return base64.b64encode(buf.getvalue()).decode("ascii")


e = html.escape
margins = rp.margins  # the margins rows per case (kept here for callers of the old name)


def _b64(data: bytes | None, fig: Figure, dpi: int) -> str:
    if data is None:
        return figure_png_base64(fig, dpi)
    return base64.b64encode(data).decode("ascii")


def build_report(ds: xr.Dataset, figs: dict[str, Figure], dpi: int = 110,
                 png: dict[str, bytes] | None = None, campbell=None) -> str:
    """The report as one HTML string (every figure of ``figs`` embedded).

    Parameters
    ----------
    ds : the run dataset.
    figs : name -> figure (:func:`windflutter.post.plots.all_figures`); a figure named
        ``operating_campbell`` goes to the Campbell section.
    png : figures already rendered as PNG bytes (name -> bytes), used instead of redrawing.
    campbell : the operating-point Campbell result or dataset of the run, if any.
    """
    png = png or {}
    a = ds.attrs
    camp = as_campbell_dataset(campbell) if campbell is not None else None
    v = verdict(ds, camp)
    title = str(a.get("title", "windflutter stability analysis"))
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
             f"<title>{e(title)}</title><style>{_CSS}</style></head><body>",
             f"<h1>{e(title)}</h1>",
             f"<p>windflutter {e(str(a.get('windflutter_version', '?')))} · turbine "
             f"<b>{e(str(a.get('turbine', '?')))}</b> · finished {e(str(a.get('finished_utc', 'not finished')))}"
             f" · {e(fmt.value(a.get('n_points_done', '?')))} of {e(fmt.value(a.get('n_points_planned', '?')))} "
             "operating points</p>",
             rp.verdict_box(v, camp is not None), rp.assumptions_box(v),
             "<h2>Summary: margins</h2>",
             f"<p>Rated rotor speed <b>{fmt.qty(a.get('rated_rpm'), 'RPM')}</b>, overspeed "
             f"<b>{fmt.qty(a.get('overspeed_rpm'), 'RPM')}</b>. Margin = onset / reference − 1; negative "
             "means the instability lies inside the operating range.</p>",
             rp.margins_table(ds)]
    if camp is not None:
        fig = figs.get("operating_campbell")
        img = _b64(png.get("operating_campbell"), fig, dpi) if fig is not None or "operating_campbell" in png else None
        parts.append(rp.campbell_section(camp, img))
    parts.append("<h2>Figures</h2>")
    for name, fig in figs.items():
        if name == "operating_campbell" and camp is not None:
            continue
        parts.append(_figure(name, fig, png, dpi))
    parts.append(_points_table(ds))
    parts += ["<h2>Model</h2>", rp.kv_table(rp.model_rows(a)), "<h2>Settings</h2>", rp.kv_table(rp.settings_rows(a)),
              "<h2>Inputs: analysis config</h2>", f"<pre>{e(str(a.get('config_yaml', '')))}</pre>",
              "<h2>Versions</h2>", rp.kv_table([(k, str(a[k])) for k in a if k.endswith("_version")]),
              "</body></html>"]
    return "\n".join(parts)


def _figure(name: str, fig: Figure, png: dict, dpi: int) -> str:
    key = next((k for k in _CAPTIONS if name == k or name.startswith(k + "_")), None)
    cap = _CAPTIONS.get(key, name)
    tag = name[len(key) + 1:].replace("_", ", ") if key and name != key else ""
    return (f"<figure data-figure='{e(name)}'><img alt='{e(name)}' "
            f"src='data:image/png;base64,{_b64(png.get(name), fig, dpi)}'>"
            f"<figcaption><b>{e(name)}</b>{' (' + e(tag) + ')' if tag else ''}: {e(cap)}</figcaption></figure>")


def _points_table(ds: xr.Dataset) -> str:
    parts = ["<h2>Results per operating point</h2><table><tr><th>#</th><th>V (m/s)</th>"
             "<th class='l'>aero</th><th class='l'>method</th><th>flutter (RPM)</th><th>f (Hz)</th>"
             "<th class='l'>flutter mode at onset</th><th class='l'>grown from</th><th>divergence (RPM)</th>"
             "<th class='l'>status</th><th>time (s)</th></tr>"]
    if "point" in ds.dims:
        for i in range(ds.sizes["point"]):
            st = str(ds["status"].values[i])
            reason = str(ds["reason"].values[i])
            onset, grew, note = fmt.flutter_label(ds["flutter_mode"].values[i])
            cls = " class='failed'" if st != "ok" else ""
            parts.append(f"<tr{cls}><td>{int(ds['point'].values[i])}</td><td>{fmt.num(ds['wind_speed'].values[i], 1)}</td>"
                         f"<td class='l'>{e(str(ds['aero'].values[i]))}</td><td class='l'>{e(str(ds['method'].values[i]))}</td>"
                         f"<td>{fmt.num(ds['flutter_rpm'].values[i])}</td><td>{fmt.num(ds['flutter_frequency'].values[i], 3)}</td>"
                         f"<td class='l'>{e(onset + (' (' + note + ')' if note else '')) or fmt.DASH}</td>"
                         f"<td class='l'>{e(grew) or fmt.DASH}</td><td>{fmt.num(ds['divergence_rpm'].values[i])}</td>"
                         f"<td class='l'>{e(st + (': ' + reason if reason else ''))}</td>"
                         f"<td>{fmt.num(ds['elapsed'].values[i], 1)}</td></tr>")
    parts.append("</table>")
    return "".join(parts)
