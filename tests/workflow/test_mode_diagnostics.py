"""Flutter-mode pictures on the FE strips: the per-station aero work adds up to the assembled
structural-level work pi Im(u^H A u), and the shape components are the blade-frame ones."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.aero.strip import AeroOptions, OperatingPoint, StripAero
from windflutter.post.aerowork import flutter_mode_diagnostics, harmonic_force, total_work


def _rotor(n_blades=3, n_sec=4, R=60.0):
    """Straight blades in the rotor plane (x = 0), one structural node per strip."""
    ns = n_blades * n_sec
    r = np.tile(np.linspace(0.3 * R, 0.95 * R, n_sec), n_blades)
    az = np.repeat(2 * np.pi * np.arange(n_blades) / n_blades, n_sec)
    span = np.stack([np.zeros(ns), np.sin(az), np.cos(az)], axis=1)
    # chord in the rotor plane (flat pitch), leading edge towards the rotation direction
    chord = np.cross(span, [1.0, 0.0, 0.0])
    origin = span * r[:, None] + np.array([0.0, 0.0, 90.0])
    mm = sp.identity(6 * ns, format="csr")
    sec = AeroSections(blade=np.repeat(np.arange(n_blades), n_sec), radius=r,
                       width=np.full(ns, 0.65 * R / n_sec), chord=np.full(ns, 3.0),
                       elastic_axis=np.full(ns, -0.2), origin=origin, e_chord=chord, e_span=span,
                       airfoil=np.zeros(ns, int), polars=[], twist=np.zeros(ns), motion_map=mm)
    geom = RotorGeometry(hub_center=np.array([0.0, 0.0, 90.0]), shaft_axis=np.array([1.0, 0.0, 0.0]))
    return sec, geom


def test_station_work_sums_to_structural_work():
    sec, geom = _rotor()
    strip = StripAero(sec, OperatingPoint(wind_speed=10.0, omega=1.5, rotor=geom), AeroOptions())
    rng = np.random.default_rng(11)
    n = 6 * sec.n_sections
    u = rng.normal(size=n) + 1j * rng.normal(size=n)
    omega = 9.0
    d = flutter_mode_diagnostics(u, strip, sec, omega)
    # the same mode scaled as the diagnostic scales it
    ref = d.shape[np.unravel_index(np.argmax(np.abs(d.shape[:, :2])), d.shape[:, :2].shape)]
    assert ref == pytest.approx(1.0)
    # recover the scale from one component: flap of the shown blade's first strip
    j0 = np.where(sec.blade == d.blade)[0][0]
    flapdir = np.cross(sec.e_chord[j0], sec.e_span[j0])
    scale = d.shape[0, 0] / (flapdir @ u[6 * j0:6 * j0 + 3])
    us = u * scale
    Ma, Da, Ka = strip.matrices(omega)
    W = total_work(us, (-omega**2 * Ma + 1j * omega * Da + Ka).toarray())
    # assembled (P^T A P) and per-strip evaluations are the same algebra in another order:
    # equal to rounding
    assert d.work_total == pytest.approx(W, rel=1e-10)
    assert d.work.sum() == pytest.approx(W, rel=1e-10)       # equal blades: station sums = total
    assert d.work.shape == (4, 3) and d.radius.shape == (4,)
    np.testing.assert_allclose(np.diff(d.radius) > 0, True)
    f = harmonic_force(us, omega, Ma, Da, Ka)
    assert np.pi * np.imag(np.vdot(us, f)) == pytest.approx(W, rel=1e-10)


def test_shape_components_are_blade_frame():
    sec, geom = _rotor(n_blades=1, n_sec=3)
    strip = StripAero(sec, OperatingPoint(wind_speed=8.0, omega=1.0, rotor=geom), AeroOptions())
    n = 6 * sec.n_sections
    u = np.zeros(n, complex)
    flapdir = np.cross(sec.e_chord, sec.e_span)
    for j in range(3):
        u[6 * j:6 * j + 3] = (j + 1) * 0.1 * flapdir[j] + 0.05j * sec.e_chord[j]
        u[6 * j + 3:6 * j + 6] = 0.01 * (j + 1) * sec.e_span[j]
    d = flutter_mode_diagnostics(u, strip, sec, 5.0)
    s = 1 / 0.3                                  # largest translation: flap of the tip strip
    np.testing.assert_allclose(d.shape[:, 0], s * 0.1 * np.arange(1, 4), rtol=1e-12)
    np.testing.assert_allclose(d.shape[:, 1], s * 0.05j, rtol=1e-12)
    np.testing.assert_allclose(d.shape[:, 2], s * 0.01 * np.arange(1, 4), rtol=1e-12)
