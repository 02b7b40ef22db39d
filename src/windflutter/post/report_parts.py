"""HTML parts of the run report: the verdict box, the assumptions box, the margins table, the
operating-point Campbell section and the key/value tables with units.

Each function returns an HTML string; :mod:`windflutter.post.report` assembles the page.
Numbers go through :mod:`windflutter.post.fmt` (rounded, with units, booleans as yes/no).
"""

from __future__ import annotations

import html
import math

import numpy as np
import xarray as xr

from windflutter.post import fmt
from windflutter.post.campbell_data import least_damped_per_point
from windflutter.post.plots import case_points, cases
from windflutter.post.verdict import (
    Verdict,
    instability_text,
    least_damped_text,
    searched_text,
)

e = html.escape

#: readable names and units of the run attributes shown in the model table
ATTR_NAMES: dict[str, tuple[str, str]] = {
    "turbine": ("turbine", ""), "rotor_diameter": ("rotor diameter", "m"), "hub_height": ("hub height", "m"),
    "n_blades": ("blades", ""), "rated_rpm": ("rated rotor speed", "RPM"),
    "overspeed_rpm": ("overspeed rotor speed", "RPM"), "air_density": ("air density", "kg/m³"),
    "n_dof": ("FE degrees of freedom", ""), "n_nodes": ("FE nodes", ""),
    "n_aero_sections": ("aerodynamic strips", ""), "n_reduced_dof": ("reduced model size", "DOF"),
    "n_points_planned": ("operating points planned", ""), "n_points_done": ("operating points done", ""),
    "complete": ("run complete", "bool"), "finished_utc": ("finished (UTC)", ""),
    "config_fingerprint": ("config fingerprint", ""), "source": ("turbine file", ""),
}
#: units of config fields (section.field)
CONFIG_UNITS = {"rotor_speed.min_rpm": "RPM", "rotor_speed.max_rpm": "RPM", "rotor_speed.tolerance_rpm": "RPM",
                "damping.reference_hz": "Hz", "operating.rated_rpm": "RPM", "operating.overspeed_rpm": "RPM",
                "air_density": "kg/m³", "wind_speeds": "m/s"}

_STATUS_CLASS = {"unstable in operation": "bad", "instability below rated": "bad",
                 "instability below overspeed": "bad", "stable up to overspeed": "good",
                 "no instability found": "good", "no result": "none"}


def verdict_box(v: Verdict, has_campbell: bool) -> str:
    """The verdict: status, first instability, least damped mode in operation."""
    cls = _STATUS_CLASS.get(v.status, "none")
    parts = [f"<section class='verdict {cls}' data-section='verdict'><h2>Verdict: {e(v.status)}</h2><ul>"]
    if v.first is not None:
        parts.append(f"<li><b>First instability</b>: {e(instability_text(v.first, v))}.</li>")
    else:
        parts.append(f"<li><b>First instability</b>: none found{e(searched_text(v))}.</li>")
    if has_campbell:
        parts.append(f"<li><b>Least damped mode in operation</b>: {e(least_damped_text(v.least_damped))}.</li>")
    parts.append(f"<li>Rated rotor speed {e(fmt.qty(v.rated_rpm, 'RPM'))}, overspeed "
                 f"{e(fmt.qty(v.overspeed_rpm, 'RPM'))}; margin = onset / reference − 1 (negative: the "
                 "instability lies below the reference).</li></ul></section>")
    return "".join(parts)


def assumptions_box(v: Verdict) -> str:
    """The modelling assumptions, one small table per analysis."""
    if not v.assumptions:
        return ""
    parts = ["<section class='assumptions' data-section='assumptions'><h2>Modelling assumptions</h2>"]
    for group, items in v.assumptions.items():
        parts.append(f"<table class='kv'><caption>{e(group)}</caption>")
        parts += [f"<tr><th class='l'>{e(k.replace('_', ' '))}</th><td class='l'>{e(str(x))}</td></tr>"
                  for k, x in items.items()]
        parts.append("</table>")
    parts.append("</section>")
    return "".join(parts)


def margins(ds: xr.Dataset) -> list[dict]:
    """Per case: lowest flutter / divergence onset (RPM), where, the flutter mode (field terms)
    and frequency, and the margins to rated/overspeed (%) of the lower of the two."""
    rated, over = ds.attrs.get("rated_rpm"), ds.attrs.get("overspeed_rpm")
    rows = []
    for case in cases(ds):
        c = case_points(ds, case)
        row = {"case": f"{case[0]}, {case[1]}", "flutter_mode": "", "flutter_frequency": math.nan}
        for kind in ("flutter", "divergence"):
            vals = c[f"{kind}_rpm"].values
            j = int(np.nanargmin(vals)) if np.any(np.isfinite(vals)) else None
            row[f"{kind}_rpm"] = float(vals[j]) if j is not None else math.nan
            row[f"{kind}_wind"] = float(c["wind_speed"].values[j]) if j is not None else math.nan
            if kind == "flutter" and j is not None:
                row["flutter_mode"] = fmt.field_label(c["flutter_mode"].values[j])
                row["flutter_frequency"] = float(c["flutter_frequency"].values[j])
        both = [row["flutter_rpm"], row["divergence_rpm"]]
        onset = float(np.nanmin(both)) if np.any(np.isfinite(both)) else math.nan
        row["onset_rpm"] = onset
        row["margin_rated_pct"] = 100 * (onset / rated - 1) if rated else math.nan
        row["margin_overspeed_pct"] = 100 * (onset / over - 1) if over else math.nan
        row["n_failed"] = int(sum(str(s) != "ok" for s in c["status"].values))
        rows.append(row)
    return rows


