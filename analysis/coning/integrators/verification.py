"""The integrator itself against the exact solution: coning drift, sculling rate, local-error exponent.

An identified algorithm is a model of an integrator; these checks run the
integrator, not the model, and compare with the model's closed forms.

Coning drift.  The integrator is fed the exact increments (2.1) of classical
coning (:class:`~strapdown.analysis.coning.precession.RegularPrecession` with
ε = −1, half-cone angle α, rate ν), preceded by warm-up steps from the same
motion so that its memory is in steady state at t = 0; its steps are composed
(:func:`~strapdown.analysis.coning.simulator.prefix_product`) from the exact
attitude and compared with the exact attitude, Lebedev & Panov (1989), (4.4):
``δφ_I = rotvec(Λ* ∘ Λ̄)``, exact minus computed.  The error one step adds,
seen in frame I, has the same component along the cone axis
``a = −(0, sin α, cos α)`` every step (the motion is equivariant), so that
component grows linearly and its least-squares slope is the drift ``u``
without the periodic bias of a finite run.  ``u = α² ν D(νh) + O(α⁴)``
(:func:`strapdown.derivations.coning.drift.coning_drift`): the simulated
``u / (α² ν)`` at the cone angles α_k = α_0 / 2^k is extrapolated to α → 0 by
Richardson's scheme in α², with an uncertainty (the last two extrapolations'
difference plus the round-off floor
:func:`strapdown.analysis.core.roundoff.drift_floor` of each run, propagated
through the weights), and compared with the closed form ``D(νh)`` of the
identified algorithm.  A point is *resolved* when that uncertainty is below a
tenth of the tolerance times ``|D|``; the check holds when every resolved point
agrees within the tolerance (1e-6 relative by default) and at least one is
resolved.  Nothing here shares code with the closed form: the truth is the
exact attitude of the motion.

Sculling rate.  The same under classical sculling
(:class:`~strapdown.analysis.coning.sculling_motion.ScullingMotion`,
amplitudes θ₀ and A): the integrator's velocity increments, rotated by its
own attitude, are summed into ``W_I`` and compared with the exact apparent
velocity (Jacobi–Anger series).  At ``νh = 2π/K`` a run of whole vibration
periods makes the mean error rate exact: ``(ΔW_I(T) − ΔW_I(0))·e_n / T``.
``rate / (θ₀ A)`` is extrapolated to θ₀ → 0 and compared with
:meth:`~.sculling_terms.ScullingTerms.rectification_error`.

Velocity local-error exponent.  On the same tumbling motion with a smooth
specific force ``f(t)`` in the body axes, the integrator's velocity increment
of one step is compared with the exact one, ``∫ Λ̄(t_0) ∘ Λ(t) f(t) Λ̄(t) ∘ Λ(t_0) dt``
over the step (the body axes at its start), by Gauss–Legendre quadrature of
the closed-form attitude; the exponent of the error against the step is
w, the velocity accuracy order being w − 1.

Local-error exponent.  On
:class:`~strapdown.analysis.coning.local_error.TumblingMotion` (no symmetry),
the exponent of the one-step error of the integrator against the step, to be
compared with ρ + 1 of the identified algorithm's series: the remainder
changes the order only if the exponents part.

Public API
----------
:data:`DRIFT_TOLERANCE`, :data:`OMEGA_H`, :data:`CONE_ANGLES`, :data:`SCULLING_PERIOD_SAMPLES`,
:func:`sculling_points`,
:data:`ANGLE_AMPLITUDES`, :class:`CheckPoint`, :class:`Check`,
:func:`attitude_errors`, :func:`coning_drift_rate`, :func:`sculling_rate`,
:func:`coning_drift_check`, :func:`sculling_check`,
:func:`local_error_exponent`, :func:`velocity_error_exponent`.

References
----------
Lebedev & Panov (1989), eqs. (2.1), (4.1), (4.4); Savage (1998), part 2.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ....derivations.coning.algorithms import Algorithm
from ...core import budget
from ...core import quaternion as quat
from ...core.roundoff import drift_floor
from ...core.validation import as_int, positive
from ..drift_theory import coning_drift_function
from ..local_error import TumblingMotion
from ..precession import RegularPrecession
from ..sculling_motion import ScullingMotion
from ..simulator import drift_rate, prefix_product
from .defaults import DRIFT_TOLERANCE, OMEGA_H
from .interface import Integrator, step_increments
from .sculling_terms import ScullingTerms

__all__ = [
    "DRIFT_TOLERANCE",
    "OMEGA_H",
    "CONE_ANGLES",
    "SCULLING_PERIOD_SAMPLES",
    "sculling_points",
    "ANGLE_AMPLITUDES",
    "CheckPoint",
    "Check",
    "attitude_errors",
    "coning_drift_rate",
    "sculling_rate",
    "coning_drift_check",
    "sculling_check",
    "local_error_exponent",
    "velocity_error_exponent",
]

#: Half-cone angles α_k of the extrapolation to α → 0 [rad].
CONE_ANGLES = (0.04, 0.02, 0.01, 0.005)
#: Coning rate of the runs [rad/s] (the relative results do not depend on it).
NU = 2.0 * math.pi
#: Algorithm steps per coning run.
STEPS = 200
#: Samples per vibration period K of the sculling check (νh = 2π/K), before :func:`sculling_points` moves
#: any that would make ν N h a multiple of π.
SCULLING_PERIOD_SAMPLES = (24, 12, 6)
#: Amplitudes θ₀_k of the extrapolation to θ₀ → 0 [rad].
ANGLE_AMPLITUDES = (0.02, 0.01, 0.005, 0.0025)
#: Vibration periods per sculling run.
PERIODS = 16


@dataclass(frozen=True)
class CheckPoint:
    """One frequency of a check: the integrator's simulated coefficient against the model's closed form.

    Attributes
    ----------
    x : float
        ωh (coning) or νh (sculling) [rad].
    closed_form : float
        The identified model's coefficient: ``D(ωh)`` (drift ``u = α² ω D``) or the
        rectification rate over ``θ₀ A`` [dimensionless].
    simulated : float
        The integrator's, extrapolated to zero amplitude [dimensionless].
    uncertainty : float
        Of ``simulated``: extrapolation and round-off [dimensionless].
    raw : tuple of float
        The simulated coefficient at each amplitude, largest first.
    tolerance : float
        Relative tolerance of the agreement [dimensionless].
    """

    x: float
    closed_form: float
    simulated: float
    uncertainty: float
    raw: tuple
    tolerance: float

    @property
    def relative_difference(self) -> float:
        """``simulated / closed_form − 1`` (infinite when the closed form vanishes)."""
        return self.simulated / self.closed_form - 1.0 if self.closed_form else math.inf

    @property
    def resolved(self) -> bool:
        """The uncertainty is below a tenth of the tolerance times ``|closed_form|``: the point can decide."""
        return self.uncertainty <= 0.1 * self.tolerance * abs(self.closed_form)

    @property
    def agrees(self) -> bool | None:
        """Agreement within the tolerance (None for a point that is not resolved)."""
        return abs(self.relative_difference) <= self.tolerance if self.resolved else None


@dataclass(frozen=True)
class Check:
    """A simulated-against-closed-form check over several frequencies.

    Attributes
    ----------
    quantity : str
        What is compared.
    points : tuple of CheckPoint
        One per frequency.
    amplitudes : tuple of float
        Amplitudes of the extrapolation (cone angles α or θ₀) [rad].
    """

    quantity: str
    points: tuple
    amplitudes: tuple

    @property
    def resolved(self) -> tuple:
        """The points that can decide."""
        return tuple(p for p in self.points if p.resolved)

    @property
    def holds(self) -> bool | None:
        """Every resolved point agrees (None when no point is resolved)."""
        return all(p.agrees for p in self.resolved) if self.resolved else None

    @property
    def consistent(self) -> bool:
        """Every point agrees within its own uncertainty plus the tolerance (resolved or not): the weaker verdict where none resolves."""
        return all(abs(p.simulated - p.closed_form) <= p.uncertainty + p.tolerance * abs(p.closed_form) for p in self.points)

    @property
    def largest_difference(self) -> float | None:
        """Largest ``|relative_difference|`` over the resolved points (None without any)."""
        return max((abs(p.relative_difference) for p in self.resolved), default=None)


def _richardson(values, errors):
    """Extrapolate values at amplitudes halving each time to zero amplitude (errors even in the amplitude)."""
    table, err = list(values), list(errors)
    previous = table[-1]
    m = 1
    while len(table) > 1:
        f = 4.0**m
        previous = table[-1]
        table = [(f * table[k + 1] - table[k]) / (f - 1) for k in range(len(table) - 1)]
        err = [(f * err[k + 1] + err[k]) / (f - 1) for k in range(len(err) - 1)]
        m += 1
    return table[0], abs(table[0] - previous) + err[0]


def _warmup(history: int, samples: int) -> int:
    return -(-history // samples) + 1


#: The component order that turns the motion's body frame so that its z axis becomes body axis k (a cyclic permutation: a rotation).
_AXIS_ORDER = {0: [2, 0, 1], 1: [1, 2, 0], 2: [0, 1, 2]}


def _axis(axis) -> list:
    k = as_int(axis, "axis", minimum=0)
    if k > 2:
        raise ValueError(f"Expected `axis` 0, 1 or 2 (x, y, z), got {k}")
    return _AXIS_ORDER[k]


def attitude_errors(
    integrator: Integrator, samples_per_step, motion: RegularPrecession, sample_interval, steps, *, history: int = 0, axis: int = 2, limits: budget.Limits | None = None
):
    """Run ``integrator`` on the exact increments of ``motion`` and return the attitude error after every step.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    motion : RegularPrecession
        The motion (its exact attitude is the truth).
    sample_interval : float
        h [s].
    steps : int
        Steps compared (after the warm-up).
    history : int, keyword-only
        Samples before a step the integrator reads; ``⌈history/N⌉ + 1`` warm-up
        steps from the same motion precede t = 0.
    axis : int, keyword-only
        Body axis that takes the role of the motion's z axis: 2 (z, the motion
        as it is), 0 (x) or 1 (y); the motion's body and reference frames are
        turned by the cyclic permutation of the axes that brings z there (the
        same motion seen in turned axes), so that a cone about z becomes one
        about that axis.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    time : ndarray, shape (steps + 1,)
        Step ends [s], from 0.
    error : ndarray, shape (steps + 1, 3)
        ``δφ_I = rotvec(Λ* ∘ Λ̄)`` [rad], frame I (turned with ``axis``), with Λ(0) = Λ*(0) = (1, 0, 0, 0).

    Raises
    ------
    ValueError
        Sizes out of range, or a run beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``steps``).
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    h = positive(sample_interval, "sample_interval")
    steps = as_int(steps, "steps", minimum=2)
    warm = _warmup(history, n)
    budget.check(budget.INTEGRATOR_SAMPLE.estimate(float(warm + steps) * n, what=f"`steps` = {steps:.3g} steps of {n} samples"), limits)
    order = _axis(axis)
    inc = motion.grid_increments(h, -warm * n, (warm + steps) * n, limits=limits)[:, order]
    rotation = step_increments(integrator, inc, n).rotation[warm:]
    lam = prefix_product(quat.rotvec_to_quat(rotation, validate=False))
    lam = np.concatenate([quat.identity((1,)), lam], axis=0)
    time = np.arange(steps + 1) * n * h
    # the general solution (1.8) through Λ*(0) = 1: Λ*(t) = Q̄(0) ∘ Q(t)
    exact = quat.multiply(quat.conjugate(motion.attitude(0.0)), motion.attitude(time))
    exact = np.concatenate([exact[:, :1], exact[:, 1:][:, order]], axis=-1)  # the same rotations in the turned axes
    # rotvec(Λ* ∘ Λ̄) = −rotvec(Λ ∘ Λ̄*), as the simulator forms it
    error = -quat.quat_to_rotvec(quat.multiply(lam, quat.conjugate(exact)), canonical=True, validate=False)
    return time, error


