"""Parts of a turbine FE model: placed blades with their aero strips, the tower with the nacelle,
the hub mass; and the :class:`ModelBuilder` that collects them into an
:class:`~windflutter.structure.fem.FEModel` and :class:`~windflutter.aero.sections.AeroSections`.

Used by :func:`windflutter.mesh.turbine.build_model`; the node numbering is the order in which
the parts are added (blades, tower, nacelle, hub).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from windflutter.aero_types import AeroSections
from windflutter.mesh import aero_map as am
from windflutter.mesh.beam_model import blade_beam_mesh, blade_beam_properties
from windflutter.mesh.blade_shell import blade_shell_mesh
from windflutter.mesh.frames import blade_placement, rot_y
from windflutter.mesh.loft import chord_frame
from windflutter.mesh.tower import tower_beam_mesh, tower_shell_mesh
from windflutter.structure.fem import Diaphragm, FEModel, LumpedMass, RigidLink

_STRIP_KEYS = ("blade", "radius", "width", "chord", "ea", "origin", "ec", "es", "af", "twist")


@dataclass
class ModelBuilder:
    """Accumulates nodes, elements (shell / beam), properties, masses, links, constraints, node
    groups and aero strips of a model under construction."""

    nodes: list = field(default_factory=list)
    n: int = 0
    elements: dict = field(default_factory=lambda: {k: {f: [] for f in ("conn", "prop", "orient", "region")}
                                                    for k in ("shell", "beam")})
    properties: dict = field(default_factory=lambda: {"shell": [], "beam": []})
    region_names: list = field(default_factory=list)
    masses: list = field(default_factory=list)
    links: list = field(default_factory=list)
    diaphragms: list = field(default_factory=list)
    spc: dict = field(default_factory=dict)
    groups: dict = field(default_factory=dict)
    strips: dict = field(default_factory=lambda: {k: [] for k in _STRIP_KEYS})
    strip_blocks: list = field(default_factory=list)
    strip_eta: np.ndarray | None = None

    def add_nodes(self, xyz: np.ndarray) -> np.ndarray:
        """Append node coordinates (m); return their indices."""
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
        start = len(self.properties[kind])
        self.properties[kind].extend(properties)
        return start

    def add_elements(self, kind: str, conn, prop, orient, region) -> None:
        """Append elements: connectivity, property index, material axis (shells) or section y
        reference (beams), region id per element."""
        e = self.elements[kind]
        for key, v in zip(("conn", "prop", "orient", "region"), (conn, prop, orient, region)):
            e[key].append(v)

    def fe_model(self) -> FEModel:
        """The collected :class:`FEModel`."""
        def cat(lst, shape, dt):
            return np.concatenate(lst).astype(dt) if lst else np.zeros(shape, dtype=dt)

        s, b = self.elements["shell"], self.elements["beam"]
        return FEModel(
            nodes=np.vstack(self.nodes),
            shell_conn=cat(s["conn"], (0, 4), np.int64), shell_prop=cat(s["prop"], (0,), np.int64),
            shell_matdir=cat(s["orient"], (0, 3), float), shell_properties=self.properties["shell"],
            beam_conn=cat(b["conn"], (0, 2), np.int64), beam_section=cat(b["prop"], (0,), np.int64),
            beam_orient=cat(b["orient"], (0, 3), float), beam_sections=self.properties["beam"],
            masses=self.masses, rigid_links=self.links, diaphragms=self.diaphragms, spc=self.spc, node_groups=self.groups,
            element_regions={"shell": cat(s["region"], (0,), np.int64), "beam": cat(b["region"], (0,), np.int64)},
            region_names=self.region_names,
        )

    def sections(self, turbine, n_dof: int) -> AeroSections:
        """The collected strips (empty when no blade was added)."""
        st = self.strips

        def cat_s(key, shape):
            return np.concatenate(st[key]) if st[key] else np.zeros(shape)

        ns = sum(len(x) for x in st["blade"])
        polars = am.strip_polars(turbine.blade, turbine.airfoils, self.strip_eta) if ns else []
        mm = am.assemble_motion_map(self.strip_blocks, n_dof) if ns else sp.csr_matrix((0, n_dof))
        return AeroSections(
            blade=cat_s("blade", (0,)).astype(np.int64), radius=cat_s("radius", (0,)), width=cat_s("width", (0,)),
            chord=cat_s("chord", (0,)), elastic_axis=cat_s("ea", (0,)), origin=cat_s("origin", (0, 3)).reshape(-1, 3),
            e_chord=cat_s("ec", (0, 3)).reshape(-1, 3), e_span=cat_s("es", (0, 3)).reshape(-1, 3),
            airfoil=cat_s("af", (0,)).astype(np.int64), polars=polars, twist=cat_s("twist", (0,)), motion_map=mm)


def local_blade_mesh(turbine, st):
    """(mesh, first property index kind) of one blade in its root frame: shell or beam."""
    if st.model == "shell":
        return blade_shell_mesh(turbine.blade, turbine.airfoils, turbine.materials, st)
    return blade_beam_mesh(turbine.blade, st.n_span, st.span_clustering, blade_beam_properties(turbine))


def _strip_rows(b: ModelBuilder, bm, st, gx: np.ndarray, off: int, o: np.ndarray) -> None:
    """Motion-map rows of each strip of one blade: rigid fit of the section's skin nodes (shell) or
    the mean of the element's end nodes carried to the strip point (beam)."""
    if st.model == "shell":
        for i in range(len(o)):
            sn = np.concatenate([bm.station_nodes[i], bm.station_nodes[i + 1]])
            b.strip_blocks.append(am.rigid_fit_rows(gx[sn], sn + off, o[i]))
        return
    k = np.arange(len(o))
    c0, W0 = am.rigid_transfer_rows(gx[k], k + off, o)
    c1, W1 = am.rigid_transfer_rows(gx[k + 1], k + 1 + off, o)
    cols, W = np.concatenate([c0, c1], axis=1), 0.5 * np.concatenate([W0, W1], axis=2)
    b.strip_blocks.extend(zip(cols, W))


