"""Progress on stderr: tqdm bars, shown only when stderr is a terminal.

Long work shows a progress bar on stderr when a person is watching (stderr is
a terminal) and nothing at all otherwise: a log file or a pipe never receives
carriage returns or ANSI escapes.  Two forms:

:func:`bar`
    a tqdm bar over an iterable or a known total (Monte Carlo chunks, report
    sections);
:func:`activity`
    a context manager for work without a natural count (a vectorised run, a
    symbolic derivation): after ``delay`` seconds it shows the elapsed time,
    refreshed twice a second, and erases itself when the work ends.

Whether to show progress is decided once, at the edge, by :func:`wanted`, and
passed down as a plain ``bool``; library functions never look at the terminal.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Iterable, Iterator
from contextlib import contextmanager

__all__ = ["wanted", "bar", "activity"]


def wanted(requested: bool | None = None, stream=None) -> bool:
    """Whether to show progress: ``requested`` if given, else whether ``stream`` is a terminal.

    Parameters
    ----------
    requested : bool or None
        An explicit choice (``--progress`` / ``--no-progress``); None decides by the terminal.
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


def bar(iterable: Iterable | None = None, *, desc: str, total: float | None = None, enabled: bool = False, unit: str = "it", leave: bool = False):
    """A tqdm progress bar on stderr (a silent pass-through when not ``enabled``).

    Parameters
    ----------
    iterable : iterable, optional
        What to iterate over; omit it and call ``update(n)`` on the bar instead.
    desc : str, keyword-only
        Label in front of the bar.
    total : float, optional, keyword-only
        Expected number of iterations [count] (default ``len(iterable)`` when it has one).
    enabled : bool, keyword-only
        Show the bar (decide with :func:`wanted`).
    unit : str, keyword-only
        Name of one iteration.
    leave : bool, keyword-only
        Keep the finished bar on screen.

    Returns
    -------
    tqdm.tqdm
        Iterable, and usable as a context manager.
    """
    from tqdm import tqdm

    return tqdm(iterable, desc=desc, total=total, unit=unit, file=sys.stderr, leave=leave, disable=not enabled, dynamic_ncols=True)


@contextmanager
def activity(desc: str, *, enabled: bool = False, delay: float = 2.0, interval: float = 0.5) -> Iterator[None]:
    """Show ``desc`` and the elapsed time on stderr while the block runs longer than ``delay``.

    Parameters
    ----------
    desc : str
        What is running (e.g. the command name).
    enabled : bool, keyword-only
        Show anything at all (decide with :func:`wanted`).
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
