"""HAWC2 data files: structural ``st`` (Timoshenko, 19 columns), aerodynamic layout ``ae`` and
profile coefficients ``pc``.

* st: main sets ``#N`` containing subsets ``$M n_rows comment`` of rows ``r m x_cg y_cg ri_x
  ri_y x_sh y_sh E G I_x I_y I_p k_x k_y A pitch x_e y_e`` (HAWC2 body frame: x towards the
  leading edge at zero twist, y towards the suction side, z along the body; ``pitch`` in deg
  about z).  Fully populated (FPM, 30-column) files are refused with a clear message.
* ae: ``n_sets``, then per set ``set_no n_rows`` and rows ``r chord t/c[%] pc_set``.
* pc: ``n_sets``, then per set ``n_profiles`` and per profile ``no n_alpha t/c[%] name`` and rows
  ``alpha[deg] cl cd cm``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.model.fastfile import numbers, read_text
from windflutter.model.plausibility import MAX_STATIONS

ST_COLUMNS = ("r", "m", "x_cg", "y_cg", "ri_x", "ri_y", "x_sh", "y_sh", "E", "G", "I_x", "I_y", "I_p", "k_x",
              "k_y", "A", "pitch", "x_e", "y_e")


@dataclass(frozen=True)
class Profile:
    """One pc profile: relative thickness (fraction), name, alpha (rad), cl, cd, cm."""

    tc: float
    name: str
    alpha: np.ndarray
    cl: np.ndarray
    cd: np.ndarray
    cm: np.ndarray


def _lines(path: Path, what: str) -> list[str]:
    return read_text(path, what).splitlines()


def read_st(path: str | Path, main_set: int, sub_set: int) -> dict[str, np.ndarray]:
    """Columns of set ``#main_set`` subset ``$sub_set`` of an st file, by :data:`ST_COLUMNS` name."""
    p = Path(path)
    lines = _lines(p, "HAWC2 st file")
    where = f"set {main_set} {sub_set}"
    i_main = next((i for i, ln in enumerate(lines) if _tag(ln, "#") == main_set), None)
    if i_main is None:
        raise InputError(f"st {where}", f"#{main_set}", f"a main set '#{main_set}' in the st file", str(p))
    for i in range(i_main + 1, len(lines)):
        if _tag(lines[i], "#") is not None:
            break
        if _tag(lines[i], "$") == sub_set:
            tok = lines[i].split()
            try:
                n = int(tok[1])
            except (IndexError, ValueError):
                raise InputError(f"st {where} header", lines[i].strip()[:60], "'$set n_rows comment'", str(p)) from None
            if not 1 < n <= MAX_STATIONS:
                raise InputError(f"st {where} rows", n, f"between 2 (a beam has two ends) and {MAX_STATIONS}", str(p))
            rows = [numbers(ln) for ln in lines[i + 1:i + 1 + n]]
            for k, r in enumerate(rows):
                if r is None or len(r) < 19:
                    more = " (a fully populated 'FPM' st file? windflutter reads the 19-column Timoshenko format)" \
                        if r is not None and len(r) >= 30 else ""
                    raise InputError(f"st {where} row {k + 1}", (lines[i + 1 + k].strip()[:60]),
                                     "19 numbers: " + " ".join(ST_COLUMNS) + more, str(p))
                if len(r) != len(rows[0]) or not np.all(np.isfinite(r)):  # HAWC2 reads free format:
                    raise InputError(f"st {where} row {k + 1}", lines[i + 1 + k].strip()[:60],  # a shifted row
                                     f"{len(rows[0])} finite numbers, as row 1", str(p))
            if len(rows) < n:
                raise InputError(f"st {where}", f"{len(rows)} rows", f"{n} rows", str(p))
            a = np.array([r[:19] for r in rows], dtype=float)
            return {name: a[:, j] for j, name in enumerate(ST_COLUMNS)}
    raise InputError(f"st {where}", f"${sub_set}", f"a subset '${sub_set}' in main set #{main_set}", str(p))


def _tag(line: str, mark: str) -> int | None:
    s = line.strip()
    if not s.startswith(mark):
        return None
    tok = s[1:].split()
    try:
        return int(tok[0]) if tok else None
    except ValueError:
        return None


