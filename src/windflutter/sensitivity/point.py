"""The design sensitivities of the named modes of one operating point.

:func:`point_sensitivities` gives ``dlambda/dp`` of each mode for

* every blade property of :data:`~windflutter.sensitivity.parameters.BLADE_PROPERTIES` at every
  element of the blade's beam mesh (the three blades changed alike: the rotor stays isotropic):
  the element's mass, stiffness, structural damping, Coriolis and spin-softening matrices
  differentiated by central differences of the element routines themselves
  (:func:`~windflutter.structure.beam.beam_global_matrices`,
  :func:`~windflutter.rotor.spin.beam_spin_elements`), all elements at once, and contracted with the
  mode's left and right vectors expanded to the blade's nodes (:mod:`windflutter.sensitivity.eigen`);
* the global parameters of :data:`~windflutter.sensitivity.parameters.GLOBAL_PARAMETERS`: central
  differences of the assembled multi-blade matrices, the support rebuilt from the changed turbine
  (tower, nacelle, drivetrain), the strip aerodynamics scaled (air density: every strip force is
  proportional to it at a fixed inflow) or the point reassembled with changed strips on its blade
  basis (pitch axis).

Held fixed (first-order perturbation of the point's linear system, not of its steady state): the
steady state -- the deflected shape, its stress (the initial-stress matrix), the inflow and the
strips' linearization --, the blade's reduction basis and the named modes' eigenvectors.  A
parameter that moves the steady state (a stiffer blade deflects less; a heavier one pulls harder
at the root) has a further effect through it that these derivatives leave out
(docs/sensitivity.md quantifies it for the NREL 5 MW).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from windflutter.rotor.spin import beam_spin_elements
from windflutter.sensitivity.eigen import (ModeVectors, blade_jacobians, blade_vectors, mbc_derivative, mode_vectors,
                                          pair_ratio, pair_vectors, system_derivative)
from windflutter.sensitivity.parameters import (BLADE_PROPERTIES, GLOBAL_PARAMETERS, blade_sections, check_parameters,
                                                unit_change)
from windflutter.structure.beam import beam_global_matrices
from windflutter.system.blade import RotorBlade
from windflutter.system.multiblade import BladeSystem, multiblade_system
from windflutter.structure.fem import BeamSection
from windflutter.system.damping import MU_FLOOR, blade_mu
from windflutter.system.support import fixed_frame
from windflutter.errors import InputError

#: a mode's first-order derivative is "not defined" for a parameter when that change couples it to
#: its nearest eigenvalue by more than this fraction of half their distance, ``2 sqrt(|kappa_ij
#: kappa_ji|) dp / |lambda_i - lambda_j|`` (:func:`~windflutter.sensitivity.eigen.pair_vectors`): a
#: pair near a veering or crossing, whose eigenvalues move as ``sqrt((Delta/2)^2 + kappa_ij kappa_ji
#: dp^2)``, not linearly
PAIR_LIMIT = 0.2


@dataclass
class PointSensitivity:
    """The sensitivities of the named modes of one point.

    ``modes`` the :class:`~windflutter.system.modes.ModeRecord` objects; ``blade[prop]`` (k, ne)
    complex ``dlambda/dp`` (1/s per unit of ``p``) of every mode and blade element;
    ``globals_[name]`` (k,) complex; ``station`` (ne,) the elements' mid-span radius over the tip
    radius; ``pair_ratio[name]`` (k,) the coupling of each mode to its nearest eigenvalue by the unit
    change of the parameter over the whole blade (:data:`PAIR_LIMIT`) and ``defined[name]`` (k,)
    whether it is below the limit; ``gap`` (k,) the distance to the nearest eigenvalue over
    ``|lambda|``, ``condition`` (k,) the eigenvalue's condition number.
    """

    wind_speed: float
    omega: float
    modes: list
    blade: dict = field(default_factory=dict)
    globals_: dict = field(default_factory=dict)
    station: np.ndarray | None = None
    pair_ratio: dict = field(default_factory=dict)
    defined: dict = field(default_factory=dict)
    #: ``{name: (k,) dlambda/dp}`` by whole re-analyses (steady state recomputed), when asked for
    total: dict = field(default_factory=dict)
    #: ``{property: (k, n_segments) dlambda/dp}`` with the steady state's own change, per spanwise
    #: segment of r/R (:func:`~windflutter.sensitivity.steady.segment_totals`), when asked for
    total_segments: dict = field(default_factory=dict)
    gap: np.ndarray | None = None
    condition: np.ndarray | None = None
    #: the modes' :class:`~windflutter.sensitivity.eigen.ModeVectors` (re-used by the total derivatives)
    vectors: list | None = None

    @property
    def names(self) -> list[str]:
        return [m.identity_name for m in self.modes]


def element_stations(om) -> np.ndarray:
    """(ne,) mid-element distance from the rotor apex over the tip radius (undeformed blade)."""
    fe = om.blade(0.0).fe
    x = np.asarray(fe.nodes, float) - np.asarray(om.rotor.hub_center, float)
    conn = np.asarray(fe.beam_conn, dtype=np.int64)
    r = np.linalg.norm(0.5 * (x[conn[:, 0]] + x[conn[:, 1]]), axis=1)
    return r / np.linalg.norm(x, axis=1).max()


def damping_sections(fe, mu):
    """``fe`` with each section stiffness ``S`` replaced by ``sqrt(diag(mu)) S sqrt(diag(mu))``:
    the element matrices of the blade's damping (:func:`windflutter.system.damping.
    blade_damping_matrix`, the same floor of the coefficients)."""

    r = np.sqrt(np.maximum(mu, MU_FLOOR * mu.max()))
    secs = [BeamSection(stiffness=r[:, None] * s.stiffness * r[None, :], mass=s.mass, name=s.name)
            for s in fe.beam_sections]
    return dataclasses.replace(fe, beam_sections=secs, masses=[], springs=[])


def _element_matrices(rb, fe, mu):
    """Per element (K, M, D, G1, Kr1) in global axes, (ne, 12, 12) each; D None without damping."""
    K, M, dofs = beam_global_matrices(fe)
    D = beam_global_matrices(damping_sections(fe, mu))[0] if mu is not None else None
    G, Kr, _ = beam_spin_elements(fe, rb.axis, rb.apex)
    G = 0.5 * (G - np.swapaxes(G, 1, 2))
    Kr = 0.5 * (Kr + np.swapaxes(Kr, 1, 2))
    return {"K": K, "M": M, "D": D, "G": G, "Kr": Kr}, dofs


def _expanded(ps, mvs: list[ModeVectors]):
    """Left and right vectors of the modes at the blade's nodes: dict of (k, N, n_dof) arrays --
    ``L`` (all of y), ``L0`` (the elastic part eta only), ``RM``, ``RC``, ``RC0``, ``RK``, ``RK0``."""
    rb = ps.blade
    B = rb.basis_full(ps.Phi)
    B = B.toarray() if hasattr(B, "toarray") else np.asarray(B)
    B0 = B[:, 6:]
    jac = blade_jacobians(ps.mbc, ps.fixed.L, ps.omega, rb.axis)
    out = {k: [] for k in ("L", "L0", "RM", "RC", "RC0", "RK", "RK0")}
    for mv in mvs:
        bv = blade_vectors(mv, ps.mbc, jac, ps.omega)
        out["L"].append(bv.l @ B.T)
        out["L0"].append(bv.l[:, 6:] @ B0.T)
        out["RM"].append(bv.rM @ B.T)
        out["RC"].append(bv.rC @ B.T)
        out["RC0"].append(bv.rC[:, 6:] @ B0.T)
        out["RK"].append(bv.rK @ B.T)
        out["RK0"].append(bv.rK[:, 6:] @ B0.T)
    return {k: np.array(v) for k, v in out.items()}


def _contract(V, dofs, left: str, mats, right: str) -> np.ndarray:
    """(k, ne) ``sum_b left_b[e]^T mats[e] right_b[e]`` over the blades."""
    Lg, Rg = V[left][:, :, dofs], V[right][:, :, dofs]  # (k, N, ne, 12)
    return np.einsum("kbei,eij,kbej->ke", Lg, mats, Rg, optimize=True)


def blade_derivatives(om, ps, mvs: list[ModeVectors], properties) -> dict:
    """``{property: (k, ne) dlambda/dp}`` of the blade properties at every element (module docstring)."""

    rb = ps.blade
    fe = rb.fe
    mu = blade_mu(om.turbine) if om.options.damping == "file" else None
    V = _expanded(ps, mvs)
    norms = np.array([mv.norm for mv in mvs])
    om_ = ps.omega
    out = {}
    nominal = None
    for name in properties:
        prop = BLADE_PROPERTIES[name]
        if prop.change is None:  # structural damping: d/d ln(mu) of each element's damping matrix
            if mu is None:
                out[name] = np.zeros((len(mvs), len(fe.beam_conn)), complex)
                continue
            if nominal is None:
                nominal = _element_matrices(rb, fe, mu)
            (mats, dofs) = nominal
            t = _contract(V, dofs, "L0", mats["D"], "RC0")
            out[name] = -t / norms[:, None]
            continue
        h = prop.step
        (p, dofs), (m, _) = (_element_matrices(rb, blade_sections(fe, name, s), mu) for s in (h, -h))
        d = {k: None if p[k] is None else (p[k] - m[k]) / (2 * h) for k in p}
        t = _contract(V, dofs, "L0", d["K"], "RK0") + _contract(V, dofs, "L", d["M"], "RM")
        if d["D"] is not None:
            t += _contract(V, dofs, "L0", d["D"], "RC0")
        t += om_ * _contract(V, dofs, "L", d["G"], "RC") - om_**2 * _contract(V, dofs, "L", d["Kr"], "RK")
        out[name] = -t / norms[:, None]
    return out


def _aero_scaled(bs: BladeSystem, structure, damping, factor: float) -> BladeSystem:
    """The blade system with its aerodynamic terms (everything but the structure's M, C, K) times
    ``factor``."""
    M0, K0 = structure
    return BladeSystem(M=M0 + factor * (bs.M - M0), C=damping + factor * (bs.C - damping), K=K0 + factor * (bs.K - K0),
                       F=factor * bs.F, Az=bs.Az, Bq=bs.Bq, Bv=bs.Bv)


def global_derivatives(om, ps, mvs: list[ModeVectors], names, models: dict | None = None) -> dict:
    """``{name: (k,) dlambda/dp}`` of the global parameters: central differences of the multi-blade
    matrices (the support rebuilt from the changed turbine, or the aerodynamics scaled).
    ``models``: a cache ``{(name, p): OperationalModel}`` of the changed turbines' models."""

    axis = om.rotor.shaft_axis
    out = {}
    for name in names:
        g = GLOBAL_PARAMETERS[name]
        h = g.step
        mbcs = []
        for s in (h, -h):
            if g.part == "strips":
                mbcs.append(changed_strips_point(om, ps, g.strips, s).mbc)
                continue
            if g.part == "aero":
                bs = _aero_scaled(ps.blade_system, ps.blade_structure, ps.blade_damping, 1.0 + s)
                mbcs.append(multiblade_system(ps.fixed, bs, ps.n_blades, ps.omega, axis))
                continue
            key = (name, s)
            mod = None if models is None else models.get(key)
            if mod is None:
                mod = om.variant(*g.change(om.turbine, om.options, s))
                if models is not None:
                    models[key] = mod
            mbcs.append(fixed_frame(mod.support(), mod.hub_mass(), axis, mod.drivetrain()))
        if g.part in ("aero", "strips"):
            out[name] = np.array([mbc_derivative(mv, mbcs[0], mbcs[1], h) for mv in mvs])
        else:
            out[name] = np.array([_fixed_derivative(mv, ps, mbcs[0], mbcs[1], h) for mv in mvs])
    return out


def changed_strips_point(om, ps, strips, s: float, Phi="nominal"):
    """The point ``ps`` rebuilt with the blade's strips changed by ``strips(sections, s)`` (the
    deflected blade's and the steady state's alike), the steady state held; ``Phi`` the blade basis
    (default the point's; None: recomputed); the aerodynamic states reduced as the point's."""
    rb, st = ps.blade, ps.steady
    rb2 = RotorBlade(rb.fe, rb.struct, strips(rb.sections, s), rb.apex, rb.axis, damping=rb.damping)
    st2 = None if st is None else dataclasses.replace(st, sections=strips(st.sections, s))
    return om.assemble_point(rb2, st2, ps.ksigma, ps.klink, ps.wind_speed, ps.omega, ps.pitch, tip_frame=ps.tip_frame,
                             Phi=ps.Phi if isinstance(Phi, str) else Phi, aero_projection=ps.aero_projection)


def _fixed_derivative(mv: ModeVectors, ps, plus, minus, h: float) -> complex:
    """``dlambda/dp`` of a change of the ground-fixed part alone (:class:`~windflutter.system.
    multiblade.FixedFrame`, its hub-motion map unchanged): it enters the multi-blade matrices as
    their ground-fixed block (the Coleman transformation is the identity there)."""
    if plus.size != minus.size or not np.allclose(plus.L, minus.L, rtol=0, atol=1e-12 * max(np.abs(plus.L).max(), 1)):
        raise ValueError("the hub-motion map of the ground-fixed part changed: not a ground-fixed-only parameter")
    n, nF = ps.mbc.M.shape[0], plus.size
    d = []
    for k in ("M", "C", "K"):
        D = np.zeros((n, n))
        D[:nF, :nF] = (getattr(plus, k) - getattr(minus, k)) / (2.0 * h)
        d.append(D)
    return system_derivative(mv, *d)


def point_sensitivities(om, ps, modes, blade_properties=None, global_parameters=None,
                        models: dict | None = None, eig: tuple | None = None) -> PointSensitivity:
    """The sensitivities of ``modes`` (the point's named modes, :func:`~windflutter.system.modes.
    point_modes` of ``ps``) of the point system ``ps`` of the operating-point model ``om``.

    ``blade_properties``, ``global_parameters``: names (None: all of
    :data:`~windflutter.sensitivity.parameters.BLADE_PROPERTIES` / ``GLOBAL_PARAMETERS``).
    ``eig``: the point's eigen-solve with left vectors, when already done
    (:func:`~windflutter.system.modes.state_eig`, shared with ``point_modes``).
    """
    props = check_parameters(blade_properties, BLADE_PROPERTIES, "blade_properties")
    globs = check_parameters(global_parameters, GLOBAL_PARAMETERS, "global_parameters")
    if len(ps.blade.fe.shell_conn):

        raise InputError("model", "shell", "beam blades (shell blades: windflutter.sensitivity.shell_results)")
    mvs = mode_vectors(ps.mbc, [m.eigenvalue for m in modes], eig=eig)
    res = PointSensitivity(wind_speed=ps.wind_speed, omega=ps.omega, modes=list(modes), station=element_stations(om),
                           gap=np.array([mv.gap for mv in mvs]), condition=np.array([mv.condition for mv in mvs]),
                           vectors=mvs)
    if not mvs:
        return res
    pairs = [pair_vectors(mv) for mv in mvs]
    every = mvs + [p[0] for p in pairs] + [p[1] for p in pairs]
    k = len(mvs)
    found = {}
    if props:
        found.update(blade_derivatives(om, ps, every, props))
    if globs:
        found.update(global_derivatives(om, ps, every, globs, models))
    for name, v in found.items():
        main = v[:k]
        whole = v.sum(axis=1) if v.ndim == 2 else v  # the blade properties: the whole blade's change
        unit = unit_change(name)
        ratio = np.array([pair_ratio(mv, whole[k + i], whole[2 * k + i], unit) for i, mv in enumerate(mvs)])
        (res.blade if v.ndim == 2 else res.globals_)[name] = main
        res.pair_ratio[name] = ratio
        res.defined[name] = ratio < PAIR_LIMIT
    return res
