"""A HAWCStab2-style ``.amp`` file: each Campbell mode's amplitudes, beside the ``.cmb``.

HAWCStab2 writes, with its Campbell ``.cmb``, an ``.amp`` file of the modes' motion at the last node
of the tower, the shaft and blade 1: per wind speed one row, the wind speed and then, mode after
mode, 15 (magnitude, phase in degrees) pairs -- tower top x, y, yaw; shaft x, y, torsion; blade tip
symmetric / BW / FW edge, flap and torsion -- the magnitudes normalized to the mode's largest.  The
columns of :func:`write_amp` are the same, the modes those of :func:`~windflutter.post.campbell_export.
write_cmb` in the same order, so CampbellViewer-style tools and the reading of
``docs/scripts/extract_hawcstab2_modes.py`` (``row[1:].reshape(n_modes, 30)[:, 0::2]``) take it.
HAWCStab2's x at the tower top is across the wind, its y along it.  The tower-top yaw is about
windflutter's vertical (z up; HAWC2's z points down, so its sign may be the other).  windflutter does
not give the shaft's motion: those columns are ``NaN``, as is every column of a mode not found at a
wind speed.  Magnitudes and phases from :meth:`~windflutter.system.modes.ModeRecord.multiblade_components`
(m; torsion rad; the blade tip in the blade's pitching frame, as HAWCStab2's), phases relative to the
largest component and in windflutter's convention: HAWCStab2's own files write the FW parts
conjugated, the edge the other way and blade 1 at another azimuth (docs/campbell.md, "HAWCStab2's
phases"; ``tests/system/test_hawcstab2_iea15mw.py::test_mode_shape_phases_as_hawcstab2s``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from windflutter.errors import InputError
from windflutter.post.campbell_export import cmb_tracks, writable_path, write_table

#: HAWCStab2's 15 columns (name, unit) and windflutter's component of each (None: not given)
AMP_COLUMNS: tuple[tuple[str, str, str | None], ...] = (
    ("TWR x", "m", "tower_ss"), ("TWR y", "m", "tower_fa"), ("TWR yaw", "rad", "tower_yaw"),
    ("SFT x", "m", None), ("SFT y", "m", None), ("SFT tor", "rad", None),
    ("Sym edge", "m", "sym_edge"), ("BW edge", "m", "bw_edge"), ("FW edge", "m", "fw_edge"),
    ("Sym flap", "m", "sym_flap"), ("BW flap", "m", "bw_flap"), ("FW flap", "m", "fw_flap"),
    ("Sym tors", "rad", "sym_tors"), ("BW tors", "rad", "bw_tors"), ("FW tors", "rad", "fw_tors"),
)


def mode_amplitudes(mode) -> np.ndarray:
    """(15, 2) magnitude (normalized to the largest) and phase (deg, relative to the largest) of one
    mode in :data:`AMP_COLUMNS` order; NaN where windflutter gives no value or the mode has no blades."""
    out = np.full((len(AMP_COLUMNS), 2), np.nan)
    comps = None if mode is None else mode.multiblade_components()
    if not comps:
        return out
    z = np.array([comps.get(key, np.nan) if key else np.nan for _, _, key in AMP_COLUMNS], complex)
    mag = np.abs(z)
    if not np.any(mag > 0):
        return out
    ref = int(np.nanargmax(mag))
    out[:, 0] = mag / mag[ref]
    out[:, 1] = np.degrees(np.angle(z * np.exp(-1j * np.angle(z[ref]))))
    return out


def write_amp(campbell, path, field: str = "--amp") -> Path:
    """Write the ``.amp`` of a :class:`~windflutter.system.campbell.CampbellResult` (the module
    docstring); ``field`` names the option in error messages.

    Raises
    ------
    InputError
        the result is not a Campbell result with modes (e.g. a dataset read back from a file), or the
        path cannot be written.
    """
    if not hasattr(campbell, "points") or not hasattr(campbell, "tracks"):
        raise InputError(field, type(campbell).__name__, "a Campbell result with its modes (the .amp needs the "
                         "mode shapes, which a results file does not keep)")
    order, keep = cmb_tracks(campbell)
    p = writable_path(path, field)
    n = len(keep)
    cols = "".join(f"{2 + 2 * j:>14d}{3 + 2 * j:>14d}" for j in range(len(AMP_COLUMNS) * n))
    names = "".join(f"{f'{c} [{u}]':>14s}{'phase [deg]':>14s}" for c, u, _ in AMP_COLUMNS) * n
    lines = ["# Modal MAGNITUDE | PHASE of the following DOFs",
             "# Last node of: tower, shaft, blade1 (windflutter: tower top and blade tip; NaN: not given)",
             "# Mode number:" + "".join(f"{k + 1:>14d}" * (2 * len(AMP_COLUMNS)) for k in range(n)),
             "# Column num.:" + cols,
             "# Wind speed  " + names]
    rows = []
    for i in order:
        pt = campbell.points[i]
        row = [float(pt.wind_speed)]
        for t in keep:
            k = campbell.tracks[t].index[i]
            row.extend(mode_amplitudes(pt.modes[k] if k >= 0 else None).ravel())
        rows.append(row)
    return write_table(p, lines, rows, 14, 6, field)
