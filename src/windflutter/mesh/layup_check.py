"""Is the blade layup the blade of the file's 6x6 tables?  The check behind the shell model's warning.

A turbine file can describe its blade twice: as a composite layup (from which the shell model is
built) and as 6x6 section tables (from which the beam model is built).  When the two are not the
same blade the shell and beam models answer different questions, and nothing says so.  The
WISDEM ``NREL-5MW.yaml`` is the case in point: its layup (carbon spar caps, "modified to be more
realistic") is not the Jonkman (2009) blade that its BeamDyn-derived 6x6 describe, and the shell
blade's first flap frequency is 0.91 Hz against 0.68 Hz.

:func:`check_layup_against_6x6` evaluates the project's thin-walled section properties of the
layup (:func:`windflutter.model.section.layup_beam_sections`, the calculator the beam model uses
when a file has no 6x6) at the file's own 6x6 stations and compares, station by station:

* mass per length ``m`` (kg/m);
* flapwise and edgewise bending stiffness (N m^2): the weaker and the stronger principal value
  of the bending block condensed about the tension centre (the Schur complement of EA), which is
  independent of the reference point and of the section frame's twist, so a diagonal 6x6 given at
  the elastic axis (BeamDyn NREL 5 MW) and a coupled one at the pitch axis compare alike;
* torsion stiffness ``GJ`` (N m^2) about the shear centre: the torsion entry condensed over the
  shear strains (the Schur complement of the shear block, where it is given), so a 6x6 at the
  pitch axis with shear-torsion couplings and one without compare alike;
* axial stiffness ``EA`` (N), shown but not judged (it hardly moves the lowest modes).

The verdict of each judged quantity is its *span median*: the median of the station ratios
``layup / file``, each station weighted by the span it represents (trapezoid weights), so that
the root and tip stations -- where thin-walled theory is least reliable and tables are least
careful -- and clustered stations cannot decide it alone.  The quantity disagrees when that median
is off by more than its tolerance:

* **mass 15 %**, **stiffness 25 %**.  Why: the same calculator reproduces an independent
  upstream cross-section code on the *same* layup (IEA 22 MW, 20-90 % span) within 5 % on mass,
  EA and EI and 10 % on GJ (``tests/model/test_layup_section.py``), so a consistent file stays
  well inside (3x the mass error, 2.5-5x the stiffness errors); and 25 % in stiffness or 15 % in
  mass shifts a natural frequency by about 12 % or 7 %, beyond what the project's frequency checks
  accept between two models of one blade.

:func:`shell_layup_warning` returns the one-line warning text (or ``None``) and
:func:`warn_if_shell_is_another_blade` emits it once per turbine as an
:class:`~windflutter.errors.InputWarning`, for the places where the shell model is built.
"""

from __future__ import annotations

import warnings
import weakref
from dataclasses import dataclass, field

import numpy as np

from windflutter.errors import InputError, InputWarning
from windflutter.model.section import layup_beam_sections
from windflutter.model import windio  # module access: tests patch windio.load_turbine

MASS_TOLERANCE = 0.15
STIFFNESS_TOLERANCE = 0.25


@dataclass(frozen=True)
class QuantityCheck:
    """One section property at the file's stations.

    Attributes
    ----------
    name : short key (``"mass"``, ``"EI_flap"``, ``"EI_edge"``, ``"GJ"``, ``"EA"``).
    label : words for tables and warnings, e.g. ``"flap EI"``.
    unit : SI unit of ``layup`` and ``file``.
    layup, file : (n,) values from the layup (thin-walled) and from the file's 6x6.
    weights : (n,) span weight of each station (trapezoid, sums to the compared span fraction).
    tolerance : relative tolerance on the span median; ``None`` = shown, not judged.
    """

    name: str
    label: str
    unit: str
    layup: np.ndarray
    file: np.ndarray
    weights: np.ndarray
    tolerance: float | None

    @property
    def relative(self) -> np.ndarray:
        """(n,) ``layup / file - 1``; NaN where the file value is not positive."""
        f = np.asarray(self.file, dtype=float)
        return np.where(f > 0, np.asarray(self.layup) / np.where(f > 0, f, 1.0) - 1.0, np.nan)

    @property
    def median(self) -> float:
        """Span-weighted median of :attr:`relative` (NaN if no station has a file value)."""
        return weighted_median(self.relative, self.weights)

    @property
    def beyond(self) -> np.ndarray:
        """(n,) stations where ``|relative|`` exceeds the tolerance (all False if not judged)."""
        if self.tolerance is None:
            return np.zeros(self.layup.shape, dtype=bool)
        r = self.relative
        return np.isfinite(r) & (np.abs(r) > self.tolerance)

    @property
    def disagrees(self) -> bool:
        """True when the span median is off by more than the tolerance."""
        m = self.median
        return self.tolerance is not None and bool(np.isfinite(m) and abs(m) > self.tolerance)

    def summary(self) -> str:
        """E.g. ``"flap EI +87 % (span median; stations -6..+215 %, 40 of 49 beyond 25 %)"``."""
        r = self.relative[np.isfinite(self.relative)]
        if r.size == 0:
            return f"{self.label}: no file values"
        tol = f", {int(self.beyond.sum())} of {r.size} beyond {self.tolerance:.0%}" if self.tolerance else ""
        return (f"{self.label} {100 * self.median:+.0f} % (span median; stations "
                f"{100 * r.min():+.0f}..{100 * r.max():+.0f} %{tol})")


