"""`windflutter modes TURBINE`: natural frequencies with a label per mode.

The options are those of :func:`windflutter.api.modes` (same names with ``--``, same checks); the
model is the beam model unless ``--model shell``, as for every command.
"""

from __future__ import annotations

import argparse
import json

from windflutter.config.commands import DEFAULT_MODEL, MESH_DEFAULTS, MESH_OPTIONS, MODES_OPTIONS
from windflutter.cli.options import Flag, add_flags, command_values


def _flag(key: str) -> str:
    return "--" + key.replace("_", "-")


def _mesh_flag(key: str) -> Flag:
    if key == "n_span":  # the config's model.n_aero_sections
        return Flag("--n-span", "model.n_aero_sections", metavar="N", help="blade elements along the span")
    return Flag(_flag(key), spec=MESH_OPTIONS[key], default=MESH_DEFAULTS[key])


#: the mesh flags of `modes` and `mesh`
MESH_FLAGS = tuple(_mesh_flag(k) for k in MESH_OPTIONS)

FLAGS = (
    Flag("--rpm", spec=MODES_OPTIONS["rpm"], default=0.0),
    Flag("--n", spec=MODES_OPTIONS["n"], default=10),
) + MESH_FLAGS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("modes", help="natural frequencies and mode labels of a turbine, blade or tower",
                       description=f"Natural frequencies and mode labels (the {DEFAULT_MODEL} model unless "
                                   "--model shell).")
    p.add_argument("turbine", help="turbine file (windIO, OpenFAST .fst, HAWC2 .htc) or bundled name (e.g. nrel5mw)")
    add_flags(p, FLAGS)
    p.add_argument("--json", action="store_true", help='print {"frequencies_hz": [...], "labels": [...]}')
    p.set_defaults(func=run)


def settings_from_args(args: argparse.Namespace, values: dict | None = None):
    """:class:`~windflutter.mesh.settings.MeshSettings` from the mesh flags (checked by their specs;
    errors name the flag)."""
    from windflutter.api import mesh_settings  # noqa: PLC0415

    v = values if values is not None else command_values(args, MESH_FLAGS, with_paths=True)
    return mesh_settings({k: v.get(k) for k in MESH_OPTIONS}, name=_flag)


def load(name: str):
    """A turbine from a path or bundled name (:func:`windflutter.api.load_turbine`)."""
    from windflutter.api import load_turbine  # noqa: PLC0415

    return load_turbine(name)


def run(args: argparse.Namespace) -> int:
    from windflutter.cli.warn import one_line_warnings  # noqa: PLC0415
    from windflutter.mesh.analysis import turbine_modes  # noqa: PLC0415

    v = command_values(args, FLAGS, with_paths=True)
    settings = settings_from_args(args, v)  # every flag checked before the turbine is read
    with one_line_warnings("windflutter modes"):
        turbine = load(args.turbine)
        res = turbine_modes(turbine, settings, n_modes=v["n"], rpm=v["rpm"])
    if args.json:
        print(json.dumps({"frequencies_hz": [float(f) for f in res.frequencies_hz], "labels": res.labels}))
        return 0
    print(f"{turbine.name}: {v['part']}, {settings.model} model, {res.fe.n_nodes} nodes, "
          f"{res.struct.nq} DOF, {v['rpm']:g} rpm")
    print(f"{'mode':>4}  {'freq (Hz)':>10}  label")
    for i, (f, lab) in enumerate(zip(res.frequencies_hz, res.labels), 1):
        print(f"{i:>4}  {f:>10.4f}  {lab}")
    return 0
