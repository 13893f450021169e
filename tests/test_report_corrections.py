"""The list of corrections to earlier versions: complete and exact against the pages themselves."""

from pathlib import Path

from strapdown.analysis.report.alignment import EARLIER
from strapdown.analysis.report.corrections import ChangedCell, changed_cells, corrections_lines, earlier_page

REPORTS = Path(__file__).resolve().parent.parent / "reports"


def test_changed_cells_match_tables_by_heading_columns_and_rows():
    earlier = "## A\n\n| case | x | y |\n|---|---|---|\n| p | 1 | 2 |\n| p | 3 | 4 |\n| q | 5 | 6 |\n\n## B\n\n| k | v |\n|---|---|\n| r | 7 |\n"
    now = "## A\n\n| case | y | x | new |\n|---|---|---|---|\n| p | 2 | 1 | 9 |\n| p | 4.5 | 3 | 9 |\n\n## B\n\n| k | v |\n|---|---|\n| r | 8 |\n| s | 1 |\n"
    assert changed_cells(earlier, now) == [ChangedCell("A", "p #2", "y", "4", "4.5"), ChangedCell("B", "r", "v", "7", "8")]
    lines = corrections_lines(changed_cells(earlier, now), version="0.0.1", causes=["Why."])
    assert lines[0] == "## Corrections to earlier versions" and "| B | r | v | 7 | 8 |" in lines
    assert "No number of version 0.0.1 changed." in corrections_lines([], version="0.0.1", causes=[])


def test_tables_under_one_heading_are_matched_table_to_table():
    """Two tables under one heading with the same first column are never compared with each other (the 0.1.0 differ did)."""
    earlier = (
        "## 5. Stats\n\n| rocking | T [s] | n |\n|---|---|---|\n| nb | 10 | 100 |\n| nb | 30 | 300 |\n\n"
        "| T [s] | model |\n|---|---|\n| 10 | 0.96 |\n\n| rocking | budget [°] | n | T [s] |\n|---|---|---|---|\n| nb | 0.1 | 437 | 43.7 |\n"
    )
    same = changed_cells(earlier, earlier)
    assert same == []
    # a real change in the third table, and a column added to the first: each table against its own
    now = earlier.replace("| nb | 0.1 | 437 | 43.7 |", "| nb | 0.1 | 440 | 44 |").replace("| rocking | T [s] | n |\n|---|---|---|\n| nb | 10 | 100 |\n| nb | 30 | 300 |",
                                                                                    "| rocking | T [s] | n | new |\n|---|---|---|---|\n| nb | 10 | 100 | 1 |\n| nb | 30 | 301 | 1 |")  # fmt: skip
    assert changed_cells(earlier, now) == [ChangedCell("5. Stats", "nb #2", "n", "300", "301"), ChangedCell("5. Stats", "nb", "n", "437", "440"), ChangedCell("5. Stats", "nb", "T [s]", "43.7", "44")]


def test_the_finite_sample_tables_of_the_alignment_page_never_changed():
    """Section 5 of the alignment page is the same in version 0.1.0 and now: none of its cells is a correction."""
    page = (REPORTS / "alignment.md").read_text(encoding="utf-8")
    earlier = earlier_page(f"alignment-{EARLIER}.md")
    fifth = lambda text: [line for line in text.split("## 5.", 1)[1].split("\n## ", 1)[0].splitlines() if line.startswith("|")]  # noqa: E731
    assert fifth(earlier) == fifth(page) and len(fifth(page)) > 20
    assert not [c for c in changed_cells(earlier, page) if c.heading.startswith("5.")]


def test_the_committed_alignment_page_lists_every_changed_number():
    """Every cell of the earlier page that differs in the committed page is in its corrections table, and nothing else."""
    page = (REPORTS / "alignment.md").read_text(encoding="utf-8")
    assert "Mode: full" in page  # the committed reports are the full run
    expected = changed_cells(earlier_page(f"alignment-{EARLIER}.md"), page)
    listed = page.split("## Corrections to earlier versions", 1)[1]
    rows = [line for line in listed.splitlines() if line.startswith("| ") and not line.startswith("| table |")]
    assert len(expected) > 0
    assert rows == [f"| {c.heading} | {c.row} | {c.column} | {c.earlier} | {c.now} |" for c in expected]
