"""Shared fixtures of the workflow tests: the toy analyser (an analytic typical section) on the
import path, and small configs."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

HERE = Path(__file__).parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))


@pytest.fixture
def toy_config():
    from windflutter.config import load_config

    def make(**over):
        base = {"wind_speeds": [4, 10, 16, 25], "aero": ["potential", "viscous"],
                "rotor_speed": {"min_rpm": 2, "max_rpm": 26, "n_points": 9, "tolerance_rpm": 0.01},
                "solver": {"backend": "toy", "n_tracked": 2},
                "output": {"plots": False, "report": False, "animations": False}}
        for k, v in over.items():
            if isinstance(v, dict) and isinstance(base.get(k), dict):
                base[k] = {**base[k], **v}
            else:
                base[k] = v
        return load_config(None, base)

    return make
