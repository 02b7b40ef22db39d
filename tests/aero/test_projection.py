"""Projection of the strip state space on a basis, the first-order pencil, and the seed's skin
distribution consumed by the state-space operator (states merged per parent strip)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "mesh"))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "solver"))
from test_skin_aero import shell_wing  # noqa: E402

from windflutter.aero.flow import OperatingPoint  # noqa: E402
from windflutter.aero.operators import StateSpaceAero, make_operator  # noqa: E402
from windflutter.aero.sections import RotorGeometry  # noqa: E402
from windflutter.aero.skin import skin_distribution  # noqa: E402
from windflutter.aero.statespace import block_diagonal, project  # noqa: E402
from windflutter.aero.unsteady import UnsteadyOptions  # noqa: E402
from windflutter.errors import InputError  # noqa: E402


@pytest.fixture(scope="module")
def wing():
    fe, sec = shell_wing(n_span=4, n_chord=8)
    # wind at 6 deg to the chord, from the pressure side: a lifting wing (mean loads non-zero)
    n = np.cross(sec.e_chord[0], sec.e_span[0])
    a = np.radians(6.0)
    wind = np.cos(a) * sec.e_chord[0] + np.sin(a) * n
    op = OperatingPoint(60.0, 0.0, 1.225, RotorGeometry(np.zeros(3), np.array([1.0, 0, 0]), wind))
    return fe, sec, op


def _dense_reference(op_, Phi, s):
    """``Phi^T P^T blockdiag(H_j(s)) P Phi`` assembled with sparse matrices (no projection code)."""
    H = block_diagonal(op_.state_space().transfer(s))
    return Phi.T @ (op_.PT @ (H @ (op_.P @ Phi)))


def test_projected_transfer_equals_the_assembled_strips(wing):
    # project() (batched products) against the sparse assembly of the strips' transfer
    # functions at complex s, including the lag states: round-off (1e-12)
    fe, sec, op = wing
    st = StateSpaceAero(sec, op, UnsteadyOptions(dynamic_stall=True))
    assert np.all(st.linearization.cl > 0.3)  # lifting
    Phi = np.random.default_rng(1).standard_normal((fe.n_dof, 6))
    pss = st.projected(Phi)
    assert pss.n_states == sec.n_sections * 3
    for s in (0.0, 5j, -3.0 + 4.0j):
        m = Phi.shape[1]
        X = np.linalg.solve(s * np.eye(pss.n_states) - pss.Az.toarray(), pss.Bq + s * pss.Bv)
        got = s * s * pss.Ma + s * pss.Da + pss.Ka + pss.Fz @ X
        ref = _dense_reference(st, Phi, s)
        assert got.shape == (m, m)
        assert np.abs(got - ref).max() < 1e-12 * np.abs(ref).max()
    Ma, Da, Ka = pss(5.0)  # harmonic form = H(5i)
    assert np.abs(-25 * Ma + 5j * Da + Ka - _dense_reference(st, Phi, 5j)).max() < 1e-12 * np.abs(Ka).max()


def test_pencil_eigenpairs_solve_the_nonlinear_aeroelastic_problem(wing):
    # each eigenvalue lam of E X' = A X makes (lam^2 M + lam D + K - H(lam)) singular, H the
    # assembled aerodynamic transfer (lag states eliminated): smallest singular value < 1e-9
    # of the largest; and state_matrix = E^-1 A has the same eigenvalues
    fe, sec, op = wing
    m = 5
    rng = np.random.default_rng(2)
    Phi = rng.standard_normal((fe.n_dof, m)) * 1e-2
    M = np.eye(m) * 50.0
    K = np.diag(np.linspace(1.0, 4.0, m) ** 2 * 2e4)
    D = 0.01 * K / 100.0
    st = StateSpaceAero(sec, op, UnsteadyOptions())
    pss = st.projected(Phi)
    lam = np.linalg.eigvals(pss.state_matrix(M, D, K))
    E, A = pss.pencil(M, D, K)
    lam2 = sla.eigvals(A, E)
    # (the lag roots are a cluster of near-repeated values, sensitive at sqrt(eps): compare the
    # oscillatory roots)
    up = lam[lam.imag > 1.0]
    up2 = np.array([lam2[np.argmin(np.abs(lam2 - x))] for x in up])
    assert np.allclose(up, up2, rtol=1e-9)
    for la in up[:4]:
        T = la * la * M + la * D + K - _dense_reference(st, Phi, la)
        sv = np.linalg.svd(T, compute_uv=False)
        assert sv[-1] < 1e-9 * sv[0]
    with pytest.raises(InputError, match="basis"):
        pss.pencil(np.eye(m + 1), np.eye(m + 1), np.eye(m + 1))


def smooth_fields(nodes: np.ndarray) -> np.ndarray:
    """(n_dof, 8) smooth displacement fields: translations and rotations varying as polynomials
    of the spanwise and chordwise coordinates (bending, torsion, camber-like distortion)."""
    x, y, z = (nodes - nodes.mean(axis=0)).T / np.ptp(nodes, axis=0).max()
    cols = []
    for f, comp in ((z**2, 0), (z**2, 2), (z**3, 0), (z, 4), (z * x, 0), (z**2 * y, 2), (x**2, 1), (z**2, 5)):
        v = np.zeros((nodes.shape[0], 6))
        v[:, comp] = f
        cols.append(v.ravel())
    return 1e-2 * np.stack(cols, axis=1)


def test_skin_sub_strips_with_states_merged_per_parent(wing):
    # The seed's skin distribution (one sub-strip per skin Gauss point) through the state-space
    # operator: the states of a parent strip's sub-strips are merged (SVD of each pole's lag
    # response, compress()) -- far fewer states, the same transfer function (1e-10) and the same
    # eigenvalues (1e-8) as the uncompressed sub-strip system.
    fe, sec, op = wing
    d = skin_distribution(fe, sec)
    o = UnsteadyOptions()
    full = StateSpaceAero(d.sections, op, o)
    merged = make_operator(d.sections, op, o, parent=d.parent)
    Phi = smooth_fields(fe.nodes)
    m = Phi.shape[1]
    pf, pm = full.projected(Phi), merged.projected(Phi)
    assert pf.n_states == 2 * d.sections.n_sections
    # per parent and pole at most m states; a smooth basis needs far fewer than 2 per Gauss point
    assert pm.n_states <= 2 * sec.n_sections * m and pm.n_states < pf.n_states / 4
    print(f"skin: {d.sections.n_sections} sub-strips, {pf.n_states} states -> {pm.n_states} merged")
    for s in (2j, -1.0 + 7.0j):
        Hf = [pf.Fz @ np.linalg.solve(s * np.eye(pf.n_states) - pf.Az.toarray(), pf.Bq + s * pf.Bv)]
        Hm = [pm.Fz @ np.linalg.solve(s * np.eye(pm.n_states) - pm.Az.toarray(), pm.Bq + s * pm.Bv)]
        assert np.abs(Hf[0] - Hm[0]).max() < 1e-10 * np.abs(Hf[0]).max()
    for A, B in zip(pf(3.0), pm(3.0)):
        assert np.abs(A - B).max() < 1e-10 * np.abs(A).max()
    M, K = np.eye(m) * 50.0, np.diag(np.linspace(1.0, 3.0, m) ** 2 * 2e4)
    lf = np.linalg.eigvals(pf.state_matrix(M, 0 * M, K))
    lm = np.linalg.eigvals(pm.state_matrix(M, 0 * M, K))
    osc_f = lf[lf.imag > 1.0]
    osc_m = np.array([lm[np.argmin(np.abs(lm - x))] for x in osc_f])
    assert np.allclose(osc_f, osc_m, rtol=1e-8)
    # rigid section motion: skin and spline strips give the same generalized aero terms
    spline = StateSpaceAero(sec, op, o).projected(sp.csr_matrix(Phi))
    assert spline.n_states == 2 * sec.n_sections


def test_project_rejects_a_wrong_basis(wing):
    fe, sec, op = wing
    st = StateSpaceAero(sec, op, UnsteadyOptions())
    with pytest.raises(InputError, match="R"):
        project(st.state_space(), np.zeros((5, 2)))
    with pytest.raises(InputError, match="parent"):
        StateSpaceAero(sec, op, UnsteadyOptions(), parent=np.zeros(2, int))
