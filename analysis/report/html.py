"""Report section ``index.html``: the whole report as one self-contained page.

Every Markdown page of the report (``README.md`` first, then the sections in
index order, then any other page a section wrote) is converted with
python-markdown into one HTML document that needs nothing but a browser:

* figures are embedded as base64 ``data:`` URIs;
* links between pages become in-page anchors;
* ``$...$`` and ``$$...$$`` math is rendered to inline SVG paths by
  matplotlib's mathtext, without LaTeX and without network access.  An
  expression mathtext cannot parse is shown verbatim in a
  ``<code class="math-error">`` and logged as a warning: the build never
  fails on it, and ``tools/check_html.py`` reports it;
* the style sheet is inline, and a table of contents leads the page.

The page is a pure function of the Markdown pages and figures: SVG output is
salted with a fixed hash salt, carries no date or software stamp, and
element ids are numbered in document order, so two builds are byte-identical.
"""

from __future__ import annotations

import base64
import html
import io
import logging
import posixpath
import re
from dataclasses import dataclass
from pathlib import Path

from . import Section

SECTION = Section("html", "HTML edition", order=110, summary="The whole report as one self-contained web page.", page="index.html", gathers=True)

__all__ = ["SECTION", "build", "render_site", "MathRenderer"]

log = logging.getLogger(__name__)

#: Output file name, relative to the report directory.
OUTPUT = "index.html"

#: LaTeX commands that mathtext lacks, mapped to an equivalent it knows.
_LATEX_ALIASES = {
    r"\le": r"\leq",
    r"\ge": r"\geq",
    r"\tfrac": r"\frac",
    r"\lvert": "|",
    r"\rvert": "|",
    r"\lVert": r"\Vert",
    r"\rVert": r"\Vert",
    r"\bmod": r"\ \mathrm{mod}\ ",
    r"\displaystyle": "",
    r"\textstyle": "",
    r"\big": "",
    r"\Big": "",
    r"\bigl": "",
    r"\bigr": "",
    r"\Bigl": "",
    r"\Bigr": "",
}
_ALIAS_RE = re.compile("(" + "|".join(re.escape(k) for k in sorted(_LATEX_ALIASES, key=len, reverse=True)) + r")(?![A-Za-z])")

#: Font size of rendered math [pt]; SVG sizes are expressed in em relative to it.
_MATH_SIZE = 12.0


