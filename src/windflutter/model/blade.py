"""Blade description: airfoils, layup (webs, layers), 6x6 beam properties, structural damping.

Part of the reader contract of :mod:`windflutter.model.turbine` (which re-exports every class);
frames and units are described there.  Everything is SI (m, kg, s, N, Pa, rad).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import trapezoid  # numpy < 2 (pyNastran env) has no np.trapezoid

from windflutter.aero_types import Polar

#: BeamDyn/windIO order (F1 shear flap, F2 shear edge, F3 axial, M1 edgewise bending, M2 flapwise
#: bending, M3 torsion) -> BeamSection order (axial, shear y, shear z, torsion, bending about y,
#: bending about z); see :mod:`windflutter.model.beamprops`.
PERM_BEAMDYN_TO_SECTION = np.array([2, 0, 1, 5, 3, 4])


def interp_span(grid: np.ndarray, values: np.ndarray, s: np.ndarray | float) -> np.ndarray:
    """Piecewise-linear interpolation of a spanwise field, constant extrapolation at the ends.

    Parameters
    ----------
    grid : (n,) nondimensional span positions, increasing.
    values : (n,) or (n, ...) field values at ``grid``.
    s : query positions.
    """
    grid = np.asarray(grid, dtype=float)
    values = np.asarray(values, dtype=float)
    sq = np.asarray(s, dtype=float)
    if values.ndim == 1:
        return np.interp(sq, grid, values)
    flat = values.reshape(values.shape[0], -1)
    out = np.stack([np.interp(sq.ravel(), grid, flat[:, j]) for j in range(flat.shape[1])], axis=-1)
    return out.reshape(sq.shape + values.shape[1:])


# --------------------------------------------------------------------------------------- airfoils
@dataclass(frozen=True)
class Airfoil:
    """An airfoil: normalised coordinates and static polars.

    Parameters
    ----------
    name : airfoil name (key used by :attr:`Blade.airfoil_names`).
    x, y : (n,) coordinates normalised by chord, x from leading edge (0) to trailing edge (1),
        y towards the suction side; as given in the file (windIO: TE -> suction side -> LE ->
        pressure side -> TE).  May be empty when the source gives no coordinates.
    relative_thickness : t/c (-).
    aerodynamic_center : chordwise position of the aerodynamic centre (fraction of chord).
    polars : one :class:`~windflutter.aero.sections.Polar` per Reynolds number set
        (alpha in rad, increasing).
    reynolds : (npol,) Reynolds number of each polar (nan if unknown).
    """

    name: str
    x: np.ndarray
    y: np.ndarray
    relative_thickness: float
    aerodynamic_center: float = 0.25
    polars: tuple[Polar, ...] = ()
    reynolds: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def polar(self) -> Polar:
        """The default polar: the set with the highest Reynolds number (closest to operating
        Reynolds numbers of multi-MW blades, 5e6..2e7); the only one if there is just one."""
        if not self.polars:
            raise ValueError(f"airfoil {self.name!r} has no polar")
        if len(self.polars) == 1:
            return self.polars[0]
        re = np.nan_to_num(np.asarray(self.reynolds, dtype=float), nan=-1.0)
        return self.polars[int(np.argmax(re))]


# ----------------------------------------------------------------------------------------- layup
@dataclass(frozen=True)
class Web:
    """A shear web, spanning ``s_start..s_end``; its two shell attachment points are given as
    nondimensional arc positions along the airfoil contour (0 = trailing edge on the suction side,
    increasing over the suction side to the leading edge and back along the pressure side to 1,
    windIO convention).  ``start_arc`` is the suction-side attachment (< 0.5), ``end_arc`` the
    pressure-side one (> 0.5), both on ``s``.
    """

    name: str
    s: np.ndarray
    start_arc: np.ndarray
    end_arc: np.ndarray
    s_start: float = 0.0
    s_end: float = 1.0

    def arcs_at(self, s: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """(start_arc, end_arc) at span positions ``s`` (NaN outside ``s_start..s_end``)."""
        sq = np.asarray(s, dtype=float)
        inside = (sq >= self.s_start - 1e-12) & (sq <= self.s_end + 1e-12)
        a = np.where(inside, np.interp(sq, self.s, self.start_arc), np.nan)
        b = np.where(inside, np.interp(sq, self.s, self.end_arc), np.nan)
        return a, b


@dataclass(frozen=True)
class Layer:
    """A composite layer (a stack of plies of one material and orientation).

    Parameters
    ----------
    name : layer name.
    material : key into :attr:`Turbine.materials`.
    s : (n,) span grid of the arrays below.
    thickness : (n,) total layer thickness (m); 0 where absent.
    orientation : (n,) fibre angle (rad) from the span direction, positive about the outward
        normal of the surface (windIO ``fiber_orientation``).
    start_arc, end_arc : (n,) nondimensional contour positions of the layer's extent (windIO
        convention, see :class:`Web`).  ``end_arc < start_arc`` means the layer wraps through the
        trailing edge (arc 1 -> 0).  For a web layer they are 0 and 1 (the whole web height).
    web : name of the web this layer lies on, or ``None`` for the outer shell.
    s_start, s_end : spanwise extent.
    """

    name: str
    material: str
    s: np.ndarray
    thickness: np.ndarray
    orientation: np.ndarray
    start_arc: np.ndarray
    end_arc: np.ndarray
    web: str | None = None
    s_start: float = 0.0
    s_end: float = 1.0

    def thickness_at(self, s: np.ndarray | float) -> np.ndarray:
        """Thickness (m) at ``s``; 0 outside the spanwise extent."""
        sq = np.asarray(s, dtype=float)
        inside = (sq >= self.s_start - 1e-12) & (sq <= self.s_end + 1e-12)
        return np.where(inside, np.interp(sq, self.s, self.thickness), 0.0)

    def arcs_at(self, s: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """(start_arc, end_arc) at ``s``, interpolated."""
        sq = np.asarray(s, dtype=float)
        return np.interp(sq, self.s, self.start_arc), np.interp(sq, self.s, self.end_arc)

    def orientation_at(self, s: np.ndarray | float) -> np.ndarray:
        return np.interp(np.asarray(s, dtype=float), self.s, self.orientation)


@dataclass(frozen=True)
class Layup:
    """Blade internal structure: shear webs and layers (outer shell and webs), listed from the
    outer surface inwards as in the file."""

    webs: tuple[Web, ...] = ()
    layers: tuple[Layer, ...] = ()

    def web(self, name: str) -> Web:
        for w in self.webs:
            if w.name == name:
                return w
        raise KeyError(name)

    @property
    def shell_layers(self) -> tuple[Layer, ...]:
        return tuple(lay for lay in self.layers if lay.web is None)

    def web_layers(self, name: str) -> tuple[Layer, ...]:
        return tuple(lay for lay in self.layers if lay.web == name)


@dataclass(frozen=True)
class BeamProperties:
    """Spanwise 6x6 beam section properties about the reference axis, in the ``BeamSection``
    convention (see module docstring): section x along the span, y flapwise, z edgewise, rotated
    with the local structural ``twist``.

    Parameters
    ----------
    s : (n,) nondimensional span positions (blade: along the reference axis; tower: height
        fraction).
    stiffness : (n, 6, 6) N, N·m, N·m² (order axial, shear y, shear z, torsion, bending about y,
        bending about z).
    mass : (n, 6, 6) kg/m, kg, kg·m (order ux, uy, uz, rx, ry, rz).
    twist : (n,) rotation of the section frame about the span axis (rad), positive nose-down
        (NREL), that must be applied to go from the blade root frame to the section frame.
    length : length of the reference axis (m), to convert ``s`` to arc length.
    source : where the numbers come from (e.g. ``"BeamDyn NRELOffshrBsline5MW_BeamDyn_Blade.dat"``).
    """

    s: np.ndarray
    stiffness: np.ndarray
    mass: np.ndarray
    twist: np.ndarray
    length: float
    source: str = ""

    @property
    def mass_per_length(self) -> np.ndarray:
        return self.mass[:, 0, 0]

    @property
    def total_mass(self) -> float:
        """Integrated mass (kg), trapezoidal rule over the arc length."""
        return float(trapezoid(self.mass_per_length, self.s * self.length))


# ------------------------------------------------------------------------------------- damping
@dataclass(frozen=True)
class BladeDamping:
    """Structural damping of the blade as the files give it (nothing is applied here).

    Parameters
    ----------
    mu : (6,) stiffness-proportional coefficients (s) in the BeamSection order (axial, shear y,
        shear z, torsion, bending about y = edgewise, bending about z = flapwise), or ``None``:
        the section damping matrix is ``diag(mu) K`` (BeamDyn ``mu1..mu6``, windIO
        ``structural_damping: mu``); a mode of frequency f dominated by one direction has a
        damping ratio of about ``pi f mu``.
    flap_ratio : (2,) modal damping ratios (fractions of critical) of the 1st and 2nd flap modes
        (ElastoDyn ``BldFlDmp``), NaN if not given; for information and comparison.
    edge_ratio : (1,) the same for the 1st edge mode (ElastoDyn ``BldEdDmp``).
    source : which file and field the numbers come from.
    """

    mu: np.ndarray | None = None
    flap_ratio: np.ndarray = field(default_factory=lambda: np.full(2, np.nan))
    edge_ratio: np.ndarray = field(default_factory=lambda: np.full(1, np.nan))
    source: str = ""

    @classmethod
    def from_beamdyn_mu(cls, mu_beamdyn, source: str = "", **kw) -> "BladeDamping":
        """From ``mu1..mu6`` in the BeamDyn/windIO order (shear flap, shear edge, axial,
        edgewise bending, flapwise bending, torsion)."""
        mu = np.asarray(mu_beamdyn, dtype=float)[:6]
        return cls(mu=mu[PERM_BEAMDYN_TO_SECTION], source=source, **kw)

    @property
    def mu_beamdyn(self) -> np.ndarray | None:
        """``mu`` back in the BeamDyn order (``mu1..mu6``)."""
        if self.mu is None:
            return None
        out = np.empty(6)
        out[PERM_BEAMDYN_TO_SECTION] = self.mu
        return out

    def merged(self, other: "BladeDamping | None") -> "BladeDamping":
        """This record with the fields ``other`` gives (``mu`` not None, ratios not NaN) taken
        from ``other``; sources joined."""
        if other is None:
            return self
        pick = (lambda a, b: np.where(np.isfinite(b), b, a))
        keeps = (self.mu is not None and other.mu is None) or any(
            np.any(np.isfinite(a) & ~np.isfinite(b)) for a, b in ((self.flap_ratio, other.flap_ratio),
                                                                   (self.edge_ratio, other.edge_ratio)))
        return BladeDamping(mu=other.mu if other.mu is not None else self.mu,
                            flap_ratio=pick(self.flap_ratio, other.flap_ratio),
                            edge_ratio=pick(self.edge_ratio, other.edge_ratio),
                            source="; ".join(x for x in ((self.source if keeps else ""), other.source) if x))


# ----------------------------------------------------------------------------------------- blade
@dataclass(frozen=True)
class Blade:
    """One blade (all blades identical).

    Parameters
    ----------
    s : (n,) nondimensional coordinate along the reference axis, 0 root, 1 tip.
    ref_axis : (n, 3) reference-axis points in the blade root frame (m); z is the span.
    arc_length : (n,) curvilinear length along the reference axis (m).
    chord : (n,) m.
    twist : (n,) aerodynamic twist (rad), positive nose-down / towards feather (NREL).
    pitch_axis : (n,) chordwise position of the reference axis, fraction of chord from the
        leading edge (windIO ``pitch_axis``; v2 ``section_offset_y / chord``).
    section_offset_y : (n,) the same in metres from the leading edge.
    relative_thickness : (n,) t/c (-).
    airfoil_positions : (na,) span positions of the airfoil stack, increasing.
    airfoil_names : (na,) airfoil at each position (keys into :attr:`Turbine.airfoils`).
    layup : composite layup, if given.
    beam : beam section properties (6x6), if given by the source or computed.
    damping : structural damping from the files (:class:`BladeDamping`), ``None`` if none gives any.
    """

    s: np.ndarray
    ref_axis: np.ndarray
    arc_length: np.ndarray
    chord: np.ndarray
    twist: np.ndarray
    pitch_axis: np.ndarray
    section_offset_y: np.ndarray
    relative_thickness: np.ndarray
    airfoil_positions: np.ndarray
    airfoil_names: tuple[str, ...]
    layup: Layup | None = None
    beam: BeamProperties | None = None
    damping: BladeDamping | None = None

    @property
    def length(self) -> float:
        """Length of the reference axis (m)."""
        return float(self.arc_length[-1])

    def at(self, name: str, s: np.ndarray | float) -> np.ndarray:
        """Interpolate a geometric field (``"chord"``, ``"twist"``, ...) at span positions ``s``."""
        return interp_span(self.s, getattr(self, name), s)


