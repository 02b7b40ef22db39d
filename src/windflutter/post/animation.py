"""Animation of a (complex) mode shape as a VTK time series: one cycle, openable in ParaView.

Frame k of n shows the real motion ``u_k = s * Re(phi * exp(i * 2 pi k / n))`` -- the physical
displacement of an oscillation ``Re(phi e^{i omega t})`` at ``t = k T / n`` -- written as a
VTU with the *deformed* node positions (so the animation plays without filters) plus the
arrays ``displacement`` (m), ``rotation`` (rad) and the per-node peak amplitude
``amplitude`` (m).  Cells carry the model's ``region_id`` / ``property_id`` / ``element_kind``
(see :mod:`windflutter.structure.io_vtk`).  A ParaView ``.pvd`` collection lists the frames
with their times (s if the frequency is given, else fractions of the period).

The scale ``s`` makes the largest translation over the cycle (exact, not sampled) equal to
``fraction`` times the model size (diagonal of the node bounding box).
"""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.fem import FEModel
from windflutter.structure.io_vtk import model_cells, region_field_data, write_vtu

__all__ = ["write_mode_animation", "peak_translation", "model_size", "animation_scale"]


def model_size(fe: FEModel) -> float:
    """Diagonal of the nodes' bounding box (m)."""
    nodes = np.asarray(fe.nodes, float)
    return float(np.linalg.norm(nodes.max(axis=0) - nodes.min(axis=0))) if len(nodes) else 0.0


def peak_translation(fe: FEModel, mode: np.ndarray) -> np.ndarray:
    """Per-node maximum over one cycle of ``|Re(phi_t e^{i theta})|`` (translations only).

    With ``phi_t = a + i b`` the squared length ``|a cos t - b sin t|^2`` has the exact maximum
    ``(|a|^2 + |b|^2)/2 + sqrt(((|a|^2 - |b|^2)/2)^2 + (a.b)^2)``.
    """
    u = np.asarray(mode).reshape(fe.n_nodes, 6)[:, :3]
    a, b = u.real, np.imag(u)
    A, B, C = (a * a).sum(1), (b * b).sum(1), (a * b).sum(1)
    return np.sqrt(0.5 * (A + B) + np.sqrt((0.5 * (A - B)) ** 2 + C * C))


def animation_scale(fe: FEModel, mode: np.ndarray, fraction: float = 0.1) -> float:
    """Scale factor making the largest translation over a cycle ``fraction`` x model size."""
    if not (np.isfinite(fraction) and fraction > 0):
        raise InputError("fraction", fraction, "a positive fraction of the model size, e.g. 0.1")
    peak = float(peak_translation(fe, mode).max(initial=0.0))
    size = model_size(fe)
    if not peak > 0:
        raise InputError("mode", "zero translations", "a mode shape with non-zero translations")
    if not size > 0:
        raise InputError("fe.nodes", "all nodes coincide", "a model with a non-zero extent")
    return fraction * size / peak


def write_mode_animation(
    fe: FEModel,
    mode: np.ndarray,
    out: str | Path,
    n_frames: int = 24,
    fraction: float = 0.1,
    scale: float | None = None,
    *,
    name: str = "mode",
    frequency_hz: float | None = None,
    align_phase: bool = True,
    rigid_links: bool = True,
) -> Path:
    """Write one cycle of a mode's motion as ``.pvd`` + one ``.vtu`` per frame.

    Parameters
    ----------
    fe : the model.
    mode : (n_dof,) real or complex mode shape, global numbering ``6*node + c`` (m, rad).
    out : a directory (created; files ``<name>.pvd`` and ``<name>_0000.vtu``...) or a path
        ending in ``.pvd`` (frames next to it, named after its stem).
    n_frames : frames per cycle (>= 4; 24 by default, >= 16 recommended for a smooth loop).
    fraction : largest translation over the cycle as a fraction of the model size (used
        when ``scale`` is None).
    scale : explicit scale factor on the mode (overrides ``fraction``).
    name : base name of the files.
    frequency_hz : if given, frame times are in seconds (one period ``1/f``); else fractions
        of the period.
    align_phase : shift the time origin so that the largest translation component is real
        (frame 0 then shows the mode near its largest deflection); the motion is unchanged.
    rigid_links : include rigid-link spokes in the cells.

    Returns
    -------
    Path of the ``.pvd`` collection.
    """
    # imported first, as before the split: without meshio nothing is checked or created
    import meshio  # noqa: F401

    phi = np.asarray(mode)
    _check_animation_inputs(fe, phi, n_frames, frequency_hz, name)
    phi = phi.astype(complex)
    if align_phase:
        phi = _phase_aligned(fe, phi)
    s = animation_scale(fe, phi, fraction) if scale is None else float(scale)
    if not (np.isfinite(s) and s > 0):
        raise InputError("scale", scale, "a positive scale factor")
    pvd, stem = _collection_path(Path(out), name)
    entries = _write_frames(fe, phi, s, pvd.parent, stem, int(n_frames), frequency_hz, rigid_links)
    _write_collection(pvd, entries)
    return pvd


