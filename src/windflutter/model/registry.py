"""One entry point for every turbine input: the reader is chosen by file type.

=========  =====================================  ==========================================
reader     chosen for                             module
=========  =====================================  ==========================================
windio     ``.yaml`` / ``.yml`` (windIO v1, v2,   :mod:`windflutter.model.windio`
           windflutter seed files)
openfast   ``.fst`` (OpenFAST deck)               :mod:`windflutter.model.openfast`
hawc2      ``.htc`` (HAWC2 / HAWCStab2 model)     :mod:`windflutter.model.hawc2`
=========  =====================================  ==========================================

Other suffixes are recognised by the first kilobytes (``begin new_htc_structure`` -> HAWC2,
``EDFile``/``CompElast`` -> OpenFAST, else YAML).  Bundled names (``nrel5mw``, ``iea15mw_openfast``
...) resolve to files first.  :func:`register_reader` adds a reader in this process; an installed
package publishes one in the entry-point group :data:`ENTRY_POINT_GROUP` (``windflutter.readers``),
one line of its ``pyproject.toml``::

    [project.entry-points."windflutter.readers"]
    bladed = "mypackage.bladed:READER"     # a TurbineReader

Readers are tried in the order: registered in this process, entry points (by name), built-ins.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, replace
from importlib import metadata
from pathlib import Path

from windflutter.errors import InputError
from windflutter.model.bundled import resolve_turbine_path
from windflutter.model.plausibility import MAX_FILE_BYTES
from windflutter.model.turbine import Turbine


@dataclass(frozen=True)
class TurbineReader:
    """A turbine-file reader.

    name : short name (``"windio"``).
    suffixes : file suffixes it is chosen for (lower case, with the dot).
    loader : ``"module:function"``, the function taking ``(path: Path, validate: bool)`` and
        returning a :class:`Turbine` (imported when first used).
    sniff : text fragments (lower case) that identify the format in a file's first 4 kB.
    description : one line for messages and docs.
    """

    name: str
    suffixes: tuple[str, ...]
    loader: str
    sniff: tuple[str, ...] = ()
    description: str = ""

    def load(self, path: Path, validate: bool = True) -> Turbine:
        module, func = self.loader.split(":")
        return getattr(importlib.import_module(module), func)(path, validate)


_READERS: list[TurbineReader] = [
    TurbineReader("openfast", (".fst",), "windflutter.model.openfast:load_openfast", ("compelast", "edfile"),
                  "OpenFAST deck (.fst with ElastoDyn, BeamDyn/ElastoDyn blade, AeroDyn 15)"),
    TurbineReader("hawc2", (".htc",), "windflutter.model.hawc2:load_hawc2", ("new_htc_structure",),
                  "HAWC2 model (.htc with st, ae, pc files)"),
    TurbineReader("windio", (".yaml", ".yml"), "windflutter.model.windio:load_windio", (),
                  "windIO v1/v2 turbine (YAML)"),
]
_BUILTIN = tuple(_READERS)


ENTRY_POINT_GROUP = "windflutter.readers"


def register_reader(reader: TurbineReader) -> None:
    """Add (or replace, by name) a reader; it is tried before the built-in ones."""
    _READERS[:] = [reader] + [r for r in _READERS if r.name != reader.name]


def unregister_reader(name: str) -> None:
    """Forget a reader registered with :func:`register_reader` (the built-in of that name comes back)."""
    _READERS[:] = [r for r in _READERS if r.name != name]
    _READERS.extend(r for r in _BUILTIN if r.name == name)


def _entry_point_readers(taken: set[str]) -> list[TurbineReader]:
    """The readers published in :data:`ENTRY_POINT_GROUP` (by name; names already taken skipped)."""
    out = []
    for ep in sorted(metadata.entry_points(group=ENTRY_POINT_GROUP), key=lambda e: e.name):
        if ep.name in taken:
            continue
        try:
            obj = ep.load()
        except Exception as exc:  # noqa: BLE001 - a broken plug-in is the user's input
            raise InputError("turbine reader", ep.name, f"a loadable plug-in (entry point {ep.value!r}: "
                             f"{type(exc).__name__}: {exc})") from None
        if not isinstance(obj, TurbineReader):
            raise InputError("turbine reader", ep.name, f"a plug-in whose entry point {ep.value!r} is a "
                             "windflutter.model.TurbineReader")
        out.append(obj if obj.name == ep.name else replace(obj, name=ep.name))
    return out


def readers() -> tuple[TurbineReader, ...]:
    """The readers, in the order they are tried: registered here, entry points, built-ins."""
    own = [r for r in _READERS if r not in _BUILTIN]
    builtin = [r for r in _READERS if r in _BUILTIN]
    return tuple(own + _entry_point_readers({r.name for r in _READERS}) + builtin)


def reader_for(path: Path, fmt: str | None = None) -> TurbineReader:
    """The reader for ``path``: by ``fmt`` name if given, by suffix, else by content."""
    pool = readers()
    if fmt is not None:
        for r in pool:
            if r.name == fmt:
                return r
        raise InputError("format", fmt, "one of " + ", ".join(r.name for r in pool))
    suffix = path.suffix.lower()
    for r in pool:
        if suffix in r.suffixes:
            return r
    try:
        head = path.open("rb").read(4096).decode("utf-8", errors="replace").lower()
    except OSError as exc:
        raise InputError("turbine file", str(path), f"a readable file ({exc.strerror})") from None
    for r in pool:
        if r.sniff and any(tok in head for tok in r.sniff):
            return r
    return next(r for r in pool if r.name == "windio")


def load_turbine(path_or_name: str | Path, validate: bool = True, fmt: str | None = None) -> Turbine:
    """Read a turbine: a windIO v1/v2 file, an OpenFAST deck, a HAWC2 model, a seed file, or a
    bundled name (see :func:`windflutter.model.bundled.bundled_turbines`).

    Parameters
    ----------
    path_or_name : a file path or a bundled name, e.g. ``"nrel5mw"``, ``"nrel5mw_openfast"``.
    validate : run schema validation where the format has one (windIO v2).
    fmt : force a reader by name (``"windio"``, ``"openfast"``, ``"hawc2"``).

    Raises
    ------
    InputError
        Missing or unreadable file, syntax or schema error, implausible data; the message names
        the file, the field and, for tables, the station.
    """
    path = resolve_turbine_path(path_or_name)
    if path.is_dir():
        raise InputError("turbine", str(path), "a turbine file, not a folder")
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise InputError("turbine file", f"{size} bytes", f"a file under {MAX_FILE_BYTES // 2**20} MiB", str(path))
    return reader_for(path, fmt).load(path, validate)

