"""Design sensitivities of method p's operating point against finite differences of re-analyses.

The reference (:mod:`windflutter.sensitivity.finite_difference`) changes the model's data by +-h,
rebuilds the point (blade basis recomputed), re-solves its eigenproblem, names the modes again and
differences the eigenvalue of the mode of the same name: nothing of the perturbation formula or of
the element derivatives.  Blade properties: about the nominal steady state (held fixed, as the
sensitivities define it); support parameters (tower, nacelle, drivetrain), which do not move the
blade's steady state: whole re-analyses of the changed turbine.

Tolerance (issue 31): the frequency derivative within 1 % or 1e-4 x the frequency, the damping
ratio's within 1 % or 1e-4 (per unit of the parameter), for the modes whose derivative is defined
(not near a veering).  The differences are central with h = 1e-3 (relative) or 1 mm (offsets).
"""

from __future__ import annotations

import numpy as np
import pytest

from windflutter.sensitivity import finite_difference as fd
from windflutter.sensitivity.eigen import blade_jacobians, blade_vectors, frequency_damping, mbc_derivative
from windflutter.sensitivity.point import point_sensitivities
from windflutter.system.modes import point_modes
from windflutter.system.multiblade import BladeSystem, multiblade_system

WIND, MAX_HZ = 15.0, 2.0
#: the blade elements of the spanwise segment changed (r/R ~ 0.3-0.5 of the 30-element blade)
SEGMENT = np.arange(8, 14)


@pytest.fixture(scope="module")
def point(nrel5mw):
    from windflutter.api import analysis_config
    from windflutter.operating import campbell_model

    om = campbell_model(nrel5mw, analysis_config())
    ps = om.at(WIND)
    modes = point_modes(ps, MAX_HZ)
    return om, ps, modes, point_sensitivities(om, ps, modes)


def mismatches(res, derivs: dict, reference: dict, label: str) -> list[str]:
    """The modes whose frequency or damping derivative misses the reference (module tolerance)."""
    bad = []
    for i, m in enumerate(res.modes):
        ref = reference[m.identity_name]
        assert np.isfinite(ref), f"{label}: {m.identity_name} not found after the change"
        lam = complex(m.eigenvalue)
        (df, dz), (df0, dz0) = frequency_damping(lam, derivs[i]), frequency_damping(lam, ref)
        if abs(df - df0) > max(0.01 * abs(df0), 1e-4 * m.frequency_hz):
            bad.append(f"{label} {m.identity_name}: dfreq {df:.6g} against {df0:.6g} Hz")
        if abs(dz - dz0) > max(0.01 * abs(dz0), 1e-4):
            bad.append(f"{label} {m.identity_name}: dzeta {dz:.6g} against {dz0:.6g}")
    return bad


def _defined(res, name):
    assert np.all(res.defined[name]), f"{name}: a mode near a veering at {WIND} m/s: {res.pair_ratio[name]}"


@pytest.mark.parametrize("prop, h", [("edge_stiffness", 1e-3), ("mass_offset", 1e-3)])
def test_blade_segment_against_reanalyses(point, prop, h):
    """A spanwise segment's edge stiffness and mass-centre position: every mode up to 2 Hz of the
    NREL 5 MW at 15 m/s (tower, 1st/2nd flap, 1st edge, all whirls)."""
    om, ps, modes, res = point
    _defined(res, prop)
    ref = fd.frozen_blade(om, ps, res.names, prop, h, SEGMENT, MAX_HZ)
    assert mismatches(res, res.blade[prop][:, SEGMENT].sum(axis=1), ref, prop) == []


def test_tower_stiffness_against_reanalyses(point):
    """The tower's stiffness (its wall's Young's modulus): the whole turbine re-analysed (steady state
    included: the blade's does not depend on the tower)."""
    om, ps, modes, res = point
    _defined(res, "tower_stiffness")
    ref = fd.full_reanalysis(om, WIND, res.names, "tower_stiffness", 1e-3, MAX_HZ)
    assert mismatches(res, res.globals_["tower_stiffness"], ref, "tower_stiffness") == []


def test_blade_contraction_is_the_multiblade_systems(point):
    """The blade vectors (the multi-blade transformation's adjoint written out, eigen.blade_vectors)
    give the same derivative as central differences of the multi-blade system assembled with a
    random change of the blade's M, C, K: the derivation of the Coleman and Jacobian terms."""
    om, ps, modes, res = point
    from windflutter.sensitivity.eigen import mode_vectors

    rng = np.random.default_rng(0)
    bs = ps.blade_system
    n = bs.M.shape[0]
    d = {k: rng.standard_normal((n, n)) * np.abs(getattr(bs, k)).max() for k in ("M", "C", "K")}
    h = 1e-6

    def changed(s):
        return multiblade_system(ps.fixed, BladeSystem(M=bs.M + s * d["M"], C=bs.C + s * d["C"], K=bs.K + s * d["K"],
                                                       F=bs.F, Az=bs.Az, Bq=bs.Bq, Bv=bs.Bv),
                                 ps.n_blades, ps.omega, om.rotor.shaft_axis)

    plus, minus = changed(h), changed(-h)
    jac = blade_jacobians(ps.mbc, ps.fixed.L, ps.omega, om.rotor.shaft_axis)
    for mv in mode_vectors(ps.mbc, [m.eigenvalue for m in modes[:6]]):
        bv = blade_vectors(mv, ps.mbc, jac, ps.omega)
        t = sum(bv.l[b] @ (d["M"] @ bv.rM[b] + d["C"] @ bv.rC[b] + d["K"] @ bv.rK[b]) for b in range(ps.n_blades))
        got = -t / mv.norm
        ref = mbc_derivative(mv, plus, minus, h)
        assert abs(got - ref) <= 1e-6 * abs(ref), (got, ref)


def test_station_sums_and_units(point):
    """The stations are the blade's elements (r/R increasing within (0, 1]); the structural damping's
    derivative is linear (d/d ln mu of a linear term): it equals the reanalysis with a 1 % change."""
    om, ps, modes, res = point
    st = res.station
    assert np.all(np.diff(st) > 0) and 0 < st[0] and st[-1] <= 1.0
    assert res.blade["edge_stiffness"].shape == (len(modes), len(st))
    ref = fd.frozen_blade(om, ps, res.names, "damping", 1e-2, SEGMENT, MAX_HZ)
    assert mismatches(res, res.blade["damping"][:, SEGMENT].sum(axis=1), ref, "damping") == []