def _check_animation_inputs(fe: FEModel, phi: np.ndarray, n_frames, frequency_hz, name: str) -> None:
    """Raise InputError unless ``phi`` is a finite (n_dof,) mode, ``n_frames`` an integer >= 4,
    ``frequency_hz`` None or a positive frequency (Hz) and ``name`` a plain file base name."""
    if phi.shape != (fe.n_dof,):
        raise InputError("mode", phi.shape, f"a ({fe.n_dof},) mode shape")
    if not np.all(np.isfinite(phi)):
        raise InputError("mode", "non-finite values", "a finite mode shape")
    if int(n_frames) != n_frames or n_frames < 4:
        raise InputError("n_frames", n_frames, "an integer >= 4 (>= 16 for a smooth animation)")
    if frequency_hz is not None:
        try:
            f_ok = bool(np.isfinite(float(frequency_hz)) and float(frequency_hz) > 0)
        except (TypeError, ValueError):
            f_ok = False
        if not f_ok:
            raise InputError("frequency_hz", frequency_hz, "a positive frequency (Hz) or None")
    if not name or any(c in name for c in "/\\"):
        raise InputError("name", name, "a non-empty file base name without path separators")


def _phase_aligned(fe: FEModel, phi: np.ndarray) -> np.ndarray:
    """The complex mode ``phi`` (m, rad) times ``exp(-i angle)`` making its largest translation
    component real (unchanged if all translations are zero)."""
    trans = phi.reshape(fe.n_nodes, 6)[:, :3].ravel()
    k = int(np.argmax(np.abs(trans)))
    if abs(trans[k]) > 0:
        phi = phi * np.exp(-1j * np.angle(trans[k]))
    return phi


def _collection_path(out: Path, name: str) -> tuple[Path, str]:
    """``(pvd, stem)``: the ``.pvd`` path and the frames' base name for ``out`` (a ``.pvd`` path,
    whose folder is created, or a directory, created, holding ``<name>.pvd``)."""
    if out.suffix.lower() == ".pvd":
        pvd, stem = out, out.stem
        out.parent.mkdir(parents=True, exist_ok=True)
    else:
        out.mkdir(parents=True, exist_ok=True)
        pvd, stem = out / f"{name}.pvd", name
    return pvd, stem


def _write_frames(fe: FEModel, phi: np.ndarray, s: float, folder: Path, stem: str, n_frames: int,
                  frequency_hz: float | None, rigid_links: bool) -> list[tuple[float, str]]:
    """Write the ``n_frames`` VTU frames ``<stem>_<k>.vtu`` of one cycle into ``folder``.

    Parameters
    ----------
    fe : the model.  phi : (n_dof,) complex mode (m, rad).  s : scale factor on it (-).
    frequency_hz : frame times in s of the period ``1/f`` (Hz); None: fractions of the period.
    rigid_links : include rigid-link spokes in the cells.

    Returns
    -------
    ``(time, file name)`` of every frame, time in s (or periods) as a plain float.
    """
    import meshio  # noqa: PLC0415

    cells, cdata = model_cells(fe, rigid_links=rigid_links)
    nodes = np.asarray(fe.nodes, float)
    amp = s * peak_translation(fe, phi)
    period = 1.0 / float(frequency_hz) if frequency_hz is not None else 1.0  # plain float: the .pvd gets "0.25", not "np.float64(0.25)"
    entries = []
    for k in range(n_frames):
        theta = 2.0 * np.pi * k / n_frames
        u = (s * (phi * np.exp(1j * theta)).real).reshape(fe.n_nodes, 6)
        mesh = meshio.Mesh(nodes + u[:, :3], cells, cell_data=cdata,
                           point_data={"displacement": u[:, :3], "rotation": u[:, 3:], "amplitude": amp})
        fname = f"{stem}_{k:04d}.vtu"
        write_vtu(folder / fname, mesh, region_field_data(fe.region_names))
        entries.append((float(k * period / n_frames), fname))
    return entries


def _write_collection(pvd: Path, entries: list[tuple[float, str]]) -> None:
    """Write the ParaView ``.pvd`` collection of the frames (``(time, file)``), atomically."""
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    lines += [f'    <DataSet timestep="{t!r}" group="" part="0" file={quoteattr(f)}/>' for t, f in entries]
    lines += ["  </Collection>", "</VTKFile>", ""]
    tmp = pvd.with_name(pvd.name + ".tmp")
    tmp.write_text("\n".join(lines))
    tmp.replace(pvd)
