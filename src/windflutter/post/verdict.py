"""The verdict of a stability analysis: the first instability and the least damped mode in
operation, with the margins to the rated and overspeed rotor speeds.

Two sources, either may be absent:

* the run dataset (``results.nc``, :mod:`windflutter.post.store`): per operating point the lowest
  flutter and divergence onset of the rotor-speed sweep (overspeed search);
* the operating-point Campbell dataset (:mod:`windflutter.post.campbell_data`): every mode at the
  operating rotor speed and pitch of each wind speed; a negative damping ratio there is an
  instability *in operation*.

The *first instability* is the one at the lowest rotor speed.  Margin = onset / reference - 1
(negative: the instability lies below the reference).  :func:`verdict` gives the structure,
:func:`headline` the text the terminal prints at the end of ``windflutter run``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from windflutter.post import fmt
from windflutter.post.campbell_data import as_campbell_dataset, assumptions, least_damped, unstable

#: verdict levels, from the worst
UNSTABLE_IN_OPERATION = "unstable in operation"
UNSTABLE_BELOW_RATED = "instability below rated"
UNSTABLE_BELOW_OVERSPEED = "instability below overspeed"
STABLE_TO_OVERSPEED = "stable up to overspeed"
NO_INSTABILITY = "no instability found"
NO_RESULT = "no result"
#: the two analyses, as the groups of :attr:`Verdict.assumptions`
SWEEP = "overspeed search (rotor-speed sweep)"
OPERATING = "operating points (Campbell)"


@dataclass
class Instability:
    """One instability: kind (``flutter``, ``divergence``, ``negative damping``), the mode's name
    in the field's terms (and the structural mode a flutter mode grew from), frequency (Hz),
    rotor speed (RPM), wind speed (m/s), where it was found, and the margins (fractions)."""

    kind: str
    mode: str
    frequency_hz: float
    rotor_speed_rpm: float
    wind_speed: float
    where: str
    grew_from: str = ""
    damping_ratio: float = float("nan")
    margin_rated: float = float("nan")
    margin_overspeed: float = float("nan")
    caveat: str = ""


@dataclass
class Verdict:
    """``status`` (one of the levels above), the first instability, the least damped mode in
    operation (a :func:`~windflutter.post.campbell_data.cell` dict), the reference rotor speeds
    (RPM), the rotor speed every point's sweep reached (``searched_rpm``, the lowest of their
    ends: what "none found up to" may claim) and the highest end (``searched_max_rpm``), and the
    modelling assumptions by analysis (:data:`SWEEP`, :data:`OPERATING`: name -> words)."""

    status: str
    first: Instability | None = None
    least_damped: dict | None = None
    rated_rpm: float = float("nan")
    overspeed_rpm: float = float("nan")
    searched_rpm: float = float("nan")
    searched_max_rpm: float = float("nan")
    assumptions: dict = field(default_factory=dict)

    @property
    def stable(self) -> bool:
        return self.status in (STABLE_TO_OVERSPEED, NO_INSTABILITY)


#: said of an onset whose point kept a note (a model used outside its range, e.g. the BEM in the
#: propeller-brake state: :func:`windflutter.analysers._with_validity_notes`)
CAVEAT = "at this rotor speed a model is outside its range of validity (see the point's note)"


def _note_from_rpm(note: str) -> float:
    """The lowest rotor speed (RPM) a point's validity notes hold (``"... [from 17.31 RPM]"``);
    -inf for a note without one (it then applies to the whole sweep)."""
    found = [float(x) for x in re.findall(r"\[from ([0-9.]+) RPM\]", note)]
    return min(found) if found else -math.inf


def _margin(rpm: float, ref) -> float:
    try:
        ref = float(ref)
    except (TypeError, ValueError):
        return float("nan")
    return rpm / ref - 1.0 if math.isfinite(ref) and ref > 0 else float("nan")


def _sweep_onsets(ds: xr.Dataset) -> list[Instability]:
    """Flutter and divergence onsets of the run's points (every case)."""
    out = []
    if ds is None or "point" not in ds.dims:
        return out
    v = ds["wind_speed"].values
    case = [f"{a} aero, {m} search" for a, m in zip(ds["aero"].values, ds["method"].values)]
    for kind in ("flutter", "divergence"):
        rpm = ds[f"{kind}_rpm"].values
        for i in np.where(np.isfinite(rpm))[0]:
            onset, grew, _ = fmt.flutter_label(ds["flutter_mode"].values[i]) if kind == "flutter" else ("static divergence", "", "")
            f = float(ds["flutter_frequency"].values[i]) if kind == "flutter" else 0.0
            note = str(ds["reason"].values[i]) if "reason" in ds and str(ds["status"].values[i]) == "ok" else ""
            out.append(Instability(kind, onset, f, float(rpm[i]), float(v[i]), case[i],
                                   grew_from=grew, damping_ratio=0.0,
                                   caveat=CAVEAT if note and float(rpm[i]) >= _note_from_rpm(note) - 1e-9 else ""))
    return out


