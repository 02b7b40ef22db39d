"""Whole-turbine FE model (shell or beam) and its aerodynamic strips: ``build_model``.

Topology (seed, Castillo Capponi 2010, sec. 4.1.2-4.1.4): tower clamped at the base; hub and
nacelle lumped at their centres of mass; one rigid tie (RBE2-like) joining the tower-top centre
node (independent) to the tower-top ring, the nacelle and hub nodes and every blade-root node,
so hub and nacelle are rigid and the rotor is locked to the nacelle.

The model is composed from parts (:mod:`windflutter.mesh.parts`): the blades placed at their
azimuths with their strips, the tower with the nacelle, the hub.  Besides the seed's parts
(``turbine``, ``blade``, ``tower``, ``rotor``) two substructures serve the multi-blade
(ground-fixed) formulation of :mod:`windflutter.system.multiblade`:

* ``rotor_blade`` -- blade 0 on a massless hub node at the rotor apex, the hub clamped (the
  fixed-interface blade of a Craig-Bampton model; the hub's rigid motion is added there);
* ``support`` -- tower, nacelle and yaw bearing with a massless hub node tied to the tower top
  (the ground-fixed part the rotor sits on).
"""

from __future__ import annotations

import numpy as np

from windflutter.aero_types import AeroSections, RotorGeometry
from windflutter.errors import InputError
from windflutter.mesh import aero_map as am
from windflutter.mesh.beam_model import blade_beam_mesh, blade_beam_properties
from windflutter.mesh.blade_shell import blade_shell_mesh
from windflutter.mesh.frames import blade_placement, rot_y
from windflutter.mesh.layup_check import warn_if_shell_is_another_blade
from windflutter.mesh.parts import ModelBuilder, add_blades, add_tower, hub_mass
from windflutter.mesh.settings import MeshSettings
from windflutter.structure.fem import LumpedMass, RigidLink

ALL6 = (0, 1, 2, 3, 4, 5)


def rotor_geometry(turbine) -> RotorGeometry:
    """Rotor apex and shaft axis (global) of the turbine."""
    return RotorGeometry(hub_center=turbine.rotor_apex, shaft_axis=turbine.nacelle.shaft_axis())


def _blade_ids(turbine, part: str) -> range:
    nb = int(turbine.n_blades)
    if nb < 1:
        raise InputError("assembly.number_of_blades", nb, "at least 1")
    if part in ("blade", "rotor_blade"):
        return range(1)
    return range(nb) if part in ("turbine", "rotor") else range(0)


def build_model(turbine, settings: MeshSettings | None = None):
    """Turn a :class:`~windflutter.model.turbine.Turbine` into an FE model and aero strips.

    Parameters
    ----------
    turbine : the turbine description (SI).
    settings : :class:`MeshSettings` (model kind, part, element counts, pitch, azimuth).

    Returns
    -------
    fe : :class:`FEModel` with node groups ``blade0..``, ``tower``, ``rotor`` (blades + hub),
        ``hub``, ``nacelle``, ``tower_top`` as present.
    sections : :class:`AeroSections`, ``n_span`` strips per blade (empty without blades).
    """
    st = (settings or MeshSettings()).resolved(turbine)
    if hasattr(turbine, "require"):  # refuse a turbine file that lacks what this part needs
        turbine.require(st.part)
    if st.model == "shell" and st.part != "support":  # the shell blades are the layup's blade
        warn_if_shell_is_another_blade(turbine)
    b = ModelBuilder()
    blade_ids = _blade_ids(turbine, st.part)
    roots = add_blades(b, turbine, st, blade_ids) if len(blade_ids) else []
    tied: list = []
    top_node = None
    if st.part in ("turbine", "tower", "support"):
        top_node, tied = add_tower(b, turbine, st)
    if st.part in ("turbine", "tower", "rotor", "rotor_blade", "support"):
        hub_node = int(b.add_nodes(turbine.rotor_apex[None, :])[0])
        b.groups["hub"] = np.array([hub_node])
        if st.part in ("turbine", "tower", "rotor"):
            b.masses.append(hub_mass(turbine, hub_node))
        if st.part == "tower":
            m, I, cg = rotor_lumped_properties(turbine, st)
            b.masses.append(LumpedMass(hub_node, m, I, offset=cg - turbine.rotor_apex, name="blades"))
        tied.append([hub_node])
        if st.part in ("rotor", "rotor_blade"):
            b.spc[hub_node] = ALL6
            b.links.append(RigidLink(hub_node, np.concatenate(roots).astype(np.int64), name="hub-blade roots"))
            tied = []
    if st.part == "blade":
        for nd in roots[0]:
            b.spc[int(nd)] = ALL6
    if tied:
        dep = np.concatenate([np.asarray(t, dtype=np.int64) for t in tied] + [r.astype(np.int64) for r in roots])
        b.links.append(RigidLink(top_node, dep, name="tower top-nacelle-hub-blade roots"))
    if len(blade_ids):
        rot = [b.groups[f"blade{k}"] for k in blade_ids] + ([b.groups["hub"]] if "hub" in b.groups else [])
        b.groups["rotor"] = np.concatenate(rot).astype(np.int64)
    fe = b.fe_model()
    fe.shell_shear = st.shell_shear
    fe.check()
    return fe, b.sections(turbine, fe.n_dof)


def blade_mass_points(turbine, settings: MeshSettings) -> tuple[np.ndarray, np.ndarray]:
    """Point masses (kg) and positions (blade root frame, m) representing one blade.

    Shell: element area x areal mass at the element centroid; beam: mass per length x length at
    the element midpoint (offset by the section mass centre).
    """
    settings = settings.resolved(turbine)
    if settings.model == "shell":
        bm = blade_shell_mesh(turbine.blade, turbine.airfoils, turbine.materials, settings)
        p = bm.nodes[bm.conn]
        area = 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]), axis=1)
        mpa = np.array([pr.mass_per_area for pr in bm.properties])[bm.prop]
        return area * mpa, p.mean(axis=1)
    bm = blade_beam_mesh(turbine.blade, settings.n_span, settings.span_clustering, blade_beam_properties(turbine))
    x0, x1 = bm.nodes[bm.conn[:, 0]], bm.nodes[bm.conn[:, 1]]
    L = np.linalg.norm(x1 - x0, axis=1)
    m = np.array([s.mass[0, 0] for s in bm.sections])
    return m * L, 0.5 * (x0 + x1)


def rotor_lumped_properties(turbine, settings: MeshSettings) -> tuple[float, np.ndarray, np.ndarray]:
    """Mass (kg), inertia about the CG (3x3, kg m^2, global) and CG (global, m) of all blades,
    from point masses of the blade model, for the tower-only model with the rotor lumped."""
    m, x = blade_mass_points(turbine, settings)
    pts, ms = [], []
    for k in range(turbine.n_blades):
        R, origin = blade_placement(
            turbine.rotor_apex, turbine.hub.radius, settings.pitch, turbine.hub.precone,
            settings.azimuth + 2 * np.pi * k / turbine.n_blades, turbine.nacelle.shaft_tilt,
        )
        pts.append(origin[None, :] + x @ R.T)
        ms.append(m)
    P, M = np.vstack(pts), np.concatenate(ms)
    mt = float(M.sum())
    cg = (M[:, None] * P).sum(axis=0) / mt
    d = P - cg
    I = np.eye(3) * np.sum(M * np.sum(d * d, axis=1)) - (M[:, None] * d).T @ d
    return mt, I, cg


__all__ = ["build_model", "rotor_geometry", "blade_mass_points", "rotor_lumped_properties", "rot_y", "am"]
