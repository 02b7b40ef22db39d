"""Energy audit of the edgewise aerodynamic damping (issue 14, docs/notes/edgewise_damping.md).

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


def build(V: float, n_span: int = 20, aero: UnsteadyOptions | None = None, turbine="iea15mw", aero_state=None,
          pitch: float | None = None, **opts) -> Point:
    """The rotor model at ``V`` (m/s) on its operating curve, with the pieces kept apart.

    ``aero_state``: a steady state of another model with the same strips whose strip geometry
    (points, chord and span directions) and BEM induction replace this model's in the
    aerodynamics (the structure keeps its own geometry and prestress).  ``pitch`` (rad) replaces
    the operating curve's."""
    aero = aero or UnsteadyOptions()
    tb = load_turbine(turbine) if isinstance(turbine, str) else turbine
    om = OperationalModel(tb, OperationalOptions(part="rotor", mesh={"n_span": n_span},
                                                                    aero=aero, **opts))
    omega, pitch_c = om.operating_point(V)
    pitch = pitch_c if pitch is None else pitch
    rb = om.blade(pitch)
    st = om.steady(rb, V, omega)
    if aero_state is not None:
        a = aero_state.sections
        sec = dataclasses.replace(st.sections, origin=a.origin, e_chord=a.e_chord, e_span=a.e_span, radius=a.radius)
        st = dataclasses.replace(st, sections=sec, bem=aero_state.bem)
    ksig, klink = om._prestress(rb, st, omega)
    blocks, P = om._aero_blocks(rb, st, V, omega)
    Phi = om.blade_basis(rb, omega, ksig, blocks, P)
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
    span, chord (LE -> TE), the arms to the quarter and 3/4 chord, the steady relative wind W0
    (induced, as the strip sees it)."""
    om = p.model
    sec = p.st.sections
    n = _unit(np.asarray(om.rotor.shaft_axis, float))
    r = np.asarray(sec.origin, float) - np.asarray(om.rotor.hub_center, float)
    t = _unit(np.cross(n, r))
    a, ap = p.st.bem.a, p.st.bem.ap
    W0 = p.V * (1 - a)[:, None] * n[None, :] - (1 + ap)[:, None] * p.omega * np.cross(n, r)
    b, ea = 0.5 * np.asarray(sec.chord, float), np.asarray(sec.elastic_axis, float)
    return dict(n=n, t=t, span=_unit(np.asarray(sec.e_span, float)), chord=_unit(np.asarray(sec.e_chord, float)),
                W0=W0, c=2 * b, d14=b * (ea + 0.5), d34=b * (0.5 - ea), polars=sec.polars,
                airfoil=np.asarray(sec.airfoil), rho=p.oper.op.air_density, omega=p.omega)


def quasi_steady_force(g, dv, du, tw, twdot):
    """Blade-element force (ns, 3) and moment about the span (ns,) per unit span on each strip.

    Inputs: velocity ``dv`` and displacement ``du`` (ns, 3) of the section point (the latter for
    the transport velocity ``Omega n x du``), twist ``tw`` about the span and its rate ``twdot``
    (ns,).  The wind is taken at the 3/4-chord point, lift normal to it and drag along it, both
    at the quarter chord; ``alpha = phi - beta`` with the inflow angle ``phi`` from the rotor
    plane and the chord angle ``beta`` (+ towards feather).  Returns (F, M, alpha, phi).
    """
    n, t, s = g["n"], g["t"], g["span"]
    c0 = g["chord"]
    ch = c0 * np.cos(tw)[:, None] + np.cross(s, c0) * np.sin(tw)[:, None]  # turned about the span
    ch = _unit(ch - np.sum(ch * s, axis=1, keepdims=True) * s)
    r34, r14 = g["d34"][:, None] * ch, -g["d14"][:, None] * ch
    v34 = dv + twdot[:, None] * np.cross(s, r34)
    W = g["W0"] - v34 - g["omega"] * np.cross(n[None, :], du)
    W = W - np.sum(W * s, axis=1, keepdims=True) * s
    # section-plane axes: x backwards (-t), y downwind (n), both normal to the span; x cross y = -s,
    # so a turn about +s lowers beta: +s is the nose-up axis
    x = _unit(-t + np.sum(t * s, axis=1, keepdims=True) * s)
    y = _unit(np.cross(s, x))
    y = np.where((y @ n < 0)[:, None], -y, y)
    phi = np.arctan2(np.sum(W * y, 1), np.sum(W * x, 1))  # inflow angle from the rotor plane
    beta = np.arctan2(np.sum(ch * y, 1), np.sum(ch * x, 1))  # chord angle, + to feather
    alpha = phi - beta
    cl, cd, cm = (np.empty_like(alpha) for _ in range(3))
    for kk in np.unique(g["airfoil"]):
        sel = g["airfoil"] == kk
        pol = g["polars"][int(kk)]
        for out, tab in ((cl, pol.cl), (cd, pol.cd), (cm, pol.cm)):
            out[sel] = np.interp(alpha[sel], pol.alpha, tab)
    qc = 0.5 * g["rho"] * np.sum(W * W, 1) * g["c"]
    lift = np.cos(phi)[:, None] * y - np.sin(phi)[:, None] * x  # normal to W, downwind / forward
    F = qc[:, None] * (cl[:, None] * lift + cd[:, None] * _unit(W))
    M = np.sum(np.cross(r14, F) * s, 1) + qc * g["c"] * cm  # about +s (nose-up)
    return F, M, alpha, phi


def quasi_steady_jacobians(g, h=1e-4):
    """Central-difference Jacobians of (F, M) w.r.t. dv, du (per m/s, per m; (ns, 4, 3)) and tw,
    twdot (per rad, per rad/s; (ns, 4)); rows (F_x, F_y, F_z, M)."""
    ns = g["W0"].shape[0]
    z3, z1 = np.zeros((ns, 3)), np.zeros(ns)

    def fm(dv=z3, du=z3, tw=z1, twdot=z1):
        F, M, _, _ = quasi_steady_force(g, dv, du, tw, twdot)
        return np.column_stack([F, M])

    J = {}
    for name in ("dv", "du"):
        Jn = np.zeros((ns, 4, 3))
        for c in range(3):
            e = np.zeros((ns, 3))
            e[:, c] = h
            Jn[:, :, c] = (fm(**{name: e}) - fm(**{name: -e})) / (2 * h)
        J[name] = Jn
    for name, step in (("tw", 1e-6), ("twdot", h)):
        e = np.full(ns, step)
        J[name] = (fm(**{name: e}) - fm(**{name: -e})) / (2 * step)
    return J


def quasi_steady_audit(p: Point, lam: complex, Q: np.ndarray, rotations: bool = True):
    """sigma shares (1/s) of the independent blade-element force on the mode ``(lam, Q)``, by
    work term: forces on the in-plane (t), out-of-plane (n) and radial (r) translations from each
    velocity component, from the twist and its rate, from the transport velocity; the moment's
    work on the twist ("moment").  ``rotations=False``: the mode's twist left out."""
    g = quasi_steady_setup(p)
    J = quasi_steady_jacobians(g)
    sec = p.st.sections
    ns = sec.n_sections
    width = np.asarray(sec.width, float)
    m = np.real(np.vdot(Q, p.Ms @ Q))
    k = np.real(np.vdot(Q, p.Ks @ Q))
    den = abs(lam) ** 2 * m + k
    n, t, s = g["n"], g["t"], g["span"]
    out = {}
    for Y in blade_vectors(p, Q):
        w = np.asarray(sec.motion_map @ (p.B @ Y)).reshape(ns, 6)
        u = w[:, :3]
        tw = np.sum(w[:, 3:] * s, 1) if rotations else np.zeros(ns)
        comps = {"n": np.outer(u @ n, n), "t": np.sum(u * t, 1)[:, None] * t}
        comps["r"] = u - comps["n"] - comps["t"]
        sources = {**{f"v:{b_}": np.einsum("jab,jb->ja", J["dv"], lam * ub) for b_, ub in comps.items()},
                   "twist": J["tw"] * tw[:, None] + J["twdot"] * (lam * tw)[:, None],
                   "transport": np.einsum("jab,jb->ja", J["du"], u)}
        terms = {}
        for src, f in sources.items():
            for a_, ua in comps.items():
                terms[f"{src}->{a_}"] = np.sum(np.conj(ua) * f[:, :3], 1)
            terms[f"{src}->moment"] = np.conj(tw) * f[:, 3]
        for key, A_j in terms.items():
            out[key] = out.get(key, 0.0) - np.real(np.conj(lam) * A_j * width) / den
    return out, g


