"""Command-line interface: ``windflutter COMMAND ...``.

Each sub-command lives in its own module of this package, exposing
``add_parser(subparsers)`` and ``run(args) -> int``.  This module only dispatches and turns
:class:`~windflutter.errors.InputError` into one clear line and a non-zero exit code.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from windflutter import __version__
from windflutter.errors import InputError, ModelError, WindflutterError

#: Sub-command modules, in the order shown by ``--help``.
COMMANDS = ("section", "simple", "wing", "modes", "mesh", "stability", "run")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="windflutter",
        description="Flutter and divergence of wind turbines from finite-element models.",
    )
    parser.add_argument("--version", action="version", version=f"windflutter {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name in COMMANDS:
        module = importlib.import_module(f"windflutter.cli.{name}")
        module.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``windflutter`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except InputError as exc:
        print(f"windflutter {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except ModelError as exc:
        print(f"windflutter {args.command}: model error: {exc}", file=sys.stderr)
        return 3
    except WindflutterError as exc:
        print(f"windflutter {args.command}: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 4
    except KeyboardInterrupt:
        print(f"windflutter {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # output piped into e.g. `head`, which closed early: not an error of ours
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
