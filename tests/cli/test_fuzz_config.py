"""Hostile analysis configs: every one is refused by ``windflutter run`` before any work, with
exit code 2 and one line on stderr naming the field (generated from the config declarations)."""

from __future__ import annotations

import pytest
import yaml

from cli_cases import assert_one_line_error, config_field_cases, nested

FIELD_CASES = config_field_cases()


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("configs")


def _run_config(run_cli, path, out):
    return run_cli(["run", "nrel5mw", "-c", path, "-o", out, "-q"])


@pytest.mark.parametrize("case, field, value", FIELD_CASES, ids=[c[0] for c in FIELD_CASES])
def test_bad_field_value(folder, run_cli, no_heavy_work, case, field, value):
    path = folder / f"{case.replace('#', '_')}.yaml"
    path.write_text(yaml.safe_dump(nested(field, value)))
    out = folder / f"out_{path.stem}"
    rc, _, err = _run_config(run_cli, path, out)
    assert_one_line_error(rc, err, field)
    assert not out.exists()  # nothing is written for a bad config


# (id, YAML text, the field or words the one line must name)
RULES = [
    ("reversed", "rotor_speed: {min_rpm: 30, max_rpm: 5}\n", "rotor_speed.max_rpm"),
    ("reversed-min", "rotor_speed: {min_rpm: 50}\n", "rotor_speed.min_rpm"),
    ("tolerance-above-step", "rotor_speed: {n_points: 20, tolerance_rpm: 5}\n", "rotor_speed.tolerance_rpm"),
    ("damping-none-with-ratio", "damping: {model: none, ratio: 0.02}\n", "damping.model"),
    ("modal-full-order", "damping: {model: modal, ratio: 0.01}\nsolver: {reduction: none}\n", "damping.model"),
    ("skin-on-beams", "solver: {aero_distribution: skin}\n", "solver.aero_distribution"),
    ("tracked-above-basis", "solver: {basis_modes: 10, n_tracked: 11}\n", "solver.n_tracked"),
    ("too-few-strips", "model: {n_aero_sections: 10, mesh_density: 0.2}\n", "model.mesh_density"),
    ("too-many-strips", "model: {n_aero_sections: 600, mesh_density: 2}\n", "model.mesh_density"),
    ("overspeed-below-rated", "operating: {rated_rpm: 12, overspeed_rpm: 10}\n", "operating.overspeed_rpm"),
    ("renamed-n_modes", "solver: {n_modes: 20}\n", "solver.n_modes"),
    ("removed-shift_hz", "solver: {shift_hz: 1.0}\n", "solver.shift_hz"),
    ("unknown-top", "colour: red\n", "colour"),
    ("unknown-nested", "solver: {nmodes: 4}\n", "solver.nmodes"),
    ("unknown-int-key", "1: 2\n", "1"),
    ("section-not-mapping", "rotor_speed: 5\n", "rotor_speed"),
    ("section-list", "solver: [mta]\n", "solver"),
    ("top-list", "- wind_speeds\n- [4]\n", "(top level)"),
    ("top-scalar", "42\n", "(top level)"),
    ("duplicate-top", "aero: [potential]\naero: [viscous]\n", "duplicate key 'aero'"),
    ("duplicate-nested", "solver:\n  basis_modes: 10\n  basis_modes: 20\n", "duplicate key 'basis_modes'"),
    ("yaml-syntax", "wind_speeds: [4, 6\n", "valid YAML"),
    ("yaml-tab", "solver:\n\treduction: mta\n", "valid YAML"),
    ("yaml-deep", "a: " + "[" * 70 + "]" * 70 + "\n", "nesting deeper"),
    ("yaml-very-deep", "a: " + "[" * 5000 + "]" * 5000 + "\n", "valid YAML"),
    ("yaml-unhashable", "? [a]\n: 1\n", "valid YAML"),
]


@pytest.mark.parametrize("case, text, words", RULES, ids=[r[0] for r in RULES])
def test_bad_config_file(folder, run_cli, no_heavy_work, case, text, words):
    path = folder / f"rule_{case}.yaml"
    path.write_text(text)
    rc, _, err = _run_config(run_cli, path, folder / f"out_{case}")
    assert_one_line_error(rc, err, words)


def _unreadable_file(folder):
    return "/proc/self/mem"  # a regular file whose read fails (EIO), even for root


FILES = [
    ("missing", lambda d: d / "none.yaml", "no such file"),
    ("directory", lambda d: d, "not a folder"),
    ("empty-path", lambda d: "", "config"),
    ("device", lambda d: "/dev/null", "config"),
    ("unreadable", _unreadable_file, "readable"),
    ("latin-1", lambda d: _write(d / "latin1.yaml", "title: caf\xe9\n".encode("latin-1")), "UTF-8"),
    ("binary", lambda d: _write(d / "bin.yaml", bytes(range(256))), "UTF-8"),
    ("too-large", lambda d: _sparse(d / "big.yaml", 11 * 1024 * 1024), "at most"),
]


def _write(path, data: bytes):
    path.write_bytes(data)
    return path


def _sparse(path, size):
    with open(path, "wb") as fh:
        fh.truncate(size)
    return path


@pytest.mark.parametrize("case, make, words", FILES, ids=[f[0] for f in FILES])
def test_bad_config_path(folder, run_cli, no_heavy_work, case, make, words):
    rc, _, err = _run_config(run_cli, make(folder), folder / f"out_{case}")
    assert_one_line_error(rc, err, "config", words)


def test_empty_config_file_is_the_defaults(folder):
    from windflutter.config import AnalysisConfig, load_config

    (folder / "empty.yaml").write_text("# nothing\n")
    assert load_config(folder / "empty.yaml") == AnalysisConfig()
