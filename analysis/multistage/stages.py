"""Corrected multistage quaternion attitude equations of Plotnikov (1999).

Stage 1, eqs. (1.5)–(1.6):

    2ν' = ν∘ω_x + μ⁺∘(ω_μ − ω_x) + k (μ⁺ − cν) + l ∫(μ⁺ − cν) dτ + ρ(1 − |ν|²) ν.

Stages 2, 3, … (2.1)–(2.4) have the same form without the kinematic term; the
input of stage j+1 is the frame η^(j) modelled by stage j: its absolute rate
``ω_η(j) = ν_j∘(ω − ω^(j))∘ν̄_j`` and the specific force re-projected on it,
``μ_j⁺ = ν_j∘μ⁺∘ν̄_j``.  The attitude after m stages is the product (2.6)

    ν⁺ = ν_{m−1} ∘ … ∘ ν_1 ∘ ν.

How μ⁺ is formed (``Stage.reference``):

``"external"``
    μ⁺ = μ from another attitude system (first variant, c = 1): every component
    is corrected and the kinematic term is kept.
``"pure"``
    the pure quaternion (1.4) of load factors, ``M = {0, (f × e₂)/g}`` =
    ``(0, −n₃, 0, n₁)`` as in (3.7), compared with ``2ν`` (c = 2) on the
    horizontal components 1 and 3 only: the angles in M are whole angles, those
    in ν half angles.
``"tilt"``
    the tilt quaternion (1.9)–(1.10) with ψ = 0, a unit quaternion of half
    angles, so that the consistent factor is c = 1; corrected on components 1
    and 3 only.  (With c = 2 the stage settles at half the tilt; the report
    shows this numerically.)

The integral is carried as the state ``y`` with ``y' = l (μ⁺ − cν)`` — the
form of (3.1) — so that a gain switch (as at 600 s in section 5) leaves the
accumulated integral correction in place.

Numerical scheme.  Each step of length h is a symmetric (Strang) splitting:
half a step of the correction flow, half a step of the norm flow
``ν' = ½ρ(1 − |ν|²)ν``, the kinematic flow over h, and the two half steps in
reverse order.  The correction flow is linear with constant coefficients on a
step and is integrated exactly (matrix exponential); the norm flow is solved in
closed form (logistic); the kinematic flow is exact for the measured rotation
increment.  The scheme is second order in h; the report shows the
convergence study.  The recursion is sequential by nature and runs as one
plain loop over floats; everything else is vectorised.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from ..core import quaternion as quat
from ..core.validation import as_array, as_float, nonnegative, positive
from .ship_angles import angles_to_quat, quat_to_angles, wrap_angle
from .trajectory import Scenario, SensorData, sample

__all__ = [
    "Stage",
    "MultistageResult",
    "accelerometer_quaternion",
    "tilt_quaternion",
    "run_stage",
    "run_multistage",
    "plotnikov_1999_stages",
    "simulate",
]

_REFERENCES = ("external", "pure", "tilt")
_DEFAULT_C = {"external": 1.0, "pure": 2.0, "tilt": 1.0}


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

    Examples
    --------
    >>> Stage(((0.0, 0.01, 5e-5),), "pure").c
    2.0
    """

    schedule: tuple
    reference: str = "pure"
    c: float | None = None
    rho: float = 1.0

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
        if self.reference not in _REFERENCES:
            raise ValueError(f"Expected `reference` in {_REFERENCES}, got {self.reference!r}")
        c = _DEFAULT_C[self.reference] if self.c is None else positive(self.c, "c")
        object.__setattr__(self, "c", c)
        object.__setattr__(self, "rho", nonnegative(self.rho, "rho"))

    @classmethod
    def constant(cls, k, l, reference: str = "pure", **kw) -> Stage:
        """A stage with fixed gains k [1/s], l [1/s²]."""
        return cls(((0.0, k, l),), reference, **kw)

    @property
    def effective_gains(self) -> tuple:
        """Gains of the linearised tilt loop ``s² + K s + L`` [(1/s, 1/s²)] per schedule row.

        In angle terms the correction acts with ``K = kc/2`` and ``L = lc/2``
        (ν carries half angles); for the (1.4) stage with c = 2 they are k and l.
        """
        return tuple((t, k * self.c / 2.0, l * self.c / 2.0) for t, k, l in self.schedule)


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
def _correction_map(k, l, c, tau):
    """Exact flow over ``tau`` of ``v' = ½(k(m − cv) + y)``, ``y' = l(m − cv)`` (m frozen).

    Returns the 2×2 transition matrix and the 2-vector multiplying m.
    """
    a = np.array([[-0.5 * k * c, 0.5, 0.5 * k], [-l * c, 0.0, l], [0.0, 0.0, 0.0]])
    e = expm(a * tau)
    return (e[0, 0], e[0, 1], e[1, 0], e[1, 1], e[0, 2], e[1, 2])