def read_ae(path: str | Path, set_no: int) -> dict[str, np.ndarray]:
    """``r`` (m), ``chord`` (m), ``tc`` (fraction) and ``pc_set`` of ae set ``set_no``."""
    p = Path(path)
    rows = [ln for ln in _lines(p, "HAWC2 ae file") if ln.strip()]
    i = 1
    while i < len(rows):
        head = rows[i].split()
        try:
            no, n = int(head[0]), int(head[1])
        except (IndexError, ValueError):
            raise InputError(f"ae file line {i + 1}", rows[i].strip()[:60], "'set_no n_rows'", str(p)) from None
        if not 0 < n <= MAX_STATIONS:
            raise InputError(f"ae set {no} rows", n, f"between 1 and {MAX_STATIONS}", str(p))
        if no == set_no:
            if n < 2:
                raise InputError(f"ae set {set_no} rows", n, "at least 2 (root and tip)", str(p))
            tab = [numbers(ln) for ln in rows[i + 1:i + 1 + n]]
            if len(tab) < n or any(t is None or len(t) < 4 for t in tab):
                raise InputError(f"ae set {set_no}", f"{len(tab)} rows", f"{n} rows of r, chord, t/c (%), pc set", str(p))
            bad = next((k for k, t in enumerate(tab) if not np.all(np.isfinite(t[:4]))), None)
            if bad is not None:
                raise InputError(f"ae set {set_no} row {bad + 1}", rows[i + 1 + bad].strip()[:60], "finite numbers", str(p))
            a = np.array([t[:4] for t in tab], dtype=float)
            return {"r": a[:, 0], "chord": a[:, 1], "tc": a[:, 2] / 100.0, "pc_set": a[:, 3].astype(int)}
        i += n + 1
    raise InputError("ae_sets", set_no, "an ae set of the ae file", str(p))


def read_pc(path: str | Path, set_no: int) -> list[Profile]:
    """The profiles of pc set ``set_no`` (sorted by thickness, as HAWC2 interpolates them)."""
    p = Path(path)
    lines = _lines(p, "HAWC2 pc file")
    try:
        n_sets = int(lines[0].split()[0])
    except (IndexError, ValueError):
        raise InputError("pc file line 1", lines[0].strip()[:60] if lines else "", "the number of sets", str(p)) from None
    i = 1
    for s in range(1, n_sets + 1):
        try:
            n_prof = int(lines[i].split()[0])
        except (IndexError, ValueError):
            raise InputError(f"pc set {s} line {i + 1}", lines[i].strip()[:60] if i < len(lines) else "",
                             "the number of profiles", str(p)) from None
        i += 1
        profiles = []
        for _ in range(n_prof):
            prof, i = _profile(lines, i, p)
            profiles.append(prof)
        if s == set_no:
            return sorted(profiles, key=lambda q: q.tc)
    raise InputError("pc set", set_no, f"a set of the pc file (it has {n_sets})", str(p))


def _profile(lines: list[str], i: int, p: Path) -> tuple[Profile, int]:
    try:
        head = lines[i].split()
        n, tc = int(head[1]), float(head[2])
    except (IndexError, ValueError):
        raise InputError(f"pc profile header line {i + 1}", lines[i].strip()[:60] if i < len(lines) else "",
                         "'no n_alpha t/c[%] name'", str(p)) from None
    if not 1 < n <= MAX_STATIONS:
        raise InputError(f"pc profile line {i + 1} n_alpha", n, f"between 2 and {MAX_STATIONS}", str(p))
    tab = [numbers(ln) for ln in lines[i + 1:i + 1 + n]]
    if len(tab) < n or any(t is None or len(t) < 4 for t in tab):
        raise InputError(f"pc profile at line {i + 1}", " ".join(head[3:])[:40], f"{n} rows of alpha, cl, cd, cm", str(p))
    a = np.array([t[:4] for t in tab], dtype=float)
    if not np.all(np.isfinite(a)):
        k = int(np.argmax(~np.all(np.isfinite(a), axis=1)))
        raise InputError(f"pc profile at line {i + 1} row {k + 1}", lines[i + 1 + k].strip()[:60], "finite numbers", str(p))
    order = np.argsort(a[:, 0], kind="stable")
    a = a[order][np.concatenate([[True], np.diff(a[order, 0]) > 0])]
    name = " ".join(head[3:4]) or f"pc{head[0]}"
    return Profile(tc=tc / 100.0, name=name, alpha=np.radians(a[:, 0]), cl=a[:, 1], cd=a[:, 2], cm=a[:, 3]), i + 1 + n


def interpolate_profiles(profiles: list[Profile], tc: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(alpha, cl, cd, cm) at relative thickness ``tc``: linear between the two profiles of the
    set that bracket it (HAWC2's rule), on the union of their alpha grids; clamped at the ends."""
    t = np.array([q.tc for q in profiles])
    j = int(np.clip(np.searchsorted(t, tc, side="right") - 1, 0, len(t) - 1))
    k = min(j + 1, len(t) - 1)
    w = 0.0 if k == j or t[k] == t[j] else float(np.clip((tc - t[j]) / (t[k] - t[j]), 0.0, 1.0))
    lo, hi = profiles[j], profiles[k]
    al = np.union1d(lo.alpha, hi.alpha)
    coef = [(1 - w) * np.interp(al, lo.alpha, getattr(lo, c)) + w * np.interp(al, hi.alpha, getattr(hi, c))
            for c in ("cl", "cd", "cm")]
    return al, coef[0], coef[1], coef[2]
