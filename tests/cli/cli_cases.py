"""Generated bad inputs for the hardening tests, and the assertion every one of them must meet.

The config cases are generated from the declarations of :mod:`windflutter.config` (each field's
kind and bounds), so a new option gets its hostile cases without writing them: values of the
wrong kind, NaN and infinities, integers too large for a float, values just outside each bound,
``null`` where it is not allowed.
"""

from __future__ import annotations

import math
from typing import Any

from windflutter.config import declared_fields

HUGE = 10 ** 400  # too large for float(): must be refused without an OverflowError


def assert_one_line_error(rc: int, err: str, *words: str) -> str:
    """Exit code 2, exactly one line on stderr, naming each of ``words``, no traceback."""
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert rc == 2, (rc, err)
    assert len(lines) == 1, err
    assert "Traceback" not in err and "internal error" not in err, err
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


def _below(spec) -> list[Any]:
    if spec.lower is None:
        return []
    lo = spec.lower
    if spec.kind == "int":
        return [int(lo) - 1]
    return [lo] if spec.lower_open else [lo - max(abs(lo), 1.0) * 1e-3]


def _above(spec) -> list[Any]:
    if spec.upper is None:
        return []
    hi = spec.upper
    if spec.kind == "int":
        return [int(hi) + 1, int(hi) * 1000]
    return ([hi] if spec.upper_open else []) + [hi * 1.001 + 1e-9, hi * 1e6]


def bad_values(spec) -> list[Any]:
    """Values the spec must refuse."""
    k = spec.kind
    out: list[Any]
    if k == "float":
        out = ["fast", True, [1.0], {"a": 1}, math.nan, math.inf, -math.inf, HUGE, -HUGE]
        out += _below(spec) + _above(spec)
    elif k == "int":
        out = [1.5, "3", True, math.nan, math.inf, HUGE, [3]] + _below(spec) + _above(spec)
    elif k == "bool":
        out = [1, "true", [True], {"a": True}]
    elif k == "choice":
        out = ["nonsense", 1, [spec.choices[0]], {"a": 1}]
    elif k == "choices":
        out = [[], ["nonsense"], [spec.choices[0], spec.choices[0]], 5, {"a": 1}, [[spec.choices[0]]]]
    elif k == "str":
        out = [5, ["x"], "x" * 501]
    else:
        out = []
    if not spec.nullable and k not in ("custom",):
        out.append(None)
    return out


CUSTOM = {
    "wind_speeds": [[], [0], [-1.0], [5, 4], [4, 4], [1e5], [math.nan], [math.inf], "fast", [[4]],
                    {"start": 1}, {"start": 1, "stop": 2, "step": 0}, {"start": 1, "stop": 25, "step": 1e-9},
                    {"start": 5, "stop": 4, "step": 1}, {"start": 0, "stop": 4, "step": 1},
                    {"start": 1, "stop": 2, "step": 1, "by": 3}, {"start": 1, "stop": 1e6, "step": 1},
                    {"start": 1, "stop": 2, "step": 1e-320}, list(range(1, 1002)), {"start": "a", "stop": 2, "step": 1}],
    "solver.backend": ["os:system", "subprocess:run", "a.b:c", "", 5, "no_such_backend", "../x", None, ["toy"]],
}


def nested(dotted: str, value: Any) -> dict:
    """``{"a": {"b": value}}`` for ``"a.b"``."""
    d: Any = value
    for k in reversed(dotted.split(".")):
        d = {k: d}
    return d


def config_field_cases() -> list[tuple[str, str, Any]]:
    """``(case id, field, value)`` for every declared config field and each bad value."""
    cases = []
    for name, _, spec in declared_fields():
        values = CUSTOM.get(name, []) if spec.kind == "custom" else bad_values(spec)
        for i, v in enumerate(values):
            cases.append((f"{name}#{i}", name, v))
    return cases


#: a small analysis of the instant plug-in back-end, for the --resume cases
RESUME_CONFIG = {"wind_speeds": [4, 10, 16], "aero": ["potential"],
                 "rotor_speed": {"min_rpm": 2, "max_rpm": 26, "n_points": 7},
                 "solver": {"backend": "instant", "n_tracked": 2},
                 "output": {"plots": False, "report": False, "animations": False}}


def recorded_run(tmp_path):
    """``(config file, turbine file, output folder)``: a config file, a turbine file for the plug-in
    (hashed by its bytes) and an output folder holding the record of a run of both."""
    import yaml

    from windflutter.config import load_config
    from windflutter.post import runfolder

    cfg = tmp_path / "analysis.yaml"
    cfg.write_text(yaml.safe_dump(RESUME_CONFIG))
    turbine = tmp_path / "turbine.txt"
    turbine.write_text("toy rotor, radius 40 m\n")
    out = tmp_path / "out"
    out.mkdir()
    runfolder.write_run_record(out, runfolder.run_record(load_config(cfg), str(turbine), str(turbine)))
    return cfg, turbine, out