def _pct_cell(x: float) -> str:
    if not math.isfinite(x):
        return fmt.DASH
    return f"<span class='{'warn' if x < 0 else 'ok'}'>{x:+.1f} %</span>"


def margins_table(ds: xr.Dataset) -> str:
    head = ("<table><tr><th class='l'>case</th><th>lowest flutter (RPM)</th><th>at V (m/s)</th>"
            "<th class='l'>flutter mode</th><th>flutter f (Hz)</th><th>lowest divergence (RPM)</th>"
            "<th>at V (m/s)</th><th>margin to rated</th><th>margin to overspeed</th><th>failed points</th></tr>")
    body = [f"<tr><td class='l'>{e(r['case'])}</td><td>{fmt.num(r['flutter_rpm'])}</td>"
            f"<td>{fmt.num(r['flutter_wind'], 1)}</td><td class='l'>{e(r['flutter_mode']) or fmt.DASH}</td>"
            f"<td>{fmt.num(r['flutter_frequency'], 3)}</td><td>{fmt.num(r['divergence_rpm'])}</td>"
            f"<td>{fmt.num(r['divergence_wind'], 1)}</td><td>{_pct_cell(r['margin_rated_pct'])}</td>"
            f"<td>{_pct_cell(r['margin_overspeed_pct'])}</td><td>{r['n_failed']}</td></tr>" for r in margins(ds)]
    return head + "".join(body) + "</table>"


def campbell_section(camp: xr.Dataset, img: str | None) -> str:
    """'Operating-point Campbell diagram': the figure and the least damped mode per wind speed."""
    parts = ["<section data-section='campbell'><h2>Operating-point Campbell diagram</h2>",
             "<p>Every mode of the turbine at the operating rotor speed and pitch of each wind speed "
             f"({e(str(camp.attrs.get('frame', 'ground-fixed')))} frame): frequency and damping ratio, "
             "one colour per mode family and a line style per whirl; the drivetrain's rigid-body root "
             "is not drawn.</p>"]
    if img:
        parts.append(f"<figure data-figure='operating_campbell'><img alt='operating-point Campbell diagram' "
                     f"src='data:image/png;base64,{img}'><figcaption><b>operating_campbell</b>: frequency (top) "
                     "and damping ratio (bottom, heavily damped modes above the break) vs wind speed, 1P/3P/6P/9P "
                     "lines, least damped mode starred, unstable points crossed.</figcaption></figure>")
    parts.append("<table><caption>Least damped mode per wind speed</caption><tr><th>V (m/s)</th>"
                 "<th>rotor speed (RPM)</th><th>pitch (deg)</th><th class='l'>mode</th><th>f (Hz)</th>"
                 "<th>ζ (%)</th></tr>")
    for c in least_damped_per_point(camp):
        if c is None:
            continue
        z = 100 * c["damping_ratio"]
        zs = f"<span class='warn'>{z:.2f}</span>" if z < 0 else f"{z:.2f}"
        parts.append(f"<tr><td>{fmt.sig(c['wind_speed'])}</td><td>{fmt.num(c['rotor_speed_rpm'])}</td>"
                     f"<td>{fmt.num(c['pitch_deg'])}</td><td class='l'>{e(c['name'])}</td>"
                     f"<td>{fmt.num(c['frequency_hz'], 3)}</td><td>{zs}</td></tr>")
    parts.append("</table>")
    changed = _identity_changes(camp)
    if changed:
        parts.append("<p>Tracks whose name changes along the wind speeds (the mode followed by its shape "
                     "changes rank in its family): " + "; ".join(e(x) for x in changed) + ".</p>")
    parts.append("</section>")
    return "".join(parts)


def _identity_changes(camp: xr.Dataset) -> list[str]:
    out = []
    names = camp["mode_name"].values
    for t in range(camp.sizes["track"]):
        seq = [str(x) for x in names[:, t] if str(x)]
        distinct = list(dict.fromkeys(seq))
        if len(distinct) > 1:
            out.append(" → ".join(distinct))
    return out


def kv_table(rows: list[tuple[str, str]]) -> str:
    return "<table class='kv'>" + "".join(f"<tr><th class='l'>{e(k)}</th><td class='l'>{e(v)}</td></tr>"
                                          for k, v in rows) + "</table>"


def model_rows(a: dict) -> list[tuple[str, str]]:
    """The model table: known attributes by name with units, then the rest."""
    skip = {"config_yaml", "title", "Conventions", "history"}
    rows = []
    for k, v in a.items():
        if k in skip or k.endswith("_version") or k.startswith(("solver_", "damping_", "model_")):
            continue
        name, unit = ATTR_NAMES.get(k, (k.replace("_", " "), ""))
        rows.append((name, fmt.value(bool(int(v)), "") if unit == "bool" else fmt.value(v, unit)))
    return rows


def settings_rows(a: dict) -> list[tuple[str, str]]:
    """Solver, model, damping and operating settings from the config (typed: yes/no for flags)."""
    cfg = _config(a)
    rows = []
    if cfg:
        for section in ("rotor_speed", "model", "damping", "solver", "operating"):
            for k, v in (cfg.get(section) or {}).items():
                rows.append((f"{section}.{k}", fmt.value(v, CONFIG_UNITS.get(f"{section}.{k}", ""))))
        rows.append(("air_density", fmt.value(cfg.get("air_density"), CONFIG_UNITS["air_density"])))
        return rows
    return [(k, fmt.value(v)) for k, v in a.items() if k.startswith(("solver_", "damping_", "model_"))]


def _config(a: dict) -> dict:
    text = a.get("config_yaml")
    if not text:
        return {}
    import yaml  # noqa: PLC0415

    try:
        cfg = yaml.safe_load(str(text))
    except yaml.YAMLError:
        return {}
    return cfg if isinstance(cfg, dict) else {}
