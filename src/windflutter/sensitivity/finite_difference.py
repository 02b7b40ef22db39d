"""Finite-difference re-analyses: the reference of the design sensitivities (and their cost baseline).

Each changes the model's data by ``+h`` and ``-h``, rebuilds the point system (its blade basis
recomputed), solves its eigenproblem again (:func:`~windflutter.system.modes.point_modes`), names the
modes again and takes central differences of the eigenvalue of the mode with the same name.  It
shares no step of the perturbation formula (:mod:`windflutter.sensitivity.eigen`) and no element
derivative of :mod:`windflutter.sensitivity.point`.

* :func:`frozen_blade` / :func:`frozen_global`: the steady state held fixed (the assumption of the
  sensitivities): the changed blade on the nominal deflected shape with the nominal stress, strips
  and inflow (:meth:`~windflutter.system.operational.OperationalModel.assemble_point`), or the
  nominal blade on the changed turbine's support;
* :func:`full_reanalysis`: the turbine's data changed and the whole point recomputed, steady state
  included (what the frozen derivatives leave out shows in the difference);
* :func:`steady_reanalysis`: the same with the steady state iterated to a tighter tolerance and the
  blade basis held at the nominal point's (the reference of the total derivatives,
  :mod:`windflutter.sensitivity.steady`, which differentiate the reduced model).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from windflutter.sensitivity.parameters import BLADE_PROPERTIES, GLOBAL_PARAMETERS, blade_sections
from windflutter.system.modes import point_modes
from windflutter.structure.assembly import assemble_matrices
from windflutter.system.blade import RotorBlade
from windflutter.system.damping import blade_damping_matrix, blade_mu
from windflutter.sensitivity.point import damping_sections
from windflutter.sensitivity.steady import ROTOR_MASS, changed_rotor_blade
from windflutter.system.operational import OperationalModel
from windflutter.steady import SteadyOptions, steady_state
from windflutter.system.deflected import deflected_blade


def _by_name(modes) -> dict:
    return {m.identity_name: m.eigenvalue for m in modes}


def _difference(plus: dict, minus: dict, names, h: float) -> dict:
    """``{name: dlambda/dp}`` (NaN where a name is missing at either side)."""
    return {n: (plus[n] - minus[n]) / (2 * h) if n in plus and n in minus else complex(np.nan, np.nan)
            for n in names}


def changed_blade(om, ps, name: str, p: float, elements=None):
    """The point's blade (:class:`~windflutter.system.blade.RotorBlade`, deflected geometry) with the
    property ``name`` of ``elements`` changed by ``p``: sections and damping reassembled; its
    stiffness the nominal one plus the change of the assembled elastic stiffness."""

    rb = ps.blade
    fe = rb.fe
    mu = blade_mu(om.turbine) if om.options.damping == "file" else None
    if BLADE_PROPERTIES[name].change is None:  # structural damping of the elements
        D = rb.damping
        if mu is not None:
            sel = np.arange(len(fe.beam_conn)) if elements is None else np.atleast_1d(elements)
            sub = dataclasses.replace(damping_sections(fe, mu), beam_conn=fe.beam_conn[sel],
                                      beam_section=fe.beam_section[sel], beam_orient=fe.beam_orient[sel])
            D = D + p * assemble_matrices(sub)[1]
        return RotorBlade(fe, rb.struct, rb.sections, rb.apex, rb.axis, damping=D)
    fe2 = blade_sections(fe, name, p, elements)
    M0, K0 = assemble_matrices(fe)
    M2, K2 = assemble_matrices(fe2)
    st = dataclasses.replace(rb.struct, fe=fe2, M=M2, K=(rb.struct.K + (K2 - K0)).tocsr())
    return RotorBlade(fe2, st, rb.sections, rb.apex, rb.axis, damping=blade_damping_matrix(fe2, mu))


def _point(om, ps, rb, steady=None, Phi=None):
    return om.assemble_point(rb, ps.steady if steady is None else steady, ps.ksigma, ps.klink, ps.wind_speed,
                             ps.omega, ps.pitch, tip_frame=ps.tip_frame, Phi=Phi)


def frozen_blade(om, ps, names, name: str, h: float, elements=None, max_hz: float = 2.5, Phi=None) -> dict:
    """``{mode name: dlambda/dp}`` of the blade property ``name`` (of ``elements``) by central
    differences of re-analyses about the nominal steady state; ``Phi``: the blade basis to hold
    (None: recomputed)."""
    out = [_by_name(point_modes(_point(om, ps, changed_blade(om, ps, name, s, elements), Phi=Phi), max_hz))
           for s in (h, -h)]
    return _difference(out[0], out[1], names, h)


def frozen_global(om, ps, names, name: str, h: float, max_hz: float = 2.5) -> dict:
    """``{mode name: dlambda/dp}`` of the global parameter ``name``: the nominal blade and steady state
    on the changed turbine's support (or with the changed air density in the strips, or the changed
    strips on the nominal deflected blade)."""

    g = GLOBAL_PARAMETERS[name]
    out = []
    for s in (h, -h):
        t, o = g.change(om.turbine, om.options, s)
        mod = OperationalModel(t, o)
        steady, rb = ps.steady, ps.blade
        if g.part == "aero" and steady is not None:
            steady = dataclasses.replace(steady, air_density=o.air_density)
        if g.part == "strips":  # the changed strips on the nominal deflected blade
            rb = RotorBlade(rb.fe, rb.struct, g.strips(rb.sections, s), rb.apex, rb.axis, damping=rb.damping)
            steady = dataclasses.replace(steady, sections=g.strips(steady.sections, s))
        out.append(_by_name(point_modes(_point(mod, ps, rb, steady), max_hz)))
    return _difference(out[0], out[1], names, h)


def blade_data(turbine, name: str, p: float):
    """``turbine`` with the blade property ``name`` changed by ``p`` at every station of its beam
    properties (the whole blade); ``damping``: its stiffness-proportional coefficients times ``1 + p``."""
    if BLADE_PROPERTIES[name].change is None:
        d = turbine.blade.damping
        if d is None or d.mu is None:
            return turbine
        blade = dataclasses.replace(turbine.blade, damping=dataclasses.replace(d, mu=np.asarray(d.mu, float) * (1 + p)))
        return dataclasses.replace(turbine, blade=blade)
    beam = turbine.blade.beam
    K, M = np.array(beam.stiffness, float), np.array(beam.mass, float)
    change = BLADE_PROPERTIES[name].change
    for j in range(K.shape[0]):
        K[j], M[j] = change(K[j], M[j], p)
    blade = dataclasses.replace(turbine.blade, beam=dataclasses.replace(beam, stiffness=K, mass=M))
    return dataclasses.replace(turbine, blade=blade)


def full_reanalysis(om, wind_speed: float, names, name: str, h: float, max_hz: float = 2.5) -> dict:
    """``{mode name: dlambda/dp}`` by whole re-analyses of the changed turbine at ``wind_speed``
    (steady state recomputed): a blade property over the whole blade or a global parameter."""

    out = []
    for s in (h, -h):
        if name in GLOBAL_PARAMETERS:
            t, o = GLOBAL_PARAMETERS[name].change(om.turbine, om.options, s)
        else:
            t, o = blade_data(om.turbine, name, s), om.options
        out.append(_by_name(point_modes(OperationalModel(t, o).at(wind_speed), max_hz)))
    return _difference(out[0], out[1], names, h)


def changed_model(om, name: str, s: float) -> OperationalModel:
    """The operating-point model of the turbine with the parameter ``name`` changed by ``s`` (a blade
    property over the whole blade: the turbine's beam data changed and the blade meshed again)."""
    if name in GLOBAL_PARAMETERS:
        return OperationalModel(*GLOBAL_PARAMETERS[name].change(om.turbine, om.options, s))
    return OperationalModel(blade_data(om.turbine, name, s), om.options)


def _segment_model(om, ps, name: str, s: float, elements):
    """(model, undeformed blade at the point's pitch) with the blade property ``name`` of the beam
    elements ``elements`` changed by ``s`` (the FE sections themselves: the turbine's data are per
    station, not per element); the support's damping with the changed rotor mass."""
    mu = blade_mu(om.turbine) if om.options.damping == "file" else None
    mod = om
    if name in ROTOR_MASS and om.options.part != "rotor":
        mod = om.with_rotor_mass(om.rotor_rigid_mass(blade=changed_rotor_blade(om.blade(0.0), name, s, elements)))
    return mod, changed_rotor_blade(om.blade(ps.pitch), name, s, elements, mu)


def steady_reanalysis(om, ps, names, name: str, h: float, max_hz: float = 2.5, tol: float = 1e-9,
                      elements=None) -> dict:
    """``{mode name: dlambda/dp}`` by re-analyses of the changed turbine (:func:`changed_model`) at the
    point's wind speed, rotor speed and pitch: the steady state iterated from the start to ``tol``
    (:func:`~windflutter.steady.steady_state`, co-rotational beam, BEM), the blade linearized about
    it (:func:`~windflutter.system.deflected.deflected_blade`) on the nominal point's blade basis.
    A parameter of the strips (the pitch axis) changes them by its own ``strips`` function (the
    turbine data's pitch axis interpolates differently: by up to 3.5 % of the change at the tip).
    ``elements``: a blade property of those beam elements only (:func:`_segment_model`)."""
    out = []
    g = GLOBAL_PARAMETERS.get(name)
    for s in (h, -h):
        if elements is not None:
            mod, rb = _segment_model(om, ps, name, s, elements)
        else:
            mod = om if g is not None and g.part == "strips" else changed_model(om, name, s)
            rb = mod.blade(ps.pitch)
        o = mod.options
        if g is not None and g.part == "strips":
            rb = RotorBlade(rb.fe, rb.struct, g.strips(rb.sections, s), rb.apex, rb.axis, damping=rb.damping)
        so = SteadyOptions(deflection=True, corotational=True, tol=tol, max_iterations=300,
                           bem={"high_thrust": o.high_thrust})
        st = steady_state(rb.fe, rb.struct, rb.sections, mod.rotor, ps.wind_speed, ps.omega, n_blades=mod.n_blades,
                          air_density=o.air_density, options=so)
        d = deflected_blade(rb, st, ps.omega, blade_mu(mod.turbine) if o.damping == "file" else None)
        p = mod.assemble_point(d.blade, d.steady, d.ksigma, d.klink, ps.wind_speed, ps.omega, ps.pitch,
                               tip_frame=ps.tip_frame, Phi=ps.Phi)
        out.append(_by_name(point_modes(p, max_hz)))
    return _difference(out[0], out[1], names, h)
