"""Issue 33: which term of the bent state raises the bent tube's lateral-torsional buckling load
(docs/notes/shell_same_blade.md section 3, "The bent tube"; the tube, load and buckling search of
docs/scripts/bent_tube_torsion.py).

Run:  OMP_NUM_THREADS=1 PYTHONPATH=src python docs/scripts/bent_tube_routes.py   (about 15 s)

On the BEAM of the 10 mm tube, the linearized stiffness ``K_mat + K_geo`` of the co-rotational beam
(structure/corotational.py ``beam_tangent``) is built from a configuration and a set of element
resultants (local end loads) chosen independently:

* configuration: the exact equilibrium under the tip load (``system/deflected.py``), or the linear
  displacement chained into moderate rotations (``chained_configuration``: the carried geometry of
  the shell's route);
* resultants: the equilibrium's own, or the linear solution's (the stress carried with the
  elements: what the shell's route took before 5 Dec 2026), or either with the axial force (end
  loads 0 and 6) exchanged.

Each row's buckling load over the classical one (undeformed, linear initial stress).  The shell's
route with its stress balanced on the bent geometry (``system/deflected_shell.py``
``balanced_stress``) is printed last for comparison (the ribbed shell of bent_tube_torsion.py).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

from windflutter.structure.corotational import beam_tangent, chained_configuration, linear_resultants
from windflutter.system.deflected import deflected_blade

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bent_tube_torsion as bt  # noqa: E402

ROWS = [("eq", "own", "exact equilibrium, its own resultants (the exact Hessian)"),
        ("eq", "noN", "exact equilibrium, its resultants without their axial force"),
        ("eq", "lin", "exact equilibrium, the linear resultants"),
        ("lin", "lin", "linear displacement carried, the linear resultants (the carried route)"),
        ("lin", "linN", "linear displacement carried, the linear resultants + the equilibrium's axial force")]


def beam_stiffness(rb, P: float, geometry: str, stress: str):
    """(blade, K_mat + K_geo) of the beam tube ``rb`` under the tip load ``P`` (N)."""
    fe, f = rb.fe, bt.tip_load(rb, P)
    _, _, u = rb.prestress(f)
    g_lin = linear_resultants(fe, u)
    bent = bt.Bent(u=u, load_aero=f, load=f, f_internal=rb.struct.K @ u, sections=rb.sections,
                   strip_loads=bt.tip_strips(rb, P))
    eq = deflected_blade(rb, bent, 0.0).equilibrium
    config = eq.config if geometry == "eq" else chained_configuration(fe, u)
    g = {"own": eq.tangent.resultants, "lin": g_lin}.get(stress)
    if stress == "noN":
        g = eq.tangent.resultants.copy()
        g[:, [0, 6]] = 0.0
    elif stress == "linN":
        g = g_lin.copy()
        g[:, [0, 6]] = eq.tangent.resultants[:, [0, 6]]
    tan = beam_tangent(fe, config, resultants=g)
    return rb, tan.K_mat + tan.K_geo


def main() -> None:
    warnings.simplefilter("ignore")
    rb, consts = bt.tube("beam", 0.01)
    Pc, Pp = bt.closed_forms(*consts, bt.lever_arm(rb))
    classical = bt.buckling_load(rb, "beam", "classical", Pc)
    print(f"beam tube, wall 10 mm: classical {classical / Pc:.3f} x the closed form; the prebuckling estimate "
          f"{Pp / Pc:.3f} x")
    base = bt.stiffness
    for geometry, stress, label in ROWS:
        bt.stiffness = lambda r, kind, route, P, g=geometry, s=stress: beam_stiffness(r, P, g, s)
        print(f"  {label}: {bt.buckling_load(rb, 'beam', 'bent', Pc) / classical:.3f} x classical")
    bt.stiffness = base
    eq = deflected_blade(rb, bt.Bent(u=rb.prestress(bt.tip_load(rb, Pc))[2], load_aero=bt.tip_load(rb, Pc),
                                     load=bt.tip_load(rb, Pc), f_internal=np.zeros(rb.fe.n_dof),
                                     sections=rb.sections), 0.0).equilibrium
    N = eq.tangent.resultants[:, 6] / Pc
    print(f"  the equilibrium's axial force at the classical load (tension positive): {N.min():+.3f} ... "
          f"{N.max():+.3f} P (the linear solution's: 0)")
    sh, sconsts = bt.tube("shell", 0.01, ribs=True)
    sPc = bt.closed_forms(*sconsts, bt.lever_arm(sh))[0]
    ratio = bt.buckling_load(sh, "shell", "deflected", sPc) / bt.buckling_load(sh, "shell", "classical", sPc)
    print(f"ribbed shell, the deflected route (stress balanced on the bent geometry): {ratio:.3f} x classical")


if __name__ == "__main__":
    main()