def _add_blade_strips(b: ModelBuilder, turbine, k: int, R: np.ndarray, origin: np.ndarray, geo: dict) -> np.ndarray:
    """Record the strip geometry of blade ``k`` placed by ``(R, origin)``; return strip points."""
    apex, shaft = turbine.rotor_apex, turbine.nacelle.shaft_axis()
    o = origin[None, :] + geo["ref_mid"] @ R.T
    rel = o - apex[None, :]
    radius = np.linalg.norm(rel - (rel @ shaft)[:, None] * shaft[None, :], axis=1)
    n = len(geo["eta_mid"])
    for key, val in (("blade", np.full(n, k)), ("radius", radius), ("width", geo["width"]),
                     ("chord", geo["chord"]), ("ea", geo["ea"]), ("origin", o), ("ec", geo["ec_local"] @ R.T),
                     ("es", geo["es_local"] @ R.T), ("af", np.arange(n)), ("twist", geo["twist"])):
        b.strips[key].append(val)
    return o


def _strip_geometry(blade, eta: np.ndarray) -> dict:
    """Strip geometry of one blade in its root frame at the element mid-points of stations ``eta``."""
    eta_mid = 0.5 * (eta[:-1] + eta[1:])
    ref = np.column_stack([np.interp(eta, blade.s, blade.ref_axis[:, c]) for c in range(3)])
    ref_mid = np.column_stack([np.interp(eta_mid, blade.s, blade.ref_axis[:, c]) for c in range(3)])
    tw_mid = blade.at("twist", eta_mid)
    dref = np.diff(ref, axis=0)
    width = np.linalg.norm(dref, axis=1)
    return {"eta_mid": eta_mid, "ref_mid": ref_mid, "twist": tw_mid, "ec_local": chord_frame(tw_mid)[0],
            "es_local": dref / width[:, None], "width": width, "chord": blade.at("chord", eta_mid),
            "ea": 2.0 * blade.at("pitch_axis", eta_mid) - 1.0}


