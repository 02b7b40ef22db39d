"""Results on disk: one NetCDF file per finished operating point, combined into one dataset.

Layout of an output folder::

    OUTDIR/analysis.yaml        the resolved analysis config of the run
    OUTDIR/points/p0003.nc      one file per finished (or failed) operating point
    OUTDIR/results.nc           all finished points combined (rewritten after every point)

Every file is written to a temporary name in the same folder and moved into place with
:func:`os.replace`, which is atomic on POSIX and Windows: a kill at any moment leaves either the
old file or the new one, never a torn file.  ``--resume`` reads ``points/`` and skips what is
there; stray temporaries of a killed run are removed.

The combined dataset has one dimension ``point`` (the operating point, ordered by its index)
with coordinates ``wind_speed`` (m/s), ``aero`` and ``method``, and per-point sub-dimensions
``sweep`` (Campbell rotor speeds), ``mode`` (tracked modes), ``station`` (span stations),
``component`` (flap, edge, torsion of the mode shape) and ``dof`` (plunge, pitch, edgewise of
the aero-work diagnostic).  NetCDF has no complex type: complex mode shapes are stored as
``*_real`` / ``*_imag`` pairs.  Every variable has ``units`` and ``long_name`` attributes.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import secrets
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

if TYPE_CHECKING:  # pragma: no cover
    from windflutter.results import OperatingPoint, PointResult

POINTS_DIR = "points"
RESULTS_FILE = "results.nc"
COMPONENTS = ("flap", "edge", "torsion")
WORK_DOFS = ("plunge", "pitch", "edgewise")

#: units and long names of the stored variables
VARIABLES: dict[str, tuple[str, str]] = {
    "wind_speed": ("m/s", "free wind speed"),
    "flutter_rpm": ("rpm", "lowest rotor speed with flutter (NaN: none in the searched range)"),
    "flutter_frequency": ("Hz", "frequency of the flutter mode at onset"),
    "flutter_mode": ("1", "label of the flutter mode"),
    "divergence_rpm": ("rpm", "lowest rotor speed with static divergence (NaN: none in range)"),
    "status": ("1", "ok or failed"),
    "reason": ("1", "why the point failed (empty if ok)"),
    "elapsed": ("s", "wall-clock time of the point"),
    "rotor_speed": ("rpm", "rotor speed of the sweep"),
    "frequency": ("Hz", "damped frequency of the tracked mode"),
    "damping_ratio": ("1", "damping ratio zeta = -sigma/|lambda| of the tracked mode"),
    "mode_label": ("1", "label of the tracked mode"),
    "station_radius": ("m", "radius of the span station from the shaft axis"),
    "flutter_shape_real": ("m or rad", "flutter mode shape at onset, real part (flap, edge m; torsion rad)"),
    "flutter_shape_imag": ("m or rad", "flutter mode shape at onset, imaginary part"),
    "aero_work": ("J", "aerodynamic work per cycle on the flutter mode, per station and section DOF"),
    "aero_work_total": ("J", "total aerodynamic work per cycle on the flutter mode"),
}


def _attrs(name: str) -> dict:
    units, long_name = VARIABLES.get(name, ("1", name))
    return {"units": units, "long_name": long_name}


def point_dataset(point: OperatingPoint, result: PointResult, attrs: dict | None = None) -> xr.Dataset:
    """One operating point's results as a dataset with a length-1 ``point`` dimension."""
    nan = np.nan
    data: dict[str, tuple] = {
        "flutter_rpm": (("point",), [_f(result.flutter_rpm)]),
        "flutter_frequency": (("point",), [_f(result.flutter_frequency_hz)]),
        "flutter_mode": (("point",), np.array([result.flutter_mode or ""], dtype=object)),
        "divergence_rpm": (("point",), [_f(result.divergence_rpm)]),
        "status": (("point",), np.array([result.status], dtype=object)),
        "reason": (("point",), np.array([result.reason or ""], dtype=object)),
        "elapsed": (("point",), [_f(result.elapsed)]),
    }
    coords: dict[str, tuple] = {
        "point": ("point", [point.index]),
        "wind_speed": ("point", [point.wind_speed]),
        "aero": ("point", np.array([point.aero], dtype=object)),
        "method": ("point", np.array([point.method], dtype=object)),
    }
    # sub-dimension variables always exist (size 0 when absent) so that points combine
    rpm = np.asarray(result.sweep_rpm if result.sweep_rpm is not None else [], float).ravel()
    nr = rpm.size
    if nr:
        freq = np.asarray(result.frequency_hz, float).reshape(nr, -1)
        zeta = np.asarray(result.damping_ratio, float).reshape(nr, -1)
    else:
        freq = zeta = np.zeros((0, 0))
    nm = freq.shape[1]
    labels = list(result.mode_labels or [])
    labels = (labels + [f"mode {i + 1}" for i in range(len(labels), nm)])[:nm]
    data["rotor_speed"] = (("point", "sweep"), rpm[None, :])
    data["frequency"] = (("point", "sweep", "mode"), freq[None])
    data["damping_ratio"] = (("point", "sweep", "mode"), zeta[None])
    data["mode_label"] = (("point", "mode"), np.array(labels, dtype=object).reshape(1, nm))
    r = np.asarray(result.station_radius if result.station_radius is not None else [], float).ravel()
    ns = r.size
    shp = (np.asarray(result.flutter_shape, complex).reshape(ns, 3) if result.flutter_shape is not None and ns
           else np.full((ns, 3), nan + 0j))
    w = (np.asarray(result.aero_work, float).reshape(ns, 3) if result.aero_work is not None and ns
         else np.full((ns, 3), nan))
    data["station_radius"] = (("point", "station"), r[None])
    data["flutter_shape_real"] = (("point", "station", "component"), shp.real[None])
    data["flutter_shape_imag"] = (("point", "station", "component"), shp.imag[None])
    data["aero_work"] = (("point", "station", "dof"), w[None])
    data["aero_work_total"] = (("point",), [float(np.sum(w)) if ns and np.all(np.isfinite(w)) else nan])
    coords.update(sweep=("sweep", np.arange(nr)), mode=("mode", np.arange(nm)),
                  station=("station", np.arange(ns)), component=("component", list(COMPONENTS)),
                  dof=("dof", list(WORK_DOFS)))
    ds = xr.Dataset(data, coords=coords)
    for name in list(ds.data_vars) + ["wind_speed"]:
        ds[name].attrs.update(_attrs(name))
    for k, v in (result.info or {}).items():
        ds.attrs[f"info_{k}"] = _attr_value(v)
    ds.attrs.update({k: _attr_value(v) for k, v in (attrs or {}).items()})
    return ds


