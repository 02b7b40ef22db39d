"""The built-in writers of the exporter registry (:mod:`windflutter.exporters`): one adapter per
format giving each existing writer the registry's signature ``write(campbell, path, *, field, dpi)``.

The formats themselves live in :mod:`~windflutter.post.campbell_export` (CSV, ``.cmb``),
:mod:`~windflutter.post.campbell_amp` (``.amp``), :mod:`~windflutter.post.campbell_plots` (the
figure) and :mod:`~windflutter.post.store` (the CF NetCDF, a run's ``campbell.nc``).
"""

from __future__ import annotations

from pathlib import Path

from windflutter.errors import InputError
from windflutter.post.campbell_amp import write_amp
from windflutter.post.campbell_data import as_campbell_dataset
from windflutter.post.campbell_export import writable_path, write_cmb, write_csv
from windflutter.post.store import atomic_write_netcdf


def export_csv(campbell, path, *, field: str = "--export", dpi: int = 110) -> Path:
    return write_csv(campbell, path, field=field)


def export_cmb(campbell, path, *, field: str = "--export", dpi: int = 110) -> Path:
    return write_cmb(campbell, path, field=field)


def export_amp(campbell, path, *, field: str = "--export", dpi: int = 110) -> Path:
    return write_amp(campbell, path, field=field)


def export_figure(campbell, path, *, field: str = "--export", dpi: int = 110) -> Path:
    from windflutter.post.campbell_plots import save_campbell_plot  # noqa: PLC0415  (matplotlib is slow to import)

    return save_campbell_plot(campbell, path, dpi=dpi, field=field)


def export_netcdf(campbell, path, *, field: str = "--export", dpi: int = 110) -> Path:
    ds = as_campbell_dataset(campbell)
    p = writable_path(path, field)
    try:
        return atomic_write_netcdf(ds, p)
    except OSError as exc:
        raise InputError(field, str(path), f"a writable file ({exc.strerror})") from None
