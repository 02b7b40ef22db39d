"""Stability maps for the comparison with the seed thesis (docs/notes/seed_comparison.md).

Rotor alone (hub clamped, ``part="rotor"``), beam model, default strips, p-k search, no
structural damping; flutter and divergence onset (RPM) per wind speed, pitch from each turbine's
operating curve.

* NREL 5 MW: potential / viscous x thesis physics (no K_sigma) / full physics;
* the seed's 20 MW (``seed20mw``) and the IEA 15 MW (``iea15mw``): potential and viscous, full
  physics.

Usage::

    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR [--turbines nrel5mw ...]
    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR --plot-only
    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR --fits nrel5mw
    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR --candidates
    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR --divergence-full
    OMP_NUM_THREADS=1 .venv/bin/python docs/scripts/seed_comparison.py OUTDIR --damping-check iea15mw 10

writes ``OUTDIR/maps.csv`` (one row per turbine, variant and wind speed; appended as it goes, so
a run can be split by turbine), ``OUTDIR/maps.md`` (the same as a markdown table) and
``OUTDIR/<turbine>_flutter.png`` / ``OUTDIR/<turbine>_divergence.png``; ``--candidates`` runs the
study of why the seed's viscous onset is above its potential one (``candidates.csv/.md``).
"""

from __future__ import annotations

import argparse
import csv
import math
import time
from pathlib import Path

# per turbine: wind speeds (m/s), rotor-speed grid (RPM: min, max, step), variants (aero, physics)
CASES = {
    "nrel5mw": dict(wind=(4, 6, 8, 10, 12, 15, 20, 25), rpm=(8.0, 36.0, 2.0),
                    variants=(("potential", "thesis"), ("potential", "full"),
                              ("viscous", "thesis"), ("viscous", "full"))),
    "seed20mw": dict(wind=(4, 10, 16, 25), rpm=(2.0, 20.0, 1.5),
                     variants=(("potential", "full"), ("viscous", "full"))),
    "iea15mw": dict(wind=(4, 10, 16, 25), rpm=(2.0, 20.0, 1.5),
                    variants=(("potential", "full"), ("viscous", "full"))),
}
RATED_RPM = {"nrel5mw": 12.1, "seed20mw": 6.31, "iea15mw": 7.56}
#: model reduction of the p-k runs: the plain 30+30-mode basis that was the default when the page
#: was made (commit db17d2b); the default is now "mta" (b40b4a3), which adds aerodynamic
#: static-correction vectors -- set REDUCTION = "mta" to redo the maps with it
REDUCTION = "modal"
FIELDS = ("turbine", "aero", "physics", "wind_speed", "pitch_deg", "flutter_rpm", "flutter_hz",
          "flutter_mode", "divergence_rpm", "seconds")


def _tolerate_lost_start_vectors():
    """Work-around (this script only): the p-k search may return ``None`` for a mode it could not
    follow at the first grid point (seen on the seed 20 MW at 2 RPM with commit 48119ce), and
    ``TurbineStability`` then fails while labelling the starting modes.  Replace such vectors by
    zeros (their label is meaningless and is replaced by "lost" in the table)."""
    import numpy as np

    import windflutter.frozen.turbine as tmod

    inner = tmod.pk_search
    if getattr(inner, "_tolerant", False):
        return

    def pk_search(*args, **kwargs):
        on = inner(*args, **kwargs)
        vs = on.vectors0
        if vs is not None and any(v is None for v in vs):
            n = next(len(v) for v in vs if v is not None)
            on.lost0 = [i for i, v in enumerate(vs) if v is None]
            on.vectors0 = [np.zeros(n, complex) if v is None else v for v in vs]
        return on

    pk_search._tolerant = True
    tmod.pk_search = pk_search


