"""The analysis configuration of ``windflutter run``: what to compute, how, and what to write.

An analysis config is a small YAML file.  Every field has a documented default (the bundled
``data/analysis_default.yaml`` lists them all, with comments); a user file only states what it
changes.  Each field is **declared once**, in the dataclasses below, with its
:class:`~windflutter.schema.Spec` (kind, bounds, unit, choices, doc); :func:`config_from_dict`
is driven by those declarations, and the command-line flags of every command are checked by the
same specs (:mod:`windflutter.cli.options`).  Adding an option is one declaration (plus its line
in the default YAML and the reference, which a test keeps in step).

Validation is strict: an unknown key, a value of the wrong kind, a non-finite number or one out
of its declared range raises :class:`~windflutter.errors.InputError` naming the dotted field
(``rotor_speed.max_rpm``), the value and what was expected.  Every size (wind speeds, grid
points, elements, modes, frames, dpi) is bounded here, before any work starts.  The rules that
tie fields together are the ``_rule_*`` functions at the end.  Reference: ``docs/config_reference.md``.

Units at this edge follow the engineer's habits: wind speed m/s, rotor speed RPM, frequencies
Hz.  :class:`AnalysisConfig` keeps them as given; the workflow converts to SI.
"""

from windflutter.config.declarations import (  # noqa: F401
    AERO_VARIANTS,
    SEARCH_METHODS,
    MODEL_TYPES,
    MODEL_PARTS,
    DAMPING_MODELS,
    DRIVETRAINS,
    CIRCULATIONS,
    STRUCTURES,
    PLOT_FORMATS,
    REDUCTIONS,
    AERO_DISTRIBUTIONS,
    MAX_RPM,
    MAX_WIND_SPEED,
    MAX_WIND_SPEEDS,
    MAX_GRID_POINTS,
    MAX_BLADE_ELEMENTS,
    MAX_MODES,
    MAX_AIR_DENSITY,
    RotorSpeedConfig,
    ModelConfig,
    DampingConfig,
    SolverConfig,
    CampbellConfig,
    OperatingConfig,
    OutputConfig,
    AnalysisConfig,
    declared_fields,
    field_spec,
    field_specs,
)
from windflutter.config.validation import (  # noqa: F401
    RULES,
    config_from_dict,
    check_config,
    n_points_for_step,
    default_config_text,
    default_config,
    load_config,
)
