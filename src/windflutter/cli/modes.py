"""`windflutter modes TURBINE`: natural frequencies with a label per mode."""

from __future__ import annotations

import argparse
import json

import numpy as np


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("modes", help="natural frequencies and mode labels of a turbine, blade or tower")
    p.add_argument("turbine", help="windIO/seed turbine file or bundled name (e.g. nrel5mw)")
    p.add_argument("--rpm", type=float, default=0.0, help="rotor speed (rev/min); >0 adds centrifugal stiffening and spin softening")
    p.add_argument("--part", choices=("blade", "tower", "turbine", "rotor"), default="turbine")
    p.add_argument("--model", choices=("shell", "beam"), default="shell")
    p.add_argument("--n", type=int, default=10, help="number of modes (default 10)")
    p.add_argument("--pitch", type=float, default=0.0, help="blade pitch (deg)")
    p.add_argument("--azimuth", type=float, default=0.0, help="rotor azimuth of blade 0 (deg, 0 = up)")
    p.add_argument("--n-chord", type=int, default=None, help="shell elements around a blade section")
    p.add_argument("--n-span", type=int, default=None, help="blade elements along the span")
    p.add_argument("--tower-model", choices=("shell", "beam"), default="shell")
    p.add_argument("--json", action="store_true", help='print {"frequencies_hz": [...], "labels": [...]}')
    p.set_defaults(func=run)


def settings_from_args(args: argparse.Namespace):
    from windflutter.mesh.settings import MeshSettings

    kw = dict(model=args.model, part=args.part, pitch=float(np.radians(args.pitch)),
              azimuth=float(np.radians(args.azimuth)), tower_model=args.tower_model)
    if args.n_chord is not None:
        kw["n_chord"] = args.n_chord
    if args.n_span is not None:
        kw["n_span"] = args.n_span
    return MeshSettings(**kw)


def load(name: str):
    """A turbine from a path or bundled name (the input engineer's reader)."""
    from windflutter.model.windio import load_turbine

    return load_turbine(name)


def run(args: argparse.Namespace) -> int:
    from windflutter.errors import InputError
    from windflutter.mesh.analysis import turbine_modes

    if args.n < 1:
        raise InputError("--n", args.n, "a positive number of modes")
    turbine = load(args.turbine)
    res = turbine_modes(turbine, settings_from_args(args), n_modes=args.n, rpm=args.rpm)
    if args.json:
        print(json.dumps({"frequencies_hz": [float(f) for f in res.frequencies_hz], "labels": res.labels}))
        return 0
    print(f"{turbine.name}: {args.part}, {args.model} model, {res.fe.n_nodes} nodes, "
          f"{res.struct.nq} DOF, {args.rpm:g} rpm")
    print(f"{'mode':>4}  {'freq (Hz)':>10}  label")
    for i, (f, lab) in enumerate(zip(res.frequencies_hz, res.labels), 1):
        print(f"{i:>4}  {f:>10.4f}  {lab}")
    return 0
