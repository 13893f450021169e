"""Report generation: ``strapdown report`` regenerates ``reports/``.

Each module of this package that defines ``SECTION`` and ``build`` is one
report section (the others, :mod:`.output`, :mod:`.rendering` and
:mod:`.warm_up`, are the machinery).  A section module defines

``SECTION``
    a :class:`Section` (name, title, order);
``build(ctx)``
    writes the section's files through the :class:`Context` ``ctx``;
``errata(ctx)`` (optional)
    returns a list of :class:`Erratum`, each with evidence computed by the
    package; the ``errata`` section gathers them into ``errata.md``;
``warm_up()`` (optional)
    compiles and derives into the caches what ``build`` will need, writing
    nothing else; a cold run does it on the second core (:mod:`.warm_up`).

Reports are pure functions of (configuration, seed): figures carry no dates
or software stamps and are rendered from coordinates rounded far below a pixel
(:mod:`.rendering`), and every random stream is seeded, so two regenerations
are byte-identical, on this machine and on any other with the same matplotlib.

Output is written into a staging directory and swapped into place atomically
only when every section succeeded; a directory holding files that no earlier
run wrote is refused, and so is a regular file, and so is a report whose
generated files were edited since (the manifest keeps the hash of every file),
unless ``overwrite_modified`` (:mod:`.output`).
"""

from __future__ import annotations

import contextlib
import gc
import importlib
import io
import pkgutil
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Any

from ...derivations.reproducible import reproducible
from . import output, warm_up
from .rendering import agg_canvas, configure_matplotlib, drawn_ticks_only, quantise, unplaced_empty_labels

__all__ = ["Section", "Erratum", "Context", "discover", "section_names", "generate", "configure_matplotlib", "SEED"]

#: Root seed of every report (streams are split with ``SeedSequence.spawn``).
SEED = 20261122

#: Modules of this package that are machinery, not sections.
_MACHINERY = frozenset({"output", "rendering", "corrections", "warm_up", "log_figures"})


@dataclass(frozen=True)
class Section:
    """A report section: ``name`` is its file stem, ``order`` its place in the index.

    Attributes
    ----------
    name : str
        Section name (``strapdown report --only NAME``) and file stem.
    title : str
        Title in the index.
    order : int
        Place in the index and build order (lower first).
    summary : str
        One line for the index.
    page : str
        The file the index links to (``<name>.md`` when empty).
    gathers : bool
        The section is built from the other sections (errata, index, HTML edition):
        it is rebuilt whenever any section is.
    """

    name: str
    title: str
    order: int
    summary: str = ""
    page: str = ""
    gathers: bool = False

    @property
    def link(self) -> str:
        """File the index links to, relative to the report directory."""
        return self.page or f"{self.name}.md"


@dataclass(frozen=True)
class Erratum:
    """A place where a source paper and the package's checks part, with the evidence.

    Attributes
    ----------
    source : str
        Paper and place, e.g. "Lebedev & Panov (1989), eq. (1.12)".
    printed : str
        What the paper prints.
    correct : str
        For a misprint, what the check establishes; for an ambiguous place, our
        (likely) reading.
    evidence : str
        How it was established (a computed residual, a convergence study, ...).
    section : str
        Report section holding the full evidence.
    kind : str or None
        ``"misprint"`` (a check decides it) or ``"ambiguous"`` (the text admits
        readings; ``correct`` is ours, ``alternatives`` the others, with their
        numbers).  None only for entries not classified yet (default, so that
        sections that predate the classes keep working).
    alternatives : str
        For an ambiguous entry: the other readings and their numbers.

    Raises
    ------
    ValueError
        For a ``kind`` other than those of :attr:`KINDS` (or None).
    """

    #: The classes: a check decides it, or the text admits readings.
    KINDS = ("misprint", "ambiguous")  # not annotated: a class attribute, not a field

    source: str
    printed: str
    correct: str
    evidence: str
    section: str = ""
    kind: str | None = None
    alternatives: str = ""

    def __post_init__(self):
        if self.kind is not None and self.kind not in self.KINDS:
            raise ValueError(f"Expected `kind` among {', '.join(self.KINDS)}, got {self.kind!r}")


