"""Malformed turbine files are rejected with an InputError naming the path in the file."""

from __future__ import annotations

import copy
import functools

import numpy as np
import pytest
import yaml

from windflutter.errors import InputError
from windflutter.model import load_turbine
from windflutter.model.bundled import DATA_DIR
from windflutter.model.windio import read_windio_dict
from windflutter.model.yamlio import load_yaml_file, load_yaml_text


@functools.lru_cache(maxsize=None)
def _raw(name: str) -> dict:
    return load_yaml_file(DATA_DIR / name)


def v2() -> dict:
    return copy.deepcopy(_raw("seed/seed20mw.yaml"))  # small v2 file (validates in ~0.3 s)


def v1() -> dict:
    return copy.deepcopy(_raw("turbines/windIO_v1/IEA-15-240-RWT.yaml"))


def _err(data: dict) -> InputError:
    with pytest.raises(InputError) as exc:
        read_windio_dict(data, source="bad.yaml")
    return exc.value


def test_missing_key_v2_schema_names_path():
    d = v2()
    del d["components"]["blade"]["outer_shape"]["chord"]
    e = _err(d)
    assert e.field == "components.blade.outer_shape"
    assert "chord" in str(e) and "bad.yaml" in str(e)


def test_missing_key_v1_names_path():
    d = v1()
    del d["components"]["blade"]["outer_shape_bem"]["chord"]
    e = _err(d)
    assert e.field == "components.blade.outer_shape_bem.chord"


def test_wrong_type_names_index():
    d = v2()
    d["components"]["blade"]["outer_shape"]["chord"]["values"][3] = "abc"
    e = _err(d)
    assert e.field == "components.blade.outer_shape.chord.values[3]"


def test_wrong_type_v1():
    d = v1()
    d["components"]["tower"]["outer_shape_bem"]["outer_diameter"]["values"] = "ten"
    e = _err(d)
    assert e.field == "components.tower.outer_shape_bem.outer_diameter.values"


def test_negative_chord_rejected_v2_and_v1():
    d = v2()
    d["components"]["blade"]["outer_shape"]["chord"]["values"][5] = -1.0
    e = _err(d)
    assert e.field.startswith("components.blade.outer_shape.chord.values")
    d = v1()
    d["components"]["blade"]["outer_shape_bem"]["chord"]["values"][2] = -0.5
    e = _err(d)
    assert e.field == "components.blade.outer_shape_bem.chord.values[2]"


def test_quoted_number_string_rejected():
    d = v2()
    d["components"]["blade"]["structure"]["layers"][0]["thickness"]["values"][1] = "5e-05"
    e = _err(d)
    assert e.field == "components.blade.structure.layers[0].thickness.values[1]"


def test_unquoted_exponent_is_a_number():
    """The PyYAML YAML-1.1 gotcha: ``5e-05`` and ``2e6`` must load as floats, a quoted value as str."""
    d = load_yaml_text('a: [5e-05, 2e6, 1E+3, "5e-05", .5]')
    assert d["a"][:3] == [5e-05, 2e6, 1e3] and isinstance(d["a"][0], float)
    assert d["a"][3] == "5e-05" and d["a"][4] == 0.5


def test_bundled_file_with_string_numbers_loads(turbine):
    # NREL-5MW.yaml has 30 unquoted '5e-05' thicknesses (README of the reference data)
    t = turbine("nrel5mw")
    uv = next(lay for lay in t.blade.layup.layers if lay.name == "UV_protection")
    assert uv.thickness[0] == pytest.approx(5e-05)


def test_unknown_material_and_airfoil():
    d = v2()
    d["components"]["blade"]["structure"]["layers"][1]["material"] = "unobtainium"
    e = _err(d)
    assert e.field == "components.blade.structure.layers[1].material"
    d = v2()
    d["components"]["blade"]["outer_shape"]["airfoils"][4]["name"] = "NACA0000"
    e = _err(d)
    assert "NACA0000" in str(e)


def test_grid_values_length_mismatch():
    d = v1()
    d["components"]["blade"]["outer_shape_bem"]["chord"]["values"].pop()
    e = _err(d)
    assert e.field == "components.blade.outer_shape_bem.chord.values"


