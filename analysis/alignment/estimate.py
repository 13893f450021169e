"""What an alignment method returns: the estimated attitude against its truth.

Each method estimates the attitude at its *reference instant*: the analytic
method the stable attitude (the mean position, the α of Hrechka & Koroliov),
the inertial-frame and Kalman methods the attitude at the end of the
alignment, the one handed to navigation.  The error is ``estimate − truth``,
wrapped to (−π, π] for the heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["AlignmentEstimate", "wrap_angle"]


def wrap_angle(x):
    """Angles wrapped to (−π, π] [rad].

    Parameters
    ----------
    x : array_like
        Angles [rad].

    Returns
    -------
    ndarray

    >>> float(wrap_angle(3 * math.pi / 2))
    -1.5707963267948966
    """
    x = np.asarray(x, dtype=float)
    return x - 2.0 * math.pi * np.ceil((x - math.pi) / (2.0 * math.pi))


@dataclass(frozen=True)
class AlignmentEstimate:
    """Estimated heading and tilts of ``n`` trials with the true values at the reference instant.

    Attributes
    ----------
    method : str
        ``"analytic"``, ``"inertial"`` or ``"kalman"``.
    heading, beta, gamma : ndarray
        ``(n,)`` estimates [rad].
    true_heading, true_beta, true_gamma : ndarray
        ``(n,)`` truth at the reference instant [rad].
    reference : str
        ``"stable"`` (the stable attitude) or ``"end"`` (the attitude at the end of the alignment).
    """

    method: str
    heading: np.ndarray
    beta: np.ndarray
    gamma: np.ndarray
    true_heading: np.ndarray
    true_beta: np.ndarray
    true_gamma: np.ndarray
    reference: str

    @property
    def heading_error(self) -> np.ndarray:
        """Azimuth error ``ψ̂ − ψ`` wrapped to (−π, π] [rad]."""
        return wrap_angle(self.heading - self.true_heading)

    @property
    def tilt_error(self) -> np.ndarray:
        """``(n, 2)`` errors of β̂, γ̂ [rad]."""
        return np.stack([self.beta - self.true_beta, self.gamma - self.true_gamma], axis=-1)
