"""Per-sample recursions as flight code writes them, and the quaternion composition of the samples.

Savage's recursion (Savage 1998, part 1, section 7.1.2) forms the coning
term of a step of N samples one sample at a time: with ``Δα_m = p_m`` the
m-th increment of the step, ``α_m = Δα_1 + … + Δα_m`` the angle accumulated
through it (``α_0 = 0``) and ``β_0 = 0``,

    β_m = β_{m−1} + ½ (α_{m−1} + Δα_{m−1}/6) × Δα_m,        Δφ = α_N + β_N,

where ``Δα_0`` is the last increment of the previous step (the recursion
keeps it across steps).  Expanded, ``c_ij = ½`` for i < j in the step, plus
``1/12`` for each adjacent pair, ``p_0 × p_1`` included: the second-order
condition holds for every N.  Its sculling counterpart (Savage 1998, part 2)
is the dual extension of the same recursion,

    γ_m = γ_{m−1} + ½ [(α_{m−1} + Δα_{m−1}/6) × Δν_m + (ν_{m−1} + Δν_{m−1}/6) × Δα_m],
    Δv = ν_N + ½ α_N × ν_N + γ_N,

with ``ν_m`` the velocity increments accumulated through sample m.

Three ways flight code has written it are parameters of one recursion:

``alpha_lag``
    which accumulated angle the β update reads: ``α_{m−1}`` (1, Savage), or
    ``α_{m−2}`` (2): the accumulated angle stored at the previous sample
    *before* that sample was added, the "previous α" of PX4's
    ``IntegratorConing`` (``src/modules/sensors/vehicle_imu/Integrator.hpp``,
    2021–2023 as published: ``β += ½(α_last + Δα_last/6) × Δα``, then
    ``α_last ← α``, then ``α ← α + Δα``);
``previous_lag``
    which increment the ``1/6`` term reads: ``Δα_{m−1}`` (1), or the current
    one (0), the update-order slip in which the stored previous increment is
    overwritten before it is read, so that the term is ``Δα_m × Δα_m = 0``
    (the coning terms of PX4's and ArduPilot's EKFs, PX4 issue #2663 and
    ArduPilot pull request #1480, 2014–2015);
``one_accumulator``
    α and β summed in one accumulator, which the β update reads (ArduPilot's
    ``AP_InertialSensor_Backend``: ``δ = ½(acc + Δθ_last/6) × Δθ``,
    ``acc ← acc + Δθ + δ``): the same bilinear part as Savage's, with terms
    of degree three and more.

:func:`recursion` is the recursion vectorised over the steps of a record (a
loop over the N sample positions of a step), :class:`SavageRecursion` the same
recursion one sample per call, as flight code runs it (for
:func:`~.adapters.stateful`).  :func:`quaternion_composition` composes the
exact rotation of every sample (``Λ(p_1) ∘ … ∘ Λ(p_N)``) with no coning term,
and rotates each velocity increment by the attitude at the start of its
sample.

Public API
----------
:func:`recursion`, :class:`SavageRecursion`, :func:`quaternion_composition`.

References
----------
Savage (1998), "Strapdown inertial navigation integration algorithm design",
part 1 (attitude, section 7.1.2) and part 2 (velocity).
"""

from __future__ import annotations

import numpy as np

from ...core import quaternion as quat
from ...core.validation import as_int
from .interface import Integrator

__all__ = ["recursion", "SavageRecursion", "quaternion_composition"]


def _check(alpha_lag, previous_lag, one_accumulator, velocity):
    alpha_lag = as_int(alpha_lag, "alpha_lag", minimum=1)
    previous_lag = as_int(previous_lag, "previous_lag", minimum=0)
    if previous_lag > 1:
        raise ValueError(f"Expected `previous_lag` 0 or 1, got {previous_lag}")
    if one_accumulator and alpha_lag != 1:
        raise ValueError(f"Expected `alpha_lag` = 1 with `one_accumulator` (the accumulator is read as it stands), got {alpha_lag}")
    if one_accumulator and velocity:
        raise ValueError("Expected `velocity` False with `one_accumulator` (no sculling form of the single accumulator is modelled)")
    return alpha_lag, previous_lag


def _name(alpha_lag, previous_lag, one_accumulator):
    if one_accumulator:
        return "Savage recursion, one accumulator"
    parts = ["Savage recursion"]
    if alpha_lag != 1:
        parts.append(f"previous α = α_(m−{alpha_lag})")
    if previous_lag != 1:
        parts.append("previous Δα overwritten before use")
    return ", ".join(parts)


def _columns_cross(a, b):
    """Cross products of the columns of two (3, n) arrays (each component a contiguous row, so each product runs on contiguous memory)."""
    out = np.empty_like(a)
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]
    return out


