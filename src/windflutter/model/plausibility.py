"""Physical plausibility of turbine data at the file's own stations (before any interpolation).

Every reader calls these checks on the arrays as they come out of the file, so a problem is
named by the file, the field and the station (index and span position) where it is.  Two
levels:

* **impossible** (a non-positive-definite 6x6, negative drag, a folded span axis, a chord larger
  than half the blade, radians in a degree file ...): :class:`~windflutter.errors.InputError`;
* **unusual** (outside the range of built turbines, but physically possible): an
  :class:`~windflutter.errors.InputWarning` printed once and recorded in :class:`Notes`, which
  the reader stores on :attr:`Turbine.warnings <windflutter.model.turbine.Turbine.warnings>`.

The bounds are deliberately wide (the "unusual" band is about the range of today's multi-MW
reference turbines, the "impossible" band is one to several orders of magnitude beyond it); each
is stated where it is used.  Whole-turbine consistency (rotor diameter, hub height, lumped
masses, the blade's frequency scale) is in :mod:`windflutter.model.consistency`.
"""

from __future__ import annotations

import contextlib
import warnings

import numpy as np

from windflutter.errors import InputError, InputWarning

MAX_STATIONS = 20_000  #: stations in any one spanwise table (blade, tower, polar): a bound before work
MAX_FILE_BYTES = 64 * 2**20  #: largest turbine input file read (the IEA 22 MW windIO file is 3 MB)

# BeamDyn-order (F1, F2, F3, M1, M2, M3) names of the diagonal terms, for messages
_K_NAMES = ("K11 (shear, flapwise)", "K22 (shear, edgewise)", "K33 (EA)", "K44 (edgewise EI)",
            "K55 (flapwise EI)", "K66 (torsion GJ)")


class Notes:
    """Warnings found while reading one turbine: printed as :class:`InputWarning` and kept.

    Parameters
    ----------
    source
        The file being read (named in every message).
    """

    def __init__(self, source: str | None):
        self.source = source
        self.items: list[str] = []

    def for_file(self, source: str | None) -> "Notes":
        """Notes for another file of the same turbine (same list of warnings)."""
        other = Notes(source)
        other.items = self.items
        return other

    def warn(self, field: str, message: str, source: str | None = None) -> None:
        """Record and print one warning ``<file>: <field>: <message>``."""
        where = source or self.source
        text = f"{where}: {field}: {message}" if where else f"{field}: {message}"
        if text not in self.items:
            self.items.append(text)
            warnings.warn(text, InputWarning, stacklevel=3)

    def error(self, field: str, value, expected: str, source: str | None = None):
        """Raise :class:`InputError` for this file (or ``source``)."""
        raise InputError(field, value, expected, source or self.source)