@dataclass
class Context:
    """What a section builder gets: where to write, how big to run, how to draw.

    Attributes
    ----------
    out_dir : Path
        Directory the section writes into (the staging directory during ``generate``).
    quick : bool
        Reduced Monte Carlo sizes and grids (for CI).
    seed : int
        Root seed of the report.
    show_progress : bool
        Progress bars on stderr.
    files : list of str
        Files written so far, relative to ``out_dir`` (POSIX paths).
    command : str
        The command line stamped in the index.
    sections : tuple
        Section modules of this run, in index order (default: :func:`discover`).
    figure_check : callable or None
        Called as ``figure_check(relpath, fig)`` after each figure is written and
        before it is closed (``tools/check_figures.py`` measures the layout there).
    """

    out_dir: Path
    quick: bool = False
    seed: int = SEED
    show_progress: bool = True
    files: list = field(default_factory=list)
    command: str = "strapdown report"
    sections: tuple = ()
    figure_check: Callable | None = None
    _shared: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self):
        self.out_dir = Path(self.out_dir)
        if not self.sections:
            self.sections = tuple(discover())

    # ---------------------------------------------------------------- shared results
    def shared(self, key: str, compute: Callable[[], Any]) -> Any:
        """The result of ``compute()``, computed once per report run and shared by key.

        A section and its ``errata`` (gathered later by the errata section) quote
        the same Monte Carlo or derivation; the first caller computes it, later
        callers get the same object.  The key must name everything the result
        depends on besides this context (its size and seed), e.g.
        ``"azimuth/violation-cases"``.

        Parameters
        ----------
        key : str
            Name of the result, unique in the report.
        compute : callable
            ``compute() -> result``, called at most once per key and context.

        Returns
        -------
        object
            The result.
        """
        if not isinstance(key, str) or not key:
            raise TypeError(f"Expected `key` as a non-empty str, got {key!r}")
        if key not in self._shared:
            self._shared[key] = compute()
        return self._shared[key]

    # ---------------------------------------------------------------- writing
    def path(self, relpath: str) -> Path:
        """Absolute path of ``relpath`` under :attr:`out_dir`, its parent directory created.

        Parameters
        ----------
        relpath : str
            A relative POSIX path such as ``"figures/x.png"`` (no ``..``).

        Returns
        -------
        Path
        """
        parts = PurePosixPath(relpath).parts
        if not parts or PurePosixPath(relpath).is_absolute() or any(p in ("..", ".") for p in parts):
            raise ValueError(f"Expected `relpath` relative and inside the report, got {relpath!r}")
        p = self.out_dir.joinpath(*parts)
        p.parent.mkdir(parents=True, exist_ok=True)
        return p

    def _record(self, relpath: str) -> None:
        name = PurePosixPath(relpath).as_posix()
        if name not in self.files:
            self.files.append(name)

    def write_text(self, relpath: str, text: str) -> Path:
        """Write a UTF-8 text file (``\\n`` line ends) under :attr:`out_dir`.

        Parameters
        ----------
        relpath : str
            Relative POSIX path of the file.
        text : str
            Its content (a final newline is added if missing).

        Returns
        -------
        Path
            The file written.
        """
        p = self.path(relpath)
        p.write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8", newline="\n")
        self._record(relpath)
        return p

    def savefig(self, fig, relpath: str, *, dpi: int = 110) -> Path:
        """Save a matplotlib figure deterministically and close it.

        No date or software metadata is written, and every drawn coordinate is
        rounded far below a pixel first (:func:`.rendering.quantise`), so the
        bytes do not depend on the last bits of the machine's floating point.
        The figure is saved at its own size, drawn once: its layout is fixed
        when it is built (:func:`.rendering.fixed_layout`), because a layout
        engine or ``bbox_inches="tight"`` measures every text in extra passes
        that cost more than the drawing itself.  Log axes make tick objects only
        for the ticks in view (:func:`.rendering.drawn_ticks_only`), and empty axis
        labels are not placed (:func:`.rendering.unplaced_empty_labels`).  The cycle collector is paused
        while the figure is drawn and encoded (it would otherwise walk the heap
        many times over the drawing's short-lived objects); the figure's
        reference cycles are collected by a later pass, after it is closed.

        Parameters
        ----------
        fig : matplotlib.figure.Figure
            The figure.
        relpath : str
            Relative POSIX path; its suffix (``.png``, ``.svg``, ``.pdf``) sets the format.
        dpi : int, keyword-only
            Resolution of raster formats [dots per inch].

        Returns
        -------
        Path
            The file written.
        """
        import matplotlib.pyplot as plt

        p = self.path(relpath)
        suffix = p.suffix.lower()
        if suffix == ".svg":
            metadata = {"Date": None, "Creator": None}
        elif suffix == ".pdf":
            metadata = {"CreationDate": None, "Creator": None, "Producer": None}
        else:
            metadata = {"Software": None}
        quantise(fig)
        drawn_ticks_only(fig)
        unplaced_empty_labels(fig)
        if suffix == ".png":
            agg_canvas(fig)
        buf = io.BytesIO()
        collecting = gc.isenabled()
        gc.disable()  # drawing allocates thousands of small objects: no cycle collection passes while it runs
        try:
            fig.savefig(buf, format=suffix.lstrip("."), dpi=dpi, metadata=metadata)
        finally:
            if collecting:
                gc.enable()
        p.write_bytes(buf.getvalue())
        self._record(relpath)
        if self.figure_check is not None:
            self.figure_check(relpath, fig)
        plt.close(fig)
        return p

    # ---------------------------------------------------------------- progress
    def progress(self, iterable: Iterable, desc: str, total: int | None = None):
        """Wrap ``iterable`` in a progress bar on stderr (silent when :attr:`show_progress` is off).

        Parameters
        ----------
        iterable : iterable
            What to iterate over.
        desc : str
            Label of the bar.
        total : int, optional
            Number of items [count] (default ``len(iterable)``).

        Returns
        -------
        tqdm.tqdm or a task of :func:`strapdown.analysis.core.progress.lines`
        """
        from ..core.progress import bar

        return bar(iterable, desc=desc, total=total, enabled=self.show_progress)


