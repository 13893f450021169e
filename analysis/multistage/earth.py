"""A spherical, rotating Earth: frames, position and the specific force of a moving point.

The geographic frame ζ has its axes along (north, up, east) — a right-handed
triad, ``north × up = east`` — as in section 5 of Plotnikov (1999).  The Earth
frame e is fixed to the Earth (axis 3 along the polar axis, axis 1 through
longitude 0); the inertial frame ξ coincides with e at ``t = 0`` and the Earth
turns about axis 3 at the rate Ω.

Gravity is the usual navigation model: the plumb-bob gravity (gravitation plus
the centrifugal acceleration of the Earth's rotation) has magnitude ``g`` and
points down the radius.  The gravitation is therefore
``G = −g u + Ω × (Ω × r)``, with u the local vertical and r the position: it has
a horizontal part, the horizontal centripetal acceleration
``Ω²R sin φ cos φ`` (:func:`horizontal_centripetal`), which no accelerometer
senses.

For a point moving over the surface with ground velocity V (in ζ), the
navigation equation ``V̇ = f − (2Ω + ρ) × V + g`` gives the specific force

    f = V̇ + (2Ω + ρ) × V − g,

with Ω the Earth rate and ρ the transport rate in ζ
(:func:`specific_force_geographic`).  :func:`inertial_position` and
:func:`inertial_velocity` give the same motion in ξ, so that
``v_ξ(t₁) − v_ξ(t₀) = ∫ (f + G) dt`` can be checked independently
(:func:`strapdown.analysis.multistage.trajectory.specific_force_residual`).

Examples
--------
>>> import numpy as np
>>> q = geographic_to_earth(0.0, 0.0)
>>> np.round(quat.rotate(q, [0.0, 1.0, 0.0]), 12) + 0.0   # up at (0°, 0°) is the x axis
array([1., 0., 0.])
"""

from __future__ import annotations

import numpy as np

from ..core import quaternion as quat
from ..core.validation import as_array, as_float, nonnegative, positive

__all__ = [
    "axis_rotation",
    "geographic_to_earth",
    "earth_to_inertial",
    "geographic_to_inertial",
    "inertial_position",
    "inertial_velocity",
    "gravitation",
    "specific_force_geographic",
    "horizontal_centripetal",
]

# ζ → e at latitude 0, longitude 0: north → e3, up → e1, east → e2.
_EQUATOR = np.array([0.5, -0.5, -0.5, -0.5])


def axis_rotation(axis: int, angle):
    """Quaternion of a rotation by ``angle`` about the coordinate axis ``axis`` (0, 1 or 2).

    Parameters
    ----------
    axis : int
        0, 1 or 2 for the axes 1, 2, 3.
    angle : array_like
        Rotation angle(s) [rad], right-handed.

    Returns
    -------
    ndarray, shape (..., 4)

    Raises
    ------
    ValueError
        If ``axis`` is not 0, 1 or 2.

    Examples
    --------
    >>> axis_rotation(2, np.pi)[..., 3].round(12)
    np.float64(1.0)
    """
    if axis not in (0, 1, 2):
        raise ValueError(f"Expected `axis` in (0, 1, 2), got {axis!r}")
    a = as_array(angle, "angle") * 0.5
    out = np.zeros(a.shape + (4,))
    out[..., 0] = np.cos(a)
    out[..., axis + 1] = np.sin(a)
    return out


def geographic_to_earth(latitude, longitude):
    """Quaternion of the geographic frame ζ (north, up, east) in the Earth frame e.

    Parameters
    ----------
    latitude : array_like
        Geocentric latitude φ [rad].
    longitude : array_like
        Longitude [rad].

    Returns
    -------
    ndarray, shape (..., 4)
        ``q`` with ``v_e = q ∘ v_ζ ∘ q̄``.
    """
    lat = as_array(latitude, "latitude")
    lon = as_array(longitude, "longitude")
    return quat.multiply(quat.multiply(axis_rotation(2, lon), axis_rotation(1, -lat)), _EQUATOR)


def earth_to_inertial(t, earth_rate: float):
    """Quaternion of the Earth frame e in the inertial frame ξ at time ``t``.

    Parameters
    ----------
    t : array_like
        Time [s] (the frames coincide at t = 0).
    earth_rate : float
        Ω [rad/s].

    Returns
    -------
    ndarray, shape (..., 4)
    """
    return axis_rotation(2, as_array(t, "t") * nonnegative(earth_rate, "earth_rate"))


def geographic_to_inertial(t, latitude, longitude, earth_rate: float):
    """Quaternion of ζ in ξ: :func:`earth_to_inertial` ∘ :func:`geographic_to_earth`.

    Parameters
    ----------
    t : array_like
        Time [s].
    latitude, longitude : array_like
        Position [rad] at ``t``.
    earth_rate : float
        Ω [rad/s].

    Returns
    -------
    ndarray, shape (..., 4)
    """
    return quat.multiply(earth_to_inertial(t, earth_rate), geographic_to_earth(latitude, longitude))


