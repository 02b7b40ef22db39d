"""Rotating-frame terms of rigid sections: mass-centre offsets and rotary inertia included.

:mod:`windflutter.rotor.rotating` builds the Coriolis and spin-softening matrices from the
translational mass alone, exact for point masses on their nodes (shell nodes).  A beam section or a
lumped mass is a rigid body attached to its node: a material point at ``s`` from the node (section
frame) moves by ``d = u + theta x s + 1/2 theta x (theta x s)`` (second order in the rotation).
Its kinetic energy in a frame spinning at ``Omega``,
``T = 1/2 int |d' + Omega x (X + s + d)|^2 dm``, gives per section, with ``B = [I, -S(s)]``,

* Coriolis ``G = int B^T 2 S(Omega) B dm``;
* spin softening ``Kr = int B^T P B dm + [[0, 0], [0, A]]``, ``P = S(Omega)^T S(Omega)``, where
  ``A = int sym(F s^T) - (F . s) I dm`` with ``F = P (X + s)`` the centrifugal acceleration is the
  stiffness of the centrifugal force on an offset point turned by the section's rotation (the
  second-order term of ``d``): for a point at ``s`` radially outside a hinge at radius ``r`` the two
  parts give the lead-lag pendulum ``omega^2 = Omega^2 r / s``;
* centrifugal load ``f = int B^T F dm`` (force ``m P (X + c)``, moment ``S(c) m P X + int S(s) P s dm``).

Every integral needs only the section's mass ``m``, first moment ``m c`` and second moment
``Q = int s s^T dm = tr(J)/2 I - J``, all in the 6x6 rigid-body mass ``[[m I, -m S(c)], [m S(c), J]]``
(``J`` about the node) -- the beam sections' and the lumped masses' own matrices.  The beam
elements integrate them with the element's section-motion interpolation (the consistent mass's,
4-point Gauss along the element), so the offsets' centrifugal and Coriolis couplings of bending and
torsion (the ``m Omega^2 x e w'`` "tension offset" term of the Hodges-Dowell torsion equation) and
the slope DOFs' share of the translational inertia are all present.  The centrifugal load is
lumped on the element's nodes (linear weights, forces on translations and moments on rotations):
consistent loads would turn the sections' distributed moment ``S(c) m P X`` into transverse nodal
forces, which the element reads as a shear force that is not there, and the initial-stress matrix
of that shear (``geometric_stiffness(moments=True)``, the deflected blade's) then couples torsion
and flap wrongly by an amount that does not shrink with the mesh (measured: the torsion-flap term
of the beam of the tests at half its value, with the opposite sign).  Every other mass (shells)
keeps the translational terms.  Tested against point masses on rigid links (a model that shares none of
this code) in ``tests/solver/test_section_spin.py``.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.linalg_tools import skew
from windflutter.rotor.translational import coriolis_and_softening
from windflutter.structure.assembly import coo_matrix_of, lumped_mass_matrices
from windflutter.structure.beam import beam_section_integrals
from windflutter.structure.fem import FEModel

_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0


def inertia_moments(Ms: np.ndarray):
    """Mass ``m`` (...,), first moment ``mc`` (..., 3) and second moment ``Q`` (..., 3, 3) of
    rigid-body 6x6 mass matrices ``Ms`` (..., 6, 6) about their reference point."""
    Ms = np.asarray(Ms, float)
    m = Ms[..., 0, 0]
    Smc = 0.5 * (Ms[..., 3:, :3] - np.swapaxes(Ms[..., 3:, :3], -1, -2))  # m S(c)
    mc = np.stack([Smc[..., 2, 1], Smc[..., 0, 2], Smc[..., 1, 0]], axis=-1)
    J = 0.5 * (Ms[..., 3:, 3:] + np.swapaxes(Ms[..., 3:, 3:], -1, -2))
    tr = np.trace(J, axis1=-2, axis2=-1)
    Q = 0.5 * tr[..., None, None] * np.eye(3) - J
    return m, mc, Q


def _sandwich(A: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """``int S(s) A S(s) dm`` (..., 3, 3) from the second moment ``Q`` (..., 3, 3)."""
    # S(s)_ik = eps_ilk s_l:  (S A S)_ij = eps_ilk A_km eps_mnj s_l s_n
    return np.einsum("ilk,...km,mnj,...ln->...ij", _EPS, A, _EPS, Q)


def section_spin(m, mc, Q, omega_unit: np.ndarray, X: np.ndarray):
    """Per-section 6x6 Coriolis ``G`` (per rad/s) and softening ``Kr`` (per (rad/s)^2) and the
    centrifugal load ``f`` (6,) (per (rad/s)^2), all in the sections' frame.

    Parameters
    ----------
    m, mc, Q : :func:`inertia_moments` of the sections (kg, kg m, kg m^2; per metre for beams).
    omega_unit : (..., 3) unit rotor-speed vector in the sections' frame.
    X : (..., 3) position of the reference point from a point on the spin axis (m), same frame.
    """
    W, Sc = skew(np.stack(np.broadcast_arrays(omega_unit, mc)))  # S(omega), m S(c)
    P = np.swapaxes(W, -1, -2) @ W
    m_ = np.asarray(m, float)[..., None, None]

    def blocks(A):
        out = np.zeros(A.shape[:-2] + (6, 6))
        out[..., :3, :3] = m_ * A
        out[..., :3, 3:] = -A @ Sc
        out[..., 3:, :3] = Sc @ A
        out[..., 3:, 3:] = -_sandwich(A, Q)
        return out

    shape = np.broadcast_shapes(np.shape(X)[:-1], np.shape(m)) + (6, 6)  # (Gauss points and) sections
    G = np.broadcast_to(blocks(2.0 * W), shape)
    Kr = np.broadcast_to(blocks(P), shape).copy()
    PX = np.einsum("...ij,...j->...i", P, X)
    FsT = np.einsum("...i,...j->...ij", PX, mc) + P @ Q  # int F s^T dm
    Fs = np.einsum("...i,...i->...", PX, mc) + np.trace(P @ Q, axis1=-2, axis2=-1)
    Kr[..., 3:, 3:] += 0.5 * (FsT + np.swapaxes(FsT, -1, -2)) - Fs[..., None, None] * np.eye(3)
    f = np.zeros(np.shape(X)[:-1] + (6,))
    f[..., :3] = np.asarray(m, float)[..., None] * PX + np.einsum("...ij,...j->...i", P, mc)
    f[..., 3:] = np.einsum("...ij,...j->...i", Sc, PX) + np.einsum("ilk,...km,...lm->...i", _EPS, P, Q)
    return G, Kr, f


def _beam_terms(fe: FEModel, spin: np.ndarray, axis: np.ndarray, center: np.ndarray):
    """(G, Kr, f, M, dofs) of the rotating beam elements ``spin`` (mask), global axes; ``M`` is the
    elements' consistent mass (the same quadrature as :mod:`windflutter.structure.beam`'s)."""
    # the section masses as assembled (validated there); symmetric part
    Ms = np.array([np.asarray(fe.beam_sections[i].mass, float) for i in np.asarray(fe.beam_section)[spin]])
    Ms = 0.5 * (Ms + np.swapaxes(Ms, -1, -2))
    m, mc, Q = inertia_moments(Ms)

    def sections(X, R):
        Gs, Ks, fs = section_spin(m, mc, Q, np.einsum("eij,j->ei", R, axis), X)
        return np.stack(np.broadcast_arrays(Gs, Ks, Ms[None])), fs

    (G, Kr, Me), f, dofs = beam_section_integrals(fe, spin, sections, center)
    return G, Kr, f, Me, dofs


def _lumped_terms(fe: FEModel, rotating: np.ndarray, axis: np.ndarray, center: np.ndarray):
    """(G, Kr, f, M, dofs) of the lumped masses on rotating nodes (6x6 per mass, global axes)."""
    Me, dofs = lumped_mass_matrices(fe)
    nodes = dofs[:, 0] // 6
    keep = np.isin(nodes, rotating)
    m, mc, Q = inertia_moments(Me[keep])
    X = np.asarray(fe.nodes, float)[nodes[keep]] - np.asarray(center, float)
    G, Kr, f = section_spin(m, mc, Q, np.broadcast_to(axis, X.shape), X)
    return G, Kr, f, Me[keep], dofs[keep]


def _sparse(mats: tuple[np.ndarray, ...], dofs: np.ndarray, n: int) -> list[sp.csr_matrix]:
    """Each of ``mats`` (element matrices on the same ``dofs``) as a sparse (n, n) matrix."""
    r, c, _ = coo_matrix_of(mats[0], dofs)
    return [sp.csr_matrix((A.reshape(-1), (r, c)), shape=(n, n)) for A in mats]


def spin_terms(fe: FEModel, M: sp.spmatrix | None, nodes: np.ndarray, axis: np.ndarray, center: np.ndarray):
    """``(G1, Kr1, f1)``: Coriolis (per rad/s), spin softening and centrifugal load (per (rad/s)^2)
    of the rotating nodes ``nodes`` about ``axis`` (unit) through ``center`` (m), full numbering.

    Beam elements with both nodes rotating and lumped masses on rotating nodes are rigid sections
    (module docstring); the rest of ``M`` (shells) enters by its translational block.  ``M`` may be
    None for a model of beams and lumped masses only (nothing else carries mass).
    """

    axis = np.asarray(axis, float)
    if not np.isclose(np.linalg.norm(axis), 1.0, atol=1e-6):
        raise InputError("rotor.shaft_axis", axis.tolist(), "a unit vector")
    if M is None and len(fe.shell_conn):
        raise InputError("M", None, "the mass matrix of a model with shells")
    n = fe.n_dof
    nodes = np.unique(np.asarray(nodes, dtype=np.int64))
    parts = []  # (G, Kr, f, M, dofs) per element of the rigid sections
    if len(fe.beam_conn):
        spin = np.isin(np.asarray(fe.beam_conn, dtype=np.int64), nodes).all(axis=1)
        if spin.any():
            parts.append(_beam_terms(fe, spin, axis, center))
    if fe.masses:
        lt = _lumped_terms(fe, nodes, axis, center)
        if len(lt[4]):
            parts.append(lt)
    G1 = Kr1 = sp.csr_matrix((n, n))
    f1 = np.zeros(n)
    sparse = [_sparse((Ge, Ke, Me), de, n) for Ge, Ke, _, Me, de in parts]
    if M is not None:
        rest = sp.csr_matrix(M).copy()
        for _, _, Ms in sparse:
            rest = rest - Ms
        scale = abs(sp.csr_matrix(M)).max() if sp.csr_matrix(M).nnz else 1.0
        rest.data[np.abs(rest.data) <= 1e-12 * scale] = 0.0
        rest.eliminate_zeros()
        if rest.nnz:
            G1, Kr1 = coriolis_and_softening(rest, (6 * nodes[:, None] + np.arange(3)[None, :]).ravel(), axis)
            X = np.zeros(n)
            X.reshape(-1, 6)[nodes, :3] = np.asarray(fe.nodes, float)[nodes] - np.asarray(center, float)
            f1 = np.asarray(Kr1 @ X)
    for (Gs, Ks, _), (_, _, fe_, _, de) in zip(sparse, parts):
        G1, Kr1 = G1 + Gs, Kr1 + Ks
        np.add.at(f1, de.ravel(), fe_.ravel())
    return (0.5 * (G1 - G1.T)).tocsr(), (0.5 * (Kr1 + Kr1.T)).tocsr(), f1


def beam_spin_elements(fe: FEModel, axis: np.ndarray, center: np.ndarray):
    """``(G1, Kr1, dofs)`` of every beam element of ``fe`` as a rigid-section rotating element, global
    axes: (nb, 12, 12) Coriolis per rad/s and spin softening per (rad/s)^2, (nb, 12) global DOFs --
    the element terms :func:`spin_terms` sums (before its final symmetrization), for derivatives
    element by element (:mod:`windflutter.sensitivity`)."""
    G, Kr, _, _, dofs = _beam_terms(fe, np.ones(len(fe.beam_conn), dtype=bool), np.asarray(axis, float), center)
    return G, Kr, dofs
