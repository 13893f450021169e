"""Report framework: atomic writes, byte-identical regeneration, --only keeps other sections."""

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


def test_only_keeps_other_files(tmp_path):
    out = tmp_path / "reports"
    report.generate(out, only=["errata", "index"], show_progress=False)
    (out / "keep.md").write_text("kept\n")
    report.generate(out, only=["index"], show_progress=False)
    assert (out / "keep.md").read_text() == "kept\n"
    assert (out / "errata.md").exists()


def test_unknown_section_rejected(tmp_path):
    with pytest.raises(ValueError, match="Expected `only` among"):
        report.generate(tmp_path / "r", only=["nope"], show_progress=False)