PIECE_NAMES = {"cl": "Cl0", "cd": "Cd0", "cm": "Cm0", "dcl": "dCl/da", "dcd": "dCd/da", "dcm": "dCm/da",
               "apparent mass": "apparent mass"}


def piece_table(res) -> list[str]:
    """Markdown rows: sigma share (1/s) of each piece, instantaneous / lag, relative / transport."""
    rows = ["| piece | relative, instantaneous | relative, lag states | transport, instantaneous | "
            "transport, lag states | total |", "|---|---|---|---|---|---|"]
    for name, label in PIECE_NAMES.items():
        v = [res["per"][(name, part, kind)].sum() for part in ("relative", "transport") for kind in ("inst", "lag")]
        rows.append(f"| {label} | " + " | ".join(f"{x:+.4f}" for x in v) + f" | {sum(v):+.4f} |")
    rows.append(f"| **aerodynamic** | | | | | **{res['aero']:+.4f}** |")
    rows.append(f"| structural (file damping) | | | | | {res['structural']:+.4f} |")
    rows.append(f"| sum = sigma = -Re(lambda) | | | | | {res['structural'] + res['aero']:.4f} "
                f"(eigenvalue {res['sigma']:.4f}) |")
    return rows


def span_table(p: Point, res, edges=(0.0, 0.2, 0.4, 0.6, 0.8, 1.0)) -> list[str]:
    """Markdown rows: the aerodynamic sigma by span station (fraction of the tip radius)."""
    r = np.asarray(p.st.sections.radius, float)
    x = r / r.max()
    tot = sum(v for v in res["per"].values())
    by = {n: sum(res["per"][(n, a, b)] for a in ("relative", "transport") for b in ("inst", "lag"))
          for n in PIECE_NAMES}
    rows = ["| r/R | all pieces | Cl0 | Cd0 | dCl/da | other |", "|---|---|---|---|---|---|"]
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (x > lo) & (x <= hi)
        main = [by[k][sel].sum() for k in ("cl", "cd", "dcl")]
        rows.append(f"| {lo:.1f}-{hi:.1f} | {tot[sel].sum():+.4f} | " + " | ".join(f"{v:+.4f}" for v in main)
                    + f" | {tot[sel].sum() - sum(main):+.4f} |")
    return rows


