"""NREL 5 MW beam model: the aero-augmented reduced model against the full-order model.

Reference: the same solver with ``n_modes=None`` (full constrained model, 672 DOF), i.e. no
projection at all. The fast test compares eigenvalues at one operating point; the slow one the
flutter and divergence onsets of the p-k search (issue 7 target: within 0.5 %).
"""

import dataclasses
import math

import numpy as np
import pytest

from windflutter.solve.linsolve import blas_limit
from windflutter.solve.qep import solve_qep

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def turbine():
    from windflutter.model import load_turbine

    t = load_turbine("nrel5mw")
    I = np.asarray(t.nacelle.inertia)
    if not (np.allclose(I, I.T) and np.linalg.eigvalsh(0.5 * (I + I.T)).min() >= -1e-9 * abs(I).max()):
        # as tests/mesh/conftest.py: yaw inertia of Jonkman et al. 2009 (NacYIner)
        t = dataclasses.replace(t, nacelle=dataclasses.replace(t.nacelle, inertia=np.diag([0.0, 0.0, 2607890.0])))
    return t


def _stability(turbine, n_modes, mta, rpm=(20.0, 34.0, 2.0), wind=10.0):
    import windflutter.frozen.turbine as tmod
    from windflutter.solve.aero_reduction import MTAAeroelasticModel

    # reduction "modal": the plain basis; the MTA vectors are added below by hand when asked
    o = tmod.TurbineOptions(model="beam", aero="potential", method="pk", basis_modes=n_modes, reduction="modal",
                            min_rpm=rpm[0], max_rpm=rpm[1], rpm_step=rpm[2])
    ts = tmod.TurbineStability(turbine, o)
    if mta:
        orig = tmod.AeroelasticModel
        tmod.AeroelasticModel = lambda **kw: MTAAeroelasticModel(**kw, mta_wind_speeds=(wind,))
        try:
            ts.model(ts.pitch_at(wind))  # built (and cached) with the augmented basis
        finally:
            tmod.AeroelasticModel = orig
    return ts


def _eigs(ts, wind, rpm, omega, n=8):
    _, _, am = ts.model(ts.pitch_at(wind))
    M, D, K = am.at(wind, rpm * RPM).matrices(omega)
    with blas_limit(1):  # see docs/performance.md, "The biggest effect: BLAS threads on a busy machine"
        e = solve_qep(M, D, K, shift=1j * omega, n_eig=n)
    return e.values


def _worst(lam, ref):
    return max(float(np.min(np.abs(lam - r)) / abs(r)) for r in ref)


def test_mta_reduced_eigenvalues_match_full_order(turbine):
    # 28 RPM is past this model's divergence (23.6 RPM) and near its flutter point (29.1 RPM,
    # 0.18 Hz): the eigenvalues nearest i*1.15 rad/s include the divergent (real-dominated) ones
    wind, rpm, omega = 10.0, 28.0, 1.15
    ref = _eigs(_stability(turbine, None, False), wind, rpm, omega, n=6)
    plain = _eigs(_stability(turbine, 15, False), wind, rpm, omega, n=20)
    mta = _eigs(_stability(turbine, 15, True), wind, rpm, omega, n=20)
    # measured: plain 15 modes/speed misses the divergent eigenvalues (error > 100 %); with the
    # aero MTA vectors the worst error is 2e-4. Require 1e-3 (5x below the 0.5 % onset target)
    # and at least a 100x gain.
    assert _worst(mta, ref) < 1e-3
    assert _worst(mta, ref) < 1e-2 * _worst(plain, ref)


