"""Pure geometry: airfoil parametrisation, key-arc grids, loft placement, frames."""

import numpy as np
import pytest

from synthetic import ellipse
from windflutter.errors import InputError
from windflutter.mesh import loft as lf
from windflutter.mesh.frames import blade_rotation
from windflutter.mesh.layup import arc_covers, group_laminates
from windflutter.structure.fem import IsotropicMaterial


def test_orient_flips_pressure_first_airfoil():
    x, y = ellipse(0.3)
    xy = lf.orient_airfoil(np.column_stack([x, -y * (1 + 0.2 * (y > 0))]))
    ile = np.argmin(xy[:, 0])
    assert xy[1:ile, 1].mean() > 0  # first half is now the suction side (y > 0)


def test_orient_rejects_bad_coordinates():
    with pytest.raises(InputError):
        lf.orient_airfoil(np.zeros((3, 2)))


def test_resample_reproduces_polyline_points():
    x, y = ellipse(0.25, 101)
    xy = lf.orient_airfoil(np.column_stack([x, y]))
    s = lf.arc_parameter(xy)
    # exact at the original vertices (piecewise-linear arc parametrisation)
    assert np.allclose(lf.resample_airfoil(xy, s), xy, atol=1e-12)
    # LE of a symmetric ellipse lies at half the arc (tolerance: one polyline segment)
    assert abs(lf.leading_edge_arc(xy) - 0.5) < 1.0 / 101
    assert lf.relative_thickness(xy) == pytest.approx(0.25, rel=2e-3)


def test_segmented_grid_hits_keys_and_counts():
    keys = np.array([0.0, 0.2, 0.55, 0.8])
    counts = lf.distribute_counts(np.diff(np.append(keys, 1.0)), 20)
    g = lf.segmented_grid(keys, counts)
    assert counts.sum() == 20 and len(g) == 20
    idx = np.cumsum(counts)[:-1]
    assert np.allclose(g[idx], keys[1:])
    with pytest.raises(InputError):
        lf.distribute_counts(np.ones(5), 3)


def test_loft_recovers_chord_twist_thickness():
    x, y = ellipse(0.3, 400)
    xy = lf.orient_airfoil(np.column_stack([x, y]))
    s = np.linspace(0, 1, 200, endpoint=False)
    shape = lf.resample_airfoil(xy, s)[None]
    tw = np.radians(12.0)
    p = lf.loft(shape, np.array([3.0]), np.array([tw]), np.array([0.25]), np.array([[0.1, -0.2, 10.0]]))[0]
    ile, ite = np.argmin(shape[0, :, 0]), np.argmax(shape[0, :, 0])
    c = p[ite] - p[ile]
    assert np.linalg.norm(c) == pytest.approx(3.0, rel=1e-9)
    # chord LE->TE = cos(tw) y_b + sin(tw) x_b (twist towards feather)
    assert np.arctan2(c[0], c[1]) == pytest.approx(tw, abs=1e-12)
    # pitch axis at 25 % chord from the LE
    assert np.allclose(p[ile] + 0.25 * c, [0.1, -0.2, 10.0], atol=1e-12)
    assert np.all(p[:, 2] == 10.0)


def test_quad_grid_outward_normals_for_skin_order():
    # a circle listed TE(+y) -> suction (+x) -> LE(-y): clockwise about z
    th = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    ring = np.column_stack([np.sin(th), np.cos(th)])
    nodes = np.concatenate([np.column_stack([ring, np.full(16, z)]) for z in (0.0, 1.0)])
    conn = lf.quad_grid(2, 16)
    p = nodes[conn]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 3] - p[:, 0])
    c = p.mean(axis=1)
    assert np.all(np.sum(n[:, :2] * c[:, :2], axis=1) > 0)


def test_blade_rotation_conventions():
    # zero angles: identity; azimuth 90 deg moves blade 0 from +z towards -y (rotor spin +x)
    assert np.allclose(blade_rotation(0, 0, 0, 0), np.eye(3))
    assert np.allclose(blade_rotation(0, 0, np.pi / 2, 0) @ [0, 0, 1], [0, -1, 0], atol=1e-15)
    # positive precone tilts the blade upwind (-x) for an upwind rotor
    assert (blade_rotation(0, 0.1, 0, 0) @ [0, 0, 1])[0] < 0
    # pitch towards feather turns the TE direction (+y_b) downwind (+x)
    assert (blade_rotation(0.2, 0, 0, 0) @ [0, 1, 0])[0] > 0
    # tilt raises the upwind end: shaft axis (downwind) points slightly down
    assert (blade_rotation(0, 0, 0, 0.1) @ [1, 0, 0])[2] < 0


def test_arc_covers_wraps_through_te():
    a = np.array([0.02, 0.5, 0.97])
    assert list(arc_covers(a, 0.9, 0.1)) == [True, False, True]
    assert list(arc_covers(a, 0.1, 0.9)) == [False, True, False]
    assert list(arc_covers(a, 0.0, 1.0)) == [True, True, True]


def test_group_laminates_merges_and_orders_plies():
    m1, m2 = IsotropicMaterial(1e9, 0.3, 1000.0, "a"), IsotropicMaterial(2e9, 0.3, 2000.0, "b")
    T = np.array([[1e-3, 2e-3], [1e-3, 2e-3], [1e-3, 0.0]])
    A = np.zeros_like(T)
    idx, props = group_laminates(T, A, [m1, m2])
    assert len(props) == 2 and idx[0] == idx[1] != idx[2]
    p = props[idx[0]]
    # layers are listed outer -> inner; plies bottom (inner) -> top (outer)
    assert [q.material.name for q in p.plies] == ["b", "a"]
    assert p.mass_per_area == pytest.approx(1e-3 * 1000 + 2e-3 * 2000)


def test_web_keys_keep_order_where_webs_are_absent():
    """A trailing-edge web that exists only on the first half of the span and would cross its
    neighbour near the tip if held constant: the filled keys stay ordered and exact where the
    web exists."""
    from windflutter.mesh.blade_shell import fill_web_keys

    eta = np.linspace(0, 1, 11)
    main = 0.25 - 0.1 * eta  # main web start, drifting towards the TE
    te = np.full(11, 0.18)  # TE web start, only for eta <= 0.4
    on_te = eta <= 0.4
    keys = dict(fill_web_keys([("main", main, np.ones(11, bool)), ("te", te, on_te)], eta))
    assert np.allclose(keys["main"], main)
    assert np.allclose(keys["te"][on_te], 0.18)
    assert np.all(keys["te"] < keys["main"]) and np.all(keys["te"] > 0)


def test_zero_shear_stiffness_means_shear_rigid():
    from windflutter.mesh.beam_model import SHEAR_RIGID_FACTOR, shear_rigid_where_missing

    K = np.diag([10.0, 0.0, 3.0, 1.0, 1.0, 1.0])[None]
    Kr = shear_rigid_where_missing(K)
    assert Kr[0, 1, 1] == SHEAR_RIGID_FACTOR * 10.0 and Kr[0, 2, 2] == 3.0 and K[0, 1, 1] == 0.0