def blade_element_table(p: Point, lam, Q) -> list[str]:
    """Markdown rows: the independent blade-element evaluation against the operator's
    quasi-steady law on the same mode, translations only and with the section rotations."""
    qs_law = dataclasses.replace(p.oper.options, circulation="quasi_steady", apparent_mass=0.0)
    rows = ["| motion used | operator, quasi-steady law | blade element (independent) | difference |",
            "|---|---|---|---|"]
    for rot in (False, True):
        a = audit(p, lam, Q, options=qs_law, rotations=rot)["aero"]
        b = sum(v.sum() for v in quasi_steady_audit(p, lam, Q, rotations=rot)[0].values())
        rows.append(f"| {'translations and rotations' if rot else 'translations only'} | {a:+.5f} | {b:+.5f} | "
                    f"{b - a:+.1e} |")
    return rows


def blade_element_terms(p: Point, lam, Q) -> list[str]:
    """Markdown rows: the blade-element sigma shares by work term."""
    qs = quasi_steady_audit(p, lam, Q)[0]
    groups = {"in-plane force from in-plane velocity": ["v:t->t"],
              "flap force from flap velocity": ["v:n->n"],
              "cross terms: in-plane force from flap velocity": ["v:n->t"],
              "cross terms: flap force from in-plane velocity": ["v:t->n"],
              "forces from the twist and its rate (on translations)": ["twist->n", "twist->t", "twist->r"],
              "moment on the twist (all sources)": [k for k in qs if k.endswith("->moment")],
              "transport velocity (on translations)": ["transport->n", "transport->t", "transport->r"],
              "radial components": ["v:r->n", "v:r->t", "v:r->r", "v:n->r", "v:t->r"]}
    rows = ["| blade-element work term | sigma share (1/s) |", "|---|---|"]
    for label, keys in groups.items():
        rows.append(f"| {label} | {sum(qs[k].sum() for k in keys):+.4f} |")
    rows.append(f"| total | {sum(v.sum() for v in qs.values()):+.4f} |")
    return rows