def _by_position(x, n):
    """Increments (k·N, 3) as (N, 3, k): sample position, component, step (C order)."""
    return x.reshape(-1, n, 3).transpose(1, 2, 0).copy()


def _before_step(x):
    """The increment before the first sample of each step, (3, k), from ``x`` of :func:`_by_position`: zero before the record."""
    out = np.empty_like(x[0])
    out[:, 0] = 0.0
    out[:, 1:] = x[-1][:, :-1]
    return out


def recursion(*, alpha_lag: int = 1, previous_lag: int = 1, one_accumulator: bool = False, velocity: bool = False) -> Integrator:
    """Savage's per-sample recursion (module docstring) as an integrator, vectorised over the steps.

    Parameters
    ----------
    alpha_lag : int, keyword-only
        The β update reads ``α_{m − alpha_lag}`` (1: Savage; 2: the stored previous α).
    previous_lag : int, keyword-only
        The ``1/6`` term reads ``Δα_{m − previous_lag}`` (1: Savage; 0: overwritten before use).
    one_accumulator : bool, keyword-only
        Accumulate α and β together (the β update reads the sum).
    velocity : bool, keyword-only
        Also the sculling recursion (not with ``one_accumulator``).

    Returns
    -------
    Integrator
        Rotation-vector output (and velocity increments).

    Raises
    ------
    ValueError
        For lags out of range or a combination not modelled.

    References
    ----------
    Savage (1998), part 1, section 7.1.2; part 2.

    Examples
    --------
    >>> from .interface import step_increments
    >>> p = np.array([[1e-3, 0, 0], [0, 1e-3, 0]])
    >>> float(step_increments(recursion(), p, 2).rotation[0, 2] / 1e-6)     # (1/2 + 1/12) p1 × p2
    0.5833333333333334
    """
    alpha_lag, previous_lag = _check(alpha_lag, previous_lag, one_accumulator, velocity)

    def run(gyro, samples_per_step, accel=None):
        n = samples_per_step
        # Component-major (N, 3, steps): the same elementwise operations as on
        # (steps, 3) rows, on contiguous memory instead of every third value.
        p = _by_position(gyro, n)
        b = None if accel is None else _by_position(accel, n)
        steps = p.shape[2]
        zero = np.zeros((3, steps))
        alpha = [zero]  # alpha[m] = α_m (accumulated through sample m)
        beta = zero
        nu = [zero]
        gamma = zero
        acc = zero
        for m in range(n):
            d = p[m]
            if previous_lag:
                last = p[m - 1] if m else _before_step(p)
            else:
                last = d
            if one_accumulator:
                acc = acc + d + 0.5 * _columns_cross(acc + last / 6.0, d)
                continue
            a_read = alpha[m + 1 - alpha_lag] if m + 1 - alpha_lag >= 0 else zero
            read = a_read + last / 6.0
            beta = beta + 0.5 * _columns_cross(read, d)
            if b is not None:
                db = b[m]
                if previous_lag:
                    last_b = b[m - 1] if m else _before_step(b)
                else:
                    last_b = db
                nu_read = nu[m + 1 - alpha_lag] if m + 1 - alpha_lag >= 0 else zero
                gamma = gamma + 0.5 * (_columns_cross(read, db) + _columns_cross(nu_read + last_b / 6.0, d))
                nu.append(nu[-1] + db)
            alpha.append(alpha[-1] + d)
        if one_accumulator:
            return np.ascontiguousarray(acc.T)
        rotation = np.ascontiguousarray((alpha[-1] + beta).T)
        if b is None:
            return rotation
        return rotation, np.ascontiguousarray((nu[-1] + 0.5 * _columns_cross(alpha[-1], nu[-1]) + gamma).T)

    return Integrator(run, velocity=velocity, name=_name(alpha_lag, previous_lag, one_accumulator))