def _operating(camp: xr.Dataset) -> list[Instability]:
    return [Instability("negative damping", c["name"], c["frequency_hz"], c["rotor_speed_rpm"], c["wind_speed"],
                        "at the operating point", damping_ratio=c["damping_ratio"]) for c in unstable(camp)]


def verdict(ds: xr.Dataset | None = None, campbell=None) -> Verdict:
    """The verdict from a run dataset and/or a Campbell result or dataset (see module docstring)."""
    camp = as_campbell_dataset(campbell) if campbell is not None else None
    a = ds.attrs if ds is not None else {}
    rated, over = float(a.get("rated_rpm", math.nan)), float(a.get("overspeed_rpm", math.nan))
    if camp is not None and not math.isfinite(rated) and camp.sizes["wind_speed"]:
        rated = float(np.nanmax(camp["rotor_speed"].values))
    found = _sweep_onsets(ds) + (_operating(camp) if camp is not None else [])
    for x in found:
        x.margin_rated, x.margin_overspeed = _margin(x.rotor_speed_rpm, rated), _margin(x.rotor_speed_rpm, over)
    searched, searched_max = _sweep_ends(ds)
    ld = least_damped(camp) if camp is not None else None
    info = {}
    if ds is not None:
        info[SWEEP] = _run_assumptions(a)
    if camp is not None:
        info[OPERATING] = assumptions(camp)
    v = Verdict(NO_RESULT, None, ld, rated, over, searched, searched_max, info)
    # a run whose map points all failed has no result: its Campbell alone does not make the overspeed
    # range "searched" (the IEA 15 MW shell: every point refused, its Campbell damped)
    mapped = ds is not None and "point" in ds.dims and ds.sizes["point"] > 0
    has_result = any(str(s) == "ok" for s in ds["status"].values) if mapped else (camp is not None and ld is not None)
    if found:
        v.first = min(found, key=lambda x: (x.rotor_speed_rpm, x.kind != "negative damping"))
        f = v.first
        if f.kind == "negative damping" or f.rotor_speed_rpm <= _operating_rpm(ds, f.wind_speed):
            v.status = UNSTABLE_IN_OPERATION
        elif f.margin_rated <= 0:
            v.status = UNSTABLE_BELOW_RATED
        elif f.margin_overspeed < 0:
            v.status = UNSTABLE_BELOW_OVERSPEED
        else:
            v.status = STABLE_TO_OVERSPEED
    elif has_result:
        v.status = NO_INSTABILITY
    return v


def _sweep_ends(ds: xr.Dataset | None) -> tuple[float, float]:
    """(lowest, highest) end (RPM) of the finished points' sweeps: a sweep stopped early (no steady
    state, the structure alone unstable) ends below the grid's top."""
    if ds is None or "rotor_speed" not in ds or "point" not in ds.dims:
        return math.nan, math.nan
    r = np.asarray(ds["rotor_speed"].values, float).reshape(ds.sizes["point"], -1)
    ok = np.array([str(s) == "ok" for s in ds["status"].values]) if "status" in ds else np.ones(len(r), bool)
    ends = np.array([np.nanmax(x) if np.any(np.isfinite(x)) else np.nan for x in r[ok]])
    ends = ends[np.isfinite(ends)]
    return (float(ends.min()), float(ends.max())) if ends.size else (math.nan, math.nan)


#: sweeps whose ends differ by less than this fraction searched one range (:func:`searched_text`)
ENDS_SPREAD = 0.02


def searched_text(v: Verdict) -> str:
    """`` up to 14 RPM at every wind speed (22 RPM at most)`` (empty without sweeps); where a sweep
    ended below overspeed (or rated), that too: "no instability found" then covers less than the
    turbine's range (the IEA 22 MW shell's sweep at 10 m/s stops between 6.2 and 8 RPM, where its
    blade structure alone loses stability, below its 8.59 RPM overspeed)."""
    if not math.isfinite(v.searched_rpm):
        return ""
    text = f" up to {fmt.qty(v.searched_rpm, 'RPM')}"
    # ends within ENDS_SPREAD of each other are one range: method p's tip-Mach bound lies 1 % lower at
    # 25 m/s than at 4 m/s (the wind adds to the tip's speed), which no point's note explains
    if math.isfinite(v.searched_max_rpm) and v.searched_max_rpm > v.searched_rpm * (1 + ENDS_SPREAD):
        text += f" at every wind speed ({fmt.qty(v.searched_max_rpm, 'RPM')} at most; see the points' notes)"
    short = next(((name, ref) for name, ref in (("rated", v.rated_rpm), ("overspeed", v.overspeed_rpm))
                  if math.isfinite(ref) and v.searched_rpm < ref - 1e-6), None)
    if short is not None:
        text += f", below {short[0]} {fmt.qty(short[1], 'RPM')}: not searched up to it at every wind speed"
    return text


