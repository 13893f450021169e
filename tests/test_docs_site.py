"""The documentation site: its API reference is complete, its gallery covers the report, its link check can fail.

The API reference is the full build in ``docs/_build/html`` when it is newer
than every source of the site and the package (CI builds it just before the
tests); otherwise it is built here (without executing the pages of the user
guide and the gallery) from a copy of ``docs/``. It is read back as a reader's tools would: the object inventory
``objects.inv`` and the anchors of the HTML pages. Every public name of every
module of the installed packages must be in both. A module's public names are
its ``__all__``; without one, the functions and classes it defines and the
names it binds at module level, not starting with ``_``.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
import re
import shutil
import subprocess
import sys
import zlib
from pathlib import Path

import pytest

import strapdown.analysis
import strapdown.derivations

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


# --------------------------------------------------------------------------- what the package exposes
def _module_names() -> list:
    names = []
    for package in (strapdown.analysis, strapdown.derivations):
        names.append(package.__name__)
        names += [i.name for i in pkgutil.walk_packages(package.__path__, prefix=package.__name__ + ".")]
    return sorted(n for n in names if not any(part.startswith("_") for part in n.split(".")))


def _public_names(module) -> list:
    explicit = getattr(module, "__all__", None)
    if explicit is not None:
        return list(explicit)
    tree = ast.parse(inspect.getsource(module))
    bound = []
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            bound.append(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            for target in node.targets if isinstance(node, ast.Assign) else [node.target]:
                bound += [leaf.id for leaf in ast.walk(target) if isinstance(leaf, ast.Name)]
    return [n for n in dict.fromkeys(bound) if not n.startswith("_") and not inspect.ismodule(getattr(module, n, None))]


def _inventory(path: Path) -> dict:
    """``{name: uri}`` of the Python objects of a Sphinx ``objects.inv`` (format version 2)."""
    raw = path.read_bytes()
    lines = raw.split(b"\n", 4)
    assert lines[0].startswith(b"# Sphinx inventory version 2"), lines[0]
    out = {}
    for line in zlib.decompress(lines[4]).decode("utf-8").splitlines():
        m = re.match(r"(?x)(.+?)\s+(\S+:\S+)\s+(-?\d+)\s+(\S+)\s+(.*)", line)
        if m and m.group(2).startswith("py:"):
            name, uri = m.group(1), m.group(4)
            out[name] = uri[:-1] + name if uri.endswith("$") else uri
    return out


# --------------------------------------------------------------------------- the API reference, built
def _copy_repository_pages(work: Path) -> None:
    """Copy the Markdown and reST files of the repository outside docs/ into ``work``, at their paths.

    A page may link to such a file (``../reports/algorithms.md``); the site
    shows the link as the file's path when the file exists beside ``docs/``
    (``docs/_ext/repository_links.py``), and a ``-W`` build fails when it does not.
    """
    for path in sorted(ROOT.rglob("*")):
        relative = path.relative_to(ROOT)
        if path.suffix not in (".md", ".rst") or not path.is_file() or relative.parts[0] == "docs":
            continue
        if any(part.startswith(".") or part in ("build", "dist") or part.endswith(".egg-info") for part in relative.parts[:-1]):
            continue
        (work / relative).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, work / relative)


def _fresh_full_build() -> Path | None:
    """``docs/_build/html`` when it is newer than every source it is built from (CI builds it just before), else None."""
    site = DOCS / "_build" / "html"
    inventory = site / "objects.inv"
    if not inventory.is_file():
        return None
    generated = {"_build", "api", "concepts", "tasks", "gallery", "__pycache__"}
    sources = [p for p in DOCS.rglob("*") if p.is_file() and not generated & set(p.relative_to(DOCS).parts[:1] + p.relative_to(DOCS).parts[-2:-1])]
    for package in ("analysis", "derivations"):  # the repository's sources (an install copies them later, with new times)
        sources += list((ROOT / package).rglob("*.py"))
    built = inventory.stat().st_mtime
    return site if all(p.stat().st_mtime < built for p in sources) else None


@pytest.fixture(scope="module")
def api_site(tmp_path_factory) -> Path:
    """The site: the full build in ``docs/_build/html`` when it is up to date, else one built here from a copy of docs/, the pages of the user guide and the gallery not executed."""
    fresh = _fresh_full_build()
    if fresh is not None:
        return fresh
    work = tmp_path_factory.mktemp("docs")
    source = work / "docs"
    generated = {"_build", "api", "concepts", "tasks", "gallery"}  # outputs of an earlier build in docs/ itself

    def ignore(folder, names):
        return [n for n in names if n == "__pycache__" or (Path(folder) == DOCS and n in generated)]

    shutil.copytree(DOCS, source, ignore=ignore)
    _copy_repository_pages(work)
    # the landing page shows a figure the gallery draws; unexecuted, the gallery draws none, so the
    # report's copy of that figure (the gallery page draws the same one) stands in for it
    landing = source / "gallery" / "coning" / "images" / "sphx_glr_plot_drift_vs_step_001.png"
    landing.parent.mkdir(parents=True, exist_ok=True)
    shutil.copy2(ROOT / "reports" / "figures" / "algorithms-drift-vs-step.png", landing)
    out = work / "html"
    cmd = [sys.executable, "-m", "sphinx", "-b", "html", "-q", "-W", "-D", "plot_gallery=0", str(source), str(out)]
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=1200)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return out


def test_every_public_name_is_in_the_api_reference(api_site):
    inventory = _inventory(api_site / "objects.inv")
    missing, no_anchor = [], []
    pages = {}
    for name in _module_names():
        if name not in inventory:
            missing.append(f"module {name}")
        page = api_site / "api" / "generated" / f"{name}.html"
        if not page.is_file():
            missing.append(f"page of {name}")
            continue
        text = pages.setdefault(name, page.read_text(encoding="utf-8"))
        for public in _public_names(importlib.import_module(name)):
            full = f"{name}.{public}"
            if full not in inventory:
                missing.append(full)
            elif f'id="{full}"' not in text:
                no_anchor.append(full)
    assert not missing, f"{len(missing)} public names missing from the API reference: {missing[:20]}"
    assert not no_anchor, f"{len(no_anchor)} names without an anchor on their module's page: {no_anchor[:20]}"


def test_api_reference_documents_members_and_parameters(api_site):
    """A sample of what a reader looks for: a class's methods and fields, a function's parameters with units."""
    inventory = _inventory(api_site / "objects.inv")
    for name in (
        "strapdown.analysis.coning.simulator.simulate",
        "strapdown.analysis.coning.simulator.SimulationResult.drift_rate",
        "strapdown.analysis.coning.precession.RegularPrecession.omega",
        "strapdown.derivations.coning.drift.ConingDrift.step_coefficient",
    ):
        assert name in inventory, name
    page = (api_site / "api" / "generated" / "strapdown.analysis.coning.simulator.html").read_text(encoding="utf-8")
    assert "sample_interval" in page and "Sample interval h [s]" in page


def test_public_names_come_from_the_source():
    """The rule above, on modules with and without ``__all__``."""
    from strapdown.analysis.coning import simulator
    from strapdown.analysis.report import errata

    assert _public_names(simulator) == list(simulator.__all__)
    names = _public_names(errata)
    assert "errata" in names and "SECTION" in names and "CHECK_SEED" in names
    assert "printed_formula_checks" not in names  # imported, not defined there


# --------------------------------------------------------------------------- the gallery and the report
def _gallery_figures() -> dict:
    out = {}
    for path in sorted((DOCS / "examples" / "gallery").rglob("*.py")):
        for figure in re.findall(r"Report figure ``([\w.-]+\.png)``", ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""):
            out.setdefault(figure, []).append(path.relative_to(DOCS).as_posix())
    return out


def test_gallery_draws_every_figure_of_the_report():
    report = sorted(p.name for p in (ROOT / "reports" / "figures").glob("*.png"))
    gallery = _gallery_figures()
    assert report, "no figures in reports/figures"
    missing = [f for f in report if f not in gallery]
    assert not missing, f"report figures without a gallery page: {missing}"
    unknown = [f for f in gallery if f not in report]
    assert not unknown, f"gallery pages naming figures the report does not have: {unknown}"
    twice = {f: pages for f, pages in gallery.items() if len(pages) > 1}
    assert not twice, f"figures drawn by more than one gallery page: {twice}"


# --------------------------------------------------------------------------- the browser check can fail
def test_link_check_finds_missing_files_and_anchors(tmp_path):
    sys.path.insert(0, str(ROOT / "tools"))
    try:
        import check_docs
    finally:
        sys.path.pop(0)
    site = tmp_path / "site"
    (site / "api").mkdir(parents=True)
    (site / "index.html").write_text('<h1 id="top">x</h1><a name="legacy"></a>', encoding="utf-8")
    (site / "api" / "page.html").write_text('<section id="strapdown.analysis.core.units.deg">', encoding="utf-8")
    page = site / "index.html"
    good = [page.as_uri() + "#top", page.as_uri() + "#legacy", (site / "api" / "page.html").as_uri() + "#strapdown.analysis.core.units.deg", "https://example.org/x"]
    bad = [(site / "api" / "missing.html").as_uri(), (site / "api" / "page.html").as_uri() + "#no-such-id", (tmp_path / "outside.html").as_uri()]
    cache = {}
    assert check_docs.broken_links(page, good, site, cache) == []
    found = check_docs.broken_links(page, bad, site, cache)
    assert len(found) == 3
    assert "no such file" in found[0] and "no anchor #no-such-id" in found[1] and "leaves the site" in found[2]


def _fenced(text: str, language: str) -> list:
    return re.findall(rf"^```{re.escape(language)}\n(.*?)^```$", text, flags=re.S | re.M)


def test_the_landing_page_example_prints_what_the_page_shows():
    """The five lines of docs/index.md run, and print the output the page shows under them."""
    import contextlib
    import io

    page = (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
    (code,), (shown,) = _fenced(page, "python"), _fenced(page, "text")
    assert len(code.strip().splitlines()) == 5
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "docs/index.md", "exec"), {})
    assert out.getvalue() == shown
    assert "sphx_glr_plot_drift_vs_step_001.png" in page and (ROOT / "docs" / "examples" / "gallery" / "coning" / "plot_drift_vs_step.py").is_file()


def test_command_lines_are_not_read_as_arithmetic():
    """The ``cli`` lexer of the site keeps ``panov-4s-3`` one plain word and ``--algorithm`` an option; Python's does not."""
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    try:
        from cli_lexer import CommandLineLexer
    finally:
        sys.path.remove(str(ROOT / "docs" / "_ext"))
    from pygments.lexers import PythonLexer
    from pygments.token import Name, Number, Operator, Text

    line = "strapdown drift --algorithm panov-4s-3 --freq-hz 10  # coning\n"
    tokens = [(t, v) for t, v in CommandLineLexer().get_tokens(line) if v.strip()]
    assert (Text, "panov-4s-3") in tokens and (Name.Attribute, "--algorithm") in tokens
    assert not any(t in Operator or t in Number for t, _ in tokens)
    python = [(t, v) for t, v in PythonLexer().get_tokens(line) if v.strip()]
    assert any(t in Operator and v == "-" for t, v in python)  # the failure the lexer avoids
    # every shell block of the pages is a cli block
    for page in sorted((ROOT / "docs").glob("*.md")):
        for block in _fenced(page.read_text(encoding="utf-8"), ""):
            assert not re.match(r"\s*(strapdown|pip|python|sphinx-build) ", block), f"{page.name}: a shell block without the cli lexer"
