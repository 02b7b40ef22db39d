"""Operating curves (wind speed -> rotor speed, pitch) from steady-state tables or the control block.

Readers
-------
* :func:`read_openfast_steady_csv` - tab/comma separated with a header naming ``WS``,
  ``RotSpeed`` (rpm), ``BldPitch`` (deg), optionally ``GenPower`` (kW) and ``RotThrust`` (kN)
  (e.g. ``NREL5MW_Oper_Onshore_Flexible_Discon.csv``).
* :func:`read_hawc2_opt` - HAWCStab2 ``.opt``: first line either the number of rows followed by
  column titles (wind, pitch deg, rpm, power kW, thrust kN) or directly data with 3+ columns.
* :func:`curve_from_control` - below-rated curve from the windIO ``control`` block (TSR tracking
  between the minimum and maximum rotor speed, minimum pitch); above rated the pitch is unknown
  without an aerodynamic solution, so the curve stops at the wind speed where the maximum rotor
  speed is reached.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model.turbine import ControlSettings, OperatingCurve
from windflutter.units import DEG, RPM


def _check_curve(v, w, p, source: str) -> None:
    if v.size < 2 or np.any(np.diff(v) <= 0):
        raise InputError("operating curve wind speed", v.tolist()[:5], "at least 2 increasing wind speeds (m/s)",
                         source)
    if np.any(w < 0) or not np.all(np.isfinite(w)):
        raise InputError("operating curve rotor speed", w.tolist()[:5], "non-negative rotor speeds", source)
    if not np.all(np.isfinite(p)):
        raise InputError("operating curve pitch", p.tolist()[:5], "finite pitch angles", source)


def read_openfast_steady_csv(path: str | Path) -> OperatingCurve:
    """Read an OpenFAST steady-state table (see module docstring)."""
    p = Path(path)
    text = p.read_text().strip().splitlines()
    sep = "\t" if "\t" in text[0] else ","
    head = [h.strip() for h in text[0].split(sep)]

    def col(prefix: str) -> int | None:
        for i, h in enumerate(head):
            if h.split("_")[0].split(" ")[0].lower() == prefix.lower():
                return i
        return None

    iw, ir, ip = col("WS"), col("RotSpeed"), col("BldPitch")
    if None in (iw, ir, ip):
        raise InputError("steady-state table header", head[:6], "columns WS, RotSpeed [rpm], BldPitch [deg]", str(p))
    data = np.array([[float(x) for x in ln.split(sep)] for ln in text[1:] if ln.strip()])
    v, w, pit = data[:, iw], data[:, ir] * RPM, data[:, ip] * DEG
    _check_curve(v, w, pit, str(p))
    ig, it = col("GenPower"), col("RotThrust")
    power = data[:, ig] * 1e3 if ig is not None else None
    thrust = data[:, it] * 1e3 if it is not None else None
    return OperatingCurve(wind_speed=v, rotor_speed=w, pitch=pit, power=power, thrust=thrust,
                          source=f"steady-state table {p.name}")


def read_hawc2_opt(path: str | Path) -> OperatingCurve:
    """Read a HAWCStab2 operational-data file (``.opt``), see module docstring."""
    p = Path(path)
    lines = [ln for ln in p.read_text().splitlines() if ln.strip()]
    first = lines[0].split()
    try:
        vals = [float(x) for x in first]
        body = lines if len(vals) >= 3 else lines[1:]
    except ValueError:
        body = lines[1:]
    data = np.array([[float(x) for x in ln.split()] for ln in body])
    if data.ndim != 2 or data.shape[1] < 3:
        raise InputError("HAWCStab2 .opt", str(p), "rows of wind speed, pitch (deg), rotor speed (rpm)", str(p))
    v, pit, w = data[:, 0], data[:, 1] * DEG, data[:, 2] * RPM
    _check_curve(v, w, pit, str(p))
    power = data[:, 3] * 1e3 if data.shape[1] > 3 else None
    thrust = data[:, 4] * 1e3 if data.shape[1] > 4 else None
    return OperatingCurve(wind_speed=v, rotor_speed=w, pitch=pit, power=power, thrust=thrust,
                          source=f"HAWCStab2 {p.name}")


def curve_from_control(control: ControlSettings, rotor_radius: float, n: int = 41) -> OperatingCurve | None:
    """Below-rated operating curve from TSR tracking (see module docstring); ``None`` if the
    control block lacks TSR, speed limits or cut-in."""
    c = control
    if not all(np.isfinite([c.tsr, c.max_rotor_speed, c.cut_in])):
        return None
    w_min = c.min_rotor_speed if np.isfinite(c.min_rotor_speed) else 0.0
    w_max = c.max_rotor_speed
    if np.isfinite(c.max_tip_speed):
        w_max = min(w_max, c.max_tip_speed / rotor_radius)
    v_rated_speed = w_max * rotor_radius / c.tsr
    v = np.linspace(c.cut_in, max(v_rated_speed, c.cut_in + 1e-3), n)
    w = np.clip(c.tsr * v / rotor_radius, w_min, w_max)
    p = np.full_like(v, c.min_pitch)
    return OperatingCurve(wind_speed=v, rotor_speed=w, pitch=p,
                          source="control block: TSR tracking below rated (pitch above rated unknown)")


def curve_from_inline(d: dict, source: str) -> OperatingCurve:
    """Inline table ``{wind_speed: [...], rotor_speed_rpm: [...], pitch_deg: [...]}``."""
    try:
        v = np.asarray(d["wind_speed"], dtype=float)
        w = np.asarray(d["rotor_speed_rpm"], dtype=float) * RPM
        p = np.asarray(d["pitch_deg"], dtype=float) * DEG
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError("windflutter.operating_curve", str(exc), "wind_speed, rotor_speed_rpm, pitch_deg lists of "
                         "numbers", source) from None
    if not (v.shape == w.shape == p.shape):
        raise InputError("windflutter.operating_curve", (v.size, w.size, p.size), "lists of equal length", source)
    _check_curve(v, w, p, source)
    return OperatingCurve(wind_speed=v, rotor_speed=w, pitch=p, source=str(d.get("source", "inline table")))
