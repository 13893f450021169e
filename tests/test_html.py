"""The HTML edition: one self-contained, deterministic page built from the Markdown reports."""

from __future__ import annotations

import base64
import logging
import re
import subprocess
import sys
from pathlib import Path

import pytest

from strapdown.analysis.report import Context, Section, configure_matplotlib, html

README = """# Reports

| Section | What it holds |
|---|---|
| [Drift](drift.md) | Drift against step. |
| [HTML edition](index.html) | This page. |
"""

DRIFT = r"""# Drift of $\Delta\varphi$ algorithms

The increment $\Delta\varphi_4 = \frac{2}{3}(p_1+p_2)\times(p_3+p_4)$ costs $5 and $10.
Code keeps its dollars: `$a_b$`. Back to the [index](README.md), on to [the table](#drift-for-h-le-001).

$$
2\dot\Lambda = \Lambda \circ \omega
$$

## Drift for $h \le 0.01$

| Algorithm | drift [deg/h] | bound |
|---|---:|---|
| optimal-3 | 1.2e-3 | $|\delta| \leq \varepsilon$ |

![Drift against step $h$](figures/drift-step.png)

A broken one: $\frac{1}{$.
"""

SECTIONS = [Section("drift", "Drift", 10)]


def _figure(path: Path) -> None:
    import matplotlib.pyplot as plt

    configure_matplotlib()
    fig, ax = plt.subplots(figsize=(2, 1.5))
    ax.loglog([1e-3, 1e-2], [1e-9, 1e-5])
    Context(out_dir=path.parent.parent).savefig(fig, "figures/" + path.name)


@pytest.fixture(scope="module")
def staging(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("reports")
    (root / "README.md").write_text(README, encoding="utf-8")
    (root / "drift.md").write_text(DRIFT, encoding="utf-8")
    (root / "notes.md").write_text("# Notes\n\nSee [drift](drift.md#drift-for-h-le-001).\n", encoding="utf-8")
    (root / "figures").mkdir()
    _figure(root / "figures" / "drift-step.png")
    return root


@pytest.fixture(scope="module")
def page(staging) -> str:
    doc, _ = html.render_site(staging, SECTIONS)
    return doc


def test_figures_are_embedded_as_data_uris(staging, page):
    srcs = re.findall(r'<img\b[^>]*\ssrc="([^"]*)"', page)
    assert len(srcs) == 1
    prefix = "data:image/png;base64,"
    assert srcs[0].startswith(prefix)
    assert 'alt="Drift against step $h$"' in page  # math in an attribute stays TeX
    assert base64.b64decode(srcs[0][len(prefix) :]) == (staging / "figures" / "drift-step.png").read_bytes()


def test_math_becomes_inline_svg(page):
    body = page[page.index("<main>") :]
    # inline, display, heading and table-cell math: all SVG, no TeX left as text
    assert body.count('<span class="math inline"') >= 4
    assert body.count('<span class="math display"') == 1
    assert '<div class="math-block">' in body
    assert "<svg" in body and "<path" in body
    assert r"\Delta" not in re.sub(r'aria-label="[^"]*"', "", body.split('class="math-error"')[0])
    # the table cell kept its columns although the math holds pipes
    assert re.search(r"<td>optimal-3</td>\s*<td[^>]*>1.2e-3</td>\s*<td><span class=\"math inline\"", body)


def test_dollars_that_are_not_math_stay_text(page):
    assert "costs $5 and $10." in page
    assert "<code>$a_b$</code>" in page


def test_unparsable_math_is_shown_not_fatal(staging, caplog):
    with caplog.at_level(logging.WARNING, logger=html.__name__):
        doc, errors = html.render_site(staging, SECTIONS)
    assert errors == [r"\frac{1}{"]
    assert '<code class="math-error"' in doc and r"$\frac{1}{$" in doc
    assert any("mathtext cannot render" in r.getMessage() for r in caplog.records)


def test_no_external_urls(page):
    refs = re.findall(r'\s(?:src|href)="([^"]*)"', page)
    assert refs, "expected some links"
    assert not [r for r in refs if re.match(r"(?i)(https?:)?//", r)]
    assert "<script" not in page and "<link" not in page


def test_pages_in_index_order_with_in_page_links(page):
    anchors = re.findall(r'<section class="page" id="([^"]+)">', page)
    assert anchors == ["readme", "drift", "notes"]
    ids = set(re.findall(r'\bid="([^"]+)"', page))
    hrefs = re.findall(r'<a\b[^>]*href="#([^"]+)"', page)
    assert set(hrefs) <= ids
    assert 'href="#drift"' in page  # README -> drift.md
    assert 'href="#readme"' in page  # drift.md -> README.md
    assert 'href="#top"' in page  # README -> index.html (this page)
    assert page.count('href="#drift--drift-for-h-le-001"') >= 2  # same-page fragment and cross-page fragment
    assert '<nav class="toc"' in page


def test_ids_are_unique(page):
    ids = re.findall(r'\bid="([^"]+)"', page)
    assert len(ids) == len(set(ids))


def test_build_is_byte_identical_across_processes(staging, tmp_path):
    ctx = Context(out_dir=staging, show_progress=False)
    html.build(ctx)
    first = (staging / "index.html").read_bytes()
    html.build(ctx)
    assert (staging / "index.html").read_bytes() == first
    # a fresh interpreter (new font caches, new hash seeds) writes the same bytes
    out = tmp_path / "again.html"
    code = (
        "import sys; from pathlib import Path; from strapdown.analysis.report import html, Context;"
        f"html.build(Context(out_dir=Path({str(staging)!r}), show_progress=False));"
        f"Path({str(out)!r}).write_bytes((Path({str(staging)!r}) / 'index.html').read_bytes())"
    )
    root = Path(__file__).resolve().parent.parent
    subprocess.run([sys.executable, "-c", code], check=True, cwd=root, env={"PYTHONPATH": str(root), "PYTHONHASHSEED": "12345", "PATH": "/usr/bin:/bin"}, capture_output=True)
    assert out.read_bytes() == first


def test_missing_figure_is_left_for_the_browser_check(tmp_path, caplog):
    (tmp_path / "README.md").write_text("# R\n\n![gone](figures/gone.png)\n", encoding="utf-8")
    with caplog.at_level(logging.WARNING, logger=html.__name__):
        doc, _ = html.render_site(tmp_path)
    assert 'src="figures/gone.png"' in doc
    assert any("figures/gone.png" in r.getMessage() for r in caplog.records)