def coning_drift_rate(integrator: Integrator, samples_per_step, motion: RegularPrecession, sample_interval, *, steps: int = STEPS, history: int = 0,
                      axis: int = 2, limits: budget.Limits | None = None) -> float:  # fmt: skip
    """Simulated coning drift of ``integrator`` along the cone axis [rad/s], exact minus integrator.

    The least-squares slope of the cone-axis component of :func:`attitude_errors`
    (module docstring); the cone axis of the motion (ε = −1, nutation α) in
    frame I is ``−(0, sin α, cos α)`` with the run starting at Λ(0) = 1.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    motion : RegularPrecession
        Classical coning (ε = −1).
    sample_interval : float
        h [s].
    steps : int, keyword-only
        Steps of the run.
    history : int, keyword-only
        Samples before a step the integrator reads (sets the warm-up).
    axis : int, keyword-only
        Body axis of the cone: 2 (z, the motion as it is), 0 (x) or 1 (y)
        (:func:`attitude_errors`); the drift is taken along the turned cone axis.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    float
        u [rad/s]; positive when the computed attitude lags the coning rotation.

    Raises
    ------
    ValueError
        If the motion is not coning (ε ≠ −1), or the run exceeds ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``steps``).
    """
    if not isinstance(motion, RegularPrecession) or motion.eps != -1.0:
        raise ValueError(f"Expected `motion` to be classical coning, a RegularPrecession with eps = -1, got {motion!r}")
    time, error = attitude_errors(integrator, samples_per_step, motion, sample_interval, steps, history=history, axis=axis, limits=limits)
    cone = -np.array([0.0, math.sin(motion.nutation), math.cos(motion.nutation)])[_axis(axis)]
    return float(drift_rate(time, error) @ cone)


