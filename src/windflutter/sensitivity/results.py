"""The sensitivities along the operating curve: the xarray Dataset, the ranked table and the plot.

:func:`sensitivities` analyses each wind speed (the operating-point model's point, its named modes
carried from the previous wind speed as the Campbell diagram does, :func:`point_sensitivities`) and
:func:`as_dataset` gathers them on the dimensions ``mode`` (the modes' identity names) x
``wind_speed`` x ``parameter`` (the blade properties) x ``station`` (the blade's beam elements),
plus ``global_parameter`` for the whole-turbine ones, with units in the attributes.
"""

from __future__ import annotations

import numpy as np

from windflutter.errors import InputError
from windflutter.units import RPM
from windflutter.sensitivity.eigen import frequency_damping
from windflutter.sensitivity.parameters import BLADE_PROPERTIES, change_words, is_relative, unit_change
from windflutter.sensitivity.point import PAIR_LIMIT, PointSensitivity, point_sensitivities
from windflutter.system.campbell import ambiguous
from windflutter.system.modes import point_modes, state_eig
from windflutter.sensitivity.steady import point_totals, segment_totals, steady_base

#: the spanwise segments (r/R) the ranked table sums the stations over
SEGMENTS = (0.0, 0.2, 0.4, 0.6, 0.8, 1.0)


def sensitivities(om, wind_speeds, max_hz: float, modes=None, blade_properties=None, global_parameters=None,
                  progress=None, total: bool = False) -> list[PointSensitivity]:
    """:class:`PointSensitivity` of each wind speed (m/s) of the operating-point model ``om``: its
    modes up to ``max_hz`` (Hz), named and carried along the wind speeds as
    :func:`windflutter.system.campbell.campbell` does; ``modes`` (identity names) keeps only those.
    ``total``: also the whole-blade and global parameters' derivatives with the steady state's own
    change included (:func:`~windflutter.sensitivity.steady.point_totals`) in
    ``PointSensitivity.total``."""

    out, models = [], {}
    for ps, eig, keep in named_points(om, wind_speeds, max_hz, modes, progress):
        res = point_sensitivities(om, ps, keep, blade_properties, global_parameters, models=models, eig=eig)
        if total and keep:
            base = steady_base(om, ps)
            res.total = point_totals(om, ps, res, base)
            res.total_segments = segment_totals(om, ps, res, SEGMENTS, base)
        out.append(res)
    check_found(modes, [r.names for r in out])
    return out


def named_points(om, wind_speeds, max_hz: float, modes=None, progress=None):
    """Yield ``(point system, its eigen-solve with left vectors, kept named modes)`` of each wind speed
    (m/s): the modes up to ``max_hz`` (Hz) named and carried along the wind speeds as
    :func:`windflutter.system.campbell.campbell` does; ``modes`` (identity names) keeps only those."""
    prev = None
    ws = [float(v) for v in np.atleast_1d(wind_speeds)]
    for i, v in enumerate(ws):
        if progress is not None:
            progress(i / len(ws), f"V = {v:g} m/s")
        ps = om.at(v)
        eig = state_eig(ps.mbc)  # one eigen-solve with left vectors for the names and the sensitivities
        named = point_modes(ps, max_hz=max_hz, previous=prev, eig=eig)
        if prev is not None and ambiguous(prev, named):
            mid = point_modes(om.at(0.5 * (ws[i - 1] + v)), max_hz=max_hz, previous=prev)
            named = point_modes(ps, max_hz=max_hz, previous=mid, eig=eig)
        prev = named
        yield ps, eig, (named if modes is None else [m for m in named if m.identity_name in set(modes)])
    if progress is not None:
        progress(1.0, "done")


def check_found(modes, found: list[list[str]]) -> None:
    """InputError naming the first of the asked ``modes`` that no point's named modes ``found`` has."""
    if modes is not None:
        seen = {n for names in found for n in names}
        missing = [n for n in modes if n not in seen]
        if missing:
            raise InputError("modes", missing[0], "a mode name of the point (e.g. '1st edge BW'; "
                             "`windflutter campbell` lists them), below the frequency limit")


def _unit(name: str) -> float:
    return unit_change(name)


