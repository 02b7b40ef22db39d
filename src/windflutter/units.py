"""Unit factors (bottom layer: imports only the standard library).

windflutter computes in SI units and radians; revolutions per minute, degrees, percent and hertz
appear only at the edges (files, config, command line, plots, stored results). Multiply a value
in the edge unit by the factor to get SI, divide to go back::

    omega = rpm * RPM            # rad/s
    rpm = omega / RPM
    twist = twist_deg * DEG      # rad
    f_hz = omega / HZ            # an angular frequency (rad/s) in Hz

The factors are the exact expressions the package used before they were collected here
(``math.pi / 30``, ``math.pi / 180``, ``2 pi``), so results are unchanged bit for bit where the
same product is formed.
"""

from __future__ import annotations

import math

__all__ = ["RPM", "DEG", "PERCENT", "HZ"]

RPM = math.pi / 30.0  #: revolutions per minute -> rad/s
DEG = math.pi / 180.0  #: degrees -> radians
PERCENT = 0.01  #: percent -> fraction
HZ = 2.0 * math.pi  #: hertz (cycles/s) -> rad/s

