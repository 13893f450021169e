"""Linear analysis of a corrected attitude stage with python-control.

The tilt channel of a stage, linearised (Plotnikov 1999, eqs. (3.8)–(3.10)),
is a second-order loop.  With ``e`` the tilt error (estimate minus truth), ``y``
the integral correction, ``d`` a rate disturbance (gyro drift, uncompensated
frame rate) and ``δ`` the error of the accelerometer-indicated tilt
(``a/g`` for a horizontal acceleration a, ``b/g`` for an accelerometer bias b):

    e' = −k e + y + d + k δ,        y' = −l e + l δ.

Its characteristic polynomial is ``s² + k s + l``.  Seen as a filter the stage
is complementary: the estimate is ``H_g θ_gyro + H_a θ_acc`` with the gyro
high-pass ``H_g = s²/(s² + ks + l)`` and the accelerometer low-pass
``H_a = (ks + l)/(s² + ks + l)``, ``H_g + H_a = 1``.  On a moving base the
truth itself turns with the vertical (``ω = V/R``), and the error transfer
function from horizontal acceleration (derived in :mod:`strapdown.derivations.multistage.schuler`)
is ``(ks + l − g/R)/(g(s² + ks + l))``: zero for Schuler tuning ``k = 0``,
``l = g/R``.

The gains here are the loop gains of the (1.4) stage with c = 2; a stage with
c = 1 acts with ``k/2, l/2`` (:attr:`strapdown.analysis.multistage.stages.Stage.effective_gains`).
All linear-systems work (poles, damping, root loci, time and frequency
responses) is done by python-control; on a uniform time grid a step response
is run as the recursive filter of the system that python-control discretises
(:func:`step_response_on_grid`), which gives the same samples without a
Python loop over the time steps.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import control
import numpy as np

from ..core import budget
from ..core.cache import compiled
from ..core.validation import as_array, as_float, as_int, positive
from .response_grid import MAX_POINTS, pulse_grid

__all__ = [
    "STABILITY_LABELS",
    "StageLoop",
    "LoopSummary",
    "RootLocus",
    "LoopResponses",
    "FilterResponse",
    "schuler_period",
    "classify_poles",
    "root_locus_k",
    "root_locus_l",
    "responses",
    "step_response_on_grid",
    "complementary_filter",
    "AccelSensitivity",
    "acceleration_sensitivity",
]

#: Labels of :func:`classify_poles`.
STABILITY_LABELS = ("asymptotically stable", "marginal", "unstable")


def schuler_period(gravity: float = 9.81, earth_radius: float = 6.371e6) -> float:
    """Schuler period ``2π √(R/g)`` [s].

    Parameters
    ----------
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].

    Returns
    -------
    float

    >>> round(schuler_period() / 60.0, 2)
    84.39
    """
    return float(2.0 * np.pi * np.sqrt(positive(earth_radius, "earth_radius") / positive(gravity, "gravity")))


def classify_poles(poles, *, rtol: float = 1e-9) -> str:
    """Stability of a linear time-invariant system from its poles.

    "asymptotically stable" if every pole has a negative real part;
    "marginal" if none is in the right half-plane and the poles on the
    imaginary axis are simple; "unstable" otherwise (a right-half-plane pole,
    or a repeated pole on the imaginary axis, whose response grows).

    Parameters
    ----------
    poles : array_like of complex
        Poles [1/s].
    rtol : float
        Relative tolerance for "on the imaginary axis" (scaled by the largest ``|pole|``).

    Returns
    -------
    str
        One of :data:`STABILITY_LABELS`.

    Examples
    --------
    >>> classify_poles([-1.0, -2.0]), classify_poles([1j, -1j]), classify_poles([0.0, 0.0])
    ('asymptotically stable', 'marginal', 'unstable')
    """
    p = np.asarray(poles, dtype=complex).ravel()
    tol = rtol * max(1.0, float(np.abs(p).max(initial=0.0))) if p.size else 0.0
    tol = max(tol, 1e-300)
    if np.any(p.real > tol):
        return "unstable"
    axis = p[np.abs(p.real) <= tol]
    if axis.size == 0:
        return "asymptotically stable"
    for i in range(axis.size):
        for j in range(i + 1, axis.size):
            if abs(axis[i] - axis[j]) <= tol:
                return "unstable"
    return "marginal"


def step_response_on_grid(system, time) -> np.ndarray:
    """Unit-step response of a continuous-time SISO system from rest, on a uniform time grid.

    A step is held exactly by a zero-order hold, so the response at the grid
    points is that of the system discretised with ``control.sample_system``
    (method "zoh", on its state-space form); that discrete recursion is run
    as a recursive filter (``scipy.signal.lfilter`` on its transfer function)
    instead of the loop over the time steps in ``control.step_response``.
    The two agree to about 1e-10 of the largest value (tests).

    Parameters
    ----------
    system : control.LTI
        Continuous-time system with one input and one output.
    time : array_like, shape (n,)
        Uniform grid from 0 [s], n >= 2.

    Returns
    -------
    ndarray, shape (n,)
        The response at ``time`` [output unit per input unit].

    Raises
    ------
    TypeError
        If ``system`` is not a python-control LTI system.
    ValueError
        If it is not SISO or not continuous-time, or ``time`` is not a uniform grid from 0.

    References
    ----------
    Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 3rd ed. (1998),
    section 4.3.3 (zero-order-hold equivalent).
    """
    from scipy.signal import lfilter, ss2tf

    if not isinstance(system, control.LTI):
        raise TypeError(f"Expected `system` to be a python-control LTI system, got {type(system).__name__}")
    if system.ninputs != 1 or system.noutputs != 1 or not system.isctime(strict=True):
        raise ValueError(f"Expected `system` to be a continuous-time SISO system, got {system.ninputs} inputs, {system.noutputs} outputs, dt = {system.dt}")
    t = as_array(time, "time")
    if t.ndim != 1 or t.size < 2 or t[0] != 0.0:
        raise ValueError(f"Expected `time` to be a 1-D grid from 0 with at least 2 points, got shape {t.shape}" + (f" from {t[0]:g}" if t.size else ""))
    dt = (t[-1] - t[0]) / (t.size - 1)
    if not dt > 0.0 or np.abs(np.diff(t) - dt).max() > 1e-9 * dt + 1e-12 * abs(t[-1]):
        raise ValueError("Expected `time` to be a uniform, increasing grid")
    discrete = control.sample_system(control.ss(system), dt, method="zoh")
    num, den = ss2tf(discrete.A, discrete.B, discrete.C, discrete.D)
    return lfilter(num[0], den, np.ones(t.size))


def _accel_tf_build(part: int):
    def build():
        from ...derivations.multistage.schuler import SYMBOLS, accel_to_tilt_tf

        coefficients = accel_to_tilt_tf()[part]
        return (SYMBOLS.k, SYMBOLS.l, SYMBOLS.g, SYMBOLS.R), tuple(coefficients)

    return build


def _accel_tf_coefficients(k, l, g, r):
    """Numerator and denominator of E(s)/A(s), from the derivation's generated (cached) code."""
    num = compiled("multistage:schuler:accel-to-tilt-tf:numerator:v1", _accel_tf_build(0))
    den = compiled("multistage:schuler:accel-to-tilt-tf:denominator:v1", _accel_tf_build(1))
    return np.array(num(k, l, g, r), dtype=float), np.array(den(k, l, g, r), dtype=float)


