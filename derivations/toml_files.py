"""Small TOML files from users, read defensively: a regular UTF-8 file, bounded in size and nesting.

An algorithm file (:mod:`strapdown.derivations.coning.algorithms`) and an
environment file (:mod:`strapdown.analysis.vibration.environment`) are written by
hand or by other tools; before their contents are interpreted, the file itself
must be a regular file of bounded size, UTF-8, valid TOML, and not nested
deeper than the format needs.  Every failure is a ``ValueError`` whose message
starts with the path.

Public API
----------
read_toml
    The parsed contents of a small TOML file.
"""

from __future__ import annotations

import os
import stat
import tomllib
from pathlib import Path

__all__ = ["read_toml"]


def read_toml(path, *, max_bytes: int, max_depth: int, kind: str) -> dict:
    """The parsed contents of the TOML file ``path``, within ``max_bytes`` and ``max_depth``.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    max_bytes : int
        Largest file size accepted [bytes].
    max_depth : int
        Deepest nesting of tables and arrays accepted [levels].
    kind : str
        What the file is, for the messages (e.g. ``"algorithm file"``).

    Returns
    -------
    dict
        The document, as :func:`tomllib.loads` returns it.

    Raises
    ------
    ValueError
        Naming the path: not found, a directory or other non-regular file,
        unreadable, larger than ``max_bytes``, not UTF-8, not valid TOML, or
        nested deeper than ``max_depth``.

    Examples
    --------
    >>> read_toml("no-such-file.toml", max_bytes=1024, max_depth=4, kind="algorithm file")
    Traceback (most recent call last):
    ...
    ValueError: no-such-file.toml: file not found
    """
    path = Path(path)
    try:
        info = os.stat(path)
        if stat.S_ISDIR(info.st_mode):
            raise ValueError(f"{path}: is a directory, expected a TOML {kind}")
        if not stat.S_ISREG(info.st_mode):
            raise ValueError(f"{path}: not a regular file (a device, pipe or socket), expected a TOML {kind}")
        if info.st_size > max_bytes:
            raise ValueError(f"{path}: {info.st_size} bytes, more than the limit of {max_bytes} bytes for an {kind}")
        with open(path, "rb") as f:
            raw = f.read(max_bytes + 1)
    except FileNotFoundError:
        raise ValueError(f"{path}: file not found") from None
    except OSError as exc:
        raise ValueError(f"{path}: cannot be read ({exc.strerror or type(exc).__name__})") from None
    if len(raw) > max_bytes:
        raise ValueError(f"{path}: more than the limit of {max_bytes} bytes for an {kind}")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not UTF-8 text (undecodable byte at offset {exc.start})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML ({str(exc).splitlines()[0] if str(exc) else 'parse error'})") from None
    except RecursionError:
        raise ValueError(f"{path}: nested deeper than the limit of {max_depth} levels") from None
    except ValueError as exc:  # e.g. an integer literal of more than 4300 digits
        raise ValueError(f"{path}: not valid TOML ({str(exc).splitlines()[0] if str(exc) else 'bad value'})") from None
    depth = _depth(data)
    if depth > max_depth:
        raise ValueError(f"{path}: nested {depth} levels deep, more than the limit of {max_depth} ([table] then key = value)")
    return data


def _depth(value, level: int = 0) -> int:
    """Nesting depth of tables and arrays (iterative: a hostile file cannot exhaust the stack)."""
    deepest, stack = level, [(value, level)]
    while stack:
        item, d = stack.pop()
        children = item.values() if isinstance(item, dict) else item if isinstance(item, list) else None
        if children is None:
            continue
        deepest = max(deepest, d)
        stack.extend((child, d + 1) for child in children if isinstance(child, (dict, list)))
    return deepest + 1 if isinstance(value, (dict, list)) and value else deepest
