"""The composition root: an analysis config -> the models and the solver of one ``(aero, method)`` case.

Every command that analyses a turbine (``run``, ``stability``, ``campbell``) builds its solver here,
from the one options vocabulary of :mod:`windflutter.config`:

* method ``p`` -> :class:`~windflutter.overspeed.OperationalStability`: the whole turbine
  in multi-blade coordinates with the drivetrain, unsteady (state-space) strip aerodynamics with the
  mean-load terms and local polar slopes, linearized about the deflected steady state, with the
  turbine files' structural damping (:class:`~windflutter.system.operational.OperationalOptions`);
* methods ``pk`` and ``thesis`` -> :class:`~windflutter.frozen.turbine.TurbineStability`: the
  seed's model (frozen azimuth, rotor locked to the nacelle, Theodorsen strips in the frequency
  domain, undeformed blades) with the config's options (:class:`~windflutter.frozen.turbine.
  TurbineOptions`, via :func:`~windflutter.frozen.turbine.options_from_config`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

from windflutter.aero.unsteady import UnsteadyOptions
from windflutter.config.declarations import BEAM_SPAN_ELEMENTS, SHELL_SPAN_ELEMENTS
from windflutter.errors import InputError
from windflutter.overspeed import OperationalStability, SearchSettings
from windflutter.system.operational import OperationalOptions


def mesh_settings(config) -> dict:
    """Mesh-setting overrides from ``model.part``, ``model.mesh_density``, ``model.n_aero_sections`` and,
    for shells, ``model.element_length``, ``model.reference_surface`` and ``model.tip_closure``: blade
    elements (= strips) along the span ``n_aero_sections * density``; shells without ``n_aero_sections``
    take theirs from the element length / density (null: the blade length / 100 at density 1,
    :func:`windflutter.mesh.settings.resolve_counts`); for shells at density != 1 also the elements
    around a section (default 40, kept even) and along / around the tower."""
    m = config.model
    d = m.mesh_density
    out: dict = {"part": m.part}
    if m.n_aero_sections is not None or m.type != "shell":
        out["n_span"] = max(4, int(round((m.n_aero_sections or BEAM_SPAN_ELEMENTS) * d)))
    if m.type != "shell":
        return out
    out["tip_closure"] = m.tip_closure
    out["reference_surface"] = m.reference_surface
    out["shell_shear"] = m.shell_shear
    if m.n_aero_sections is None:
        if m.element_length is not None:
            out["element_length"] = m.element_length / d
        elif d != 1.0:
            out["n_span"] = max(4, int(round(SHELL_SPAN_ELEMENTS * d)))
    if d != 1.0:
        if "element_length" not in out:
            out["n_chord"] = max(8, 2 * int(round(20 * d)))
        out["n_tower_circ"] = max(8, int(round(20 * d)))
        out["n_tower_axial"] = max(4, int(round(22 * d)))
    return out


def with_span_count(config):
    """``config`` with ``model.n_aero_sections`` filled for beams (null means 30 for them): for
    readers that take it as the beam's element count."""
    m = config.model
    if m.n_aero_sections is not None or m.type == "shell":
        return config
    return dataclasses.replace(config, model=dataclasses.replace(m, n_aero_sections=BEAM_SPAN_ELEMENTS))


def unsteady_options(config, aero: str):
    """The strip operator of method p for aero variant ``aero`` (viscous: the polars' local slopes;
    potential: a flat plate, 2 pi, no drag)."""
    s = config.solver
    return UnsteadyOptions(circulation=s.circulation, n_lag=s.n_lag,
                           polar="table" if aero == "viscous" else "flat_plate",
                           mean_loads=bool(s.mean_loads), dynamic_stall=bool(s.dynamic_stall and aero == "viscous"))


def operational_options(config, aero: str):
    """:class:`~windflutter.system.operational.OperationalOptions` of a config (method p)."""
    m, s = config.model, config.solver
    if m.type not in ("beam", "shell"):
        raise InputError("model.type", m.type, "'beam' or 'shell' for the turbine solver")
    if config.damping.model not in ("file", "none"):
        raise InputError("damping.model", config.damping.model, "file or none with method p (the turbine files' "
                         "damping; stiffness, rayleigh and modal belong to the seed's methods pk and thesis)")
    structure = resolved_structure(config)
    return OperationalOptions(model=m.type, part=m.part, mesh=mesh_settings(config),
                              basis_modes=None if s.reduction == "none" else s.basis_modes,
                              corrections=s.reduction == "mta", correction_tol=max(s.correction_tol, 1e-10),
                              drivetrain=m.drivetrain, aero=unsteady_options(config, aero),
                              deflection=bool(s.deflection), corotational=bool(s.corotational), structure=structure, induction=bool(s.induction),
                              high_thrust=s.high_thrust, damping=config.damping.model,
                              tower_damping=config.damping.tower_ratio,
                              air_density=config.air_density, aero_state_tol=s.aero_state_tol)