@contextlib.contextmanager
def collected(notes: Notes):
    """Record every :class:`InputWarning` raised inside (also by code that warns directly, such
    as the WISDEM-defect repairs) in ``notes``, and still show it once."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", InputWarning)
        yield notes
    for w in caught:
        text = str(w.message)
        if issubclass(w.category, InputWarning) and text not in notes.items:
            notes.items.append(text)
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)


def station(s: np.ndarray, i: int) -> str:
    """``"station 17 (span 0.5000)"`` for messages."""
    return f"station {int(i)} (span {float(s[i]):.4f})"


def bounded_count(n: int, field: str, source: str | None, limit: int = MAX_STATIONS) -> int:
    """``n`` if it is a sane table size, else :class:`InputError` (checked before allocating)."""
    if not 0 < n <= limit:
        raise InputError(field, n, f"a table size between 1 and {limit}", source)
    return int(n)


# ------------------------------------------------------------------------------- section matrices
def section_stiffness(K: np.ndarray, s: np.ndarray, field: str, source: str | None) -> None:
    """(n, 6, 6) BeamDyn-order stiffness: finite, symmetric, positive EA, EIs and GJ, shear >= 0
    (0 = shear-rigid, as WISDEM writes it), and positive definite over the non-rigid terms.

    Raises :class:`InputError` naming the first bad station and the entry."""
    K = np.asarray(K, dtype=float)
    if not np.all(np.isfinite(K)):
        i = int(np.argwhere(~np.isfinite(K))[0][0])
        raise InputError(f"{field} at {station(s, i)}", "non-finite entry", "finite stiffness terms", source)
    d = np.diagonal(K, axis1=1, axis2=2)
    for j in range(6):
        bad = d[:, j] < 0 if j < 2 else d[:, j] <= 0
        if bad.any():
            i = int(np.argmax(bad))
            need = ">= 0 (0 = shear-rigid)" if j < 2 else "> 0"
            raise InputError(f"{field} {_K_NAMES[j]} at {station(s, i)}", float(d[i, j]),
                             f"a stiffness {need} (N, N m^2)", source)
    scale = np.maximum(np.abs(K).max(axis=(1, 2)), 1e-300)
    asym = np.abs(K - K.transpose(0, 2, 1)).max(axis=(1, 2)) > 1e-6 * scale
    if asym.any():
        i = int(np.argmax(asym))
        raise InputError(f"{field} at {station(s, i)}", "not symmetric", "a symmetric 6x6 stiffness matrix", source)
    rigid = d <= 0  # zero shear terms: treat as rigid (unit diagonal after scaling)
    dd = np.where(rigid, 1.0, d)
    Kn = K / np.sqrt(dd[:, :, None] * dd[:, None, :])
    # rigid (zero) shear terms are replaced by a rigid section when meshed: leave their rows out
    Kn = np.where(rigid[:, :, None] | rigid[:, None, :], 0.0, Kn) + np.einsum("ni,ij->nij", rigid, np.eye(6))
    lam = np.linalg.eigvalsh(0.5 * (Kn + Kn.transpose(0, 2, 1))).min(axis=1)
    bad = lam <= 1e-9
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(f"{field} at {station(s, i)}", f"smallest scaled eigenvalue {lam[i]:.3g}",
                         "a positive definite 6x6 stiffness (couplings smaller than the direct terms allow)",
                         source)


def section_mass(M: np.ndarray, s: np.ndarray, field: str, source: str | None) -> None:
    """(n, 6, 6) section mass matrices (any order): finite, mass > 0, symmetric positive
    semi-definite (tolerance 1e-9 of the largest entry); :class:`InputError` at the first bad
    station."""
    M = np.asarray(M, dtype=float)
    if not np.all(np.isfinite(M)):
        i = int(np.argwhere(~np.isfinite(M))[0][0])
        raise InputError(f"{field} at {station(s, i)}", "non-finite entry", "finite mass terms", source)
    scale = np.maximum(np.abs(M).max(axis=(1, 2)), 1e-300)
    lam = np.linalg.eigvalsh(0.5 * (M + M.transpose(0, 2, 1))).min(axis=1)
    asym = np.abs(M - M.transpose(0, 2, 1)).max(axis=(1, 2)) > 1e-9 * scale
    bad = asym | (lam < -1e-9 * scale) | (M[:, 0, 0] <= 0)
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(f"{field} at {station(s, i)}", f"smallest eigenvalue {lam[i]:.4g}",
                         "a positive semi-definite section mass matrix: mass > 0, i_edge, i_flap >= 0, "
                         "i_cp^2 <= i_edge i_flap, i_plr = i_edge + i_flap (fix the file's inertia_matrix)",
                         source)


def section_matrices(K: np.ndarray | None, M: np.ndarray | None, s: np.ndarray, field: str,
                     notes: Notes, source: str | None = None) -> None:
    """Both checks above at the file's stations ``s`` (BeamDyn order)."""
    src = source or notes.source
    if K is not None:
        section_stiffness(K, s, field, src)
    if M is not None:
        section_mass(M, s, field, src)


