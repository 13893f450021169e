"""The gap-free segments of a log, as the analyses take them.

A log with gaps is a sequence of :class:`~strapdown.analysis.logs.imu_log.ImuLog`
segments, each at one constant rate and without gaps; the analyses take one
segment or a sequence of them, at one sample interval.

Public API
----------
.. autosummary::

   as_segments
   sample_interval
"""

from __future__ import annotations

from collections.abc import Sequence

from .imu_log import ImuLog

__all__ = ["as_segments", "sample_interval"]


def as_segments(segments, name: str = "segments") -> tuple:
    """``segments`` as a non-empty tuple of :class:`ImuLog` (types only: no pass over the samples).

    Parameters
    ----------
    segments : ImuLog or sequence of ImuLog
        One segment or several.
    name : str
        Argument name for the messages.

    Returns
    -------
    tuple of ImuLog

    Raises
    ------
    TypeError
        If it holds something else.
    ValueError
        If it is empty.
    """
    if isinstance(segments, ImuLog):
        return (segments,)
    if not isinstance(segments, Sequence) or isinstance(segments, (str, bytes)):
        raise TypeError(f"Expected `{name}` to be an ImuLog or a sequence of ImuLog, got {type(segments).__name__}")
    out = tuple(segments)
    if not out:
        raise ValueError(f"Expected `{name}` to hold at least one ImuLog, got none")
    for k, s in enumerate(out):
        if not isinstance(s, ImuLog):
            raise TypeError(f"Expected `{name}` to hold ImuLog, got {type(s).__name__} at position {k}")
    return out


def sample_interval(segments: tuple, name: str = "segments") -> float:
    """The sample interval common to ``segments`` [s] (one pass over their times).

    Parameters
    ----------
    segments : tuple of ImuLog
        From :func:`as_segments`.
    name : str
        Argument name for the messages.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If two segments differ in their interval by more than 10⁻⁶ of it.
    """
    h = segments[0].dt
    for k, s in enumerate(segments[1:], start=1):
        if abs(s.dt - h) > 1e-6 * h:
            raise ValueError(f"Expected every segment of `{name}` at one sample interval, got {h:.9g} s and {s.dt:.9g} s (segment {k})")
    return h