def resolved_structure(config) -> str:
    """``solver.structure`` with ``auto`` resolved: ``deflected`` for blades linearized about the
    deflected steady state (``solver.deflection``; beams: :mod:`windflutter.system.deflected`,
    shells: :mod:`windflutter.system.deflected_shell`), ``undeformed`` otherwise.  An explicit
    ``deflected`` without a deflected state is refused by the config's own rules
    (:func:`windflutter.config.check_config`)."""
    s = config.solver
    if s.structure == "auto":
        return "deflected" if bool(s.deflection) else "undeformed"
    return s.structure


def search_settings(config):
    """The rotor-speed sweep of method p from the config's rotor_speed and campbell sections."""
    r = config.rotor_speed
    step = (r.max_rpm - r.min_rpm) / max(r.n_points - 1, 1)
    return SearchSettings(max_rpm=r.max_rpm, rpm_step=step, tolerance_rpm=r.tolerance_rpm,
                          max_hz=config.campbell.max_hz, full_sweep=r.full_sweep, max_tip_mach=r.max_tip_mach)


def turbine_options(config, aero: str, method: str):
    """The seed's solver options (methods pk, thesis) of one case, with the mesh."""
    from windflutter.frozen.turbine import options_from_config

    opts = options_from_config(with_span_count(config), aero, method)
    return dataclasses.replace(opts, mesh={**opts.mesh, **mesh_settings(config)})


@dataclasses.dataclass(frozen=True)
class Method:
    """A search method of the registry :data:`METHODS`: ``options(config, aero)`` checks the case's
    options before any turbine is read and returns them; ``solver(turbine, config, aero)`` builds the
    solver of one ``(aero, method)`` case (``.analyse_operating_point(V, rpm_grid)``);
    ``config_grid``: whether it sweeps the config's rotor-speed grid (the seed's searches) or its own
    from the operating rotor speed (method p)."""

    name: str
    options: Callable
    solver: Callable
    config_grid: bool
    doc: str = ""


def _p_solver(turbine, config, aero: str):
    return OperationalStability(turbine, operational_options(config, aero), search_settings(config))


def _seed_solver(method: str):
    def build(turbine, config, aero: str):
        from windflutter.frozen.turbine import TurbineStability

        return TurbineStability(turbine, turbine_options(config, aero, method))
    return build


#: the search methods, by the name the config's ``method`` field and ``--method`` take
METHODS: dict[str, Method] = {
    "p": Method("p", operational_options, _p_solver, config_grid=False,
                doc="the whole turbine in multi-blade coordinates, linearized about its steady state"),
    "pk": Method("pk", lambda config, aero: turbine_options(config, aero, "pk"), _seed_solver("pk"), config_grid=True,
                 doc="the seed's frozen-azimuth model, p-k tracking and root finding"),
    "thesis": Method("thesis", lambda config, aero: turbine_options(config, aero, "thesis"), _seed_solver("thesis"),
                     config_grid=True, doc="the seed's frozen-azimuth model, the thesis's 8-k search"),
}


def method(name: str) -> Method:
    """The registered search method ``name`` (:data:`METHODS`)."""
    if name not in METHODS:
        raise InputError("method", name, f"one of {', '.join(METHODS)}")
    return METHODS[name]


def case_options(config, aero: str, method_name: str):
    """The checked solver options of one ``(aero, method)`` case (before any turbine is read)."""
    return method(method_name).options(config, aero)


def stability_analysis(turbine, config, aero: str, method_name: str):
    """The solver of one ``(aero, method)`` case: ``.analyse_operating_point(V, rpm_grid)``."""
    return method(method_name).solver(turbine, config, aero)


__all__ = ["METHODS", "Method", "method", "case_options", "mesh_settings", "with_span_count", "unsteady_options", "operational_options", "search_settings", "turbine_options",
           "stability_analysis"]
