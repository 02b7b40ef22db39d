"""Unit factors of the turbine readers: kept importable here; they live in :mod:`windflutter.units`.

Multiply a value in the file's unit by the factor to get SI: ``twist_rad = twist_deg * DEG``.
"""

from __future__ import annotations

from windflutter.units import DEG, PERCENT, RPM

__all__ = ["DEG", "PERCENT", "RPM"]