def damping_mu(mu: np.ndarray, field: str, notes: Notes) -> None:
    """Stiffness-proportional damping coefficients (s): >= 0; above 1 s the damping ratio of a
    1 Hz mode would be pi: impossible; above 0.05 s (16 % at 1 Hz) unusual."""
    mu = np.asarray(mu, dtype=float)
    if np.any(~np.isfinite(mu)) or np.any(mu < 0) or np.any(mu > 1.0):
        notes.error(field, mu.tolist(), "six stiffness-proportional coefficients between 0 and 1 s")
    if np.any(mu > 0.05):
        notes.warn(field, f"max {mu.max():.3g} s: a damping ratio of {np.pi * mu.max():.0%} at 1 Hz")


def modal_ratios(values, field: str, notes: Notes) -> None:
    """Modal damping ratios (fractions): 0..1 possible, above 0.2 unusual for structure."""
    v = np.asarray(values, dtype=float)
    if np.any(~np.isfinite(v)) or np.any(v < 0) or np.any(v >= 1.0):
        notes.error(field, (v * 100).tolist(), "damping ratios between 0 and 100 % of critical")
    if np.any(v > 0.2):
        notes.warn(field, f"{v.max():.0%} of critical: unusually high structural damping")


# ---------------------------------------------------------------------------------------- control
#: tip speed (m/s) of the maximum rotor speed: at or above the speed of sound impossible (rpm given
#: where rad/s is expected?), outside 40-130 m/s unusual (today's reference turbines: NREL 5 MW 80,
#: IEA 10 MW 90, IEA 15 MW 95, IEA 22 MW 105 m/s)
TIP_SPEED_IMPOSSIBLE = 340.0
TIP_SPEED_USUAL = (40.0, 130.0)
#: usual design tip-speed ratio
TSR_USUAL = (3.0, 15.0)


def control_limits(c, where: dict, radius: float, notes: Notes, radius_name: str = "assembly.rotor_diameter / 2") -> None:
    """The control block's limits against each other and the rotor radius (m).

    ``c`` is a :class:`~windflutter.model.turbine.ControlSettings` (SI), ``where`` maps its
    fields to ``(key in the file, value as written)`` for the messages.  Impossible: cut-out at or
    below cut-in, a minimum rotor speed above the maximum, a tip speed at or above the speed of
    sound (at ``radius``, named ``radius_name``); unusual: tip speeds and TSR outside the ranges
    above."""
    def name(f):
        return where[f][0]

    def given(f):
        return f in where and np.isfinite(getattr(c, f))

    if given("cut_in") and given("cut_out") and not c.cut_out > c.cut_in:
        notes.error(name("cut_out"), where["cut_out"][1], f"a cut-out wind speed above cut-in ({c.cut_in:g} m/s)")
    if given("min_rotor_speed") and given("max_rotor_speed") and c.min_rotor_speed > c.max_rotor_speed:
        notes.error(name("min_rotor_speed"), where["min_rotor_speed"][1],
                    f"a minimum rotor speed at most the maximum ({name('max_rotor_speed')} = "
                    f"{where['max_rotor_speed'][1]:g})")
    for f, w in (("max_rotor_speed", c.max_rotor_speed * radius), ("max_tip_speed", c.max_tip_speed)):
        if not given(f):
            continue
        if w >= TIP_SPEED_IMPOSSIBLE:
            notes.error(name(f), where[f][1], f"a tip speed below the speed of sound (this one gives {w:.4g} m/s at "
                        f"{radius_name} = {radius:.4g} m; rpm given where rad/s is expected, or a wrong radius?)")
        lo, hi = TIP_SPEED_USUAL
        if not lo <= w <= hi:
            notes.warn(name(f), f"{where[f][1]:g} gives a tip speed of {w:.3g} m/s, outside the {lo:g}-{hi:g} m/s "
                       "of built multi-MW turbines")
    if given("tsr") and not TSR_USUAL[0] <= c.tsr <= TSR_USUAL[1]:
        notes.warn(name("tsr"), f"tip-speed ratio {c.tsr:g} is outside the usual {TSR_USUAL[0]:g}-{TSR_USUAL[1]:g}")


