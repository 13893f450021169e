"""Increments of an epoch of samples: rotation, velocity and its first moment, in the epoch-start body frame.

Alignment filters and the inertial-frame alignment work at a low rate (an
*epoch* of M samples); the sensors deliver increments at the sample rate.  For
every epoch ``[t_j, t_j + M h]`` this module condenses the M angle and velocity
increments into

* the rotation ``ΔR_j`` of the body from the epoch start to its end (the
  sample rotation vectors with the two-sample coning correction
  ``(1/12) Δθ_{k−1} × Δθ_k``);
* the velocity increment ``ΔV_j = ∫ R(t) f dt`` resolved in the epoch-start
  body frame (rotation compensation ``½ Δθ × Δv + ⅙ Δθ × (Δθ × Δv)`` and the
  two-sample sculling correction ``(1/12)(Δθ_{k−1} × Δv_k + Δv_{k−1} × Δθ_k)``);
* its first moment ``S_j = ∫ (t − t_j) R(t) f dt``, which carries the turn of
  the navigation frame during the epoch (a correction ``−[ω×] C S_j`` of the
  navigation velocity).

The loop runs over the M samples of an epoch, vectorised over trials and
epochs, so its Python cost does not grow with the record length.

References
----------
Savage, P. G., "Strapdown inertial navigation integration algorithm design,
part 1: attitude algorithms", *J. Guid. Control Dyn.* 21(1), 1998, eq. (35)
(two-sample coning), and part 2, eq. (56) (two-sample sculling).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import quaternion as quat
from ..core.validation import as_array, as_int
from . import kernels

__all__ = ["EpochIncrements", "preintegrate", "chain_rotations"]


@dataclass(frozen=True)
class EpochIncrements:
    """Epoch increments of ``n`` trials.

    Attributes
    ----------
    rotation : ndarray
        ``(n, E, 4)`` quaternions of the body from epoch start to end (``C(t_j)ᵀ C(t_{j+1})``).
    velocity : ndarray
        ``(n, E, 3)`` ``∫ R(t) f dt`` in the epoch-start body frame [m/s].
    moment : ndarray
        ``(n, E, 3)`` ``∫ (t − t_j) R(t) f dt`` [m].
    epoch : float
        Epoch length M·h [s].
    samples_per_epoch : int
        M.
    """

    rotation: np.ndarray
    velocity: np.ndarray
    moment: np.ndarray
    epoch: float
    samples_per_epoch: int

    @property
    def n_epochs(self) -> int:
        """Epochs E."""
        return self.rotation.shape[1]


def preintegrate(dtheta, dv, dt: float, samples_per_epoch: int, *, compiled: bool | None = None) -> EpochIncrements:
    """Condense sample increments into epoch increments (trailing samples of a partial epoch are dropped).

    Parameters
    ----------
    dtheta : ndarray
        ``(n, N, 3)`` angle increments [rad].
    dv : ndarray
        ``(n, N, 3)`` velocity increments [m/s].
    dt : float
        Sample interval h [s].
    samples_per_epoch : int
        M, at least 1.
    compiled : bool or None, keyword-only
        One compiled loop over trials and samples (:mod:`~strapdown.analysis.alignment.kernels`)
        or the numpy form vectorised over trials and epochs, kept as the
        reference (equal to round-off); None (default): the loop when it pays
        off (:func:`~strapdown.analysis.alignment.kernels.use_compiled`).

    Returns
    -------
    EpochIncrements

    Raises
    ------
    ValueError
        If the record is shorter than one epoch, or the increments are not
        finite arrays of one shape ``(n, N, 3)``.
    """
    M = as_int(samples_per_epoch, "samples_per_epoch", minimum=1)
    dtheta, dv = as_array(dtheta, "dtheta", last=3), as_array(dv, "dv", last=3)
    if dtheta.ndim != 3 or dtheta.shape != dv.shape:
        raise ValueError(f"Expected `dtheta` and `dv` of the same shape (n, N, 3), got {dtheta.shape} and {dv.shape}")
    n, N, _ = dtheta.shape
    E = N // M
    if E < 1:
        raise ValueError(f"Expected at least one epoch of {M} samples, got {N} samples")
    if kernels.use_compiled(compiled, n * E * M):
        return EpochIncrements(*kernels.preintegrate_loop(dtheta, dv, dt, M, E), M * dt, M)
    prev_th = np.concatenate([np.zeros((n, 1, 3)), dtheta[:, : E * M - 1]], axis=1).reshape(n, E, M, 3)
    prev_v = np.concatenate([np.zeros((n, 1, 3)), dv[:, : E * M - 1]], axis=1).reshape(n, E, M, 3)
    th = dtheta[:, : E * M].reshape(n, E, M, 3)
    v = dv[:, : E * M].reshape(n, E, M, 3)
    R = quat.identity((n, E))
    V = np.zeros((n, E, 3))
    S = np.zeros((n, E, 3))
    for k in range(M):  # samples of an epoch; vectorised over trials and epochs
        a, b = th[:, :, k], v[:, :, k]
        pa, pb = prev_th[:, :, k], prev_v[:, :, k]  # the previous sample may belong to the previous epoch
        dvk = b + 0.5 * np.cross(a, b) + np.cross(a, np.cross(a, b)) / 6.0 + (np.cross(pa, b) + np.cross(pb, a)) / 12.0
        rot = quat.rotate(R, dvk)
        V += rot
        S += ((k + 0.5) * dt) * rot
        R = quat.multiply(R, quat.rotvec_to_quat(a + np.cross(pa, a) / 12.0, validate=False))
    return EpochIncrements(R, V, S, M * dt, M)


def chain_rotations(start, rotations, *, compiled: bool | None = None) -> np.ndarray:
    """Attitudes at the epoch boundaries: ``Q_0 = start``, ``Q_{j+1} = Q_j ∘ ΔR_j``.

    Parameters
    ----------
    start : array_like
        ``(n, 4)`` initial quaternions.
    rotations : ndarray
        ``(n, E, 4)`` epoch rotations.
    compiled : bool or None, keyword-only
        One compiled loop (:mod:`~strapdown.analysis.alignment.kernels`) or the numpy loop over
        epochs, kept as the reference (equal to round-off); None (default):
        the loop when it pays off (:func:`~strapdown.analysis.alignment.kernels.use_compiled`).

    Returns
    -------
    ndarray
        ``(n, E + 1, 4)``.
    """
    if kernels.use_compiled(compiled, np.size(rotations) // 4):  # one per epoch and trial
        return kernels.chain_loop(np.asarray(start, dtype=float), rotations)
    rotations = np.asarray(rotations, dtype=float)
    n, E, _ = rotations.shape
    out = np.empty((n, E + 1, 4))
    out[:, 0] = np.broadcast_to(np.asarray(start, dtype=float), (n, 4))
    for j in range(E):  # one step per epoch, vectorised over trials
        out[:, j + 1] = quat.multiply(out[:, j], rotations[:, j])
    return out
