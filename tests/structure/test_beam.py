"""Beam element verification against Euler-Bernoulli / Saint-Venant closed forms."""

import numpy as np
import pytest

from windflutter.errors import InputError, ModelError
from windflutter.structure import assemble, modes
from windflutter.structure.fem import BeamSection, FEModel

BETA_L = np.array([1.87510407, 4.69409113, 7.85475744])  # cantilever roots of 1 + cos cosh = 0


def cantilever(ne=20, L=10.0, section=None, orient=(0.0, 1.0, 0.0), axis=(1.0, 0.0, 0.0)):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    x = np.linspace(0, L, ne + 1)[:, None] * axis[None, :]
    if section is None:
        section = BeamSection.from_properties(EA=1e9, EIy=1e6, EIz=1e6, GJ=5e5, mass_per_length=10.0, Ixx_mass=0.5)
    return FEModel(nodes=x, beam_conn=np.c_[np.arange(ne), np.arange(1, ne + 1)],
                   beam_section=np.zeros(ne, int), beam_orient=np.tile(orient, (ne, 1)),
                   beam_sections=[section], spc={0: (0, 1, 2, 3, 4, 5)})


def test_cantilever_bending_and_torsion_frequencies():
    # oblique axis to exercise the frame rotation
    fe = cantilever(ne=20, axis=(1.0, 2.0, -0.5), orient=(0.0, 0.0, 1.0))
    md = modes(assemble(fe), n=10)
    L, EI, m, GJ, Ip = 10.0, 1e6, 10.0, 5e5, 0.5
    f_b = BETA_L**2 / L**2 * np.sqrt(EI / m) / (2 * np.pi)
    f_t = np.array([1, 3]) / (4 * L) * np.sqrt(GJ / Ip)
    f = md.freq
    # bending pairs (EIy = EIz): Hermite consistent mass + exact stiffness converge as h^4;
    # with 20 elements the 3rd mode is within 1e-4 (shear-rigid section: GA = 1e3 EA)
    for k, fb in enumerate(f_b):
        assert np.sum(np.abs(f - fb) / fb < 1e-4) == 2
    # torsion: linear twist interpolation with consistent mass over-estimates the frequency by
    # (k h)^2 / 24 (k = wave number, h = element length): 2.6e-4 and 2.3e-3; allow 1.5x that
    for n_half, ft in zip((1, 3), f_t):
        kh = n_half * np.pi / 2 / 20
        assert 0 < np.min(np.abs(f - ft)) / ft < 1.5 * kh**2 / 24


def test_static_tip_load_exact():
    # exact element stiffness: tip deflection PL^3/3EI (+ tiny shear term with GA = 1e3 EA)
    fe = cantilever(ne=3)
    st = assemble(fe)
    from windflutter.structure import static_solve

    F = np.zeros(st.n_dof)
    F[6 * 3 + 2] = 1000.0
    u = static_solve(st, F)
    assert u[6 * 3 + 2] == pytest.approx(1000.0 * 10.0**3 / (3 * 1e6), rel=1e-6)
    assert u[6 * 3 + 4] == pytest.approx(-1000.0 * 10.0**2 / (2 * 1e6), rel=1e-6)


def test_unconstrained_model_raises():
    fe = cantilever(ne=4)
    fe.spc = {}
    with pytest.raises(ModelError, match="not sufficiently constrained"):
        assemble(fe)
    # a pinned support only (rotation about x free: torsional mechanism)
    fe.spc = {0: (0, 1, 2, 4, 5)}
    with pytest.raises(ModelError):
        assemble(fe)


def test_bad_orientation_raises():
    fe = cantilever(ne=4, orient=(1.0, 0.0, 0.0))
    with pytest.raises(InputError, match="beam_orient"):
        assemble(fe)