def run_case(name: str, out_csv: Path) -> None:
    """Analyse every variant and wind speed of one turbine, appending rows to ``out_csv``."""
    from windflutter.model.windio import load_turbine
    from windflutter.frozen.turbine import TurbineOptions, TurbineStability

    _tolerate_lost_start_vectors()

    case = CASES[name]
    turbine = load_turbine(name)
    new = not out_csv.exists()
    with out_csv.open("a", newline="") as fh:
        w = csv.DictWriter(fh, FIELDS)
        if new:
            w.writeheader()
        for aero, physics in case["variants"]:
            lo, hi, step = case["rpm"]
            opts = TurbineOptions(model="beam", aero=aero, physics=physics, method="pk",
                                  rpm_min=lo, rpm_max=hi, rpm_step=step, mesh={"part": "rotor"}, reduction=REDUCTION)
            ts = TurbineStability(turbine, opts)
            for v in case["wind"]:
                t0 = time.time()
                p = ts.analyse_operating_point(float(v))
                f = (lambda x: "" if x is None else f"{x:.3f}")
                mode = p.flutter_mode or ""
                if p.onset.flutter_mode in getattr(p.onset, "lost0", []) and " -> " in mode:
                    mode = "lost -> " + mode.split(" -> ", 1)[1]
                w.writerow(dict(turbine=name, aero=aero, physics=physics, wind_speed=v,
                                pitch_deg=f"{p.pitch_deg:.2f}", flutter_rpm=f(p.flutter_rpm),
                                flutter_hz=f(p.flutter_frequency_hz), flutter_mode=mode,
                                divergence_rpm=f(p.divergence_rpm), seconds=f"{time.time() - t0:.0f}"))
                fh.flush()
                print(name, aero, physics, v, p.flutter_rpm, p.divergence_rpm, flush=True)


def read_rows(out_csv: Path) -> list[dict]:
    with out_csv.open() as fh:
        return list(csv.DictReader(fh))


def write_markdown(rows: list[dict], path: Path) -> None:
    head = "| turbine | aero | physics | V (m/s) | pitch (deg) | flutter (RPM) | f (Hz) | divergence (RPM) | flutter mode |"
    lines = [head, "|" + "---|" * 9]
    for r in rows:
        lines.append(f"| {r['turbine']} | {r['aero']} | {r['physics']} | {r['wind_speed']} | {r['pitch_deg']} | "
                     f"{r['flutter_rpm'] or '-'} | {r['flutter_hz'] or '-'} | {r['divergence_rpm'] or '-'} | "
                     f"{r['flutter_mode']} |")
    path.write_text("\n".join(lines) + "\n")


