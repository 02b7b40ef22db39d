"""The beam section of a shell blade at one station, free of end effects (issue 33 item 3).

:mod:`windflutter.mesh.shell_beam` cuts a segment of the blade a chord or so either side of a station
and loads it through rigid end rings.  Those rings restrain the warping and the in-plane deformation
of the thin-walled section, which decay slowly along the span: on a closed box the torsion stiffness
and the shear centre come out 2-4 % off, and on a blade the torsion-related terms move with the
distance of the ends (docs/mesh.md).

Here the section is read where nothing restrains it.  The ring of shell nodes on the station's plane
and the row of elements that starts there (skin and webs, with their laminates, material directions
and reference-surface offsets) are extruded straight along the reference axis into a prismatic
piece; between two of its rings :func:`~windflutter.structure.equivalent_beam.section_properties`
with periodic ends gives the axial, torsion and bending stiffness, their couplings and the tension
and shear centres of exactly that section (the Saint-Venant state, no end, no taper), and the
elements between the rings its mass per length, mass centre and inertia.  Only the transverse
shear block is read through the prism's rigid ends.  This is what a cross-section code does with a
2-D mesh of the section; here the section is the shell model's own.

Units: SI.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.equivalent_beam import SectionProperties, section_properties
from windflutter.structure.fem import FEModel

__all__ = ["extruded_station", "station_section"]

#: the prism's half length on either side of the reading rings, in chords (its rigid ends, which give
#: only the transverse shear block, this far from the rings)
PRISM_CHORDS = 1.5


def extruded_station(fe: FEModel, st: np.ndarray, on: np.ndarray, j: int, ref: np.ndarray, e1: np.ndarray,
                     step: float, rows: int) -> tuple[FEModel, np.ndarray]:
    """The prism of station ``j``: ``(model, rings)`` with ``rings`` (rows + 1, n) the node indices of
    each ring, ring ``k`` the station's nodes, projected on the plane through ``ref`` normal to the unit
    vector ``e1``, moved ``k step`` along ``e1``.

    ``st``, ``on``: each node's station and whether it lies on the station's plane
    (:func:`~windflutter.mesh.shell_beam.station_planes`).  The elements are those between station
    ``j`` and ``j + 1`` (``j - 1`` and ``j`` at the last station), each node of the other station
    replaced by its partner on station ``j`` along the elements' spanwise edges."""
    conn = np.asarray(fe.shell_conn)
    here = np.flatnonzero(on & (st == j))
    other = j + 1 if j + 1 <= st.max() else j - 1
    there = on & (st == other)
    row = np.all(np.isin(conn, here) | there[conn], axis=1) & np.any(there[conn], axis=1) & \
        np.any(np.isin(conn, here), axis=1)
    quads = conn[row]
    if not len(here) or not len(quads):
        raise InputError("station", j, "a station with a ring of shell nodes and a row of elements beside it")
    slot = -np.ones(fe.n_nodes, dtype=np.int64)
    slot[here] = np.arange(len(here))
    partner = -np.ones(fe.n_nodes, dtype=np.int64)
    for c in range(4):  # the spanwise edges (c, c+1): one end on each station
        p, q = quads[:, c], quads[:, (c + 1) % 4]
        for a, b in ((p, q), (q, p)):
            sel = (slot[a] >= 0) & there[b]
            partner[b[sel]] = a[sel]
    if np.any((partner[quads] < 0) & there[quads]):
        raise InputError("station", j, "a row of elements whose every node off the station has a partner on it")
    # each element's nodes as (ring offset, slot): the station's own at offset 0, the others at 1
    far = there[quads]
    ring_of = far.astype(np.int64) if other > j else (~far).astype(np.int64)
    slots = np.where(far, slot[np.where(far, partner[quads], 0)], slot[quads])
    n = len(here)
    X0 = np.asarray(fe.nodes, float)[here]
    X0 = X0 - np.outer((X0 - np.asarray(ref, float)) @ e1, e1)
    nodes = np.vstack([X0 + k * step * np.asarray(e1, float) for k in range(rows + 1)])
    cells = np.concatenate([(k + ring_of) * n + slots for k in range(rows)])
    m = len(quads)
    prism = FEModel(nodes=nodes, shell_conn=cells, shell_prop=np.tile(np.asarray(fe.shell_prop)[row], rows),
                    shell_matdir=np.tile(np.asarray(fe.shell_matdir)[row], (rows, 1)),
                    shell_properties=list(fe.shell_properties), shell_shear=fe.shell_shear)
    assert prism.shell_conn.shape == (rows * m, 4)
    return prism, np.arange((rows + 1) * n).reshape(rows + 1, n)


def station_section(fe: FEModel, st: np.ndarray, on: np.ndarray, j: int, ref: np.ndarray, e1: np.ndarray,
                    e2: np.ndarray, chord: float) -> SectionProperties:
    """The section of station ``j`` about the reference point ``ref`` (module docstring): the prism of
    :func:`extruded_station`, ``PRISM_CHORDS`` either side of a one-step cell, steps of a tenth of the
    chord."""
    e1 = np.asarray(e1, float) / np.linalg.norm(e1)
    step = 0.1 * float(chord)
    half = int(np.ceil(PRISM_CHORDS / 0.1))
    ref = np.asarray(ref, float)
    prism, rings = extruded_station(fe, st, on, j, ref, e1, step, 2 * half + 1)
    # the reference points of the reading rings: the station's on its ring, moved with the prism
    refs = (ref + half * step * e1, ref + (half + 1) * step * e1)
    return section_properties(prism, rings[0], rings[-1], (rings[half], rings[half + 1]), refs, axis=e1, e2=e2,
                              ends="periodic")
