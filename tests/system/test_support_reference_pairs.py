"""The support's reference modes on a degenerate fore-aft / side-side pair (system/reference.py).

An axisymmetric tower's pair (the shell tower's 2.228, 3.053 and 4.585 Hz pairs on the IEA 22 MW) comes
out of the eigen-solver in any rotation within its eigen-space.  The reference named each vector by the
direction its arbitrary rotation leaned to, so two identical runs named the 4.585 Hz pair "4th / 5th
tower side-side" once and "7th tower fore-aft" / "4th tower side-side" the next.  Now the pair is turned
onto its directions first (:func:`windflutter.structure.modal.split_directions`): for every rotation the
solver may return, the names are those of the directions solved on their own, and each reference shape
is one direction's (the other direction's motion below 1e-9 of it)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.system import reference

K2 = np.array([[2.0, -1.0], [-1.0, 1.0]]) * 4e6  # N/m: two tower levels in one direction
M2 = np.diag([2e4, 1e4])  # kg


def _support():
    """Two nodes of 6 DOFs; coordinates (x1, y1, x2, y2): x fore-aft, y side-side."""
    K, M = np.zeros((4, 4)), np.zeros((4, 4))
    for d in (0, 1):
        K[d::2, d::2], M[d::2, d::2] = K2, M2
    expand = np.zeros((12, 4))
    for node in (0, 1):
        for d in (0, 1):
            expand[6 * node + d, 2 * node + d] = 1.0
    masses = np.repeat(np.diag(M2), 6)
    return SimpleNamespace(K=K, M=M, expand=sp.csr_matrix(expand), struct=SimpleNamespace(M=sp.diags(masses)))


@pytest.mark.parametrize("angle", [0.0, 10.0, 45.0, 73.0, 90.0])
def test_a_degenerate_tower_pair_is_named_by_its_directions_whatever_the_solvers_rotation(monkeypatch, angle):
    sup = _support()
    w2, V = reference.symmetric_eigs(sup.K, sup.M)
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    R = np.eye(4)
    for i in (0, 2):  # each pair turned within its eigen-space
        R[i:i + 2, i:i + 2] = [[c, -s], [s, c]]
    real = reference.symmetric_eigs
    monkeypatch.setattr(reference, "symmetric_eigs",
                        lambda K_, M_: (w2, V @ R) if np.shape(K_) == sup.K.shape else real(K_, M_))
    named, Phi, _ = reference.support_reference(sup)
    assert [(fam, order) for fam, order, _ in named] == [("tower_fa", 1), ("tower_ss", 1), ("tower_fa", 2),
                                                         ("tower_ss", 2)]
    for k, (fam, _, _) in enumerate(named):
        own, other = (0, 1) if fam == "tower_fa" else (1, 0)
        v = Phi[:, k]
        assert np.sum(v[other::2] ** 2) < 1e-9 * np.sum(v[own::2] ** 2)
