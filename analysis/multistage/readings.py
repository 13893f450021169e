"""Readings of the section-5 example of Plotnikov (1999) that the text cannot decide, run side by side.

Section 5 leaves open, or prints in a way that cannot be taken literally:

* the rocking envelope ``E = exp(−0.1(t − 600))`` for t = 1000…5000 s (as
  printed it is 4·10⁻¹⁸ when rocking starts): read with the origin at the start
  of rocking, or with a decay of 10⁻³ s⁻¹;
* the acceleration, 20 m/s² as printed (2 m/s² brings stage 1 near the
  printed pitch error only together with a second change, (1.4) for (1.10));
* the factor c (printed c = 2; c = 1 is consistent with the half-angle
  quaternion (1.10));
* which components stage 1 corrects: the horizontal ones (1, 3) or all four;
* the integral at the gain switch of stage 2: carried, rescaled with l(t), or
  bumpless.

:class:`Reading` holds one choice of each; :func:`standard_readings` the set
the stability report compares; :func:`run_readings` runs them on the truth
model of :mod:`strapdown.analysis.multistage.trajectory`.  :func:`section5_loops`
gives the linearised loops of the printed gains.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

from ..core import montecarlo
from ..core.validation import positive
from .stages import plotnikov_1999_stages, run_multistage
from .tilt_loop import AccelSensitivity, StageLoop, acceleration_sensitivity
from .trajectory import Scenario, sample

__all__ = [
    "Reading",
    "ReadingResult",
    "standard_readings",
    "run_readings",
    "PaperComparison",
    "compare_with_paper",
    "printed_envelope_at_rocking_start",
    "NamedLoop",
    "section5_loops",
    "schuler_detuning",
]


def _section5():
    from ...derivations.multistage.published import SECTION5

    return SECTION5


@dataclass(frozen=True)
class Reading:
    """One reading of section 5: the scenario constants and stage choices the text leaves open.

    Parameters
    ----------
    label : str
        Short description.
    rocking_decay : float, optional
        d of the envelope [1/s]; default the printed 0.1.
    rocking_decay_origin : float, optional
        t_d of the envelope [s]; None: the start of rocking.
    accel : float, optional
        Acceleration [m/s²]; default the printed 20.
    stage1_reference : {"tilt", "pure"}
        μ⁺ of stage 1.
    stage1_c : float, optional
        c of stage 1 (default the consistent one).
    stage1_components : tuple of int
        Components corrected by stage 1.
    switch : {"carry", "rescale", "bumpless"}
        The integral of stage 2 at its switch.
    truth : {"rotating-earth", "no-coriolis"}
        Truth model.
    earth_rate : float, optional
        Ω [rad/s]; default the Earth's.
    """

    label: str
    rocking_decay: float | None = None
    rocking_decay_origin: float | None = None
    accel: float | None = None
    stage1_reference: str = "tilt"
    stage1_c: float | None = None
    stage1_components: tuple = (1, 3)
    switch: str = "carry"
    truth: str = "rotating-earth"
    earth_rate: float | None = None

    def scenario(self, base: Scenario | None = None) -> Scenario:
        """The scenario of this reading.

        Parameters
        ----------
        base : Scenario, optional
            Scenario whose other fields are kept; default :class:`Scenario`.

        Returns
        -------
        Scenario
        """
        s5 = _section5()
        sc = Scenario() if base is None else base
        kw = dict(
            rocking_decay=s5.envelope_decay if self.rocking_decay is None else self.rocking_decay,
            rocking_decay_origin=self.rocking_decay_origin,
            accel=s5.accel if self.accel is None else self.accel,
            truth=self.truth,
        )
        if self.earth_rate is not None:
            kw["earth_rate"] = self.earth_rate
        return replace(sc, **kw)

    def stages(self, gravity: float = 9.81, earth_radius: float = 6.371e6) -> tuple:
        """The two stages of this reading.

        Parameters
        ----------
        gravity : float
            g [m/s²].
        earth_radius : float
            R [m].

        Returns
        -------
        tuple of Stage
        """
        return plotnikov_1999_stages(
            gravity, earth_radius, stage1_reference=self.stage1_reference, stage1_c=self.stage1_c, stage1_components=self.stage1_components, switch=self.switch
        )


def standard_readings() -> tuple:
    """The readings the stability report compares: the default first, then one change at a time (and one pair).

    Returns
    -------
    tuple of Reading
    """
    s5 = _section5()
    return (
        Reading("default: E = exp(−0.1(t − 1000)), 20 m/s², (1.10) with c = 1 on ν₁, ν₃, integral carried"),
        Reading("envelope as printed, exp(−0.1(t − 600)) (no rocking)", rocking_decay_origin=s5.envelope_origin),
        Reading("envelope exp(−0.001(t − 600))", rocking_decay=1e-3, rocking_decay_origin=s5.envelope_origin),
        Reading("2 m/s² instead of 20", accel=2.0),
        Reading("stage 1 on (1.4) with c = 2", stage1_reference="pure"),
        Reading("2 m/s² and stage 1 on (1.4) with c = 2", accel=2.0, stage1_reference="pure"),
        Reading("stage 1 with the printed c = 2 on (1.10)", stage1_c=2.0),
        Reading("stage 1 corrects all four components", stage1_components=(0, 1, 2, 3)),
        Reading("all four components and envelope exp(−0.001(t − 600))", stage1_components=(0, 1, 2, 3), rocking_decay=1e-3, rocking_decay_origin=s5.envelope_origin),
        Reading("integral rescaled with l(t) at the switch", switch="rescale"),
        Reading("bumpless switch", switch="bumpless"),
        Reading("earlier truth model (no Coriolis, body turning with η at rest)", truth="no-coriolis"),
        Reading("diagnostic: Earth rotation off (Ω = 0)", earth_rate=0.0),
    )


@dataclass(frozen=True)
class ReadingResult:
    """Peak errors of one reading (:func:`run_readings`).

    Attributes
    ----------
    reading : Reading
        The reading.
    peaks : tuple of StagePeaks
        After stage 1 and after two stages, over the whole run [rad].
    yaw_at_switch : tuple of float
        Δψ after stage 1 and after two stages at the gain switch of stage 2 [rad].
    time_of_peak : tuple of tuple
        Times of the peaks (yaw, pitch, roll) per stage [s].
    """

    reading: Reading
    peaks: tuple
    yaw_at_switch: tuple
    time_of_peak: tuple = field(default=())

    @property
    def roll_ratio(self) -> float:
        """Stage-1 roll peak over the two-stage roll peak: the reduction by stage 2 [-]."""
        return self.peaks[0].roll / self.peaks[-1].roll

    def peak_change(self, other: ReadingResult) -> float:
        """Largest relative change of the two-stage yaw, pitch and roll peaks from this reading to ``other`` [-].

        Parameters
        ----------
        other : ReadingResult
            The other reading.

        Returns
        -------
        float
            ``max |other / self − 1|`` over the three angles after the last stage.
        """
        change = other.peaks[-1].relative_to(self.peaks[-1])
        return float(max(abs(change.yaw), abs(change.pitch), abs(change.roll)))


def run_readings(readings=None, *, base: Scenario | None = None, step: float = 0.2, rng=None, progress=None) -> tuple:
    """Simulate every reading (each distinct scenario is sampled once).

    Parameters
    ----------
    readings : sequence of Reading, optional
        Default :func:`standard_readings`.
    base : Scenario, optional
        Scenario the readings modify; default :class:`Scenario`.
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    rng : numpy.random.Generator, int, SeedSequence or None
        Sensor-noise source (the same stream for every reading).
    progress : callable, optional
        ``progress(iterable, description)`` wrapping the loop (e.g. a tqdm bar).

    Returns
    -------
    tuple of ReadingResult
    """
    from ...derivations.multistage.published import PRINTED_GAINS

    readings = standard_readings() if readings is None else tuple(readings)
    if not all(isinstance(r, Reading) for r in readings):
        raise TypeError("Expected `readings` to be a sequence of Reading")
    root = montecarlo.root_seed_sequence(rng)  # the same noise stream for every scenario
    data_for = {}
    out = []
    loop = readings if progress is None else progress(readings, "stability: readings")
    for r in loop:
        sc = r.scenario(base)
        if sc not in data_for:
            data_for[sc] = sample(sc, step, rng=root)
        data = data_for[sc]
        res = run_multistage(data, r.stages(sc.gravity, sc.earth_radius))
        i = int(round(PRINTED_GAINS.switch_time / data.step))
        abs_err = np.abs(res.errors)
        t_peak = tuple(tuple(float(data.time[j]) for j in abs_err[s].argmax(axis=0)) for s in range(abs_err.shape[0]))
        out.append(ReadingResult(r, res.peaks(), (float(res.errors[0, i, 0]), float(res.errors[1, i, 0])), t_peak))
    return tuple(out)


class PaperComparison(NamedTuple):
    """What the readings decide against the printed results of section 5.

    Attributes
    ----------
    stage1_pitch_near : tuple of ReadingResult
        Readings whose stage-1 pitch peak is within ``tolerance`` of the printed one.
    above_bound : tuple of ReadingResult
        Readings whose two-stage pitch peak exceeds the printed bound.
    roll_ratio_range : tuple of float
        Smallest and largest :attr:`ReadingResult.roll_ratio` of the consistent
        readings (rotating Earth, the Earth's rate, integral not rescaled).
    earlier_truth : ReadingResult or None
        The reading of the earlier truth model (no Coriolis force), if run.
    tolerance : float
        Relative distance from the printed stage-1 pitch counted as near.
    """

    stage1_pitch_near: tuple
    above_bound: tuple
    roll_ratio_range: tuple
    earlier_truth: ReadingResult | None
    tolerance: float


def compare_with_paper(results, *, tolerance: float = 0.2) -> PaperComparison:
    """Set the readings against the printed stage-1 pitch, two-stage bound and roll reduction.

    Parameters
    ----------
    results : sequence of ReadingResult
        From :func:`run_readings`.
    tolerance : float, keyword-only
        Relative distance from the printed stage-1 pitch peak counted as near [-].

    Returns
    -------
    PaperComparison

    References
    ----------
    Plotnikov (1999), section 5 (:data:`strapdown.derivations.multistage.published.PAPER`).
    """
    from ...derivations.multistage.published import PAPER

    results = tuple(results)
    tolerance = positive(tolerance, "tolerance")
    pitch1, bound = PAPER.stage1_pitch_peak.value, PAPER.two_stage_pitch_bound.value
    near = tuple(r for r in results if abs(r.peaks[0].pitch / pitch1 - 1.0) < tolerance)
    over = tuple(r for r in results if r.peaks[-1].pitch > bound)
    consistent = [r.roll_ratio for r in results if r.reading.truth == "rotating-earth" and r.reading.earth_rate is None and r.reading.switch != "rescale"]
    span = (min(consistent), max(consistent)) if consistent else (float("nan"), float("nan"))
    old = next((r for r in results if r.reading.truth == "no-coriolis"), None)
    return PaperComparison(near, over, span, old, tolerance)


def printed_envelope_at_rocking_start() -> float:
    """The rocking envelope as printed, ``exp(−d(t − 600))`` with no onset, just after rocking starts [-].

    Returns
    -------
    float
        ``E`` at the printed start of rocking: far below any effect (no rocking at all).
    """
    s5 = _section5()
    printed = Scenario(rocking_decay_origin=s5.envelope_origin, rocking_onset=0.0)
    return float(printed.envelope(s5.rest_end + 1e-9))


@dataclass(frozen=True)
class NamedLoop:
    """A linearised stage loop of section 5 with its label.

    Attributes
    ----------
    label : str
        What it is.
    loop : StageLoop
        Its loop gains (K, L).
    """

    label: str
    loop: StageLoop


def section5_loops(gravity: float = 9.81, earth_radius: float = 6.371e6) -> tuple:
    """The loops of the printed gains: stage 1 under both readings, stage 2 before and after the switch.

    Parameters
    ----------
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].

    Returns
    -------
    tuple of NamedLoop
        Stage 1 on (1.10) with c = 1 (K = k/2, L = l/2); stage 1 read with
        (1.4), c = 2; stage 2 before the switch; stage 2 Schuler-tuned
        (k = 0, l = g/R); stage 2 with the printed l = 1.24·10⁻³.
    """
    from ...derivations.multistage.published import PRINTED_GAINS

    k1, l1 = PRINTED_GAINS.stage1
    return (
        NamedLoop("stage 1 (tilt quaternion, c = 1: K = k/2, L = l/2)", StageLoop(k1 / 2, l1 / 2, gravity, earth_radius)),
        NamedLoop("stage 1 read with the (1.4) quaternion, c = 2", StageLoop(k1, l1, gravity, earth_radius)),
        NamedLoop("stage 2 before 600 s", StageLoop(*PRINTED_GAINS.stage2_before, gravity, earth_radius)),
        NamedLoop("stage 2 from 600 s: Schuler k = 0, l = g/R", StageLoop.schuler(gravity, earth_radius)),
        NamedLoop("stage 2 with the printed l = 1.24e-3 s⁻²", StageLoop(*PRINTED_GAINS.stage2_after, gravity, earth_radius)),
    )


def schuler_detuning(gravity: float = 9.81, earth_radius: float = 6.371e6, *, detuning: float = 0.01, damping_gain: float = 1e-3) -> tuple:
    """How the tilt loop answers a horizontal acceleration at and near Schuler tuning, and with the printed gains.

    The acceleration is the printed one of section 5 (20 m/s² for 20 s).  At
    ``k = 0, l = g/R`` (3.11) the loop does not answer it; any other gains do.

    Parameters
    ----------
    gravity : float
        g [m/s²].
    earth_radius : float
        R [m].
    detuning : float, keyword-only
        Relative change of l away from g/R of the second row [-].
    damping_gain : float, keyword-only
        k of the damped third row [1/s].

    Returns
    -------
    tuple of AccelSensitivity
        ``(0, g/R)``; ``(0, (1 + detuning) g/R)``; ``(damping_gain, g/R)``;
        stage 1 and stage 2 before the switch as printed.
    """
    from ...derivations.multistage.published import PRINTED_GAINS

    s5 = _section5()
    schuler = StageLoop.schuler(gravity, earth_radius).l
    detuned = (1.0 + detuning) * gravity / earth_radius
    gains = [(0.0, schuler), (0.0, detuned), (damping_gain, schuler), PRINTED_GAINS.stage1, PRINTED_GAINS.stage2_before]
    out: list[AccelSensitivity] = []
    for k, l in gains:
        out.append(acceleration_sensitivity(StageLoop(k, l, gravity, earth_radius), s5.accel, s5.accel_duration))
    return tuple(out)
