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
    _added: set = field(default_factory=set)

    def add(self, name: str, func: Callable[[argparse.Namespace], Result | dict], help: str, *, group: str | None = None, description: str | None = None) -> argparse.ArgumentParser:
        """Add a command (or ``group`` subcommand) and return its parser for arguments."""
        subparsers = self._root if group is None else self._group(group)
        parser = subparsers.add_parser(name, help=help, description=description or help)
        self._added.add((group, name))
        parser.add_argument("--json", action="store_true", help="print exactly one JSON object on stdout")
        parser.set_defaults(_func=func)
        return parser

    def _group(self, group: str):
        if group not in self._groups:
            helps = {"algorithms": "the registry of algorithms: list it, show one", "derive": "regenerate a symbolic derivation", "reproduce": "reproduce published tables"}
            parser = self._root.add_parser(group, help=helps.get(group, group), description=helps.get(group, group))
            self._groups[group] = parser.add_subparsers(dest=f"{group}_command", metavar="SUBCOMMAND", parser_class=_Parser, required=True)
        return self._groups[group]


#: Every command, ``"name"`` or ``"group name"``, with the module that defines it and its help
#: line: ``strapdown --help`` lists them, and a call imports only the module of the command it
#: runs (the help is checked against what the module registers by tests/test_cli.py).
COMMANDS = {
    "algorithms list": ("algorithms", "list the registry: name, samples, previous samples read, order, source"),
    "algorithms show": ("algorithms", "one algorithm: terms as exact fractions, samples, history, second-order defect, order, source"),
    "align": ("align", "self-alignment on a rocking base (analytic, inertial-frame or Kalman) by Monte Carlo, with its theory"),
    "azimuth": ("azimuth", "Monte Carlo of the gyrocompass azimuth error under rocking against bounds (14), (15)"),
    "azimuth-design": ("azimuth", "largest admissible rocking amplitude against rocking frequency for an azimuth budget (tilt channel)"),
    "derive coning-drift": ("derive_coning_drift", "coning drift of an algorithm in closed form: coefficient · α² ω (ωh)^order, exact fraction"),
    "derive local-error": ("derive_local_error", "local-error series of an algorithm (exact fractions, LaTeX) to any order"),
    "derive lyapunov": ("lyapunov", "Lyapunov function and its derivative for the corrected stage (Plotnikov 1999, (3.2)-(3.4))"),
    "design": ("design", "largest step and computational load of each algorithm for a drift budget"),
    "drift": ("drift", "constant drift rate of an algorithm under regular precession (parallel computation)"),
    "multistage": ("multistage", "simulate the two-stage corrected attitude system of Plotnikov (1999), section 5"),
    "report": ("report", "regenerate every report (errata, algorithms, derivations, stability, azimuth)"),
    "reproduce tables": ("tables", "Budennyi et al. Table 3 (u*) and the Lebedev & Panov (1989) table: ours next to the printed values"),
    "stability": ("stability", "poles, damping, stability and peak tilt error of a corrected attitude stage (Plotnikov 1999)"),
    "velocity-error": ("velocity_error", "apparent-velocity error |ΔW_E|, |ΔW_I| of an algorithm's dual extension (dual regular precession or classical sculling)"),
}


def _command_modules() -> list:
    """Every command module of this package (also those not yet in :data:`COMMANDS`)."""
    return sorted(info.name for info in pkgutil.iter_modules(__path__) if not info.name.startswith("_"))


def _wanted(argv) -> list:
    """Modules needed to parse ``argv``: the one of the command it names (none for a bare listing)."""
    words = [a for a in argv if not a.startswith("-")]
    key = " ".join(words[:1]) if words[:1] and words[0] in COMMANDS else " ".join(words[:2])
    return [COMMANDS[key][0]] if key in COMMANDS else []


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """Build the parser: in full (``argv`` None), or just enough to parse ``argv``.

    With ``argv`` only the module of the command it names is imported; every
    other command of :data:`COMMANDS` is listed by its help line, so that
    ``strapdown --help`` and a call of a light command import nothing heavy.
    """
    parser = _Parser(prog="strapdown", description="Error analysis of strapdown inertial navigation algorithms.")
    parser.add_argument("--version", action="version", version=f"strapdown-analysis {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser, required=True)
    commands = Commands(sub)
    wanted = None if argv is None else _wanted(argv)
    declared = {module for module, _ in COMMANDS.values()}
    modules = _command_modules() if wanted is None else wanted + [m for m in _command_modules() if m not in declared]
    for name in modules:
        importlib.import_module(f"{__name__}.{name}").register(commands)
    for key, (_, help_text) in COMMANDS.items():
        group, _, name = key.rpartition(" ")
        if (group or None, name) not in commands._added:
            commands.add(name, None, help_text, group=group or None)
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
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(argv)
    args, _ = parser.parse_known_args(argv)
    # A command listed only by its help line (its module not loaded) is parsed by the full parser.
    args = (parser if args._func is not None else build_parser()).parse_args(argv)
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
