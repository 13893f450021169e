"""The lazy command registry: help lines declared once, a call imports only its own command module."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from strapdown.analysis import cli
from strapdown.analysis.cli import COMMANDS, build_parser, main


def _listed(parser) -> dict:
    """``{"name" or "group name": help}`` of every command, as ``strapdown --help`` lists them."""
    out = {}
    for line in parser.epilog.splitlines()[1:]:
        name, help_text = re.split(r"\s{2,}", line.strip(), maxsplit=1)
        out[name] = help_text
    return out


def test_declared_help_is_what_the_modules_register():
    assert _listed(build_parser()) == {k: help_text for k, (_, help_text) in COMMANDS.items()}


def test_lazy_listing_equals_the_full_one():
    assert _listed(build_parser(["--help"])) == _listed(build_parser())


@pytest.mark.parametrize("key", sorted(COMMANDS))
def test_a_command_needs_only_its_module(key):
    module, _ = COMMANDS[key]
    parser = build_parser([*key.split(), "--help"])
    leaf = parser
    for word in key.split():
        leaf = leaf._subparsers._group_actions[0].choices[word]
    assert any("--json" in a.option_strings for a in leaf._actions)
    assert leaf.get_default("func_") is not None, f"{key}: not registered by {module}"


def _imported_after(argv) -> set:
    code = (
        "import sys\n"
        "from strapdown.analysis.cli import main\n"
        f"try:\n    main({argv!r})\nexcept SystemExit:\n    pass\n"
        "print(' '.join(sorted(m for m in sys.modules if m.split('.')[0] in ('numpy', 'sympy', 'scipy', 'numba', 'control', 'matplotlib'))))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    return set(out.stdout.split("\n")[-2].split())


def test_help_imports_no_numerical_library():
    assert _imported_after(["--help"]) == set()
    assert _imported_after(["derive", "--help"]) == set()


def test_an_unknown_command_is_still_one_line_and_lists_every_command(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["no-such-command"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    for key in COMMANDS:
        assert f"'{key.split()[0]}'" in err


def test_listed_only_command_falls_back_to_the_full_parser(monkeypatch, capsys):
    """Should the registry miss a module's command, the call still runs through the full parser."""
    monkeypatch.setattr(cli, "_wanted", lambda argv: [])
    assert main(["stability", "--schuler", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["schuler_tuning"] is True