def inertial_position(t, latitude, longitude, earth_rate: float, earth_radius: float):
    """Position ``r = R u`` in ξ of a point on the sphere [m].

    Parameters
    ----------
    t : array_like
        Time [s].
    latitude, longitude : array_like
        Position [rad] at ``t``.
    earth_rate : float
        Ω [rad/s].
    earth_radius : float
        R [m].

    Returns
    -------
    ndarray, shape (..., 3)
    """
    q = geographic_to_inertial(t, latitude, longitude, earth_rate)
    return positive(earth_radius, "earth_radius") * quat.rotate(q, np.array([0.0, 1.0, 0.0]))


def inertial_velocity(t, latitude, longitude, ground_velocity, earth_rate: float, earth_radius: float):
    """Velocity ``ṙ = Ω × r + V`` in ξ [m/s], for a ground velocity V given in ζ.

    Parameters
    ----------
    t : array_like
        Time [s].
    latitude, longitude : array_like
        Position [rad] at ``t``.
    ground_velocity : array_like, shape (..., 3)
        Velocity relative to the Earth in ζ (north, up, east) [m/s]; its up
        component must be 0 on the sphere.
    earth_rate : float
        Ω [rad/s].
    earth_radius : float
        R [m].

    Returns
    -------
    ndarray, shape (..., 3)
    """
    v = as_array(ground_velocity, "ground_velocity", last=3)
    r = inertial_position(t, latitude, longitude, earth_rate, earth_radius)
    omega = np.array([0.0, 0.0, nonnegative(earth_rate, "earth_rate")])
    q = geographic_to_inertial(t, latitude, longitude, earth_rate)
    return np.cross(omega, r) + quat.rotate(q, v)


def gravitation(position, gravity: float, earth_rate: float):
    """Gravitation ``G = −g u + Ω × (Ω × r)`` in ξ [m/s²] (plumb-bob gravity g down the radius).

    Parameters
    ----------
    position : array_like, shape (..., 3)
        r in ξ [m].
    gravity : float
        Plumb-bob gravity g [m/s²].
    earth_rate : float
        Ω [rad/s] (the Earth's axis is axis 3 of ξ).

    Returns
    -------
    ndarray, shape (..., 3)
    """
    r = as_array(position, "position", last=3)
    g = positive(gravity, "gravity")
    omega = np.array([0.0, 0.0, nonnegative(earth_rate, "earth_rate")])
    up = r / np.linalg.norm(r, axis=-1, keepdims=True)
    return -g * up + np.cross(omega, np.cross(omega, r))


def specific_force_geographic(latitude, north_velocity, north_acceleration, *, gravity: float, earth_rate: float, earth_radius: float):
    """Specific force in ζ of a point moving north over the rotating sphere [m/s²].

    ``f = V̇ + (2Ω + ρ) × V − g`` with ``V = (V, 0, 0)``,
    ``Ω = Ω(cos φ, sin φ, 0)``, ``ρ = (0, 0, −V/R)`` and ``g = (0, −g, 0)``:

        f = (V̇,  g − V²/R,  −2Ω sin φ V).

    The last two terms are the centripetal and the Coriolis specific force.

    Parameters
    ----------
    latitude : array_like
        φ [rad].
    north_velocity : array_like
        Ground speed V to the north [m/s].
    north_acceleration : array_like
        V̇ [m/s²].
    gravity : float
        Plumb-bob gravity g [m/s²].
    earth_rate : float
        Ω [rad/s].
    earth_radius : float
        R [m].

    Returns
    -------
    ndarray, shape (..., 3)
        (north, up, east) components.
    """
    lat = as_array(latitude, "latitude")
    v = as_array(north_velocity, "north_velocity")
    a = as_array(north_acceleration, "north_acceleration")
    g = positive(gravity, "gravity")
    w = nonnegative(earth_rate, "earth_rate")
    r = positive(earth_radius, "earth_radius")
    lat, v, a = np.broadcast_arrays(lat, v, a)
    return np.stack([a, g - v * v / r, -2.0 * w * np.sin(lat) * v], axis=-1)


def horizontal_centripetal(latitude, earth_rate: float, earth_radius: float) -> float:
    """Northward horizontal part ``Ω²R sin φ cos φ`` of the centripetal acceleration of a point at rest [m/s²].

    With plumb-bob gravity down the radius no accelerometer senses it, yet it
    turns the inertial velocity ``Ω × r`` that a Schuler loop integrates.

    Parameters
    ----------
    latitude : float
        φ [rad].
    earth_rate : float
        Ω [rad/s].
    earth_radius : float
        R [m].

    Returns
    -------
    float

    Examples
    --------
    >>> round(horizontal_centripetal(np.radians(45.0), 7.292115e-5, 6.371e6), 5)
    0.01694
    """
    lat = as_float(latitude, "latitude")
    w = nonnegative(earth_rate, "earth_rate")
    return float(w * w * positive(earth_radius, "earth_radius") * np.sin(lat) * np.cos(lat))