def mode_names(points) -> list[str]:
    """The identity names of the points' modes, each once, in the order they first appear."""
    names: list[str] = []
    for p in points:
        names += [n for n in p.names if n not in names]
    return names


def modal_dataset(points, names: list[str], turbine: str, method: str, held_fixed: str):
    """The :class:`xarray.Dataset` both sensitivity datasets start from: each named mode's
    ``frequency`` and ``damping_ratio`` at each point (mode x wind_speed), the ``mode``,
    ``wind_speed`` and ``rotor_speed`` coordinates, and the title, method and what is held."""
    import xarray as xr

    f, z = np.full((len(names), len(points)), np.nan), np.full((len(names), len(points)), np.nan)
    for j, p in enumerate(points):
        for m in p.modes:
            i = names.index(m.identity_name)
            f[i, j], z[i, j] = m.frequency_hz, m.damping_ratio
    return xr.Dataset(
        {"frequency": (("mode", "wind_speed"), f, {"units": "Hz", "long_name": "undamped natural frequency"}),
         "damping_ratio": (("mode", "wind_speed"), z, {"units": "1", "long_name": "damping ratio"})},
        coords={"mode": names, "wind_speed": ("wind_speed", [p.wind_speed for p in points], {"units": "m/s"}),
                "rotor_speed": ("wind_speed", [p.omega / RPM for p in points], {"units": "rpm"})},
        attrs={"title": f"windflutter design sensitivities {turbine}".strip(), "method": method,
               "held_fixed": held_fixed})


def finish_dataset(ds, assumptions: dict | None):
    """``ds`` with ``defined`` (the pair ratio below :data:`PAIR_LIMIT`) and the model's assumptions
    as ``model_*`` attributes."""
    ds["defined"] = ds["pair_ratio"] < PAIR_LIMIT
    ds["defined"].attrs["long_name"] = "the first-order derivative is defined (not at a veering or crossing)"
    for k, v in (assumptions or {}).items():
        ds.attrs[f"model_{k}"] = str(v)
    return ds