def _sculling_run(integrator, n, motion, h, steps, warm, *, limits=None):
    """(rate along e_r × e_a [m/s²], its round-off floor) of one run of whole periods."""
    dual = motion.grid_increments(h, -warm * n, (warm + steps) * n, dual=True, limits=limits)
    out = step_increments(integrator, dual.re, n, dual.du)
    lam = prefix_product(quat.rotvec_to_quat(out.rotation, validate=False))
    lam = np.concatenate([quat.identity((1,)), lam], axis=0)
    # W_I from t = 0 (the end of the warm-up), in the integrator's frame, and the exact
    # solution from the same attitude and W_I = 0 at t = 0
    w_end = np.sum(quat.rotate(lam[warm:-1], out.velocity[warm:]), axis=0)
    t_total = steps * n * h
    # the exact solution through the same attitude and W_I = 0 at t = 0 is θ = C ∘ P(t) with
    # C = Λ(0) ∘ Q̄(0) (Lebedev & Panov 1989, (1.5)): its W_I(T) is C turning the motion's own
    # apparent velocity W(T) (zero at t = 0), and e_r × e_a of the motion's frame is C e_n in frame I
    c = quat.multiply(lam[warm], quat.conjugate(motion.attitude(0.0)))
    w_exact = motion.apparent_velocity(t_total)
    e_n = np.cross(motion.e_r, motion.e_a)
    rate = float(w_exact @ e_n - quat.rotate(quat.conjugate(c), w_end) @ e_n) / t_total
    return rate, 64 * float(np.finfo(float).eps) * float(np.abs(w_exact).max()) / t_total


