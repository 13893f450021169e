"""Parallel computation: an algorithm run side by side with the exact solution.

The simulator drives a rotation-vector algorithm (and, through its dual
extension, the matching apparent-velocity algorithm) with the exact
increments (2.1) of the regular precession (4.1) or its dual analogue
(4.2)–(4.3) — or of the classical sculling motion
(:class:`~strapdown.analysis.coning.sculling_motion.ScullingMotion`) — and
compares the computed attitude Λ and apparent velocity W_E, W_I with the
closed-form solution (1.5), (4.4)–(4.5) of Lebedev & Panov (1989).  This is the
"method of parallel computation" behind Table 3 of Budennyi, Kalinovsky, Panov
et al. and the table of Lebedev & Panov (1989).

Everything is vectorised: the increments of all steps come at once from the
motion's ``grid_increments``, cut into step windows by :func:`step_windows`
(one index array, :func:`window_index`), the algorithm is evaluated on a
``(..., steps, W, 3)`` array, and the attitude (or biquaternion) after every
step is an associative prefix product of the step quaternions
(:func:`prefix_product`), of depth ``log2(steps)``.  Leading axes batch over
parameter points.

Errors are exact minus algorithm (package docstring, "Errors"): the
attitude error is the rotation vector ``δφ_I = rotvec(Λ* ∘ Λ̄)`` of the error
rotation from the computed attitude Λ to the exact Λ*, resolved in frame I
(``Λ* = exp(δφ_I) ∘ Λ``), and the apparent-velocity errors are
``ΔW_E = W_E* − W_E`` (resolved in E) and ``ΔW_I = W_I* − W_I`` (in I).  The
drift is the least-squares slope of ``δφ_I``, a vector in frame I with the same
sign; the constant drift rate is its norm.

Cross-step algorithms (indices ≤ 0, :attr:`Algorithm.history` > 0) read
``history`` samples before each step; the windows of consecutive steps
overlap by that many rows.  For the first step those samples are the exact
increments before t = 0 of the same motion, so the run starts in steady state.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import budget
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_array, as_quaternion, as_vector, positive
from . import kernels
from .evaluation import increment
from .precession import RegularPrecession, exact_state, initial_biquaternion
from .sculling_motion import ScullingMotion

__all__ = [
    "SimulationResult",
    "step_count",
    "window_index",
    "step_windows",
    "sample_increments",
    "prefix_product",
    "drift_rate",
    "MOTIONS",
    "simulate",
]

@dataclass(frozen=True)
class SimulationResult:
    """Outcome of :func:`simulate` (leading axes: the batch of parameter points).

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm run.
    sample_interval : float
        Sample interval h [s].
    step : float
        Algorithm step H = N h [s].
    time : ndarray, shape (steps + 1,)
        Step ends t_k = k H [s], t_0 = 0.
    attitude_error : ndarray, shape (..., steps + 1, 3)
        Attitude error δφ_I, exact minus algorithm: the rotation vector
        ``rotvec(Λ_exact ∘ Λ̄_alg)`` of the error rotation, components in frame I
        (``Λ_exact = exp(δφ_I) ∘ Λ_alg``) [rad].
    drift : ndarray, shape (..., 3)
        Least-squares slope of ``attitude_error`` against time, frame I [rad/s]
        (exact minus algorithm).
    dw_body, dw_inertial : ndarray, shape (..., steps + 1, 3), or None
        ``ΔW_E = W_E* − W_E`` (components in E) and ``ΔW_I = W_I* − W_I``
        (components in I), exact minus algorithm [m/s] (velocity runs only).
    """

    algorithm: Algorithm
    sample_interval: float
    step: float
    time: np.ndarray
    attitude_error: np.ndarray
    drift: np.ndarray
    dw_body: np.ndarray | None = None
    dw_inertial: np.ndarray | None = None

    @property
    def steps(self) -> int:
        """Number of algorithm steps simulated."""
        return self.time.shape[0] - 1

    @property
    def duration(self) -> float:
        """Simulated time n H [s], the last step end."""
        return float(self.time[-1])

    @property
    def drift_rate(self) -> np.ndarray:
        """Constant drift rate ``|slope|`` of the attitude error [rad/s], shape ``(...)``."""
        return np.linalg.norm(self.drift, axis=-1)

    @property
    def periodic_error(self) -> np.ndarray:
        """Peak of the attitude error about its least-squares line, ``max_k |δφ_I(t_k) − a − drift t_k|`` [rad], shape ``(...)``.

        The periodic part of the error that the slope has to average out: when
        it is large against ``drift × duration`` a short run biases the slope
        (the bias falls as 1/duration² for a periodic error).
        """
        t = self.time
        tc = t - t.mean()
        line = self.attitude_error.mean(axis=-2)[..., None, :] + tc[:, None] * self.drift[..., None, :]
        return np.linalg.norm(self.attitude_error - line, axis=-1).max(axis=-1)

    @property
    def velocity_error_rate(self) -> np.ndarray:
        """Least-squares slope of ``dw_inertial`` against time, frame I [m/s²], shape ``(..., 3)``.

        Under a periodic motion this is the rectification error of the velocity
        algorithm: the constant rate at which the apparent-velocity error
        ``W_I* − W_I`` grows (exact minus algorithm, as
        :func:`strapdown.analysis.coning.sculling_motion.rectification_error`).
        """
        if self.dw_inertial is None:
            raise ValueError("Expected a velocity run for `velocity_error_rate`, got an attitude-only run (pass velocity=True)")
        return drift_rate(self.time, self.dw_inertial)

    @property
    def final_dw_body(self) -> np.ndarray:
        """``|ΔW_E|`` at the end of the run [m/s], shape ``(...)``."""
        return _final_norm(self.dw_body, "dw_body")

    @property
    def final_dw_inertial(self) -> np.ndarray:
        """``|ΔW_I|`` at the end of the run [m/s], shape ``(...)``."""
        return _final_norm(self.dw_inertial, "dw_inertial")


def _final_norm(values, name):
    if values is None:
        raise ValueError(f"Expected a velocity run for `{name}`, got an attitude-only run (pass velocity=True)")
    return np.linalg.norm(values[..., -1, :], axis=-1)


def step_count(sample_interval, duration, samples: int) -> int:
    """Number of whole algorithm steps ``H = N h`` in ``duration``.

    Parameters
    ----------
    sample_interval : float
        Sample interval h [s], > 0.
    duration : float
        Length of the run [s], at least one step.
    samples : int
        Samples N per step.

    Raises
    ------
    ValueError
        If h or the duration is not positive, or the duration is shorter than one step.

    Examples
    --------
    >>> step_count(0.01, 100.0, 4)
    2500
    """
    h = positive(sample_interval, "sample_interval")
    duration = positive(duration, "duration")
    step = samples * h
    # A relative tolerance lets 100 s / 0.04 s count 2500 steps despite round-off.
    n = math.floor(duration / step * (1.0 + 1e-12))
    if n < 1:
        raise ValueError(f"Expected `duration` >= one step H = {samples} × `sample_interval` = {samples} × {h:g} s = {step:g} s, got {duration:g}")
    return n


def window_index(steps: int, samples: int, history: int = 0, *, limits: budget.Limits | None = None) -> np.ndarray:
    """Rows of the step windows in a flat sequence of sample increments.

    Row ``r`` of the flat sequence is sample ``r − history`` counted from the
    first step's first sample (so rows ``0 … history − 1`` precede the first
    step).  Window k, the input of step k, is ``p_{1−history} … p_N`` of that
    step: rows ``k N … k N + history + N − 1``.  Consecutive windows overlap by
    ``history`` rows.  This one index array is the whole construction, shared
    by every evaluator (numpy here, compiled kernels elsewhere).

    Parameters
    ----------
    steps : int
        Number of algorithm steps.
    samples : int
        Samples N per step.
    history : int
        Samples before the step that the algorithm reads (:attr:`Algorithm.history`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray of int, shape (steps, history + samples)

    Raises
    ------
    ValueError
        If the index array would exceed ``limits`` (named by ``steps``).

    Examples
    --------
    >>> window_index(3, 2, 1)
    array([[0, 1, 2],
           [2, 3, 4],
           [4, 5, 6]])
    """
    budget.check(budget.arrays(float(steps) * (history + samples), what=f"`steps` = {steps:.3g} windows of {history + samples} rows"), limits)
    return np.arange(steps)[:, None] * samples + np.arange(history + samples)[None, :]


def step_windows(sequence, samples: int, history: int = 0):
    """Cut a flat sequence of increments into the overlapping windows of consecutive steps.

    Parameters
    ----------
    sequence : ndarray or Dual, shape (..., history + steps·N, 3)
        Sample increments, oldest first, beginning ``history`` samples before
        the first step.
    samples : int
        Samples N per step.
    history : int
        Samples before a step that the algorithm reads.

    Returns
    -------
    ndarray or Dual, shape (..., steps, history + N, 3)
        The windows :func:`strapdown.analysis.coning.evaluation.increment` takes.

    Raises
    ------
    ValueError
        If the sequence length is not ``history`` plus a positive multiple of N.
    """
    count = sequence.shape[-2] - history
    if count < samples or count % samples:
        raise ValueError(f"Expected `sequence` of history + k·N = {history} + k·{samples} rows (k >= 1), got {sequence.shape[-2]}")
    steps = count // samples
    if history == 0:
        return np.reshape(sequence, sequence.shape[:-2] + (steps, samples, 3))
    return sequence[..., window_index(steps, samples, history), :]


def sample_increments(motion, sample_interval: float, steps: int, samples: int, *, first_step: int = 0, dual: bool = False, history: int = 0, limits: budget.Limits | None = None):
    """Exact increments of every sample of ``steps`` consecutive steps, in step windows.

    Parameters
    ----------
    motion : RegularPrecession or ScullingMotion
        The motion (anything with ``grid_increments``).
    sample_interval : float
        Sample interval h [s].
    steps : int
        Number of algorithm steps.
    samples : int
        Samples N per step.
    first_step : int, keyword-only
        Index of the first step (it starts at ``first_step · N h``).
    dual : bool, keyword-only
        Return ``q = p + s b`` (``b`` in m/s) instead of ``p`` alone.
    history : int, keyword-only
        Samples before each step that the window also holds (cross-step
        algorithms).  Before t = 0 they come from the exact motion, so a run
        starts in steady state.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray or Dual, shape (steps, history + samples, 3)
        Row ``history + j − 1`` of window k is ``p_j`` (or ``q_j``) of step k, over
        ``[((k N + j − 1) h, (k N + j) h]``, j = 1 − history … N.

    Raises
    ------
    ValueError
        If the increments would exceed ``limits`` (named by ``steps``).
    """
    rows = float(steps) * (samples + history)
    budget.check(budget.arrays(3.0 * rows, what=f"`steps` = {steps:.3g} steps of {samples + history} samples", copies=24.0 if dual else 12.0), limits)
    inc = motion.grid_increments(sample_interval, first_step * samples - history, steps * samples + history, dual=dual, limits=limits)
    return step_windows(inc, samples, history)


_qmul = quat.multiply_parts


def _scan(q):
    """Inclusive prefix products along the last axis of 4-tuples of ``(..., n)`` arrays."""
    n = q[0].shape[-1]
    if n == 1:
        return q
    if n % 2:
        q = tuple(np.concatenate([c, np.full(c.shape[:-1] + (1,), float(k == 0))], axis=-1) for k, c in enumerate(q))
    lead = q[0].shape[:-1]
    odd = _scan(_qmul(tuple(c[..., 0::2] for c in q), tuple(c[..., 1::2] for c in q)))  # c_{2i+1}
    even = _qmul(tuple(c[..., :-1] for c in odd), tuple(c[..., 2::2] for c in q))  # c_{2i}, i ≥ 1
    out = []
    for k in range(4):
        if isinstance(q[k], np.ndarray):
            # interleave by slice assignment: the values of the stack below, without its two temporaries
            c = np.empty(lead + (2 * odd[k].shape[-1],), dtype=np.result_type(q[k], even[k], odd[k]))
            c[..., :1] = q[k][..., :1]
            c[..., 2::2] = even[k]
            c[..., 1::2] = odd[k]
            out.append(c[..., :n])
            continue
        e = np.concatenate([q[k][..., :1], even[k]], axis=-1)
        out.append(np.reshape(np.stack([e, odd[k]], axis=-1), lead + (2 * odd[k].shape[-1],))[..., :n])
    return tuple(out)


def prefix_product(q):
    """Inclusive prefix products ``c_k = q_0 ∘ q_1 ∘ … ∘ q_k`` along axis −2.

    A work-efficient associative scan: adjacent pairs are multiplied, the
    half-length sequence is scanned recursively, and the even positions are
    filled in from it.  Depth ``O(log n)``, work ``O(n)`` quaternion products,
    and no Python loop over the n elements.  Works on quaternions and on
    biquaternions (:class:`~strapdown.analysis.core.dual.Dual`).

    Parameters
    ----------
    q : ndarray or Dual, shape (..., n, 4)
        Quaternions in the order they are applied (each on the right).

    Returns
    -------
    ndarray or Dual, shape (..., n, 4)

    Examples
    --------
    >>> q = quat.rotvec_to_quat(np.array([[0.1, 0, 0], [0, 0.2, 0], [0, 0, 0.3]]))
    >>> c = prefix_product(q)
    >>> bool(np.allclose(c[2], quat.multiply(quat.multiply(q[0], q[1]), q[2])))
    True
    """
    if not isinstance(q, Dual):
        q = np.asarray(q, dtype=float)
    if q.ndim < 2 or q.shape[-1] != 4 or q.shape[-2] < 1:
        raise ValueError(f"Expected `q` with shape (..., n, 4), n >= 1, got shape {q.shape}")
    return np.stack(_scan(tuple(q[..., k] for k in range(4))), axis=-1)


def drift_rate(time, error):
    """Least-squares slope of ``error`` against ``time`` (the constant drift).

    Parameters
    ----------
    time : ndarray, shape (n,)
        Times [s].
    error : ndarray, shape (..., n, 3)
        Error rotation vectors [rad].

    Returns
    -------
    ndarray, shape (..., 3)
        Slope [rad/s].

    Raises
    ------
    ValueError
        For fewer than two times, or times that are all equal.
    """
    t = as_array(time, "time")
    if t.ndim != 1 or t.size < 2 or t.min() == t.max():
        raise ValueError(f"Expected `time` with at least two distinct times, got shape {t.shape}")
    tc = t - t.mean()
    return np.einsum("k,...kj->...j", tc, error) / np.dot(tc, tc)


#: Motions with a closed-form solution that the simulator can drive.
MOTIONS = (RegularPrecession, ScullingMotion)


def _as_motions(motion):
    if isinstance(motion, MOTIONS):
        return [motion], False
    motions = list(motion) if isinstance(motion, (Sequence, np.ndarray)) else None
    if not motions or not all(isinstance(m, MOTIONS) for m in motions):
        raise TypeError(f"Expected `motion` to be a RegularPrecession or ScullingMotion, or a non-empty sequence of them, got {type(motion).__name__}")
    return motions, True


#: Work is cut into chunks of at most ``CHUNK_STEPS`` algorithm steps (batch
#: points × steps) and ``TIME_CHUNK`` consecutive steps, so that the working set
#: stays small; the attitude is carried from one time chunk to the next.  The
#: chunking sets how the work is cut, not the result.
CHUNK_STEPS = 65536
TIME_CHUNK = 16384


def simulate(
    algorithm: Algorithm,
    motion,
    sample_interval,
    duration,
    *,
    attitude0=(1.0, 0.0, 0.0, 0.0),
    w_inertial0=(0.0, 0.0, 0.0),
    velocity: bool = False,
    engine: str = "auto",
    limits: budget.Limits | None = None,
) -> SimulationResult:
    """Run ``algorithm`` against the exact solution of ``motion`` ("parallel computation").

    The attitude after step k is ``Λ_k = Λ_0 ∘ Λ(Δφ_1) ∘ … ∘ Λ(Δφ_k)`` with
    ``Δφ`` from :func:`strapdown.analysis.coning.evaluation.increment`.  With ``velocity`` the
    same runs on dual numbers: ``ΔΦ = Δφ + s Δφ°`` from the dual increments
    ``q = p + s b`` (Lebedev & Panov 1989, eq. (2.5)), the biquaternion step
    ``ϑ_k`` from ``ΔΦ`` by (1.12), ``θ_k = θ_0 ∘ ϑ_1 ∘ … ∘ ϑ_k``, and
    ``W_E = 2 vect(Λ̄ ∘ M)``, ``W_I = 2 vect(M ∘ Λ̄)`` (1.3), which is the
    recursion (2.6) in closed form.  The exact solution is the general
    solution (1.5) ``θ = C ∘ P(t)`` through the same initial state.

    Parameters
    ----------
    algorithm : Algorithm
        The rotation-vector algorithm (its dual extension for velocity).
    motion : RegularPrecession, ScullingMotion, or a sequence of them
        The motion (4.1) or its dual analogue (4.2), or classical sculling; a
        sequence is a batch of parameter points and adds a leading axis to
        every result.
    sample_interval : float
        Sample interval h [s], > 0.
    duration : float
        Length of the run [s]; the run covers ``floor(duration / H)`` whole steps.
    attitude0 : array_like, shape (4,), keyword-only
        Initial attitude Λ(0), unit quaternion (E → I).
    w_inertial0 : array_like, shape (3,), keyword-only
        Initial apparent velocity W_I(0) [m/s] (velocity runs).
    velocity : bool, keyword-only
        Also integrate the apparent velocity (biquaternion run).
    engine : {"auto", "numpy", "compiled"}, keyword-only
        ``"numpy"``: the vectorised path below (the reference);
        ``"compiled"``: the fused kernel of :mod:`strapdown.analysis.coning.kernels`
        (same results to round-off); ``"auto"``: compiled when numba is
        available, the motion is a :class:`RegularPrecession`, and the kernel
        pays (:func:`strapdown.analysis.coning.kernels.use_compiled`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    SimulationResult
        Errors exact minus algorithm: ``δφ_I = rotvec(Λ_exact ∘ Λ̄_alg)`` in
        frame I, ``ΔW_E = W_E* − W_E``, ``ΔW_I = W_I* − W_I``.

    Raises
    ------
    ValueError
        Non-positive step or duration, a duration shorter than one step, a
        non-unit ``attitude0``, an unknown ``engine``, or a run whose estimated
        memory or time exceeds ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration``).
    ImportError
        ``engine="compiled"`` without numba.
    TypeError
        If ``algorithm`` is not an :class:`Algorithm` or ``motion`` is not a
        :class:`RegularPrecession` or :class:`ScullingMotion` (or a sequence of them).

    References
    ----------
    Lebedev & Panov (1989), eqs. (1.3), (1.5), (1.12), (2.1)–(2.6), (4.1)–(4.5);
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3 ("parallel computation").

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> m = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))
    >>> r = simulate(get("panov-4s-1"), m, 0.0025, 1.0)
    >>> r.steps, round(float(r.drift_rate) * 180 / np.pi * 3600, 2)   # deg/h
    (100, 2.47)
    >>> cone_axis = -np.array([0.0, np.sin(np.radians(1.0)), np.cos(np.radians(1.0))])   # −n, frame I
    >>> bool(r.drift @ cone_axis > 0)   # exact minus algorithm: the computed attitude lags the coning
    True
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    motions, batched = _as_motions(motion)
    h = positive(sample_interval, "sample_interval")
    n_samples = algorithm.samples
    steps = step_count(h, duration, n_samples)
    degree_sum = sum(t.degree for t in algorithm.terms)
    runs = f"{len(motions)} runs of " if batched else ""
    what = f"`duration` = {float(duration):.3g} s over `sample_interval` = {h:g} s ({runs}{steps:.3g} steps of {n_samples} samples)"
    chunk = CHUNK_STEPS if batched else TIME_CHUNK
    budget.check(budget.coning_simulation(len(motions) * steps, window=algorithm.window, degree_sum=degree_sum, velocity=velocity, chunk_steps=chunk, what=what), limits)
    lam0 = as_quaternion(attitude0, "attitude0", unit=True)
    w0 = as_vector(w_inertial0, "w_inertial0")
    if lam0.shape != (4,) or w0.shape != (3,):
        raise ValueError(f"Expected `attitude0` of shape (4,) and `w_inertial0` of shape (3,), got {lam0.shape} and {w0.shape}")
    step = n_samples * h
    time = np.arange(steps + 1) * step
    theta0 = initial_biquaternion(lam0, w0) if velocity else lam0
    supported = all(type(m) is RegularPrecession for m in motions)
    if kernels.use_compiled(engine, supported=supported, algorithm=algorithm, work=len(motions) * steps):
        error, dw_body, dw_inertial = kernels.compiled_series(algorithm, motions, h, steps, lam0, w0, velocity=velocity)
        if not batched:
            error, dw_body, dw_inertial = (None if a is None else a[0] for a in (error, dw_body, dw_inertial))
        return SimulationResult(algorithm, h, step, time, error, drift_rate(time, error), dw_body, dw_inertial)

    count = len(motions)
    error = np.empty((count, steps + 1, 3))
    dw = np.empty((2, count, steps + 1, 3)) if velocity else None
    group = max(1, CHUNK_STEPS // steps)
    chunk = min(steps, TIME_CHUNK)
    for g0 in range(0, count, group):
        ms = motions[g0 : g0 + group]
        rows = slice(g0, g0 + len(ms))
        carry = tuple(np.broadcast_to(theta0[..., k], (len(ms), 1)) for k in range(4))
        _compare(carry, ms, time[:1], lam0, w0, error[rows, :1], None if dw is None else dw[:, rows, :1])
        for k0 in range(0, steps, chunk):
            k1 = min(steps, k0 + chunk)
            inc = np.stack([sample_increments(m, h, k1 - k0, n_samples, first_step=k0, dual=velocity, history=algorithm.history) for m in ms])
            step_q = quat.rotvec_to_quat(increment(algorithm, inc), validate=False)
            theta = _qmul(carry, _scan(tuple(step_q[..., k] for k in range(4))))
            carry = tuple(c[:, -1:] for c in theta)
            span = slice(k0 + 1, k1 + 1)
            _compare(theta, ms, time[span], lam0, w0, error[rows, span], None if dw is None else dw[:, rows, span])
    if not batched:
        error = error[0]
        dw = None if dw is None else dw[:, 0]
    drift = drift_rate(time, error)
    return SimulationResult(algorithm, h, step, time, error, drift, None if dw is None else dw[0], None if dw is None else dw[1])


def _compare(theta, motions, time, lam0, w0, error_out, dw_out) -> None:
    """Write the errors of the computed ``theta`` against the exact state, exact minus algorithm.

    ``δφ_I = rotvec(Λ* ∘ Λ̄)``, ``ΔW_E = W_E* − W_E``, ``ΔW_I = W_I* − W_I``.
    """
    velocity = dw_out is not None
    if velocity:
        exact = [exact_state(m, time, lam0, w0) for m in motions]
        lam_true = np.stack([e.attitude for e in exact])
        lam = tuple(c.re for c in theta)
    else:
        lam_true = np.stack([_exact_attitude(m, time, lam0) for m in motions])
        lam = theta
    conj_true = (lam_true[..., 0], -lam_true[..., 1], -lam_true[..., 2], -lam_true[..., 3])
    # Λ* ∘ Λ̄ is the conjugate of Λ ∘ Λ̄*, so rotvec(Λ* ∘ Λ̄) = −rotvec(Λ ∘ Λ̄*), exactly in
    # floating point as well (the compiled kernels form it the same way).
    error_out[...] = -quat.quat_to_rotvec(np.stack(_qmul(lam, conj_true), axis=-1), canonical=True, validate=False)
    if velocity:
        m = tuple(c.du for c in theta)
        lam_bar = (lam[0], -lam[1], -lam[2], -lam[3])
        w_body = _qmul(lam_bar, m)[1:]
        w_inertial = _qmul(m, lam_bar)[1:]
        dw_out[0] = np.stack([e.w_body for e in exact]) - 2.0 * np.stack(w_body, axis=-1)
        dw_out[1] = np.stack([e.w_inertial for e in exact]) - 2.0 * np.stack(w_inertial, axis=-1)


def _exact_attitude(motion, time, lam0):
    """Λ(t) = C ∘ Q(t) with C = Λ(0) ∘ Q̄(0): the general solution (1.8)."""
    c = quat.multiply(lam0, quat.conjugate(motion.attitude(0.0)))
    return quat.multiply(c, motion.attitude(time))
