"""Aerodynamic strips, polars and rotor geometry: the contract between ``model/``, ``mesh/``,
``rotor/`` and ``aero/`` (bottom layer: imports only NumPy and SciPy).

A model built from a turbine (shell or beam) comes with an :class:`AeroSections`: one strip per
spanwise station of each blade, with its geometry at zero deflection (pitch and azimuth already
applied) and a sparse ``motion_map`` that gives each section's rigid motion from the structural
DOFs.  The aerodynamic matrices act on that section motion and are brought back to the structure
with the transpose (consistent virtual work), so the same code serves beam and shell models.
The turbine description (``model/``) keeps its airfoil :class:`Polar` data in the same type, and
:class:`RotorGeometry` says where the rotor is and how it turns (``mesh/``, ``rotor/``, ``aero/``).

The types are plain data, so they live below every layer that makes or reads them; they stay
importable from :mod:`windflutter.aero.sections`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

__all__ = ["Polar", "RotorGeometry", "AeroSections", "HIGH_THRUST"]

#: the names of the BEM's thrust--induction relations (:mod:`windflutter.aero.momentum`; here, in the
#: bottom layer, so that the config can offer them as choices)
HIGH_THRUST = ("buhl", "madsen", "momentum")


@dataclass(frozen=True)
class Polar:
    """Static airfoil polar.

    Parameters
    ----------
    alpha : (n,) angle of attack (rad), increasing.
    cl, cd, cm : (n,) lift, drag and pitching-moment (quarter chord) coefficients.
    name : airfoil name.
    relative_thickness : t/c (-), for information.
    """

    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    cm: np.ndarray
    name: str = ""
    relative_thickness: float = float("nan")


@dataclass(frozen=True)
class RotorGeometry:
    """Where the rotor is and how it turns.

    Parameters
    ----------
    hub_center : (3,) point on the shaft axis at the rotor apex (m), global.
    shaft_axis : (3,) unit vector; the rotor speed vector is ``omega * shaft_axis`` (right-hand
        rule), so the blades move with velocity ``omega * shaft_axis x (x - hub_center)``.
    wind_direction : (3,) unit vector of the free wind (global +x, downwind, by default).
    """

    hub_center: np.ndarray
    shaft_axis: np.ndarray
    wind_direction: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))


@dataclass
class AeroSections:
    """Aerodynamic strips (arrays of length ``ns``), global frame, SI units.

    Attributes
    ----------
    blade : (ns,) int, blade index (0-based).
    radius : (ns,) distance of the strip's elastic-axis point from the shaft axis (m).
    width : (ns,) strip width along the span (m); sum over a blade = aerodynamic span.
    chord : (ns,) chord (m); the semi-chord is ``b = chord / 2``.
    elastic_axis : (ns,) ``a``: elastic-axis position aft of mid-chord in semi-chords (-).
    origin : (ns, 3) elastic-axis point at zero deflection (m).
    e_chord : (ns, 3) unit chord direction, leading edge -> trailing edge, with twist, pitch
        and azimuth applied.
    e_span : (ns, 3) unit span direction, root -> tip.
    airfoil : (ns,) int, index into ``polars`` (interpolated stations get their own polar).
    polars : list of :class:`Polar`.
    twist : (ns,) structural twist (rad), positive nose-down towards feather (NREL convention).
    motion_map : sparse (6 ns, n_dof): rows ``6 j .. 6 j + 5`` give section j's rigid motion
        ``(ux, uy, uz, rx, ry, rz)`` of its elastic-axis point, global axes, from the structural
        DOF vector (unconstrained numbering ``6 node + c``).
    """

    blade: np.ndarray
    radius: np.ndarray
    width: np.ndarray
    chord: np.ndarray
    elastic_axis: np.ndarray
    origin: np.ndarray
    e_chord: np.ndarray
    e_span: np.ndarray
    airfoil: np.ndarray
    polars: list[Polar]
    twist: np.ndarray
    motion_map: sp.csr_matrix

    @property
    def n_sections(self) -> int:
        return int(self.radius.shape[0])

    @property
    def semi_chord(self) -> np.ndarray:
        return 0.5 * self.chord
