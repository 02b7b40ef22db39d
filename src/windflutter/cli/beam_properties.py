"""`windflutter beam-properties TURBINE --csv F --beamdyn F`: the beam properties of the shell blade's
layup, station by station, from the shell model itself (:mod:`windflutter.mesh.shell_beam`), beside the
turbine file's 6x6."""

from __future__ import annotations

import argparse

from windflutter.cli.modes import load
from windflutter.cli.options import Flag, add_flags, command_values
from windflutter.schema import Spec

FLAGS = (
    Flag("--stations", spec=Spec("int", lower=2, upper=200, doc="output stations along the span"), default=20),
    Flag("--element-length", spec=Spec("float", lower=0.0, lower_open=True, upper=100.0, unit="m", nullable=True,
                                       doc="target skin element length along the span (default: the blade "
                                           "length / 100)"), default=None),
    Flag("--reference-surface", spec=Spec("choice", choices=("midsurface", "outer"), nullable=True,
                                          doc="the skin's reference surface (default midsurface)"), default=None),
    Flag("--extraction", spec=Spec("choice", choices=("segment", "section"),
                                   doc="segment: a blade segment loaded through rigid end rings (the 3-D blade's "
                                       "behaviour around the station); section: the station's own section on a "
                                       "periodic prism (Saint-Venant, as a cross-section code)"), default="segment"),
)


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("beam-properties", help="beam properties of the shell blade (CSV, BeamDyn), from the "
                       "shell model, beside the file's 6x6",
                       description="Mass, mass centre, tension and shear centres and the 6x6 stiffness of the "
                                   "shell blade at stations along the span, extracted from the shell model by "
                                   "unit loads on segments or on periodic prisms of the sections, printed beside the turbine file's 6x6 (docs/mesh.md).")
    p.add_argument("turbine", help="turbine file (windIO with a layup) or bundled name (e.g. iea22mw)")
    p.add_argument("--csv", metavar="FILE.csv", help="write the station table to this CSV file")
    p.add_argument("--beamdyn", metavar="FILE.dat", help="write a BeamDyn blade file (stations whose segment is "
                   "not cut by a blade end; the end stations repeated at eta 0 and 1)")
    add_flags(p, FLAGS)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import dataclasses  # noqa: PLC0415

    import numpy as np  # noqa: PLC0415

    from windflutter.errors import InputError  # noqa: PLC0415
    from windflutter.files import check_output_file, prepare_output_file  # noqa: PLC0415
    from windflutter.mesh.settings import MeshSettings  # noqa: PLC0415
    from windflutter.mesh.shell_beam import (  # noqa: PLC0415
        shell_beam_table, table_rows, usable_stations, write_beamdyn_blade, write_csv)

    v = command_values(args, FLAGS)
    for flag, path, ext in (("--csv", args.csv, (".csv",)), ("--beamdyn", args.beamdyn, (".dat", ".inp", ".txt"))):
        if path is not None:
            check_output_file(path, flag, ext)
    kw = {k: v[k] for k in ("element_length", "reference_surface") if v.get(k) is not None}
    settings = MeshSettings(model="shell", part="blade", **kw)
    turbine = load(args.turbine)
    if turbine.blade.layup is None:
        raise InputError("blade.layup", None, "a composite layup: the beam properties come from the shell model")
    table = shell_beam_table(turbine, n_stations=v["stations"], settings=settings, extraction=v["extraction"])
    rows = table_rows(table, turbine.blade.beam)
    print(f"{turbine.name}: shell blade ({table.beam.source}); ratios to the file's 6x6 where it has one")
    print("     s   mass/kg/m    EA/N   GJ/Nm2  EIflap  EIedge   sc_flap sc_edge (m)   vs file: mass  EA   GJ  flap "
          "edge")
    for r in rows:
        ratio = [r[a] / r[b] - 1 for a, b in (("mass", "file_mass"), ("EA", "file_EA"), ("GJ", "file_GJ"),
                                             ("EI_flap", "file_EI_flap"), ("EI_edge", "file_EI_edge"))]
        txt = " ".join("   -  " if not np.isfinite(x) else f"{x:+5.0%}" for x in ratio)
        print(f"{r['s']:6.3f} {r['mass']:9.1f} {r['EA']:9.3g} {r['GJ']:8.3g} {r['EI_flap']:8.3g} {r['EI_edge']:8.3g} "
              f"{r['sc_flap']:+8.3f} {r['sc_edge']:+8.3f}   {txt}{'  (end)' if r['clipped'] else ''}"
              f"{'' if r['usable'] else '  (reading failed: not used)'}")
    if args.csv:
        write_csv(prepare_output_file(args.csv), rows)
        print(f"wrote {args.csv}")
    if args.beamdyn:
        keep = ~table.clipped & usable_stations(table)
        if keep.sum() < 2:
            raise InputError("--stations", v["stations"], "more stations (fewer than two usable ones away from the "
                             "blade ends)")
        b = table.beam
        inner = dataclasses.replace(b, s=b.s[keep], stiffness=b.stiffness[keep], mass=b.mass[keep], twist=b.twist[keep])
        write_beamdyn_blade(prepare_output_file(args.beamdyn), inner, title=f"{turbine.name}: {b.source}")
        print(f"wrote {args.beamdyn}")
    return 0
