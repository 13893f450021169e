"""The committed reports: every equation renders, and the HTML edition matches the Markdown."""

from pathlib import Path

import pytest

from analysis.report import discover
from analysis.report.html import OUTPUT, render_site

REPORTS = Path(__file__).resolve().parent.parent / "reports"


@pytest.fixture(scope="module")
def site():
    if not (REPORTS / "README.md").exists():
        pytest.fail("reports/ is missing: run `strapdown report` and commit the result")
    return render_site(REPORTS, [m.SECTION for m in discover()])


def test_every_equation_renders(site):
    _, errors = site
    assert errors == [], f"mathtext cannot render: {errors[:3]}"


def test_html_edition_is_up_to_date(site):
    doc, _ = site
    committed = (REPORTS / OUTPUT).read_text(encoding="utf-8")
    assert committed == (doc if doc.endswith("\n") else doc + "\n"), "reports/index.html is stale: regenerate the reports"


def test_every_section_is_committed():
    for module in discover():
        link = module.SECTION.link
        assert (REPORTS / link).exists(), f"reports/{link} missing"
