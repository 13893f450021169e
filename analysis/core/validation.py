"""Validation of user input: one place, messages a user can act on.

Every check raises :class:`ValueError` for a bad value and :class:`TypeError` for
a wrong type, and names the argument, what was expected and what came.  The
name is the Python argument (``sample_interval``); the command line puts the
option it came from in front of the message (``argument --sample-interval:``).
A limit is stated in the unit of the value checked: a command line that takes
degrees checks degrees (``in_open_interval(lat, "--lat-deg", -90, 90, text="(-90, 90)
degrees")``) before it converts to radians.
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
    "in_closed_interval",
    "levels",
    "positive",
    "nonnegative",
]


def _describe(x) -> str:
    text = repr(x)
    return text if len(text) <= 60 else text[:57] + "..."


def as_float(x, name: str) -> float:
    """Return ``x`` as a finite float, or raise naming ``name``.

    Parameters
    ----------
    x : real number
        The value (a Python or numpy real, or a 0-d numeric array; not a bool).
    name : str
        Argument name for the message.

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``x`` is not a real number.
    ValueError
        If ``x`` is NaN or infinite.

    Examples
    --------
    >>> as_float(2, "eps")
    2.0
    """
    if type(x) is float or type(x) is np.float64:  # the common cases, decided without the abstract-base-class checks
        value = float(x)
    else:
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
    """Return ``x`` as an int (at least ``minimum``), or raise naming ``name``.

    Parameters
    ----------
    x : int or integral float
        The value (``3.0`` is accepted, ``3.5`` and booleans are not).
    name : str
        Argument name for the message.
    minimum : int, optional, keyword-only
        Smallest value accepted.

    Returns
    -------
    int

    Raises
    ------
    TypeError
        If ``x`` is not an integer.
    ValueError
        If ``x`` is below ``minimum``.

    Examples
    --------
    >>> as_int(1e6, "samples", minimum=2)
    1000000
    """
    if type(x) is int:  # the common case, decided without the abstract-base-class checks
        value = x
    else:
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
    """Return ``x`` as a finite float > 0.

    Parameters
    ----------
    x : real number
        The value.
    name : str
        Argument name for the message.

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``x`` is not a real number.
    ValueError
        If ``x`` is not finite or not positive.
    """
    value = as_float(x, name)
    if value <= 0:
        raise ValueError(f"Expected `{name}` > 0, got {value}")
    return value


def nonnegative(x, name: str) -> float:
    """Return ``x`` as a finite float >= 0.

    Parameters
    ----------
    x : real number
        The value.
    name : str
        Argument name for the message.

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``x`` is not a real number.
    ValueError
        If ``x`` is not finite or negative.
    """
    value = as_float(x, name)
    if value < 0:
        raise ValueError(f"Expected `{name}` >= 0, got {value}")
    return value


def in_open_interval(x, name: str, low: float, high: float, *, text: str | None = None) -> float:
    """Return ``x`` as a finite float in the open interval ``(low, high)``.

    Parameters
    ----------
    x : real number
        The value.
    name : str
        Argument name for the message.
    low, high : float
        Ends of the interval (excluded), in the unit of ``x``.
    text : str, optional, keyword-only
        How the message shows the interval, with its unit (e.g. ``"(0, 180) degrees"``).

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``x`` is not a real number.
    ValueError
        If ``x`` is not finite or outside the interval.

    Examples
    --------
    >>> in_open_interval(4.2, "nutation", 0.0, math.pi, text="(0, π)")
    Traceback (most recent call last):
    ...
    ValueError: Expected `nutation` in (0, π), got 4.2
    """
    return _in_interval(x, name, low, high, closed=False, text=text)


def in_closed_interval(x, name: str, low: float, high: float, *, text: str | None = None) -> float:
    """Return ``x`` as a finite float in the closed interval ``[low, high]``.

    Parameters
    ----------
    x : real number
        The value.
    name : str
        Argument name for the message.
    low, high : float
        Ends of the interval (included), in the unit of ``x``.
    text : str, optional, keyword-only
        How the message shows the interval, with its unit (e.g. ``"[1e-06, 3] rad"``).

    Returns
    -------
    float

    Raises
    ------
    TypeError
        If ``x`` is not a real number.
    ValueError
        If ``x`` is not finite or outside the interval.

    Examples
    --------
    >>> in_closed_interval(1e-9, "tolerance", 1e-6, 0.5)
    Traceback (most recent call last):
    ...
    ValueError: Expected `tolerance` in [1e-06, 0.5], got 1e-09
    """
    return _in_interval(x, name, low, high, closed=True, text=text)


def levels(x, name: str) -> tuple:
    """Return ``x``, a sequence of probability levels, as a tuple of floats in (0, 1).

    Parameters
    ----------
    x : sequence of real number
        The levels (may be empty).
    name : str
        Argument name for the message.

    Returns
    -------
    tuple of float

    Raises
    ------
    TypeError
        If ``x`` is not a sequence (a single number or a string) or holds a non-number.
    ValueError
        If a level is not finite or outside (0, 1).

    Examples
    --------
    >>> levels([0.5, 0.95], "quantiles")
    (0.5, 0.95)
    >>> levels(0.5, "quantiles")
    Traceback (most recent call last):
    ...
    TypeError: Expected `quantiles` as a sequence of levels in (0, 1), got 0.5
    """
    if isinstance(x, (str, bytes)) or not isinstance(x, (list, tuple, np.ndarray, range)):
        raise TypeError(f"Expected `{name}` as a sequence of levels in (0, 1), got {_describe(x)}")
    out = tuple(as_float(v, name) for v in np.asarray(x, dtype=object).ravel())
    for v in out:
        if not 0.0 < v < 1.0:
            raise ValueError(f"Expected `{name}` as levels in (0, 1), got {v:g}")
    return out


def _in_interval(x, name: str, low: float, high: float, *, closed: bool, text: str | None) -> float:
    value = as_float(x, name)
    inside = low <= value <= high if closed else low < value < high
    if not inside:
        span = text or (f"[{low:g}, {high:g}]" if closed else f"({low:g}, {high:g})")
        raise ValueError(f"Expected `{name}` in {span}, got {value:g}")
    return value


def as_array(x, name: str, *, last: int | None = None, finite: bool = True, nonempty: bool = False) -> np.ndarray:
    """Return ``x`` as a float array, optionally with last axis of length ``last``.

    Parameters
    ----------
    x : array_like
        Numbers.
    name : str
        Argument name for the message.
    last : int, optional, keyword-only
        Required length of the last axis.
    finite : bool, keyword-only
        Refuse NaN and infinities.
    nonempty : bool, keyword-only
        Refuse an array without elements.

    Returns
    -------
    ndarray of float

    Raises
    ------
    TypeError
        If ``x`` is not numeric.
    ValueError
        If the last axis has the wrong length, (with ``finite``) an entry is
        NaN or inf, or (with ``nonempty``) the array is empty.

    Examples
    --------
    >>> as_array([], "omega", nonempty=True)
    Traceback (most recent call last):
    ...
    ValueError: Expected `omega` to hold at least one value, got an empty array (shape (0,))
    """
    try:
        arr = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"Expected `{name}` to be a numeric array, got {type(x).__name__} {_describe(x)}") from None
    if nonempty and arr.size == 0:
        raise ValueError(f"Expected `{name}` to hold at least one value, got an empty array (shape {arr.shape})")
    if last is not None and (arr.ndim == 0 or arr.shape[-1] != last):
        raise ValueError(f"Expected `{name}` with shape (..., {last}), got shape {arr.shape}")
    if finite and not np.all(np.isfinite(arr)):
        raise ValueError(f"Expected `{name}` to be finite, got an array with NaN or inf")
    return arr


def as_vector(x, name: str) -> np.ndarray:
    """Return ``x`` as a finite ``(..., 3)`` float array.

    Parameters
    ----------
    x : array_like, shape (..., 3)
        Vector(s).
    name : str
        Argument name for the message.

    Returns
    -------
    ndarray, shape (..., 3)

    Raises
    ------
    TypeError
        If ``x`` is not numeric.
    ValueError
        If the last axis is not of length 3 or an entry is not finite.
    """
    return as_array(x, name, last=3)


def as_quaternion(q, name: str, *, unit: bool = False, atol: float = 1e-9) -> np.ndarray:
    """Return ``q`` as a finite ``(..., 4)`` float array; with ``unit``, require ``|q|`` = 1.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternion(s), scalar first.
    name : str
        Argument name for the message.
    unit : bool, keyword-only
        Require unit norm.
    atol : float, keyword-only
        Tolerance of the unit norm [dimensionless].

    Returns
    -------
    ndarray, shape (..., 4)

    Raises
    ------
    TypeError
        If ``q`` is not numeric.
    ValueError
        If the last axis is not of length 4, an entry is not finite, or (with
        ``unit``) a norm differs from 1 by more than ``atol``.

    Examples
    --------
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
