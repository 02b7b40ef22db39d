"""Warnings at the command line: one line each, ``windflutter COMMAND: warning: ...``.

Python's default shows a warning as two lines with the file and source line of the code that
raised it, which means nothing to the user of a command.  :func:`one_line_warnings` replaces that
for the duration of every command (the entry point, :func:`windflutter.cli.main`); the local
worker processes of ``run`` print theirs in one line too (:mod:`windflutter.parallel`).

A warning that carries a ``kind`` and a ``wind_speed`` (a
:class:`~windflutter.errors.ValidityWarning` such as the BEM's propeller-brake state) is not
printed at each wind speed: the command prints one line per kind at its end, listing the wind
speeds it applies to and, with the operating curve (:func:`operating_rotor_speed`), whether it
applies inside the operating range or only at overspeed.  The full text per wind speed stays in
the results (the point's notes, the report).
"""

from __future__ import annotations

import contextlib
import math
import re
import sys
import warnings
from typing import Callable

from windflutter.errors import one_line
from windflutter.units import RPM

#: the command's operating rotor speed (RPM) at a wind speed (m/s), set once it has read the
#: turbine (:func:`operating_rotor_speed`); None: the range is not stated
_OPERATING: list[Callable[[float], float] | None] = [None]
#: the running command's gathered warnings: kind -> {wind speed (m/s): lowest rotor speed (RPM)}
_GROUPED: list[dict[str, dict[float, float]] | None] = [None]
#: a point's note of a gathered warning (:func:`windflutter.analysers` keeps them in ``reason``)
_NOTE = re.compile(r"at V = ([0-9.]+) m/s (.+?) \[from ([0-9.]+|inf) RPM\]")


def gather(kind: str, wind_speed: float, rpm: float = math.inf) -> None:
    """Add a warning ``kind`` at ``wind_speed`` (m/s), found from ``rpm`` (RPM), to the running
    command's one line of that kind (nothing outside a command)."""
    grouped = _GROUPED[0]
    if grouped is None:
        return
    low = grouped.setdefault(one_line(kind), {})
    low[float(wind_speed)] = min(low.get(float(wind_speed), math.inf), float(rpm))


def gather_notes(reasons) -> None:
    """The gathered warnings recorded in the points' ``reason`` texts (``at V = 4.0 m/s KIND [from
    12.00 RPM]``): a run's worker processes do not print them, the command prints them once."""
    for text in reasons:
        for v, kind, rpm in _NOTE.findall(str(text)):
            gather(kind, float(v), float(rpm))


def is_gathered(message) -> bool:
    """A warning printed once per kind at the end of a command (it has a kind and a wind speed)."""
    return bool(getattr(message, "kind", None)) and getattr(message, "wind_speed", None) is not None


def operating_rotor_speed(rpm_at: Callable[[float], float] | None) -> None:
    """Tell the running command's warnings the operating rotor speed (RPM) at a wind speed (m/s),
    so that a range warning says whether it applies inside the operating range."""
    _OPERATING[0] = rpm_at


def curve_rpm(turbine) -> Callable[[float], float] | None:
    """The turbine's operating rotor speed (RPM) at a wind speed inside its operating curve (NaN
    outside it); None without a curve."""
    oc = getattr(turbine, "operating_curve", None)
    if oc is None:
        return None
    lo, hi = float(oc.wind_speed[0]), float(oc.wind_speed[-1])
    return lambda v: float(oc.rotor_speed_at(v)) / RPM if lo - 1e-9 <= v <= hi + 1e-9 else math.nan


def grouped_line(kind: str, lowest: dict[float, float], rpm_at: Callable[[float], float] | None = None) -> str:
    """One line for a warning ``kind`` found at the wind speeds of ``lowest`` (m/s -> lowest rotor
    speed found at, RPM, inf if unknown)."""
    plain, inside, over = [], [], []
    for v in sorted(lowest):
        rpm = lowest[v]
        op = rpm_at(v) if rpm_at is not None and math.isfinite(rpm) else math.nan
        item = f"{v:g} m/s" + (f" from {rpm:.1f} RPM" if math.isfinite(rpm) else "")
        if not math.isfinite(op):
            plain.append(item)
        else:
            (inside if rpm <= op * (1 + 1e-9) else over).append(f"{item} (operating {op:.1f} RPM)")
    where = [f"{label}V = {', '.join(items)}" for label, items in
             (("at ", plain), ("inside the operating range at ", inside), ("only at overspeed at ", over)) if items]
    return f"{kind} -- {'; '.join(where)}"


@contextlib.contextmanager
def one_line_warnings(prog: str, stream=None):
    """Within the block, every shown warning is printed as ``PROG: warning: MESSAGE`` (whitespace
    folded to one line) on ``stream`` (default stderr), each text once (a run's worker processes
    and its Campbell each build the model and would repeat its warnings); warnings of a kind at a
    wind speed are gathered and printed at the end, one line per kind (module docstring); the
    filters are unchanged."""
    shown: set[str] = set()
    grouped: dict[str, dict[float, float]] = {}

    def show(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001
        if is_gathered(message):
            rpm = getattr(message, "rotor_speed_rpm", None)
            gather(message.kind, message.wind_speed,
                   float(rpm) if rpm is not None and math.isfinite(rpm) else math.inf)
            return
        text = one_line(message)
        if text in shown:
            return
        shown.add(text)
        print(f"{prog}: warning: {text}", file=stream or file or sys.stderr)

    _OPERATING[0], _GROUPED[0] = None, grouped
    with warnings.catch_warnings():
        warnings.showwarning = show
        try:
            yield
        finally:
            for kind, lowest in grouped.items():
                print(f"{prog}: warning: {grouped_line(kind, lowest, _OPERATING[0])}", file=stream or sys.stderr)
            _OPERATING[0], _GROUPED[0] = None, None
