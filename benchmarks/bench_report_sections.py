"""Benchmark: where the full report spends its time, section by section, with warm caches.

``run_all.py`` times the whole ``strapdown report`` (target: under 30 s on one core);
this script says where that time goes.  A first full report in a child process fills
the on-disk caches (numba's machine code, the generated code and the results of the
derivations), as any run after the first would find them; then the report is built
again in this process with every section's ``build`` timed, and, inside the sections,
every figure's ``Context.savefig`` (drawing and PNG encoding).  Imports made before the
first section are listed on their own line; those a section makes itself count in it.

    python benchmarks/bench_report_sections.py
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path


def main() -> None:
    with tempfile.TemporaryDirectory(prefix="bench-sections-") as tmp:
        subprocess.run([sys.executable, "-m", "strapdown.analysis", "report", "--no-progress", "--out", str(Path(tmp) / "warm-up")], check=True, stdout=subprocess.DEVNULL)
        start = time.perf_counter()
        from strapdown.analysis import report

        modules = report.discover()
        imported = time.perf_counter() - start
        sections, figures = {}, {}
        save = report.Context.savefig

        def timed_save(ctx, fig, relpath, **kwargs):
            t = time.perf_counter()
            out = save(ctx, fig, relpath, **kwargs)
            figures[relpath] = time.perf_counter() - t
            return out

        def timed(module):
            build = module.build

            def run(ctx):
                before = set(figures)
                t = time.perf_counter()
                build(ctx)
                sections[module.SECTION.name] = (time.perf_counter() - t, sum(v for k, v in figures.items() if k not in before), len(set(figures) - before))

            return run

        report.Context.savefig = timed_save
        for m in modules:
            m.build = timed(m)
        t = time.perf_counter()
        report.generate(Path(tmp) / "timed", show_progress=False, sections=modules)
        total = time.perf_counter() - t
    print("| part | wall [s] | of which figures [s] | figures |")
    print("|---|---:|---:|---:|")
    print(f"| imports before the sections | {imported:.2f} | | |")
    for name, (secs, figs, n) in sections.items():
        print(f"| {name} | {secs:.2f} | {figs:.2f} | {n} |")
    rest = total - sum(s for s, _, _ in sections.values())
    print(f"| staging, manifest, atomic swap | {rest:.2f} | | |")
    print(f"| **report, in process** | **{imported + total:.2f}** | **{sum(figures.values()):.2f}** | **{len(figures)}** |")
    print("(one process, warm on-disk caches; interpreter start-up not included)")


if __name__ == "__main__":
    main()