# ----------------------------------------------------------------------------------- blade shape
def span_axis(g: np.ndarray, z: np.ndarray, field: str, notes: Notes) -> None:
    """The span coordinate (m) must increase from root to tip at every station (a folded axis is
    not a blade)."""
    dz = np.diff(z)
    if np.any(dz <= 0):
        i = int(np.argmax(dz <= 0)) + 1
        notes.error(f"{field}[{i}] ({station(g, i)})", float(z[i]),
                    f"span positions increasing from root to tip (previous {float(z[i - 1]):.6g} m)")


def offsets(g: np.ndarray, v: np.ndarray, length: float, what: str, field: str, notes: Notes) -> None:
    """Prebend or sweep (m) against the blade length ``length``: beyond half the blade impossible,
    beyond 15 % unusual (the IEA 22 MW has about 5 %)."""
    a = np.abs(v)
    i = int(np.argmax(a))
    if a[i] > 0.5 * length:
        notes.error(f"{field}[{i}] ({station(g, i)})", float(v[i]), f"a {what} smaller than half the blade length "
                    f"({0.5 * length:.4g} m)")
    if a[i] > 0.15 * length:
        notes.warn(f"{field}[{i}]", f"{what} {v[i]:.4g} m is {a[i] / length:.0%} of the blade length")


def chord_twist(cg, cv, tg, tv, length: float, chord_field: str, twist_field: str, notes: Notes) -> None:
    """Chord (m) against the blade length ``length`` (above half of it impossible, above 20 %
    unusual) and twist (rad) within +-180 deg (above 45 deg unusual), at the file's stations."""
    i = int(np.argmax(cv))
    if cv[i] > 0.5 * length:
        notes.error(f"{chord_field}[{i}] ({station(cg, i)})", float(cv[i]),
                    f"a chord smaller than half the blade length ({0.5 * length:.4g} m)")
    if cv[i] > 0.2 * length:
        notes.warn(f"{chord_field}[{i}]", f"chord {cv[i]:.4g} m is {cv[i] / length:.0%} of the blade length")
    j = int(np.argmax(np.abs(tv)))
    if abs(tv[j]) > np.pi:
        notes.error(f"{twist_field}[{j}] ({station(tg, j)})", float(np.degrees(tv[j])),
                    "a twist within +-180 deg (radians given where degrees are expected, or the reverse?)")
    if abs(tv[j]) > np.radians(45.0):
        notes.warn(f"{twist_field}[{j}]", f"twist {np.degrees(tv[j]):.1f} deg: unusually large")


def pitch_axis(g: np.ndarray, pa: np.ndarray, field: str, notes: Notes) -> None:
    """Chordwise position of the reference axis (fraction of chord from the LE)."""
    out = (pa < -0.5) | (pa > 1.5)
    if out.any():
        i = int(np.argmax(out))
        notes.error(f"{field}[{i}] ({station(g, i)})", float(pa[i]), "a pitch-axis position between -0.5 and 1.5 "
                    "chords from the leading edge")
    if np.any((pa < 0) | (pa > 1)):
        notes.warn(field, "reference axis outside the chord at some stations")


def relative_thickness(tc: float, field: str, notes: Notes) -> None:
    """t/c is a fraction: above 1 (a percentage?) impossible."""
    if not 0 < tc <= 1.0 + 1e-6:
        notes.error(field, tc, "a relative thickness t/c in (0, 1] (a fraction, not percent)")


