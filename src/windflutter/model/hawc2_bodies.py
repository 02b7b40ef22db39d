"""HAWC2 main bodies and their placement: ``c2_def`` centre lines, ``orientation`` (base and
relative Euler rotations), concentrated masses, st sets -> positions and frames in the global
frame.

HAWC2's global frame has x lateral, y downwind and z down; windflutter's (IEC/OpenFAST) has x
downwind, y lateral and z up: ``(x, y, z)_wf = (y, x, -z)_h2``.  Each ``mbdy2_eulerang a b c``
line turns the body frame about its own x, then y, then z axis (successive lines compose in the
turned frame), the reading under which the IEA 15 MW model's comments hold ("zC along shaft
upwind", "zH along blade, xH towards LE").
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model.hawc2_htc import Block

H2_TO_WF = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])  #: rows: wf axes in h2 components


@dataclass
class Body:
    """A ``main_body``: c2 sections (n, 4: x, y, z, twist deg) in its own frame, st file and set,
    concentrated masses (node, x, y, z, m, Ixx, Iyy, Izz) and, once placed, origin and frame."""

    name: str
    c2: np.ndarray
    st_file: Path | None
    st_set: tuple[int, int]
    masses: list[list[float]] = field(default_factory=list)
    damping: tuple[str, list[float]] | None = None  # ("damping_aniso" | "damping_posdef", 6 values)
    origin: np.ndarray | None = None  # global (h2) position of the body frame origin
    frame: np.ndarray | None = None  # columns: body axes in global (h2) components

    def node(self, which: str | int, where: str, source: str | None) -> np.ndarray:
        """Body-frame position of node ``which`` (1-based c2 section, or 'last')."""
        n = self.c2.shape[0]
        k = n if str(which).lower() == "last" else _int(which, where, source)
        if not 1 <= k <= n:
            raise InputError(where, which, f"a node number 1..{n} or 'last' of body {self.name!r}", source)
        return self.c2[k - 1, :3]

    def to_global(self, p_body: np.ndarray) -> np.ndarray:
        return self.origin + self.frame @ np.asarray(p_body, dtype=float)

    @property
    def length(self) -> float:
        return float(np.sum(np.linalg.norm(np.diff(self.c2[:, :3], axis=0), axis=1)))


def _int(v, where: str, source: str | None) -> int:
    try:
        x = float(v)
    except (TypeError, ValueError):
        raise InputError(where, v, "a whole number", source) from None
    if x != int(x):
        raise InputError(where, v, "a whole number", source)
    return int(x)


def read_bodies(struct: Block, base: Path, source: str) -> dict[str, Body]:
    """Every ``main_body`` of ``new_htc_structure`` by name."""
    out: dict[str, Body] = {}
    for i, mb in enumerate(struct.children("main_body")):
        where = f"new_htc_structure.main_body[{i}]"
        name = mb.values("name", where, source)[0]
        copy = mb.all("copy_main_body")
        if copy:
            src_body = _body(out, copy[0][0][0], f"{where} ({name}).copy_main_body", source)
            out[name] = Body(name=name, c2=src_body.c2.copy(), st_file=src_body.st_file, st_set=src_body.st_set,
                             masses=[list(m) for m in src_body.masses], damping=src_body.damping)
            continue
        c2b = mb.child("c2_def", f"{where} ({name})", source)
        n = _int(c2b.values("nsec", f"{where}.c2_def", source)[0], f"{where}.c2_def.nsec", source)
        secs = c2b.all("sec")
        if n < 2 or len(secs) < n:
            raise InputError(f"{where} ({name}).c2_def", f"nsec {n}, {len(secs)} sec lines", "nsec >= 2 sec lines", source)
        try:
            c2 = np.array([[float(x) for x in v[1:5]] for v, _ in secs[:n]])
        except ValueError:
            raise InputError(f"{where} ({name}).c2_def.sec", "non-numeric", "sec i x y z twist", source) from None
        if c2.shape != (n, 4) or not np.all(np.isfinite(c2)):
            raise InputError(f"{where} ({name}).c2_def.sec", "incomplete", "sec i x y z twist (finite)", source)
        st_file, st_set = None, (1, 1)
        ti = mb.children("timoschenko_input")
        if ti:
            f = ti[0].values("filename", f"{where}.timoschenko_input", source)[0]
            st_file = Path(f) if Path(f).is_absolute() else base / f
            st_set = tuple(_int(x, f"{where}.timoschenko_input.set", source)
                           for x in ti[0].values("set", f"{where}.timoschenko_input", source, default=["1", "1"])[:2])
        masses = []
        for vals, at in mb.all("concentrated_mass"):
            try:
                masses.append([float(x) for x in vals[:8]] + [0.0] * max(0, 8 - len(vals)))
            except ValueError:
                raise InputError(f"concentrated_mass ({at})", " ".join(vals), "node x y z mass Ixx Iyy Izz", source) from None
        out[name] = Body(name=name, c2=c2, st_file=st_file, st_set=st_set, masses=masses,
                         damping=_damping(mb, f"{where} ({name})", source))
    return out


def _damping(mb: Block, where: str, source: str) -> tuple[str, list[float]] | None:
    """The body's ``damping_aniso`` or ``damping_posdef`` line: (keyword, its 6 coefficients)."""
    for key in ("damping_aniso", "damping_posdef"):
        lines = mb.all(key)
        if lines:
            vals, at = lines[0]
            try:
                c = [float(x) for x in vals[:6]]
            except ValueError:
                c = []
            if len(c) != 6 or not all(np.isfinite(c)) or min(c) < 0:
                raise InputError(f"{where}.{key} ({at})", " ".join(vals), "six non-negative numbers: mx my mz kx ky kz",
                                 source)
            return key, c
    return None


