"""The edge mode on a blade whose STRUCTURE is built on its deflected shape (docs/notes/edgewise_damping.md sec. 5).

The operating-point model linearizes about the deflected steady state by updating the strips
(geometry, induction) and the axial-force geometric stiffness; the beam itself stays on the
undeformed reference axis, so the edge-torsion coupling that a flapwise-deflected blade has
(Kallesoe 2011, Wind Energy 14:209) is absent.  This script bounds that effect:

* the steady state of the default model gives the flapwise deflection of every strip;
* a copy of the turbine gets ``f`` times it built into its blade reference axis (x), and is
  linearized *undeformed* (``deflection=False``: its own centrifugal prestress, no bending
  stress), so ``f = 1`` is a stress-free blade manufactured in the deflected shape (the
  curved-beam coupling only, without the initial-stress terms of the bending moments, which
  cancel part of it);
* the strips keep the default model's deflected geometry and induction (``HybridModel``), so the
  aerodynamics are the same for every ``f``; ``f = 0`` reproduces the default model.

Run: ``PYTHONPATH=src:docs/scripts python docs/scripts/edgewise_geometry.py [V ...]`` (~20 s a
wind speed).  It reads the HAWCStab2 Campbell data from /work/shared (not a test).
"""

from __future__ import annotations

import dataclasses
import sys

import numpy as np

from edgewise_audit import build, rotating_modes
from windflutter.model import load_turbine
from windflutter.system.modes import point_modes
from windflutter.system.operational import OperationalModel, OperationalOptions

HS2 = "/work/shared/data/iea15mw/hawcstab2_campbell/"
FACTORS = (0.0, 0.5, 1.0)


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def chord_angle(p, sec) -> np.ndarray:
    """Chord angle from the rotor plane (rad, + towards feather) of strips ``sec`` (blade 0)."""
    om = p.model
    n = _unit(np.asarray(om.rotor.shaft_axis, float))
    r = np.asarray(sec.origin, float) - np.asarray(om.rotor.hub_center, float)
    t = _unit(np.cross(n, r))
    s = _unit(np.asarray(sec.e_span, float))
    x = _unit(-t + np.sum(t * s, 1, keepdims=True) * s)
    y = _unit(np.cross(s, x))
    y = np.where((y @ n < 0)[:, None], -y, y)
    ch = np.asarray(sec.e_chord, float)
    return np.arctan2(np.sum(ch * y, 1), np.sum(ch * x, 1))


def built_in_deflection(p, f: float):
    """A copy of ``p``'s turbine with ``f`` x the strips' steady flapwise deflection built into the
    blade reference axis (x, by fraction of span).  The elastic twist is added to the blade's
    (aerodynamic) twist too; the beam's section axes keep theirs (``blade.beam.twist``), and the
    strips are replaced by the default model's in :func:`experiment`, so only the flapwise shape
    reaches the linearization (building the twist into the section axes as well moves the cyclic
    edge sigma by +0.6 % and the collective by +16 % at 10 m/s, docs/notes/edgewise_damping.md)."""
    frame = p.st.frames[0]
    o0, o1 = p.rb.sections.origin, p.st.sections.origin
    flap = ((o1 - o0) @ frame)[:, 0]
    z = ((o0 - p.model.rotor.hub_center) @ frame)[:, 2]
    twist = chord_angle(p, p.st.sections) - chord_angle(p, p.rb.sections)
    tb = p.model.turbine
    b = tb.blade
    zr = b.ref_axis[:, 2]
    fs = (z - z.min()) / (z.max() - z.min())
    fr = (zr - zr.min()) / (zr.max() - zr.min())
    ax = b.ref_axis.copy()
    ax[:, 0] += f * np.interp(fr, fs, flap, left=0.0)
    blade = dataclasses.replace(b, ref_axis=ax, twist=b.twist + f * np.interp(fr, fs, twist, left=0.0))
    return dataclasses.replace(tb, blade=blade)


class HybridModel(OperationalModel):
    """The structure of ``turbine``, the strips' geometry and induction of ``aero_state``."""

    def __init__(self, turbine, options, aero_state):
        super().__init__(turbine, options)
        self._aero_state = aero_state

    def steady(self, rb, wind_speed, omega):
        st = super().steady(rb, wind_speed, omega)
        a = self._aero_state.sections
        sec = dataclasses.replace(st.sections, origin=a.origin, e_chord=a.e_chord, e_span=a.e_span, radius=a.radius)
        return dataclasses.replace(st, sections=sec, bem=self._aero_state.bem)


