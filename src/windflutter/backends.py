"""Analysis back-ends of ``windflutter run`` (``solver.backend``): a registry, never an import path.

A back-end is a factory ``factory(turbine, config) -> analyse`` (see ``docs/workflow.md``).
``solver.backend`` names one:

* ``windflutter`` -- the built-in stability solver;
* a name registered in this process with :func:`register_backend`;
* a name published by an installed package in the entry-point group :data:`ENTRY_POINT_GROUP`
  (``windflutter.backends``), e.g. in that package's ``pyproject.toml``::

      [project.entry-points."windflutter.backends"]
      mysolver = "mypackage.analysis:factory"

Only these names are accepted.  An import path such as ``"os:system"`` is refused when the config
is read, so a config file cannot make the program import and call arbitrary code.
"""

from __future__ import annotations

import re
from importlib import metadata
from typing import Any, Callable

from windflutter.errors import InputError

BUILTIN = "windflutter"
ENTRY_POINT_GROUP = "windflutter.backends"
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_\-]{0,63}$")
_REGISTRY: dict[str, Callable[..., Any]] = {}


def register_backend(name: str, factory: Callable[..., Any]) -> None:
    """Make ``solver.backend: NAME`` use ``factory(turbine, config)`` in this process."""
    if not isinstance(name, str) or not _NAME.match(name) or name == BUILTIN:
        raise InputError("backend name", name, "a name of letters, digits, '_' or '-' (not 'windflutter')")
    if not callable(factory):
        raise InputError("backend factory", factory, "a callable factory(turbine, config)")
    _REGISTRY[name] = factory


def unregister_backend(name: str) -> None:
    """Forget a name registered with :func:`register_backend` (no error if unknown)."""
    _REGISTRY.pop(name, None)


def _entry_points() -> dict[str, metadata.EntryPoint]:
    return {ep.name: ep for ep in metadata.entry_points(group=ENTRY_POINT_GROUP)}


def backend_names() -> list[str]:
    """Every accepted ``solver.backend`` value, the built-in first."""
    return [BUILTIN] + sorted(set(_REGISTRY) | set(_entry_points()))


def _expected() -> str:
    others = backend_names()[1:]
    known = ", ".join(["windflutter"] + others)
    return (f"a back-end name: {known} (plug-ins register a name in the entry-point group "
            f"'{ENTRY_POINT_GROUP}'; import paths are not accepted)")


def check_backend_name(value: Any, name: str = "solver.backend", source: str | None = None) -> str:
    """``value`` if it names a known back-end, else :class:`InputError` (no import happens)."""
    if not isinstance(value, str) or not _NAME.match(value):
        raise InputError(name, value, _expected(), source)
    if value != BUILTIN and value not in _REGISTRY and value not in _entry_points():
        raise InputError(name, value, _expected(), source)
    return value


def backend_factory(value: str) -> Callable[..., Any]:
    """The factory of a plug-in back-end (not the built-in), loaded from the registry or its
    entry point."""
    check_backend_name(value)
    if value in _REGISTRY:
        return _REGISTRY[value]
    ep = _entry_points()[value]
    try:
        factory = ep.load()
    except Exception as exc:  # noqa: BLE001 - a broken plug-in is the user's input
        raise InputError("solver.backend", value, f"a loadable plug-in (entry point {ep.value!r}: "
                         f"{type(exc).__name__}: {exc})") from None
    if not callable(factory):
        raise InputError("solver.backend", value, f"a plug-in whose entry point {ep.value!r} is callable")
    return factory
