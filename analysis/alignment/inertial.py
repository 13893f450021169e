"""Inertial-frame (coarse) self-alignment: the rocking is integrated out.

The body attitude relative to its own initial orientation frozen in inertial
space (frame ib0) is integrated from the gyros, and the specific force is
accumulated in that frame: ``v^{ib0}(t) = ∫ C_b^{ib0} f dt``.  For a block at
rest on the Earth the same quantity in the navigation frame frozen at t = 0
(frame in0) is known: ``v^{in0}(t) = ∫_0^t exp([ω_ie^n ×] τ) dτ · (−g^n)``,
the gravity vector turning with the Earth.  The constant rotation
``C_{ib0}^{in0}`` that maps one set of vectors onto the other is the solution
of Wahba's problem, solved for all trials at once by a batched SVD (Kabsch);
then ``C_b^n(T) = C_n^{in0}(T)ᵀ C_{ib0}^{in0} C_b^{ib0}(T)``.  The rocking
moves the body frame but the gyros follow it, and the lever-arm velocity it
adds to ``v^{ib0}`` stays bounded while the gravity term grows.

A block off the rocking centre has a lever-arm velocity ``v_r(t)``: it enters
``v^{ib0}`` as ``v_r(t) − v_r(0)``, a bounded oscillation plus the constant
``−v_r(0)`` of the (unknown) initial velocity.  Both sets of vectors are
therefore projected, before the fit, onto the complement of the functions the
disturbance can contain without bound: the constants for
``observation="velocity"``; the constants and the linear functions for
``observation="position"`` (the default), which integrates the vectors once
more, ``p(t) = ∫ v dt`` on both sides (exactly, from the first moments of the
epoch increments), so that the oscillation leaves a bounded displacement
against a gravity term growing as t².

The estimate is the attitude at the end of the alignment (reference "end").

References
----------
Wahba, G., "A least squares estimate of satellite attitude", *SIAM Review*
7(3), 1965, p. 409 (the problem); Markley, F. L., "Attitude determination using
vector observations and the singular value decomposition", *J. Astronaut. Sci.*
36(3), 1988 (the SVD solution).
"""

from __future__ import annotations

import math

import numpy as np

from ..core import quaternion as quat
from ..core.validation import positive
from .earth import earth_rate_ned, gravity_ned
from .estimate import AlignmentEstimate
from .imu import ImuRecord
from .preintegration import chain_rotations, preintegrate
from .tilt_attitude import angles_from_matrix

__all__ = ["inertial_alignment", "reference_velocity", "reference_position", "wahba_rotation", "OBSERVATIONS"]

OBSERVATIONS = ("position", "velocity")