def _operating_rpm(ds: xr.Dataset | None, wind_speed: float) -> float:
    """The control curve's rotor speed (RPM) at ``wind_speed`` (NaN without one)."""
    if ds is None or "operating_rpm" not in ds:
        return math.nan
    v, rpm = ds["operating_wind_speed"].values, ds["operating_rpm"].values
    if not (v.min() <= wind_speed <= v.max()):
        return math.nan
    return float(np.interp(wind_speed, v, rpm))


def _run_assumptions(a) -> dict:
    """The run's modelling choices as words (from its attributes)."""
    out = {}
    if "turbine" in a:
        out["turbine"] = str(a["turbine"])
    if "model_type" in a:
        out["model"] = f"{a['model_type']} ({a.get('model_part', '')})"
    for key, name in (("solver_reduction", "reduction"), ("damping_model", "structural damping")):
        if key in a:
            out[name] = str(a[key])
    if "damping_ratio" in a and str(a.get("damping_model", "none")) != "none":
        out["structural damping"] += f", ζ = {100 * float(a['damping_ratio']):.2g} %"
    for key, name in (("solver_induction", "induction"), ("solver_steady_loads", "steady loads (deflection)"),
                      ("solver_geometric_stiffness", "geometric stiffness")):
        if key in a:
            out[name] = "yes" if int(a[key]) else "no"
    return out


def instability_text(f: Instability, v: Verdict) -> str:
    """One sentence on an instability, e.g. ``"flutter of flap, blade 2 at 21.18 RPM, 3.496 Hz
    (V = 25 m/s; rotor-speed sweep (potential, pk)): +75.0 % to rated 12.10 RPM, +45.9 % to
    overspeed 14.52 RPM"``."""
    what = f"flutter of {f.mode}" if f.kind == "flutter" else (
        "static divergence" if f.kind == "divergence" else f"negative damping of {f.mode} (ζ = {fmt.pct(f.damping_ratio, 2, False)})")
    freq = f", {fmt.qty(f.frequency_hz, 'Hz', 3)}" if f.kind != "divergence" else ""
    grew = f", grown from {f.grew_from}" if f.grew_from and f.grew_from != f.mode else ""
    margins = [f"{fmt.pct(m)} to {name} {fmt.qty(ref, 'RPM')}" for m, name, ref in
               ((f.margin_rated, "rated", v.rated_rpm), (f.margin_overspeed, "overspeed", v.overspeed_rpm))
               if math.isfinite(m)]
    return (f"{what} at {fmt.qty(f.rotor_speed_rpm, 'RPM')}{freq}{grew} (V = {fmt.sig(f.wind_speed)} m/s; {f.where})"
            + (": " + ", ".join(margins) if margins else "") + (f" -- caution: {f.caveat}" if f.caveat else ""))


def least_damped_text(ld: dict | None) -> str:
    if ld is None:
        return "no operating-point modes"
    return (f"{ld['name']}, ζ = {fmt.pct(ld['damping_ratio'], 2, False)} at V = {fmt.sig(ld['wind_speed'])} m/s "
            f"({fmt.qty(ld['frequency_hz'], 'Hz', 3)}, {fmt.qty(ld['rotor_speed_rpm'], 'RPM')})")


def headline(ds: xr.Dataset | None = None, campbell=None) -> str:
    """The lines ``windflutter run`` prints at its end: the verdict, the first instability (mode,
    RPM, margins) and the least damped mode in operation (name, ζ, wind speed).  Plain text."""
    v = verdict(ds, campbell)
    lines = [f"verdict: {v.status.upper() if not v.stable else v.status}"]
    if v.first is not None:
        lines.append(f"first instability: {instability_text(v.first, v)}")
    elif v.status == NO_INSTABILITY:
        lines.append(f"first instability: none found{searched_text(v)}")
    if campbell is not None:
        lines.append(f"least damped mode in operation: {least_damped_text(v.least_damped)}{_campbell_scope(v, campbell)}")
    return "\n".join(lines)


def _campbell_scope(v: Verdict, campbell) -> str:
    """When the verdict's instability in operation is the sweep's and the operating-point Campbell
    found every mode damped, the Campbell line says which wind speeds it covered, so the two lines
    do not read as a contradiction (issue 34: "UNSTABLE IN OPERATION" above "least damped ... ζ > 0")."""
    f, ld = v.first, v.least_damped
    if (v.status != UNSTABLE_IN_OPERATION or f is None or f.kind == "negative damping" or ld is None
            or not ld["damping_ratio"] >= 0):
        return ""
    ws = as_campbell_dataset(campbell)["wind_speed"].values
    return (f" -- every mode damped at the Campbell's operating points (V = {fmt.sig(float(np.min(ws)))}-"
            f"{fmt.sig(float(np.max(ws)))} m/s); the instability above is the rotor-speed sweep's at V = "
            f"{fmt.sig(f.wind_speed)} m/s, at or below that wind speed's operating rotor speed")
