"""The composite attitude (2.6) and the yaw: stage 2 undoes what stage 1 does to the yaw.

By :mod:`strapdown.derivations.multistage.composition` the composite
``P = ν₁∘ν`` of two stages obeys ``2P' = P∘ω + C₁∘ν``: every correction of
stage 1 cancels, and P is the gyro-integrated attitude corrected by stage 2
only.  The discrete cascade has the same property exactly: with stage 2 fed
``ν_n ∘ Δq_n ∘ ν̄_{n+1}`` and left without correction, ``P_{n+1} = P_n ∘ Δq_n``
for any stage 1 (:func:`composite_identity`).

So when stage 1 corrects all four components of ν toward the tilt quaternion
(1.10) — whose yaw is 0 by construction — its yaw is pulled away from the true
yaw (which, for a body fixed to the Earth, grows relative to the azimuth-free
frame by ``Ω sin φ t``), while the composite yaw still follows the gyros
(:func:`yaw_study`).

Examples
--------
>>> import numpy as np
>>> from strapdown.analysis.core import quaternion as quat
>>> dq = quat.rotvec_to_quat(np.full((3, 3), 0.1))
>>> np.allclose(gyro_attitude(dq)[-1], quat.rotvec_to_quat([0.3, 0.3, 0.3]))
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core import quaternion as quat
from ..core.validation import as_array, positive
from .sensors import SensorData
from .stages import Stage, plotnikov_1999_stages, run_multistage, run_stage
from .trajectory import Scenario, sample

__all__ = ["gyro_attitude", "CompositeIdentity", "composite_identity", "YawReading", "YawStudy", "yaw_study"]


def gyro_attitude(rotation, *, initial=(1.0, 0.0, 0.0, 0.0)) -> np.ndarray:
    """Attitude integrated from the increments alone: ``P_{n+1} = P_n ∘ Δq_n``.

    Parameters
    ----------
    rotation : array_like, shape (N, 4)
        Unit quaternion increments Δq_n.
    initial : array_like, shape (4,)
        P_0.

    Returns
    -------
    ndarray, shape (N+1, 4)
        (A stage with zero gains and ρ = 0 run by the same recursion.)
    """
    dq = as_array(rotation, "rotation", last=4)
    still = Stage.constant(0.0, 0.0, "external", rho=0.0)
    frozen = np.broadcast_to(np.zeros(4), (dq.shape[0] + 1, 4))
    nu, _ = run_stage(still, 1.0, dq, reference=frozen, initial=initial)
    return nu


@dataclass(frozen=True)
class CompositeIdentity:
    """Result of :func:`composite_identity`.

    Attributes
    ----------
    max_difference : float
        Largest ``|P − P_gyro|`` over the run (components of unit quaternions).
    stage1_yaw_peak : float
        Peak ``|Δψ|`` of stage 1 alone [rad] (to show that stage 1 did act).
    composite_yaw_peak : float
        Peak ``|Δψ|`` of the composite [rad].
    """

    max_difference: float
    stage1_yaw_peak: float
    composite_yaw_peak: float


def composite_identity(data: SensorData, stage1: Stage, *, engine: str = "compiled") -> CompositeIdentity:
    """Run ``stage1`` and an uncorrected stage 2 and compare the composite with the gyro attitude.

    Parameters
    ----------
    data : SensorData
        Sensor record.
    stage1 : Stage
        Any first stage.
    engine : {"compiled", "python"}
        Implementation of the stage recursion.

    Returns
    -------
    CompositeIdentity
        ``max_difference`` is at round-off: the corrections of stage 1 cancel
        in the composite.

    References
    ----------
    Plotnikov (1999), eqs. (2.2), (2.6), (3.13).
    """
    if not isinstance(stage1, Stage):
        raise TypeError(f"Expected `stage1` to be a Stage, got {type(stage1).__name__}")
    idle = Stage.constant(0.0, 0.0, "pure", rho=0.0)
    res = run_multistage(data, (stage1, idle), engine=engine)
    p_gyro = gyro_attitude(quat.rotvec_to_quat(data.gyro, validate=False))
    p_gyro /= np.linalg.norm(p_gyro, axis=-1, keepdims=True)
    diff = res.composite[1] - p_gyro * np.sign(np.sum(res.composite[1] * p_gyro, axis=-1, keepdims=True))
    peak = res.peak()
    return CompositeIdentity(float(np.abs(diff).max()), float(peak[0, 0]), float(peak[1, 0]))


@dataclass(frozen=True)
class YawReading:
    """Yaw errors of one reading of stage 1 (:func:`yaw_study`).

    Attributes
    ----------
    components : tuple of int
        Components corrected by stage 1.
    times : ndarray
        Sample times [s].
    stage1_yaw : ndarray
        Δψ after stage 1 at ``times`` [rad].
    two_stage_yaw : ndarray
        Δψ after two stages at ``times`` [rad].
    stage1_peak : float
        Peak ``|Δψ|`` after stage 1 over the run [rad].
    two_stage_peak : float
        Peak ``|Δψ|`` after two stages over the run [rad].
    true_yaw_end : float
        True yaw relative to η at the end of the run [rad].
    series_time : ndarray
        Times of the decimated series [s].
    series_stage1 : ndarray
        Δψ after stage 1 on ``series_time`` [rad].
    series_two_stage : ndarray
        Δψ after two stages on ``series_time`` [rad].
    """

    components: tuple
    times: np.ndarray
    stage1_yaw: np.ndarray
    two_stage_yaw: np.ndarray
    stage1_peak: float
    two_stage_peak: float
    true_yaw_end: float
    series_time: np.ndarray
    series_stage1: np.ndarray
    series_two_stage: np.ndarray

    @property
    def peak(self) -> float:
        """The larger of the two peaks, after stage 1 and after two stages [rad]."""
        return max(self.stage1_peak, self.two_stage_peak)

    def stage1_yaw_at(self, t: float) -> float:
        """Δψ after stage 1 at one of :attr:`times` [rad]; NaN if ``t`` is not among them.

        Parameters
        ----------
        t : float
            Time [s].

        Returns
        -------
        float
        """
        hit = np.flatnonzero(self.times == t)
        return float(self.stage1_yaw[hit[0]]) if hit.size else float("nan")


@dataclass(frozen=True)
class YawStudy:
    """Yaw of the section-5 cascade for stage 1 correcting components (1, 3) or all four.

    Attributes
    ----------
    readings : tuple of YawReading
        (1, 3) first, then (0, 1, 2, 3).
    identity : CompositeIdentity
        The composite identity for the all-four stage 1 on the same record.
    yaw_rate : float
        ``Ω sin φ0``, the rate of the true yaw relative to η at rest [rad/s].
    """

    readings: tuple
    identity: CompositeIdentity
    yaw_rate: float

    def true_yaw(self, t):
        """The true yaw relative to η at rest, ``Ω sin φ0 t`` [rad].

        Parameters
        ----------
        t : float or array_like
            Time [s].

        Returns
        -------
        float or ndarray
        """
        return self.yaw_rate * t


def yaw_study(scenario: Scenario | None = None, *, step: float = 0.1, times=(600.0, 1000.0, 2000.0, 5000.0), rng=None, engine: str = "compiled") -> YawStudy:
    """Yaw errors of stage 1 and of the composite for both readings of the stage-1 correction.

    Parameters
    ----------
    scenario : Scenario, optional
        Default: section 5 with the package's readings.
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    times : sequence of float
        Times at which to report the errors [s] (rounded to the grid).
    rng : numpy.random.Generator, int, SeedSequence or None
        Sensor-noise source.
    engine : {"compiled", "python"}
        Implementation of the stage recursion.

    Returns
    -------
    YawStudy
    """
    sc = Scenario() if scenario is None else scenario
    positive(step, "step")
    data = sample(sc, step, rng=rng)
    times = np.asarray([t for t in times if 0.0 <= t <= sc.duration], dtype=float)
    idx = np.rint(times / data.step).astype(int)
    every = max(1, data.time.size // 2500)
    readings = []
    for comps in ((1, 3), (0, 1, 2, 3)):
        stages = plotnikov_1999_stages(sc.gravity, sc.earth_radius, stage1_components=comps)
        res = run_multistage(data, stages, engine=engine)
        peak = res.peak()
        e = res.errors[:, :, 0]
        readings.append(
            YawReading(comps, data.time[idx], e[0, idx], e[1, idx], float(peak[0, 0]), float(peak[1, 0]), float(data.angles[-1, 0]), data.time[::every], e[0, ::every], e[1, ::every])
        )
    stage1_all = plotnikov_1999_stages(sc.gravity, sc.earth_radius, stage1_components=(0, 1, 2, 3))[0]
    identity = composite_identity(data, stage1_all, engine=engine)
    return YawStudy(tuple(readings), identity, sc.vertical_earth_rate)
