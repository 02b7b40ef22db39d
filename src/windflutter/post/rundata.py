"""The description of a run in its dataset: turbine, model size, reference rotor speeds, versions.

:func:`describe_run` gathers what the run knows about the turbine and the analyser;
:func:`assemble_dataset` combines the stored points (:mod:`windflutter.post.store`) with the run's
attributes and the turbine's operating curve.  The model-size attributes come from the stored
points themselves, so a resumed run has the attributes of an uninterrupted one whichever points
it computed in this process.
"""

from __future__ import annotations

import math
import platform
from typing import Any

import numpy as np
import xarray as xr

from windflutter.version import __version__
from windflutter.config import AnalysisConfig
from windflutter.errors import InputError
from windflutter.post import store
from windflutter.units import RPM


def describe_run(turbine: Any, config: AnalysisConfig, analyser: Any) -> dict[str, Any]:
    """Turbine, model and reference rotor speeds of a run (for attributes, plots and report).

    Values from ``analyser.describe()`` (if present) win over those read from ``turbine``.
    Returns keys ``turbine``, ``rated_rpm``, ``overspeed_rpm``, ``operating_wind_speed``,
    ``operating_rpm``, ``operating_pitch_deg`` (arrays or None) and any model-size entries.
    """
    info: dict[str, Any] = {"turbine": str(getattr(turbine, "name", turbine))}
    curve = getattr(turbine, "operating_curve", None)
    if curve is not None:
        info["operating_wind_speed"] = np.asarray(curve.wind_speed, float)
        info["operating_rpm"] = np.asarray(curve.rotor_speed, float) / RPM
        info["operating_pitch_deg"] = np.degrees(np.asarray(curve.pitch, float))
    rated = getattr(turbine, "rated_rotor_speed", None)
    if rated is not None and np.isfinite(rated) and rated > 0:
        info["rated_rpm"] = float(rated) / RPM
    for attr in ("rotor_diameter", "hub_height", "n_blades", "source"):
        val = getattr(turbine, attr, None)
        if val is not None:
            info[attr] = val
    describe = getattr(analyser, "describe", None)
    if callable(describe):
        info.update(describe() or {})
    if config.operating.rated_rpm is not None:
        info["rated_rpm"] = config.operating.rated_rpm
    if "rated_rpm" not in info and info.get("operating_rpm") is not None:
        info["rated_rpm"] = float(np.max(info["operating_rpm"]))
    rated = info.get("rated_rpm")
    if config.operating.overspeed_rpm is not None:
        info["overspeed_rpm"] = config.operating.overspeed_rpm
    elif rated is not None:
        info["overspeed_rpm"] = config.operating.overspeed_factor * float(rated)
    return info


def check_operating(turbine: Any, config: AnalysisConfig) -> None:
    """An explicit ``operating.overspeed_rpm`` must not lie below the rated rotor speed (the
    config's ``operating.rated_rpm`` or the turbine's); :class:`InputError` otherwise."""
    o = config.operating
    rated = o.rated_rpm
    r = getattr(turbine, "rated_rotor_speed", None)
    if rated is None and isinstance(r, (int, float)) and math.isfinite(r) and r > 0:
        rated = float(r) / RPM
    if rated is not None and o.overspeed_rpm is not None and o.overspeed_rpm < rated:
        raise InputError("operating.overspeed_rpm", o.overspeed_rpm,
                         f"an overspeed at least the rated rotor speed {rated:.4g} RPM")


def versions() -> dict[str, str]:
    import scipy  # noqa: PLC0415

    v = {"windflutter_version": __version__, "numpy_version": np.__version__,
         "scipy_version": scipy.__version__, "xarray_version": xr.__version__,
         "python_version": platform.python_version()}
    try:
        import pyfe3d  # noqa: PLC0415
        v["pyfe3d_version"] = getattr(pyfe3d, "__version__", "?")
    except ImportError:  # pragma: no cover
        pass
    return v


def run_attrs(config: AnalysisConfig, info: dict[str, Any]) -> dict[str, Any]:
    attrs: dict[str, Any] = {
        "title": config.title or f"windflutter stability analysis of {info.get('turbine', '?')}",
        "Conventions": "CF-1.8",
        "source": "windflutter run",
        "history": f"created by windflutter {__version__} run",
        "config_fingerprint": config.fingerprint(),
        "config_yaml": config.to_yaml(),
    }
    attrs.update(versions())
    for section in ("solver", "model", "damping"):
        for k, v in config.to_dict()[section].items():
            attrs[f"{section}_{k}"] = v
    attrs["air_density"] = config.air_density
    for k, v in info.items():
        if isinstance(v, np.ndarray):
            continue
        attrs[k] = v
    return attrs


def operating_vars(info: dict[str, Any]) -> dict[str, xr.DataArray]:
    out = {}
    v = info.get("operating_wind_speed")
    if v is None:
        return out
    out["operating_rpm"] = xr.DataArray(np.asarray(info["operating_rpm"], float), dims="operating",
                                        coords={"operating_wind_speed": ("operating", np.asarray(v, float))},
                                        attrs={"units": "rpm", "long_name": "rotor speed of the control curve"})
    if info.get("operating_pitch_deg") is not None:
        out["operating_pitch"] = xr.DataArray(np.asarray(info["operating_pitch_deg"], float), dims="operating",
                                              attrs={"units": "degree", "long_name": "blade pitch of the control curve"})
    return out


#: model-size entries of a point's ``info`` that become run attributes (largest over the points)
MODEL_SIZE_KEYS = ("n_nodes", "n_dof", "n_aero_sections", "n_reduced_dof")


def assemble_dataset(points: dict[int, xr.Dataset], config: AnalysisConfig, info: dict[str, Any],
                     n_planned: int) -> xr.Dataset:
    """Combine stored points with the run's attributes and the operating curve."""
    attrs = run_attrs(config, info)
    attrs["n_points_planned"] = n_planned
    attrs["n_points_done"] = len(points)
    attrs["complete"] = int(len(points) == n_planned)
    for key in MODEL_SIZE_KEYS:  # from the stored points: the same whichever points ran in this process
        sizes = [int(d.attrs[f"info_{key}"]) for d in points.values() if f"info_{key}" in d.attrs]
        if sizes:
            attrs[key] = max(sizes)
    ds = store.combine(points, attrs)
    for name, da in operating_vars(info).items():
        ds[name] = da
    if "operating_wind_speed" in ds.coords:
        ds["operating_wind_speed"].attrs.update(units="m/s", long_name="wind speed of the control curve")
    return ds