def add_blades(b: ModelBuilder, turbine, st, blade_ids) -> list[np.ndarray]:
    """Mesh the blades ``blade_ids`` at their azimuths ``st.azimuth + 2 pi k / B`` with pitch,
    precone and tilt; add their strips.  Returns the root nodes of each blade."""
    nb = int(turbine.n_blades)
    bm = local_blade_mesh(turbine, st)
    kind = "shell" if st.model == "shell" else "beam"
    pstart = b.add_properties(kind, bm.properties if kind == "shell" else bm.sections)
    geo = _strip_geometry(turbine.blade, bm.eta)
    b.strip_eta = geo["eta_mid"]
    roots = []
    for k in blade_ids:
        R, origin = blade_placement(turbine.rotor_apex, turbine.hub.radius, st.pitch, turbine.hub.precone,
                                    st.azimuth + 2 * np.pi * k / nb, turbine.nacelle.shaft_tilt)
        ids = b.add_nodes(origin[None, :] + bm.nodes @ R.T)
        off = ids[0]
        if kind == "shell":
            rid = np.array([b.region(f"blade{k}:{nm}") for nm in bm.region_names])
            b.add_elements("shell", bm.conn + off, bm.prop + pstart, bm.matdir @ R.T, rid[bm.region])
            roots.append(bm.station_nodes[0] + off)
            _close_tip(b, bm.station_nodes[-1] + off, R[:, 2], st.tip_closure, f"blade{k} tip")
        else:
            b.add_elements("beam", bm.conn + off, np.arange(len(bm.sections)) + pstart, bm.orient @ R.T,
                           np.full(len(bm.conn), b.region(f"blade{k}")))
            roots.append(np.array([off]))
        b.groups[f"blade{k}"] = ids
        o = _add_blade_strips(b, turbine, k, R, origin, geo)
        _strip_rows(b, bm, st, b.nodes[-1], off, o)
    return roots


def _close_tip(b: ModelBuilder, tip: np.ndarray, normal: np.ndarray, closure: str, name: str) -> None:
    """Close a shell blade's end section (skin nodes ``tip``, plane normal ``normal``): a rib
    (:class:`Diaphragm`), a rigid section (:class:`RigidLink`) or nothing (``"open"``)."""
    tip = np.asarray(tip, dtype=np.int64)
    if closure == "rib":
        b.diaphragms.append(Diaphragm(int(tip[0]), tip[1:], np.asarray(normal, float), name=f"{name} rib"))
    elif closure == "rigid":
        b.links.append(RigidLink(int(tip[0]), tip[1:], name=f"{name} rigid section"))


def add_tower(b: ModelBuilder, turbine, st) -> tuple[int, list]:
    """Tower (clamped at the base), nacelle and yaw-bearing masses.  Returns the tower-top node
    (independent node of the top tie) and the node lists to tie to it (top ring, nacelle)."""
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
    b.groups["tower"] = np.concatenate([tm.ring_nodes.ravel(), [top_node] if not use_beam else []]).astype(np.int64)
    b.groups["tower_top"] = np.array([top_node])
    for nd in tm.ring_nodes[0]:
        b.spc[int(nd)] = (0, 1, 2, 3, 4, 5)
    nac = turbine.nacelle
    nac_node = int(b.add_nodes([[0.0, 0.0, turbine.tower.top_z] + np.asarray(nac.cg, dtype=float)])[0])
    b.groups["nacelle"] = np.array([nac_node])
    b.masses.append(LumpedMass(nac_node, float(nac.mass), np.asarray(nac.inertia, dtype=float), name="nacelle"))
    if nac.yaw_bearing_mass > 0:
        b.masses.append(LumpedMass(top_node, float(nac.yaw_bearing_mass), name="yaw_bearing"))
    return top_node, [top_ring, [nac_node]]


def hub_mass(turbine, hub_node: int) -> LumpedMass:
    """The hub's lumped mass at the rotor apex node, inertia turned by the shaft tilt."""
    Rt = rot_y(turbine.nacelle.shaft_tilt)
    I_hub = Rt @ np.asarray(turbine.hub.inertia, dtype=float) @ Rt.T
    shaft = turbine.nacelle.shaft_axis()
    return LumpedMass(hub_node, float(turbine.hub.mass), I_hub, offset=turbine.hub.cg_offset * shaft, name="hub")
