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
...) resolve to files first.  :func:`register_reader` adds a reader (e.g. from a plug-in).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from pathlib import Path

from windflutter.errors import InputError
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


def register_reader(reader: TurbineReader) -> None:
    """Add (or replace, by name) a reader; it is tried before the built-in ones."""
    _READERS[:] = [reader] + [r for r in _READERS if r.name != reader.name]


def readers() -> tuple[TurbineReader, ...]:
    """The registered readers, in the order they are tried."""
    return tuple(_READERS)


def reader_for(path: Path, fmt: str | None = None) -> TurbineReader:
    """The reader for ``path``: by ``fmt`` name if given, by suffix, else by content."""
    if fmt is not None:
        for r in _READERS:
            if r.name == fmt:
                return r
        raise InputError("format", fmt, "one of " + ", ".join(r.name for r in _READERS))
    suffix = path.suffix.lower()
    for r in _READERS:
        if suffix in r.suffixes:
            return r
    try:
        head = path.open("rb").read(4096).decode("utf-8", errors="replace").lower()
    except OSError as exc:
        raise InputError("turbine file", str(path), f"a readable file ({exc.strerror})") from None
    for r in _READERS:
        if r.sniff and any(tok in head for tok in r.sniff):
            return r
    return next(r for r in _READERS if r.name == "windio")


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
    from windflutter.model.bundled import resolve_turbine_path

    path = resolve_turbine_path(path_or_name)
    if path.is_dir():
        raise InputError("turbine", str(path), "a turbine file, not a folder")
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise InputError("turbine file", f"{size} bytes", f"a file under {MAX_FILE_BYTES // 2**20} MiB", str(path))
    return reader_for(path, fmt).load(path, validate)