def test_tower_wall_thicker_than_radius():
    d = v2()
    d["components"]["tower"]["structure"]["layers"][0]["thickness"]["values"] = [9.0] * 11
    e = _err(d)
    assert "tower" in e.field


def test_yaml_syntax_error_reports_line(tmp_path):
    p = tmp_path / "broken.yaml"
    p.write_text("windIO_version: '2.0'\nname: x\ncomponents: {blade: [1, 2\n")
    with pytest.raises(InputError) as exc:
        load_turbine(p)
    assert "line" in exc.value.field


def test_missing_file_and_unknown_name(tmp_path):
    with pytest.raises(InputError):
        load_turbine(tmp_path / "nope.yaml")
    with pytest.raises(InputError) as exc:
        load_turbine("nrel6mw")
    assert "nrel5mw" in str(exc.value)


def test_missing_lumped_masses_are_assumed_with_a_warning(tmp_path):
    """A windIO file without hub/nacelle masses and no supplement must not silently give zero:
    it loads with the masses assumed from the rotor diameter (issue 34; formerly every model
    with a hub was refused), one warning each naming the assumption and the key that gives
    the turbine's own (tests/model/test_own_files.py checks the scaling)."""
    from windflutter.model.consistency import DEFAULT_MASS_PER_D3

    d = v2()
    d.pop("windflutter")
    p = tmp_path / "no_masses.yaml"
    p.write_text(yaml.safe_dump(d))
    with pytest.warns(Warning) as rec:
        t = load_turbine(p)
    assert not {"hub.mass", "nacelle.mass"} & set(t.missing)
    assert t.hub.mass == pytest.approx(DEFAULT_MASS_PER_D3["hub"] * t.rotor_diameter ** 3)
    for part in ("hub", "nacelle"):
        hits = [str(w.message) for w in rec if f"{part}.mass: not in the files" in str(w.message)]
        assert len(hits) == 1 and "no_masses.yaml" in hits[0] and "assumed" in hits[0]
    for part in ("blade", "turbine", "tower", "rotor"):
        t.require(part)


def test_supplement_errors_name_the_block(tmp_path):
    d = v2()
    d["windflutter"]["nacelle"]["mass"] = -5.0
    p = tmp_path / "neg.yaml"
    p.write_text(yaml.safe_dump(d))
    with pytest.raises(InputError) as exc:
        load_turbine(p)
    assert exc.value.field == "windflutter.nacelle.mass"


def test_inputerror_is_valueerror():
    d = v2()
    d["assembly"]["number_of_blades"] = "three"
    with pytest.raises(ValueError):
        read_windio_dict(d)
    assert np.isfinite(1.0)


def test_indefinite_nacelle_inertia_is_rejected(turbine):
    """WISDEM's NREL-5MW drivetrain inertia puts the yaw inertia in the Iyz slot; the supplement
    resets it.  A tensor like that must be refused by name, not passed on to the mass matrix."""
    import dataclasses

    import numpy as np

    from windflutter.errors import InputError
    from windflutter.model.consistency import rigid_body_inertias as _check_rigid_body_inertias

    t = turbine("nrel5mw")
    assert np.linalg.eigvalsh(t.nacelle.inertia).min() >= 0.0  # the bundled file is repaired
    bad = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 2.6e6], [0.0, 2.6e6, 0.0]])
    t_bad = dataclasses.replace(t, nacelle=dataclasses.replace(t.nacelle, inertia=bad))
    with pytest.raises(InputError, match="nacelle.inertia"):
        _check_rigid_body_inertias(t_bad, "x.yaml")


def test_check_choice_names_field_value_and_choices():
    from windflutter.errors import check_choice
    from windflutter.mesh.settings import MeshSettings

    assert check_choice("a.b", "beam", ("shell", "beam")) == "beam"
    with pytest.raises(InputError) as exc:
        check_choice("mesh.model", "plate", ("shell", "beam"), source="cfg.yaml")
    msg = str(exc.value)
    assert exc.value.field == "mesh.model" and "'plate'" in msg and "'shell', 'beam'" in msg and "cfg.yaml" in msg
    with pytest.raises(InputError):
        check_choice("x", ["unhashable"], {"a", "b"})
    with pytest.raises(InputError, match="mesh.part.*'nacelle'.*'turbine', 'blade'"):
        MeshSettings(part="nacelle")
