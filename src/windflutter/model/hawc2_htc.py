"""A parser for HAWC2 ``.htc`` files: nested ``begin NAME; ... end NAME;`` blocks of ``key
values;`` commands.

Text after a command's ``;`` is a comment, as are lines starting with ``;``.  ``continue_in_file
PATH;`` includes another file (relative to the folder of the main file, as HAWC2 resolves it), and
``exit;`` ends the included file.  Nesting, includes and file sizes are bounded before any work.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from windflutter.errors import InputError
from windflutter.model.fastfile import read_text

MAX_DEPTH = 32  #: nested begin/end blocks
MAX_INCLUDES = 64  #: continue_in_file includes per model
MAX_COMMANDS = 200_000


@dataclass
class Block:
    """One ``begin NAME ... end NAME`` block: its commands (key, values, line) in order and its
    sub-blocks."""

    name: str
    title: str = ""
    commands: list[tuple[str, list[str], str]] = field(default_factory=list)
    blocks: list["Block"] = field(default_factory=list)

    def children(self, name: str) -> list["Block"]:
        return [b for b in self.blocks if b.name == name]

    def child(self, name: str, where: str, source: str | None) -> "Block":
        found = self.children(name)
        if not found:
            raise InputError(f"{where}.{name}", "<missing>", f"a 'begin {name};' block", source)
        return found[0]

    def all(self, key: str) -> list[tuple[list[str], str]]:
        """Every command ``key`` in this block: (values, 'file:line')."""
        return [(v, at) for k, v, at in self.commands if k == key]

    def values(self, key: str, where: str, source: str | None, default=None) -> list[str] | None:
        found = self.all(key)
        if not found:
            if default is not None:
                return default
            raise InputError(f"{where}.{key}", "<missing>", f"a '{key} ...;' command", source)
        return found[0][0]

    def numbers(self, key: str, n: int, where: str, source: str | None, default=None) -> list[float]:
        vals = self.values(key, where, source, default=None if default is None else [str(x) for x in default])
        try:
            out = [float(x) for x in vals[:n]]
        except ValueError:
            raise InputError(f"{where}.{key}", " ".join(vals), f"{n} numbers", source) from None
        if len(out) < n:
            raise InputError(f"{where}.{key}", " ".join(vals), f"{n} numbers", source)
        return out


def model_folder(path: str | Path) -> Path:
    """The folder HAWC2 resolves relative file names against: the htc's folder, or its parent when
    the htc lives in a folder named ``htc`` (HAWC2 runs from the model root: ``./data/...``)."""
    p = Path(path)
    return p.parent.parent if p.parent.name.lower() == "htc" else p.parent


def parse_htc(path: str | Path) -> Block:
    """The whole model (with its includes) as a root :class:`Block` named ``"htc"``.

    ``continue_in_file`` names are relative to :func:`model_folder`, like every other file name.
    """
    main = Path(path)
    root = Block("htc")
    stack = [root]
    state = {"includes": 0, "commands": 0}
    _parse_file(main, model_folder(main), stack, state)
    if len(stack) > 1:
        raise InputError(f"begin {stack[-1].name}", "<no end>", f"an 'end {stack[-1].name};'", str(main))
    return root


def _parse_file(path: Path, base: Path, stack: list[Block], state: dict) -> None:
    text = read_text(path, "HAWC2 htc file")
    for ln_no, raw in enumerate(text.splitlines(), 1):
        if ";" not in raw or raw.lstrip().startswith(";"):
            continue  # a comment line, or text without a command
        tok = raw.split(";", 1)[0].split()  # one command per line; after its ';' a comment
        if not tok:
            continue
        where = f"{path.name}:{ln_no}"
        state["commands"] += 1
        if state["commands"] > MAX_COMMANDS:
            raise InputError("htc commands", state["commands"], f"at most {MAX_COMMANDS}", str(path))
        key = tok[0].lower()
        if key == "exit":
            return
        if key == "begin":
            _begin(tok, stack, path, ln_no)
        elif key == "end":
            _end(tok, stack, path, ln_no)
        elif key == "continue_in_file":
            state["includes"] += 1
            if state["includes"] > MAX_INCLUDES or len(tok) < 2:
                raise InputError(f"continue_in_file ({where})", " ".join(tok[1:]),
                                 f"a file name (at most {MAX_INCLUDES} includes)", str(path))
            inc = Path(tok[1])
            _parse_file(inc if inc.is_absolute() else base / inc, base, stack, state)
        else:
            stack[-1].commands.append((key, tok[1:], where))


def _begin(tok: list[str], stack: list[Block], path: Path, ln_no: int) -> None:
    if len(tok) < 2:
        raise InputError(f"begin ({path.name}:{ln_no})", "", "a block name after 'begin'", str(path))
    if len(stack) > MAX_DEPTH:
        raise InputError(f"begin {tok[1]} ({path.name}:{ln_no})", len(stack), f"at most {MAX_DEPTH} nested blocks",
                         str(path))
    b = Block(tok[1].lower(), " ".join(tok[2:]))
    stack[-1].blocks.append(b)
    stack.append(b)


def _end(tok: list[str], stack: list[Block], path: Path, ln_no: int) -> None:
    name = tok[1].lower() if len(tok) > 1 else ""
    if len(stack) == 1 or (name and name != stack[-1].name):
        raise InputError(f"end {name} ({path.name}:{ln_no})", name or "end",
                         f"'end {stack[-1].name};'" if len(stack) > 1 else "a matching 'begin'", str(path))
    stack.pop()
