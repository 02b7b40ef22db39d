"""The deck writer: an :class:`~windflutter.structure.fem.FEModel` -> NASTRAN bulk data text."""

from __future__ import annotations

import json
import warnings
from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.bdf.beam import BEAM_E, BEAM_G, BEAM_NU, BeamCardValues, dropped_terms
from windflutter.structure.bdf.cards import CARDS, BdfApproximationWarning
from windflutter.structure.constraints import diaphragm_rows
from windflutter.structure.fem import FEModel, IsotropicMaterial, OrthotropicMaterial

META_TAG = "$WF "
#: the MPC set of the diaphragms
MPC_SET = 2
META_WIDTH = 72


def bdf_text(fe: FEModel, title: str, full_deck: bool, n_modes: int) -> str:
    """The whole deck (SOL 103 case control if ``full_deck``) with the ``$WF`` exact-data block."""
    fe.check()
    deck = _Deck(fe)
    if full_deck:
        deck.case_control(title, n_modes)
    deck.out.append("$ written by windflutter.structure.io_bdf; SI units (m, kg, s, N)\n"
                    f"$ {fe.n_nodes} GRID, {len(fe.shell_conn)} CQUAD4, {len(fe.beam_conn)} CBEAM, "
                    f"{len(fe.masses)} CONM2, {len(fe.rigid_links)} RBE2, {len(fe.diaphragms)} diaphragms (MPC)\n")
    deck.grids()
    deck.shell_properties()
    deck.beam_properties()
    deck.materials()
    deck.shells()
    deck.beams()
    deck.masses()
    deck.rigid_links()
    deck.diaphragms()
    deck.springs()
    deck.spcs()
    return deck.finish()


