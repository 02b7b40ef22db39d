"""`windflutter section` (not implemented yet)."""

from __future__ import annotations

import argparse
import sys


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("section", help="(not implemented yet)")
    p.add_argument("args", nargs="*")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    print("windflutter section: not implemented yet", file=sys.stderr)
    return 2
