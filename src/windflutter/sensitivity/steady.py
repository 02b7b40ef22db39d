"""The steady state's own sensitivity: the total derivative of the modes, the deflected equilibrium
moving with the parameter.

The steady state of a beam blade (:mod:`windflutter.steady.exact`) is a configuration ``c`` of the
co-rotational beam (node positions and rotations) in equilibrium with the centrifugal loads of its
deformed sections and the BEM aerodynamic loads of its deflected strips:

    ``R(c, p) = f_int(c; p) - f_cf(c; p) - f_aero(c; p) = 0``.

Its sensitivity is ``dc/dp = -K_T^-1 dR/dp`` with the tangent ``K_T = K_mat + K_geo - Omega^2 K_r
+ K_aero``: the structural part (the equilibrium's own tangent with the dead aerodynamic loads,
factorized once) and ``K_aero = -df_aero/dc``, the change of the nodal aerodynamic loads with the
deflection -- strip geometry, angle of attack, the lever arms of the motion map and the BEM
induction re-solved on the moved strips (induction *included*).  ``K_aero`` is formed once per point
by coloured central differences of the loads (:func:`whole_tangent`: a node's motion loads only the
nodes of the strips it carries, except the end strips', whose radii are the Prandtl factors' tip and
hub radius), checked against one product along a random direction, and ``K_T dc = -dR/dp`` is solved
with the LU of ``K_T`` for every parameter; should the colouring's check fail, by GMRES on products of
``K_aero`` along a vector, preconditioned with the structural part (:func:`steady_derivative`).
``dR/dp`` is a central difference of the residual in ``p`` at the nominal configuration.

The operating point's matrices are then differentiated along the path ``(p0 + s, c0 + s dc/dp)``:
the point is rebuilt (:func:`point_at`: the changed blade, the strips and their BEM inflow and loads
at the moved configuration, the equilibrium confirmed by :func:`~windflutter.system.deflected.
deflected_blade` -- a Newton step of order ``s^2`` --, the initial-stress matrix of that state, the
strips' linearization) with the blade basis held fixed, at ``s = +-h``, and the central difference
of the multi-blade matrices is contracted with the mode's left and right vectors
(:func:`~windflutter.sensitivity.eigen.mbc_derivative`).  That is a directional finite difference
of the assembly, not a re-analysis: no steady-state iteration and no eigen-solve.

The support's damping is the files' tower modal ratios set on the tower modes with the rotor's
rigid-body mass lumped at the hub (:meth:`~windflutter.system.operational.OperationalModel.
with_rotor_mass`): a change of the blade's mass (``mass``, ``mass_offset``) changes it too, and the
total derivative includes that (the per-element derivatives with the steady state held keep the
nominal support).

Parameters that leave the blade's steady state as it is -- the structural damping, and the support
(tower, nacelle, drivetrain: the blade's steady state is that of a blade clamped at the hub) --
have a total derivative equal to the one with the steady state held.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from windflutter.aero.induction import sections_induction
from windflutter.aero.strip import OperatingPoint
from windflutter.errors import InputError, ModelError
from windflutter.sensitivity.eigen import ModeVectors, mbc_derivative, mode_vectors
from windflutter.sensitivity.parameters import BLADE_PROPERTIES, GLOBAL_PARAMETERS, blade_sections
from windflutter.steady.exact import (centrifugal_loads, configuration_deflection, configuration_displacement,
                                      deformed_motion_map)
from windflutter.steady.geometry import deflected_sections
from windflutter.steady.loads import strip_loads
from windflutter.structure.assembly import assemble_matrices
from windflutter.structure.corotational import displaced, internal_forces
from windflutter.system.blade import RotorBlade
from windflutter.system.damping import blade_damping_matrix, blade_mu
from windflutter.system.deflected import deflected_blade

#: relative tolerance of the GMRES solve of ``K_T dc = -dR/dp``
GMRES_TOL = 1e-7
#: step of the directional differences of the aerodynamic loads along a configuration change: the
#: largest nodal translation (m) / rotation (rad) of the step
LOAD_STEP = 1e-6
#: the equilibrium of a point along the path ``c0 + s dc/dp`` is confirmed by ONE Newton step (this
#: tolerance stops after it): the path's residual is of order ``s^2`` and one step leaves ``s^4``, far
#: below the central difference's own ``h^2`` error
NEWTON_TOL = np.inf


@dataclass
class SteadyBase:
    """The nominal point's steady state, ready for its sensitivity: the model ``om``, the point
    ``ps``, the undeformed blade ``rb`` at the point's pitch, the blade damping coefficients
    ``mu``, the steady state ``steady`` and its co-rotational equilibrium ``config``; ``stiffness``
    the structural tangent ``T^T (K_mat + K_geo - Omega^2 K_r) T`` (free DOFs), ``factor`` its LU."""

    om: object
    ps: object
    rb: RotorBlade
    mu: np.ndarray | None
    steady: object
    config: object
    stiffness: sp.csc_matrix
    factor: object
    #: the LU of the whole tangent ``K_T`` (structure + coloured ``K_aero``, :func:`whole_tangent`), once
    #: built; False when the colouring's check failed (GMRES then)
    tangent_lu: object = None


def steady_base(om, ps) -> SteadyBase:
    """The :class:`SteadyBase` of the point ``ps`` of the operating-point model ``om`` (a beam blade
    linearized about its deflected co-rotational steady state)."""
    o = om.options
    st = ps.steady
    if st is None or getattr(st, "configuration", None) is None or o.structure != "deflected" or \
            len(ps.blade.fe.shell_conn):
        raise InputError("total", True, "a beam blade linearized about its co-rotational deflected steady "
                         "state (solver.structure deflected, solver.corotational true) with aerodynamics")
    rb = om.blade(ps.pitch)
    mu = blade_mu(om.turbine) if o.damping == "file" else None
    eq = deflected_blade(rb, st, ps.omega, mu).equilibrium
    T = rb.struct.T
    K = eq.tangent.K if eq.K_ext is None else eq.tangent.K - eq.K_ext
    Ks = sp.csc_matrix(T.T @ K @ T)
    return SteadyBase(om=om, ps=ps, rb=rb, mu=mu, steady=st, config=eq.config, stiffness=Ks, factor=spla.splu(Ks))


def changed_rotor_blade(rb: RotorBlade, name: str, p: float, elements=None, mu=None) -> RotorBlade:
    """The undeformed blade ``rb`` with the section property ``name`` of ``elements`` (None: all)
    changed by ``p`` (:func:`~windflutter.sensitivity.parameters.blade_sections`)."""
    fe = blade_sections(rb.fe, name, p, elements)
    M, K = assemble_matrices(fe)
    st = dataclasses.replace(rb.struct, fe=fe, M=sp.csr_matrix(M), K=sp.csr_matrix(K))
    return RotorBlade(fe, st, rb.sections, rb.apex, rb.axis, damping=blade_damping_matrix(fe, mu))


#: blade properties that change the blade's mass: the support's damping follows them (module docstring)
ROTOR_MASS = frozenset({"mass", "mass_offset"})


def _variant(base: SteadyBase, name: str, s: float, elements=None, support: bool = False):
    """(blade, air density, model) of the parameter ``name`` changed by ``s``; ``support``: the model's
    support damping set with the changed rotor mass (:data:`ROTOR_MASS`)."""
    om = base.om
    if name in BLADE_PROPERTIES:
        if support and name in ROTOR_MASS and om.options.part != "rotor":
            om = om.with_rotor_mass(om.rotor_rigid_mass(blade=changed_rotor_blade(om.blade(0.0), name, s, elements)))
        return changed_rotor_blade(base.rb, name, s, elements, base.mu), base.steady.air_density, om
    g = GLOBAL_PARAMETERS[name]
    if g.part == "strips":
        rb = base.rb
        return RotorBlade(rb.fe, rb.struct, g.strips(rb.sections, s), rb.apex, rb.axis, damping=rb.damping), \
            base.steady.air_density, om
    t, o = g.change(om.turbine, om.options, s)
    return base.rb, o.air_density, om.variant(t, o)


def strip_state(base: SteadyBase, config, air_density: float, rb: RotorBlade | None = None):
    """``(aero, f_aero)`` of the strips of the undeformed blade ``rb`` (default the nominal one)
    carried by the configuration: the deflected strips, their BEM induction (re-solved), polar
    coefficients and loads (``aero`` a dict of the :class:`~windflutter.steady.SteadyState` fields) and
    the nodal loads (n_dof,) through the motion map with its lever arms turned."""
    om, st = base.om, base.steady
    rb = base.rb if rb is None else rb
    defl = configuration_deflection(rb.sections, rb.fe, config)
    sec = deflected_sections(rb.sections, om.rotor, defl)
    V, Om = st.wind_speed, st.omega
    bem = sections_induction(sec, om.rotor, V, Om, n_blades=om.n_blades, pitch=st.pitch, air_density=air_density,
                             cone=True, warn=False, xtol=1e-13, high_thrust=om.options.high_thrust)
    sl = strip_loads(sec, OperatingPoint(V, Om, air_density, om.rotor, st.pitch, induction=(bem.a, bem.ap)))
    f = deformed_motion_map(rb.sections.motion_map, config.R).T @ sl.loads.reshape(-1)
    aero = dict(sections=sec, bem=bem, flow=sl.flow, cl=sl.cl, cd=sl.cd, cm=sl.cm, strip_loads=sl.loads,
                load_aero=np.asarray(f, float))
    return aero, np.asarray(f, float)


def residual(base: SteadyBase, rb: RotorBlade, config, air_density: float | None, fe=None) -> np.ndarray:
    """(n_dof,) ``f_int - f_cf - f_aero`` of the blade ``rb`` at the configuration; ``air_density``
    None: without ``f_aero`` (the structure's part); ``fe`` the blade's FE model (default ``rb.fe``)."""
    fe = rb.fe if fe is None else fe
    f_cf, _ = centrifugal_loads(fe, base.steady.omega, rb.apex, rb.axis)(config)
    r = internal_forces(fe, config) - f_cf
    return r if air_density is None else r - strip_state(base, config, air_density, rb)[1]


def _column_nodes(T) -> np.ndarray | None:
    """The node of each free DOF of the constraint map ``T`` (each column within one node's six DOFs:
    a selection, turned by the pitch), else None."""
    T = sp.csc_matrix(T)
    T.eliminate_zeros()
    nodes = T.indices // 6
    first = nodes[T.indptr[:-1]]
    if np.any(np.diff(T.indptr) == 0) or np.any(nodes != np.repeat(first, np.diff(T.indptr))):
        return None
    return first


def aero_colours(sections, fe, T) -> tuple[list, np.ndarray] | None:
    """The columns of ``K_aero`` grouped for coloured differences: ``(groups, rows)``, each group a list
    of free columns whose loaded rows (the nodes tied to the strips their node is tied to, motion
    map) do not overlap, ``rows[c]`` the boolean free rows column ``c`` reaches.  The nodes of the
    outermost and innermost strips (the Prandtl factors' tip and hub radius, which every strip sees,
    :func:`~windflutter.aero.induction.rotor_extent`) reach every row: their columns are alone."""
    node_of = _column_nodes(T)
    if node_of is None:
        return None
    mm = sp.coo_matrix(sections.motion_map)
    pairs = np.unique(np.stack([mm.row // 6, mm.col // 6], axis=1), axis=0)
    nn = fe.n_dof // 6
    tied = sp.csr_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(sections.n_sections, nn))
    reach = (tied.T @ tied).toarray() > 0  # node n's motion loads node m through a shared strip
    r, dr = np.asarray(sections.radius, float), np.asarray(sections.width, float)
    ends = [int(np.argmax(r + 0.5 * dr)), int(np.argmin(r - 0.5 * dr))]
    whole = np.asarray(tied[ends].sum(axis=0)).ravel() > 0
    rows = reach[node_of][:, node_of] | whole[node_of][:, None]
    groups, used = [], []
    for c in range(len(node_of)):
        if whole[node_of[c]]:
            groups.append([c])
            used.append(np.ones(len(node_of), bool))
            continue
        for g, u in zip(groups, used):
            if len(g) and not whole[node_of[g[0]]] and not np.any(u & rows[c]):
                g.append(c)
                u |= rows[c]
                break
        else:
            groups.append([c])
            used.append(rows[c].copy())
    return groups, rows


def whole_tangent(base: SteadyBase):
    """The LU of ``K_T = K_s + K_aero`` (free DOFs, dense), ``K_aero`` by coloured central differences
    of the nodal aerodynamic loads (:func:`aero_colours`; the step of :func:`steady_derivative`'s
    products), checked against one product along a fixed random direction: None when the colouring
    does not hold (relative mismatch above 1e-5)."""
    T = base.rb.struct.T
    col = aero_colours(base.rb.sections, base.rb.fe, T)
    if col is None:
        return None
    groups, rows = col
    rho = base.steady.air_density

    def product(q):  # -T^T df_aero/du T q
        v = np.asarray(T @ q)
        e = LOAD_STEP / max(np.abs(v).max(), 1e-300)
        fp, fm = (strip_state(base, displaced(base.config, s * e * v), rho)[1] for s in (1.0, -1.0))
        return -np.asarray(T.T @ ((fp - fm) / (2.0 * e)))

    n = T.shape[1]
    KA = np.zeros((n, n))
    for g in groups:
        q = np.zeros(n)
        q[g] = 1.0
        y = product(q)
        for c in g:
            KA[rows[c], c] = y[rows[c]]
    q = np.random.default_rng(31).standard_normal(n)
    ref = product(q)
    if np.linalg.norm(KA @ q - ref) > 1e-5 * np.linalg.norm(ref):
        return None
    return sla.lu_factor(base.stiffness.toarray() + KA)


def steady_derivative(base: SteadyBase, name: str, elements=None, h: float | None = None) -> np.ndarray:
    """(n_dof,) ``dc/dp`` of the equilibrium (node translations and spatial rotation increments,
    full numbering) for the parameter ``name`` (a blade property of ``elements`` or a global one):
    ``K_T dc = -dR/dp`` (module docstring)."""
    step = h if h is not None else (BLADE_PROPERTIES[name].step if name in BLADE_PROPERTIES
                                    else GLOBAL_PARAMETERS[name].step)
    T = base.rb.struct.T
    r = [_residual_of(base, name, s, elements) for s in (step, -step)]
    rhs = -np.asarray(T.T @ ((r[0] - r[1]) / (2.0 * step)))
    if not np.any(rhs):
        return np.zeros(base.rb.fe.n_dof)
    rho = base.steady.air_density

    def k_aero(q):
        v = np.asarray(T @ q)
        size = max(np.abs(v).max(), 1e-300)
        e = LOAD_STEP / size
        fp = strip_state(base, displaced(base.config, e * v), rho)[1]
        fm = strip_state(base, displaced(base.config, -e * v), rho)[1]
        return -np.asarray(T.T @ ((fp - fm) / (2.0 * e)))

    if base.tangent_lu is None:
        base.tangent_lu = whole_tangent(base) or False
    if base.tangent_lu is not False:
        return np.asarray(T @ sla.lu_solve(base.tangent_lu, rhs))
    n = rhs.size
    KT = spla.LinearOperator((n, n), matvec=lambda q: base.stiffness @ q + k_aero(q), dtype=float)
    pre = spla.LinearOperator((n, n), matvec=base.factor.solve, dtype=float)
    dq, info = spla.gmres(KT, rhs, M=pre, rtol=GMRES_TOL, atol=0.0, restart=40, maxiter=4)
    if info != 0:
        raise ModelError(f"the steady state's sensitivity to {name}: GMRES did not converge ({info})")
    return np.asarray(T @ dq)


def _residual_of(base: SteadyBase, name: str, s: float, elements) -> np.ndarray:
    """The residual at the nominal configuration with the parameter changed by ``s`` (a blade
    property leaves the aerodynamic loads of a configuration as they are: the structure's part)."""
    if name in BLADE_PROPERTIES:  # the changed sections alone (the residual needs no assembled matrix)
        return residual(base, base.rb, base.config, None, fe=blade_sections(base.rb.fe, name, s, elements))
    rb, rho, _ = _variant(base, name, s, elements)
    return residual(base, rb, base.config, rho)


def point_at(base: SteadyBase, name: str, s: float, dc: np.ndarray, elements=None):
    """The point system with the parameter changed by ``s`` and the steady state moved to ``c0 + s
    dc`` (module docstring), the blade basis the nominal point's."""
    ps, st = base.ps, base.steady
    rb, rho, om = _variant(base, name, s, elements, support=True)
    config = displaced(base.config, s * dc)
    aero, _ = strip_state(base, config, rho, rb)
    steady = dataclasses.replace(st, u=configuration_displacement(rb.fe, config), configuration=config,
                                 air_density=rho, **aero)
    d = deflected_blade(rb, steady, ps.omega, base.mu, tol=NEWTON_TOL)
    return om.assemble_point(d.blade, d.steady, d.ksigma, d.klink, ps.wind_speed, ps.omega, ps.pitch,
                             tip_frame=ps.tip_frame, Phi=ps.Phi)


#: the parameters whose total derivative equals the held one (they leave the blade's steady state)
HELD_EXACTLY = frozenset({"damping"} | {n for n, g in GLOBAL_PARAMETERS.items() if g.part == "support"})


def total_derivatives(base: SteadyBase, mvs: list[ModeVectors], names, elements=None) -> dict:
    """``{name: (k,) dlambda/dp}`` of the modes ``mvs`` with the steady state's own change included
    (module docstring), for the parameters ``names`` not in :data:`HELD_EXACTLY` (a blade property
    of ``elements``, None: the whole blade)."""
    out = {}
    for name in names:
        if name in HELD_EXACTLY:
            continue
        h = BLADE_PROPERTIES[name].step if name in BLADE_PROPERTIES else GLOBAL_PARAMETERS[name].step
        dc = steady_derivative(base, name, elements)
        plus, minus = (point_at(base, name, s, dc, elements).mbc for s in (h, -h))
        out[name] = np.array([mbc_derivative(mv, plus, minus, h) for mv in mvs])
    return out


def point_totals(om, ps, res, base: SteadyBase | None = None) -> dict:
    """``{name: (k,) dlambda/dp}`` with the steady state's own change included for the parameters of
    the point's sensitivities ``res`` (:class:`~windflutter.sensitivity.point.PointSensitivity`): the
    blade properties over the whole blade and the global parameters; those of :data:`HELD_EXACTLY`
    are the held ones.  ``base``: the point's :func:`steady_base`, when already built."""
    names = list(res.blade) + list(res.globals_)
    if not res.modes or not names:
        return {}
    base = steady_base(om, ps) if base is None else base
    mvs = res.vectors if res.vectors is not None else mode_vectors(ps.mbc, [m.eigenvalue for m in res.modes])
    out = {n: (res.blade[n].sum(axis=1) if n in res.blade else res.globals_[n]) for n in names if n in HELD_EXACTLY}
    out.update(total_derivatives(base, mvs, [n for n in names if n not in HELD_EXACTLY]))
    return {n: out[n] for n in names}


def segment_elements(station: np.ndarray, segments) -> list[np.ndarray]:
    """The blade elements (indices) of each spanwise segment ``[a, b)`` of ``segments`` (r/R edges; the
    last one closed), by the elements' mid-span ``station``."""
    st = np.asarray(station, float)
    out = []
    for a, b in zip(segments[:-1], segments[1:]):
        sel = (st >= a) & (st < b) if b < segments[-1] else (st >= a)
        out.append(np.flatnonzero(sel))
    return out


def segment_totals(om, ps, res, segments, base: SteadyBase | None = None) -> dict:
    """``{property: (k, n_segments) dlambda/dp}`` with the steady state's own change included, for the
    blade properties of ``res`` over each spanwise segment (:func:`segment_elements`; an empty
    segment gives NaN); :data:`HELD_EXACTLY` ones (structural damping) are the held segment sums."""
    if not res.modes or not res.blade:
        return {}
    base = steady_base(om, ps) if base is None else base
    mvs = res.vectors if res.vectors is not None else mode_vectors(ps.mbc, [m.eigenvalue for m in res.modes])
    groups = segment_elements(res.station, segments)
    out = {}
    for name, held in res.blade.items():
        cols = []
        for el in groups:
            if not el.size:
                cols.append(np.full(len(mvs), np.nan + 0j))
            elif name in HELD_EXACTLY:
                cols.append(held[:, el].sum(axis=1))
            else:
                cols.append(total_derivatives(base, mvs, [name], elements=el)[name])
        out[name] = np.stack(cols, axis=1)
    return out