@dataclass(frozen=True)
class LayupCheck:
    """The layup's section properties against the file's 6x6, at the file's stations.

    Attributes
    ----------
    turbine : turbine name.
    applicable : False when the file lacks a layup or a 6x6 (nothing to compare; no warning).
    reason : why not applicable (empty otherwise).
    source_6x6 : where the file's 6x6 came from (``BeamProperties.source``).
    s : (n,) span fractions of the compared stations.
    radius : (n,) distance from the blade root along the span (m).
    quantities : the compared properties (mass, EI_flap, EI_edge, GJ judged; EA shown).
    """

    turbine: str
    applicable: bool
    reason: str = ""
    source_6x6: str = ""
    s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    radius: np.ndarray = field(default_factory=lambda: np.zeros(0))
    quantities: tuple[QuantityCheck, ...] = ()

    def quantity(self, name: str) -> QuantityCheck:
        """The :class:`QuantityCheck` called ``name`` (KeyError if there is none)."""
        return {q.name: q for q in self.quantities}[name]

    @property
    def disagreeing(self) -> tuple[QuantityCheck, ...]:
        """The judged quantities whose span median is beyond tolerance."""
        return tuple(q for q in self.quantities if q.disagrees)

    @property
    def disagrees(self) -> bool:
        """True when the layup is not the blade of the 6x6 (any judged quantity disagrees)."""
        return bool(self.disagreeing)

    @property
    def warning(self) -> str | None:
        """One line for the CLI, the report and the store, or ``None`` when they agree."""
        if not self.disagrees:
            return None
        what = ", ".join(f"{q.label} {100 * q.median:+.0f} %" for q in self.disagreeing)
        return (f"{self.turbine}: the blade layup is not the blade of the file's 6x6 tables: layup/6x6 {what} "
                f"(span medians at the file's {self.s.size} stations; tolerance {STIFFNESS_TOLERANCE:.0%} on "
                f"stiffness, {MASS_TOLERANCE:.0%} on mass), so the shell model (from the layup) and the beam "
                "model (from the 6x6) are different blades; station table: python -m windflutter.mesh.layup_check")

    def table(self) -> str:
        """Station-by-station text table: span, radius, then each quantity's layup/file - 1 (%),
        ``*`` marking a station beyond the tolerance."""
        if not self.applicable:
            return f"{self.turbine}: layup vs 6x6 not compared ({self.reason})"
        head = f"{'s':>6} {'r (m)':>7} " + " ".join(f"{q.label:>10}" for q in self.quantities)
        lines = [f"{self.turbine}: layup (thin-walled) / file 6x6 - 1, per cent; * beyond tolerance", head]
        rel = [q.relative for q in self.quantities]
        bey = [q.beyond for q in self.quantities]
        for i, (s, r) in enumerate(zip(self.s, self.radius)):
            cells = [f"{100 * v[i]:+9.1f}{'*' if b[i] else ' '}" if np.isfinite(v[i]) else f"{'-':>10}"
                     for v, b in zip(rel, bey)]
            lines.append(f"{s:6.3f} {r:7.2f} " + " ".join(cells))
        lines.append(f"{'median':>14} " + " ".join(f"{100 * q.median:+9.1f} " for q in self.quantities))
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """Plain-Python form (lists, floats) for JSON output."""
        return {
            "turbine": self.turbine, "applicable": self.applicable, "reason": self.reason,
            "source_6x6": self.source_6x6, "disagrees": self.disagrees, "warning": self.warning,
            "s": self.s.tolist(), "radius_m": self.radius.tolist(),
            "quantities": {q.name: {"label": q.label, "unit": q.unit, "tolerance": q.tolerance,
                                    "span_median": q.median, "disagrees": q.disagrees,
                                    "layup": q.layup.tolist(), "file": q.file.tolist(),
                                    "relative": q.relative.tolist()} for q in self.quantities},
        }

    def store_attributes(self) -> dict[str, str]:
        """Flat string attributes for a NetCDF/zarr store (as ``Turbine.store_attributes``)."""
        if not self.applicable:
            verdict = f"not compared ({self.reason})"
        else:
            verdict = self.warning or "agree: " + "; ".join(q.summary() for q in self.quantities if q.tolerance)
        return {"layup_vs_6x6": verdict}