class _Deck:
    """Cards and ``$WF`` data of one deck, written group by group in deck order.

    Element ids run on across CQUAD4, CBEAM, CONM2, RBE2 and CELAS2 (``eid``); material ids
    in order of first use by a shell property.
    """

    def __init__(self, fe: FEModel):
        self.fe = fe
        self.out: list[str] = []
        self.meta: dict[str, Any] = {"version": 1}
        self.eid = 0
        self.materials_used: list[Any] = []
        self.mat_id: dict[Any, int] = {}
        self.nodes = np.asarray(fe.nodes, dtype=float)

    def card(self, name: str, rows: list[tuple] = (), **values: Any) -> None:
        self.out.append(CARDS[name].text(rows, **values))

    def next_eid(self) -> int:
        self.eid += 1
        return self.eid

    def mid_of(self, mat: Any) -> int:
        if mat not in self.mat_id:
            self.materials_used.append(mat)
            self.mat_id[mat] = len(self.materials_used)
        return self.mat_id[mat]

    # ------------------------------------------------------------------ groups of cards
    def case_control(self, title: str, n_modes: int) -> None:
        self.out.append("SOL 103\nCEND\n")
        self.out.append(f"TITLE = {title[:60]}\nECHO = NONE\n")
        if self.fe.spc:
            self.out.append("SPC = 1\n")
        if self.fe.diaphragms:
            self.out.append(f"MPC = {MPC_SET}\n")
        self.out.append("METHOD = 1\nDISPLACEMENT(PLOT) = ALL\nBEGIN BULK\n")
        self.out.append("PARAM,COUPMASS,1\nPARAM,GRDPNT,0\nPARAM,WTMASS,1.0\n")
        self.card("EIGRL", SID=1, V1=None, V2=None, ND=int(n_modes))

    def grids(self) -> None:
        for i, xyz in enumerate(self.nodes):
            self.card("GRID", ID=i + 1, CP=0, X1=xyz[0], X2=xyz[1], X3=xyz[2])

    def shell_properties(self) -> None:
        """PSHELL for a single isotropic ply at 0 degrees, else PCOMP (plies MID, T, THETA deg)."""
        for k, prop in enumerate(self.fe.shell_properties):
            pid = k + 1
            if len(prop.plies) == 0:
                raise InputError(f"shell_properties[{k}].plies", (), "at least one ply")
            for j, p in enumerate(prop.plies):
                if not p.thickness > 0:
                    raise InputError(f"shell_properties[{k}].plies[{j}].thickness", p.thickness,
                                     "a positive thickness (m)")
            ply0 = prop.plies[0]
            if len(prop.plies) == 1 and isinstance(ply0.material, IsotropicMaterial) and ply0.angle == 0.0:
                mid = self.mid_of(ply0.material)
                self.card("PSHELL", PID=pid, MID1=mid, T=ply0.thickness, MID2=mid, MID3=mid, NSM=0.0,
                          **{"12I/T**3": 1.0, "TS/T": 5.0 / 6.0})
            else:
                rows = [(self.mid_of(p.material), p.thickness, np.degrees(p.angle), "NO") for p in prop.plies]
                self.card("PCOMP", rows, PID=pid, NSM=0.0)

    def beam_properties(self) -> None:
        """PBEAM per section and one unit-modulus MAT1 shared by all (warns of lost terms)."""
        fe = self.fe
        pid0 = len(fe.shell_properties)
        beam_meta, lossy = [], []
        beam_mid = len(self.materials_used) + 1 + 10_000  # kept clear of ply materials
        for k, sec in enumerate(fe.beam_sections):
            K, M = np.asarray(sec.stiffness, float), np.asarray(sec.mass, float)
            if K.shape != (6, 6) or M.shape != (6, 6):
                raise InputError(f"beam_sections[{k}]", (K.shape, M.shape), "6x6 stiffness and mass matrices")
            cv = BeamCardValues.from_section(sec)
            if not (cv.EA > 0 and cv.GJ > 0 and cv.EIy > 0 and cv.EIz > 0 and cv.GAy > 0 and cv.GAz > 0):
                raise InputError(f"beam_sections[{k}].stiffness", np.diag(K).tolist(), "a positive diagonal")
            dropped = dropped_terms(sec, cv.section())
            if dropped:
                lossy.append(f"section {k} ({sec.name or 'unnamed'}): {dropped}")
            self.card("PBEAM", **cv.pbeam_fields(pid0 + k + 1, beam_mid))
            beam_meta.append({"pid": pid0 + k + 1, "name": sec.name, "card": cv.as_list(),
                              "K": K.tolist(), "M": M.tolist()})
        if fe.beam_sections:
            self.card("MAT1", MID=beam_mid, E=BEAM_E, G=BEAM_G, NU=BEAM_NU, RHO=0.0)
        if lossy:
            shown = "; ".join(lossy[:3]) + (f"; ... ({len(lossy) - 3} more)" if len(lossy) > 3 else "")
            warnings.warn(
                f"{len(lossy)} of {len(fe.beam_sections)} beam sections have terms PBEAM cannot carry, "
                f"NASTRAN will see the sections without them (windflutter's read_bdf restores them from "
                f"the $WF comments): {shown}", BdfApproximationWarning, stacklevel=4)
        self.meta["beam_sections"] = beam_meta

    def materials(self) -> None:
        for mat in self.materials_used:
            mid = self.mat_id[mat]
            if isinstance(mat, IsotropicMaterial):
                self.card("MAT1", MID=mid, E=mat.E, G=mat.G, NU=mat.nu, RHO=mat.rho)
            elif isinstance(mat, OrthotropicMaterial):
                self.card("MAT8", MID=mid, E1=mat.E1, E2=mat.E2, NU12=mat.nu12, G12=mat.G12, G1Z=mat.G13,
                          G2Z=mat.G23, RHO=mat.rho)
            else:
                raise InputError("material", type(mat).__name__, "IsotropicMaterial or OrthotropicMaterial")
        self.meta["materials"] = {str(self.mat_id[m]): m.name for m in self.materials_used if m.name}
        self.meta["shell_properties"] = [p.name for p in self.fe.shell_properties]

    def shells(self) -> None:
        """One CORD2R per distinct material axis (its x-axis), CQUAD4 with MCID and ZOFFS."""
        conn = np.asarray(self.fe.shell_conn, dtype=np.int64)
        if len(conn):
            dirs, inv = _unique_directions(np.asarray(self.fe.shell_matdir, float))
            for c, d in enumerate(dirs):
                z = _perp_unit(d)
                self.card("CORD2R", CID=c + 1, RID=0, A1=0.0, A2=0.0, A3=0.0, B1=z[0], B2=z[1], B3=z[2],
                          C1=d[0], C2=d[1], C3=d[2])
            offsets = np.array([p.offset for p in self.fe.shell_properties], float)
            pids = np.asarray(self.fe.shell_prop, np.int64)
            for e in range(len(conn)):
                off = float(offsets[pids[e]])
                g = conn[e] + 1
                self.card("CQUAD4", EID=self.next_eid(), PID=int(pids[e]) + 1, G1=g[0], G2=g[1], G3=g[2],
                          G4=g[3], **{"THETA/MCID": int(inv[e]) + 1}, ZOFFS=off if off != 0.0 else None)
        self.meta["n_shell"] = int(len(conn))

    def beams(self) -> None:
        fe = self.fe
        bconn = np.asarray(fe.beam_conn, dtype=np.int64)
        borient = np.asarray(fe.beam_orient, float)
        self.meta["beam_eid0"] = self.eid
        if len(bconn):
            _check_orientations(self.nodes, bconn, borient)
        pid0 = len(fe.shell_properties)
        for e in range(len(bconn)):
            v = borient[e]
            self.card("CBEAM", EID=self.next_eid(), PID=pid0 + int(fe.beam_section[e]) + 1,
                      GA=bconn[e, 0] + 1, GB=bconn[e, 1] + 1, X1=v[0], X2=v[1], X3=v[2])
        self.meta["n_beam"] = int(len(bconn))

    def masses(self) -> None:
        """CONM2 in the basic system; the card holds ``I21 = -J_xy`` etc. (QRG CONM2 remarks)."""
        for m in self.fe.masses:
            J = np.asarray(m.inertia, float).reshape(3, 3)
            J = 0.5 * (J + J.T)
            X = np.asarray(m.offset, float).reshape(3)
            self.card("CONM2", EID=self.next_eid(), G=m.node + 1, CID=0, M=m.mass, X1=X[0], X2=X[1], X3=X[2],
                      BLANK=None, I11=J[0, 0], I21=-J[1, 0], I22=J[1, 1], I31=-J[2, 0], I32=-J[2, 1],
                      I33=J[2, 2])
        self.meta["masses"] = [m.name for m in self.fe.masses]

    def rigid_links(self) -> None:
        for r in self.fe.rigid_links:
            comps = "".join(str(c + 1) for c in sorted(set(r.dofs)))
            rows = [(g,) for g in (np.asarray(r.dependent, np.int64) + 1).tolist()]
            self.card("RBE2", rows, EID=self.next_eid(), GN=r.independent + 1, CM=comps)
        self.meta["rigid_links"] = [r.name for r in self.fe.rigid_links]

    def diaphragms(self) -> None:
        """One MPC (set :data:`MPC_SET`) per eliminated DOF of every diaphragm: ``u_dep - sum a u = 0``
        (the relation :mod:`windflutter.structure.constraints` imposes); the diaphragms themselves in
        the ``$WF`` data."""
        x = np.asarray(self.fe.nodes, float)
        for k, dia in enumerate(self.fe.diaphragms):
            for rows, cols, vals, deps in diaphragm_rows(x, dia, k):
                for d in deps:
                    on = rows == d
                    terms = [(int(d) // 6 + 1, int(d) % 6 + 1, 1.0)]
                    terms += [(int(c) // 6 + 1, int(c) % 6 + 1, -float(v)) for c, v in zip(cols[on], vals[on])]
                    terms += [(None, None, None)] * (len(terms) % 2)
                    lines = [terms[i] + terms[i + 1] + (None, None) for i in range(0, len(terms), 2)]
                    self.card("MPC", lines, SID=MPC_SET)
        self.meta["diaphragms"] = [{"name": d.name, "independent": int(d.independent),
                                    "dependent": np.asarray(d.dependent, np.int64).tolist(),
                                    "normal": np.asarray(d.normal, float).tolist()} for d in self.fe.diaphragms]

    def springs(self) -> None:
        """CELAS2 per non-zero diagonal entry (off-diagonal terms: warning, kept in $WF)."""
        spring_meta = []
        for k, s in enumerate(self.fe.springs):
            Ks = np.asarray(s.stiffness, float)
            if Ks.shape != (6, 6):
                raise InputError(f"springs[{k}].stiffness", Ks.shape, "a 6x6 matrix (N/m, N m/rad)")
            off = Ks - np.diag(np.diag(Ks))
            if np.any(np.abs(off) > 1e-12 * (np.max(np.abs(np.diag(Ks))) or 1.0)):
                warnings.warn(f"spring {k} ({s.name or 'unnamed'}): off-diagonal stiffness terms cannot be "
                              "written as CELAS2 and are dropped for NASTRAN (kept in the $WF comments)",
                              BdfApproximationWarning, stacklevel=4)
            eids = []
            for c in np.flatnonzero(np.diag(Ks) != 0.0):
                eids.append(self.next_eid())
                grounded = s.node_b is None
                self.card("CELAS2", EID=eids[-1], K=Ks[c, c], G1=s.node_a + 1, C1=c + 1,
                          G2=None if grounded else s.node_b + 1, C2=None if grounded else c + 1)
            spring_meta.append({"name": s.name, "eids": eids, "K": Ks.tolist()})
        self.meta["springs"] = spring_meta

    def spcs(self) -> None:
        """SPC1 (set 1) grouped by component set."""
        groups: dict[str, list[int]] = {}
        for node, comps in sorted(self.fe.spc.items()):
            cs = "".join(str(c + 1) for c in sorted(set(comps)))
            if cs:
                groups.setdefault(cs, []).append(node + 1)
        for cs, nids in groups.items():
            self.card("SPC1", [(g,) for g in nids], SID=1, C=cs)

    def finish(self) -> str:
        """Append the ``$WF`` block (names, regions, node groups, exact sections) and ENDDATA."""
        fe, meta = self.fe, self.meta
        meta["node_groups"] = {k: np.asarray(v, np.int64).tolist() for k, v in fe.node_groups.items()}
        meta["element_regions"] = {k: np.asarray(v, np.int64).tolist() for k, v in fe.element_regions.items()}
        meta["region_names"] = list(fe.region_names)
        self.out.append("$ windflutter exact data (names, regions, full sections); a comment to NASTRAN\n")
        blob = json.dumps(meta, separators=(",", ":"))
        self.out.extend(META_TAG + blob[i : i + META_WIDTH] + "\n" for i in range(0, len(blob), META_WIDTH))
        self.out.append("ENDDATA\n")
        return "".join(self.out)


def _perp_unit(d: np.ndarray) -> np.ndarray:
    """A unit vector perpendicular to unit vector d."""
    a = np.eye(3)[int(np.argmin(np.abs(d)))]
    z = np.cross(d, a)
    return z / np.linalg.norm(z)


def _unique_directions(dirs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Normalise the material axes and group equal ones (to 1e-12). Returns (unique, inverse)."""
    if len(dirs) == 0:
        return np.zeros((0, 3)), np.zeros(0, dtype=np.int64)
    if dirs.ndim != 2 or dirs.shape[1] != 3:
        raise InputError("shell_matdir", dirs.shape, "an (ns, 3) array of material axis vectors")
    nrm = np.linalg.norm(dirs, axis=1)
    if np.any(~np.isfinite(nrm)) or np.any(nrm <= 0):
        bad = int(np.flatnonzero(~(nrm > 0))[0])
        raise InputError(f"shell_matdir[{bad}]", dirs[bad].tolist(), "a non-zero material axis vector")
    unit = dirs / nrm[:, None]
    key = np.round(unit, 12) + 0.0  # +0.0 folds -0.0 into 0.0
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return unit[first], inverse.reshape(-1)


def _check_orientations(nodes: np.ndarray, bconn: np.ndarray, borient: np.ndarray) -> None:
    """Each beam's orientation vector is given and not parallel to the beam."""
    if borient.shape != (len(bconn), 3):
        raise InputError("beam_orient", borient.shape, f"an ({len(bconn)}, 3) array of orientation vectors")
    axis = nodes[bconn[:, 1]] - nodes[bconn[:, 0]]
    cross = np.linalg.norm(np.cross(axis, borient), axis=1)
    bad = np.flatnonzero(~(cross > 1e-9 * np.linalg.norm(axis, axis=1) * np.linalg.norm(borient, axis=1)))
    if bad.size:
        raise InputError(f"beam_orient[{int(bad[0])}]", borient[bad[0]].tolist(),
                         "a vector not parallel to its beam (and beams of non-zero length)")
