"""The design sensitivities of shell blades along the operating curve: the ply thickness of each
layup region, as an xarray Dataset and a ranked table (``windflutter sensitivity --model shell``).

A *region* is a group of the layup's layers (:data:`REGIONS`: the spar caps, the trailing- and
leading-edge reinforcements, the shell panels' core, the skins, the webs), found by the layers'
names; the parameter is relative (every thickness of the region's layers times ``1 + p``).  Each
wind speed's modes are named and carried as the beam path's (:func:`~windflutter.sensitivity.
results.named_points`), and their derivatives are :func:`~windflutter.sensitivity.shell.
layer_derivatives`: the steady state and the blade basis held.  The veering flag is the beam
path's (:data:`~windflutter.sensitivity.point.PAIR_LIMIT`), for the unit change (+1 %).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.errors import InputError
from windflutter.sensitivity.eigen import frequency_damping, mode_vectors, pair_ratio, pair_vectors
from windflutter.sensitivity.parameters import UNIT_RELATIVE
from windflutter.sensitivity.point import PAIR_LIMIT
from windflutter.sensitivity.results import (check_found, chosen_modes, finish_dataset, modal_dataset, mode_names,
                                             named_points)
from windflutter.sensitivity.shell import layer_derivatives, layer_names, layer_thickness_check

#: the default regions: ``(name, test of a lower-case layer name)``, in this order; a layer goes to
#: the first region whose test it passes, and layers of no region (e.g. a UV coating) are left out
REGIONS = (
    ("spar caps", lambda n: "spar" in n and "cap" in n),
    ("TE reinforcement", lambda n: n.startswith("te_reinf") or "te_reinforcement" in n),
    ("LE reinforcement", lambda n: n.startswith("le_reinf") or "le_reinforcement" in n),
    ("webs", lambda n: n.startswith("web")),
    ("shell panels", lambda n: "filler" in n or "panel" in n or "core" in n),
    ("shell skin", lambda n: "skin" in n),
)


def default_regions(turbine) -> dict[str, tuple[str, ...]]:
    """``{region: layer names}`` of the turbine's layup grouped by :data:`REGIONS` (the empty ones
    left out)."""
    out: dict[str, list[str]] = {}
    for lay in layer_names(turbine):
        low = lay.lower()
        region = next((name for name, test in REGIONS if test(low)), None)
        if region is not None:
            out.setdefault(region, []).append(lay)
    if not out:
        raise InputError("blade.layup", layer_names(turbine) or None, "layers named like the regions (spar caps, "
                         "TE/LE reinforcement, webs, panels' filler, skin): pass regions={name: layers}")
    return {name: tuple(out[name]) for name, _ in REGIONS if name in out}


def chosen_regions(turbine, regions=None) -> dict[str, tuple[str, ...]]:
    """``regions`` as ``{name: layer names}``: a dict (layer names checked), names of the
    :func:`default_regions` (a list), or None (all the default regions)."""
    if isinstance(regions, dict):
        out = {str(k): (v,) if isinstance(v, str) else tuple(v) for k, v in regions.items()}
        for name, layers in out.items():
            layer_thickness_check(turbine, layers)
        return out
    found = default_regions(turbine)
    if regions is None:
        return found
    names = [regions] if isinstance(regions, str) else list(regions)
    bad = [n for n in names if n not in found]
    if bad or not names:
        raise InputError("regions", bad[0] if bad else names, f"layup regions of the blade: {', '.join(found)} "
                         "(or a dict {name: layer names})")
    return {n: found[n] for n in names}


@dataclass
class ShellPointSensitivity:
    """The named modes of one point and ``region[name]`` (k,) complex ``dlambda/dp`` (1/s per unit of
    the relative thickness ``p``); ``pair_ratio[name]`` (k,) the veering measure of the +1 % change."""

    wind_speed: float
    omega: float
    modes: list
    region: dict = field(default_factory=dict)
    pair_ratio: dict = field(default_factory=dict)

    @property
    def names(self) -> list[str]:
        return [m.identity_name for m in self.modes]


def shell_sensitivities(om, wind_speeds, max_hz: float, modes=None, regions=None,
                        progress=None) -> list[ShellPointSensitivity]:
    """:class:`ShellPointSensitivity` of each wind speed (m/s) of the shell operating-point model
    ``om``; ``regions`` ``{name: layer names}`` (default :func:`default_regions`)."""
    regions = chosen_regions(om.turbine, regions)
    out = []
    for ps, eig, keep in named_points(om, wind_speeds, max_hz, modes, progress):
        res = ShellPointSensitivity(wind_speed=ps.wind_speed, omega=ps.omega, modes=list(keep))
        if keep:
            mvs = mode_vectors(ps.mbc, [m.eigenvalue for m in keep], eig=eig)
            pairs = [pair_vectors(mv) for mv in mvs]
            k = len(mvs)
            found = layer_derivatives(om, ps, mvs + [p[0] for p in pairs] + [p[1] for p in pairs], regions)
            for name, v in found.items():
                res.region[name] = v[:k]
                res.pair_ratio[name] = np.array([pair_ratio(mv, v[k + i], v[2 * k + i], UNIT_RELATIVE)
                                                 for i, mv in enumerate(mvs)])
        out.append(res)
    check_found(modes, [r.names for r in out])
    return out


def shell_dataset(points: list[ShellPointSensitivity], regions: dict, turbine: str = "",
                  assumptions: dict | None = None):
    """The :class:`xarray.Dataset` (``mode`` x ``wind_speed`` x ``region``) of the sensitivities."""
    names = mode_names(points)
    regs = list(regions)
    shape = (len(names), len(points))
    df, dz, ratio = (np.full(shape + (len(regs),), np.nan) for _ in range(3))
    for j, p in enumerate(points):
        for k, m in enumerate(p.modes):
            i = names.index(m.identity_name)
            for a, r in enumerate(regs):
                df[i, j, a], dz[i, j, a] = frequency_damping(complex(m.eigenvalue), p.region[r][k])
                ratio[i, j, a] = p.pair_ratio[r][k]
    per = "per unit of the region's relative ply thickness (per +100 %, i.e. 100 x the change for +1 %)"
    dims = ("mode", "wind_speed", "region")
    ds = modal_dataset(points, names, turbine, "first-order eigenvalue perturbation of the operating point's "
                       "linear system (left and right eigenvectors); the point reassembled with the region's "
                       "layers at +-1 % thickness (the blade meshed again, its laminates on the nominal elements), "
                       "central differences",
                       "the steady state (deflected shape, its stress, inflow, strip linearization), the blade's "
                       "reduction basis and the shell's reference surface")
    ds = ds.assign(
        {"dfrequency_region": (dims, df, {"units": "Hz", "long_name": "d frequency / d thickness " + per}),
         "ddamping_region": (dims, dz, {"units": "1", "long_name": "d damping ratio / d thickness " + per}),
         "pair_ratio": (dims, ratio, {"units": "1", "long_name": "coupling of the mode to its nearest eigenvalue by "
                                      "+1 % of the region's thickness, over half their distance; >= "
                                      f"{PAIR_LIMIT:g}: the derivative is not defined (a veering or crossing)"})})
    ds = ds.assign_coords(
        {"region": regs,
         "region_layers": ("region", [", ".join(regions[r]) for r in regs],
                           {"long_name": "the layup layers of the region (all their thicknesses scaled)"}),
         "region_unit": ("region", ["1"] * len(regs), {"long_name": "unit of the parameter: 1 relative (d/d ln t)"})})
    return finish_dataset(ds, assumptions)


def shell_table(ds, modes=None, least: int = 3) -> list[str]:
    """Sentences ``"+1 % ply thickness of the spar caps (Spar_Cap_SS, Spar_Cap_PS) raises the 1st edge
    BW damping at 10 m/s by 0.012 points (frequency +0.003 Hz)"``, largest first; ``modes`` the mode
    names (default: the ``least`` least damped at each wind speed)."""
    rows = []
    for j, v in enumerate(ds["wind_speed"].values):
        for mode in chosen_modes(ds, j, modes, least):
            for r, layers in zip(ds["region"].values, ds["region_layers"].values):
                sel = {"mode": mode, "region": r}
                x = 100 * UNIT_RELATIVE * float(ds["ddamping_region"].sel(**sel).values[j])
                fq = UNIT_RELATIVE * float(ds["dfrequency_region"].sel(**sel).values[j])
                if not np.isfinite(x):
                    continue
                tail = "" if bool(ds["defined"].sel(**sel).values[j]) else " (not defined: near a veering or crossing)"
                rows.append((abs(x), f"+1 % ply thickness of the {r} ({layers}) {'raises' if x >= 0 else 'lowers'} "
                                     f"the {mode} damping at {v:g} m/s by {abs(x):.3g} points "
                                     f"(frequency {fq:+.3g} Hz){tail}"))
    return [r[1] for r in sorted(rows, key=lambda r: -r[0])]