def _segments(schedule, n_steps, step):
    """Step-index ranges of each schedule row (switches rounded to the grid)."""
    starts = [min(n_steps, int(round(t / step))) for t, _, _ in schedule] + [n_steps]
    return [(starts[i], starts[i + 1]) for i in range(len(schedule))]


def _loop_horizontal(nu, dq, target, segments, maps, rho, step):
    """Splitting recursion with correction on components 1 and 3 (references "pure", "tilt").

    ``target`` holds (m1, m3) per step.  Sequential by nature; plain floats for speed.
    """
    n0, n1, n2, n3 = nu
    y1 = y3 = 0.0
    out = [(n0, n1, n2, n3)]
    outy = [(0.0, 0.0)]
    grow = math.exp(rho * step * 0.5)
    sqrt = math.sqrt
    norm_flow = rho > 0.0
    for (i0, i1), (e11, e12, e21, e22, f1, f2) in zip(segments, maps):
        for n in range(i0, i1):
            m1, m3 = target[n]
            a1 = e11 * n1 + e12 * y1 + f1 * m1
            y1 = e21 * n1 + e22 * y1 + f2 * m1
            a3 = e11 * n3 + e12 * y3 + f1 * m3
            y3 = e21 * n3 + e22 * y3 + f2 * m3
            a0, a2 = n0, n2
            if norm_flow:
                r = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3
                f = sqrt(grow / (1.0 - r + r * grow))  # exact norm flow over h/2
                a0, a1, a2, a3 = a0 * f, a1 * f, a2 * f, a3 * f
            b0, b1, b2, b3 = dq[n]
            c0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
            c1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
            c2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
            c3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0
            if norm_flow:
                r = c0 * c0 + c1 * c1 + c2 * c2 + c3 * c3
                f = sqrt(grow / (1.0 - r + r * grow))  # exact norm flow over h/2
                c0, c1, c2, c3 = c0 * f, c1 * f, c2 * f, c3 * f
            n0, n2 = c0, c2
            n1 = e11 * c1 + e12 * y1 + f1 * m1
            y1 = e21 * c1 + e22 * y1 + f2 * m1
            n3 = e11 * c3 + e12 * y3 + f1 * m3
            y3 = e21 * c3 + e22 * y3 + f2 * m3
            out.append((n0, n1, n2, n3))
            outy.append((y1, y3))
    nu_out = np.array(out)
    y_out = np.zeros_like(nu_out)
    y_out[:, [1, 3]] = np.array(outy)
    return nu_out, y_out


def _loop_external(nu, dq, ref, segments, maps, rho, step):
    """Splitting recursion of the first variant: every component corrected toward ``ref``,
    with the exact kinematic step ``ν ← μ_{n+1} + (ν − μ_n)∘Δq`` of (1.5)."""
    v = list(nu)
    y = [0.0, 0.0, 0.0, 0.0]
    out = [tuple(v)]
    outy = [tuple(y)]
    grow = math.exp(rho * step * 0.5)
    sqrt = math.sqrt
    norm_flow = rho > 0.0
    for (i0, i1), (e11, e12, e21, e22, f1, f2) in zip(segments, maps):
        for n in range(i0, i1):
            p, q = ref[n], ref[n + 1]
            for j in range(4):
                vj, yj, mj = v[j], y[j], p[j]
                v[j] = e11 * vj + e12 * yj + f1 * mj
                y[j] = e21 * vj + e22 * yj + f2 * mj
            a0, a1, a2, a3 = v
            if norm_flow:
                r = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3
                f = sqrt(grow / (1.0 - r + r * grow))  # exact norm flow over h/2
                a0, a1, a2, a3 = a0 * f, a1 * f, a2 * f, a3 * f
            a0, a1, a2, a3 = a0 - p[0], a1 - p[1], a2 - p[2], a3 - p[3]
            b0, b1, b2, b3 = dq[n]
            c0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3 + q[0]
            c1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2 + q[1]
            c2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1 + q[2]
            c3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0 + q[3]
            if norm_flow:
                r = c0 * c0 + c1 * c1 + c2 * c2 + c3 * c3
                f = sqrt(grow / (1.0 - r + r * grow))  # exact norm flow over h/2
                c0, c1, c2, c3 = c0 * f, c1 * f, c2 * f, c3 * f
            v = [c0, c1, c2, c3]
            for j in range(4):
                vj, yj, mj = v[j], y[j], q[j]
                v[j] = e11 * vj + e12 * yj + f1 * mj
                y[j] = e21 * vj + e22 * yj + f2 * mj
            out.append(tuple(v))
            outy.append(tuple(y))
    return np.array(out), np.array(outy)