def sculling_rate(integrator: Integrator, samples_per_step, motion: ScullingMotion, sample_interval, *, periods: int = PERIODS, history: int = 0,
                  limits: budget.Limits | None = None) -> float:  # fmt: skip
    """Simulated rectification error rate of ``integrator`` along ``e_r × e_a`` [m/s²], exact minus integrator.

    A run of whole vibration periods (``ν h = 2π/K``), its velocity increments
    rotated by its own attitude and summed, against the exact apparent velocity
    (module docstring).

    Parameters
    ----------
    integrator : Integrator
        The black box (with ``velocity``).
    samples_per_step : int
        N.
    motion : ScullingMotion
        Classical sculling.
    sample_interval : float
        h [s]; ``2π / (ν h)`` must be a whole number.
    periods : int, keyword-only
        Vibration periods of the run (times N).
    history : int, keyword-only
        Samples before a step the integrator reads (sets the warm-up).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    float
        Rate [m/s²]; positive when the integrator under-rectifies.

    Raises
    ------
    ValueError
        If ``2π / (ν h)`` is not a whole number, or the run exceeds ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``periods``).
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    h = positive(sample_interval, "sample_interval")
    per_period = 2 * math.pi / (motion.nu * h)
    if abs(per_period - round(per_period)) > 1e-9:
        raise ValueError(f"Expected `sample_interval` with 2π/(ν h) a whole number of samples per period, got {per_period:g}")
    periods = as_int(periods, "periods", minimum=1)
    steps = int(round(per_period)) * periods
    warm = _warmup(history, n)
    what = f"`periods` = {periods:.3g} vibration periods ({steps:.3g} steps of {n} samples)"
    budget.check(budget.INTEGRATOR_SAMPLE.estimate(float(warm + steps) * n, what=what, bytes_factor=2.0), limits)  # dual increments: twice the memory
    return _sculling_run(integrator, n, motion, h, steps, warm, limits=limits)[0]


def coning_drift_check(
    integrator: Integrator,
    samples_per_step,
    algorithm: Algorithm,
    *,
    omega_h=OMEGA_H,
    cone_angles=CONE_ANGLES,
    steps: int = STEPS,
    tolerance: float = DRIFT_TOLERANCE,
    history: int | None = None,
    axis: int = 2,
    closed_form=None,
) -> Check:
    """The integrator's simulated coning drift against the closed form of ``algorithm`` (module docstring).

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N (``algorithm.samples``).
    algorithm : Algorithm
        The identified algorithm; its history sets the warm-up.
    omega_h : sequence of float, keyword-only
        ωh [rad] of the points, each in (0, π].
    cone_angles : sequence of float, keyword-only
        Half-cone angles α_k, halving [rad].
    steps : int, keyword-only
        Steps per run.
    tolerance : float, keyword-only
        Relative tolerance [dimensionless].
    history : int, optional, keyword-only
        Samples before a step the integrator reads, for the warm-up (default ``algorithm.history``).
    axis : int, keyword-only
        Body axis of the cone (:func:`coning_drift_rate`).
    closed_form : callable, optional, keyword-only
        ``D(ωh)`` to compare with (default: that of ``algorithm``,
        :func:`~strapdown.analysis.coning.drift_theory.coning_drift_function`;
        :meth:`~.anisotropy.AxisCorrection.drift_function` for one axis of an
        integrator that treats the axes differently).

    Returns
    -------
    Check
        Coefficients ``D = u / (α² ω)`` [dimensionless].

    Raises
    ------
    ValueError
        An ωh outside (0, π].

    References
    ----------
    Lebedev & Panov (1989), eqs. (2.1), (4.4); :func:`strapdown.derivations.coning.drift.coning_drift`.
    """
    closed = coning_drift_function(algorithm) if closed_form is None else closed_form
    history = algorithm.history if history is None else as_int(history, "history", minimum=0)
    points = []
    for x in omega_h:
        x = positive(x, "omega_h")
        if x > math.pi:
            raise ValueError(f"Expected `omega_h` in (0, π] (above π per sample the samples alias the coning rate), got {x:g}")
        h = x / NU
        values, errors = [], []
        for alpha in cone_angles:
            u = coning_drift_rate(integrator, samples_per_step, RegularPrecession(-1.0, NU, alpha), h, steps=steps, history=history, axis=axis)
            scale = alpha**2 * NU
            values.append(u / scale)
            errors.append(drift_floor(NU, -NU) / scale)
        value, unc = _richardson(values, errors)
        points.append(CheckPoint(x, float(closed(x)), float(value), float(unc), tuple(values), float(tolerance)))
    about = "" if axis == 2 else f" (cone about the {'xyz'[axis]} axis)"
    return Check(f"coning drift D(ωh) = u / (α² ω), along the cone axis, exact minus integrator{about}", tuple(points), tuple(cone_angles))


def sculling_points(samples_per_step) -> tuple:
    """νh of the sculling check for N samples per step: ``2π/K`` for K of :data:`SCULLING_PERIOD_SAMPLES`.

    A K that divides 2N would make ν N h a multiple of π (every step sees the
    vibration at the same phase, and the error is no constant rate); it is
    replaced by the next K that does not.

    Parameters
    ----------
    samples_per_step : int
        N.

    Returns
    -------
    tuple of float
        νh [rad].

    Examples
    --------
    >>> [round(2 * math.pi / x) for x in sculling_points(6)]
    [24, 13, 7]
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    out = []
    for k in SCULLING_PERIOD_SAMPLES:
        while (2 * n) % k == 0:
            k += 1
        out.append(2 * math.pi / k)
    return tuple(out)