def as_dataset(points: list[PointSensitivity], turbine: str = "", assumptions: dict | None = None):
    """The :class:`xarray.Dataset` of the sensitivities (module docstring)."""
    names = mode_names(points)
    props = list(points[0].blade) if points else []
    globs = list(points[0].globals_) if points else []
    nm, nw, ne = len(names), len(points), len(points[0].station) if points else 0
    shape = (nm, nw)
    df_b, dz_b = np.full(shape + (len(props), ne), np.nan), np.full(shape + (len(props), ne), np.nan)
    df_g, dz_g = np.full(shape + (len(globs),), np.nan), np.full(shape + (len(globs),), np.nan)
    allp = props + globs
    ratio = np.full(shape + (len(allp),), np.nan)
    df_t, dz_t = np.full(shape + (len(allp),), np.nan), np.full(shape + (len(allp),), np.nan)
    for j, p in enumerate(points):
        for k, m in enumerate(p.modes):
            i = names.index(m.identity_name)
            lam = complex(m.eigenvalue)
            for a, name in enumerate(props):
                df_b[i, j, a], dz_b[i, j, a] = frequency_damping(lam, p.blade[name][k])
            for a, name in enumerate(globs):
                df_g[i, j, a], dz_g[i, j, a] = frequency_damping(lam, p.globals_[name][k])
            for a, name in enumerate(allp):
                ratio[i, j, a] = p.pair_ratio[name][k]
                if name in p.total:
                    df_t[i, j, a], dz_t[i, j, a] = frequency_damping(lam, p.total[name][k])
    per = "per unit of the parameter (relative ones: per +100 %, i.e. 100 x the change for +1 %; offsets: per m)"
    dims_b, dims_g = ("mode", "wind_speed", "parameter", "station"), ("mode", "wind_speed", "global_parameter")
    ds = modal_dataset(points, names, turbine, "first-order eigenvalue perturbation of the operating point's "
                       "linear system (left and right eigenvectors); element matrices and assembled global "
                       "matrices differentiated by central differences",
                       "the steady state (deflected shape, its stress, inflow, strip linearization) and the "
                       "blade's reduction basis")
    ds = ds.assign(
        {"dfrequency": (dims_b, df_b, {"units": "Hz", "long_name": "d frequency / d parameter of each blade "
                                       "element (the three blades alike) " + per}),
         "ddamping": (dims_b, dz_b, {"units": "1", "long_name": "d damping ratio / d parameter of each blade "
                                     "element (the three blades alike) " + per}),
         "dfrequency_global": (dims_g, df_g, {"units": "Hz", "long_name": "d frequency / d parameter " + per}),
         "ddamping_global": (dims_g, dz_g, {"units": "1", "long_name": "d damping ratio / d parameter " + per}),
         "pair_ratio": (("mode", "wind_speed", "any_parameter"), ratio, {
             "units": "1", "long_name": "coupling of the mode to its nearest eigenvalue by the unit change of the "
             "parameter over the whole blade, over half their distance; >= " f"{PAIR_LIMIT:g}" ": the derivative is "
             "not defined (a veering or crossing)"})})
    ds = ds.assign_coords(
        {"parameter": props, "global_parameter": globs, "any_parameter": allp,
         "station": ("station", points[0].station if points else [], {
             "units": "1", "long_name": "blade element mid-point radius over the tip radius (r/R)"}),
         "global_parameter_unit": ("global_parameter", ["1" if is_relative(n) else "m" for n in globs], {
             "long_name": "unit of the parameter: 1 relative (d/d ln p), m an offset along the chord "
                          "(towards the trailing edge)"}),
         "parameter_unit": ("parameter", [BLADE_PROPERTIES[n].unit for n in props], {
             "long_name": "unit of the parameter: 1 relative (d/d ln p), m an offset along the chord "
                          "(towards the trailing edge)"})})
    if any(p.total for p in points):
        ds["dfrequency_total"] = (("mode", "wind_speed", "any_parameter"), df_t, {
            "units": "Hz", "long_name": "d frequency / d parameter with the steady state's own change included "
            "(its sensitivity; blade properties over the whole blade; blade basis held) " + per})
        ds["ddamping_total"] = (("mode", "wind_speed", "any_parameter"), dz_t, {
            "units": "1", "long_name": "d damping ratio / d parameter with the steady state's own change "
            "included (its sensitivity; blade properties over the whole blade; blade basis held) " + per})
    if any(p.total_segments for p in points):
        _segment_totals(ds, points, names, props)
    return finish_dataset(ds, assumptions)


def _segment_totals(ds, points, names, props, segments=SEGMENTS) -> None:
    """``dfrequency_total_segment``, ``ddamping_total_segment`` (mode x wind_speed x parameter x
    segment) into ``ds``: the blade properties over each spanwise segment, steady state included."""
    ns = len(segments) - 1
    df, dz = np.full((len(names), len(points), len(props), ns), np.nan), np.full((len(names), len(points),
                                                                               len(props), ns), np.nan)
    for j, p in enumerate(points):
        for k, m in enumerate(p.modes):
            i = names.index(m.identity_name)
            for a, name in enumerate(props):
                if name in p.total_segments:
                    df[i, j, a], dz[i, j, a] = frequency_damping(complex(m.eigenvalue), p.total_segments[name][k])
    per = "per unit of the parameter over the segment (relative ones: per +100 %; offsets: per m)"
    dims = ("mode", "wind_speed", "parameter", "segment")
    ds.coords["segment"] = [f"{a:.1f}-{b:.1f}" for a, b in zip(segments[:-1], segments[1:])]
    ds.coords["segment_start"] = ("segment", list(segments[:-1]), {"units": "1", "long_name": "r/R"})
    ds.coords["segment_end"] = ("segment", list(segments[1:]), {"units": "1", "long_name": "r/R"})
    ds["dfrequency_total_segment"] = (dims, df, {"units": "Hz", "long_name": "d frequency / d parameter of the "
                                                 "blade elements of the segment, with the steady state's own change "
                                                 "included (blade basis held) " + per})
    ds["ddamping_total_segment"] = (dims, dz, {"units": "1", "long_name": "d damping ratio / d parameter of the "
                                               "blade elements of the segment, with the steady state's own change "
                                               "included (blade basis held) " + per})


