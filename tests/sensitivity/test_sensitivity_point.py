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

from sensitivity_checks import MAX_HZ, SEGMENT, WIND, mismatches
from windflutter.sensitivity import finite_difference as fd
from windflutter.sensitivity.eigen import blade_jacobians, blade_vectors, frequency_damping, mbc_derivative
from windflutter.system.multiblade import BladeSystem, multiblade_system

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


def test_shear_centre_against_reanalyses(point):
    """A segment's shear centre (issue 31's item 2), on the basis held (the blade basis's own change:
    test_sensitivity_point_slow.py)."""
    om, ps, modes, res = point
    _defined(res, "shear_offset")
    ref = fd.frozen_blade(om, ps, res.names, "shear_offset", 1e-3, SEGMENT, MAX_HZ, Phi=ps.Phi)
    assert mismatches(res, res.blade["shear_offset"][:, SEGMENT].sum(axis=1), ref, "shear_offset") == []


def test_shear_and_tension_offsets_move_their_centres():
    """The meaning of the offsets, from the changed section alone: a flapwise shear force applied at
    the shear centre ``e = C[3,1] / C[3,3]`` (C the compliance) does not twist the section, and an
    axial force at the tension centre ``z = -C[4,0] / C[4,4]`` does not bend it edgewise; both move by
    the offset ``p`` (here from a coupled section)."""
    from windflutter.sensitivity.parameters import BLADE_PROPERTIES

    rng = np.random.default_rng(1)
    A = rng.standard_normal((6, 6))
    K = np.diag([2e9, 2e8, 2e8, 2e8, 4e9, 1.7e9]) + 1e7 * (A @ A.T)
    M = np.eye(6)
    p = 0.07
    shear = lambda K: np.linalg.inv(K)[3, 1] / np.linalg.inv(K)[3, 3]  # noqa: E731
    tension = lambda K: -np.linalg.inv(K)[4, 0] / np.linalg.inv(K)[4, 4]  # noqa: E731
    K_s, _ = BLADE_PROPERTIES["shear_offset"].change(K, M, p)
    assert shear(K_s) - shear(K) == pytest.approx(p, rel=1e-9)
    K_t, _ = BLADE_PROPERTIES["tension_offset"].change(K, M, p)
    assert tension(K_t) - tension(K) == pytest.approx(p, rel=1e-9)


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


def test_dataset_and_ranked_table(point):
    """The Dataset of the point (dimensions, units, the derivatives of the point's result) and the
    ranked table's sentence: +1 % of a property over a segment is the segment's sum x 0.01, in
    percentage points of damping."""
    from windflutter.sensitivity.results import as_dataset, segment_table, sentence

    om, ps, modes, res = point
    ds = as_dataset([res], "NREL 5MW")
    assert dict(ds["ddamping"].sizes) == {"mode": len(modes), "wind_speed": 1, "parameter": 9,
                                          "station": len(res.station)}
    assert ds["dfrequency"].attrs["units"] == "Hz" and ds["station"].attrs["units"] == "1"
    i = res.names.index("1st edge BW")
    lam = complex(modes[i].eigenvalue)
    dz = [frequency_damping(lam, d)[1] for d in res.blade["edge_stiffness"][i]]
    assert np.allclose(ds["ddamping"].sel(mode="1st edge BW", parameter="edge_stiffness").values[0], dz)
    rows = segment_table(ds, modes=["1st edge BW"])
    assert abs(rows[0]["dzeta_points"]) >= abs(rows[-1]["dzeta_points"])
    row = next(r for r in rows if r["parameter"] == "edge_stiffness" and r["segment"] == (0.2, 0.4))
    sel = (res.station >= 0.2) & (res.station < 0.4)
    assert row["dzeta_points"] == pytest.approx(100 * 0.01 * np.sum(np.array(dz)[sel]))
    text = sentence(row)
    assert text.startswith("+1 % edge stiffness at r/R 0.2-0.4 ") and "the 1st edge BW damping at 15 m/s by" in text


def test_total_columns(point):
    """``total`` (whole re-analyses) enter the dataset on ``any_parameter`` and the second table;
    plumbing only (here the held derivatives stand in for them: the sentence must then show the same
    number twice). The re-analyses themselves: test_sensitivity_point_slow.py, test_tower_stiffness_... above."""
    import dataclasses

    from windflutter.sensitivity.results import as_dataset, total_table

    om, ps, modes, res = point
    whole = {k: v.sum(axis=1) for k, v in res.blade.items()} | dict(res.globals_)
    ds = as_dataset([dataclasses.replace(res, total=whole)])
    assert ds["ddamping_total"].sizes["any_parameter"] == 14
    lines = total_table(ds, modes=["1st edge BW"])
    assert len(lines) == 14
    for line in lines:
        by = float(line.split(" by ")[1].split(" points")[0])
        held = float(line.split("points (")[1].split(" with")[0])
        assert abs(held) == pytest.approx(by, rel=2e-3, abs=1e-6)


def test_one_eigen_solve_shared_with_point_modes(point):
    """The point's eigen-solve with left vectors handed to ``point_modes`` and to the sensitivities
    (``eig=``, one dense solve per point instead of two) gives the same named modes and bit-identical
    derivatives as each solving its own."""
    from windflutter.system.modes import state_eig
    from windflutter.sensitivity.point import point_sensitivities
    from windflutter.system.modes import point_modes

    om, ps, modes, res = point
    eig = state_eig(ps.mbc)
    shared = point_modes(ps, MAX_HZ, eig=eig)
    assert [m.identity_name for m in shared] == res.names
    assert np.array_equal([m.eigenvalue for m in shared], [m.eigenvalue for m in modes])
    got = point_sensitivities(om, ps, shared, ["edge_stiffness"], ["air_density"], eig=eig)
    assert np.array_equal(got.blade["edge_stiffness"], res.blade["edge_stiffness"])
    assert np.array_equal(got.globals_["air_density"], res.globals_["air_density"])
    assert len(got.vectors) == len(modes)


def test_segment_total_columns(point):
    """``total_segments`` enter the dataset (mode x wind_speed x parameter x segment, units) and the
    second table as one sentence per property and segment; plumbing only (the held segment sums stand
    in for them: each sentence shows the same number twice)."""
    import dataclasses

    from windflutter.sensitivity.results import SEGMENTS, as_dataset, total_table
    from windflutter.sensitivity.steady import segment_elements

    om, ps, modes, res = point
    groups = segment_elements(res.station, SEGMENTS)
    segs = {k: np.stack([v[:, g].sum(axis=1) for g in groups], axis=1) for k, v in res.blade.items()}
    ds = as_dataset([dataclasses.replace(res, total_segments=segs)])
    assert dict(ds["ddamping_total_segment"].sizes) == {"mode": len(modes), "wind_speed": 1, "parameter": 9,
                                                        "segment": 5}
    assert ds["ddamping_total_segment"].attrs["units"] == "1" and list(ds["segment"].values)[1] == "0.2-0.4"
    lines = total_table(ds, modes=["1st edge BW"])
    seg_lines = [ln for ln in lines if " at r/R " in ln]
    assert len(seg_lines) == 9 * 5
    for line in seg_lines:
        by = float(line.split(" by ")[1].split(" points")[0])
        held = float(line.split("points (")[1].split(" with")[0])
        assert abs(held) == pytest.approx(by, rel=2e-3, abs=1e-6)