def sculling_check(
    integrator: Integrator,
    samples_per_step,
    terms: ScullingTerms,
    *,
    history: int = 0,
    nu_h=None,
    angle_amplitudes=ANGLE_AMPLITUDES,
    periods: int = PERIODS,
    tolerance: float = DRIFT_TOLERANCE,
) -> Check:
    """The integrator's simulated rectification error against the closed form of ``terms`` (module docstring).

    Parameters
    ----------
    integrator : Integrator
        The black box (with ``velocity``).
    samples_per_step : int
        N.
    terms : ScullingTerms
        The identified sculling part.
    history : int, keyword-only
        Samples before a step the integrator reads (sets the warm-up).
    nu_h : sequence of float, optional, keyword-only
        νh [rad], each 2π/K for a whole number K of samples per period (default :func:`sculling_points`).
    angle_amplitudes : sequence of float, keyword-only
        θ₀_k, halving [rad].
    periods : int, keyword-only
        Vibration periods per run (times N).
    tolerance : float, keyword-only
        Relative tolerance [dimensionless].

    Returns
    -------
    Check
        Coefficients ``rate / (θ₀ A)`` [dimensionless].

    Raises
    ------
    ValueError
        A νh that is not 2π/K for a whole K.
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    warm = _warmup(history, n)
    points = []
    for x in sculling_points(n) if nu_h is None else nu_h:
        x = positive(x, "nu_h")
        per_period = 2 * math.pi / x
        if abs(per_period - round(per_period)) > 1e-9:
            raise ValueError(f"Expected `nu_h` = 2π/K for a whole number K of samples per period, got {x:g} (K = {per_period:g})")
        steps = int(round(per_period)) * as_int(periods, "periods", minimum=1)
        h = x / NU
        values, errors, closed = [], [], None
        for theta0 in angle_amplitudes:
            motion = ScullingMotion(theta0, 1.0, NU)
            rate, floor = _sculling_run(integrator, n, motion, h, steps, warm)
            scale = theta0 * motion.accel_amplitude
            values.append(rate / scale)
            errors.append(floor / scale)
            if closed is None:
                closed = terms.rectification_error(motion, h)
        value, unc = _richardson(values, errors)
        cf = closed.rate / (angle_amplitudes[0] * 1.0)
        points.append(CheckPoint(x, float(cf), float(value), float(unc), tuple(values), float(tolerance)))
    return Check("rectification error rate / (θ₀ A) along e_r × e_a, exact minus integrator", tuple(points), tuple(angle_amplitudes))


@functools.lru_cache(maxsize=64)
def _tumbling_rotations(n: int, warm: int, steps: tuple, times: tuple) -> tuple:
    """The records and exact rotations of :func:`local_error_exponent`, per step middle and step H.

    They depend on N, the warm-up and the grid only, not on the integrator:
    computed once per process and shared by every integrator checked (the
    callers pass copies to the integrators).
    """
    motion = TumblingMotion()
    out = []
    for t_mid in times:
        per_time = []
        for big_h in steps:
            h = big_h / n
            t0 = t_mid - 0.5 * big_h
            record = motion.increments(t0 - warm * big_h, h, (warm + 1) * n)
            exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(motion.attitude(t0)), motion.attitude(t0 + big_h)), validate=False)
            per_time.append((_frozen(record), _frozen(exact)))
        out.append(tuple(per_time))
    return tuple(out)


def _frozen(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


def local_error_exponent(integrator: Integrator, samples_per_step, *, history: int = 0, steps=(0.05, 0.025, 0.0125, 0.00625), times=(0.3, 1.1, 2.4)) -> float:
    """Exponent of the integrator's one-step error against the step H on :class:`TumblingMotion`.

    The slope of ``log|δφ|`` against ``log H`` over the three smallest steps
    whose error is above ``1e-13`` (a thousand times the round-off of a step),
    averaged over the step middles: the asymptotic exponent ρ + 1 where the
    data reach it.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    history : int, keyword-only
        Samples before a step the integrator reads (sets the warm-up).
    steps : sequence of float, keyword-only
        Steps H [s], decreasing.
    times : sequence of float, keyword-only
        Middles of the step [s].

    Returns
    -------
    float
        ``d log|δφ| / d log H`` (ρ + 1 for an integrator of order ρ); NaN when fewer than two steps are above round-off.
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    warm = _warmup(history, n)
    references = _tumbling_rotations(n, warm, tuple(float(x) for x in steps), tuple(float(x) for x in times))
    errors = [[float(np.linalg.norm(exact - step_increments(integrator, record.copy(), n).rotation[-1])) for record, exact in per_time] for per_time in references]
    return _mean_slope(steps, errors)


