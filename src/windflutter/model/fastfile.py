"""A reader for the OpenFAST input-file layout: one ``value  Key  - description`` per line.

Used by the ElastoDyn, BeamDyn, AeroDyn and AirfoilInfo readers.  Keys are matched without case
and without parentheses (``PreCone(1)`` = ``PreCone1``); values may be quoted strings, numbers,
``True``/``False`` or ``"DEFAULT"``.  Every failure is an :class:`InputError` naming the file and
the key; file sizes and table sizes are bounded before anything is allocated.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model.plausibility import MAX_FILE_BYTES, MAX_STATIONS

_LINE = re.compile(r"""^\s*("[^"]*"|'[^']*'|\S+)\s+(\S+)""")
_MISSING = object()


def read_text(path: Path, what: str) -> str:
    """The text of an input file: bounded size, UTF-8 (or plain ASCII/Latin-1 tables)."""
    p = Path(path)
    try:
        size = p.stat().st_size
    except FileNotFoundError:
        raise InputError(what, str(p), "an existing file") from None
    except OSError as exc:
        raise InputError(what, str(p), f"a readable file ({exc.strerror})") from None
    if not p.is_file():
        raise InputError(what, str(p), "a file (not a folder)")
    if size > MAX_FILE_BYTES:
        raise InputError(what, f"{size} bytes", f"a file under {MAX_FILE_BYTES // 2**20} MiB", str(p))
    raw = p.read_bytes()
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(what, f"byte {exc.start}: {raw[exc.start:exc.start + 1]!r}",
                         "a UTF-8 (or ASCII) text file", str(p)) from None


def _norm(key: str) -> str:
    return key.replace("(", "").replace(")", "").lower()


