"""``windflutter run --resume`` after the turbine file or the analysis changed (issue 34): one line
naming ``--resume`` and what differs, before any work; the flags that set config fields (the
derived ones too) count as a changed config."""

from __future__ import annotations

import pytest

from cli_cases import RESUME_CONFIG, assert_one_line_error, recorded_run

CFG = RESUME_CONFIG


@pytest.fixture
def recorded(tmp_path):
    return recorded_run(tmp_path)


FLAG_CHANGES = [["--air-density", "1.1"], ["--damping-tower-ratio", "0.002"], ["--n-eig", "24"],
                ["--wind-speeds", "4", "10"], ["--rpm", "2", "30", "4"], ["--aero", "viscous"],
                ["--tolerance-rpm", "0.02"], ["--damping", "none"], ["--mesh-density", "2"],
                ["--operating-overspeed-factor", "1.3"]]


@pytest.mark.parametrize("flags", FLAG_CHANGES, ids=[f[0] for f in FLAG_CHANGES])
def test_resume_with_a_changed_setting(recorded, run_cli, no_heavy_work, flags):
    cfg, turbine, out = recorded
    rc, _, err = run_cli(["run", turbine, "-c", cfg, "-o", out, "-q", "--workers", "1", "--resume", *flags])
    assert_one_line_error(rc, err, "--resume", "analysis config")


TURBINE_CHANGES = [
    ("one-byte-appended", lambda t: t.write_text(t.read_text() + " "), "turbine"),
    ("emptied", lambda t: t.write_text(""), "turbine"),
    ("replaced", lambda t: t.write_bytes(b"\x00\x01binary"), "turbine"),
]


@pytest.mark.parametrize("name, change, words", TURBINE_CHANGES, ids=[c[0] for c in TURBINE_CHANGES])
def test_resume_after_the_turbine_changed(recorded, run_cli, no_heavy_work, name, change, words):
    cfg, turbine, out = recorded
    change(turbine)
    rc, _, err = run_cli(["run", turbine, "-c", cfg, "-o", out, "-q", "--workers", "1", "--resume"])
    assert_one_line_error(rc, err, "--resume", words)


def test_resume_with_another_turbine_file(recorded, run_cli, no_heavy_work, tmp_path):
    cfg, _, out = recorded
    other = tmp_path / "other.txt"
    other.write_text("toy rotor, radius 50 m\n")
    rc, _, err = run_cli(["run", other, "-c", cfg, "-o", out, "-q", "--workers", "1", "--resume"])
    assert_one_line_error(rc, err, "--resume", "turbine")
