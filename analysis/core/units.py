"""Every unit factor of the package, in one place.

The library works in SI units with angles in radians (rates in rad/s).  Degrees,
degrees per hour and arc-seconds appear only at the edges (the command line and
the reports), which convert with the factors below.

>>> round(RAD_PER_S_TO_DEG_PER_H * 1e-6, 6)
0.206265
"""

from __future__ import annotations

import math
import numbers

__all__ = [
    "DEG",
    "RAD_PER_DEG",
    "DEG_PER_RAD",
    "RAD_PER_S_TO_DEG_PER_H",
    "DEG_PER_H_TO_RAD_PER_S",
    "SECONDS_PER_HOUR",
    "STANDARD_GRAVITY",
    "ARCSEC_PER_RAD",
    "ARCSEC",
    "PPM",
    "DEG_PER_RT_H_TO_RAD_PER_RT_S",
    "M_S_PER_RT_H_TO_M_S_PER_RT_S",
    "DEG_PER_H_PER_RT_H_TO_RAD_PER_S_PER_RT_S",
    "MICRO_G",
    "deg",
    "rad",
    "deg_per_h",
    "rad_per_s",
    "deg_per_sqrt_h",
    "micro_g_per_sqrt_hz",
    "milli_g",
]

SECONDS_PER_HOUR = 3600.0
#: Standard gravity g₀ [m/s²] (for specific forces quoted in g or µg).
STANDARD_GRAVITY = 9.80665
#: One degree [rad].
DEG = math.pi / 180.0
RAD_PER_DEG = DEG
DEG_PER_RAD = 180.0 / math.pi
#: Factor from rad/s to deg/h.
RAD_PER_S_TO_DEG_PER_H = DEG_PER_RAD * SECONDS_PER_HOUR
#: Factor from deg/h to rad/s.
DEG_PER_H_TO_RAD_PER_S = 1.0 / RAD_PER_S_TO_DEG_PER_H
#: Arc-seconds in one radian.
ARCSEC_PER_RAD = DEG_PER_RAD * 3600.0
#: One arc-second [rad].
ARCSEC = DEG / 3600.0
#: One part per million [1].
PPM = 1e-6
#: Factor from deg/√h (angle random walk) to rad/√s.
DEG_PER_RT_H_TO_RAD_PER_RT_S = DEG / math.sqrt(SECONDS_PER_HOUR)
#: Factor from m/s/√h (velocity random walk) to m/s/√s.
M_S_PER_RT_H_TO_M_S_PER_RT_S = 1.0 / math.sqrt(SECONDS_PER_HOUR)
#: Factor from deg/h/√h (rate random walk) to rad/s/√s.
DEG_PER_H_PER_RT_H_TO_RAD_PER_S_PER_RT_S = DEG_PER_H_TO_RAD_PER_S / math.sqrt(SECONDS_PER_HOUR)
#: One micro-g [m/s²] (g the standard gravity).
MICRO_G = STANDARD_GRAVITY * 1e-6


def _quantity(x):
    """``x`` itself if it scales like a number (a number, an array, a dual number), an array for a list or tuple; else a clear TypeError."""
    if isinstance(x, numbers.Number) and not isinstance(x, bool) or hasattr(x, "__array_ufunc__"):
        return x  # numbers, numpy arrays and scalars (the hot path)
    if isinstance(x, (list, tuple)):
        from .validation import as_array

        return as_array(x, "x", finite=False)
    if not isinstance(x, (str, bytes, bool)) and x is not None and hasattr(x, "__mul__") and hasattr(x, "__rmul__"):
        return x  # dual numbers and other numeric types
    text = repr(x) if len(repr(x)) <= 60 else repr(x)[:57] + "..."
    raise TypeError(f"Expected `x` to be a number or an array of numbers, got {type(x).__name__} {text}")


def deg(x):
    """Radians → degrees.

    Parameters
    ----------
    x : float or array_like
        Value(s) [rad].

    Returns
    -------
    float or ndarray
        The same value(s) [deg].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.
    """
    return _quantity(x) * DEG_PER_RAD


def rad(x):
    """Degrees → radians.

    Parameters
    ----------
    x : float or array_like
        Value(s) [deg].

    Returns
    -------
    float or ndarray
        The same value(s) [rad].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.
    """
    return _quantity(x) * RAD_PER_DEG


def deg_per_h(x):
    """rad/s → deg/h.

    Parameters
    ----------
    x : float or array_like
        Value(s) [rad/s].

    Returns
    -------
    float or ndarray
        The same value(s) [deg/h].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.
    """
    return _quantity(x) * RAD_PER_S_TO_DEG_PER_H


def rad_per_s(x):
    """deg/h → rad/s.

    Parameters
    ----------
    x : float or array_like
        Value(s) [deg/h].

    Returns
    -------
    float or ndarray
        The same value(s) [rad/s].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.
    """
    return _quantity(x) * DEG_PER_H_TO_RAD_PER_S


def deg_per_sqrt_h(x):
    """Angle random walk rad/√s → deg/√h.

    Parameters
    ----------
    x : float or array_like
        Value(s) [rad/√s].

    Returns
    -------
    float or ndarray
        The same value(s) [deg/√h].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.
    """
    return deg(x) * math.sqrt(SECONDS_PER_HOUR)


def micro_g_per_sqrt_hz(x):
    """Velocity random walk m/s/√s → µg/√Hz (g the standard gravity).

    Parameters
    ----------
    x : float or array_like
        Value(s) [m/s/√s].

    Returns
    -------
    float or ndarray
        The same value(s) [µg/√Hz].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.
    """
    return _quantity(x) / STANDARD_GRAVITY * 1e6


def milli_g(x):
    """Acceleration m/s² → mg (thousandths of the standard gravity).

    Parameters
    ----------
    x : float or array_like
        Value(s) [m/s²].

    Returns
    -------
    float or ndarray
        The same value(s) [mg].

    Raises
    ------
    TypeError
        If ``x`` is not a number, an array of numbers or a dual number.

    >>> round(milli_g(2e-3), 4)
    0.2039
    """
    return _quantity(x) / STANDARD_GRAVITY * 1e3
