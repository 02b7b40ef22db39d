"""Mesh settings: element counts, model kind and operating geometry (pitch, azimuth)."""

from __future__ import annotations

from dataclasses import dataclass

from windflutter.config.declarations import TIP_CLOSURES
from windflutter.errors import InputError, check_choice

PARTS = ("turbine", "blade", "tower", "rotor", "rotor_blade", "support")
MODELS = ("shell", "beam")


@dataclass(frozen=True)
class MeshSettings:
    """How to turn a :class:`~windflutter.model.turbine.Turbine` into an FE model.

    The defaults give a whole NREL 5 MW shell model of the seed's size (Castillo Capponi 2010,
    table 4.6: 4650 CQUAD4, 4455 nodes, 26136 DOF): 3 blades x (40 x 30 skin + webs 3 high)
    + tower 20 x 22; the bundled ``seed5mw`` gives 4526 quads, 4519 nodes, 26142 free DOF.

    Parameters
    ----------
    model : ``"shell"`` (lofted composite skin + webs, shell tower) or ``"beam"`` (Timoshenko beams).
    part : ``"turbine"``, ``"blade"`` (one blade clamped at the root), ``"tower"`` (tower clamped at
        the base with the rotor-nacelle assembly lumped at the top) or ``"rotor"`` (blades and hub,
        hub clamped).
    n_chord : skin elements around each blade section (closed contour).
    n_span : blade elements along the span (stations = n_span + 1).
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
        closure: the skin's free edge, whose thin, nearly flat tip section buckles locally under the
        steady compression at overspeed; docs/mesh.md).
    """

    model: str = "shell"
    part: str = "turbine"
    n_chord: int = 40
    n_span: int = 30
    n_web: int = 3
    n_tower_circ: int = 20
    n_tower_axial: int = 22
    tower_model: str = "shell"
    pitch: float = 0.0
    azimuth: float = 0.0
    span_clustering: float = 0.0
    tip_closure: str = "rib"

    def __post_init__(self) -> None:
        check_choice("mesh.model", self.model, MODELS)
        check_choice("mesh.part", self.part, PARTS)
        check_choice("mesh.tower_model", self.tower_model, MODELS)
        check_choice("mesh.tip_closure", self.tip_closure, TIP_CLOSURES)
        for name, lo in (("n_chord", 8), ("n_span", 2), ("n_web", 1), ("n_tower_circ", 8), ("n_tower_axial", 2)):
            v = getattr(self, name)
            if not isinstance(v, int) or v < lo:
                raise InputError(f"mesh.{name}", v, f"an integer >= {lo}")
        if not 0.0 <= self.span_clustering <= 1.0:
            raise InputError("mesh.span_clustering", self.span_clustering, "a number in [0, 1]")