# --------------------------------------------------------------------------- math
class MathRenderer:
    """Render TeX math to inline SVG with matplotlib mathtext, with a cache.

    Identical expressions are rendered once.  Every inserted SVG gets its own
    id prefix (numbered in document order), so glyph definitions never clash.

    Attributes
    ----------
    errors : list of str
        Expressions that mathtext could not parse, in order of appearance.
    """

    def __init__(self):
        self._cache: dict = {}
        self._count = 0
        self.errors: list = []

    def render(self, tex: str, *, display: bool = False) -> str:
        """HTML for the TeX expression ``tex`` (without dollar signs).

        Parameters
        ----------
        tex : str
            The expression, e.g. ``r"\\frac{1}{12}"``.
        display : bool, keyword-only
            Display math (``$$...$$``) rather than inline math.

        Returns
        -------
        str
            An inline ``<span>`` with the SVG, or a ``<code class="math-error">``
            with the source when mathtext cannot parse it.
        """
        tex = " ".join(tex.split())
        entry = self._entry(tex)
        kind = "display" if display else "inline"
        if entry is None:
            self.errors.append(tex)
            delim = "$$" if display else "$"
            return f'<code class="math-error" title="mathtext could not render this expression">{html.escape(delim + tex + delim)}</code>'
        self._count += 1
        svg = entry.replace("__ID__", f"m{self._count}-")
        return f'<span class="math {kind}" role="img" aria-label="{html.escape(tex, quote=True)}">{svg}</span>'

    @staticmethod
    def _key(tex: str) -> str:
        import matplotlib

        # the SVG depends on the expression and on matplotlib (fonts, mathtext): cached per version
        return f"html:math-svg:v1:{matplotlib.__version__}:{_MATH_SIZE}:{tex}"

    def _entry(self, tex: str) -> str | None:
        """The SVG template of ``tex`` (whitespace already collapsed), or None if mathtext cannot render it."""
        if tex not in self._cache:
            from ..core.cache import derived

            entry = derived(self._key(tex), lambda: self._svg(tex))
            self._cache[tex] = entry if entry is not None else self._svg(tex)  # a failure renders again, to log its warning
        return self._cache[tex]

    def prefetch(self, texs) -> None:
        """Render the expressions ``texs`` that are not cached yet, half of them in a second process.

        On a cold cache a report has hundreds of expressions to render; a
        second process renders every other one into the shared cache while
        this one renders the rest.  The SVGs are the same either way (the
        cache holds what :meth:`render` would draw); with few expressions to
        render, or one CPU, everything stays in this process.

        Parameters
        ----------
        texs : iterable of str
            TeX expressions (without dollar signs).
        """
        import os

        from ..core.cache import contains

        missing = sorted({" ".join(t.split()) for t in texs} - set(self._cache))
        missing = [t for t in missing if not contains(self._key(t))]
        if len(missing) < _PARALLEL_MATH or (os.cpu_count() or 1) < 2:
            return
        import json
        import subprocess
        import sys

        code = "import json, sys; from strapdown.analysis.report import html; html._render_into_cache(json.load(sys.stdin))"
        try:
            other = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            other.stdin.write(json.dumps(missing[1::2]).encode())
            other.stdin.close()
        except OSError:  # no second process here: render them in this one, when needed
            return
        try:
            for tex in missing[0::2]:
                self._entry(tex)
        finally:
            other.wait()  # it only fills the cache; render() draws whatever it missed

    def _svg(self, tex: str) -> str | None:
        import matplotlib
        from matplotlib.figure import Figure
        from matplotlib.font_manager import FontProperties
        from matplotlib.mathtext import MathTextParser

        source = "$" + _ALIAS_RE.sub(lambda m: _LATEX_ALIASES[m.group(1)], tex) + "$"
        prop = FontProperties(size=_MATH_SIZE)
        try:
            width, height, depth = MathTextParser("path").parse(source, dpi=72, prop=prop)[:3]
        except Exception as exc:  # mathtext raises ValueError and friends; never fail the build
            first = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
            log.warning("mathtext cannot render $%s$: %s", tex, first)
            return None
        with matplotlib.rc_context({"svg.hashsalt": "strapdown-analysis", "svg.fonttype": "path", "text.usetex": False}):
            fig = Figure(figsize=(max(width, 1.0) / 72.0, max(height, 1.0) / 72.0))
            fig.text(0.0, depth / max(height, 1.0), source, fontproperties=prop)
            buf = io.StringIO()
            fig.savefig(buf, format="svg", dpi=72, transparent=True, metadata={"Date": None, "Creator": None})
        return _clean_svg(buf.getvalue(), width / _MATH_SIZE, height / _MATH_SIZE, depth / _MATH_SIZE)


#: Fewest uncached expressions for which :meth:`MathRenderer.prefetch` starts a second process.
_PARALLEL_MATH = 40


def _render_into_cache(texs) -> int:
    """Render ``texs`` into the cache (the work of :meth:`MathRenderer.prefetch`'s second process); returns how many rendered."""
    from .rendering import configure_matplotlib

    configure_matplotlib()
    renderer = MathRenderer()
    return sum(renderer._entry(tex) is not None for tex in texs)