def segment_table(ds, segments=SEGMENTS, modes=None, least: int = 3) -> list[dict]:
    """Rows ``{mode, wind_speed, parameter, segment, change, dzeta_points, dfreq_hz, defined}``: the
    unit change (+1 %, +1 cm) of each property over each spanwise segment and of each global
    parameter, and the damping ratio's change in percentage points; largest first.  ``modes``: the
    mode names to tabulate (default: the ``least`` least damped modes of each wind speed)."""
    rows = []
    st = np.asarray(ds["station"].values, float)
    for j, v in enumerate(ds["wind_speed"].values):
        for mode in chosen_modes(ds, j, modes, least):
            if not np.isfinite(ds["damping_ratio"].sel(mode=mode).values[j]):
                continue
            for p in ds["parameter"].values:
                u = _unit(str(p))
                dz = ds["ddamping"].sel(mode=mode, parameter=p).values[j]
                dfq = ds["dfrequency"].sel(mode=mode, parameter=p).values[j]
                ok = bool(ds["defined"].sel(mode=mode, any_parameter=p).values[j])
                for a, b in zip(segments[:-1], segments[1:]):
                    sel = (st >= a) & (st < b) if b < segments[-1] else (st >= a)
                    if sel.any():
                        rows.append({"mode": str(mode), "wind_speed": float(v), "parameter": str(p),
                                     "segment": (a, b), "change": u, "dzeta_points": 100 * u * float(dz[sel].sum()),
                                     "dfreq_hz": u * float(dfq[sel].sum()), "defined": ok})
            for p in ds["global_parameter"].values:
                sel = {"mode": mode, "global_parameter": p}
                rows.append({"mode": str(mode), "wind_speed": float(v), "parameter": str(p), "segment": None,
                             "change": _unit(str(p)),
                             "dzeta_points": 100 * _unit(str(p)) * float(ds["ddamping_global"].sel(**sel).values[j]),
                             "dfreq_hz": _unit(str(p)) * float(ds["dfrequency_global"].sel(**sel).values[j]),
                             "defined": bool(ds["defined"].sel(mode=mode, any_parameter=p).values[j])})
    rows.sort(key=lambda r: -abs(r["dzeta_points"]))
    return rows


def chosen_modes(ds, j: int, modes, least: int) -> list[str]:
    """The mode names a table covers at the ``j``-th wind speed: ``modes``, or the ``least`` least damped."""
    if modes is not None:
        return [str(m) for m in modes]
    z = ds["damping_ratio"].values[:, j]
    order = [i for i in np.argsort(np.where(np.isfinite(z), z, np.inf)) if np.isfinite(z[i])]
    return [str(ds["mode"].values[i]) for i in order[:least]]


def total_table(ds, modes=None, least: int = 3) -> list[str]:
    """Sentences of the total derivatives (``ddamping_total``, ``ddamping_total_segment``, when the
    dataset has them): the unit change of each parameter (blade properties over the whole blade and
    over each r/R segment) with the steady state's own change included, beside the derivative with it
    held; largest first."""
    if "ddamping_total" not in ds and "ddamping_total_segment" not in ds:
        return []
    rows = []
    whole = ds["any_parameter"].values if "ddamping_total" in ds else []
    for j, v in enumerate(ds["wind_speed"].values):
        for mode in chosen_modes(ds, j, modes, least):
            for p in whole:
                p = str(p)
                u = _unit(p)
                tot = 100 * u * float(ds["ddamping_total"].sel(mode=mode, any_parameter=p).values[j])
                if p in BLADE_PROPERTIES:
                    held = float(ds["ddamping"].sel(mode=mode, parameter=p).values[j].sum())
                    words = change_words(p) + " (whole blade)"
                else:
                    held = float(ds["ddamping_global"].sel(mode=mode, global_parameter=p).values[j])
                    words = change_words(p)
                if np.isfinite(tot):
                    rows.append((abs(tot), f"{words} {'raises' if tot >= 0 else 'lowers'} the {mode} damping at "
                                           f"{v:g} m/s by {abs(tot):.3g} points ({100 * u * held:+.3g} with the "
                                           "steady state held)"))
            rows += _segment_rows(ds, j, mode, v)
    return [r[1] for r in sorted(rows, key=lambda r: -r[0])]


