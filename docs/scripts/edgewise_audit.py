"""Energy audit of the edgewise aerodynamic damping (issue 14, docs/edgewise_damping.md).

For the rotor on a fixed nacelle (``part="rotor"``) the periodic system in physical blade
coordinates ``q = [azimuth, generator, eta_0, eta_1, eta_2]`` is time-invariant, so its
eigenpairs ``(lambda, Q)`` are the rotating-frame modes: the cyclic edge pair (whose decay rate is
the BW and FW modes' ``sigma``) and the collective edge mode.  For an exact eigenpair,

    Q^H (lambda^2 M + lambda C + K) Q = sum_b Y_b^H R^T f_b = A,      Y_b = J_b Q

(``M, C, K`` structural, symmetric ``M, K``; ``f_b`` the strip forces of blade ``b``) gives the
exact partition of the decay rate ``sigma = -Re lambda``::

    sigma (|lambda|^2 m + k) = |lambda|^2 d - Re(conj(lambda) A),   A = sum_i A_i

``m, k, d`` the structural mass, stiffness and (symmetric) damping forms.  Every piece ``A_i`` of the
strip force (linear in the polar data ``Cl0, Cd0, Cm0, dCl, dCd, dCm``; apparent mass; the lag
states; the transport velocity) gets its share of ``sigma``, per strip.

The independent check (``quasi_steady_force``) is the textbook blade-element force written here
from the rotor-plane geometry (inflow angle phi from the rotor plane, chord angle beta, alpha =
phi - beta, lift normal to the wind, drag along it), linearized by central differences; only the
mode shape (section translations and rotations from the structural DOFs) and the steady state
(deflected strip geometry, BEM induction, polars) come from the model.

Run: ``PYTHONPATH=src python docs/scripts/edgewise_audit.py [wind speeds]``  (~2 s a point).
"""

from __future__ import annotations

import dataclasses
import sys

import numpy as np
import scipy.linalg as sla

from windflutter.aero.unsteady import UnsteadyOptions, strip_state_space
from windflutter.model import load_turbine
from windflutter.system.blade_aero import blade_system
from windflutter.system.multiblade import _blade_jacobians, periodic_system
from windflutter.system.operational import OperationalModel, OperationalOptions
from windflutter.system.support import fixed_frame

COEFFS = ("cl", "cd", "cm", "dcl", "dcd", "dcm")


@dataclasses.dataclass
class Point:
    """Everything the audit needs at one operating point (rotor on a fixed nacelle)."""

    V: float
    omega: float
    model: OperationalModel
    rb: object
    st: object
    oper: object
    Phi: np.ndarray
    B: object
    R: np.ndarray  # (3 ns, ny) section motion of y = (h, eta)
    Rt: np.ndarray  # (3 ns, ny) transport map
    Ms: np.ndarray  # structural periodic system
    Cs: np.ndarray
    Ks: np.ndarray
    ff: object
    blade_full: object  # BladeSystem with aero (for the eigenproblem)


def build(V: float, n_span: int = 20, aero: UnsteadyOptions | None = None, turbine="iea15mw", **opts) -> Point:
    """The rotor model at ``V`` (m/s) on its operating curve, with the pieces kept apart."""
    aero = aero or UnsteadyOptions()
    tb = load_turbine(turbine) if isinstance(turbine, str) else turbine
    om = OperationalModel(tb, OperationalOptions(part="rotor", mesh={"n_span": n_span},
                                                                    aero=aero, **opts))
    omega, pitch = om.operating_point(V)
    rb = om.blade(pitch)
    st = om.steady(rb, V, omega)
    ksig, klink = om._prestress(rb, st, omega)
    blocks, P = om._aero_blocks(rb, st, V, omega)
    Phi = om._blade_basis(rb, omega, ksig, klink, blocks, P)
    bm = rb.matrices(Phi, ksigma_full=ksig, klink=klink)
    M, C, K = bm.at(omega, ksigma=bm.Ks1)
    B = rb.basis_full(Phi)
    R = np.asarray(P @ B)
    Rt = np.asarray(P @ (rb.St @ B))
    from windflutter.aero.flow import OperatingPoint
    from windflutter.aero.operators import make_operator

    op = st.operating_point(om.rotor) if om.options.induction else OperatingPoint(V, omega, om.options.air_density,
                                                                                  om.rotor, 0.0)
    oper = make_operator(st.sections, op, aero)
    from windflutter.system.blade_aero import project_blade_aero

    aero_proj = project_blade_aero(blocks, R, Rt, omega)
    ff = fixed_frame(None, om.hub_mass(), om.rotor.shaft_axis, om.drivetrain())
    ps = periodic_system(ff, blade_system(M, C, K), om.n_blades, omega, om.rotor.shaft_axis)
    return Point(V, omega, om, rb, st, oper, Phi, B, R, Rt, ps.M, ps.C, ps.K, ff, blade_system(M, C, K, aero_proj))


