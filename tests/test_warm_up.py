"""The first run: caches filled on the second core while the report is written, and shared without duplicate work."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import pytest

from strapdown.analysis.report import Section, generate, warm_up

SECTIONS = textwrap.dedent(
    """
    import os
    import time
    from pathlib import Path

    from strapdown.analysis.report import Section

    FLAG = Path(os.environ["WARM_UP_TEST_FLAG"])


    class First:
        SECTION = Section("first", "First", 1)

        @staticmethod
        def build(ctx):
            # the report's first section: it waits (up to a minute) for the warm-up of a later one
            deadline = time.monotonic() + 60.0
            while not FLAG.exists() and time.monotonic() < deadline:
                time.sleep(0.05)
            ctx.write_text("first.md", "warmed\\n" if FLAG.exists() else "not warmed\\n")


    def warm_up():
        FLAG.write_text(str(os.getpid()))


    SECTION = Section("second", "Second", 2)


    def build(ctx):
        ctx.write_text("second.md", "second\\n")
    """
)


@pytest.fixture
def sections(tmp_path, monkeypatch):
    (tmp_path / "warm_up_sections.py").write_text(SECTIONS, encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(tmp_path), os.environ.get("PYTHONPATH", "")]))
    monkeypatch.setenv("WARM_UP_TEST_FLAG", str(tmp_path / "warmed"))
    monkeypatch.setenv("STRAPDOWN_CACHE_DIR", str(tmp_path / "cache"))
    import importlib

    module = importlib.import_module("warm_up_sections")
    yield [module.First, module]
    sys.modules.pop("warm_up_sections", None)


def test_later_sections_are_warmed_in_another_process_while_the_first_is_built(tmp_path, sections):
    generate(tmp_path / "r", sections=sections, show_progress=False)
    assert (tmp_path / "r" / "first.md").read_text() == "warmed\n"
    assert int((tmp_path / "warmed").read_text()) != os.getpid()


def test_a_finished_warm_up_is_not_repeated(sections):
    process = warm_up.start(sections)
    assert process is not None and process.wait(timeout=120) == 0
    assert warm_up.start(sections) is None  # its marker is in the cache directory


def test_nothing_to_warm_starts_nothing():
    class Plain:
        SECTION = Section("plain", "Plain", 1)

    assert warm_up.start([Plain, Plain]) is None


def test_two_processes_derive_a_cached_entry_once(tmp_path):
    """The second process waits for the first one's entry instead of deriving it again."""
    log = tmp_path / "builds.txt"
    code = textwrap.dedent(
        f"""
        import os, sys, time
        from strapdown.analysis.core.cache import derived

        def build():
            with open({str(log)!r}, "a") as f:
                f.write(f"{{os.getpid()}} {{time.time()}}\\n")
            time.sleep(3.0)
            return 42

        sys.stdout.write(f"{{time.time()}} ")
        print(derived("test:single-flight:v1", build))
        """
    )
    env = dict(os.environ, STRAPDOWN_CACHE_DIR=str(tmp_path / "cache"))
    procs = [subprocess.Popen([sys.executable, "-c", code], env=env, stdout=subprocess.PIPE, text=True) for _ in range(2)]
    outs = [p.communicate(timeout=300)[0].split() for p in procs]
    assert [o[1] for o in outs] == ["42", "42"]
    builds = log.read_text().splitlines()
    if max(float(o[0]) for o in outs) >= float(builds[0].split()[1]) + 3.0:
        pytest.skip("the second process started after the first had finished: nothing to share")
    assert len(builds) == 1, builds  # both asked while the first was building: the second waited and loaded it


def test_the_warm_up_module_is_machinery_not_a_section():
    from strapdown.analysis.report import section_names

    assert "warm-up" not in section_names()
