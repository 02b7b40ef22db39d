"""The files' per-direction structural damping on shell blades (system/damping.py
``shell_modal_damping``, issue 33): modal damping of the blade's fixed-interface modes, each mode
getting ``zeta = omega / 2 * sum_d e_d mu_d`` from its shares ``e_d`` of flap, edge, torsion and
axial motion -- what the beam's stiffness-proportional ``mu`` per direction gives a mode of that
direction (Rayleigh: ``zeta = pi f mu``).  Against the beam of the same blade:
tests/system/test_shell_same_blade.py."""

from __future__ import annotations

import dataclasses
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.structure.modal import symmetric_eigs
from windflutter.system.damping import DIRECTIONS, ModalDamping, shell_modal_damping
from windflutter.system.operational import OperationalModel, OperationalOptions

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "mesh"))
from synthetic import synthetic_turbine, tube_blade  # noqa: E402

MU = np.array([1e-3, 9e-4, 9e-4, 5e-4, 2e-3, 4e-3])  # axial, shear y, shear z, torsion, edge, flap (s)


@pytest.fixture(scope="module")
def tube():
    """A straight isotropic elliptical tube shell blade (40 m, chord 2 m, t/c 0.5, wall 10 mm, the
    pitch axis at the ellipse's centre: shear and mass centres on it), clamped at the hub, and its
    modal damping for :data:`MU`."""
    tb = synthetic_turbine(tube_blade(40.0, 2.0, 0.5, 0.01))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        om = OperationalModel(tb, OperationalOptions(model="shell", part="rotor", damping="none",
                                                     mesh={"n_span": 20, "n_chord": 24}))
        rb = om.blade(0.0)
    return rb, shell_modal_damping(rb.fe, rb.struct, rb.sections, MU)


def test_pure_modes_of_a_tube_get_pi_f_mu_of_their_direction(tube):
    """Rayleigh's closed form: a mode whose motion is all in one direction gets ``zeta = pi f mu`` of
    that direction.  The tube's lowest five modes (1st and 2nd flap and edge, 1st torsion, 0.67-10.7
    Hz): the mode's share of its own direction at least 0.99 and its damping ratio within 1 % of
    ``pi f mu`` (measured: shares 1.000, ratios 1.0000).  Above them come the section's own
    (ovalization) modes, which no beam has: not compared."""
    _, D = tube
    seen = []
    for f, z, e in zip(D.freq_hz[:5], D.zeta, D.shares):
        k = int(np.argmax(e))
        seen.append(DIRECTIONS[k])
        assert e[k] >= 0.99, (f, e)
        assert z == pytest.approx(np.pi * f * MU[(0, 3, 4, 5)[k]], rel=0.01), (f, DIRECTIONS[k])
    assert seen == ["flap", "edge", "flap", "edge", "torsion"]


def test_the_matrix_gives_each_mode_its_ratio_and_turns_with_the_nodes(tube):
    """On the blade's modes computed again here (another Lanczos start): ``phi_i^T C phi_i = 2
    zeta_i omega_i`` (1e-6 of the largest); with every ``mu`` equal the matrix is stiffness-
    proportional damping on the modes, ``phi_i^T C phi_j = mu omega_i^2 delta_ij`` (the direction
    terms off the diagonal cancel: 1e-6); a mode above the damped set gets nothing.  Turned by
    nodal rotations, the matrix is ``Q C Q^T`` (1e-12); ``C @ X`` is the same for dense and sparse
    ``X``."""
    rb, D = tube
    st = rb.struct
    n = len(D.zeta)
    w2, X = symmetric_eigs(sp.csc_matrix(st.Kr), sp.csc_matrix(st.Mr), n + 3, shift=-1.0)
    X = X / np.sqrt(np.einsum("im,im->m", X, st.Mr @ X))
    P = np.asarray(st.T @ X)
    G = P.T @ (D @ P)
    want = 2.0 * D.zeta * 2 * np.pi * D.freq_hz
    scale = want.max()
    assert np.allclose(np.diag(G)[:n], want, rtol=1e-6, atol=1e-9 * scale)
    assert np.abs(G[n:, n:]).max() < 1e-6 * scale  # above the set: undamped
    D1 = shell_modal_damping(rb.fe, st, rb.sections, np.full(6, 2e-3))
    G1 = P.T @ (D1 @ P)
    assert np.abs(np.abs(G1[:n, :n]) - np.diag(2e-3 * w2[:n])).max() < 1e-6 * 2e-3 * w2[n - 1]

    rng = np.random.default_rng(1)
    small = ModalDamping(rng.standard_normal((24, 3)), np.array([1.0, 2.0, 3.0]))
    R = np.array([sp.linalg.expm(np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]]))
                  for a in rng.standard_normal((4, 3))])
    Q = sp.block_diag([sp.block_diag([r, r]) for r in R]).toarray()
    assert np.allclose(small.rotated(R).toarray(), Q @ small.toarray() @ Q.T, atol=1e-12)
    Xs = sp.random(24, 5, density=0.3, random_state=2, format="csr")
    assert np.allclose(small @ Xs, small.toarray() @ Xs.toarray(), atol=1e-12)
    assert np.allclose(small @ Xs.toarray()[:, 0], small.toarray() @ Xs.toarray()[:, 0], atol=1e-12)


