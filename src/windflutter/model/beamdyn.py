"""BeamDyn input files: the main file (key points, initial twist, blade file name) and the blade
file (6x6 stiffness and mass per station, stiffness-proportional damping ``mu1..mu6``).

BeamDyn's section frame and order are those of windIO's 6x6 (see
:mod:`windflutter.model.beamprops`); every station is checked (positive-definite stiffness,
positive semi-definite mass) before anything is interpolated.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from windflutter.model import plausibility as pl
from windflutter.model.beamprops import beamdyn_to_section
from windflutter.model.fastfile import FastFile, numbers
from windflutter.model.turbine import BeamProperties, BladeDamping


@dataclass(frozen=True)
class BeamDynMain:
    """The geometry of a BeamDyn main file.

    kp : (n, 3) key points (m) in the blade reference frame (x flapwise towards the suction
        side, y towards the trailing edge, z along the pitch axis).
    twist_deg : (n,) initial (structural) twist at the key points (deg, positive nose-down).
    blade_file : the ``BldFile`` it names (None if absent).
    """

    kp: np.ndarray
    twist_deg: np.ndarray
    blade_file: Path | None
    source: str

    @property
    def eta(self) -> np.ndarray:
        """Nondimensional arc length of the key points along the reference axis."""
        seg = np.linalg.norm(np.diff(self.kp, axis=0), axis=1)
        arc = np.concatenate([[0.0], np.cumsum(seg)])
        return arc / arc[-1]

    @property
    def length(self) -> float:
        return float(np.sum(np.linalg.norm(np.diff(self.kp, axis=0), axis=1)))

    @property
    def twist_by_eta(self) -> tuple[np.ndarray, np.ndarray]:
        return self.eta, self.twist_deg


def read_beamdyn_main(path: str | Path) -> BeamDynMain:
    """Key points ``kp_xr kp_yr kp_zr initial_twist`` (``kp_total`` rows) and ``BldFile``."""
    f = FastFile(path, "BeamDyn main file")
    n = f.integer("kp_total", lo=2)
    i0 = f.header("kp_zr")
    tab = f.rows(i0 + 1, n, 4, "BeamDyn key-point table (kp_xr kp_yr kp_zr initial_twist)")
    kp = tab[:, :3]
    if np.any(np.diff(kp[:, 2]) <= 0):
        i = int(np.argmax(np.diff(kp[:, 2]) <= 0)) + 1
        f.error(f"kp_zr of key point {i + 1}", float(kp[i, 2]), "key points increasing from root to tip along z")
    return BeamDynMain(kp=kp, twist_deg=tab[:, 3], blade_file=f.file("BldFile", required=False), source=f.source)


def read_beamdyn_blade(path: str | Path, twist_deg_by_eta: tuple[np.ndarray, np.ndarray] | None = None,
                       length: float = float("nan"), notes: pl.Notes | None = None
                       ) -> tuple[BeamProperties, BladeDamping | None]:
    """A BeamDyn blade file: ``station_total`` blocks of eta, 6x6 K and 6x6 M (BeamDyn order).

    Parameters
    ----------
    path : BeamDyn blade file.
    twist_deg_by_eta : optional (eta, twist_deg) of the main file's key points, stored in the
        result (converted to rad); zeros otherwise.
    length : blade length (m) for :attr:`BeamProperties.length`.
    notes : where plausibility warnings go (a new one for this file if None).

    Returns
    -------
    (BeamProperties in the BeamSection convention, BladeDamping with ``mu`` when
    ``damp_type`` = 1, else None)
    """
    f = FastFile(path, "BeamDyn blade file")
    notes = notes or pl.Notes(f.source)
    n = f.integer("station_total", lo=2)
    eta, K, M = _stations(f, n)
    src = f.source
    field = f"{Path(src).name} stiffness matrix"
    pl.section_stiffness(K, eta, field, src)
    pl.section_mass(M, eta, f"{Path(src).name} mass matrix", src)
    Ks, Ms = beamdyn_to_section(K, M)
    tw = np.zeros_like(eta)
    if twist_deg_by_eta is not None:
        tw = np.radians(np.interp(eta, *twist_deg_by_eta))
    bp = BeamProperties(s=eta, stiffness=Ks, mass=Ms, twist=tw, length=float(length), source=f"BeamDyn {Path(src).name}")
    return bp, _damping(f, notes)


def _stations(f: FastFile, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """eta (n,), K (n, 6, 6), M (n, 6, 6) from the DISTRIBUTED PROPERTIES section."""
    start = next((i for i, ln in enumerate(f.lines) if "DISTRIBUTED PROPERTIES" in ln.upper()), None)
    if start is None:
        f.error("DISTRIBUTED PROPERTIES", "<missing>", "a BeamDyn blade file with a DISTRIBUTED PROPERTIES section")
    rows = []
    for i in range(start + 1, len(f.lines)):
        nums = numbers(f.lines[i])
        if nums is not None:
            rows.append((i, nums))
        if len(rows) >= 13 * n:
            break
    if len(rows) < 13 * n:
        f.error("station_total", n, f"as many stations as the file has ({len(rows) // 13} complete blocks of "
                "eta + 6 stiffness rows + 6 mass rows)")
    eta, K, M = np.empty(n), np.empty((n, 6, 6)), np.empty((n, 6, 6))
    for k in range(n):
        block = rows[13 * k:13 * k + 13]
        line, first = block[0]
        if len(first) != 1:
            f.error(f"station {k + 1} (line {line + 1})", " ".join(f"{x:g}" for x in first[:3]),
                    "one number (eta) followed by 6 rows of K and 6 rows of M")
        for j, (ln, r) in enumerate(block[1:]):
            if len(r) != 6:
                what = "stiffness" if j < 6 else "mass"
                f.error(f"station {k + 1} {what} row {j % 6 + 1} (line {ln + 1})", f"{len(r)} numbers", "6 numbers")
        eta[k] = first[0]
        K[k] = [r for _, r in block[1:7]]
        M[k] = [r for _, r in block[7:13]]
    if eta[0] < -1e-9 or eta[-1] > 1 + 1e-9 or np.any(np.diff(eta) <= 0):
        f.error("station eta values", eta.tolist()[:6], "increasing nondimensional positions in [0, 1]")
    return eta, K, M


def _damping(f: FastFile, notes: pl.Notes) -> BladeDamping | None:
    """``mu1..mu6`` (s) when ``damp_type`` is 1."""
    if not f.has("damp_type") or f.integer("damp_type", lo=0, hi=2) == 0:
        return None
    i0 = f.header("mu1")
    mu = f.rows(i0 + 1, 1, 6, "BeamDyn damping coefficients mu1..mu6")[0]
    pl.damping_mu(mu, f"{Path(f.source).name} mu1..mu6", notes)
    return BladeDamping.from_beamdyn_mu(mu, source=f"BeamDyn {Path(f.source).name} mu1..mu6")
