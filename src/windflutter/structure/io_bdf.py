"""NASTRAN bulk-data export and import of an :class:`~windflutter.structure.fem.FEModel`.

``write_bdf`` writes the deck as plain text in *large-field* fixed format (16-character fields,
about ten significant digits) and needs no third-party package.  ``read_bdf`` parses a deck
with pyNastran (optional extra ``pip install 'windflutter[nastran]'``) and builds an FEModel.

Card mapping (all in the basic coordinate system; grid id = node index + 1)
---------------------------------------------------------------------------
=====================  ======================================================================
FEModel                NASTRAN
=====================  ======================================================================
nodes                  GRID
shell elements         CQUAD4 with MCID (one CORD2R per distinct material axis; NASTRAN
                       projects the MCID x-axis onto the element plane, which is exactly
                       windflutter's ``shell_matdir`` convention) and ZOFFS = property offset
laminate               PCOMP (plies: MID, T, THETA in degrees from the material axis);
                       a single isotropic ply is written as PSHELL (MID1 = MID2 = MID3)
materials              MAT1 (isotropic), MAT8 (orthotropic: E1 E2 NU12 G12 G1Z=G13 G2Z=G23)
beam elements          CBEAM with orientation vector; PBEAM + a unit-modulus MAT1 (E = 1 Pa,
                       nu = 0.3) so that A = EA, I1 = EIz, I2 = EIy, I12 = -EIyz, J = GJ/G,
                       K1 = GAy/(G A), K2 = GAz/(G A); all mass as non-structural mass:
                       NSM = m, M1/M2 = mass-centre offset, NSI = torsional inertia about it
lumped masses          CONM2 (CID 0: offset and inertia in basic axes)
rigid links            RBE2
SPC                    SPC1 (set 1)
springs                CELAS2 per non-zero diagonal term (scalar spring between like DOFs)
=====================  ======================================================================

What standard cards cannot carry -- the off-diagonal terms of a general 6x6 beam section
(extension-twist, bend-twist, shear couplings, tension-centre offsets), the sectional rotary
inertia about y and z, and off-diagonal spring terms -- is reported with a
:class:`BdfApproximationWarning` and, together with names, regions and node groups, stored
exactly in ``$WF`` comment lines that NASTRAN ignores.  ``read_bdf`` restores the exact data
from those comments *only if* the standard cards still hold the values written (an edited
card wins, with a warning), so the round trip ``read_bdf(write_bdf(fe))`` is lossless.
"""

from __future__ import annotations

import json
import math
import shutil
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.fem import (
    BeamSection,
    FEModel,
    IsotropicMaterial,
    LumpedMass,
    OrthotropicMaterial,
    Ply,
    RigidLink,
    ShellProperty,
    Spring,
)

__all__ = ["write_bdf", "read_bdf", "BdfApproximationWarning", "NASTRAN_EXTRA_HINT"]

NASTRAN_EXTRA_HINT = "pip install 'windflutter[nastran]'"
_META_TAG = "$WF "
_META_WIDTH = 72
#: Unit-modulus material used for beams (stiffnesses are carried by the PBEAM "geometry").
_BEAM_E = 1.0
_BEAM_NU = 0.3
_BEAM_G = _BEAM_E / (2.0 * (1.0 + _BEAM_NU))
#: relative tolerance for "the card still holds the value we wrote" (16-character fields)
_CARD_RTOL = 1e-8


class BdfApproximationWarning(UserWarning):
    """Part of the model cannot be represented exactly by standard NASTRAN cards."""


# --------------------------------------------------------------------------------------
# large-field card formatting
# --------------------------------------------------------------------------------------
def _real16(x: float) -> str:
    """Format a real in at most 16 characters with as many significant digits as fit."""
    x = float(x)
    if not math.isfinite(x):
        raise InputError("BDF real field", x, "a finite number")
    if x == 0.0:
        return "0.0"
    # shortest general format that fits in 15 characters (keeps a blank between fields)
    for p in range(17, 8, -1):
        s = format(x, f".{p}g")
        mant, _, exp = s.partition("e")
        if "." not in mant:
            mant += "."
        s = mant + ("e" + exp if exp else "")
        if len(s) <= 15:
            return s
    for p in range(10, 0, -1):
        s = f"{x:.{p}e}"
        if len(s) <= 16:
            return s
    raise InputError("BDF real field", x, "a number representable in 16 characters")


def _field16(v: Any) -> str:
    if v is None:
        return " " * 16
    if isinstance(v, (bool, np.bool_)):
        raise InputError("BDF field", v, "an integer, real or string")
    if isinstance(v, (int, np.integer)):
        s = str(int(v))
    elif isinstance(v, (float, np.floating)):
        s = _real16(float(v))
    else:
        s = str(v)
    if len(s) > 16:
        raise InputError("BDF field", s, "at most 16 characters")
    return s.rjust(16)


