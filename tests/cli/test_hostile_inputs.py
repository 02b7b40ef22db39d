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
