"""AeroDyn 15 input files: the main file (airfoil file list, table columns, blade file), the
blade file (span, chord, twist, airfoil id per node) and AirfoilInfo polar files (one or more
Reynolds-number tables in degrees; optional shape coordinates, inline or in an ``@file``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from windflutter.model import plausibility as pl
from windflutter.model.airfoil_geom import orient_contour, thickness_ratio
from windflutter.model.fastfile import FastFile
from windflutter.model.turbine import Airfoil, Polar
from windflutter.units import DEG


@dataclass(frozen=True)
class AeroDynMain:
    """``AFNames`` (files, in order), ``InCol_*`` columns (1-based; Cm 0 = none), ``ADBlFile(1)``."""

    airfoil_files: tuple[Path, ...]
    columns: tuple[int, int, int, int]
    blade_file: Path
    source: str


@dataclass(frozen=True)
class AeroDynBlade:
    """Nodes of an AeroDyn blade file: span (m from the root along the pitch axis), chord (m),
    aerodynamic twist (rad, positive nose-down) and airfoil id (1-based into ``AFNames``)."""

    span: np.ndarray
    chord: np.ndarray
    twist: np.ndarray
    af_id: np.ndarray
    source: str
    ac_offset: np.ndarray | None = None  # (n, 2) BlCrvAC (flapwise, +downwind), BlSwpAC (in-plane, +towards TE)


def read_aerodyn_main(path: str | Path, need_airfoils: bool = True) -> AeroDynMain:
    """The AeroDyn 15 main file; the airfoil files must exist when ``need_airfoils``."""
    f = FastFile(path, "AeroDyn main file")
    n = f.integer("NumAFfiles", lo=0)
    cols = tuple(f.integer(k, d, lo=0, hi=50) for k, d in
                 (("InCol_Alfa", 1), ("InCol_Cl", 2), ("InCol_Cd", 3), ("InCol_Cm", 4)))
    files = []
    if n:
        i0 = f.line_of("AFNames")
        for j in range(n):
            if i0 + j >= len(f.lines):
                f.error("AFNames", f"{j} names", f"NumAFfiles = {n} airfoil file names")
            tok = f.lines[i0 + j].split()
            name = tok[0].strip("\"'") if tok else ""
            p = Path(name) if Path(name).is_absolute() else f.path.parent / name
            if need_airfoils and not p.is_file():
                f.error(f"AFNames[{j + 1}]", str(p), "an existing airfoil (AirfoilInfo) file")
            files.append(p)
    blade_key = "ADBlFile(1)" if f.has("ADBlFile(1)") else "ADBlFile1"
    return AeroDynMain(airfoil_files=tuple(files), columns=cols, blade_file=f.file(blade_key), source=f.source)


def read_aerodyn_blade(path: str | Path, notes: pl.Notes) -> AeroDynBlade:
    """``NumBlNds`` rows of ``BlSpn BlCrvAC BlSwpAC BlCrvAng BlTwist BlChord BlAFID`` (+ extra
    columns of newer versions), checked at the file's nodes."""
    f = FastFile(path, "AeroDyn blade file")
    n = f.integer("NumBlNds", lo=2)
    i0 = f.header("BlSpn")
    names = f.lines[i0].split()
    need = ("BlSpn", "BlTwist", "BlChord", "BlAFID")
    for nm in need:
        if nm not in names:
            f.error(f"column {nm}", " ".join(names), "a blade table with " + ", ".join(need))
    tab = f.rows(i0 + 1, n, len(names), "AeroDyn blade table")
    col = {nm: tab[:, j] for j, nm in enumerate(names)}
    span, chord, twist = col["BlSpn"], col["BlChord"], col["BlTwist"] * DEG
    sub = notes.for_file(f.source)
    pl.span_axis(span / span[-1], span, "BlSpn", sub)
    if np.any(chord <= 0):
        i = int(np.argmax(chord <= 0))
        f.error(f"BlChord at node {i + 1}", float(chord[i]), "a positive chord (m)")
    s = span / span[-1]
    length = float(span[-1] - span[0])
    pl.chord_twist(s, chord, s, twist, length, "BlChord", "BlTwist", sub)
    af = col["BlAFID"]
    if np.any(af != np.round(af)) or np.any(af < 1):
        f.error("BlAFID", af.tolist()[:6], "airfoil numbers 1, 2, ... into the AeroDyn AFNames list")
    ac = np.column_stack([col["BlCrvAC"], col["BlSwpAC"]]) if "BlCrvAC" in col and "BlSwpAC" in col else None
    return AeroDynBlade(span=span, chord=chord, twist=twist, af_id=af.astype(int), source=f.source, ac_offset=ac)


