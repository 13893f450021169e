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


def test_the_committed_alignment_page_lists_every_changed_number():
    """Every cell of the earlier page that differs in the committed page is in its corrections table, and nothing else."""
    page = (REPORTS / "alignment.md").read_text(encoding="utf-8")
    assert "Mode: full" in page  # the committed reports are the full run
    expected = changed_cells(earlier_page(f"alignment-{EARLIER}.md"), page)
    listed = page.split("## Corrections to earlier versions", 1)[1]
    rows = [line for line in listed.splitlines() if line.startswith("| ") and not line.startswith("| table |")]
    assert len(expected) > 0
    assert rows == [f"| {c.heading} | {c.row} | {c.column} | {c.earlier} | {c.now} |" for c in expected]
