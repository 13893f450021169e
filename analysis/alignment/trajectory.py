"""A manoeuvring vehicle over the rotating Earth: exact kinematics and the ideal sensor increments.

The vehicle (a car, a ship) stays at constant height on the WGS-84 ellipsoid,
level (its body z axis down the local vertical), its body x axis along its
track.  Its motion is given by two smooth functions of time
(:class:`Manoeuvre`): the speed ``s(t)`` (a half-cosine run-up from a start
speed to the cruise speed) and the heading ``ψ(t) = ψ0 + A sin(2π t/P)`` (a
weave).  Then, in NED,

    v^n = s (cos ψ, sin ψ, 0),
    v̇^n = (s' cos ψ − s ψ' sin ψ, s' sin ψ + s ψ' cos ψ, 0),

the position follows ``φ' = v_N/(R_N + h)``, ``λ' = v_E/((R_E + h) cos φ)``
(integrated by DOP853 at rtol 1e-12), the transport rate is
``ω_en^n = (v_E/(R_E + h), −v_N/(R_N + h), −v_E tan φ/(R_E + h))``, and the
sensors measure

    ω_ib^b = C_n^b (ω_ie^n + ω_en^n) + ψ' e_z,
    f^b = C_n^b (v̇^n + (2ω_ie^n + ω_en^n) × v^n − g^n),

``C_b^n = R_z(ψ)``, g^n the normal gravity of :mod:`~strapdown.analysis.alignment.earth` (with its
free-air decrease with height).  The increments over each sample interval are
the two-point Gauss–Legendre quadrature of these rates, as in :mod:`~strapdown.analysis.alignment.imu`.

The peak horizontal acceleration of the weave, ``s · A · 2π/P``, measures the
manoeuvre (:attr:`Manoeuvre.lateral_acceleration`).

References
----------
Groves (2013), sec. 2.4.3 (radii of curvature), 5.4 (the local-navigation-frame equations).

Public API
----------
Manoeuvre, TrajectoryState, radii, position_solution, trajectory_state, trajectory_increments, WGS84_A, WGS84_E2
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import budget
from ..core.validation import as_float, nonnegative, positive
from .earth import EARTH_RATE, normal_gravity

__all__ = ["Manoeuvre", "TrajectoryState", "radii", "position_solution", "trajectory_state", "trajectory_increments", "WGS84_A", "WGS84_E2"]

#: WGS-84 semi-major axis [m] and first eccentricity squared.
WGS84_A = 6378137.0
WGS84_E2 = 0.00669437999013
_GAUSS = (0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0))


def radii(latitude):
    """Meridian and prime-vertical radii of curvature ``(R_N, R_E)`` of WGS-84 [m].

    Parameters
    ----------
    latitude : array_like
        Geodetic latitude [rad].

    Returns
    -------
    tuple of ndarray

    >>> [round(float(r)) for r in radii(0.0)]
    [6335439, 6378137]
    """
    s2 = np.sin(np.asarray(latitude, dtype=float)) ** 2
    w = np.sqrt(1.0 - WGS84_E2 * s2)
    return WGS84_A * (1.0 - WGS84_E2) / w**3, WGS84_A / w


@dataclass(frozen=True)
class Manoeuvre:
    """Where the vehicle starts and how it drives: a run-up to cruise speed and a heading weave.

    Parameters
    ----------
    latitude, longitude : float
        Start position [rad].
    height : float
        Height above the ellipsoid, constant [m].
    heading : float
        Mean heading ψ0 [rad].
    speed : float
        Cruise speed [m/s].
    start_speed : float
        Speed at t = 0 [m/s] (equal to ``speed``: no run-up).
    run_up : float
        Duration of the half-cosine run-up from ``start_speed`` to ``speed`` [s].
    weave_amplitude : float
        Amplitude A of the heading weave [rad] (0: a straight track).
    weave_period : float
        Period P of the weave [s].
    """

    latitude: float = math.radians(45.0)
    longitude: float = 0.0
    height: float = 0.0
    heading: float = 0.0
    speed: float = 10.0
    start_speed: float | None = None
    run_up: float = 20.0
    weave_amplitude: float = 0.0
    weave_period: float = 60.0

    def __post_init__(self):
        lat = as_float(self.latitude, "latitude")
        if not abs(lat) < 0.5 * math.pi - 0.01:
            raise ValueError(f"Expected `latitude` inside (-89.4°, 89.4°) [rad], got {lat:g}")
        for name in ("longitude", "height", "heading", "weave_amplitude"):
            object.__setattr__(self, name, as_float(getattr(self, name), name))
        object.__setattr__(self, "speed", nonnegative(self.speed, "speed"))
        object.__setattr__(self, "start_speed", self.speed if self.start_speed is None else nonnegative(self.start_speed, "start_speed"))
        object.__setattr__(self, "run_up", positive(self.run_up, "run_up"))
        object.__setattr__(self, "weave_period", positive(self.weave_period, "weave_period"))

    @property
    def lateral_acceleration(self) -> float:
        """Peak horizontal acceleration of the weave at cruise speed, ``s A 2π/P`` [m/s²]."""
        return self.speed * abs(self.weave_amplitude) * 2.0 * math.pi / self.weave_period

    def speed_profile(self, t):
        """``(s, s')`` at times t [m/s, m/s²].

        Parameters
        ----------
        t : array_like
            Times [s].

        Returns
        -------
        tuple of ndarray
        """
        t = np.asarray(t, dtype=float)
        d = self.start_speed - self.speed
        inside = t < self.run_up
        arg = math.pi * np.minimum(t, self.run_up) / self.run_up
        s = np.where(inside, self.speed + 0.5 * d * (1.0 + np.cos(arg)), self.speed)
        ds = np.where(inside, -0.5 * d * math.pi / self.run_up * np.sin(arg), 0.0)
        return s, ds

    def heading_profile(self, t):
        """``(ψ, ψ', ψ'')`` at times t [rad, rad/s, rad/s²].

        Parameters
        ----------
        t : array_like
            Times [s].

        Returns
        -------
        tuple of ndarray
        """
        w = 2.0 * math.pi / self.weave_period
        a = self.weave_amplitude
        t = np.asarray(t, dtype=float)
        return self.heading + a * np.sin(w * t), a * w * np.cos(w * t), -a * w * w * np.sin(w * t)


@dataclass(frozen=True)
class TrajectoryState:
    """The vehicle's true state at a set of times.

    Attributes
    ----------
    times : ndarray
        ``(K,)`` [s].
    latitude, longitude : ndarray
        ``(K,)`` [rad].
    height : float
        [m].
    velocity : ndarray
        ``(K, 3)`` NED [m/s].
    acceleration : ndarray
        ``(K, 3)`` ``v̇^n`` [m/s²].
    heading : ndarray
        ``(K,)`` ψ [rad].
    attitude : ndarray
        ``(K, 3, 3)`` ``C_b^n``.
    specific_force : ndarray
        ``(K, 3)`` f^n [m/s²].
    gyro, accel : ndarray
        ``(K, 3)`` ideal ω_ib^b [rad/s] and f^b [m/s²].
    """

    times: np.ndarray
    latitude: np.ndarray
    longitude: np.ndarray
    height: float
    velocity: np.ndarray
    acceleration: np.ndarray
    heading: np.ndarray
    attitude: np.ndarray
    specific_force: np.ndarray
    gyro: np.ndarray
    accel: np.ndarray


def _max_step(man: Manoeuvre) -> float:
    """Largest DOP853 step of :func:`position_solution` [s]."""
    return max(1.0, man.weave_period / 20)


def _solution_estimate(man: Manoeuvre, duration: float, what: str) -> budget.Estimate:
    return budget.TRAJECTORY_STEP.estimate(math.ceil(duration / _max_step(man)) + 1.0, what=what)


def _speed_and_heading(man: Manoeuvre, t: float) -> tuple:
    """``(s, ψ)`` at one time t [m/s, rad]: :meth:`Manoeuvre.speed_profile` and :meth:`Manoeuvre.heading_profile`
    on a float, with the same operations in the same order (hence the same bits), without numpy's per-call cost."""
    if t < man.run_up:
        arg = math.pi * min(t, man.run_up) / man.run_up
        s = man.speed + 0.5 * (man.start_speed - man.speed) * (1.0 + math.cos(arg))
    else:
        s = man.speed
    w = 2.0 * math.pi / man.weave_period
    return s, man.heading + man.weave_amplitude * math.sin(w * t)


def position_solution(man: Manoeuvre, duration: float, *, limits: budget.Limits | None = None):
    """Dense DOP853 solution (rtol 1e-12) of the latitude and longitude ``(φ, λ)`` over ``[0, duration]``.

    Parameters
    ----------
    man : Manoeuvre
        The drive.
    duration : float
        [s].
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    scipy.integrate OdeResult
        With ``sol(t)`` → ``(φ, λ)`` [rad], for :func:`trajectory_state`.

    Raises
    ------
    ValueError
        A negative ``duration``, or one whose integration exceeds ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration``).
    """
    t_end = nonnegative(duration, "duration")
    steps = math.ceil(t_end / _max_step(man))
    budget.check(_solution_estimate(man, t_end, f"`duration` = {t_end:.3g} s of the drive (at least {steps:.3g} DOP853 steps)"), limits)
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        s, psi = _speed_and_heading(man, float(t))
        RN, RE = radii(y[0])
        return [s * math.cos(psi) / (RN + man.height), s * math.sin(psi) / ((RE + man.height) * math.cos(y[0]))]

    return solve_ivp(rhs, (0.0, t_end), [man.latitude, man.longitude], method="DOP853", rtol=1e-12, atol=1e-15, dense_output=True, max_step=_max_step(man))


def trajectory_state(man: Manoeuvre, times, *, solution=None, limits: budget.Limits | None = None) -> TrajectoryState:
    """The true state of the vehicle at ``times``.

    Parameters
    ----------
    man : Manoeuvre
        The drive.
    times : array_like
        ``(K,)`` times ≥ 0 [s].
    solution : OdeSolution-like, optional, keyword-only
        A dense position solution over a span covering ``times`` (saves the integration).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the position solution made
        without ``solution`` (default 2 GB, 300 s), naming ``times``.

    Returns
    -------
    TrajectoryState

    Raises
    ------
    ValueError
        Negative ``times``, or a last time whose position solution exceeds
        ``limits`` (:class:`~strapdown.analysis.core.budget.BudgetExceeded`).

    Examples
    --------
    At rest the gyros read the Earth rate and the accelerometers −g, in body axes:

    >>> st = trajectory_state(Manoeuvre(speed=0.0, heading=0.0), [0.0])
    >>> [round(float(x) / 7.292115e-5, 9) for x in st.gyro[0]]
    [0.707106781, 0.0, -0.707106781]
    """
    t = np.asarray(times, dtype=float).ravel()
    if np.any(t < 0):
        raise ValueError("Expected `times` >= 0 [s]")
    if solution is None:
        t_end = float(t.max()) if t.size else 0.0
        budget.check(_solution_estimate(man, t_end, f"`times` up to {t_end:.3g} s (the position solution to the last time)"), limits)
        sol = position_solution(man, t_end, limits=limits)
    else:
        sol = solution
    lat, lon = sol.sol(t) if hasattr(sol, "sol") else sol(t)
    s, ds = man.speed_profile(t)
    psi, dpsi, _ = man.heading_profile(t)
    c, sn = np.cos(psi), np.sin(psi)
    v = np.stack([s * c, s * sn, np.zeros_like(t)], axis=-1)
    a = np.stack([ds * c - s * dpsi * sn, ds * sn + s * dpsi * c, np.zeros_like(t)], axis=-1)
    RN, RE = radii(lat)
    h = man.height
    wie = EARTH_RATE * np.stack([np.cos(lat), np.zeros_like(lat), -np.sin(lat)], axis=-1)
    wen = np.stack([v[:, 1] / (RE + h), -v[:, 0] / (RN + h), -v[:, 1] * np.tan(lat) / (RE + h)], axis=-1)
    g = normal_gravity(lat) * (1.0 - 2.0 * h / WGS84_A)
    gn = np.stack([np.zeros_like(g), np.zeros_like(g), g], axis=-1)
    fn = a + np.cross(2.0 * wie + wen, v) - gn
    C = np.zeros((t.size, 3, 3))
    C[:, 0, 0], C[:, 0, 1], C[:, 1, 0], C[:, 1, 1], C[:, 2, 2] = c, -sn, sn, c, 1.0
    gyro = np.einsum("kji,kj->ki", C, wie + wen) + dpsi[:, None] * np.array([0.0, 0.0, 1.0])
    accel = np.einsum("kji,kj->ki", C, fn)
    return TrajectoryState(t, lat, lon, h, v, a, psi, C, fn, gyro, accel)


def trajectory_increments(man: Manoeuvre, sample_rate: float, duration: float, *, limits: budget.Limits | None = None):
    """Ideal angle and velocity increments of the drive, and the dense position solution.

    Parameters
    ----------
    man : Manoeuvre
        The drive.
    sample_rate : float
        [Hz].
    duration : float
        [s].
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    tuple
        ``(dtheta (N, 3) [rad], dv (N, 3) [m/s], solution)``: the two-point
        Gauss–Legendre quadrature of the exact rates over each interval, and the
        position solution (for :func:`trajectory_state`).

    Raises
    ------
    ValueError
        A non-positive rate or duration, or a drive beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming
        ``duration`` and ``sample_rate``).
    """
    fs, T = positive(sample_rate, "sample_rate"), positive(duration, "duration")
    N = int(round(T * fs))
    samples, solution = budget.TRAJECTORY_SAMPLE.estimate(N, what=""), _solution_estimate(man, N / fs, what="")
    what = f"`duration` = {T:.3g} s at `sample_rate` = {fs:g} Hz ({N:.3g} IMU samples)"
    budget.check(budget.Estimate(samples.seconds + solution.seconds, samples.memory + solution.memory, what), limits)
    dt = 1.0 / fs
    sol = position_solution(man, N * dt, limits=limits)
    k = np.arange(N)
    dth, dv = np.zeros((N, 3)), np.zeros((N, 3))
    for node in _GAUSS:
        st = trajectory_state(man, (k + node) * dt, solution=sol)
        dth += 0.5 * dt * st.gyro
        dv += 0.5 * dt * st.accel
    return dth, dv, sol