# ---------------------------------------------------------------------------------------- polars
def polar(alpha: np.ndarray, cl: np.ndarray, cd: np.ndarray, tc: float, field: str, unit: str,
          notes: Notes, alpha_field: str | None = None) -> None:
    """One polar (alpha in rad, after the file's unit conversion; ``unit`` the file's unit).

    Impossible: angles that only make sense in the other unit (|alpha| <= pi throughout a degree
    file spanning more than 1 "deg"; |alpha| > 2 pi in a radian file), Cd < 0, |Cl| > 5, Cd > 5,
    and for airfoils (t/c < 0.5) a lift slope <= 0 (sign-flipped) or no lift at all.  Unusual: a
    lift slope outside 0.4..1.6 x 2 pi per rad, Cd > 2.5.
    """
    af = alpha_field or f"{field}.alpha"
    bounded_count(alpha.size, af, notes.source)
    for name, v in (("alpha", alpha), ("Cl", cl), ("Cd", cd)):  # a NaN passes every bound below
        bad = ~np.isfinite(np.asarray(v, dtype=float))
        if bad.any():
            i = int(np.argmax(bad))
            notes.error(af if name == "alpha" else f"{field} {name}", f"{v[i]} (row {i + 1})", "finite numbers")
    raw = alpha / (np.pi / 180.0) if unit == "deg" else alpha
    if unit == "deg" and np.max(np.abs(raw)) <= np.pi * (1 + 1e-5) and np.ptp(raw) > 1.0:  # 6-digit files
        notes.error(af, f"{raw.min():.4g} .. {raw.max():.4g}", "angles of attack in degrees (these look like radians)")
    if unit == "rad" and np.max(np.abs(raw)) > 2 * np.pi * (1 + 1e-5):
        notes.error(af, f"{raw.min():.4g} .. {raw.max():.4g}", "angles of attack in radians (these look like degrees)")
    if np.any(cd < -1e-6):
        i = int(np.argmax(cd < -1e-6))
        notes.error(f"{field} Cd at alpha {np.degrees(alpha[i]):.2f} deg", float(cd[i]), "a drag coefficient >= 0")
    for name, c, lim in (("Cl", np.abs(cl), 5.0), ("Cd", cd, 5.0)):
        if np.max(c) > lim:
            i = int(np.argmax(c))
            notes.error(f"{field} {name} at alpha {np.degrees(alpha[i]):.2f} deg", float(c[i]),
                        f"|{name}| <= {lim:g} (a 2D section coefficient)")
    if np.max(cd) > 2.5:
        notes.warn(field, f"Cd up to {np.max(cd):.3g}: unusually high")
    if tc >= 0.5 or alpha.size < 2:
        return  # cylinders and thick root sections may have no lift
    slope = lift_slope(alpha, cl)
    if np.max(np.abs(cl)) < 1e-6 or slope <= 0:
        notes.error(f"{field} Cl", f"lift slope {slope:.3g} /rad",
                    "a positive lift slope near zero angle of attack (about 2 pi /rad; sign-flipped or zero lift?)")
    if not 0.4 * 2 * np.pi <= slope <= 1.6 * 2 * np.pi:
        notes.warn(f"{field} Cl", f"lift slope {slope:.3g} /rad near zero angle of attack (thin airfoil: 2 pi)")


def lift_slope(alpha: np.ndarray, cl: np.ndarray) -> float:
    """dCl/dalpha (1/rad) by least squares over -4..+6 deg (the attached range of wind-turbine
    airfoils), or between the values interpolated at -2 and +4 deg when fewer than 3 points lie
    there."""
    lo, hi = np.radians(-4.0), np.radians(6.0)
    m = (alpha >= lo) & (alpha <= hi)
    if m.sum() >= 3:
        return float(np.polyfit(alpha[m], cl[m], 1)[0])
    a0, a1 = np.radians(-2.0), np.radians(4.0)
    return float((np.interp(a1, alpha, cl) - np.interp(a0, alpha, cl)) / (a1 - a0))


# -------------------------------------------------------------------------------------- materials
def material(name: str, E: float, rho: float, field: str, notes: Notes) -> None:
    """Young's modulus (Pa) and density (kg/m^3) of a material: E in 1e4..1e13 Pa and rho in
    1..25000 kg/m^3 possible (foams to tungsten, carbon fibre's 2e11 Pa); E below 1e6 Pa or rho
    below 10 kg/m^3 unusual."""
    if not 1e4 <= E <= 1e13:
        notes.error(f"{field}.E", E, "a Young's modulus between 1e4 and 1e13 Pa")
    if not 1.0 <= rho <= 25000.0:
        notes.error(f"{field}.rho", rho, "a density between 1 and 25000 kg/m^3")
    if E < 1e6 or rho < 10.0:
        notes.warn(field, f"{name}: E = {E:.3g} Pa, rho = {rho:.3g} kg/m^3: unusually soft or light")
