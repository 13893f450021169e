"""Coning algorithms replayed on a recorded log: each algorithm's mean correction rate.

An N-sample rotation-vector algorithm forms the increment of each step
``H = N h`` from the step's gyro increments as ``Δφ = P + C``: the plain sum
``P = p_1 + … + p_N``, the same for every algorithm, and the correction ``C``,
the algorithm's bilinear sum ``Σ c_ij p_i × p_j`` (and its higher terms, for
the few algorithms that have them) (:mod:`strapdown.derivations.coning.algorithms`).
Run on the recorded increments, the corrections summed over every step of the
log, divided by the time those steps cover, are the algorithm's *mean
correction rate* on this record [rad/s], a 3-vector in body axes.

The attitude an algorithm computes is the composition of its steps,
``Λ = exp(Δφ_1) ∘ exp(Δφ_2) ∘ …``; the drift (exact minus algorithm) of two
algorithms on the same increments therefore differs by exactly the rotation
between the two attitudes they compute, which the log alone gives:
``(u_a − u_b) T = rotvec(Λ_b ∘ Λ̄_a)`` (to first order in the difference of
the two errors, over a span T that both cover with whole steps), with no
model of the motion — what the two algorithms really do on this flight
(:meth:`Replay.drift_difference`).

When the two share their step (the same N), their compositions differ only
through their corrections, and the difference of drifts is also the
difference of the mean correction rates with the opposite sign,
``u_a − u_b = −(c_a − c_b)``, wherever the attitude changes little over the
log (each step's correction is resolved in the body axes of that step).
Between algorithms of different steps it is not: the composition of longer
steps misses more of the motion's non-commutativity between the samples, which
the corrections of a longer step make up for, so their corrections differ by
much more than their drifts (a reading of the claim that the difference of
correction rates is the difference of drifts: it holds for one step length).

Steps restart after a gap: each gap-free segment of the log is cut into whole
steps from its start; an algorithm that reads ``k`` samples of earlier steps
(:attr:`~strapdown.derivations.coning.algorithms.Algorithm.history`) begins
``k`` samples into the segment (those samples serve as its history only), and
samples after the last whole step are left out.  Work is vectorised over
steps, in chunks whose size does not change the result beyond round-off.

Public API
----------
.. autosummary::

   AlgorithmReplay
   Replay
   replay
   REPLAY_SAMPLE
   CHUNK_STEPS
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..coning.evaluation import increment
from ..core import budget
from ..core import quaternion as quat
from ..core.progress import bar
from ..core.validation import as_int
from .segments import as_segments, sample_interval

__all__ = ["AlgorithmReplay", "Replay", "replay", "REPLAY_SAMPLE", "CHUNK_STEPS"]

#: Replay cost per log sample and per term of an algorithm (the plain sum counts as one term):
#: time on one core of the reference machine (``benchmarks/bench_log_analysis.py``), rounded up;
#: the chunk buffers are the fixed memory.
REPLAY_SAMPLE = budget.CostModel(seconds_per_unit=3e-8, bytes_per_unit=0.0, fixed_seconds=0.05, fixed_bytes=5e7)
#: Steps evaluated at once [count] (the working set: a few arrays of this many windows).
CHUNK_STEPS = 1 << 16


@dataclass(frozen=True)
class AlgorithmReplay:
    """One algorithm run on the increments of a log.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm.
    correction : ndarray, shape (3,)
        Sum of the corrections ``Δφ − P`` over every step, body axes [rad].
    steps : int
        Steps run, over all segments [count].
    integrated_time : float
        Time covered by those steps, ``steps · N · h`` [s].
    attitudes : tuple of ndarray
        Per segment, the attitude the algorithm computes over the span common
        to every algorithm replayed, ``exp(Δφ_1) ∘ … ∘ exp(Δφ_K)`` from the
        identity (body axes at the span's start), shape (4,).
    """

    algorithm: Algorithm
    correction: np.ndarray
    steps: int
    integrated_time: float
    attitudes: tuple = ()

    @property
    def rate(self) -> np.ndarray:
        """Mean correction rate, ``correction / integrated_time``, body axes [rad/s]."""
        return self.correction / self.integrated_time


@dataclass(frozen=True)
class Replay:
    """Several algorithms run on the same log (:func:`replay`).

    Attributes
    ----------
    algorithms : tuple of AlgorithmReplay
        One per algorithm, in the order given.
    segments : int
        Gap-free segments of the log [count].
    samples : int
        Samples of the log, all segments [count].
    sample_interval : float
        h [s].
    common_time : float
        Time of the span common to every algorithm, all segments [s] (the
        attitudes compared by :meth:`drift_difference`).
    """

    algorithms: tuple
    segments: int
    samples: int
    sample_interval: float
    common_time: float = 0.0

    def drift_difference(self, a: int, b: int) -> np.ndarray:
        """Drift of algorithm ``a`` minus that of algorithm ``b`` on this log [rad/s] (exact minus algorithm, both).

        From the attitudes the two compute over the common span of each
        segment: ``(u_a − u_b) T = Σ_s rotvec(Λ_b ∘ Λ̄_a)`` (to first order in
        the difference of the errors), resolved in the body axes at the start
        of each segment's span.  For two algorithms of one step (the same N)
        it is the difference of their corrections, ``−(c_a − c_b)`` with ``c``
        the mean correction rates (module docstring), wherever the attitude
        changes little over the log.

        Parameters
        ----------
        a, b : int
            Positions in :attr:`algorithms`.

        Returns
        -------
        ndarray, shape (3,)

        Raises
        ------
        ValueError
            Positions out of range, or no span common to every algorithm.
        """
        n = len(self.algorithms)
        i, j = as_int(a, "a", minimum=0), as_int(b, "b", minimum=0)
        if i >= n or j >= n:
            raise ValueError(f"Expected `a` and `b` in 0..{n - 1}, got {a} and {b}")
        if self.common_time <= 0:
            raise ValueError("Expected a span of the log common to every algorithm replayed (a whole number of every step), got none: the segments are too short")
        total = np.zeros(3)
        for qa, qb in zip(self.algorithms[i].attitudes, self.algorithms[j].attitudes):
            total += quat.quat_to_rotvec(quat.multiply(qb, quat.conjugate(qa)), validate=False)
        return total / self.common_time


def _steps(n: int, algorithm: Algorithm) -> int:
    return max(0, (n - algorithm.history) // algorithm.samples)


def _step_rows(dtheta: np.ndarray, history: int, samples: int, s0: int, s1: int) -> np.ndarray:
    """The windows of steps ``s0 … s1 − 1`` as a contiguous ``(W, 3, s1 − s0)`` array: window row r, axis c, step k.

    Row r of step k is sample ``k N + r`` of ``dtheta`` (the windows of
    :func:`strapdown.analysis.coning.simulator.step_windows`, transposed so that
    each row and axis is contiguous over the steps).
    """
    k, w = s1 - s0, history + samples
    axes = np.ascontiguousarray(dtheta[s0 * samples : history + s1 * samples].T)  # (3, L)
    out = np.empty((w, 3, k))
    for r in range(w):
        out[r] = axes[:, r : r + (k - 1) * samples + 1 : samples]
    return out


def _pairwise_sum(pairs: dict, rows: np.ndarray, history: int) -> np.ndarray:
    """``Σ_k Σ_(i,j) c_ij p_i × p_j`` over the steps of ``rows`` (:func:`_step_rows`).

    A pair's cross product summed over the steps is made of sums of products of
    two components, ``Σ_k a_k × b_k = (Σ a_y b_z − Σ a_z b_y, …)``: one
    ``einsum`` of two contiguous rows per pair (numpy's own loops: BLAS
    threads cost more than they bring on vectors this short).
    """
    total = np.zeros(3)
    for (i, j), c in pairs.items():
        m = np.einsum("ck,dk->cd", rows[history + i - 1], rows[history + j - 1])  # Σ_k a_c b_d
        total += float(c) * np.array([m[1, 2] - m[2, 1], m[2, 0] - m[0, 2], m[0, 1] - m[1, 0]])
    return total


def _other_terms(algorithm: Algorithm) -> Algorithm | None:
    """The algorithm's terms that are not plain pairs ``p_i × p_j`` (nested, with dot factors), as an algorithm, or None."""
    others = tuple(t for t in algorithm.terms if t.dots or not (isinstance(t.cross[0], int) and isinstance(t.cross[1], int)))
    return Algorithm(algorithm.name, algorithm.samples, others) if others else None


def _other_sum(others: Algorithm, rows: np.ndarray, history: int) -> np.ndarray:
    """Σ over the steps of ``rows`` of the non-pairwise terms: ``increment`` of those terms alone, minus the plain sum."""
    windows = rows[history - others.history :].transpose(2, 0, 1)  # (k, W', 3), each component contiguous over the steps
    plain = windows[:, others.history, :].copy()
    for j in range(others.history + 1, others.window):  # P in the order increment() adds it
        plain += windows[:, j, :]
    return (increment(others, windows) - plain).sum(axis=0)


def _product(q: np.ndarray) -> np.ndarray:
    """``q_0 ∘ q_1 ∘ … ∘ q_{k−1}`` of ``(k, 4)`` quaternions, by pairs (depth log₂ k, no loop over k)."""
    parts = tuple(q[:, i] for i in range(4))
    while parts[0].size > 1:
        if parts[0].size % 2:
            parts = tuple(np.append(c, 1.0 if i == 0 else 0.0) for i, c in enumerate(parts))
        parts = quat.multiply_parts(tuple(c[0::2] for c in parts), tuple(c[1::2] for c in parts))
    return np.array([c[0] for c in parts])


def _attitude(algorithm: Algorithm, dtheta: np.ndarray, steps: int, chunk: int) -> np.ndarray:
    """``exp(Δφ_1) ∘ … ∘ exp(Δφ_K)`` of ``steps`` steps cut from ``dtheta`` from its first row (history first)."""
    q = quat.identity()
    for s0 in range(0, steps, chunk):
        rows = _step_rows(dtheta, algorithm.history, algorithm.samples, s0, min(steps, s0 + chunk))
        phi = increment(algorithm, rows.transpose(2, 0, 1))
        q = quat.multiply(q, _product(quat.rotvec_to_quat(phi, validate=False)))
    return quat.normalize(q)


def _common_span(n: int, algorithms) -> tuple:
    """``(start, length)`` of a segment of n samples that every algorithm covers with whole steps (after the longest history)."""
    start = max(a.history for a in algorithms)
    period = math.lcm(*(a.samples for a in algorithms))
    return start, max(0, (n - start) // period * period)


def _correction_sum(algorithm: Algorithm, dtheta: np.ndarray, steps: int, chunk: int) -> np.ndarray:
    """Σ over ``steps`` steps of the corrections ``Δφ − P``, the steps cut from ``dtheta`` from its first row (history first)."""
    pairs, others = algorithm.pairwise, _other_terms(algorithm)
    total = np.zeros(3)
    for s0 in range(0, steps, chunk):
        rows = _step_rows(dtheta, algorithm.history, algorithm.samples, s0, min(steps, s0 + chunk))
        total += _pairwise_sum(pairs, rows, algorithm.history)
        if others is not None:
            total += _other_sum(others, rows, algorithm.history)
    return total


def replay(segments, algorithms, *, chunk_steps: int = CHUNK_STEPS, limits: budget.Limits | None = None, progress: bool = False) -> Replay:
    """Run ``algorithms`` on the recorded increments and sum each one's corrections (module docstring).

    Parameters
    ----------
    segments : ImuLog or sequence of ImuLog
        The gap-free segments of a log, at one sample interval; steps restart
        in each.
    algorithms : Algorithm or sequence of Algorithm
        Registry or file algorithms (cross-step and higher-degree terms allowed).
    chunk_steps : int, keyword-only
        Steps evaluated at once [count] (memory; the result does not depend on
        it beyond round-off).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.
    progress : bool, keyword-only
        Show progress on stderr.

    Returns
    -------
    Replay

    Raises
    ------
    TypeError
        If ``segments`` or ``algorithms`` hold something else.
    ValueError
        No segment or algorithm, segments at different sample intervals, a log
        with no whole step for an algorithm, or work beyond ``limits`` (named by
        ``segments``).

    References
    ----------
    Lebedev & Panov (1989), eq. (2.2) (the rotation-vector increment of a step);
    Savage (1998), part 1 (the coning correction of a step).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> from strapdown.analysis.logs.imu_log import ImuLog
    >>> t = 0.01 * np.arange(1, 5)
    >>> log = ImuLog(t, [[1e-3, 0, 0], [0, 1e-3, 0], [1e-3, 0, 0], [0, 1e-3, 0]], np.zeros((4, 3)))
    >>> r = replay(log, [get("two-sample")])
    >>> r.algorithms[0].correction   # two steps of (2/3) p1 × p2
    array([0.00000000e+00, 0.00000000e+00, 1.33333333e-06])
    """
    segs = as_segments(segments)
    algs = (algorithms,) if isinstance(algorithms, Algorithm) else tuple(algorithms) if isinstance(algorithms, Sequence) else None
    if algs is None or not algs:
        raise ValueError(f"Expected `algorithms` to hold at least one Algorithm, got {algorithms!r:.60}")
    for k, a in enumerate(algs):
        if not isinstance(a, Algorithm):
            raise TypeError(f"Expected `algorithms` to hold Algorithm, got {type(a).__name__} at position {k}")
    chunk = as_int(chunk_steps, "chunk_steps", minimum=1)
    samples = sum(s.n_samples for s in segs)
    terms = sum(1 + len(a.terms) + a.samples for a in algs)
    what = f"`segments` = {samples:.3g} samples × {len(algs)} algorithm(s)"
    budget.check(REPLAY_SAMPLE.estimate(float(samples) * terms, what=what, extra_bytes=48.0 * chunk * max(a.window for a in algs)), limits)
    h = sample_interval(segs)
    spans = [_common_span(s.n_samples, algs) for s in segs]
    results = []
    with bar(desc="replaying the algorithms", total=2 * samples * len(algs), enabled=progress, unit="sample") as pb:
        for alg in algs:
            steps = [_steps(s.n_samples, alg) for s in segs]
            if sum(steps) == 0:
                raise ValueError(
                    f"Expected `segments` to hold at least one whole step of {alg.name!r} ({alg.samples} samples after {alg.history} of history), "
                    f"got segments of at most {max(s.n_samples for s in segs)} samples"
                )
            total = np.zeros(3)
            for s, k in zip(segs, steps):
                if k:
                    total += _correction_sum(alg, s.dtheta, k, chunk)
                pb.update(s.n_samples)
            attitudes = []
            for s, (start, length) in zip(segs, spans):
                k = length // alg.samples
                attitudes.append(_attitude(alg, s.dtheta[start - alg.history :], k, chunk) if k else quat.identity())
                pb.update(s.n_samples)
            results.append(AlgorithmReplay(alg, total, int(sum(steps)), float(sum(steps)) * alg.samples * h, tuple(attitudes)))
    return Replay(tuple(results), len(segs), int(samples), h, float(sum(length for _, length in spans)) * h)