def _skew(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def reference_velocity(latitude: float, times) -> np.ndarray:
    """``v^{in0}(t) = ∫_0^t exp([ω_ie^n ×] τ) dτ (−g^n)`` for a point at rest on the Earth [m/s].

    With the unit Earth axis u and ``K = [u ×]``:
    ``∫_0^t exp(KΩτ) dτ = t I + (1 − cos Ωt)/Ω K + (t − sin(Ωt)/Ω) K²``.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    times : array_like
        Times t [s].

    Returns
    -------
    ndarray
        ``(len(times), 3)`` in the navigation frame frozen at t = 0.
    """
    W = earth_rate_ned(latitude)
    Om = float(np.linalg.norm(W))
    K = _skew(W / Om)
    f = -gravity_ned(latitude)
    t = np.asarray(times, dtype=float)[:, None]
    return t * f + ((1.0 - np.cos(Om * t)) / Om) * (K @ f) + (t - np.sin(Om * t) / Om) * (K @ K @ f)


def reference_position(latitude: float, times) -> np.ndarray:
    """``p^{in0}(t) = ∫_0^t v^{in0} dτ`` of :func:`reference_velocity` [m].

    ``∫_0^t ∫_0^τ exp(KΩs) ds dτ = t²/2 I + (t − sin(Ωt)/Ω)/Ω K + (t²/2 − (1 − cos Ωt)/Ω²) K²``.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    times : array_like
        Times t [s].

    Returns
    -------
    ndarray
        ``(len(times), 3)``.
    """
    W = earth_rate_ned(latitude)
    Om = float(np.linalg.norm(W))
    K = _skew(W / Om)
    f = -gravity_ned(latitude)
    t = np.asarray(times, dtype=float)[:, None]
    return 0.5 * t * t * f + ((t - np.sin(Om * t) / Om) / Om) * (K @ f) + (0.5 * t * t - (1.0 - np.cos(Om * t)) / (Om * Om)) * (K @ K @ f)


def wahba_rotation(reference, body, weights=None) -> np.ndarray:
    """Rotations ``C`` minimising ``Σ_k w_k |r_k − C b_k|²`` for many problems at once.

    Parameters
    ----------
    reference : ndarray
        ``(n, K, 3)`` vectors ``r_k``.
    body : ndarray
        ``(n, K, 3)`` vectors ``b_k``.
    weights : array_like, optional
        ``(K,)`` weights (default 1).

    Returns
    -------
    ndarray
        ``(n, 3, 3)`` proper rotations.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> rng = np.random.default_rng(0)
    >>> b = rng.normal(size=(1, 5, 3))
    >>> C = Rotation.from_rotvec([0.1, -0.2, 0.3]).as_matrix()
    >>> bool(np.allclose(wahba_rotation(b @ C.T, b)[0], C))
    True
    """
    r, b = np.asarray(reference, dtype=float), np.asarray(body, dtype=float)
    w = np.ones(r.shape[1]) if weights is None else np.asarray(weights, dtype=float)
    B = np.swapaxes(r * w[:, None], 1, 2) @ b  # Σ_k w_k r_k b_kᵀ
    U, _, Vt = np.linalg.svd(B)
    d = np.sign(np.linalg.det(U) * np.linalg.det(Vt))
    U[:, :, 2] *= d[:, None]
    return U @ Vt


def inertial_alignment(record: ImuRecord, *, epoch: float = 1.0, observation: str = "position") -> AlignmentEstimate:
    """Inertial-frame alignment of every trial of a record.

    Parameters
    ----------
    record : ImuRecord
        Sensor increments of n trials.
    epoch : float
        Spacing of the vector observations [s] (rounded to whole samples).
    observation : str
        ``"position"`` (integrated velocity, default) or ``"velocity"``.

    Returns
    -------
    AlignmentEstimate
        Against the attitude at the end of the record.

    Examples
    --------
    >>> from strapdown.analysis.alignment.imu import Scenario, simulate_imu
    >>> rec = simulate_imu(Scenario(math.radians(50), heading=2.0, duration=60.0, sample_rate=20.0), n_trials=1, rng=0)
    >>> abs(float(inertial_alignment(rec).heading_error[0])) < 1e-7
    True
    """
    if not isinstance(record, ImuRecord):
        raise TypeError(f"Expected `record` to be an ImuRecord, got {type(record).__name__}")
    if observation not in OBSERVATIONS:
        raise ValueError(f"Expected `observation` in {OBSERVATIONS}, got {observation!r}")
    sc = record.scenario
    M = max(1, int(round(positive(epoch, "epoch") / sc.dt)))
    ep = preintegrate(record.dtheta, record.dv, sc.dt, M)
    n, E = record.n_trials, ep.n_epochs
    Q = chain_rotations(quat.identity((n,)), ep.rotation)
    dV = quat.rotate(Q[:, :-1], ep.velocity)
    v_body = np.cumsum(dV, axis=1)  # v^{ib0} at the epoch ends
    times = ep.epoch * np.arange(1, E + 1)
    if observation == "velocity":
        body, ref, basis = v_body, reference_velocity(sc.latitude, times), [np.ones(E)]
    else:  # p_{j+1} = p_j + v_j Δ + Q_j (ΔV_j Δ − S_j), exact
        v_start = v_body - dV
        step = v_start * ep.epoch + dV * ep.epoch - quat.rotate(Q[:, :-1], ep.moment)
        body, ref, basis = np.cumsum(step, axis=1), reference_position(sc.latitude, times), [np.ones(E), times / times[-1]]
    P = _residual_projector(np.stack(basis, axis=-1))
    C_ib0_in0 = wahba_rotation(np.broadcast_to(P @ ref, body.shape), P @ body)
    T = sc.n_samples * sc.dt
    W = earth_rate_ned(sc.latitude)
    Om = float(np.linalg.norm(W))
    K = _skew(W / Om)
    C_n_in0 = np.eye(3) + math.sin(Om * T) * K + (1.0 - math.cos(Om * T)) * (K @ K)
    q_end = Q[:, -1]
    C_b_ib0 = _quat_to_matrix(q_end)
    # samples after the last whole epoch: continue the body attitude to the end of the record
    tail = record.dtheta[:, E * M :]
    for k in range(tail.shape[1]):
        C_b_ib0 = C_b_ib0 @ _quat_to_matrix(quat.rotvec_to_quat(tail[:, k], validate=False))
    C = np.einsum("ji,njk,nkl->nil", C_n_in0, C_ib0_in0, C_b_ib0)
    a = angles_from_matrix(C)
    truth = record.truth_angles[:, -1]
    return AlignmentEstimate("inertial", a.heading, a.beta, a.gamma, truth[:, 0], truth[:, 1], truth[:, 2], "end")


def _residual_projector(basis):
    """``I − X (XᵀX)⁻¹ Xᵀ``: removes the span of the columns of ``basis`` from a time series."""
    q, _ = np.linalg.qr(basis)
    return np.eye(basis.shape[0]) - q @ q.T


def _quat_to_matrix(q):
    """Rotation matrices of scalar-first unit quaternions ``(..., 4)`` (scipy)."""
    from scipy.spatial.transform import Rotation

    q = np.asarray(q, dtype=float)
    return Rotation.from_quat(q.reshape(-1, 4), scalar_first=True).as_matrix().reshape(q.shape[:-1] + (3, 3))
