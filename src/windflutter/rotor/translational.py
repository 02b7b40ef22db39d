"""Rotating-frame terms of translational mass: the Coriolis matrix and the spin softening of point
masses (the seed's frozen-azimuth model, :mod:`windflutter.rotor.rotating`, and the lumped masses of
:mod:`windflutter.rotor.spin`).  A module of its own so that both import it at the top (they
imported each other inside functions)."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from windflutter.errors import InputError
from windflutter.linalg_tools import skew


def spin_operator(n_nodes: int, omega_vec: np.ndarray) -> sp.csr_matrix:
    """``blockdiag(S, ..., S)`` (``n_nodes`` blocks) with ``S = [omega]x``: the cross product with the
    rotor speed vector of every node's translation."""
    return sp.kron(sp.identity(n_nodes, format="csr"), sp.csr_matrix(skew(omega_vec)), format="csr")


def coriolis_and_softening(M: sp.spmatrix, dofs: np.ndarray, omega_vec: np.ndarray):
    """G and Kr (n_dof x n_dof sparse) from the translational mass of the DOFs ``dofs``.

    Parameters
    ----------
    M : (n_dof, n_dof) structural mass matrix (kg), unconstrained numbering.
    dofs : translational DOFs of the rotating part, node-major triplets (ux, uy, uz).
    omega_vec : rotor speed vector (rad/s).
    """
    n = M.shape[0]
    dofs = np.asarray(dofs, dtype=np.int64)
    if dofs.size % 3:
        raise InputError("dofs", dofs.size, "triplets of translational DOFs")
    Mt = sp.csr_matrix(M)[dofs][:, dofs]
    S = spin_operator(dofs.size // 3, np.asarray(omega_vec, float))
    Gt = (Mt @ S + S @ Mt).tocoo()
    Krt = (S.T @ Mt @ S).tocoo()

    def expand(A):
        return sp.csr_matrix((A.data, (dofs[A.row], dofs[A.col])), shape=(n, n))

    return expand(Gt), expand(Krt)
