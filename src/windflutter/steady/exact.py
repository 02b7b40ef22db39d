"""The steady state of beam blades on the co-rotational beam: a structure exact for any reference line.

The linear structure of :mod:`windflutter.steady.state` (second-order moments of the aerodynamic
loads, the centrifugal tension's axial geometric stiffness, composed strip rotations) is a good
approximation where the beam's reference line runs near its sections' shear and tension centres.
It is not where the line is far from them: the same straight blade described about 0.375, 0.5 and
0.25 of its chord (IEA 15 MW sections, 10 m/s, ``tests/steady/test_steady_reference_axis.py``) gave
a rotor thrust of 2114 / 2154 / 2079 kN and a tip twist of -5.8 / -5.2 / -6.3 deg, while the
co-rotational beam under the same loads gives -6.37 deg for all three (0.01 deg).  A windIO blade
is described about its pitch axis, a HAWC2 blade about its half chord; for the IEA 15 MW the two
steady states differed by 6 % in thrust.

With ``SteadyOptions(corotational=True)`` (the default for beam-only models; config
``solver.corotational``) the steady state is the equilibrium of the co-rotational
beam (:mod:`windflutter.structure.corotational`, geometrically exact rigid sections):

1. start from the linear steady state (:func:`windflutter.steady.state.steady_state`'s iteration);
2. the strips of the current configuration (:func:`configuration_deflection`: each strip carried
   rigidly by its nodes' finite motions) -> BEM -> strip loads -> nodal loads through the motion
   map with its lever arms turned (:func:`deformed_motion_map`);
3. Newton equilibrium of the co-rotational beam under those loads (held fixed) and the centrifugal
   loads of its deformed rigid sections (:func:`centrifugal_loads`);
4. Aitken-relaxed update of the nodal aerodynamic loads; stop when the strip motions and loads
   change by less than ``tol``.

Units: SI (m, rad, s, N, N m).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.sparse as sp

from windflutter.rotor.rotating import rotating_nodes
from windflutter.rotor.spin import spin_terms
from windflutter.steady.fixedpoint import aitken, strip_change
from windflutter.steady.geometry import Deflection, inner_edges, blade_strips, rotation_matrices, rotation_vectors
from windflutter.structure.assembly import assemble_matrices
from windflutter.structure.corotational import BeamConfiguration, deformed_model, reference_configuration, solve_equilibrium

__all__ = ["centrifugal_loads", "deformed_motion_map", "configuration_deflection", "configuration_displacement"]

#: Newton tolerance of each equilibrium (largest increment: m over the model size, rad)
EQUILIBRIUM_TOL = 1e-10


def centrifugal_loads(fe, omega: float, apex: np.ndarray, axis: np.ndarray, group: str = "rotor") -> Callable:
    """``loads(config) -> (F (n_dof,), dF/dq)``: centrifugal loads of the rotating nodes in a
    configuration (its deformed geometry and mass) and their stiffness ``Omega^2 K_r`` (rigid
    sections: :func:`windflutter.rotor.spin.spin_terms`)."""
    nodes = rotating_nodes(fe, group)

    def loads(config):
        if omega == 0.0:
            return np.zeros(fe.n_dof), None
        fe_c = deformed_model(fe, config)
        M = assemble_matrices(fe_c)[0] if len(fe.shell_conn) else None  # beams: the sections alone
        _, Kr1, f1 = spin_terms(fe_c, M, nodes, axis, apex)
        return omega**2 * f1, omega**2 * Kr1

    return loads


def _blocks(motion_map: sp.spmatrix):
    """(strip, node) pairs of a motion map and their 6x6 blocks ``W``."""
    mm = sp.coo_matrix(motion_map)
    nodes = -(-mm.shape[1] // 6)  # one integer key a (strip, node) pair, in the same order as the pairs:
    keys, inv = np.unique((mm.row // 6).astype(np.int64) * nodes + mm.col // 6, return_inverse=True)
    blocks = np.stack([keys // nodes, keys % nodes], axis=1)  # a row-wise unique took 0.1 s a point
    W = np.zeros((len(blocks), 6, 6))
    np.add.at(W, (inv.ravel(), mm.row % 6, mm.col % 6), mm.data)
    return blocks, W


def deformed_motion_map(motion_map: sp.spmatrix, R: np.ndarray) -> sp.csr_matrix:
    """The strip motion map of the deformed blade: every (strip, node) block ``W`` of a rigid
    transfer ``u_p = u_n + theta_n x (p - x_n)`` turned with the node's rotation ``R[n]``,
    ``blockdiag(R, R) W blockdiag(R, R)^T`` (the lever arm ``p - x_n`` turned by ``R[n]``)."""
    blocks, W = _blocks(motion_map)
    T6 = np.zeros((len(blocks), 6, 6))
    Rn = R[blocks[:, 1]]
    T6[:, :3, :3] = T6[:, 3:, 3:] = Rn
    Wd = T6 @ W @ np.transpose(T6, (0, 2, 1))
    k = np.arange(6)
    rows = (6 * blocks[:, 0])[:, None, None] + k[None, :, None]
    cols = (6 * blocks[:, 1])[:, None, None] + k[None, None, :]
    out = sp.coo_matrix((Wd.ravel(), (np.broadcast_to(rows, Wd.shape).ravel(), np.broadcast_to(cols, Wd.shape).ravel())),
                        shape=motion_map.shape).tocsr()
    out.eliminate_zeros()
    return out


def configuration_deflection(sections, fe, config: BeamConfiguration) -> Deflection:
    """The strips of a beam configuration: strip ``j`` carried rigidly by each node ``n`` it is tied
    to (weight ``w_jn``, the motion map's translation weight), ``p'_j = sum_n w_jn (x_n +
    R_n (p_j - X_n))``, rotation ``exp(sum_n w_jn log R_n)``.  To first order in the motion it is
    the linear ``p + motion_map u`` (finite=False kinematics of :func:`~windflutter.steady.
    geometry.deflection`)."""
    blocks, W = _blocks(sections.motion_map)
    w = W[:, 0, 0]
    ns = sections.n_sections
    p = np.asarray(sections.origin, float)
    X = np.asarray(fe.nodes, float)
    j, n = blocks[:, 0], blocks[:, 1]
    R = np.asarray(config.R, float)
    carried = np.asarray(config.x, float)[n] + np.einsum("kab,kb->ka", R[n], p[j] - X[n])
    origin = np.zeros((ns, 3))
    np.add.at(origin, j, w[:, None] * carried)
    theta = np.zeros((ns, 3))
    np.add.at(theta, j, w[:, None] * rotation_vectors(R[n]))
    Rs = rotation_matrices(theta)
    t = np.asarray(sections.e_span, float)
    t = t / np.linalg.norm(t, axis=1, keepdims=True)
    cut0 = np.empty((ns, 3))
    for idx in blade_strips(sections):
        cut0[idx] = inner_edges(p[idx], t[idx], np.asarray(sections.width, float)[idx])
    cut = origin + np.einsum("jab,jb->ja", Rs, cut0 - p)
    motion = np.hstack([origin - p, theta])
    return Deflection(motion=motion, origin=origin, shift=origin - p, R=Rs, cut0=cut0, cut=cut, R_cut=Rs)


def configuration_displacement(fe, config: BeamConfiguration) -> np.ndarray:
    """(n_dof,) nodal displacement of a configuration: translations and rotation vectors (m, rad)."""
    u = np.zeros(fe.n_dof)
    u.reshape(-1, 6)[:, :3] = np.asarray(config.x, float) - reference_configuration(fe).x
    u.reshape(-1, 6)[:, 3:] = rotation_vectors(np.asarray(config.R, float))
    return u


def iterate_corotational(fe, struct, sections, config: BeamConfiguration, aero_at: Callable, centrifugal: Callable,
                         tol: float, max_iterations: int, relaxation: float = 1.0):
    """Fixed point of the co-rotational equilibrium and the strip loads (module docstring).

    Parameters
    ----------
    fe, struct : the beam model and its assembly (``struct.T`` the constraint map).
    sections : its undeformed strips.
    config : the start (e.g. the chained linear steady displacement).
    aero_at : ``aero_at(deflection, xtol) -> aero`` with ``aero.loads.loads`` (ns, 6) strip loads at
        the deflected strip points (global axes) and ``aero.defl`` the deflection.
    centrifugal : :func:`centrifugal_loads` of the model.
    tol, max_iterations, relaxation : as :class:`~windflutter.steady.SteadyOptions`.

    Returns
    -------
    (config, aero, f_aero, iterations, residual, converged): ``f_aero`` the nodal aerodynamic loads
    (N, N m) of the last equilibrium.
    """
    def nodal(a, c):
        return deformed_motion_map(sections.motion_map, c.R).T @ a.loads.loads.reshape(-1)

    aero = aero_at(configuration_deflection(sections, fe, config), 1e-12)
    f = nodal(aero, config)
    r_prev, w, res = None, relaxation, 1.0
    for it in range(1, max_iterations + 1):
        def external(c, factor, f=f):
            fc, K = centrifugal(c)
            return factor * (fc + f), (None if K is None else factor * K)

        # one Newton step per update of the loads (no exact equilibrium of loads that are still
        # moving); the converged loads get their exact equilibrium
        config = solve_equilibrium(fe, struct.T, external, start=config, tol=np.inf, max_iterations=1,
                                   final=False).config
        new = aero_at(configuration_deflection(sections, fe, config), float(np.clip(1e-3 * res, 1e-12, 1e-5)))
        res = strip_change(new, aero, sections)
        aero = new
        if res <= tol:
            config = solve_equilibrium(fe, struct.T, external, start=config, tol=EQUILIBRIUM_TOL, final=False).config
            return config, aero, f, it, res, True
        r = nodal(new, config) - f  # Aitken-relaxed fixed point on the nodal aerodynamic loads
        w = aitken(w, r, r_prev)
        f, r_prev = f + w * r, r
    return config, aero, f, max_iterations, res, False
