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

:func:`line_drift_check` — any deterministic lines, aliasing pairs included
    The body rate and specific force are the lines themselves,
    ``ω(t) = Σ Re(A_k e^{iω_k t})``, ``f(t) = Σ Re(B_k e^{iω_k t})``; DOP853
    integrates the true attitude ``2Λ̇ = Λ ∘ ω``, the true apparent velocity
    ``Ẇ_I = Λ ∘ f ∘ Λ̄``, the analog filters of the six channels and the
    integrals of their outputs.  The digital filters and the decimation run on
    the samples, the algorithm (and, for the velocity, its dual extension and
    the biquaternion product) on the result, from a step that begins at a
    whole common period of the lines and the step clock, so the lines' phases
    relative to the clock are those of t = 0.  The errors
    ``rotvec(Λ_true ∘ Λ̄_computed)`` and ``W_I,true − W_I,computed`` are
    sampled at whole common periods, where their bounded oscillation repeats:
    their slopes are the mean drift and rectification error exactly, cross
    terms of aliasing pairs included, with nothing taken from the closed form
    (no response function, no coning vector, no aliasing condition).

:func:`monte_carlo_drift` — lines and spectra, by realisations
    See :mod:`strapdown.analysis.vibration.monte_carlo`.

Public API
----------
.. autosummary::

   FilteredConingCheck
   filtered_coning_check
   LineDriftCheck
   line_drift_check
   common_period
   cone_rate

References
----------
Savage (1998), part 1 (pseudo-coning); Hairer, Nørsett & Wanner (1993), DOP853.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from scipy import signal
from scipy.integrate import solve_ivp

from ...derivations.coning.algorithms import Algorithm
from ..coning.evaluation import increment
from ..coning.simulator import step_windows
from ..core import budget
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.validation import as_int, in_open_interval, positive
from .environment import Environment, orthonormal_pair, unit_vector
from .sensor_dynamics import Sensor

__all__ = ["FilteredConingCheck", "filtered_coning_check", "LineDriftCheck", "line_drift_check", "common_period", "cone_rate"]


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


def _half_products(q, a, b, out) -> None:
    """``out[0:4] = ½ q[0:4] ∘ (0, a)`` and ``out[4:8] = ½ q[4:8] ∘ (0, b)``: :func:`_qmul`'s operations, on Python floats.

    The same IEEE double operations in the same order as :func:`_qmul` on the
    arrays (hence the same bits), without a numpy call per product.
    """
    p0, p1, p2, p3, r0, r1, r2, r3 = q.tolist()
    a0, a1, a2 = a.tolist()
    b0, b1, b2 = b.tolist()
    out[0:8] = (
        0.5 * (p0 * 0.0 - p1 * a0 - p2 * a1 - p3 * a2),
        0.5 * (p0 * a0 + p1 * 0.0 + p2 * a2 - p3 * a1),
        0.5 * (p0 * a1 - p1 * a2 + p2 * 0.0 + p3 * a0),
        0.5 * (p0 * a2 + p1 * a1 - p2 * a0 + p3 * 0.0),
        0.5 * (r0 * 0.0 - r1 * b0 - r2 * b1 - r3 * b2),
        0.5 * (r0 * b0 + r1 * 0.0 + r2 * b2 - r3 * b1),
        0.5 * (r0 * b1 - r1 * b2 + r2 * 0.0 + r3 * b0),
        0.5 * (r0 * b2 + r1 * b1 - r2 * b0 + r3 * 0.0),
    )  # fmt: skip


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
    # cone_rate's constants, computed once (the same operations per call: the same bits)
    cw = unit_vector(w, "axis")
    cu, cv = orthonormal_pair(cw)
    rate_scale = omega * math.sin(alpha)
    drift_rate = (1.0 - math.cos(alpha)) * omega * cw

    cu0, cu1, cu2 = cu.tolist()
    cv0, cv1, cv2 = cv.tolist()
    dr0, dr1, dr2 = drift_rate.tolist()

    def rhs(t, y):
        # cone_rate on a float: its operations in its order, without a numpy call per component
        psi = omega * float(t) + 0.0
        s, c = -math.sin(psi), math.cos(psi)
        om = np.array([rate_scale * (s * cu0 + c * cv0) - dr0, rate_scale * (s * cu1 + c * cv1) - dr1, rate_scale * (s * cu2 + c * cv2) - dr2])
        x = y[8 : 8 + n]
        out = C @ x + D * om
        dy = np.empty(y.shape)
        _half_products(y[0:8], om, out, dy)
        dy[8 : 8 + n] = A @ x + B @ om
        dy[8 + n :] = out
        return dy

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


