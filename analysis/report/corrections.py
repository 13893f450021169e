"""Corrections to earlier versions of a report page: every table cell whose value changed.

An earlier version of a page is kept verbatim (``earlier/<page>-<version>.md``,
package data); :func:`changed_cells` compares the tables of that version with
the page being written, table by table (matched by the heading above them and
their columns, or their first column and place under that heading, so that
several tables under one heading are never compared with each other) and row
by row (matched by their first cell and its occurrence), and :func:`corrections_lines` lists what changed.  Formatting only:
the numbers are those the two versions printed.

Public API
----------
ChangedCell
    One cell that differs between the versions.
changed_cells
    The cells of the earlier tables whose values the current page changed.
corrections_lines
    The Markdown of a "Corrections to earlier versions" section.
earlier_page
    The text of a kept earlier version.
"""

from __future__ import annotations

from importlib import resources
from typing import NamedTuple

__all__ = ["ChangedCell", "changed_cells", "corrections_lines", "earlier_page"]


class ChangedCell(NamedTuple):
    """A table cell whose value changed between two versions of a page.

    Attributes
    ----------
    heading : str
        The heading above the table.
    row : str
        The row's first cell (with ``#k`` for the k-th row of that name).
    column : str
        The column's name.
    earlier, now : str
        The cell in the earlier version and now.
    """

    heading: str
    row: str
    column: str
    earlier: str
    now: str


def earlier_page(name: str) -> str:
    """The text of a kept earlier version of a page, e.g. ``"alignment-0.1.0.md"``.

    Parameters
    ----------
    name : str
        File name under ``earlier/``.

    Returns
    -------
    str
    """
    return resources.files(__package__).joinpath("earlier", name).read_text(encoding="utf-8")


def _cells(line: str) -> list:
    return [c.strip() for c in line.strip().strip("|").split("|")]


def _tables(text: str) -> list:
    """``[(heading, columns, {row key: {column: cell}})]``: the Markdown tables of a page, in order."""
    out = []
    heading = ""
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("#"):
            heading = line.lstrip("#").strip()
        if line.startswith("|") and i + 1 < len(lines) and set(lines[i + 1].replace("|", "").strip()) <= {"-", ":", " "} and lines[i + 1].startswith("|"):
            columns = tuple(_cells(line))
            rows, seen = {}, {}
            i += 2
            while i < len(lines) and lines[i].startswith("|"):
                cells = _cells(lines[i])
                name = cells[0]
                seen[name] = seen.get(name, 0) + 1
                rows[name if seen[name] == 1 else f"{name} #{seen[name]}"] = dict(zip(columns, cells))
                i += 1
            out.append((heading, columns, rows))
            continue
        i += 1
    return out


def _match(earlier: list, now: list) -> list:
    """Pairs ``(earlier table, current table)``: the same heading, then the same columns, else the same first column and place.

    Several tables may sit under one heading, often with the same first
    column.  A table is matched to the table of the same heading and the
    same columns when there is exactly one such; otherwise (a column added
    or renamed) to the table of the same heading and first column at the same
    place among those (the k-th such table of each version).  No table is
    matched twice; a table with no partner is new, or gone, and not compared.
    """
    pairs, used = [], set()
    for k, (heading, columns, rows) in enumerate(earlier):
        same = [j for j, (h, c, _) in enumerate(now) if h == heading and c == columns and j not in used]
        twins = [e for e, (h, c, _) in enumerate(earlier) if h == heading and c == columns]
        if len(same) == 1 and len(twins) == 1:
            j = same[0]
        else:
            mine = [e for e, (h, c, _) in enumerate(earlier) if h == heading and c[0] == columns[0]]
            theirs = [j for j, (h, c, _) in enumerate(now) if h == heading and c[0] == columns[0]]
            place = mine.index(k)
            if place >= len(theirs) or theirs[place] in used:
                continue
            j = theirs[place]
        used.add(j)
        pairs.append(((heading, columns, rows), now[j]))
    return pairs


def changed_cells(earlier: str, now: str) -> list:
    """The cells of the earlier version's tables whose values differ now.

    A table is matched to a table under the same heading: the one with the
    same columns, or, where a column was added or renamed, the one with the
    same first column at the same place under that heading (several tables
    under one heading are told apart, never compared with each other); a
    column is matched by its name, a row by its first cell (and occurrence).
    Columns, rows and tables that exist in one version only are not compared
    (they are new, or gone).

    Parameters
    ----------
    earlier, now : str
        Markdown of the two versions.

    Returns
    -------
    list of ChangedCell
        In the order of the earlier page.

    Examples
    --------
    >>> a = "## T\\n\\n| x | y |\\n|---|---|\\n| 1 | 0.5 |\\n"
    >>> b = "## T\\n\\n| x | y | z |\\n|---|---|---|\\n| 1 | 0.52 | 3 |\\n"
    >>> changed_cells(a, b)
    [ChangedCell(heading='T', row='1', column='y', earlier='0.5', now='0.52')]
    """
    out = []
    for (heading, columns, rows), (_, _, current) in _match(_tables(earlier), _tables(now)):
        for key, cells in rows.items():
            row = current.get(key)
            if row is None:
                continue
            for column in columns[1:]:
                if column in row and row[column] != cells[column]:
                    out.append(ChangedCell(heading, key, column, cells[column], row[column]))
    return out


def corrections_lines(cells, *, version: str, causes) -> list:
    """Markdown of the section "Corrections to earlier versions".

    Parameters
    ----------
    cells : list of ChangedCell
        From :func:`changed_cells`.
    version : str
        The earlier version.
    causes : sequence of str
        Paragraphs that say why the numbers changed.

    Returns
    -------
    list of str
    """
    lines = ["## Corrections to earlier versions", "", *causes, ""]
    if not cells:
        return lines + [f"No number of version {version} changed.", ""]
    lines += [
        f"Every table cell of version {version} whose value changed ({len(cells)} cells):",
        "",
        "| table | row | column | version " + version + " | now |",
        "|---|---|---|---|---|",
    ]
    for c in cells:
        lines.append(f"| {c.heading} | {c.row} | {c.column} | {c.earlier} | {c.now} |")
    return lines + [""]
