"""Errors that reach the user.

Every problem with user input is raised as :class:`InputError`, which names the field, the
value received and what was expected.  The CLI prints it as one line and exits non-zero;
library users can catch it (it is a ``ValueError``).
"""

from __future__ import annotations

from typing import Any


class WindflutterError(Exception):
    """Base class of windflutter's own errors."""


class InputError(WindflutterError, ValueError):
    """Bad user input: a config, turbine file or argument.

    Parameters
    ----------
    field
        Dotted path of the offending field, e.g. ``"blade.chord[3]"``.
    value
        The value received (shown with ``repr``; long values are shortened).
    expected
        What was expected, in words, e.g. ``"a positive number (kg/m)"``.
    source
        Optional file name the field came from.
    """

    def __init__(self, field: str, value: Any, expected: str, source: str | None = None):
        self.field = field
        self.value = value
        self.expected = expected
        self.source = source
        shown = _shown(value)
        where = f"{source}: " if source else ""
        super().__init__(f"{where}{field} = {shown}: expected {expected}")

    def __reduce__(self):
        # rebuilt from its fields (the default rebuilds from the message alone, which __init__ refuses):
        # an error raised in a worker process reaches the parent as itself
        return type(self), (self.field, self.value, self.expected, self.source)


def _shown(value: Any) -> str:
    """``repr(value)`` shortened to 80 characters; never fails (a 5000-digit integer has no
    ``repr`` in Python >= 3.11, a broken object may raise)."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 256:
        return f"<an integer of about {int(value.bit_length() * 0.30103) + 1} digits>"
    try:
        shown = repr(value)
    except Exception:  # noqa: BLE001 - the message must not fail
        shown = f"<{type(value).__name__}>"
    return shown if len(shown) <= 80 else shown[:77] + "..."


class InputWarning(UserWarning):
    """Input data that windflutter corrected or interpreted; the message names the field, what
    was found and what was done."""


class ValidityWarning(UserWarning):
    """A model used outside its range of validity (e.g. momentum theory in the propeller-brake
    state); the message says where and what the result then depends on.  ``rotor_speed_rpm``: the
    rotor speed at which it was found (RPM), when there is one; ``wind_speed`` (m/s) and ``kind``
    (the message without the wind speed): a command prints one line per kind listing the wind
    speeds (:func:`windflutter.cli.warn.one_line_warnings`)."""

    def __init__(self, message: str, rotor_speed_rpm: float | None = None, wind_speed: float | None = None,
                 kind: str | None = None):
        super().__init__(message)
        self.rotor_speed_rpm = rotor_speed_rpm
        self.wind_speed = wind_speed
        self.kind = kind


def one_line(text: object) -> str:
    """``text`` with every run of whitespace (newlines included) folded to one space: a message
    printed as one line at the command line."""
    return " ".join(str(text).split())


def check_choice(field: str, value: Any, choices, source: str | None = None) -> Any:
    """Return ``value`` if it is one of ``choices``, else raise :class:`InputError` naming the
    field, the value and the allowed choices.

    Parameters
    ----------
    field
        Dotted path of the field, e.g. ``"mesh.model"``.
    value
        The value received.
    choices
        The allowed values (any iterable; shown in its order).
    source
        Optional file name the field came from.
    """
    allowed = tuple(choices)
    try:
        ok = value in allowed
    except TypeError:  # e.g. an unhashable or incomparable value
        ok = False
    if not ok:
        raise InputError(field, value, "one of " + ", ".join(repr(c) for c in allowed), source)
    return value


class ModelError(WindflutterError):
    """A model that cannot be analysed, e.g. unconstrained rigid-body motion."""


class ConvergenceError(WindflutterError):
    """An iteration (p-k, root finding, eigen-solve) did not converge."""
