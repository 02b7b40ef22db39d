"""Thin-walled beam properties (6x6 stiffness and mass) from the blade layup, per beam element.

A thin use of the one layup -> 6x6 section calculator,
:func:`windflutter.model.section.layup_beam_sections` (classical lamination theory, wall midline
offset inwards from the outer mould line by half the laminate thickness, multi-cell Bredt-Batho
torsion; verified against analytic tubes and boxes and against the IEA 22 MW windIO 6x6 in
``tests/model/test_layup_section.py``).  This module only chooses where the sections are
evaluated: at the midpoints of the beam elements of a blade with ``n_span`` elements.

Used for the beam model when the turbine gives no 6x6 properties (e.g. the seed's UpWind layup).
Until 2026-11 this module had a second implementation on the shell mesh's outer-mould-line
geometry with single-cell torsion; against the IEA 22 MW file 6x6 (20-90 % span) it gave flap EI
+8..+16 % and GJ -8..-23 %, the kept calculator +-5 % (see ``docs/mesh.md``).
"""

from __future__ import annotations

import dataclasses

from windflutter.errors import InputError
from windflutter.mesh.blade_shell import station_positions
from windflutter.model.section import layup_beam_sections
from windflutter.model.turbine import BeamProperties


def thin_walled_properties(turbine, n_span: int = 40, n_contour: int = 240, clustering: float = 0.0) -> BeamProperties:
    """6x6 beam properties of the blade from its layup at the ``n_span`` element midpoints.

    Parameters
    ----------
    turbine : :class:`windflutter.model.turbine.Turbine` with a blade layup.
    n_span : number of blade elements (sections at their midpoints, span fraction).
    n_contour : points on the airfoil contour of each section.
    clustering : station clustering as :func:`windflutter.mesh.blade_shell.station_positions`.
    """
    if turbine.blade.layup is None:
        raise InputError("blade.layup", None, "a layup or 6x6 beam properties for the beam model")
    eta = station_positions(n_span, clustering)
    bp = layup_beam_sections(turbine, 0.5 * (eta[:-1] + eta[1:]), n_contour=n_contour)
    return dataclasses.replace(bp, source=f"thin-walled layup sections at {n_span} element midpoints (model/section.py)")