def hawcstab2(V: float) -> dict:
    """HAWCStab2 BW / FW / collective 1st edge: (Hz, zeta, sigma 1/s, flap, torsion amplitude)."""
    c = np.loadtxt(HS2 + "aeroelastic_entire_turbine.cmb", comments="#")
    a = np.loadtxt(HS2 + "aeroelastic_entire_turbine.amp", comments="#")
    i = int(np.argmin(abs(c[:, 0] - V)))
    j = int(np.argmin(abs(a[:, 0] - V)))
    f, z, amp = c[i, 1:61], c[i, 61:121] / 100, a[j, 1:].reshape(60, 15, 2)[:, :, 0]
    out = {}
    for key, col in (("BW", 7), ("FW", 8), ("collective", 6)):
        cand = [m for m in range(60) if 0.4 < f[m] < 1.6 and np.argmax(amp[m, 6:15]) + 6 == col]
        m = min(cand, key=lambda m: f[m])
        out[key] = (f[m], z[m], z[m] * 2 * np.pi * f[m], amp[m, col + 3], amp[m, col + 6])
    return out


def edge_modes(om, V, pitch=None) -> dict:
    out = {}
    ps = om.at(V) if pitch is None else om.at(V, rpm=om.operating_point(V)[0] * 30 / np.pi, pitch=pitch)
    for m in point_modes(ps, max_hz=1.7):
        if m.family == "edge" and m.order == 1:
            out[m.whirl] = (m.frequency_hz, m.damping_ratio, -m.eigenvalue.real)
    return out


def experiment(V: float, factors=FACTORS, pitch: float | None = None, turbine: bool = True) -> dict:
    """Per ``f``: rotor (fixed nacelle) rotating-frame cyclic and collective edge, and the
    whole-turbine BW / FW / collective edge (``turbine``); ``pitch`` (rad) replaces the
    operating curve's."""
    p0 = build(V, pitch=pitch)
    res = {}
    for f in factors:
        tb = built_in_deflection(p0, f)
        p = build(V, turbine=tb, deflection=False, aero_state=p0.st, pitch=pitch)
        modes = [m for m in rotating_modes(p) if abs(m[0]) > 2 * np.pi * 0.3]
        cyc = modes[0][0]
        col = [lam for lam, _ in modes if 1.2 < abs(lam) / 2 / np.pi < 1.7 and -lam.real < 0.1 * abs(lam)][0]
        res[f] = {"rotor cyclic": cyc, "rotor collective": col, "steady": (p.st.power, p.st.thrust)}
        if turbine:
            om = HybridModel(tb, OperationalOptions(part="turbine", mesh={"n_span": 20}, deflection=False), p0.st)
            res[f]["turbine"] = edge_modes(om, V, pitch)
    return res


def main(speeds):
    print("| V (m/s) | model | rotor: cyclic Hz / sigma | rotor: collective Hz / sigma | turbine BW Hz / zeta % | "
          "turbine FW Hz / zeta % | turbine collective Hz / zeta % | mean BW, FW sigma |")
    print("|---|---|---|---|---|---|---|---|")
    for V in speeds:
        h = hawcstab2(V)
        print(f"| {V:g} | HAWCStab2 | | | {h['BW'][0]:.3f} / {100 * h['BW'][1]:.2f} | {h['FW'][0]:.3f} / "
              f"{100 * h['FW'][1]:.2f} | {h['collective'][0]:.3f} / {100 * h['collective'][1]:.2f} | "
              f"{(h['BW'][2] + h['FW'][2]) / 2:.4f} |")
        for f, r in experiment(V).items():
            c, k, t = r["rotor cyclic"], r["rotor collective"], r["turbine"]
            cells = [f"{t[w][0]:.3f} / {100 * t[w][1]:.2f}" for w in ("BW", "FW", "collective")]
            print(f"| | f = {f:g} | {abs(c) / 2 / np.pi:.3f} / {-c.real:.4f} | {abs(k) / 2 / np.pi:.3f} / "
                  f"{-k.real:.4f} | " + " | ".join(cells) + f" | {(t['BW'][2] + t['FW'][2]) / 2:.4f} |")


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or [5.0, 10.0])
