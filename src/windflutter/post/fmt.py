"""Numbers and labels as a reader wants them: rounded, with units, booleans as yes/no, and mode
labels in the field's terms.

The operating-point analysis names modes in the field's vocabulary ("1st edge BW", "1st tower
fore-aft", :func:`windflutter.system.modes.mode_name`).  The rotor-speed sweep of the overspeed
stability search labels a mode by its dominant strip motion, its blade and where it peaks
(``"flap-edge b3 r/R=1.00"``), and a flutter mode as ``"<structural mode> -> <shape at onset>"``;
:func:`field_label` and :func:`flutter_label` put those in words ("flap-edge, blade 3").  Labels
already in the field's vocabulary pass unchanged.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

DASH = "—"
_LEGACY = re.compile(r"^(?P<kind>[a-z]+(?:-[a-z]+)?) b(?P<blade>\d+) r/R=(?P<r>[0-9.]+)$")


def _as_number(x: Any, spec: str) -> str:
    """``x`` formatted with ``spec``; NaN/None: a dash; not a number: its text."""
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    return DASH if not math.isfinite(v) else format(v, spec)


def num(x: Any, digits: int = 2) -> str:
    """``x`` with ``digits`` decimals; NaN/None: a dash; not a number: the text."""
    return _as_number(x, f".{digits}f")


def qty(x: Any, unit: str, digits: int = 2) -> str:
    """``"12.10 RPM"``; a dash without unit when not finite."""
    s = num(x, digits)
    return s if s == DASH or not unit else f"{s} {unit}"


def sig(x: Any, n: int = 4) -> str:
    """``n`` significant digits, no trailing float noise (``12.100000000000001`` -> ``12.1``)."""
    return _as_number(x, f".{n}g")


def pct(fraction: Any, digits: int = 1, signed: bool = True) -> str:
    """A fraction as percent: ``0.174`` -> ``"+17.4 %"``."""
    try:
        v = 100.0 * float(fraction)
    except (TypeError, ValueError):
        return DASH
    if not math.isfinite(v):
        return DASH
    return f"{v:+.{digits}f} %" if signed else f"{v:.{digits}f} %"


def value(v: Any, unit: str = "") -> str:
    """Any attribute or config value: booleans yes/no, floats to 4 significant digits, sequences
    joined, with ``unit`` when given."""
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (float, np.floating)):
        s = sig(v)
    elif isinstance(v, (int, np.integer)):
        s = str(int(v))
    elif isinstance(v, (list, tuple, np.ndarray)):
        s = ", ".join(value(x) for x in np.asarray(v, dtype=object).ravel())
    elif v is None:
        return DASH
    else:
        s = str(v)
    return f"{s} {unit}" if unit and s != DASH else s


def field_label(label: Any) -> str:
    """A mode label in the field's terms (see the module docstring); unknown forms unchanged."""
    s = str(label or "").strip()
    if " -> " in s:
        return flutter_label(s)[0]
    m = _LEGACY.match(s)
    if not m:
        return s
    r = float(m["r"])
    where = "" if r >= 0.75 else f", peak at r/R {r:.2f}"  # an inboard peak is worth saying
    return f"{m['kind']}, blade {m['blade']}{where}"


def flutter_label(label: Any) -> tuple[str, str, str]:
    """``(shape at onset, structural mode it grew from, note)`` of a flutter-mode label; the
    parts absent are empty.  ``"flap-edge b3 r/R=1.00 -> flap b2 r/R=1.00 (above divergence)"``
    gives ``("flap, blade 2", "flap-edge, blade 3", "above divergence")``."""
    s = str(label or "").strip()
    note = ""
    m = re.search(r"\s*\(([^()]*)\)$", s)
    if m and m.group(1) == "above divergence":
        note, s = m.group(1), s[:m.start()]
    start, _, onset = s.partition(" -> ")
    if not onset:
        return field_label(start), "", note
    return field_label(onset), field_label(start), note
