"""Typed access to the tables of a profile or mount file, with messages naming the file, the table and the key.

Used by :mod:`strapdown.analysis.vibration.profile` and
:mod:`strapdown.analysis.vibration.mount`; the files themselves are read by
:func:`strapdown.derivations.toml_files.read_toml` (size, encoding, nesting).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

#: Longest string of a file [characters].
TEXT_LIMIT = 1000


def show(value, width: int = 40) -> str:
    """``repr(value)`` cut to ``width`` characters.

    Parameters
    ----------
    value : object
        What to show.
    width : int
        Most characters [count].

    Returns
    -------
    str
    """
    text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


def _is_number(x) -> bool:
    return not isinstance(x, bool) and isinstance(x, (int, float)) and math.isfinite(float(x))


class Table:
    """One table of a file: checks its keys on creation, then reads typed values.

    Parameters
    ----------
    path : Path
        The file (for the messages).
    where : str
        The table, as the messages name it (``"[[isolator]] #2"``).
    table : dict
        Its contents.
    allowed : set of str
        Its keys.

    Raises
    ------
    ValueError
        A table that is not a table, or an unknown key.
    """

    def __init__(self, path: Path, where: str, table, allowed: set):
        self.path, self.where, self.table = path, where, table
        if not isinstance(table, dict):
            raise ValueError(f"{path}: {where} must be a table, got {type(table).__name__}")
        extra = sorted(set(table) - allowed)
        if extra:
            raise ValueError(f"{path}: {where} unknown key {show(extra[0])} (expected one of {', '.join(sorted(allowed))})")

    def fail(self, key: str, expected: str, got) -> ValueError:
        """The error of a bad value.

        Parameters
        ----------
        key : str
            The key.
        expected : str
            What it should hold.
        got : object
            What it holds.

        Returns
        -------
        ValueError
        """
        return ValueError(f"{self.path}: {self.where} key {key!r}: expected {expected}, got {show(got)}")

    def has(self, key: str) -> bool:
        """Whether ``key`` is present.

        Parameters
        ----------
        key : str
            The key.

        Returns
        -------
        bool
        """
        return key in self.table

    def number(self, key: str, default=None, *, low=None, open_low=False, required=False) -> float:
        """A finite number, at least (or above, ``open_low``) ``low``.

        Parameters
        ----------
        key : str
            The key.
        default : float, optional
            Value when absent.
        low : float, keyword-only, optional
            Lowest value.
        open_low : bool, keyword-only
            ``low`` itself is refused.
        required : bool, keyword-only
            Absence is an error.

        Returns
        -------
        float or None
        """
        if key not in self.table:
            if required:
                raise ValueError(f"{self.path}: {self.where} missing key {key!r}")
            return default
        v = self.table[key]
        if not _is_number(v):
            raise self.fail(key, "a finite number", v)
        v = float(v)
        if low is not None and (v < low or (open_low and v == low)):
            raise self.fail(key, f"a number {'>' if open_low else '≥'} {low:g}", v)
        return v

    def text(self, key: str, default: str = "") -> str:
        """A string of at most :data:`TEXT_LIMIT` characters.

        Parameters
        ----------
        key : str
            The key.
        default : str
            Value when absent.

        Returns
        -------
        str
        """
        if key not in self.table:
            return default
        v = self.table[key]
        if not isinstance(v, str) or len(v) > TEXT_LIMIT:
            raise self.fail(key, f"a string of at most {TEXT_LIMIT} characters", v)
        return v

    def choice(self, key: str, choices, default=None) -> str:
        """One of ``choices`` (required when ``default`` is None).

        Parameters
        ----------
        key : str
            The key.
        choices : sequence of str
            The values allowed.
        default : str, optional
            Value when absent.

        Returns
        -------
        str
        """
        if key not in self.table:
            if default is None:
                raise ValueError(f"{self.path}: {self.where} missing key {key!r} (one of {', '.join(repr(c) for c in choices)})")
            return default
        v = self.table[key]
        if v not in choices:
            raise self.fail(key, f"one of {', '.join(repr(c) for c in choices)}", v)
        return v

    def vector(self, key: str, default=None, *, low=None, required=False) -> np.ndarray:
        """Three finite numbers (each at least ``low``).

        Parameters
        ----------
        key : str
            The key.
        default : sequence of float, optional
            Value when absent.
        low : float, keyword-only, optional
            Lowest value of each.
        required : bool, keyword-only
            Absence is an error.

        Returns
        -------
        ndarray (3,) or None
        """
        if key not in self.table:
            if required:
                raise ValueError(f"{self.path}: {self.where} missing key {key!r}")
            return None if default is None else np.asarray(default, dtype=float)
        v = self.table[key]
        if not isinstance(v, list) or len(v) != 3 or not all(_is_number(x) for x in v):
            raise self.fail(key, "a list of three finite numbers", v)
        arr = np.asarray(v, dtype=float)
        if low is not None and np.any(arr < low):
            raise self.fail(key, f"three numbers, each ≥ {low:g}", v)
        return arr

    def matrix(self, key: str, *, required=False) -> np.ndarray:
        """A 3×3 matrix given as three rows of three finite numbers.

        Parameters
        ----------
        key : str
            The key.
        required : bool, keyword-only
            Absence is an error.

        Returns
        -------
        ndarray (3, 3) or None
        """
        if key not in self.table:
            if required:
                raise ValueError(f"{self.path}: {self.where} missing key {key!r}")
            return None
        v = self.table[key]
        if not isinstance(v, list) or len(v) != 3 or not all(isinstance(r, list) and len(r) == 3 and all(_is_number(x) for x in r) for r in v):
            raise self.fail(key, "three rows of three finite numbers", v)
        return np.asarray(v, dtype=float)

    def tables(self, key: str, *, limit: int) -> list:
        """An array of tables (``[[key]]`` or a list of inline tables), at most ``limit`` of them.

        Parameters
        ----------
        key : str
            The key.
        limit : int, keyword-only
            Most tables [count].

        Returns
        -------
        list of dict
        """
        v = self.table.get(key, [])
        if not isinstance(v, list) or not all(isinstance(t, dict) for t in v):
            raise self.fail(key, "an array of tables", v)
        if len(v) > limit:
            raise ValueError(f"{self.path}: {self.where} key {key!r}: more than the limit of {limit} entries")
        return v
