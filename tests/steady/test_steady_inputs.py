"""The coned BEM hook of aero/induction.py, the blade frames, and bad input / no steady state."""

import dataclasses
import math

import numpy as np
import pytest

from steady_blades import ROTOR, constant_polar, linear_polar, straight_blade
from windflutter.aero.induction import bem_induction, sections_induction
from windflutter.errors import InputError, ModelError
from windflutter.steady import SteadyOptions, steady_state
from windflutter.steady.geometry import pitching_frames, rotation_matrices, rotation_vectors
from windflutter.structure.assembly import assemble


def _bem(**kw):
    r = np.linspace(5.0, 50.0, 20)
    args = dict(r=r, chord=np.full(20, 2.0), theta=np.radians(np.linspace(15.0, 2.0, 20)), polars=[linear_polar()],
                airfoil=np.zeros(20, int), omega=1.0, n_blades=3, r_tip=51.0, r_hub=4.0, dr=np.full(20, 2.3))
    args.update(kw)
    return bem_induction(**args)


def test_normal_factor_is_the_velocity_triangle_of_the_normal_wind():
    # None and ones are the same code path to the bit; a factor c scales the wind in every
    # element's velocity triangle, so the induction equals that of the wind c V exactly (the totals
    # keep V for Cp, Ct)
    plain = _bem(wind_speed=9.0)
    ones = _bem(wind_speed=9.0, normal_factor=np.ones(20))
    for k in ("a", "ap", "phi", "alpha", "W", "fn", "ft"):
        np.testing.assert_array_equal(getattr(plain, k), getattr(ones, k), err_msg=k)
    c = math.cos(math.radians(12.0))
    coned = _bem(wind_speed=9.0, normal_factor=np.full(20, c))
    slow = _bem(wind_speed=9.0 * c)
    for k in ("a", "ap", "phi", "alpha", "W", "fn", "ft"):
        np.testing.assert_allclose(getattr(coned, k), getattr(slow, k), rtol=1e-12, atol=1e-12, err_msg=k)
    assert coned.power == pytest.approx(slow.power, rel=1e-12)
    assert coned.cp == pytest.approx(slow.cp * c**3, rel=1e-12)
    with pytest.raises(InputError, match="normal_factor"):
        _bem(wind_speed=9.0, normal_factor=np.full(20, 1.5))


def test_sections_induction_cone_uses_each_strips_span():
    # a blade coned 10 deg upwind: cone=True gives every strip the factor cos(10 deg)
    bl = straight_blade(n=10, theta=math.radians(8.0))
    R = rotation_matrices(np.array([[0.0, -math.radians(10.0), 0.0]]))[0]
    sec = dataclasses.replace(bl.sections, origin=bl.sections.origin @ R.T, e_span=bl.sections.e_span @ R.T,
                              e_chord=bl.sections.e_chord @ R.T)
    sec = dataclasses.replace(sec, radius=np.hypot(sec.origin[:, 1], sec.origin[:, 2]))
    got = sections_induction(sec, ROTOR, 8.0, 1.0, n_blades=3, cone=True)
    flat = sections_induction(sec, ROTOR, 8.0, 1.0, n_blades=3)
    ref = sections_induction(sec, ROTOR, 8.0, 1.0, n_blades=3, normal_factor=np.full(10, math.cos(math.radians(10.0))))
    np.testing.assert_allclose(got.phi, ref.phi, rtol=1e-12)
    assert np.abs(got.phi - flat.phi).max() > 1e-3


def test_rotation_vectors_invert_rotation_matrices():
    th = np.array([[0.1, -0.2, 0.3], [0.0, 0.0, 0.0], [1e-9, 0.0, 0.0], [2.0, 1.0, -0.5]])
    np.testing.assert_allclose(rotation_vectors(rotation_matrices(th)), th, atol=1e-12)


def test_pitching_frames_follow_the_mesh_pitch():
    # the frame's y axis is the root chord with its structural twist undone: the pitch.  The blade
    # of steady_blades has its chord angle as twist (pitch 0: the hub frame x, y, z), or, with the
    # twist set to zero, as pitch (y along the chord)
    for theta in (0.0, 0.3):
        bl = straight_blade(n=4, theta=theta)
        np.testing.assert_allclose(pitching_frames(bl.sections, ROTOR)[0], np.eye(3), atol=1e-12)
        sec = dataclasses.replace(bl.sections, twist=np.zeros(4))
        Fp = pitching_frames(sec, ROTOR)[0]
        np.testing.assert_allclose(Fp[:, 1], [math.sin(theta), math.cos(theta), 0.0], atol=1e-12)


def _blade_state(**kw):
    bl = straight_blade(n=10, theta=math.radians(80.0), polar=constant_polar(1.0, 0.1, 0.0))
    args = dict(wind_speed=10.0, omega=0.0, n_blades=3)
    args.update(kw)
    return bl, lambda **o: steady_state(bl.fe, assemble(bl.fe), bl.sections, ROTOR, options=SteadyOptions(**o), **args)


@pytest.mark.parametrize("kw, field", [({"wind_speed": -1.0}, "wind_speed"), ({"omega": float("nan")}, "omega"),
                                       ({"n_blades": 0}, "n_blades"), ({"air_density": 0.0}, "air_density"),
                                       ({"pitch": float("inf")}, "pitch")])
def test_bad_operating_point(kw, field):
    _, run = _blade_state(**kw)
    with pytest.raises(InputError) as e:
        run()
    assert e.value.field == field


@pytest.mark.parametrize("opt, field", [({"tol": 0.0}, "steady.tol"), ({"max_iterations": 0}, "steady.max_iterations"),
                                        ({"relaxation": 2.0}, "steady.relaxation"),
                                        ({"deflection": "yes"}, "steady.deflection"),
                                        ({"max_deflection": -1.0}, "steady.max_deflection")])
def test_bad_options(opt, field):
    with pytest.raises(InputError) as e:
        SteadyOptions(**opt)
    assert e.value.field == field


def test_wrong_model_pieces():
    bl, _ = _blade_state()
    st = assemble(bl.fe)
    other = straight_blade(n=12)
    with pytest.raises(InputError, match="motion_map"):
        steady_state(bl.fe, st, other.sections, ROTOR, 10.0, 0.0, n_blades=3)
    with pytest.raises(InputError, match="rotor_geometry"):
        steady_state(bl.fe, st, bl.sections, None, 10.0, 0.0, n_blades=3)
    fe = dataclasses.replace(bl.fe, node_groups={})
    with pytest.raises(InputError, match="node_groups"):
        steady_state(fe, assemble(fe), bl.sections, ROTOR, 10.0, 1.0, n_blades=3)


def test_no_convergence_and_divergence_are_model_errors():
    _, run = _blade_state(wind_speed=40.0)
    with pytest.raises(ModelError, match="did not converge in 1 iterations"):
        run(max_iterations=1, tol=1e-12)
    s = run(max_iterations=1, tol=1e-12, strict=False)
    assert not s.converged and s.iterations == 1 and s.residual > 1e-12
    with pytest.raises(ModelError, match="no steady state"):
        run(max_deflection=1e-6)
    # and the default converges
    assert run().converged
