"""The decay rate of the whole turbine's whirling 1st edge modes split by term (docs/notes/edgewise_damping.md sec. 12).

For an eigenpair (lambda, q, z) of the multi-blade system ``M q'' + C q' + K q = F z`` (aerodynamic
states ``z``), the structural part alone (``Ms, Cs, Ks``: the same steady state without the
aerodynamic matrices) satisfies ``q^H D (lambda^2 Ms + lambda Cs + Ks) q = q^H D W`` with ``W`` the
aerodynamic generalized force and ``D = T^T T`` the Coleman scaling that makes ``D Ms`` symmetric.
The real part of ``conj(lambda)`` times it partitions sigma = -Re(lambda) exactly into: the
structural damping (by group), the circulatory part of the structural stiffness (``omega Im
q^H D Ks q``: the rotating damping seen in multi-blade coordinates) and the aerodynamic work, split by
the coordinates it acts through (rows) and the motion it comes from (columns: tower, drivetrain,
collective and cyclic blade coordinates; the lag states' part by the motion that drives them).  The pieces must add up
to sigma (asserted).  IEA 15 MW in HAWCStab2's configuration (tests/reference_axis.py, HAWC2's
thrust relation, tower damping 0.1 %), at HAWCStab2's operating points.

    python docs/scripts/whirl_split_audit.py [WIND ...]
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "system"))
from hawcstab2_reference import operating_point  # noqa: E402
from reference_axis import moved_reference  # noqa: E402

from windflutter.model import load_turbine  # noqa: E402
from windflutter.system.blade_aero import blade_system  # noqa: E402
from windflutter.system.modes import point_modes  # noqa: E402
from windflutter.system.multiblade import _transform, multiblade_system  # noqa: E402
from windflutter.system.operational import OperationalModel, OperationalOptions  # noqa: E402


def groups(ps) -> dict[str, np.ndarray]:
    """Indices of the multi-blade coordinates by group."""
    nF, m = ps.mbc.n_fixed, ps.mbc.n_eta
    sup = [i for i, lb in enumerate(ps.labels) if lb.startswith("support")]
    drv = [i for i, lb in enumerate(ps.labels) if not lb.startswith("support")]
    return {"tower": np.array(sup, int), "drivetrain": np.array(drv, int),
            "blade collective": np.arange(nF, nF + m), "blade cyclic": np.arange(nF + m, ps.mbc.M.shape[0])}


def partition(ps, lam: complex, x: np.ndarray) -> dict[str, float]:
    """sigma's share of every term for the eigenpair (``lam``, ``x = [q, q', z]``) of ``ps.mbc``."""
    mb = ps.mbc
    n = mb.M.shape[0]
    M0, K0 = ps.blade_structure
    st = multiblade_system(ps.fixed, blade_system(M0, ps.blade_damping, K0), ps.n_blades, ps.omega, ps.blade.axis)
    T, _, _ = _transform(mb.n_fixed, mb.n_eta, ps.n_blades, 0.0, ps.omega)
    D = T.T @ T
    q, z = x[:n], x[2 * n:]
    Ms, Cs, Ks = D @ st.M, D @ st.C, D @ st.K
    Aq = -D @ (lam**2 * (mb.M - st.M) + lam * (mb.C - st.C) + (mb.K - st.K))
    Fz = D @ mb.F
    # the lag states driven by each group's motion: z = (lam - A)^-1 (Bq + lam Bv) q, linear in q
    idx = groups(ps)
    drive = np.linalg.solve(lam * np.eye(mb.A.shape[0]) - mb.A, mb.Bq + lam * mb.Bv)
    z_from = {g: drive[:, ii] @ q[ii] for g, ii in idx.items()}
    assert np.allclose(sum(z_from.values()), z, rtol=1e-6, atol=1e-9 * np.abs(z).max())
    kap = np.vdot(q, Ks @ q)
    den = abs(lam) ** 2 * np.vdot(q, Ms @ q).real + kap.real
    out = {}
    Csym = 0.5 * (Cs + Cs.T)
    for g, ii in idx.items():
        out[f"structural damping, {g}"] = abs(lam) ** 2 * np.vdot(q[ii], Csym[np.ix_(ii, ii)] @ q[ii]).real / den
    out["structural damping, cross terms"] = abs(lam) ** 2 * np.vdot(q, Cs @ q).real / den - sum(out.values())
    out["structural circulatory (rotating damping)"] = lam.imag * kap.imag / den
    for gr, ir in idx.items():
        for gc, ic in idx.items():
            out[f"aero through {gr} <- {gc} motion"] = -(np.conj(lam) * np.vdot(q[ir], Aq[np.ix_(ir, ic)] @ q[ic])).real / den
        for gc, zc in z_from.items():
            out[f"aero through {gr} <- lag states <- {gc} motion"] = -(np.conj(lam) * np.vdot(q[ir], Fz[ir] @ zc)).real / den
    total = sum(out.values())
    assert abs(total + lam.real) < 1e-6 * abs(lam), (total, -lam.real)
    return out


def main(winds: list[float]) -> None:
    tb = moved_reference(load_turbine("iea15mw", validate=False), 0.5)
    om = OperationalModel(tb, OperationalOptions(mesh={"n_span": 20}, structure="deflected", tower_damping=0.001,
                                                 high_thrust="madsen"))
    for v in winds:
        rpm, pitch = operating_point(v)
        ps = om.at(v, rpm=rpm, pitch=math.radians(pitch))
        lam_all, X = np.linalg.eig(ps.mbc.state_matrix())
        for mode in point_modes(ps, max_hz=1.0):
            if mode.name not in ("1st edge BW", "1st edge FW"):
                continue
            k = int(np.argmin(np.abs(lam_all - mode.eigenvalue)))
            parts = partition(ps, lam_all[k], X[:, k])
            print(f"\n{v:g} m/s {mode.name}: sigma {-lam_all[k].real:.4f} 1/s (zeta {100 * mode.damping_ratio:.2f} %)")
            for name, val in parts.items():
                if abs(val) > 2e-4:
                    print(f"   {name:52s} {val:+.4f}")


if __name__ == "__main__":
    main([float(a) for a in sys.argv[1:]] or [10.0])
