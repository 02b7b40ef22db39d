"""VTU export of the model and mode shapes, read back with meshio."""

from __future__ import annotations

import sys
from pathlib import Path

import meshio
import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))
from _models import mixed_model  # noqa: E402

from windflutter.errors import InputError  # noqa: E402
from windflutter.structure.io_vtk import KIND_BEAM, KIND_MASS, KIND_RIGID, KIND_SHELL, write_vtk  # noqa: E402


def _cell_array(mesh, name):
    return np.concatenate([np.asarray(a).reshape(-1) for a in mesh.cell_data[name]])


def test_mesh_cells_and_region_data(tmp_path):
    fe = mixed_model()
    path = write_vtk(fe, tmp_path / "m.vtu")
    mesh = meshio.read(path)
    np.testing.assert_array_equal(mesh.points, fe.nodes)
    blocks = [(c.type, len(c.data)) for c in mesh.cells]
    n_spokes = sum(len(r.dependent) for r in fe.rigid_links)
    assert blocks == [("quad", 6), ("line", 3), ("vertex", 2), ("line", n_spokes)]
    np.testing.assert_array_equal(mesh.cells[0].data, fe.shell_conn)
    np.testing.assert_array_equal(mesh.cells[1].data, fe.beam_conn)
    np.testing.assert_array_equal(mesh.cells[2].data.ravel(), [m.node for m in fe.masses])
    kind = _cell_array(mesh, "element_kind")
    assert kind.tolist() == [KIND_SHELL] * 6 + [KIND_BEAM] * 3 + [KIND_MASS] * 2 + [KIND_RIGID] * n_spokes
    region = _cell_array(mesh, "region_id")
    np.testing.assert_array_equal(region[:6], fe.element_regions["shell"])
    np.testing.assert_array_equal(region[6:9], fe.element_regions["beam"])
    assert np.all(region[9:] == -1)
    prop = _cell_array(mesh, "property_id")
    np.testing.assert_array_equal(prop[:9], np.concatenate([fe.shell_prop, fe.beam_section]))
    np.testing.assert_allclose(_cell_array(mesh, "lumped_mass")[9:11], [25.0, 1.5])
    assert {k: int(np.asarray(v).ravel()[0]) for k, v in mesh.field_data.items()} == {
        "region:skin": 0, "region:cap": 1, "region:tip beam": 2}
    np.testing.assert_array_equal(np.flatnonzero(mesh.point_data["group:beam"]), fe.node_groups["beam"])


def test_mode_shapes_real_and_complex(tmp_path):
    fe = mixed_model()
    rng = np.random.default_rng(0)
    real = rng.standard_normal((fe.n_dof, 2))
    cplx = rng.standard_normal(fe.n_dof) + 1j * rng.standard_normal(fe.n_dof)
    path = write_vtk(fe, tmp_path / "modes.vtu", mode_shapes=np.column_stack([real, cplx]),
                     names=["flap", "edge", "flutter"], point_data={"temperature": np.arange(fe.n_nodes)})
    mesh = meshio.read(path)
    pd = mesh.point_data
    # translations are DOFs 0..2 of each node, rotations 3..5 (global numbering 6*node + c)
    np.testing.assert_array_equal(pd["flap"], real[:, 0].reshape(-1, 6)[:, :3])
    np.testing.assert_array_equal(pd["edge_rot"], real[:, 1].reshape(-1, 6)[:, 3:])
    np.testing.assert_array_equal(pd["flutter_re"], cplx.real.reshape(-1, 6)[:, :3])
    np.testing.assert_array_equal(pd["flutter_im"], cplx.imag.reshape(-1, 6)[:, :3])
    np.testing.assert_array_equal(pd["flutter_rot_im"], cplx.imag.reshape(-1, 6)[:, 3:])
    np.testing.assert_array_equal(pd["temperature"], np.arange(fe.n_nodes))


def test_default_names_and_no_rigid_spokes(tmp_path):
    fe = mixed_model()
    mesh = meshio.read(write_vtk(fe, tmp_path / "a.vtu", mode_shapes=np.ones(fe.n_dof), rigid_links=False))
    assert "mode_1" in mesh.point_data and "mode_1_rot" in mesh.point_data
    assert [c.type for c in mesh.cells] == ["quad", "line", "vertex"]


def test_bad_inputs(tmp_path):
    fe = mixed_model()
    with pytest.raises(InputError, match="mode_shapes"):
        write_vtk(fe, tmp_path / "a.vtu", mode_shapes=np.ones(fe.n_dof - 1))
    with pytest.raises(InputError, match="names"):
        write_vtk(fe, tmp_path / "a.vtu", mode_shapes=np.ones((fe.n_dof, 2)), names=["a"])
    with pytest.raises(InputError, match="point_data"):
        write_vtk(fe, tmp_path / "a.vtu", point_data={"x": np.ones(3)})
    with pytest.raises(InputError, match="vtu"):
        write_vtk(fe, tmp_path / "a.vtk")
    fe.element_regions["shell"] = np.zeros(2, dtype=int)
    with pytest.raises(InputError, match="element_regions"):
        write_vtk(fe, tmp_path / "a.vtu")
