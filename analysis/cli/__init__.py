"""Command-line interface: ``strapdown <command> [options] [--json]``.

Commands live in the modules of this package; each module defines
``register(commands)`` and adds its commands through :class:`Commands`.

The contract of every command
-----------------------------
* With ``--json`` it prints exactly one JSON object on stdout, with no NaN or
  infinity: a result that comes out NaN or infinite means the arguments lie
  outside the range where the model is defined, and is refused like a bad
  argument.
* A bad argument prints one line on stderr, ``strapdown <command>: error:
  <message>``, naming the option as typed, and exits with status 2, without a
  traceback.  This holds for argparse errors, for ``ValueError`` /
  ``TypeError`` raised by the library (the message names the Python argument,
  and the option it came from is put in front: ``argument --duration: ...``),
  for work refused by its estimate (:mod:`strapdown.analysis.core.budget`), for
  operating-system errors (a directory given as a file, an unreadable file, a
  read-only output directory), and for ``MemoryError``, ``RecursionError`` and
  arithmetic errors (division by zero, overflow).
* Who names the option: a check in a command module names it as typed
  (``Expected `--lat-deg` in (-90, 90) degrees, got 90``) and checks only what
  the command line alone knows (values in the unit typed, relations between
  options, the sizes of a work estimate, options the library knows under
  another name); every other value goes to the library unchecked, whose message
  names the Python argument, and the edge puts the option in front
  (``argument --duration: Expected `duration` > 0, got 0.0``).  An option that
  applies only with some values of another is declared with
  :meth:`Commands.only_with` and refused, not ignored, with the others.
* Ctrl-C prints one line and exits with status 130.
* Numerical warnings (numpy's ``RuntimeWarning``) never reach stderr; other
  warnings are printed as one line each.
* Work longer than a few seconds shows its progress on stderr
  (:mod:`strapdown.analysis.core.progress`): bars on a terminal, and
  otherwise (a log, a pipe, a notebook) a plain line at least every few
  seconds with what runs, the fraction done and the time elapsed; ``--quiet``
  (or ``--no-progress``) turns it off.

Any other exception is a defect of the package: it prints one line asking for
a report and exits with status 70.  ``STRAPDOWN_DEBUG=1`` in the environment
shows the traceback of every error instead, and the numerical warnings.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import json
import math
import os
import pkgutil
import re
import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from .. import __version__
from ..core.progress import activity, lines, mode, wanted

__all__ = ["main", "script", "build_parser", "plain_text", "Commands", "Result", "UsageError", "EXIT_USAGE", "EXIT_INTERRUPTED", "EXIT_SOFTWARE"]

#: Exit status of a bad argument (argparse's convention).
EXIT_USAGE = 2
#: Exit status after Ctrl-C (128 + SIGINT).
EXIT_INTERRUPTED = 130
#: Exit status of a defect of the package (``EX_SOFTWARE`` of sysexits.h).
EXIT_SOFTWARE = 70


class UsageError(Exception):
    """A command-line usage problem detected after parsing (exit status 2)."""


@dataclass
class Result:
    """What a command returns.

    Attributes
    ----------
    data : dict
        JSON-able result (printed with ``--json``); every number must be finite.
    text : str or None
        Text for people (default: one ``key: value`` line per entry of ``data``).
    """

    data: dict
    text: str | None = None


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit status 2.

    A value such as ``-1e-3`` or ``-inf`` is read as a (negative) number, not as
    an option: ``--eps -1e-3`` works as typed.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)

    def error(self, message):  # noqa: D401 - argparse API
        _say(self.prog, "error: " + _one_line(message))
        sys.exit(EXIT_USAGE)


class _Given:
    """Default of an option declared with :meth:`Commands.only_with`: tells a default from a value typed."""

    def __init__(self, value):
        self.value = value

    def __repr__(self):
        return repr(self.value)

    def __str__(self):
        return str(self.value)

    def __format__(self, spec):
        return format(self.value, spec)


def _apply_rules(args) -> None:
    """Refuse options given where they do not apply; replace untouched defaults by their values."""
    for dest, option, other_dest, other, values in getattr(args, "only_with_", None) or ():
        value = getattr(args, dest)
        if isinstance(value, _Given):
            setattr(args, dest, value.value)
        elif getattr(args, other_dest) not in values:
            allowed = " or ".join(str(v) for v in values)
            raise UsageError(f"{option} does not apply to {other} {getattr(args, other_dest)} (it applies to {other} {allowed})")


@dataclass
class Commands:
    """Registry handed to each command module's ``register`` function.

    Attributes
    ----------
    root : argparse._SubParsersAction
        The subparsers of ``strapdown`` (commands are added to it, or to a group under it).
    listing : list of (str, str)
        Every command added so far, as (full name, one-line help), for ``strapdown --help``.
    """

    root: Any
    listing: list = field(default_factory=list)
    _groups: dict = field(default_factory=dict, init=False, repr=False)

    def add(
        self,
        name: str,
        func: Callable[[argparse.Namespace], Result | dict],
        help: str,
        *,
        group: str | None = None,
        description: str | None = None,
        progress: str = "activity",
    ) -> argparse.ArgumentParser:
        """Add a command (or ``group`` subcommand) and return its parser for arguments.

        Parameters
        ----------
        name : str
            Command name, kebab-case.
        func : callable
            ``func(args) -> Result | dict``; raise ``ValueError`` / ``TypeError`` on bad input.
        help : str
            One line for ``strapdown --help``.
        group : str, optional, keyword-only
            Parent command (``"derive"``, ``"reproduce"``), created on first use.
        description : str, optional, keyword-only
            Longer text for ``strapdown <command> --help`` (default ``help``).
        progress : {"activity", "own"}, keyword-only
            ``"activity"``: the edge shows the elapsed time on stderr once the
            command runs longer than two seconds (on a terminal); ``"own"``: the
            command draws its own progress bar (it reads ``args.progress``).
            Where stderr is not a terminal, the edge writes progress lines for
            both (:func:`strapdown.analysis.core.progress.lines`), refined by
            the bars of the command.

        Returns
        -------
        argparse.ArgumentParser
            The command's parser, with ``--json``, ``--quiet`` and ``--no-progress`` already added.
        """
        if progress not in ("activity", "own"):
            raise ValueError(f"Expected `progress` in ('activity', 'own'), got {progress!r}")
        help, description = plain_text(help), None if description is None else plain_text(description)
        if group is None:  # `strapdown --help` lists the commands itself, one line each (build_parser)
            parser = self.root.add_parser(name, description=description or help)
        else:
            parser = self._group(group).add_parser(name, help=help, description=description or help)
        parser.add_argument("--json", action="store_true", help="print exactly one JSON object on stdout")
        parser.add_argument(
            "--quiet", action="store_true", help="no progress on stderr (by default: bars on a terminal, otherwise a plain line every few seconds for work that lasts)"
        )
        parser.add_argument("--no-progress", dest="no_progress", action="store_true", help="the same as --quiet")
        parser.set_defaults(func_=func, parser_=parser, command_=name if group is None else f"{group} {name}", progress_mode_=progress)
        self.listing.append((name if group is None else f"{group} {name}", help))
        return parser

    def only_with(self, parser, option: str, other: str, values) -> None:
        """Declare that ``option`` applies only when ``other`` takes one of ``values``.

        Giving ``option`` explicitly with another value of ``other`` is then
        refused with a one-line error (``--period does not apply to --rocking
        normal (it applies to --rocking sine or narrowband)``) instead of being
        ignored.  A flag (``store_true``) can be declared too.  The default of
        ``option`` is what the command sees when the option is not given.

        Parameters
        ----------
        parser : argparse.ArgumentParser
            The command's parser (from :meth:`add`), on which both options are defined.
        option : str
            The option that may not apply, e.g. ``"--period"``.
        other : str
            The option that decides, e.g. ``"--rocking"``.
        values : iterable of str
            Values of ``other`` with which ``option`` applies.
        """
        actions = {s: a for a in parser._actions for s in a.option_strings}
        if option not in actions or other not in actions:
            raise ValueError(f"Expected options of this parser, got {option!r} and {other!r}")
        action = actions[option]
        if not isinstance(action.default, _Given):
            action.default = _Given(action.default)
        rules = list(parser.get_default("only_with_") or [])
        rules.append((action.dest, option, actions[other].dest, other, tuple(values)))
        parser.set_defaults(only_with_=rules)

    def _group(self, group: str):
        if group not in self._groups:
            helps = {
                "algorithms": "the registry of algorithms: list it, show one",
                "derive": "regenerate a symbolic derivation",
                "log": "recorded IMU logs: inspect one, its vibration environment, algorithms replayed on it, the noise of a static stretch",
                "reproduce": "reproduce published tables",
            }
            parser = self.root.add_parser(group, description=helps.get(group, group))
            self._groups[group] = parser.add_subparsers(dest=f"{group}_command", metavar="SUBCOMMAND", parser_class=_Parser, required=True)
        return self._groups[group]


#: Every command, ``"name"`` or ``"group name"``, with the module that defines it and its help
#: line: ``strapdown --help`` lists them, and a call imports only the module of the command it
#: runs (the help is checked against what the module registers by tests/test_cli.py).
COMMANDS = {
    "algorithms list": ("algorithms", "list the registry: name, samples, previous samples read, accuracy, local-error and coning-drift orders, source"),
    "algorithms show": ("algorithms", "one algorithm: terms as exact fractions, samples, history, second-order defect, orders, source"),
    "align": ("align", "self-alignment on a rocking base (analytic, inertial-frame or Kalman) by Monte Carlo, with its theory"),
    "azimuth": ("azimuth", "Monte Carlo of the gyrocompass azimuth error under rocking against bounds (14), (15)"),
    "azimuth-design": ("azimuth", "largest admissible rocking amplitude against rocking frequency for an azimuth budget (tilt channel)"),
    "budget": ("budget", "error budget of an IMU at rest over its mission: attitude, velocity and horizontal position error per source, the total, the dominant source"),
    "derive coning-drift": ("derive_coning_drift", "coning drift of an algorithm in closed form: coefficient · α² ω (ωh)^m, the next term in α and where the leading term holds"),
    "derive local-error": ("derive_local_error", "local-error series of an algorithm, every weight through h^K (exact fractions, LaTeX)"),
    "derive lyapunov": ("lyapunov", "Lyapunov function and its derivative for the corrected stage (Plotnikov 1999, (3.2)-(3.4))"),
    "design": ("design", "largest step and computational load of each algorithm for a drift budget"),
    "design-coning": ("environment", "coning algorithm tuned to a vibration environment: coefficients, algorithm file, drift across the band"),
    "design-sculling": ("environment", "sculling (velocity) algorithm tuned to a vibration environment: coefficients and algorithm file"),
    "drift": ("drift", "constant drift rate of an algorithm under regular precession or classical coning (parallel computation, series, exact)"),
    "environment-drift": ("environment", "mean coning drift and sculling rectification of an algorithm in a vibration environment (closed form)"),
    "environment-rates": ("environment", "lowest sample rate and load of each algorithm, classical and tuned, for a drift budget in an environment"),
    "log allan": ("log_analysis", "Allan deviation of a static log: ARW, bias instability and RRW with intervals, written as a sensor file"),
    "log coning": ("log_analysis", "replay coning algorithms on a log: mean correction rate of each, their exact drift differences, the closed form beside"),
    "log environment": ("log_analysis", "vibration environment of a log: lines and cross-spectra with intervals, written as an environment file"),
    "log inspect": ("log_inspect", "what a recorded IMU log holds: streams, rate, gaps, units, frame, sensor filters, plausibility checks"),
    "mount-environment": ("mount", "a base vibration profile through an IMU mount: modes, rms, and the IMU's cross-spectra as an environment file"),
    "identify": ("identify", "identify a user's coning and sculling code as an exact algorithm: terms, consistency, orders, drift, remainder, check"),
    "observability": ("observability", "rank, unobservable directions and degree of observability of the alignment error states"),
    "multistage": ("multistage", "simulate the two-stage corrected attitude system of Plotnikov (1999), section 5"),
    "report": ("report", "regenerate every report (errata, algorithms, derivations, stability, azimuth, index, HTML)"),
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

    Parameters
    ----------
    argv : list of str, optional
        The command line to be parsed (default: build every command).

    Returns
    -------
    argparse.ArgumentParser
        ``strapdown``'s parser; its help lists every command, one line each.
    """
    parser = _Parser(prog="strapdown", description="Error analysis of strapdown inertial navigation algorithms.", formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"strapdown-analysis {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser, required=True, help="one of the commands below; `strapdown COMMAND --help` for its options")
    commands = Commands(sub)
    wanted_modules = None if argv is None else _wanted(argv)
    declared = {module for module, _ in COMMANDS.values()}
    modules = _command_modules() if wanted_modules is None else wanted_modules + [m for m in _command_modules() if m not in declared]
    for name in modules:
        importlib.import_module(f"{__name__}.{name}").register(commands)
    added = {full for full, _ in commands.listing}
    for key, (_, help_text) in COMMANDS.items():
        if key not in added:
            group, _, name = key.rpartition(" ")
            commands.add(name, None, help_text, group=group or None)
    width = max(len(name) for name, _ in commands.listing)
    lines = [f"  {name:<{width}}  {_one_line(text)}" for name, text in sorted(commands.listing)]
    parser.epilog = "commands:\n" + "\n".join(lines)
    return parser


#: A Sphinx cross-reference: ``:role:`~dotted.name``` or ``:role:`title <dotted.name>```.
_ROLE = re.compile(r":(?:py:)?(?:class|func|meth|mod|attr|data|obj|exc|ref|doc):`(~?)([^`<]*?)(?:\s*<([^`>]*)>)?`")


def plain_text(text: str) -> str:
    """``text`` (a docstring paragraph) as a terminal shows it: Sphinx roles and literal markup removed.

    ``:class:`~a.b.C``` becomes ``C``, ``:func:`a.b.f``` becomes ``a.b.f``,
    a titled reference its title, and double backticks are dropped, so that
    ``--help`` never shows reStructuredText.

    Parameters
    ----------
    text : str
        Help or description text, possibly with reStructuredText markup.

    Returns
    -------
    str

    Examples
    --------
    >>> plain_text("an :class:`~strapdown.analysis.coning.integrators.interface.Integrator` (``assess``)")
    'an Integrator (assess)'
    """

    def role(match):
        tilde, target, titled = match.groups()
        if titled is not None:
            return target.strip() or titled
        return target.rsplit(".", 1)[-1] if tilde else target

    return _ROLE.sub(role, str(text)).replace("``", "")


def _one_line(text: str) -> str:
    """The first non-empty line of ``text``, whitespace collapsed."""
    for line in str(text).splitlines():
        if line.strip():
            return " ".join(line.split())
    return ""


def _say(prog: str, message: str) -> None:
    sys.stderr.write(f"{prog}: {message}\n")
    sys.stderr.flush()


def _jsonable(obj):
    """Plain JSON types (numpy scalars and arrays unwrapped); non-finite floats kept for the check."""
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if hasattr(obj, "tolist"):
        return _jsonable(obj.tolist())
    if hasattr(obj, "item"):
        return _jsonable(obj.item())
    return obj


def _non_finite(obj, path: str = ""):
    """Path and value of the first NaN or infinite number in ``obj`` (or None)."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return path or "result", obj
    if isinstance(obj, dict):
        for k, v in obj.items():
            found = _non_finite(v, f"{path}.{k}" if path else str(k))
            if found:
                return found
    if isinstance(obj, list):
        for i, v in enumerate(obj):
            found = _non_finite(v, f"{path}[{i}]")
            if found:
                return found
    return None


def _human(data: dict) -> str:
    lines = []
    for key, value in data.items():
        if isinstance(value, float):
            value = f"{value:.6g}"
        lines.append(f"{key}: {value}")
    return "\n".join(lines)


def _write_stdout(text: str) -> None:
    try:
        sys.stdout.write(text)
    except UnicodeEncodeError:  # e.g. PYTHONIOENCODING=ascii and a Greek letter in the text
        encoding = getattr(sys.stdout, "encoding", None) or "ascii"
        sys.stdout.write(text.encode(encoding, "backslashreplace").decode(encoding))
    sys.stdout.flush()


# --------------------------------------------------------------------------- errors
_TICKED = re.compile(r"`(-{0,2}[A-Za-z_][\w-]*)`")  # a Python name, or an option the message names itself


def _option_strings(parser) -> dict:
    """``dest → option string as typed`` for the options of a command's parser."""
    out = {}
    for action in getattr(parser, "_actions", ()):
        longs = [s for s in action.option_strings if s.startswith("--")]
        if longs:
            out[action.dest] = longs[0]
    return out


_UNIT_SUFFIXES = ("s", "m", "hz", "deg", "rad", "rad_s", "deg_per_h", "deg_per_rt_h", "m_s", "m_s2", "m_s_per_rt_h", "ppm", "arcsec", "mb", "per_s", "per_s2")


def _option_for(name: str, args) -> str | None:
    """The option a Python argument name of a library message refers to (None if unclear).

    By dest (``duration`` → ``--duration``), by dest with a unit suffix
    (``natural_frequency`` → ``--natural-frequency-rad-s``, ``accel`` →
    ``--accel-m-s2``), then by the words of the name in exactly one option's
    help (``latitude`` → ``--lat-deg``, "initial latitude [deg]").
    """
    parser = getattr(args, "parser_", None)
    options = _option_strings(parser)
    dest = name.lstrip("-").replace("-", "_")
    if dest in options:
        return options[dest]
    suffixed = [options[d] for d in options if any(d == f"{dest}_{u}" for u in _UNIT_SUFFIXES)]
    if len(suffixed) == 1:
        return suffixed[0]
    words = dest.replace("_", " ").lower()
    if len(words) > 3:
        helped = [a for a in getattr(parser, "_actions", ()) if a.help and words in a.help.lower() and any(o.startswith("--") for o in a.option_strings)]
        if len(helped) == 1:
            return [o for o in helped[0].option_strings if o.startswith("--")][0]
    return None


def _typed(flag: str, argv) -> bool:
    """Whether ``flag`` was typed in ``argv`` (in full or as the abbreviation argparse accepts)."""
    for token in argv or ():
        word = token.split("=", 1)[0]
        if word.startswith("--") and len(word) > 2 and flag.startswith(word):
            return True
    return False


def _blame(message: str, args, argv=()) -> str:
    """Name the option a library message is about: ``argument --duration: ...``.

    The library names the Python argument (``duration``); the user typed
    ``--duration``.  The option is found from a backticked name in the message
    (:func:`_option_for`) that the user typed (a value the command derived,
    such as a gain designed from ``--natural-frequency-rad-s``, is not blamed
    on an option left at its default), or from an option value (a file name)
    that the message quotes; a message about several typed options names them
    all (``arguments --step and --duration: ...``).  A message that names no
    option gets the options given on the command line appended, so that the
    user sees what was refused.
    """
    parser = getattr(args, "parser_", None)
    options = _option_strings(parser)
    flags = []
    for name in _TICKED.findall(message):
        found = _option_for(name, args)
        if found and (not argv or _typed(found, argv)) and found not in flags:
            flags.append(found)
    if len(flags) > 1:  # a relation between options: name every one the user typed
        if all(re.search(rf"(^|[\s`(]){re.escape(f)}(?![\w-])", message) for f in flags):
            return message
        return f"arguments {', '.join(flags[:-1])} and {flags[-1]}: {message}"
    flag = flags[0] if flags else None
    if flag is None:
        words = re.split(r"[\s'\"]+", message)
        choices = {a.dest for a in getattr(parser, "_actions", ()) if a.choices is not None}
        for dest, option in options.items():
            value = getattr(args, dest, None)
            values = [v for v in (value if isinstance(value, list | tuple) else [value]) if isinstance(v, str) and len(v) >= 2]  # an option given several times holds a list
            if dest in choices or not values or (argv and not _typed(option, argv)):
                continue  # a default the user did not type is never blamed
            if any(w.strip(":,;()") == v or f"{v!r}" in message for v in values for w in words):
                flag = option
                break
    if flag is not None:
        return message if re.search(rf"(^|[\s`(]){re.escape(flag)}(?![\w-])", message) else f"argument {flag}: {message}"
    if re.search(r"(^|[\s`(])--[a-z]", message):
        return message
    given = _given(argv)
    return f"{message} (given: {given})" if given else message


#: Options that set how a command runs, not what it computes (left out of "given: ..." lists).
_QUIET = {"--json", "--quiet", "--no-progress", "--progress", "--time-limit", "--memory-limit-mb"}


def _given(argv) -> str:
    """The options given on the command line, for messages that cannot name one argument."""
    pairs, tokens, i = [], list(argv or []), 0
    while i < len(tokens):
        token = tokens[i]
        if token.startswith("--") and "=" in token:
            flag, value = token.split("=", 1)
            i += 1
        elif token.startswith("--") and i + 1 < len(tokens) and not tokens[i + 1].startswith("--"):
            flag, value = token, tokens[i + 1]
            i += 2
        else:
            i += 1
            continue
        if flag not in _QUIET:
            pairs.append(f"{flag} {value[:40]}")
    return ", ".join(pairs)


def _as_options(text: str, args) -> str:
    """``text`` with each backticked Python argument replaced by its option: `` `horizon` = 3e+09 s`` → ``--horizon 3e+09 s``."""

    def option(match):
        return _option_for(match.group(1), args) or match.group(0)

    return re.sub(r"`([A-Za-z_]\w*)`(?: =)?", option, text)


def _budget_message(exc, args) -> str:
    from ..core.budget import format_bytes, format_seconds

    options = _option_strings(getattr(args, "parser_", None))
    what = _as_options(exc.estimate.what, args)
    if exc.resource == "memory":
        flag = options.get("memory_limit_mb", "--memory-limit-mb")
        return (
            f"{what} needs an estimated {format_bytes(exc.estimate.memory)} of memory, "
            f"over the limit of {format_bytes(exc.limits.memory)}; reduce the request or raise the limit with {flag}"
        )
    flag = options.get("time_limit", "--time-limit")
    return (
        f"{what} would take an estimated {format_seconds(exc.estimate.seconds)}, "
        f"over the limit of {format_seconds(exc.limits.seconds)}; reduce the request or raise the limit with {flag} (seconds)"
    )


#: numpy's ValueErrors for an array too large to allocate: treated like MemoryError.
_TOO_LARGE = ("Maximum allowed size exceeded", "array is too big")


def _message(exc: BaseException, args, argv) -> tuple[str, int]:
    """The one-line message and the exit status for an exception raised by a command."""
    given = _given(argv) or "the defaults"
    from ..core.budget import BudgetExceeded  # imported on an error only: it pulls in numpy

    if isinstance(exc, BudgetExceeded):
        return _budget_message(exc, args), EXIT_USAGE
    if isinstance(exc, MemoryError) or (isinstance(exc, ValueError) and str(exc).startswith(_TOO_LARGE)):
        return f"out of memory: the request is too large for this machine (given: {given})", EXIT_USAGE
    if isinstance(exc, UnicodeDecodeError):
        return _blame(f"expected UTF-8 text, got undecodable bytes ({exc.reason} at byte {exc.start})", args, argv), EXIT_USAGE
    if isinstance(exc, (ValueError, TypeError, UsageError)):
        return _blame(_one_line(str(exc)) or type(exc).__name__, args, argv), EXIT_USAGE
    if isinstance(exc, OSError):
        what = exc.strerror or _one_line(str(exc)) or type(exc).__name__
        target = exc.filename if exc.filename is not None else ""
        return _blame(f"{what}: {target!r}" if target else what, args, argv), EXIT_USAGE
    if isinstance(exc, RecursionError):
        return f"input nested too deeply to process (given: {given})", EXIT_USAGE
    if isinstance(exc, ArithmeticError):
        detail = _one_line(str(exc)) or type(exc).__name__
        return f"arithmetic error ({detail}): the arguments lie outside the range the computation supports (given: {given})", EXIT_USAGE
    detail = _one_line(str(exc))
    return f"internal error ({type(exc).__name__}{': ' + detail if detail else ''}); please report it with the command line (STRAPDOWN_DEBUG=1 shows the traceback)", EXIT_SOFTWARE


def _debug() -> bool:
    return os.environ.get("STRAPDOWN_DEBUG", "") not in ("", "0")


# --------------------------------------------------------------------------- entry point
def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``strapdown`` console script.

    Parameters
    ----------
    argv : list of str, optional
        Arguments after the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 on success, 2 for a bad argument, 130 after Ctrl-C, 70 for a defect.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        return _main(argv)
    except KeyboardInterrupt:
        if _debug():
            raise
        if wanted(None):  # a terminal: clear what a progress bar left on the line
            sys.stderr.write("\r\033[K")
        _say("strapdown", "interrupted")
        return EXIT_INTERRUPTED


def script() -> None:
    """The ``strapdown`` console script: :func:`main` on the process's arguments, then exit with its status.

    Before the interpreter ends, the objects the command leaves are moved out
    of the cycle collector's reach (:func:`gc.freeze`): its last pass at exit
    would walk all of them (a finished full report leaves about 360 000; 0.7 s of
    a 31 s warm report, 0.07 s frozen).  The interpreter still tears the
    modules down and runs the exit handlers; only that pass is saved.  Call
    :func:`main` to run a command inside a process that goes on.
    """
    status = main()
    gc.freeze()
    sys.exit(status)


def _main(argv: list[str]) -> int:
    parser = build_parser(argv)
    args, _ = parser.parse_known_args(argv)
    # A command listed only by its help line (its module not loaded) is parsed by the full parser.
    args = (parser if args.func_ is not None else build_parser()).parse_args(argv)
    prog = f"strapdown {args.command_}"
    with warnings.catch_warnings(record=True) as caught:
        if not _debug():
            warnings.simplefilter("ignore", RuntimeWarning)
        try:
            how = mode(args.quiet or args.no_progress)
            if getattr(args, "progress", False) and how != "off":  # --progress: bars even in a log
                how = "bar"
            args.progress = how != "off"
            _apply_rules(args)
            display = lines(prog) if how == "lines" else activity(prog, enabled=how == "bar" and args.progress_mode_ == "activity")
            with display:
                result = args.func_(args)
            if isinstance(result, dict):
                result = Result(result)
            data = _jsonable(result.data)
            bad = _non_finite(data)
            if bad:
                raise ValueError(f"the result {bad[0]} came out {bad[1]}: the arguments lie outside the range where the model is defined")
        except KeyboardInterrupt:
            raise
        except Exception as exc:  # the edge of the contract: every exception becomes one line
            if _debug():
                raise
            message, status = _message(exc, args, argv)
            _say(prog, "error: " + message)
            return status
    for w in caught:
        if not issubclass(w.category, RuntimeWarning) or _debug():
            _say(prog, f"warning: {_one_line(str(w.message))}")
    try:
        if args.json:
            _write_stdout(json.dumps(data, allow_nan=False) + "\n")
        else:
            _write_stdout((result.text if result.text is not None else _human(data)) + "\n")
    except BrokenPipeError:  # `strapdown ... | head`: the reader left; say nothing more
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
