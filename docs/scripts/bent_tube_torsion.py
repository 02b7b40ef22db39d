"""Issue 33: lateral-torsional buckling of a bent elliptical tube, the beam's and the shell's
linearizations about the bent state against closed forms (docs/notes/shell_same_blade.md
section 3, "The bent tube").

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/bent_tube_torsion.py   (about 20 s)

A straight isotropic elliptical tube (chord 2 m, t/c 0.25, L 20 m; the synthetic blade of
tests/mesh/synthetic.py, clamped at the hub, no rotation, no aerodynamics) under a dead tip load
``P`` in its STIFF (chordwise) direction, applied to the tip strip as the blades' loads are.  Its
flapwise (weak) bending and twist couple: lateral-torsional buckling.  For each model and each
linearization, the buckling load is the smallest ``P`` at which the linearized stiffness ceases to
be positive definite (the lowest ``omega^2`` of ``K(P)`` against the mass crosses zero: a coarse
scan in P, then bisection):

* ``classical``: the undeformed structure with the initial stress of the linear static state under
  ``P`` (beam: the co-rotational tangent's ``K_geo`` of the linear resultants at the reference
  configuration; shell: the blade's complete initial-stress matrix, ``RotorBlade.prestress``).
  Reference: Timoshenko & Gere, Theory of Elastic Stability (1961), sec. 6.3, cantilever with a
  load at the centroid of the end section, ``P_cr = 4.013 sqrt(EI_minor GJ) / L^2`` (no warping:
  a closed section), with prebuckling deflections neglected.
* ``deflected``: the linearization about the bent state as the code does it for blades (beam:
  system/deflected.py, the co-rotational equilibrium and its exact Hessian; shell:
  system/deflected_shell.py, the linear steady displacement carrying the mesh and its stress).
  Reference: the prebuckling-deflection factor ``1/sqrt((1 - EI_minor/EI_major)(1 - GJ/EI_major))``
  (Pettersson 1952; Trahair, Flexural-Torsional Buckling of Structures, 1993, ch. on
  prebuckling deflections; Kirby & Nethercot 1979) -- derived for small prebuckling deflections
  (beams in uniform bending); for the cantilever under a tip load it is an estimate.

The shell is run as meshed (no ribs but the tip's: its flat section distorts) and with a rib at
every ring of nodes (:func:`with_ribs`: the rigid section the closed forms assume).

``L`` in the closed forms is the load's lever arm about the tube's root (from the nodal loads: the
tip strip's load acts half a strip inboard of the tip; 19.5 m), the root rigidly linked to the
clamped hub node.
"""

from __future__ import annotations

import dataclasses
import sys
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from windflutter.errors import ModelError
from windflutter.structure.assembly import assemble
from windflutter.structure.corotational import beam_tangent, linear_resultants, reference_configuration
from windflutter.structure.fem import Diaphragm
from windflutter.structure.modal import symmetric_eigs
from windflutter.system.blade import RotorBlade
from windflutter.system.deflected import deflected_blade
from windflutter.system.deflected_shell import deflected_shell_blade
from windflutter.system.operational import OperationalModel, OperationalOptions

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests" / "mesh"))
from synthetic import synthetic_turbine, tube_beam_props, tube_blade  # noqa: E402

L, CHORD, TC = 20.0, 2.0, 0.25  # m, m, thickness/chord
SHELL_MESH = {"n_span": 20, "n_chord": 24}
HUB_LINK = 1.5  # m: the synthetic turbine's hub radius, a rigid link from the clamped hub node to the root


@dataclass
class Bent:
    """The minimal steady-state-like record the deflected routes read (no rotation, no aero BEM)."""
    u: np.ndarray
    load_aero: np.ndarray
    load: np.ndarray
    f_internal: np.ndarray
    sections: object
    strip_loads: np.ndarray = None
    Ksigma: object = None