def _clean_svg(svg: str, width_em: float, height_em: float, depth_em: float) -> str:
    """Strip an SVG file down to an inline element sized in em, with prefixable ids."""
    svg = svg[svg.index("<svg") :]
    svg = re.sub(r"<metadata>.*?</metadata>\s*", "", svg, flags=re.S)
    svg = re.sub(r"<!--.*?-->\s*", "", svg, flags=re.S)
    svg = re.sub(r"<style[^>]*>.*?</style>\s*", "", svg, flags=re.S)
    svg = re.sub(r'\s+xmlns(:\w+)?="[^"]*"', "", svg)
    svg = re.sub(r'\s+version="[^"]*"', "", svg)
    svg = re.sub(r"<defs>\s*</defs>\s*", "", svg)
    svg = re.sub(r'\bd="([^"]*)"', lambda m: 'd="' + " ".join(m.group(1).split()) + '"', svg)
    svg = re.sub(r'\swidth="[^"]*"', f' width="{_em(width_em)}"', svg, count=1)
    svg = re.sub(r'\sheight="[^"]*"', f' height="{_em(height_em)}"', svg, count=1)
    svg = svg.replace("<svg", f'<svg style="vertical-align:{_em(-depth_em)}" aria-hidden="true" focusable="false"', 1)
    svg = re.sub(r'\bid="([^"]+)"', r'id="__ID__\1"', svg)
    svg = re.sub(r'(href|clip-path)="(url\()?#([^")]+)', r'\1="\2#__ID__\3', svg)
    # Stretch of transparent background: the figure patch is not wanted inline.
    svg = re.sub(r'<g id="__ID__patch_1">.*?</g>\s*', "", svg, count=1, flags=re.S)
    return "\n".join(line.strip() for line in svg.strip().splitlines() if line.strip())


def _em(x: float) -> str:
    text = f"{x:.3f}".rstrip("0").rstrip(".")
    return ("0" if text in ("", "-0") else text) + "em"


# --------------------------------------------------------------------------- math extraction
_FENCE_RE = re.compile(r"^( {0,3})(`{3,}|~{3,})")
_TOKEN = "MATHTOKEN{:05d}Z"
_TOKEN_RE = re.compile(r"MATHTOKEN(\d{5})Z")


@dataclass
class _Math:
    tex: str
    display: bool


def _extract_math(text: str, found: list) -> str:
    """Replace math spans by placeholder tokens, leaving code untouched.

    Fenced code blocks and backtick code spans are kept verbatim; ``\\$`` is a
    literal dollar.  ``$$...$$`` is display math (it may span lines), ``$...$``
    inline math (Pandoc's rule: no space after the opening or before the
    closing dollar, and no digit right after the closing one).
    """
    out = []
    lines = text.split("\n")
    fence = None
    prose: list = []

    def flush():
        if prose:
            out.append(_math_in_prose("\n".join(prose), found))
            prose.clear()

    for line in lines:
        m = _FENCE_RE.match(line)
        if fence is None and m:
            flush()
            fence = m.group(2)
            out.append(line)
        elif fence is not None:
            out.append(line)
            if line.strip().startswith(fence[0] * len(fence)) and set(line.strip()) == {fence[0]}:
                fence = None
        else:
            prose.append(line)
    flush()
    return "\n".join(out)


_PROSE_RE = re.compile(r"(?P<code>(?P<ticks>`+).*?(?P=ticks))|(?P<esc>\\\$)|\$\$(?P<display>.+?)\$\$|\$(?P<inline>[^\s$`](?:[^$`\n]|\n(?!\s*\n))*?(?<![\s\\]))\$(?!\d)", re.S)


def _math_in_prose(text: str, found: list) -> str:
    def sub(m):
        if m.group("code"):
            return m.group(0)
        if m.group("esc"):
            return "&#36;"
        display = m.group("display") is not None
        found.append(_Math(m.group("display") if display else m.group("inline"), display))
        return _TOKEN.format(len(found) - 1)

    return _PROSE_RE.sub(sub, text)


