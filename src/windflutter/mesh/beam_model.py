"""One blade as 2-node Timoshenko beams along its reference axis (blade root frame)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from windflutter.errors import InputError
from windflutter.mesh.blade_shell import station_positions
from windflutter.mesh.loft import chord_frame
from windflutter.mesh.section_props import thin_walled_properties
from windflutter.model.turbine import interp_span
from windflutter.structure.fem import BeamSection


@dataclass
class BladeBeamMesh:
    """Beam blade in the root frame: ``nodes`` (n_st, 3) on the reference axis, ``conn`` (ne, 2),
    ``sections`` (one per element), ``orient`` (ne, 3) section y axis (flapwise, with twist)."""

    nodes: np.ndarray
    conn: np.ndarray
    sections: list[BeamSection]
    orient: np.ndarray
    eta: np.ndarray


SHEAR_RIGID_FACTOR = 1e3  # shear stiffness = factor x EA where a 6x6 gives none


def shear_rigid_where_missing(K: np.ndarray) -> np.ndarray:
    """(n, 6, 6) section stiffness with zero/negative shear terms K[1,1], K[2,2] replaced by
    ``SHEAR_RIGID_FACTOR * EA``: windIO 6x6 tables from WISDEM leave the shear stiffness 0,
    meaning an Euler-Bernoulli (shear-rigid) section."""
    K = np.array(K, dtype=float, copy=True)
    for c in (1, 2):
        bad = K[:, c, c] <= 0
        K[bad, c, c] = SHEAR_RIGID_FACTOR * np.abs(K[bad, 0, 0])
    return K


def blade_beam_properties(turbine):
    """The blade's 6x6 properties: from the turbine file if given, else thin-walled sections of
    the shell layup (:func:`windflutter.mesh.section_props.thin_walled_properties`)."""
    if turbine.blade.beam is not None:
        return turbine.blade.beam
    if turbine.blade.layup is None:
        raise InputError("blade.beam", None, "6x6 beam properties or a composite layup for the beam model")

    return thin_walled_properties(turbine)


def blade_beam_mesh(blade, n_span: int, clustering: float = 0.0, props=None) -> BladeBeamMesh:
    """Beam elements between ``n_span + 1`` stations; each element takes the 6x6 stiffness and
    mass of ``props`` (default :attr:`Blade.beam`) averaged over its length (Simpson rule on the piecewise-linear
    tables), and the section y axis turned by the structural twist at its midpoint.
    """
    bp = props if props is not None else blade.beam
    if bp is None:
        raise InputError("blade.beam", None, "6x6 beam properties (windIO elastic_properties or BeamDyn) for the beam model")
    eta = station_positions(n_span, clustering)
    nodes = np.column_stack([np.interp(eta, blade.s, blade.ref_axis[:, c]) for c in range(3)])
    conn = np.column_stack([np.arange(n_span), np.arange(1, n_span + 1)])
    a, b = eta[:-1], eta[1:]
    m = 0.5 * (a + b)

    def avg(v: np.ndarray) -> np.ndarray:
        return (interp_span(bp.s, v, a) + 4 * interp_span(bp.s, v, m) + interp_span(bp.s, v, b)) / 6.0

    K = shear_rigid_where_missing(avg(bp.stiffness))
    M = avg(bp.mass)
    tw = np.interp(m, bp.s, bp.twist)
    _, e_n = chord_frame(tw)
    secs = [BeamSection(stiffness=0.5 * (K[e] + K[e].T), mass=0.5 * (M[e] + M[e].T), name=f"blade_{e}") for e in range(n_span)]
    return BladeBeamMesh(nodes=nodes, conn=conn, sections=secs, orient=e_n, eta=eta)
