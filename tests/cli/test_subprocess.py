"""A few hostile inputs through a real ``windflutter`` process (the in-process cases cover the
rest): one line on stderr, exit code 2, nothing printed later by a library's clean-up."""

from __future__ import annotations

import subprocess
import sys
import time

from cli_cases import assert_one_line_error


def _windflutter(*args, timeout=60):
    t0 = time.monotonic()
    out = subprocess.run([sys.executable, "-m", "windflutter", *map(str, args)], capture_output=True, text=True,
                         timeout=timeout)
    return out.returncode, out.stdout, out.stderr, time.monotonic() - t0


def test_malformed_scheduler_is_one_line_and_quick(tmp_path):
    # before: the error, then 20 s later a `Client.__del__` traceback
    rc, _, err, dt = _windflutter("run", "nrel5mw", "-o", tmp_path / "out", "-q", "--scheduler", "tcp://nohost:abc")
    assert_one_line_error(rc, err, "--scheduler")
    assert "Exception ignored" not in err and dt < 30
    assert not (tmp_path / "out").exists()


def test_non_utf8_config(tmp_path):
    cfg = tmp_path / "a.yaml"
    cfg.write_bytes("title: Großwindanlage\n".encode("latin-1"))
    rc, _, err, _ = _windflutter("run", "nrel5mw", "-c", cfg, "-o", tmp_path / "out")
    assert_one_line_error(rc, err, "config", "UTF-8")