# --------------------------------------------------------------------------- pages
@dataclass
class _Page:
    relpath: str  # posix path relative to the report directory
    anchor: str
    title: str
    body: str = ""
    toc: list = None


def _anchor_for(relpath: str) -> str:
    stem = relpath[:-3] if relpath.endswith(".md") else relpath
    return re.sub(r"[^A-Za-z0-9_-]+", "-", stem).strip("-").lower() or "page"


def _page_order(root: Path, sections) -> list:
    """Markdown pages under ``root``: README first, then sections in index order, then the rest."""
    present = sorted(p.relative_to(root).as_posix() for p in root.rglob("*.md") if not any(part.startswith(".") for part in p.relative_to(root).parts))
    order = []
    if "README.md" in present:
        order.append("README.md")
    for s in sections:
        name = f"{s.name}.md"
        if name in present and name not in order:
            order.append(name)
    order += [p for p in present if p not in order]
    return order


def _convert(page: _Page, text: str, math: MathRenderer) -> None:
    import markdown
    from markdown.extensions.toc import slugify_unicode

    found: list = []
    source = _extract_math(text, found)

    def slugify(value, separator):
        value = _TOKEN_RE.sub(lambda m: found[int(m.group(1))].tex, value)
        return f"{page.anchor}--" + slugify_unicode(value, separator)

    md = markdown.Markdown(extensions=["tables", "fenced_code", "toc"], extension_configs={"toc": {"slugify": slugify, "toc_depth": "1-3"}}, output_format="html")
    body = md.convert(source)

    def block(m):
        item = found[int(m.group(1))]
        if item.display:
            return f'<div class="math-block">{math.render(item.tex, display=True)}</div>'
        return m.group(0)

    # Inside tags (alt, title, href) math stays TeX source.
    body = re.sub(r"<[^<>]*MATHTOKEN[^<>]*>", lambda t: _TOKEN_RE.sub(lambda m: html.escape("$" + found[int(m.group(1))].tex + "$", quote=True), t.group(0)), body)
    body = re.sub(r"<p>MATHTOKEN(\d{5})Z</p>", block, body)
    # Render in document order so that id prefixes are stable.
    body = _TOKEN_RE.sub(lambda m: math.render(found[int(m.group(1))].tex, display=found[int(m.group(1))].display), body)
    page.body = body
    page.toc = [_toc_entry(t, found) for t in md.toc_tokens]
    heads = [t for t in md.toc_tokens]
    if heads and heads[0]["level"] == 1:
        page.title = _TOKEN_RE.sub(lambda m: found[int(m.group(1))].tex, html.unescape(heads[0]["name"]))


def _toc_entry(token: dict, found: list) -> dict:
    return {"id": token["id"], "name": token["name"], "level": token["level"], "math": found, "children": [_toc_entry(c, found) for c in token["children"]]}


_ATTR_RE = re.compile(r'(<(?:a|img)\b[^>]*?\s)(href|src)="([^"]*)"')
_SCHEME_RE = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
_MIME = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg", ".gif": "image/gif", ".svg": "image/svg+xml", ".webp": "image/webp"}


def _rewrite_refs(page: _Page, pages: dict, ids: set, root: Path) -> str:
    """Embed images as data URIs and turn links between pages into anchors."""
    base = posixpath.dirname(page.relpath)

    def sub(m):
        prefix, attr, url = m.group(1), m.group(2), html.unescape(m.group(3))
        if not url or _SCHEME_RE.match(url) or url.startswith("//"):
            return m.group(0)
        path, _, frag = url.partition("#")
        if attr == "src":
            return f'{prefix}src="{_data_uri(root, posixpath.normpath(posixpath.join(base, path)))}"'
        if not path:
            target = page
        else:
            rel = posixpath.normpath(posixpath.join(base, path))
            if rel == OUTPUT:
                return f'{prefix}href="#top"'
            target = pages.get(rel)
            if target is None:
                if rel.lower().endswith(tuple(_MIME)) and (root / rel).is_file():
                    return f'{prefix}href="{_data_uri(root, rel)}"'
                return m.group(0)  # another file next to the page: a relative link is fine
        anchor = f"{target.anchor}--{frag}" if frag else target.anchor
        if frag and anchor not in ids:
            anchor = frag if frag in ids else target.anchor
        return f'{prefix}href="#{html.escape(anchor, quote=True)}"'

    return _ATTR_RE.sub(sub, page.body)


