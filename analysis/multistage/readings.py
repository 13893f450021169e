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

import numpy as np

from ..core import montecarlo
from .stages import plotnikov_1999_stages, run_multistage
from .tilt_loop import StageLoop
from .trajectory import Scenario, sample

__all__ = ["Reading", "ReadingResult", "standard_readings", "run_readings", "NamedLoop", "section5_loops"]


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


def run_readings(readings=None, *, base: Scenario | None = None, step: float = 0.2, rng=None, progress=None) -> tuple:
    """Simulate every reading (each distinct scenario is sampled once).

    Parameters
    ----------
    readings : sequence of Reading, optional
        Default :func:`standard_readings`.
    base : Scenario, optional
        Scenario the readings modify; default :class:`Scenario`.
    step : float
        Grid step [s].
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