@pytest.mark.slow
def test_onset_reduced_within_half_percent_of_full_order(turbine):
    # measured: full 21.9851 / 23.5966 RPM, reduced (basis 64) +0.002 % / -0.007 %;
    # one BLAS thread: with the library default a busy machine slows the full order 5-10x
    with blas_limit(1):
        full = _stability(turbine, None, False).analyse_operating_point(10.0)
        red = _stability(turbine, 15, True).analyse_operating_point(10.0)
    assert full.flutter_rpm is not None and full.divergence_rpm is not None
    assert abs(red.flutter_rpm - full.flutter_rpm) / full.flutter_rpm < 0.005
    assert abs(red.divergence_rpm - full.divergence_rpm) / full.divergence_rpm < 0.005


#: cases whose first onset lies above the default grid's 40 RPM: their grid is continued (same step,
#: same reduced basis, built from the config's 40 RPM range) up to this speed.  NREL 5 MW, 4 m/s, with
#: the default steady BEM induction (solver.induction): no flutter or divergence up to 40 RPM in the
#: reduced nor the full model (least damped mode: edge, zeta = +0.0058 at 40 RPM in both); the BEM at
#: tip-speed ratios 40-66 (a -> 1, a' -> -0.5..-0.7 over the outer span) takes the tip's relative
#: speed to 0.3-0.55 Omega r.  First onsets: edgewise flutter 59.14 RPM, divergence 63.74 RPM (without
#: induction: flutter 23.3 RPM, divergence 23.65 RPM, inside the default grid).
_GRID_MAX_RPM = {("nrel5mw", "potential", 4.0): 70.0}


@pytest.mark.slow
@pytest.mark.parametrize("name, aero, wind", [("nrel5mw", "potential", 4.0), ("nrel5mw", "potential", 12.0),
                                              ("nrel5mw", "potential", 25.0), ("nrel5mw", "viscous", 14.0),
                                              ("seed20mw", "potential", 10.0)])
def test_map_onsets_default_reduction_within_half_percent_of_full_order(turbine, name, aero, wind):
    # The issue-7 target over the map: the `windflutter run` defaults (whole turbine, beam, mta
    # with 30 modes per reference speed, aero correction vectors at 4 and 25 m/s) against full
    # order (672 DOF, no projection), below, at and above rated and with the viscous strips,
    # and the seed 20 MW, whose onsets are the most sensitive to the correction cut-off (1e-4:
    # -2.2 % / -4.6 %).  Measured: NREL 5 MW flutter within 5e-5, divergence within 1e-7; seed
    # 20 MW +0.02 % / +0.01 %.  The target is 0.5 %; flutter frequency 0.1 %.  NREL 5 MW 4 m/s on
    # its continued grid (_GRID_MAX_RPM): flutter 59.1388 / 59.1360 RPM (+4.6e-5), 1.2058 / 1.2056 Hz,
    # divergence 63.7407 / 63.7408 RPM (reduced / full).
    from windflutter.config import default_config
    from windflutter.model import load_turbine
    from windflutter.workflow import make_analyser

    cfg = default_config()
    grid = np.asarray(cfg.sweep_rpm(), float)
    top = _GRID_MAX_RPM.get((name, aero, wind))
    if top is not None:
        step = grid[1] - grid[0]
        grid = np.arange(grid[0], top + 0.5 * step, step)
    if name != "nrel5mw":
        turbine = load_turbine(name)
    ts = make_analyser(turbine, cfg)._stability(aero, "pk")
    with blas_limit(1):
        red = ts.analyse_operating_point(wind, rpm_grid=grid)
        ts.options = dataclasses.replace(ts.options, reduction="none")
        ts._models.clear()
        full = ts.analyse_operating_point(wind, rpm_grid=grid)
    assert full.flutter_rpm is not None and full.divergence_rpm is not None
    assert ts.model(ts.pitch_at(wind))[2].size == 672  # really the full order
    assert abs(red.flutter_rpm - full.flutter_rpm) / full.flutter_rpm < 0.005
    assert abs(red.divergence_rpm - full.divergence_rpm) / full.divergence_rpm < 0.005
    assert red.flutter_frequency_hz == pytest.approx(full.flutter_frequency_hz, rel=1e-3)
