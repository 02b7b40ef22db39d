"""The deck reader: pyNastran's parsed cards -> :class:`~windflutter.structure.fem.FEModel` parts.

Each reader takes the named fields of its cards from the tables of
:mod:`windflutter.structure.bdf.cards` (``CARDS[name].read(card)``).
"""

from __future__ import annotations

import json
import math
import shutil
import tempfile
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from windflutter.errors import InputError
from windflutter.structure.bdf.beam import CARD_RTOL, BeamCardValues, beam_values, close
from windflutter.structure.bdf.cards import CARDS, BdfApproximationWarning
from windflutter.structure.bdf.write import META_TAG
from windflutter.structure import fem

NASTRAN_EXTRA_HINT = "pip install 'windflutter[nastran]'"
SUPPORTED_ELEMENTS = ("CQUAD4", "CBEAM", "CBAR", "CELAS1", "CELAS2")


def _import_pynastran():
    try:
        from pyNastran.bdf.bdf import BDF  # noqa: PLC0415
    except ImportError as exc:  # pragma: no cover - exercised only without the extra
        raise ImportError(f"read_bdf needs pyNastran: {NASTRAN_EXTRA_HINT} "
                          "(pyNastran 1.4.1 pins numpy < 2; use a separate environment, see docs/io.md)") from exc
    return BDF


def load_deck(path: Path) -> Any:
    """pyNastran's cross-referenced model of the deck (bulk data alone, or with case control)."""
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
    return model


def read_meta(path: Path) -> dict[str, Any]:
    """The ``$WF`` exact-data block of a deck written by windflutter ({} if none)."""
    chunks = []
    with open(path, errors="replace") as f:
        for line in f:
            if line.startswith(META_TAG):
                chunks.append(line[len(META_TAG):].rstrip("\n"))
    if not chunks:
        return {}
    try:
        return json.loads("".join(chunks))
    except json.JSONDecodeError:
        warnings.warn(f"{path}: unreadable $WF metadata ignored", BdfApproximationWarning, stacklevel=3)
        return {}


def check_supported(model: Any, source: str) -> None:
    """Refuse element, rigid-element and mass cards the reader has no mapping for."""
    unsupported = sorted({e.type for e in model.elements.values()} - set(SUPPORTED_ELEMENTS))
    unsupported += sorted({r.type for r in model.rigid_elements.values()} - {"RBE2"})
    unsupported += sorted({m.type for m in model.masses.values()} - {"CONM2"})
    if unsupported:
        raise InputError("bdf element types", unsupported, "only CQUAD4, CBEAM, CBAR, CELAS1/2, CONM2, RBE2",
                         source=source)


class Grids:
    """Node coordinates in ascending GRID id order and the id -> index map."""

    def __init__(self, model: Any, source: str):
        nids = np.array(sorted(model.nodes), dtype=np.int64)
        if len(nids) == 0:
            raise InputError("GRID", 0, "at least one grid point", source=source)
        self.source = source
        self.index = {int(n): i for i, n in enumerate(nids)}
        self.xyz = np.array([model.nodes[int(n)].get_position() for n in nids], dtype=float)

    def __call__(self, nid: int, where: str) -> int:
        """Node index of GRID ``nid`` (referenced by card ``where``)."""
        if nid not in self.index:
            raise InputError(where, nid, "a GRID id defined in the deck", source=self.source)
        return self.index[nid]


def materials(model: Any, meta: dict) -> dict[int, fem.IsotropicMaterial | fem.OrthotropicMaterial]:
    """MAT1 / MAT8 by MID (names from the ``$WF`` data)."""
    names = meta.get("materials", {})
    out = {}
    for mid, card in model.materials.items():
        if card.type not in ("MAT1", "MAT8"):
            continue
        r = CARDS[card.type].read(card)
        name = names.get(str(r["MID"]), "")
        if card.type == "MAT1":
            out[mid] = fem.IsotropicMaterial(E=r["E"], nu=r["NU"], rho=r["RHO"], name=name)
        else:
            out[mid] = fem.OrthotropicMaterial(E1=r["E1"], E2=r["E2"], nu12=r["NU12"], G12=r["G12"],
                                           G13=r["G1Z"] or r["G12"], G23=r["G2Z"] or r["G12"], rho=r["RHO"],
                                           name=name)
    return out


