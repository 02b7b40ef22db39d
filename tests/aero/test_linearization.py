"""Steady strip linearization: polar values and local slopes, aerodynamic centre, separation point."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.aero.linearization import (SLOPE_STEP, centred_slope, flat_plate_linearization,
                                            kirchhoff_separation, polar_linearization)
from windflutter.aero.polars import fit_polar
from windflutter.aero.sections import AeroSections, Polar
from windflutter.errors import InputError


@pytest.fixture(scope="module")
def nrel_airfoils():
    from windflutter.model.windio import load_turbine

    return load_turbine("nrel5mw", validate=False).airfoils  # schema validation is tested elsewhere


def _sections(polars, airfoil):
    ns = len(airfoil)
    return AeroSections(blade=np.zeros(ns, int), radius=np.arange(1.0, ns + 1), width=np.ones(ns),
                        chord=np.ones(ns), elastic_axis=np.zeros(ns), origin=np.zeros((ns, 3)),
                        e_chord=np.tile([1.0, 0, 0], (ns, 1)), e_span=np.tile([0, 1.0, 0], (ns, 1)),
                        airfoil=np.asarray(airfoil), polars=polars, twist=np.zeros(ns),
                        motion_map=sp.identity(6 * ns, format="csr"))


def test_centred_slope_exact_on_lines_and_second_order_on_smooth_polars():
    a = np.radians(np.arange(-20.0, 20.01, 0.05))
    at = np.radians([-7.3, 0.0, 4.1, 11.9])
    assert np.allclose(centred_slope(a, 5.9 * a - 0.2, at), 5.9, rtol=1e-12)
    # smooth Cl = sin(2 alpha) tabulated finely: error of the +-delta difference is
    # -(2 delta)^2/6 * 2 cos(2 alpha) + table interpolation (O(0.05 deg^2)); halving delta
    # divides it by ~4
    e = [np.abs(centred_slope(a, np.sin(2 * a), at, d) - 2 * np.cos(2 * at)).max() for d in np.radians([2.0, 1.0])]
    assert 3.5 < e[0] / e[1] < 4.2
    assert e[1] < 2e-3
    with pytest.raises(InputError, match="slope_step"):
        centred_slope(a, a, at, 0.0)


def test_local_slopes_of_the_nrel_tables(nrel_airfoils):
    # The strips get the table's slope where they work: in attached flow it is near the
    # attached-range fit, past stall it is small or NEGATIVE (kept: it is the physics of stall
    # vibrations).  Aerodynamic centre x_ac = -dCm/dCl within 5 % chord of the quarter chord at
    # 0..4 deg for the outboard airfoils (thin-airfoil theory puts it at c/4; thickness and
    # camber move it by a few % chord).
    names = ["DU21_A17", "DU25_A17", "DU30_A17", "NACA64_A17"]
    pols = [nrel_airfoils[n].polar for n in names]
    idx = np.repeat(np.arange(4), 3)
    alpha = np.tile(np.radians([0.0, 4.0, 16.0]), 4)
    alpha[[2, 5, 8, 11]] = np.radians([12.0, 12.0, 12.0, 20.0])  # stalled angles
    lin = polar_linearization(_sections(pols, idx), alpha)
    for j in range(12):
        p = pols[idx[j]]
        assert lin.cl[j] == pytest.approx(np.interp(alpha[j], p.alpha, p.cl))
        ref = (np.interp(alpha[j] + SLOPE_STEP, p.alpha, p.cl) - np.interp(alpha[j] - SLOPE_STEP, p.alpha, p.cl))
        assert lin.dcl[j] == pytest.approx(ref / (2 * SLOPE_STEP), rel=1e-12)
    attached = np.arange(12) % 3 < 2
    assert np.all(np.abs(lin.aerodynamic_centre[attached]) < 0.05)
    assert np.all(lin.dcl[~attached] < 0) and np.all(lin.dcd[~attached] > 0)
    fits = np.array([fit_polar(p).cl_alpha for p in pols])[idx]
    assert np.all(np.abs(lin.dcl[attached] / fits[attached] - 1) < 0.25)
    sub = lin.take(np.array([0, 0, 5]))
    assert sub.n_sections == 3 and sub.dcl[1] == lin.dcl[0] and sub.alpha[2] == lin.alpha[5]


def test_kirchhoff_separation_recovers_the_generating_f():
    # A polar generated FROM a known separation curve by Kirchhoff's relation
    # Cl = Cla (alpha - a0) ((1 + sqrt f)/2)^2 must give that f back (1e-10 away from the
    # table's kinks) and dCl/df = Cla (alpha - a0) - Cl_fs with Cl_fs the decomposition's
    # (Cl = f Cl_inv + (1 - f) Cl_fs; Cl/2 where f = 1, as OpenFAST's AeroDyn).
    a = np.radians(np.arange(-30.0, 30.01, 0.25))
    cla, a0 = 6.0, np.radians(-1.5)
    d = np.abs(a - a0)  # attached to 9 deg from zero lift, then separating (Gaussian decay)
    f_true = np.where(d < np.radians(9.0), 1.0, np.exp(-((d - np.radians(9.0)) / np.radians(4.0)) ** 2))
    cl = cla * (a - a0) * ((1 + np.sqrt(f_true)) / 2) ** 2
    pol = Polar(a, cl, 0.01 + 0 * a, 0 * a)
    fit = fit_polar(pol)
    at = np.radians([6.125, 11.125, 13.125, 17.125])
    s = kirchhoff_separation(pol, at)
    f_fit = (2 * np.sqrt(np.interp(at, a, cl) / (fit.cl_alpha * (at - fit.alpha_zero_lift))) - 1) ** 2
    assert np.allclose(s.f, np.clip(f_fit, 0, 1), atol=1e-12)
    inv = fit.cl_alpha * (at - fit.alpha_zero_lift)
    cl_at = np.interp(at, a, cl)
    fs = np.where(s.f < 1, (cl_at - inv * s.f) / np.where(s.f < 1, 1 - s.f, 1.0), cl_at / 2)  # Cl/2 at f = 1
    assert np.allclose(s.dcl_df, inv - fs, rtol=1e-12)
    # the fit recovers cla (0.2 %) and a0 of the attached part, so f follows the generating
    # curve (0.005: the fit's slope error times the angle)
    assert fit.cl_alpha == pytest.approx(cla, rel=5e-3)
    assert np.allclose(s.f, np.interp(at, a, f_true), atol=5e-3)
    assert s.f[0] == 1.0 and s.df[0] == 0.0 and np.all(np.diff(s.f) < 0) and np.all(s.df[1:] < 0)


def test_flat_plate_and_bad_input():
    lin = flat_plate_linearization(np.radians([0.0, 3.0]))
    assert np.allclose(lin.cl, 2 * np.pi * np.radians([0.0, 3.0])) and np.all(lin.dcl == 2 * np.pi)
    assert np.allclose(lin.aerodynamic_centre, 0.0)
    pol = Polar(np.radians([-10.0, 0.0, 10.0]), np.array([-1.0, 0.0, 1.0]), np.zeros(3), np.zeros(3))
    with pytest.raises(InputError, match="polars"):
        polar_linearization(_sections([], [0]), np.zeros(1))
    with pytest.raises(InputError, match="alpha"):
        polar_linearization(_sections([pol], [0]), np.zeros(2))
    with pytest.raises(InputError, match="airfoil"):
        polar_linearization(_sections([pol], [1]), np.zeros(1))
    bad = Polar(np.radians([0.0, -1.0, 2.0]), np.zeros(3), np.zeros(3), np.zeros(3), name="bad")
    with pytest.raises(InputError, match="increasing"):
        polar_linearization(_sections([bad], [0]), np.zeros(1))
