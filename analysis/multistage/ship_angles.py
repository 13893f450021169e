"""Krylov angles (yaw ψ, pitch θ, roll γ) and the attitude quaternion.

Plotnikov (1999), eqs. (1.7) and (3.6).  The horizontal frame η has its axis 2
up (``η2`` along the local vertical) and axes 1, 3 in the horizontal plane; the
body frame x has ``x1`` longitudinal, ``x2`` normal and ``x3`` starboard.  The
body attitude relative to η is reached by yaw ψ about axis 2, then pitch θ
about the new axis 3, then roll γ about the body axis 1:

    μ = q₂(ψ) ∘ q₃(θ) ∘ q₁(γ),        v_η = μ ∘ v_x ∘ μ̄,

where ``qⱼ(a) = (cos a/2, sin a/2 eⱼ)``.  Written out in components this is
eq. (3.6) of the paper, and the direction-cosine matrix ``A`` of (1.7), with
``x = A η``, is the transpose of the rotation matrix of μ.

Examples
--------
>>> import numpy as np
>>> q = angles_to_quat(0.3, -0.2, 0.1)
>>> np.allclose(quat_to_angles(q), [0.3, -0.2, 0.1])
True
"""

from __future__ import annotations

import numpy as np

from ..core import quaternion as quat
from ..core.blocks import row_slices
from ..core.validation import as_array, as_quaternion

__all__ = ["angles_to_quat", "quat_to_angles", "wrap_angle"]


def angles_to_quat(yaw, pitch, roll):
    """Quaternion μ of Krylov angles, eq. (3.6) of Plotnikov (1999).

    Parameters
    ----------
    yaw : array_like
        Yaw ψ about the vertical axis η2 [rad].
    pitch : array_like
        Pitch θ about the intermediate axis 3 [rad].
    roll : array_like
        Roll γ about the body axis x1 [rad].

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternion mapping the body frame x to the horizontal frame η.

    Raises
    ------
    ValueError
        If an angle is NaN or infinite.
    """
    psi = as_array(yaw, "yaw") * 0.5
    theta = as_array(pitch, "pitch") * 0.5
    gamma = as_array(roll, "roll") * 0.5
    cp, sp = np.cos(psi), np.sin(psi)
    ct, st = np.cos(theta), np.sin(theta)
    cg, sg = np.cos(gamma), np.sin(gamma)
    slices = row_slices(psi.shape) if psi.shape == theta.shape == gamma.shape else None
    if slices is not None:  # large arrays: the same products block by block (elementwise, so the same bits)
        out = np.empty(psi.shape + (4,))
        for b in slices:
            for k, part in enumerate(_products(cp[b], sp[b], ct[b], st[b], cg[b], sg[b])):
                out[b][..., k] = part
        return out
    return np.stack(_products(cp, sp, ct, st, cg, sg), axis=-1)


def _products(cp, sp, ct, st, cg, sg) -> tuple:
    """The components of (3.6) from the cosines and sines of the half angles."""
    return (
        cp * ct * cg - sp * st * sg,
        sp * st * cg + cp * ct * sg,
        sp * ct * cg + cp * st * sg,
        cp * st * cg - sp * ct * sg,
    )


def quat_to_angles(q):
    """Krylov angles (ψ, θ, γ) of an attitude quaternion, from the matrix (1.7).

    The quaternion is normalised first.  With ``A`` the matrix of (1.7):
    ``sin θ = a12``, ``tan γ = −a32 / a22`` and ``tan ψ = −a13 / a11``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Attitude quaternion(s), body x to horizontal η (need not be unit).

    Returns
    -------
    ndarray, shape (..., 3)
        ``(ψ, θ, γ)`` [rad]; θ in [−π/2, π/2], ψ and γ in (−π, π].

    Raises
    ------
    ValueError
        If ``q`` is not ``(..., 4)``, not finite, or zero.
    """
    q = quat.normalize(as_quaternion(q, "q"), "q")
    q0, q1, q2, q3 = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    a11 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
    a12 = 2.0 * (q1 * q2 + q0 * q3)
    a13 = 2.0 * (q1 * q3 - q0 * q2)
    a22 = q0 * q0 + q2 * q2 - q1 * q1 - q3 * q3
    a32 = 2.0 * (q2 * q3 - q0 * q1)
    pitch = np.arcsin(np.clip(a12, -1.0, 1.0))
    roll = np.arctan2(-a32, a22)
    yaw = np.arctan2(-a13, a11)
    return np.stack([yaw, pitch, roll], axis=-1)


def wrap_angle(a):
    """Wrap angles to (−π, π] [rad].

    Parameters
    ----------
    a : array_like
        Angles [rad].

    Returns
    -------
    ndarray
    """
    a = np.asarray(a, dtype=float)
    return np.pi - np.mod(np.pi - a, 2.0 * np.pi)
