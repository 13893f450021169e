"""Progress on stderr: tqdm bars on a terminal, plain lines in a log, nothing when asked to be quiet.

Long work shows its progress on stderr in one of three ways, chosen once, at
the edge (:func:`mode`), and never by library code:

``"bar"``
    stderr is a terminal: tqdm bars that redraw in place (:func:`bar`), and
    for work without a natural count the elapsed time (:func:`activity`);
``"lines"``
    stderr is a file, a pipe or a notebook: plain lines, no carriage returns
    or escapes, each saying what runs, the fraction done and the time elapsed,
    the first after a few seconds and then at least every ten
    (:func:`lines`), so that a long run in a CI log never looks like a hang;
``"off"``
    ``--quiet``: nothing.

Library functions take a plain ``progress: bool`` and wrap their loops in
:func:`bar`.  Inside a :func:`lines` block the bars draw nothing themselves:
they report their position to the block, whose timer thread writes the lines
(nested bars, such as the chunks of a Monte Carlo inside a report section,
refine the fraction).  The block is scoped to the command that opened it (a
context variable), like a logging handler, so that library code never looks
at the terminal.

Public API: :func:`mode`, :func:`wanted`, :func:`bar`, :func:`activity`,
:func:`lines`, :data:`MODES`, :data:`LINE_INTERVAL`.
"""

from __future__ import annotations

import contextvars
import os
import sys
import threading
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager

__all__ = ["MODES", "LINE_INTERVAL", "mode", "wanted", "bar", "activity", "lines"]

#: The ways of showing progress (module docstring).
MODES = ("bar", "lines", "off")
#: Seconds between two progress lines, and before the first (``STRAPDOWN_PROGRESS_INTERVAL`` overrides it).
LINE_INTERVAL = 5.0

_active: contextvars.ContextVar = contextvars.ContextVar("strapdown_progress_lines", default=None)


def mode(quiet: bool = False, stream=None) -> str:
    """How to show progress: ``"off"`` when ``quiet``, ``"bar"`` on a terminal, ``"lines"`` otherwise.

    Parameters
    ----------
    quiet : bool
        ``--quiet`` was given.
    stream : file, optional
        The stream progress goes to (default ``sys.stderr``).

    Returns
    -------
    str
        One of :data:`MODES`.

    Examples
    --------
    >>> import io
    >>> mode(False, io.StringIO()), mode(True, io.StringIO())
    ('lines', 'off')
    """
    if quiet:
        return "off"
    return "bar" if wanted(None, stream) else "lines"


def wanted(requested: bool | None = None, stream=None) -> bool:
    """Whether to draw progress bars: ``requested`` if given, else whether ``stream`` is a terminal.

    Parameters
    ----------
    requested : bool or None
        An explicit choice; None decides by the terminal.
    stream : file, optional
        The stream the bar would write to (default ``sys.stderr``).

    Returns
    -------
    bool

    Examples
    --------
    >>> import io
    >>> wanted(None, io.StringIO()), wanted(True, io.StringIO())
    (False, True)
    """
    if requested is not None:
        return bool(requested)
    stream = sys.stderr if stream is None else stream
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):  # closed or not a file
        return False


