"""Compass-loop (gyrocompass) alignment: levelling loops and the azimuth loop, with tunable bandwidth and damping.

The classical alignment before Kalman filters (Britting 1971, ch. 10; Titterton
& Weston 2004, sec. 10.3.2).  A strapdown navigator runs in NED from an initial
attitude; its velocity, which should stay zero, drives corrections of the
computed frame (a rate ``u`` applied as ``C̃ ← exp([u D ×]) C̃``, so that
``φ' = … − u``) and damps itself:

east channel (levelling, north tilt φ_N)
    ``δv_E' = −g φ_N + ∇_E − k1 δv_E``, ``u_N = −(k2/g) δv_E − z``,
    ``z' = (k3/g) δv_E``: a third-order loop whose integrator z absorbs the
    tilt drift;
north channel (gyrocompass, east tilt φ_E and azimuth φ_D)
    ``δv_N' = g φ_E + ∇_N − c1 δv_N``, ``u_E = (c2/g) δv_N``,
    ``u_D = c3/(g Ω cos φ) · δv_N``: the east tilt drifts at
    ``Ω cos φ φ_D − ε_E``, the north velocity it builds turns the azimuth, and
    the loop settles where the drift vanishes, at the gyro-bias floor
    ``φ_D = ε_E/(Ω cos φ) − tan φ ∇_E/g``.

Each loop has the characteristic polynomial ``(s + ω)(s² + 2ζω s + ω²)``
(``k1 = ω(1 + 2ζ)``, ``k2 = ω²(1 + 2ζ)``, ``k3 = ω³``), with its own bandwidth ω
and damping ζ (:class:`CompassLoopDesign`); the vertical velocity is damped at
the levelling k1.  The navigator runs on epoch increments
(:mod:`~strapdown.analysis.alignment.preintegration`), one step per epoch vectorised over trials.

:func:`compass_loop_system` is the linear closed loop as a python-control state
space, and :func:`compass_loop_theory` its response to the fixed biases and
its covariance under the sensor noise and the initial errors: the theory the
Monte Carlo checks.

References
----------
Britting, K. R., *Inertial Navigation Systems Analysis*, Wiley, 1971, ch. 10.
Titterton, D. H., Weston, J. L., *Strapdown Inertial Navigation Technology*,
2nd ed., IEE, 2004, sec. 10.3.2 (gyrocompassing).

Public API
----------
CompassLoopDesign, CompassLoopResult, CompassLoopTheory, loop_gains,
compass_loop_alignment, compass_loop_system, compass_loop_theory
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from ..core import kalman
from ..core.validation import as_array, as_float, positive
from ..gyrocompass.rocking import as_generator
from .earth import EARTH_RATE, earth_rate_ned, gravity_ned, normal_gravity
from .error_model import skew
from .estimate import AlignmentEstimate
from .imu import ImuRecord, Scenario, SensorErrors
from .preintegration import preintegrate
from .tilt_attitude import angles_from_matrix, attitude_matrix

__all__ = ["CompassLoopDesign", "CompassLoopResult", "CompassLoopTheory", "loop_gains", "compass_loop_alignment", "compass_loop_system", "compass_loop_theory"]


@dataclass(frozen=True)
class CompassLoopDesign:
    """Bandwidths and dampings of the two loops, and the epoch the navigator runs at.

    Parameters
    ----------
    levelling_bandwidth : float
        ω of the levelling (east-channel) loop [rad/s].
    levelling_damping : float
        ζ of the levelling loop, in (0, 1] (1: three real poles at −ω).
    compass_bandwidth : float
        ω of the gyrocompass (north-channel and azimuth) loop [rad/s].
    compass_damping : float
        ζ of the gyrocompass loop, in (0, 1].
    epoch : float
        Navigator step [s] (rounded to whole samples); ``ω · epoch`` must stay small.
    """

    levelling_bandwidth: float = 0.1
    levelling_damping: float = 0.7
    compass_bandwidth: float = 0.02
    compass_damping: float = 0.7
    epoch: float = 0.2

    def __post_init__(self):
        for name in ("levelling_bandwidth", "compass_bandwidth", "epoch"):
            object.__setattr__(self, name, positive(getattr(self, name), name))
        for name in ("levelling_damping", "compass_damping"):
            z = as_float(getattr(self, name), name)
            if not 0.0 < z <= 1.0:
                raise ValueError(f"Expected `{name}` in (0, 1], got {z:g}")
            object.__setattr__(self, name, z)
        fastest = max(self.levelling_bandwidth, self.compass_bandwidth) * (1.0 + 2.0 * max(self.levelling_damping, self.compass_damping))
        if fastest * self.epoch > 0.2:
            raise ValueError(f"Expected `epoch` below 0.2/(ω(1 + 2ζ)) = {0.2 / fastest:.3g} s for the fastest loop, got {self.epoch:g}")


def loop_gains(bandwidth: float, damping: float) -> tuple:
    """``(k1, k2, k3)`` of the loop ``s³ + k1 s² + k2 s + k3 = (s + ω)(s² + 2ζω s + ω²)``.

    Parameters
    ----------
    bandwidth : float
        ω [rad/s].
    damping : float
        ζ [1].

    Returns
    -------
    tuple of float
        ``(k1 [1/s], k2 [1/s²], k3 [1/s³])``.

    >>> loop_gains(0.1, 0.5)
    (0.2, 0.020000000000000004, 0.0010000000000000002)
    """
    w, z = positive(bandwidth, "bandwidth"), as_float(damping, "damping")
    return w * (1.0 + 2.0 * z), w * w * (1.0 + 2.0 * z), w**3


@dataclass(frozen=True)
class CompassLoopResult:
    """The compass loop's estimates at the end and its azimuth error over time.

    Attributes
    ----------
    estimate : AlignmentEstimate
        Heading and tilts at the end, against the attitude there.
    times : ndarray
        ``(E,)`` epoch ends [s].
    heading_error : ndarray
        ``(n, E)`` azimuth error ``ψ̂ − ψ`` at each epoch end [rad] (NaN where the record has no truth).
    """

    estimate: AlignmentEstimate
    times: np.ndarray
    heading_error: np.ndarray


def _gains(latitude: float, design: CompassLoopDesign) -> dict:
    g = normal_gravity(latitude)
    k1, k2, k3 = loop_gains(design.levelling_bandwidth, design.levelling_damping)
    c1, c2, c3 = loop_gains(design.compass_bandwidth, design.compass_damping)
    return {"damp": np.array([c1, k1, k1]), "uE": c2 / g, "uD": c3 / (g * EARTH_RATE * math.cos(latitude)), "uN": k2 / g, "z": k3 / g}


def compass_loop_alignment(
    record: ImuRecord, design: CompassLoopDesign | None = None, *, initial_attitude=None, prior_tilt: float = math.radians(0.1), prior_heading: float = math.radians(1.0), rng=None
) -> CompassLoopResult:
    """Run the compass loop on every trial of a record.

    Parameters
    ----------
    record : ImuRecord
        Sensor increments, with the truth at every epoch to follow the error
        over time (``truth_stride`` = samples per epoch), else at the end only.
    design : CompassLoopDesign, optional
        Bandwidths, dampings and epoch (default :class:`CompassLoopDesign`).
    initial_attitude : array_like, optional, keyword-only
        ``(n, 3, 3)`` initial ``C̃_b^n`` (a coarse alignment's); default the
        true attitude turned by errors drawn with ``prior_tilt`` and ``prior_heading``.
    prior_tilt, prior_heading : float, keyword-only
        Standard deviations of the drawn initial errors [rad].
    rng : Generator | SeedSequence | int | None, keyword-only
        Stream of the drawn initial errors.

    Returns
    -------
    CompassLoopResult

    Raises
    ------
    TypeError
        If ``record`` is not an ImuRecord.
    ValueError
        If the record is shorter than one epoch or the loop too fast for the epoch.

    References
    ----------
    Titterton & Weston (2004), sec. 10.3.2.
    """
    if not isinstance(record, ImuRecord):
        raise TypeError(f"Expected `record` to be an ImuRecord, got {type(record).__name__}")
    design = CompassLoopDesign() if design is None else design
    sc = record.scenario
    M = max(1, int(round(design.epoch / sc.dt)))
    ep = preintegrate(record.dtheta, record.dv, sc.dt, M)
    n, E, D = record.n_trials, ep.n_epochs, ep.epoch
    k = _gains(sc.latitude, design)
    W, gn = earth_rate_ned(sc.latitude), gravity_ned(sc.latitude)
    Wx = skew(W)
    E_earth = Rotation.from_rotvec(-W * D).as_matrix()
    dR = Rotation.from_quat(ep.rotation.reshape(-1, 4), scalar_first=True).as_matrix().reshape(n, E, 3, 3)
    every_epoch = record.truth_times.size >= E + 1 and np.allclose(record.truth_times[: E + 1], D * np.arange(E + 1))
    C_true0 = attitude_matrix(record.truth_angles[:, 0])
    if initial_attitude is None:
        g = as_generator(rng)
        phi0 = g.standard_normal((n, 3)) * np.array([prior_tilt, prior_tilt, prior_heading])
        C = Rotation.from_rotvec(-phi0).as_matrix() @ C_true0
    else:
        C = as_array(initial_attitude, "initial_attitude").reshape(n, 3, 3).copy()
    v = np.zeros((n, 3))
    z = np.zeros(n)
    heading = np.full((n, E), np.nan)
    truth = attitude_matrix(record.truth_angles[:, : E + 1]) if every_epoch else None
    for j in range(E):  # one step per epoch, vectorised over trials
        v = v + np.einsum("nij,nj->ni", C, ep.velocity[:, j]) - np.einsum("nij,nj->ni", C, ep.moment[:, j]) @ Wx.T + gn * D - 2.0 * D * (v @ Wx.T)
        C = E_earth @ C @ dR[:, j]
        z = z + k["z"] * v[:, 1] * D
        u = np.stack([-k["uN"] * v[:, 1] - z, k["uE"] * v[:, 0], k["uD"] * v[:, 0]], axis=-1)
        C = Rotation.from_rotvec(u * D).as_matrix() @ C
        v = v * (1.0 - k["damp"] * D)
        if truth is not None:
            heading[:, j] = angles_from_matrix(C).heading - record.truth_angles[:, j + 1, 0]
    a = angles_from_matrix(C)
    t = record.truth_angles[:, -1] if not every_epoch else record.truth_angles[:, E]
    est = AlignmentEstimate("compass", a.heading, a.beta, a.gamma, t[:, 0], t[:, 1], t[:, 2], "end")
    if truth is not None:
        heading = (heading + math.pi) % (2.0 * math.pi) - math.pi
    return CompassLoopResult(est, D * np.arange(1, E + 1), heading)


#: States of the linear closed loop (:func:`compass_loop_system`).
LOOP_STATES = ("phi_N", "phi_E", "phi_D", "dv_N", "dv_E", "dv_D", "z", "eps_N", "eps_E", "eps_D", "acc_N", "acc_E", "acc_D")


def _closed_loop(latitude: float, design: CompassLoopDesign) -> np.ndarray:
    """``A`` of the linear closed loop over :data:`LOOP_STATES` (biases constant, resolved in NED)."""
    k = _gains(latitude, design)
    W = earth_rate_ned(latitude)
    A = np.zeros((13, 13))
    A[0:3, 0:3] = -skew(W)
    A[0:3, 7:10] = -np.eye(3)
    A[3:6, 0:3] = skew(-gravity_ned(latitude))
    A[3:6, 3:6] = -2.0 * skew(W) - np.diag(k["damp"])
    A[3:6, 10:13] = np.eye(3)
    # φ' = … − u with u_N = −kN δv_E − z, u_E = kE δv_N, u_D = kD δv_N
    A[0, 4] += k["uN"]
    A[0, 6] += 1.0
    A[1, 3] -= k["uE"]
    A[2, 3] -= k["uD"]
    A[6, 4] = k["z"]
    return A


def compass_loop_system(latitude: float, design: CompassLoopDesign | None = None):
    """The linear closed loop as a python-control state space: bias inputs, azimuth-error output.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    design : CompassLoopDesign, optional
        The loops (default :class:`CompassLoopDesign`).

    Returns
    -------
    control.StateSpace
        States ``(φ, δv, z)``, inputs the gyro biases and accelerometer biases
        in NED (steps), output the azimuth error ``−φ_D`` [rad]; its poles are
        the roots of the two loops' polynomials (shifted by the Earth rate).

    Examples
    --------
    >>> import control
    >>> sys = compass_loop_system(math.radians(45.0), CompassLoopDesign(levelling_bandwidth=0.1, compass_bandwidth=0.02))
    >>> wn, zeta, _ = control.damp(sys, doprint=False)
    >>> [round(float(w), 3) for w in np.sort(wn)]
    [0.02, 0.02, 0.02, 0.1, 0.1, 0.1, 0.24]
    """
    import control

    design = CompassLoopDesign() if design is None else design
    A = _closed_loop(as_float(latitude, "latitude"), design)
    out = np.zeros((1, 7))
    out[0, 2] = -1.0
    return control.ss(A[:7, :7], A[:7, 7:], out, np.zeros((1, 6)))


@dataclass(frozen=True)
class CompassLoopTheory:
    """The linear closed loop's azimuth error over time: the response to the fixed biases and the standard deviation.

    Attributes
    ----------
    times : ndarray
        ``(K,)`` [s].
    mean : ndarray
        ``(K,)`` azimuth error of the fixed biases (and zero initial errors) [rad].
    std : ndarray
        ``(K,)`` standard deviation from the sensor noise, the random turn-on
        biases and the initial errors [rad].
    floor : float
        ``−ε_E/(Ω cos φ) + tan φ ∇_E/g`` of the fixed biases at the stable attitude [rad].
    floor_std : float
        Standard deviation of that floor over the random turn-on biases [rad].
    settling_time : float
        Time after which the azimuth error left by an initial azimuth error
        stays within 2 % of it (python-control's ``initial_response`` of the loop) [s].
    """

    times: np.ndarray
    mean: np.ndarray
    std: np.ndarray
    floor: float
    floor_std: float
    settling_time: float


def compass_loop_theory(
    scenario: Scenario,
    errors: SensorErrors | None = None,
    design: CompassLoopDesign | None = None,
    *,
    prior_tilt: float = math.radians(0.1),
    prior_heading: float = math.radians(1.0),
    points: int = 200,
) -> CompassLoopTheory:
    """The linear closed loop's azimuth error after 0 … T: mean from the fixed biases, covariance from the random terms.

    Parameters
    ----------
    scenario : Scenario
        Latitude, stable attitude and the alignment time T (its duration).
    errors : SensorErrors, optional
        Fixed and random biases, angle and velocity random walks (default ideal).
    design : CompassLoopDesign, optional
        The loops.
    prior_tilt, prior_heading : float, keyword-only
        Standard deviations of the initial attitude errors [rad].
    points : int, keyword-only
        Times returned.

    Returns
    -------
    CompassLoopTheory

    References
    ----------
    Britting (1971), ch. 10 (the gyrocompass loop's steady state).
    """
    import control

    e = SensorErrors() if errors is None else errors
    design = CompassLoopDesign() if design is None else design
    lat = scenario.latitude
    A = _closed_loop(lat, design)
    C0 = attitude_matrix(scenario.stable_angles)
    x0 = np.zeros(13)
    x0[7:10] = C0 @ e.gyro_bias
    x0[10:13] = C0 @ e.accel_bias
    P = np.zeros((13, 13))
    P[0:3, 0:3] = np.diag([prior_tilt**2, prior_tilt**2, prior_heading**2])
    P[7:10, 7:10] = e.gyro_bias_sigma**2 * np.eye(3)
    P[10:13, 10:13] = e.accel_bias_sigma**2 * np.eye(3)
    Qc = np.zeros((13, 13))
    Qc[0:3, 0:3] = e.gyro_noise**2 * np.eye(3)
    Qc[3:6, 3:6] = e.accel_noise**2 * np.eye(3)
    T = scenario.n_samples * scenario.dt
    times = np.linspace(0.0, T, int(points))
    F, Q = kalman.discretise(A, Qc, times[1] - times[0])
    mean, std = np.empty(times.size), np.empty(times.size)
    x = x0.copy()
    for i in range(times.size):
        mean[i], std[i] = -x[2], math.sqrt(max(P[2, 2], 0.0))
        x, P = F @ x, F @ P @ F.T + Q
    g = normal_gravity(lat)
    gain = np.zeros(13)
    gain[8] = -1.0 / (EARTH_RATE * math.cos(lat))  # −ε_E/(Ω cos φ)
    gain[11] = math.tan(lat) / g  # + tan φ ∇_E/g
    floor = float(gain @ x0)
    floor_std = math.hypot(gain[8] * e.gyro_bias_sigma, gain[11] * e.accel_bias_sigma)
    sys = compass_loop_system(lat, design)
    # the azimuth error after an initial azimuth error: the free response from φ_D(0) = 1
    t_resp = np.linspace(0.0, 40.0 / design.compass_bandwidth, 4000)
    resp = control.initial_response(sys, t_resp, X0=np.eye(7)[2])
    y = np.abs(np.squeeze(resp.outputs))
    outside = np.flatnonzero(y > 0.02)
    settling = float(t_resp[outside[-1] + 1]) if outside.size and outside[-1] + 1 < t_resp.size else (0.0 if not outside.size else math.inf)
    return CompassLoopTheory(times, mean, std, floor, floor_std, settling)