def run_stage(stage: Stage, step, rotation, force=None, *, gravity: float = 9.81, reference=None, initial=(1.0, 0.0, 0.0, 0.0)):
    """Integrate one stage over a uniform grid.

    Parameters
    ----------
    stage : Stage
    step : float
        Grid step h [s].
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
    """
    if not isinstance(stage, Stage):
        raise TypeError(f"Expected `stage` to be a Stage, got {type(stage).__name__}")
    h = positive(step, "step")
    dq = as_array(rotation, "rotation", last=4)
    if dq.ndim != 2 or dq.shape[0] < 1:
        raise ValueError(f"Expected `rotation` with shape (N, 4), N >= 1, got shape {dq.shape}")
    n_steps = dq.shape[0]
    nu0 = as_array(initial, "initial", last=4)
    segments = _segments(stage.schedule, n_steps, h)
    maps = [_correction_map(k, l, stage.c, 0.5 * h) for _, k, l in stage.schedule]
    start = tuple(float(v) for v in nu0)
    if stage.reference == "external":
        if reference is None:
            raise ValueError("Expected `reference` (the external attitude μ) for a stage with reference 'external', got None")
        ref = as_array(reference, "reference", last=4)
        if ref.shape != (n_steps + 1, 4):
            raise ValueError(f"Expected `reference` with shape ({n_steps + 1}, 4), got shape {ref.shape}")
        return _loop_external(start, dq.tolist(), ref.tolist(), segments, maps, stage.rho, h)
    if force is None:
        raise ValueError(f"Expected `force` for a stage with reference {stage.reference!r}, got None")
    f = as_array(force, "force", last=3)
    if f.shape != (n_steps, 3):
        raise ValueError(f"Expected `force` with shape ({n_steps}, 3), got shape {f.shape}")
    m = accelerometer_quaternion(f, gravity) if stage.reference == "pure" else tilt_quaternion(f)
    return _loop_horizontal(start, dq.tolist(), m[:, [1, 3]].tolist(), segments, maps, stage.rho, h)


# ---------------------------------------------------------------------------
# The cascade
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class MultistageResult:
    """Outcome of a multistage run.

    Attributes
    ----------
    time : ndarray, shape (N+1,)
    stages : ndarray, shape (m, N+1, 4)
        Normalised stage quaternions ν, ν_1, …, ν_{m−1}.
    composite : ndarray, shape (m, N+1, 4)
        ν⁺ after 1, 2, …, m stages, eq. (2.6).
    errors : ndarray, shape (m, N+1, 3)
        Angle errors (Δψ, Δθ, Δγ) = estimate − truth after 1, …, m stages [rad].
    truth : ndarray, shape (N+1, 3)
        True (ψ, θ, γ) [rad].
    """

    time: np.ndarray
    stages: np.ndarray
    composite: np.ndarray
    errors: np.ndarray
    truth: np.ndarray

    def peak(self, since: float = 0.0) -> np.ndarray:
        """Largest |error| per stage and angle for t >= ``since``, shape (m, 3) [rad]."""
        sel = self.time >= since
        return np.abs(self.errors[:, sel, :]).max(axis=1)

    def tilt(self) -> np.ndarray:
        """Tilt error magnitude √(Δθ² + Δγ²) per stage, shape (m, N+1) [rad]."""
        return np.hypot(self.errors[..., 1], self.errors[..., 2])


