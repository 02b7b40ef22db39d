"""Warnings at the command line: one line each, ``windflutter COMMAND: warning: ...``.

Python's default shows a warning as two lines with the file and source line of the code that
raised it, which means nothing to the user of a command.  :func:`one_line_warnings` replaces that
for the duration of every command (the entry point, :func:`windflutter.cli.main`); the local
worker processes of ``run`` print theirs in one line too (:mod:`windflutter.parallel`).
"""

from __future__ import annotations

import contextlib
import sys
import warnings

from windflutter.errors import one_line


@contextlib.contextmanager
def one_line_warnings(prog: str, stream=None):
    """Within the block, every shown warning is printed as ``PROG: warning: MESSAGE`` (whitespace
    folded to one line) on ``stream`` (default stderr), each text once (a run's worker processes
    and its Campbell each build the model and would repeat its warnings); the filters are
    unchanged."""
    shown: set[str] = set()

    def show(message, category, filename, lineno, file=None, line=None):  # noqa: ARG001
        text = one_line(message)
        if text in shown:
            return
        shown.add(text)
        print(f"{prog}: warning: {text}", file=stream or file or sys.stderr)

    with warnings.catch_warnings():
        warnings.showwarning = show
        yield