def section_names() -> list:
    """Names of the report sections, without importing them (cheap enough for ``--help``).

    Returns
    -------
    list of str
        Sorted section names; each section module is named after its section (``_`` in a module name is ``-`` in the section name).
    """
    return sorted(info.name.replace("_", "-") for info in pkgutil.iter_modules(__path__) if not info.name.startswith("_") and info.name not in _MACHINERY)


def discover() -> list:
    """Section modules of this package, in report order.

    Returns
    -------
    list of module
        Modules with ``SECTION`` and ``build``, sorted by ``SECTION.order``.
    """
    modules = []
    for name in section_names():
        module = importlib.import_module(f"{__name__}.{name.replace('-', '_')}")
        if hasattr(module, "SECTION") and hasattr(module, "build"):
            modules.append(module)
    return sorted(modules, key=lambda m: (m.SECTION.order, m.SECTION.name))


def generate(
    out: Path | str = "reports",
    *,
    only: Iterable[str] | None = None,
    quick: bool = False,
    show_progress: bool = True,
    command: str = "strapdown report",
    sections: Sequence | None = None,
    figure_check: Callable | None = None,
    overwrite_modified: bool = False,
    background: bool = True,
) -> list[str]:
    """Regenerate the reports into ``out``, atomically and without touching foreign files.

    The destination is checked first (:func:`.output.prepare`): a regular file,
    or a directory holding files that no earlier run wrote, is refused before
    any work.  Under the destination's lock, what killed runs left is cleaned
    up; the report is built in a staging directory, its manifest written, and
    the staging directory swapped with ``out`` in one atomic step
    (:func:`.output.commit`).  A failure at any point leaves the previous report
    as it was.

    Parameters
    ----------
    out : str or Path
        Destination directory (``reports/`` by default).
    only : iterable of str, optional
        Section names to rebuild; the sections that gather the others (errata,
        index, HTML edition) are rebuilt too, and the files of every other
        section are carried over from the previous report.
    quick : bool, keyword-only
        Reduced Monte Carlo sizes and grids (for CI).
    show_progress : bool, keyword-only
        Progress bars on stderr.
    command : str, keyword-only
        The command line stamped in the index.
    sections : sequence of module, optional, keyword-only
        Section modules to use instead of :func:`discover` (each with ``SECTION`` and ``build``).
    figure_check : callable, optional, keyword-only
        ``figure_check(relpath, fig)``, called for every figure after it is written
        (:attr:`Context.figure_check`).
    overwrite_modified : bool, keyword-only
        Replace generated files of ``out`` that were edited since the run that
        wrote them (by default such a run is refused and the edits kept).
    background : bool, keyword-only
        Fill the caches of the sections ahead of them in a second process
        (:mod:`.warm_up`; only while they are cold, and without effect on the
        result).

    Returns
    -------
    list of str
        Names of the sections rebuilt, in build order.

    Raises
    ------
    ValueError
        If ``only`` names an unknown section.
    strapdown.analysis.report.output.OutputError
        If ``out`` must not be replaced (foreign files, a regular file), another
        run holds its lock, or it cannot be written.
    strapdown.analysis.report.output.ModifiedFilesError
        If the run would replace generated files edited since they were written
        (and not ``overwrite_modified``); they are named and left untouched.
    """
    from ..core.progress import bar

    modules = list(discover() if sections is None else sections)
    names = [m.SECTION.name for m in modules]
    requested = list(names) if only is None else list(only)
    unknown = [n for n in requested if n not in names]
    if unknown or not requested:
        raise ValueError(f"Expected `only` among {', '.join(names)}, got {', '.join(repr(n) for n in unknown) or 'no section'}")
    selected = set(requested) | {m.SECTION.name for m in modules if m.SECTION.gathers}
    todo = [m for m in modules if m.SECTION.name in selected]
    replaced = None if only is None else {m.SECTION.name for m in todo}  # the sections whose files are replaced
    dest = output.prepare(out)  # refuse early, before the lock and any work
    output.refuse_modified(dest, replaced, overwrite_modified=overwrite_modified)
    configure_matplotlib()
    with output.lock(dest), _frozen_heap():
        output.clean(dest)
        dest = output.prepare(out)  # again under the lock: another run may have replaced it meanwhile
        output.refuse_modified(dest, replaced, overwrite_modified=overwrite_modified)
        if dest.legacy and only is not None:
            raise output.OutputError(
                f"Expected `out` with a report manifest for --only, got {str(dest.path)!r} written before manifests existed: "
                "regenerate it whole once, then sections one by one"
            )
        staged = output.stage(dest)
        helper = warm_up.start(todo) if background else None
        try:
            output.fault("staged")
            kept = _carry_over(dest, staged, {m.SECTION.name for m in todo}) if only is not None else {}
            ctx = Context(out_dir=staged, quick=quick, show_progress=show_progress, command=command, sections=tuple(modules), figure_check=figure_check)
            written = dict(kept)
            expected = _expected_seconds([m.SECTION.name for m in todo], quick) if show_progress else None
            progress = bar(todo, desc="report", enabled=show_progress, leave=False, expected=expected)
            seconds = {}
            for module in progress:
                progress.set_description(f"report: {module.SECTION.name}")
                before = len(ctx.files)
                started = time.monotonic()
                with reproducible():  # SymPy's random choices fixed: same path and time every run
                    module.build(ctx)
                seconds[module.SECTION.name] = time.monotonic() - started
                gc.freeze()  # what the section leaves (its imports, shared results) joins the frozen heap: later full passes skip it
                written[module.SECTION.name] = tuple(sorted(ctx.files[before:]))
                output.fault("section")
            progress.close()
            _record_seconds(seconds, quick)
            files = {f for fs in written.values() for f in fs}
            output.check_legacy(dest, files)
            import matplotlib

            previous = dest.previous.hashes if dest.previous is not None else {}
            carried = {f for fs in kept.values() for f in fs}
            hashes = {f: previous[f] if f in carried and f in previous else output.file_digest(staged.joinpath(*PurePosixPath(f).parts)) for f in sorted(files)}
            manifest = output.Manifest({k: v for k, v in written.items() if v}, matplotlib.__version__, hashes)
            (staged / output.MANIFEST).write_text(manifest.to_json(), encoding="utf-8", newline="\n")
            output.fault("complete")
            output.commit(dest, staged)
        except BaseException:
            import shutil

            shutil.rmtree(staged, ignore_errors=True)
            raise
        finally:
            warm_up.stop(helper)
    return [m.SECTION.name for m in todo]