def _mean_slope(steps, errors) -> float:
    """Mean over the step middles of the slope of log error against log H.

    Each slope is fitted through the last three errors above round-off (1e-13), over at least
    two; a step middle without two such errors is left out (nan when every one is).
    """
    exps = []
    for errs in errors:
        keep = [k for k, e in enumerate(errs) if e > 1e-13][-3:]
        if len(keep) >= 2:
            exps.append(np.polyfit(np.log(np.array(steps)[keep]), np.log(np.array(errs)[keep]), 1)[0])
    return float(np.mean(exps)) if exps else math.nan


#: Specific force of the velocity check in the body axes [m/s²], smooth and along no fixed axis.
def _specific_force(t):
    t = np.asarray(t, dtype=float)
    return np.stack([0.8 + 0.5 * np.sin(1.7 * t), -0.3 + 0.4 * np.cos(1.1 * t), 0.2 + 0.6 * t], axis=-1)


#: Gauss–Legendre nodes per sample of the velocity check (the integrands are smooth over a sample: exact to round-off).
_NODES = 12


def _gauss(t0, t1, f):
    """∫_{t0}^{t1} f(t) dt by Gauss–Legendre, for arrays of intervals (f maps times (..., m) to (..., m, 3))."""
    x, w = np.polynomial.legendre.leggauss(_NODES)
    t0, t1 = np.asarray(t0, dtype=float), np.asarray(t1, dtype=float)
    half = (t1 - t0) / 2
    t = (t0 + t1)[..., None] / 2 + half[..., None] * x
    return np.einsum("...m,...mk->...k", w, f(t)) * half[..., None]


