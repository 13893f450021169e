"""Earth model of the self-alignment: rotation rate and normal gravity (WGS-84), NED frame.

The navigation frame n is the local level frame at the rocking centre, x north,
y east, z down (NED), fixed to the Earth.  Seen from an inertial frame it turns
with the Earth rate ``ω_ie^n = Ω (cos φ, 0, −sin φ)``; gravity (the plumb-line
gravity, centrifugal part included) is ``g^n = (0, 0, g(φ))`` and the specific
force of a point at rest is ``−g^n``.

References
----------
NIMA TR8350.2, *Department of Defense World Geodetic System 1984*, 3rd ed.:
the Earth rate and the Somigliana normal gravity formula (eq. 4-1).
"""

from __future__ import annotations

import math

import numpy as np

from ..core.validation import as_float

__all__ = ["EARTH_RATE", "SOMIGLIANA", "normal_gravity", "earth_rate_ned", "gravity_ned"]

#: Earth rotation rate Ω [rad/s] (WGS-84).
EARTH_RATE = 7.292115e-5
_GAMMA_E = 9.7803253359  # normal gravity at the equator [m/s²]
_K = 0.00193185265241  # Somigliana constant
_E2 = 0.00669437999013  # first eccentricity squared
#: The constants of :func:`normal_gravity` (Somigliana's formula, WGS-84): normal gravity at the
#: equator [m/s²], Somigliana's constant and the first eccentricity squared, for compiled loops that repeat it.
SOMIGLIANA = (_GAMMA_E, _K, _E2)


def normal_gravity(latitude):
    """Normal gravity on the ellipsoid [m/s²] (Somigliana's formula, WGS-84).

    Parameters
    ----------
    latitude : float or array_like
        Geodetic latitude φ [rad].

    Returns
    -------
    float or ndarray
        A float for a scalar latitude, an array of its shape otherwise.

    >>> round(normal_gravity(0.0), 6), round(normal_gravity(math.pi / 2), 6)
    (9.780325, 9.832185)
    """
    if np.ndim(latitude):
        s2 = np.sin(np.asarray(latitude, dtype=float)) ** 2
        return _GAMMA_E * (1.0 + _K * s2) / np.sqrt(1.0 - _E2 * s2)
    s2 = math.sin(as_float(latitude, "latitude")) ** 2
    return _GAMMA_E * (1.0 + _K * s2) / math.sqrt(1.0 - _E2 * s2)


def earth_rate_ned(latitude) -> np.ndarray:
    """Earth rate in the NED frame, ``Ω (cos φ, 0, −sin φ)`` [rad/s].

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].

    Returns
    -------
    ndarray
        Shape (3,).
    """
    lat = as_float(latitude, "latitude")
    return EARTH_RATE * np.array([math.cos(lat), 0.0, -math.sin(lat)])


def gravity_ned(latitude) -> np.ndarray:
    """Gravity ``(0, 0, g(φ))`` in the NED frame [m/s²].

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].

    Returns
    -------
    ndarray
        Shape (3,).
    """
    return np.array([0.0, 0.0, normal_gravity(latitude)])