@contextlib.contextmanager
def _frozen_heap():
    """Keep the objects that exist now out of the cycle collector's full passes while the block runs.

    They are the imported modules and what they built (a few hundred thousand
    objects), alive as long as the process; every full pass during a report
    would walk them again (about a third of the time of those passes).  The
    report freezes again after each section, so that what a section leaves
    (the modules it imported, the results it shares with later sections) is
    not walked by the later sections' passes either: the full passes of a
    warm report take 0.1 s instead of 0.5–0.7 s, for about 50 MB more at the
    peak (what a section leaves in reference cycles is collected only when
    the block ends).  Everything is handed back to the collector when the
    block ends.
    """
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


def _timings_file() -> Path:
    """Where the sections' durations of the last run are kept (beside the cache of generated code)."""
    from ..core.cache import cache_directory

    return cache_directory().parent / "report-timings.json"


def _expected_seconds(names: list, quick: bool) -> list | None:
    """Each section's duration in the last run of the same kind, to weight the progress (None before any run).

    A section the last run did not time counts as the median of the others.
    The durations only pace the progress lines; the report does not depend on them.
    """
    import json
    import statistics

    try:
        known = json.loads(_timings_file().read_text(encoding="utf-8")).get("quick" if quick else "full", {})
    except (OSError, ValueError, AttributeError):
        return None
    values = [known.get(n) for n in names]
    timed = [float(v) for v in values if isinstance(v, (int, float)) and v >= 0]
    if not timed:
        return None
    fill = statistics.median(timed)
    return [float(v) if isinstance(v, (int, float)) and v >= 0 else fill for v in values]