@functools.lru_cache(maxsize=64)
def _tumbling_velocities(n: int, warm: int, steps: tuple, times: tuple) -> tuple:
    """The records (gyro, accelerometer) and exact velocity increments of :func:`velocity_error_exponent`.

    Per step middle and step H; shared by every integrator checked, as
    :func:`_tumbling_rotations`.
    """
    motion = TumblingMotion()
    out = []
    for t_mid in times:
        per_time = []
        for big_h in steps:
            h = big_h / n
            t0 = t_mid - 0.5 * big_h
            start = t0 - warm * big_h
            count = (warm + 1) * n
            gyro = motion.increments(start, h, count)
            edges = start + h * np.arange(count + 1)
            accel = _gauss(edges[:-1], edges[1:], _specific_force)
            ref = motion.attitude(t0)

            def turned(t, ref=ref):
                q = quat.multiply(quat.conjugate(ref), motion.attitude(t))
                return quat.rotate(q, _specific_force(t))

            sub = t0 + h * np.arange(n + 1)
            exact = _gauss(sub[:-1], sub[1:], turned).sum(axis=0)
            per_time.append((_frozen(gyro), _frozen(accel), _frozen(exact)))
        out.append(tuple(per_time))
    return tuple(out)


def velocity_error_exponent(integrator: Integrator, samples_per_step, *, history: int = 0, steps=(0.05, 0.025, 0.0125, 0.00625), times=(0.3, 1.1, 2.4)) -> float:
    """Exponent of the integrator's one-step velocity error against the step H (module docstring).

    Parameters
    ----------
    integrator : Integrator
        The black box (with ``velocity``).
    samples_per_step : int
        N.
    history : int, keyword-only
        Samples before a step the integrator reads (sets the warm-up).
    steps : sequence of float, keyword-only
        Steps H [s], decreasing.
    times : sequence of float, keyword-only
        Middles of the step [s].

    Returns
    -------
    float
        ``d log|δv| / d log H`` (w for a local velocity error O(h^w)); NaN
        when fewer than two steps are above round-off.

    Raises
    ------
    ValueError
        If the integrator takes no accelerometer increments.

    References
    ----------
    Savage (1998), part 2.
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    if not integrator.velocity:
        raise ValueError(f"Expected an integrator with velocity output, got {integrator.name!r} (coning only)")
    warm = _warmup(history, n)
    references = _tumbling_velocities(n, warm, tuple(float(x) for x in steps), tuple(float(x) for x in times))
    errors = [[float(np.linalg.norm(exact - step_increments(integrator, gyro.copy(), n, accel.copy()).velocity[-1])) for gyro, accel, exact in per_time] for per_time in references]
    return _mean_slope(steps, errors)
