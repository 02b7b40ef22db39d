"""The analysis configs shown in the tutorials are accepted by the methods they name.

Each YAML block of ``docs/tutorial_*.md`` is an analysis config a reader copies (the IEA 15 MW
tutorial's once carried a uniform modal damping ratio that method p, the default method, refuses):
here every block is validated as ``windflutter run -c`` validates it, and for method p the operating
model's options are built as the run builds them (``methods.operational_options``), which is where
such a refusal is raised.  Nothing is computed.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from windflutter import methods
from windflutter.config import config_from_dict

DOCS = Path(__file__).resolve().parent.parent / "docs"
BLOCKS = [(path.name, i, block) for path in sorted(DOCS.glob("tutorial_*.md"))
          for i, block in enumerate(re.findall(r"```yaml\n(.*?)```", path.read_text(), flags=re.S))]


def test_the_tutorials_have_configs():
    assert {name for name, _, _ in BLOCKS} == {"tutorial_nrel5mw.md", "tutorial_iea15mw.md"}


@pytest.mark.parametrize("name,i,block", BLOCKS, ids=[f"{n}[{i}]" for n, i, _ in BLOCKS])
def test_a_tutorial_config_is_accepted_by_its_methods(name, i, block):
    config = config_from_dict(yaml.safe_load(block), source=f"{name} block {i}")
    if "p" in config.method:
        for aero in config.aero:
            methods.operational_options(config, aero)