def _laminate(p: Any, mats: dict, source: str) -> tuple[tuple[fem.Ply, ...], float]:
    """Plies of a PSHELL / PCOMP and the laminate mid-plane's offset from the reference plane."""
    r = CARDS[p.type].read(p)
    pid = r["PID"]
    if r["NSM"] != 0.0:
        raise InputError(f"{p.type} {pid}.NSM", r["NSM"], "no non-structural mass on shells (add CONM2s)",
                         source=source)
    if p.type == "PSHELL":
        if r["MID1"] is None:
            raise InputError(f"PSHELL {pid}.MID1", None, "a membrane material", source=source)
        if r["MID2"] not in (None, r["MID1"]) or r["12I/T**3"] != 1.0:
            raise InputError(f"PSHELL {pid}", (r["MID1"], r["MID2"], r["12I/T**3"]),
                             "a homogeneous shell (MID2 = MID1, 12I/T^3 = 1)", source=source)
        plies = (fem.Ply(mats[r["MID1"]], r["T"], 0.0),)
        z0 = -0.5 * r["T"]
    else:
        mids, ts, ths = list(r["MID"]), [float(t) for t in r["T"]], [float(t) for t in r["THETA"]]
        if str(r["LAM"]).upper().startswith("SYM") and len(mids) == p.nplies:
            mids, ts, ths = mids + mids[::-1], ts + ts[::-1], ths + ths[::-1]
        plies = tuple(fem.Ply(mats[m], t, math.radians(th)) for m, t, th in zip(mids, ts, ths))
        z0 = r["Z0"] if r["Z0"] is not None else -0.5 * sum(ts)
    return plies, z0 + 0.5 * sum(pl.thickness for pl in plies)


def shells(model: Any, meta: dict, grids: Grids, mats: dict):
    """``(shell_properties, shell_conn, shell_prop, shell_matdir)`` from CQUAD4 and PSHELL/PCOMP.

    One ShellProperty per property and distinct ZOFFS of the quads using it.
    """
    quads = sorted((e for e in model.elements.values() if e.type == "CQUAD4"), key=lambda e: e.eid)
    quad_fields = [CARDS["CQUAD4"].read(q) for q in quads]
    shell_pids = sorted(pid for pid, p in model.properties.items() if p.type in ("PSHELL", "PCOMP"))
    prop_names = meta.get("shell_properties", [])
    laminates = {pid: _laminate(model.properties[pid], mats, grids.source) for pid in shell_pids}
    shell_properties: list[fem.ShellProperty] = []
    prop_index: dict[tuple[int, float], int] = {}
    for k, pid in enumerate(shell_pids):
        used = sorted({q["ZOFFS"] for q in quad_fields if q["PID"] == pid}) or [0.0]
        for zo in used:
            plies, extra = laminates[pid]
            name = (prop_names[k] if (k < len(prop_names) and len(used) == 1)
                    else f"PID{pid}" + (f"_z{zo:g}" if len(used) > 1 else ""))
            prop_index[(pid, zo)] = len(shell_properties)
            shell_properties.append(fem.ShellProperty(plies=plies, name=name, offset=zo + extra))
    conn = np.array([[grids(q[g], f"CQUAD4 {q['EID']}") for g in ("G1", "G2", "G3", "G4")] for q in quad_fields],
                    dtype=np.int64).reshape(-1, 4)
    prop = np.array([prop_index[(q["PID"], q["ZOFFS"])] for q in quad_fields], dtype=np.int64)
    matdir = np.array([_quad_material_axis(grids.xyz[conn[i]], q["THETA/MCID"], model)
                       for i, q in enumerate(quad_fields)], dtype=float).reshape(-1, 3)
    return shell_properties, conn, prop, matdir


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


def _station_a(v: Any) -> float:
    """The end-A value of a PBEAM per-station field (blank: 0)."""
    return float(np.atleast_1d(v)[0] or 0.0)


def _card_values(p: Any, mat: Any, source: str) -> BeamCardValues:
    """Section values of a PBEAM (constant, no neutral-axis offsets) or PBAR with its MAT1."""
    r = CARDS[p.type].read(p)
    pid = r["PID"]
    if mat.type != "MAT1":
        raise InputError(f"{p.type} {pid}.MID", r["MID"], "a MAT1 material", source=source)
    m = CARDS["MAT1"].read(mat)
    if p.type == "PBAR":
        return beam_values(m["E"], m["G"], m["RHO"], r["A"], r["I1"], r["I2"], r["I12"], r["J"], r["NSM"],
                           r["K1"], r["K2"], 0.0, 0.0, 0.0)
    n_off = [float(v or 0.0) for k in ("N1(A)", "N2(A)", "N1(B)", "N2(B)") for v in np.atleast_1d(r[k])]
    if any(n_off):
        raise InputError(f"PBEAM {pid} N1/N2", n_off, "zero neutral-axis offsets (not supported)", source=source)
    A = np.atleast_1d(r["A"])
    if len(A) > 2 or not np.allclose(A, A[0]):
        raise InputError(f"PBEAM {pid}", "tapered section", "a constant section", source=source)
    return beam_values(m["E"], m["G"], m["RHO"], *(_station_a(r[k]) for k in ("A", "I1", "I2", "I12", "J", "NSM")),
                       r["K1"], r["K2"], r["NSI(A)"], _station_a(r["M1(A)"]), _station_a(r["M2(A)"]))


