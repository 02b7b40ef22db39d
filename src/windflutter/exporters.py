"""Campbell exporters: one registry of output formats, a name each, never an import path.

An exporter writes an operating-point Campbell diagram (a
:class:`~windflutter.system.campbell.CampbellResult`; most formats also take its dataset,
:func:`~windflutter.post.campbell_data.campbell_dataset`) to one file.  The same registry serves
``windflutter campbell --export FILE [--format NAME]`` (the old ``--csv``/``--cmb``/``--amp``/
``--plot`` flags are its aliases) and ``output.exports`` of a run's config (``OUTDIR/campbell.<suffix>``).

=========  =====================  ============================================================
name       suffixes               writes
=========  =====================  ============================================================
csv        ``.csv``               one row per wind speed and mode (the JSON's fields)
cmb        ``.cmb`` ``.txt``      HAWCStab2-style Campbell table (damped frequency, damping %)
amp        ``.amp`` ``.txt``      HAWCStab2-style mode amplitudes (needs the modes: a result)
figure     ``.png`` ``.pdf``      the Campbell figure
           ``.svg``
netcdf     ``.nc``                the CF-1.8 Campbell dataset (as a run's ``campbell.nc``)
=========  =====================  ============================================================

A writer is a callable ``write(campbell, path, *, field, dpi) -> Path``: ``field`` names the
option in its :class:`~windflutter.errors.InputError` messages, ``dpi`` is the raster resolution
(``output.dpi``) for the formats that draw.  A new format is one module with its writer plus one
line: :func:`register_exporter` in this process, or from another package one line of its
``pyproject.toml`` in the entry-point group :data:`ENTRY_POINT_GROUP`::

    [project.entry-points."windflutter.exporters"]
    myformat = "mypackage.export:EXPORTER"    # an Exporter, or a bare writer (then --format only)

Only registered names are accepted; the config is checked against them before any work starts.
"""

from __future__ import annotations

import importlib
import re
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path
from typing import Any, Callable

from windflutter.errors import InputError

ENTRY_POINT_GROUP = "windflutter.exporters"
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_\-]{0,63}$")


@dataclass(frozen=True)
class Exporter:
    """One output format.

    name : the format's name (``--format``, ``output.exports``).
    suffixes : file suffixes it writes (lower case, with the dot; the first is the run's file name
        ``OUTDIR/campbell<suffix>``); empty: chosen by name only.
    writer : ``"module:function"`` (imported when first used) or the writer itself.
    description : one line for help and messages.
    needs_modes : the writer needs the result's mode shapes (not a dataset read from a file).
    """

    name: str
    suffixes: tuple[str, ...]
    writer: str | Callable[..., Any]
    description: str = ""
    needs_modes: bool = False

    def load(self) -> Callable[..., Any]:
        if callable(self.writer):
            return self.writer
        module, func = str(self.writer).split(":")
        return getattr(importlib.import_module(module), func)

    def write(self, campbell: Any, path: str | Path, field: str = "--export", dpi: int = 110) -> Path:
        """Write ``campbell`` to ``path`` in this format."""
        out = self.load()(campbell, Path(path), field=field, dpi=dpi)
        return Path(out) if out is not None else Path(path)


_BUILTIN: tuple[Exporter, ...] = (
    Exporter("csv", (".csv",), "windflutter.post.campbell_formats:export_csv",
             "one row per wind speed and mode (the fields of --json)"),
    Exporter("cmb", (".cmb", ".txt"), "windflutter.post.campbell_formats:export_cmb",
             "HAWCStab2-style .cmb Campbell table"),
    Exporter("amp", (".amp", ".txt"), "windflutter.post.campbell_formats:export_amp",
             "HAWCStab2-style .amp mode amplitudes (tower top, blade tip)", needs_modes=True),
    Exporter("figure", (".png", ".pdf", ".svg"), "windflutter.post.campbell_formats:export_figure",
             "the Campbell figure"),
    Exporter("netcdf", (".nc",), "windflutter.post.campbell_formats:export_netcdf",
             "the CF-1.8 Campbell dataset (as a run's campbell.nc)"),
)
_REGISTRY: dict[str, Exporter] = {}


