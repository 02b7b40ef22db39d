"""Equivalent beam section stiffness of a shell segment by unit loads (structure/equivalent_beam.py)
against the closed-form thin-walled tube."""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.structure.equivalent_beam import ring_rigid_motion, segment_stiffness
from shellmodels import iso, tube

E, NU, T, R = 70e9, 0.3, 0.01, 1.0


def test_ring_rigid_motion_recovers_a_rigid_motion():
    rng = np.random.default_rng(1)
    P = rng.normal(size=(12, 3))
    ref = np.array([0.2, -0.1, 0.3])
    u0, th = np.array([0.01, -0.02, 0.03]), np.array([0.002, 0.001, -0.003])
    u = u0 + np.cross(th, P - ref)
    np.testing.assert_allclose(ring_rigid_motion(P, u, ref), np.r_[u0, th], atol=1e-14)


@pytest.fixture(scope="module")
def tube_stiffness():
    """A 10 m tube of radius 1 m and 10 mm aluminium-like wall, 48 x 40 elements; measured between
    the rings at 3 and 7 m (1.5 diameters from the clamped root and the tied tip)."""
    nc, nl, L = 48, 40, 10.0
    fe, idx = tube(nc, nl, R, L, iso(E, NU, 2700.0, T))
    a, b = 12, 28
    xa, xb = np.array([L * a / nl, 0, 0]), np.array([L * b / nl, 0, 0])
    return segment_stiffness(fe, idx[0], idx[-1], (idx[a], idx[b]), (xa, xb), axis=[1.0, 0, 0], e2=[0, 1.0, 0])


def test_tube_axial_bending_and_torsion_stiffness_are_the_closed_form(tube_stiffness):
    """Thin-walled circular tube: EA = 2 pi R t E, EI = pi R^3 t E, GJ = 2 pi R^3 t G (Bredt), within
    2 % (measured -0.07, -0.34 and -0.50 %: the 48-sided polygon); no couplings about the tube's own
    axis (measured 1e-12 of the diagonal; tolerance 1e-3)."""
    s = tube_stiffness
    G = E / (2 * (1 + NU))
    assert s.EA == pytest.approx(2 * np.pi * R * T * E, rel=0.02)
    assert s.EI2 == pytest.approx(np.pi * R**3 * T * E, rel=0.02)
    assert s.EI3 == pytest.approx(np.pi * R**3 * T * E, rel=0.02)
    assert s.GJ == pytest.approx(2 * np.pi * R**3 * T * G, rel=0.02)
    K = s.stiffness
    d = np.sqrt(np.outer(np.diag(K), np.diag(K)))
    off = np.abs(K / d - np.eye(4))
    assert off.max() < 1e-3


def test_an_offset_reference_axis_shows_as_the_coupling_of_the_offset():
    """The same tube measured about an axis 0.5 m off its centre along e2: the axial force at the
    reference axis bends it, ``EA e`` appears as the axial--bending coupling about e3 and EI3 about
    the offset axis is ``EI + EA e^2`` (parallel axes), within 2 % (measured -0.07 and -0.25 %)."""
    nc, nl, L = 48, 40, 10.0
    fe, idx = tube(nc, nl, R, L, iso(E, NU, 2700.0, T))
    e = 0.5
    xa, xb = np.array([3.0, e, 0]), np.array([7.0, e, 0])
    s = segment_stiffness(fe, idx[0], idx[-1], (idx[12], idx[28]), (xa, xb), axis=[1.0, 0, 0], e2=[0, 1.0, 0])
    EA, EI = 2 * np.pi * R * T * E, np.pi * R**3 * T * E
    # the tension centre at -e along e2: N = EA (eps + e kappa3), M3 = EA e eps + (EI + EA e^2) kappa3
    assert s.stiffness[0, 3] == pytest.approx(EA * e, rel=0.02)
    assert s.stiffness[3, 3] == pytest.approx(EI + EA * e**2, rel=0.02)


def test_reference_points_must_run_along_the_axis():
    fe, idx = tube(8, 4, R, 4.0, iso(E, NU, 2700.0, T))
    with pytest.raises(InputError, match="refs"):
        segment_stiffness(fe, idx[0], idx[-1], (idx[3], idx[1]), (np.array([3.0, 0, 0]), np.array([1.0, 0, 0])),
                          axis=[1.0, 0, 0])