def mode_content(p: Point, Q) -> tuple[complex, complex]:
    """Tip flap / tip edge (m/m) and tip torsion / tip edge (rad/m) of blade 0, blade-root frame."""
    sec = p.st.sections
    ns = sec.n_sections
    Y = blade_vectors(p, Q)[0]
    w = np.asarray(sec.motion_map @ (p.B @ Y)).reshape(ns, 6)
    F = p.st.frames[0]
    u, th = w[:, :3] @ F, w[:, 3:] @ F
    return u[-1, 0] / u[-1, 1], th[-1, 2] / u[-1, 1]


def edge_pair(p: Point):
    """(cyclic, collective) 1st edge eigenpairs of the rotor on a fixed nacelle."""
    modes = [m for m in rotating_modes(p) if abs(m[0]) > 2 * np.pi * 0.3]
    col = [m for m in modes if 1.2 < abs(m[0]) / 2 / np.pi < 1.7 and -m[0].real < 0.1 * abs(m[0])][0]
    return modes[0], col


def main(speeds):
    for V in speeds:
        p = build(V)
        (lc, Qc), (lk, Qk) = edge_pair(p)
        for label, lam, Q in (("cyclic (BW/FW) 1st edge", lc, Qc), ("collective 1st edge", lk, Qk)):
            res = audit(p, lam, Q)
            fl, to = mode_content(p, Q)
            print(f"\n### V = {V} m/s, {label}: {abs(lam) / 2 / np.pi:.4f} Hz (rotating frame), "
                  f"zeta {-lam.real / abs(lam):.4f}; tip flap/edge {abs(fl):.3f} at {np.degrees(np.angle(fl)):.0f} deg, "
                  f"torsion/edge {abs(to):.4f} rad/m at {np.degrees(np.angle(to)):.0f} deg\n")
            print("\n".join(piece_table(res)))
            if Q is Qc:
                print()
                print("\n".join(span_table(p, res)))
            print()
            print("\n".join(blade_element_table(p, lam, Q)))
            print()
            print("\n".join(blade_element_terms(p, lam, Q)))
        pm = build(V, aero=dataclasses.replace(p.oper.options, mean_loads=False))
        (lm, Qm), _ = edge_pair(pm)
        res = audit(pm, lm, Qm)
        fl, to = mode_content(pm, Qm)
        print(f"\n### V = {V} m/s, cyclic 1st edge WITHOUT mean loads: {abs(lm) / 2 / np.pi:.4f} Hz, "
              f"sigma {-lm.real:.4f}; tip flap/edge {abs(fl):.3f} at {np.degrees(np.angle(fl)):.0f} deg\n")
        print("\n".join(piece_table(res)))
        print()
        print("\n".join(blade_element_terms(pm, lm, Qm)))


if __name__ == "__main__":
    main([float(x) for x in sys.argv[1:]] or [10.0])
