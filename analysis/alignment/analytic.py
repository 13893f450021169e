"""Analytic self-alignment: formula (2) of Hrechka & Koroliov on averaged sensor outputs.

The method averages the gyro increments over the alignment time T into the
mean rate ``ω̄ = Σ Δθ_k / T`` and estimates the tilts by the sample means (16)
of the per-sample tilts ``(β_k, γ_k)`` of the accelerometer increments.  The
heading is then

``formula="paper"``
    eq. (2) with the tilt correction of the estimates (16),
    ``ψ̂ = −atan2(ω̄2, ω̄1) + σ(β̂, γ̂)``, two horizontal gyros; exact at ψ = 0
    (the correction σ of the paper is the one at zero heading);
``formula="levelled"``
    the mean rate levelled by the estimated tilts, ``ω_h = R_x(−β̂) R_y(γ̂) ω̄``,
    ``ψ̂ = atan2(−ω_h,y, ω_h,x)``; exact at any heading, the same as (2) to
    first order at ψ = 0.

It estimates the stable attitude (the reference is the stable heading ψ0).
Its theory is :func:`strapdown.analysis.alignment.theory.analytic_theory`.

References
----------
Hrechka & Koroliov, eqs. (2), (16).
"""

from __future__ import annotations

import math

import numpy as np

from ..gyrocompass.azimuth import relative_angle, tilt_components
from .estimate import AlignmentEstimate
from .imu import ImuRecord
from .tilt_attitude import tilts_from_specific_force

__all__ = ["analytic_alignment", "FORMULAS"]

FORMULAS = ("levelled", "paper")


def analytic_alignment(record: ImuRecord, *, formula: str = "levelled") -> AlignmentEstimate:
    """Heading and tilts from the averaged outputs of a record.

    Parameters
    ----------
    record : ImuRecord
        Sensor increments of n trials.
    formula : str
        ``"levelled"`` (default) or ``"paper"`` (eq. (2) with σ).

    Returns
    -------
    AlignmentEstimate
        Against the stable attitude.

    Raises
    ------
    ValueError
        For an unknown formula.

    References
    ----------
    Hrechka & Koroliov, eqs. (2), (16).

    Examples
    --------
    >>> from strapdown.analysis.alignment.imu import Scenario, simulate_imu
    >>> rec = simulate_imu(Scenario(math.radians(50), heading=0.3, beta0=0.01, gamma0=-0.02, duration=10.0), n_trials=1, rng=0)
    >>> est = analytic_alignment(rec)
    >>> abs(float(est.heading_error[0])) < 1e-12
    True
    """
    if formula not in FORMULAS:
        raise ValueError(f"Expected `formula` in {FORMULAS}, got {formula!r}")
    if not isinstance(record, ImuRecord):
        raise TypeError(f"Expected `record` to be an ImuRecord, got {type(record).__name__}")
    sc = record.scenario
    w = record.dtheta.sum(axis=1) / (sc.n_samples * sc.dt)
    tilts = tilts_from_specific_force(record.dv).mean(axis=1)  # the sample means (16)
    b, g = tilts[:, 0], tilts[:, 1]
    if formula == "paper":
        A, B = tilt_components(b, g, math.sin(sc.latitude), math.cos(sc.latitude))
        sigma = relative_angle(A, B, 1.0, 0.0)
        heading = -np.arctan2(w[:, 1], w[:, 0]) + sigma
    else:
        cb, sb, cg, sg = np.cos(b), np.sin(b), np.cos(g), np.sin(g)
        hx = cg * w[:, 0] + sg * w[:, 2]
        hy = -sb * sg * w[:, 0] + cb * w[:, 1] + sb * cg * w[:, 2]
        heading = np.arctan2(-hy, hx)
    n = record.n_trials
    stable = sc.stable_angles
    return AlignmentEstimate("analytic", heading, b, g, np.full(n, stable[0]), np.full(n, stable[1]), np.full(n, stable[2]), "stable")