def test_the_operational_shell_blade_carries_its_damping_to_the_pitch(tube):
    """The pitch-0 blade's modal damping turned with the pitch: a shell blade's damping at pitch
    ``p`` is the pitch-0 one carried by the pitch rotation (the blade modes turn with it)."""
    from windflutter.model.blade import BladeDamping
    from windflutter.system.pitch import pitch_rotation

    tb = synthetic_turbine(tube_blade(40.0, 2.0, 0.5, 0.01))
    tb = dataclasses.replace(tb, blade=dataclasses.replace(tb.blade, damping=BladeDamping(mu=MU)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        om = OperationalModel(tb, OperationalOptions(model="shell", part="rotor", mesh={"n_span": 20, "n_chord": 24}))
        b0, b1 = om.blade(0.0), om.blade(0.3)
    assert isinstance(b1.damping, ModalDamping)
    v0 = np.random.default_rng(3).standard_normal(b0.struct.n_dof)
    R, _ = pitch_rotation(tb, 0.3)  # a motion of the pitch-0 blade, turned with it: u1 = Q u0
    Q = sp.kron(sp.identity(b0.fe.n_nodes), sp.block_diag([R, R])).tocsr()
    assert np.allclose(b1.damping @ (Q @ v0), Q @ (b0.damping @ v0), atol=1e-10 * np.abs(b0.damping @ v0).max())


def test_the_frozen_azimuth_model_gives_its_shell_blades_the_same_damping(tube):
    """The seed's frozen-azimuth model (frozen/turbine.py) with the files' damping: each shell blade
    gets method p's per-direction modal damping (the clamped blade's, placed on the blade by its
    pitch, azimuth, cone and tilt), not one ``beta K``.  The three-bladed tube rotor (hub clamped,
    2.5 deg cone, 5 deg tilt) at pitch 0.3 rad, standstill, vacuum: its lowest six modes (1st flap
    and 1st edge of each blade) have the damping ratio Rayleigh's closed form gives the direction,
    ``pi f mu`` (1 %, as above), and method p's ``zeta`` of that blade mode (1 %).  One ``beta K``
    with the larger bending ``mu`` (the old model) gives the edge modes twice their ratio.  A point
    set that is not the blade moved rigidly is refused."""
    from windflutter.frozen.turbine import TurbineOptions, TurbineStability
    from windflutter.model.blade import BladeDamping
    from windflutter.system.damping import rigid_fit

    _, D = tube
    tb = synthetic_turbine(tube_blade(40.0, 2.0, 0.5, 0.01))
    tb = dataclasses.replace(tb, blade=dataclasses.replace(tb.blade, damping=BladeDamping(mu=MU)))
    opts = TurbineOptions(model="shell", damping="file", reduction="modal", basis_modes=20, max_rpm=10.0,
                          mesh={"part": "rotor", "n_span": 20, "n_chord": 24})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, _, am = TurbineStability(tb, opts).model(0.3)
    M, C, K = (np.asarray(A.toarray() if sp.issparse(A) else A) for A in (am.Mr, am.Dr, am.Kr0))
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam = np.linalg.eigvals(A)
    lam = lam[lam.imag > 0]
    lam = lam[np.argsort(np.abs(lam))][:6]
    f, zeta = np.abs(lam) / (2 * np.pi), -lam.real / np.abs(lam)
    for i, (mu, zp) in enumerate(((MU[5], D.zeta[0]), (MU[4], D.zeta[1]))):  # flap, then edge
        fi, zi = f[3 * i:3 * i + 3], zeta[3 * i:3 * i + 3]
        assert np.allclose(fi, D.freq_hz[i], rtol=1e-3), (fi, D.freq_hz[i])
        assert np.allclose(zi, np.pi * fi * mu, rtol=0.01), (zi, np.pi * fi * mu)
        assert np.allclose(zi, zp, rtol=0.01), (zi, zp)

    x = np.random.default_rng(4).standard_normal((10, 3))
    with pytest.raises(ValueError):
        rigid_fit(x, x * 1.1)
