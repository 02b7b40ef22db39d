"""Typed description of a wind turbine: the contract between the readers (``model/``) and ``mesh/``.

Everything is SI (m, kg, s, N, Pa, rad).  Degrees and rpm from input files are converted at load.

Frames
------
* **Global** (IEC / OpenFAST): origin at the tower base, x downwind along the untilted shaft,
  z up, y = z x x (to port, looking downwind).
* **Blade root frame** (windIO): origin at the blade root on the pitch axis, z along the pitch
  axis root -> tip, x towards the suction side of the airfoils (flapwise; standard prebend is
  negative x), y towards the trailing edge at zero twist/pitch (edgewise; standard sweep positive).
* **Section frame of beam properties** (:class:`BeamProperties`, the ``BeamSection`` convention of
  ``windflutter.structure.fem``): x along the reference axis (root -> tip), y flapwise (towards
  the suction side) and z edgewise (towards the trailing edge), *both rotated by the local twist*,
  i.e. ``(x, y, z)_section = (z, x, y)_blade`` turned about the span axis by ``-twist``
  (twist is positive nose-down towards feather, which turns the leading edge towards the pressure
  side, -x).  See ``model/beamprops.py`` and ``docs/turbine_input.md``.

Spanwise quantities are given on a nondimensional coordinate ``s`` in [0, 1] measured along the
(possibly curved) reference axis, as in windIO.  The blade's aerodynamic/geometric arrays share one
grid (``Blade.s``); layers, webs and elastic properties keep their own grids and are sampled with
:func:`interp_span`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import trapezoid  # numpy < 2 (pyNastran env) has no np.trapezoid

from windflutter.aero.sections import Polar
from windflutter.structure.fem import IsotropicMaterial, Material, OrthotropicMaterial

__all__ = [
    "Airfoil",
    "Web",
    "Layer",
    "Layup",
    "BeamProperties",
    "Blade",
    "TowerLayer",
    "Tower",
    "Hub",
    "Nacelle",
    "ControlSettings",
    "OperatingCurve",
    "Turbine",
    "interp_span",
    "IsotropicMaterial",
    "OrthotropicMaterial",
    "Material",
    "Polar",
]


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

    @property
    def length(self) -> float:
        """Length of the reference axis (m)."""
        return float(self.arc_length[-1])

    def at(self, name: str, s: np.ndarray | float) -> np.ndarray:
        """Interpolate a geometric field (``"chord"``, ``"twist"``, ...) at span positions ``s``."""
        return interp_span(self.s, getattr(self, name), s)


# ----------------------------------------------------------------------------------------- tower
@dataclass(frozen=True)
class TowerLayer:
    """A tower wall layer: material key and thickness (m) on :attr:`Tower.s`."""

    name: str
    material: str
    thickness: np.ndarray


@dataclass(frozen=True)
class Tower:
    """Tubular tower (circular, thin-walled).

    Parameters
    ----------
    s : (n,) nondimensional position along the tower axis, 0 base, 1 top.
    z : (n,) heights (m) of the stations, global frame (windIO tower reference axis; the tower
        base is ``z[0]``, normally 0 for land-based turbines).
    outer_diameter : (n,) m.
    layers : wall layers (thickness on ``s``).
    outfitting_factor : multiplier on the wall mass for flanges, bolts, platforms (-), 1 if none.
    """

    s: np.ndarray
    z: np.ndarray
    outer_diameter: np.ndarray
    layers: tuple[TowerLayer, ...]
    outfitting_factor: float = 1.0

    @property
    def height(self) -> float:
        return float(self.z[-1] - self.z[0])

    @property
    def top_z(self) -> float:
        return float(self.z[-1])

    @property
    def wall_thickness(self) -> np.ndarray:
        """Total wall thickness (m) on ``s``."""
        return np.sum([lay.thickness for lay in self.layers], axis=0)


# -------------------------------------------------------------------------------- hub / nacelle
@dataclass(frozen=True)
class Hub:
    """Hub (rotating) lumped properties.

    Parameters
    ----------
    mass : kg.
    inertia : (3, 3) kg·m² about the hub CG in the shaft frame (x along the shaft); normally only
        ``inertia[0, 0]`` (about the shaft, OpenFAST ``HubIner``) is known.
    cg_offset : distance of the hub CG from the rotor apex along the shaft (m), positive
        downwind (OpenFAST ``HubCM``).
    diameter : hub diameter (m); blade roots are at ``diameter / 2`` from the apex along the coned
        blade axis.
    precone : cone angle (rad), positive tilting the blades away from the tower for an upwind
        rotor (OpenFAST ``PreCone`` sign flipped: OpenFAST uses negative for upwind coning).
    """

    mass: float
    inertia: np.ndarray
    diameter: float
    precone: float
    cg_offset: float = 0.0

    @property
    def radius(self) -> float:
        return 0.5 * self.diameter


@dataclass(frozen=True)
class Nacelle:
    """Nacelle/drivetrain (non-rotating lumped part) and the rotor's position.

    Parameters
    ----------
    mass : nacelle mass incl. drivetrain (kg), without hub/blades.
    inertia : (3, 3) kg·m² about the nacelle CG, global axes (yaw-aligned); often only the yaw
        inertia ``inertia[2, 2]`` is known (OpenFAST ``NacYIner``).
    cg : (3,) nacelle CG relative to the tower top (yaw bearing) in global axes (m)
        (OpenFAST ``NacCMxn, NacCMyn, NacCMzn``).
    overhang : distance along the tilted shaft from the tower (yaw) axis to the rotor apex (m),
        signed as OpenFAST ``OverHang``: negative for an upwind rotor.
    shaft_tilt : shaft uptilt (rad), positive raising the upwind end of the shaft (OpenFAST
        ``ShftTilt`` sign, windIO ``uptilt``).
    tower_to_shaft : vertical distance from the tower top to the shaft/yaw-axis intersection (m)
        (OpenFAST ``Twr2Shft``).
    generator_inertia : generator inertia about the high-speed shaft (kg·m²), 0 if unknown.
    gear_ratio : gearbox ratio (-), 1 for direct drive.
    drivetrain_torsional_stiffness : equivalent low-speed-shaft torsional spring (N·m/rad),
        ``inf`` for rigid.
    yaw_bearing_mass : mass lumped at the tower top (kg).
    """

    mass: float
    inertia: np.ndarray
    cg: np.ndarray
    overhang: float
    shaft_tilt: float
    tower_to_shaft: float
    generator_inertia: float = 0.0
    gear_ratio: float = 1.0
    drivetrain_torsional_stiffness: float = float("inf")
    yaw_bearing_mass: float = 0.0

    def rotor_apex(self, tower_top_z: float) -> np.ndarray:
        """Rotor apex (hub centre on the shaft axis) in the global frame (m)."""
        c, s_ = np.cos(self.shaft_tilt), np.sin(self.shaft_tilt)
        return np.array([self.overhang * c, 0.0, tower_top_z + self.tower_to_shaft - self.overhang * s_])

    def shaft_axis(self) -> np.ndarray:
        """Unit vector along the shaft pointing downwind (global); upwind end raised by tilt."""
        return np.array([np.cos(self.shaft_tilt), 0.0, -np.sin(self.shaft_tilt)])


# ------------------------------------------------------------------------------ control/operation
@dataclass(frozen=True)
class ControlSettings:
    """Controller limits (windIO ``control`` block), SI: m/s, rad/s, rad, rad/s."""

    cut_in: float = float("nan")
    cut_out: float = float("nan")
    max_tip_speed: float = float("nan")
    min_pitch: float = 0.0
    max_pitch: float = float("nan")
    max_pitch_rate: float = float("nan")
    tsr: float = float("nan")
    min_rotor_speed: float = float("nan")
    max_rotor_speed: float = float("nan")


@dataclass(frozen=True)
class OperatingCurve:
    """Steady operating points: wind speed -> rotor speed and blade pitch.

    Parameters
    ----------
    wind_speed : (n,) hub-height wind speed (m/s), increasing.
    rotor_speed : (n,) rad/s.
    pitch : (n,) collective blade pitch (rad), positive towards feather.
    power : (n,) electrical or aerodynamic power (W), nan if unknown.
    thrust : (n,) rotor thrust (N), nan if unknown.
    source : description of the origin (table file or "control block").
    """

    wind_speed: np.ndarray
    rotor_speed: np.ndarray
    pitch: np.ndarray
    power: np.ndarray | None = None
    thrust: np.ndarray | None = None
    source: str = ""

    def rotor_speed_at(self, v: np.ndarray | float) -> np.ndarray:
        """Rotor speed (rad/s) at wind speed(s) ``v`` (m/s), linear interpolation."""
        return np.interp(v, self.wind_speed, self.rotor_speed)

    def pitch_at(self, v: np.ndarray | float) -> np.ndarray:
        """Blade pitch (rad) at wind speed(s) ``v`` (m/s), linear interpolation."""
        return np.interp(v, self.wind_speed, self.pitch)

    @property
    def rated_rotor_speed(self) -> float:
        return float(np.max(self.rotor_speed))

    @property
    def rated_wind_speed(self) -> float:
        """Lowest wind speed at which the rotor speed reaches 99.9 % of its maximum and the pitch
        starts to increase (the knee of the curve), m/s."""
        w = self.rotor_speed
        at_max = w >= 0.999 * w.max()
        pitching = self.pitch > self.pitch[at_max].min() + np.radians(0.1)
        cand = np.where(at_max & ~pitching)[0]
        i = cand[-1] if cand.size else int(np.argmax(at_max))
        return float(self.wind_speed[i])


# --------------------------------------------------------------------------------------- turbine
@dataclass(frozen=True)
class Turbine:
    """A complete wind turbine description.

    Parameters
    ----------
    name : turbine name.
    n_blades : number of blades.
    hub_height : m (from the file's assembly block).
    rotor_diameter : m.
    rated_power : W.
    rated_rotor_speed : rad/s.
    blade, tower, hub, nacelle : components.
    airfoils : name -> :class:`Airfoil`.
    materials : name -> material (``IsotropicMaterial`` / ``OrthotropicMaterial``).
    ply_thickness : material name -> single-ply thickness (m), where given.
    control : controller limits.
    operating_curve : steady operating points, if known.
    rotor_orientation : ``"upwind"`` or ``"downwind"``.
    source : path of the file read.
    notes : provenance notes (supplement files, assumptions).
    """

    name: str
    n_blades: int
    hub_height: float
    rotor_diameter: float
    rated_power: float
    rated_rotor_speed: float
    blade: Blade
    tower: Tower
    hub: Hub
    nacelle: Nacelle
    airfoils: dict[str, Airfoil]
    materials: dict[str, Material]
    ply_thickness: dict[str, float] = field(default_factory=dict)
    control: ControlSettings = field(default_factory=ControlSettings)
    operating_curve: OperatingCurve | None = None
    rotor_orientation: str = "upwind"
    source: str = ""
    notes: tuple[str, ...] = ()
    windio_version: str = ""

    @property
    def rotor_apex(self) -> np.ndarray:
        """Rotor apex in the global frame (m)."""
        return self.nacelle.rotor_apex(self.tower.top_z)

    @property
    def tip_radius(self) -> float:
        """Rotor radius from hub radius + blade length, projected (m) (ignores prebend)."""
        return self.hub.radius + float(self.blade.ref_axis[-1, 2])
