#!/usr/bin/env python3
"""Check the built documentation site in a real headless Chromium.

Opens every page of the site built by ``sphinx-build -b html docs
docs/_build/html`` from disk (``file://``, as a reader without a network
would), waits until its images are decoded and MathJax has typeset it, then
fails on

* an image that did not load (``naturalWidth == 0``), and a page of the
  gallery, the user guide or the task pages that should show a figure and
  shows none;
* mathematics MathJax could not render (``mjx-merror`` elements), or a page
  with ``.math`` markup that MathJax never typeset;
* a broken internal link: a link to a file of the site that does not exist,
  or to an anchor (``#id``) that the target page does not have;
* a code or output block cut at the viewport width (1280 px by default): a
  ``pre`` whose text runs past its box without a scroll bar, or whose box runs
  past the window (``docs/_static/blocks.css`` wraps them; a self-test page
  with a cut block checks first that the check can fail);
* a resource fetched from outside the site (the site must read offline);
* a console error, an uncaught exception or a failed load reported by the
  browser.

The browser is driven as in ``tools/check_html.py`` (the DevTools protocol on
a pipe, the Debian ``chromium`` package installed with apt-get when missing).
With ``--screenshots DIR`` it saves the first viewport of every page outside
the API reference, for a look at the layout.

Exit status: 0 when the site passes, 1 when a check fails, 2 when Chromium
cannot be installed or started.

Usage::

    python tools/check_docs.py [docs/_build/html] [--screenshots tools/screenshots/docs]
"""

from __future__ import annotations

import argparse
import html.parser
import sys
import time
from pathlib import Path
from urllib.parse import unquote, urldefrag, urlparse

from check_html import Browser, CheckError, console_errors, find_chromium

ROOT = Path(__file__).resolve().parent.parent

#: Folders of pages that run code and draw: each of their pages must show at least one figure.
FIGURE_FOLDERS = ("gallery",)
#: Pages of the user guide and the task pages that draw a figure (the others print numbers only).
FIGURE_PAGES = (
    "concepts/04_three_orders.html",
    "concepts/05_precession_and_coning.html",
    "tasks/01_algorithm_and_rate.html",
    "tasks/05_stage_stability.html",
    "tasks/06_alignment_design.html",
)

#: Code and output blocks cut at the viewport: text past the box with no scroll bar, or a box past the window.
CUT_BLOCKS = r"""
(() => [...document.querySelectorAll('pre')].filter(p => p.offsetParent !== null).filter(p => {
  const r = p.getBoundingClientRect(), style = getComputedStyle(p);
  const hidden = p.scrollWidth > p.clientWidth + 1 && !['auto', 'scroll'].includes(style.overflowX);
  return hidden || r.right > document.documentElement.clientWidth + 1;
}).map(p => p.textContent.trim().split('\n')[0].slice(0, 60)))()
"""

#: A page with one block cut at any width: the check of cut blocks must flag it.
CUT_SELF_TEST = (
    "<!DOCTYPE html><html><body><pre style='overflow: hidden; width: 200px'>strapdown drift --algorithm panov-4s-3 --half-angle-deg 1 "
    "--freq-hz 10 --sample-interval 0.0025 --duration 100</pre><pre>short</pre></body></html>"
)

INSPECT = r"""
(async () => {
  const CUT_BLOCKS = () => """ + CUT_BLOCKS.strip() + r""";
  const deadline = Date.now() + 20000;
  await Promise.all([...document.images].map(img => img.decode().catch(() => null)));
  let typeset = null;
  if (window.MathJax) {
    while (!(MathJax.startup && MathJax.startup.promise) && Date.now() < deadline) {
      await new Promise(r => setTimeout(r, 50));
    }
    if (MathJax.startup && MathJax.startup.promise) { await MathJax.startup.promise; typeset = true; }
    else { typeset = false; }
  }
  return {
    title: document.title,
    images: [...document.images].map(img => ({src: img.getAttribute('src'), alt: img.alt,
      natural: img.naturalWidth, gallery: !!img.closest('.sphx-glr-thumbcontainer')})),
    figures: document.querySelectorAll('img.sphx-glr-single-img, img.sphx-glr-multi-img').length,
    mathMarkup: document.querySelectorAll('.math, span.math, div.math').length,
    mathTypeset: document.querySelectorAll('mjx-container').length,
    mathErrors: [...document.querySelectorAll('mjx-merror')].map(e => e.getAttribute('data-mjx-error') || e.textContent),
    mathjax: typeset,
    cut: CUT_BLOCKS(),
    links: [...document.querySelectorAll('a[href]')].map(a => a.href),
    external: [...document.querySelectorAll('[src], link[href]')]
      .map(e => e.getAttribute('src') || e.getAttribute('href'))
      .filter(s => /^(https?:)?\/\//.test(s)),
  };
})()
"""


class _Ids(html.parser.HTMLParser):
    """Every ``id`` (and legacy ``name``) attribute of a page: the anchors a link may point to."""

    def __init__(self):
        super().__init__()
        self.ids = set()

    def handle_starttag(self, tag, attrs):
        for key, value in attrs:
            if key == "id" or (key == "name" and tag == "a"):
                self.ids.add(value)


def page_ids(path: Path, cache: dict) -> set:
    """The anchors of the page at ``path`` (parsed once)."""
    if path not in cache:
        parser = _Ids()
        parser.feed(path.read_text(encoding="utf-8", errors="replace"))
        cache[path] = parser.ids
    return cache[path]