def _card(name: str, fields: list[Any]) -> str:
    """One card in large-field format: each small-field line (8 fields) becomes two lines."""
    lines = []
    nchunks = max(1, math.ceil(len(fields) / 8))
    for i in range(nchunks):
        chunk = list(fields[8 * i : 8 * i + 8])
        head = (name + "*") if i == 0 else "*"
        lines.append(head.ljust(8) + "".join(_field16(v) for v in chunk[:4]).rstrip())
        if len(chunk) > 4:
            lines.append("*".ljust(8) + "".join(_field16(v) for v in chunk[4:8]).rstrip())
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------------------
# beam section <-> PBEAM mapping
# --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _BeamCardValues:
    """The values a PBEAM (with the unit-modulus MAT1) carries, in windflutter terms."""

    EA: float
    GAy: float
    GAz: float
    GJ: float
    EIy: float
    EIz: float
    EIyz: float
    m: float
    cy: float
    cz: float
    nsi: float  # torsional mass inertia about the mass centre (kg m^2/m)
    Iyy_m: float = 0.0  # rotary inertia (only from a structural density on foreign decks)
    Izz_m: float = 0.0
    Iyz_m: float = 0.0

    @staticmethod
    def from_section(sec: BeamSection) -> "_BeamCardValues":
        K = np.asarray(sec.stiffness, dtype=float)
        M = np.asarray(sec.mass, dtype=float)
        m = float(M[0, 0])
        cy = float(M[3, 2] / m) if m > 0 else 0.0
        cz = float(-M[3, 1] / m) if m > 0 else 0.0
        return _BeamCardValues(
            EA=K[0, 0], GAy=K[1, 1], GAz=K[2, 2], GJ=K[3, 3], EIy=K[4, 4], EIz=K[5, 5],
            EIyz=0.5 * (K[4, 5] + K[5, 4]), m=m, cy=cy, cz=cz,
            nsi=float(M[3, 3] - m * (cy * cy + cz * cz)),
        )

    def section(self, name: str = "") -> BeamSection:
        """The BeamSection these card values represent exactly."""
        K = np.diag([self.EA, self.GAy, self.GAz, self.GJ, self.EIy, self.EIz]).astype(float)
        K[4, 5] = K[5, 4] = self.EIyz
        m, cy, cz = self.m, self.cy, self.cz
        S = np.array([[0.0, -cz, cy], [cz, 0.0, 0.0], [-cy, 0.0, 0.0]])
        M = np.zeros((6, 6))
        M[:3, :3] = m * np.eye(3)
        M[3:, :3] = m * S
        M[:3, 3:] = (m * S).T
        M[3, 3] = self.nsi + m * (cy * cy + cz * cz)
        M[4, 4] = self.Iyy_m + m * cz * cz
        M[5, 5] = self.Izz_m + m * cy * cy
        M[4, 5] = M[5, 4] = self.Iyz_m - m * cy * cz
        return BeamSection(stiffness=K, mass=M, name=name)

    def as_list(self) -> list[float]:
        return [self.EA, self.GAy, self.GAz, self.GJ, self.EIy, self.EIz, self.EIyz, self.m,
                self.cy, self.cz, self.nsi]


def _close(a: list[float], b: list[float]) -> bool:
    a_, b_ = np.asarray(a, float), np.asarray(b, float)
    scale = np.maximum(np.abs(a_), np.abs(b_))
    # lengths (cg offsets) are compared against the overall magnitude of the entry group
    return bool(np.all(np.abs(a_ - b_) <= _CARD_RTOL * np.maximum(scale, 1e-12 * np.max(scale) + 1e-300)))


def _dropped_terms(sec: BeamSection, rep: BeamSection) -> str:
    """Describe the section entries the standard cards lose (empty if none)."""
    msgs = []
    for label, full, part in (("stiffness", sec.stiffness, rep.stiffness), ("mass", sec.mass, rep.mass)):
        full = np.asarray(full, float)
        diff = np.abs(full - part)
        ref = np.max(np.abs(np.diag(full))) or 1.0
        bad = np.argwhere(diff > 1e-9 * ref)
        bad = [(int(i), int(j)) for i, j in bad if i <= j]
        if bad:
            rel = float(np.max(diff) / ref)
            msgs.append(f"{label} entries {bad} (max {rel:.2e} of the largest diagonal term)")
    return "; ".join(msgs)


# --------------------------------------------------------------------------------------
# writer
# --------------------------------------------------------------------------------------
def _material_cards(mat: IsotropicMaterial | OrthotropicMaterial, mid: int) -> str:
    if isinstance(mat, IsotropicMaterial):
        return _card("MAT1", [mid, float(mat.E), float(mat.G), float(mat.nu), float(mat.rho)])
    if isinstance(mat, OrthotropicMaterial):
        return _card("MAT8", [mid, float(mat.E1), float(mat.E2), float(mat.nu12), float(mat.G12),
                              float(mat.G13), float(mat.G23), float(mat.rho)])
    raise InputError("material", type(mat).__name__, "IsotropicMaterial or OrthotropicMaterial")


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