def weighted_median(values: np.ndarray, weights: np.ndarray) -> float:
    """Median of ``values`` with non-negative ``weights`` (NaN values ignored): the smallest value
    whose cumulative weight reaches half the total, averaged with the next one on an exact tie."""
    v, w = np.asarray(values, dtype=float), np.asarray(weights, dtype=float)
    ok = np.isfinite(v) & (w > 0)
    if not np.any(ok):
        return float("nan")
    order = np.argsort(v[ok])
    vs, cw = v[ok][order], np.cumsum(w[ok][order])
    half = 0.5 * cw[-1]
    i = int(np.searchsorted(cw, half * (1 - 1e-12)))
    if abs(cw[i] - half) <= 1e-12 * cw[-1] and i + 1 < vs.size:
        return float(0.5 * (vs[i] + vs[i + 1]))
    return float(vs[i])


def span_weights(s: np.ndarray) -> np.ndarray:
    """Trapezoid weights of stations ``s`` (sorted span fractions): half of each neighbouring gap."""
    s = np.asarray(s, dtype=float)
    if s.size < 2:
        return np.ones_like(s)
    gaps = np.diff(s)
    w = np.zeros_like(s)
    w[:-1] += 0.5 * gaps
    w[1:] += 0.5 * gaps
    return w


