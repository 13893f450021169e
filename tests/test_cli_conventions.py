"""The naming scheme of CONTRIBUTING.md, checked on the real argparse tree of every command.

For every option of every command (and subcommand):

* **kebab-case**: ``--lower-case-words`` (paper symbols such as ``--k`` included);
* **the help states what the value is**, in square brackets: a unit (``[deg]``,
  ``[s]``, ``[Hz]``, ``[deg/h]``, ``[m/s²]``, ``[1/s]``, ...), or
  ``[dimensionless]``, ``[count]``, ``[name]`` or ``[path]``; options with a
  fixed set of choices and flags are exempt;
* **units as suffixes**: a unit other than seconds and metres is the option's
  last word (``[deg]`` → ``--lat-deg``, ``[deg/h]`` → ``-deg-per-h``, ``[Hz]`` →
  ``-hz``, ``[m/s²]`` → ``-m-s2``, ``[m/s]`` → ``-m-s``, ``[rad]`` → ``-rad``,
  ``[deg/√h]`` → ``-deg-per-rt-h``, ``[ppm]`` → ``-ppm``, ``[arcsec]`` →
  ``-arcsec``, ``[MB]`` → ``-mb``); seconds and metres carry none (``--duration``, not
  ``--duration-s``); gains in ``[1/s]``, ``[1/s²]`` keep their paper symbol;
* **defaults shown**: the help of an option that is not required names its
  default, ``(default 5)`` or ``(default: reports)``, with the value argparse
  really uses;
* **names listed**: ``--algorithm`` lists the valid algorithm names (or points
  to ``strapdown algorithms list``) and ``report --only`` the section names;
  an option with a fixed set of choices shows them (argparse does, as
  ``{a,b}``, unless a metavar hides them: then its help lists them).

Commands that do not comply yet are listed in :data:`PENDING` (strict xfail:
a command taken off the list must pass).
"""

from __future__ import annotations

import math
import re

import pytest
from cli_contract import leaf_parsers

from strapdown.analysis.report import section_names
from strapdown.derivations.coning.registry import names as algorithm_names

#: Commands whose options are still being renamed to the scheme (strict xfail: a command that
#: complies while listed fails as XPASS).  Every command complies now; a new one that cannot yet
#: is listed here with the reason.
PENDING: set = set()

#: Unit in the help → required last words of the option (None: none allowed; "gain": no rule).
SUFFIX = {
    "s": None,
    "m": None,
    "deg": "deg",
    "deg/h": "deg-per-h",
    "Hz": "hz",
    "m/s²": "m-s2",
    "m/s^2": "m-s2",
    "m/s2": "m-s2",
    "m/s": "m-s",
    "rad": "rad",
    "rad/s": "rad-s",
    "deg/√h": "deg-per-rt-h",
    "m/s/√h": "m-s-per-rt-h",
    "ppm": "ppm",
    "arcsec": "arcsec",
    "MB": "mb",
    "1/s": "gain",
    "1/s²": "gain",
}
KINDS = {"dimensionless", "count", "name", "path"}
KEBAB = re.compile(r"^--[a-z0-9]+(-[a-z0-9]+)*$")
BRACKET = re.compile(r"\[([^\]]+)\]")
DEFAULT = re.compile(r"\(default:?\s*([^)]*)\)")


def _value_options(parser):
    for action in parser._actions:
        longs = [s for s in action.option_strings if s.startswith("--")]
        if longs and longs[0] != "--help":
            yield longs[0], action


def _in_required_group(parser, action) -> bool:
    return any(g.required and action in g._group_actions for g in parser._mutually_exclusive_groups)


