"""One rotor blade as a substructure in its own rotating frame (Craig-Bampton, rigid interface).

The blade (beam or shell) sits on the hub node at the rotor apex (``MeshSettings(part=
"rotor_blade")``): blade 0 at azimuth 0, so its rotating frame coincides with the global frame at
``t = 0``.  Its displacement in the rotating frame is

    ``w = Gamma h + T Phi eta``

with ``h`` (6) the rigid motion of the hub (translation, rotation about the apex, rotating-frame
components), ``Gamma`` the blade's rigid-body modes about the apex and ``Phi`` a basis of the
fixed-interface (hub clamped) blade: structural modes plus aerodynamic static corrections, or the
identity (full order).  For a rigid interface the constraint modes of Craig-Bampton are exactly
``Gamma``, so nothing is lost at the interface.

Rotating-frame terms (:mod:`windflutter.rotor.rotating`) act on the TOTAL rotating-frame
displacement ``w``: the Coriolis ``Omega G1`` and the spin softening ``Omega^2 Kr1`` (translational
masses) and the geometric stiffness of the steady stress, ``Ksigma``. With this, a hub displacement
that is at rest in the ground-fixed frame produces no inertial force (checked in the tests). The
elastic stiffness and the structural damping act on ``eta`` only.


The hub link carries the root reaction: under tension ``T`` a link of length ``r_hub`` has the
geometric stiffness ``T r_hub`` of a tensioned bar for rotations of the hub
(:func:`link_geometric_stiffness`); without it a rigid rotation of the rotor about the shaft
would not be a zero-stiffness motion (the "drivetrain" rigid-body mode, tested).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.rotor.spin import spin_terms
from windflutter.structure.assembly import rigid_body_vectors
from windflutter.structure.prestress import geometric_stiffness, static_solve
from windflutter.structure.shell import shell_element_blocks


def axis_skew_translations(n_nodes: int, axis: np.ndarray) -> sp.csr_matrix:
    """(6 n, 6 n) sparse ``S_t``: ``skew(axis)`` on the translations of every node, 0 on rotations.

    ``Omega S_t w`` is the velocity a rotating-frame displacement ``w`` adds to a point of a body
    spinning at ``Omega`` about ``axis`` (the transport velocity seen by the air).
    """
    a = np.asarray(axis, float)
    S = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    blk = np.zeros((6, 6))
    blk[:3, :3] = S
    return sp.kron(sp.identity(n_nodes, format="csr"), sp.csr_matrix(blk), format="csr")


def link_geometric_stiffness(fe, link_forces: np.ndarray, hub_node: int) -> np.ndarray:
    """(3, 3) geometric stiffness (N m/rad) of the rigid hub links for rotations of the hub.

    ``link_forces`` (n_dof,): the structure's internal nodal forces minus the loads of the static
    state, nonzero only where the links act: ``K u0 - F`` of a linear solution, ``f_int - f_ext``
    of a co-rotational equilibrium; ``f`` below is its force at each dependent node ``B``.  A rigid link from the hub ``A`` to ``B`` carrying them rotates with the
    hub; its second-order (tensioned-bar) energy is ``1/2 theta^T (tr(S) I - S) theta`` with the
    virial ``S = -sum_B sym(d_B f_B^T)``, ``d_B = x_B - x_A`` (``T L (I - e e^T)`` for a tension
    ``T`` along ``e``).  The links' transmitted moments are not included.
    """
    r = np.asarray(link_forces, float).reshape(-1, 6)
    xa = np.asarray(fe.nodes[hub_node], float)
    S = np.zeros((3, 3))
    for link in fe.rigid_links:
        if int(link.independent) != int(hub_node):
            continue
        dep = np.asarray(link.dependent, dtype=np.int64)
        d = np.asarray(fe.nodes[dep], float) - xa
        f = r[dep, :3]
        S -= 0.5 * (d.T @ f + f.T @ d)
    return np.trace(S) * np.eye(3) - S


@dataclass
class BladeMatrices:
    """A blade's matrices in its coordinates ``y = (h, eta)`` per unit rotor speed.

    ``M`` mass; ``G1`` Coriolis per rad/s; ``Ke`` elastic stiffness (eta block only); ``Kr1`` spin
    softening per (rad/s)^2; ``Ks1`` geometric stiffness of the centrifugal prestress per
    (rad/s)^2 incl. the hub-link term; ``D`` structural damping (eta block only).  Dense
    ``(6 + m, 6 + m)``, SI.
    """

    M: np.ndarray
    G1: np.ndarray
    Ke: np.ndarray
    Kr1: np.ndarray
    Ks1: np.ndarray
    D: np.ndarray

    def at(self, omega: float, ksigma: np.ndarray | None = None):
        """``(M, C, K)`` at rotor speed ``omega`` (rad/s); ``ksigma`` replaces ``omega^2 Ks1`` (a
        steady state with aerodynamic loads)."""
        Ks = omega**2 * self.Ks1 if ksigma is None else ksigma
        return self.M, self.D + omega * self.G1, self.Ke + Ks - omega**2 * self.Kr1


class RotorBlade:
    """The fixed-interface blade substructure and its reduced matrices.

    Parameters
    ----------
    fe, struct : the ``rotor_blade`` model (hub node clamped) and its assembly.
    sections : the blade's aerodynamic strips.
    apex : (3,) rotor apex (m); ``axis`` : (3,) unit shaft axis (rotor speed vector direction).
    damping : optional full-numbering structural damping matrix (N s/m).
    shell_blocks : the shell elements' ``(K, M)`` blocks when known (:meth:`shell_blocks`; a pitched
        copy's are the pitch-0 blade's turned), else computed on first use.
    """

    def __init__(self, fe, struct, sections, apex, axis, damping=None, shell_blocks=None):
        self.fe, self.struct, self.sections = fe, struct, sections
        self.apex = np.asarray(apex, float)
        self.axis = np.asarray(axis, float) / np.linalg.norm(axis)
        if "hub" not in fe.node_groups or len(fe.node_groups["hub"]) != 1:
            raise InputError("fe.node_groups['hub']", fe.node_groups.get("hub"), "one hub node (part rotor_blade)")
        self.hub_node = int(fe.node_groups["hub"][0])
        self.Gamma = rigid_body_vectors(fe.nodes, center=self.apex)
        self.G1, self.Kr1, self._f1 = spin_terms(fe, struct.M, np.arange(fe.n_nodes), self.axis, self.apex)
        self.damping = damping
        self.St = axis_skew_translations(fe.n_nodes, self.axis)
        self._unit_prestress = None
        self._shell_blocks = shell_blocks

    def shell_blocks(self) -> tuple[np.ndarray, np.ndarray]:
        """``(K, M)`` (ne, 24, 24): the shell elements' stiffness and consistent mass blocks of this
        blade in global axes (:func:`~windflutter.structure.shell.shell_element_blocks`), computed
        once: a deflected shell blade carries them with its elements
        (:mod:`windflutter.system.deflected_shell`)."""
        if self._shell_blocks is None:
            self._shell_blocks = shell_element_blocks(self.fe)
        return self._shell_blocks

    # -- prestress ---------------------------------------------------------------------------
    def centrifugal_load(self, omega: float = 1.0) -> np.ndarray:
        """Centrifugal nodal loads (N, N m) at ``omega`` (rad/s), full numbering: the rigid sections'
        (:func:`windflutter.rotor.spin.spin_terms`)."""
        return omega**2 * self._f1

    def prestress(self, load: np.ndarray):
        """``(Ksigma (full, sparse), Klink (3, 3), u0)`` of the static state under ``load`` (N)."""
        u0 = static_solve(self.struct, load) if self.struct.nq else np.zeros(self.fe.n_dof)
        cf = self.struct.K @ u0 - load
        Kg = geometric_stiffness(self.fe, u0, constraint_forces=cf)
        Kl = link_geometric_stiffness(self.fe, cf, self.hub_node)
        return Kg, Kl, u0

    def unit_prestress(self):
        """``prestress`` of the centrifugal load at 1 rad/s (cached)."""
        if self._unit_prestress is None:
            self._unit_prestress = self.prestress(self.centrifugal_load(1.0))
        return self._unit_prestress

    # -- reduction ---------------------------------------------------------------------------
    def basis_full(self, Phi_q: np.ndarray | None) -> np.ndarray | sp.spmatrix:
        """``B = [Gamma, T Phi]`` (full numbering); ``Phi_q`` None: full order (T itself)."""
        TP = self.struct.T if Phi_q is None else self.struct.T @ Phi_q
        if sp.issparse(TP):
            return sp.hstack([sp.csr_matrix(self.Gamma), TP]).tocsr()
        return np.hstack([self.Gamma, np.asarray(TP)])

    def project(self, A, B):
        """``B^T A B`` as a dense array."""
        out = B.T @ (A @ B)
        return out.toarray() if sp.issparse(out) else np.asarray(out)

    def matrices(self, Phi_q: np.ndarray | None = None, ksigma_full=None, klink=None) -> BladeMatrices:
        """The blade's :class:`BladeMatrices` on the basis ``Phi_q`` (fixed-interface coordinates).

        ``ksigma_full``/``klink`` per (rad/s)^2 default to the centrifugal unit prestress.
        """
        B = self.basis_full(Phi_q)
        if ksigma_full is None:
            ksigma_full, klink, _ = self.unit_prestress()
        st = self.struct
        Me = self.project(st.M, B)
        Ke = self.project(st.K, B)
        Ks = self.project(ksigma_full, B)
        Ks[3:6, 3:6] += klink
        D = self.project(self.damping, B) if self.damping is not None else np.zeros_like(Me)
        for A in (Ke, D):  # elastic terms act on the deformation only
            A[:6, :] = 0.0
            A[:, :6] = 0.0
        return BladeMatrices(M=Me, G1=self.project(self.G1, B), Ke=0.5 * (Ke + Ke.T), Kr1=self.project(self.Kr1, B),
                             Ks1=0.5 * (Ks + Ks.T), D=0.5 * (D + D.T))
