"""Blade pitch as a rigid rotation of an assembled blade model: pay the mesh and assembly once.

Pitching a blade turns it rigidly about its pitch axis (through the blade root and the rotor apex,
along the coned blade axis).  With ``R`` that rotation and ``T_R = blockdiag(R, R)`` per node, the
pitched model's matrices are ``M' = T_R M T_R^T``, ``K' = T_R K T_R^T``, its constraint map
``T' = T_R T`` (same reduced coordinates, so the reduced matrices do not change at all), its nodes,
element axes and strips rotated.  Only what depends on the orientation relative to the shaft --
centrifugal load, spin softening, Coriolis, the steady state -- is computed again (it is, per
operating point).  A shell blade's set-up (loft, laminates, assembly) is then paid once per turbine
instead of once per pitch (issue 17: ~60 s per pitch on the NREL 5 MW shell model).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from windflutter.mesh.frames import blade_placement
from windflutter.structure.assembly import Structural


def pitch_rotation(turbine, pitch: float) -> tuple[np.ndarray, np.ndarray]:
    """``(R, point)``: the rotation (3, 3) from the pitch-0 blade 0 (azimuth 0) to pitch ``pitch``
    (rad, towards feather) and a point of its axis (the blade root)."""
    R0, root = blade_placement(turbine.rotor_apex, turbine.hub.radius, 0.0, turbine.hub.precone, 0.0,
                               turbine.nacelle.shaft_tilt)
    R1, _ = blade_placement(turbine.rotor_apex, turbine.hub.radius, pitch, turbine.hub.precone, 0.0,
                            turbine.nacelle.shaft_tilt)
    return R1 @ R0.T, root


def _node_rotation(n_nodes: int, R: np.ndarray) -> sp.csr_matrix:
    blk = np.zeros((6, 6))
    blk[:3, :3] = blk[3:, 3:] = R
    return sp.kron(sp.identity(n_nodes, format="csr"), sp.csr_matrix(blk), format="csr")


def rotate_blade(fe, struct: Structural, sections, R: np.ndarray, point: np.ndarray, apex=None, axis=None):
    """The model ``(fe, struct, sections)`` turned rigidly by ``R`` about ``point`` (m); the strips'
    radii from the shaft (``apex``, unit ``axis``) are recomputed when those are given."""
    point = np.asarray(point, float)
    TR = _node_rotation(fe.n_nodes, R)
    nodes = point[None, :] + (np.asarray(fe.nodes, float) - point[None, :]) @ R.T
    fe2 = replace(fe, nodes=nodes, shell_matdir=np.asarray(fe.shell_matdir) @ R.T,
                  beam_orient=np.asarray(fe.beam_orient) @ R.T,
                  masses=[replace(m, inertia=R @ np.asarray(m.inertia) @ R.T, offset=R @ np.asarray(m.offset))
                          for m in fe.masses],
                  diaphragms=[replace(d, normal=R @ np.asarray(d.normal, float)) for d in fe.diaphragms])
    st2 = Structural(fe=fe2, M=(TR @ struct.M @ TR.T).tocsr(), K=(TR @ struct.K @ TR.T).tocsr(),
                     T=(TR @ struct.T).tocsr(), free_dofs=struct.free_dofs, auto_spc=struct.auto_spc)
    st2.__dict__["Kr"], st2.__dict__["Mr"] = struct.Kr, struct.Mr  # unchanged (same coordinates)
    ns = sections.n_sections
    TS = _node_rotation(ns, R)
    origin = point[None, :] + (np.asarray(sections.origin) - point[None, :]) @ R.T
    radius = sections.radius
    if apex is not None and axis is not None:
        rel = origin - np.asarray(apex, float)[None, :]
        n = np.asarray(axis, float)
        radius = np.linalg.norm(rel - (rel @ n)[:, None] * n[None, :], axis=1)
    sec2 = replace(sections, origin=origin, radius=radius,
                   e_chord=np.asarray(sections.e_chord) @ R.T, e_span=np.asarray(sections.e_span) @ R.T,
                   motion_map=(TS @ sections.motion_map @ TR.T).tocsr())
    return fe2, st2, sec2
