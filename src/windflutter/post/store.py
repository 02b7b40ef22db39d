"""Results on disk: one NetCDF file per finished operating point, combined into one dataset.

Layout of an output folder::

    OUTDIR/analysis.yaml        the resolved analysis config of the run
    OUTDIR/points/p0003.nc      one file per finished (or failed) operating point
    OUTDIR/results.nc           all finished points combined (rewritten after every point)
    OUTDIR/campbell.nc          the operating-point Campbell diagram, when the run has one
                                (:mod:`windflutter.post.campbell_data`; :func:`write_campbell`)

Every file is written to a temporary name in the same folder and moved into place with
:func:`os.replace`, which is atomic on POSIX and Windows: a kill at any moment leaves either the
old file or the new one, never a torn file.  ``--resume`` reads ``points/`` and skips what is
there; stray temporaries of a killed run are removed.

The combined dataset has one dimension ``point`` (the operating point, ordered by its index)
with coordinates ``wind_speed`` (m/s), ``aero`` and ``method``, and per-point sub-dimensions
``sweep`` (Campbell rotor speeds), ``mode`` (tracked modes), ``station`` (span stations),
``translation`` (flap, edge translations of the mode shape) and ``dof`` (plunge, pitch, edgewise
of the aero-work diagnostic; names in the auxiliary coordinates ``translation_name`` and
``dof_name``).  The files follow CF-1.8: one UDUNITS unit per variable (the flutter shape is
split into its translations, m, and its torsion, rad), ``long_name`` everywhere, 32-bit integer
indices, numeric coordinate variables.  NetCDF has no complex type: complex values are stored as
``*_real`` / ``*_imag`` pairs (mode shapes; the eigenvalues of the tracked modes, s-1).
In the combined dataset the ``mode`` dimension is the mode's identity across points: a point's
modes are placed by label (the k-th mode of a label at a point in the label's k-th slot), and
``mode_name`` names each slot.
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

from windflutter.errors import InputError
from windflutter.post.campbell_data import as_campbell_dataset

if TYPE_CHECKING:  # pragma: no cover
    from windflutter.results import OperatingPoint, PointResult

POINTS_DIR = "points"
RESULTS_FILE = "results.nc"
CAMPBELL_FILE = "campbell.nc"
COMPONENTS = ("flap", "edge", "torsion")
TRANSLATIONS = ("flap", "edge")
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
    "frequency": ("Hz", "undamped natural frequency |lambda|/(2 pi) of the tracked mode"),
    "damped_frequency": ("Hz", "damped frequency |Im lambda|/(2 pi) of the tracked mode"),
    "damping_ratio": ("1", "damping ratio zeta = -sigma/|lambda| of the tracked mode"),
    "mode_label": ("1", "label of the tracked mode"),
    "station_radius": ("m", "radius of the span station from the shaft axis"),
    "eigenvalue_real": ("s-1", "real part of the tracked mode's eigenvalue lambda"),
    "eigenvalue_imag": ("s-1", "imaginary part of the tracked mode's eigenvalue lambda (damped angular frequency, rad/s)"),
    "mode_name": ("1", "label of the mode slot (the same mode at every point)"),
    "flutter_translation_real": ("m", "flutter mode shape at onset: flap and edge translation, real part"),
    "flutter_translation_imag": ("m", "flutter mode shape at onset: flap and edge translation, imaginary part"),
    "flutter_torsion_real": ("rad", "flutter mode shape at onset: torsion, real part"),
    "flutter_torsion_imag": ("rad", "flutter mode shape at onset: torsion, imaginary part"),
    "point": ("1", "index of the operating point in the run's plan"),
    "aero": ("1", "aerodynamic model variant of the operating point"),
    "method": ("1", "stability search method of the operating point"),
    "sweep": ("1", "index of the rotor speed in the sweep"),
    "mode": ("1", "index of the tracked mode"),
    "station": ("1", "index of the span station"),
    "translation_name": ("1", "translation component of the mode shape"),
    "dof_name": ("1", "section degree of freedom of the aero-work diagnostic"),
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
        freq = np.asarray(result.damped_frequency_hz, float).reshape(nr, -1)
        zeta = np.asarray(result.damping_ratio, float).reshape(nr, -1)
    else:
        freq = zeta = np.zeros((0, 0))
    nm = freq.shape[1]
    labels = list(result.mode_labels or [])
    labels = (labels + [f"mode {i + 1}" for i in range(len(labels), nm)])[:nm]
    lam = _eigenvalues(result, freq, zeta)
    data["rotor_speed"] = (("point", "sweep"), rpm[None, :])
    data["frequency"] = (("point", "sweep", "mode"), (np.abs(lam) / (2 * np.pi))[None])
    data["damped_frequency"] = (("point", "sweep", "mode"), freq[None])
    data["damping_ratio"] = (("point", "sweep", "mode"), zeta[None])
    data["mode_label"] = (("point", "mode"), np.array(labels, dtype=object).reshape(1, nm))
    r = np.asarray(result.station_radius if result.station_radius is not None else [], float).ravel()
    ns = r.size
    shp = (np.asarray(result.flutter_shape, complex).reshape(ns, 3) if result.flutter_shape is not None and ns
           else np.full((ns, 3), nan + 0j))
    w = (np.asarray(result.aero_work, float).reshape(ns, 3) if result.aero_work is not None and ns
         else np.full((ns, 3), nan))
    data["eigenvalue_real"] = (("point", "sweep", "mode"), lam.real[None])
    data["eigenvalue_imag"] = (("point", "sweep", "mode"), lam.imag[None])
    data["station_radius"] = (("point", "station"), r[None])
    data["flutter_translation_real"] = (("point", "station", "translation"), shp.real[None, :, :2])
    data["flutter_translation_imag"] = (("point", "station", "translation"), shp.imag[None, :, :2])
    data["flutter_torsion_real"] = (("point", "station"), shp.real[None, :, 2])
    data["flutter_torsion_imag"] = (("point", "station"), shp.imag[None, :, 2])
    data["aero_work"] = (("point", "station", "dof"), w[None])
    data["aero_work_total"] = (("point",), [float(np.sum(w)) if ns and np.all(np.isfinite(w)) else nan])
    i32 = np.int32
    coords.update(sweep=("sweep", np.arange(nr, dtype=i32)), mode=("mode", np.arange(nm, dtype=i32)),
                  station=("station", np.arange(ns, dtype=i32)),
                  translation_name=("translation", list(TRANSLATIONS)), dof_name=("dof", list(WORK_DOFS)))
    coords["point"] = ("point", np.array([point.index], i32))
    ds = xr.Dataset(data, coords=coords)
    _set_attrs(ds)
    ds.attrs.update(Conventions="CF-1.8", title=f"windflutter operating point {point.index}",
                    history="created by windflutter run")
    for k, v in (result.info or {}).items():
        ds.attrs[f"info_{k}"] = _attr_value(v)
    ds.attrs.update({k: _attr_value(v) for k, v in (attrs or {}).items()})
    return ds


def _set_attrs(ds: xr.Dataset) -> None:
    """``units`` and ``long_name`` on every variable that has an entry in :data:`VARIABLES`."""
    for name in ds.variables:
        if name in VARIABLES:
            ds[name].attrs.update(_attrs(name))


def _eigenvalues(result, freq: np.ndarray, zeta: np.ndarray) -> np.ndarray:
    """The tracked modes' eigenvalues (1/s): the result's own (``eigenvalues``) when it has them,
    else from the damped frequency f and damping ratio zeta: ``Im = 2 pi f``,
    ``Re = -zeta Im / sqrt(1 - zeta^2)`` (NaN for zeta >= 1, where f carries no |lambda|)."""
    lam = getattr(result, "eigenvalues", None)
    if lam is not None and np.shape(lam) == freq.shape:
        return np.asarray(lam, complex)
    wd = 2 * np.pi * freq
    with np.errstate(invalid="ignore", divide="ignore"):
        re = np.where(np.abs(zeta) < 1, -zeta * wd / np.sqrt(1 - zeta**2), np.nan)
    return re + 1j * wd


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


def _atomic(path: str | Path, suffix: str, write) -> Path:
    """``write(fd, tmp)`` fills a temporary file beside ``path`` (synced to disk), which then
    replaces ``path`` in one step; on any error the temporary file is removed."""
    path = Path(path)
    fd, tmp = _temporary(path, suffix)
    try:
        write(fd, tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return path


def _atomic_write_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    def write(fd, tmp):
        os.close(fd)
        _strings_fixed(ds).to_netcdf(tmp, engine="netcdf4")
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())

    return _atomic(path, ".nc.tmp", write)


def atomic_write_text(text: str, path: str | Path) -> Path:
    """Write text atomically."""
    def write(fd, tmp):
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())

    return _atomic(path, ".tmp", write)


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
_POINT_VARS = ("flutter_rpm", "divergence_rpm", "status", "wind_speed", "aero", "method",
               "flutter_torsion_real",  # the CF layout: a point file of the earlier layout is computed again
               "damped_frequency")  # frequency undamped, damped_frequency damped: an older file is computed again


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
        items, names = _mode_slots(items)
        ds = xr.concat(items, dim="point", data_vars="all", coords="different",
                       compat="equals", join="outer", combine_attrs="drop")
        for name in ds.data_vars:
            if ds[name].dtype == object:
                ds[name] = ds[name].fillna("")
        for dim in ("point", "sweep", "mode", "station"):
            if dim in ds.coords:
                ds[dim] = ds[dim].astype(np.int32)
        ds["mode_name"] = (("mode",), np.array(names, dtype=object))
        _set_attrs(ds)
    ds.attrs.update({"Conventions": "CF-1.8", "history": "created by windflutter run"})
    ds.attrs.update({k: _attr_value(v) for k, v in (attrs or {}).items()})
    return ds


def _mode_slots(items: list[xr.Dataset]) -> tuple[list[xr.Dataset], list[str]]:
    """Each point's ``mode`` coordinate set to the slot of its label (the k-th mode of a label at
    a point -> the label's k-th slot, slots numbered in order of first appearance), so that the
    concatenation aligns the same mode across points; returns the points and the slot names."""
    slots: dict[tuple[str, int], int] = {}
    out = []
    for d in items:
        labels = [str(x) for x in d["mode_label"].values[0]] if "mode_label" in d and d.sizes.get("mode", 0) else []
        seen: dict[str, int] = {}
        idx = []
        for lab in labels:
            k = seen.get(lab, 0)
            seen[lab] = k + 1
            idx.append(slots.setdefault((lab, k), len(slots)))
        out.append(d.assign_coords(mode=("mode", np.asarray(idx, np.int32))) if labels else d)
    return out, [lab for lab, _ in slots]


def open_results(path: str | Path) -> xr.Dataset:
    """Open a ``results.nc`` (or an output folder) fully into memory.

    Raises
    ------
    InputError
        no such file, a folder where the file should be, or a file that is not readable NetCDF.
    """

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
    """The complex flutter mode shape (point, station, component): flap and edge (m), torsion
    (rad).  Reads the split variables and, for files of earlier versions, ``flutter_shape_*``."""
    if "flutter_shape_real" in ds:
        return ds["flutter_shape_real"] + 1j * ds["flutter_shape_imag"]
    tr = ds["flutter_translation_real"] + 1j * ds["flutter_translation_imag"]
    to = ds["flutter_torsion_real"] + 1j * ds["flutter_torsion_imag"]
    out = xr.concat([tr.isel(translation=0), tr.isel(translation=1), to], dim="component", coords="minimal",
                    compat="override")
    out = out.drop_vars([c for c in out.coords if c not in ("point", "station", "wind_speed")], errors="ignore")
    return out.assign_coords(component=list(COMPONENTS)).transpose("point", "station", "component")


def write_campbell(outdir: str | Path, campbell) -> Path:
    """Store the operating-point Campbell diagram (a result or its dataset) as
    ``OUTDIR/campbell.nc`` (atomic; CF-1.8, dimensions wind_speed x track)."""

    return atomic_write_netcdf(as_campbell_dataset(campbell), Path(outdir) / CAMPBELL_FILE)


def open_campbell(path: str | Path) -> xr.Dataset:
    """Open a ``campbell.nc`` (or the folder of a run) fully into memory.

    Raises
    ------
    InputError
        no such file, or not a readable Campbell dataset.
    """

    given, path = str(path), Path(path)
    if path.is_dir():
        path = path / CAMPBELL_FILE
    if not path.is_file():
        raise InputError("campbell", given, f"a campbell.nc file or the folder of a run ({path} is missing)")
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            ds = ds.load()
    except Exception as exc:  # noqa: BLE001 - netCDF4/HDF5 raise OSError, ValueError, ...
        raise InputError("campbell", given, f"a readable NetCDF file ({type(exc).__name__})") from None
    return as_campbell_dataset(ds)
