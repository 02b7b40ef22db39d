"""The blades' stiffness-proportional damping (system/damping.py) against the closed form of
stiffness-proportional (Rayleigh) damping, and its robustness to coefficients of very different
size on a coupled section."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from windflutter.structure import assemble, modes
from windflutter.structure.fem import BeamSection
from windflutter.system.damping import blade_damping_matrix

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "structure"))
from test_beam import cantilever  # noqa: E402


def _damped_modes(fe, mu, n=6):
    """(frequency Hz, damping ratio) of the lowest ``n`` modes of M q'' + C q' + K q = 0."""
    st = assemble(fe)
    T = st.T.toarray()
    M, K = T.T @ st.M.toarray() @ T, T.T @ st.K.toarray() @ T
    C = T.T @ blade_damping_matrix(fe, mu).toarray() @ T
    k = M.shape[0]
    A = np.block([[np.zeros((k, k)), np.eye(k)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam = np.linalg.eigvals(A)
    lam = lam[lam.imag > 0]
    lam = lam[np.argsort(np.abs(lam))][:n]
    return np.abs(lam) / (2 * np.pi), -lam.real / np.abs(lam)


def test_a_mode_in_one_direction_gets_zeta_pi_f_mu():
    """C = mu K restricted to one direction: a mode whose strain energy is all in that direction
    has zeta = mu omega / 2 = pi f mu (Rayleigh damping, exact).  A uniform cantilever with
    uncoupled section, different mu for flapwise and edgewise bending (each with its shear) and
    torsion: the 1st bending pairs and the 1st torsion mode each get their own direction's
    zeta = pi f mu to 1e-6."""
    sec = BeamSection.from_properties(EA=1e9, EIy=4e6, EIz=1e6, GJ=5e5, mass_per_length=10.0, Ixx_mass=0.5)
    fe = cantilever(ne=16, section=sec)
    st = np.asarray(sec.stiffness)
    mu = np.array([1e-3, 3e-3, 2e-3, 5e-4, 2e-3, 3e-3])  # axial, shear y, shear z, torsion, bending y, bending z
    assert np.allclose(st, np.diag(np.diag(st)))  # uncoupled
    f, z = _damped_modes(fe, mu, n=8)
    undamped = np.sort(modes(assemble(fe), n=4).freq)
    for fk, zk in zip(f, z):
        expected = [np.pi * fk * m for m in (mu[4], mu[5], mu[3])]
        assert min(abs(zk / e - 1) for e in expected) < 1e-6, (fk, zk, expected)
    assert np.allclose(np.sort(f)[:4], undamped[:4], rtol=1e-4)  # light damping hardly moves |lambda|


def test_coupled_section_with_tiny_torsion_coefficient_stays_positive():
    """The IEA 15 MW HAWC2 model's coefficients (flap 3.0e-3, edge 2.2e-3, torsion 1e-8 s) on a
    section with flap-torsion and edge-extension coupling: the damping matrix assembles (the
    arithmetic symmetrization (D S + S D) / 2 it replaced was indefinite there and stopped the
    analysis) and is symmetric positive semi-definite."""
    sec = BeamSection.from_properties(EA=1e9, EIy=4e6, EIz=1e6, GJ=5e5, mass_per_length=10.0, Ixx_mass=0.5)
    S = np.array(sec.stiffness, float)
    S[3, 5] = S[5, 3] = 0.6 * np.sqrt(S[3, 3] * S[5, 5])  # torsion - flap bending
    S[0, 4] = S[4, 0] = 0.5 * np.sqrt(S[0, 0] * S[4, 4])  # extension - edge bending
    fe = cantilever(ne=8, section=replace(sec, stiffness=S))
    mu = np.array([1e-8, 3.038e-3, 2.167e-3, 1e-8, 2.167e-3, 3.038e-3])
    D = np.diag(mu)
    assert np.linalg.eigvalsh(0.5 * (D @ S + S @ D)).min() < 0  # the old form: indefinite
    C = blade_damping_matrix(fe, mu).toarray()
    assert np.allclose(C, C.T, atol=1e-12 * abs(C).max())
    assert np.linalg.eigvalsh(C).min() >= -1e-9 * np.abs(C).max()
    f, z = _damped_modes(fe, mu, n=4)
    assert np.all(z > 0)
