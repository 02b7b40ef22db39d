"""The same blade described about another reference axis: a helper of the tests, written here.

A beam blade's 6x6 section matrices refer to one line through its sections (a windIO pitch axis,
a HAWC2 half-chord line).  :func:`moved_reference` describes the same sections about the line
at another chord fraction: the reference points move along each section's chord, the stiffness
by the rigid-offset strain transfer ``K_O = T^T K_P T`` and the mass by the rigid-body transfer
``M_O = X^T M_P X`` (BeamDyn order and axes: x towards the suction side, y towards the trailing
edge, z along the span).  For a blade of constant chord and twist the new line is straight and
parallel to the old one, and the model is the same blade; otherwise the new line is curved in
the chord plane (as a HAWC2 c2 line is) and the sections stay normal to it.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from windflutter.model.blade import PERM_BEAMDYN_TO_SECTION

_INV = np.argsort(PERM_BEAMDYN_TO_SECTION)


def _strain_transfer(py: np.ndarray) -> np.ndarray:
    """(n, 6, 6) strains at P = O + (0, py) from those at O (BeamDyn order
    ``(g1, g2, eps, k1, k2, k3)``): ``eps_P = eps + k1 y_P``, ``g1_P = g1 - k3 y_P``."""
    T = np.tile(np.eye(6), (py.size, 1, 1))
    T[:, 2, 3] = py
    T[:, 0, 5] = -py
    return T


def _motion_transfer(py: np.ndarray) -> np.ndarray:
    """(n, 6, 6) rigid motion of P = O + (0, py) from that of O: ``u_P = u_O + theta x r``."""
    X = np.tile(np.eye(6), (py.size, 1, 1))
    # theta x (0, py, 0) = (-theta_z py, 0, theta_x py)
    X[:, 0, 5] = -py
    X[:, 2, 3] = py
    return X


def moved_reference(turbine, chord_fraction: float):
    """``turbine`` with its blade's reference axis at ``chord_fraction`` of the chord from the LE."""
    b = turbine.blade
    bp = b.beam
    e_te = np.stack([np.sin(b.twist), np.cos(b.twist), np.zeros_like(b.twist)], axis=1)  # blade root frame
    ref = b.ref_axis + ((chord_fraction - b.pitch_axis) * b.chord)[:, None] * e_te
    d = (chord_fraction - np.interp(bp.s, b.s, b.pitch_axis)) * np.interp(bp.s, b.s, b.chord)
    py = -d  # the old reference point seen from the new one (towards the TE positive)
    T, X = _strain_transfer(py), _motion_transfer(py)
    K = np.einsum("nji,njk,nkl->nil", T, bp.stiffness[:, _INV][:, :, _INV], T)
    M = np.einsum("nji,njk,nkl->nil", X, bp.mass[:, _INV][:, :, _INV], X)
    P = PERM_BEAMDYN_TO_SECTION
    beam = dataclasses.replace(bp, stiffness=K[:, P][:, :, P], mass=M[:, P][:, :, P])
    blade = dataclasses.replace(b, ref_axis=ref, pitch_axis=np.full_like(b.pitch_axis, chord_fraction),
                                section_offset_y=chord_fraction * b.chord, beam=beam)
    return dataclasses.replace(turbine, blade=blade)


def straight_blade(turbine, chord: float = 3.0, chord_fraction: float = 0.375):
    """``turbine`` with a blade of constant chord, no twist and a constant reference-axis chord
    fraction (the 6x6 matrices unchanged): moving its reference axis keeps it straight."""
    b = turbine.blade
    blade = dataclasses.replace(b, chord=np.full_like(b.chord, chord), twist=np.zeros_like(b.twist),
                                pitch_axis=np.full_like(b.pitch_axis, chord_fraction),
                                section_offset_y=np.full_like(b.chord, chord_fraction * chord),
                                beam=dataclasses.replace(b.beam, twist=np.zeros_like(b.beam.twist)))
    return dataclasses.replace(turbine, blade=blade)
