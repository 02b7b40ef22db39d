"""The options of the ``modes`` and ``mesh`` commands and of :func:`windflutter.api.modes` /
:func:`windflutter.api.mesh_settings`: one declaration (keyword -> :class:`~windflutter.schema.Spec`)
read by the API's checks and the command line's flags.

They live here, beside the analysis config's declarations, rather than in :mod:`windflutter.api`, so
that building the command line's parser (``windflutter --help``) does not import the whole API.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from windflutter.config.declarations import MAX_MODES, MAX_RPM, field_spec
from windflutter.schema import Spec

__all__ = ["MESH_MODELS", "MESH_PARTS", "DEFAULT_MODEL", "SHELL_ONLY", "MESH_OPTIONS", "MESH_DEFAULTS", "MODES_OPTIONS"]

MESH_MODELS = ("beam", "shell")
MESH_PARTS = ("turbine", "blade", "tower", "rotor")
#: the model every command builds unless told otherwise
DEFAULT_MODEL = "beam"
#: the options that only the shell model has
SHELL_ONLY = ("n_chord", "tower_model", "tip_closure", "element_length", "reference_surface", "shell_shear")

#: options of :func:`modes` and ``windflutter mesh`` (keyword -> check); the CLI flag of each is the
#: keyword with ``--`` and ``-`` for ``_`` (``n_span`` is the config field ``model.n_aero_sections``)
MESH_OPTIONS: dict[str, Spec] = {
    "part": Spec("choice", choices=MESH_PARTS, doc="which part: turbine, blade (root clamped), tower "
                 "(rotor-nacelle lumped) or rotor (blades and hub, the hub clamped: no drivetrain in a modal analysis)"),
    "model": Spec("choice", choices=MESH_MODELS, doc="beam (Timoshenko beams, the default of every command) "
                  "or shell (composite shells)"),
    "pitch": Spec("float", lower=-180.0, upper=180.0, unit="deg", doc="blade pitch"),
    "azimuth": Spec("float", lower=-360.0, upper=360.0, unit="deg", doc="rotor azimuth of blade 0 (0 = up)"),
    "n_chord": Spec("int", lower=8, upper=400, nullable=True, doc="shell model: elements around a blade section"),
    "n_span": field_spec("model.n_aero_sections"),
    "tower_model": Spec("choice", choices=MESH_MODELS, nullable=True, doc="shell model: the tower as shell "
                        "(default) or beam"),
    "tip_closure": dataclasses.replace(field_spec("model.tip_closure"), nullable=True),
    "element_length": field_spec("model.element_length"),
    "reference_surface": dataclasses.replace(field_spec("model.reference_surface"), nullable=True),
    "shell_shear": dataclasses.replace(field_spec("model.shell_shear"), nullable=True),
}
MESH_DEFAULTS: dict[str, Any] = {"part": "turbine", "model": DEFAULT_MODEL, "pitch": 0.0, "azimuth": 0.0,
                                 "n_chord": None, "n_span": None, "tower_model": None, "tip_closure": None,
                                 "element_length": None, "reference_surface": None, "shell_shear": None}

#: the options of :func:`modes` besides the mesh
MODES_OPTIONS: dict[str, Spec] = {
    "rpm": Spec("float", lower=0.0, upper=MAX_RPM, unit="RPM", doc="rotor speed; > 0 adds centrifugal "
                "stiffening and spin softening"),
    "n": Spec("int", lower=1, upper=MAX_MODES, doc="number of modes"),
}
