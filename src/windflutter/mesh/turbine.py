"""Whole-turbine FE model (shell or beam) and its aerodynamic strips: ``build_model``.

Topology (seed, Castillo Capponi 2010, sec. 4.1.2-4.1.4): tower clamped at the base; hub and
nacelle lumped at their centres of mass; one rigid tie (RBE2-like) joining the tower-top centre
node (independent) to the tower-top ring, the nacelle and hub nodes and every blade-root node,
so hub and nacelle are rigid and the rotor is locked to the nacelle.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.aero.sections import AeroSections, RotorGeometry
from windflutter.errors import InputError
from windflutter.mesh import aero_map as am
from windflutter.mesh.beam_model import blade_beam_mesh, blade_beam_properties
from windflutter.mesh.blade_shell import blade_shell_mesh
from windflutter.mesh.frames import blade_placement, rot_y
from windflutter.mesh.loft import chord_frame
from windflutter.mesh.settings import MeshSettings
from windflutter.mesh.tower import tower_beam_mesh, tower_shell_mesh
from windflutter.structure.fem import FEModel, LumpedMass, RigidLink


@dataclass
class _Builder:
    nodes: list = field(default_factory=list)
    n: int = 0
    shell_conn: list = field(default_factory=list)
    shell_prop: list = field(default_factory=list)
    shell_matdir: list = field(default_factory=list)
    shell_region: list = field(default_factory=list)
    shell_properties: list = field(default_factory=list)
    beam_conn: list = field(default_factory=list)
    beam_section: list = field(default_factory=list)
    beam_orient: list = field(default_factory=list)
    beam_region: list = field(default_factory=list)
    beam_sections: list = field(default_factory=list)
    region_names: list = field(default_factory=list)

    def add_nodes(self, xyz: np.ndarray) -> np.ndarray:
        xyz = np.atleast_2d(np.asarray(xyz, dtype=float))
        ids = self.n + np.arange(len(xyz))
        self.nodes.append(xyz)
        self.n += len(xyz)
        return ids

    def region(self, name: str) -> int:
        if name not in self.region_names:
            self.region_names.append(name)
        return self.region_names.index(name)

    def add_properties(self, kind: str, properties) -> int:
        """Append shell properties (``kind="shell"``) or beam sections (``"beam"``); return the
        index of the first one."""
        props = self.shell_properties if kind == "shell" else self.beam_sections
        start = len(props)
        props.extend(properties)
        return start

    def add_elements(self, kind: str, conn, prop, orient, region) -> None:
        """Append elements: connectivity, property index, material axis (shells) or section y
        reference (beams), region id per element."""
        lists = ((self.shell_conn, self.shell_prop, self.shell_matdir, self.shell_region) if kind == "shell"
                 else (self.beam_conn, self.beam_section, self.beam_orient, self.beam_region))
        for lst, v in zip(lists, (conn, prop, orient, region)):
            lst.append(v)


def rotor_geometry(turbine) -> RotorGeometry:
    """Rotor apex and shaft axis (global) of the turbine."""
    return RotorGeometry(hub_center=turbine.rotor_apex, shaft_axis=turbine.nacelle.shaft_axis())


def build_model(turbine, settings: MeshSettings | None = None) -> tuple[FEModel, AeroSections]:
    """Turn a :class:`~windflutter.model.turbine.Turbine` into an FE model and aero strips.

    Parameters
    ----------
    turbine : the turbine description (SI).
    settings : :class:`MeshSettings` (model kind, part, element counts, pitch, azimuth).

    Returns
    -------
    fe : :class:`FEModel` with node groups ``blade0..``, ``tower``, ``rotor`` (blades + hub),
        ``hub``, ``nacelle``, ``tower_top`` as present.
    sections : :class:`AeroSections`, ``n_span`` strips per blade (empty for ``part="tower"``).
    """
    st = settings or MeshSettings()
    if hasattr(turbine, "require"):
        turbine.require(st.part)  # data the files lack (e.g. nacelle mass) refused by name, part by part
    b = _Builder()
    apex = turbine.rotor_apex
    shaft = turbine.nacelle.shaft_axis()
    tilt = turbine.nacelle.shaft_tilt
    nb = int(turbine.n_blades)
    if nb < 1:
        raise InputError("assembly.number_of_blades", nb, "at least 1")
    groups: dict[str, np.ndarray] = {}
    masses: list[LumpedMass] = []
    links: list[RigidLink] = []
    spc: dict[int, tuple[int, ...]] = {}
    all6 = (0, 1, 2, 3, 4, 5)

    with_blades = st.part in ("turbine", "blade", "rotor")
    blade_ids = range(1 if st.part == "blade" else nb) if with_blades else range(0)

    # ---------------------------------------------------------------- blade (local) mesh, once
    if st.model == "shell":
        bm = blade_shell_mesh(turbine.blade, turbine.airfoils, turbine.materials, st)
        eta = bm.eta
        local_nodes = bm.nodes
        pstart = b.add_properties("shell", bm.properties)
    else:
        bm = blade_beam_mesh(turbine.blade, st.n_span, st.span_clustering, blade_beam_properties(turbine))
        eta = bm.eta
        local_nodes = bm.nodes
        pstart = b.add_properties("beam", bm.sections)
    eta_mid = 0.5 * (eta[:-1] + eta[1:])
    blade = turbine.blade
    ref = np.column_stack([np.interp(eta, blade.s, blade.ref_axis[:, c]) for c in range(3)])
    ref_mid = np.column_stack([np.interp(eta_mid, blade.s, blade.ref_axis[:, c]) for c in range(3)])
    tw_mid = blade.at("twist", eta_mid)
    ec_local, _ = chord_frame(tw_mid)
    root_nodes_all = []
    blade_place = []
    strip_blocks = []
    strips: dict[str, list] = {k: [] for k in ("blade", "radius", "width", "chord", "ea", "origin", "ec", "es", "af", "twist")}
    for k in blade_ids:
        psi = st.azimuth + 2 * np.pi * k / nb
        R, origin = blade_placement(apex, turbine.hub.radius, st.pitch, turbine.hub.precone, psi, tilt)
        blade_place.append((R, origin))
        ids = b.add_nodes(origin[None, :] + local_nodes @ R.T)
        off = ids[0]
        if st.model == "shell":
            rid = np.array([b.region(f"blade{k}:{nm}") for nm in bm.region_names])
            b.add_elements("shell", bm.conn + off, bm.prop + pstart, bm.matdir @ R.T, rid[bm.region])
            roots = bm.station_nodes[0] + off
        else:
            b.add_elements("beam", bm.conn + off, np.arange(len(bm.sections)) + pstart, bm.orient @ R.T,
                           np.full(len(bm.conn), b.region(f"blade{k}")))
            roots = np.array([off])
        groups[f"blade{k}"] = ids
        root_nodes_all.append(roots)
        # aero strips of this blade
        o = origin[None, :] + ref_mid @ R.T
        dref = np.diff(ref, axis=0)
        width = np.linalg.norm(dref, axis=1)
        es = (dref / width[:, None]) @ R.T
        rel = o - apex[None, :]
        radius = np.linalg.norm(rel - (rel @ shaft)[:, None] * shaft[None, :], axis=1)
        gx = b.nodes[-1]  # this blade's global node coordinates
        for i in range(len(eta_mid)):
            if st.model == "shell":
                sn = np.concatenate([bm.station_nodes[i], bm.station_nodes[i + 1]])
                cols, W = am.rigid_fit_rows(gx[sn], sn + off, o[i])
            else:
                c0, W0 = am.rigid_transfer_rows(gx[i], i + off, o[i])
                c1, W1 = am.rigid_transfer_rows(gx[i + 1], i + 1 + off, o[i])
                cols, W = np.concatenate([c0, c1]), 0.5 * np.hstack([W0, W1])
            strip_blocks.append((cols, W))
        strips["blade"].append(np.full(len(eta_mid), k))
        strips["radius"].append(radius)
        strips["width"].append(width)
        strips["chord"].append(blade.at("chord", eta_mid))
        strips["ea"].append(2.0 * blade.at("pitch_axis", eta_mid) - 1.0)
        strips["origin"].append(o)
        strips["ec"].append(ec_local @ R.T)
        strips["es"].append(es)
        strips["af"].append(np.arange(len(eta_mid)))
        strips["twist"].append(tw_mid)

    # ---------------------------------------------------------------- tower
    top_node = None
    if st.part in ("turbine", "tower"):
        use_beam = st.model == "beam" or st.tower_model == "beam"
        if use_beam:
            tm = tower_beam_mesh(turbine.tower, turbine.materials, st.n_tower_axial, offset=b.n)
        else:
            tm = tower_shell_mesh(turbine.tower, turbine.materials, st.n_tower_circ, st.n_tower_axial, offset=b.n)
        kind = "beam" if use_beam else "shell"
        b.add_nodes(tm.nodes)
        start = b.add_properties(kind, tm.properties)
        b.add_elements(kind, tm.conn, tm.prop + start, tm.matdir, np.full(len(tm.conn), b.region("tower")))
        if use_beam:
            top_node = int(tm.ring_nodes[-1, 0])
            top_ring = np.zeros(0, dtype=np.int64)
        else:
            top_ring = tm.ring_nodes[-1]
            top_node = int(b.add_nodes([[0.0, 0.0, turbine.tower.top_z]])[0])
        groups["tower"] = np.concatenate([tm.ring_nodes.ravel(), [top_node] if not use_beam else []]).astype(np.int64)
        groups["tower_top"] = np.array([top_node])
        for nd in tm.ring_nodes[0]:
            spc[int(nd)] = all6
        nac = turbine.nacelle
        nac_node = int(b.add_nodes([[0.0, 0.0, turbine.tower.top_z] + np.asarray(nac.cg, dtype=float)])[0])
        groups["nacelle"] = np.array([nac_node])
        masses.append(LumpedMass(nac_node, float(nac.mass), np.asarray(nac.inertia, dtype=float), name="nacelle"))
        if nac.yaw_bearing_mass > 0:
            masses.append(LumpedMass(top_node, float(nac.yaw_bearing_mass), name="yaw_bearing"))
        tied = [top_ring, [nac_node]]
    else:
        tied = []

    # ---------------------------------------------------------------- hub
    if st.part in ("turbine", "tower", "rotor"):
        hub_node = int(b.add_nodes(apex[None, :])[0])
        groups["hub"] = np.array([hub_node])
        Rt = rot_y(tilt)
        I_hub = Rt @ np.asarray(turbine.hub.inertia, dtype=float) @ Rt.T
        masses.append(LumpedMass(hub_node, float(turbine.hub.mass), I_hub, offset=turbine.hub.cg_offset * shaft, name="hub"))
        if st.part == "tower":
            m, I, cg = rotor_lumped_properties(turbine, st)
            masses.append(LumpedMass(hub_node, m, I, offset=cg - apex, name="blades"))
        tied.append([hub_node])
        if st.part == "rotor":
            spc[hub_node] = all6
            links.append(RigidLink(hub_node, np.concatenate(root_nodes_all).astype(np.int64), name="hub-blade roots"))
            tied = []
    if st.part == "blade":
        for nd in root_nodes_all[0]:
            spc[int(nd)] = all6
    if tied:
        dep = np.concatenate([np.asarray(t, dtype=np.int64) for t in tied] + [r.astype(np.int64) for r in root_nodes_all])
        links.append(RigidLink(top_node, dep, name="tower top-nacelle-hub-blade roots"))
    if with_blades:
        rot = [groups[f"blade{k}"] for k in blade_ids] + ([groups["hub"]] if "hub" in groups else [])
        groups["rotor"] = np.concatenate(rot).astype(np.int64)

    nodes = np.vstack(b.nodes)
    cat = lambda lst, shape, dt: np.concatenate(lst).astype(dt) if lst else np.zeros(shape, dtype=dt)  # noqa: E731
    fe = FEModel(
        nodes=nodes,
        shell_conn=cat(b.shell_conn, (0, 4), np.int64),
        shell_prop=cat(b.shell_prop, (0,), np.int64),
        shell_matdir=cat(b.shell_matdir, (0, 3), float),
        shell_properties=b.shell_properties,
        beam_conn=cat(b.beam_conn, (0, 2), np.int64),
        beam_section=cat(b.beam_section, (0,), np.int64),
        beam_orient=cat(b.beam_orient, (0, 3), float),
        beam_sections=b.beam_sections,
        masses=masses,
        rigid_links=links,
        spc=spc,
        node_groups=groups,
        element_regions={"shell": cat(b.shell_region, (0,), np.int64), "beam": cat(b.beam_region, (0,), np.int64)},
        region_names=b.region_names,
    )
    fe.check()
    polars = am.strip_polars(blade, turbine.airfoils, eta_mid) if with_blades else []
    ns = sum(len(x) for x in strips["blade"])

    def cat_s(key, shape):
        return np.concatenate(strips[key]) if strips[key] else np.zeros(shape)

    sections = AeroSections(
        blade=cat_s("blade", (0,)).astype(np.int64),
        radius=cat_s("radius", (0,)),
        width=cat_s("width", (0,)),
        chord=cat_s("chord", (0,)),
        elastic_axis=cat_s("ea", (0,)),
        origin=cat_s("origin", (0, 3)).reshape(-1, 3),
        e_chord=cat_s("ec", (0, 3)).reshape(-1, 3),
        e_span=cat_s("es", (0, 3)).reshape(-1, 3),
        airfoil=cat_s("af", (0,)).astype(np.int64),
        polars=polars,
        twist=cat_s("twist", (0,)),
        motion_map=am.assemble_motion_map(strip_blocks, fe.n_dof) if ns else am.sp.csr_matrix((0, fe.n_dof)),
    )
    return fe, sections


def blade_mass_points(turbine, settings: MeshSettings) -> tuple[np.ndarray, np.ndarray]:
    """Point masses (kg) and positions (blade root frame, m) representing one blade.

    Shell: element area x areal mass at the element centroid; beam: mass per length x length at
    the element midpoint (offset by the section mass centre).
    """
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
