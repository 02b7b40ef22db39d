"""The 1st edge modes of the IEA 15 MW with the blade linearized about its deflected shape
(``OperationalOptions(structure="deflected")``) against the undeformed axis and HAWCStab2
(docs/notes/edgewise_damping.md sec. 8).

Per wind speed (the turbine file's operating curve, beam blades, ``n_span = 20``):

* rotor on a fixed nacelle: the rotating-frame cyclic 1st edge mode (the blade's clamped-hub
  first-order system: frequency, decay rate sigma, tip flap / edge, tip torsion / edge in the blade
  frame) and the collective 1st edge mode of the multi-blade system;
* whole turbine: the 1st edge BW / FW / collective modes (Hz, zeta) and the mean BW, FW sigma;
* HAWCStab2 (whole turbine, ``/work/shared/data/iea15mw/hawcstab2_campbell``).

Run: ``PYTHONPATH=src:docs/scripts python docs/scripts/deflected_structure.py [V ...]`` (about 8 s a
wind speed).  Not a test: it reads the HAWCStab2 data from /work/shared.
"""

from __future__ import annotations

import sys

import numpy as np
import scipy.linalg as sla

from edgewise_geometry import edge_modes, hawcstab2
from windflutter.model import load_turbine
from windflutter.system.modes import point_modes
from windflutter.system.operational import OperationalModel, OperationalOptions

SPEEDS = (3.0, 5.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 14.0)
STRUCTURES = ("undeformed", "deflected")


def clamped_blade_modes(ps, fmax: float = 2.0):
    """Eigenpairs (lambda, eta) of the blade with its hub clamped, rotating frame, with aerodynamics:
    the cyclic modes of an isotropic rotor on a fixed nacelle."""
    b = ps.blade_system
    e = slice(6, None)
    M, C, K, F, Bq, Bv, Az = b.M[e, e], b.C[e, e], b.K[e, e], b.F[e, :], b.Bq[:, e], b.Bv[:, e], b.Az
    n, nz = M.shape[0], Az.shape[0]
    E = np.eye(2 * n + nz)
    E[n:2 * n, n:2 * n] = M
    A = np.zeros_like(E)
    A[:n, n:2 * n] = np.eye(n)
    A[n:2 * n, :n], A[n:2 * n, n:2 * n], A[n:2 * n, 2 * n:] = -K, -C, F
    A[2 * n:, :n], A[2 * n:, n:2 * n], A[2 * n:, 2 * n:] = Bq, Bv, Az
    lam, X = sla.eig(A, E)
    keep = (lam.imag > 0.01) & (np.abs(lam) < 2 * np.pi * fmax) & (-lam.real < 0.9 * np.abs(lam))
    out = [(complex(lam[i]), X[:n, i]) for i in np.where(keep)[0]
           if np.linalg.norm(X[n:2 * n, i]) >= 0.2 * np.linalg.norm(X[:, i]) * abs(lam[i]) / (1 + abs(lam[i]))]
    return sorted(out, key=lambda t: abs(t[0]))


def tip_content(ps, eta):
    """(tip flap / edge m/m, tip torsion / edge rad/m, edge share of the tip motion) of a blade
    motion, blade-root (pitching) frame of the steady state."""
    rb = ps.blade
    B = rb.basis_full(ps.Phi)
    y = np.concatenate([np.zeros(6), eta])
    w = np.asarray(rb.sections.motion_map @ (B @ y)).reshape(-1, 6)
    Fr = ps.steady.frames[0]
    u, th = w[-1, :3] @ Fr, w[-1, 3:] @ Fr
    return u[0] / u[1], th[2] / u[1], abs(u[1]) / np.linalg.norm(u)


def rotor_edge(om, V):
    ps = om.at(V)
    cyc = None
    for lam, eta in clamped_blade_modes(ps):
        if abs(lam) > 2 * np.pi * 0.3 and tip_content(ps, eta)[2] > 0.5:
            cyc = (lam, tip_content(ps, eta))
            break
    col = [m for m in point_modes(ps, max_hz=1.7) if m.family == "edge" and m.order == 1 and m.whirl == "collective"]
    return cyc, col[0].eigenvalue if col else complex("nan")


def _hawcstab2_cells(h) -> list[str]:
    bw, fw, col = h["BW"], h["FW"], h["collective"]
    return ["HAWCStab2 (BW / FW)", "", f"{bw[3]:.3f} / {fw[3]:.3f}, {bw[4]:.4f} / {fw[4]:.4f}", ""] \
        + [f"{m[0]:.3f} / {100 * m[1]:.2f}" for m in (bw, fw, col)] + [f"{(bw[2] + fw[2]) / 2:.4f}"]


def _model_cells(s, rotor, turbine) -> list[str]:
    (lam, (fe_ratio, te_ratio, _)), col = rotor
    return [s, f"{abs(lam) / 2 / np.pi:.3f} / {-lam.real:.4f}", f"{abs(fe_ratio):.3f}, {abs(te_ratio):.4f}",
            f"{abs(col) / 2 / np.pi:.3f} / {-col.real:.4f}"] \
        + [f"{turbine[w][0]:.3f} / {100 * turbine[w][1]:.2f}" for w in ("BW", "FW", "collective")] \
        + [f"{(turbine['BW'][2] + turbine['FW'][2]) / 2:.4f}"]


COLUMNS = ("V", "model", "rotor cyclic Hz / sigma", "tip flap/edge, torsion/edge", "rotor collective Hz / sigma",
           "turbine BW Hz / zeta %", "FW Hz / zeta %", "collective Hz / zeta %", "mean BW, FW sigma")


def main(speeds):
    tb = load_turbine("iea15mw")
    models = {(s, part): OperationalModel(tb, OperationalOptions(part=part, mesh={"n_span": 20}, structure=s))
              for s in STRUCTURES for part in ("rotor", "turbine")}
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    for V in speeds:
        rows = [[f"{V:g}"] + _hawcstab2_cells(hawcstab2(V))]
        rows += [[""] + _model_cells(s, rotor_edge(models[(s, "rotor")], V), edge_modes(models[(s, "turbine")], V))
                 for s in STRUCTURES]
        for r in rows:
            print("| " + " | ".join(r) + " |", flush=True)


if __name__ == "__main__":
    main([float(v) for v in sys.argv[1:]] or SPEEDS)