class _Task:
    """A counted piece of work reported to a :func:`lines` block (the subset of tqdm's interface the package uses)."""

    def __init__(self, block, iterable, desc: str, total, expected=None):
        self._block, self._iterable = block, iterable
        self.desc, self.n = desc, 0
        if total is None and iterable is not None:
            try:
                total = len(iterable)
            except TypeError:
                total = None
        self.total = total
        # expected seconds of each iteration (an earlier run's), or None: every iteration counts alike
        self.expected = None
        if expected is not None and total and len(expected) == total and all(e >= 0 for e in expected) and sum(expected) > 0:
            self.expected = [float(e) for e in expected]
        self.since = block.clock()  # when the current iteration started
        self._open = True
        block.push(self)

    def __iter__(self):
        try:
            for item in self._iterable:
                self.since = self._block.clock()
                yield item
                self.n += 1
        finally:
            self.close()

    def update(self, n: float = 1) -> None:
        self.n += n
        self.since = self._block.clock()

    def set_description(self, desc: str, refresh: bool = True) -> None:
        self.desc = desc

    def close(self) -> None:
        if self._open:
            self._open = False
            self._block.pop(self)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class _Lines:
    """The state of a :func:`lines` block: the open tasks, innermost last, and the timer thread."""

    def __init__(self, label: str, stream, interval: float, clock=time.monotonic):
        self.label, self.stream, self.interval, self.clock = label, stream, interval, clock
        self.start = clock()
        self.shown = 0.0  # the largest fraction written so far: the next is never smaller
        self.tasks: list = []
        self._lock = threading.Lock()
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._run, name="strapdown-progress-lines", daemon=True)

    def push(self, task: _Task) -> None:
        with self._lock:
            self.tasks.append(task)

    def pop(self, task: _Task) -> None:
        with self._lock:
            if task in self.tasks:
                self.tasks.remove(task)

    def fraction(self) -> float | None:
        """The fraction done, from the open counted tasks (None while none is counted); see :func:`lines`."""
        now = self.clock()
        with self._lock:
            tasks = [(t.n, t.total, t.expected, t.since) for t in self.tasks]
        fraction, scale, known, budget, since = 0.0, 1.0, False, None, now
        for n, total, expected, started in tasks:  # nested counts: the inner ones refine the current step of the outer
            if not total:
                break
            done = min(max(int(n), 0), int(total))
            if expected is None:
                fraction += scale * min(max(n, 0) / total, 1.0)
                scale /= total
                budget = None
            else:
                whole = sum(expected)
                fraction += scale * sum(expected[:done]) / whole
                current = expected[done] if done < len(expected) else 0.0
                scale *= current / whole
                budget, since = current, started
            known = True
        if not known:
            return None
        if budget:  # the current iteration reports nothing finer: let it advance with its expected time, to 90 %
            fraction += scale * min((now - since) / budget, 0.9)
        return fraction

    def text(self) -> str:
        """One line: what runs, the fraction done (when the work is counted) and the time elapsed.

        The fraction never decreases from one line to the next (an inner task
        that starts afresh does not take back what the line said).
        """
        fraction = self.fraction()
        with self._lock:
            tasks = [(t.desc, t.n, t.total) for t in self.tasks]
            if fraction is not None:
                fraction = self.shown = min(max(fraction, self.shown), 1.0)
        steps = "; ".join(f"{d} {n:.0f}/{total:.0f}" if total else f"{d} {n:.0f}" for d, n, total in tasks if d)
        parts = [f"{100.0 * fraction:.0f}% done" if fraction is not None else None, steps or None, f"{self.clock() - self.start:.0f} s elapsed"]
        return f"{self.label}: " + ", ".join(p for p in parts if p)

    def _run(self) -> None:
        while not self._done.wait(self.interval):
            try:
                self.stream.write(self.text() + "\n")
                self.stream.flush()
            except (OSError, ValueError):  # the log went away: stop reporting, not the work
                return

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._done.set()
        self._thread.join()
        return False


def _interval(interval) -> float:
    if interval is not None:
        return float(interval)
    try:
        value = float(os.environ.get("STRAPDOWN_PROGRESS_INTERVAL", LINE_INTERVAL))
    except ValueError:
        return LINE_INTERVAL
    return value if value > 0 else LINE_INTERVAL


