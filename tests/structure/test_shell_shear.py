"""The shells' transverse shear: pyfe3d's one-point shear reproduced, and its MITC4 replacement.

References, none of them the code under test: pyfe3d's own ``Quad4`` (its stiffness is linear in the
transverse shear moduli, so ``K(2 G13, 2 G23) - K(G13, G23)`` is its shear term alone); the count of
an element's zero-energy modes (six rigid-body modes; Hughes et al. 1977 report two more for the
one-point shear: the hourglass and the in-plane twist); the constant-shear patch test (a field of
constant transverse shear strain carries exactly ``A_s`` times its area in energy, on any mesh).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.sparse as sp
from shellmodels import iso, plate

from windflutter.errors import InputError
from windflutter.structure import shell as sh
from windflutter.structure.fem import FEModel, OrthotropicMaterial, Ply, ShellProperty
from windflutter.structure.shell_shear import element_frames, one_point_shear, to_global


def _stiffness(fe: FEModel) -> sp.csr_matrix:
    (r, c, v), _ = sh.shell_coo(fe)
    n = 6 * fe.n_nodes
    return sp.coo_matrix((v, (r, c)), shape=(n, n)).tocsr()


def _laminate(t: float, g13: float) -> ShellProperty:
    m = OrthotropicMaterial(E1=40e9, E2=10e9, nu12=0.28, G12=4e9, G13=g13, G23=0.7 * g13, rho=1900.0)
    return ShellProperty(plies=(Ply(m, t / 3, np.radians(30.0)), Ply(m, t / 3, np.radians(-45.0)), Ply(m, t / 3, 0.0)))


def _curved_patch(t: float, g13: float, seed: int = 3) -> FEModel:
    """6 x 5 distorted, curved and warped quads, turned in space, random material directions."""
    rng = np.random.default_rng(seed)
    X, Y = np.meshgrid(np.linspace(0, 2.0, 7), np.linspace(0, 1.5, 6), indexing="ij")
    X = X + 0.05 * rng.standard_normal(X.shape)
    Y = Y + 0.04 * rng.standard_normal(Y.shape)
    Z = 0.3 * np.sin(X) * np.cos(Y) + 0.007 * rng.standard_normal(X.shape)
    turn = np.linalg.qr(rng.standard_normal((3, 3)))[0]
    nodes = np.c_[X.ravel(), Y.ravel(), Z.ravel()] @ turn.T
    idx = np.arange(X.size).reshape(X.shape)
    conn = np.c_[idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()]
    return FEModel(nodes=nodes, shell_conn=conn, shell_prop=np.zeros(len(conn), int),
                   shell_matdir=rng.standard_normal((len(conn), 3)), shell_properties=[_laminate(t, g13)],
                   shell_shear="one-point")


@pytest.mark.parametrize("t", [0.01, 0.6])  # thin, and thicker than the elements (pyfe3d's other rule)
def test_one_point_shear_is_pyfe3d_s(t):
    """What MITC4 subtracts is exactly pyfe3d's shear term (to 1e-12 of its largest entry), thin and
    thick elements, on a curved, warped, distorted patch with an angle-ply laminate."""
    fe1, fe2 = _curved_patch(t, 2e9), _curved_patch(t, 4e9)
    pyfe3d_shear = _stiffness(fe2) - _stiffness(fe1)
    X = np.asarray(fe1.nodes)[fe1.shell_conn]
    prop = sh.pyfe3d_shellprop(fe1.shell_properties[0])
    cs = sh.material_rotation(X, fe1.shell_matdir)
    Ats = np.array([prop.calc_Ats_element(np.degrees(np.arctan2(s, c))) for c, s in cs])
    R, xy = element_frames(X)
    d13, d24 = xy[:, 2] - xy[:, 0], xy[:, 3] - xy[:, 1]
    area = 0.5 * np.abs(d13[:, 0] * d24[:, 1] - d13[:, 1] * d24[:, 0])
    thick = prop.h >= np.sqrt(area)
    assert thick.all() == (t > 0.5) and thick.any() == (t > 0.5)
    Ke = to_global(one_point_shear(xy, Ats, thick), R)
    dofs = (6 * np.asarray(fe1.shell_conn)[:, :, None] + np.arange(6)).reshape(-1, 24)
    rows, cols = np.broadcast_to(dofs[:, :, None], Ke.shape), np.broadcast_to(dofs[:, None, :], Ke.shape)
    mine = sp.coo_matrix((Ke.ravel(), (rows.ravel(), cols.ravel())), shape=pyfe3d_shear.shape).tocsr()
    assert abs(pyfe3d_shear - mine).max() <= 1e-12 * abs(pyfe3d_shear).max()


@pytest.mark.parametrize("t", [0.002, 0.05])
def test_mitc4_element_has_only_its_rigid_body_modes(t):
    """One distorted element: pyfe3d's one-point shear leaves 8 zero-energy modes (rigid body,
    hourglass, in-plane twist); MITC4 the 6 rigid-body ones."""
    fe, _ = plate(1, 1, 1.0, 0.8, iso(70e9, 0.3, 2700.0, t))
    fe.nodes[2] += [0.2, 0.1, 0.0]
    for model, zero in (("one-point", 8), ("mitc4", 6)):
        w = np.linalg.eigvalsh(_stiffness(dataclasses.replace(fe, shell_shear=model)).toarray())
        assert int(np.sum(np.abs(w) < 1e-9 * w.max())) == zero, (model, w[:10])


def test_mitc4_constant_shear_patch():
    """A field of constant transverse shear (``w = a x + b y``, constant rotations; no membrane strain,
    no curvature) on a patch of distorted quads: its energy is ``A_55 |gamma|^2 / 2`` times the area
    (isotropic: ``A_44 = A_55``, ``A_45 = 0``), to round-off."""
    fe, idx = plate(4, 3, 2.0, 1.5, iso(70e9, 0.3, 2700.0, 0.02))
    rng = np.random.default_rng(1)
    inner = idx[1:-1, 1:-1].ravel()
    fe.nodes[inner, :2] += 0.08 * rng.standard_normal((len(inner), 2))
    a, b, rx, ry = 0.01, -0.02, 0.005, 0.003
    d = np.zeros((fe.n_nodes, 6))
    d[:, 2] = a * fe.nodes[:, 0] + b * fe.nodes[:, 1]
    d[:, 3], d[:, 4] = rx, ry
    gamma_xz, gamma_yz = a + ry, b - rx
    A55 = sh.pyfe3d_shellprop(fe.shell_properties[0]).A55
    expected = 0.5 * A55 * (gamma_xz**2 + gamma_yz**2) * 2.0 * 1.5
    for model in ("mitc4", "one-point"):
        K = _stiffness(dataclasses.replace(fe, shell_shear=model))
        energy = 0.5 * d.ravel() @ (K @ d.ravel())
        assert energy == pytest.approx(expected, rel=1e-10), model


def test_unknown_shear_model_is_an_input_error():
    fe, _ = plate(1, 1, 1.0, 1.0, iso(70e9, 0.3, 2700.0, 0.01))
    with pytest.raises(InputError) as exc:
        _stiffness(dataclasses.replace(fe, shell_shear="two-point"))
    assert exc.value.field == "shell_shear"
