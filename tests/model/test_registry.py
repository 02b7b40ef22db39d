"""Reader registry (file type -> reader), blade-only analyses of incomplete files, damping data."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from windflutter.errors import InputError
from windflutter.model import TurbineReader, load_turbine, readers, register_reader, unregister_reader
from windflutter.model.beamdyn import read_beamdyn_blade
from windflutter.model.bundled import DATA_DIR
from windflutter.model.registry import reader_for


def test_reader_chosen_by_suffix_then_content(tmp_path):
    assert reader_for(DATA_DIR / "nrel5mw" / "NREL-5MW_Onshore.fst").name == "openfast"
    assert reader_for(DATA_DIR / "nrel5mw" / "hawc2" / "htc" / "NREL_5MW.htc").name == "hawc2"
    assert reader_for(DATA_DIR / "turbines" / "NREL-5MW.yaml").name == "windio"
    deck = tmp_path / "deck"
    shutil.copytree(DATA_DIR / "iea15mw" / "openfast", deck)
    main = deck / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile.fst"
    renamed = main.with_suffix(".inp")  # unknown suffix: recognised by its CompElast/EDFile lines
    main.rename(renamed)
    assert reader_for(renamed).name == "openfast"
    t = load_turbine(renamed)
    assert t.source_format == "OpenFAST" and str(renamed) in t.input_files
    with pytest.raises(InputError, match="format"):
        load_turbine(renamed, fmt="nastran")


def test_bundled_names_and_bad_paths(tmp_path):
    assert load_turbine("IEA15MW-OpenFAST").source_format == "OpenFAST"  # case, '-' and '_' ignored
    with pytest.raises(InputError, match="bundled name"):
        load_turbine(tmp_path / "nothing.fst")
    with pytest.raises(InputError):
        load_turbine(tmp_path)  # a folder


def test_register_a_reader(tmp_path):
    """A registered reader is tried first for its suffix (here the OpenFAST reader under a
    plug-in name and suffix)."""
    deck = tmp_path / "deck"
    shutil.copytree(DATA_DIR / "iea15mw" / "openfast", deck)
    f = deck / "IEA-15-240-RWT-Monopile" / "x.mine"
    shutil.copy(deck / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile.fst", f)
    register_reader(TurbineReader("mine", (".mine",), "windflutter.model.openfast:load_openfast"))
    try:
        assert readers()[0].name == "mine" and reader_for(f).name == "mine"
        assert load_turbine(f).name == "x"
    finally:
        unregister_reader("mine")
    assert "mine" not in [r.name for r in readers()]


def test_entry_point_reader(tmp_path, monkeypatch):
    """A package publishing ``[windflutter.readers] nrelish = ...`` (a distribution on sys.path) is
    chosen for its suffix, after the readers registered in the process and before the built-ins."""
    pkg = tmp_path / "plugins"
    info = pkg / "nrelish_reader-0.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: nrelish-reader\nVersion: 0\n")
    (info / "entry_points.txt").write_text("[windflutter.readers]\nnrelish = nrelish_reader:READER\n")
    (pkg / "nrelish_reader.py").write_text(
        "import dataclasses\nfrom windflutter.model import TurbineReader, load_turbine\n"
        "def load(path, validate):\n"
        "    t = load_turbine('nrel5mw')\n"
        "    return dataclasses.replace(t, name='read by the plug-in: ' + path.read_text().strip())\n"
        "READER = TurbineReader('nrelish', ('.nrelish',), 'nrelish_reader:load')\n")
    monkeypatch.syspath_prepend(str(pkg))
    f = tmp_path / "t.nrelish"
    f.write_text("hello")
    names = [r.name for r in readers()]
    assert names.index("nrelish") < names.index("openfast")
    assert reader_for(f).name == "nrelish"
    assert load_turbine(f).name == "read by the plug-in: hello"
    assert reader_for(f, "nrelish").name == "nrelish"


def test_raw_wisdem_file_runs_with_assumed_masses(tmp_path):
    """The WISDEM windIO file alone (no windflutter supplement, no hub/nacelle masses): blade
    modes run; the hub and nacelle masses are assumed from the rotor diameter with one warning
    each (issue 34; formerly every model with a hub was refused), so no model is refused."""
    from windflutter.mesh.analysis import turbine_modes
    from windflutter.mesh.settings import MeshSettings

    f = tmp_path / "IEA-15-240-RWT.yaml"
    shutil.copy(DATA_DIR / "turbines" / "IEA-15-240-RWT.yaml", f)
    t = load_turbine(f, validate=False)
    assert not {"hub.mass", "nacelle.mass"} & set(t.missing)
    assert sum("hub.mass: not in the files" in w for w in t.warnings) == 1
    fr = turbine_modes(t, MeshSettings(model="beam", part="blade", n_span=20), n_modes=2).frequencies_hz
    assert 0.4 < fr[0] < 0.6  # 1st flap of the IEA 15 MW blade, about 0.5 Hz
    for part in ("turbine", "tower", "rotor"):
        t.require(part)


def test_damping_from_files_in_beamsection_order(turbine):
    """windIO/BeamDyn mu1..mu6 (shear flap, shear edge, axial, edgewise bending, flapwise bending,
    torsion) are stored in the BeamSection order (axial, shear y, shear z, torsion, bending about
    y = edgewise, about z = flapwise); the bundled IEA 15 MW supplement carries the values of the
    IEA 15 MW BeamDyn blade file (the windIO file has zeros); ElastoDyn modal ratios in fractions."""
    t = turbine("iea15mw")
    _, bd = read_beamdyn_blade(DATA_DIR / "iea15mw" / "openfast" / "IEA-15-240-RWT" / "IEA-15-240-RWT_BeamDyn_blade.dat")
    np.testing.assert_allclose(t.blade.damping.mu, bd.mu, rtol=1e-12)
    np.testing.assert_allclose(t.blade.damping.mu_beamdyn, [0.00299005, 0.00218775, 0.00084171, 0.00218775,
                                                            0.00299005, 0.00084171])
    assert t.blade.damping.mu[3] == pytest.approx(0.00084171)  # torsion
    np.testing.assert_allclose(t.blade.damping.flap_ratio, [0.0048, 0.0048])
    np.testing.assert_allclose(t.tower.damping.side_side_ratio, [0.01, 0.01])
    assert t.nacelle.drivetrain_torsional_damping == 49418406.0
    assert turbine("iea22mw").blade.damping.mu_beamdyn[0] == pytest.approx(0.004048)
    n5 = turbine("nrel5mw")  # windIO file and its BeamDyn file agree
    np.testing.assert_allclose(n5.blade.damping.mu_beamdyn, [1e-3, 1e-3, 1e-3, 1.4e-3, 2.2e-3, 2.2e-3])
    assert turbine("iea10mw").tower.damping is None  # no file gives any: documented default (none)
    attrs = n5.store_attributes()
    assert attrs["turbine_warnings"] == "none" and "NREL-5MW.windflutter.yaml" in attrs["turbine_input_files"]