# --------------------------------------------------------------------------- any lines
#: Largest common period :func:`common_period` accepts [s].
MAX_COMMON_PERIOD = 100.0


def common_period(frequencies, step: float, *, max_period: float = MAX_COMMON_PERIOD) -> float:
    """Smallest time that is a whole number of periods of every frequency and of the step ``H``.

    The frequencies and the step rate are read as rationals (denominators up to
    10⁶, exactly to 10⁻¹² relative); the period is ``1/gcd`` of them.

    Parameters
    ----------
    frequencies : sequence of float
        Line frequencies [Hz], > 0.
    step : float
        Step H [s], > 0.
    max_period : float, keyword-only
        Largest period accepted [s].

    Returns
    -------
    float
        The common period [s].

    Raises
    ------
    ValueError
        A frequency or step rate that is not such a rational, or a common
        period above ``max_period``.

    Examples
    --------
    >>> common_period([60.0, 140.0], 1 / 200)
    0.05
    """
    rates = [positive(f, "frequencies") for f in frequencies] + [1.0 / positive(step, "step")]
    fracs = []
    for r in rates:
        fr = Fraction(r).limit_denominator(10**6)
        if abs(float(fr) - r) > 1e-12 * r:
            raise ValueError(f"Expected frequencies and a step rate with a common period, got {r!r} Hz, not a ratio of whole numbers up to 10⁶")
        fracs.append(fr)
    num, den = 0, 1
    for fr in fracs:  # gcd of rationals a/b, c/d: gcd(a d, c b) / (b d)
        num, den = math.gcd(num * fr.denominator, fr.numerator * den), den * fr.denominator
        g = math.gcd(num, den)
        num, den = num // g, den // g
    period = den / num
    if period > max_period:
        raise ValueError(f"Expected a common period of the lines and the step of at most {max_period:g} s, got {period:g} s")
    return period


@dataclass(frozen=True, eq=False)
class LineDriftCheck:
    """Mean drift of deterministic lines through the sensors, by DOP853 simulation.

    Attributes
    ----------
    drift : ndarray (3,)
        Slope of ``rotvec(Λ_true ∘ Λ̄_computed)`` [rad/s] (frame I = body axes to this order).
    sculling : ndarray (3,) or None
        Slope of ``W_I,true − W_I,computed`` [m/s²] (None without ``velocity``).
    period : float
        Common period of the lines and the step clock [s].
    periods : int
        Common periods measured [count].
    warmup : float
        Time before the measurement, a whole number of common periods [s].
    """

    drift: np.ndarray
    sculling: np.ndarray | None
    period: float
    periods: int
    warmup: float


def _six_channel_state_space(environment: Environment):
    g = _block_state_space(environment.gyro)
    a = _block_state_space(environment.accelerometer)
    ng, na = g[0].shape[0], a[0].shape[0]
    A = np.zeros((ng + na, ng + na))
    B = np.zeros((ng + na, 6))
    C = np.zeros((6, ng + na))
    A[:ng, :ng], A[ng:, ng:] = g[0], a[0]
    B[:ng, :3], B[ng:, 3:] = g[1], a[1]
    C[:3, :ng], C[3:, ng:] = g[2], a[2]
    return A, B, C, np.concatenate([g[3], a[3]])