def plot(rows: list[dict], outdir: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {("potential", "full"): ("C0", "-o"), ("potential", "thesis"): ("C0", "--s"),
              ("viscous", "full"): ("C3", "-o"), ("viscous", "thesis"): ("C3", "--s")}
    for name in sorted({r["turbine"] for r in rows}):
        for key, title in (("flutter_rpm", "flutter"), ("divergence_rpm", "divergence")):
            fig, ax = plt.subplots(figsize=(5.2, 3.6))
            for (aero, physics), (color, fmt) in styles.items():
                sel = [r for r in rows if r["turbine"] == name and r["aero"] == aero and r["physics"] == physics]

                f_ref = [float(r["flutter_hz"]) for r in sorted(sel, key=lambda r: float(r["wind_speed"]))
                         if r["flutter_hz"]][:1]

                def edgewise(r):
                    """An onset of another, nearly undamped mode: a pure in-plane shape, or a frequency
                    50 % away from the flutter mode at the lowest wind speed (checked by --damping-check)."""
                    if key != "flutter_rpm":
                        return False
                    other = bool(f_ref) and r["flutter_hz"] and abs(float(r["flutter_hz"]) / f_ref[0] - 1) > 0.5
                    return r["flutter_mode"].split(" -> ")[-1].startswith("edge ") or bool(other)

                pts = [(float(r["wind_speed"]), float(r[key])) for r in sel if r[key] and not edgewise(r)]
                if pts:
                    x, y = zip(*pts)
                    ax.plot(x, y, fmt, color=color, ms=4, label=f"{aero}, {physics} physics")
                edge = [(float(r["wind_speed"]), float(r[key])) for r in sel if r[key] and edgewise(r)]
                if edge:
                    x, y = zip(*edge)
                    ax.plot(x, y, "x", color=color, ms=7, label=f"{aero}: other mode, nearly undamped (see text)")
            full = outdir / "divergence_full.csv"
            if key == "divergence_rpm" and full.exists():
                for aero, color in (("potential", "C0"), ("viscous", "C3")):
                    fr = [r for r in read_rows(full) if r["turbine"] == name and r["aero"] == aero
                          and r["physics"] == "full" and r["divergence_full_rpm"]]
                    if fr:
                        ax.plot([float(r["wind_speed"]) for r in fr], [float(r["divergence_full_rpm"]) for r in fr],
                                "+", color=color, ms=9, mew=1.5, label=f"{aero}, full order (static)")
            ax.axhline(RATED_RPM[name], color="k", lw=0.8, ls=":", label=f"rated {RATED_RPM[name]} RPM")
            if name == "nrel5mw" and key == "flutter_rpm":
                # the only values the seed's text gives for fig. 4.9 (at 10 m/s)
                ax.plot([10.0], [19.1], "k*", ms=9, label="AIAA 2008-1302: 19.1 RPM")
                ax.plot([10.0], [19.0], "o", mfc="none", mec="C0", ms=8, label="seed potential ~19")
                ax.plot([10.0], [21.0], "o", mfc="none", mec="C3", ms=8, label="seed viscous ~21")
            ax.set_xlabel("wind speed (m/s)")
            ax.set_ylabel("rotor speed (RPM)")
            ax.set_title(f"{name}: {title} onset (rotor alone, beam, p-k)", fontsize=9)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(outdir / f"{name}_{title}.png", dpi=90)
            plt.close(fig)


# ------------------------------------------------------------------------------------------
# Part 1: why the seed's viscous onset lies above its potential one (NREL 5 MW, 10 m/s)

def _stall_fit(polar, start: str) -> float:
    """Cl_alpha of a straight line fitted from ``start`` ("alpha0": the zero-lift angle, "m15":
    -15 deg) up to the angle of maximum lift below 25 deg: readings of the seed's "until the
    separation angle of attack" that reach into the rounded top of the lift curve."""
    import numpy as np

    from windflutter.aero.polars import fit_polar

    f = fit_polar(polar)
    if f.cl_alpha == 0:
        return 0.0
    a, cl = polar.alpha, polar.cl
    m = (a > f.alpha_zero_lift) & (a < np.radians(25.0))
    a_stall = a[np.where(m)[0][np.argmax(cl[m])]]
    a_lo = f.alpha_zero_lift if start == "alpha0" else np.radians(-15.0)
    sel = (a >= a_lo) & (a <= a_stall)
    return float(np.polyfit(a[sel], cl[sel], 1)[0])


def candidates(outdir: Path, wind: float = 10.0) -> list[dict]:
    """Onset at one wind speed for each candidate explanation; rows also written to
    ``outdir/candidates.csv`` / ``.md``.  The variants change only the strip slopes (public
    ``AeroOptions.lift_slope/drag_slope`` of the built model) or, for the a.c. shift and the
    flat-plate drag, wrap ``strip.section_matrices`` inside this script."""
    import numpy as np
    from dataclasses import replace

    import windflutter.aero.strip as strip
    from windflutter.aero.polars import fit_polar
    from windflutter.model.windio import load_turbine
    from windflutter.frozen.turbine import TurbineOptions, TurbineStability

    turbine = load_turbine("nrel5mw")
    base_sm = strip.section_matrices

    def flat_plate_drag(b, a, U, C, rho, cla=2 * np.pi, cda=0.0, am_scale=1.0, ac_shift=0.0):
        # the seed's eqs. 3.46-3.48: alpha_unsteady = L_flat_plate / (2 pi rho U^2 b), including
        # the non-circulatory terms (ours: circulatory lift only)
        Ma, Da, Ka = base_sm(b, a, U, C, rho, cla, 0.0, am_scale, ac_shift)
        Mf, Df, Kf = base_sm(b, a, U, C, rho, 2 * np.pi, 0.0, 1.0)
        f = np.broadcast_to(np.asarray(cda, float), (len(b),))[:, None] / (2 * np.pi)
        for X, Y in ((Ma, Mf), (Da, Df), (Ka, Kf)):
            X[:, 2, :] = f * Y[:, 0, :]
        return Ma, Da, Ka

    def case(label, aero="potential", ams=False, cla=None, cda=None, ac=False, sm=None):
        opts = TurbineOptions(model="beam", aero=aero, apparent_mass_scaling=ams, mesh={"part": "rotor"},
                              rpm_min=10.0, rpm_max=32.0, rpm_step=2.0, reduction=REDUCTION)
        ts = TurbineStability(turbine, opts)
        fe, sec, am = ts.model(ts.pitch_at(wind))
        fits = [fit_polar(p) for p in sec.polars]
        idx = np.asarray(sec.airfoil)
        if aero == "viscous":
            c0, d0 = np.asarray(am.aero.lift_slope, float), np.asarray(am.aero.drag_slope, float)
            c1 = c0 if cla is None else np.asarray(cla(c0, sec), float)
            d1 = d0 if cda is None else np.asarray(cda(d0), float)
            am.aero = replace(am.aero, lift_slope=c1, drag_slope=d1)
        wrap = sm
        if ac:
            dx = np.array([fits[i].ac_shift for i in idx])
            inner = sm or base_sm
            wrap = (lambda *a, **k: inner(*a, **{**k, "ac_shift": dx}))
        strip.section_matrices = wrap or base_sm
        try:
            p = ts.analyse_operating_point(wind)
        finally:
            strip.section_matrices = base_sm
        tip = np.asarray(am.aero.lift_slope)[np.argmax(sec.radius)] if aero == "viscous" else 2 * np.pi
        row = dict(candidate=label, tip_cl_alpha=f"{tip:.2f}", flutter_rpm=f"{p.flutter_rpm:.2f}" if p.flutter_rpm else "",
                   flutter_hz=f"{p.flutter_frequency_hz:.3f}" if p.flutter_frequency_hz else "",
                   divergence_rpm=f"{p.divergence_rpm:.2f}" if p.divergence_rpm else "")
        print(row, flush=True)
        return row

    def uniform(c):
        return lambda c0, sec: np.where(c0 > 0, c, 0.0)

    def stall_fit(start):
        return lambda c0, sec: np.array([_stall_fit(sec.polars[i], start) for i in np.asarray(sec.airfoil)])

    rows = [case("potential (2 pi, no drag)"),
            case("viscous as fitted (default)", "viscous"),
            case("viscous, drag off", "viscous", cda=lambda d: 0 * d),
            case("viscous, drag x10", "viscous", cda=lambda d: 10 * d),
            case("viscous, drag x(-10)", "viscous", cda=lambda d: -10 * d),
            case("viscous, seed's flat-plate alpha_unsteady in the drag", "viscous", sm=flat_plate_drag),
            case("viscous, Cl_alpha = 2 pi (drag only)", "viscous", cla=uniform(2 * np.pi)),
            case("viscous + apparent-mass scaling Cl_alpha/2pi", "viscous", ams=True)]
    for c in (5.0, 5.5, 6.0, 7.0):
        rows.append(case(f"viscous, Cl_alpha = {c} everywhere", "viscous", cla=uniform(c)))
    rows.append(case("viscous, Cl_alpha = 5.0 everywhere + am scaling", "viscous", ams=True, cla=uniform(5.0)))
    rows.append(case("viscous, Cl_alpha fitted -15 deg .. Cl_max", "viscous", cla=stall_fit("m15")))
    rows.append(case("viscous, Cl_alpha fitted alpha_0 .. Cl_max", "viscous", cla=stall_fit("alpha0")))
    rows.append(case("viscous, Cl_alpha fitted -15 deg .. Cl_max + am scaling", "viscous", ams=True,
                     cla=stall_fit("m15")))
    rows.append(case("viscous + a.c. from Cm_alpha", "viscous", ac=True))
    rows.append(case("viscous + a.c. from Cm_alpha + am scaling", "viscous", ams=True, ac=True))
    rows.append(case("potential + a.c. from Cm_alpha (not a model: isolates the a.c.)", ac=True))
    with (outdir / "candidates.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["| candidate (NREL 5 MW, rotor alone, beam, p-k, full physics, %g m/s) | tip Cl_alpha (1/rad) | flutter (RPM) | f (Hz) | divergence (RPM) |" % wind,
             "|---|---|---|---|---|"]
    lines += [f"| {r['candidate']} | {r['tip_cl_alpha']} | {r['flutter_rpm'] or '-'} | {r['flutter_hz'] or '-'} | "
              f"{r['divergence_rpm'] or '-'} |" for r in rows]
    (outdir / "candidates.md").write_text("\n".join(lines) + "\n")
    return rows


def damping_check(outdir: Path, name: str = "iea15mw", wind: float = 10.0) -> list[dict]:
    """The low-speed edgewise "flutter" of the IEA 15 MW: the same point without and with 0.5 %
    modal structural damping (``damping="modal"``), and the least damping ratio of the tracked
    modes over the grid; written to ``outdir/damping_check_<name>_<wind>.md``."""
    import numpy as np

    from windflutter.model.windio import load_turbine
    from windflutter.frozen.turbine import TurbineOptions, TurbineStability

    _tolerate_lost_start_vectors()
    turbine = load_turbine(name)
    lo, hi, step = CASES[name]["rpm"]
    rows = []
    for zeta in (0.0, 0.005):
        opts = TurbineOptions(model="beam", aero="potential", rpm_min=lo, rpm_max=hi, rpm_step=step,
                              mesh={"part": "rotor"}, damping="modal" if zeta else "none", damping_ratio=zeta,
                              reduction=REDUCTION)
        p = TurbineStability(turbine, opts).analyse_operating_point(wind)
        z = np.asarray(p.damping_ratio, float)
        i, j = np.unravel_index(np.nanargmin(z), z.shape)
        rows.append(dict(zeta=zeta, flutter_rpm=p.flutter_rpm, flutter_hz=p.flutter_frequency_hz,
                         mode=p.flutter_mode, divergence_rpm=p.divergence_rpm, min_zeta=float(z[i, j]),
                         at_rpm=float(p.sweep_rpm[i]), at_hz=float(p.damped_frequency_hz[i, j])))
        print(rows[-1], flush=True)
    lines = [f"| {name} {wind:g} m/s, structural damping | flutter (RPM) | f (Hz) | mode | divergence (RPM) | "
             "least damping ratio on the grid (at RPM, Hz) |", "|---|---|---|---|---|---|"]
    fmt = (lambda x, d=2: "-" if x is None else f"{x:.{d}f}")
    for r in rows:
        lines.append(f"| {100 * r['zeta']:.1f} % | {fmt(r['flutter_rpm'])} | {fmt(r['flutter_hz'], 3)} | "
                     f"{r['mode'] or '-'} | {fmt(r['divergence_rpm'])} | {r['min_zeta']:.2e} "
                     f"({r['at_rpm']:.1f}, {r['at_hz']:.2f}) |")
    (outdir / f"damping_check_{name}_{wind:g}.md").write_text("\n".join(lines) + "\n")
    return rows


def fits(outdir: Path, name: str = "nrel5mw") -> str:
    """The polar fits of one turbine beside a central difference of each table at its zero-lift
    angle (+-2 deg); written to ``outdir/fits_<name>.md``."""
    import numpy as np

    from windflutter.aero.polars import fit_polar
    from windflutter.model.windio import load_turbine

    t = load_turbine(name)
    lines = ["| airfoil | fit Cl_alpha (1/rad) | table slope at alpha0 +- 2 deg | range (deg) | Cd_alpha (1/rad) | "
             "Cm_alpha (1/rad) | a.c. (x/c) |", "|---|---|---|---|---|---|---|"]
    h = np.radians(2.0)
    for af in t.airfoils.values():
        p = af.polar
        f = fit_polar(p)
        if f.cl_alpha == 0:
            continue
        fd = (np.interp(f.alpha_zero_lift + h, p.alpha, p.cl) - np.interp(f.alpha_zero_lift - h, p.alpha, p.cl)) / (2 * h)
        lines.append(f"| {af.name} | {f.cl_alpha:.2f} | {fd:.2f} | {np.degrees(f.alpha_min):.1f} ... "
                     f"{np.degrees(f.alpha_max):.1f} | {f.cd_alpha:.3f} | {f.cm_alpha:.2f} | {0.25 + f.ac_shift:.3f} |")
    text = "\n".join(lines) + "\n"
    (outdir / f"fits_{name}.md").write_text(text)
    print(text)
    return text


def divergence_full(outdir: Path, names) -> list[dict]:
    """Static divergence at full order (``reduction="none"``): the first + -> - sign change of
    ``static_min_eig`` (sign(det Kt(k=0)) x least |eigenvalue|) on the case's rotor-speed grid,
    located by Brent.  Cheap (static eigenproblems only) and independent of the modal basis,
    which the p-k maps use; rows in ``outdir/divergence_full.csv``."""
    import numpy as np
    from scipy.optimize import brentq

    from windflutter.model.windio import load_turbine
    from windflutter.frozen.search import static_min_eig
    from windflutter.frozen.turbine import RPM, TurbineOptions, TurbineStability

    rows = []
    for name in names:
        case = CASES[name]
        lo, hi, step = case["rpm"]
        turbine = load_turbine(name)
        for aero, physics in case["variants"]:
            ts = TurbineStability(turbine, TurbineOptions(model="beam", aero=aero, physics=physics, reduction="none",
                                                          rpm_min=lo, rpm_max=hi, rpm_step=step, mesh={"part": "rotor"}))
            for v in case["wind"]:
                fe, sec, am = ts.model(ts.pitch_at(float(v)))

                def g(rpm):
                    return static_min_eig(am.at(float(v), rpm * RPM))

                grid = np.arange(lo, hi + 1e-9, step / 2)
                vals = [g(r) for r in grid]
                div = None
                for i in range(1, len(grid)):
                    if vals[i - 1] > 0 >= vals[i]:
                        div = brentq(g, grid[i - 1], grid[i], xtol=0.01)
                        break
                rows.append(dict(turbine=name, aero=aero, physics=physics, wind_speed=v,
                                 divergence_full_rpm="" if div is None else f"{div:.2f}"))
                print(rows[-1], flush=True)
    with (outdir / "divergence_full.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir")
    ap.add_argument("--turbines", nargs="+", choices=sorted(CASES), default=list(CASES))
    ap.add_argument("--plot-only", action="store_true", help="only redo maps.md and the PNGs from maps.csv")
    ap.add_argument("--candidates", action="store_true",
                    help="only the candidate study (NREL 5 MW, 10 m/s) -> candidates.csv/.md")
    ap.add_argument("--damping-check", nargs=2, metavar=("TURBINE", "V"), default=None,
                    help="only one point (e.g. iea15mw 10) without/with 0.5 %% modal damping -> "
                         "damping_check_TURBINE_V.md")
    ap.add_argument("--fits", metavar="TURBINE", default=None, help="only the polar-fit table -> fits_TURBINE.md")
    ap.add_argument("--divergence-full", action="store_true",
                    help="only the full-order static divergence of --turbines -> divergence_full.csv")
    a = ap.parse_args(argv)
    out = Path(a.outdir)
    out.mkdir(parents=True, exist_ok=True)
    if a.fits:
        fits(out, a.fits)
        return 0
    if a.divergence_full:
        divergence_full(out, a.turbines)
        return 0
    if a.candidates:
        candidates(out)
        return 0
    if a.damping_check:
        damping_check(out, a.damping_check[0], float(a.damping_check[1]))
        return 0
    csv_path = out / "maps.csv"
    if not a.plot_only:
        for name in a.turbines:
            run_case(name, csv_path)
    rows = read_rows(csv_path)
    write_markdown(rows, out / "maps.md")
    plot(rows, out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