@dataclass(frozen=True)
class StageLoop:
    """Linearised tilt channel of a corrected stage with gains (k, l).

    Parameters
    ----------
    k : float
        Position-correction gain [1/s].  Any finite value (k < 0 is analysed, flagged unstable).
    l : float
        Integral-correction gain [1/s²].  Any finite value.
    gravity : float
        g [m/s²], > 0.
    earth_radius : float
        R [m], > 0.

    Examples
    --------
    >>> loop = StageLoop(0.01, 5e-5)
    >>> loop.stability
    'asymptotically stable'
    >>> StageLoop.schuler().stability
    'marginal'
    """

    k: float
    l: float
    gravity: float = 9.81
    earth_radius: float = 6.371e6

    def __post_init__(self):
        object.__setattr__(self, "k", as_float(self.k, "k"))
        object.__setattr__(self, "l", as_float(self.l, "l"))
        object.__setattr__(self, "gravity", positive(self.gravity, "gravity"))
        object.__setattr__(self, "earth_radius", positive(self.earth_radius, "earth_radius"))

    @classmethod
    def schuler(cls, gravity: float = 9.81, earth_radius: float = 6.371e6) -> StageLoop:
        """Schuler tuning ``k = 0``, ``l = g/R`` (Plotnikov 1999, (3.11)).

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
        g, r = positive(gravity, "gravity"), positive(earth_radius, "earth_radius")
        return cls(0.0, g / r, g, r)

    # ---------------------------------------------------------------- models
    def state_space(self) -> control.StateSpace:
        """States (e, y); inputs (d [rad/s], δ [rad]); output e [rad]."""
        k, l = self.k, self.l
        a = [[-k, 1.0], [-l, 0.0]]
        b = [[1.0, k], [0.0, l]]
        return control.ss(a, b, [[1.0, 0.0]], [[0.0, 0.0]], inputs=["rate", "tilt"], outputs=["e"], states=["e", "y"])

    def error_from_accel(self) -> control.TransferFunction:
        """E(s)/A(s) [rad per m/s²] from :mod:`strapdown.derivations.multistage.schuler` (zero under Schuler tuning)."""
        num, den = _accel_tf_coefficients(self.k, self.l, self.gravity, self.earth_radius)
        # Under Schuler tuning the numerator vanishes identically (the derivation shows it);
        # in floating point l − g/R leaves round-off, which is set to zero.
        scale = (abs(self.k) + abs(self.l) + self.gravity / self.earth_radius) / self.gravity
        num = np.where(np.abs(num) <= 64.0 * np.finfo(float).eps * scale, 0.0, num)
        return control.tf(num, den)

    def error_from_drift(self) -> control.TransferFunction:
        """E(s)/D(s): tilt error per rate disturbance [rad per rad/s]."""
        return control.tf([1.0, 0.0], [1.0, self.k, self.l])

    def accel_lowpass(self) -> control.TransferFunction:
        """``H_a = (ks + l)/(s² + ks + l)``: how the accelerometer tilt enters the estimate."""
        return control.tf([self.k, self.l], [1.0, self.k, self.l])

    def gyro_highpass(self) -> control.TransferFunction:
        """``H_g = s²/(s² + ks + l)``: how the gyro-integrated attitude enters the estimate."""
        return control.tf([1.0, 0.0, 0.0], [1.0, self.k, self.l])

    # ---------------------------------------------------------------- numbers
    def poles(self) -> np.ndarray:
        """Closed-loop poles [1/s] (eigenvalues of the state matrix), sorted."""
        p = self.state_space().poles()
        return np.sort_complex(np.asarray(p, dtype=complex))

    def damp(self):
        """``(natural frequency [rad/s], damping ratio [-], poles)`` per pole, from ``control.damp``."""
        with np.errstate(invalid="ignore", divide="ignore"):  # ζ is undefined for a pole at 0
            wn, zeta, p = control.damp(self.state_space(), doprint=False)
        order = np.lexsort((np.asarray(p).imag, np.asarray(p).real))
        return np.asarray(wn)[order], np.asarray(zeta)[order], np.asarray(p)[order]

    @property
    def stability(self) -> str:
        """One of :data:`STABILITY_LABELS`."""
        return classify_poles(self.poles())

    @property
    def schuler_period(self) -> float:
        """``2π√(R/g)`` [s]."""
        return schuler_period(self.gravity, self.earth_radius)

    def require_bounded(self, what: str = "the tilt error") -> None:
        """Raise ValueError if the loop is unstable (its responses grow without bound).

        Parameters
        ----------
        what : str
            What was asked for, for the message.

        Raises
        ------
        ValueError
            If :attr:`stability` is "unstable".
        """
        if self.stability == "unstable":
            p = self.poles()
            bad = ", ".join(f"{z.real:+.3g}{z.imag:+.3g}j" for z in p if z.real > -1e-12 * max(1.0, float(np.abs(p).max())))
            raise ValueError(
                f"Expected gains with a stable tilt loop (k >= 0 and l >= 0, not both 0) for {what}, got k = {self.k:g} 1/s, l = {self.l:g} 1/s²: "
                f"poles {bad} make the response grow without bound"
            )

    def pulse_response(self, accel, duration, *, horizon=None, max_points: int = MAX_POINTS, limits: budget.Limits | None = None):
        """Tilt error for a horizontal acceleration ``accel`` held ``duration`` s from rest.

        By superposition of two step responses of :meth:`error_from_accel`
        (:func:`step_response_on_grid`): ``e(t) = A (s(t) − s(t − T))``.

        Parameters
        ----------
        accel : float
            Acceleration A [m/s²].
        duration : float
            T [s], > 0.
        horizon : float, optional
            End of the response [s]; default ``T`` plus two Schuler periods.
        max_points : int
            Number of time samples the grid aims at; more when the
            acceleration is short against the horizon (the grid keeps the end
            of the acceleration on a sample: :func:`~strapdown.analysis.multistage.response_grid.pulse_grid`).
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        t, e : ndarray
            Times [s] and tilt error [rad].

        Raises
        ------
        ValueError
            For a non-finite acceleration, a non-positive duration, a horizon
            shorter than it, an unstable loop, or a response whose estimated
            memory or time exceeds ``limits``
            (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``horizon``).
        """
        a = as_float(accel, "accel")
        dur = positive(duration, "accel_duration")
        end = dur + 2.0 * self.schuler_period if horizon is None else positive(horizon, "horizon")
        if end < dur:
            raise ValueError(f"Expected `horizon` >= `accel_duration` ({dur:g} s), got {end:g} s")
        self.require_bounded("the response to an acceleration")
        # The response is exact on any uniform grid (zero-order hold of a piecewise-constant
        # input); the grid only has to resolve the peak.
        fastest = float(np.abs(self.poles()).max(initial=0.0))
        dt, m, samples = pulse_grid(dur, end, fastest, max_points)
        if horizon is not None:
            asked = f"`horizon` = {end:.3g} s"
        else:
            asked = f"the default horizon, `accel_duration` = {dur:.3g} s plus two Schuler periods 2π√(`earth_radius`/`gravity`) = {self.schuler_period:.3g} s"
        budget.check(budget.loop_response(samples, what=f"{asked} at a time step of {dt:.3g} s ({samples:.3g} samples)"), limits)
        t = np.arange(int(samples)) * dt
        step = step_response_on_grid(self.error_from_accel(), t)
        shifted = np.concatenate([np.zeros(m), step[:-m]])
        return t, a * (step - shifted)

    def peak_tilt_error(self, accel, duration, *, horizon=None, limits: budget.Limits | None = None) -> float:
        """Largest ``|tilt error|`` [rad] of :meth:`pulse_response`.

        Parameters
        ----------
        accel : float
            Acceleration A [m/s²].
        duration : float
            T [s], > 0.
        horizon : float, optional
            End of the response [s]; default ``T`` plus two Schuler periods.
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        float

        Raises
        ------
        ValueError
            As :meth:`pulse_response`.
        """
        _, e = self.pulse_response(accel, duration, horizon=horizon, limits=limits)
        return float(np.abs(e).max())

    def drift_response(self, rate, horizon, *, points: int = 6001, limits: budget.Limits | None = None):
        """Tilt error for a constant rate disturbance from t = 0 (e.g. an Earth rate not yet in the integral).

        Parameters
        ----------
        rate : float
            Rate disturbance d [rad/s].
        horizon : float
            End of the response [s], > 0.
        points : int
            Number of time samples, >= 2.
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        t, e : ndarray
            Times [s] and tilt error [rad] (``d`` times the step response of :meth:`error_from_drift`).

        Raises
        ------
        ValueError
            For an unstable loop, bad arguments, or more ``points`` than ``limits`` allow.
        """
        d = as_float(rate, "rate")
        end = positive(horizon, "horizon")
        count = as_int(points, "points", minimum=2)
        budget.check(budget.loop_response(count, what=f"`points` = {count:.3g} samples"), limits)
        self.require_bounded("the response to a rate disturbance")
        t = np.linspace(0.0, end, count)
        return t, d * step_response_on_grid(self.error_from_drift(), t)

    def summary(self, accel: float = 20.0, duration: float = 20.0, *, horizon=None, limits: budget.Limits | None = None) -> LoopSummary:
        """Poles, damping, natural frequency, stability and peak tilt error.

        Parameters
        ----------
        accel : float
            Acceleration of the manoeuvre [m/s²].
        duration : float
            Its duration [s].
        horizon : float, optional
            End of the response [s]; default ``duration`` plus two Schuler periods.
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        LoopSummary

        Raises
        ------
        ValueError
            For an unstable loop (its peak error is unbounded), bad arguments, or
            a response beyond ``limits`` (as :meth:`pulse_response`).
        """
        wn, zeta, p = self.damp()
        dur = positive(duration, "accel_duration")
        end = dur + 2.0 * self.schuler_period if horizon is None else positive(horizon, "horizon")
        return LoopSummary(
            k=self.k,
            l=self.l,
            gravity=self.gravity,
            earth_radius=self.earth_radius,
            schuler_period=self.schuler_period,
            poles=tuple(complex(z) for z in p),
            damping=tuple(float(v) + 0.0 for v in zeta),
            natural_frequency=tuple(float(v) for v in wn),
            stability=self.stability,
            accel=as_float(accel, "accel"),
            accel_duration=dur,
            horizon=float(end),
            peak_tilt_error=self.peak_tilt_error(accel, dur, horizon=horizon, limits=limits),
        )


@dataclass(frozen=True)
class LoopSummary:
    """What :meth:`StageLoop.summary` computes.

    Attributes
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].
    schuler_period : float
        2π√(R/g) [s].
    poles : tuple of complex
        Closed-loop poles [1/s].
    damping : tuple of float
        Damping ratio of each pole [-].
    natural_frequency : tuple of float
        Natural frequency of each pole [rad/s].
    stability : str
        One of :data:`STABILITY_LABELS`.
    accel : float
        Acceleration of the manoeuvre [m/s²].
    accel_duration : float
        Its duration [s].
    horizon : float
        End of the response [s].
    peak_tilt_error : float
        Largest ``|tilt error|`` [rad].
    """

    k: float
    l: float
    gravity: float
    earth_radius: float
    schuler_period: float
    poles: tuple
    damping: tuple
    natural_frequency: tuple
    stability: str
    accel: float
    accel_duration: float
    horizon: float
    peak_tilt_error: float


class RootLocus(NamedTuple):
    """Closed-loop poles over a gain (:func:`root_locus_k`, :func:`root_locus_l`).

    Attributes
    ----------
    gains : ndarray, shape (G,)
        The swept gain.
    loci : ndarray of complex, shape (G, 2)
        Poles for each gain [1/s].
    """

    gains: np.ndarray
    loci: np.ndarray


def root_locus_k(l, ks) -> RootLocus:
    """Closed-loop poles over the position gain k at fixed l: ``1 + k s/(s² + l) = 0``.

    Parameters
    ----------
    l : float
        Integral gain [1/s²].
    ks : array_like
        Values of k [1/s].

    Returns
    -------
    RootLocus
        From ``control.root_locus_map``.
    """
    l = as_float(l, "l")
    ks = as_array(ks, "ks", nonempty=True)
    return RootLocus(ks, control.root_locus_map(control.tf([1.0, 0.0], [1.0, 0.0, l]), ks).loci)


def root_locus_l(k, ls) -> RootLocus:
    """Closed-loop poles over the integral gain l at fixed k: ``1 + l/(s(s + k)) = 0``.

    Parameters
    ----------
    k : float
        Position gain [1/s].
    ls : array_like
        Values of l [1/s²].

    Returns
    -------
    RootLocus
        From ``control.root_locus_map``.
    """
    k = as_float(k, "k")
    ls = as_array(ls, "ls", nonempty=True)
    return RootLocus(ls, control.root_locus_map(control.tf([1.0], [1.0, k, 0.0]), ls).loci)


class LoopResponses(NamedTuple):
    """Time responses of a stage loop (:func:`responses`).

    Attributes
    ----------
    time : ndarray
        [s].
    accel_step : ndarray
        Tilt error for a unit acceleration step [rad per m/s²].
    accel_impulse : ndarray
        Tilt error for a unit acceleration impulse [rad per m/s].
    drift_step : ndarray
        Tilt error for a unit rate step [rad per rad/s].
    """

    time: np.ndarray
    accel_step: np.ndarray
    accel_impulse: np.ndarray
    drift_step: np.ndarray


def responses(loop: StageLoop, time) -> LoopResponses:
    """Step and impulse responses of :meth:`StageLoop.error_from_accel` and the drift step response.

    Parameters
    ----------
    loop : StageLoop
        The loop.
    time : array_like
        Times from 0, increasing [s].

    Returns
    -------
    LoopResponses
    """
    t = as_array(time, "time", nonempty=True)
    tf = loop.error_from_accel()

    def out(r):
        return np.asarray(r.outputs, dtype=float).reshape(-1)

    return LoopResponses(t, out(control.step_response(tf, T=t)), out(control.impulse_response(tf, T=t)), out(control.step_response(loop.error_from_drift(), T=t)))


class FilterResponse(NamedTuple):
    """The stage as a complementary filter (:func:`complementary_filter`).

    Attributes
    ----------
    omega : ndarray
        Frequencies [rad/s].
    gyro_magnitude, gyro_phase : ndarray
        ``H_g(iω)``: magnitude [-] and phase [rad].
    accel_magnitude, accel_phase : ndarray
        ``H_a(iω)``.
    max_sum_error : float
        ``max |H_g + H_a − 1|`` over the grid.
    """

    omega: np.ndarray
    gyro_magnitude: np.ndarray
    gyro_phase: np.ndarray
    accel_magnitude: np.ndarray
    accel_phase: np.ndarray
    max_sum_error: float


def complementary_filter(loop: StageLoop, omega) -> FilterResponse:
    """Frequency responses of the gyro high-pass and the accelerometer low-pass of a stage.

    Parameters
    ----------
    loop : StageLoop
        The loop.
    omega : array_like
        Frequencies [rad/s], > 0.

    Returns
    -------
    FilterResponse
    """
    w = as_array(omega, "omega", nonempty=True)
    hg = control.frequency_response(loop.gyro_highpass(), w)
    ha = control.frequency_response(loop.accel_lowpass(), w)
    gm, gp = np.asarray(hg.magnitude).ravel(), np.asarray(hg.phase).ravel()
    am, ap = np.asarray(ha.magnitude).ravel(), np.asarray(ha.phase).ravel()
    total = gm * np.exp(1j * gp) + am * np.exp(1j * ap)
    return FilterResponse(w, gm, gp, am, ap, float(np.abs(total - 1.0).max()))


class AccelSensitivity(NamedTuple):
    """How a loop answers a horizontal acceleration (:func:`acceleration_sensitivity`).

    Attributes
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    dc_gain : float
        ``E/A`` at s = 0 [rad per m/s²] (NaN for l = 0).
    peak : float
        Peak tilt error for the manoeuvre [rad].
    """

    k: float
    l: float
    dc_gain: float
    peak: float


def acceleration_sensitivity(loop: StageLoop, accel: float = 20.0, duration: float = 20.0) -> AccelSensitivity:
    """Static gain of E(s)/A(s) and the peak tilt error of an acceleration pulse.

    Parameters
    ----------
    loop : StageLoop
        The loop.
    accel : float
        Acceleration [m/s²].
    duration : float
        Its duration [s].

    Returns
    -------
    AccelSensitivity
    """
    dc = float(np.real(loop.error_from_accel()(0))) if loop.l != 0 else float("nan")
    return AccelSensitivity(loop.k, loop.l, dc, loop.peak_tilt_error(accel, duration))
