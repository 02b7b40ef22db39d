"""Hostile inputs added for issue 34: each gives a clean one-line error naming the field (exit
code 2, no traceback, nothing computed) or a documented warning and a correct result."""

from __future__ import annotations

import math

import pytest
import yaml

from cli_cases import assert_one_line_error
from test_fuzz_commands import GOLAND, SECTION

# a lift slope must be in [0.1, 20] 1/rad (windflutter.cli.wing.LIFT_SLOPE): 1e-300 gave all-null
# results without a word
LIFT_SLOPES = [1e-300, 0.05, 0.0, -6.28, math.nan, math.inf, 25.0, "steep"]


@pytest.mark.parametrize("command, base", [("wing", GOLAND), ("section", SECTION)])
@pytest.mark.parametrize("slope", LIFT_SLOPES, ids=[str(s) for s in LIFT_SLOPES])
def test_implausible_lift_slope(tmp_path, run_cli, no_heavy_work, command, base, slope):
    p = tmp_path / "in.yaml"
    p.write_text(yaml.safe_dump({**base, "lift_slope": slope}))
    for extra in ([], ["--method", "thesis"]) if command == "wing" else ([],):
        rc, _, err = run_cli([command, p, *extra])
        assert_one_line_error(rc, err, "lift_slope", str(slope)[:4])


# ------------------------------------------------------------------ every config field has its flag
def test_every_result_changing_field_has_a_flag():
    """Every declared config field but the output ones and the title has a ``run`` flag (the
    others, derived from the field's name, e.g. ``--damping-tower-ratio``)."""
    from windflutter.cli.options import NO_FLAG, RPM_PATHS
    from windflutter.cli.run import FLAGS
    from windflutter.config import declared_fields

    paths = {f.path for f in FLAGS if f.path} | set(RPM_PATHS) | {"solver.geometric_stiffness", "solver.rigid_sections"}
    missing = [p for p, _, _ in declared_fields() if p not in paths and not p.startswith("output.") and p != "title"]
    assert missing == []
    assert "damping.tower_ratio" in paths and "solver.n_eig" in paths and "operating.rated_rpm" in paths
    assert "title" in NO_FLAG and "output." in NO_FLAG


def test_tower_ratio_flag_reaches_the_config():
    from windflutter.cli import build_parser
    from windflutter.cli.stability import options_from_args

    args = build_parser().parse_args(["stability", "iea15mw", "--damping", "file", "--damping-tower-ratio", "0.001",
                                      "--n-eig", "24", "--no-full-sweep", "--tolerance-rpm", "0.02"])
    config, _ = options_from_args(args)
    assert config.damping.tower_ratio == 0.001 and config.solver.n_eig == 24
    assert config.rotor_speed.full_sweep is False and config.rotor_speed.tolerance_rpm == 0.02


DERIVED_BAD = [("--damping-tower-ratio", "-0.1", "damping.tower_ratio"), ("--damping-tower-ratio", "1.5", "damping.tower_ratio"),
               ("--damping-ratio", "nan", "damping.ratio"), ("--damping-reference-hz", "0", "damping.reference_hz"),
               ("--tolerance-rpm", "-1", "rotor_speed.tolerance_rpm"), ("--tolerance-rpm", "30", "rotor_speed.tolerance_rpm"),
               ("--mesh-density", "0", "model.mesh_density"), ("--mesh-density", "x", "model.mesh_density"),
               ("--n-eig", "1", "solver.n_eig"), ("--n-eig", "2.5", "solver.n_eig"), ("--n-lag", "0", "solver.n_lag"),
               ("--correction-tol", "2", "solver.correction_tol"), ("--correction-tol", "inf", "solver.correction_tol"),
               ("--backend", "os:system", "solver.backend")]
RUN_BAD = [("--operating-overspeed-factor", "0.5", "operating.overspeed_factor"),
           ("--operating-rated-rpm", "-12", "operating.rated_rpm"), ("--campbell-max-hz", "nan", "campbell.max_hz"),
           ("--operating-overspeed-rpm", "x", "operating.overspeed_rpm")]


@pytest.mark.parametrize("flag, value, field", DERIVED_BAD + RUN_BAD, ids=[f"{c[0]}={c[1]}" for c in DERIVED_BAD + RUN_BAD])
def test_bad_derived_flag(tmp_path, monkeypatch, run_cli, no_heavy_work, flag, value, field):
    monkeypatch.chdir(tmp_path)
    commands = (["run", "nrel5mw", "-q"],) + ((["stability", "nrel5mw"],) if (flag, value, field) in DERIVED_BAD else ())
    for argv in commands:
        rc, _, err = run_cli([*argv, flag, value])
        assert_one_line_error(rc, err, flag, field)
    assert list(tmp_path.iterdir()) == []