def broken_links(page: Path, links: list, site: Path, cache: dict) -> list:
    """Links of ``page`` into the site whose file or anchor does not exist."""
    out = []
    for link in links:
        url, fragment = urldefrag(link)
        parsed = urlparse(url)
        if parsed.scheme != "file":
            continue  # http(s), mailto: not part of the site
        target = Path(unquote(parsed.path))
        try:
            target.relative_to(site)
        except ValueError:
            out.append(f"{link} leaves the site")
            continue
        if target.is_dir():
            target = target / "index.html"
        if not target.is_file():
            out.append(f"{link}: no such file")
        elif fragment and target.suffix == ".html" and unquote(fragment) not in page_ids(target, cache):
            out.append(f"{link}: no anchor #{fragment} in {target.relative_to(site)}")
    return out


def check(site: Path, *, screenshots: Path | None = None, width: int = 1280, height: int = 900) -> int:
    site = site.resolve()
    index = site / "index.html"
    if not index.is_file():
        print(f"FAIL: {index} does not exist (build the site first: sphinx-build -W -b html docs docs/_build/html)", file=sys.stderr)
        return 1
    pages = sorted(p for p in site.rglob("*.html") if "_sources" not in p.parts and "_static" not in p.parts)
    if screenshots:
        screenshots.mkdir(parents=True, exist_ok=True)
        for old in screenshots.glob("*.png"):
            old.unlink()
    failures, ids = [], {}
    counts = {"pages": 0, "images": 0, "figures": 0, "equations": 0, "links": 0}
    start = time.monotonic()
    browser = Browser(find_chromium(), width=width, height=height)
    try:
        browser.open_page()
        browser.send("Emulation.setDeviceMetricsOverride", {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
        probe = site.parent / ".check-docs-cut-block.html"
        probe.write_text(CUT_SELF_TEST, encoding="utf-8")
        try:
            browser.send("Page.navigate", {"url": probe.as_uri()})
            browser.wait_event("Page.loadEventFired")
            flagged = browser.evaluate(CUT_BLOCKS)
        finally:
            probe.unlink(missing_ok=True)
        if len(flagged) != 1:
            failures.append(f"self-test: the check of cut blocks flagged {flagged!r} on a page with exactly one cut block")
        for page in pages:
            rel = page.relative_to(site).as_posix()
            browser.events.clear()
            browser.send("Page.navigate", {"url": page.as_uri()})
            browser.wait_event("Page.loadEventFired")
            info = browser.evaluate(INSPECT)
            browser.evaluate("new Promise(r => setTimeout(r, 50))")
            counts["pages"] += 1
            counts["images"] += len(info["images"])
            counts["figures"] += info["figures"]
            counts["equations"] += info["mathTypeset"]
            counts["links"] += len(info["links"])
            for img in info["images"]:
                if img["natural"] == 0:
                    failures.append(f"{rel}: image {img['src']!r} ({img['alt'] or 'no alt text'}) did not load")
            wants_figure = rel.split("/")[0] in FIGURE_FOLDERS or rel in FIGURE_PAGES
            is_index = rel.endswith("index.html") or rel.endswith("sg_execution_times.html")
            if wants_figure and not is_index and info["figures"] == 0:
                failures.append(f"{rel}: a page that draws shows no figure")
            failures += [f"{rel}: math not rendered: {e}" for e in info["mathErrors"]]
            if info["mathMarkup"] and not info["mathTypeset"]:
                failures.append(f"{rel}: {info['mathMarkup']} math elements, none typeset by MathJax (loaded: {info['mathjax']})")
            failures += [f"{rel}: a code or output block is cut at {width} px: {text!r}" for text in info["cut"]]
            failures += [f"{rel}: external resource (the site must read offline): {s}" for s in info["external"]]
            failures += [f"{rel}: broken link {b}" for b in broken_links(page, info["links"], site, ids)]
            failures += [f"{rel}: browser: {e}" for e in console_errors(browser.events)]
            if screenshots and not rel.startswith("api/"):
                browser.screenshot(screenshots / (rel.replace("/", "--").removesuffix(".html") + ".png"))
    finally:
        browser.close()

    print(
        f"{site}: {counts['pages']} pages in {time.monotonic() - start:.0f} s, {counts['images']} images ({counts['figures']} figures drawn by the pages), "
        f"{counts['equations']} typeset equations, {counts['links']} links checked"
    )
    if screenshots:
        print(f"screenshots of the pages outside the API reference in {screenshots}")
    if failures:
        print(f"FAIL: {len(failures)} problem(s):", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        return 1
    print("OK: every image loaded, every figure present, every equation typeset, no block cut, no broken internal link, no browser error")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("site", nargs="?", type=Path, default=ROOT / "docs" / "_build" / "html", help="the built site (default: docs/_build/html)")
    parser.add_argument("--screenshots", type=Path, default=None, help="save the first viewport of every page outside the API reference here")
    parser.add_argument("--width", type=int, default=1280, help="viewport width [px]")
    parser.add_argument("--height", type=int, default=900, help="viewport height [px]")
    args = parser.parse_args(argv)
    try:
        return check(args.site, screenshots=args.screenshots, width=args.width, height=args.height)
    except CheckError as exc:
        print(f"ERROR: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
