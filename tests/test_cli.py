"""CLI skeleton: help, one JSON object on stdout, one-line errors with exit status 2."""

import json
import subprocess
import sys

import pytest

from strapdown.analysis.cli import build_parser, main


def run(*args):
    return subprocess.run([sys.executable, "-m", "strapdown.analysis", *args], capture_output=True, text=True, timeout=300)


def test_help_lists_subcommands():
    out = run("--help")
    assert out.returncode == 0
    parser = build_parser()
    names = parser._subparsers._group_actions[0].choices.keys()
    assert "report" in names
    for name in names:
        assert name in out.stdout


def test_every_subcommand_accepts_json():
    parser = build_parser()
    stack = [parser]
    seen = 0
    while stack:
        p = stack.pop()
        sub = [a for a in p._actions if a.__class__.__name__ == "_SubParsersAction"]
        if sub:
            stack.extend(sub[0].choices.values())
        else:
            assert any("--json" in a.option_strings for a in p._actions), p.prog
            seen += 1
    assert seen >= 1


def test_unknown_command_is_one_line_exit_2():
    out = run("no-such-command")
    assert out.returncode == 2
    assert out.stdout == ""
    assert len(out.stderr.strip().splitlines()) == 1
    assert "Traceback" not in out.stderr


def test_bad_option_value_is_one_line_exit_2(tmp_path):
    out = run("report", "--only", "no-such-section", "--out", str(tmp_path / "r"), "--json")
    assert out.returncode == 2
    assert out.stdout == ""
    lines = out.stderr.strip().splitlines()
    from strapdown.analysis.report import discover

    sections = ", ".join(m.SECTION.name for m in discover())
    assert lines == [f"strapdown report: error: argument --only: Expected `only` among {sections}, got 'no-such-section'"]
    assert "Traceback" not in out.stderr
    assert not (tmp_path / "r").exists()  # nothing half-written


def test_report_json_is_one_object(tmp_path):
    out = run("report", "--only", "errata", "index", "--out", str(tmp_path / "r"), "--json", "--no-progress")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["sections"] == ["errata", "index", "html"]  # the gathering sections are always rebuilt
    assert out.stdout.count("\n") == 1
    assert (tmp_path / "r" / "errata.md").exists()


def test_main_returns_2_on_value_error(capsys, tmp_path):
    code = main(["report", "--only", "nope", "--out", str(tmp_path / "x")])
    assert code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1


@pytest.mark.parametrize("argv", [["--version"]])
def test_version(argv):
    out = run(*argv)
    assert out.returncode == 0 and "strapdown-analysis" in out.stdout