def _segment_rows(ds, j: int, mode: str, v: float) -> list[tuple]:
    """``(|change|, sentence)`` of the segment totals (``ddamping_total_segment``) of a mode at the
    ``j``-th wind speed ``v``: the unit change over each segment, beside the held segment sum."""
    if "ddamping_total_segment" not in ds:
        return []
    st = np.asarray(ds["station"].values, float)
    rows = []
    for p in ds["parameter"].values:
        p = str(p)
        u = _unit(p)
        held_el = ds["ddamping"].sel(mode=mode, parameter=p).values[j]
        for g, a, b in zip(ds["segment"].values, ds["segment_start"].values, ds["segment_end"].values):
            tot = 100 * u * float(ds["ddamping_total_segment"].sel(mode=mode, parameter=p, segment=g).values[j])
            sel = (st >= a) & (st < b) if b < ds["segment_end"].values[-1] else (st >= a)
            held = 100 * u * float(held_el[sel].sum())
            if np.isfinite(tot):
                rows.append((abs(tot), f"{change_words(p)} at r/R {a:.1f}-{b:.1f} {'raises' if tot >= 0 else 'lowers'} "
                                       f"the {mode} damping at {v:g} m/s by {abs(tot):.3g} points ({held:+.3g} with "
                                       "the steady state held)"))
    return rows


def sentence(row: dict) -> str:
    """``"+1 % edge stiffness at r/R 0.2-0.4 raises the 1st edge BW damping at 15 m/s by 0.012 points"``."""
    p = row["parameter"]
    if p in BLADE_PROPERTIES:
        what = change_words(p)
        a, b = row["segment"]
        what += f" at r/R {a:.1f}-{b:.1f}"
    else:
        what = change_words(p)
    x = row["dzeta_points"]
    verb = "raises" if x >= 0 else "lowers"
    tail = "" if row["defined"] else " (not defined: near a veering or crossing)"
    return (f"{what} {verb} the {row['mode']} damping at {row['wind_speed']:g} m/s by {abs(x):.3g} points "
            f"(frequency {row['dfreq_hz']:+.3g} Hz){tail}")


def spanwise_figure(ds, mode: str | None = None, wind_speed: float | None = None):
    """The spanwise sensitivity of a mode's damping (default: the least damped mode at the wind speed
    where it is least damped) to each blade property: the damping change (percentage points) for the
    unit change (+1 %, +1 cm) of the property over 0.1 of r/R, against r/R."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    z = ds["damping_ratio"]
    if mode is None or wind_speed is None:
        flat = np.nanargmin(z.values)
        i, j = np.unravel_index(flat, z.shape)
        mode = mode or str(ds["mode"].values[i])
        wind_speed = float(ds["wind_speed"].values[j]) if wind_speed is None else wind_speed
    st = np.asarray(ds["station"].values, float)
    edges = np.concatenate([[max(0.0, st[0] - 0.5 * (st[1] - st[0]))], 0.5 * (st[1:] + st[:-1]),
                            [st[-1] + 0.5 * (st[-1] - st[-2])]]) if st.size > 1 else np.array([0.0, 1.0])
    width = np.diff(edges)
    props = [str(p) for p in ds["parameter"].values]
    ncol = 2
    nrow = int(np.ceil(len(props) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(9, 2.2 * nrow), sharex=True, squeeze=False)
    for ax, p in zip(axes.ravel(), props):
        dz = ds["ddamping"].sel(mode=mode, parameter=p, wind_speed=wind_speed).values
        y = 100 * _unit(p) * dz / width * 0.1
        ax.step(st, y, where="mid")
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.set_title(change_words(p), fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes.ravel()[len(props):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("r/R")
    for ax in axes[:, 0]:
        ax.set_ylabel("damping change\n(points per 0.1 r/R)", fontsize=8)
    fig.suptitle(f"{ds.attrs.get('title', '')}: {mode} at {wind_speed:g} m/s", fontsize=10)
    fig.tight_layout()
    return fig