def _half(dq):
    """Square root of unit quaternions (half the rotation)."""
    return quat.rotvec_to_quat(0.5 * quat.quat_to_rotvec(dq, canonical=True, validate=False), validate=False)


def run_multistage(data: SensorData, stages) -> MultistageResult:
    """Run the cascade (1.5), (2.1)–(2.4) on sampled signals and compose by (2.6).

    Parameters
    ----------
    data : SensorData
        Gyro increments and specific force of the body (see :func:`strapdown.analysis.multistage.trajectory.sample`).
    stages : sequence of Stage
        Stage 1 first.  Only stage 1 may use the reference "external"
        (fed with the true attitude).

    Returns
    -------
    MultistageResult
    """
    if not isinstance(data, SensorData):
        raise TypeError(f"Expected `data` to be a SensorData, got {type(data).__name__}")
    stages = list(stages)
    if not stages or not all(isinstance(s, Stage) for s in stages):
        raise TypeError("Expected `stages` to be a non-empty sequence of Stage")
    if any(s.reference == "external" for s in stages[1:]):
        raise ValueError("Expected the reference 'external' on stage 1 only")
    g = data.scenario.gravity
    dq = quat.rotvec_to_quat(data.gyro, validate=False)
    force = data.accel
    nus, comps = [], []
    comp = None
    for j, stage in enumerate(stages):
        nu, _ = run_stage(stage, data.step, dq, force, gravity=g, reference=data.attitude if stage.reference == "external" else None)
        nu = nu / np.linalg.norm(nu, axis=-1, keepdims=True)
        nus.append(nu)
        comp = nu if comp is None else quat.multiply(nu, comp)
        comps.append(comp)
        if j + 1 < len(stages):
            # Input of the next stage: the frame modelled by this one, (2.2).
            half = _half(dq)
            mid = quat.multiply(nu[:-1], half) + quat.multiply(nu[1:], quat.conjugate(half))
            mid /= np.linalg.norm(mid, axis=-1, keepdims=True)
            force = quat.rotate(mid, force)
            dq = quat.multiply(quat.multiply(nu[:-1], dq), quat.conjugate(nu[1:]))
    comps = np.array(comps)
    est = quat_to_angles(comps)
    errors = wrap_angle(est - data.angles)
    return MultistageResult(time=data.time, stages=np.array(nus), composite=comps, errors=errors, truth=data.angles)


def plotnikov_1999_stages(gravity: float = 9.81, earth_radius: float = 6.371e6, *, switch_time: float = 600.0, rho: float = 1.0) -> tuple:
    """The two stages of Plotnikov (1999), section 5.

    Stage 1: k = 0.01 s⁻¹, l = 0.5·10⁻⁴ s⁻², μ⁺ from (1.9)–(1.10).
    Stage 2: k⁽¹⁾ = 1.5·10⁻² s⁻¹, l⁽¹⁾ = 1.25·10⁻⁴ s⁻² until ``switch_time``,
    then Schuler tuning k⁽¹⁾ = 0, l⁽¹⁾ = g/R; μ₁⁺ from (1.4).

    Parameters
    ----------
    gravity, earth_radius : float
        g [m/s²] and R [m] of the Schuler tuning.
    switch_time : float
        Gain switch of stage 2 [s].
    rho : float
        Norm-keeping gain ρ [1/s] of both stages (not given in the paper).
    """
    g = positive(gravity, "gravity")
    r = positive(earth_radius, "earth_radius")
    t = positive(switch_time, "switch_time")
    return (
        Stage(((0.0, 0.01, 0.5e-4),), "tilt", rho=rho),
        Stage(((0.0, 1.5e-2, 1.25e-4), (t, 0.0, g / r)), "pure", rho=rho),
    )


def simulate(scenario: Scenario | None = None, stages=None, *, step: float = 0.02, rng=0) -> MultistageResult:
    """Sample ``scenario`` and run the cascade ``stages`` (defaults: section 5 of Plotnikov 1999).

    Parameters
    ----------
    scenario : Scenario, optional
    stages : sequence of Stage, optional
    step : float
        Grid step h [s].
    rng : numpy.random.Generator, int or None
        Sensor-noise source.
    """
    scenario = Scenario() if scenario is None else scenario
    stages = plotnikov_1999_stages(scenario.gravity, scenario.earth_radius) if stages is None else stages
    return run_multistage(sample(scenario, step, rng=rng), stages)