def _bdf_text(fe: FEModel, title: str, full_deck: bool, n_modes: int) -> str:
    fe.check()
    out: list[str] = []
    meta: dict[str, Any] = {"version": 1}
    if full_deck:
        out.append("SOL 103\nCEND\n")
        out.append(f"TITLE = {title[:60]}\nECHO = NONE\n")
        if fe.spc:
            out.append("SPC = 1\n")
        out.append("METHOD = 1\nDISPLACEMENT(PLOT) = ALL\nBEGIN BULK\n")
        out.append("PARAM,COUPMASS,1\nPARAM,GRDPNT,0\nPARAM,WTMASS,1.0\n")
        out.append(_card("EIGRL", [1, None, None, int(n_modes)]))
    out.append("$ written by windflutter.structure.io_bdf; SI units (m, kg, s, N)\n"
               f"$ {fe.n_nodes} GRID, {len(fe.shell_conn)} CQUAD4, {len(fe.beam_conn)} CBEAM, "
               f"{len(fe.masses)} CONM2, {len(fe.rigid_links)} RBE2\n")

    # grids
    nodes = np.asarray(fe.nodes, dtype=float)
    out.extend(_card("GRID", [i + 1, 0, *map(float, xyz)]) for i, xyz in enumerate(nodes))

    # materials
    materials: list[Any] = []
    mat_id: dict[Any, int] = {}

    def mid_of(mat: Any) -> int:
        if mat not in mat_id:
            materials.append(mat)
            mat_id[mat] = len(materials)
        return mat_id[mat]

    # shell properties
    shell_pid = []
    for k, prop in enumerate(fe.shell_properties):
        pid = k + 1
        shell_pid.append(pid)
        if len(prop.plies) == 0:
            raise InputError(f"shell_properties[{k}].plies", (), "at least one ply")
        for j, p in enumerate(prop.plies):
            if not p.thickness > 0:
                raise InputError(f"shell_properties[{k}].plies[{j}].thickness", p.thickness, "a positive thickness (m)")
        if len(prop.plies) == 1 and isinstance(prop.plies[0].material, IsotropicMaterial) and prop.plies[0].angle == 0.0:
            mid = mid_of(prop.plies[0].material)
            out.append(_card("PSHELL", [pid, mid, float(prop.plies[0].thickness), mid, 1.0, mid, 5.0 / 6.0, 0.0]))
        else:
            fields: list[Any] = [pid, None, 0.0, None, None, None, None, None]
            for p in prop.plies:
                fields += [mid_of(p.material), float(p.thickness), float(np.degrees(p.angle)), "NO"]
            out.append(_card("PCOMP", fields))

    # beam sections (PBEAM + one unit-modulus MAT1 shared by all)
    beam_pid0 = len(fe.shell_properties)
    beam_meta = []
    lossy: list[str] = []
    if fe.beam_sections:
        beam_mid = None
        for k, sec in enumerate(fe.beam_sections):
            K = np.asarray(sec.stiffness, float)
            M = np.asarray(sec.mass, float)
            if K.shape != (6, 6) or M.shape != (6, 6):
                raise InputError(f"beam_sections[{k}]", (K.shape, M.shape), "6x6 stiffness and mass matrices")
            cv = _BeamCardValues.from_section(sec)
            if not (cv.EA > 0 and cv.GJ > 0 and cv.EIy > 0 and cv.EIz > 0 and cv.GAy > 0 and cv.GAz > 0):
                raise InputError(f"beam_sections[{k}].stiffness", np.diag(K).tolist(), "a positive diagonal")
            dropped = _dropped_terms(sec, cv.section())
            if dropped:
                lossy.append(f"section {k} ({sec.name or 'unnamed'}): {dropped}")
            if beam_mid is None:
                beam_mid = len(materials) + 1 + 10_000  # kept clear of ply materials
            A = cv.EA / _BEAM_E
            fields = [beam_pid0 + k + 1, beam_mid, A, cv.EIz / _BEAM_E, cv.EIy / _BEAM_E,
                      -cv.EIyz / _BEAM_E, cv.GJ / _BEAM_G, cv.m]
            fields += [0.0] * 8  # stress recovery points C, D, E, F (end A)
            fields += ["YESA", 1.0, A, cv.EIz / _BEAM_E, cv.EIy / _BEAM_E, -cv.EIyz / _BEAM_E,
                       cv.GJ / _BEAM_G, cv.m]
            fields += [cv.GAy / (_BEAM_G * A), cv.GAz / (_BEAM_G * A), 0.0, 0.0, cv.nsi, cv.nsi, 0.0, 0.0]
            fields += [cv.cy, cv.cz, cv.cy, cv.cz, 0.0, 0.0, 0.0, 0.0]
            out.append(_card("PBEAM", fields))
            beam_meta.append({"pid": beam_pid0 + k + 1, "name": sec.name, "card": cv.as_list(),
                              "K": K.tolist(), "M": M.tolist()})
        out.append(_card("MAT1", [beam_mid, _BEAM_E, _BEAM_G, _BEAM_NU, 0.0]))
    if lossy:
        shown = "; ".join(lossy[:3]) + (f"; ... ({len(lossy) - 3} more)" if len(lossy) > 3 else "")
        warnings.warn(
            f"{len(lossy)} of {len(fe.beam_sections)} beam sections have terms PBEAM cannot carry, "
            f"NASTRAN will see the sections without them (windflutter's read_bdf restores them from "
            f"the $WF comments): {shown}", BdfApproximationWarning, stacklevel=3)
    meta["beam_sections"] = beam_meta

    for mat in materials:
        out.append(_material_cards(mat, mat_id[mat]))
    meta["materials"] = {str(mat_id[m]): m.name for m in materials if m.name}
    meta["shell_properties"] = [p.name for p in fe.shell_properties]

    # material axes -> CORD2R (x-axis = material axis), CQUAD4 with MCID
    eid = 0
    conn = np.asarray(fe.shell_conn, dtype=np.int64)
    if len(conn):
        dirs, inv = _unique_directions(np.asarray(fe.shell_matdir, float))
        for c, d in enumerate(dirs):
            z = _perp_unit(d)
            out.append(_card("CORD2R", [c + 1, 0, 0.0, 0.0, 0.0, *map(float, z), *map(float, d)]))
        offsets = np.array([p.offset for p in fe.shell_properties], float)
        pids = np.asarray(fe.shell_prop, np.int64)
        for e in range(len(conn)):
            eid += 1
            off = float(offsets[pids[e]])
            out.append(_card("CQUAD4", [eid, int(pids[e]) + 1, *(conn[e] + 1).tolist(), int(inv[e]) + 1,
                                        off if off != 0.0 else None]))
    meta["n_shell"] = int(len(conn))

    # beams
    bconn = np.asarray(fe.beam_conn, dtype=np.int64)
    borient = np.asarray(fe.beam_orient, float)
    meta["beam_eid0"] = eid
    if len(bconn):
        if borient.shape != (len(bconn), 3):
            raise InputError("beam_orient", borient.shape, f"an ({len(bconn)}, 3) array of orientation vectors")
        axis = nodes[bconn[:, 1]] - nodes[bconn[:, 0]]
        cross = np.linalg.norm(np.cross(axis, borient), axis=1)
        bad = np.flatnonzero(~(cross > 1e-9 * np.linalg.norm(axis, axis=1) * np.linalg.norm(borient, axis=1)))
        if bad.size:
            raise InputError(f"beam_orient[{int(bad[0])}]", borient[bad[0]].tolist(),
                             "a vector not parallel to its beam (and beams of non-zero length)")
    for e in range(len(bconn)):
        eid += 1
        out.append(_card("CBEAM", [eid, beam_pid0 + int(fe.beam_section[e]) + 1, *(bconn[e] + 1).tolist(),
                                   *map(float, borient[e])]))
    meta["n_beam"] = int(len(bconn))

    # lumped masses
    for m in fe.masses:
        eid += 1
        J = np.asarray(m.inertia, float).reshape(3, 3)
        J = 0.5 * (J + J.T)
        X = np.asarray(m.offset, float).reshape(3)
        out.append(_card("CONM2", [eid, m.node + 1, 0, float(m.mass), *map(float, X), None,
                                   float(J[0, 0]), float(-J[1, 0]), float(J[1, 1]), float(-J[2, 0]),
                                   float(-J[2, 1]), float(J[2, 2])]))
    meta["masses"] = [m.name for m in fe.masses]

    # rigid links
    for r in fe.rigid_links:
        eid += 1
        comps = "".join(str(c + 1) for c in sorted(set(r.dofs)))
        out.append(_card("RBE2", [eid, r.independent + 1, comps, *(np.asarray(r.dependent, np.int64) + 1).tolist()]))
    meta["rigid_links"] = [r.name for r in fe.rigid_links]

    # springs: CELAS2 per non-zero diagonal entry
    spring_meta = []
    for k, s in enumerate(fe.springs):
        Ks = np.asarray(s.stiffness, float)
        if Ks.shape != (6, 6):
            raise InputError(f"springs[{k}].stiffness", Ks.shape, "a 6x6 matrix (N/m, N m/rad)")
        off = Ks - np.diag(np.diag(Ks))
        if np.any(np.abs(off) > 1e-12 * (np.max(np.abs(np.diag(Ks))) or 1.0)):
            warnings.warn(f"spring {k} ({s.name or 'unnamed'}): off-diagonal stiffness terms cannot be written "
                          "as CELAS2 and are dropped for NASTRAN (kept in the $WF comments)",
                          BdfApproximationWarning, stacklevel=3)
        eids = []
        for c in range(6):
            if Ks[c, c] != 0.0:
                eid += 1
                eids.append(eid)
                out.append(_card("CELAS2", [eid, float(Ks[c, c]), s.node_a + 1, c + 1,
                                            None if s.node_b is None else s.node_b + 1,
                                            None if s.node_b is None else c + 1]))
        spring_meta.append({"name": s.name, "eids": eids, "K": Ks.tolist()})
    meta["springs"] = spring_meta

    # SPC1 grouped by component set
    groups: dict[str, list[int]] = {}
    for node, comps in sorted(fe.spc.items()):
        cs = "".join(str(c + 1) for c in sorted(set(comps)))
        if cs:
            groups.setdefault(cs, []).append(node + 1)
    for cs, nids in groups.items():
        out.append(_card("SPC1", [1, cs, *nids]))

    meta["node_groups"] = {k: np.asarray(v, np.int64).tolist() for k, v in fe.node_groups.items()}
    meta["element_regions"] = {k: np.asarray(v, np.int64).tolist() for k, v in fe.element_regions.items()}
    meta["region_names"] = list(fe.region_names)

    out.append("$ windflutter exact data (names, regions, full sections); a comment to NASTRAN\n")
    blob = json.dumps(meta, separators=(",", ":"))
    out.extend(_META_TAG + blob[i : i + _META_WIDTH] + "\n" for i in range(0, len(blob), _META_WIDTH))
    out.append("ENDDATA\n")
    return "".join(out)