def principal_bending(K: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Weaker and stronger principal bending stiffness (N m^2) of (n, 6, 6) section stiffness
    matrices (``BeamProperties`` order N, V_y, V_z, T, M_y, M_z), about the tension centre.

    The axial-bending block ``[[EA, k_b^T], [k_b, K_bb]]`` (indices 0, 4, 5) is condensed to
    ``K_bb - k_b k_b^T / EA``, which removes the reference point's offset from the tension centre;
    its eigenvalues do not depend on the section frame's orientation.
    """
    K = np.asarray(K, dtype=float)
    EA = K[:, 0, 0]
    kb = K[:, [4, 5], 0]
    Kbb = 0.5 * (K[:, 4:6, 4:6] + np.swapaxes(K[:, 4:6, 4:6], 1, 2))
    safe = np.where(EA > 0, EA, np.inf)
    S = Kbb - kb[:, :, None] * kb[:, None, :] / safe[:, None, None]
    ev = np.linalg.eigvalsh(S)
    return ev[:, 0], ev[:, 1]


def torsion_stiffness(K: np.ndarray) -> np.ndarray:
    """(n,) torsion stiffness (N m^2) about the shear centre of (n, 6, 6) section stiffnesses:
    ``K33 - k^T GA^-1 k`` with ``GA = K[1:3, 1:3]`` and ``k = K[1:3, 3]``; ``K33`` where the shear
    block is not positive definite (tables without shear stiffness)."""
    K = np.asarray(K, float)
    GA, k = K[:, 1:3, 1:3], K[:, 1:3, 3]
    out = K[:, 3, 3].copy()
    ok = (np.linalg.det(GA) > 0) & (GA[:, 0, 0] > 0)
    if np.any(ok):
        out[ok] -= np.einsum("ni,ni->n", k[ok], np.linalg.solve(GA[ok], k[ok][:, :, None])[:, :, 0])
    return out


def _quantities(layup_bp, file_bp, w: np.ndarray) -> tuple[QuantityCheck, ...]:
    lf, le = principal_bending(layup_bp.stiffness)
    ff, fe = principal_bending(file_bp.stiffness)
    rows = (
        ("mass", "mass", "kg/m", layup_bp.mass[:, 0, 0], file_bp.mass[:, 0, 0], MASS_TOLERANCE),
        ("EI_flap", "flap EI", "N m^2", lf, ff, STIFFNESS_TOLERANCE),
        ("EI_edge", "edge EI", "N m^2", le, fe, STIFFNESS_TOLERANCE),
        ("GJ", "GJ", "N m^2", torsion_stiffness(layup_bp.stiffness), torsion_stiffness(file_bp.stiffness),
         STIFFNESS_TOLERANCE),
        ("EA", "EA", "N", layup_bp.stiffness[:, 0, 0], file_bp.stiffness[:, 0, 0], None),
    )
    return tuple(QuantityCheck(n, lab, u, np.asarray(a, float), np.asarray(b, float), w, tol)
                 for n, lab, u, a, b, tol in rows)


def check_layup_against_6x6(turbine, n_contour: int = 240) -> LayupCheck:
    """Compare the blade layup's thin-walled section properties with the file's 6x6 tables.

    Parameters
    ----------
    turbine : :class:`~windflutter.model.turbine.Turbine`.
    n_contour : points on each section's airfoil contour for the thin-walled calculator.

    Returns
    -------
    :class:`LayupCheck` (``applicable`` False when the blade has no layup or no 6x6).  A layup the
    thin-walled calculator cannot evaluate raises its :class:`~windflutter.errors.InputError`, as
    the shell and beam models would.
    """

    blade = turbine.blade
    name = turbine_label(turbine)
    if blade.layup is None or not blade.layup.layers:
        return LayupCheck(name, False, "the file gives no blade layup")
    bp = blade.beam
    if bp is None or bp.s.size == 0:
        return LayupCheck(name, False, "the file gives no 6x6 section tables")
    s = np.asarray(bp.s, dtype=float)
    lay = layup_beam_sections(turbine, s, n_contour=n_contour)
    length = bp.length if np.isfinite(bp.length) and bp.length > 0 else blade.length
    return LayupCheck(name, True, "", bp.source, s, s * length, _quantities(lay, bp, span_weights(s)))


def turbine_label(turbine) -> str:
    """``name (file)`` of a turbine, for messages."""
    from pathlib import Path

    src = Path(turbine.source).name if getattr(turbine, "source", "") else ""
    name = getattr(turbine, "name", "") or src or "turbine"
    return f"{name} ({src})" if src and src != name else name


_DONE: dict[tuple[int, int, int], tuple[weakref.ref, object, object, LayupCheck, list]] = {}


def _entry(turbine) -> tuple[LayupCheck, list]:
    """Cached (check, [warned]) for the turbine's blade, airfoils and materials (the objects the
    check reads; ``dataclasses.replace`` copies of a turbine share them, and so share the entry)."""
    b, af, mats = turbine.blade, turbine.airfoils, turbine.materials
    key = (id(b), id(af), id(mats))
    hit = _DONE.get(key)
    if hit is not None and hit[0]() is b and hit[1] is af and hit[2] is mats:
        return hit[3], hit[4]
    try:
        res = check_layup_against_6x6(turbine)
    except InputError as e:  # the shell mesher may accept a layup the section calculator refuses
        res = LayupCheck(turbine_label(turbine), False, f"thin-walled sections not computable: {e}")
    flag = [False]
    try:
        _DONE[key] = (weakref.ref(b, lambda _r, k=key: _DONE.pop(k, None)), af, mats, res, flag)
    except TypeError:  # an object without weak references: do not cache
        pass
    return res, flag


def cached_check(turbine) -> LayupCheck:
    """:func:`check_layup_against_6x6`, computed once per blade (the shell model is built again
    for every pitch and part; the check costs 0.1-1 s)."""
    return _entry(turbine)[0]


def shell_layup_warning(turbine) -> str | None:
    """The one-line warning for a shell model of ``turbine``, or ``None`` when its layup is the
    blade of its 6x6 (or there is no 6x6 to compare with)."""
    return cached_check(turbine).warning


def warn_if_shell_is_another_blade(turbine) -> str | None:
    """Emit :func:`shell_layup_warning` as an :class:`~windflutter.errors.InputWarning`, once per
    blade, and return it (also when already emitted); call where a shell model is built."""
    res, warned = _entry(turbine)
    msg = res.warning
    if msg and not warned[0]:
        warned[0] = True
        warnings.warn(msg, InputWarning, stacklevel=3)
    return msg


def main(argv: list[str] | None = None) -> int:
    """``python -m windflutter.mesh.layup_check TURBINE [--json]``: print the station table."""
    import argparse
    import json


    ap = argparse.ArgumentParser(prog="python -m windflutter.mesh.layup_check", description=main.__doc__)
    ap.add_argument("turbine", help="turbine file or bundled name")
    ap.add_argument("--json", action="store_true", help="print the result as JSON")
    a = ap.parse_args(argv)
    res = check_layup_against_6x6(windio.load_turbine(a.turbine))
    if a.json:
        print(json.dumps(res.to_dict(), indent=1))
    else:
        print(res.table())
        print(res.warning or "layup and 6x6 agree within tolerance" if res.applicable else "")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
