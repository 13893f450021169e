"""One vocabulary for "order": accuracy order, local-error order, coning-drift order and drift order, named alike
in ``algorithms list``/``show``, ``derive``, ``drift``, the docs and the committed reports (package docstring, "Orders")."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from strapdown.analysis.cli import main
from strapdown.derivations.coning.drift import coning_drift
from strapdown.derivations.coning.registry import get, names
from strapdown.derivations.coning.series import local_error

ROOT = Path(__file__).resolve().parent.parent
NAMES = ("accuracy_order", "local_error_order", "coning_drift_order")


def _json(capsys, argv):
    assert main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _keys(value):
    if isinstance(value, dict):
        for k, v in value.items():
            yield k
            yield from _keys(v)
    elif isinstance(value, list):
        for v in value:
            yield from _keys(v)


def test_algorithms_list_gives_the_three_orders_from_their_derivations(capsys):
    rows = {r["name"]: r for r in _json(capsys, ["algorithms", "list"])["algorithms"]}
    assert set(rows) == set(names(library=True))
    for name, row in rows.items():
        alg = get(name)
        rho = local_error(alg).order
        first = next(w for w, part in enumerate(local_error(alg).parts) if any(part))
        assert (row["accuracy_order"], row["local_error_order"], row["coning_drift_order"]) == (rho, first, coning_drift(alg).order), name
    # the two differ most for the algorithms tuned to coning
    assert (rows["ignagni-1996-5"]["accuracy_order"], rows["ignagni-1996-5"]["coning_drift_order"]) == (3, 8)


@pytest.mark.parametrize(
    "argv",
    [
        ["algorithms", "list"],
        ["algorithms", "show", "ignagni-1996-5"],
        ["derive", "local-error", "--algorithm", "ignagni-1996-5"],
        ["derive", "coning-drift", "--algorithm", "ignagni-1996-5", "--omega-h-rad", "0.1"],
        ["drift", "--algorithm", "ignagni-1996-5", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1", "--max-order", "9"],
        ["identify", "--integrator", f"{ROOT / 'docs' / 'integrator_examples.py'}:PerSample", "--samples-per-step", "2", "--max-previous", "0", "--skip-verification"],
    ],
)
def test_no_command_says_order_without_saying_which(argv, capsys):
    """No JSON key is a bare "order"; the orders a command gives carry their names, with one value per name."""
    data = _json(capsys, argv)
    keys = set(_keys(data))
    assert "order" not in keys
    assert keys & (set(NAMES) | {"drift_order"})


def test_commands_agree_on_each_order(capsys):
    show = _json(capsys, ["algorithms", "show", "ignagni-1996-5"])
    local = _json(capsys, ["derive", "local-error", "--algorithm", "ignagni-1996-5"])
    coning = _json(capsys, ["derive", "coning-drift", "--algorithm", "ignagni-1996-5", "--omega-h-rad", "0.1"])
    drift = _json(capsys, ["drift", "--algorithm", "ignagni-1996-5", "--half-angle-deg", "1", "--freq-hz", "10", "--sample-interval", "0.0025", "--duration", "1", "--max-order", "9"])
    assert show["accuracy_order"] == local["accuracy_order"] == 3 and show["local_error_order"] == local["local_error_order"] == 4
    assert show["coning_drift_order"] == coning["coning_drift_order"] == 8
    # at 1° the drift is led by the α⁴ term: the drift order there is 4, below the coning-drift order
    assert drift["drift_order"] == 4 and drift["leading_weight"] == 5
    assert main(["algorithms", "show", "ignagni-1996-5"]) == 0
    text = capsys.readouterr().out
    assert "accuracy order ρ = 3" in text and "local-error order 4" in text and "coning-drift order m = 8" in text


def test_docs_state_the_vocabulary():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    files = (ROOT / "docs" / "algorithm-files.md").read_text(encoding="utf-8")
    for text in (readme, files):
        for name in ("accuracy order", "local-error order", "coning-drift order"):
            assert name in text


def test_reports_name_their_orders():
    """Every "order ρ" in the committed reports is an accuracy order (or the local-error order ρ + 1); none says "local order" or "global order"."""
    text = "\n".join(p.read_text(encoding="utf-8") for p in sorted((ROOT / "reports").glob("*.md")))
    assert not re.search(r"(?<!accuracy )(?<!local-error )order ρ", text)
    assert "local order" not in text and "global order" not in text
    assert "accuracy order ρ" in text and "coning-drift order m" in text and "drift order" in text
