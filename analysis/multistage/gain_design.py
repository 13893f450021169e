"""Gains of a corrected stage from a requested loop, Schuler tuning, and the Schuler error budget.

The linearised tilt channel of a stage is ``θ'' + K θ' + L θ = …`` with
``K = kc/2`` and ``L = lc/2`` (ν carries half angles, Plotnikov 1999, (3.8)),
and the estimate settles at ``a/c`` times the true tilt, with a = 1 for the
half-angle tilt quaternion (1.10) and a = 2 for the whole-angle quaternion
(1.4) (:attr:`strapdown.analysis.multistage.stages.Stage.static_gain`).  So:

* a requested natural frequency ω_n and damping ζ give ``K = 2ζω_n``,
  ``L = ω_n²`` and ``k = 2K/c``, ``l = 2L/c`` (:func:`design_gains`);
* Schuler tuning makes the integral path turn the frame by exactly the
  transport rate, ``y' = f_h/R``: ``k = 0``, ``l = 2g/(aR)`` with the
  consistent ``c = a`` — ``l = g/R`` for (1.4) (:func:`schuler_gains`, (3.11));
* a change from one to the other keeps the correction continuous with the
  ``"bumpless"`` switch (:func:`switched_stage`).

The Schuler-tuned stage answers a constant gyro drift d, accelerometer bias b
and an acceleration u that the accelerometers do not sense (all in the level
frame, axes north, up, east) in closed form (:class:`SchulerErrorBudget`),
with ``Ω_s = √(g/R)`` and ``τ = t − t₀``.  Its equilibrium tilt is
``((b₁ − u₁)/g, −(b₃ − u₃)/g)`` (pitch, roll); started level with an empty
integral at t₀,

    Δθ = (d₃/Ω_s) sin Ω_s τ + ((b₁ − u₁)/g)(1 − cos Ω_s τ),
    Δγ = (d₁/Ω_s) sin Ω_s τ − ((b₃ − u₃)/g)(1 − cos Ω_s τ),
    Δψ = d₂ τ,

(checked by simulation in :func:`check_error_budget`); entered at t₀ from a
damped phase that has settled — tilt at the accelerometer level ``b/g``, drift
held by the integral — only the unsensed part oscillates:

    Δθ = b₁/g − (u₁/g)(1 − cos Ω_s τ),    Δγ = −b₃/g + (u₃/g)(1 − cos Ω_s τ).

With plumb-bob gravity the horizontal centripetal acceleration ``Ω²R sin φ cos φ``
(:func:`strapdown.analysis.multistage.earth.horizontal_centripetal`) turns the
inertial velocity that the Schuler loop integrates, yet no accelerometer
senses it: it is such a u, to the north (:func:`section5_budget`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.validation import as_array, as_float, nonnegative, positive
from . import earth
from .sensors import SensorErrors
from .stages import REFERENCES, Stage, StagePeaks, simulate
from .tilt_loop import StageLoop, step_response_on_grid
from .trajectory import Scenario

__all__ = [
    "StageGains",
    "design_gains",
    "schuler_gains",
    "switched_stage",
    "SchulerErrorBudget",
    "schuler_error_budget",
    "section5_budget",
    "BudgetCheck",
    "check_error_budget",
    "static_tilt_estimate",
    "RateTransient",
    "initial_rate_transient",
    "DesignCheck",
    "check_design",
    "largest_design_difference",
]

_ANGLE = {"external": 1.0, "tilt": 1.0, "pure": 2.0}


def _reference(reference):
    if reference not in REFERENCES:
        raise ValueError(f"Expected `reference` in {REFERENCES}, got {reference!r}")
    return reference


@dataclass(frozen=True)
class StageGains:
    """Gains (k, l) of a stage with the factor c of its reference.

    Parameters
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    c : float
        Factor c of (1.5) [-].
    reference : {"external", "pure", "tilt"}
        The reference quaternion the gains are meant for.

    Examples
    --------
    >>> g = design_gains(5e-3, 0.7, reference="tilt")
    >>> round(g.k, 6), round(g.l, 8), round(g.damping, 3)
    (0.014, 5e-05, 0.7)
    """

    k: float
    l: float
    c: float
    reference: str

    def __post_init__(self):
        object.__setattr__(self, "k", as_float(self.k, "k"))
        object.__setattr__(self, "l", as_float(self.l, "l"))
        object.__setattr__(self, "c", positive(self.c, "c"))
        _reference(self.reference)

    @property
    def loop_gains(self) -> tuple:
        """``(K, L) = (kc/2, lc/2)`` of the tilt loop ``s² + Ks + L`` [(1/s, 1/s²)]."""
        return (self.k * self.c / 2.0, self.l * self.c / 2.0)

    @property
    def natural_frequency(self) -> float:
        """ω_n = √L [rad/s] (NaN for L < 0)."""
        big_l = self.loop_gains[1]
        return float(np.sqrt(big_l)) if big_l >= 0 else float("nan")

    @property
    def damping(self) -> float:
        """ζ = K/(2√L) [-] (NaN for L <= 0)."""
        big_k, big_l = self.loop_gains
        return float(big_k / (2.0 * np.sqrt(big_l))) if big_l > 0 else float("nan")

    def loop(self, gravity: float = 9.81, earth_radius: float = 6.371e6) -> StageLoop:
        """The linearised loop with these gains (python-control).

        Parameters
        ----------
        gravity : float
            g [m/s²].
        earth_radius : float
            R [m].

        Returns
        -------
        StageLoop
        """
        return StageLoop(*self.loop_gains, gravity, earth_radius)

    def stage(self, **kw) -> Stage:
        """A stage with these gains for the whole run.

        Parameters
        ----------
        **kw
            Other fields of :class:`strapdown.analysis.multistage.stages.Stage` (rho, components).

        Returns
        -------
        Stage
        """
        return Stage.constant(self.k, self.l, self.reference, c=self.c, **kw)


def design_gains(natural_frequency, damping, *, reference: str = "pure", c=None) -> StageGains:
    """Gains of a stage whose tilt loop has the requested natural frequency and damping.

    Parameters
    ----------
    natural_frequency : float
        ω_n [rad/s], > 0.
    damping : float
        ζ [-], >= 0.
    reference : {"external", "pure", "tilt"}
        The stage's reference quaternion.
    c : float, optional
        Factor c; default the consistent one (2 for "pure", 1 otherwise).

    Returns
    -------
    StageGains
        ``k = 4ζω_n/c``, ``l = 2ω_n²/c``.

    Raises
    ------
    ValueError
        For a non-positive frequency, a negative damping or an unknown reference.

    References
    ----------
    Plotnikov (1999), eqs. (3.8)–(3.10).
    """
    wn = positive(natural_frequency, "natural_frequency")
    zeta = nonnegative(damping, "damping")
    ref = _reference(reference)
    cc = _ANGLE[ref] if c is None else positive(c, "c")
    return StageGains(2.0 * (2.0 * zeta * wn) / cc, 2.0 * wn * wn / cc, cc, ref)


def schuler_gains(gravity: float = 9.81, earth_radius: float = 6.371e6, *, reference: str = "pure") -> StageGains:
    """Schuler tuning: k = 0 and the integral gain that turns the frame by the transport rate.

    Parameters
    ----------
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].
    reference : {"pure", "tilt"}
        The stage's accelerometer quaternion: l = g/R with c = 2 for (1.4),
        l = 2g/R with c = 1 for (1.10) (only for small tilts: (1.10) is not
        linear in the specific force).

    Returns
    -------
    StageGains

    Raises
    ------
    ValueError
        For the reference "external" (it has no accelerometer) or bad g, R.

    References
    ----------
    Plotnikov (1999), eqs. (3.11)–(3.12).
    """
    g, r = positive(gravity, "gravity"), positive(earth_radius, "earth_radius")
    if reference not in ("pure", "tilt"):
        raise ValueError(f"Expected `reference` in ('pure', 'tilt') for Schuler tuning, got {reference!r}")
    a = _ANGLE[reference]
    return StageGains(0.0, 2.0 * g / (a * r), a, reference)


def switched_stage(before: StageGains, after: StageGains, switch_time, *, switch: str = "bumpless", **kw) -> Stage:
    """A stage that runs ``before`` until ``switch_time`` and ``after`` from then on.

    Parameters
    ----------
    before, after : StageGains
        Gains of the two phases (same reference and c).
    switch_time : float
        Time of the switch [s], > 0.
    switch : {"carry", "rescale", "bumpless"}
        What the integral state does at the switch; "bumpless" keeps the
        whole correction ``k(m − cν) + y`` continuous.
    **kw
        Other fields of :class:`strapdown.analysis.multistage.stages.Stage` (rho, components).

    Returns
    -------
    Stage

    Raises
    ------
    ValueError
        If the two gain sets belong to different references or factors c.
    """
    if not isinstance(before, StageGains) or not isinstance(after, StageGains):
        raise TypeError("Expected `before` and `after` to be StageGains")
    if (before.reference, before.c) != (after.reference, after.c):
        raise ValueError(f"Expected `before` and `after` for the same reference and c, got {before.reference!r}, c = {before.c:g} and {after.reference!r}, c = {after.c:g}")
    t = positive(switch_time, "switch_time")
    return Stage(((0.0, before.k, before.l), (t, after.k, after.l)), before.reference, c=before.c, switch=switch, **kw)


@dataclass(frozen=True)
class SchulerErrorBudget:
    """Closed-form errors of a Schuler-tuned stage for constant sensor errors (module docstring).

    Parameters
    ----------
    gyro_drift : 3 floats
        Drift about the level axes (1: north, 2: up, 3: east) [rad/s].
    accel_bias : 3 floats
        Bias along the level axes [m/s²].
    unsensed_accel : 3 floats
        Horizontal acceleration of the inertial velocity that no accelerometer senses [m/s²].
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].
    start : float
        t₀, when the Schuler tuning starts [s].
    settled : bool
        False: started level with an empty integral; True: entered from a
        settled damped phase.
    """

    gyro_drift: tuple
    accel_bias: tuple
    unsensed_accel: tuple = (0.0, 0.0, 0.0)
    gravity: float = 9.81
    earth_radius: float = 6.371e6
    start: float = 0.0
    settled: bool = False

    def __post_init__(self):
        for name in ("gyro_drift", "accel_bias", "unsensed_accel"):
            v = np.broadcast_to(as_array(getattr(self, name), name), (3,)) if np.ndim(getattr(self, name)) == 0 else as_array(getattr(self, name), name).reshape(-1)
            if v.shape != (3,):
                raise ValueError(f"Expected `{name}` with 3 components, got shape {v.shape}")
            object.__setattr__(self, name, tuple(float(x) for x in v))
        object.__setattr__(self, "gravity", positive(self.gravity, "gravity"))
        object.__setattr__(self, "earth_radius", positive(self.earth_radius, "earth_radius"))
        object.__setattr__(self, "start", as_float(self.start, "start"))
        object.__setattr__(self, "settled", bool(self.settled))

    @property
    def schuler_frequency(self) -> float:
        """Ω_s = √(g/R) [rad/s]."""
        return float(np.sqrt(self.gravity / self.earth_radius))

    def errors(self, t) -> np.ndarray:
        """(Δψ, Δθ, Δγ) at times ``t`` >= ``start`` [rad], shape (..., 3).

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        ndarray
        """
        tau = np.maximum(as_array(t, "t") - self.start, 0.0)
        w, g = self.schuler_frequency, self.gravity
        d1, d2, d3 = self.gyro_drift
        b1, _, b3 = self.accel_bias
        u1, _, u3 = self.unsensed_accel
        s, one_c = np.sin(w * tau), 1.0 - np.cos(w * tau)
        if self.settled:
            pitch = b1 / g - u1 / g * one_c
            roll = -b3 / g + u3 / g * one_c
        else:
            pitch = d3 / w * s + (b1 - u1) / g * one_c
            roll = d1 / w * s - (b3 - u3) / g * one_c
        return np.stack([d2 * tau, pitch + 0.0 * tau, roll + 0.0 * tau], axis=-1)

    def peaks(self, until: float) -> StagePeaks:
        """Peak ``|errors|`` over ``[start, until]`` (dense evaluation of the closed form).

        Parameters
        ----------
        until : float
            End of the window [s].

        Returns
        -------
        StagePeaks
        """
        end = as_float(until, "until")
        t = np.linspace(self.start, max(end, self.start), 20001)
        e = np.abs(self.errors(t))
        tilt = np.hypot(e[:, 1], e[:, 2]).max()
        return StagePeaks(float(e[:, 0].max()), float(e[:, 1].max()), float(e[:, 2].max()), float(tilt))

    @property
    def pitch_amplitudes(self) -> tuple:
        """Largest pitch error from the drift and from the bias and unsensed acceleration alone [rad].

        Started level: ``(|d₃|/Ω_s, 2|b₁ − u₁|/g)``; settled: ``(0, max(|b₁|, |b₁ − 2u₁|)/g)``.
        """
        b1, u1 = self.accel_bias[0], self.unsensed_accel[0]
        if self.settled:
            return (0.0, max(abs(b1), abs(b1 - 2.0 * u1)) / self.gravity)
        return (abs(self.gyro_drift[2]) / self.schuler_frequency, 2.0 * abs(b1 - u1) / self.gravity)

    @property
    def roll_amplitudes(self) -> tuple:
        """As :attr:`pitch_amplitudes` for the roll (d₁, b₃, u₃) [rad]."""
        b3, u3 = self.accel_bias[2], self.unsensed_accel[2]
        if self.settled:
            return (0.0, max(abs(b3), abs(b3 - 2.0 * u3)) / self.gravity)
        return (abs(self.gyro_drift[0]) / self.schuler_frequency, 2.0 * abs(b3 - u3) / self.gravity)


def schuler_error_budget(
    gyro_drift, accel_bias, *, unsensed_accel=(0.0, 0.0, 0.0), gravity: float = 9.81, earth_radius: float = 6.371e6, start: float = 0.0, settled: bool = False
) -> SchulerErrorBudget:
    """The closed-form error budget of a Schuler-tuned stage (module docstring).

    Parameters
    ----------
    gyro_drift : float or 3 floats
        Drift about the level axes (north, up, east) [rad/s].
    accel_bias : float or 3 floats
        Bias along the level axes [m/s²].
    unsensed_accel : float or 3 floats
        Acceleration no accelerometer senses [m/s²].
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].
    start : float
        Time the Schuler tuning starts [s].
    settled : bool
        Entered from a settled damped phase (True) or level with an empty integral (False).

    Returns
    -------
    SchulerErrorBudget

    Examples
    --------
    >>> b = schuler_error_budget((0.0, 0.0, 5e-8), (1e-3, 0.0, 0.0))
    >>> [round(x, 7) for x in b.pitch_amplitudes]
    [4.03e-05, 0.0002039]
    """
    return SchulerErrorBudget(gyro_drift, accel_bias, unsensed_accel, gravity, earth_radius, start, settled)


def section5_budget(scenario: Scenario | None = None, *, switch_time: float | None = None, include_centripetal: bool = True) -> SchulerErrorBudget:
    """Budget of the Schuler-tuned stage 2 of section 5 after its switch.

    Stage 2 enters the Schuler tuning settled by its damped phase; the body is
    level with x = (north, up, east), so the body sensor errors act on the
    level axes directly; the horizontal centripetal acceleration of the
    Earth's rotation is the unsensed acceleration, to the north.  (The
    azimuth-free frame turns slowly away from north, by ``Ω sin φ`` per
    second, and the manoeuvre and the rocking add transients: the simulation
    shows how far this budget goes.)

    Parameters
    ----------
    scenario : Scenario, optional
        Default :class:`strapdown.analysis.multistage.trajectory.Scenario`.
    switch_time : float, optional
        Start of the Schuler tuning [s]; default the printed 600 s.
    include_centripetal : bool
        Include the centripetal term.

    Returns
    -------
    SchulerErrorBudget
    """
    from ...derivations.multistage.published import PRINTED_GAINS

    sc = Scenario() if scenario is None else scenario
    t0 = PRINTED_GAINS.switch_time if switch_time is None else positive(switch_time, "switch_time")
    u = earth.horizontal_centripetal(sc.latitude, sc.earth_rate, sc.earth_radius) if include_centripetal else 0.0
    return SchulerErrorBudget(sc.sensors.gyro_drift, sc.sensors.accel_bias, (u, 0.0, 0.0), sc.gravity, sc.earth_radius, t0, True)


@dataclass(frozen=True)
class BudgetCheck:
    """A budget against the simulated stage (:func:`check_error_budget`).

    Attributes
    ----------
    time : ndarray
        [s].
    simulated : ndarray, shape (N, 3)
        Simulated (Δψ, Δθ, Δγ) [rad].
    predicted : ndarray, shape (N, 3)
        Closed form [rad].
    max_difference : float
        Largest ``|simulated − predicted|`` [rad].
    scale : float
        Largest ``|predicted|`` [rad].
    """

    time: np.ndarray
    simulated: np.ndarray
    predicted: np.ndarray
    max_difference: float
    scale: float


def check_error_budget(budget: SchulerErrorBudget, *, duration: float = 6000.0, step: float = 1.0) -> BudgetCheck:
    """Simulate a single Schuler-tuned (1.4) stage at rest on a non-rotating Earth with the budget's errors.

    The body is level and aligned with (north, up, east), the stage starts
    at t = 0 with ν(0) = 1; the budget must start at 0.

    Parameters
    ----------
    budget : SchulerErrorBudget
        Drift and bias (level axes = body axes here) and g, R.
    duration : float
        Length of the run [s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).

    Returns
    -------
    BudgetCheck

    Raises
    ------
    ValueError
        If the budget does not start at 0.
    """
    if not isinstance(budget, SchulerErrorBudget):
        raise TypeError(f"Expected `budget` to be a SchulerErrorBudget, got {type(budget).__name__}")
    if budget.start != 0.0 or budget.settled or any(budget.unsensed_accel):
        raise ValueError("Expected a budget started level at t = 0 without unsensed acceleration for the check")
    sensors = SensorErrors(gyro_drift=budget.gyro_drift, accel_bias=budget.accel_bias)
    sc = Scenario(duration=duration, rocking_amplitude=(0.0, 0.0, 0.0), accel=0.0, earth_rate=0.0, gravity=budget.gravity, earth_radius=budget.earth_radius, sensors=sensors)
    st = schuler_gains(budget.gravity, budget.earth_radius).stage()
    res = simulate(sc, (st,), step=step)
    pred = budget.errors(res.time)
    sim = res.errors[0]
    return BudgetCheck(res.time, sim, pred, float(np.abs(sim - pred).max()), float(np.abs(pred).max()))


def static_tilt_estimate(stage: Stage, tilt: float = 0.1, *, duration: float = 6000.0, step: float = 0.5) -> float:
    """Pitch estimate of a single stage on a body statically pitched by ``tilt``, after ``duration``.

    The body is pitched since before t = 0 on a non-rotating Earth with ideal
    sensors; the stage starts level (ν = 1), so the estimate converges through
    the correction loop to :attr:`strapdown.analysis.multistage.stages.Stage.static_gain` × tilt.

    Parameters
    ----------
    stage : Stage
        The stage (references "pure" or "tilt").
    tilt : float
        Pitch of the body [rad].
    duration : float
        Length of the run [s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).

    Returns
    -------
    float
        Estimated pitch at the end [rad].
    """
    pitch = as_float(tilt, "tilt")
    sc = Scenario(
        duration=duration,
        rocking_start=-1.0,
        rocking_frequency=0.0,
        rocking_phase=(0.0, np.pi / 2, 0.0),
        rocking_amplitude=(0.0, pitch, 0.0),
        rocking_decay=0.0,
        rocking_onset=0.0,
        accel=0.0,
        earth_rate=0.0,
        sensors=SensorErrors(),
    )
    res = simulate(sc, (stage,), step=step)
    return float(res.errors[0, -1, 1] + res.truth[-1, 1])


@dataclass(frozen=True)
class RateTransient:
    """The transient of a damped stage taking a constant rate into its empty integral (:func:`initial_rate_transient`).

    Attributes
    ----------
    rate : float
        The horizontal rate taken up [rad/s].
    time : float
        Time of the largest error [s].
    peak : float
        Largest tilt error [rad].
    loop : StageLoop
        The loop.
    """

    rate: float
    time: float
    peak: float
    loop: StageLoop


def initial_rate_transient(scenario: Scenario | None = None, *, horizon: float | None = None) -> RateTransient:
    """Linear prediction of the start-up error of stage 2 of section 5: the horizontal Earth rate entering its integral.

    Both stages start with an empty integral while the body, fixed to the
    Earth, turns at ``Ω cos φ`` about north; until the switch stage 2 is a
    damped loop, whose tilt error for that rate is the drift response of
    :class:`strapdown.analysis.multistage.tilt_loop.StageLoop`.

    Parameters
    ----------
    scenario : Scenario, optional
        Default :class:`strapdown.analysis.multistage.trajectory.Scenario`.
    horizon : float, optional
        End of the response [s]; default the printed switch time.

    Returns
    -------
    RateTransient
    """
    from ...derivations.multistage.published import PRINTED_GAINS

    sc = Scenario() if scenario is None else scenario
    end = PRINTED_GAINS.switch_time if horizon is None else positive(horizon, "horizon")
    loop = StageLoop(*PRINTED_GAINS.stage2_before, sc.gravity, sc.earth_radius)
    rate = sc.earth_rate * float(np.cos(sc.latitude))
    t, e = loop.drift_response(rate, end)
    i = int(np.argmax(np.abs(e)))
    return RateTransient(rate, float(t[i]), float(abs(e[i])), loop)


@dataclass(frozen=True)
class DesignCheck:
    """A designed stage simulated against its loop (:func:`check_design`).

    Attributes
    ----------
    gains : StageGains
        The design.
    time : ndarray
        [s].
    simulated : ndarray
        Pitch error of the simulated stage [rad].
    predicted : ndarray
        ``e0`` × the step response of ``H_g = s²/(s² + Ks + L)`` (python-control) [rad].
    max_difference : float
        Largest ``|simulated − predicted|`` [rad].
    """

    gains: StageGains
    time: np.ndarray
    simulated: np.ndarray
    predicted: np.ndarray
    max_difference: float


def check_design(gains: StageGains, *, tilt: float = 0.01, duration: float = 1500.0, step: float = 0.5) -> DesignCheck:
    """Simulate a designed stage started level on a statically pitched body and compare with its loop.

    The pitch error starts at ``−tilt`` and decays like the homogeneous
    response of the loop, ``−tilt`` times the step response of the gyro
    high-pass ``H_g``; the difference is second order in the tilt.

    Parameters
    ----------
    gains : StageGains
        The design (references "pure" or "tilt").
    tilt : float
        Pitch of the body [rad].
    duration : float
        Length of the run [s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).

    Returns
    -------
    DesignCheck
    """
    if not isinstance(gains, StageGains):
        raise TypeError(f"Expected `gains` to be a StageGains, got {type(gains).__name__}")
    pitch = as_float(tilt, "tilt")
    sc = Scenario(
        duration=duration,
        rocking_start=-1.0,
        rocking_frequency=0.0,
        rocking_phase=(0.0, np.pi / 2, 0.0),
        rocking_amplitude=(0.0, pitch, 0.0),
        rocking_decay=0.0,
        rocking_onset=0.0,
        accel=0.0,
        earth_rate=0.0,
        sensors=SensorErrors(),
    )
    res = simulate(sc, (gains.stage(rho=1.0),), step=step)
    sim = res.errors[0, :, 1]
    pred = -pitch * step_response_on_grid(gains.loop(sc.gravity, sc.earth_radius).gyro_highpass(), res.time)
    return DesignCheck(gains, res.time, sim, pred, float(np.abs(sim - pred).max()))


def largest_design_difference(checks) -> float:
    """The largest difference between a simulated designed stage and its loop, over several checks [rad].

    Parameters
    ----------
    checks : sequence of DesignCheck
        From :func:`check_design`.

    Returns
    -------
    float
        ``max`` of their :attr:`DesignCheck.max_difference`; NaN for none.
    """
    return max((c.max_difference for c in checks), default=float("nan"))
