"""Campbell exports: CSV (one row per wind speed and mode) and a HAWCStab2-style ``.cmb`` file.

* :func:`write_csv` / :func:`read_csv` -- the fields of ``windflutter campbell --json``, one row per
  wind speed and mode (modes of a point in ascending frequency, as in the JSON), floats written
  with ``repr`` so that reading gives the same numbers bit for bit.
* :func:`write_cmb` / :func:`read_cmb` -- the layout of HAWCStab2's ``.cmb`` Campbell file: the
  first line ``# Wind [m/s]  1 2 ... N  1 2 ... N``, then per wind speed one row: the wind speed,
  the N track frequencies (Hz; damped, ``Im lambda / 2 pi``, as HAWCStab2 writes them -- its
  1st flap frequencies in operation match ours so, docs/notes/iea15mw_hawcstab2.md, "HAWCStab2's
  frequencies are damped frequencies"), the N damping ratios (% of critical); ``NaN`` where a track
  has no mode at that wind speed.  Comment lines after the first name the tracks (``# mode k: name``),
  their two largest participations at each wind speed (``# participation of mode k ...``) and the
  frequency definition; numerical readers that skip ``#`` lines (``numpy.loadtxt``)
  read the table as it is.  :func:`read_cmb` also reads HAWCStab2's own files (two or three
  blocks of N columns; the third, when present, is kept as ``extra``).
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.post.campbell_data import as_campbell_dataset, present

CSV_FIELDS = ("wind_speed", "rotor_speed_rpm", "pitch_deg", "name", "family", "order", "whirl",
              "frequency_hz", "damped_frequency_hz", "damping_ratio", "share", "mixed", "heavily_damped",
              "participation_1", "participation_1_share", "participation_2", "participation_2_share")
_CSV_FLOATS = {"wind_speed", "rotor_speed_rpm", "pitch_deg", "frequency_hz", "damped_frequency_hz", "damping_ratio",
               "share", "participation_1_share", "participation_2_share"}
_CSV_INTS = {"order", "mixed", "heavily_damped"}
_FREQUENCY_VARS = {"undamped": "frequency", "damped": "damped_frequency"}


def csv_rows(campbell) -> list[dict]:
    """The export rows: per wind speed (ascending) its modes in ascending undamped frequency."""
    ds = as_campbell_dataset(campbell)
    pres = present(ds)
    f = ds["frequency"].values
    rows = []
    for i in range(ds.sizes["wind_speed"]):
        cols = np.where(pres[i])[0]
        for t in cols[np.argsort(f[i, cols], kind="stable")]:
            rows.append({"wind_speed": float(ds["wind_speed"].values[i]),
                         "rotor_speed_rpm": float(ds["rotor_speed"].values[i]),
                         "pitch_deg": float(ds["pitch"].values[i]),
                         "name": str(ds["mode_name"].values[i, t]), "family": str(ds["family"].values[i, t]),
                         "order": int(ds["order"].values[i, t]), "whirl": str(ds["whirl"].values[i, t]),
                         "frequency_hz": float(f[i, t]),
                         "damped_frequency_hz": float(ds["damped_frequency"].values[i, t]),
                         "damping_ratio": float(ds["damping_ratio"].values[i, t]),
                         **{k: _finite_or_none(ds[k].values[i, t]) for k in ("share", "participation_1_share",
                                                                             "participation_2_share") if k in ds},
                         **{k: int(ds[k].values[i, t]) for k in ("mixed", "heavily_damped") if k in ds},
                         **{k: str(ds[k].values[i, t]) for k in ("participation_1", "participation_2") if k in ds}})
    return rows


def _finite_or_none(x) -> float | None:
    """A share as the JSON has it: None where the mode has none (NaN in the dataset)."""
    x = float(x)
    return x if math.isfinite(x) else None


def writable_path(path, field: str) -> Path:
    p = Path(path)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(field, str(path), f"a writable location ({exc.strerror})") from None
    if p.is_dir():
        raise InputError(field, str(path), "a file name, not a folder")
    return p


def write_csv(campbell, path, field: str = "--csv") -> Path:
    """Write the CSV export; ``field`` names the option in error messages.

    Raises
    ------
    InputError
        the path is a folder or cannot be written.
    """
    p = writable_path(path, field)
    try:
        with open(p, "w", newline="", encoding="utf-8") as fh:
            w = csv.DictWriter(fh, fieldnames=CSV_FIELDS, lineterminator="\n")
            w.writeheader()
            for r in csv_rows(campbell):
                w.writerow({k: repr(v) if isinstance(v, float) else v for k, v in r.items()})
    except OSError as exc:
        raise InputError(field, str(path), f"a writable file ({exc.strerror})") from None
    return p


def read_csv(path) -> list[dict]:
    """Rows of a CSV export, typed as written (floats, ``order`` int, strings).

    Raises
    ------
    InputError
        missing file, other columns than :data:`CSV_FIELDS`, or a value that is not a number.
    """
    p = Path(path)
    try:
        with open(p, newline="", encoding="utf-8") as fh:
            reader = csv.DictReader(fh)
            if tuple(reader.fieldnames or ()) != CSV_FIELDS:
                raise InputError("columns", reader.fieldnames, f"the Campbell CSV columns {', '.join(CSV_FIELDS)}",
                                 source=str(p))
            rows = list(reader)
    except OSError as exc:
        raise InputError("campbell csv", str(path), f"a readable file ({exc.strerror})") from None
    out = []
    for n, r in enumerate(rows, start=2):
        try:
            out.append({k: (None if v == "" else float(v)) if k in _CSV_FLOATS else int(v) if k in _CSV_INTS else v
                        for k, v in r.items()})
        except (TypeError, ValueError):
            raise InputError(f"line {n}", r, "numbers in the numeric columns", source=str(p)) from None
    return out


@dataclass
class CmbData:
    """A ``.cmb`` table: ``wind_speed`` (n,), ``frequency`` (n, N) Hz, ``damping_pct`` (n, N) % of
    critical, ``extra`` (n, N) a third block (HAWCStab2's aeroelastic files) or None, ``names``
    (N track names; empty when the file names none)."""

    wind_speed: np.ndarray
    frequency: np.ndarray
    damping_pct: np.ndarray
    extra: np.ndarray | None = None
    names: list[str] = field(default_factory=list)


def write_cmb(campbell, path, frequency: str = "damped", field: str = "--cmb") -> Path:
    """Write the HAWCStab2-style ``.cmb`` (see the module docstring).

    Parameters
    ----------
    frequency : ``"damped"`` (``Im lambda / 2 pi``, HAWCStab2's; the default) or ``"undamped"``
        (``|lambda|/2 pi``, the JSON's ``frequency_hz``).
    """
    if frequency not in _FREQUENCY_VARS:
        raise InputError("frequency", frequency, "'undamped' or 'damped'")
    ds = as_campbell_dataset(campbell)
    p = writable_path(path, field)
    keep = [t for t in range(ds.sizes["track"]) if present(ds)[:, t].any()]
    n = len(keep)
    num = "".join(f"{k + 1:>17d}" for k in range(n))
    lines = [f"  # Wind [m/s]{num}{num}",
             f"# windflutter Campbell export (HAWCStab2 .cmb layout): {ds.attrs.get('turbine', '')}, "
             f"part {ds.attrs.get('part', '')}, {ds.attrs.get('frame', 'ground-fixed')} frame",
             f"# columns: wind speed (m/s); {frequency} frequency (Hz) of modes 1..{n}; damping ratio "
             f"(% of critical) of modes 1..{n}; NaN: mode not found at that wind speed"]
    lines += [f"# mode {k + 1}: {ds['track_name'].values[t]}" for k, t in enumerate(keep)]
    lines += participation_lines(ds, keep)
    f = ds[_FREQUENCY_VARS[frequency]].values[:, keep]
    z = 100.0 * ds["damping_ratio"].values[:, keep]
    rows = [[v, *f[i], *z[i]] for i, v in enumerate(ds["wind_speed"].values)]
    return write_table(p, lines, rows, 17, 9, field)


def participation_lines(ds, keep: list[int]) -> list[str]:
    """Comment lines of the ``.cmb``: each mode's (track's) two largest participations at each wind
    speed, ``# participation of mode k (wind m/s: largest % / second %): 3: 1st edge BW 92 / 1st flap
    BW 5; ...`` (none when the dataset has no participations)."""
    if "participation_1" not in ds:
        return []
    v = ds["wind_speed"].values
    out = []
    for k, t in enumerate(keep):
        cells = []
        for i in range(len(v)):
            p1, s1 = str(ds["participation_1"].values[i, t]), ds["participation_1_share"].values[i, t]
            if not p1 or not math.isfinite(s1):
                continue
            cell = f"{v[i]:g}: {p1} {100 * s1:.0f}"
            p2, s2 = str(ds["participation_2"].values[i, t]), ds["participation_2_share"].values[i, t]
            if p2 and math.isfinite(s2):
                cell += f" / {p2} {100 * s2:.0f}"
            cells.append(cell)
        if cells:
            out.append(f"# participation of mode {k + 1} (wind m/s: largest % / second %): " + "; ".join(cells))
    return out


def write_table(p: Path, header: list[str], rows, width: int, digits: int, field: str) -> Path:
    """Write ``header`` lines and the number ``rows`` in fixed columns of ``width`` (``digits`` after the
    point, ``NaN`` for non-finite values) to ``p``; ``field`` names the option in error messages."""
    lines = list(header)
    for vals in rows:
        lines.append("".join(f"{x:{width}.{digits}E}" if math.isfinite(x) else f"{'NaN':>{width}s}" for x in vals))
    try:
        p.write_text("\n".join(lines) + "\n", encoding="utf-8")
    except OSError as exc:
        raise InputError(field, str(p), f"a writable file ({exc.strerror})") from None
    return p


def cmb_tracks(result) -> tuple[np.ndarray, list[int]]:
    """The rows and columns of :func:`write_cmb` for a Campbell result: its points in ascending wind
    speed and the tracks that have a mode at some wind speed (the dataset's order)."""
    v = np.array([float(p.wind_speed) for p in result.points])
    keep = [t for t, tr in enumerate(result.tracks) if any(k >= 0 for k in tr.index)]
    return np.argsort(v, kind="stable"), keep


def read_cmb(path) -> CmbData:
    """Read a ``.cmb`` file (ours or HAWCStab2's).

    Raises
    ------
    InputError
        missing file, no ``# Wind`` header, or a table whose width is not 1 + 2N or 1 + 3N.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError as exc:
        raise InputError("cmb file", str(path), f"a readable file ({exc.strerror})") from None
    if not text or "wind" not in text[0].lower():
        raise InputError("header", text[0][:60] if text else "", "a first line '# Wind [m/s] 1 2 ... N'", source=str(p))
    nums = [int(x) for x in text[0].split() if x.isdigit()]
    n = max(nums) if nums else 0
    names = {}
    rows = []
    for ln in text[1:]:
        s = ln.strip()
        if s.startswith("# mode ") and ":" in s:
            k, _, name = s[len("# mode "):].partition(":")
            if k.strip().isdigit():
                names[int(k)] = name.strip()
        elif s and not s.startswith("#"):
            try:
                rows.append([float(x) for x in s.split()])
            except ValueError:
                raise InputError("row", s[:60], "numbers (or NaN)", source=str(p)) from None
    width = {len(r) for r in rows}
    if n == 0 or len(width) != 1 or (width.pop() - 1) not in (2 * n, 3 * n):
        raise InputError("table", f"{len(rows)} rows for {n} modes", f"rows of 1 + 2x{n} or 1 + 3x{n} numbers",
                         source=str(p))
    a = np.array(rows, float)
    return CmbData(wind_speed=a[:, 0], frequency=a[:, 1:n + 1], damping_pct=a[:, n + 1:2 * n + 1],
                   extra=a[:, 2 * n + 1:] if a.shape[1] == 1 + 3 * n else None,
                   names=[names.get(k + 1, "") for k in range(n)] if names else [])
