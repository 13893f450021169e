"""The black-box interface of a coning (and sculling) integrator, and its checked call.

An integrator is a Python callable

    ``function(gyro, samples_per_step)``                    (coning only)
    ``function(gyro, samples_per_step, accel)``             (``velocity=True``)

that takes the gyro increments ``p_j = ∫ ω dt`` of a record, shape
``(n_samples, 3)`` [rad], and, for sculling, the accelerometer (velocity)
increments ``b_j = ∫ a dt`` of the same samples, shape ``(n_samples, 3)``
[m/s], and returns one row per output step of ``N = samples_per_step``
samples.  What a row holds is declared by :attr:`Integrator.output`:

``"rotation_vector"``
    the rotation vector ``Δφ_k`` of each step, shape ``(n_steps, 3)`` [rad],
    and (``velocity=True``) the velocity increment ``Δv_k`` of each step in
    the body axes at the start of the step, shape ``(n_steps, 3)`` [m/s];
``"quaternion"``
    the attitude ``Λ_k`` (E → I, scalar first) after each step, starting
    from ``Λ_0 = (1, 0, 0, 0)``, shape ``(n_steps, 4)``, and the apparent
    velocity ``W_I`` after each step, starting from zero [m/s];
``"dcm"``
    the same attitude as body-to-reference direction-cosine matrices,
    shape ``(n_steps, 3, 3)``.

Every record starts from rest: the integrator's state (a previous sample, an
accumulated angle) is that of a record preceded by zero increments.  The
identification assumes that a call depends on its arguments alone (no state
left over from an earlier call, no dependence on a sample's position in the
record); it tests that assumption and reports what it finds
(:mod:`.assumptions`) rather than refusing the integrator.

Rate samples.  An integrator declared with ``input="rate"`` takes the mean
rate of each sample, ``ω̄_j = p_j / h`` [rad/s], and with ``velocity`` the
mean specific force ``f̄_j = b_j / h`` [m/s²], at its ``sample_interval`` h:
what an integrating-rate gyro or a gyro with a box-car (sample-and-average)
output gives.  Its outputs are the same as those of an increment integrator.

:func:`step_increments` calls an integrator, checks what it returns (shape,
finite values, unit quaternions, orthonormal matrices) and turns every kind
of output into the steps ``Δφ_k`` and ``Δv_k``: from attitudes,
``Δφ_k = rotvec(Λ̄_{k−1} ∘ Λ_k)`` and ``Δv_k = Λ̄_{k−1} ∘ (W_k − W_{k−1}) ∘ Λ_{k−1}``.
A bad integrator gets an :class:`IntegratorError` (a ``ValueError``) that names
it, says what was expected and what came.

Public API
----------
:data:`OUTPUTS`, :data:`INPUTS`, :class:`Integrator`, :class:`StepIncrements`,
:class:`IntegratorError`, :class:`IntegratorStopped`, :class:`IntegratorRaised`,
:func:`step_increments`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ...core import quaternion as quat
from ...core.validation import as_int, as_vector, positive

__all__ = ["OUTPUTS", "INPUTS", "Integrator", "StepIncrements", "IntegratorError", "IntegratorStopped", "IntegratorRaised", "step_increments"]

#: The kinds of output an integrator may declare (module docstring).
OUTPUTS = ("rotation_vector", "quaternion", "dcm")
#: What an integrator may take (module docstring): increments [rad, m/s] or mean rates [rad/s, m/s²].
INPUTS = ("increment", "rate")

#: Tolerance of a unit quaternion's norm and of a direction-cosine matrix's orthonormality [dimensionless].
UNIT_TOLERANCE = 1e-6


class IntegratorError(ValueError):
    """An integrator that raised, or returned something other than its declared output."""


class IntegratorStopped(IntegratorError):
    """An integrator run in a child process that did not return within its time limit, or whose process died."""


class IntegratorRaised(Exception):
    """An exception the integrator raised in a child process, as its type name and message.

    Parameters
    ----------
    kind : str
        The name of the exception's type (``"RuntimeError"``).
    message : str
        Its message.
    """

    def __init__(self, kind: str, message: str):
        super().__init__(message)
        self.kind = kind


@dataclass(frozen=True)
class Integrator:
    """A coning (and sculling) integrator as a black box.

    Attributes
    ----------
    function : callable
        ``function(gyro, samples_per_step)`` or, with ``velocity``,
        ``function(gyro, samples_per_step, accel)`` (module docstring).
    output : str
        One of :data:`OUTPUTS`: what the rows returned hold.
    velocity : bool
        The integrator also takes accelerometer increments and returns
        velocity (a pair ``(attitude_rows, velocity_rows)``).
    name : str
        Name in messages and reports (default: the function's name).
    input : str
        One of :data:`INPUTS`: ``"increment"`` (default) or ``"rate"`` (mean
        rates of each sample, module docstring).
    sample_interval : float or None
        h [s] of a rate integrator (required with ``input="rate"``, None otherwise).

    Raises
    ------
    TypeError
        If ``function`` is not callable or ``velocity`` not a bool.
    ValueError
        If ``output`` is not one of :data:`OUTPUTS`, ``input`` not one of
        :data:`INPUTS`, or ``sample_interval`` missing, not positive or given
        for an increment integrator.

    Examples
    --------
    >>> import numpy as np
    >>> integ = Integrator(lambda gyro, n: gyro.reshape(-1, n, 3).sum(axis=1), name="sum")
    >>> step_increments(integ, np.full((4, 3), 1e-3), 2).rotation
    array([[0.002, 0.002, 0.002],
           [0.002, 0.002, 0.002]])
    """

    function: Callable
    output: str = "rotation_vector"
    velocity: bool = False
    name: str = ""
    input: str = "increment"
    sample_interval: float | None = None

    def __post_init__(self):
        if not callable(self.function):
            raise TypeError(f"Expected `function` to be callable, got {type(self.function).__name__}")
        if self.output not in OUTPUTS:
            raise ValueError(f"Expected `output` to be one of {', '.join(OUTPUTS)}, got {self.output!r}")
        if not isinstance(self.velocity, bool):
            raise TypeError(f"Expected `velocity` to be a bool, got {type(self.velocity).__name__}")
        if not isinstance(self.name, str):
            raise TypeError(f"Expected `name` to be a str, got {type(self.name).__name__}")
        if not self.name:
            object.__setattr__(self, "name", getattr(self.function, "__qualname__", None) or type(self.function).__name__)
        if self.input not in INPUTS:
            raise ValueError(f"Expected `input` to be one of {', '.join(INPUTS)}, got {self.input!r}")
        if self.input == "rate":
            if self.sample_interval is None:
                raise ValueError("Expected `sample_interval` [s] for an integrator that takes rates (`input` = 'rate'), got None")
            object.__setattr__(self, "sample_interval", positive(self.sample_interval, "sample_interval"))
        elif self.sample_interval is not None:
            raise ValueError(f"Expected no `sample_interval` for an integrator that takes increments, got {self.sample_interval!r}")


class StepIncrements(NamedTuple):
    """What one record gave, as steps.

    Attributes
    ----------
    rotation : ndarray, shape (n_steps, 3)
        Rotation vector ``Δφ_k`` of each step [rad].
    velocity : ndarray, shape (n_steps, 3), or None
        Velocity increment ``Δv_k`` of each step, body axes at the start of the
        step [m/s] (integrators with ``velocity``).
    """

    rotation: np.ndarray
    velocity: np.ndarray | None


def _rows(value, integrator: Integrator, what: str, shape: tuple, context: str, samples: int) -> np.ndarray:
    """``value`` as a finite float array of ``shape``, or an :class:`IntegratorError`."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise IntegratorError(
            f"integrator {integrator.name!r} returned {type(value).__name__} as {what}, expected a numeric array of shape {shape} ({context})"
        ) from None
    if arr.shape != shape:
        hint = ""
        if arr.ndim >= 1 and arr.shape[0] == samples != shape[0]:
            hint = ": one row per sample? Expected one row per step"
        raise IntegratorError(f"integrator {integrator.name!r} returned {what} of shape {arr.shape}, expected {shape} ({context}){hint}")
    bad = ~np.isfinite(arr)
    if bad.any():
        row = int(np.argwhere(bad)[0][0])
        raise IntegratorError(f"integrator {integrator.name!r} returned NaN or infinity in {what}, first at step {row} ({context}, all of them finite)")
    return arr


