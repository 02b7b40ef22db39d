"""The operating-point Campbell diagram as a CF-1.8 dataset (wind speed x mode track).

:func:`campbell_dataset` turns a :class:`~windflutter.system.campbell.CampbellResult` into an
:class:`xarray.Dataset` that the figure (:mod:`windflutter.post.campbell_plots`), the exports
(:mod:`windflutter.post.campbell_export`), the verdict (:mod:`windflutter.post.verdict`) and the
store (``OUTDIR/campbell.nc``) all read, so a stored diagram can be re-plotted and re-exported.

Dimensions ``wind_speed`` (m/s, strictly increasing) and ``track`` (a mode followed along the
wind speeds by :func:`~windflutter.system.campbell.track_modes`).  Every mode of every point sits
in exactly one cell; a cell without a mode is NaN (strings: empty).  Per cell the mode's name,
family, whirl and order (a track is one structural identity, :mod:`windflutter.system.identity`;
a mixed mode's name adds its second participation), its two largest participations and their
shares, its undamped and damped frequencies (Hz), damping ratio (1), the real and imaginary parts
of its eigenvalue (s-1; NetCDF has no complex type) and the flags rigid-body root, mixed and heavily
damped.  ``track_name`` is the identity a track follows.  The modelling assumptions are global attributes ``assumption_<key>``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr

from windflutter.version import __version__
from windflutter.errors import InputError

#: units and long names; units are UDUNITS-2 strings (CF section 3.1)
CAMPBELL_VARIABLES: dict[str, tuple[str | None, str]] = {
    "wind_speed": ("m/s", "free wind speed of the operating point"),
    "track": (None, "index of the mode track (a mode followed along the wind speeds)"),
    "rotor_speed": ("rpm", "rotor speed of the operating point"),
    "pitch": ("degree", "blade pitch of the operating point"),
    "power": ("W", "aerodynamic rotor power of the steady state"),
    "thrust": ("N", "rotor thrust of the steady state"),
    "tip_deflection": ("m", "flapwise blade-tip deflection of the steady state"),
    "track_name": (None, "structural identity the track follows (its last mode's name for a track without one)"),
    "mode_name": (None, "name of the mode at this operating point: its identity, with its second participation "
                        "when mixed (empty: not found)"),
    "family": (None, "mode family: flap, edge, torsion, tower_fa, tower_ss, tower_torsion, tower_wall (a shell "
                     "tower's wall mode), drivetrain, rigid, mixed, buckling (the prestressed blade statically "
                     "unstable on its own)"),
    "whirl": (None, "whirl of the mode: BW, FW, collective, asymmetric or none"),
    "participation_1": (None, "the structural identity with the largest share of the mode"),
    "participation_2": (None, "the structural identity with the second largest share of the mode"),
    "participation_1_share": ("1", "share of the mode's energy in participation_1"),
    "participation_2_share": ("1", "share of the mode's energy in participation_2"),
    "share": ("1", "share of the mode's energy in the identity it is named by"),
    "mixed": ("1", "1 when the identity it is named by carries less than 60 % of the mode"),
    "heavily_damped": ("1", "1 for a damping ratio above 0.3"),
    "order": ("1", "order of the mode within its family and whirl (0: none / not found)"),
    "frequency": ("Hz", "undamped natural frequency |lambda|/(2 pi) of the mode"),
    "damped_frequency": ("Hz", "damped frequency Im(lambda)/(2 pi) of the mode"),
    "damping_ratio": ("1", "damping ratio -Re(lambda)/|lambda| of the mode"),
    "eigenvalue_real": ("s-1", "real part of the mode's eigenvalue lambda"),
    "eigenvalue_imag": ("s-1", "imaginary part of the mode's eigenvalue lambda (damped angular frequency, rad/s)"),
    "rigid_body": ("1", "1 for the drivetrain's rigid-body root, 0 otherwise"),
}
CELL_FLOATS = ("frequency", "damped_frequency", "damping_ratio", "eigenvalue_real", "eigenvalue_imag", "share",
               "participation_1_share", "participation_2_share")
CELL_STRINGS = ("mode_name", "family", "whirl", "participation_1", "participation_2")
CELL_FLAGS = ("rigid_body", "mixed", "heavily_damped")
POINT_FLOATS = {"rotor_speed": "rotor_speed_rpm", "pitch": "pitch_deg", "power": "power",
                "thrust": "thrust", "tip_deflection": "tip_deflection"}


def _var_attrs(name: str) -> dict:
    units, long_name = CAMPBELL_VARIABLES[name]
    return {"long_name": long_name, **({"units": units} if units is not None else {})}


def _cells(result, order: np.ndarray) -> dict[str, np.ndarray]:
    """Per-cell arrays (n_points, n_tracks) in the wind-speed ``order``."""
    pts = [result.points[i] for i in order]
    tracks = list(result.tracks)
    n, nt = len(pts), len(tracks)
    out: dict[str, np.ndarray] = {k: np.full((n, nt), np.nan) for k in CELL_FLOATS}
    out.update({k: np.full((n, nt), "", dtype=object) for k in CELL_STRINGS})
    out["order"] = np.zeros((n, nt), np.int32)
    out.update({k: np.zeros((n, nt), np.int8) for k in CELL_FLAGS})
    for t, tr in enumerate(tracks):
        for row, i in enumerate(order):
            k = tr.index[i]
            if k < 0:
                continue
            m = result.points[i].modes[k]
            lam = complex(m.eigenvalue)
            for key, val in (("frequency", m.frequency_hz), ("damped_frequency", m.damped_frequency_hz),
                             ("damping_ratio", m.damping_ratio), ("eigenvalue_real", lam.real),
                             ("eigenvalue_imag", lam.imag)):
                out[key][row, t] = val
            out["mode_name"][row, t], out["family"][row, t], out["whirl"][row, t] = m.name, m.family, m.whirl
            out["order"][row, t] = int(m.order)
            out["rigid_body"][row, t] = int(bool(m.rigid))
            out["mixed"][row, t] = int(bool(getattr(m, "mixed", False)))
            out["heavily_damped"][row, t] = int(m.damping_ratio > 0.3)
            out["share"][row, t] = float(getattr(m, "share", np.nan))
            for j, (name, share) in enumerate(list(getattr(m, "participation", []))[:2], start=1):
                out[f"participation_{j}"][row, t], out[f"participation_{j}_share"][row, t] = name, float(share)
    return out


def _last_names(names: np.ndarray) -> np.ndarray:
    """Per track the name at its last row with a mode."""
    out = np.full(names.shape[1], "", dtype=object)
    for t in range(names.shape[1]):
        rows = [r for r in range(names.shape[0]) if names[r, t]]
        out[t] = names[rows[-1], t] if rows else ""
    return out


def _check_tracks(result) -> None:
    """Every mode of every point in exactly one track (else the diagram would lose modes)."""
    n = len(result.points)
    for i, p in enumerate(result.points):
        seen = sorted(tr.index[i] for tr in result.tracks if len(tr.index) == n and tr.index[i] >= 0)
        if seen != list(range(len(p.modes))):
            raise InputError(f"tracks at point {i} (V = {p.wind_speed:g} m/s)", seen,
                             f"each of the point's {len(p.modes)} modes in exactly one track")


def campbell_dataset(result) -> xr.Dataset:
    """The CF-1.8 dataset of a Campbell result (see the module docstring).

    Parameters
    ----------
    result : :class:`~windflutter.system.campbell.CampbellResult` (or an object with the same
        attributes: ``turbine``, ``part``, ``frame``, ``points``, ``tracks``, ``assumptions``).

    Raises
    ------
    InputError
        repeated wind speeds (a CF coordinate must be strictly monotonic), or tracks that do not
        cover every mode once.
    """
    v = np.array([float(p.wind_speed) for p in result.points])
    order = np.argsort(v, kind="stable")
    if v.size > 1 and np.any(np.diff(v[order]) <= 0):
        raise InputError("wind_speeds", v.tolist(), "distinct wind speeds (m/s)")
    _check_tracks(result)
    cells = _cells(result, order)
    dims = ("wind_speed", "track")
    data = {k: (dims, cells[k]) for k in (*CELL_STRINGS, "order", *CELL_FLOATS, *CELL_FLAGS)}
    for key, attr in POINT_FLOATS.items():
        data[key] = (("wind_speed",), np.array([float(getattr(result.points[i], attr)) for i in order]))
    last = _last_names(cells["mode_name"])
    data["track_name"] = (("track",), np.array([getattr(tr, "identity", "") or last[t]
                                                for t, tr in enumerate(result.tracks)], dtype=object))
    ds = xr.Dataset(data, coords={"wind_speed": ("wind_speed", v[order]),
                                  "track": ("track", np.arange(len(result.tracks), dtype=np.int32))})
    for name in ds.variables:
        ds[name].attrs.update(_var_attrs(name))
    ds["wind_speed"].attrs["standard_name"] = "wind_speed"
    ds["wind_speed"].encoding["_FillValue"] = None  # CF 2.5.1: no fill value on a coordinate variable
    ds["rigid_body"].attrs.update(flag_values=np.array([0, 1], np.int8), flag_meanings="elastic rigid_body")
    ds["mixed"].attrs.update(flag_values=np.array([0, 1], np.int8), flag_meanings="named mixed")
    ds["heavily_damped"].attrs.update(flag_values=np.array([0, 1], np.int8), flag_meanings="normal heavily_damped")
    ds.attrs.update(campbell_attrs(result))
    return ds


def campbell_attrs(result) -> dict[str, Any]:
    """Global attributes: conventions, what it is, and the modelling assumptions (strings)."""
    attrs: dict[str, Any] = {
        "Conventions": "CF-1.8",
        "title": f"Operating-point Campbell diagram of {result.turbine}",
        "source": f"windflutter {__version__} campbell",
        "history": f"created by windflutter {__version__}",
        "turbine": str(result.turbine), "part": str(result.part), "frame": str(result.frame),
    }
    for k, val in (getattr(result, "assumptions", None) or {}).items():
        attrs[f"assumption_{k}"] = str(val)
    return attrs


def as_campbell_dataset(obj) -> xr.Dataset:
    """``obj`` if it is already a Campbell dataset, else :func:`campbell_dataset` of it."""
    if isinstance(obj, xr.Dataset):
        missing = [k for k in ("frequency", "damping_ratio", "mode_name") if k not in obj]
        if missing or "track" not in obj.dims:
            raise InputError("campbell", f"a dataset without {', '.join(missing) or 'a track dimension'}",
                             "a Campbell dataset (windflutter.post.campbell_data.campbell_dataset)")
        return obj
    return campbell_dataset(obj)


def assumptions(ds: xr.Dataset) -> dict[str, str]:
    """The modelling assumptions recorded in a Campbell dataset (``assumption_*`` attributes)."""
    return {k[len("assumption_"):]: str(v) for k, v in ds.attrs.items() if k.startswith("assumption_")}


def present(ds: xr.Dataset) -> np.ndarray:
    """(n_wind, n_track) bool: a mode sits in the cell."""
    return np.isfinite(ds["frequency"].values)


def track_style_keys(ds: xr.Dataset) -> list[tuple[str, str, str]]:
    """Per track ``(name, family, whirl)`` at its last point with a mode ('' if never present)."""
    pres = present(ds)
    out = []
    fam, whl = ds["family"].values, ds["whirl"].values
    for t in range(ds.sizes["track"]):
        rows = np.where(pres[:, t])[0]
        if rows.size == 0:
            out.append(("", "", ""))
            continue
        r = rows[-1]
        out.append((str(ds["track_name"].values[t]), str(fam[r, t]), str(whl[r, t])))
    return out


def least_damped(ds: xr.Dataset, exclude_rigid: bool = True) -> dict | None:
    """The least damped mode over all points: ``{wind_speed, rotor_speed_rpm, name, frequency_hz,
    damping_ratio, track}`` (None without modes); the rigid-body drivetrain root left out."""
    z = np.where(present(ds), ds["damping_ratio"].values, np.nan)
    if exclude_rigid:
        z = np.where((ds["rigid_body"].values == 1) | (ds["family"].values == "buckling"), np.nan, z)
    if not np.any(np.isfinite(z)):
        return None
    i, t = np.unravel_index(int(np.nanargmin(z)), z.shape)
    return cell(ds, i, t)


def cell(ds: xr.Dataset, i: int, t: int) -> dict:
    """The mode at wind-speed row ``i`` and track ``t`` as a plain dict (SI and Hz, RPM)."""
    return {"wind_speed": float(ds["wind_speed"].values[i]), "rotor_speed_rpm": float(ds["rotor_speed"].values[i]),
            "pitch_deg": float(ds["pitch"].values[i]), "name": str(ds["mode_name"].values[i, t]),
            "family": str(ds["family"].values[i, t]), "whirl": str(ds["whirl"].values[i, t]),
            "frequency_hz": float(ds["frequency"].values[i, t]),
            "damped_frequency_hz": float(ds["damped_frequency"].values[i, t]),
            "damping_ratio": float(ds["damping_ratio"].values[i, t]), "track": int(t)}


def least_damped_per_point(ds: xr.Dataset, exclude_rigid: bool = True) -> list[dict | None]:
    """Per wind speed the least damped mode (:func:`cell` dict; None where a point has none)."""
    z = np.where(present(ds), ds["damping_ratio"].values, np.nan)
    if exclude_rigid:
        z = np.where((ds["rigid_body"].values == 1) | (ds["family"].values == "buckling"), np.nan, z)
    out: list[dict | None] = []
    for i in range(ds.sizes["wind_speed"]):
        row = z[i]
        out.append(cell(ds, i, int(np.nanargmin(row))) if np.any(np.isfinite(row)) else None)
    return out


def unstable(ds: xr.Dataset) -> list[dict]:
    """Every mode with negative damping (rigid-body root and the blade structure's own static
    instabilities, family ``buckling``, excluded), by wind speed then damping."""
    z = np.where(present(ds) & (ds["rigid_body"].values != 1) & (ds["family"].values != "buckling"),
                 ds["damping_ratio"].values, np.nan)
    rows, cols = np.where(np.nan_to_num(z, nan=math.inf) < 0)
    found = sorted(zip(rows, cols), key=lambda rc: (rc[0], z[rc[0], rc[1]]))
    return [cell(ds, int(i), int(t)) for i, t in found]
