"""HAWCStab2's IEA 15 MW Campbell analysis as the tests read it (tests/data/iea15mw_hawcstab2,
DLR-AE/CampbellViewer, Apache-2.0): its modes, operating points, amplitude-file labels and mode-shape
pairing, shared by test_hawcstab2_iea15mw.py, test_hawcstab2_structural_damping.py,
test_deflected_blade.py and docs/scripts/edgewise_split.py, whirl_split_audit.py."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

DATA = Path(__file__).resolve().parents[1] / "data" / "iea15mw_hawcstab2"
WINDS = (5.0, 10.0, 15.0, 20.0, 25.0)


def amplitude_rows(wind: float | None = None) -> list[dict]:
    """The rows of modes.csv (HAWCStab2's aeroelastic modes with their .amp magnitudes and phases),
    at ``wind`` only if given."""
    with open(DATA / "modes.csv") as fh:
        return [r for r in csv.DictReader(fh) if wind is None or float(r["wind_speed"]) == wind]


def hawcstab2_continued(label: str, order: int, wind: float):
    """(natural frequency Hz, damping ratio) at ``wind`` of HAWCStab2's ``order``-th mode labelled
    ``label`` ("BW flap", "Sym flap", ...) *as HAWCStab2 continues it*: its mode numbers follow its
    structural modes along the wind speeds, so the mode is chosen once, at the lowest wind speed, as
    the ``order``-th of that label in the frequency of its structural mode of the same number (above
    0.3 Hz: the 1st tower modes carry blade labels too), and read at ``wind`` by that number.  Its
    aeroelastic file's frequency is the damped one (converted with ``sqrt(1 - zeta^2)``)."""
    st = np.loadtxt(DATA / "structural_entire_turbine.cmb", comments="#")
    low = amplitude_rows(float(st[0, 0]))
    ks = sorted((int(r["mode"]) for r in low if r["blade_label"] == label and st[0, int(r["mode"])] > 0.3),
                key=lambda k: st[0, k])
    k = ks[order - 1]
    (r,) = [r for r in amplitude_rows(wind) if int(r["mode"]) == k]
    z = float(r["damping_pct"]) / 100.0
    return float(r["frequency_hz"]) / np.sqrt(1 - z**2), z


def hawcstab2_1st_edge_whirl(wind: float, whirl: str) -> dict:
    """HAWCStab2's 1st edge ``whirl`` ("BW" or "FW") mode at ``wind``: its only mode below 1 Hz whose
    largest tip amplitude is that whirl's edge (a row of modes.csv)."""
    rows = [r for r in amplitude_rows(wind) if r["blade_label"] == f"{whirl} edge" and float(r["frequency_hz"]) < 1.0]
    assert len(rows) == 1, (wind, whirl, len(rows))
    return rows[0]


def hawcstab2_modes(wind: float, max_hz: float = 2.2, max_zeta: float = 0.10):
    """(natural frequency Hz, damping ratio -) of the HAWCStab2 modes at ``wind`` below the limits
    (its file's damped frequencies over ``sqrt(1 - zeta^2)``, _pairs; < 0.5 % for these modes)."""
    d = np.loadtxt(DATA / "aeroelastic_entire_turbine.cmb", comments="#")
    row = d[np.argmin(np.abs(d[:, 0] - wind))]
    f, z = row[1:61], row[61:121] / 100.0
    sel = (f > 1e-3) & (f < max_hz) & (z < max_zeta) & (z > -1.0)
    return f[sel] / np.sqrt(1 - z[sel] ** 2), z[sel]


def operating_point(wind: float):
    """HAWCStab2's rotor speed (RPM) and pitch (deg) at ``wind``."""
    op = np.loadtxt(DATA / "operation_1_25_windspeed.opt", skiprows=1)
    i = int(np.argmin(np.abs(op[:, 0] - wind)))
    return float(op[i, 2]), float(op[i, 1])


def matches(f_ref, z_ref, f, z, df=0.05, dz_abs=0.01, dz_rel=0.40) -> int:
    """Size of the largest one-to-one matching of reference modes by modes within the tolerances."""
    from scipy.optimize import linear_sum_assignment

    ok = (np.abs(f[None, :] - f_ref[:, None]) <= df * f_ref[:, None]) & (
        (np.abs(z[None, :] - z_ref[:, None]) <= dz_abs) | (np.abs(z[None, :] - z_ref[:, None]) <= dz_rel * np.abs(z_ref[:, None])))
    if not ok.size:
        return 0
    rows, cols = linear_sum_assignment(-ok.astype(float))
    return int(ok[rows, cols].sum())


def hawcstab2_labelled(wind: float, min_hz: float = 0.3):
    """HAWCStab2's modes at ``wind`` named by their largest blade amplitude in its own .amp file
    (tests/data/iea15mw_hawcstab2/modes.csv, docs/scripts/extract_hawcstab2_modes.py): the n-th mode
    labelled e.g. "BW edge" above ``min_hz`` (the 1st tower modes, whose blade tip moves more than the
    tower top, carry blade labels too) and below 99 % damping is ``("BW edge", n)``."""
    rows = [r for r in amplitude_rows(wind) if min_hz < float(r["frequency_hz"]) < 6.0 and float(r["damping_pct"]) < 99.0]
    rows.sort(key=lambda r: float(r["frequency_hz"]))
    out: dict = {}
    for r in rows:
        n = sum(1 for k in out if k[0] == r["blade_label"]) + 1
        out[(r["blade_label"], n)] = (float(r["frequency_hz"]), float(r["damping_pct"]) / 100.0)
    return out


# ------------------------------------------------------------------ mode shapes: the amplitude file
#: HAWCStab2's tip amplitudes (its .amp file, modes.csv) and ours (ModeRecord.multiblade_amplitudes):
#: the same quantities, blade tip flap / edge (m) and torsion (rad) in multi-blade components
TIP_AMPLITUDES = {f"{w}_{d}": f"{w}_{d}" for d in ("edge", "flap", "tors") for w in ("sym", "bw", "fw")}


#: the tower top's motion along and across the wind: HAWCStab2's TWR y and TWR x
TOWER_AMPLITUDES = {"twr_y": "tower_fa", "twr_x": "tower_ss"}


def hawcstab2_1st_tower_modes(wind: float):
    """HAWCStab2's 1st tower side-side and fore-aft modes at ``wind`` (rows of modes.csv, its .amp
    amplitudes): of its modes at 0.1-0.4 Hz, those with the largest tower-top motion across and
    along the wind."""
    ref = [r for r in amplitude_rows(wind) if 0.1 < float(r["frequency_hz"]) < 0.4]
    return max(ref, key=lambda r: float(r["twr_x"])), max(ref, key=lambda r: float(r["twr_y"]))


def shape_pairs(points, min_hz=6.0, max_hz=8.2, kind="tors", df=0.10, min_cos=0.8, max_support=0.5, tower=False):
    """HAWCStab2's modes whose largest tip amplitude is of ``kind`` (``min_hz``-``max_hz``) paired one
    to one (maximum total similarity) with our modes (less than ``max_support`` of their kinetic energy
    in the support) within ``df`` in natural frequency whose amplitudes are alike: cosine of the two
    vectors of magnitudes (sym / BW / FW x edge / flap / torsion at the tip, with ``tower`` also the
    tower top's two translations) at least ``min_cos``.  Yields (wind, HAWCStab2 label, natural
    frequency, zeta, our mode or None, cosine)."""
    from scipy.optimize import linear_sum_assignment

    rows = amplitude_rows()
    names = {**TIP_AMPLITUDES, **(TOWER_AMPLITUDES if tower else {})}
    keys = list(names)
    for v, modes in points.items():
        ref = [r for r in rows if float(r["wind_speed"]) == v and min_hz < float(r["frequency_hz"]) < max_hz
               and float(r["damping_pct"]) < 99.0 and r["blade_label"].endswith(kind)]
        ours = [m for m in modes if m.energy.get("support", 0.0) < max_support and m.tip is not None]
        if not ref or not ours:
            continue
        A = np.array([[float(r[k]) for k in keys] for r in ref])
        B = np.array([[m.multiblade_amplitudes()[names[k]] for k in keys] for m in ours])
        cos = (A / np.linalg.norm(A, axis=1, keepdims=True)) @ (B / np.linalg.norm(B, axis=1, keepdims=True)).T
        z = np.array([float(r["damping_pct"]) / 100.0 for r in ref])
        fn = np.array([float(r["frequency_hz"]) for r in ref]) / np.sqrt(1 - z**2)
        f = np.array([m.frequency_hz for m in ours])
        ok = (np.abs(f[None, :] / fn[:, None] - 1) <= df) & (cos >= min_cos)
        rr, cc = linear_sum_assignment(-np.where(ok, cos, -1.0))
        paired = {int(i): int(j) for i, j in zip(rr, cc) if ok[i, j]}
        for i, r in enumerate(ref):
            j = paired.get(i)
            yield v, r["blade_label"], fn[i], z[i], (ours[j] if j is not None else None), (cos[i, j] if j is not None else 0.0)


# ------------------------------------------------------------------ mode shapes: the amplitude file's phases
#: the .amp file's components (modes.csv columns; shaft omitted: ours has no shaft-end motion) and ours
#: (ModeRecord.multiblade_components)
PHASE_COMPONENTS = {"twr_x": "tower_ss", "twr_y": "tower_fa", "twr_yaw": "tower_yaw",
                    **{f"{w}_{d}": f"{w}_{d}" for d in ("edge", "flap", "tors") for w in ("sym", "bw", "fw")}}


def magnitude_pairs(ref: list[dict], ours: list, df, min_cos: float, max_dzeta: float | None = None):
    """HAWCStab2's modes ``ref`` (rows of modes.csv) paired one to one with ``ours`` (maximum total
    similarity) by the cosine of their vectors of component magnitudes (PHASE_COMPONENTS; at least
    ``min_cos``), the natural frequency within ``df`` (a number, or one per row of ``ref``) and, if
    given, the damping ratio within ``max_dzeta``.  Returns (our mode or None per row, natural
    frequencies Hz, damping ratios)."""
    from scipy.optimize import linear_sum_assignment

    keys = list(PHASE_COMPONENTS)
    z = np.array([float(r["damping_pct"]) / 100.0 for r in ref])
    fn = np.array([float(r["frequency_hz"]) for r in ref]) / np.sqrt(1 - z**2)
    if not ref or not ours:
        return [None] * len(ref), fn, z
    a = np.array([[float(r[k]) for k in keys] for r in ref])
    b = np.array([[abs(m.multiblade_components()[PHASE_COMPONENTS[k]]) for k in keys] for m in ours])
    cos = (a / np.linalg.norm(a, axis=1, keepdims=True)) @ (b / np.linalg.norm(b, axis=1, keepdims=True)).T
    f = np.array([m.frequency_hz for m in ours])
    ok = (np.abs(f[None, :] / fn[:, None] - 1) <= np.reshape(df, (-1, 1))) & (cos >= min_cos)
    if max_dzeta is not None:
        ok &= np.abs(np.array([m.damping_ratio for m in ours])[None, :] - z[:, None]) <= max_dzeta
    got: list = [None] * len(ref)
    for i, j in zip(*linear_sum_assignment(-np.where(ok, cos, -1.0))):
        if ok[i, j]:
            got[i] = ours[j]
    return got, fn, z


def phase_pairs(points, max_hz=2.2, max_zeta=0.5, df=0.08, min_cos=0.9):
    """Our modes paired one to one with HAWCStab2's (below ``max_hz``, ``max_zeta``) by the cosine of
    their vectors of component magnitudes (at least ``min_cos``) within ``df`` in natural frequency
    (:func:`magnitude_pairs`).  Yields (wind, HAWCStab2's components: complex array, ours: complex
    array, our mode)."""
    keys = list(PHASE_COMPONENTS)
    for v, modes in points.items():
        ref = [r for r in amplitude_rows(v) if 0.05 < float(r["frequency_hz"]) < max_hz
               and float(r["damping_pct"]) < 100 * max_zeta]
        ours = [m for m in modes if m.tip is not None and m.frequency_hz < 1.2 * max_hz]
        got, _, _ = magnitude_pairs(ref, ours, df, min_cos)
        for r, m in zip(ref, got):
            if m is not None:
                h = np.array([float(r[k]) * np.exp(1j * np.radians(float(r[k + "_ph"]))) for k in keys])
                w = np.array([m.multiblade_components()[PHASE_COMPONENTS[k]] for k in keys])
                yield v, h, w, m


def phase_misfit(h, w, conjugate, flip, azimuth, min_share=0.05):
    """How far HAWCStab2's phases ``h`` are from ours ``w`` (complex components, PHASE_COMPONENTS
    order) read in a convention: the blade's components of the kinds in ``flip`` ("flap", "edge",
    "tors") reversed, blade 1's azimuth origin turned by ``azimuth`` (rad: BW x exp(-i azimuth), FW x
    exp(+i azimuth)), then the groups in ``conjugate`` ("sym", "bw", "fw") conjugated.  Each code's
    eigenvector carries its own phase (its time origin): a factor exp(i theta) on our eigenvector
    turns the conjugated groups by -theta and the others by +theta, and HAWCStab2's own factor turns
    all alike, so both are fitted.  Over the components above ``min_share`` of the largest in both,
    returns (weighted rms phase difference in deg, number of components); weights the smaller share.
    ``azimuth`` may be an array: the differences are then an array of the same shape."""
    keys = list(PHASE_COMPONENTS)
    sh, sw = np.abs(h) / np.abs(h).max(), np.abs(w) / np.abs(w).max()
    use = (sh > min_share) & (sw > min_share)
    weight = np.minimum(sh, sw)[use]
    group = [k.split("_")[0] if k[:3] in ("sym", "bw_", "fw_") else "tower" for k, u in zip(keys, use) if u]
    kind = [k.split("_")[1] if k[:3] in ("sym", "bw_", "fw_") else k for k, u in zip(keys, use) if u]
    az = np.asarray(azimuth, float)
    x = w[use] * np.exp(1j * az[..., None] * np.array([{"bw": -1, "fw": 1}.get(g, 0) for g in group]))
    x = x * np.where([k in flip for k in kind], -1.0, 1.0)
    sign = np.where([g in conjugate for g in group], -1.0, 1.0)
    pred = np.where(sign < 0, np.conj(x), x)  # (..., n)
    # d = a - sign theta - psi: the two factors enter the unconjugated components as theta + psi and
    # the conjugated ones as psi - theta, two independent angles, each fitted in closed form
    # (the weighted mean direction): min sum w (1 - cos d) = sum w - |sum_+ w e^ia| - |sum_- w e^ia|
    e = weight * np.exp(1j * (np.angle(h[use]) - np.angle(pred)))
    r = (weight.sum() - np.abs(np.sum(np.where(sign > 0, e, 0), axis=-1))
         - np.abs(np.sum(np.where(sign < 0, e, 0), axis=-1))) / weight.sum()
    out = np.degrees(np.sqrt(2 * np.maximum(r, 0.0)))
    return (float(out) if out.ndim == 0 else out), int(use.sum())
