"""The linear error model of a strapdown navigator in the NED frame, in continuous time.

The states, in this order (the optional blocks only when asked for):

====================  =====================================================================
block                 states
====================  =====================================================================
attitude              φ_N, φ_E, φ_D with ``C̃ = (I − [φ×]) C`` (φ_N, φ_E the tilt errors,
                      ``−φ_D`` the azimuth error) [rad]
velocity              δv_N, δv_E, δv_D [m/s]
position (optional)   δp_N, δp_E, δp_D [m]
gyro biases           resolved in NED (ε_N, ε_E, ε_D: constant while the attitude is) or in
                      body axes (ε_x, ε_y, ε_z: constant while the block turns) [rad/s]
accelerometer biases  ∇_N, ∇_E, ∇_D or ∇_x, ∇_y, ∇_z [m/s²]
rocking (optional)    angle and rate of the shaping filter of each rocking axis (the rocking
                      the filter of :mod:`~strapdown.analysis.alignment.fine` assumes) [rad, rad/s]
====================  =====================================================================

with the dynamics (Savage 2007, ch. 12; Groves 2013, sec. 14.2)

    φ'  = −ω_in × φ + M δv − C ε + w_g,
    δv' = f^n × φ − (2ω_ie + ω_en) × δv + C ∇ + (2g/R) δp_D e_D + w_a,
    δp' = δv,

where ``ω_in = ω_ie + ω_en``, ``C = C_b^n`` for body-axis biases (the identity
for NED biases) and ``M δv = (δv_E, −δv_N, −δv_E tan φ)/R`` the error of the
transport rate (only with ``transport=True``, the in-motion model; the
stationary model of :mod:`~strapdown.analysis.alignment.fine` omits it, as it omits the Schuler coupling).
The measurements are the velocity (zero velocity at rest, or a GNSS velocity)
and, with the position block, the position.

:func:`alignment_error_model` is the continuous form of the fine-alignment
filter's model (:func:`strapdown.analysis.alignment.fine.filter_model`
discretises the same equations), :func:`navigation_error_model` the model of a
moving vehicle at one instant.

Each state also has an *equivalent-angle scale*: the error of that state that
acts like an attitude error of one radian (a gyro bias of Ω, an accelerometer
bias of g, a velocity error of g/Ω, a position error of g/Ω², a rocking rate of
ω0); :mod:`~strapdown.analysis.alignment.observability` compares states in these units.

References
----------
Savage, P. G., *Strapdown Analytics*, 2nd ed., 2007, ch. 12.
Groves, P. D., *Principles of GNSS, Inertial, and Multisensor Integrated
Navigation Systems*, 2nd ed., Artech House, 2013, sec. 14.2.

Public API
----------
ErrorModel, alignment_error_model, navigation_error_model, state_labels, skew, EARTH_RADIUS
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import kalman
from ..core.validation import as_array, as_float
from .earth import EARTH_RATE, earth_rate_ned, gravity_ned, normal_gravity
from .tilt_attitude import attitude_matrix, euler_rate_matrix

__all__ = ["ErrorModel", "alignment_error_model", "navigation_error_model", "state_labels", "skew", "EARTH_RADIUS", "BIAS_FRAMES"]

#: Mean radius of the Earth used by the transport-rate and gravity-gradient terms [m].
EARTH_RADIUS = 6_371_000.0
#: How bias states are resolved: in the navigation frame or in body axes.
BIAS_FRAMES = ("navigation", "body")

_AXES = {"navigation": ("N", "E", "D"), "body": ("x", "y", "z")}
_WORDS = {"N": "north", "E": "east", "D": "down", "x": "x", "y": "y", "z": "z"}


def skew(w) -> np.ndarray:
    """``[w×]``, the cross-product matrix of a 3-vector.

    Parameters
    ----------
    w : array_like
        ``(3,)`` vector.

    Returns
    -------
    ndarray
        ``(3, 3)``.

    >>> skew([1.0, 2.0, 3.0]) @ np.array([4.0, 5.0, 6.0])
    array([-3.,  6., -3.])
    """
    w = np.asarray(w, dtype=float)
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


@dataclass(frozen=True)
class ErrorModel:
    """A continuous linear error model ``x' = A x + w``, ``z = H x + v``.

    Attributes
    ----------
    A : ndarray
        ``(n, n)`` dynamics [1/s].
    Qc : ndarray
        ``(n, n)`` spectral density of the process noise w.
    H : ndarray
        ``(m, n)`` measurement matrix.
    names : tuple of str
        State names (``phi_N``, ``dv_E``, ``eps_x``, ...).
    scales : ndarray
        ``(n,)`` equivalent-angle scale of each state (the error acting like one radian of attitude error).
    measurement_names : tuple of str
        Names of the measured quantities.
    """

    A: np.ndarray
    Qc: np.ndarray
    H: np.ndarray
    names: tuple
    scales: np.ndarray
    measurement_names: tuple

    @property
    def dim(self) -> int:
        """State dimension."""
        return self.A.shape[0]

    def discretise(self, step: float):
        """``(F, Q)`` over ``step`` seconds, exactly (Van Loan, :func:`strapdown.analysis.core.kalman.discretise`).

        Parameters
        ----------
        step : float
            Interval [s].

        Returns
        -------
        tuple of ndarray
        """
        return kalman.discretise(self.A, self.Qc, step)

    def index(self, name: str) -> int:
        """Position of the state ``name``.

        Parameters
        ----------
        name : str
            A state name.

        Returns
        -------
        int

        Raises
        ------
        ValueError
            For a name that is not a state of the model.
        """
        if name not in self.names:
            raise ValueError(f"Expected `name` among {self.names}, got {name!r}")
        return self.names.index(name)


def state_labels(names) -> tuple:
    """Words for state names: ``phi_D`` → "azimuth", ``eps_E`` → "east gyro bias", ``acc_x`` → "accelerometer bias x".

    Parameters
    ----------
    names : sequence of str
        State names of an :class:`ErrorModel`.

    Returns
    -------
    tuple of str

    >>> state_labels(["phi_N", "phi_D", "eps_E", "acc_N", "acc_z", "dv_D", "beta_r'"])
    ('north tilt', 'azimuth', 'east gyro bias', 'north accelerometer bias', 'accelerometer bias z', 'down velocity', 'rocking rate β')
    """
    rocking = {"psi_r": "yaw", "beta_r": "β", "gamma_r": "γ"}
    out = []
    for name in names:
        head, _, axis = name.partition("_")
        word = _WORDS.get(axis, axis)
        body = axis in ("x", "y", "z")
        if name in ("phi_N", "phi_E"):
            out.append(f"{word} tilt")
        elif name == "phi_D":
            out.append("azimuth")
        elif head in ("dv", "dp"):
            out.append(f"{word} {'velocity' if head == 'dv' else 'position'}")
        elif head in ("eps", "acc"):
            kind = "gyro bias" if head == "eps" else "accelerometer bias"
            out.append(f"{kind} {axis}" if body else f"{word} {kind}")
        elif name.rstrip("'") in rocking:
            out.append(f"rocking {'rate' if name.endswith(chr(39)) else 'angle'} {rocking[name.rstrip(chr(39))]}")
        else:
            out.append(name)
    return tuple(out)


def _blocks(position: bool, biases: str) -> tuple:
    if biases not in BIAS_FRAMES:
        raise ValueError(f"Expected `biases` in {BIAS_FRAMES}, got {biases!r}")
    a = _AXES[biases]
    names = ["phi_N", "phi_E", "phi_D", "dv_N", "dv_E", "dv_D"]
    if position:
        names += ["dp_N", "dp_E", "dp_D"]
    names += [f"eps_{x}" for x in a] + [f"acc_{x}" for x in a]
    return tuple(names)


def _scales(names, gravity: float, extra=()) -> np.ndarray:
    per = {"phi": 1.0, "dv": gravity / EARTH_RATE, "dp": gravity / EARTH_RATE**2, "eps": EARTH_RATE, "acc": gravity}
    return np.array([per[n.partition("_")[0]] for n in names] + list(extra))


def alignment_error_model(scenario, tuning) -> ErrorModel:
    """The continuous model of the fine-alignment filter (:func:`strapdown.analysis.alignment.fine.filter_model`).

    Twelve states (attitude, velocity, NED biases) and, for a ``"shaping"``
    or ``"matched"`` disturbance, the angle and rate of each rocking axis it models
    (as a shaping filter driven by white noise; the filter of a ``"matched"``
    one replaces their transition over an epoch by the rocking's own); the
    velocity is measured (the zero velocity of the rocking centre), and sees the
    rocking rates through the lever arm unless the filter compensates it.

    Parameters
    ----------
    scenario : Scenario
        Latitude, stable attitude and lever arm
        (:class:`strapdown.analysis.alignment.imu.Scenario`).
    tuning : FilterTuning
        What the filter assumes (:class:`strapdown.analysis.alignment.fine.FilterTuning`).

    Returns
    -------
    ErrorModel
        ``model.discretise(epoch)`` equals the ``F, Q`` of ``filter_model`` at that epoch.

    References
    ----------
    Savage (2007), ch. 12 (the φ-angle error model).
    """
    W = earth_rate_ned(scenario.latitude)
    g = normal_gravity(scenario.latitude)
    fn = -gravity_ned(scenario.latitude)
    dist = tuning.disturbance
    axes = tuple(int(a) for a in np.flatnonzero(dist.sigma > 0)) if dist.kind in ("shaping", "matched") else ()
    n = 12 + 2 * len(axes)
    A = np.zeros((n, n))
    A[0:3, 0:3] = -skew(W)
    A[0:3, 6:9] = -np.eye(3)
    A[3:6, 0:3] = skew(fn)
    A[3:6, 3:6] = -2.0 * skew(W)
    A[3:6, 9:12] = np.eye(3)
    Qc = np.zeros((n, n))
    Qc[0:3, 0:3] = tuning.gyro_noise**2 * np.eye(3)
    Qc[3:6, 3:6] = tuning.accel_noise**2 * np.eye(3)
    H = np.zeros((3, n))
    H[:, 3:6] = np.eye(3)
    names = _blocks(False, "navigation")
    w = 2.0 * math.pi / dist.period
    extra = []
    if axes:
        C0 = attitude_matrix(scenario.stable_angles)
        L = -C0 @ skew(scenario.lever_arm) @ euler_rate_matrix(scenario.stable_angles)
        s2 = dist.sigma**2
        z = dist.damping
        labels = ("psi_r", "beta_r", "gamma_r")
        for k, i in enumerate(axes):
            a, b = 12 + 2 * k, 13 + 2 * k
            A[a, b] = 1.0
            A[b, a], A[b, b] = -w * w, -2.0 * z * w
            Qc[b, b] = 4.0 * z * w**3 * s2[i]
            if not tuning.lever_arm_known:
                H[:, b] = L[:, i]
            names = names + (labels[i], labels[i] + "'")
            extra += [1.0, w]
    return ErrorModel(A, Qc, H, names, _scales(names[:12], g, extra), ("v_N", "v_E", "v_D"))


def navigation_error_model(
    latitude,
    *,
    velocity=(0.0, 0.0, 0.0),
    specific_force=None,
    attitude=None,
    height: float = 0.0,
    biases: str = "navigation",
    position: bool = False,
    transport: bool = False,
    gyro_noise: float = 0.0,
    accel_noise: float = 0.0,
    gyro_bias_walk: float = 0.0,
    accel_bias_walk: float = 0.0,
    measure_position: bool | None = None,
) -> ErrorModel:
    """The error model of a navigator at one instant of its motion.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    velocity : array_like, keyword-only
        Velocity over the Earth, NED [m/s] (enters the Coriolis and transport terms).
    specific_force : array_like, optional, keyword-only
        Specific force f^n, NED [m/s²] (default ``−g^n``, at rest).
    attitude : array_like, optional, keyword-only
        ``C_b^n`` (3, 3) of the block, needed for body-axis biases (default the identity).
    height : float, keyword-only
        Height above the ellipsoid [m].
    biases : str, keyword-only
        ``"navigation"`` (biases resolved in NED) or ``"body"``.
    position : bool, keyword-only
        Include the position error states (NED metres).
    transport : bool, keyword-only
        Include the transport rate ω_en and its error (a moving vehicle).
    gyro_noise, accel_noise : float, keyword-only
        Angle random walk [rad/√s] and velocity random walk [m/s/√s].
    gyro_bias_walk, accel_bias_walk : float, keyword-only
        Rate random walk [rad/s/√s] and its accelerometer counterpart [m/s²/√s].
    measure_position : bool, optional, keyword-only
        Measure the position too (default: when there are position states).

    Returns
    -------
    ErrorModel

    Raises
    ------
    ValueError
        For bad shapes or an unknown ``biases``.

    References
    ----------
    Groves (2013), sec. 14.2.4 (the local-navigation-frame error equations).

    Examples
    --------
    At rest the vertical channel is uncoupled, and an east tilt error drives the north velocity error at g:

    >>> m = navigation_error_model(math.radians(45.0))
    >>> round(float(m.A[m.index("dv_N"), m.index("phi_E")]), 4)
    9.8062
    """
    lat = as_float(latitude, "latitude")
    v = as_array(velocity, "velocity", last=3).reshape(3)
    g = normal_gravity(lat)
    fn = -gravity_ned(lat) if specific_force is None else as_array(specific_force, "specific_force", last=3).reshape(3)
    C = np.eye(3) if attitude is None else as_array(attitude, "attitude").reshape(3, 3)
    names = _blocks(position, biases)
    n = len(names)
    Wie = earth_rate_ned(lat)
    R = EARTH_RADIUS + as_float(height, "height")
    Wen = np.array([v[1] / R, -v[0] / R, -v[1] * math.tan(lat) / R]) if transport else np.zeros(3)
    A = np.zeros((n, n))
    A[0:3, 0:3] = -skew(Wie + Wen)
    A[3:6, 0:3] = skew(fn)
    A[3:6, 3:6] = -skew(2.0 * Wie + Wen)
    if transport:
        A[0:3, 3:6] = np.array([[0.0, 1.0 / R, 0.0], [-1.0 / R, 0.0, 0.0], [0.0, -math.tan(lat) / R, 0.0]])
    b = 6
    if position:
        A[6:9, 3:6] = np.eye(3)
        A[5, 8] = 2.0 * g / R  # gravity grows downwards
        b = 9
    Cb = C if biases == "body" else np.eye(3)
    A[0:3, b : b + 3] = -Cb
    A[3:6, b + 3 : b + 6] = Cb
    Qc = np.zeros((n, n))
    Qc[0:3, 0:3] = gyro_noise**2 * np.eye(3)
    Qc[3:6, 3:6] = accel_noise**2 * np.eye(3)
    Qc[b : b + 3, b : b + 3] = gyro_bias_walk**2 * np.eye(3)
    Qc[b + 3 : b + 6, b + 3 : b + 6] = accel_bias_walk**2 * np.eye(3)
    measure_position = position if measure_position is None else bool(measure_position)
    rows = [3, 4, 5] + ([6, 7, 8] if measure_position and position else [])
    H = np.zeros((len(rows), n))
    H[np.arange(len(rows)), rows] = 1.0
    meas = ("v_N", "v_E", "v_D") + (("p_N", "p_E", "p_D") if len(rows) > 3 else ())
    return ErrorModel(A, Qc, H, names, _scales(names, g), meas)