@contextmanager
def lines(label: str, *, stream=None, interval: float | None = None) -> Iterator[None]:
    """Write a plain progress line every ``interval`` seconds while the block runs.

    The first line comes after ``interval`` seconds (work shorter than that
    writes nothing), the next every ``interval`` seconds after, until the
    block ends.  Each line is ``<label>: <fraction>% done, <task> <n>/<total>;
    <inner task> <n>/<total>, <seconds> s elapsed``, from the :func:`bar`
    tasks open at that instant (the fraction is left out while no task has a
    count).  Nested counts refine the current step of the task around them;
    a task with ``expected`` seconds per step weights its steps by them.  The
    fraction never goes backwards: a line repeats the largest fraction shown
    so far rather than a smaller one (as when an inner task starts afresh).

    Parameters
    ----------
    label : str
        What runs (e.g. ``"strapdown report"``).
    stream : file, optional, keyword-only
        Where the lines go (default ``sys.stderr``).
    interval : float, optional, keyword-only
        Seconds between lines [s] (default :data:`LINE_INTERVAL`, or
        ``STRAPDOWN_PROGRESS_INTERVAL`` from the environment).

    Yields
    ------
    None

    Examples
    --------
    >>> import io, time
    >>> log = io.StringIO()
    >>> with lines("demo", stream=log, interval=0.05):
    ...     for _ in bar(range(2), desc="step", enabled=True):
    ...         time.sleep(0.12)
    >>> log.getvalue().splitlines()[0].startswith("demo: ")
    True
    """
    block = _Lines(label, sys.stderr if stream is None else stream, _interval(interval))
    token = _active.set(block)
    try:
        with block:
            yield
    finally:
        _active.reset(token)


def bar(iterable: Iterable | None = None, *, desc: str, total: float | None = None, enabled: bool = False, unit: str = "it", leave: bool = False, expected=None):
    """A progress bar on stderr: tqdm on a terminal, a counted task inside :func:`lines`, else silent.

    Parameters
    ----------
    iterable : iterable, optional
        What to iterate over; omit it and call ``update(n)`` on the bar instead.
    desc : str, keyword-only
        Label in front of the bar.
    total : float, optional, keyword-only
        Expected number of iterations [count] (default ``len(iterable)`` when it has one).
    enabled : bool, keyword-only
        Show progress at all (the edge decides with :func:`mode`).
    unit : str, keyword-only
        Name of one iteration.
    leave : bool, keyword-only
        Keep the finished bar on screen.
    expected : sequence of float, keyword-only, optional
        Expected seconds of each iteration (for example an earlier run's), one
        per iteration [s].  Inside :func:`lines` they weight the fraction done,
        and an iteration that reports nothing finer advances with its expected
        time (to 90 % of its share); ignored when their number is not ``total``.

    Returns
    -------
    tqdm.tqdm or a task of the enclosing :func:`lines` block
        Iterable, usable as a context manager, with ``update``, ``set_description`` and ``close``.
    """
    block = _active.get() if enabled else None
    if block is not None:
        return _Task(block, iterable, desc, total, expected)
    from tqdm import tqdm

    return tqdm(iterable, desc=desc, total=total, unit=unit, file=sys.stderr, leave=leave, disable=not enabled, dynamic_ncols=True)


@contextmanager
def activity(desc: str, *, enabled: bool = False, delay: float = 2.0, interval: float = 0.5) -> Iterator[None]:
    """Show ``desc`` and the elapsed time on stderr (a terminal) while the block runs longer than ``delay``.

    Parameters
    ----------
    desc : str
        What is running (e.g. the command name).
    enabled : bool, keyword-only
        Show anything at all (decide with :func:`mode`: ``"bar"``).
    delay : float, keyword-only
        Seconds before the line appears [s]; short work shows nothing.
    interval : float, keyword-only
        Refresh period of the elapsed time [s].

    Yields
    ------
    None
    """
    if not enabled:
        yield
        return
    from tqdm import tqdm

    line = tqdm(total=None, desc=desc, file=sys.stderr, leave=False, delay=delay, bar_format="{desc}: {elapsed} elapsed", dynamic_ncols=True)
    done = threading.Event()

    def tick():
        while not done.wait(interval):
            line.update(0)  # redraws the elapsed time once ``delay`` has passed

    thread = threading.Thread(target=tick, name="strapdown-activity", daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        thread.join()
        line.close()
