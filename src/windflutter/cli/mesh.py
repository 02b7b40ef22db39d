"""`windflutter mesh TURBINE --vtk OUT.vtu --bdf OUT.bdf`: build and export the FE model."""

from __future__ import annotations

import argparse

from windflutter.cli.modes import load, settings_from_args


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("mesh", help="build a turbine FE model and export it (VTK / NASTRAN BDF)")
    p.add_argument("turbine", help="windIO/seed turbine file or bundled name (e.g. nrel5mw)")
    p.add_argument("--vtk", help="write the mesh to this .vtu file")
    p.add_argument("--bdf", help="write the model to this NASTRAN .bdf file")
    p.add_argument("--part", choices=("blade", "tower", "turbine", "rotor"), default="turbine")
    p.add_argument("--model", choices=("shell", "beam"), default="shell")
    p.add_argument("--pitch", type=float, default=0.0, help="blade pitch (deg)")
    p.add_argument("--azimuth", type=float, default=0.0, help="rotor azimuth of blade 0 (deg)")
    p.add_argument("--n-chord", type=int, default=None)
    p.add_argument("--n-span", type=int, default=None)
    p.add_argument("--tower-model", choices=("shell", "beam"), default="shell")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from windflutter.errors import InputError
    from windflutter.mesh.turbine import build_model

    if not args.vtk and not args.bdf:
        raise InputError("--vtk/--bdf", None, "at least one output file")
    turbine = load(args.turbine)
    fe, sec = build_model(turbine, settings_from_args(args))
    print(f"{turbine.name}: {fe.n_nodes} nodes, {len(fe.shell_conn)} quads, {len(fe.beam_conn)} beams, "
          f"{fe.n_dof} DOF, {len(fe.shell_properties)} laminates, {sec.n_sections} aero strips")
    if args.vtk:
        from windflutter.structure.io_vtk import write_vtk

        write_vtk(fe, args.vtk)
        print(f"wrote {args.vtk}")
    if args.bdf:
        from windflutter.structure.io_bdf import write_bdf

        write_bdf(fe, args.bdf)
        print(f"wrote {args.bdf}")
    return 0
