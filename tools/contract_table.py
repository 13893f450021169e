"""Run the hostile-input table of the command-line fuzz tests and print how many cases meet the contract.

Usage::

    python tools/contract_table.py            # Markdown table: input class, cases, met the contract
    python tools/contract_table.py --failures  # also one line per case that does not
    python tools/contract_table.py --by-command  # also the cases of each command

The cases are those of ``tests/test_cli_fuzz.py`` (one option of a valid
command, or of a variant for a rocking model, method or motion, mutated at a
time; hostile algorithm files for every command that reads them) and of
``tests/test_cli_contract.py`` (work limits, counts, physical ranges, command-line syntax);
the contract is checked by ``tests/cli_contract.py``.
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

from cli_contract import run, violations, warm_up  # noqa: E402


def _cases(tmp: Path) -> list:
    import test_cli_contract as contract
    import test_cli_fuzz as fuzz

    cases = [(kind, argv, expect, names, 5.0) for kind, argv, expect, names in fuzz.CASES]
    for _label, path in fuzz.file_cases(tmp):
        for command in fuzz.algorithm_file_commands():
            cases.append((f"hostile algorithm file ({command})", fuzz.with_algorithm_file(command, path), "refuse", ("--algorithm-file",), 2.0))
    for kind, argv, expect, names in contract.EXTRA_CASES:
        cases.append((kind, argv, expect, names, 5.0))
    return cases


def _command(argv) -> str:
    """The command a case runs (``"derive coning-drift"``), or ``"(none)"`` for a bare or unknown one."""
    from strapdown.analysis.cli import COMMANDS

    words = [a for a in argv if not a.startswith("-")][:2]
    for n in (2, 1):
        if " ".join(words[:n]) in COMMANDS:
            return " ".join(words[:n])
    return " ".join(words[:1]) if words[:1] in (["derive"], ["algorithms"], ["reproduce"]) else "(none)"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--failures", action="store_true", help="print every case that breaks the contract")
    parser.add_argument("--by-command", action="store_true", help="print a second table: cases per command")
    args = parser.parse_args()
    import test_cli_fuzz

    warm_up(test_cli_fuzz.baseline_invocations())  # imports and caches paid before the timed cases
    with tempfile.TemporaryDirectory() as tmp:
        cases = _cases(Path(tmp))
        tried, met = collections.Counter(), collections.Counter()
        per_command, per_command_met = collections.Counter(), collections.Counter()
        failures = []
        for kind, argv, expect, names, limit in cases:
            outcome = run(argv, timeout=120.0)
            problems = violations(outcome, expect=expect, names=names, limit=limit, json_out="--json" in argv, argv=argv)
            command = _command(argv)
            tried[kind] += 1
            per_command[command] += 1
            if problems:
                failures.append((kind, argv, problems))
            else:
                met[kind] += 1
                per_command_met[command] += 1
    print("| input class | cases | met the contract |")
    print("|---|---:|---:|")
    for kind in sorted(tried):
        print(f"| {kind} | {tried[kind]} | {met[kind]} |")
    print(f"| **all** | **{sum(tried.values())}** | **{sum(met.values())}** |")
    if args.by_command:
        print()
        print("| command | cases | met the contract |")
        print("|---|---:|---:|")
        for command in sorted(per_command):
            print(f"| {command} | {per_command[command]} | {per_command_met[command]} |")
    if args.failures:
        for kind, argv, problems in failures:
            print(f"- {kind}: `{' '.join(argv)[:160]}`: {'; '.join(problems)[:300]}")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
