"""Independent checks of the vibration drift by simulation: a DOP853 reference and a Monte Carlo.

Neither check uses the closed form of :mod:`strapdown.analysis.vibration.drift`
nor its frequency responses: the truth is built from the kinematics, the
analog filters are integrated in continuous time from their state-space form,
the digital filters run on the samples, and the algorithm runs on what comes
out.

:func:`filtered_coning_check` — one classical coning line, high accuracy
    The state ``(Λ_true, Λ_sensed, filter states, ∫y dt)`` is integrated by
    DOP853 (rtol 1e-13) from the exact body rate of the cone,
    ``ω = (sin α/α) θ̇ − (1 − cos α) ψ̇ w``: ``2Λ̇_true = Λ_true ∘ ω``, the
    analog filters ``ẋ = A x + B ω``, ``y = C x + D ω`` (``scipy.signal.tf2ss``),
    ``2Λ̇_sensed = Λ_sensed ∘ y`` and the increments ``∫ y dt``.  After the
    filters' transient has died out (e^{−40}), the attitude error is sampled
    at whole coning periods, where the periodic steady state repeats, so its
    growth per period is the drift exactly: ``Λ_true ∘ Λ̄_sensed`` gives the
    pseudo-coning, ``Λ_true ∘ Λ̄_computed`` (the algorithm run on the
    increments, after the digital filters and the decimation) the total.

:func:`monte_carlo_drift` — lines and spectra, by realisations
    See :mod:`strapdown.analysis.vibration.monte_carlo`.

Public API
----------
.. autosummary::

   FilteredConingCheck
   filtered_coning_check
   cone_rate

References
----------
Savage (1998), part 1 (pseudo-coning); Hairer, Nørsett & Wanner (1993), DOP853.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import signal
from scipy.integrate import solve_ivp

from ...derivations.coning.algorithms import Algorithm
from ..coning.evaluation import increment
from ..coning.simulator import step_windows
from ..core import budget
from ..core import quaternion as quat
from ..core.validation import as_int, in_open_interval, positive
from .environment import orthonormal_pair, unit_vector
from .sensor_dynamics import Sensor

__all__ = ["FilteredConingCheck", "filtered_coning_check", "cone_rate"]


def cone_rate(t, half_angle: float, omega: float, axis, phase: float = 0.0) -> np.ndarray:
    """Exact body rate of classical coning about ``axis`` (positive sense), shape ``t.shape + (3,)`` [rad/s].

    The attitude is ``Λ = exp(θ)``, ``θ = α (cos ψ u + sin ψ v)``, ψ = ωt + phase,
    ``(u, v, axis)`` right-handed; with ``|θ| = α`` constant and ``θ̇ ⟂ θ`` the
    right Jacobian gives ``ω = (sin α/α) θ̇ − (1 − cos α) ψ̇ w`` exactly.

    Parameters
    ----------
    t : array_like
        Times [s].
    half_angle : float
        α [rad].
    omega : float
        Coning rate ψ̇ [rad/s].
    axis : sequence of three float
        Cone axis w (normalised).
    phase : float
        ψ at t = 0 [rad].

    Returns
    -------
    ndarray
    """
    w = unit_vector(axis, "axis")
    u, v = orthonormal_pair(w)
    psi = omega * np.asarray(t, dtype=float)[..., None] + phase
    return omega * math.sin(half_angle) * (-np.sin(psi) * u + np.cos(psi) * v) - (1.0 - math.cos(half_angle)) * omega * w


def cone_attitude(t, half_angle: float, omega: float, axis, phase: float = 0.0) -> np.ndarray:
    """``Λ(t) = exp(θ(t))`` of :func:`cone_rate` (for checks), shape ``t.shape + (4,)``.

    Parameters
    ----------
    t : array_like
        Times [s].
    half_angle, omega, axis, phase
        As :func:`cone_rate`.

    Returns
    -------
    ndarray
    """
    w = unit_vector(axis, "axis")
    u, v = orthonormal_pair(w)
    psi = omega * np.asarray(t, dtype=float)[..., None] + phase
    return quat.rotvec_to_quat(half_angle * (np.cos(psi) * u + np.sin(psi) * v))


def _block_state_space(sensor: Sensor):
    """Block-diagonal (A, B, C, D) of the three analog filters, inputs and outputs the three axes."""
    blocks = [a.analog.state_space() for a in sensor.axes]
    n = sum(b[0].shape[0] for b in blocks)
    A, B, C, D = np.zeros((n, n)), np.zeros((n, 3)), np.zeros((3, n)), np.zeros(3)
    k = 0
    for axis, (a, b, c, d) in enumerate(blocks):
        m = a.shape[0]
        A[k : k + m, k : k + m] = a
        B[k : k + m, axis] = b[:, 0]
        C[axis, k : k + m] = c[0]
        D[axis] = d[0, 0]
        k += m
    return A, B, C, D


def _qmul(a, b):
    return np.array([
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ])  # fmt: skip


@dataclass(frozen=True)
class FilteredConingCheck:
    """Drift of a classical coning line through sensor filters, by DOP853 simulation.

    Attributes
    ----------
    sensor_drift : float
        Pseudo-coning: slope of ``Λ_true ∘ Λ̄_sensed`` along the cone axis [rad/s].
    total_drift : float
        Slope of ``Λ_true ∘ Λ̄_computed`` along the cone axis [rad/s].
    algorithm_drift : float
        ``total_drift − sensor_drift`` [rad/s].
    periods : int
        Coning periods measured [count].
    warmup : float
        Time left to the filters' transient before the measurement [s].
    """

    sensor_drift: float
    total_drift: float
    algorithm_drift: float
    periods: int
    warmup: float


def _warmup_time(gyro: Sensor, period: float, sample_interval: float) -> float:
    """Whole periods covering e^{−40} of every analog and digital transient."""
    rates = [a.analog.slowest_rate for a in gyro.axes]
    t = max((40.0 / r for r in rates if math.isfinite(r)), default=0.0)
    hs = sample_interval / gyro.decimation
    for a in gyro.axes:
        _, den = a.digital.coefficients(hs)
        if len(den) > 1:
            r = float(np.max(np.abs(np.roots(den))))
            if r > 0:
                t = max(t, 40.0 / -math.log(r) * hs)
        t = max(t, 2 * len(a.digital.coefficients(hs)[0]) * hs)
    return period * max(1, math.ceil(t / period))


def filtered_coning_check(algorithm: Algorithm, gyro: Sensor, sample_interval: float, *, freq_hz: float, half_angle: float, axis=(0.0, 0.0, 1.0),
                          periods: int = 4, rtol: float = 1e-13, limits: budget.Limits | None = None) -> FilteredConingCheck:  # fmt: skip
    """Simulate classical coning seen through ``gyro`` and run ``algorithm`` on it (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (cross-step indices allowed).
    gyro : Sensor
        Gyro filters (analog per axis, digital, decimation).
    sample_interval : float
        Algorithm sample interval h [s]; the coning period must be a whole
        number of steps N h.
    freq_hz : float, keyword-only
        Coning frequency f [Hz].
    half_angle : float, keyword-only
        Half-cone angle α [rad], in (0, π/4).
    axis : sequence of three float, keyword-only
        Cone axis (default +z).
    periods : int, keyword-only
        Periods measured after the warm-up [count], ≥ 1.
    rtol : float, keyword-only
        Relative tolerance of DOP853 (absolute tolerance ``rtol`` × 1e-3).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    FilteredConingCheck

    Raises
    ------
    ValueError
        A period that is not a whole number of steps, bad parameters, or a
        run beyond ``limits`` (:class:`~strapdown.analysis.core.budget.BudgetExceeded`,
        naming ``periods``).
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(gyro, Sensor):
        raise TypeError(f"Expected `gyro` to be a Sensor, got {type(gyro).__name__}")
    h = positive(sample_interval, "sample_interval")
    f = positive(freq_hz, "freq_hz")
    alpha = in_open_interval(half_angle, "half_angle", 0.0, math.pi / 4)
    periods = as_int(periods, "periods", minimum=1)
    period = 1.0 / f
    step = algorithm.samples * h
    per_period = period / step
    if abs(per_period - round(per_period)) > 1e-9 * per_period:
        raise ValueError(f"Expected the coning period {period:g} s to be a whole number of steps H = {step:g} s, got {per_period:.6g}")
    per_period = int(round(per_period))
    w = unit_vector(axis, "axis")
    omega = 2.0 * math.pi * f
    M = gyro.decimation
    hs = h / M
    warm = _warmup_time(gyro, period, h)
    history_time = algorithm.history * h
    start = warm + history_time
    start = period * math.ceil(start / period)  # measurement starts at a whole period
    first_sample = int(round((start - history_time) / hs))  # sensor sample where the algorithm's window begins
    n_sensor = int(round((start + periods * period) / hs))
    what = f"`periods` = {periods:.3g} coning periods after a warm-up of {start:.3g} s ({n_sensor:.3g} sensor samples at `sample_interval` = {h:g} s)"
    work = max(float(n_sensor), 16.0 * (start / period + periods))  # DOP853 takes at least 16 steps per period
    budget.check(budget.FILTERED_CONING_SAMPLE.estimate(work, what=what), limits)
    A, B, C, D = _block_state_space(gyro)
    n = A.shape[0]

    def rhs(t, y):
        om = cone_rate(t, alpha, omega, w)
        x = y[8 : 8 + n]
        out = C @ x + D * om
        dq = 0.5 * _qmul(y[0:4], np.concatenate([[0.0], om]))
        dm = 0.5 * _qmul(y[4:8], np.concatenate([[0.0], out]))
        return np.concatenate([dq, dm, A @ x + B @ om, out])

    q0 = cone_attitude(0.0, alpha, omega, w)
    y0 = np.concatenate([q0, q0, np.zeros(n), np.zeros(3)])
    times = np.arange(n_sensor + 1) * hs
    sol = solve_ivp(rhs, (0.0, times[-1]), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-3, t_eval=times, max_step=period / 16)
    if not sol.success:
        raise ValueError(f"DOP853 failed: {sol.message}")
    y = sol.y.T
    q_true, q_sensed, integral = y[:, 0:4], y[:, 4:8], y[:, 8 + n :]
    inc = np.diff(integral, axis=0)  # sensor increments
    for k, a in enumerate(gyro.axes):
        b, den = a.digital.coefficients(hs)
        if len(b) > 1 or len(den) > 1:
            inc[:, k] = signal.lfilter(b, den, inc[:, k])
    inc = inc[first_sample:]
    inc = inc[: (inc.shape[0] // M) * M].reshape(-1, M, 3).sum(axis=1)
    steps = periods * per_period
    inc = inc[: algorithm.history + steps * algorithm.samples]
    dphi = increment(algorithm, step_windows(inc, algorithm.samples, algorithm.history))
    step_q = quat.rotvec_to_quat(dphi)
    idx_start = int(round(start / hs))
    q = q_true[idx_start] / np.linalg.norm(q_true[idx_start])
    computed = [q]
    for k in range(steps):
        q = _qmul(q, step_q[k])
        computed.append(q)
    computed = np.array(computed)[::per_period]
    at = idx_start + np.arange(periods + 1) * per_period * algorithm.samples * M
    t = at * hs

    def slope(qa, qb):
        e = quat.quat_to_rotvec(quat.multiply(qa, quat.conjugate(qb))) @ w
        return float(np.polyfit(t, e, 1)[0])

    s_sensed = slope(q_true[at], q_sensed[at])
    # the sensed attitude started with the filter's transient: measure its growth only (slope over whole periods)
    s_total = slope(q_true[at], computed)
    return FilteredConingCheck(s_sensed, s_total, s_total - s_sensed, periods, start)
