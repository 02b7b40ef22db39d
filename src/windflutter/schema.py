"""Declared options: one :class:`Spec` per setting gives its kind, bounds, unit, choices and doc.

The analysis config (:mod:`windflutter.config`) declares every field once with a :class:`Spec`
in the dataclass field's metadata; the command-line flags of every command are checked by the
same specs (a flag that sets a config field uses that field's spec; a command-only flag declares
its own).  :meth:`Spec.check` turns a raw value (from YAML or a command line) into the typed value
or raises :class:`~windflutter.errors.InputError` naming the field, the value and the expected
range in words, e.g. ``rotor_speed.max_rpm = 1e9: expected a number in (0, 1000] (RPM)``.

Every number is checked finite and inside its bounds *before* anything is allocated from it, so
a size (points, elements, frames, ...) can never start an unbounded computation.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field, fields
from typing import Any, Callable

from windflutter.errors import InputError

KINDS = ("float", "int", "bool", "str", "choice", "choices", "custom")


def is_number(v: Any) -> bool:
    """A real number that is not a bool (YAML ``true`` is an int in Python)."""
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _fmt(x: float) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


@dataclass(frozen=True)
class Spec:
    """How one setting is checked.

    Parameters
    ----------
    kind : ``float``, ``int``, ``bool``, ``str``, ``choice`` (one of ``choices``), ``choices``
        (a non-empty list of distinct ``choices``; a single string is a list of one) or
        ``custom`` (``parse(value, name, source)`` does the work).
    lower, upper : bounds of a number (``None``: none on that side).
    lower_open, upper_open : exclude the bound itself (``(0, 2]`` is ``lower_open=True``).
    unit : shown in messages and docs (``"RPM"``, ``"m/s"``, ``"-"``).
    choices : allowed strings of ``choice`` / ``choices`` (compared lower-case).
    nullable : ``None`` (YAML ``null``) is allowed and kept.
    max_len : longest string / list.
    doc : one line for ``--help`` and the reference.
    parse : the checker of a ``custom`` setting.
    """

    kind: str
    lower: float | None = None
    upper: float | None = None
    lower_open: bool = False
    upper_open: bool = False
    unit: str = ""
    choices: tuple[str, ...] = ()
    nullable: bool = False
    max_len: int | None = None
    doc: str = ""
    parse: Callable[[Any, str, str | None], Any] | None = None

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"unknown Spec kind {self.kind!r}")

    # -- words ---------------------------------------------------------------------------
    def range_text(self) -> str:
        """``(0, 2]``, ``>= 1``, or ``""`` without bounds."""
        lo, hi = self.lower, self.upper
        if lo is not None and hi is not None:
            return f"{'(' if self.lower_open else '['}{_fmt(lo)}, {_fmt(hi)}{')' if self.upper_open else ']'}"
        if lo is not None:
            return f"{'>' if self.lower_open else '>='} {_fmt(lo)}"
        if hi is not None:
            return f"{'<' if self.upper_open else '<='} {_fmt(hi)}"
        return ""

    def expected(self) -> str:
        """What a good value looks like, in words."""
        u = f" ({self.unit})" if self.unit and self.unit != "-" else ""
        rng = self.range_text()
        if self.kind == "float":
            text = f"a finite number in {rng}{u}" if rng else f"a finite number{u}"
        elif self.kind == "int":
            text = f"an integer in {rng}" if rng else "an integer"
        elif self.kind == "bool":
            text = "true or false"
        elif self.kind == "str":
            text = "a string" + (f" of at most {self.max_len} characters" if self.max_len else "")
        elif self.kind == "choice":
            text = "one of " + ", ".join(self.choices)
        elif self.kind == "choices":
            text = "a non-empty list of " + ", ".join(self.choices)
        else:
            text = self.doc or "a valid value"
        return text + (", or null" if self.nullable else "")

    # -- checking ------------------------------------------------------------------------
    def check(self, value: Any, name: str, source: str | None = None) -> Any:
        """The checked, typed value; :class:`InputError` naming ``name`` otherwise."""
        if value is None and self.nullable:
            return None
        if self.kind == "custom":
            assert self.parse is not None
            return self.parse(value, name, source)
        return getattr(self, f"_check_{self.kind}")(value, name, source)

    def _in_bounds(self, x: float) -> bool:
        lo, hi = self.lower, self.upper
        if lo is not None and (x < lo or (self.lower_open and x == lo)):
            return False
        if hi is not None and (x > hi or (self.upper_open and x == hi)):
            return False
        return True

    def _check_float(self, v: Any, name: str, src: str | None) -> float:
        # ints are compared exactly (a 400-digit integer must not overflow float())
        ok = is_number(v) and (isinstance(v, numbers.Integral) or math.isfinite(v)) and self._in_bounds(v)
        if not ok:
            raise InputError(name, v, self.expected(), src)
        return float(v)

    def _check_int(self, v: Any, name: str, src: str | None) -> int:
        integral = isinstance(v, numbers.Integral) or (is_number(v) and math.isfinite(v) and float(v).is_integer())
        if not (is_number(v) and integral and self._in_bounds(v)):
            raise InputError(name, v, self.expected(), src)
        return int(v)

    def _check_bool(self, v: Any, name: str, src: str | None) -> bool:
        if not isinstance(v, bool):
            raise InputError(name, v, self.expected(), src)
        return v

    def _check_str(self, v: Any, name: str, src: str | None) -> str:
        if not isinstance(v, str) or (self.max_len is not None and len(v) > self.max_len):
            raise InputError(name, v, self.expected(), src)
        return v

    def _check_choice(self, v: Any, name: str, src: str | None) -> str:
        if not isinstance(v, str) or v.lower() not in self.choices:
            raise InputError(name, v, self.expected(), src)
        return v.lower()

    def _check_choices(self, v: Any, name: str, src: str | None) -> tuple[str, ...]:
        items = [v] if isinstance(v, str) else v
        if not isinstance(items, (list, tuple)) or not items or len(items) > max(len(self.choices), 1):
            raise InputError(name, v, self.expected() + " without repeats", src)
        one = Spec("choice", choices=self.choices)
        out = tuple(one.check(x, f"{name}[{i}]", src) for i, x in enumerate(items))
        if len(set(out)) != len(out):
            raise InputError(name, v, "a list without repeated entries", src)
        return out


def check_keys(prefix: str, data: dict, allowed, source: str | None,
               renamed: dict[str, str] | None = None) -> None:
    """Every key of ``data`` is one of ``allowed`` (a renamed key names its new place)."""
    for k in data:
        name = f"{prefix}{k}"
        if renamed and k in renamed:
            raise InputError(name, data[k], f"a current key ({renamed[k]})", source)
        if not isinstance(k, str) or k not in allowed:
            raise InputError(name, data[k], "a known key (unknown key; allowed: "
                             + ", ".join(sorted(allowed)) + ")", source)


# ------------------------------------------------------------------------------------------------
# settings declared as dataclass fields, each with its Spec
# ------------------------------------------------------------------------------------------------
def setting(default: Any, kind: str, doc: str, **spec: Any) -> Any:
    """A dataclass field declared with its default and :class:`Spec` (in the field's metadata)."""
    return field(default=default, metadata={"spec": Spec(kind, doc=doc, **spec)})


def section(cls: type) -> Any:
    """A nested section of settings (a dataclass of declared fields)."""
    return field(default_factory=cls, metadata={"section": cls})


def document_settings(cls: type) -> None:
    """Append a NumPy ``Attributes`` section, generated from the declared settings, to ``cls.__doc__``."""
    lines = ["", "", "Attributes", "----------"]
    for f in fields(cls):
        if "section" in f.metadata:
            lines.append(f"{f.name} : :class:`{f.metadata['section'].__name__}`")
            continue
        s: Spec = f.metadata["spec"]
        extra = ", ".join(x for x in (s.unit if s.unit not in ("", "-") else "", s.range_text()) if x)
        lines.append(f"{f.name} : {s.doc}" + (f" ({extra})" if extra else "") + f"; default {f.default!r}.")
    cls.__doc__ = (cls.__doc__ or "") + "\n    ".join(lines)
