"""The files' tower modal ratios on a degenerate fore-aft / side-side pair (system/damping.py)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla

from windflutter.system import damping


def _energy(v):
    return float(v[0] ** 2 + v[2] ** 2), float(v[1] ** 2 + v[3] ** 2)  # (fore-aft, side-side) of two levels


def _tower():
    """Two levels of an axisymmetric tower, DOFs (x1, y1, x2, y2): every mode a degenerate pair; and
    the modes of one direction (squared frequencies, mass-normalized shapes), solved on their own."""
    k = np.array([[2.0, -1.0], [-1.0, 1.0]]) * 4e6
    m = np.diag([2e4, 1e4])
    K, M = np.zeros((4, 4)), np.zeros((4, 4))
    for d in (0, 1):
        K[d::2, d::2], M[d::2, d::2] = k, m
    return K, M, sla.eigh(k, m)


@pytest.mark.parametrize("angle", [0.0, 10.0, 45.0, 73.0])
def test_a_degenerate_pair_gets_the_fore_aft_and_side_side_ratios_whatever_the_solvers_rotation(monkeypatch, angle):
    """The solver may return a degenerate pair's eigenvectors in any rotation; each used to take the
    ratio of the direction its arbitrary vector leaned to (1.3 / 1.7 % in one run, 1.7 / 1.7 % in the
    next on the IEA 22 MW).  Now the pair is turned onto its fore-aft and side-side directions first:
    for every returned rotation, the fore-aft shape of each order sees 2 zeta_fa omega and the side-side
    one 2 zeta_ss omega -- the modal damping written out per direction, with the shapes of one
    direction solved on their own (1e-9).  At 45 deg the old assignment gave both the fore-aft ratio."""
    K, M, (w2_1, phi) = _tower()
    w2, V = damping.symmetric_eigs(K, M)
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    R = np.eye(4)
    for i in (0, 2):  # turn each pair within its eigen-space
        R[i:i + 2, i:i + 2] = [[c, -s], [s, c]]
    real = damping.symmetric_eigs  # the tower's solve returns the turned pairs; any other solve is real
    monkeypatch.setattr(damping, "symmetric_eigs", lambda K_, M_: (w2, V @ R) if K_.shape == K.shape else real(K_, M_))
    fa, ss = np.array([0.013, 0.02]), np.array([0.017, 0.03])
    D = damping.support_modal_damping(K, M, np.zeros_like(M), fa, ss, _energy)
    for order in range(2):
        for d, ratios in ((0, fa), (1, ss)):
            u = np.zeros(4)
            u[d::2] = phi[:, order]  # mass-normalized: u^T D u = 2 zeta omega
            assert u @ D @ u == pytest.approx(2 * ratios[order] * np.sqrt(w2_1[order]), rel=1e-9)
