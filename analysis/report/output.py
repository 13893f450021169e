"""Safe replacement of a report directory: manifest, lock, staging and atomic exchange.

``strapdown report --out DIR`` must never lose a user's data and never leave a
half-written report.  The rules:

Ownership
    DIR is replaced only if it is new, empty, or holds nothing but the files
    that an earlier run wrote.  Each run leaves a manifest, :data:`MANIFEST`
    (JSON: the files of each section and the SHA-256 of every file), in DIR.  Any other file or directory in
    DIR, a regular file given as DIR, or an unreadable manifest is refused
    with :class:`OutputError` before any work starts.  A directory written
    before manifests existed (its ``README.md`` starts with the report
    signature :data:`LEGACY_SIGNATURE`) is accepted by a full run if every file
    in it is one the new run writes; that is checked once the new report is
    complete, before anything is replaced.  A partial run (``--only``) on it is
    refused: without a manifest it cannot tell the report's files from a user's.
Nothing lost
    A generated file whose content no longer has the hash the manifest
    recorded has been edited since: a run that would replace it refuses
    (:class:`ModifiedFilesError`, naming the files) before any work, and the
    edit stays as it is, unless the caller allows the overwrite
    (``overwrite_modified``).  A file of a section a partial run keeps is
    carried over with its edit and its recorded hash, so it stays marked.
Staging
    The new report is written into a staging directory next to DIR
    (``.DIR.strapdown-stage-*``, same file system), never into DIR itself.
Atomic exchange
    When the report is complete, the staging directory and DIR swap places in
    one system call (``renameat2(RENAME_EXCHANGE)`` on Linux): a reader finds
    either the complete previous report or the complete new one, and DIR is
    never missing.  Where the exchange is not available (other systems, some
    network file systems) two renames are used, DIR → ``.DIR.strapdown-old-*``
    and staging → DIR; a crash between them leaves DIR missing until the next
    run, which restores the previous report first.
Clean-up
    Left-over staging and old directories of DIR (a killed run leaves them)
    are removed at the start of the next run, under the lock.
Lock
    ``.DIR.strapdown-lock`` next to DIR is held with ``flock`` for the whole
    run; a second run on the same DIR exits at once with :class:`OutputError`
    naming the lock.  The kernel drops the lock of a killed process, and the
    lock file is removed when the run ends.

Fault injection (tests only)
----------------------------
``STRAPDOWN_REPORT_FAULT=<point>`` in the environment kills the process with
SIGKILL when the writer reaches ``<point>`` (:data:`FAULT_POINTS`), so that a
test can check what a crash at that instant leaves behind, without timing
races.  ``STRAPDOWN_REPORT_SWAP=rename`` forces the two-rename fallback.
Neither has any effect when unset.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import json
import os
import shutil
import signal
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

__all__ = [
    "MANIFEST",
    "LEGACY_SIGNATURE",
    "FAULT_POINTS",
    "OutputError",
    "ModifiedFilesError",
    "Manifest",
    "file_digest",
    "modified_files",
    "refuse_modified",
    "Destination",
    "prepare",
    "check_legacy",
    "lock",
    "clean",
    "stage",
    "commit",
    "fault",
]

#: Manifest file name inside a report directory.
MANIFEST = ".strapdown-report.json"
#: First line of the index page of every report (how pre-manifest report directories are recognised).
LEGACY_SIGNATURE = "# strapdown-analysis reports"
#: Instants at which ``STRAPDOWN_REPORT_FAULT`` can kill the writer, in the order they occur.
FAULT_POINTS = ("staged", "section", "complete", "before-swap", "between-renames", "swapped", "cleaning")

_STAGE = "strapdown-stage-"
_OLD = "strapdown-old-"
_LOCK = "strapdown-lock"
_FORMAT = 2
#: Manifest formats this version reads (1: no hashes, written before files were hashed).
_READABLE = (1, 2)


class OutputError(ValueError):
    """An output directory that must not be replaced, or cannot be written (a ``ValueError``)."""


class ModifiedFilesError(OutputError):
    """Generated files changed since they were written, which a run would replace (an :class:`OutputError`).

    Parameters
    ----------
    directory : Path
        The report directory.
    files : list of str
        The changed files, relative POSIX paths.
    """

    def __init__(self, directory, files):
        self.directory = Path(directory)
        self.files = list(files)
        shown = ", ".join(self.files[:5]) + (f" and {len(self.files) - 5} more" if len(self.files) > 5 else "")
        super().__init__(
            f"Expected `out` to hold the generated files as an earlier `strapdown report` wrote them, got {len(self.files)} changed since "
            f"in {str(self.directory)!r}: {shown}; they are left untouched: move them away, or pass `overwrite_modified=True` to replace them"
        )


def file_digest(path) -> str:
    """SHA-256 of a file's bytes, as hex.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    str
    """
    import hashlib

    with open(path, "rb") as handle:
        return hashlib.file_digest(handle, "sha256").hexdigest()


def fault(point: str) -> None:
    """Kill this process with SIGKILL if ``STRAPDOWN_REPORT_FAULT`` names ``point`` (tests only).

    Parameters
    ----------
    point : str
        One of :data:`FAULT_POINTS`.
    """
    if point not in FAULT_POINTS:
        raise ValueError(f"Expected `point` in {FAULT_POINTS}, got {point!r}")
    if os.environ.get("STRAPDOWN_REPORT_FAULT") == point:
        sys.stdout.flush()
        sys.stderr.flush()
        os.kill(os.getpid(), signal.SIGKILL)


# --------------------------------------------------------------------------- manifest
@dataclass(frozen=True)
class Manifest:
    """What a run wrote: the files of each section, relative to the report directory.

    Attributes
    ----------
    sections : dict
        Section name → sorted tuple of POSIX relative paths.
    matplotlib : str
        Version of matplotlib that rendered the figures (byte equality of figures needs the same one).
    hashes : dict
        Relative path → SHA-256 (hex) of the file as the run wrote it (empty for a
        manifest written before hashes were recorded).
    """

    sections: dict = field(default_factory=dict)
    matplotlib: str = ""
    hashes: dict = field(default_factory=dict)

    @property
    def files(self) -> set:
        """Every file of every section."""
        return {f for files in self.sections.values() for f in files}

    def to_json(self) -> str:
        """The manifest as deterministic JSON text (sorted keys, one trailing newline)."""
        body = {
            "format": _FORMAT,
            "generator": "strapdown report",
            "matplotlib": self.matplotlib,
            "sections": {k: sorted(v) for k, v in sorted(self.sections.items())},
            "sha256": dict(sorted(self.hashes.items())),
        }
        return json.dumps(body, indent=1, sort_keys=True, ensure_ascii=False) + "\n"

    @classmethod
    def read(cls, directory: Path) -> Manifest | None:
        """The manifest of ``directory``, or None if it has none.

        Parameters
        ----------
        directory : Path
            A report directory.

        Returns
        -------
        Manifest or None

        Raises
        ------
        OutputError
            If the manifest exists but is not one this package wrote.
        """
        path = Path(directory) / MANIFEST
        if not path.is_file():
            if path.exists() or path.is_symlink():
                raise OutputError(f"Expected `out` to hold a report manifest file {MANIFEST}, got something else at {path}")
            return None
        try:
            body = json.loads(path.read_text(encoding="utf-8"))
            sections = {str(k): tuple(_relpath(f) for f in v) for k, v in body["sections"].items()}
            if body.get("format") not in _READABLE:
                raise ValueError(f"format {body.get('format')!r}")
            hashes = {_relpath(k): str(v) for k, v in body.get("sha256", {}).items()}
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
            raise OutputError(f"Expected `out` to hold a readable report manifest, got an unreadable {path} ({_first_line(exc)}); move it away or choose another directory") from None
        return cls(sections, str(body.get("matplotlib", "")), hashes)


def _relpath(text) -> str:
    text = str(text)
    parts = text.split("/")
    if not text or text.startswith("/") or any(p in ("", ".", "..") for p in parts):
        raise ValueError(f"bad path {text!r}")
    return text


def _first_line(exc) -> str:
    return (str(exc).strip().splitlines() or [type(exc).__name__])[0]


# --------------------------------------------------------------------------- destination
@dataclass(frozen=True)
class Destination:
    """A checked output directory.

    Attributes
    ----------
    path : Path
        The report directory (absolute, symbolic links resolved).
    previous : Manifest or None
        Its manifest (None when it is new, empty or a pre-manifest report).
    legacy : bool
        It is a pre-manifest report: its files are checked against the new run before the swap.
    present : frozenset
        Files found in it (relative POSIX paths).
    """

    path: Path
    previous: Manifest | None
    legacy: bool
    present: frozenset

    @property
    def parent(self) -> Path:
        """Directory holding the report directory, its staging directories and its lock."""
        return self.path.parent

    def sibling(self, kind: str) -> str:
        """Name prefix of the entries next to the report directory.

        Parameters
        ----------
        kind : {"stage", "old", "lock"}
            Staging directories, previous reports being removed, or the lock file.

        Returns
        -------
        str
            For example ``".reports.strapdown-stage-"``.
        """
        return f".{self.path.name}." + {"stage": _STAGE, "old": _OLD, "lock": _LOCK}[kind]


def _listing(root: Path) -> tuple[set, set]:
    """Files and directories under ``root`` (relative POSIX paths); symbolic links count as files."""
    files, dirs = set(), set()
    for dirpath, dirnames, filenames in os.walk(root, onerror=_raise):
        rel = Path(dirpath).relative_to(root)
        for d in list(dirnames):
            p = Path(dirpath) / d
            if p.is_symlink():
                dirnames.remove(d)
                files.add((rel / d).as_posix())
            else:
                dirs.add((rel / d).as_posix())
        files.update((rel / f).as_posix() for f in filenames)
    return files, dirs


def _raise(exc):
    raise exc


def prepare(out) -> Destination:
    """Check that ``out`` may receive a report; nothing is written.

    Parameters
    ----------
    out : str or Path
        The output directory (created later if missing; its parents are created).

    Returns
    -------
    Destination

    Raises
    ------
    OutputError
        ``out`` is a regular file (or anything but a directory), a file-system
        root, holds files that no earlier run wrote, or cannot be read.
    """
    if not str(out).strip():
        raise OutputError(f"Expected `out` to name a directory, got an empty name {str(out)!r}")
    raw = Path(out)
    path = Path(os.path.abspath(raw))
    if path.is_symlink():
        path = path.resolve()
    if path.parent == path:
        raise OutputError(f"Expected `out` to be a directory below a file-system root, got {str(raw)!r}")
    if path.exists() and not path.is_dir():
        kind = "regular file" if path.is_file() else "special file"
        raise OutputError(f"Expected `out` to be a directory, got the {kind} {str(raw)!r} (it is left untouched)")
    if not path.exists():
        if path.is_symlink():
            raise OutputError(f"Expected `out` to be a directory, got a dangling symbolic link {str(raw)!r}")
        return Destination(path, None, False, frozenset())
    try:
        files, dirs = _listing(path)
        previous = Manifest.read(path)
    except OutputError:
        raise
    except OSError as exc:
        raise OutputError(f"Expected `out` to be a readable directory, got {str(raw)!r} ({exc.strerror or _first_line(exc)})") from None
    files.discard(MANIFEST)
    legacy = False
    if previous is not None:
        ours = previous.files
        foreign = sorted(f for f in files if f not in ours)
        foreign += sorted(d for d in dirs if not any(f.startswith(d + "/") for f in ours))
    elif files or dirs:
        legacy = _is_legacy(path)
        foreign = [] if legacy else sorted(files) + sorted(d for d in dirs if not any(f.startswith(d + "/") for f in files))
    else:
        foreign = []
    if foreign:
        raise OutputError(_foreign_message(raw, foreign, previous is not None))
    return Destination(path, previous, legacy, frozenset(files))


def _is_legacy(path: Path) -> bool:
    readme = path / "README.md"
    try:
        with open(readme, encoding="utf-8") as f:
            return f.readline().rstrip("\n") == LEGACY_SIGNATURE
    except (OSError, UnicodeDecodeError):
        return False


def _foreign_message(raw, foreign: list, has_manifest: bool) -> str:
    shown = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
    why = "that no earlier `strapdown report` wrote" if has_manifest else "and no report manifest"
    return f"Expected `out` to be a new or empty directory or an earlier report, got {str(raw)!r} holding files {why} ({shown}); they are left untouched: choose another directory or move them away"


def modified_files(dest: Destination, sections=None) -> list:
    """Generated files of ``dest`` changed since the run that wrote them (their hash differs).

    Parameters
    ----------
    dest : Destination
        The destination.
    sections : iterable of str, optional
        Only the files of these sections (default: every section).

    Returns
    -------
    list of str
        Relative POSIX paths, sorted.  A missing file is not a change (the new
        run restores it), and a manifest without hashes has none to compare.
    """
    if dest.previous is None or not dest.previous.hashes:
        return []
    keep = None if sections is None else set(sections)
    files = {f for name, fs in dest.previous.sections.items() if keep is None or name in keep for f in fs}
    out = []
    for rel in sorted(files):
        recorded = dest.previous.hashes.get(rel)
        path = dest.path.joinpath(*rel.split("/"))
        if recorded is None or not path.is_file():
            continue
        try:
            if file_digest(path) != recorded:
                out.append(rel)
        except OSError:
            out.append(rel)  # unreadable now: it is not what the run wrote
    return out


def refuse_modified(dest: Destination, sections=None, *, overwrite_modified: bool = False) -> None:
    """Raise :class:`ModifiedFilesError` if a run would replace generated files changed since they were written.

    Parameters
    ----------
    dest : Destination
        The destination.
    sections : iterable of str, optional
        The sections the run rebuilds (default: all of them).
    overwrite_modified : bool, keyword-only
        Allow the run to replace them.

    Raises
    ------
    ModifiedFilesError
        Naming the changed files.
    """
    if overwrite_modified:
        return
    changed = modified_files(dest, sections)
    if changed:
        raise ModifiedFilesError(dest.path, changed)


def check_legacy(dest: Destination, written: set) -> None:
    """Refuse to replace a pre-manifest report that holds files the new run does not write.

    Parameters
    ----------
    dest : Destination
        The destination (only checked when ``dest.legacy``).
    written : set
        Files of the new report (relative POSIX paths).

    Raises
    ------
    OutputError
        If the old directory holds a file the new report does not replace.
    """
    if not dest.legacy:
        return
    foreign = sorted(f for f in dest.present if f not in written)
    if foreign:
        raise OutputError(_foreign_message(dest.path, foreign, False) + " (the new report was not installed)")


# --------------------------------------------------------------------------- lock
@contextlib.contextmanager
def lock(dest: Destination):
    """Hold the lock of ``dest`` for the duration of the block.

    Parameters
    ----------
    dest : Destination
        The destination to lock.

    Yields
    ------
    Path
        The lock file.

    Raises
    ------
    OutputError
        If another run holds the lock, or the lock cannot be created (a read-only directory).
    """
    try:
        dest.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"Expected `out` in a directory that can be created, got {str(dest.path)!r} ({exc.strerror or _first_line(exc)})") from None
    path = dest.parent / dest.sibling("lock")
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX: exclusive creation instead of flock
        fcntl = None
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | (os.O_EXCL if fcntl is None else 0), 0o644)
        except FileExistsError:  # pragma: no cover - not POSIX
            raise OutputError(f"Expected `out` free, got another `strapdown report` writing {str(dest.path)!r} (its lock {str(path)!r}; remove it if no run is active)") from None
        except OSError as exc:
            raise OutputError(f"Expected a writable directory for `out`, got {str(dest.parent)!r} ({exc.strerror})") from None
        if fcntl is None:  # pragma: no cover
            break
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise OutputError(f"Expected `out` free, got another `strapdown report` writing {str(dest.path)!r} (it holds {str(path)!r}); wait for it to finish") from None
        # The file may have been removed by the run that held it just before: lock the current one.
        try:
            same = os.path.samestat(os.fstat(fd), os.stat(path))
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)
    try:
        os.write(fd, f"{os.getpid()}\n".encode())
        yield path
    finally:
        with contextlib.suppress(OSError):
            os.unlink(path)
        os.close(fd)


# --------------------------------------------------------------------------- staging and swap
def clean(dest: Destination) -> None:
    """Remove what killed runs left next to ``dest``; restore it if a crash left it missing.

    Call with the lock held.

    Parameters
    ----------
    dest : Destination
        The destination.
    """
    parent = dest.parent
    if not parent.is_dir():
        return
    stages, olds = [], []
    for entry in parent.iterdir():
        if entry.is_dir() and not entry.is_symlink():
            if entry.name.startswith(dest.sibling("stage")):
                stages.append(entry)
            elif entry.name.startswith(dest.sibling("old")):
                olds.append(entry)
    if olds and not dest.path.exists():
        newest = max(olds, key=lambda p: p.stat().st_mtime_ns)
        os.rename(newest, dest.path)  # a crash between the two renames of the fallback
        olds.remove(newest)
    for entry in stages + olds:
        shutil.rmtree(entry, ignore_errors=True)


def stage(dest: Destination) -> Path:
    """Create an empty staging directory for ``dest`` (same file system, default permissions).

    Parameters
    ----------
    dest : Destination
        The destination.

    Returns
    -------
    Path
        The staging directory.
    """
    path = Path(tempfile.mkdtemp(prefix=dest.sibling("stage"), dir=dest.parent))
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(path, 0o777 & ~umask)
    return path


_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


def _exchange(a: Path, b: Path) -> bool:
    """Swap ``a`` and ``b`` atomically; False if the system or file system cannot."""
    if os.environ.get("STRAPDOWN_REPORT_SWAP") == "rename" or not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    if renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), str(b))


def commit(dest: Destination, staged: Path) -> None:
    """Put the complete report ``staged`` in place of ``dest`` and remove the previous one.

    Parameters
    ----------
    dest : Destination
        The destination (locked).
    staged : Path
        The complete staging directory.
    """
    _sync(staged)
    fault("before-swap")
    if not dest.path.exists():
        os.rename(staged, dest.path)
        fault("swapped")
        return
    if _exchange(staged, dest.path):
        old = staged  # now holds the previous report
    else:
        old = Path(tempfile.mkdtemp(prefix=dest.sibling("old"), dir=dest.parent))
        os.rmdir(old)
        os.rename(dest.path, old)
        fault("between-renames")
        try:
            os.rename(staged, dest.path)
        except BaseException:
            os.rename(old, dest.path)
            raise
    fault("swapped")
    _remove(old)


def _sync(root: Path) -> None:
    """Flush the files and directories of ``root`` to disk, so the swap never exposes unwritten data."""
    for dirpath, _, filenames in os.walk(root):
        for name in filenames:
            with contextlib.suppress(OSError):
                fd = os.open(os.path.join(dirpath, name), os.O_RDONLY)
                try:
                    os.fsync(fd)
                finally:
                    os.close(fd)
        with contextlib.suppress(OSError):
            fd = os.open(dirpath, os.O_RDONLY)
            try:
                os.fsync(fd)
            finally:
                os.close(fd)


def _remove(path: Path) -> None:
    first = True
    for child in sorted(path.iterdir()) if path.is_dir() else ():
        if child.is_dir() and not child.is_symlink():
            shutil.rmtree(child, ignore_errors=True)
        else:
            with contextlib.suppress(OSError):
                child.unlink()
        if first:
            fault("cleaning")
            first = False
    shutil.rmtree(path, ignore_errors=True)