def write_bdf(fe: FEModel, path: str | Path, *, title: str = "windflutter model", full_deck: bool = True,
              n_modes: int = 20) -> Path:
    """Write an FEModel as a NASTRAN deck (large-field fixed format).

    Parameters
    ----------
    fe : the model (SI units; written as is, so the deck is in m, kg, s, N).
    path : output file (``.bdf``/``.dat``).
    title : TITLE line of the case control.
    full_deck : if True write a SOL 103 deck (executive + case control with ``SPC = 1``,
        ``METHOD = 1``, EIGRL for ``n_modes`` modes, consistent mass); else bulk data only.
    n_modes : number of modes requested on the EIGRL card.

    Returns
    -------
    Path of the written file.

    Warns
    -----
    BdfApproximationWarning
        when a beam section or spring has terms the standard cards cannot carry (see module
        docstring); windflutter's :func:`read_bdf` still restores them exactly.
    """
    path = Path(path)
    text = _bdf_text(fe, title, full_deck, int(n_modes))
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text)
    tmp.replace(path)
    return path


# --------------------------------------------------------------------------------------
# reader
# --------------------------------------------------------------------------------------
_SUPPORTED_ELEMENTS = {"CQUAD4", "CBEAM", "CBAR", "CELAS1", "CELAS2"}