def read_airfoil(path: str | Path, columns: tuple[int, int, int, int] = (1, 2, 3, 4),
                 notes: pl.Notes | None = None, name: str | None = None) -> Airfoil:
    """An AirfoilInfo file: every table (``Re`` in millions, ``NumAlf`` rows, alpha in degrees)
    and, when ``NumCoords`` names them, the shape coordinates (the first point is the reference
    point, not part of the contour).  The relative thickness comes from the contour (NaN without
    one)."""
    f = FastFile(path, "airfoil file")
    notes = notes.for_file(f.source) if notes is not None else pl.Notes(f.source)
    x, y = _coordinates(f)
    tc = thickness_ratio(x, y) if x.size >= 3 else float("nan")
    ia, icl, icd, icm = (c - 1 for c in columns)
    polars, res = [], []
    for k, i in enumerate(f.lines_of("NumAlf")):
        n = int(f.number_at(i, "NumAlf"))
        tab = f.rows(i + 1, n, max(columns), f"table {k + 1} (NumAlf = {n})")
        alpha = tab[:, ia] * DEG
        order = np.argsort(alpha, kind="stable")
        keep = np.concatenate([[True], np.diff(alpha[order]) > 0])
        a, cl, cd = alpha[order][keep], tab[order, icl][keep], tab[order, icd][keep]
        cm = tab[order, icm][keep] if icm >= 0 else np.zeros_like(a)
        pl.polar(a, cl, cd, tc if np.isfinite(tc) else 0.0, f"table {k + 1}", "deg", notes,
                 alpha_field=f"table {k + 1} alpha")
        polars.append(Polar(alpha=a, cl=cl, cd=cd, cm=cm, name=name or f.path.stem,
                            relative_thickness=tc if np.isfinite(tc) else 0.0))
    res = [1e6 * f.number_at(i, "Re") for i in f.lines_of("Re")][:len(polars)]
    if not polars:
        f.error("NumAlf", "<missing>", "at least one polar table")
    return Airfoil(name=name or f.path.stem, x=x, y=y, relative_thickness=tc, aerodynamic_center=0.25,
                   polars=tuple(polars), reynolds=np.asarray(res + [np.nan] * (len(polars) - len(res)), dtype=float))


def _coordinates(f: FastFile) -> tuple[np.ndarray, np.ndarray]:
    """Shape coordinates (TE -> suction -> LE -> pressure -> TE) without the reference point."""
    if not f.has("NumCoords"):
        return np.zeros(0), np.zeros(0)
    v = f.raw("NumCoords").strip()
    if v.startswith("@"):
        src = FastFile(f.path.parent / v[1:].strip("\"'"), "airfoil coordinates file")
        i0 = src.line_of("NumCoords")
        n = src.integer("NumCoords", lo=0)
    else:
        src, i0 = f, f.line_of("NumCoords")
        n = f.integer("NumCoords", lo=0)
    if n < 4:
        return np.zeros(0), np.zeros(0)
    xy = src.rows(i0 + 1, n, 2, "airfoil coordinates (reference point first)")[1:]
    return orient_contour(xy[:, 0], xy[:, 1])