def register_exporter(exporter: Exporter) -> None:
    """Add (or replace, by name) an exporter in this process; it is chosen before the built-ins."""
    if not isinstance(exporter, Exporter):
        raise InputError("exporter", type(exporter).__name__, "an windflutter.exporters.Exporter")
    if not _NAME.match(exporter.name):
        raise InputError("exporter name", exporter.name, "a name of letters, digits, '_' or '-'")
    _REGISTRY[exporter.name] = exporter


def unregister_exporter(name: str) -> None:
    """Forget a name registered with :func:`register_exporter` (no error if unknown)."""
    _REGISTRY.pop(name, None)


def _entry_points() -> dict[str, metadata.EntryPoint]:
    return {ep.name: ep for ep in metadata.entry_points(group=ENTRY_POINT_GROUP)}


def exporter_names() -> list[str]:
    """Every accepted format name: the built-ins in their order, then the plug-ins sorted."""
    builtin = [e.name for e in _BUILTIN]
    return builtin + sorted((set(_REGISTRY) | set(_entry_points())) - set(builtin))


def _expected() -> str:
    return (f"a registered export format: {', '.join(exporter_names())} (plug-ins register a name in the "
            f"entry-point group '{ENTRY_POINT_GROUP}')")


def check_export_format(value: Any, name: str = "--format", source: str | None = None) -> str:
    """``value`` if it names a registered format, else :class:`InputError` (nothing is imported)."""
    if not isinstance(value, str) or not _NAME.match(value) or value not in exporter_names():
        raise InputError(name, value, _expected(), source)
    return value


def _from_entry_point(ep: metadata.EntryPoint) -> Exporter:
    try:
        obj = ep.load()
    except Exception as exc:  # noqa: BLE001 - a broken plug-in is the user's input
        raise InputError("export format", ep.name, f"a loadable plug-in (entry point {ep.value!r}: "
                         f"{type(exc).__name__}: {exc})") from None
    if isinstance(obj, Exporter):
        return obj if obj.name == ep.name else Exporter(ep.name, obj.suffixes, obj.writer, obj.description,
                                                         obj.needs_modes)
    if callable(obj):
        return Exporter(ep.name, (), obj, f"plug-in {ep.value}")
    raise InputError("export format", ep.name, f"a plug-in whose entry point {ep.value!r} is an Exporter or a "
                     "callable writer")


def get_exporter(name: str, field: str = "--format") -> Exporter:
    """The exporter called ``name`` (registered, built-in or entry point, in this order)."""
    check_export_format(name, field)
    if name in _REGISTRY:
        return _REGISTRY[name]
    for e in _BUILTIN:
        if e.name == name:
            return e
    return _from_entry_point(_entry_points()[name])


def exporters() -> list[Exporter]:
    """Every exporter (plug-ins loaded), in :func:`exporter_names` order."""
    return [get_exporter(n) for n in exporter_names()]


def exporter_for(path: str | Path, fmt: str | None = None, field: str = "--export",
                 candidates: tuple[str, ...] | None = None) -> Exporter:
    """The exporter writing ``path``: ``fmt`` if given (the file must have one of its suffixes),
    else the one format among ``candidates`` (default: all) whose suffixes hold the file's.

    Raises
    ------
    InputError
        an unknown format, a suffix no format writes (``field``, naming the suffixes), or one that
        several write (then ``--format`` must choose).
    """
    suffix = Path(str(path)).suffix.lower()
    if fmt is not None:
        e = get_exporter(fmt)
        if e.suffixes and suffix not in e.suffixes:
            raise InputError(field, str(path), f"a {e.name} file name ending in {', '.join(e.suffixes)}")
        return e
    pool = [get_exporter(n) for n in (candidates or exporter_names())]
    found = [e for e in pool if suffix in e.suffixes]
    if len(found) == 1:
        return found[0]
    if not found:
        known = sorted({s for e in pool for s in e.suffixes})
        hint = "" if candidates else " (or --format NAME for a plug-in without suffixes)"
        raise InputError(field, str(path), f"a file name ending in {', '.join(known)}{hint}")
    raise InputError(field, str(path), f"a suffix of one format ({suffix} is written by "
                     f"{', '.join(e.name for e in found)}: choose with --format)")