class FastFile:
    """One OpenFAST-format input file.

    Parameters
    ----------
    path : the file.
    what : what it is, for messages (e.g. ``"ElastoDyn main file"``).
    """

    def __init__(self, path: str | Path, what: str):
        self.path = Path(path)
        self.what = what
        self.lines = read_text(self.path, what).splitlines()
        self._index: dict[str, int] = {}
        for i, ln in enumerate(self.lines):
            if _comment(ln):
                continue
            m = _LINE.match(ln)
            if m:
                self._index.setdefault(_norm(m.group(2)), i)

    @property
    def source(self) -> str:
        return str(self.path)

    def error(self, key: str, value, expected: str):
        raise InputError(key, value, expected, self.source)

    # -------------------------------------------------------------------------------- scalars
    def has(self, key: str) -> bool:
        return _norm(key) in self._index

    def line_of(self, key: str) -> int:
        """Line index of ``key`` (InputError if absent)."""
        i = self._index.get(_norm(key))
        if i is None:
            self.error(key, "<missing>", f"a line 'value {key}' in this {self.what}")
        return i

    def raw(self, key: str, default=_MISSING) -> str:
        if default is not _MISSING and not self.has(key):
            return default
        return _LINE.match(self.lines[self.line_of(key)]).group(1)

    def string(self, key: str, default=_MISSING) -> str:
        v = self.raw(key, default)
        return v.strip("\"'") if isinstance(v, str) else v

    def number(self, key: str, default=_MISSING, positive: bool = False, nonneg: bool = False) -> float:
        v = self.raw(key, default)
        if not isinstance(v, str):
            return v
        if v.strip("\"'").lower() == "default" and default is not _MISSING:
            return default
        try:
            x = float(v.replace("D", "E").replace("d", "e"))
        except ValueError:
            self.error(key, v, "a number")
        if not np.isfinite(x):
            self.error(key, v, "a finite number")
        if positive and x <= 0:
            self.error(key, x, "a positive number")
        if nonneg and x < 0:
            self.error(key, x, "a non-negative number")
        return x

    def integer(self, key: str, default=_MISSING, lo: int = 0, hi: int = MAX_STATIONS) -> int:
        x = self.number(key, default)
        if x != int(x) or not lo <= x <= hi:
            self.error(key, x, f"a whole number between {lo} and {hi}")
        return int(x)

    def flag(self, key: str, default=_MISSING) -> bool:
        v = self.string(key, default)
        if isinstance(v, bool):
            return v
        if v.lower() in ("true", "t", "1"):
            return True
        if v.lower() in ("false", "f", "0"):
            return False
        self.error(key, v, "True or False")

    def file(self, key: str, required: bool = True) -> Path | None:
        """A file named by ``key``, relative to this file's folder (checked to exist when
        ``required``; ``None`` for 'unused' or a missing optional file)."""
        name = self.string(key, default=None) if not required else self.string(key)
        if name is None or name.lower() in ("unused", "none", ""):
            if required:
                self.error(key, name, "the name of an existing file")
            return None
        f = Path(name)
        f = f if f.is_absolute() else self.path.parent / f
        if not f.is_file():
            if required:
                self.error(key, str(f), "an existing file")
            return None
        return f

    # --------------------------------------------------------------------------------- tables
    def header(self, token: str, start: int = 0) -> int:
        """Index of the first line from ``start`` having ``token`` as a whole word (no case)."""
        t = token.lower()
        for i in range(start, len(self.lines)):
            if t in (w.lower() for w in self.lines[i].replace(",", " ").split()):
                return i
        self.error(f"table header '{token}'", "<missing>", f"a {self.what} with a '{token}' column header")

    def rows(self, start: int, n: int, n_col: int, field: str) -> np.ndarray:
        """``n`` rows of at least ``n_col`` numbers from line ``start`` on.  Blank and ``!``
        comment lines are skipped; text lines before the first row (column names, units) too;
        a text line after it ends the table."""
        if not 0 < n <= MAX_STATIONS:
            self.error(field, n, f"between 1 and {MAX_STATIONS} rows")
        out = []
        i = start
        while len(out) < n and i < len(self.lines):
            line = self.lines[i]
            i += 1
            s = line.strip()
            if not s or s.startswith("!"):
                continue
            nums = numbers(line)
            if nums is None:
                if not out:
                    continue
                break
            if len(nums) < n_col:
                self.error(f"{field} row {len(out) + 1}", s[:60], f"{n_col} numbers")
            if not np.all(np.isfinite(nums[:n_col])):  # NaN / inf would pass every later bound
                self.error(f"{field} row {len(out) + 1}", s[:60], f"{n_col} finite numbers")
            out.append(nums[:n_col])
        if len(out) != n:
            self.error(field, f"{len(out)} rows", f"{n} rows of {n_col} numbers")
        self.next_line = i
        return np.array(out, dtype=float)

    def lines_of(self, key: str, start: int = 0) -> list[int]:
        """Every line index from ``start`` whose key is ``key`` (repeated keys, e.g. one
        ``NumAlf`` per airfoil table)."""
        k = _norm(key)
        out = []
        for i in range(start, len(self.lines)):
            if not _comment(self.lines[i]):
                m = _LINE.match(self.lines[i])
                if m and _norm(m.group(2)) == k:
                    out.append(i)
        return out

    def number_at(self, i: int, key: str) -> float:
        """The number on line ``i`` (whose key is ``key``, for messages)."""
        v = self.value_at(i)
        try:
            x = float(v)
        except ValueError:
            self.error(f"{key} (line {i + 1})", v, "a number")
        if not np.isfinite(x):
            self.error(f"{key} (line {i + 1})", v, "a finite number")
        return x

    def value_at(self, i: int) -> str:
        """The value token of line ``i`` (unquoted)."""
        return _LINE.match(self.lines[i]).group(1).strip("\"'")


def _comment(line: str) -> bool:
    """Blank, ``!``/``#`` comment or ``----``/``====`` separator line."""
    s = line.lstrip()
    return not s or s[0] in "!#" or s.startswith("--") or s.startswith("==")


def numbers(line: str) -> list[float] | None:
    """The numbers of a line (commas allowed), or None if any token is not a number."""
    toks = line.replace(",", " ").split()
    if not toks:
        return None
    try:
        return [float(t) for t in toks]
    except ValueError:
        return None
