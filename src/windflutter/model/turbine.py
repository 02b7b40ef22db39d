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

from windflutter.aero_types import Polar
from windflutter.errors import InputError, ValidityWarning
from windflutter.model.blade import (
    Airfoil,
    BeamProperties,
    Blade,
    BladeDamping,
    Layer,
    Layup,
    Web,
    interp_span,
)
from windflutter.structure.fem import IsotropicMaterial, Material, OrthotropicMaterial

__all__ = [
    "Airfoil",
    "Web",
    "Layer",
    "Layup",
    "BeamProperties",
    "Blade",
    "BladeDamping",
    "TowerDamping",
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


# ----------------------------------------------------------------------------------------- tower
@dataclass(frozen=True)
class TowerLayer:
    """A tower wall layer: material key and thickness (m) on :attr:`Tower.s`."""

    name: str
    material: str
    thickness: np.ndarray


@dataclass(frozen=True)
class TowerDamping:
    """Tower structural damping as the files give it (modal ratios, fractions of critical; NaN
    if not given), e.g. ElastoDyn ``TwrFADmp(1..2)`` / ``TwrSSDmp(1..2)`` (%)."""

    fore_aft_ratio: np.ndarray = field(default_factory=lambda: np.full(2, np.nan))
    side_side_ratio: np.ndarray = field(default_factory=lambda: np.full(2, np.nan))
    source: str = ""


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
    damping : structural damping from the files, ``None`` if none gives any.
    """

    s: np.ndarray
    z: np.ndarray
    outer_diameter: np.ndarray
    layers: tuple[TowerLayer, ...]
    outfitting_factor: float = 1.0
    damping: TowerDamping | None = None

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
    drivetrain_torsional_damping : equivalent low-speed-shaft torsional damper (N·m·s/rad),
        0 if not given (OpenFAST ``DTTorDmp``).
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
    drivetrain_torsional_damping: float = 0.0
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

    def warn_outside(self, v: float) -> None:
        """A :class:`~windflutter.errors.ValidityWarning` when ``v`` (m/s) lies outside the curve:
        its end point's rotor speed and pitch are used there (a wind speed above cut-out silently
        took the 25 m/s pitch before)."""
        import warnings

        lo, hi = float(self.wind_speed[0]), float(self.wind_speed[-1])
        if lo - 1e-9 <= v <= hi + 1e-9:
            return
        end = lo if v < lo else hi
        warnings.warn(ValidityWarning(
            f"V = {v:g} m/s is outside the operating curve ({lo:g}-{hi:g} m/s, {self.source or 'the turbine files'}): "
            f"the rotor speed and pitch of its end at {end:g} m/s ({self.rotor_speed_at(end) * 30 / np.pi:.2f} RPM, "
            f"{np.degrees(self.pitch_at(end)):.2f} deg) are used"), stacklevel=3)

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
#: What each kind of missing data is, and which models need it.
MISSING_HINTS = {
    "hub.mass": "a lumped hub mass (kg)",
    "nacelle.mass": "a lumped nacelle mass (kg)",
    "tower": "a tower description",
    "airfoil polars": "airfoil polar tables (lift, drag and moment coefficients)",
    "blade torsion": "a blade torsional stiffness (ElastoDyn blades have none: use BeamDyn, CompElast = 2)",
}
_NEEDED_FOR_AERODYNAMICS = ("airfoil polars", "blade torsion")
_NEEDED_BY_PART = {
    "turbine": ("hub.mass", "nacelle.mass", "tower"),
    "tower": ("hub.mass", "nacelle.mass", "tower"),
    "rotor": ("hub.mass",),  # the hub node of the rotor model carries the hub mass (clamped)
    "blade": (),
    "rotor_blade": (),  # blade 0 on a massless clamped hub
    "support": ("nacelle.mass", "tower"),  # tower and nacelle with a massless hub node
}


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
    notes : provenance notes (supplement files, assumptions, defaults filled in).
    windio_version : the windIO version of a windIO file ("" for other formats).
    source_format : reader that produced it (``"windIO 2.x"``, ``"OpenFAST"``, ``"HAWC2"`` ...).
    input_files : every file read (turbine file, referenced files, supplement), for
        fingerprints and provenance.
    warnings : plausibility warnings (unusual but possible data), one line each naming the file,
        field and station; printed as :class:`~windflutter.errors.InputWarning` when read.
    missing : data the files do not give (keys of :data:`MISSING_HINTS`, e.g. ``"nacelle.mass"``);
        :meth:`require` refuses an analysis that needs them.
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
    source_format: str = ""
    input_files: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    missing: tuple[str, ...] = ()

    @property
    def rotor_apex(self) -> np.ndarray:
        """Rotor apex in the global frame (m)."""
        return self.nacelle.rotor_apex(self.tower.top_z)

    @property
    def tip_radius(self) -> float:
        """Rotor radius from hub radius + blade length, projected (m) (ignores prebend)."""
        return self.hub.radius + float(self.blade.ref_axis[-1, 2])

    def require(self, part: str = "turbine", aerodynamics: bool = False) -> None:
        """Refuse a model that needs data the files did not give.

        Parameters
        ----------
        part : ``"turbine"``, ``"tower"``, ``"rotor"`` or ``"blade"`` (the mesh part); a blade
            alone needs only blade data.
        aerodynamics : also require airfoil polars (stability analyses).

        Raises
        ------
        InputError
            Naming the first missing item, the file and how to supply it.
        """
        need = _NEEDED_BY_PART.get(part, _NEEDED_BY_PART["turbine"]) + (_NEEDED_FOR_AERODYNAMICS if aerodynamics else ())
        for item in need:
            if item in self.missing:
                what = "a stability analysis" if item in _NEEDED_FOR_AERODYNAMICS else f"the {part!r} model"
                raise InputError(item, None, f"{MISSING_HINTS.get(item, item)} for {what}: the turbine files give "
                                 "none; add it to the file or to a 'windflutter:' supplement "
                                 "(docs/turbine_input.md)", self.source)

    def store_attributes(self) -> dict[str, str]:
        """Provenance as flat string attributes (for a NetCDF/zarr store): format, files,
        plausibility warnings, missing data and notes."""
        return {
            "turbine_source": self.source,
            "turbine_format": self.source_format or (f"windIO {self.windio_version}" if self.windio_version else ""),
            "turbine_input_files": "; ".join(self.input_files),
            "turbine_warnings": "\n".join(self.warnings) or "none",
            "turbine_missing": ", ".join(self.missing) or "none",
            "turbine_notes": "\n".join(self.notes),
        }

