"""Command-line interface: ``windflutter COMMAND ...``.

Each sub-command lives in its own module of this package, exposing
``add_parser(subparsers)`` and ``run(args) -> int``.  This module only dispatches, runs every
command under the BLAS-thread policy (:mod:`windflutter.threads`: one thread unless
``WINDFLUTTER_BLAS_THREADS`` says otherwise) and turns :class:`~windflutter.errors.InputError`
into one clear line and a non-zero exit code.

Nothing here imports NumPy before :func:`main` has applied the policy (the sub-command modules
are imported by :func:`build_parser`), so BLAS libraries start with the policy's thread count.
"""

from __future__ import annotations

import argparse
import functools
import importlib
import os
import sys

from windflutter import __version__, threads
from windflutter.errors import InputError, ModelError, WindflutterError, one_line
from windflutter.heap import keep_freed_memory

#: Sub-command modules, in the order shown by ``--help``.
COMMANDS = ("section", "simple", "wing", "modes", "mesh", "beam_properties", "stability", "campbell", "sensitivity",
            "simulate", "run")


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The parser of ``argv``'s sub-command alone when ``argv`` starts with one (the others'
    options are not built: they are never read), else of every command (``--help``, ``--version``,
    a mistyped command: the message lists them all).  Built once per command."""
    typed = {c.replace("_", "-"): c for c in COMMANDS}
    return _parser(typed.get(argv[0]) if argv else None)


@functools.lru_cache(maxsize=None)
def _parser(command: str | None) -> argparse.ArgumentParser:
    from windflutter.cli.options import OneLineParser  # noqa: PLC0415

    parser = OneLineParser(
        prog="windflutter",
        description="Flutter and divergence of wind turbines from finite-element models.",
    )
    parser.add_argument("--version", action="version", version=f"windflutter {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    sub.required = True
    for name in COMMANDS if command is None else (command,):
        module = importlib.import_module(f"windflutter.cli.{name}")
        module.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``windflutter`` console script; returns the exit code.

    Every problem is one line on stderr: bad input (exit 2, also argument errors), a file that
    cannot be written (2), a model that cannot be analysed (3), another windflutter error (4),
    Ctrl-C (130); an unexpected exception is one line too (exit 70), with the traceback only
    when the environment variable ``WINDFLUTTER_TRACEBACK`` is set.

    The command runs with ``WINDFLUTTER_BLAS_THREADS`` BLAS threads (default 1; ``auto``: the
    BLAS library's default), undone afterwards for an in-process call
    (:func:`windflutter.threads.policy_scope`); freed memory is kept for reuse
    (:func:`windflutter.heap.keep_freed_memory`).
    """
    keep_freed_memory()
    with threads.policy_scope():
        return _main(argv)


def _main(argv: list[str] | None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(argv)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a usage error already printed in one line
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    prog = f"windflutter {args.command}"
    from windflutter.cli.warn import one_line_warnings  # noqa: PLC0415

    try:
        with one_line_warnings(prog):
            return int(args.func(args) or 0)
    except InputError as exc:
        print(f"{prog}: error: {one_line(exc)}", file=sys.stderr)
        return 2
    except ModelError as exc:
        print(f"{prog}: model error: {one_line(exc)}", file=sys.stderr)
        return 3
    except WindflutterError as exc:
        print(f"{prog}: {type(exc).__name__}: {one_line(exc)}", file=sys.stderr)
        return 4
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # output piped into e.g. `head`, which closed early: not an error of ours
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except OSError as exc:  # a file that could not be written or read after the up-front checks
        where = f": {exc.filename}" if getattr(exc, "filename", None) else ""
        print(f"{prog}: error: file error ({exc.strerror or type(exc).__name__}){where}", file=sys.stderr)
        return 2
    except Exception as exc:  # noqa: BLE001 - a bug of ours: still one line, unless asked for more
        if os.environ.get("WINDFLUTTER_TRACEBACK"):
            raise
        print(f"{prog}: internal error: {type(exc).__name__}: {one_line(exc)[:300]} (please report it; "
              "set WINDFLUTTER_TRACEBACK=1 for the traceback)", file=sys.stderr)
        return 70


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
