"""Unit factors of the turbine readers (SI and radians inside; degrees and rpm only in files).

Multiply a value in the file's unit by the factor to get SI: ``twist_rad = twist_deg * DEG``.
"""

from __future__ import annotations

import math

DEG = math.pi / 180.0  #: degrees -> radians
RPM = math.pi / 30.0  #: revolutions per minute -> rad/s
PERCENT = 0.01  #: percent -> fraction
