"""Broken OpenFAST decks and HAWC2 models (issue 34, beyond tests/model/fuzz_cases.py): missing,
circular or directory references, non-UTF-8 files, NaN or negative table entries, mismatched
columns, a one-station blade.  Every case ends in one InputError whose message names the key or
file (``words``) -- never another exception, a hang or a silent number."""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import pytest

from windflutter.errors import InputError, InputWarning
from windflutter.model import load_turbine
from windflutter.model.bundled import DATA_DIR

FST = "NREL-5MW_Onshore.fst"
ED = "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat"
EDT = "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"
BD = "NRELOffshrBsline5MW_BeamDyn.dat"
BDB = "NRELOffshrBsline5MW_BeamDyn_Blade.dat"
AD = "NRELOffshrBsline5MW_Onshore_AeroDyn15.dat"
ADB = "NRELOffshrBsline5MW_AeroDyn_blade.dat"
AF = "Airfoils/DU25_A17.dat"
HTC = "htc/NREL_5MW.htc"
ST, AE, PC = "data/NREL_5MW_st.txt", "data/NREL_5MW_ae.txt", "data/NREL_5MW_pc.txt"


def sub(path: Path, old: str, new: str, count: int = 1) -> None:
    text = path.read_text(errors="surrogateescape")
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, count), errors="surrogateescape")


def row(path: Path, marker: str, offset: int, fn) -> None:
    """Apply ``fn(tokens) -> tokens`` to the line ``offset`` lines after the first containing ``marker``."""
    lines = path.read_text().splitlines()
    i = next(k for k, ln in enumerate(lines) if marker in ln) + offset
    lines[i] = "\t".join(fn(lines[i].split()))
    path.write_text("\n".join(lines) + "\n")


def setcol(k: int, v: str):
    return lambda tok: tok[:k] + [v] + tok[k + 1:]


def dir_instead(d: Path, name: str) -> None:
    (d / name).unlink()
    (d / name).mkdir()


def non_utf8(d: Path, name: str) -> None:
    (d / name).write_bytes(b"\xff\xfe bad " + (d / name).read_bytes())


OPENFAST = [  # d = a copy of data/nrel5mw (deck + supplement)
    ("ed-missing", lambda d: (d / ED).unlink(), "EDFile"),
    ("ed-is-directory", lambda d: dir_instead(d, ED), "EDFile"),
    ("ed-non-utf8", lambda d: non_utf8(d, ED), "UTF-8"),
    ("ed-refers-to-the-fst", lambda d: sub(d / FST, f'"{ED}"', f'"{FST}"'), "NumBl"),
    ("ed-empty", lambda d: (d / ED).write_text(""), "ElastoDyn"),
    ("edfile-empty-name", lambda d: sub(d / FST, f'"{ED}"', '""'), "EDFile"),
    ("tower-missing", lambda d: (d / EDT).unlink(), "TwrFile"),
    ("tower-is-directory", lambda d: dir_instead(d, EDT), "TwrFile"),
    ("tower-non-utf8", lambda d: non_utf8(d, EDT), "UTF-8"),
    ("tower-refers-to-ed", lambda d: sub(d / ED, f'"{EDT}"', f'"{ED}"'), "NTwInpSt"),
    ("tower-nan-mass", lambda d: row(d / EDT, "1.0000000E-01  5.2324300E+03", 0, setcol(1, "nan")), "row 2"),
    ("tower-short-row", lambda d: row(d / EDT, "3.0000000E-01  4.5508700E+03", 0, lambda t: t[:2]), "row 4"),
    ("beamdyn-missing", lambda d: (d / BD).unlink(), "BDBldFile"),
    ("beamdyn-is-directory", lambda d: dir_instead(d, BD), "BDBldFile"),
    ("beamdyn-blade-missing", lambda d: (d / BDB).unlink(), "BldFile"),
    ("beamdyn-blade-is-directory", lambda d: dir_instead(d, BDB), "BldFile"),
    ("beamdyn-blade-refers-to-itself", lambda d: sub(d / BD, f'"{BDB}"', f'"{BD}"'), "station_total"),
    ("beamdyn-one-station", lambda d: sub(d / BDB, "49   station_total", "1   station_total"), "station_total"),
    ("beamdyn-nan-stiffness", lambda d: row(d / BDB, "  0.000000", 1, setcol(0, "NaN")), "station"),
    ("beamdyn-mu-nan", lambda d: sub(d / BDB, "1.0E-03    1.0E-03", "NaN    1.0E-03"), "mu"),
    ("beamdyn-text-in-table", lambda d: row(d / BDB, "  0.000000", 2, setcol(1, "abc")), "station"),
    ("beamdyn-truncated", lambda d: (d / BDB).write_text("\n".join((d / BDB).read_text().splitlines()[:200])),
     "station"),
    ("aerodyn-missing", lambda d: (d / AD).unlink(), "AeroFile"),
    ("aerodyn-is-directory", lambda d: dir_instead(d, AD), "AeroFile"),
    ("aerodyn-non-utf8", lambda d: non_utf8(d, AD), "UTF-8"),
    ("aerodyn-blade-missing", lambda d: (d / ADB).unlink(), "ADBlFile"),
    ("aerodyn-blade-is-directory", lambda d: dir_instead(d, ADB), "ADBlFile"),
    ("aerodyn-blade-nan-chord", lambda d: row(d / ADB, "(m)", 3, setcol(5, "nan")), "AeroDyn blade table row"),
    ("aerodyn-blade-negative-chord", lambda d: row(d / ADB, "(m)", 3, setcol(5, "-3.5")), "BlChord"),
    ("aerodyn-blade-short-row", lambda d: row(d / ADB, "(m)", 4, lambda t: t[:4]), ADB),
    ("aerodyn-blade-one-node", lambda d: sub(d / ADB, "19   NumBlNds", "1   NumBlNds"), "NumBlNds"),
    ("airfoil-is-directory", lambda d: dir_instead(d, AF), "AFNames"),
    ("airfoil-non-utf8", lambda d: non_utf8(d, AF), "UTF-8"),
    ("airfoil-nan-lift", lambda d: row(d / AF, "NumAlf", 3, setcol(1, "nan")), "row 1"),
    ("airfoil-short-row", lambda d: row(d / AF, "NumAlf", 5, lambda t: t[:1]), "DU25"),
    ("numafiles-zero", lambda d: sub(d / AD, "8   NumAFfiles", "0   NumAFfiles"), "airfoil polars"),
    ("supplement-curve-file-missing", lambda d: (d / "NREL5MW_Oper_Onshore_Flexible_Discon.csv").unlink(),
     "operating_curve"),
    ("supplement-curve-file-is-directory", lambda d: dir_instead(d, "NREL5MW_Oper_Onshore_Flexible_Discon.csv"),
     "operating_curve"),
    ("supplement-non-utf8", lambda d: non_utf8(d, "NREL-5MW_Onshore.windflutter.yaml"), "UTF-8"),
    ("supplement-not-a-mapping", lambda d: (d / "NREL-5MW_Onshore.windflutter.yaml").write_text("windflutter: 5\n"),
     "windflutter"),
]

