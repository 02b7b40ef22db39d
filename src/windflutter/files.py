"""Files at the edge: reading input files and checking output paths, each problem one clear line.

Every command reads its input files (analysis configs, section and wing YAML, a run's
``analysis.yaml``) through :func:`read_text` / :func:`load_yaml`, and checks every output path
it knows up front (``-o OUTDIR``, ``--plot``, ``--vtk``, ``--bdf``) with
:func:`check_output_folder` / :func:`check_output_file` *before* any analysis runs.  A problem
is an :class:`~windflutter.errors.InputError` naming the flag or field, the path and what was
expected: a missing file, a folder where a file was expected, no read permission, bytes that
are not UTF-8, invalid YAML, a duplicate key, nesting deeper than :data:`MAX_YAML_DEPTH`, a file
larger than the caller's bound, an output folder that is a file or cannot be written, an output
file name with an extension the writer does not know.

The YAML loader (:class:`StrictLoader`) is PyYAML's safe loader (the C one where available) with
three more rules: numbers with an exponent but no decimal point (``1e-5``, ``2E6``) are floats as
in YAML 1.2 (YAML 1.1 reads them as strings); a key may appear only once in a mapping (YAML says
keys are unique; PyYAML keeps the last one silently); nesting is bounded.
"""

from __future__ import annotations

import os
import re
import tempfile
from pathlib import Path
from typing import Any

import yaml

from windflutter.errors import InputError

#: deepest nesting of YAML collections accepted (an analysis config needs 3)
MAX_YAML_DEPTH = 64
#: largest config-like YAML file read (bytes); turbine files have their own reader
MAX_CONFIG_BYTES = 10 * 1024 * 1024


class StrictLoader(getattr(yaml, "CSafeLoader", yaml.SafeLoader)):  # type: ignore[misc]
    """Safe loader: YAML-1.2 exponent floats, no duplicate keys, bounded nesting.

    The checks run on the composed node tree, before any Python object is constructed.
    """

    def get_single_data(self):  # noqa: D401 - PyYAML's hook
        node = self.get_single_node()
        if node is None:
            return None
        _check_nodes(node)
        return self.construct_document(node)


class StrictDumper(yaml.SafeDumper):
    """Safe dumper that quotes every string :class:`StrictLoader` would read as something else
    (``"1e5"``, a fingerprint like ``"0123e45678901234"``), so what it writes reads back equal."""


# added after PyYAML's own resolvers: only scalars that they leave as strings are affected
_EXPONENT_FLOAT = re.compile(r"^[-+]?(?:[0-9][0-9_]*)?(?:\.[0-9_]*)?[eE][-+]?[0-9]+$")
for _cls in (StrictLoader, StrictDumper):
    _cls.add_implicit_resolver("tag:yaml.org,2002:float", _EXPONENT_FLOAT, list("-+0123456789."))


def dump_yaml(data: Any) -> str:
    """YAML text of plain data (keys in their order) that :func:`parse_yaml` reads back equal."""
    return yaml.dump(data, Dumper=StrictDumper, sort_keys=False, allow_unicode=True)


def _check_nodes(root: yaml.Node) -> None:
    """Depth and duplicate keys of a composed YAML document (iterative: no recursion)."""
    stack: list[tuple[yaml.Node, int]] = [(root, 1)]
    seen: set[int] = set()
    while stack:
        node, depth = stack.pop()
        if id(node) in seen:  # an alias: already checked
            continue
        seen.add(id(node))
        if depth > MAX_YAML_DEPTH and not isinstance(node, yaml.ScalarNode):
            raise yaml.constructor.ConstructorError(
                None, None, f"nesting deeper than {MAX_YAML_DEPTH} levels", node.start_mark)
        if isinstance(node, yaml.MappingNode):
            keys: dict[tuple[str, str], int] = {}
            for k, v in node.value:
                if isinstance(k, yaml.ScalarNode) and k.tag != "tag:yaml.org,2002:merge":
                    if (k.tag, k.value) in keys:
                        raise yaml.constructor.ConstructorError(
                            None, None, f"duplicate key {k.value!r} (first at line "
                            f"{keys[(k.tag, k.value)]})", k.start_mark)
                    keys[(k.tag, k.value)] = k.start_mark.line + 1
                stack.append((k, depth + 1))
                stack.append((v, depth + 1))
        elif isinstance(node, yaml.SequenceNode):
            stack.extend((v, depth + 1) for v in node.value)


def _yaml_problem(exc: yaml.YAMLError) -> str:
    mark = getattr(exc, "problem_mark", None)
    where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark is not None else ""
    problem = getattr(exc, "problem", None) or (str(exc).strip().splitlines() or [type(exc).__name__])[0]
    return f"{problem}{where}"


