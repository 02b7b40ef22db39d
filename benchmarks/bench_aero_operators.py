"""Assembling and projecting the strip aerodynamic operators of a 3-blade rotor on a modal basis.

Model: the NREL 5 MW beam rotor (3 blades x 30 strips = 90 strips, ``mesh/turbine.build_model``
with ``n_span=30``, part ``turbine``) at 11.4 m/s, 12.1 RPM; basis: 100 columns (random dense
vectors of the model's DOF count: the cost does not depend on what the columns are).

Cases (median of ``REPEAT`` runs, BLAS limited to 1 thread):

1. today's thesis operator: ``StripAero(...)`` (flow, map, fitted slopes) + ``.projected(Phi)``
   + one frequency evaluation ``(Ma, Da, Ka)(omega)``;
2. the state-space operator ``StateSpaceAero(...)`` (flow, map, polar linearization with local
   slopes, section law) with Jones' 2 poles + ``.projected(Phi)`` (M_a, D_a, K_a, F_z, A_z, B_q,
   B_v) + one harmonic evaluation;
3. the same with the 4-pole Roger fit and the separation lag (5 states per strip);
4. forming the first-order state matrix ``E^-1 A`` (2 m + 90 nz) from the projected pieces;
   one dense eigen-solve of it is timed for information (it is the p-method's cost, not the
   operator's).

Usage: OPENBLAS_NUM_THREADS=1 python benchmarks/bench_aero_operators.py [--quick]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _benchutil import QUICK, header, table  # noqa: E402

from windflutter.aero.flow import OperatingPoint  # noqa: E402
from windflutter.aero.operators import StateSpaceAero  # noqa: E402
from windflutter.aero.strip import AeroOptions, StripAero  # noqa: E402
from windflutter.aero.unsteady import UnsteadyOptions  # noqa: E402

REPEAT = 3 if QUICK else 15
N_MODES = 100


def median_time(fn, repeat=REPEAT):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    return out, float(np.median(ts))


def main():
    from threadpoolctl import threadpool_limits

    threadpool_limits(limits=1, user_api="blas")
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model, rotor_geometry
    from windflutter.model import load_turbine

    tb = load_turbine("nrel5mw")
    fe, sec = build_model(tb, MeshSettings(model="beam", part="turbine", n_span=30))
    op = OperatingPoint(11.4, 12.1 * np.pi / 30, 1.225, rotor_geometry(tb))
    Phi = np.random.default_rng(0).standard_normal((fe.n_dof, N_MODES))
    header("strip aerodynamic operators", strips=sec.n_sections, dof=fe.n_dof, basis=N_MODES, repeat=REPEAT)
    rows = []
    om = 5.0
    th, t_b = median_time(lambda: StripAero(sec, op, AeroOptions(model="viscous", steady_loads=True)))
    pth, t_p = median_time(lambda: th.projected(Phi))
    _, t_e = median_time(lambda: pth(om))
    rows.append(dict(case="1 thesis StripAero (viscous+steady)", states=0, build_ms=1e3 * t_b,
                     project_ms=1e3 * t_p, eval_ms=1e3 * t_e))
    for name, o in (("2 state space, Jones", UnsteadyOptions()),
                    ("3 state space, RFA4 + stall", UnsteadyOptions(circulation="rfa", dynamic_stall=True))):
        if o.circulation == "rfa":  # the fit is computed once per run (cache it as a RogerRFA)
            from windflutter.aero.theodorsen import theodorsen_rfa

            o = UnsteadyOptions(circulation=theodorsen_rfa(4), dynamic_stall=True)
        st, t_b = median_time(lambda o=o: StateSpaceAero(sec, op, o))
        pss, t_p = median_time(lambda st=st: st.projected(Phi))
        _, t_e = median_time(lambda pss=pss: pss(om))
        rows.append(dict(case=name, states=pss.n_states, build_ms=1e3 * t_b, project_ms=1e3 * t_p,
                         eval_ms=1e3 * t_e))
    M = np.eye(N_MODES)
    K = np.diag(np.linspace(1.0, 30.0, N_MODES) ** 2)
    A, t_a = median_time(lambda: pss.state_matrix(M, 0.02 * np.sqrt(K), K))
    _, t_eig = median_time(lambda: np.linalg.eigvals(A), repeat=max(1, REPEAT // 5))
    table(rows, ["case", "states", "build_ms", "project_ms", "eval_ms"])
    print(f"first-order state matrix {A.shape[0]} x {A.shape[0]}: formed in {1e3 * t_a:.2f} ms; "
          f"dense eigenvalues {1e3 * t_eig:.0f} ms (p-method cost, for information)")


if __name__ == "__main__":
    main()
