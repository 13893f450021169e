"""Streaming statistics of a parallel-computation run: memory that does not grow with the run.

The drift fit and the error statistics of
:func:`strapdown.analysis.coning.simulator.simulate` need only running sums, so
a run of any length can keep a fixed number of numbers per parameter point
instead of its error series.  With ``t_k = k H`` (``k = 0 … n``) the
least-squares slope of the error is

    drift = Σ_k (k − n/2) δφ_k  /  (H Σ_k (k − n/2)²),   Σ_k (k − n/2)² = n (n + 1)(n + 2) / 12,

the same fit as :func:`strapdown.analysis.coning.simulator.drift_rate`, with the
weights known in advance because the number of steps is.  The accumulator layout
(one row of :data:`N_SUMS` numbers per point) is shared by the compiled kernels
(:mod:`strapdown.analysis.coning.kernels`), which add whole blocks of steps at a
time, and by :func:`accumulate`, the numpy reference that adds a chunk of an
error series.

Errors are exact minus algorithm, as in
:class:`~strapdown.analysis.coning.simulator.SimulationResult`: ``δφ`` is the
rotation vector of ``Λ* ∘ Λ̄`` in frame I, ``ΔW = W* − W``.

The periodic part of the error, the peak distance of ``δφ`` from a
least-squares line, needs the line before the distances, so it is not a
running sum: :func:`window_peak` computes it over one window of the series (a
buffer the kernels fill and reuse), and a long run takes the largest over
consecutive windows.

Columns: 0–2 ``Σ (k − n/2) δφ_k``; 3 ``Σ |δφ_k|²``; 4 ``max |δφ_k|²``; 5–7 the
final ``δφ_n``; 8–10 and 11–13 the final ``ΔW_E``, ``ΔW_I``; 14, 15
``max |ΔW_E|²``, ``max |ΔW_I|²``; 16, 17 ``Σ |ΔW_E|²``, ``Σ |ΔW_I|²``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["N_SUMS", "ErrorStatistics", "empty_sums", "accumulate", "statistics", "window_peak"]

#: Numbers kept per parameter point (module docstring).
N_SUMS = 18


@dataclass(frozen=True)
class ErrorStatistics:
    """Drift fit and error statistics of runs, from running sums (leading axes: parameter points).

    Attributes
    ----------
    step : ndarray, shape (...)
        Algorithm step H = N h [s].
    steps : ndarray of int, shape (...)
        Steps n of each run (the run covers t = 0 … n H).
    drift : ndarray, shape (..., 3)
        Least-squares slope of the attitude error ``δφ_I = rotvec(Λ_exact ∘ Λ̄_alg)``
        (exact minus algorithm, frame I) against time [rad/s].
    final_error : ndarray, shape (..., 3)
        ``δφ_I`` at the end of the run, frame I [rad].
    rms_error : ndarray, shape (...)
        Root mean square of ``|δφ_I|`` over the n + 1 step ends [rad].
    max_error : ndarray, shape (...)
        Largest ``|δφ_I|`` [rad].
    final_dw_body, final_dw_inertial : ndarray, shape (..., 3), or None
        ``ΔW_E = W_E* − W_E`` (frame E) and ``ΔW_I = W_I* − W_I`` (frame I) at the
        end, exact minus algorithm [m/s] (velocity runs only).
    max_dw_body, max_dw_inertial, rms_dw_body, rms_dw_inertial : ndarray, shape (...), or None
        Largest and root-mean-square ``|ΔW_E|``, ``|ΔW_I|`` [m/s] (velocity runs only).
    """

    step: np.ndarray
    steps: np.ndarray
    drift: np.ndarray
    final_error: np.ndarray
    rms_error: np.ndarray
    max_error: np.ndarray
    final_dw_body: np.ndarray | None = None
    final_dw_inertial: np.ndarray | None = None
    max_dw_body: np.ndarray | None = None
    max_dw_inertial: np.ndarray | None = None
    rms_dw_body: np.ndarray | None = None
    rms_dw_inertial: np.ndarray | None = None

    @property
    def drift_rate(self) -> np.ndarray:
        """Constant drift rate ``|slope|`` [rad/s], shape ``(...)``."""
        return np.linalg.norm(self.drift, axis=-1)


def empty_sums(points: int) -> np.ndarray:
    """Zeroed accumulators for ``points`` runs.

    Parameters
    ----------
    points : int
        Number of parameter points.

    Returns
    -------
    ndarray, shape (points, N_SUMS)
    """
    return np.zeros((points, N_SUMS))


def accumulate(sums, first: int, steps, error, dw_body=None, dw_inertial=None) -> None:
    """Add a chunk of error series to the accumulators (the numpy reference of the kernels' sums).

    Parameters
    ----------
    sums : ndarray, shape (P, N_SUMS)
        Accumulators, updated in place.
    first : int
        Step index k of the chunk's first row.
    steps : array_like of int, shape (P,)
        Steps n of each run (the fit weights are ``k − n/2``).
    error : ndarray, shape (P, m, 3)
        Attitude errors ``δφ_I`` (exact minus algorithm, frame I) at the step
        indices ``first … first + m − 1`` [rad].
    dw_body, dw_inertial : ndarray, shape (P, m, 3), optional
        ``ΔW_E = W_E* − W_E``, ``ΔW_I = W_I* − W_I`` at the same steps [m/s].

    Raises
    ------
    ValueError
        If the chunk runs past the end of a run.
    """
    n = np.asarray(steps, dtype=np.int64)
    error = np.asarray(error, dtype=float)
    m = error.shape[-2]
    if first < 0 or np.any(first + m - 1 > n):
        raise ValueError(f"Expected the chunk of steps {first}..{first + m - 1} within every run (n = {int(n.min())}..{int(n.max())}), got one past the end")
    k = first + np.arange(m)
    weight = k[None, :] - 0.5 * n[:, None]
    e2 = np.sum(error * error, axis=-1)
    sums[:, 0:3] += np.einsum("pk,pkj->pj", weight, error)
    sums[:, 3] += e2.sum(axis=-1)
    sums[:, 4] = np.maximum(sums[:, 4], e2.max(axis=-1))
    at_end = (first + m - 1) == n
    sums[at_end, 5:8] = error[at_end, -1]
    if dw_body is not None:
        b2 = np.sum(dw_body * dw_body, axis=-1)
        i2 = np.sum(dw_inertial * dw_inertial, axis=-1)
        sums[at_end, 8:11] = dw_body[at_end, -1]
        sums[at_end, 11:14] = dw_inertial[at_end, -1]
        sums[:, 14] = np.maximum(sums[:, 14], b2.max(axis=-1))
        sums[:, 15] = np.maximum(sums[:, 15], i2.max(axis=-1))
        sums[:, 16] += b2.sum(axis=-1)
        sums[:, 17] += i2.sum(axis=-1)


def statistics(sums, steps, step, *, velocity: bool, shape=None) -> ErrorStatistics:
    """The statistics of completed runs from their accumulators.

    Parameters
    ----------
    sums : ndarray, shape (P, N_SUMS)
        Accumulators after the last step of every run.
    steps : array_like of int, shape (P,)
        Steps n of each run (n ≥ 1).
    step : array_like, shape (P,)
        Algorithm step H of each run [s].
    velocity : bool, keyword-only
        Fill the velocity statistics.
    shape : tuple, optional
        Batch shape to give the results (default ``(P,)``).

    Returns
    -------
    ErrorStatistics
    """
    n = np.asarray(steps, dtype=np.int64)
    big_h = np.asarray(step, dtype=float)
    shape = (n.shape[0],) if shape is None else tuple(shape)
    nf = n.astype(float)
    norm = big_h * nf * (nf + 1.0) * (nf + 2.0) / 12.0
    count = nf + 1.0

    def vec(x):
        return np.reshape(x, shape + (3,))

    def sc(x):
        return np.reshape(x, shape)

    out = {
        "step": sc(big_h),
        "steps": sc(n),
        "drift": vec(sums[:, 0:3] / norm[:, None]),
        "final_error": vec(sums[:, 5:8]),
        "rms_error": sc(np.sqrt(sums[:, 3] / count)),
        "max_error": sc(np.sqrt(sums[:, 4])),
    }
    if velocity:
        out |= {
            "final_dw_body": vec(sums[:, 8:11]),
            "final_dw_inertial": vec(sums[:, 11:14]),
            "max_dw_body": sc(np.sqrt(sums[:, 14])),
            "max_dw_inertial": sc(np.sqrt(sums[:, 15])),
            "rms_dw_body": sc(np.sqrt(sums[:, 16] / count)),
            "rms_dw_inertial": sc(np.sqrt(sums[:, 17] / count)),
        }
    return ErrorStatistics(**out)


#: Rows of a window :func:`window_peak` treats at once (its temporaries stay a few MB).
PEAK_BLOCK = 1 << 16


def window_peak(error, rows=None) -> np.ndarray:
    """Peak distance of a window of an error series from its own least-squares line.

    For the m rows ``e_k`` of the window (equally spaced in time) the line is the
    least-squares fit ``a + d (k − (m − 1)/2)``, and the peak is
    ``max_k |e_k − a − d (k − (m − 1)/2)|``: the periodic error that a drift fit
    over the window averages out.  Over a whole run it is
    :attr:`strapdown.analysis.coning.simulator.SimulationResult.periodic_error`.
    The sums and the distances are formed component by component in blocks of
    :data:`PEAK_BLOCK` rows, so the temporaries do not grow with the window.

    Parameters
    ----------
    error : ndarray, shape (P, m, 3)
        Windows of P error series [rad] (any unit: the peak has the same).
    rows : array_like of int, shape (P,), optional
        Rows of each window that hold data (the first ``rows[i]``; default all m).
        A window of fewer than three rows fits its line exactly and gives 0.

    Returns
    -------
    ndarray, shape (P,)

    Examples
    --------
    >>> k = np.arange(101.0)
    >>> e = np.stack([1e-3 * k + 1e-6 * np.cos(k), 0 * k, 0 * k], axis=-1)[None]
    >>> bool(abs(window_peak(e)[0] - 1e-6) < 1e-7)
    True
    """
    error = np.asarray(error, dtype=float)
    points, m = error.shape[0], error.shape[1]
    full = np.full(points, m, dtype=np.int64) if rows is None else np.asarray(rows, dtype=np.int64)
    peak = np.zeros(points)
    for p in range(points):
        count = int(full[p])
        if count < 3:
            continue
        mid = 0.5 * (count - 1)
        blocks = [(r0, min(count, r0 + PEAK_BLOCK)) for r0 in range(0, count, PEAK_BLOCK)]
        total = np.zeros(3)
        moment = np.zeros(3)
        for r0, r1 in blocks:
            c = np.arange(r0, r1) - mid
            for j in range(3):
                x = error[p, r0:r1, j]
                total[j] += x.sum()
                moment[j] += (x * c).sum()
        line_a = total / count
        line_d = moment / (count * (count * count - 1.0) / 12.0)  # Σ (k − mid)² over k < count
        best = 0.0
        for r0, r1 in blocks:
            c = np.arange(r0, r1) - mid
            square = np.zeros(r1 - r0)
            for j in range(3):
                res = error[p, r0:r1, j] - line_a[j]
                res -= c * line_d[j]
                res *= res
                square += res
            best = max(best, float(square.max()))
        peak[p] = np.sqrt(best)
    return peak