def _data_uri(root: Path, rel: str) -> str:
    path = root / rel
    mime = _MIME.get(path.suffix.lower())
    if mime is None or not path.is_file():
        log.warning("figure %s is missing or not an image; left as a relative link", rel)
        return html.escape(rel, quote=True)
    return f"data:{mime};base64," + base64.b64encode(path.read_bytes()).decode("ascii")


# --------------------------------------------------------------------------- assembly
def render_site(root: Path | str, sections=()) -> tuple[str, list]:
    """The HTML edition of the Markdown pages under ``root``.

    Parameters
    ----------
    root : path
        Report directory holding ``README.md``, the section pages and figures.
    sections : sequence of Section
        Sections in index order; their pages come right after ``README.md``.

    Returns
    -------
    page : str
        The complete, self-contained HTML document.
    errors : list of str
        Math expressions that could not be rendered (shown verbatim in the page).
    """
    root = Path(root)
    math = MathRenderer()
    pages: dict = {}
    texts = {rel: (root / rel).read_text(encoding="utf-8") for rel in _page_order(root, sections)}
    found: list = []
    for text in texts.values():
        _extract_math(text, found)
    math.prefetch(m.tex for m in found)
    for rel, text in texts.items():
        page = _Page(rel, _anchor_for(rel), rel[:-3])
        _convert(page, text, math)
        pages[rel] = page
    ids = {p.anchor for p in pages.values()}
    for p in pages.values():
        ids.update(re.findall(r'\bid="([^"]+)"', p.body))
    parts = []
    for page in pages.values():
        body = _rewrite_refs(page, pages, ids, root)
        parts.append(f'<section class="page" id="{page.anchor}">\n{body}\n</section>')
    title = pages["README.md"].title if "README.md" in pages else "Reports"
    toc = _toc_html(pages, math)
    doc = _TEMPLATE.format(title=html.escape(title), css=_CSS, toc=toc, body="\n".join(parts))
    return doc, list(math.errors)


def _toc_html(pages: dict, math: MathRenderer) -> str:
    def text(entry):
        # toc names arrive HTML-escaped, with math still as placeholder tokens
        found = entry["math"]
        return _TOKEN_RE.sub(lambda m: math.render(found[int(m.group(1))].tex), entry["name"])

    items = []
    for page in pages.values():
        heads = page.toc or []
        top = heads[0] if len(heads) == 1 and heads[0]["level"] == 1 else None
        label = text(top) if top else html.escape(page.title)
        children = top["children"] if top else heads
        sub = "".join(f'<li><a href="#{c["id"]}">{text(c)}</a></li>' for c in children)
        sub = f"<ol>{sub}</ol>" if sub else ""
        items.append(f'<li><a href="#{page.anchor}">{label}</a>{sub}</li>')
    return '<nav class="toc" aria-label="Contents"><h2>Contents</h2><ol>' + "".join(items) + "</ol></nav>"


def build(ctx) -> None:
    """Write ``index.html``, the HTML edition of every Markdown page already in ``ctx.out_dir``.

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        The report context; pages follow the order of its ``sections``.
    """
    sections = [m.SECTION for m in ctx.sections]
    doc, errors = render_site(ctx.out_dir, sections)
    ctx.write_text(OUTPUT, doc)
    if errors:
        log.warning("%d math expression(s) shown verbatim in %s (see the math-error elements)", len(errors), OUTPUT)


