"""The BLAS-thread policy (windflutter.threads, docs/installation.md "BLAS threads").

The reference is what the BLAS libraries themselves report (``threadpoolctl.threadpool_info``,
read in the test, not through windflutter), in fresh interpreters: the test session already runs
under the policy, so only a new process shows what happens before and after windflutter is
imported. Each probe sets ``OPENBLAS_NUM_THREADS=2`` first, as a user might, so that "1 thread"
can only come from the policy; the opt-out probes show that same 2 coming back, which is also
the proof that the check can fail. On a machine with one core OpenBLAS cannot run 2 threads and
the probes that need 2 are skipped. (A number other than 1 is checked in-process, with
:func:`windflutter.threads.policy_scope`, which the CLI runs every command in.)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

from pathlib import Path

import pytest

import windflutter
from windflutter import threads
from windflutter.errors import InputError, InputWarning

CORES = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
needs_two_cores = pytest.mark.skipif(CORES < 2, reason="OpenBLAS runs at most one thread per core")

HP_YAML = "semi_chord: 1.0\nelastic_axis: -0.2\nmass_ratio: 20\nx_alpha: 0.1\nr_alpha_squared: 0.24\n" \
          "omega_h: 0.4\nomega_alpha: 1.0\n"

#: A CLI run: record the BLAS threads from inside the command (the sub-command's ``run`` is
#: wrapped before the parser is built), then print them as JSON.
CLI_PROBE = textwrap.dedent("""
    import json, sys
    import windflutter.cli as cli
    before_main = "numpy" in sys.modules
    import windflutter.cli.section as section
    seen = {}
    original = section.run
    def recording_run(args):
        import scipy.linalg, threadpoolctl
        seen["threads"] = [d["num_threads"] for d in threadpoolctl.threadpool_info() if d["user_api"] == "blas"]
        return original(args)
    section.run = recording_run
    rc = cli.main(["section", sys.argv[1], "--json"])
    print(json.dumps({"rc": rc, "numpy_before_main": before_main, **seen}))
""")

#: An API call: NumPy's BLAS is loaded before windflutter (the library must be limited after the
#: fact), SciPy's after it (the library must start limited); then a typical-section analysis.
API_PROBE = textwrap.dedent("""
    import json
    import numpy, threadpoolctl
    def blas():
        return [d["num_threads"] for d in threadpoolctl.threadpool_info() if d["user_api"] == "blas"]
    preloaded = blas()
    from windflutter.section import TypicalSection, pk_method
    import scipy.linalg
    res = pk_method(TypicalSection.from_nondimensional(semi_chord=1.0, elastic_axis=-0.2, mass_ratio=20.0,
                    x_alpha=0.1, r_alpha_squared=0.24, omega_h=0.4, omega_alpha=1.0))
    print(json.dumps({"preloaded": preloaded, "threads": blas(), "flutter": res.flutter_speed}))
""")


def _probe(code: str, *args: str, policy: str | None, tmp_path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in threads.BLAS_ENV_VARS and k != threads.ENV_VAR}
    env["OPENBLAS_NUM_THREADS"] = "2"
    # the windflutter under test, whatever the working directory
    src = str(Path(windflutter.__file__).resolve().parents[1])
    env["PYTHONPATH"] = os.pathsep.join([src] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    if policy is not None:
        env[threads.ENV_VAR] = policy
    out = subprocess.run([sys.executable, "-c", code, *args], env=env, cwd=tmp_path, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def hp_yaml(tmp_path_factory):
    p = tmp_path_factory.mktemp("threads") / "hp.yaml"
    p.write_text(HP_YAML)
    return str(p)


@needs_two_cores
@pytest.mark.parametrize("policy, expected", [(None, 1), ("auto", 2)])
def test_cli_command_runs_under_the_policy(hp_yaml, tmp_path, policy, expected):
    got = _probe(CLI_PROBE, hp_yaml, policy=policy, tmp_path=tmp_path)
    assert got["rc"] == 0
    assert not got["numpy_before_main"]  # the policy is in place before any BLAS library loads
    assert len(got["threads"]) >= 1 and set(got["threads"]) == {expected}, got


@needs_two_cores
def test_api_call_runs_under_the_policy(tmp_path):
    got = _probe(API_PROBE, policy=None, tmp_path=tmp_path)
    assert set(got["preloaded"]) == {2}  # NumPy's BLAS came up with the user's 2 threads
    assert len(got["threads"]) >= 2 and set(got["threads"]) == {1}, got  # NumPy's and SciPy's
    assert got["flutter"] == pytest.approx(2.18391, abs=5e-5)  # docs/installation.md's example


@pytest.mark.parametrize("raw, expected", [("", 1), ("1", 1), (" 3 ", 3), ("auto", None), ("AUTO", None)])
def test_the_variable_is_read(raw, expected):
    assert threads.configured_threads({threads.ENV_VAR: raw}) == expected
    assert threads.configured_threads({}) == threads.DEFAULT_THREADS == 1


@pytest.mark.parametrize("raw", ["0", "-1", "1.5", "two", "1 2"])
def test_a_bad_value_names_the_variable(raw, monkeypatch):
    with pytest.raises(InputError, match=threads.ENV_VAR) as err:
        threads.configured_threads({threads.ENV_VAR: raw})
    assert err.value.field == threads.ENV_VAR and err.value.value == raw
    # where an exception would break ``import windflutter``: one warning, and the default
    monkeypatch.setenv(threads.ENV_VAR, raw)
    monkeypatch.setattr(threads, "_WARNED", {})
    with pytest.warns(InputWarning, match=f"{threads.ENV_VAR}.*using 1"):
        with threads.policy_scope() as n:
            assert n == 1


@needs_two_cores
def test_policy_scope_restores_the_process(monkeypatch):
    """An in-process CLI call (tests, notebooks) leaves the caller's threads and variables as
    they were."""
    import scipy.linalg  # noqa: F401
    import threadpoolctl

    # the reference: what each loaded library gives for 2 threads when threadpoolctl is asked
    # directly (a single-threaded build, e.g. kvxopt's OpenBLAS, stays at 1)
    with threadpoolctl.threadpool_limits(2, user_api="blas"):
        capable = threads.blas_thread_counts()
    assert 2 in capable.values()
    before, env_before = threads.blas_thread_counts(), {v: os.environ.get(v) for v in threads.BLAS_ENV_VARS}
    monkeypatch.setenv(threads.ENV_VAR, "2")
    with threads.policy_scope() as n:
        assert n == 2
        assert threads.blas_thread_counts() == capable
        assert os.environ["OPENBLAS_NUM_THREADS"] == "2"
    assert threads.blas_thread_counts() == before
    assert {v: os.environ.get(v) for v in threads.BLAS_ENV_VARS} == env_before


def test_the_test_session_runs_under_the_policy():
    """tests/conftest.py: the session itself (unless WINDFLUTTER_BLAS_THREADS says otherwise)."""
    import scipy.linalg  # noqa: F401  (both BLAS libraries loaded)

    n = threads.configured_threads()
    counts = set(threads.blas_thread_counts().values())
    if n is not None:
        assert counts == {n}


def test_blas_limit_is_scoped():
    import scipy.linalg  # noqa: F401

    with threads.blas_limit(1):
        assert set(threads.blas_thread_counts().values()) == {1}
    with threads.blas_limit(None):
        pass