def beam_sections(model: Any, meta: dict, source: str) -> tuple[list[int], list[fem.BeamSection]]:
    """PIDs (ascending) and sections of PBEAM / PBAR; the exact ``$WF`` section where the card
    still holds the values written with it."""
    pids = sorted(pid for pid, p in model.properties.items() if p.type in ("PBEAM", "PBAR"))
    exact = {int(b["pid"]): b for b in meta.get("beam_sections", [])}
    out = []
    for pid in pids:
        p = model.properties[pid]
        cv = _card_values(p, model.materials[p.mid], source)
        ex = exact.get(pid)
        if ex is not None and close(ex["card"], cv.as_list()):
            out.append(fem.BeamSection(stiffness=np.array(ex["K"], float), mass=np.array(ex["M"], float),
                                   name=ex.get("name", "")))
        else:
            if ex is not None:
                warnings.warn(f"{source}: PBEAM {pid} differs from the windflutter data written with it; "
                              "using the card values", BdfApproximationWarning, stacklevel=3)
            out.append(cv.section(name=f"PID{pid}"))
    return pids, out


def beams(model: Any, grids: Grids, beam_pids: list[int]):
    """``(beam_conn, beam_section, beam_orient)`` of CBEAM / CBAR (no pin flags, no offsets)."""
    elements = sorted((e for e in model.elements.values() if e.type in ("CBEAM", "CBAR")), key=lambda e: e.eid)
    index = {pid: k for k, pid in enumerate(beam_pids)}
    conn, orient, section = [], [], []
    for b in elements:
        r = CARDS[b.type].read(b)
        where = f"{b.type} {r['EID']}"
        if r["PA"] or r["PB"]:
            raise InputError(f"{where} PA/PB", (r["PA"], r["PB"]), "no pin flags (not supported)",
                             source=grids.source)
        wa = np.zeros(3) if r["WA"] is None else np.asarray(r["WA"], float)
        wb = np.zeros(3) if r["WB"] is None else np.asarray(r["WB"], float)
        if np.any(wa != 0) or np.any(wb != 0):
            raise InputError(f"{where} offsets", (wa.tolist(), wb.tolist()), "no beam end offsets",
                             source=grids.source)
        conn.append([grids(r["GA"], where), grids(r["GB"], where)])
        if r["G0"] is not None:
            v = grids.xyz[grids(r["G0"], f"{where}.G0")] - grids.xyz[conn[-1][0]]
        else:
            v = np.asarray(r["X"], float)
            cd = model.nodes[r["GA"]].cd
            if cd not in (0, None):
                v = model.coords[cd].beta().T @ v
        orient.append(v)
        section.append(index[r["PID"]])
    return (np.array(conn, dtype=np.int64).reshape(-1, 2), np.array(section, dtype=np.int64),
            np.array(orient, float).reshape(-1, 3))


def masses(model: Any, meta: dict, grids: Grids) -> list[fem.LumpedMass]:
    """CONM2 (CID 0: offset in basic axes; CID -1: absolute CG position)."""
    names = meta.get("masses", [])
    out = []
    for k, m in enumerate(sorted(model.masses.values(), key=lambda m: m.eid)):
        r = CARDS["CONM2"].read(m)
        n = grids(r["G"], f"CONM2 {r['EID']}")
        X = np.array([r["X1"], r["X2"], r["X3"]], float)
        if r["CID"] == -1:
            X = X - grids.xyz[n]
        elif r["CID"] != 0:
            raise InputError(f"CONM2 {r['EID']}.CID", r["CID"], "0 or -1 (basic system)", source=grids.source)
        out.append(fem.LumpedMass(node=n, mass=r["M"], inertia=np.array(m.Inertia(), float), offset=X,
                              name=names[k] if k < len(names) else ""))
    return out