def _attitudes(arr: np.ndarray, integrator: Integrator, context: str) -> np.ndarray:
    """Declared attitudes (quaternions or DCMs) as checked unit quaternions, shape (n_steps, 4)."""
    if integrator.output == "quaternion":
        norms = np.linalg.norm(arr, axis=-1)
        worst = int(np.argmax(np.abs(norms - 1.0))) if len(norms) else 0
        if len(norms) and abs(norms[worst] - 1.0) > UNIT_TOLERANCE:
            raise IntegratorError(
                f"integrator {integrator.name!r} returned a quaternion of norm {norms[worst]:.9g} at step {worst}, "
                f"expected unit quaternions (|q| = 1 within {UNIT_TOLERANCE:g}; {context})"
            )
        return arr / norms[:, None]
    gram = np.einsum("kij,kil->kjl", arr, arr) - np.eye(3)
    off = np.abs(gram).max(axis=(1, 2)) if len(arr) else np.zeros(0)
    det = np.linalg.det(arr) if len(arr) else np.zeros(0)
    bad = (off > UNIT_TOLERANCE) | (det <= 0)
    if bad.any():
        k = int(np.argmax(bad))
        raise IntegratorError(
            f"integrator {integrator.name!r} returned a matrix at step {k} that is not a rotation "
            f"(|MᵀM − I| = {off[k]:.3g}, det M = {det[k]:.6g}), expected direction-cosine matrices ({context})"
        )
    from scipy.spatial.transform import Rotation  # here: a child process that runs user code imports no scipy

    return Rotation.from_matrix(arr).as_quat(scalar_first=True)