def read_text(path: str | Path, field: str, max_bytes: int = MAX_CONFIG_BYTES,
              what: str = "file") -> str:
    """The UTF-8 text of an input file; :class:`InputError` (``field`` = the path) otherwise."""
    p = Path(path)
    shown = str(path)
    if str(path) == "":
        raise InputError(field, shown, f"the path of an existing {what}")
    try:
        st = p.stat()
    except FileNotFoundError:
        raise InputError(field, shown, f"an existing {what} (no such file)") from None
    except OSError as exc:
        raise InputError(field, shown, f"a readable {what} ({exc.strerror or exc})") from None
    if p.is_dir():
        raise InputError(field, shown, f"a {what}, not a folder")
    if not p.is_file():
        raise InputError(field, shown, f"a regular {what} (this is a device, pipe or socket)")
    if st.st_size > max_bytes:
        raise InputError(field, shown, f"a {what} of at most {max_bytes // (1024 * 1024)} MB "
                         f"(it has {st.st_size / 1024 ** 2:.0f} MB)")
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise InputError(field, shown, f"a readable {what} ({exc.strerror or exc})") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise InputError(field, shown, f"a UTF-8 text {what} (byte 0x{data[exc.start]:02x} at line "
                         f"{line} is not UTF-8)") from None


def parse_yaml(text: str, field: str, shown: str) -> Any:
    """Parse YAML text with :class:`StrictLoader`; ``shown`` names the file in messages."""
    try:
        return yaml.load(text, Loader=StrictLoader)  # noqa: S506 - a safe loader
    except yaml.YAMLError as exc:
        raise InputError(field, shown, f"valid YAML ({_yaml_problem(exc)})") from None
    except RecursionError:  # the pure-Python composer on a pathological document
        raise InputError(field, shown, f"valid YAML (nesting deeper than {MAX_YAML_DEPTH} levels)") from None


def load_yaml(path: str | Path, field: str, max_bytes: int = MAX_CONFIG_BYTES,
              what: str = "YAML file") -> Any:
    """Read and parse a YAML input file (see the module doc for what is refused)."""
    return parse_yaml(read_text(path, field, max_bytes, what), field, str(path))


# --------------------------------------------------------------------------------------------
# output paths
# --------------------------------------------------------------------------------------------
def _writable_dir(d: Path) -> str | None:
    """``None`` if a file can be created in the existing folder ``d``, else why not.

    A real probe (create and remove a temporary file): ``os.access`` says yes to root even on a
    read-only mount.
    """
    try:
        fd, tmp = tempfile.mkstemp(prefix=".windflutter-probe-", dir=d)
    except OSError as exc:
        return exc.strerror or str(exc)
    os.close(fd)
    os.unlink(tmp)
    return None


def _nearest_existing(p: Path) -> Path:
    q = p.absolute()
    while not q.exists() and q != q.parent:
        q = q.parent
    return q


def check_output_folder(path: str | Path, field: str) -> Path:
    """A folder the run can write into (it may not exist yet: then it can be created).

    Refused: an empty path, an existing file or device (``/dev/null``), a path through a file, a
    folder (or the nearest existing parent) that cannot be written.  Nothing is created.
    """
    shown = str(path)
    if shown.strip() == "":
        raise InputError(field, shown, "a folder path")
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise InputError(field, shown, "a folder (this is an existing file or device)")
    base = _nearest_existing(p)
    if not base.is_dir():
        raise InputError(field, shown, f"a path that can be a folder ({base} is a file)")
    why = _writable_dir(base)
    if why is not None:
        where = "folder" if base == p.absolute() else f"parent folder {base}"
        raise InputError(field, shown, f"a writable folder (the {where} cannot be written: {why})")
    return p


def check_output_file(path: str | Path, field: str, extensions: tuple[str, ...]) -> Path:
    """An output file name with one of ``extensions`` (lower-case, with the dot) that can be
    written: not an existing folder or device, in a folder that exists and is writable or can be
    created (the nearest existing parent is a writable folder).  Nothing is created; the writer
    creates missing folders (:func:`prepare_output_file`)."""
    shown = str(path)
    p = Path(path)
    if shown.strip() == "" or p.name in ("", ".", ".."):
        raise InputError(field, shown, "a file name")
    if p.suffix.lower() not in extensions:
        raise InputError(field, shown, "a file name ending in " + ", ".join(extensions))
    if p.is_dir():
        raise InputError(field, shown, "a file name (this is an existing folder)")
    if p.exists() and not p.is_file():
        raise InputError(field, shown, "a regular file name (this is a device, pipe or socket)")
    base = _nearest_existing(p.absolute().parent)
    if not base.is_dir():
        raise InputError(field, shown, f"a file in a folder ({base} is a file)")
    why = _writable_dir(base)
    if why is not None:
        raise InputError(field, shown, f"a file in a writable folder ({base} cannot be written: {why})")
    return p


def prepare_output_file(path: str | Path) -> Path:
    """Create the missing folders of an output file checked by :func:`check_output_file`."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    return p
