"""The operating-point Campbell says when a blade's full-order stiffness is indefinite at a point (and, in
tests/structure/test_inertia.py, when a mode of its basis is: the IEA 15 MW shell's outboard skin).

The count comes from the factorization of the blade's basis (``PointSystem.blade_negative``,
``tests/structure/test_inertia.py``); here the Campbell's reaction: one ValidityWarning naming the wind
speed, no change to the modes.  The count is set by hand on a beam model (a beam blade's basis is its
full spectrum's lowest modes, so it has none of its own)."""

from __future__ import annotations

import warnings

import numpy as np

import windflutter
from windflutter.errors import ValidityWarning
from windflutter.system import campbell


def _run(monkeypatch, negative):
    real = campbell.SerialPoints.point

    def point(self, v, middle=False):
        ps, eig, st = real(self, v, middle)
        ps.blade_negative = negative
        return ps, eig, st

    monkeypatch.setattr(campbell.SerialPoints, "point", point)
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        res = windflutter.campbell("nrel5mw", wind_speeds=[8.0], model={"part": "rotor"}, workers=1)
    return res, [w for w in got if issubclass(w.category, ValidityWarning) and "statically unstable at the operating point" in str(w.message)]


def test_an_indefinite_blade_at_an_operating_point_warns(monkeypatch):
    res, hits = _run(monkeypatch, 2)
    assert len(hits) == 1 and "V = 8.0 m/s" in str(hits[0].message) and "2 negative" in str(hits[0].message)
    ref, none = _run(monkeypatch, 0)
    assert not none
    f = [m.frequency_hz for m in res.points[0].modes]
    np.testing.assert_array_equal(f, [m.frequency_hz for m in ref.points[0].modes])


def test_an_aperiodic_root_at_a_buckled_point_is_the_structure_s():
    """At a point whose blade structure is statically unstable on its own (a ``buckling`` mode there),
    a root growing aperiodically (zeta <= -APERIODIC) is that instability, not an aeroelastic one: the
    IEA 15 MW shell at 12 m/s with MITC4's shear named such a root "1st flap FW" (0.19 Hz, -78 %) and
    the table read UNSTABLE.  An oscillating negative root there, and an aperiodic one at a point
    without buckling, stay unstable."""
    from windflutter.system.campbell import CampbellPoint, CampbellResult

    flap, edge = _mode("1st flap FW", -0.78, 0.19, "flap"), _mode("2nd edge FW", -0.01, 2.3, "edge")
    buckled = CampbellPoint(12.0, 7.56, 3.6, [flap, edge, _mode("blade structure unstable 9", -0.99, 2.7, "buckling")])
    clean = CampbellPoint(8.0, 5.7, 0.0, [_mode("1st flap FW", -0.78, 0.19, "flap")])
    res = CampbellResult("T", "turbine", [buckled, clean])
    bad = [(p.wind_speed, m.name) for p, m in res.unstable()]
    assert bad == [(12.0, "2nd edge FW"), (8.0, "1st flap FW")]
    assert [(p.wind_speed, m.name) for p, m in res.structure_unstable()] == [
        (12.0, "1st flap FW"), (12.0, "blade structure unstable 9")]
    assert res.least_damped()[0] is clean


def _mode(name, zeta, f_hz, family, whirl="FW"):
    """A mode record's fields the Campbell's verdict reads: damped frequency ``f_hz`` (Hz), ratio ``zeta``."""
    from types import SimpleNamespace

    w = 2 * np.pi * f_hz
    lam = complex(-zeta * w / np.sqrt(1 - zeta**2), w)
    return SimpleNamespace(name=name, damping_ratio=zeta, family=family, rigid=False, eigenvalue=lam, whirl=whirl)


def test_a_root_static_in_the_rotating_frame_at_a_buckled_point_is_the_structure_s():
    """The IEA 15 MW shell at 10 m/s (7.10 RPM, 0.1183 Hz): a "1st flap FW" at 0.1147 Hz, -28.9 % in the
    ground-fixed frame, printed as UNSTABLE beside the buckled blade; in the rotating frame it is at
    0.0036 Hz, growing aperiodically (-99.5 %): the buckled structure's static instability seen from the
    ground.  The same root as BW (1.1 x the rotor speed in the rotating frame, oscillating), and an
    oscillating FW root (-29 % at 0.6 Hz), stay aeroelastic; at a point without buckling so does the first."""
    from windflutter.system.campbell import CampbellPoint, CampbellResult

    rpm = 7.10
    buckle = _mode("blade structure unstable 7", -0.9998, 5.52, "buckling")
    static_fw = _mode("1st flap FW", -0.2894, 0.1147, "flap")
    as_bw = _mode("1st flap BW", -0.2894, 0.1147, "flap", "BW")
    oscillating = _mode("2nd flap FW", -0.29, 0.6, "flap")
    res = CampbellResult("T", "turbine", [CampbellPoint(10.0, rpm, 0.0, [static_fw, as_bw, oscillating, buckle]),
                                          CampbellPoint(8.0, rpm, 0.0, [_mode("1st flap FW", -0.2894, 0.1147, "flap")])])
    assert [(p.wind_speed, m.name) for p, m in res.structure_unstable()] == [
        (10.0, "1st flap FW"), (10.0, "blade structure unstable 7")]
    assert [(p.wind_speed, m.name) for p, m in res.unstable()] == [
        (10.0, "1st flap BW"), (10.0, "2nd flap FW"), (8.0, "1st flap FW")]