def _record_seconds(seconds: dict, quick: bool) -> None:
    """Keep this run's section durations for the next run's progress (atomically; an unwritable cache is ignored)."""
    import json
    import os
    import tempfile

    path = _timings_file()
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        data = data if isinstance(data, dict) else {}
    except (OSError, ValueError):
        data = {}
    kind = "quick" if quick else "full"
    data[kind] = {**(data.get(kind) if isinstance(data.get(kind), dict) else {}), **{k: round(v, 3) for k, v in seconds.items()}}
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as handle:
                json.dump(data, handle, indent=1, sort_keys=True)
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
    except OSError:
        pass


def _carry_over(dest: output.Destination, staged: Path, rebuilt: set) -> dict:
    """Copy the files of the sections not rebuilt from the previous report into ``staged``."""
    import shutil

    kept = {}
    if dest.previous is None:  # new, empty (a pre-manifest report is refused for partial runs)
        return kept
    sections = {k: v for k, v in dest.previous.sections.items() if k not in rebuilt}
    for name, files in sections.items():
        present = []
        for rel in files:
            src = dest.path.joinpath(*PurePosixPath(rel).parts)
            if src.is_file():
                target = staged.joinpath(*PurePosixPath(rel).parts)
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, target)
                present.append(rel)
        if present:
            kept[name] = tuple(present)
    return kept
