"""``strapdown report --out DIR`` never loses data: foreign files, regular files, locks, and crashes at any instant.

The crash tests kill the writer with SIGKILL at each of the instants of
``strapdown.analysis.report.output.FAULT_POINTS`` (the fault-injection hook
``STRAPDOWN_REPORT_FAULT`` of that module, so nothing depends on timing) and
check that the report directory holds one complete report, never a mixture or
nothing, and that the next run leaves no stray directory or lock behind.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from strapdown.analysis.cli import main
from strapdown.analysis.report import generate, output

ROOT = Path(__file__).resolve().parent.parent

def fake_sections(version: str = "1") -> list:
    """Two small sections and a gathering one, whose files carry ``version``: a crash test takes a second, not a minute."""
    import types

    from strapdown.analysis.report import Section

    def module(name, order, files, gathers=False):
        m = types.ModuleType(name)
        m.SECTION = Section(name, name.title(), order, gathers=gathers)

        def build(ctx):
            for rel in files:
                ctx.write_text(rel, f"{name} {rel} version {version}\n")

        m.build = build
        return m

    return [module("first", 1, ["first.md", "figures/first.txt"]), module("second", 2, ["second.md"]), module("index", 100, ["README.md"], gathers=True)]


SCRIPT = textwrap.dedent(
    f"""
    import sys
    from pathlib import Path
    sys.path.insert(0, {str(Path(__file__).resolve().parent)!r})
    from test_report_output import fake_sections
    from strapdown.analysis.report import generate
    generate(Path(sys.argv[1]), sections=fake_sections(sys.argv[2]), show_progress=False)
    """
)


def _run(tmp_path, out, version, **env):
    script = tmp_path / "write_report.py"
    script.write_text(SCRIPT, encoding="utf-8")
    full = {k: v for k, v in os.environ.items() if not k.startswith("STRAPDOWN_REPORT_")}
    full.update(env)
    return subprocess.run([sys.executable, str(script), str(out), version], capture_output=True, text=True, env=full, cwd=ROOT, timeout=120)


def _snapshot(root: Path) -> dict:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def _versions(root: Path) -> set:
    """The versions the report files of ``root`` carry (one for a complete report)."""
    return {p.read_text().split()[-1] for p in root.rglob("*") if p.is_file() and p.name != output.MANIFEST}


def _strays(parent: Path, name: str) -> list:
    return sorted(p.name for p in parent.iterdir() if p.name.startswith(f".{name}.strapdown-"))


# --------------------------------------------------------------------------- what may be replaced
def test_directory_with_a_user_file_is_refused_and_left_untouched(tmp_path, capsys):
    out = tmp_path / "docs"
    out.mkdir()
    (out / "notes.txt").write_text("my notes\n")
    (out / "sub").mkdir()
    (out / "sub" / "data.csv").write_text("1,2\n")
    before = _snapshot(out)
    stat = os.stat(out / "notes.txt")
    assert main(["report", "--only", "errata", "--out", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("strapdown report: error: argument --out: ") and "notes.txt" in err and "left untouched" in err
    assert _snapshot(out) == before and os.stat(out / "notes.txt").st_mtime_ns == stat.st_mtime_ns
    assert sorted(p.name for p in tmp_path.iterdir()) == ["docs"]  # no staging directory, no lock


def test_regular_file_as_out_is_refused_and_stays_a_file(tmp_path, capsys):
    target = tmp_path / "report.txt"
    target.write_text("not a directory\n")
    assert main(["report", "--only", "errata", "--out", str(target), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert "regular file" in err and err.count("\n") == 1
    assert target.is_file() and target.read_text() == "not a directory\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.txt"]


def test_empty_user_subdirectory_counts_as_foreign(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections(), show_progress=False)
    (out / "mine").mkdir()
    with pytest.raises(output.OutputError, match="mine"):
        generate(out, sections=fake_sections(), show_progress=False)
    assert (out / "mine").is_dir()


def test_file_added_to_an_earlier_report_is_refused(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections(), show_progress=False)
    (out / "figures" / "added-by-hand.png").write_bytes(b"\x89PNG")
    before = _snapshot(out)
    with pytest.raises(output.OutputError, match="added-by-hand.png"):
        generate(out, sections=fake_sections("2"), show_progress=False)
    assert _snapshot(out) == before


def test_unreadable_manifest_is_refused(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections(), show_progress=False)
    (out / output.MANIFEST).write_text("{not json")
    with pytest.raises(output.OutputError, match="unreadable"):
        generate(out, sections=fake_sections(), show_progress=False)


def test_filesystem_root_is_refused():
    with pytest.raises(output.OutputError, match="root"):
        output.prepare("/")


def test_manifest_lists_what_was_written_and_only_that_is_replaced(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    manifest = json.loads((out / output.MANIFEST).read_text())
    assert manifest["sections"] == {"first": ["figures/first.txt", "first.md"], "second": ["second.md"], "index": ["README.md"]}
    generate(out, sections=fake_sections("2"), show_progress=False)
    assert _versions(out) == {"2"}
    generate(out, sections=fake_sections("3"), only=["second"], show_progress=False)
    # the gathering section is rebuilt with the one asked for; the other section is carried over
    assert (out / "second.md").read_text().endswith("version 3\n") and (out / "README.md").read_text().endswith("version 3\n")
    assert (out / "first.md").read_text().endswith("version 2\n")


def test_manifest_records_the_hash_of_every_file(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    manifest = json.loads((out / output.MANIFEST).read_text())
    files = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file() and p.name != output.MANIFEST)
    assert sorted(manifest["sha256"]) == files
    assert all(manifest["sha256"][f] == output.file_digest(out / f) for f in files)


def test_an_edited_generated_file_stops_the_next_run_and_survives(tmp_path, capsys):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    (out / "first.md").write_text("my corrections\n")
    before = _snapshot(out)
    with pytest.raises(output.ModifiedFilesError, match="first.md") as info:
        generate(out, sections=fake_sections("2"), show_progress=False)
    assert info.value.files == ["first.md"] and "`overwrite_modified=True`" in str(info.value)
    assert _snapshot(out) == before
    # the command line: exit status 2, one line naming the file and the option, before any work
    assert main(["report", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("strapdown report: error: argument --out: ") and "first.md" in err and "--overwrite-modified" in err
    assert _snapshot(out) == before and _strays(tmp_path, "r") == []


def test_overwrite_modified_replaces_the_edited_file(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    (out / "figures" / "first.txt").write_text("edited\n")
    generate(out, sections=fake_sections("2"), show_progress=False, overwrite_modified=True)
    assert _versions(out) == {"2"}
    assert output.modified_files(output.prepare(out)) == []


def test_a_partial_run_keeps_an_edit_it_does_not_replace_and_still_marks_it(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    (out / "second.md").write_text("edited\n")
    generate(out, only=["first"], sections=fake_sections("2"), show_progress=False)  # rebuilds first and the index only
    assert (out / "second.md").read_text() == "edited\n"
    assert output.modified_files(output.prepare(out)) == ["second.md"]
    with pytest.raises(output.ModifiedFilesError, match="second.md"):
        generate(out, sections=fake_sections("3"), show_progress=False)
    with pytest.raises(output.ModifiedFilesError, match="second.md"):
        generate(out, only=["second"], sections=fake_sections("3"), show_progress=False)


def test_a_missing_generated_file_is_not_an_edit(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    (out / "second.md").unlink()
    generate(out, sections=fake_sections("2"), show_progress=False)
    assert _versions(out) == {"2"} and (out / "second.md").is_file()


def test_a_manifest_without_hashes_is_still_read(tmp_path):
    out = tmp_path / "r"
    generate(out, sections=fake_sections("1"), show_progress=False)
    body = json.loads((out / output.MANIFEST).read_text())
    body["format"] = 1
    del body["sha256"]
    (out / output.MANIFEST).write_text(json.dumps(body))
    (out / "first.md").write_text("edited before hashes were kept\n")
    generate(out, sections=fake_sections("2"), show_progress=False)  # nothing to compare with: replaced, as before
    assert _versions(out) == {"2"}


def test_earlier_report_without_manifest(tmp_path):
    out = tmp_path / "r"
    out.mkdir()
    (out / "README.md").write_text(output.LEGACY_SIGNATURE + "\n\nold\n")
    (out / "first.md").write_text("old\n")
    before = _snapshot(out)
    with pytest.raises(output.OutputError, match="regenerate it whole once"):  # --only cannot tell its files from a user's
        generate(out, sections=fake_sections(), only=["first"], show_progress=False)
    assert _snapshot(out) == before
    generate(out, sections=fake_sections(), show_progress=False)  # every old file is replaced: accepted
    assert (out / output.MANIFEST).is_file() and _versions(out) == {"1"}
    legacy = tmp_path / "legacy"
    legacy.mkdir()
    (legacy / "README.md").write_text(output.LEGACY_SIGNATURE + "\n\nold\n")
    (legacy / "notes.md").write_text("kept\n")
    before = _snapshot(legacy)
    with pytest.raises(output.OutputError, match="notes.md"):
        generate(legacy, sections=fake_sections(), show_progress=False)
    assert _snapshot(legacy) == before and _strays(tmp_path, "legacy") == []


def test_symbolic_link_to_a_report_directory(tmp_path):
    real = tmp_path / "real"
    link = tmp_path / "link"
    generate(real, sections=fake_sections("1"), show_progress=False)
    link.symlink_to(real)
    generate(link, sections=fake_sections("2"), show_progress=False)
    assert link.is_symlink() and _versions(real) == {"2"}


def test_new_directory_gets_default_permissions(tmp_path):
    out = tmp_path / "r"
    old = os.umask(0o022)
    try:
        generate(out, sections=fake_sections(), show_progress=False)
    finally:
        os.umask(old)
    assert out.stat().st_mode & 0o777 == 0o755


# --------------------------------------------------------------------------- concurrency
def test_second_run_on_a_locked_directory_exits_2(tmp_path):
    out = tmp_path / "r"
    dest = output.prepare(out)
    with output.lock(dest) as lock_file:
        assert lock_file.exists()
        result = subprocess.run(
            [sys.executable, "-m", "strapdown.analysis", "report", "--only", "errata", "--out", str(out), "--no-progress"], capture_output=True, text=True, cwd=ROOT, timeout=300
        )
        assert result.returncode == 2 and result.stdout == ""
        assert result.stderr.count("\n") == 1 and "another `strapdown report`" in result.stderr and "wait for it to finish" in result.stderr
    assert not lock_file.exists() and not out.exists()


def test_lock_is_released_and_removed_after_a_failure(tmp_path):
    out = tmp_path / "r"

    def boom(ctx):
        raise RuntimeError("section failed")

    broken = fake_sections()
    broken[1].build = boom
    with pytest.raises(RuntimeError):
        generate(out, sections=broken, show_progress=False)
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    generate(out, sections=fake_sections(), show_progress=False)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r"]


# --------------------------------------------------------------------------- crashes
BEFORE_SWAP = ["staged", "section", "complete", "before-swap"]
AFTER_SWAP = ["swapped", "cleaning"]


@pytest.mark.parametrize("point", BEFORE_SWAP + AFTER_SWAP)
def test_sigkill_at_any_instant_leaves_one_complete_report(tmp_path, point):
    out = tmp_path / "reports"
    generate(out, sections=fake_sections("old"), show_progress=False)
    old = _snapshot(out)
    killed = _run(tmp_path, out, "new", STRAPDOWN_REPORT_FAULT=point)
    assert killed.returncode == -9, killed.stderr
    # never missing, never a mixture: the previous report until the swap, the new one after it
    assert out.is_dir()
    if point in BEFORE_SWAP:
        assert _snapshot(out) == old
    else:
        assert _versions(out) == {"new"} and set(_snapshot(out)) == set(old)
    generate(out, sections=fake_sections("next"), show_progress=False)
    assert _versions(out) == {"next"} and set(_snapshot(out)) == set(old)
    assert _strays(tmp_path, "reports") == []  # staging and old directories cleaned, lock removed


def test_sigkill_between_the_two_renames_of_the_fallback(tmp_path):
    """Without an atomic exchange the directory is missing between two renames; the next run restores it first."""
    out = tmp_path / "reports"
    generate(out, sections=fake_sections("old"), show_progress=False)
    old = _snapshot(out)
    killed = _run(tmp_path, out, "new", STRAPDOWN_REPORT_FAULT="between-renames", STRAPDOWN_REPORT_SWAP="rename")
    assert killed.returncode == -9
    assert not out.exists() and len(_strays(tmp_path, "reports")) >= 1  # the previous report waits beside it
    dest = output.prepare(out)
    with output.lock(dest):
        output.clean(dest)
    assert _snapshot(out) == old and _strays(tmp_path, "reports") == []
    generate(out, sections=fake_sections("next"), show_progress=False)
    assert _versions(out) == {"next"} and _strays(tmp_path, "reports") == []


def test_fault_points_are_the_documented_ones():
    with pytest.raises(ValueError, match="point"):
        output.fault("nowhere")
    assert set(BEFORE_SWAP + AFTER_SWAP + ["between-renames"]) == set(output.FAULT_POINTS)
