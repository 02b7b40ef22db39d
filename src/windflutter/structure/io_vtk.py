"""VTK (VTU) export of an :class:`~windflutter.structure.fem.FEModel` and its mode shapes.

One unstructured grid (written with meshio) holds

* cells: shells as ``quad``, beams as ``line``, lumped masses as ``vertex`` and, optionally,
  rigid links as ``line`` spokes from the independent to each dependent node;
* cell data: ``element_kind`` (0 shell, 1 beam, 2 lumped mass, 3 rigid link), ``element_index``
  (index within its kind), ``property_id`` (shell property / beam section index, -1 otherwise),
  ``region_id`` (from ``fe.element_regions``, -1 where none), ``lumped_mass`` (kg);
* field data: one entry ``region:<name>`` = id per region name (ParaView lists them);
* point data: for each mode shape ``<name>`` the translations as a vector (n, 3) and the
  rotations as ``<name>_rot``; complex shapes are written as ``<name>_re``/``<name>_im``
  (and ``_rot_re``/``_rot_im``); node groups as 0/1 arrays ``group:<name>``; any extra arrays
  given in ``point_data``.

In ParaView: open the .vtu, colour by ``region_id``, apply *Warp By Vector* with a mode array.
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence
from xml.sax.saxutils import quoteattr

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.fem import FEModel

__all__ = ["write_vtk", "write_vtu", "model_cells", "region_field_data", "KIND_SHELL", "KIND_BEAM", "KIND_MASS", "KIND_RIGID"]

KIND_SHELL, KIND_BEAM, KIND_MASS, KIND_RIGID = 0, 1, 2, 3


def _regions(fe: FEModel, kind: str, n: int) -> np.ndarray:
    r = fe.element_regions.get(kind)
    if r is None:
        return np.full(n, -1, dtype=np.int64)
    r = np.asarray(r, dtype=np.int64).reshape(-1)
    if r.shape[0] != n:
        raise InputError(f"element_regions[{kind!r}]", r.shape[0], f"{n} region ids (one per {kind} element)")
    return r


def model_cells(fe: FEModel, rigid_links: bool = True) -> tuple[list[tuple[str, np.ndarray]], dict[str, list[np.ndarray]]]:
    """meshio cell blocks and cell data of a model (see module docstring for the arrays)."""
    fe.check()
    cells: list[tuple[str, np.ndarray]] = []
    data: dict[str, list[np.ndarray]] = {k: [] for k in ("element_kind", "element_index", "property_id",
                                                          "region_id", "lumped_mass")}

    def add(ctype, conn, kind, prop, region, mass=None):
        n = len(conn)
        if n == 0:
            return
        cells.append((ctype, np.asarray(conn, dtype=np.int64)))
        data["element_kind"].append(np.full(n, kind, dtype=np.int64))
        data["element_index"].append(np.arange(n, dtype=np.int64))
        data["property_id"].append(np.asarray(prop, dtype=np.int64))
        data["region_id"].append(region)
        data["lumped_mass"].append(np.zeros(n) if mass is None else np.asarray(mass, float))

    ns, nb = len(fe.shell_conn), len(fe.beam_conn)
    add("quad", np.asarray(fe.shell_conn).reshape(-1, 4), KIND_SHELL, fe.shell_prop, _regions(fe, "shell", ns))
    add("line", np.asarray(fe.beam_conn).reshape(-1, 2), KIND_BEAM, fe.beam_section, _regions(fe, "beam", nb))
    if fe.masses:
        nm = len(fe.masses)
        add("vertex", np.array([[m.node] for m in fe.masses]), KIND_MASS, np.full(nm, -1),
            _regions(fe, "mass", nm), [m.mass for m in fe.masses])
    if rigid_links and fe.rigid_links:
        spokes = np.array([[r.independent, d] for r in fe.rigid_links for d in np.asarray(r.dependent).reshape(-1)],
                          dtype=np.int64).reshape(-1, 2)
        add("line", spokes, KIND_RIGID, np.full(len(spokes), -1), np.full(len(spokes), -1, dtype=np.int64))
    return cells, data


def _nodal(vec: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    u = vec.reshape(n_nodes, 6)
    return u[:, :3], u[:, 3:]


def write_vtk(
    fe: FEModel,
    path: str | Path,
    mode_shapes: np.ndarray | None = None,
    names: Sequence[str] | None = None,
    point_data: Mapping[str, np.ndarray] | None = None,
    *,
    rigid_links: bool = True,
) -> Path:
    """Write the model (and optional mode shapes) as a VTU file.

    Parameters
    ----------
    fe : the model.
    path : output ``.vtu`` file.
    mode_shapes : (n_dof,) or (n_dof, n_modes) real or complex array in the global numbering
        ``6*node + c`` (m and rad).
    names : one name per mode (default ``mode_1``, ``mode_2``...).
    point_data : extra nodal arrays, each (n_nodes,) or (n_nodes, k).
    rigid_links : also draw rigid links as line spokes (``element_kind`` 3).

    Returns
    -------
    Path of the written file.
    """
    import meshio  # noqa: PLC0415  (a core dependency; imported lazily to keep imports light)

    path = Path(path)
    if path.suffix.lower() != ".vtu":
        raise InputError("path", str(path), "a file name ending in .vtu")
    cells, cdata = model_cells(fe, rigid_links=rigid_links)
    n = fe.n_nodes
    pdata: dict[str, np.ndarray] = {}
    if mode_shapes is not None:
        phi = np.asarray(mode_shapes)
        if phi.ndim == 1:
            phi = phi[:, None]
        if phi.ndim != 2 or phi.shape[0] != fe.n_dof:
            raise InputError("mode_shapes", phi.shape, f"an ({fe.n_dof},) or ({fe.n_dof}, n_modes) array")
        if not np.all(np.isfinite(phi)):
            raise InputError("mode_shapes", "non-finite values", "finite mode shapes")
        nm = phi.shape[1]
        if names is None:
            names = [f"mode_{i + 1}" for i in range(nm)]
        names = list(names)
        if len(names) != nm or len(set(names)) != nm:
            raise InputError("names", names, f"{nm} distinct mode names")
        for j, name in enumerate(names):
            col = phi[:, j]
            if np.iscomplexobj(col) and np.any(col.imag != 0):
                for part, arr in (("re", col.real), ("im", col.imag)):
                    t, r = _nodal(np.ascontiguousarray(arr), n)
                    pdata[f"{name}_{part}"], pdata[f"{name}_rot_{part}"] = t, r
            else:
                pdata[name], pdata[f"{name}_rot"] = _nodal(np.ascontiguousarray(col.real, dtype=float), n)
    for gname, idx in fe.node_groups.items():
        flag = np.zeros(n, dtype=np.int64)
        flag[np.asarray(idx, dtype=np.int64)] = 1
        pdata[f"group:{gname}"] = flag
    for key, arr in (point_data or {}).items():
        a = np.asarray(arr)
        if a.shape[:1] != (n,) or a.ndim > 2:
            raise InputError(f"point_data[{key!r}]", a.shape, f"an ({n},) or ({n}, k) array")
        if key in pdata:
            raise InputError("point_data", key, "a name not already used by a mode or node group")
        pdata[key] = a
    mesh = meshio.Mesh(np.asarray(fe.nodes, float), cells, point_data=pdata, cell_data=cdata)
    write_vtu(path, mesh, region_field_data(fe.region_names))
    return path


def region_field_data(region_names: Sequence[str]) -> dict[str, int]:
    """Field-data entries ``region:<name>`` -> region id."""
    return {f"region:{nm}": i for i, nm in enumerate(region_names)}


def write_vtu(path: str | Path, mesh, field_data: Mapping[str, int] | None = None) -> Path:
    """Write a meshio mesh as VTU atomically, adding integer field data.

    meshio's VTU writer drops ``field_data``; VTK XML keeps it in a ``<FieldData>`` block
    before the ``<Piece>`` (ParaView shows it in the Information panel; meshio reads it back).
    """
    import meshio  # noqa: PLC0415

    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    meshio.write(tmp, mesh, file_format="vtu")
    if field_data:
        arrays = "".join(
            f'<DataArray type="Int64" Name={quoteattr(str(k))} NumberOfTuples="1" format="ascii">{int(v)}</DataArray>\n'
            for k, v in field_data.items())
        text = tmp.read_text()
        text = text.replace("<UnstructuredGrid>", f"<UnstructuredGrid>\n<FieldData>\n{arrays}</FieldData>", 1)
        tmp.write_text(text)
    tmp.replace(path)
    return path
