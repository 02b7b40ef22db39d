"""`windflutter modes TURBINE`: natural frequencies with a label per mode."""

from __future__ import annotations

import argparse
import json

import numpy as np

from windflutter.cli.options import Flag, add_flags, command_values
from windflutter.config import MAX_MODES, MAX_RPM
from windflutter.schema import Spec

_MESH_MODELS = ("shell", "beam")
_PARTS = ("turbine", "blade", "tower", "rotor")

#: the mesh flags of `modes` and `mesh` (``--n-span`` is the config's model.n_aero_sections)
MESH_FLAGS = (
    Flag("--part", spec=Spec("choice", choices=_PARTS, doc="which part: turbine, blade (root clamped), tower "
                             "(rotor-nacelle lumped) or rotor (hub clamped)"), default="turbine"),
    Flag("--model", spec=Spec("choice", choices=_MESH_MODELS, doc="shell (composite shells) or beam"), default="shell"),
    Flag("--pitch", spec=Spec("float", lower=-180.0, upper=180.0, unit="deg", doc="blade pitch"), default=0.0),
    Flag("--azimuth", spec=Spec("float", lower=-360.0, upper=360.0, unit="deg",
                                doc="rotor azimuth of blade 0 (0 = up)"), default=0.0),
    Flag("--n-chord", spec=Spec("int", lower=8, upper=400, doc="shell elements around a blade section")),
    Flag("--n-span", "model.n_aero_sections", metavar="N", help="blade elements along the span"),
    Flag("--tower-model", spec=Spec("choice", choices=_MESH_MODELS, doc="tower of a shell model: shell or beam"),
         default="shell"),
)

FLAGS = (
    Flag("--rpm", spec=Spec("float", lower=0.0, upper=MAX_RPM, unit="RPM", doc="rotor speed; > 0 adds "
                            "centrifugal stiffening and spin softening"), default=0.0),
    Flag("--n", spec=Spec("int", lower=1, upper=MAX_MODES, doc="number of modes"), default=10),
) + MESH_FLAGS


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("modes", help="natural frequencies and mode labels of a turbine, blade or tower")
    p.add_argument("turbine", help="windIO/seed turbine file or bundled name (e.g. nrel5mw)")
    add_flags(p, FLAGS)
    p.add_argument("--json", action="store_true", help='print {"frequencies_hz": [...], "labels": [...]}')
    p.set_defaults(func=run)


def settings_from_args(args: argparse.Namespace, values: dict | None = None):
    """:class:`~windflutter.mesh.settings.MeshSettings` from the mesh flags (checked by their specs)."""
    from windflutter.mesh.settings import MeshSettings

    v = values if values is not None else command_values(args, MESH_FLAGS, with_paths=True)
    kw = dict(model=v["model"], part=v["part"], pitch=float(np.radians(v["pitch"])),
              azimuth=float(np.radians(v["azimuth"])), tower_model=v["tower_model"])
    for k in ("n_chord", "n_span"):
        if v.get(k) is not None:
            kw[k] = v[k]
    return MeshSettings(**kw)


def load(name: str):
    """A turbine from a path or bundled name (the input engineer's reader)."""
    from windflutter.model.windio import load_turbine

    return load_turbine(name)


def run(args: argparse.Namespace) -> int:
    from windflutter.mesh.analysis import turbine_modes

    v = command_values(args, FLAGS, with_paths=True)
    settings = settings_from_args(args, v)  # every flag checked before the turbine is read
    turbine = load(args.turbine)
    res = turbine_modes(turbine, settings, n_modes=v["n"], rpm=v["rpm"])
    if args.json:
        print(json.dumps({"frequencies_hz": [float(f) for f in res.frequencies_hz], "labels": res.labels}))
        return 0
    print(f"{turbine.name}: {v['part']}, {v['model']} model, {res.fe.n_nodes} nodes, "
          f"{res.struct.nq} DOF, {v['rpm']:g} rpm")
    print(f"{'mode':>4}  {'freq (Hz)':>10}  label")
    for i, (f, lab) in enumerate(zip(res.frequencies_hz, res.labels), 1):
        print(f"{i:>4}  {f:>10.4f}  {lab}")
    return 0
