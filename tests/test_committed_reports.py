"""The committed reports: every equation renders, and the HTML edition matches the Markdown."""

from pathlib import Path

import pytest

from strapdown.analysis.report import discover
from strapdown.analysis.report.html import OUTPUT, render_site

REPORTS = Path(__file__).resolve().parent.parent / "reports"


@pytest.fixture(scope="module")
def site():
    if not (REPORTS / "README.md").exists():
        pytest.fail("reports/ is missing: run `strapdown report` and commit the result")
    return render_site(REPORTS, [m.SECTION for m in discover()])


def test_every_equation_renders(site):
    _, errors = site
    assert errors == [], f"mathtext cannot render: {errors[:3]}"


def test_html_edition_covers_every_page():
    """Every committed Markdown page is in the committed HTML edition, with no unrendered math.

    (Byte equality with a fresh rendering is left to the CI regeneration check: SVG glyph
    paths may change with the matplotlib version.)"""
    committed = (REPORTS / OUTPUT).read_text(encoding="utf-8")
    assert 'class="math-error"' not in committed
    for page in sorted(REPORTS.glob("*.md")):
        anchor = "readme" if page.name == "README.md" else page.stem
        assert f'<section class="page" id="{anchor}">' in committed, page.name


def test_every_section_is_committed():
    for module in discover():
        link = module.SECTION.link
        assert (REPORTS / link).exists(), f"reports/{link} missing"
