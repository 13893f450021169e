"""Validation of user input: one place, messages a user can act on.

Every check raises :class:`ValueError` for a bad value and :class:`TypeError` for
a wrong type, and names the argument, what was expected and what came.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

__all__ = [
    "as_array",
    "as_vector",
    "as_quaternion",
    "as_float",
    "as_int",
    "in_open_interval",
    "positive",
    "nonnegative",
]


def _describe(x) -> str:
    text = repr(x)
    return text if len(text) <= 60 else text[:57] + "..."


def as_float(x, name: str) -> float:
    """Return ``x`` as a finite float, or raise naming ``name``.

    >>> as_float(2, "eps")
    2.0
    """
    if isinstance(x, bool) or not isinstance(x, (numbers.Real, np.floating, np.integer)):
        if isinstance(x, np.ndarray) and x.shape == () and np.issubdtype(x.dtype, np.number):
            x = x.item()
        else:
            raise TypeError(f"Expected `{name}` to be a real number, got {type(x).__name__} {_describe(x)}")
    value = float(x)
    if not math.isfinite(value):
        raise ValueError(f"Expected `{name}` to be finite, got {value}")
    return value


def as_int(x, name: str, *, minimum: int | None = None) -> int:
    """Return ``x`` as an int (at least ``minimum``), or raise naming ``name``."""
    if isinstance(x, bool) or not isinstance(x, (numbers.Integral, np.integer)):
        if isinstance(x, (float, np.floating)) and math.isfinite(x) and float(x).is_integer():
            x = int(x)
        else:
            raise TypeError(f"Expected `{name}` to be an integer, got {type(x).__name__} {_describe(x)}")
    value = int(x)
    if minimum is not None and value < minimum:
        raise ValueError(f"Expected `{name}` >= {minimum}, got {value}")
    return value


def positive(x, name: str) -> float:
    """Return ``x`` as a finite float > 0."""
    value = as_float(x, name)
    if value <= 0:
        raise ValueError(f"Expected `{name}` > 0, got {value}")
    return value


def nonnegative(x, name: str) -> float:
    """Return ``x`` as a finite float >= 0."""
    value = as_float(x, name)
    if value < 0:
        raise ValueError(f"Expected `{name}` >= 0, got {value}")
    return value


def in_open_interval(x, name: str, low: float, high: float, *, text: str | None = None) -> float:
    """Return ``x`` as a finite float in the open interval ``(low, high)``.

    >>> in_open_interval(4.2, "nutation", 0.0, math.pi, text="(0, π)")
    Traceback (most recent call last):
    ...
    ValueError: Expected `nutation` in (0, π), got 4.2
    """
    value = as_float(x, name)
    if not (low < value < high):
        span = text or f"({low:g}, {high:g})"
        raise ValueError(f"Expected `{name}` in {span}, got {value:g}")
    return value


def as_array(x, name: str, *, last: int | None = None, finite: bool = True) -> np.ndarray:
    """Return ``x`` as a float array, optionally with last axis of length ``last``.

    Raises
    ------
    TypeError
        If ``x`` is not numeric.
    ValueError
        If the last axis has the wrong length, or (with ``finite``) an entry is NaN or inf.
    """
    try:
        arr = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"Expected `{name}` to be a numeric array, got {type(x).__name__} {_describe(x)}") from None
    if last is not None and (arr.ndim == 0 or arr.shape[-1] != last):
        raise ValueError(f"Expected `{name}` with shape (..., {last}), got shape {arr.shape}")
    if finite and not np.all(np.isfinite(arr)):
        raise ValueError(f"Expected `{name}` to be finite, got an array with NaN or inf")
    return arr


def as_vector(x, name: str) -> np.ndarray:
    """Return ``x`` as a finite ``(..., 3)`` float array."""
    return as_array(x, name, last=3)


def as_quaternion(q, name: str, *, unit: bool = False, atol: float = 1e-9) -> np.ndarray:
    """Return ``q`` as a finite ``(..., 4)`` float array; with ``unit``, require |q| = 1.

    >>> as_quaternion([1.0, 0.0, 0.0, 0.1], "attitude", unit=True)
    Traceback (most recent call last):
    ...
    ValueError: Expected `attitude` to be a unit quaternion (|q| = 1 within 1e-09), got |q| = 1.00499
    """
    arr = as_array(q, name, last=4)
    if unit:
        norm = np.sqrt(np.sum(arr * arr, axis=-1))
        bad = np.abs(norm - 1.0) > atol
        if np.any(bad):
            worst = float(np.ravel(norm)[np.argmax(np.ravel(np.abs(norm - 1.0)))])
            raise ValueError(f"Expected `{name}` to be a unit quaternion (|q| = 1 within {atol:g}), got |q| = {worst:g}")
    return arr
