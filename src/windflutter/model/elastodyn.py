"""ElastoDyn input files: the main file (rotor, nacelle, drivetrain, tower geometry, lumped
masses), the blade file (mass, flap and edge EI, pitch axis, modal damping) and the tower file
(mass, fore-aft and side-to-side EI, modal damping).

OpenFAST's signs are converted to windflutter's (see :class:`~windflutter.model.turbine.Hub`,
:class:`~windflutter.model.turbine.Nacelle`): ``precone = -PreCone``, ``shaft_tilt =
-ShftTilt`` (ElastoDyn's upwind rotors have negative PreCone and ShftTilt), ``overhang =
OverHang``.  Damping in percent is stored as fractions.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from windflutter.model import plausibility as pl
from windflutter.model.fastfile import FastFile
from windflutter.model.turbine import BeamProperties, BladeDamping, TowerDamping
from windflutter.units import DEG, PERCENT


@dataclass(frozen=True)
class ElastoDynMain:
    """The values windflutter takes from an ElastoDyn main file (SI, windflutter signs)."""

    n_blades: int
    tip_radius: float
    hub_radius: float
    precone: float
    hub_cm: float
    overhang: float
    shaft_tilt: float
    nacelle_cg: np.ndarray
    tower_to_shaft: float
    tower_top: float
    tower_base: float
    hub_mass: float
    hub_inertia: float
    generator_inertia: float
    nacelle_mass: float
    nacelle_yaw_inertia: float
    yaw_bearing_mass: float
    gear_ratio: float
    dt_stiffness: float
    dt_damping: float
    blade_file: Path | None
    tower_file: Path
    source: str
    ignored: tuple[str, ...] = ()  # non-zero inputs outside windflutter's model (tip brakes, platform)


def read_elastodyn_main(path: str | Path, need_blade_file: bool = True) -> ElastoDynMain:
    """Rotor/nacelle/tower values of an ElastoDyn main file (``BldFile(1)`` is required for
    ElastoDyn blades only)."""
    f = FastFile(path, "ElastoDyn main file")
    num = f.number
    nb = f.integer("NumBl", lo=1, hi=3)
    tip, hub_r = num("TipRad", positive=True), num("HubRad", nonneg=True)
    if hub_r >= tip:
        f.error("HubRad", hub_r, f"a hub radius smaller than TipRad ({tip:g} m)")
    if num("TowerHt") <= num("TowerBsHt"):
        f.error("TowerHt", num("TowerHt"), f"a tower top above TowerBsHt ({num('TowerBsHt'):g} m)")
    blade_key = "BldFile1" if f.has("BldFile1") else "BldFile(1)"
    return ElastoDynMain(
        n_blades=nb, tip_radius=tip, hub_radius=hub_r, precone=-num("PreCone(1)") * DEG, hub_cm=num("HubCM"),
        overhang=num("OverHang"), shaft_tilt=-num("ShftTilt") * DEG,
        nacelle_cg=np.array([num("NacCMxn"), num("NacCMyn"), num("NacCMzn")]), tower_to_shaft=num("Twr2Shft"),
        tower_top=num("TowerHt"), tower_base=num("TowerBsHt"),
        hub_mass=num("HubMass", nonneg=True), hub_inertia=num("HubIner", nonneg=True),
        generator_inertia=num("GenIner", nonneg=True), nacelle_mass=num("NacMass", nonneg=True),
        nacelle_yaw_inertia=num("NacYIner", nonneg=True), yaw_bearing_mass=num("YawBrMass", 0.0, nonneg=True),
        gear_ratio=num("GBRatio", positive=True), dt_stiffness=num("DTTorSpr", positive=True),
        dt_damping=num("DTTorDmp", 0.0, nonneg=True),
        blade_file=f.file(blade_key, required=need_blade_file), tower_file=f.file("TwrFile"), source=f.source,
        ignored=tuple(k for k in ("TipMass(1)", "PtfmMass") if f.has(k) and num(k, 0.0) != 0),
    )


# ------------------------------------------------------------------------------------------ blade
@dataclass(frozen=True)
class ElastoDynBlade:
    """An ElastoDyn blade table (adjustment factors applied): fraction, pitch axis (None in
    OpenFAST v4 files, which dropped the column), structural twist (deg), mass (kg/m), flap and
    edge EI (N m^2), and the modal damping ratios."""

    frac: np.ndarray
    pitch_axis: np.ndarray | None
    twist_deg: np.ndarray
    mass: np.ndarray
    ei_flap: np.ndarray
    ei_edge: np.ndarray
    damping: BladeDamping
    adj_mass: float
    source: str


def read_elastodyn_blade_table(path: str | Path, apply_adjustment: bool = True,
                               notes: pl.Notes | None = None) -> ElastoDynBlade:
    """The DISTRIBUTED BLADE PROPERTIES table, by column name, and ``BldFlDmp``/``BldEdDmp``."""
    f = FastFile(path, "ElastoDyn blade file")
    notes = notes or pl.Notes(f.source)
    n = f.integer("NBlInpSt", lo=2)
    adj = {k: (f.number(k, 1.0, positive=True) if apply_adjustment else 1.0) for k in ("AdjBlMs", "AdjFlSt", "AdjEdSt")}
    cols, tab = _named_table(f, "BlFract", n, ("BlFract", "StrcTwst", "BMassDen", "FlpStff", "EdgStff"))
    frac = _positive_columns(f, tab, cols, "BlFract", ("BMassDen", "FlpStff", "EdgStff"))
    flap, edge = _ratios(f, (("BldFlDmp(1)", "BldFlDmp(2)"), ("BldEdDmp(1)",)), "BldFlDmp/BldEdDmp", notes)
    damping = BladeDamping(flap_ratio=flap, edge_ratio=edge, source=f"ElastoDyn {Path(f.source).name} BldFlDmp/BldEdDmp")
    return ElastoDynBlade(
        frac=frac, pitch_axis=tab[:, cols["PitchAxis"]] if "PitchAxis" in cols else None,
        twist_deg=tab[:, cols["StrcTwst"]], mass=tab[:, cols["BMassDen"]] * adj["AdjBlMs"],
        ei_flap=tab[:, cols["FlpStff"]] * adj["AdjFlSt"], ei_edge=tab[:, cols["EdgStff"]] * adj["AdjEdSt"],
        damping=damping, adj_mass=adj["AdjBlMs"], source=f.source)


def read_elastodyn_blade(path: str | Path, length: float, apply_mass_adjustment: bool = True,
                         GJ: np.ndarray | None = None, EA: np.ndarray | None = None,
                         notes: pl.Notes | None = None) -> tuple[BeamProperties, BladeDamping]:
    """ElastoDyn blade file -> uncoupled sections and the modal damping ratios.

    EA and GJ are not in ElastoDyn (its blades have no torsion): pass them, or they get rigid
    placeholders of 1e3 x the largest EI, flagged in ``source``.  Mass per length is multiplied by
    ``AdjBlMs`` and the EIs by ``AdjFlSt``/``AdjEdSt`` when ``apply_mass_adjustment`` (Jonkman
    2009's 17,740 kg includes AdjBlMs = 1.04536).
    """
    b = read_elastodyn_blade_table(path, apply_mass_adjustment, notes)
    big = 1e3 * max(b.ei_flap.max(), b.ei_edge.max())
    EA_ = EA if EA is not None else np.full_like(b.mass, big)
    GJ_ = GJ if GJ is not None else np.full_like(b.mass, big)
    # section y is the flapwise *direction*: bending about y is edgewise, about z flapwise
    Ks = diagonal_sections([EA_, big, big, GJ_, b.ei_edge, b.ei_flap])
    Ms = diagonal_sections([b.mass, b.mass, b.mass, 0.0, 0.0, 0.0])
    src = f"ElastoDyn {Path(b.source).name} (AdjBlMs={b.adj_mass})" + ("" if EA is not None else "; EA/GJ rigid placeholders")
    bp = BeamProperties(s=b.frac, stiffness=Ks, mass=Ms, twist=np.radians(b.twist_deg), length=float(length), source=src)
    return bp, b.damping


# ------------------------------------------------------------------------------------------ tower
@dataclass(frozen=True)
class ElastoDynTower:
    """An ElastoDyn tower table (adjustment factors applied) and its modal damping."""

    frac: np.ndarray
    mass: np.ndarray
    ei_fore_aft: np.ndarray
    ei_side_side: np.ndarray
    damping: TowerDamping
    source: str


def read_elastodyn_tower_table(path: str | Path, notes: pl.Notes | None = None) -> ElastoDynTower:
    """``HtFract TMassDen TwFAStif TwSSStif`` (by column name), ``TwrFADmp``/``TwrSSDmp``."""
    f = FastFile(path, "ElastoDyn tower file")
    notes = notes or pl.Notes(f.source)
    n = f.integer("NTwInpSt", lo=2)
    adj = {k: f.number(k, 1.0, positive=True) for k in ("AdjTwMa", "AdjFASt", "AdjSSSt")}
    cols, tab = _named_table(f, "HtFract", n, ("HtFract", "TMassDen", "TwFAStif", "TwSSStif"))
    frac = _positive_columns(f, tab, cols, "HtFract", ("TMassDen", "TwFAStif", "TwSSStif"))
    fa, ss = _ratios(f, (("TwrFADmp(1)", "TwrFADmp(2)"), ("TwrSSDmp(1)", "TwrSSDmp(2)")), "TwrFADmp/TwrSSDmp", notes)
    return ElastoDynTower(
        frac=frac, mass=tab[:, cols["TMassDen"]] * adj["AdjTwMa"], ei_fore_aft=tab[:, cols["TwFAStif"]] * adj["AdjFASt"],
        ei_side_side=tab[:, cols["TwSSStif"]] * adj["AdjSSSt"],
        damping=TowerDamping(fore_aft_ratio=fa, side_side_ratio=ss, source=f"ElastoDyn {Path(f.source).name} TwrFADmp/TwrSSDmp"),
        source=f.source)


def read_elastodyn_tower(path: str | Path, height: float) -> BeamProperties:
    """ElastoDyn tower file -> uncoupled sections (EA, GJ and shear rigid placeholders).  Section
    frame as :func:`~windflutter.model.beamprops.tower_beam_sections`: y = fore-aft direction
    (global x), so bending about z is fore-aft."""
    t = read_elastodyn_tower_table(path)
    big = 1e3 * t.ei_fore_aft.max()
    K = diagonal_sections([big, big, big, big, t.ei_side_side, t.ei_fore_aft])
    M = diagonal_sections([t.mass, t.mass, t.mass, 0.0, 0.0, 0.0])
    return BeamProperties(s=t.frac, stiffness=K, mass=M, twist=np.zeros(t.frac.size), length=float(height),
                          source=f"ElastoDyn {Path(t.source).name}; EA/GJ/shear rigid placeholders")


# ---------------------------------------------------------------------------------------- helpers
def _named_table(f: FastFile, first: str, n: int, required: tuple[str, ...]) -> tuple[dict[str, int], np.ndarray]:
    """Column index by name (from the header line with ``first``) and the ``n`` rows below."""
    i0 = f.header(first)
    names = f.lines[i0].split()
    cols = {nm: j for j, nm in enumerate(names)}
    for nm in required:
        if nm not in cols:
            f.error(f"column {nm}", " ".join(names), f"a table with the columns {', '.join(required)}")
    return cols, f.rows(i0 + 1, n, len(names), f"{first} table")


def _positive_columns(f: FastFile, tab: np.ndarray, cols: dict, frac_key: str, keys: tuple[str, ...]) -> np.ndarray:
    """The fraction column (0 -> 1, non-decreasing) after checking that ``keys`` are positive at
    every station."""
    frac = tab[:, cols[frac_key]]
    if abs(frac[0]) > 1e-6 or abs(frac[-1] - 1.0) > 1e-6 or np.any(np.diff(frac) < 0):
        f.error(frac_key, frac.tolist()[:6], "fractions increasing from 0 to 1")
    for key in keys:
        v = tab[:, cols[key]]
        if np.any(v <= 0):
            i = int(np.argmax(v <= 0))
            f.error(f"{key} at {pl.station(frac, i)}", float(v[i]), "a positive value")
    return frac


def _ratios(f: FastFile, groups, what: str, notes: pl.Notes) -> list[np.ndarray]:
    """Modal damping ratios (fractions; NaN where absent) of each group of percent keys."""
    out = [np.array([f.number(k, np.nan, nonneg=True) for k in g]) * PERCENT for g in groups]
    allv = np.concatenate(out)
    if np.isfinite(allv).any():
        pl.modal_ratios(allv[np.isfinite(allv)], f"{Path(f.source).name} {what}", notes)
    return out


def diagonal_sections(diag: list) -> np.ndarray:
    """(n, 6, 6) diagonal matrices from six entries, each a scalar or an (n,) array."""
    d = np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in diag])
    return np.einsum("jn,jk->njk", np.array(d), np.eye(6))