def rotating_modes(p: Point, fmax: float = 2.0):
    """Eigenpairs (lambda, Q) of the rotor's periodic (time-invariant) system with aerodynamics,
    oscillatory, undamped frequency below ``fmax`` Hz, structural part of the vector only."""
    om = p.model
    ps = periodic_system(p.ff, p.blade_full, om.n_blades, p.omega, om.rotor.shaft_axis)
    n, nz = ps.M.shape[0], ps.A.shape[0]
    E = np.eye(2 * n + nz)
    E[n:2 * n, n:2 * n] = ps.M
    A = np.zeros_like(E)
    A[:n, n:2 * n] = np.eye(n)
    A[n:2 * n, :n] = -ps.K
    A[n:2 * n, n:2 * n] = -ps.C
    A[n:2 * n, 2 * n:] = ps.F
    A[2 * n:, :n] = ps.Bq
    A[2 * n:, n:2 * n] = ps.Bv
    A[2 * n:, 2 * n:] = ps.A
    lam, X = sla.eig(A, E)
    keep = (lam.imag > 0.01) & (np.abs(lam) < 2 * np.pi * fmax) & (-lam.real < 0.9 * np.abs(lam))
    out = []
    for i in np.where(keep)[0]:
        q = X[:n, i]
        if np.linalg.norm(X[n:2 * n, i]) < 0.2 * np.linalg.norm(X[:, i]) * abs(lam[i]) / (1 + abs(lam[i])):
            continue  # an aerodynamic lag root
        out.append((complex(lam[i]), q))
    return sorted(out, key=lambda t: abs(t[0]))


def blade_vectors(p: Point, Q: np.ndarray):
    """Y_b = J_b Q (6 + m) of every blade (time-invariant for the rotor on a fixed nacelle)."""
    om = p.model
    m = p.blade_full.n_eta
    return [(_blade_jacobians(p.ff, m, om.n_blades, b, 0.0, p.omega, om.rotor.shaft_axis)[0] @ Q)
            for b in range(om.n_blades)]


def _lin_only(lin, keep: str | None):
    """The linearization with every polar coefficient zero except ``keep`` (None: all zero)."""
    z = np.zeros_like(lin.cl)
    return dataclasses.replace(lin, **{c: (getattr(lin, c) if c == keep else z) for c in COEFFS})


def strip_pieces(p: Point, options: UnsteadyOptions | None = None):
    """Per-unit-span state spaces of each piece: one per polar coefficient (no apparent mass) and
    the apparent mass alone; their sum is the operator's law (checked).  ``options`` replace the
    operator's (e.g. the quasi-steady law on the same steady state)."""
    o = options or p.oper.options
    lin = p.oper.linearization
    args = (p.oper.b, p.oper.a, p.oper.flow.U, p.oper.op.air_density)
    pieces = {c: strip_state_space(*args, _lin_only(lin, c), dataclasses.replace(o, apparent_mass=0.0))
              for c in COEFFS}
    pieces["apparent mass"] = strip_state_space(*args, _lin_only(lin, None), o)
    total = p.oper.law if options is None else strip_state_space(*args, lin, o)
    for name in ("Ma", "Da", "Ka", "Cz"):
        s = sum(getattr(x, name) for x in pieces.values())
        ref = getattr(total, name)
        assert np.allclose(s, ref, atol=1e-9 * max(np.abs(ref).max(initial=0.0), 1.0)), name
    return pieces


def piece_forces(ss, q, v, a, lam):
    """(instantaneous, lag) strip forces (ns, 3) per unit span of a piece for motion q, velocity
    v, acceleration a (ns, 3) complex at the exponent lam."""
    inst = np.einsum("jab,jb->ja", ss.Ma, a) + np.einsum("jab,jb->ja", ss.Da, v) + np.einsum("jab,jb->ja", ss.Ka, q)
    nz = ss.Az.shape[-1]
    if nz == 0:
        return inst, np.zeros_like(inst)
    S = lam * np.eye(nz)[None] - ss.Az
    rhs = np.einsum("jza,ja->jz", ss.Bq, q) + np.einsum("jza,ja->jz", ss.Bv, v)
    z = np.linalg.solve(S, rhs[..., None])[..., 0]
    return inst, np.einsum("jaz,jz->ja", ss.Cz, z)