class SavageRecursion:
    """Savage's recursion one sample per call, as flight code runs it (``reset`` / ``update`` / ``output``).

    The same recursion as :func:`recursion` (module docstring), written with
    plain floats one sample at a time; the previous increment is kept across
    ``output()`` calls, the accumulators are not.

    Parameters
    ----------
    alpha_lag : int
        The β update reads ``α_{m − alpha_lag}``.
    previous_lag : int
        The ``1/6`` term reads ``Δα_{m − previous_lag}`` (0 or 1).
    one_accumulator : bool
        Accumulate α and β together.
    velocity : bool
        Also the sculling recursion: ``update(gyro, accel)``, ``output()`` a pair.

    Examples
    --------
    >>> r = SavageRecursion()
    >>> r.reset(); r.update([1e-3, 0, 0]); r.update([0, 1e-3, 0])
    >>> float(r.output()[2] / 1e-6)
    0.5833333333333334
    """

    def __init__(self, alpha_lag: int = 1, previous_lag: int = 1, one_accumulator: bool = False, velocity: bool = False):
        self.alpha_lag, self.previous_lag = _check(alpha_lag, previous_lag, one_accumulator, velocity)
        self.one_accumulator = one_accumulator
        self.velocity = velocity
        self.reset()

    def reset(self) -> None:
        """Clear every state: a new record starts from rest."""
        self._last = self._last_b = _ZERO
        self._start_step()

    def _start_step(self) -> None:
        self._alphas = [_ZERO]  # α_0, α_1, …: accumulated through each sample of the step
        self._nus = [_ZERO]
        self._beta = self._gamma = self._acc = _ZERO

    def update(self, gyro, accel=None) -> None:
        """Take one sample.

        Parameters
        ----------
        gyro : array_like, shape (3,)
            Gyro increment Δα_m [rad].
        accel : array_like, shape (3,), optional
            Velocity increment Δν_m [m/s] (with ``velocity``).
        """
        d = tuple(float(x) for x in gyro)
        last = self._last if self.previous_lag else d
        if self.one_accumulator:
            self._acc = _add(self._acc, d, _cross(_add(self._acc, _sixth(last)), d, 0.5))
        else:
            m = len(self._alphas) - 1  # samples taken in this step before this one
            a_read = self._alphas[m + 1 - self.alpha_lag] if m + 1 - self.alpha_lag >= 0 else _ZERO
            read = _add(a_read, _sixth(last))
            self._beta = _add(self._beta, _cross(read, d, 0.5))
            if self.velocity:
                db = tuple(float(x) for x in accel)
                last_b = self._last_b if self.previous_lag else db
                nu_read = self._nus[m + 1 - self.alpha_lag] if m + 1 - self.alpha_lag >= 0 else _ZERO
                self._gamma = _add(self._gamma, _cross(read, db, 0.5), _cross(_add(nu_read, _sixth(last_b)), d, 0.5))
                self._nus.append(_add(self._nus[-1], db))
                self._last_b = db
            self._alphas.append(_add(self._alphas[-1], d))
        self._last = d

    def output(self):
        """The step's rotation vector [rad] (and velocity increment [m/s]); the next step starts.

        Returns
        -------
        ndarray, shape (3,), or (ndarray, ndarray)
        """
        if self.one_accumulator:
            out = np.array(self._acc)
        else:
            alpha, nu = self._alphas[-1], self._nus[-1]
            out = np.array(_add(alpha, self._beta))
            if self.velocity:
                out = (out, np.array(_add(nu, _cross(alpha, nu, 0.5), self._gamma)))
        self._start_step()
        return out


_ZERO = (0.0, 0.0, 0.0)


def _add(*vectors):
    return tuple(sum(c) for c in zip(*vectors))


def _sixth(v):
    return (v[0] / 6.0, v[1] / 6.0, v[2] / 6.0)


def _cross(a, b, s=1.0):
    return (s * (a[1] * b[2] - a[2] * b[1]), s * (a[2] * b[0] - a[0] * b[2]), s * (a[0] * b[1] - a[1] * b[0]))


def quaternion_composition(*, velocity: bool = False) -> Integrator:
    """Exact rotation of every sample composed over the step, with no coning term.

    ``Λ_step = Λ(p_1) ∘ … ∘ Λ(p_N)``, ``Δφ = rotvec(Λ_step)``; with
    ``velocity``, ``Δv = Σ_j Λ(p_1 … p_{j−1}) b_j`` (each velocity increment
    rotated by the attitude at the start of its sample, no sculling term).

    Parameters
    ----------
    velocity : bool, keyword-only
        Take accelerometer increments too.

    Returns
    -------
    Integrator
        Rotation-vector output.

    Examples
    --------
    >>> from .interface import step_increments
    >>> p = np.array([[1e-3, 0, 0], [0, 1e-3, 0]])
    >>> round(float(step_increments(quaternion_composition(), p, 2).rotation[0, 2] / 1e-6), 6)   # ½ p1 × p2
    0.5
    """

    def run(gyro, samples_per_step, accel=None):
        p = gyro.reshape(-1, samples_per_step, 3)
        b = None if accel is None else accel.reshape(-1, samples_per_step, 3)
        q = quat.identity((p.shape[0],))
        dv = np.zeros((p.shape[0], 3))
        for j in range(samples_per_step):
            if b is not None:
                dv = dv + quat.rotate(q, b[:, j])
            q = quat.multiply(q, quat.rotvec_to_quat(p[:, j], validate=False))
        rotation = quat.quat_to_rotvec(q, canonical=True, validate=False)
        return rotation if b is None else (rotation, dv)

    return Integrator(run, velocity=velocity, name="quaternion composition, no coning term")
