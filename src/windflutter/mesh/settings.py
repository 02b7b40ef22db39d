"""Mesh settings: element counts (or the target element length they follow from), model kind and
operating geometry (pitch, azimuth)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from windflutter.config.declarations import (BEAM_SPAN_ELEMENTS, REFERENCE_SURFACES, SHELL_SHEAR_MODELS,
                                             SHELL_SPAN_ELEMENTS, TIP_CLOSURES)
from windflutter.errors import InputError, check_choice

PARTS = ("turbine", "blade", "tower", "rotor", "rotor_blade", "support")
MODELS = ("shell", "beam")

#: shell blades: elements around a section unless told (the seed's 40; the study: 40 -> 60 moves the
#: frequencies by < 1 %) -- and with a given element length, the count whose elements around the
#: largest section are 1 / SKIN_ASPECT of that length, if that is more
SHELL_CHORD_ELEMENTS = 40
SKIN_ASPECT = 4.0
#: the seed's shell mesh (Castillo Capponi 2010, table 4.6; windflutter's default until Dec 2026):
#: 30 elements along the span, 40 around, the skin on the outer mould line
SEED_MESH = {"n_span": 30, "n_chord": 40, "reference_surface": "outer"}
#: bounds on the counts an element length may give (checked before any mesh is built)
SPAN_BOUNDS = (4, 400)
CHORD_BOUNDS = (8, 400)


@dataclass(frozen=True)
class MeshSettings:
    """How to turn a :class:`~windflutter.model.turbine.Turbine` into an FE model.

    The shell blade's default mesh follows from its size: the blade length / 100 along the span, 40
    around (:func:`resolve_counts`, chosen by the convergence study of docs/mesh.md).  The seed's
    mesh, ``MeshSettings(**SEED_MESH)``, gives a whole NREL 5 MW shell model of the seed's size
    (Castillo Capponi 2010, table 4.6: 4650 CQUAD4, 4455 nodes, 26136 DOF): 3 blades x (40 x 30 skin
    + webs 3 high) + tower 20 x 22; the bundled ``seed5mw`` gives 4526 quads, 4519 nodes, 26142
    free DOF.

    Parameters
    ----------
    model : ``"shell"`` (lofted composite skin + webs, shell tower) or ``"beam"`` (Timoshenko beams).
    part : ``"turbine"``, ``"blade"`` (one blade clamped at the root), ``"tower"`` (tower clamped at
        the base with the rotor-nacelle assembly lumped at the top) or ``"rotor"`` (blades and hub,
        hub clamped).
    n_chord : skin elements around each blade section (closed contour); ``None``: from the element
        length (shells, :func:`resolve_counts`).
    n_span : blade elements along the span (stations = n_span + 1); ``None``: from the element length
        (shells) or 30 (beams).
    element_length : shell blades: target length (m) of the skin elements along the span; the counts not
        given follow from it and the blade's size (:func:`resolve_counts`). ``None``: the blade length
        over :data:`SHELL_SPAN_ELEMENTS`.
    reference_surface : shell blades: where the skin's reference surface lies -- ``"midsurface"``
        (default: the laminate midsurface, half the local laminate thickness inside the outer mould
        line, the wall midline of the thin-walled beam sections; the windIO layers stack inwards from
        the outer mould line) or ``"outer"`` (the seed's: on the outer mould line, half of each
        laminate outside the airfoil; stiffer in flap and torsion, docs/mesh.md).
    n_web : elements across the height of each shear web.
    n_tower_circ : tower shell elements around the circumference.
    n_tower_axial : tower elements (shell or beam) along the height.
    tower_model : ``"shell"`` or ``"beam"`` (only for ``model="shell"``; the beam model always
        uses tower beams).
    pitch : collective blade pitch (rad), positive towards feather.
    azimuth : rotor azimuth (rad) of blade 0, 0 = pointing up, increasing with the rotation.
    span_clustering : 0 = uniform stations along the span; 1 = cosine clustering at root and tip.
    tip_closure : how a shell blade's end section is closed: ``"rib"`` (default; a thin rib, a
        :class:`~windflutter.structure.fem.Diaphragm` keeping the section's shape in its plane, warping
        free), ``"rigid"`` (the whole section a rigid body, warping restrained) or ``"open"`` (no
        closure: the skin's free edge, whose thin, nearly flat tip section buckled under the steady
        compression at overspeed with the one-point shear; docs/mesh.md).
    shell_shear : the shells' transverse shear: ``"mitc4"`` (default; assumed covariant shear
        strains, Dvorkin and Bathe 1984) or ``"one-point"`` (pyfe3d's Quad4 as it is, the element of
        windflutter before Dec 2026: one-point shear, whose hourglass mode a compressive steady stress
        turns unstable; docs/mesh.md).
    """

    model: str = "shell"
    part: str = "turbine"
    n_chord: int | None = None
    n_span: int | None = None
    n_web: int = 3
    n_tower_circ: int = 20
    n_tower_axial: int = 22
    tower_model: str = "shell"
    pitch: float = 0.0
    azimuth: float = 0.0
    span_clustering: float = 0.0
    tip_closure: str = "rib"
    element_length: float | None = None
    reference_surface: str = "midsurface"
    shell_shear: str = "mitc4"

    def __post_init__(self) -> None:
        check_choice("mesh.model", self.model, MODELS)
        check_choice("mesh.part", self.part, PARTS)
        check_choice("mesh.tower_model", self.tower_model, MODELS)
        check_choice("mesh.tip_closure", self.tip_closure, TIP_CLOSURES)
        check_choice("mesh.reference_surface", self.reference_surface, REFERENCE_SURFACES)
        check_choice("mesh.shell_shear", self.shell_shear, SHELL_SHEAR_MODELS)
        for name, lo in (("n_chord", 8), ("n_span", 2), ("n_web", 1), ("n_tower_circ", 8), ("n_tower_axial", 2)):
            v = getattr(self, name)
            if v is None and name in ("n_chord", "n_span"):
                continue
            if not isinstance(v, (int, np.integer)) or isinstance(v, bool) or v < lo:
                raise InputError(f"mesh.{name}", v, f"an integer >= {lo}")
        if not 0.0 <= self.span_clustering <= 1.0:
            raise InputError("mesh.span_clustering", self.span_clustering, "a number in [0, 1]")
        h = self.element_length
        if h is not None and (isinstance(h, bool) or not isinstance(h, (int, float)) or not math.isfinite(h)
                              or h <= 0):
            raise InputError("mesh.element_length", h, "a positive, finite length (m)")

    def resolved(self, turbine) -> MeshSettings:
        """These settings with the element counts not given filled in for ``turbine``'s blade (its
        size; the counts given are kept)."""
        blade = getattr(turbine, "blade", None)
        if self.n_span is not None and (self.n_chord is not None or self.model != "shell"):
            return self
        if self.model != "shell" or blade is None:
            return dataclasses.replace(self, n_span=self.n_span or BEAM_SPAN_ELEMENTS,
                                       n_chord=self.n_chord or SHELL_CHORD_ELEMENTS)
        n_span, n_chord = resolve_counts(blade, self.element_length, self.n_span, self.n_chord,
                                         getattr(turbine, "airfoils", None))
        return dataclasses.replace(self, n_span=n_span, n_chord=n_chord)


def max_perimeter(blade, airfoils: dict | None = None) -> float:
    """The largest section perimeter (m) of ``blade``: chord x the airfoil's contour length at each
    airfoil position of the stack (a circle, pi x chord, where an airfoil has no coordinates)."""
    if not airfoils:
        return float(np.pi * np.max(blade.chord))
    chord = np.interp(blade.airfoil_positions, blade.s, blade.chord)
    per = []
    for name, c in zip(blade.airfoil_names, chord):
        af = airfoils.get(name)
        if af is None or len(af.x) < 3:
            per.append(np.pi * c)
            continue
        xy = np.column_stack([af.x, af.y])
        per.append(c * float(np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1))))
    return float(max(per))


def resolve_counts(blade, element_length: float | None, n_span: int | None = None, n_chord: int | None = None,
                   airfoils: dict | None = None) -> tuple[int, int]:
    """Shell blade elements along the span and around a section from a target element length.

    ``element_length`` (m; ``None``: blade length / :data:`SHELL_SPAN_ELEMENTS`) sets the span count
    ``ceil(L / h)``; around a section the count is the larger of :data:`SHELL_CHORD_ELEMENTS` and the
    count whose elements around the largest section are ``h / SKIN_ASPECT`` long (even), so that a
    finer target refines both directions.  Given counts are kept.  Counts outside
    :data:`SPAN_BOUNDS` / :data:`CHORD_BOUNDS` are an :class:`InputError` naming the element length,
    raised before any mesh is built.
    """
    L = float(blade.length)
    h = element_length if element_length is not None else L / SHELL_SPAN_ELEMENTS
    if n_span is None:
        n_span = int(math.ceil(L / h - 1e-9))
        if not SPAN_BOUNDS[0] <= n_span <= SPAN_BOUNDS[1]:
            raise InputError("mesh.element_length", element_length, f"a length giving {SPAN_BOUNDS[0]} to "
                             f"{SPAN_BOUNDS[1]} elements along the {L:.1f} m blade (it gives {n_span}): "
                             f"{L / SPAN_BOUNDS[1]:.3g} to {L / SPAN_BOUNDS[0]:.3g} m")
    if n_chord is None:
        n_chord = SHELL_CHORD_ELEMENTS
        if element_length is not None:
            k = 2 * int(math.ceil(SKIN_ASPECT * max_perimeter(blade, airfoils) / element_length / 2 - 1e-9))
            n_chord = max(n_chord, k)
            if n_chord > CHORD_BOUNDS[1]:
                raise InputError("mesh.element_length", element_length, f"a length giving at most "
                                 f"{CHORD_BOUNDS[1]} elements around a section (it gives {n_chord})")
    return int(n_span), int(n_chord)
