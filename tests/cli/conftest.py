"""Fixtures of the command-line hardening tests.

``run_cli(argv)`` calls :func:`windflutter.cli.main` in this process and returns
``(exit code, stdout, stderr)``.  The ``no_heavy_work`` fixture replaces every entry into real
work (reading a turbine, building a model, any analysis) by a :class:`HeavyWork` exception, which
is a ``BaseException`` so no ``except Exception`` can hide it (a module imported during the case
is patched as it is imported): a bad input that is not refused *before* the work starts fails
its test.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
from pathlib import Path

import pytest

WORKFLOW_TESTS = Path(__file__).parent.parent / "workflow"
if str(WORKFLOW_TESTS) not in sys.path:  # the toy analyser and its entry point (backend "toy")
    sys.path.insert(0, str(WORKFLOW_TESTS))


class HeavyWork(BaseException):
    """Raised when a test case reached real work."""


def _refuse(what):
    def stop(*args, **kwargs):
        raise HeavyWork(f"{what} was called: the input was not refused before the work started")
    return stop


#: (module, attribute) of every entry into real work
HEAVY = [
    ("windflutter.model", "load_turbine"), ("windflutter.model.windio", "load_turbine"),
    ("windflutter.workflow", "make_analyser"), ("windflutter.workflow", "_run"),
    ("windflutter.mesh.turbine", "build_model"), ("windflutter.mesh.analysis", "turbine_modes"),
    ("windflutter.frozen.wing", "analyse_wing"), ("windflutter.section", "analyse"),
    ("windflutter.frozen.simple_model", "run_simple_model"),
    ("windflutter.frozen.turbine", "TurbineStability"),
]


class _PatchOnImport(importlib.abc.MetaPathFinder):
    """Patches the work entries of a module of :data:`HEAVY` right after it is imported (a case
    may import a module for its config class, e.g. ``WingConfig``, but must not call its work)."""

    def __init__(self, monkeypatch, attrs: dict[str, list[str]]):
        self.mp, self.attrs = monkeypatch, attrs

    def find_spec(self, name, path, target=None):
        if name not in self.attrs:
            return None
        spec = importlib.machinery.PathFinder.find_spec(name, path)
        if spec is None or spec.loader is None:
            return spec
        loader, finder = spec.loader, self

        class Loader(importlib.abc.Loader):
            def create_module(self, spec):
                return loader.create_module(spec)

            def exec_module(self, module):
                loader.exec_module(module)
                for attr in finder.attrs[name]:
                    finder.mp.setattr(module, attr, _refuse(f"{name}.{attr}"))

        spec.loader = Loader()
        return spec


@pytest.fixture
def no_heavy_work(monkeypatch):
    """Entries into real work raise :class:`HeavyWork`, in modules imported before or during
    the case."""
    pending: dict[str, list[str]] = {}
    for mod, attr in HEAVY:
        if mod in sys.modules:
            monkeypatch.setattr(sys.modules[mod], attr, _refuse(f"{mod}.{attr}"))
        else:
            pending.setdefault(mod, []).append(attr)
    finder = _PatchOnImport(monkeypatch, pending)
    sys.meta_path.insert(0, finder)
    try:
        yield
    finally:
        sys.meta_path.remove(finder)


@pytest.fixture
def run_cli(capsys):
    from windflutter.cli import main

    def call(argv):
        rc = main([str(a) for a in argv])
        out, err = capsys.readouterr()
        return rc, out, err

    return call



def instant_factory(turbine, config):
    """A back-end for tests of the run machinery (store, resume): an instant, deterministic
    'analysis' whose numbers are functions of the point alone (registered as ``instant``)."""
    import numpy as np

    from windflutter.workflow import PointResult

    def analyse(point, progress=None):
        rpm = np.asarray(point.sweep_rpm, float)
        return PointResult(flutter_rpm=20.0 + 0.1 * point.wind_speed, flutter_frequency_hz=1.0,
                           flutter_mode="1st flap", divergence_rpm=float("nan"), sweep_rpm=rpm,
                           damped_frequency_hz=np.outer(1.0 + 0.01 * rpm, [1.0, 2.0]),
                           damping_ratio=np.outer(0.05 - 0.001 * rpm * point.wind_speed / 10, [1.0, 0.5]),
                           mode_labels=["1st flap", "1st torsion"], info={"n_reduced_dof": 7})

    return analyse


def _register():
    from windflutter.backends import register_backend

    register_backend("instant", instant_factory)


_register()
