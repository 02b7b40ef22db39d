"""The design parameters of the sensitivities: what a change of each one does to the model's data.

Blade properties act on the beam sections of the blade model element by element (a *station* is an
element of the blade's beam mesh; :func:`blade_sections` changes the sections of any set of them).
Each is a function ``change(K, M, p) -> (K', M')`` of the element's 6x6 section stiffness ``K`` and
mass ``M`` (the :class:`~windflutter.structure.fem.BeamSection` convention: x along the span, y the
flapwise normal of the chord, z along the chord from the leading to the trailing edge; rows
axial, shear y, shear z, torsion, bending about y (edgewise), bending about z (flapwise)):

* ``flap_stiffness``, ``edge_stiffness``, ``torsion_stiffness``, ``axial_stiffness``: relative
  (``p = 0.01`` is +1 %): row and column of the term scaled by ``sqrt(1 + p)``, so its diagonal
  grows by ``1 + p`` and its couplings keep their correlation (the section stays positive definite);
* ``mass``: relative, the whole section mass matrix (mass, its moments and inertia) times ``1 + p``;
* ``mass_offset``: m, the mass centre moved by ``p`` along the chord (towards the trailing edge),
  the inertia about the mass centre kept;
* ``tension_offset``: m, the section's stiffness moved by ``p`` along the chord (towards the
  trailing edge): the elastic (tension) centre and its axial--edgewise coupling;
* ``shear_offset``: m, the shear centre moved by ``p`` along the chord (towards the trailing
  edge): the flapwise shear strain taken at the moved centre, ``gamma_xy - p kappa_x``;
* ``damping``: relative, the element's structural damping (the files' stiffness-proportional
  ``mu``) times ``1 + p``: carried by :func:`windflutter.sensitivity.point` as the damping matrix
  itself, not through the sections.

Global parameters (:data:`GLOBAL_PARAMETERS`) change the turbine description or the options: the
tower's stiffness (the Young's modulus of its wall), the drivetrain's torsional stiffness, the
nacelle mass and the air density (relative), and the pitch-axis position (m): the blade's reference
(pitch) axis moved by ``p`` along every airfoil's chord towards the trailing edge, the beam sections
kept about it -- the airfoils (their aerodynamic forces) moved ``p`` forward relative to the blade's
structure; the strips' elastic-axis position ``a`` (half-chords aft of mid-chord) grows by
``2 p / chord`` (:func:`pitch_axis_strips`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Callable

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.fem import BeamSection


def _scaled_row(index: int):
    def change(K, M, p):
        d = np.ones(6)
        d[index] = np.sqrt(1.0 + p)
        return d[:, None] * K * d[None, :], M
    return change


def _mass(K, M, p):
    return K, (1.0 + p) * M


def _parallel_axis(c: np.ndarray) -> np.ndarray:
    """(3, 3) ``|c|^2 I - c c^T`` of a section offset ``c = (0, cy, cz)``: the inertia about the
    reference axis of a unit mass at ``c``."""
    return float(c @ c) * np.eye(3) - np.outer(c, c)


def _mass_offset(K, M, p):
    m = float(M[0, 0])
    if m <= 0:
        return K, M
    c = np.array([0.0, -M[5, 0] / m, M[4, 0] / m])  # (0, cy, cz): the coupling block is m S(c)
    c2 = c + np.array([0.0, 0.0, p])
    out = np.array(M, dtype=float, copy=True)
    S = np.array([[0.0, -c2[2], c2[1]], [c2[2], 0.0, -c2[0]], [-c2[1], c2[0], 0.0]])
    out[3:, :3] = m * S
    out[:3, 3:] = (m * S).T
    out[3:, 3:] = M[3:, 3:] + m * (_parallel_axis(c2) - _parallel_axis(c))
    return K, out


def _tension_offset(K, M, p):
    A = np.eye(6)
    A[0, 4] = p  # axial strain at z = p: eps + p kappa_y (kappa_y: curvature about y, theta_y = -w')
    return A.T @ K @ A, M


def _shear_offset(K, M, p):
    A = np.eye(6)
    A[1, 3] = -p  # flapwise shear strain at z = p: gamma_xy - p kappa_x (Gamma = u' + e1 x theta)
    return A.T @ K @ A, M


@dataclass(frozen=True)
class BladeProperty:
    """A blade section property: its ``change(K, M, p)``, unit of ``p`` and the words of the table."""

    name: str
    change: Callable | None
    unit: str
    words: str
    step: float
    relative: bool = True


BLADE_PROPERTIES: dict[str, BladeProperty] = {p.name: p for p in (
    BladeProperty("flap_stiffness", _scaled_row(5), "1", "flap stiffness", 1e-4),
    BladeProperty("edge_stiffness", _scaled_row(4), "1", "edge stiffness", 1e-4),
    BladeProperty("torsion_stiffness", _scaled_row(3), "1", "torsion stiffness", 1e-4),
    BladeProperty("axial_stiffness", _scaled_row(0), "1", "axial stiffness", 1e-4),
    BladeProperty("mass", _mass, "1", "mass per length", 1e-4),
    BladeProperty("mass_offset", _mass_offset, "m", "mass centre (aft along the chord)", 1e-4, relative=False),
    BladeProperty("tension_offset", _tension_offset, "m", "elastic centre (aft along the chord)", 1e-4,
                  relative=False),
    BladeProperty("shear_offset", _shear_offset, "m", "shear centre (aft along the chord)", 1e-4, relative=False),
    BladeProperty("damping", None, "1", "structural damping", 1.0),
)}


def blade_sections(fe, name: str, p: float, elements=None):
    """``fe`` with the beam sections of ``elements`` (indices; None: all) changed by ``p`` of the
    property ``name`` (a copy; each element must have its own section, as the blade mesh gives)."""

    prop = BLADE_PROPERTIES[name]
    if prop.change is None:
        raise InputError("parameter", name, "a blade section property (damping acts on the damping matrix)")
    sec_of = np.asarray(fe.beam_section, dtype=np.int64)
    idx = np.arange(len(sec_of)) if elements is None else np.atleast_1d(np.asarray(elements, dtype=np.int64))
    if len(np.unique(sec_of)) != len(sec_of):
        raise InputError("fe.beam_section", "shared sections", "one section per beam element (the blade mesh)")
    secs = list(fe.beam_sections)
    for e in idx:
        s = secs[sec_of[e]]
        K, M = prop.change(np.asarray(s.stiffness, float), np.asarray(s.mass, float), p)
        secs[sec_of[e]] = BeamSection(stiffness=0.5 * (K + K.T), mass=0.5 * (M + M.T), name=s.name)
    return dataclasses.replace(fe, beam_sections=secs)


# -- global parameters ------------------------------------------------------------------------
def _tower_stiffness(turbine, options, p):
    tw = turbine.tower
    mats = dict(turbine.materials)
    for lay in tw.layers:
        m = mats[lay.material]
        mats[lay.material] = dataclasses.replace(m, E=m.E * (1.0 + p)) if hasattr(m, "E") else \
            dataclasses.replace(m, E1=m.E1 * (1 + p), E2=m.E2 * (1 + p), G12=m.G12 * (1 + p), G13=m.G13 * (1 + p),
                                G23=m.G23 * (1 + p))
    return dataclasses.replace(turbine, materials=mats), options


def _drivetrain_stiffness(turbine, options, p):
    n = turbine.nacelle
    return dataclasses.replace(turbine, nacelle=dataclasses.replace(
        n, drivetrain_torsional_stiffness=n.drivetrain_torsional_stiffness * (1.0 + p))), options


def _nacelle_mass(turbine, options, p):
    n = turbine.nacelle
    return dataclasses.replace(turbine, nacelle=dataclasses.replace(n, mass=n.mass * (1.0 + p))), options


def _air_density(turbine, options, p):
    return turbine, dataclasses.replace(options, air_density=options.air_density * (1.0 + p))


def _pitch_axis(turbine, options, p):
    b = turbine.blade
    chord = np.asarray(b.chord, float)
    blade = dataclasses.replace(b, pitch_axis=np.asarray(b.pitch_axis, float) + p / chord,
                                section_offset_y=np.asarray(b.section_offset_y, float) + p)
    return dataclasses.replace(turbine, blade=blade), options


def pitch_axis_strips(sections, p: float):
    """The strips with the blade's pitch axis moved ``p`` (m) aft along their chords (the airfoils
    moved forward relative to the structure): elastic-axis position ``a + 2 p / chord``."""
    return dataclasses.replace(sections, elastic_axis=np.asarray(sections.elastic_axis, float)
                               + 2.0 * p / np.asarray(sections.chord, float))


@dataclass(frozen=True)
class GlobalParameter:
    """A whole-turbine parameter: ``change(turbine, options, p) -> (turbine', options')``; ``part``
    says which part of the point system it changes (``"support"``: the ground-fixed part;
    ``"aero"``: the blade's strip aerodynamics, scaled; ``"strips"``: the blade's strips, changed by
    ``strips(sections, p)``); ``relative``: ``p`` relative (else an offset in m)."""

    name: str
    change: Callable
    part: str
    words: str
    step: float = 1e-3
    relative: bool = True
    strips: Callable | None = None


GLOBAL_PARAMETERS: dict[str, GlobalParameter] = {g.name: g for g in (
    GlobalParameter("tower_stiffness", _tower_stiffness, "support", "tower stiffness"),
    GlobalParameter("drivetrain_stiffness", _drivetrain_stiffness, "support", "drivetrain torsional stiffness"),
    GlobalParameter("nacelle_mass", _nacelle_mass, "support", "nacelle mass"),
    GlobalParameter("air_density", _air_density, "aero", "air density"),
    GlobalParameter("pitch_axis", _pitch_axis, "strips", "pitch axis (aft along the chord)", step=1e-4,
                    relative=False, strips=pitch_axis_strips),
)}

#: the change a sensitivity is read for (the ranked table's): 1 % of a relative parameter, 1 cm of
#: an offset
UNIT_RELATIVE, UNIT_OFFSET = 0.01, 0.01


def is_relative(name: str) -> bool:
    """Whether the parameter ``name`` (blade property or global) is relative (else an offset, m)."""
    return (BLADE_PROPERTIES[name] if name in BLADE_PROPERTIES else GLOBAL_PARAMETERS[name]).relative


def unit_change(name: str) -> float:
    """The table's unit change of a parameter: 1 % (relative) or 1 cm (offsets)."""
    return UNIT_RELATIVE if is_relative(name) else UNIT_OFFSET


def change_words(name: str) -> str:
    """``"+1 % flap stiffness"``, ``"+1 cm pitch axis (aft along the chord)"``."""
    p = BLADE_PROPERTIES[name] if name in BLADE_PROPERTIES else GLOBAL_PARAMETERS[name]
    return ("+1 % " if p.relative else "+1 cm ") + p.words


def check_parameters(names, table: dict, field: str) -> tuple[str, ...]:
    """The names in ``table``, checked (InputError naming ``field``); None: all of them."""
    if names is None:
        return tuple(table)
    out = tuple(names)
    bad = [n for n in out if n not in table]
    if bad:
        raise InputError(field, bad[0], f"one of {', '.join(table)}")
    return out
