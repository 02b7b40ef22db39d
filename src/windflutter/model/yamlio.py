"""YAML loading for turbine files: fast, YAML-1.2 numbers, parse errors as :class:`InputError`.

PyYAML follows YAML 1.1, whose float pattern requires a decimal point, so ``5e-05`` or ``2e6``
are returned as *strings*.  The loader below (a subclass of the C-accelerated safe loader when
available) replaces the float resolver with a YAML-1.2-style pattern, so such values are floats.
Quoted strings (``"5e-05"``) stay strings and are rejected later by the schema/type checks.

Refused with an :class:`InputError` (never a traceback or a silent choice): a duplicated key in
one mapping (YAML says keys are unique; PyYAML would keep the last), nesting deeper than
:data:`MAX_DEPTH`, files over :data:`~windflutter.model.plausibility.MAX_FILE_BYTES`, and bytes
that are not UTF-8.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import yaml

from windflutter.errors import InputError
from windflutter.model.plausibility import MAX_FILE_BYTES

_Base = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

_FLOAT_12 = re.compile(
    r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
    |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
    |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
    |[-+]?\.(?:inf|Inf|INF)
    |\.(?:nan|NaN|NAN))$""",
    re.X,
)


MAX_DEPTH = 64  #: nesting of mappings/sequences (windIO files need about 10)


class NumberSafeLoader(_Base):  # type: ignore[misc,valid-type]
    """Safe loader resolving ``1e-5``-style scalars as floats (YAML 1.2 behaviour) and refusing
    duplicate keys."""

    def construct_mapping(self, node, deep=False):
        seen: dict = {}
        for key_node, _ in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                continue
            key = self.construct_object(key_node, deep=True)
            try:
                first = seen.setdefault(key, key_node.start_mark)
            except TypeError:  # unhashable key: PyYAML reports it itself
                continue
            if first is not key_node.start_mark:
                raise _DuplicateKey(key, first, key_node.start_mark)
        return super().construct_mapping(node, deep=deep)


class _DuplicateKey(Exception):
    def __init__(self, key, first, again):
        super().__init__(key)
        self.key, self.first, self.again = key, first, again


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
        size = p.stat().st_size
        if p.is_dir():
            raise InputError("turbine file", str(p), "a YAML file, not a folder")
        if size > MAX_FILE_BYTES:
            raise InputError("turbine file", f"{size} bytes", f"a file under {MAX_FILE_BYTES // 2**20} MiB", str(p))
        raw = p.read_bytes()
    except FileNotFoundError:
        raise InputError("turbine file", str(p), "an existing YAML file or a bundled turbine name") from None
    except OSError as exc:
        raise InputError("turbine file", str(p), f"a readable file ({exc.strerror})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        raise InputError(f"byte {exc.start} (line {line})", raw[exc.start:exc.start + 4], "UTF-8 text", str(p)) from None
    return load_yaml_text(text, source=str(p))


def load_yaml_text(text: str, source: str | None = None) -> dict[str, Any]:
    """Parse YAML text (see :func:`load_yaml_file`)."""
    try:
        data = yaml.load(text, Loader=NumberSafeLoader)  # noqa: S506 - safe loader subclass
    except _DuplicateKey as exc:
        raise InputError(f"key {exc.key!r} at line {exc.again.line + 1}", exc.key,
                         f"unique keys in a mapping (first at line {exc.first.line + 1})", source) from None
    except RecursionError:
        raise InputError("YAML nesting", f"> {MAX_DEPTH}", f"at most {MAX_DEPTH} nested levels", source) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark is not None else "?"
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise InputError(f"YAML syntax at {where}", problem, "valid YAML", source=source) from None
    if not isinstance(data, dict):
        raise InputError("<top level>", type(data).__name__, "a YAML mapping (turbine description)", source)
    _check_depth(data, source)
    return data


def _check_depth(data, source: str | None) -> None:
    """Iterative depth check (no recursion on hostile input)."""
    stack = [(data, 1)]
    while stack:
        obj, d = stack.pop()
        if d > MAX_DEPTH:
            raise InputError("YAML nesting", f"> {MAX_DEPTH}", f"at most {MAX_DEPTH} nested levels", source)
        if isinstance(obj, dict):
            stack.extend((v, d + 1) for v in obj.values() if isinstance(v, (dict, list)))
        elif isinstance(obj, list):
            stack.extend((v, d + 1) for v in obj if isinstance(v, (dict, list)))
