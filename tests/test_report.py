"""Report framework: atomic writes, byte-identical regeneration, --only keeps other sections.

The output-directory safety rules (foreign files, locks, crashes) are in test_report_output.py.
"""

import hashlib
import io
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
    (out / "errata.md").write_text("an earlier errata page\n")  # a file this package wrote, edited since
    with pytest.raises(ValueError, match="errata.md"):  # the edit is not lost silently
        report.generate(out, only=["index"], show_progress=False)
    assert (out / "errata.md").read_text() == "an earlier errata page\n"
    assert report.generate(out, only=["index"], show_progress=False, overwrite_modified=True) == ["errata", "index", "html"]
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


def test_shared_results_are_computed_once_per_context(tmp_path):
    ctx = report.Context(out_dir=tmp_path, show_progress=False, sections=(object(),))
    calls = []

    def compute():
        calls.append(1)
        return {"value": len(calls)}

    first = ctx.shared("section/result", compute)
    assert ctx.shared("section/result", compute) is first
    assert calls == [1]
    assert ctx.shared("section/other", compute) == {"value": 2}
    other = report.Context(out_dir=tmp_path, show_progress=False, sections=(object(),))
    assert other.shared("section/result", compute) == {"value": 3}  # a new run computes anew
    with pytest.raises(TypeError, match="`key`"):
        ctx.shared("", compute)


def test_fixed_layout_places_the_grid_in_inches():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from strapdown.analysis.report.rendering import fixed_layout, layout_overflow

    fig, axes = plt.subplots(2, 3, figsize=(10.0, 6.0))
    fixed_layout(fig, left=1.0, right=0.5, bottom=0.8, top=0.4, wgap=0.6, hgap=0.7)
    w, h = 10.0, 6.0
    aw, ah = (w - 1.5 - 2 * 0.6) / 3, (h - 1.2 - 0.7) / 2
    for i in range(2):
        for j in range(3):
            x0, y0, x1, y1 = axes[i, j].get_position().extents
            assert x0 * w == pytest.approx(1.0 + j * (aw + 0.6))
            assert x1 * w == pytest.approx(1.0 + j * (aw + 0.6) + aw)
            assert y1 * h == pytest.approx(h - 0.4 - i * (ah + 0.7))
            assert y0 * h == pytest.approx(h - 0.4 - i * (ah + 0.7) - ah)
    # generous margins leave the text inside; a label wider than its margin reaches past the edge
    left, bottom, right, top = layout_overflow(fig)
    assert max(left, bottom, right, top) < 0.0
    axes[0, 0].set_ylabel("a very long label " * 4)
    axes[0, 0].set_yticks([0.5], ["a tick label wider than the margin"])
    assert layout_overflow(fig)[0] > 0.0
    with pytest.raises(ValueError, match="room for the axes"):
        fixed_layout(fig, left=6.0, right=6.0)
    plt.close(fig)


def test_layout_overlaps_finds_labels_inside_a_neighbouring_frame():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from strapdown.analysis.report.rendering import fixed_layout, layout_overlaps

    fig, (a, b) = plt.subplots(1, 2, figsize=(8.0, 3.0))
    b.set_yticks([0.5], ["a long tick label"])
    fixed_layout(fig, wgap=1.5)
    assert layout_overlaps(fig) == []
    fixed_layout(fig, wgap=0.1)
    ((i, j, w, h),) = layout_overlaps(fig)
    assert (i, j) == (1, 0) and w > 0.3 and h > 0.05
    plt.close(fig)


def test_savefig_hands_each_figure_to_the_check_before_closing(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    seen = []
    ctx = report.Context(out_dir=tmp_path, show_progress=False, sections=(object(),), figure_check=lambda rel, fig: seen.append((rel, plt.fignum_exists(fig.number))))
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [0, 1])
    ctx.savefig(fig, "figures/x.png")
    assert seen == [("figures/x.png", True)]
    assert not plt.fignum_exists(fig.number)
    assert (tmp_path / "figures" / "x.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _png(fig) -> bytes:
    """The PNG bytes of ``fig`` as the report writes them (no software stamp), the figure closed."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def test_agg_canvas_draws_the_same_png_as_matplotlibs_own_with_one_parser():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from strapdown.analysis.report.rendering import agg_canvas

    def figure():
        fig, ax = plt.subplots(figsize=(3, 2))
        ax.loglog([1e-3, 1e2], [1e1, 1e-4], label="$H^4$ and $\\omega$")
        ax.legend()
        return fig

    own = _png(figure())
    first, second = figure(), figure()
    agg_canvas(first), agg_canvas(second)
    assert first.canvas.get_renderer().mathtext_parser is second.canvas.get_renderer().mathtext_parser
    assert _png(first) == own and _png(second) == own


def test_drawn_ticks_only_draws_the_same_png_with_fewer_ticks():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from strapdown.analysis.report.rendering import drawn_ticks_only, quantise

    def figure():
        fig, (a, b) = plt.subplots(1, 2, figsize=(6, 2.5))
        a.loglog([3e-4, 2e2], [7e1, 4e-5], label="$H^4$")
        a.legend()
        b.semilogx([0.15, 35.0], [-2.0, 3.0])  # a linear y axis keeps its locator
        quantise(fig)
        return fig

    def png(fig):
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=110, metadata={"Software": None})
        ticks = [len(axis.majorTicks) + len(axis.minorTicks) for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)]
        plt.close(fig)
        return buf.getvalue(), ticks

    own, own_ticks = png(figure())
    trimmed = figure()
    linear = trimmed.axes[1].yaxis.get_major_locator()
    drawn_ticks_only(trimmed)
    drawn_ticks_only(trimmed)  # a second call leaves the locators as they are
    assert trimmed.axes[1].yaxis.get_major_locator() is linear
    pixels, ticks = png(trimmed)
    assert pixels == own
    assert ticks[0] < own_ticks[0] and ticks[1] < own_ticks[1] and ticks[3] == own_ticks[3]


def test_unplaced_empty_labels_draws_the_same_png():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from strapdown.analysis.report.rendering import unplaced_empty_labels

    def figure():
        fig, (a, b) = plt.subplots(1, 2, figsize=(6, 2.5), sharey=True)
        a.plot([0.0, 1.0], [2.0, 3.0])
        b.plot([0.0, 1.0], [3.0, 2.0])
        a.set_xlabel("time [s]")
        a.set_ylabel("rate [deg/h]")
        return fig

    own = _png(figure())
    pinned = figure()
    unplaced_empty_labels(pinned)
    a, b = pinned.axes
    assert a.xaxis.label.get_position() != (0.5, 0.5) and b.yaxis.label.get_position() == (0.5, 0.5)
    assert _png(pinned) == own
