"""Rotating-frame terms: point-mass formulas and Southwell's law for a spinning cantilever."""

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.aero.sections import RotorGeometry
from windflutter.linalg_tools import skew
from windflutter.rotor.rotating import rotor_terms
from windflutter.rotor.translational import coriolis_and_softening
from windflutter.solve.qep import solve_qep
from windflutter.structure.assembly import assemble
from windflutter.structure.fem import BeamSection, FEModel


def test_point_mass_formulas():
    m = 3.0
    M = sp.csr_matrix(np.diag([m, m, m, 0, 0, 0]))
    Om = np.array([0.3, -0.2, 1.1])
    G, Kr = coriolis_and_softening(M, np.arange(3), Om)
    assert np.allclose(G.toarray()[:3, :3], 2 * m * skew(Om))
    assert np.allclose(Kr.toarray()[:3, :3], m * (Om @ Om * np.eye(3) - np.outer(Om, Om)))


def _spinning_blade(n=16, L=10.0):
    EI, m = 2.0e5, 20.0
    sec = BeamSection.from_properties(EA=1e4 * EI, EIy=EI, EIz=EI * 4.0, GJ=EI, mass_per_length=m,
                                      Ixx_mass=1e-6, Iyy_mass=1e-6, Izz_mass=1e-6)
    z = np.linspace(0.0, L, n + 1)
    fe = FEModel(nodes=np.column_stack([np.zeros(n + 1), np.zeros(n + 1), z]),
                 beam_conn=np.column_stack([np.arange(n), np.arange(1, n + 1)]),
                 beam_section=np.zeros(n, dtype=np.int64), beam_orient=np.tile([1.0, 0, 0], (n, 1)),
                 beam_sections=[sec], spc={0: (0, 1, 2, 3, 4, 5)}, node_groups={"rotor": np.arange(n + 1)})
    return fe, assemble(fe), EI, m, L


def test_southwell_flap_frequency():
    # blade along z spinning about x (the shaft): flapwise (x) bending is untouched by Kr and G,
    # stiffened by the centrifugal prestress: w^2 = w0^2 + 1.1931 Omega^2 for the first mode of
    # a uniform cantilever without hub offset (Southwell coefficient; e.g. Wright et al., J.
    # Appl. Mech. 49, 1982, table 1).  1 % tolerance: 16 Hermite elements + linear-N prestress.
    fe, st, EI, m, L = _spinning_blade()
    terms = rotor_terms(fe, st, RotorGeometry(np.zeros(3), np.array([1.0, 0, 0])), prestress=True)
    # section frame: y = global x, so EIz (= 4 EI) bends the blade along x (flapwise)
    w0 = 1.875104**2 * np.sqrt(4.0 * EI / (m * L**4))
    Om = 1.0 * w0
    G, Kr, Ks = terms.at(Om)
    M = st.reduce(st.M)
    K = st.reduce(st.K - Kr + Ks)
    e = solve_qep(M, st.reduce(G), K, n_eig=8, method="dense")
    w = np.sort(np.abs(e.values.imag))
    expected = np.sqrt(w0**2 + 1.1931 * Om**2)
    assert np.min(np.abs(w - expected)) / expected < 0.01


def test_thesis_switch_has_no_prestress():
    fe, st, *_ = _spinning_blade(n=4)
    terms = rotor_terms(fe, st, RotorGeometry(np.zeros(3), np.array([1.0, 0, 0])), prestress=False)
    G, Kr, Ks = terms.at(1.0)
    assert Ks.nnz == 0
    assert abs(G - (-G.T)).max() < 1e-12  # gyroscopic matrix is skew-symmetric


def test_rotor_terms_act_relative_to_the_hub():
    """A rotor tied to a hub node that can translate (whole-turbine model): a rigid translation of
    rotor + hub must see no spin softening and no Coriolis force (in the fixed frame there is
    none), while the blade's elastic motion relative to the hub keeps the point-mass terms."""
    n, L = 4, 10.0
    fe, st, *_ = _spinning_blade(n=n, L=L)
    fe.node_groups["hub"] = np.array([0])
    geom = RotorGeometry(np.zeros(3), np.array([1.0, 0, 0]))
    terms = rotor_terms(fe, st, geom, prestress=False)
    absolute = rotor_terms(fe, st, geom, prestress=False, reference_group=None)
    G, Kr, _ = terms.at(2.0)
    Ga, Kra, _ = absolute.at(2.0)
    rigid_y = np.zeros(st.M.shape[0])
    rigid_y[1::6] = 1.0  # every node moves 1 m along y (normal to the shaft)
    assert np.abs(Kr @ rigid_y).max() < 1e-9 * abs(Kra).max()
    assert np.abs(G @ rigid_y).max() < 1e-9 * abs(Ga).max()
    assert np.abs(Kra @ rigid_y).max() > 1.0  # the absolute form does soften it (test can fail)
    # the tip moving relative to a still hub: the same forces on the blade nodes; the relative
    # form adds their reaction on the hub (so the net force of the pair is zero)
    tip = np.zeros(st.M.shape[0])
    tip[6 * n + 1] = 1.0
    blade = np.arange(6, st.M.shape[0])
    assert np.allclose((Kr @ tip)[blade], (Kra @ tip)[blade])
    assert np.allclose((G @ tip)[blade], (Ga @ tip)[blade])
    assert abs((Kr @ tip)[0::6].sum()) + abs((Kr @ tip)[1::6].sum()) + abs((Kr @ tip)[2::6].sum()) < 1e-9
