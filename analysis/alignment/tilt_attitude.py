"""The attitude of the sensor block in the paper's angles: heading ψ and tilts β, γ.

The body-to-navigation matrix is ``C_b^n = R_z(ψ) R_x(−β) R_y(γ)`` (NED
navigation frame, elementary rotations ``R_a`` active and right-handed): a
heading ψ about the vertical, then a turn β about the first gyro's axis x,
then a tilt γ of that axis out of the horizontal plane.  At rest with ψ = 0
and zero tilts the body axes are x north, y east, z down.  With this
parametrisation the Earth rate seen by the two horizontal gyros at ψ = 0 is
``(f1, f2) = Ω (A, B)`` with exactly the ``A = cos φ cos γ + sin φ cos β sin γ``
and ``B = sin φ sin β`` of Hrechka & Koroliov (after their eq. (2)), so that
``−arctan(f2/f1) + arctan(B/A) = 0``: their σ is the tilt correction of this
attitude.

Arrays of angles have shape ``(..., 3)`` ordered ``(ψ, β, γ)``; leading axes
are batch or time.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["TiltAngles", "attitude_matrix", "angles_from_matrix", "body_rate", "body_acceleration", "tilts_from_specific_force", "euler_rate_matrix"]


class TiltAngles(NamedTuple):
    """Heading and tilts [rad].

    Attributes
    ----------
    heading : ndarray
        ψ, clockwise from north about the down axis.
    beta : ndarray
        β, about the first gyro's axis.
    gamma : ndarray
        γ, the first gyro's axis out of the horizontal plane.
    """

    heading: np.ndarray
    beta: np.ndarray
    gamma: np.ndarray


def attitude_matrix(angles) -> np.ndarray:
    """``C_b^n = R_z(ψ) R_x(−β) R_y(γ)`` of angles ``(..., 3) = (ψ, β, γ)``.

    Parameters
    ----------
    angles : array_like
        ``(..., 3)`` angles [rad].

    Returns
    -------
    ndarray
        ``(..., 3, 3)``; ``v_n = C @ v_b``.

    >>> C = attitude_matrix([0.0, 0.0, 0.0])
    >>> bool(np.allclose(C, np.eye(3)))
    True
    """
    a = np.asarray(angles, dtype=float)
    cp, sp = np.cos(a[..., 0]), np.sin(a[..., 0])
    cb, sb = np.cos(a[..., 1]), np.sin(a[..., 1])
    cg, sg = np.cos(a[..., 2]), np.sin(a[..., 2])
    # M = R_x(−β) R_y(γ): rows (cγ, 0, sγ), (−sβ sγ, cβ, sβ cγ), (−cβ sγ, −sβ, cβ cγ)
    m = np.empty(a.shape[:-1] + (3, 3))
    r1 = (cg, np.zeros_like(cg), sg)
    r2 = (-sb * sg, cb, sb * cg)
    r3 = (-cb * sg, -sb, cb * cg)
    for j in range(3):
        m[..., 0, j] = cp * r1[j] - sp * r2[j]
        m[..., 1, j] = sp * r1[j] + cp * r2[j]
        m[..., 2, j] = r3[j]
    return m


def angles_from_matrix(C) -> TiltAngles:
    """Heading and tilts of ``C_b^n`` (inverse of :func:`attitude_matrix` for ``|β|`` < π/2).

    Parameters
    ----------
    C : array_like
        ``(..., 3, 3)`` body-to-navigation matrices.

    Returns
    -------
    TiltAngles

    >>> a = angles_from_matrix(attitude_matrix([0.3, -0.02, 0.05]))
    >>> [round(float(x), 12) for x in a]
    [0.3, -0.02, 0.05]
    """
    C = np.asarray(C, dtype=float)
    beta = np.arctan2(-C[..., 2, 1], np.hypot(C[..., 2, 0], C[..., 2, 2]))
    gamma = np.arctan2(-C[..., 2, 0], C[..., 2, 2])
    heading = np.arctan2(-C[..., 0, 1], C[..., 1, 1])
    return TiltAngles(heading, beta, gamma)


def euler_rate_matrix(angles) -> np.ndarray:
    """``J`` with ``ω_nb^b = J (ψ', β', γ')``: the body rate of the angle rates.

    Parameters
    ----------
    angles : array_like
        ``(..., 3)`` angles [rad].

    Returns
    -------
    ndarray
        ``(..., 3, 3)``.
    """
    a = np.asarray(angles, dtype=float)
    cb, sb = np.cos(a[..., 1]), np.sin(a[..., 1])
    cg, sg = np.cos(a[..., 2]), np.sin(a[..., 2])
    J = np.zeros(a.shape[:-1] + (3, 3))
    J[..., 0, 0], J[..., 0, 1] = -sg * cb, -cg
    J[..., 1, 0], J[..., 1, 2] = -sb, 1.0
    J[..., 2, 0], J[..., 2, 1] = cg * cb, -sg
    return J


def body_rate(angles, rates) -> np.ndarray:
    """Body rate relative to the navigation frame, ``ω_nb^b`` [rad/s], resolved in the body frame.

    ``ω = R_y(γ)ᵀ R_x(−β)ᵀ e_z ψ' − R_y(γ)ᵀ e_x β' + e_y γ'``, i.e.
    ``ωx = −cγ β' − sγ cβ ψ'``, ``ωy = γ' − sβ ψ'``, ``ωz = −sγ β' + cγ cβ ψ'``.

    Parameters
    ----------
    angles : array_like
        ``(..., 3)`` angles (ψ, β, γ) [rad].
    rates : array_like
        ``(..., 3)`` their time derivatives [rad/s].

    Returns
    -------
    ndarray
        ``(..., 3)``.
    """
    a, d = np.asarray(angles, dtype=float), np.asarray(rates, dtype=float)
    cb, sb = np.cos(a[..., 1]), np.sin(a[..., 1])
    cg, sg = np.cos(a[..., 2]), np.sin(a[..., 2])
    dp, db, dg = d[..., 0], d[..., 1], d[..., 2]
    return np.stack([-cg * db - sg * cb * dp, dg - sb * dp, -sg * db + cg * cb * dp], axis=-1)


def body_acceleration(angles, rates, accelerations) -> np.ndarray:
    """Time derivative of :func:`body_rate`, ``dω_nb^b/dt`` [rad/s²] in body axes.

    Parameters
    ----------
    angles : array_like
        ``(..., 3)`` angles [rad].
    rates : array_like
        ``(..., 3)`` first derivatives [rad/s].
    accelerations : array_like
        ``(..., 3)`` second derivatives [rad/s²].

    Returns
    -------
    ndarray
        ``(..., 3)``.
    """
    a, d, dd = (np.asarray(x, dtype=float) for x in (angles, rates, accelerations))
    cb, sb = np.cos(a[..., 1]), np.sin(a[..., 1])
    cg, sg = np.cos(a[..., 2]), np.sin(a[..., 2])
    dp, db, dg = d[..., 0], d[..., 1], d[..., 2]
    ddp, ddb, ddg = dd[..., 0], dd[..., 1], dd[..., 2]
    wx = -cg * ddb + sg * dg * db - (cg * dg * cb - sg * sb * db) * dp - sg * cb * ddp
    wy = ddg - cb * db * dp - sb * ddp
    wz = -cg * dg * db - sg * ddb + (-sg * dg * cb - cg * sb * db) * dp + cg * cb * ddp
    return np.stack([wx, wy, wz], axis=-1)


def tilts_from_specific_force(f) -> np.ndarray:
    """Tilts ``(β, γ)`` [rad] of the body from its specific force at rest ``f_b = g (cβ sγ, sβ, −cβ cγ)``.

    Parameters
    ----------
    f : array_like
        ``(..., 3)`` specific force (or velocity increments: only the direction matters).

    Returns
    -------
    ndarray
        ``(..., 2)`` ``(β, γ)``: ``β = atan2(f_y, √(f_x² + f_z²))``, ``γ = atan2(f_x, −f_z)``.

    >>> C = attitude_matrix([1.0, 0.02, -0.03])
    >>> np.round(tilts_from_specific_force(C.T @ [0.0, 0.0, -9.8]), 12)
    array([ 0.02, -0.03])
    """
    f = np.asarray(f, dtype=float)
    beta = np.arctan2(f[..., 1], np.hypot(f[..., 0], f[..., 2]))
    gamma = np.arctan2(f[..., 0], -f[..., 2])
    return np.stack([beta, gamma], axis=-1)
