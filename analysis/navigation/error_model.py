"""The linear navigation error model at rest over the rotating Earth, with the states of one error source.

The navigation states are those of
:func:`strapdown.analysis.alignment.error_model.navigation_error_model`
(position and transport terms on, biases in body axes), stated there once
(Savage 2007, ch. 12; Groves 2013, sec. 14.2.4): estimate minus truth,
``C̃_b^n = (I − [φ×]) C_b^n`` with n the local-level frame at the computed
position, ::

    φ'  = −ω_ie × φ + M δv + (∂ω_ie/∂L) δp_N/R − C δω,
    δv' = f^n × φ − 2ω_ie × δv + C δf,
    δp' = δv + C δr,

``M δv = (δv_E, −δv_N, −δv_E tan φ)/R`` (whose loop with ``f^n × φ`` is the
Schuler loop, ``ω_s² = g/R``), ``∂ω_ie/∂L = Ω (−sin φ, 0, −cos φ)`` the error of
the Earth rate in the computed frame (added here to the model of the
alignment toolkit, which omits it: over an hour it changes a bias response by
about 1 %), C = ``C_b^n`` the attitude at rest (level,
heading ψ), δω and δf the gyro and accelerometer errors in body axes, δr a
position-rate error (the scrolling error).  The vertical channel is held (an
external height, as in every free-inertial budget: unaided it diverges with
time constant ``√(R/2g)``): δv_D and δp_D stay zero.

A *source* (:class:`Source`) adds its own states ``x_s`` with
``x_s' = F_s x_s + w_s`` and reaches the navigation through
``δω = G_g x_s``, ``δf = G_a x_s``, ``δr = G_p x_s``, plus white noise on δω
(angle random walk) or δf (velocity random walk).  At rest the body rate is the
Earth rate ``ω_b = Cᵀ ω_ie`` and the specific force ``f_b = Cᵀ(0, 0, −g)``, so that
scale-factor and misalignment errors are constant equivalent biases
``(S + M) ω_b`` and ``(S + M) f_b``.  One source per error of the data sheet
(:func:`sensor_sources`):

=========================  =====================================================
source                     states
=========================  =====================================================
gyro bias, accel bias      3 constants (fixed, signed: deterministic)
gyro/accel turn-on bias    3 constants, ``P0 = σ² I``
gyro/accel scale factor    3 constants: fixed ``S ω_b`` and random ``σ² ω_b²``
gyro/accel misalignment    3 constants: fixed ``M ω_b`` and random ``σ² (ω_j² + ω_k²)``
ARW, VRW                   none: white noise ``N²`` on δω or δf
gyro/accel bias            3 per Gauss–Markov term of the flicker band
instability                (:meth:`~strapdown.analysis.alignment.sensor_models.SensorSpec.gauss_markov`):
                           ``x' = −x/τ + w``, stationary
gyro/accel rate random     3 random walks, ``Qc = K²``
walk
gyro/accel quantization    none: the residue of the accumulated output at the
                           start (variance ``q²/12``, propagated as an initial
                           attitude or velocity error) and at the end (read
                           with the output)
=========================  =====================================================

and from a vibration environment (:func:`environment_sources`), constant
errors of the algorithms: coning drift and pseudo-coning (δω = −drift: exact
minus algorithm, a positive drift makes the computed attitude lag), sculling
and pseudo-sculling (δf = −rectification error), scrolling (δr = −e_r).

References
----------
Savage, P. G., *Strapdown Analytics*, 2nd ed., 2007, ch. 12.
Groves, P. D., *Principles of GNSS, Inertial, and Multisensor Integrated
Navigation Systems*, 2nd ed., 2013, sec. 14.2 and ch. 4 (sensor errors).
Titterton, D. H., Weston, J. L., *Strapdown Inertial Navigation Technology*,
2nd ed., 2004, ch. 12 (the Schuler, Foucault and 24-hour modes).

Public API
----------
.. autosummary::

   Site
   Source
   navigation_dynamics
   augmented_model
   sensor_sources
   environment_sources
   NAV_STATES
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..alignment.earth import EARTH_RATE, earth_rate_ned, normal_gravity
from ..alignment.error_model import EARTH_RADIUS, navigation_error_model
from ..core.validation import as_float, in_open_interval
from .imu_file import ImuSpec, TriadErrors

__all__ = ["Site", "Source", "navigation_dynamics", "augmented_model", "sensor_sources", "environment_sources", "NAV_STATES", "HELD"]

#: The navigation states, in order (attitude, velocity, position; NED).
NAV_STATES = ("phi_N", "phi_E", "phi_D", "dv_N", "dv_E", "dv_D", "dp_N", "dp_E", "dp_D")
#: The states of the held vertical channel.
HELD = (5, 8)


@dataclass(frozen=True)
class Site:
    """Where the system stands: latitude and heading, at rest and level.

    Parameters
    ----------
    latitude : float
        φ [rad], ``|φ|`` < π/2.
    heading : float
        ψ [rad]: body x points along it, z down.
    """

    latitude: float
    heading: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "latitude", in_open_interval(self.latitude, "latitude", -0.5 * math.pi, 0.5 * math.pi, text="(-π/2, π/2)"))
        object.__setattr__(self, "heading", as_float(self.heading, "heading"))

    @property
    def attitude(self) -> np.ndarray:
        """``C_b^n = R_z(ψ)`` (3, 3)."""
        c, s = math.cos(self.heading), math.sin(self.heading)
        return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    @property
    def gravity(self) -> float:
        """Normal gravity g(φ) [m/s²]."""
        return normal_gravity(self.latitude)

    @property
    def body_rate(self) -> np.ndarray:
        """``ω_b = Cᵀ ω_ie^n`` [rad/s]."""
        return self.attitude.T @ earth_rate_ned(self.latitude)

    @property
    def specific_force(self) -> np.ndarray:
        """``f_b = Cᵀ (0, 0, −g)`` [m/s²]."""
        return self.attitude.T @ np.array([0.0, 0.0, -self.gravity])


@dataclass(frozen=True)
class Source:
    """One error source: its states, how they reach the navigation, and its initial condition.

    Attributes
    ----------
    name : str
        ``"gyro bias"``, ``"ARW"``, ``"coning"``, ...
    F : ndarray
        ``(k, k)`` dynamics of the source states [1/s].
    Q : ndarray
        ``(k, k)`` their process-noise spectral density.
    G_gyro, G_accel, G_position : ndarray
        ``(3, k)`` maps to the body gyro error [rad/s], accelerometer error
        [m/s²] and position-rate error [m/s].
    white : ndarray
        ``(2,)`` spectral densities of white noise on the gyro and the accelerometer errors (N², per axis).
    mean0 : ndarray
        ``(k,)`` initial mean of the states (fixed errors).
    cov0 : ndarray
        ``(k, k)`` their initial covariance (at turn-on).
    start : ndarray
        ``(9,)`` variances of an initial navigation error of the source itself (quantization residues).
    reading : ndarray
        ``(9,)`` variances added to the navigation error read at any time (quantization residues).
    """

    name: str
    F: np.ndarray
    Q: np.ndarray
    G_gyro: np.ndarray
    G_accel: np.ndarray
    G_position: np.ndarray
    white: np.ndarray = field(default_factory=lambda: np.zeros(2))
    mean0: np.ndarray = None
    cov0: np.ndarray = None
    start: np.ndarray = field(default_factory=lambda: np.zeros(9))
    reading: np.ndarray = field(default_factory=lambda: np.zeros(9))

    def __post_init__(self):
        k = np.asarray(self.F).shape[0]
        if self.mean0 is None:
            object.__setattr__(self, "mean0", np.zeros(k))
        if self.cov0 is None:
            object.__setattr__(self, "cov0", np.zeros((k, k)))

    @property
    def size(self) -> int:
        """k, the number of source states."""
        return self.F.shape[0]

    @property
    def deterministic(self) -> bool:
        """True when nothing about the source is random (fixed errors: signed in the budget)."""
        return not (np.any(self.Q) or np.any(self.cov0) or np.any(self.white) or np.any(self.start) or np.any(self.reading))


def navigation_dynamics(site: Site) -> np.ndarray:
    """The 9 × 9 navigation dynamics at rest, vertical channel held (module docstring).

    Parameters
    ----------
    site : Site
        Latitude and heading.

    Returns
    -------
    ndarray
        ``(9, 9)`` [1/s].

    Examples
    --------
    The Schuler loop: ``∂φ_E'/∂δv_N = −1/R`` and ``∂δv_N'/∂φ_E = g``.

    >>> A = navigation_dynamics(Site(math.radians(45.0)))
    >>> round(float(-A[1, 3] * A[3, 1] * 6371000.0 / Site(math.radians(45.0)).gravity), 9)
    1.0
    """
    m = navigation_error_model(site.latitude, position=True, transport=True, biases="body", attitude=site.attitude)
    A = np.array(m.A[:9, :9])
    # the Earth rate of the computed frame is that of the computed latitude: δω_ie = ∂ω_ie^n/∂L δp_N/R
    lat = site.latitude
    A[0:3, 6] += EARTH_RATE * np.array([-math.sin(lat), 0.0, -math.cos(lat)]) / EARTH_RADIUS
    for i in HELD:
        A[i, :] = 0.0
        A[:, i] = 0.0
    return A


def augmented_model(site: Site, source: Source) -> tuple:
    """``(A, Qc)`` of the navigation states with the states of ``source`` appended.

    Parameters
    ----------
    site : Site
        Latitude and heading.
    source : Source
        The source.

    Returns
    -------
    tuple of ndarray
        ``(9 + k, 9 + k)`` each.
    """
    k = source.size
    C = site.attitude
    A = np.zeros((9 + k, 9 + k))
    A[:9, :9] = navigation_dynamics(site)
    A[0:3, 9:] = -C @ source.G_gyro
    A[3:6, 9:] = C @ source.G_accel
    A[6:9, 9:] = C @ source.G_position
    A[9:, 9:] = source.F
    Q = np.zeros_like(A)
    Q[0:3, 0:3] = source.white[0] * np.eye(3)
    Q[3:6, 3:6] = source.white[1] * np.eye(3)
    Q[9:, 9:] = source.Q
    for i in HELD:
        A[i, :] = 0.0
        Q[i, :] = 0.0
        Q[:, i] = 0.0
    return A, Q


def _constant(name, triad: str, mean=None, cov=None) -> Source:
    """Three constant states acting as a bias of ``triad`` (``"gyro"``, ``"accel"`` or ``"position"``)."""
    zero, one = np.zeros((3, 3)), np.eye(3)
    maps = {"gyro": (one, zero, zero), "accel": (zero, one, zero), "position": (zero, zero, one)}[triad]
    return Source(name, np.zeros((3, 3)), np.zeros((3, 3)), *maps, mean0=None if mean is None else np.asarray(mean, float), cov0=None if cov is None else np.asarray(cov, float))


def _empty(name, white=(0.0, 0.0), start=None, reading=None) -> Source:
    z = np.zeros((0, 0))
    s = Source(name, z, z, np.zeros((3, 0)), np.zeros((3, 0)), np.zeros((3, 0)), white=np.asarray(white, float))
    if start is not None:
        object.__setattr__(s, "start", np.asarray(start, float))
    if reading is not None:
        object.__setattr__(s, "reading", np.asarray(reading, float))
    return s


def _misalignment_variance(x: np.ndarray) -> np.ndarray:
    """Variance of ``M x`` per axis for independent off-diagonal entries of unit variance."""
    x2 = x * x
    return np.array([x2[1] + x2[2], x2[0] + x2[2], x2[0] + x2[1]])


def _triad_sources(site: Site, triad: str, e: TriadErrors) -> list:
    label = "gyro" if triad == "gyro" else "accel"
    x = site.body_rate if triad == "gyro" else site.specific_force
    out = []
    if np.any(e.bias):
        out.append(_constant(f"{label} bias", triad, mean=e.bias))
    if e.turn_on_bias:
        out.append(_constant(f"{label} turn-on bias", triad, cov=e.turn_on_bias**2 * np.eye(3)))
    if np.any(e.scale_factor) or e.scale_factor_sigma:
        out.append(_constant(f"{label} scale factor", triad, mean=e.scale_factor * x, cov=np.diag((e.scale_factor_sigma * x) ** 2)))
    if np.any(e.misalignment) or e.misalignment_sigma:
        off = e.matrix() - np.diag(np.diag(e.matrix()))
        out.append(_constant(f"{label} misalignment", triad, mean=off @ x, cov=np.diag(e.misalignment_sigma**2 * _misalignment_variance(x))))
    if e.random_walk:
        white = (e.random_walk**2, 0.0) if triad == "gyro" else (0.0, e.random_walk**2)
        out.append(_empty("ARW" if triad == "gyro" else "VRW", white=white))
    taus, qs = e.noise_spec().gauss_markov()
    if taus.size:
        k = 3 * taus.size
        F = np.diag(np.repeat(-1.0 / taus, 3))
        Q = np.diag(np.repeat(2.0 * qs / taus, 3))
        G = np.tile(np.eye(3), taus.size)
        zero = np.zeros((3, k))
        maps = (G, zero, zero) if triad == "gyro" else (zero, G, zero)
        out.append(Source(f"{label} bias instability", F, Q, *maps, cov0=np.diag(np.repeat(qs, 3))))
    if e.rate_random_walk:
        s = _constant(f"{label} rate random walk", triad)
        object.__setattr__(s, "Q", e.rate_random_walk**2 * np.eye(3))
        out.append(s)
    if e.quantum:
        v = np.zeros(9)
        v[0:3] = e.quantum**2 / 12.0 if triad == "gyro" else 0.0
        v[3:5] = e.quantum**2 / 12.0 if triad == "accel" else 0.0
        out.append(_empty(f"{label} quantization", start=v, reading=v))
    return out


def sensor_sources(site: Site, imu: ImuSpec) -> list:
    """One :class:`Source` per error of the data sheet (module docstring), gyro then accelerometer.

    Parameters
    ----------
    site : Site
        Latitude and heading (the rates the scale factors and misalignments act on).
    imu : ImuSpec
        The data sheet.

    Returns
    -------
    list of Source
        Only the errors the data sheet has.

    References
    ----------
    Groves (2013), ch. 4 (the sensor error model); IEEE Std 952-1997 (ARW, bias instability, RRW).
    """
    if not isinstance(site, Site) or not isinstance(imu, ImuSpec):
        raise TypeError("Expected a Site and an ImuSpec")
    return _triad_sources(site, "gyro", imu.gyro) + _triad_sources(site, "accel", imu.accel)


def environment_sources(drift, scrolling) -> list:
    """The algorithms' constant errors in a vibration environment as sources (module docstring).

    Parameters
    ----------
    drift : EnvironmentDrift
        From :func:`strapdown.analysis.vibration.drift.environment_drift` (body axes, exact minus algorithm).
    scrolling : array_like
        ``(3,)`` scrolling error from :func:`strapdown.analysis.navigation.scrolling.environment_scrolling` [m/s].

    Returns
    -------
    list of Source
        ``coning``, ``pseudo-coning``, ``sculling``, ``pseudo-sculling``, ``scrolling`` (those that are not zero).
    """
    parts = drift.parts
    vectors = {
        ("coning", "gyro"): sum((p.algorithm for p in parts), np.zeros(3)),
        ("pseudo-coning", "gyro"): sum((p.sensor for p in parts), np.zeros(3)),
        ("sculling", "accel"): sum((p.algorithm_sculling for p in parts), np.zeros(3)),
        ("pseudo-sculling", "accel"): sum((p.sensor_sculling for p in parts), np.zeros(3)),
        ("scrolling", "position"): np.asarray(scrolling, dtype=float).reshape(3),
    }
    return [_constant(name, triad, mean=-v) for (name, triad), v in vectors.items() if np.any(v)]
