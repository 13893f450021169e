"""Files written whole or not at all.

A file the package writes for a user (an environment file, a sensor file, a
figure) is first written to a temporary file in the same directory, checked,
and only then renamed over the target (``os.replace``, atomic on POSIX and
Windows); an error or an interruption removes the temporary file and leaves
the target as it was.

Public API
----------
.. autosummary::

   replaced_atomically
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["replaced_atomically"]


@contextmanager
def replaced_atomically(path) -> Iterator[Path]:
    """A temporary path beside ``path`` that replaces it when the block ends without an error.

    Parameters
    ----------
    path : str or Path
        The file to write.

    Yields
    ------
    Path
        The temporary file (empty, closed): write it, check it; it is renamed
        to ``path`` after the block, or removed if the block raises.

    Raises
    ------
    IsADirectoryError
        If ``path`` is a directory.
    OSError
        If the directory cannot be written.

    Examples
    --------
    >>> import tempfile
    >>> target = Path(tempfile.mkdtemp()) / "out.txt"
    >>> with replaced_atomically(target) as tmp:
    ...     _ = tmp.write_text("done")
    >>> target.read_text()
    'done'
    """
    p = Path(path)
    if p.is_dir():
        raise IsADirectoryError(21, "Is a directory", str(p))
    fd, name = tempfile.mkstemp(prefix=f".{p.name}.", suffix=p.suffix, dir=p.parent if str(p.parent) else ".")
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        os.replace(tmp, p)
    except BaseException:
        if tmp.exists():
            tmp.unlink()
        raise
