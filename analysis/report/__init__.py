"""Report generation: ``strapdown report`` regenerates ``reports/``.

Each module of this package (name not starting with ``_``) is one report
section.  It defines

``SECTION``
    a :class:`Section` (name, title, order);
``build(ctx)``
    writes the section's files through the :class:`Context` ``ctx``;
``errata(ctx)`` (optional)
    returns a list of :class:`Erratum`, each with evidence computed by the
    package; the ``errata`` section gathers them into ``errata.md``.

Reports are pure functions of (configuration, seed): figures carry no dates
or software stamps, and every random stream is seeded, so two regenerations
are byte-identical.  Output is staged in a temporary directory and moved into
place only when every section succeeded, so a failed run leaves the previous
reports intact.
"""

from __future__ import annotations

import importlib
import io
import os
import pkgutil
import shutil
import sys
import tempfile
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

from ...derivations.reproducible import reproducible

__all__ = ["Section", "Erratum", "Context", "discover", "generate", "SEED"]

#: Root seed of every report (streams are split with ``SeedSequence.spawn``).
SEED = 20261122


@dataclass(frozen=True)
class Section:
    """A report section: ``name`` is its file stem, ``order`` its place in the index.

    ``page`` is the file the index links to (``<name>.md`` when empty).
    """

    name: str
    title: str
    order: int
    summary: str = ""
    page: str = ""

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
    """What a section builder gets: where to write, how big to run, how to draw."""

    out_dir: Path
    quick: bool = False
    seed: int = SEED
    show_progress: bool = True
    files: list = field(default_factory=list)

    # ---------------------------------------------------------------- writing
    def path(self, relpath: str) -> Path:
        p = self.out_dir / relpath
        p.parent.mkdir(parents=True, exist_ok=True)
        return p

    def write_text(self, relpath: str, text: str) -> Path:
        """Write a UTF-8 text file (``\\n`` line ends) under the staging directory."""
        p = self.path(relpath)
        p.write_text(text if text.endswith("\n") else text + "\n", encoding="utf-8", newline="\n")
        self.files.append(relpath)
        return p

    def savefig(self, fig, relpath: str, *, dpi: int = 110) -> Path:
        """Save a matplotlib figure deterministically (no date or software metadata)."""
        import matplotlib.pyplot as plt

        p = self.path(relpath)
        suffix = p.suffix.lower()
        if suffix == ".svg":
            metadata = {"Date": None, "Creator": None}
        elif suffix == ".pdf":
            metadata = {"CreationDate": None, "Creator": None, "Producer": None}
        else:
            metadata = {"Software": None}
        buf = io.BytesIO()
        fig.savefig(buf, format=suffix.lstrip("."), dpi=dpi, metadata=metadata, bbox_inches="tight")
        plt.close(fig)
        p.write_bytes(buf.getvalue())
        self.files.append(relpath)
        return p

    # ---------------------------------------------------------------- progress
    def progress(self, iterable: Iterable, desc: str, total: int | None = None):
        """Wrap ``iterable`` in a tqdm bar on stderr (silent when disabled)."""
        from tqdm import tqdm

        return tqdm(iterable, desc=desc, total=total, file=sys.stderr, leave=False, disable=not self.show_progress)


def configure_matplotlib() -> None:
    """Headless, deterministic matplotlib settings used by every figure."""
    import matplotlib

    matplotlib.use("Agg")
    matplotlib.rcParams.update(
        {
            "svg.hashsalt": "strapdown-analysis",
            "svg.fonttype": "path",
            "figure.dpi": 110,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "font.size": 9,
            "axes.titlesize": 10,
            "legend.fontsize": 8,
        }
    )


def discover() -> list:
    """Section modules of this package, in report order."""
    modules = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        if hasattr(module, "SECTION") and hasattr(module, "build"):
            modules.append(module)
    return sorted(modules, key=lambda m: (m.SECTION.order, m.SECTION.name))


def generate(out: Path | str = "reports", *, only: Iterable[str] | None = None, quick: bool = False, show_progress: bool = True, command: str = "strapdown report") -> list[str]:
    """Regenerate the reports atomically.

    Parameters
    ----------
    out : path
        Destination directory (``reports/`` by default).
    only : iterable of str, optional
        Section names to rebuild; other sections' files are kept as they are.
    quick : bool
        Reduced Monte Carlo sizes and grids (for CI).
    show_progress : bool
        Progress bars on stderr.
    command : str
        The command line stamped in the index.

    Returns
    -------
    list of str
        Names of the sections rebuilt.

    Raises
    ------
    ValueError
        If ``only`` names an unknown section.
    """
    from tqdm import tqdm

    configure_matplotlib()
    out = Path(out)
    modules = discover()
    names = [m.SECTION.name for m in modules]
    selected = list(names) if not only else list(only)
    unknown = [n for n in selected if n not in names]
    if unknown:
        raise ValueError(f"Expected `only` among {', '.join(names)}, got {', '.join(unknown)}")
    out.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    try:
        if out.exists() and only:
            shutil.copytree(out, stage, dirs_exist_ok=True)
        ctx = Context(out_dir=stage, quick=quick, show_progress=show_progress)
        ctx.command = command
        ctx.sections = modules
        todo = [m for m in modules if m.SECTION.name in selected]
        bar = tqdm(todo, desc="report", file=sys.stderr, disable=not show_progress)
        for module in bar:
            bar.set_description(f"report: {module.SECTION.name}")
            with reproducible():  # SymPy's random choices fixed: same path and time every run
                module.build(ctx)
        bar.close()
        _swap(stage, out)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    return [m.SECTION.name for m in todo]


def _swap(stage: Path, out: Path) -> None:
    """Move ``stage`` to ``out``, keeping the old tree until the move succeeded."""
    os.chmod(stage, 0o755)
    if not out.exists():
        os.replace(stage, out)
        return
    backup = Path(tempfile.mkdtemp(prefix=f".{out.name}-old-", dir=out.parent))
    os.rmdir(backup)
    os.replace(out, backup)
    try:
        os.replace(stage, out)
    except BaseException:
        os.replace(backup, out)
        raise
    shutil.rmtree(backup, ignore_errors=True)
