"""`windflutter mesh TURBINE --vtk OUT.vtu --bdf OUT.bdf`: build and export the FE model (the beam
model unless ``--model shell``, as for every command)."""

from __future__ import annotations

import argparse

from windflutter.cli.modes import MESH_FLAGS, load, settings_from_args
from windflutter.cli.options import add_flags

VTK_EXTENSIONS = (".vtu",)
BDF_EXTENSIONS = (".bdf", ".dat", ".nas")


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("mesh", help="build a turbine FE model and export it (VTK / NASTRAN BDF)",
                       description="Build the FE model of a turbine or part (beam unless --model shell) and "
                                   "write it for ParaView (VTK) or NASTRAN (BDF).")
    p.add_argument("turbine", help="turbine file (windIO, OpenFAST .fst, HAWC2 .htc) or bundled name (e.g. nrel5mw)")
    p.add_argument("--vtk", metavar="FILE.vtu", help="write the mesh to this .vtu file")
    p.add_argument("--bdf", metavar="FILE.bdf", help="write the model to this NASTRAN file (" + ", ".join(BDF_EXTENSIONS) + ")")
    add_flags(p, MESH_FLAGS)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from windflutter.cli.warn import one_line_warnings  # noqa: PLC0415
    from windflutter.errors import InputError  # noqa: PLC0415
    from windflutter.files import check_output_file  # noqa: PLC0415
    from windflutter.mesh.turbine import build_model  # noqa: PLC0415

    if not args.vtk and not args.bdf:
        raise InputError("--vtk/--bdf", None, "at least one output file")
    settings = settings_from_args(args)
    for flag, path, ext in (("--vtk", args.vtk, VTK_EXTENSIONS), ("--bdf", args.bdf, BDF_EXTENSIONS)):
        if path is not None:  # before the model is built
            check_output_file(path, flag, ext)
    with one_line_warnings("windflutter mesh"):
        turbine = load(args.turbine)
        fe, sec = build_model(turbine, settings)
        print(f"{turbine.name}: {settings.model} model, {fe.n_nodes} nodes, {len(fe.shell_conn)} quads, "
              f"{len(fe.beam_conn)} beams, {fe.n_dof} DOF, {len(fe.shell_properties)} laminates, "
              f"{sec.n_sections} aero strips")
        _write(fe, args)
    return 0


def _write(fe, args: argparse.Namespace) -> None:
    from windflutter.files import prepare_output_file  # noqa: PLC0415

    if args.vtk:
        from windflutter.structure.io_vtk import write_vtk  # noqa: PLC0415

        write_vtk(fe, prepare_output_file(args.vtk))
        print(f"wrote {args.vtk}")
    if args.bdf:
        from windflutter.structure.io_bdf import write_bdf  # noqa: PLC0415

        write_bdf(fe, prepare_output_file(args.bdf))
        print(f"wrote {args.bdf}")