def _shows_default(help_text: str, default) -> bool:
    default = getattr(default, "value", default)  # Commands.only_with wraps the default to tell it from a value typed
    m = DEFAULT.search(help_text)
    if m is None:
        return False
    shown = m.group(1).strip()
    if default is None or isinstance(default, (list, tuple)):
        return bool(shown)
    if isinstance(default, (int, float)) and not isinstance(default, bool):
        numbers = re.findall(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", shown.replace("_", ""))
        return any(math.isclose(float(n), float(default), rel_tol=1e-9, abs_tol=0.0) for n in numbers)
    return str(default) in shown


def problems(name: str, parser) -> list:
    """Every breach of the scheme by the options of command ``name``."""
    out = []
    for flag, action in _value_options(parser):
        help_text = (action.help or "") % {"default": action.default, "prog": parser.prog} if action.help and "%(" in action.help else (action.help or "")
        if not KEBAB.match(flag):
            out.append(f"{flag}: not kebab-case")
        flag_only = action.nargs == 0
        if flag_only:
            continue
        if action.choices is None:
            brackets = BRACKET.findall(help_text)
            if not brackets:
                out.append(f"{flag}: help states no unit or kind in brackets ([deg], [s], [dimensionless], [count], [name], [path])")
            else:
                known = [b.strip() for b in brackets if b.strip() in SUFFIX or b.strip() in KINDS]  # others are symbols, e.g. "[u]"
                unit = known[0] if known else brackets[0].strip()
                if unit not in KINDS:
                    if unit not in SUFFIX:
                        out.append(f"{flag}: unit [{unit}] is not in the scheme {sorted(SUFFIX)}")
                    else:
                        suffix = SUFFIX[unit]
                        if suffix is None and re.search(r"-(s|m)$", flag):
                            out.append(f"{flag}: a value in [{unit}] carries no unit suffix")
                        elif suffix not in (None, "gain") and not flag.endswith("-" + suffix):
                            out.append(f"{flag}: a value in [{unit}] ends in -{suffix}")
        if not action.required and not _in_required_group(parser, action) and not _shows_default(help_text, action.default):
            out.append(f"{flag}: help does not show its default {action.default!r} as '(default ...)'")
        if action.choices is not None and action.metavar is not None and not all(str(c) in help_text for c in action.choices):
            out.append(f"{flag}: its metavar hides the choices and the help does not list them all")
        if flag == "--algorithm":
            listed = all(n in help_text for n in algorithm_names())
            if not listed and "strapdown algorithms list" not in help_text:
                out.append("--algorithm: help lists neither the algorithm names nor `strapdown algorithms list`")
        if name == "report" and flag == "--only" and not all(s in help_text for s in section_names()):
            out.append("--only: help does not list every section name")
    return out


COMMANDS = leaf_parsers()


def test_pending_commands_exist():
    assert PENDING <= set(COMMANDS)


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xfail(strict=True, reason="options not yet renamed")) if n in PENDING else n for n in COMMANDS])
def test_options_follow_the_scheme(name):
    assert problems(name, COMMANDS[name]) == []


def test_the_check_can_fail():
    import argparse

    p = argparse.ArgumentParser()
    p.add_argument("--Bad_Name", help="x")
    p.add_argument("--latitude", type=float, default=45.0, help="latitude [deg] (default 45)")
    p.add_argument("--period-s", type=float, default=8.0, help="period [s] (default 8)")
    p.add_argument("--gain", type=float, default=1.0, help="a gain [1/s] (default 2)")
    p.add_argument("--speed", type=float, default=1.0, help="a speed [furlong/fortnight] (default 1)")
    p.add_argument("--model", choices=("a", "b"), metavar="M", default="a", help="the model (default a)")
    found = problems("x", p)
    assert any("--Bad_Name: not kebab-case" in f for f in found)
    assert any("--Bad_Name: help states no unit" in f for f in found)
    assert any("--latitude: a value in [deg] ends in -deg" in f for f in found)
    assert any("--period-s: a value in [s] carries no unit suffix" in f for f in found)
    assert any("--gain: help does not show its default 1.0" in f for f in found)
    assert any("[furlong/fortnight] is not in the scheme" in f for f in found)
    assert any("--model: its metavar hides the choices" in f for f in found)


def test_defaults_of_options_that_apply_only_with_others_are_checked():
    """:meth:`Commands.only_with` wraps the default: the check reads the value the command sees."""
    import argparse

    from strapdown.analysis.cli import Commands

    commands = Commands(argparse.ArgumentParser().add_subparsers())
    p = commands.add("x", None, "x")
    p.add_argument("--rocking", choices=("a", "b"), default="a", help="rocking (default a)")
    p.add_argument("--period", type=float, default=8.0, help="period [s] (default 9)")
    p.add_argument("--damping", type=float, default=0.1, help="damping [dimensionless] (default 0.1)")
    commands.only_with(p, "--period", "--rocking", ("b",))
    commands.only_with(p, "--damping", "--rocking", ("b",))
    assert problems("x", p) == ["--period: help does not show its default 8.0 as '(default ...)'"]


def test_help_shows_no_restructuredtext():
    """Descriptions taken from docstrings reach --help as plain text (``identify --help`` showed ``:class:`~...```)."""
    from strapdown.analysis.cli import plain_text

    for name, parser in COMMANDS.items():
        text = parser.format_help()
        assert not re.search(r":(class|func|meth|mod|attr|data):`|``", text), (name, text[:300])
    assert plain_text(":func:`~strapdown.analysis.coning.integrators.assessment.assess`") == "assess"  # and can see markup
    assert re.search(r":(class|func):`", ":class:`~a.B`")  # the pattern above finds a role