def _import_pynastran():
    try:
        from pyNastran.bdf.bdf import BDF  # noqa: PLC0415
    except ImportError as exc:  # pragma: no cover - exercised only without the extra
        raise ImportError(f"read_bdf needs pyNastran: {NASTRAN_EXTRA_HINT} "
                          "(pyNastran 1.4.1 pins numpy < 2; use a separate environment, see docs/io.md)") from exc
    return BDF


def _read_meta(path: Path) -> dict[str, Any]:
    chunks = []
    with open(path, errors="replace") as f:
        for line in f:
            if line.startswith(_META_TAG):
                chunks.append(line[len(_META_TAG):].rstrip("\n"))
    if not chunks:
        return {}
    try:
        return json.loads("".join(chunks))
    except json.JSONDecodeError:
        warnings.warn(f"{path}: unreadable $WF metadata ignored", BdfApproximationWarning, stacklevel=3)
        return {}


def _material_from_card(card: Any, names: dict[str, str]) -> IsotropicMaterial | OrthotropicMaterial:
    name = names.get(str(card.mid), "")
    if card.type == "MAT1":
        return IsotropicMaterial(E=float(card.e), nu=float(card.nu), rho=float(card.rho or 0.0), name=name)
    if card.type == "MAT8":
        return OrthotropicMaterial(E1=float(card.e11), E2=float(card.e22), nu12=float(card.nu12),
                                   G12=float(card.g12), G13=float(card.g1z or card.g12),
                                   G23=float(card.g2z or card.g12), rho=float(card.rho or 0.0), name=name)
    raise InputError(f"MID {card.mid}", card.type, "a MAT1 or MAT8 material")


def _quad_material_axis(xyz: np.ndarray, theta_mcid: Any, model: Any) -> np.ndarray:
    """Material axis (global) of a CQUAD4 from its MCID or THETA (degrees from edge G1-G2)."""
    n = np.cross(xyz[2] - xyz[0], xyz[3] - xyz[1])
    n /= np.linalg.norm(n)
    if isinstance(theta_mcid, (int, np.integer)):
        coord = model.coords[int(theta_mcid)]
        return np.asarray(coord.beta()[0], float)  # x-axis of the system in basic
    e1 = xyz[1] - xyz[0]
    e1 = e1 - (e1 @ n) * n
    e1 /= np.linalg.norm(e1)
    th = np.radians(float(theta_mcid or 0.0))
    return np.cos(th) * e1 + np.sin(th) * np.cross(n, e1)


def _beam_values_from_pbeam(prop: Any, mat: Any) -> _BeamCardValues:
    E, G, rho = float(mat.e), float(mat.g), float(mat.rho or 0.0)
    A, I1, I2, I12, J = (float(np.atleast_1d(v)[0]) for v in (prop.A, prop.i1, prop.i2, prop.i12, prop.j))
    nsm = float(np.atleast_1d(prop.nsm)[0])
    k1, k2 = float(prop.k1 if prop.k1 is not None else 1.0), float(prop.k2 if prop.k2 is not None else 1.0)
    nsi = float(prop.nsia or 0.0)
    m1, m2 = float(np.atleast_1d(prop.m1a)[0] or 0.0), float(np.atleast_1d(prop.m2a)[0] or 0.0)
    return _beam_values(E, G, rho, A, I1, I2, I12, J, nsm, k1, k2, nsi, m1, m2)


def _beam_values(E, G, rho, A, I1, I2, I12, J, nsm, k1, k2, nsi, m1, m2) -> _BeamCardValues:
    EA = E * A
    big = 1e3 * max(EA, 1.0)  # K = 0 means shear-rigid in NASTRAN; same stand-in as BeamSection.from_properties
    m = rho * A + nsm
    cy = nsm * m1 / m if m > 0 else 0.0
    cz = nsm * m2 / m if m > 0 else 0.0
    # torsional inertia about the mass centre: structure (rho J_polar about the axis) + NSM part
    ixx = rho * (I1 + I2) + nsi + nsm * (m1 * m1 + m2 * m2)
    return _BeamCardValues(
        EA=EA, GAy=k1 * G * A if k1 > 0 else big, GAz=k2 * G * A if k2 > 0 else big, GJ=G * J,
        EIy=E * I2, EIz=E * I1, EIyz=-E * I12, m=m, cy=cy, cz=cz, nsi=ixx - m * (cy * cy + cz * cz),
        Iyy_m=rho * I2, Izz_m=rho * I1, Iyz_m=-rho * I12,
    )