def step_increments(integrator: Integrator, gyro, samples_per_step, accel=None) -> StepIncrements:
    """Call ``integrator`` on one record and return its steps, checked.

    Parameters
    ----------
    integrator : Integrator
        The integrator.
    gyro : array_like, shape (n_samples, 3)
        Gyro increments ``p_j`` [rad]; ``n_samples`` a positive multiple of N.
    samples_per_step : int
        N, samples per output step.
    accel : array_like, shape (n_samples, 3), optional
        Accelerometer increments ``b_j`` [m/s] (integrators with ``velocity``;
        zero when omitted).

    Returns
    -------
    StepIncrements
        ``Δφ_k`` [rad] and, with ``velocity``, ``Δv_k`` [m/s] of every step.

    Raises
    ------
    TypeError
        If ``integrator`` is not an :class:`Integrator`.
    ValueError
        Bad ``gyro``, ``accel`` or ``samples_per_step``.
    IntegratorError
        The integrator raised, or returned the wrong shape, NaN or infinity,
        a quaternion that is not unit or a matrix that is not a rotation.
    """
    if not isinstance(integrator, Integrator):
        raise TypeError(f"Expected `integrator` to be an Integrator, got {type(integrator).__name__}")
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    gyro = as_vector(gyro, "gyro")
    if gyro.ndim != 2 or gyro.shape[0] < n or gyro.shape[0] % n:
        raise ValueError(f"Expected `gyro` of shape (k·N, 3) with N = `samples_per_step` = {n} and k >= 1, got shape {gyro.shape}")
    if accel is not None:
        if not integrator.velocity:
            raise ValueError(f"Expected no `accel` for integrator {integrator.name!r} (it takes gyro increments only), got an array")
        accel = as_vector(accel, "accel")
        if accel.shape != gyro.shape:
            raise ValueError(f"Expected `accel` of the shape of `gyro`, {gyro.shape}, got {accel.shape}")
    elif integrator.velocity:
        accel = np.zeros_like(gyro)
    steps = gyro.shape[0] // n
    context = f"called with {gyro.shape[0]} samples, {n} per step"
    scale = 1.0 / integrator.sample_interval if integrator.input == "rate" else 1.0
    args = (gyro * scale, n) + ((accel * scale,) if integrator.velocity else ())
    try:
        out = integrator.function(*args)
    except IntegratorStopped:
        raise
    except Exception as exc:  # the user's code: any failure becomes one message naming it
        detail = " ".join(str(exc).split()) or "no message"
        kind = exc.kind if isinstance(exc, IntegratorRaised) else type(exc).__name__
        raise IntegratorError(f"integrator {integrator.name!r} raised {kind}: {detail} ({context})") from exc
    if integrator.velocity:
        if not isinstance(out, (tuple, list)) or len(out) != 2:
            raise IntegratorError(
                f"integrator {integrator.name!r} returned {type(out).__name__}, expected a pair (attitude rows, velocity rows) since it takes accelerometer increments ({context})"
            )
        att_out, vel_out = out
    else:
        att_out, vel_out = out, None
    shape = {"rotation_vector": (steps, 3), "quaternion": (steps, 4), "dcm": (steps, 3, 3)}[integrator.output]
    what = {"rotation_vector": "rotation vectors", "quaternion": "attitude quaternions", "dcm": "direction-cosine matrices"}[integrator.output]
    att = _rows(att_out, integrator, what, shape, context, gyro.shape[0])
    vel = None if vel_out is None else _rows(vel_out, integrator, "velocities", (steps, 3), context, gyro.shape[0])
    if integrator.output == "rotation_vector":
        return StepIncrements(att, vel)
    lam = _attitudes(att, integrator, context)
    prev = np.concatenate([quat.identity((1,)), lam[:-1]], axis=0)
    rotation = quat.quat_to_rotvec(quat.multiply(quat.conjugate(prev), lam), canonical=True, validate=False)
    if vel is None:
        return StepIncrements(rotation, None)
    dw = np.diff(np.concatenate([np.zeros((1, 3)), vel], axis=0), axis=0)
    return StepIncrements(rotation, quat.rotate(quat.conjugate(prev), dw))