def tube(kind: str, wall: float, ribs: bool = False):
    """The clamped tube blade (``kind`` beam or shell) of wall ``wall`` (m), and its section constants
    (GJ, EI_minor, EI_major) from the thin-walled closed forms (tube_beam_props).  ``ribs``: the
    shell with a rib (:func:`with_ribs`) at every interior ring of nodes."""
    props = tube_beam_props(L, CHORD, TC, wall)
    tb = synthetic_turbine(tube_blade(L, CHORD, TC, wall, beam=props))
    mesh = SHELL_MESH if kind == "shell" else {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rb = OperationalModel(tb, OperationalOptions(model=kind, part="rotor", damping="none", mesh=mesh)).blade(0.0)
    if ribs and kind == "shell":
        rb = with_ribs(rb)
    k = props.stiffness[0]
    return rb, (k[3, 3], min(k[4, 4], k[5, 5]), max(k[4, 4], k[5, 5]))


def with_ribs(rb):
    """The shell blade ``rb`` with a rib (:class:`~windflutter.structure.fem.Diaphragm`: the ring
    keeps its shape in its plane, warping free -- the rigid section of beam theory) at every ring of
    skin nodes that is neither clamped nor already tied (the root's links to the hub, the tip rib)."""
    fe = rb.fe
    skin = np.unique(np.asarray(fe.shell_conn))
    t = np.asarray(rb.sections.e_span, float)[-1]
    t = t / np.linalg.norm(t)
    s = np.round((np.asarray(fe.nodes, float)[skin] - np.asarray(fe.nodes, float)[rb.hub_node]) @ t, 6)
    taken = {int(n) for d in (*fe.diaphragms, *fe.rigid_links) for n in (d.independent, *d.dependent)} | set(fe.spc)
    ribs = [Diaphragm(int(r[0]), r[1:], t, name=f"rib at {v:.3f} m") for v in np.unique(s)
            for r in [skin[s == v]] if not taken & set(r.tolist())]
    fe2 = dataclasses.replace(fe, diaphragms=list(fe.diaphragms) + ribs)
    return RotorBlade(fe2, assemble(fe2), rb.sections, rb.apex, rb.axis)


def tip_strips(rb, P: float) -> np.ndarray:
    """(ns, 6) strip loads: a tip force ``P`` (N) in the tube's stiff (chordwise, global y) direction
    on the tip strip."""
    strips = np.zeros((rb.sections.n_sections, 6))
    strips[-1, 1] = P
    return strips


def tip_load(rb, P: float) -> np.ndarray:
    """Nodal loads (n_dof,) of the tip force :func:`tip_strips`."""
    return rb.sections.motion_map.T @ tip_strips(rb, P).reshape(-1)


def lever_arm(rb) -> float:
    """The unit tip load's moment arm (m) about the tube's root: its moment about the clamped hub
    node less the rigid hub link (``HUB_LINK``) between the two."""
    f = tip_load(rb, 1.0).reshape(-1, 6)
    x = np.asarray(rb.fe.nodes, float) - np.asarray(rb.fe.nodes, float)[rb.hub_node]
    return float(np.linalg.norm(np.sum(np.cross(x, f[:, :3]), axis=0) + f[:, 3:].sum(axis=0))) - HUB_LINK


def lowest_w2(rb, K) -> float:
    """Lowest eigenvalue omega^2 (rad^2/s^2) of the clamped blade under stiffness ``K`` (full numbering)."""
    st = rb.struct
    Kq = sp.csc_matrix(st.T.T @ K @ st.T)
    w2, _ = symmetric_eigs(0.5 * (Kq + Kq.T), sp.csc_matrix(st.T.T @ st.M @ st.T), 3, shift=0.0, v0=np.ones(st.nq))
    return float(np.min(w2))


def stiffness(rb, kind: str, route: str, P: float):
    """(blade, linearized stiffness) of ``rb`` under the tip load ``P`` by ``route``."""
    f = tip_load(rb, P)
    Kg, _, u = rb.prestress(f)
    if route == "classical":
        if kind == "beam":
            Kg = beam_tangent(rb.fe, reference_configuration(rb.fe), resultants=linear_resultants(rb.fe, u)).K_geo
        return rb, rb.struct.K + Kg
    bent = Bent(u=u, load_aero=f, load=f, f_internal=rb.struct.K @ u, sections=rb.sections,
                strip_loads=tip_strips(rb, P))
    d = deflected_blade(rb, bent, 0.0) if kind == "beam" else deflected_shell_blade(rb, bent, 0.0)
    return d.blade, d.blade.struct.K + d.ksigma


def buckling_load(rb, kind: str, route: str, P_ref: float, rel: float = 1e-3) -> float:
    """Smallest P (N) with the lowest omega^2 <= 0: scan in steps of 0.1 ``P_ref`` up to 3 ``P_ref``,
    then bisect to ``rel`` (a load without a co-rotational equilibrium counts as beyond it)."""
    def w(P):
        try:
            return lowest_w2(*stiffness(rb, kind, route, P))
        except ModelError:  # no co-rotational equilibrium near the straight path: past the limit
            return -1.0

    lo = 0.0
    for r in np.arange(0.1, 3.01, 0.1):
        if w(r * P_ref) <= 0.0:
            hi = r * P_ref
            break
        lo = r * P_ref
    else:
        return float("nan")
    while hi - lo > rel * P_ref:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if w(mid) <= 0.0 else (mid, hi)
    return 0.5 * (lo + hi)


def closed_forms(GJ: float, EImin: float, EImaj: float, arm: float):
    """(classical P_cr, with the prebuckling-deflection factor) in N."""
    P = 4.013 * np.sqrt(EImin * GJ) / arm**2
    return P, P / np.sqrt((1 - EImin / EImaj) * (1 - GJ / EImaj))


def main(walls=(0.01, 0.04)) -> None:
    for wall in walls:
        rows = []
        for kind, ribs in (("beam", False), ("shell", False), ("shell", True)):
            rb, (GJ, EImin, EImaj) = tube(kind, wall, ribs)
            Pc, Pp = closed_forms(GJ, EImin, EImaj, lever_arm(rb))
            for route in ("classical", "deflected"):
                rows.append((kind + (" with ribs" if ribs else ""), route, buckling_load(rb, kind, route, Pc) / Pc))
        print(f"wall {wall * 1e3:.0f} mm: GJ {GJ:.3e}, EI_minor {EImin:.3e}, EI_major {EImaj:.3e} N m^2; lever arm "
              f"{lever_arm(rb):.3f} m; P_cr classical {Pc / 1e3:.1f} kN, with prebuckling deflections {Pp / Pc:.3f} x")
        for kind, route, r in rows:
            print(f"  {kind:16s} {route:9s}: P_cr = {r:.3f} x classical", flush=True)


if __name__ == "__main__":
    main()