_TEMPLATE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<style>
{css}
</style>
</head>
<body>
<a id="top"></a>
<div class="layout">
{toc}
<main>
{body}
</main>
</div>
</body>
</html>"""

_CSS = """
:root { --ink: #1f2328; --muted: #59636e; --rule: #d1d9e0; --tint: #f6f8fa; --accent: #0b5cad; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
  font: 16px/1.6 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", "Liberation Sans", sans-serif; }
.layout { display: grid; grid-template-columns: minmax(14rem, 18rem) minmax(0, 1fr); max-width: 82rem; margin: 0 auto; }
.toc { position: sticky; top: 0; align-self: start; height: 100vh; overflow-y: auto;
  padding: 1.5rem 1rem 2rem 1.25rem; border-right: 1px solid var(--rule); font-size: 0.875rem; }
.toc h2 { font-size: 0.8rem; text-transform: uppercase; letter-spacing: 0.06em; color: var(--muted); margin: 0 0 0.75rem; border: 0; }
.toc ol { list-style: none; margin: 0; padding: 0; }
.toc ol ol { padding-left: 0.9rem; margin: 0.15rem 0 0.5rem; font-size: 0.82rem; }
.toc li { margin: 0.2rem 0; }
.toc > ol > li > a { font-weight: 600; }
.toc a { color: var(--ink); text-decoration: none; }
.toc a:hover { color: var(--accent); text-decoration: underline; }
main { padding: 1.5rem 2.5rem 4rem; min-width: 0; }
.page { max-width: 56rem; padding-bottom: 2rem; margin-bottom: 2.5rem; border-bottom: 2px solid var(--rule); }
.page:last-child { border-bottom: 0; }
h1, h2, h3, h4 { line-height: 1.25; margin: 1.6em 0 0.6em; scroll-margin-top: 1rem; }
h1 { font-size: 1.9rem; margin-top: 0.5em; padding-bottom: 0.3em; border-bottom: 1px solid var(--rule); }
h2 { font-size: 1.4rem; padding-bottom: 0.2em; border-bottom: 1px solid var(--rule); }
h3 { font-size: 1.15rem; }
p, ul, ol, table, pre, .math-block { margin: 0 0 1em; }
a { color: var(--accent); }
img { display: block; max-width: 100%; height: auto; margin: 1rem auto; border: 1px solid var(--rule); border-radius: 4px; background: #fff; }
table { border-collapse: collapse; display: block; overflow-x: auto; max-width: 100%; font-size: 0.92rem; font-variant-numeric: tabular-nums; }
th, td { border: 1px solid var(--rule); padding: 0.35rem 0.7rem; vertical-align: top; }
th { background: var(--tint); text-align: left; }
tr:nth-child(2n) td { background: #fbfcfd; }
code { font: 0.88em/1.4 ui-monospace, "DejaVu Sans Mono", "Liberation Mono", monospace; background: var(--tint); padding: 0.1em 0.3em; border-radius: 3px; }
pre { background: var(--tint); padding: 0.8rem 1rem; overflow-x: auto; border-radius: 6px; border: 1px solid var(--rule); }
pre code { background: none; padding: 0; }
blockquote { margin: 0 0 1em; padding: 0 1em; color: var(--muted); border-left: 0.25em solid var(--rule); }
.math svg { display: inline-block; overflow: visible; }
.math.inline svg { font-size: 1.05em; }
.math-block { text-align: center; overflow-x: auto; }
.math.display svg { font-size: 1.25em; }
code.math-error { color: #a40e26; background: #fff0f0; border: 1px dashed #a40e26; }
@media (max-width: 60rem) {
  .layout { display: block; }
  .toc { position: static; height: auto; border-right: 0; border-bottom: 1px solid var(--rule); }
  main { padding: 1rem 1.25rem 3rem; }
}
@media print {
  .layout { display: block; }
  .toc { position: static; height: auto; border: 0; }
  .page { break-after: page; border: 0; }
}
""".strip()
