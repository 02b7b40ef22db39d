"""Small typed accessors for nested dicts read from YAML: every failure is an :class:`InputError`
naming the dotted path in the file (``components.blade.outer_shape.chord.values[3]``)."""

from __future__ import annotations

from typing import Any

import numpy as np

from windflutter.errors import InputError

_MISSING = object()


class Reader:
    """Accessor bound to a source file name, for error messages."""

    def __init__(self, source: str | None):
        self.source = source

    # ----------------------------------------------------------------- primitive getters
    def get(self, d: Any, path: str, key: str, default: Any = _MISSING) -> Any:
        """``d[key]`` where ``d`` must be a mapping located at ``path``."""
        if not isinstance(d, dict):
            raise InputError(path, type(d).__name__, "a mapping", self.source)
        if key not in d:
            if default is _MISSING:
                raise InputError(_join(path, key), "<missing>", "a required key", self.source)
            return default
        return d[key]

    def number(
        self,
        d: Any,
        path: str,
        key: str,
        default: Any = _MISSING,
        positive: bool = False,
        nonneg: bool = False,
    ) -> float:
        v = self.get(d, path, key, default)
        return self.as_number(v, _join(path, key), positive=positive, nonneg=nonneg)

    def as_number(self, v: Any, path: str, positive: bool = False, nonneg: bool = False) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise InputError(path, v, "a number", self.source)
        x = float(v)
        if not np.isfinite(x):
            raise InputError(path, v, "a finite number", self.source)
        if positive and x <= 0:
            raise InputError(path, v, "a positive number", self.source)
        if nonneg and x < 0:
            raise InputError(path, v, "a non-negative number", self.source)
        return x

    def array(
        self,
        v: Any,
        path: str,
        min_len: int = 1,
        positive: bool = False,
        nonneg: bool = False,
        increasing: bool = False,
        unit_interval: bool = False,
        ndim: int = 1,
    ) -> np.ndarray:
        """A list of numbers (or list of lists for ``ndim=2``) as a float array."""
        if not isinstance(v, (list, tuple)):
            raise InputError(path, v, f"a list of numbers (at least {min_len})", self.source)
        if ndim == 1:
            for i, x in enumerate(v):
                if isinstance(x, bool) or not isinstance(x, (int, float)):
                    raise InputError(f"{path}[{i}]", x, "a number", self.source)
            a = np.asarray(v, dtype=float)
        else:
            rows = []
            for i, row in enumerate(v):
                rows.append(self.array(row, f"{path}[{i}]", min_len=1))
            if len({len(r) for r in rows}) > 1:
                raise InputError(path, "ragged rows", "rows of equal length", self.source)
            a = np.asarray(rows, dtype=float)
        if a.shape[0] < min_len:
            raise InputError(path, list(v), f"at least {min_len} values", self.source)
        bad = ~np.isfinite(a)
        if bad.any():
            i = int(np.argwhere(bad)[0][0])
            raise InputError(f"{path}[{i}]", v[i], "a finite number", self.source)
        if positive and (a <= 0).any():
            i = int(np.argwhere(a <= 0)[0][0])
            raise InputError(f"{path}[{i}]", v[i], "a positive number", self.source)
        if nonneg:
            # round-off negatives (e.g. -1.4e-20 m thicknesses in WISDEM output) are clipped to 0
            tol = 1e-12 * max(1.0, float(np.max(np.abs(a))))
            if (a < -tol).any():
                i = int(np.argwhere(a < -tol)[0][0])
                raise InputError(f"{path}[{i}]", v[i], "a non-negative number", self.source)
            a = np.maximum(a, 0.0)
        if unit_interval and ((a < -1e-9).any() or (a > 1 + 1e-9).any()):
            i = int(np.argwhere((a < -1e-9) | (a > 1 + 1e-9))[0][0])
            raise InputError(f"{path}[{i}]", v[i], "a value in [0, 1]", self.source)
        if increasing and a.shape[0] > 1 and (np.diff(a) < 0).any():
            i = int(np.argwhere(np.diff(a) < 0)[0][0]) + 1
            raise InputError(f"{path}[{i}]", v[i], "non-decreasing values", self.source)
        return a

    def grid_values(
        self,
        d: Any,
        path: str,
        key: str | None = None,
        positive: bool = False,
        nonneg: bool = False,
        default: Any = _MISSING,
        values_ndim: int = 1,
    ) -> tuple[np.ndarray, np.ndarray] | Any:
        """A windIO ``{grid: [...], values: [...]}`` pair: grid in [0, 1], non-decreasing, same
        length as values.  Repeated grid points (step changes) are nudged by 1e-9 so that the
        result can be interpolated."""
        if key is not None:
            d = self.get(d, path, key, default)
            if d is default and default is not _MISSING:
                return default
            path = _join(path, key)
        g = self.array(self.get(d, path, "grid"), _join(path, "grid"), min_len=2, increasing=True, unit_interval=True)
        v = self.array(
            self.get(d, path, "values"), _join(path, "values"), min_len=2, positive=positive, nonneg=nonneg,
            ndim=values_ndim,
        )
        if v.shape[0] != g.shape[0]:
            raise InputError(_join(path, "values"), f"{v.shape[0]} values", f"{g.shape[0]} values (one per grid point)",
                             self.source)
        return _strictly_increasing(g), v

    def string(self, d: Any, path: str, key: str, default: Any = _MISSING) -> str:
        v = self.get(d, path, key, default)
        if not isinstance(v, str):
            raise InputError(_join(path, key), v, "a string", self.source)
        return v

    def _typed(self, d: Any, path: str, key: str, default: Any, kind: type, what: str) -> Any:
        """``d[key]`` if it is a ``kind`` (else InputError "``what``"); the default as given."""
        v = self.get(d, path, key, default)
        if v is default and default is not _MISSING:
            return v
        if not isinstance(v, kind):
            raise InputError(_join(path, key), v, what, self.source)
        return v

    def mapping(self, d: Any, path: str, key: str, default: Any = _MISSING) -> dict:
        return self._typed(d, path, key, default, dict, "a mapping")

    def seq(self, d: Any, path: str, key: str, default: Any = _MISSING) -> list:
        return self._typed(d, path, key, default, list, "a list")


def _join(path: str, key: str | int) -> str:
    if isinstance(key, int):
        return f"{path}[{key}]"
    return f"{path}.{key}" if path else str(key)


def _strictly_increasing(g: np.ndarray) -> np.ndarray:
    g = g.copy()
    for i in range(1, g.size):
        if g[i] <= g[i - 1]:
            g[i] = g[i - 1] + 1e-9
    return g


join = _join