def audit(p: Point, lam: complex, Q: np.ndarray, options: UnsteadyOptions | None = None, rotations: bool = True):
    """Shares of sigma (1/s) by piece, by (instantaneous/lag, relative/transport), per strip."""
    ns = p.oper.b.shape[0]
    width = np.asarray(p.st.sections.width, float)
    Ys = blade_vectors(p, Q)
    m = np.real(np.vdot(Q, p.Ms @ Q))
    k = np.real(np.vdot(Q, p.Ks @ Q))
    d = np.real(np.vdot(Q, 0.5 * (p.Cs + p.Cs.T) @ Q))
    den = abs(lam) ** 2 * m + k
    pieces = strip_pieces(p, options)
    res = {"lambda": lam, "sigma": -lam.real, "structural": abs(lam) ** 2 * d / den}
    per = {}
    for name, ss in pieces.items():
        for part in ("relative", "transport"):
            tot_inst = np.zeros(ns)
            tot_lag = np.zeros(ns)
            for Y in Ys:
                q = (p.R @ Y).reshape(ns, 3)
                if not rotations:
                    q = q * np.array([1.0, 0.0, 1.0])
                qt = (p.omega * (p.Rt @ Y)).reshape(ns, 3)
                if part == "relative":
                    args = (q, lam * q, lam * lam * q)
                else:  # transport velocity: only through v (and what it drives)
                    args = (np.zeros_like(q), qt, lam * qt)
                inst, lag = piece_forces(ss, *args, lam)
                if part == "transport":
                    inst = inst - np.einsum("jab,jb->ja", ss.Ma, lam * qt)  # Ma acts on q'' only
                for f, acc in ((inst, tot_inst), (lag, tot_lag)):
                    A_j = np.sum(np.conj(q) * f, axis=1) * width
                    acc += -np.real(np.conj(lam) * A_j) / den
            per[(name, part, "inst")] = tot_inst
            per[(name, part, "lag")] = tot_lag
    res["per"] = per
    res["aero"] = sum(v.sum() for v in per.values())
    res["check"] = res["structural"] + res["aero"] - res["sigma"]
    return res


# -- independent quasi-steady blade-element force ----------------------------------------------
def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def quasi_steady_setup(p: Point):
    """Rotor-plane geometry of the deflected strips: n (downwind), t (direction of rotation),
    span, chord, steady relative wind W0 (induced, in the ground frame seen by the strip)."""
    om = p.model
    sec = p.st.sections
    n = _unit(np.asarray(om.rotor.shaft_axis, float))
    r = np.asarray(sec.origin, float) - np.asarray(om.rotor.hub_center, float)
    t = _unit(np.cross(n, r))
    a, ap = p.st.bem.a, p.st.bem.ap
    W0 = p.V * (1 - a)[:, None] * n[None, :] - (1 + ap)[:, None] * p.omega * np.cross(n, r)
    return dict(n=n, t=t, span=_unit(np.asarray(sec.e_span, float)), chord=_unit(np.asarray(sec.e_chord, float)),
                W0=W0, c=np.asarray(sec.chord, float), polars=sec.polars, airfoil=np.asarray(sec.airfoil),
                rho=p.oper.op.air_density, omega=p.omega)


def quasi_steady_force(g, dv, dth, du):
    """Blade-element force per unit span (ns, 3), global, for a section velocity ``dv``, rotation
    ``dth`` and displacement ``du`` (ns, 3) (transport ``Omega n x du``); returns (F, alpha)."""
    n, t, s = g["n"], g["t"], g["span"]
    W = g["W0"] - dv - g["omega"] * np.cross(n[None, :], du)
    W = W - np.sum(W * s, axis=1, keepdims=True) * s
    ch = g["chord"] + np.cross(dth, g["chord"])
    ch = ch - np.sum(ch * s, axis=1, keepdims=True) * s
    # section-plane axes: x backwards (-t), y downwind (n), both normal to the span
    x = _unit(-t + np.sum(t * s, axis=1, keepdims=True) * s)
    y = _unit(np.cross(s, x))
    y = np.where((y @ n < 0)[:, None], -y, y)
    phi = np.arctan2(np.sum(W * y, 1), np.sum(W * x, 1))  # inflow angle from the rotor plane
    beta = np.arctan2(np.sum(ch * y, 1), np.sum(ch * x, 1))  # chord (LE->TE) angle, + to feather
    alpha = phi - beta
    cl = np.empty_like(alpha)
    cd = np.empty_like(alpha)
    for kk in np.unique(g["airfoil"]):
        sel = g["airfoil"] == kk
        pol = g["polars"][int(kk)]
        cl[sel] = np.interp(alpha[sel], pol.alpha, pol.cl)
        cd[sel] = np.interp(alpha[sel], pol.alpha, pol.cd)
    qd = 0.5 * g["rho"] * np.sum(W * W, 1) * g["c"]
    Wh = _unit(W)
    lift = np.cos(phi)[:, None] * y - np.sin(phi)[:, None] * x  # normal to W, downwind / forward
    return qd[:, None] * (cl[:, None] * lift + cd[:, None] * Wh), alpha, phi


