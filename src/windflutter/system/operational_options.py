"""How the operating-point model (:mod:`windflutter.system.operational`) is built: its options, and the
error for a turbine without an operating curve."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from windflutter.aero.momentum import HIGH_THRUST
from windflutter.aero.unsteady import UnsteadyOptions
from windflutter.errors import InputError, check_choice

PARTS = ("turbine", "rotor")
DRIVETRAINS = ("flexible", "rigid", "locked")


def missing_curve_error(turbine) -> InputError:
    """The error for a turbine without an operating curve: it names the supplement key that gives
    one and the file it goes in (an OpenFAST deck or HAWC2 model carries no operating curve)."""
    src = str(getattr(turbine, "source", "") or "")
    stem = src.rsplit("/", 1)[-1].rsplit(".", 1)[0] if src else "TURBINE"
    return InputError("windflutter.operating_curve", None,
                      "an operating curve (wind speed -> rotor speed, pitch) for the operating points: the turbine "
                      "files give none; add 'windflutter: {operating_curve: {file: TABLE.csv, format: openfast_csv}}' "
                      "(or an inline table of wind_speed, rotor_speed_rpm, pitch_deg) in a supplement "
                      f"{stem}.windflutter.yaml next to the turbine file (docs/turbine_input.md), or analyse "
                      "without one with --method pk or thesis (pitch 0)", src or None)


@dataclass(frozen=True)
class OperationalOptions:
    """How the operating-point model is built.

    Parameters
    ----------
    model : ``"beam"`` or ``"shell"`` blades (and tower).
    part : ``"turbine"`` (rotor on the flexible tower) or ``"rotor"`` (rotor on a fixed nacelle, no
        tower -- the config's ``model.part: rotor``; the shaft as ``drivetrain`` says: free with
        ``flexible``/``rigid``, HAWCStab2's / OpenFAST's rotor-only analysis, the hub clamped with
        ``locked``, the seed's methods' only case).
    mesh : extra :class:`~windflutter.mesh.settings.MeshSettings` fields.
    basis_modes : fixed-interface blade modes in the basis (the config's ``solver.basis_modes``); ``None``: full order.
    corrections : add static corrections (modal truncation augmentation) of the aerodynamic loads
        of the retained modes to the blade basis; ``correction_tol`` is their relative cut-off.
    support_modes : support modes (+ 6 hub-load corrections); ``None``: its full constrained
        coordinates up to :data:`windflutter.system.operational.SUPPORT_FULL_ORDER_LIMIT` DOFs (beam towers), 30 modes above
        (shell towers).
    drivetrain : ``"flexible"`` (shaft spring, generator inertia), ``"rigid"`` or ``"locked"``.
    aero : the strip operator's options (:class:`~windflutter.aero.unsteady.UnsteadyOptions` for
        the state-space model; :class:`~windflutter.aero.strip.AeroOptions` for the thesis's
        quasi-steady strips), ``None`` for no aerodynamics.
    deflection : linearize about the deflected steady state (False: the undeformed blade).
    corotational : beam blades: the steady state on the co-rotational beam (exact for any reference
        line of the sections, :mod:`windflutter.steady.exact`); False: the linear structure with
        second-order load corrections (shell blades always).
    structure : ``"undeformed"`` (the blade on its undeformed geometry with the geometric stiffness
        of the steady stress) or ``"deflected"`` (beam blades: the co-rotational beam
        re-equilibrated and linearized about the deflected shape, with the initial-stress matrix of
        all its stress resultants, :mod:`windflutter.system.deflected`; shell blades: the shell
        carried to its deflected steady shape, its elements turned with it, with the membrane stress of
        the deformed blade's loads, :mod:`windflutter.system.deflected_shell`).
    induction : steady BEM induction in the inflow.
    high_thrust : its thrust--induction relation (:mod:`windflutter.aero.momentum`): ``"buhl"``
        (OpenFAST AeroDyn's), ``"madsen"`` (HAWC2's and HAWCStab2's) or ``"momentum"``.
    damping : ``"file"`` (the turbine files' structural damping) or ``"none"``.
    tower_damping : modal damping ratio (-) of every tower mode in place of the files' ratios
        (``None``: the files'; e.g. to match another code's tower model).
    air_density : kg/m^3.
    aero_state_tol : each blade's aerodynamic lag states reduced by balanced truncation, Hankel
        singular values below this fraction of the largest dropped, their static part kept
        (:func:`~windflutter.system.blade_aero.balanced_projection`); ``None``: every state (the reference).
    """

    model: str = "beam"
    part: str = "turbine"
    mesh: dict = field(default_factory=dict)
    basis_modes: int | None = 20
    corrections: bool = False
    correction_tol: float = 1e-6
    support_modes: int | None = None
    drivetrain: str = "flexible"
    aero: object = "default"
    deflection: bool = True
    corotational: bool = True
    structure: str = "undeformed"
    induction: bool = True
    high_thrust: str = "buhl"
    damping: str = "file"
    tower_damping: float | None = None
    air_density: float = 1.225
    aero_state_tol: float | None = None

    def __post_init__(self):
        check_choice("model", self.model, ("beam", "shell"))
        check_choice("part", self.part, PARTS)
        check_choice("drivetrain", self.drivetrain, DRIVETRAINS)
        check_choice("damping", self.damping, ("file", "none"))
        check_choice("structure", self.structure, ("undeformed", "deflected"))

        check_choice("high_thrust", self.high_thrust, HIGH_THRUST)
        if self.structure == "deflected" and not self.deflection:
            raise InputError("structure", self.structure, "'undeformed' unless the blades are linearized about the "
                                                          "deflected steady state (deflection on)")
        if self.aero == "default":
            object.__setattr__(self, "aero", UnsteadyOptions())
        for name in ("basis_modes", "support_modes"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, (int, np.integer)) and v >= 1):
                raise InputError(name, v, "a positive number of modes, or None (full order)")
        if not (np.isfinite(self.air_density) and self.air_density > 0):
            raise InputError("air_density", self.air_density, "a positive density (kg/m^3)")
        if self.aero_state_tol is not None and not (np.isfinite(self.aero_state_tol) and 0 < self.aero_state_tol < 1):
            raise InputError("solver.aero_state_tol", self.aero_state_tol, "a relative cut-off in (0, 1), or null (every state)")
        if self.tower_damping is not None and not (np.isfinite(self.tower_damping) and 0 <= self.tower_damping < 1):
            raise InputError("damping.tower_ratio", self.tower_damping, "a damping ratio in [0, 1) or null")