def _euler(lines: list[tuple[list[str], str]], source: str | None) -> np.ndarray:
    """Product of the ``*_eulerang`` lines (deg): each x, then y, then z, in the turned frame."""
    R = np.eye(3)
    for vals, at in lines:
        try:
            a, b, c = (np.radians(float(x)) for x in vals[:3])
        except ValueError:
            raise InputError(f"eulerang ({at})", " ".join(vals), "three angles (deg)", source) from None
        R = R @ _rx(a) @ _ry(b) @ _rz(c)
    return R


def _rx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _ry(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _rz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def place_bodies(bodies: dict[str, Body], orient: Block, source: str) -> None:
    """Origins and frames of every body reachable from the ``base`` through ``relative``
    blocks (a body's origin is at the named node of its parent)."""
    for k, b in enumerate(orient.children("base")):
        name = b.values("body", f"orientation.base[{k}]", source)[0]
        body = _body(bodies, name, f"orientation.base[{k}].body", source)
        body.origin = np.array(b.numbers("inipos", 3, f"orientation.base[{k}]", source, default=[0, 0, 0]))
        body.frame = _euler(b.all("body_eulerang"), source)
    pending = list(enumerate(orient.children("relative")))
    for _ in range(len(pending) + 1):
        rest = []
        for k, rel in pending:
            where = f"orientation.relative[{k}]"
            m1, m2 = rel.values("mbdy1", where, source), rel.values("mbdy2", where, source)
            parent = _body(bodies, m1[0], f"{where}.mbdy1", source)
            child = _body(bodies, m2[0], f"{where}.mbdy2", source)
            if parent.frame is None:
                rest.append((k, rel))
                continue
            child.frame = parent.frame @ _euler(rel.all("mbdy2_eulerang"), source)
            joint = parent.to_global(parent.node(m1[1] if len(m1) > 1 else "last", f"{where}.mbdy1", source))
            child.origin = joint - child.frame @ child.node(m2[1] if len(m2) > 1 else 1, f"{where}.mbdy2", source)
        if not rest:
            return
        pending = rest
    raise InputError("orientation.relative", [r.values("mbdy2", "", source)[0] for _, r in pending],
                     "bodies connected to the base body", source)


def _body(bodies: dict[str, Body], name: str, where: str, source: str | None) -> Body:
    if name not in bodies:
        raise InputError(where, name, f"a main_body name ({', '.join(bodies)})", source)
    return bodies[name]


def to_wf(v: np.ndarray) -> np.ndarray:
    """A global HAWC2 vector/point (or rows of them) in windflutter's global frame."""
    return np.asarray(v, dtype=float) @ H2_TO_WF.T
