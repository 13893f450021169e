"""The time histories of an alignment filter run on a recorded log, and the test of its innovations.

A filter run once on recorded data has no truth to score it against; what it
can be checked by is its own innovations.  When the filter's model (the sensor
noise, the measurement noise, the motion) is right, the normalised innovation
squared ``NIS_k = y_kᵀ S_k⁻¹ y_k`` of each update is χ²-distributed with m
degrees of freedom (m measurements) and the NIS of successive updates are
independent (the innovations of an optimal filter are white).  The mean NIS over a
block of K updates then lies inside ``[χ²_{α/2}(mK)/K, χ²_{1−α/2}(mK)/K]`` with
probability 1 − α.  :func:`filter_history` cuts the run into blocks and tests each
at α = 0.05/B (Bonferroni over the B blocks), so that a filter whose model fits
passes the whole run with probability at least 95 %: a mean NIS above the band
says the filter trusts itself too much (noise assumed too small, a motion it
does not model), below it says it assumes noise that the data do not have.

Public API
----------
.. autosummary::

   FilterHistory
   filter_history
   NIS_LEVEL
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.kalman import chi2_band
from ..core.validation import as_array, as_int

__all__ = ["FilterHistory", "filter_history", "NIS_LEVEL"]

#: Probability that the NIS test of a filter whose model fits passes the whole run.
NIS_LEVEL = 0.95


@dataclass(frozen=True)
class FilterHistory:
    """What an alignment filter estimated and how sure it was, update by update.

    Attributes
    ----------
    times : ndarray
        ``(E,)`` times of the updates, from the start of the aligned segment [s].
    sigma : ndarray
        ``(E, 3)`` the filter's standard deviations of the north tilt φ_N, the east tilt φ_E
        and the azimuth error after each update [rad].
    gyro_bias, accel_bias : ndarray
        ``(E, 3)`` the bias estimates after each update [rad/s, m/s²], in ``bias_frame``.
    bias_frame : str
        ``"NED"`` (the fine filter's biases resolved in the navigation frame) or ``"body"``.
    innovation : ndarray
        ``(E, m)`` the innovations ``y = z − H x̂⁻`` [m/s or m, as ``innovation_names`` say].
    innovation_names : tuple of str
        What each innovation component measures (``"v_N"``, ..., ``"p_D"``).
    nis : ndarray
        ``(E,)`` the normalised innovations squared ``yᵀ S⁻¹ y`` [dimensionless].
    block : int
        Updates per block of the NIS test [count].
    block_times : ndarray
        ``(B,)`` the end of each block [s].
    block_nis : ndarray
        ``(B,)`` the mean NIS of each block.
    band : tuple of float
        ``(low, high)``: the band of one block's mean NIS at the level α = (1 − :data:`NIS_LEVEL`)/B.
    """

    times: np.ndarray
    sigma: np.ndarray
    gyro_bias: np.ndarray
    accel_bias: np.ndarray
    bias_frame: str
    innovation: np.ndarray
    innovation_names: tuple
    nis: np.ndarray
    block: int
    block_times: np.ndarray
    block_nis: np.ndarray
    band: tuple

    @property
    def dof(self) -> int:
        """Measurements per update m (the degrees of freedom of one NIS) [count]."""
        return self.innovation.shape[1]

    @property
    def outside(self) -> np.ndarray:
        """Indices of the blocks whose mean NIS lies outside :attr:`band`."""
        return np.flatnonzero((self.block_nis < self.band[0]) | (self.block_nis > self.band[1]))

    @property
    def nis_consistent(self) -> bool:
        """Every block's mean NIS inside its band: the innovations agree with the filter's model."""
        return self.outside.size == 0

    @property
    def mean_nis(self) -> float:
        """Mean NIS over the whole run (its expectation is :attr:`dof` when the model fits)."""
        return float(np.mean(self.nis))


def filter_history(times, sigma, gyro_bias, accel_bias, innovation, nis, *, bias_frame: str, innovation_names, block: int | None = None) -> FilterHistory:
    """Collect a filter's histories and test its NIS block by block.

    Parameters
    ----------
    times : array_like
        ``(E,)`` update times [s].
    sigma : array_like
        ``(E, 3)`` standard deviations of φ_N, φ_E and the azimuth error [rad].
    gyro_bias, accel_bias : array_like
        ``(E, 3)`` bias estimates [rad/s, m/s²].
    innovation : array_like
        ``(E, m)`` innovations.
    nis : array_like
        ``(E,)`` NIS of each update.
    bias_frame : str, keyword-only
        ``"NED"`` or ``"body"``.
    innovation_names : sequence of str, keyword-only
        m names.
    block : int, optional, keyword-only
        Updates per block (default: at least 10, and at most 20 blocks) [count].

    Returns
    -------
    FilterHistory

    Raises
    ------
    ValueError
        For shapes that do not agree, or no update.

    References
    ----------
    Bar-Shalom, Y., Li, X. R., Kirubarajan, T., *Estimation with Applications to Tracking and
    Navigation*, Wiley, 2001, sec. 5.4.2 (the NIS test over a time window) and 5.4.3 (whiteness).

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(1)
    >>> y = rng.standard_normal((400, 3))   # innovations of unit covariance: NIS = |y|²
    >>> h = filter_history(np.arange(400.0), np.ones((400, 3)), np.zeros((400, 3)), np.zeros((400, 3)), y, np.sum(y * y, axis=1),
    ...                    bias_frame="NED", innovation_names=("v_N", "v_E", "v_D"))
    >>> h.nis_consistent, h.block_nis.size
    (True, 20)
    >>> filter_history(np.arange(400.0), np.ones((400, 3)), np.zeros((400, 3)), np.zeros((400, 3)), 2 * y, 4 * np.sum(y * y, axis=1),
    ...                bias_frame="NED", innovation_names=("v_N", "v_E", "v_D")).nis_consistent
    False
    """
    t = as_array(times, "times").ravel()
    E = t.size
    if E == 0:
        raise ValueError("Expected at least one update in `times`, got none")
    y = as_array(innovation, "innovation")
    if y.ndim != 2 or y.shape[0] != E:
        raise ValueError(f"Expected `innovation` with shape ({E}, m), got shape {y.shape}")
    arrays = {}
    for name, a, shape in (("sigma", sigma, (E, 3)), ("gyro_bias", gyro_bias, (E, 3)), ("accel_bias", accel_bias, (E, 3)), ("nis", nis, (E,))):
        a = as_array(a, name)
        if a.shape != shape:
            raise ValueError(f"Expected `{name}` with shape {shape}, got shape {a.shape}")
        arrays[name] = a
    names = tuple(str(n) for n in innovation_names)
    if len(names) != y.shape[1]:
        raise ValueError(f"Expected {y.shape[1]} `innovation_names`, got {len(names)}")
    if bias_frame not in ("NED", "body"):
        raise ValueError(f"Expected `bias_frame` 'NED' or 'body', got {bias_frame!r}")
    K = max(10, math.ceil(E / 20)) if block is None else as_int(block, "block", minimum=1)
    K = min(K, E)
    B = E // K
    blocks = arrays["nis"][: B * K].reshape(B, K).mean(axis=1)
    band = chi2_band(y.shape[1], K, 1.0 - (1.0 - NIS_LEVEL) / B)
    return FilterHistory(t, arrays["sigma"], arrays["gyro_bias"], arrays["accel_bias"], bias_frame, y, names, arrays["nis"], K, t[K - 1 : B * K : K], blocks, band)