def rigid_links(model: Any, meta: dict, grids: Grids) -> list[fem.RigidLink]:
    names = meta.get("rigid_links", [])
    out = []
    for k, e in enumerate(sorted(model.rigid_elements.values(), key=lambda r: r.eid)):
        r = CARDS["RBE2"].read(e)
        where = f"RBE2 {r['EID']}"
        out.append(fem.RigidLink(independent=grids(r["GN"], where),
                             dependent=np.array([grids(g, where) for g in r["GM"]], np.int64),
                             dofs=tuple(sorted(int(c) - 1 for c in r["CM"])),
                             name=names[k] if k < len(names) else ""))
    return out


def diaphragms(model: Any, meta: dict, source: str) -> list[fem.Diaphragm]:
    """The diaphragms of a deck written by windflutter (its MPC cards, restored from the ``$WF``
    data); MPC cards of any other deck are refused (no general MPC support)."""
    saved = meta.get("diaphragms", [])
    if getattr(model, "mpcs", None) and not saved:
        raise InputError("MPC", sorted(model.mpcs), "no MPC cards (only RBE2 ties are read), or a deck "
                         "written by windflutter", source=source)
    return [fem.Diaphragm(int(d["independent"]), np.asarray(d["dependent"], np.int64),
                          np.asarray(d["normal"], float), name=d.get("name", "")) for d in saved]


def spcs(model: Any, grids: Grids) -> dict[int, tuple[int, ...]]:
    """Union of all SPC1 / SPC sets (zero enforced values only)."""
    spc: dict[int, set[int]] = {}
    for sid, cards in model.spcs.items():
        for c in cards:
            if c.type not in ("SPC1", "SPC"):
                raise InputError(f"SPC set {sid}", c.type, "SPC1 or SPC cards", source=grids.source)
            r = CARDS[c.type].read(c)
            if c.type == "SPC1":
                for g in r["G"]:
                    spc.setdefault(grids(g, f"SPC1 {sid}"), set()).update(int(ch) - 1 for ch in r["C"])
                continue
            for g, comp, val in zip(r["G"], r["C"], r["D"]):
                if val not in (0, 0.0, None):
                    raise InputError(f"SPC {sid}", val, "zero enforced displacement", source=grids.source)
                spc.setdefault(grids(g, f"SPC {sid}"), set()).update(int(ch) - 1 for ch in str(comp))
    if len(model.spcs) > 1:
        warnings.warn(f"{grids.source}: {len(model.spcs)} SPC sets found; their union is used",
                      BdfApproximationWarning, stacklevel=3)
    return {n: tuple(sorted(c)) for n, c in sorted(spc.items())}


def springs(model: Any, meta: dict, grids: Grids) -> list[fem.Spring]:
    """CELAS1 / CELAS2 between like components (or to ground), grouped by node pair."""
    pairs: dict[tuple[int, int | None], np.ndarray] = {}
    pair_eids: dict[tuple[int, int | None], list[int]] = {}
    for e in sorted((e for e in model.elements.values() if e.type in ("CELAS1", "CELAS2")), key=lambda e: e.eid):
        r = CARDS[e.type].read(e)
        kval = r["K"] if e.type == "CELAS2" else float(e.pid_ref.k)
        n1, c1, n2, c2 = r["G1"], r["C1"], r["G2"], r["C2"]
        if n1 in (None, 0):
            n1, c1, n2, c2 = n2, c2, None, 0
        where = f"{e.type} {r['EID']}"
        if n2 not in (None, 0) and c1 != c2:
            raise InputError(where, (c1, c2), "a spring between like components", source=grids.source)
        key = (grids(n1, where), None if n2 in (None, 0) else grids(n2, where))
        pairs.setdefault(key, np.zeros((6, 6)))[c1 - 1, c1 - 1] += kval
        pair_eids.setdefault(key, []).append(r["EID"])
    spring_meta = {tuple(s["eids"]): s for s in meta.get("springs", []) if s["eids"]}
    out = []
    for key, Kd in pairs.items():
        s_meta = spring_meta.get(tuple(pair_eids[key]))
        name = ""
        if s_meta is not None and np.allclose(np.diag(s_meta["K"]), np.diag(Kd), rtol=CARD_RTOL, atol=0):
            Kd, name = np.array(s_meta["K"], float), s_meta.get("name", "")
        out.append(fem.Spring(node_a=key[0], node_b=key[1], stiffness=Kd, name=name))
    return out