def quasi_steady_jacobians(g, h=1e-4):
    """Central-difference Jacobians (ns, 3, 3) of the force w.r.t. dv (per m/s), dth (per rad),
    du (per m)."""
    ns = g["W0"].shape[0]
    out = []
    for which, step in (("v", h), ("th", h * 1e-2), ("u", h)):
        J = np.zeros((ns, 3, 3))
        for c in range(3):
            e = np.zeros((ns, 3))
            e[:, c] = step
            args_p = [np.zeros((ns, 3))] * 3
            args_m = [np.zeros((ns, 3))] * 3
            i = ("v", "th", "u").index(which)
            args_p[i], args_m[i] = e, -e
            J[:, :, c] = (quasi_steady_force(g, *args_p)[0] - quasi_steady_force(g, *args_m)[0]) / (2 * step)
        out.append(J)
    return out


def quasi_steady_audit(p: Point, lam: complex, Q: np.ndarray, rotations: bool = True):
    """sigma shares of the independent quasi-steady force: (in-plane, out-of-plane) blocks of
    the velocity Jacobian, rotation and transport terms, per strip (translational work only)."""
    g = quasi_steady_setup(p)
    Jv, Jth, Ju = quasi_steady_jacobians(g)
    sec = p.st.sections
    ns = sec.n_sections
    width = np.asarray(sec.width, float)
    m = np.real(np.vdot(Q, p.Ms @ Q))
    k = np.real(np.vdot(Q, p.Ks @ Q))
    den = abs(lam) ** 2 * m + k
    n, t = g["n"], g["t"]
    out = {}
    for Y in blade_vectors(p, Q):
        w = np.asarray(sec.motion_map @ (p.B @ Y)).reshape(ns, 6)
        u, th = w[:, :3], (w[:, 3:] if rotations else np.zeros((ns, 3)))
        # rotor-plane components of the translation: out of plane (n), in plane (t)
        comps = {"n": np.outer(u @ n, n), "t": np.sum(u * t, 1)[:, None] * t}
        comps["r"] = u - comps["n"] - comps["t"]
        terms = {}
        for a_, ua in comps.items():
            for b_, ub in comps.items():
                F = np.einsum("jab,jb->ja", Jv, lam * ub)
                terms[f"v:{a_}<-{b_}"] = np.sum(np.conj(ua) * F, 1)
            terms[f"twist:{a_}"] = np.sum(np.conj(ua) * np.einsum("jab,jb->ja", Jth, th), 1)
            terms[f"transport:{a_}"] = np.sum(np.conj(ua) * np.einsum("jab,jb->ja", Ju, u), 1)
        for key, A_j in terms.items():
            out[key] = out.get(key, 0.0) - np.real(np.conj(lam) * A_j * width) / den
    return out, g


def summarize(res, label):
    per = res["per"]
    print(f"  {label}: lambda = {res['lambda']:.4f}  f = {abs(res['lambda'])/2/np.pi:.4f} Hz  "
          f"sigma = {res['sigma']:.5f} 1/s  (structural {res['structural']:.5f}, aero {res['aero']:.5f}, "
          f"identity residual {res['check']:.1e})")
    rows = {}
    for (name, part, kind), v in per.items():
        rows.setdefault(name, {})[(part, kind)] = v.sum()
    print(f"    {'piece':14s} {'rel inst':>9s} {'rel lag':>9s} {'tr inst':>9s} {'tr lag':>9s} {'total':>9s}")
    for name, r in rows.items():
        vals = [r[("relative", "inst")], r[("relative", "lag")], r[("transport", "inst")], r[("transport", "lag")]]
        print(f"    {name:14s} " + " ".join(f"{x:9.5f}" for x in vals) + f" {sum(vals):9.5f}")


def main(speeds):
    for V in speeds:
        p = build(V)
        modes = rotating_modes(p)
        print(f"V = {V} m/s, Omega = {p.omega * 30 / np.pi:.3f} rpm")
        for lam, Q in modes:
            print(f"   mode {abs(lam)/2/np.pi:.4f} Hz zeta {-lam.real/abs(lam):.4f}")


if __name__ == "__main__":
    main([float(x) for x in sys.argv[1:]] or [10.0])
