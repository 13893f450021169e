"""Command-line interface: ``strapdown <command> [options] [--json]``.

Commands live in the modules of this package; each module defines
``register(commands)`` and adds its commands through :class:`Commands`.  Every
command accepts ``--json`` and then prints exactly one JSON object on stdout;
progress bars and logs go to stderr.  A bad argument or a ``ValueError`` /
``TypeError`` raised by the library prints one line on stderr and exits with
status 2, without a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import pkgutil
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from .. import __version__

__all__ = ["main", "Commands", "Result", "UsageError"]


class UsageError(Exception):
    """A command-line usage problem detected after parsing (exit status 2)."""


@dataclass
class Result:
    """What a command returns: JSON-able ``data`` and an optional human ``text``."""

    data: dict
    text: str | None = None


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit status 2."""

    def error(self, message):  # noqa: D401 - argparse API
        sys.stderr.write(f"{self.prog}: error: {message}\n")
        sys.exit(2)


@dataclass
class Commands:
    """Registry handed to each command module's ``register`` function."""

    _root: Any
    _groups: dict = field(default_factory=dict)

    def add(self, name: str, func: Callable[[argparse.Namespace], Result | dict], help: str, *, group: str | None = None, description: str | None = None) -> argparse.ArgumentParser:
        """Add a command (or ``group`` subcommand) and return its parser for arguments."""
        subparsers = self._root if group is None else self._group(group)
        parser = subparsers.add_parser(name, help=help, description=description or help)
        parser.add_argument("--json", action="store_true", help="print exactly one JSON object on stdout")
        parser.set_defaults(_func=func)
        return parser

    def _group(self, group: str):
        if group not in self._groups:
            helps = {"derive": "regenerate a symbolic derivation", "reproduce": "reproduce published tables"}
            parser = self._root.add_parser(group, help=helps.get(group, group), description=helps.get(group, group))
            self._groups[group] = parser.add_subparsers(dest=f"{group}_command", metavar="SUBCOMMAND", parser_class=_Parser, required=True)
        return self._groups[group]


def build_parser() -> argparse.ArgumentParser:
    """Build the full parser from every command module of this package."""
    parser = _Parser(prog="strapdown", description="Error analysis of strapdown inertial navigation algorithms.")
    parser.add_argument("--version", action="version", version=f"strapdown-analysis {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser, required=True)
    commands = Commands(sub)
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        module.register(commands)
    return parser


def _jsonable(obj):
    if isinstance(obj, float) and not math.isfinite(obj):
        return None if math.isnan(obj) else ("inf" if obj > 0 else "-inf")
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if hasattr(obj, "tolist"):
        return _jsonable(obj.tolist())
    if hasattr(obj, "item"):
        return _jsonable(obj.item())
    return obj


def _human(data: dict) -> str:
    lines = []
    for key, value in data.items():
        if isinstance(value, float):
            value = f"{value:.6g}"
        lines.append(f"{key}: {value}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``strapdown`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        result = args._func(args)
    except (ValueError, TypeError, UsageError, FileNotFoundError) as exc:
        message = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        sys.stderr.write(f"strapdown {args.command}: error: {message}\n")
        return 2
    if isinstance(result, dict):
        result = Result(result)
    if args.json:
        sys.stdout.write(json.dumps(_jsonable(result.data), allow_nan=False) + "\n")
    else:
        sys.stdout.write((result.text if result.text is not None else _human(result.data)) + "\n")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