def read_bdf(path: str | Path) -> FEModel:
    """Read a NASTRAN deck into an FEModel (needs the ``nastran`` extra: pyNastran).

    Supported: GRID (any CP), CQUAD4 (THETA or MCID, ZOFFS) with PSHELL/PCOMP and MAT1/MAT8,
    CBEAM with PBEAM (constant section) and CBAR with PBAR, CONM2 (CID 0/-1), RBE2, SPC1/SPC
    (all sets), CELAS1/CELAS2 between like components.  Node indices follow ascending GRID id;
    elements ascending element id.  Anything else raises :class:`InputError` naming the cards.
    Decks written by :func:`write_bdf` are restored exactly (names, regions, node groups and
    the full 6x6 beam sections from the ``$WF`` comments).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("path", str(path), "an existing NASTRAN bulk-data file")
    BDF = _import_pynastran()
    model = BDF(debug=None)
    model.log.level = "error"
    text = path.read_text(errors="replace")
    upper = text.upper()
    punch = "CEND" not in upper
    if punch and "BEGIN BULK" in upper:  # bulk data with a BEGIN BULK line but no case control
        lines = [ln for ln in text.splitlines(keepends=True) if not ln.upper().lstrip().startswith("BEGIN BULK")]
        tmpdir = tempfile.mkdtemp(prefix="wf_bdf_")
        read_path = Path(tmpdir) / path.name
        read_path.write_text("".join(lines))
    else:
        read_path = path
    try:
        model.read_bdf(str(read_path), punch=punch, xref=True)
    except Exception as exc:  # pyNastran raises many types; report them as input errors
        raise InputError("bdf", str(path), f"a deck pyNastran can read ({type(exc).__name__}: {exc})") from exc
    finally:
        if read_path != path:
            shutil.rmtree(read_path.parent, ignore_errors=True)
    meta = _read_meta(path)

    unsupported = sorted({e.type for e in model.elements.values()} - _SUPPORTED_ELEMENTS)
    unsupported += sorted({r.type for r in model.rigid_elements.values()} - {"RBE2"})
    unsupported += sorted({m.type for m in model.masses.values()} - {"CONM2"})
    if unsupported:
        raise InputError("bdf element types", unsupported, "only CQUAD4, CBEAM, CBAR, CELAS1/2, CONM2, RBE2",
                         source=str(path))

    nids = np.array(sorted(model.nodes), dtype=np.int64)
    if len(nids) == 0:
        raise InputError("GRID", 0, "at least one grid point", source=str(path))
    index = {int(n): i for i, n in enumerate(nids)}
    nodes = np.array([model.nodes[int(n)].get_position() for n in nids], dtype=float)

    def node(nid: int, where: str) -> int:
        if nid not in index:
            raise InputError(where, nid, "a GRID id defined in the deck", source=str(path))
        return index[nid]

    mat_names = meta.get("materials", {})
    mats = {mid: _material_from_card(card, mat_names) for mid, card in model.materials.items()
            if card.type in ("MAT1", "MAT8")}

    # ---- shells
    quads = sorted((e for e in model.elements.values() if e.type == "CQUAD4"), key=lambda e: e.eid)
    shell_pids = sorted(pid for pid, p in model.properties.items() if p.type in ("PSHELL", "PCOMP"))
    prop_names = meta.get("shell_properties", [])
    base_props: dict[int, tuple[tuple[Ply, ...], float]] = {}
    for pid in shell_pids:
        p = model.properties[pid]
        if float(p.nsm or 0.0) != 0.0:
            raise InputError(f"{p.type} {pid}.NSM", p.nsm, "no non-structural mass on shells (add CONM2s)",
                             source=str(path))
        if p.type == "PSHELL":
            if p.mid1 is None:
                raise InputError(f"PSHELL {pid}.MID1", None, "a membrane material", source=str(path))
            if p.mid2 not in (None, p.mid1) or float(p.twelveIt3 or 1.0) != 1.0:
                raise InputError(f"PSHELL {pid}", (p.mid1, p.mid2, p.twelveIt3),
                                 "a homogeneous shell (MID2 = MID1, 12I/T^3 = 1)", source=str(path))
            plies = (Ply(mats[p.mid1], float(p.t), 0.0),)
            z0 = -0.5 * float(p.t)
        else:
            mids, ts, ths = list(p.mids), [float(t) for t in p.thicknesses], [float(t) for t in p.thetas]
            if str(p.lam).upper().startswith("SYM") and len(mids) == p.nplies:
                mids, ts, ths = mids + mids[::-1], ts + ts[::-1], ths + ths[::-1]
            plies = tuple(Ply(mats[m], t, math.radians(th)) for m, t, th in zip(mids, ts, ths))
            z0 = float(p.z0) if p.z0 is not None else -0.5 * sum(ts)
        # offset of the laminate mid-plane from the element reference plane
        base_props[pid] = (plies, z0 + 0.5 * sum(pl.thickness for pl in plies))

    shell_properties: list[ShellProperty] = []
    prop_index: dict[tuple[int, float], int] = {}
    for k, pid in enumerate(shell_pids):
        used = sorted({float(q.zoffset or 0.0) for q in quads if q.pid == pid}) or [0.0]
        for zo in used:
            plies, extra = base_props[pid]
            name = prop_names[k] if (k < len(prop_names) and len(used) == 1) else f"PID{pid}" + (f"_z{zo:g}" if len(used) > 1 else "")
            prop_index[(pid, zo)] = len(shell_properties)
            shell_properties.append(ShellProperty(plies=plies, name=name, offset=zo + extra))
    shell_conn = np.array([[node(n, f"CQUAD4 {q.eid}") for n in q.node_ids] for q in quads], dtype=np.int64).reshape(-1, 4)
    shell_prop = np.array([prop_index[(q.pid, float(q.zoffset or 0.0))] for q in quads], dtype=np.int64)
    shell_matdir = np.array([_quad_material_axis(nodes[shell_conn[i]], q.theta_mcid, model)
                             for i, q in enumerate(quads)], dtype=float).reshape(-1, 3)

    # ---- beams
    beams = sorted((e for e in model.elements.values() if e.type in ("CBEAM", "CBAR")), key=lambda e: e.eid)
    beam_pids = sorted(pid for pid, p in model.properties.items() if p.type in ("PBEAM", "PBAR"))
    exact = {int(b["pid"]): b for b in meta.get("beam_sections", [])}
    beam_sections = []
    for pid in beam_pids:
        p = model.properties[pid]
        mat = model.materials[p.mid]
        n_off = [float(v or 0.0) for v in (*np.atleast_1d(getattr(p, "n1a", 0.0)), *np.atleast_1d(getattr(p, "n2a", 0.0)),
                                            *np.atleast_1d(getattr(p, "n1b", 0.0) or 0.0),
                                            *np.atleast_1d(getattr(p, "n2b", 0.0) or 0.0))]
        if p.type == "PBEAM" and any(n_off):
            raise InputError(f"PBEAM {pid} N1/N2", n_off, "zero neutral-axis offsets (not supported)",
                             source=str(path))
        if p.type == "PBEAM":
            if len(np.atleast_1d(p.A)) > 2 or not np.allclose(np.atleast_1d(p.A), np.atleast_1d(p.A)[0]):
                raise InputError(f"PBEAM {pid}", "tapered section", "a constant section", source=str(path))
            cv = _beam_values_from_pbeam(p, mat)
        else:
            k1 = float(p.k1) if p.k1 is not None else 0.0
            k2 = float(p.k2) if p.k2 is not None else 0.0
            cv = _beam_values(float(mat.e), float(mat.g), float(mat.rho or 0.0), float(p.A), float(p.i1),
                              float(p.i2), float(p.i12), float(p.j), float(p.nsm or 0.0), k1, k2, 0.0, 0.0, 0.0)
        ex = exact.get(pid)
        if ex is not None and _close(ex["card"], cv.as_list()):
            beam_sections.append(BeamSection(stiffness=np.array(ex["K"], float), mass=np.array(ex["M"], float),
                                             name=ex.get("name", "")))
        else:
            if ex is not None:
                warnings.warn(f"{path}: PBEAM {pid} differs from the windflutter data written with it; "
                              "using the card values", BdfApproximationWarning, stacklevel=2)
            beam_sections.append(cv.section(name=f"PID{pid}"))
    beam_index = {pid: k for k, pid in enumerate(beam_pids)}
    beam_conn = np.array([[node(b.ga, f"{b.type} {b.eid}"), node(b.gb, f"{b.type} {b.eid}")] for b in beams],
                         dtype=np.int64).reshape(-1, 2)
    orient = []
    for i, b in enumerate(beams):
        if int(b.pa or 0) or int(b.pb or 0):
            raise InputError(f"{b.type} {b.eid} PA/PB", (b.pa, b.pb), "no pin flags (not supported)", source=str(path))
        wa = np.asarray(getattr(b, "wa", np.zeros(3)) if getattr(b, "wa", None) is not None else np.zeros(3), float)
        wb = np.asarray(getattr(b, "wb", np.zeros(3)) if getattr(b, "wb", None) is not None else np.zeros(3), float)
        if np.any(wa != 0) or np.any(wb != 0):
            raise InputError(f"{b.type} {b.eid} offsets", (wa.tolist(), wb.tolist()), "no beam end offsets",
                             source=str(path))
        if b.g0 is not None:
            v = nodes[node(b.g0, f"{b.type} {b.eid}.G0")] - nodes[beam_conn[i, 0]]
        else:
            v = np.asarray(b.x, float)
            cd = model.nodes[b.ga].cd
            if cd not in (0, None):
                v = model.coords[cd].beta().T @ v
        orient.append(v)
    beam_orient = np.array(orient, float).reshape(-1, 3)
    beam_section = np.array([beam_index[b.pid] for b in beams], dtype=np.int64)

    # ---- masses
    mass_names = meta.get("masses", [])
    masses = []
    for k, m in enumerate(sorted(model.masses.values(), key=lambda m: m.eid)):
        n = node(m.nid, f"CONM2 {m.eid}")
        X = np.asarray(m.X, float)
        if m.cid == -1:
            X = X - nodes[n]
        elif m.cid != 0:
            raise InputError(f"CONM2 {m.eid}.CID", m.cid, "0 or -1 (basic system)", source=str(path))
        masses.append(LumpedMass(node=n, mass=float(m.mass), inertia=np.array(m.Inertia(), float), offset=X,
                                 name=mass_names[k] if k < len(mass_names) else ""))

    # ---- rigid links
    rl_names = meta.get("rigid_links", [])
    rigid = []
    for k, r in enumerate(sorted(model.rigid_elements.values(), key=lambda r: r.eid)):
        dofs = tuple(sorted(int(c) - 1 for c in str(r.cm)))
        rigid.append(RigidLink(independent=node(r.gn, f"RBE2 {r.eid}"),
                               dependent=np.array([node(g, f"RBE2 {r.eid}") for g in r.Gmi], np.int64),
                               dofs=dofs, name=rl_names[k] if k < len(rl_names) else ""))

    # ---- SPC (all sets)
    spc: dict[int, set[int]] = {}
    for sid, cards in model.spcs.items():
        for c in cards:
            if c.type == "SPC1":
                for g in c.node_ids:
                    spc.setdefault(node(g, f"SPC1 {sid}"), set()).update(int(ch) - 1 for ch in str(c.components))
            elif c.type == "SPC":
                for g, comp, val in zip(c.node_ids, c.components, c.enforced):
                    if val not in (0, 0.0, None):
                        raise InputError(f"SPC {sid}", val, "zero enforced displacement", source=str(path))
                    spc.setdefault(node(g, f"SPC {sid}"), set()).update(int(ch) - 1 for ch in str(comp))
            else:
                raise InputError(f"SPC set {sid}", c.type, "SPC1 or SPC cards", source=str(path))
    if len(model.spcs) > 1:
        warnings.warn(f"{path}: {len(model.spcs)} SPC sets found; their union is used", BdfApproximationWarning,
                      stacklevel=2)
    spc_t = {n: tuple(sorted(c)) for n, c in sorted(spc.items())}

    # ---- springs: group scalar springs by node pair
    pairs: dict[tuple[int, int | None], np.ndarray] = {}
    pair_eids: dict[tuple[int, int | None], list[int]] = {}
    for e in sorted((e for e in model.elements.values() if e.type in ("CELAS1", "CELAS2")), key=lambda e: e.eid):
        kval = float(e.k) if e.type == "CELAS2" else float(e.pid_ref.k)
        n1, n2 = e.nodes if hasattr(e, "nodes") else (e.node_ids)
        n1 = n1.nid if hasattr(n1, "nid") else n1
        n2 = n2.nid if hasattr(n2, "nid") else n2
        c1, c2 = int(e.c1 or 0), int(e.c2 or 0)
        if n1 in (None, 0):
            n1, c1, n2, c2 = n2, c2, None, 0
        if n2 not in (None, 0) and c1 != c2:
            raise InputError(f"{e.type} {e.eid}", (c1, c2), "a spring between like components", source=str(path))
        key = (node(n1, f"{e.type} {e.eid}"), None if n2 in (None, 0) else node(n2, f"{e.type} {e.eid}"))
        pairs.setdefault(key, np.zeros((6, 6)))[c1 - 1, c1 - 1] += kval
        pair_eids.setdefault(key, []).append(int(e.eid))
    spring_meta = {tuple(s["eids"]): s for s in meta.get("springs", []) if s["eids"]}
    springs = []
    for key, Kd in pairs.items():
        s_meta = spring_meta.get(tuple(pair_eids[key]))
        if s_meta is not None and np.allclose(np.diag(s_meta["K"]), np.diag(Kd), rtol=_CARD_RTOL, atol=0):
            Kd, name = np.array(s_meta["K"], float), s_meta.get("name", "")
        else:
            name = ""
        springs.append(Spring(node_a=key[0], node_b=key[1], stiffness=Kd, name=name))

    # ---- names, regions, groups (only if they fit this deck)
    n_sh, n_bm = len(quads), len(beams)
    regions = {}
    for kind, ids in meta.get("element_regions", {}).items():
        expect = {"shell": n_sh, "beam": n_bm}.get(kind)
        if expect is None or len(ids) == expect:
            regions[kind] = np.asarray(ids, np.int64)
    region_names = list(meta.get("region_names", []))
    if not meta:
        # a foreign deck: one region per property (shells first, then beams), named after the PID
        regions = {"shell": shell_prop.copy(), "beam": beam_section + len(shell_properties)}
        region_names = [p.name for p in shell_properties] + [f"PID{pid}" for pid in beam_pids]
    groups = {k: np.asarray(v, np.int64) for k, v in meta.get("node_groups", {}).items()
              if not v or max(v) < len(nodes)}
    if meta and (meta.get("n_shell") != n_sh or meta.get("n_beam") != n_bm):
        warnings.warn(f"{path}: element counts differ from the windflutter data; regions may not apply",
                      BdfApproximationWarning, stacklevel=2)

    fe = FEModel(
        nodes=nodes, shell_conn=shell_conn, shell_prop=shell_prop, shell_matdir=shell_matdir,
        shell_properties=shell_properties, beam_conn=beam_conn, beam_section=beam_section,
        beam_orient=beam_orient, beam_sections=beam_sections, masses=masses, rigid_links=rigid,
        springs=springs, spc=spc_t, node_groups=groups, element_regions=regions,
        region_names=region_names,
    )
    fe.check()
    return fe