HAWC2 = [  # d = a copy of data/nrel5mw/hawc2
    ("st-missing", lambda d: (d / ST).unlink(), "st"),
    ("st-is-directory", lambda d: dir_instead(d, ST), "st"),
    ("st-non-utf8", lambda d: non_utf8(d, ST), "UTF-8"),
    ("st-nan-entry", lambda d: row(d / ST, "$1\t 49", 3, setcol(1, "nan")), "set 5 1 row 3"),
    ("st-negative-mass", lambda d: row(d / ST, "$1\t 49", 3, setcol(1, "-100")), "set 5 1 column m at station 2"),
    ("st-one-station-blade", lambda d: sub(d / ST, "$1\t 49", "$1\t 1"), "st set 5 1 rows"),
    ("st-extra-column", lambda d: row(d / ST, "$1\t 49", 2, lambda t: t + ["1.0"]), "st set 5 1 row 2"),
    ("ae-missing", lambda d: (d / AE).unlink(), "ae_filename"),
    ("ae-is-directory", lambda d: dir_instead(d, AE), "ae_filename"),
    ("ae-non-utf8", lambda d: non_utf8(d, AE), "UTF-8"),
    ("ae-nan-chord", lambda d: row(d / AE, "1 19", 3, setcol(1, "nan")), "ae set 1 row 3"),
    ("ae-short-row", lambda d: row(d / AE, "1 19", 3, lambda t: t[:2]), "ae"),
    ("ae-one-station", lambda d: sub(d / AE, "1 19", "1 1"), "ae set 1 rows"),
    ("pc-missing", lambda d: (d / PC).unlink(), "pc_filename"),
    ("pc-is-directory", lambda d: dir_instead(d, PC), "pc_filename"),
    ("pc-non-utf8", lambda d: non_utf8(d, PC), "UTF-8"),
    ("htc-includes-itself", lambda d: sub(d / HTC, "begin aero ;", "continue_in_file ./htc/NREL_5MW.htc ;\nbegin aero ;"),
     "continue_in_file"),
    ("htc-st-filename-empty", lambda d: sub(d / HTC, "./data/NREL_5MW_st.txt", "./data/", 1), "st"),
    ("opt-missing", lambda d: (d.parent / "NREL5MW_hawc2_operational_data.opt").unlink(), "operational_data"),
    ("opt-nan", lambda d: row(d.parent / "NREL5MW_hawc2_operational_data.opt", "", 3, setcol(1, "nan")),
     "operational_data"),
]


def _load(kind: str, mutate, tmp_path: Path):
    if kind == "openfast":
        root = tmp_path / "deck"
        shutil.copytree(DATA_DIR / "nrel5mw", root, ignore=shutil.ignore_patterns("hawc2"))
        main = root / FST
    else:
        root = tmp_path / "hawc2"
        shutil.copytree(DATA_DIR / "nrel5mw" / "hawc2", root)
        shutil.copy(DATA_DIR / "nrel5mw" / "NREL5MW_hawc2_operational_data.opt", tmp_path)
        main = root / HTC
    mutate(root)
    return load_turbine(main)


CASES = [("openfast", *c) for c in OPENFAST] + [("hawc2", *c) for c in HAWC2]


@pytest.mark.parametrize("kind, name, mutate, words", CASES, ids=[c[1] for c in CASES])
def test_broken_deck_is_refused_by_name(tmp_path, kind, name, mutate, words):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputWarning)
        with pytest.raises(InputError) as exc:
            _load(kind, mutate, tmp_path).require("turbine", aerodynamics=True)
    msg = str(exc.value)
    assert words in msg and "\n" not in msg.strip(), msg