def _f(v) -> float:
    return float("nan") if v is None else float(v)


def _attr_value(v):
    """NetCDF attributes take str, numbers and 1-D numeric arrays."""
    if isinstance(v, (bool, np.bool_)):
        return int(v)
    if isinstance(v, (int, float, str, np.integer, np.floating)):
        return v
    if isinstance(v, (list, tuple)) and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v) and v:
        return np.asarray(v, float)
    return str(v)


def _strings_fixed(ds: xr.Dataset) -> xr.Dataset:
    """Object (string) variables as NumPy unicode arrays, which netCDF4 stores as strings
    even when empty."""
    ds = ds.copy()
    for name, var in list(ds.variables.items()):
        if var.dtype == object:
            vals = np.array([("" if (isinstance(x, float) and x != x) else str(x)) for x in var.values.ravel()],
                            dtype="U").reshape(var.shape) if var.size else np.zeros(var.shape, dtype="U1")
            ds[name] = var.copy(data=vals)
    return ds


@contextlib.contextmanager
def _interrupts_deferred():
    """Hold SIGINT/SIGTERM until the block is done (main thread, POSIX; no-op elsewhere).

    A KeyboardInterrupt raised inside xarray/netCDF4/HDF5 while they hold their (non-reentrant)
    file lock leaves that lock taken, and the next write -- the one that saves the finished
    points after Ctrl-C -- then waits on it forever.  With the signals blocked the write
    completes and the interrupt is delivered right after it.
    """
    sigs = {signal.SIGINT, signal.SIGTERM}
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, sigs)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def atomic_write_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file in the same folder + ``os.replace``);
    an interrupt arriving meanwhile is delivered once the file is complete."""
    with _interrupts_deferred():
        return _atomic_write_netcdf(ds, path)


def _temporary(path: Path, suffix: str) -> tuple[int, str]:
    """A new, uniquely named file next to ``path`` (open descriptor, name), created with the
    mode ``0o666`` less the umask -- what ``open()`` would give the final file --
    where :func:`tempfile.mkstemp` gives ``0o600``."""
    path.parent.mkdir(parents=True, exist_ok=True)
    for _ in range(100):
        tmp = os.path.join(path.parent, f".{path.stem}.{secrets.token_hex(6)}{suffix}")
        try:
            return os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"no free temporary name next to {path}")


def _atomic_write_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    path = Path(path)
    fd, tmp = _temporary(path, ".nc.tmp")
    os.close(fd)
    try:
        _strings_fixed(ds).to_netcdf(tmp, engine="netcdf4")
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def atomic_write_text(text: str, path: str | Path) -> Path:
    """Write text atomically."""
    path = Path(path)
    fd, tmp = _temporary(path, ".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def point_path(outdir: str | Path, index: int) -> Path:
    return Path(outdir) / POINTS_DIR / f"p{index:04d}.nc"


def write_point(outdir: str | Path, ds: xr.Dataset) -> Path:
    """Store one finished point (atomic)."""
    index = int(ds["point"].values[0])
    return atomic_write_netcdf(ds, point_path(outdir, index))


def clean_temporaries(outdir: str | Path) -> int:
    """Remove temporaries left by a killed run; return how many."""
    n = 0
    for folder in (Path(outdir), Path(outdir) / POINTS_DIR):
        if folder.is_dir():
            for p in folder.glob(".*.tmp"):
                p.unlink(missing_ok=True)
                n += 1
    return n


#: what a stored point file must hold to be used again
_POINT_VARS = ("flutter_rpm", "divergence_rpm", "status", "wind_speed", "aero", "method")


def read_point(path: str | Path) -> xr.Dataset:
    """One stored point file, loaded (file closed).

    Raises
    ------
    ValueError
        the file cannot be read (empty, truncated, not NetCDF, unreadable) or is not a point of
        a run (a variable missing, its index not that of its name); the message says which.
    """
    p = Path(path)
    try:
        with xr.open_dataset(p, engine="netcdf4") as ds:
            ds = ds.load()
    except Exception as exc:  # noqa: BLE001 - netCDF4/HDF5 raise OSError, ValueError, KeyError, ...
        msg = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        raise ValueError(f"unreadable ({type(exc).__name__}: {msg})"[:300]) from None
    missing = [v for v in _POINT_VARS if v not in ds.variables]
    if missing or ds.sizes.get("point") != 1:
        raise ValueError(f"not a stored point (missing {', '.join(missing) or 'the point dimension'})")
    index = int(ds["point"].values[0])
    if p.name != point_path(".", index).name:
        raise ValueError(f"holds point {index}, not the one of its name")
    return ds


def read_points(outdir: str | Path, problems: list[str] | None = None) -> dict[int, xr.Dataset]:
    """All stored points of an output folder, by index (loaded into memory, files closed).

    A file that cannot be used (see :func:`read_point`) is left out, so a resumed run computes
    that point again; ``problems`` (if given) receives one line per such file.
    """
    out: dict[int, xr.Dataset] = {}
    folder = Path(outdir) / POINTS_DIR
    if not folder.is_dir():
        return out
    for p in sorted(folder.glob("p[0-9]*.nc")):
        try:
            ds = read_point(p)
        except ValueError as exc:
            if problems is not None:
                problems.append(f"{POINTS_DIR}/{p.name}: {exc}")
            continue
        out[int(ds["point"].values[0])] = ds
    return out


def combine(points: dict[int, xr.Dataset] | list[xr.Dataset], attrs: dict | None = None) -> xr.Dataset:
    """Concatenate point datasets along ``point`` (ordered by index), padding with NaN."""
    items = list(points.values()) if isinstance(points, dict) else list(points)
    if not items:
        ds = xr.Dataset(coords={"point": ("point", np.zeros(0, int))})
    else:
        items.sort(key=lambda d: int(d["point"].values[0]))
        ds = xr.concat(items, dim="point", data_vars="all", coords="different",
                       compat="equals", join="outer", combine_attrs="drop")
        for name in ds.data_vars:
            if ds[name].dtype == object:
                ds[name] = ds[name].fillna("")
        for name in list(ds.data_vars) + ["wind_speed"]:
            ds[name].attrs.update(_attrs(name))
    ds.attrs.update({k: _attr_value(v) for k, v in (attrs or {}).items()})
    return ds


def open_results(path: str | Path) -> xr.Dataset:
    """Open a ``results.nc`` (or an output folder) fully into memory.

    Raises
    ------
    InputError
        no such file, a folder where the file should be, or a file that is not readable NetCDF.
    """
    from windflutter.errors import InputError  # noqa: PLC0415

    given, path = str(path), Path(path)
    if path.is_dir():
        path = path / RESULTS_FILE
    if not path.is_file():
        what = "a folder" if path.is_dir() else "missing"
        raise InputError("results", given, f"a results.nc file or the folder of a run ({path} is {what})")
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            return ds.load()
    except Exception as exc:  # noqa: BLE001 - netCDF4/HDF5 raise OSError, ValueError, ...
        raise InputError("results", given, f"a readable results NetCDF file ({type(exc).__name__}: "
                         f"{str(exc).strip()[:200]})") from None


def flutter_shape(ds: xr.Dataset) -> xr.DataArray:
    """The complex flutter mode shape (point, station, component)."""
    return ds["flutter_shape_real"] + 1j * ds["flutter_shape_imag"]