def line_drift_check(algorithm: Algorithm, environment: Environment, sample_interval: float, *, periods: int = 4, velocity: bool = False,
                     rtol: float = 1e-12, limits: budget.Limits | None = None) -> LineDriftCheck:  # fmt: skip
    """Run ``algorithm`` on the lines of ``environment`` seen through its sensors, against DOP853 (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (cross-step indices allowed; its dual extension for the velocity).
    environment : Environment
        Lines (no spectra), sensors and decimation.
    sample_interval : float
        Algorithm sample interval h [s], > 0; the lines and the step ``N h``
        must have a common period (:func:`common_period`).
    periods : int, keyword-only
        Common periods measured after the warm-up [count], ≥ 1.
    velocity : bool, keyword-only
        Also the apparent velocity (the rectification error).
    rtol : float, keyword-only
        Relative tolerance of DOP853 (absolute tolerance ``rtol`` × 1e-3).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    LineDriftCheck

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm or ``environment`` not an Environment.
    ValueError
        An environment with spectra or without lines, no common period, bad
        parameters, or a run beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``periods``).

    References
    ----------
    Hairer, Nørsett & Wanner (1993), DOP853; Lebedev & Panov (1989), eqs. (1.3), (1.12), (2.5).
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    if environment.spectra or not environment.lines:
        raise ValueError(f"Expected an environment of lines only, got {len(environment.lines)} lines and {len(environment.spectra)} spectra")
    h = positive(sample_interval, "sample_interval")
    periods = as_int(periods, "periods", minimum=1)
    N, M = algorithm.samples, environment.decimation
    hs = h / M
    step = N * h
    freq = np.array([ln.frequency for ln in environment.lines])
    amp = np.stack([ln.amplitude for ln in environment.lines])
    period = common_period(freq, step)
    steps_per_period = int(round(period / step))
    warm = max(_warmup_time(environment.gyro, period, h), _warmup_time(environment.accelerometer, period, h))
    start = period * math.ceil((warm + algorithm.history * h) / period)
    n_sensor = int(round((start + periods * period) / hs))
    what = f"`periods` = {periods:.3g} common periods of {period:.3g} s after a warm-up of {start:.3g} s ({n_sensor:.3g} sensor samples at `sample_interval` = {h:g} s)"
    work = max(float(n_sensor), 16.0 * float(np.max(freq)) * (start + periods * period))
    budget.check(budget.FILTERED_CONING_SAMPLE.estimate(work, what=what), limits)
    A, B, C, D = _six_channel_state_space(environment)
    n = A.shape[0]
    omega = 2.0 * math.pi * freq

    def inputs(t):
        return np.real(amp.T @ np.exp(1j * omega * t))  # (6,): body rate, specific force

    def rhs(t, y):
        u = inputs(t)
        lam = y[0:4]
        x = y[7 : 7 + n]
        out = C @ x + D * u
        dq = 0.5 * _qmul(lam, np.concatenate([[0.0], u[:3]]))
        conj = lam * np.array([1.0, -1.0, -1.0, -1.0])
        dw = _qmul(_qmul(lam, np.concatenate([[0.0], u[3:]])), conj)[1:]
        return np.concatenate([dq, dw, A @ x + B @ u, out])

    y0 = np.concatenate([[1.0, 0.0, 0.0, 0.0], np.zeros(3 + n + 6)])
    times = np.arange(n_sensor + 1) * hs
    sol = solve_ivp(rhs, (0.0, times[-1]), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-3, t_eval=times, max_step=1.0 / (16.0 * float(np.max(freq))))
    if not sol.success:
        raise ValueError(f"DOP853 failed: {sol.message}")
    y = sol.y.T
    lam_true, w_true, integral = y[:, 0:4], y[:, 4:7], y[:, 7 + n :]
    inc = np.diff(integral, axis=0)  # sensor increments of the six channels
    for k, ch in enumerate(list(environment.gyro.axes) + list(environment.accelerometer.axes)):
        b, den = ch.digital.coefficients(hs)
        if len(b) > 1 or len(den) > 1:
            inc[:, k] = signal.lfilter(b, den, inc[:, k])
    first = int(round((start - algorithm.history * h) / hs))
    total_steps = periods * steps_per_period
    inc = inc[first : first + (algorithm.history + total_steps * N) * M]
    inc = inc.reshape(-1, M, 6).sum(axis=1)
    p = step_windows(inc[:, :3], N, algorithm.history)
    idx0 = int(round(start / hs))
    q0 = lam_true[idx0] / np.linalg.norm(lam_true[idx0])
    at = idx0 + np.arange(periods + 1) * steps_per_period * N * M
    t = at * hs
    if velocity:
        b = step_windows(inc[:, 3:], N, algorithm.history)
        step_q = quat.rotvec_to_quat(increment(algorithm, Dual(p, b)))
        theta = Dual(q0, 0.5 * quat.multiply(quat.vector_to_quat(w_true[idx0]), q0))
    else:
        step_q = quat.rotvec_to_quat(increment(algorithm, p))
        theta = q0
    computed = [theta]
    for k in range(total_steps):
        theta = quat.multiply(theta, step_q[k])
        if (k + 1) % steps_per_period == 0:
            computed.append(theta)
    lam = np.stack([c.re if velocity else c for c in computed])
    err = quat.quat_to_rotvec(quat.multiply(lam_true[at], quat.conjugate(lam)), canonical=True)
    drift = np.polyfit(t - t[0], err, 1)[0]
    sculling = None
    if velocity:
        m = np.stack([c.du for c in computed])
        w_comp = 2.0 * quat.multiply(m, quat.conjugate(lam))[:, 1:]
        sculling = np.polyfit(t - t[0], w_true[at] - w_comp, 1)[0]
    return LineDriftCheck(np.asarray(drift), None if sculling is None else np.asarray(sculling), period, periods, start)
