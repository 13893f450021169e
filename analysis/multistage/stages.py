"""Corrected multistage quaternion attitude equations of Plotnikov (1999).

Stage 1, eqs. (1.5)–(1.6)::

    2ν' = ν∘ω_x + μ⁺∘(ω_μ − ω_x) + k (μ⁺ − cν) + l ∫(μ⁺ − cν) dτ + ρ(1 − |ν|²) ν.

Stages 2, 3, … (2.1)–(2.4) have the same form without the kinematic term; the
input of stage j+1 is the frame η^(j) modelled by stage j: its absolute rate
``ω_η(j) = ν_j∘(ω − ω^(j))∘ν̄_j`` and the specific force re-projected on it,
``μ_j⁺ = ν_j∘μ⁺∘ν̄_j``.  The attitude after m stages is the product (2.6)::

    ν⁺ = ν_{m−1} ∘ … ∘ ν_1 ∘ ν.

How μ⁺ is formed (``Stage.reference``):

``"external"``
    μ⁺ = μ from another attitude system (first variant, c = 1): every component
    is corrected and the kinematic term is kept.
``"pure"``
    the pure quaternion (1.4) of load factors, ``M = {0, (f × e₂)/g}`` =
    ``(0, −n₃, 0, n₁)`` as in (3.7): whole angles, compared with ``2ν`` of half
    angles, hence c = 2; only the components 1 and 3 exist.
``"tilt"``
    the tilt quaternion (1.9)–(1.10) with ψ = 0, a unit quaternion of half
    angles, so that the consistent factor is c = 1 (with c = 2 the stage
    settles at half the tilt).  The paper leaves open which components are
    corrected: the horizontal ones, 1 and 3 (default), or all four.

The integral is carried as the state ``y`` with ``y' = l (μ⁺ − cν)`` — the
form of (3.1); what happens to it at a change of the gain schedule is the
``switch`` of the stage (:data:`strapdown.analysis.multistage.stage_recursion.SWITCH_MODES`).

Each stage is integrated by the splitting recursion of
:mod:`strapdown.analysis.multistage.stage_recursion` (second order).  The
compiled engine runs the whole cascade, composition and angle errors
included, in one pass (:func:`strapdown.analysis.multistage.stage_recursion.cascade_loop`);
the reference engine runs it stage by stage in plain Python with vectorised
numpy in between, and the tests hold the two equal to round-off.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..core import budget
from ..core import quaternion as quat
from ..core.validation import as_array, as_float, nonnegative, positive
from .sensors import SensorData
from .ship_angles import angles_to_quat, quat_to_angles, wrap_angle
from .stage_recursion import SWITCH_MODES, correction_map
from .trajectory import Scenario, sample

__all__ = [
    "REFERENCES",
    "ENGINES",
    "Stage",
    "StagePeaks",
    "MultistageResult",
    "accelerometer_quaternion",
    "tilt_quaternion",
    "run_stage",
    "recursion_inputs",
    "run_multistage",
    "multistage_peaks",
    "plotnikov_1999_stages",
    "simulate",
]

#: How μ⁺ is formed (module docstring).
REFERENCES = ("external", "pure", "tilt")
#: Implementations of the stage recursion: numba-compiled, or the plain-Python reference.
ENGINES = ("compiled", "python")
_DEFAULT_C = {"external": 1.0, "pure": 2.0, "tilt": 1.0}
_DEFAULT_COMPONENTS = {"external": (0, 1, 2, 3), "pure": (1, 3), "tilt": (1, 3)}


@dataclass(frozen=True)
class Stage:
    """One corrected attitude stage and its gain schedule.

    Parameters
    ----------
    schedule : sequence of (t_start, k, l)
        Piecewise-constant gains: from ``t_start`` [s] on, position gain k [1/s]
        and integral gain l [1/s²].  The first ``t_start`` must be 0 and the
        times must increase.  Any finite gains are accepted (unstable ones too).
    reference : {"external", "pure", "tilt"}
        How μ⁺ is formed (module docstring).
    c : float, optional
        The factor c of (1.5); by default 1 for "external" and "tilt", 2 for "pure".
    rho : float
        Norm-keeping gain ρ [1/s], >= 0.
    components : tuple of int, optional
        Corrected components of ν (0 … 3); by default (1, 3) for "pure" and
        "tilt", all four for "external".  "pure" has only 1 and 3.
    switch : {"carry", "rescale", "bumpless"}
        What the integral state does at a change of the schedule: kept,
        rescaled by ``l_new/l_old``, or shifted to keep the correction continuous.

    Examples
    --------
    >>> Stage(((0.0, 0.01, 5e-5),), "pure").c
    2.0
    >>> Stage(((0.0, 0.01, 5e-5),), "tilt", components=(0, 1, 2, 3)).components
    (0, 1, 2, 3)
    """

    schedule: tuple
    reference: str = "pure"
    c: float | None = None
    rho: float = 1.0
    components: tuple | None = None
    switch: str = "carry"

    def __post_init__(self):
        rows = self.schedule
        if isinstance(rows, np.ndarray):
            rows = rows.tolist()
        try:
            rows = [tuple(r) for r in rows]
        except TypeError:
            raise TypeError(f"Expected `schedule` to be a sequence of (t_start, k, l), got {type(self.schedule).__name__}") from None
        if not rows:
            raise ValueError("Expected `schedule` to hold at least one (t_start, k, l) row, got none")
        clean = []
        for i, r in enumerate(rows):
            if len(r) != 3:
                raise ValueError(f"Expected `schedule[{i}]` to be (t_start, k, l), got {r!r}")
            clean.append((as_float(r[0], f"schedule[{i}].t_start"), as_float(r[1], f"schedule[{i}].k"), as_float(r[2], f"schedule[{i}].l")))
        if clean[0][0] != 0.0:
            raise ValueError(f"Expected `schedule[0].t_start` = 0, got {clean[0][0]:g}")
        if any(b[0] <= a[0] for a, b in zip(clean, clean[1:])):
            raise ValueError("Expected `schedule` start times to increase strictly")
        object.__setattr__(self, "schedule", tuple(clean))
        if self.reference not in REFERENCES:
            raise ValueError(f"Expected `reference` in {REFERENCES}, got {self.reference!r}")
        c = _DEFAULT_C[self.reference] if self.c is None else positive(self.c, "c")
        object.__setattr__(self, "c", c)
        object.__setattr__(self, "rho", nonnegative(self.rho, "rho"))
        comps = _DEFAULT_COMPONENTS[self.reference] if self.components is None else self.components
        try:
            comps = tuple(sorted({int(j) for j in comps}))
        except (TypeError, ValueError):
            raise TypeError(f"Expected `components` to be a sequence of component indices 0..3, got {self.components!r}") from None
        if not comps or any(j not in (0, 1, 2, 3) for j in comps):
            raise ValueError(f"Expected `components` among 0, 1, 2, 3 (at least one), got {self.components!r}")
        if self.reference == "pure" and not set(comps) <= {1, 3}:
            raise ValueError(f"Expected `components` within (1, 3) for the reference 'pure' (the quaternion (1.4) has no components 0 and 2), got {comps}")
        object.__setattr__(self, "components", comps)
        if self.switch not in SWITCH_MODES:
            raise ValueError(f"Expected `switch` in {SWITCH_MODES}, got {self.switch!r}")
        if self.switch == "rescale" and any(row[2] == 0.0 for row in clean[:-1]):
            raise ValueError("Expected a nonzero integral gain `l` before every change of the schedule with switch 'rescale' (the rescaling divides by it)")

    @classmethod
    def constant(cls, k, l, reference: str = "pure", **kw) -> Stage:
        """A stage with fixed gains.

        Parameters
        ----------
        k : float
            Position gain [1/s].
        l : float
            Integral gain [1/s²].
        reference : str
            As for :class:`Stage`.
        **kw
            Other fields of :class:`Stage`.

        Returns
        -------
        Stage
        """
        return cls(((0.0, k, l),), reference, **kw)

    @property
    def angle_factor(self) -> float:
        """How many half angles of ν one unit of μ⁺ carries: 2 for "pure" (whole angles), 1 otherwise."""
        return 2.0 if self.reference == "pure" else 1.0

    @property
    def effective_gains(self) -> tuple:
        """Gains of the linearised tilt loop ``s² + K s + L`` [(1/s, 1/s²)] per schedule row.

        In angle terms the correction acts with ``K = kc/2`` and ``L = lc/2``
        (ν carries half angles); for the (1.4) stage with c = 2 they are k and l.
        """
        return tuple((t, k * self.c / 2.0, l * self.c / 2.0) for t, k, l in self.schedule)

    @property
    def static_gain(self) -> float:
        """Steady-state estimate per unit of true tilt: ``a/c`` with a = :attr:`angle_factor` (1 when consistent)."""
        return self.angle_factor / self.c


# ---------------------------------------------------------------------------
# Accelerometer quaternions
# ---------------------------------------------------------------------------
def accelerometer_quaternion(force, gravity: float):
    """Pure quaternion (1.4) of load factors: ``{0, (f × e₂)/g} = (0, −n₃, 0, n₁)``.

    Parameters
    ----------
    force : array_like, shape (..., 3)
        Specific force in the frame being levelled [m/s²].
    gravity : float
        g [m/s²].

    Returns
    -------
    ndarray, shape (..., 4)
        For small tilts the vector part is the horizontal part of the rotation
        vector of the frame relative to the horizon (whole angles), see (3.7).
    """
    f = as_array(force, "force", last=3)
    g = positive(gravity, "gravity")
    zero = np.zeros(f.shape[:-1])
    return np.stack([zero, -f[..., 2] / g, zero, f[..., 0] / g], axis=-1)


def tilt_quaternion(force):
    """Tilt quaternion (1.9)–(1.10): attitude with ψ = 0 whose vertical is the measured one.

    ``sin θ = n₁/n``, ``cos θ = h/n``, ``sin γ = −n₃/h``, ``cos γ = n₂/h`` with
    ``h = √(n₂² + n₃²)``, then μ of (3.6) with ψ = 0.  (The signs follow from
    (1.8); the printed ``cos γ = −n₂/h`` contradicts ``W₂ = g cos θ cos γ``.)

    Parameters
    ----------
    force : array_like, shape (..., 3)
        Specific force in the frame being levelled [m/s²] (its scale cancels).

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternion.
    """
    f = as_array(force, "force", last=3)
    h = np.hypot(f[..., 1], f[..., 2])
    pitch = np.arctan2(f[..., 0], h)
    roll = np.arctan2(-f[..., 2], f[..., 1])
    return angles_to_quat(np.zeros_like(pitch), pitch, roll)


# ---------------------------------------------------------------------------
# One stage
# ---------------------------------------------------------------------------
def _segments(schedule, n_steps, step) -> np.ndarray:
    """First step of each schedule row (switches rounded to the grid), and N."""
    starts = [min(n_steps, int(round(t / step))) for t, _, _ in schedule] + [n_steps]
    return np.array(starts, dtype=np.int64)


def run_stage(stage: Stage, step, rotation, force=None, *, gravity: float = 9.81, reference=None, initial=(1.0, 0.0, 0.0, 0.0), engine: str = "compiled"):
    """Integrate one stage over a uniform grid.

    Parameters
    ----------
    stage : Stage
        The stage.
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    rotation : array_like, shape (N, 4)
        Unit quaternion increments of the input frame over each step (the
        body x for stage 1, the frame η^(j) for stage j+1): ``Δq_n`` with
        ``2Δq' = Δq∘ω`` over [t_n, t_{n+1}].
    force : array_like, shape (N, 3)
        Mean specific force in the input frame over each step [m/s²]
        (for references "pure" and "tilt").
    gravity : float
        g [m/s²] used by (1.4).
    reference : array_like, shape (N+1, 4)
        External attitude μ at the grid points (reference "external").
    initial : array_like, shape (4,)
        ν(t0).
    engine : {"compiled", "python"}
        The numba-compiled recursion, or the plain-Python reference
        (:mod:`strapdown.analysis.multistage.stage_recursion`).

    Returns
    -------
    nu : ndarray, shape (N+1, 4)
        Stage estimate ν at the grid points.
    y : ndarray, shape (N+1, 4)
        Integral correction state.

    Raises
    ------
    ValueError
        For missing or mis-shaped inputs.
    TypeError
        If ``stage`` is not a Stage.

    References
    ----------
    Plotnikov (1999), eqs. (1.5), (2.1).
    """
    from . import stage_recursion

    if engine not in ENGINES:
        raise ValueError(f"Expected `engine` in {ENGINES}, got {engine!r}")
    args = recursion_inputs(stage, step, rotation, force, gravity=gravity, reference=reference, initial=initial)
    loop = stage_recursion.stage_loop if engine == "compiled" else stage_recursion.stage_loop_python
    return loop(*args)


def recursion_inputs(stage: Stage, step, rotation, force=None, *, gravity: float = 9.81, reference=None, initial=(1.0, 0.0, 0.0, 0.0)) -> tuple:
    """The arguments of :func:`strapdown.analysis.multistage.stage_recursion.stage_loop` for one stage.

    Parameters
    ----------
    stage, step, rotation, force, gravity, reference, initial
        As for :func:`run_stage`.

    Returns
    -------
    tuple
        ``(nu0, dq, ref_start, ref_end, mask, kinematic, seg_start, maps, gains, switch, c, rho, step)``.

    Raises
    ------
    ValueError
        For missing or mis-shaped inputs.
    TypeError
        If ``stage`` is not a Stage.
    """
    if not isinstance(stage, Stage):
        raise TypeError(f"Expected `stage` to be a Stage, got {type(stage).__name__}")
    h = positive(step, "step")
    dq = np.ascontiguousarray(as_array(rotation, "rotation", last=4))
    if dq.ndim != 2 or dq.shape[0] < 1:
        raise ValueError(f"Expected `rotation` with shape (N, 4), N >= 1, got shape {dq.shape}")
    n_steps = dq.shape[0]
    nu0 = as_array(initial, "initial", last=4).reshape(4)
    if stage.reference == "external":
        if reference is None:
            raise ValueError("Expected `reference` (the external attitude μ) for a stage with reference 'external', got None")
        ref = as_array(reference, "reference", last=4)
        if ref.shape != (n_steps + 1, 4):
            raise ValueError(f"Expected `reference` with shape ({n_steps + 1}, 4), got shape {ref.shape}")
        ref_start, ref_end = np.ascontiguousarray(ref[:-1]), np.ascontiguousarray(ref[1:])
    else:
        if force is None:
            raise ValueError(f"Expected `force` for a stage with reference {stage.reference!r}, got None")
        f = as_array(force, "force", last=3)
        if f.shape != (n_steps, 3):
            raise ValueError(f"Expected `force` with shape ({n_steps}, 3), got shape {f.shape}")
        m = accelerometer_quaternion(f, gravity) if stage.reference == "pure" else tilt_quaternion(f)
        ref_start = ref_end = np.ascontiguousarray(m)
    mask = np.array([j in stage.components for j in range(4)])
    maps = np.array([correction_map(k, l, stage.c, 0.5 * h) for _, k, l in stage.schedule])
    gains = np.array([(k, l) for _, k, l in stage.schedule], dtype=float)
    return (nu0, dq, ref_start, ref_end, mask, stage.reference == "external", _segments(stage.schedule, n_steps, h), maps, gains, SWITCH_MODES.index(stage.switch), stage.c, stage.rho, h)


# ---------------------------------------------------------------------------
# The cascade
# ---------------------------------------------------------------------------
class StagePeaks(NamedTuple):
    """Largest absolute angle errors after one stage of the cascade [rad].

    Attributes
    ----------
    yaw, pitch, roll : float
        Peaks of ``|Δψ|``, ``|Δθ|``, ``|Δγ|``.
    tilt : float
        Peak of √(Δθ² + Δγ²).
    """

    yaw: float
    pitch: float
    roll: float
    tilt: float

    def over(self, other: StagePeaks) -> StagePeaks:
        """Component by component ``self / other``: e.g. the reduction of each peak by a second stage.

        Parameters
        ----------
        other : StagePeaks
            The denominators.

        Returns
        -------
        StagePeaks
            Ratios [-].
        """
        return StagePeaks(*(a / b for a, b in zip(self, other)))

    def relative_to(self, other: StagePeaks) -> StagePeaks:
        """Component by component ``self / other − 1`` [-].

        Parameters
        ----------
        other : StagePeaks
            The reference.

        Returns
        -------
        StagePeaks
        """
        return StagePeaks(*(a / b - 1.0 for a, b in zip(self, other)))


@dataclass(frozen=True)
class MultistageResult:
    """Outcome of a multistage run.

    Attributes
    ----------
    time : ndarray, shape (N+1,)
        Grid [s].
    stages : ndarray, shape (m, N+1, 4)
        Normalised stage quaternions ν, ν_1, …, ν_{m−1}.
    composite : ndarray, shape (m, N+1, 4)
        ν⁺ after 1, 2, …, m stages, eq. (2.6).
    errors : ndarray, shape (m, N+1, 3)
        Angle errors (Δψ, Δθ, Δγ) = estimate − truth after 1, …, m stages [rad].
    truth : ndarray, shape (N+1, 3)
        True (ψ, θ, γ) relative to η [rad].
    """

    time: np.ndarray
    stages: np.ndarray
    composite: np.ndarray
    errors: np.ndarray
    truth: np.ndarray

    def peak(self, since: float = 0.0, until: float = np.inf) -> np.ndarray:
        """Largest ``|error|`` per stage and angle for ``since <= t <= until``.

        Parameters
        ----------
        since, until : float
            Time window [s].

        Returns
        -------
        ndarray, shape (m, 3)
            [rad].
        """
        sel = (self.time >= since) & (self.time <= until)
        return np.abs(self.errors[:, sel, :]).max(axis=1)

    def tilt(self) -> np.ndarray:
        """Tilt error magnitude √(Δθ² + Δγ²) per stage, shape (m, N+1) [rad]."""
        return np.hypot(self.errors[..., 1], self.errors[..., 2])

    def peaks(self, since: float = 0.0, until: float = np.inf) -> tuple:
        """:class:`StagePeaks` after each stage for ``since <= t <= until``.

        Parameters
        ----------
        since, until : float
            Time window [s].

        Returns
        -------
        tuple of StagePeaks
        """
        sel = (self.time >= since) & (self.time <= until)
        p = np.abs(self.errors[:, sel, :]).max(axis=1)
        tilt = self.tilt()[:, sel].max(axis=1)
        return tuple(StagePeaks(float(a), float(b), float(c), float(d)) for (a, b, c), d in zip(p, tilt))

    def peak_times(self, since: float = 0.0, until: float = np.inf) -> tuple:
        """When the peaks of :meth:`peaks` occur, after each stage.

        Parameters
        ----------
        since, until : float
            Time window [s].

        Returns
        -------
        tuple of StagePeaks
            Times [s] of the largest ``|Δψ|``, ``|Δθ|``, ``|Δγ|`` and tilt (the first, if repeated).
        """
        sel = np.flatnonzero((self.time >= since) & (self.time <= until))
        t = self.time[sel]
        i = np.abs(self.errors[:, sel, :]).argmax(axis=1)
        j = self.tilt()[:, sel].argmax(axis=1)
        return tuple(StagePeaks(float(t[a]), float(t[b]), float(t[c]), float(t[d])) for (a, b, c), d in zip(i, j))


def _half(dq):
    """Square root of unit quaternions (half the rotation)."""
    return quat.rotvec_to_quat(0.5 * quat.quat_to_rotvec(dq, canonical=True, validate=False), validate=False)


def _cascade_inputs(data: SensorData, stages: list) -> tuple:
    """The stage parameters of :func:`strapdown.analysis.multistage.stage_recursion.cascade_loop`, padded to the longest schedule."""
    from .stage_recursion import KINDS

    n_steps, h = data.gyro.shape[0], data.step
    m, n_max = len(stages), max(len(st.schedule) for st in stages)
    seg_start = np.full((m, n_max + 1), n_steps, dtype=np.int64)
    maps, gains = np.zeros((m, n_max, 6)), np.ones((m, n_max, 2))
    for j, st in enumerate(stages):
        rows = len(st.schedule)
        seg_start[j, : rows + 1] = _segments(st.schedule, n_steps, h)
        maps[j, :rows] = [correction_map(k, l, st.c, 0.5 * h) for _, k, l in st.schedule]
        gains[j, :rows] = [(k, l) for _, k, l in st.schedule]
    return (
        np.array([KINDS.index(st.reference) for st in stages], dtype=np.int64),
        np.array([[i in st.components for i in range(4)] for st in stages]),
        np.array([st.c for st in stages]),
        np.array([st.rho for st in stages]),
        np.array([SWITCH_MODES.index(st.switch) for st in stages], dtype=np.int64),
        seg_start,
        np.array([len(st.schedule) for st in stages], dtype=np.int64),
        maps,
        gains,
        np.tile([1.0, 0.0, 0.0, 0.0], (m, 1)),
    )


def _checked(data, stages, engine) -> list:
    if not isinstance(data, SensorData):
        raise TypeError(f"Expected `data` to be a SensorData, got {type(data).__name__}")
    stages = list(stages)
    if not stages or not all(isinstance(s, Stage) for s in stages):
        raise TypeError("Expected `stages` to be a non-empty sequence of Stage")
    if any(s.reference == "external" for s in stages[1:]):
        raise ValueError("Expected the reference 'external' on stage 1 only")
    if engine not in ENGINES:
        raise ValueError(f"Expected `engine` in {ENGINES}, got {engine!r}")
    return stages


def _compiled_cascade(data: SensorData, stages: list, store: bool, terms=None) -> tuple:
    from .stage_recursion import cascade_loop

    return cascade_loop(data.gyro, data.accel, data.attitude, data.angles, data.scenario.gravity, data.step, *_cascade_inputs(data, stages), store=store, terms=terms)


def run_multistage(data: SensorData, stages, *, engine: str = "compiled") -> MultistageResult:
    """Run the cascade (1.5), (2.1)–(2.4) on sampled signals and compose by (2.6).

    The input of stage j+1 is the frame modelled by stage j, (2.2): its
    increments ``ν_n ∘ Δq_n ∘ ν̄_{n+1}`` (the discrete form of
    ``ω_η(1) = ν∘(ω − ω^(1))∘ν̄``) and the specific force re-projected with
    the stage estimate at mid-step.

    Parameters
    ----------
    data : SensorData
        Gyro increments and specific force of the body
        (:func:`strapdown.analysis.multistage.trajectory.sample`).
    stages : sequence of Stage
        Stage 1 first.  Only stage 1 may use the reference "external"
        (fed with the true attitude).
    engine : {"compiled", "python"}
        "compiled": the whole cascade in one compiled pass
        (:func:`strapdown.analysis.multistage.stage_recursion.cascade_loop`);
        "python": stage after stage with the plain-Python recursion
        (:func:`run_stage`) and vectorised numpy in between, the reference.
        Both agree to round-off.

    Returns
    -------
    MultistageResult

    Raises
    ------
    TypeError
        For a wrong ``data`` or ``stages`` type.
    ValueError
        If a stage after the first uses the reference "external", for an
        unknown engine, or if the composite attitude is not finite.

    References
    ----------
    Plotnikov (1999), eqs. (1.5), (2.1)–(2.6).
    """
    stages = _checked(data, stages, engine)
    if engine == "compiled":
        _, nus, comps, errors = _compiled_cascade(data, stages, True)
        return MultistageResult(time=data.time, stages=nus, composite=comps, errors=errors, truth=data.angles)
    g = data.scenario.gravity
    dq = quat.rotvec_to_quat(data.gyro, validate=False)
    force = data.accel
    nus, comps = [], []
    comp = None
    for j, stage in enumerate(stages):
        ref = data.attitude if stage.reference == "external" else None
        nu, _ = run_stage(stage, data.step, dq, force, gravity=g, reference=ref, engine=engine)
        nu = nu / np.linalg.norm(nu, axis=-1, keepdims=True)
        nus.append(nu)
        comp = nu if comp is None else quat.multiply(nu, comp)
        comps.append(comp)
        if j + 1 < len(stages):
            half = _half(dq)
            mid = quat.multiply(nu[:-1], half) + quat.multiply(nu[1:], quat.conjugate(half))
            mid /= np.linalg.norm(mid, axis=-1, keepdims=True)
            force = quat.rotate(mid, force)
            dq = quat.multiply(quat.multiply(nu[:-1], dq), quat.conjugate(nu[1:]))
    comps = np.array(comps)
    est = quat_to_angles(comps)
    errors = wrap_angle(est - data.angles)
    return MultistageResult(time=data.time, stages=np.array(nus), composite=comps, errors=errors, truth=data.angles)


def multistage_peaks(data: SensorData, stages, *, engine: str = "compiled", terms=None) -> np.ndarray:
    """Peak errors of the cascade over the whole run, without keeping the series.

    The same as ``run_multistage(data, stages).peaks()`` (to round-off), for
    Monte Carlo trials: the compiled engine forms the peaks on the way.

    Parameters
    ----------
    data : SensorData
        Gyro increments and specific force of the body.
    stages : sequence of Stage
        Stage 1 first (as for :func:`run_multistage`).
    engine : {"compiled", "python"}
        As for :func:`run_multistage`.
    terms : ndarray, optional
        :func:`strapdown.analysis.multistage.stage_recursion.bound_terms` of
        ``data.attitude`` and ``data.angles`` (compiled engine), for many
        records on one truth: formed once instead of at every call.

    Returns
    -------
    ndarray, shape (m, 4)
        Largest ``|Δψ|``, ``|Δθ|``, ``|Δγ|`` and √(Δθ² + Δγ²) after 1, …, m stages [rad].

    Raises
    ------
    TypeError
        For a wrong ``data`` or ``stages`` type.
    ValueError
        As :func:`run_multistage`.

    References
    ----------
    Plotnikov (1999), eqs. (1.5), (2.1)–(2.6).
    """
    stages = _checked(data, stages, engine)
    if engine == "compiled":
        return _compiled_cascade(data, stages, False, terms)[0]
    return np.array([tuple(p) for p in run_multistage(data, stages, engine=engine).peaks()])


def plotnikov_1999_stages(
    gravity: float = 9.81,
    earth_radius: float = 6.371e6,
    *,
    switch_time: float | None = None,
    rho: float = 1.0,
    stage1_reference: str = "tilt",
    stage1_c: float | None = None,
    stage1_components: tuple | None = None,
    switch: str = "carry",
) -> tuple:
    """The two stages of Plotnikov (1999), section 5, with the readings the text leaves open.

    Stage 1: k = 0.01 s⁻¹, l = 0.5·10⁻⁴ s⁻² (printed), μ⁺ from (1.9)–(1.10).
    Stage 2: k⁽¹⁾ = 1.5·10⁻² s⁻¹, l⁽¹⁾ = 1.25·10⁻⁴ s⁻² until the switch,
    then Schuler tuning k⁽¹⁾ = 0, l⁽¹⁾ = g/R; μ₁⁺ from (1.4).

    Parameters
    ----------
    gravity : float
        g [m/s²] of the Schuler tuning.
    earth_radius : float
        R [m] of the Schuler tuning.
    switch_time : float, optional
        Gain switch of stage 2 [s]; default the printed 600 s.
    rho : float
        Norm-keeping gain ρ [1/s] of both stages (not given in the paper).
    stage1_reference : {"tilt", "pure"}
        μ⁺ of stage 1: (1.10) as section 5 says, or (1.4).
    stage1_c : float, optional
        c of stage 1; default the consistent one (1 for "tilt", 2 for "pure").
    stage1_components : tuple of int, optional
        Components corrected by stage 1; default (1, 3).
    switch : {"carry", "rescale", "bumpless"}
        What the integral state of stage 2 does at the switch.

    Returns
    -------
    tuple of Stage
    """
    from ...derivations.multistage.published import PRINTED_GAINS

    g = positive(gravity, "gravity")
    r = positive(earth_radius, "earth_radius")
    t = positive(PRINTED_GAINS.switch_time if switch_time is None else switch_time, "switch_time")
    if stage1_reference not in ("tilt", "pure"):
        raise ValueError(f"Expected `stage1_reference` in ('tilt', 'pure'), got {stage1_reference!r}")
    k1, l1 = PRINTED_GAINS.stage1
    k2, l2 = PRINTED_GAINS.stage2_before
    return (
        Stage(((0.0, k1, l1),), stage1_reference, c=stage1_c, rho=rho, components=stage1_components),
        Stage(((0.0, k2, l2), (t, 0.0, g / r)), "pure", rho=rho, switch=switch),
    )


def simulate(scenario: Scenario | None = None, stages=None, *, step: float = 0.02, rng=None, engine: str = "compiled", limits: budget.Limits | None = None) -> MultistageResult:
    """Sample ``scenario`` and run the cascade ``stages`` (defaults: section 5 of Plotnikov 1999).

    Parameters
    ----------
    scenario : Scenario, optional
        Default :class:`strapdown.analysis.multistage.trajectory.Scenario`.
    stages : sequence of Stage, optional
        Default :func:`plotnikov_1999_stages`.
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    rng : numpy.random.Generator, int, SeedSequence or None
        Sensor-noise source.
    engine : {"compiled", "python"}
        Implementation of the stage recursion.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    MultistageResult

    Raises
    ------
    ValueError
        For a bad ``step``, or a run whose estimated memory or time exceeds
        ``limits`` (:class:`~strapdown.analysis.core.budget.BudgetExceeded`,
        naming the scenario's ``duration`` and ``step``).
    """
    scenario = Scenario() if scenario is None else scenario
    stages = plotnikov_1999_stages(scenario.gravity, scenario.earth_radius) if stages is None else stages
    return run_multistage(sample(scenario, step, rng=rng, limits=limits), stages, engine=engine)
