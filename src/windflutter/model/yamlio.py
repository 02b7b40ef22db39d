"""YAML loading for turbine files: fast, YAML-1.2 numbers, parse errors as :class:`InputError`.

PyYAML follows YAML 1.1, whose float pattern requires a decimal point, so ``5e-05`` or ``2e6``
are returned as *strings*.  The loader below (a subclass of the C-accelerated safe loader when
available) replaces the float resolver with a YAML-1.2-style pattern, so such values are floats.
Quoted strings (``"5e-05"``) stay strings and are rejected later by the schema/type checks.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import yaml

from windflutter.errors import InputError

_Base = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

_FLOAT_12 = re.compile(
    r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
    |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
    |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
    |[-+]?\.(?:inf|Inf|INF)
    |\.(?:nan|NaN|NAN))$""",
    re.X,
)


class NumberSafeLoader(_Base):  # type: ignore[misc,valid-type]
    """Safe loader resolving ``1e-5``-style scalars as floats (YAML 1.2 behaviour)."""


# copy the resolver table so the base class is not modified, then swap the float resolver
NumberSafeLoader.yaml_implicit_resolvers = {
    k: [(tag, rx) for tag, rx in v if tag != "tag:yaml.org,2002:float"]
    for k, v in _Base.yaml_implicit_resolvers.items()
}
NumberSafeLoader.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT_12, list("-+0123456789."))


def load_yaml_file(path: str | Path) -> dict[str, Any]:
    """Read a YAML file into plain Python objects.

    Raises
    ------
    InputError
        If the file is missing, unreadable or not valid YAML (with line/column), or if the top
        level is not a mapping.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError("turbine file", str(p), "an existing YAML file or a bundled turbine name") from None
    except OSError as exc:
        raise InputError("turbine file", str(p), f"a readable file ({exc.strerror})") from None
    return load_yaml_text(text, source=str(p))


def load_yaml_text(text: str, source: str | None = None) -> dict[str, Any]:
    """Parse YAML text (see :func:`load_yaml_file`)."""
    try:
        data = yaml.load(text, Loader=NumberSafeLoader)  # noqa: S506 - safe loader subclass
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark is not None else "?"
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise InputError(f"YAML syntax at {where}", problem, "valid YAML", source=source) from None
    if not isinstance(data, dict):
        raise InputError("<top level>", type(data).__name__, "a YAML mapping (turbine description)", source)
    return data
