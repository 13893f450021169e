"""Report framework: atomic writes, byte-identical regeneration, --only keeps other sections.

The output-directory safety rules (foreign files, locks, crashes) are in test_report_output.py.
"""

import hashlib
from pathlib import Path

import pytest

from strapdown.analysis import report


def digest(root: Path) -> dict:
    return {str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(root.rglob("*")) if p.is_file()}


def test_core_sections_byte_identical(tmp_path):
    report.generate(tmp_path / "a", only=["errata", "index"], show_progress=False)
    report.generate(tmp_path / "b", only=["errata", "index"], show_progress=False)
    a, b = digest(tmp_path / "a"), digest(tmp_path / "b")
    assert a and a == b


def test_failed_run_leaves_previous_reports_intact(tmp_path, monkeypatch):
    out = tmp_path / "reports"
    report.generate(out, only=["errata", "index"], show_progress=False)
    before = digest(out)
    from strapdown.analysis.report import index

    def boom(ctx):
        raise RuntimeError("simulated failure")

    monkeypatch.setattr(index, "build", boom)
    with pytest.raises(RuntimeError):
        report.generate(out, only=["errata", "index"], show_progress=False)
    assert digest(out) == before
    leftovers = [p.name for p in tmp_path.iterdir() if p.name != "reports"]
    assert leftovers == []


def test_only_keeps_other_sections_and_rebuilds_the_gathering_ones(tmp_path):
    out = tmp_path / "reports"
    assert report.generate(out, only=["errata"], show_progress=False) == ["errata", "index", "html"]
    errata = (out / "errata.md").read_bytes()
    (out / "errata.md").write_text("an earlier errata page\n")  # a file this package wrote: replaced only if rebuilt
    assert report.generate(out, only=["index"], show_progress=False) == ["errata", "index", "html"]
    assert (out / "errata.md").read_bytes() == errata  # errata gathers every section: rebuilt too
    assert "index.html" in {p.name for p in out.iterdir()}


def test_only_carries_the_files_of_other_sections_over(tmp_path):
    from strapdown.analysis.report import output

    out = tmp_path / "reports"
    report.generate(out, only=["errata"], show_progress=False)
    manifest = output.Manifest.read(out)
    assert set(manifest.sections) == {"errata", "index", "html"}
    assert manifest.files == {"errata.md", "README.md", "index.html"}
    assert sorted(p.name for p in out.iterdir()) == sorted([output.MANIFEST, "errata.md", "README.md", "index.html"])


def test_section_names_are_the_discovered_sections():
    assert report.section_names() == sorted(m.SECTION.name for m in report.discover())


def test_unknown_section_rejected(tmp_path):
    with pytest.raises(ValueError, match="Expected `only` among"):
        report.generate(tmp_path / "r", only=["nope"], show_progress=False)
