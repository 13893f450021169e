"""The identification's own assumptions, tested on the integrator: each gives a verdict that can say no.

:func:`~.identification.identify` recovers the linear and bilinear part of an
integrator exactly when the integrator is time invariant, reads no further
back than the probes, stays in its linear range over the probes, and computes
in the precision the uncertainties assume.  Flight code does not always meet
these conditions; each is tested here, on the code itself, and the verdict is
reported beside the coefficients (:func:`~.assessment.assess`):

:func:`precision`
    the code's noise floor, measured: along short rays ``x (1 + kδ)`` through
    random windows (``δ = 2⁻¹⁸``, nine points) a cubic fit leaves only the
    round-off, whose size relative to the outputs is ν.  Float64 code gives
    ν ≈ 10⁻¹⁶, float32 code about 10⁻⁸; the probes' uncertainties, and with
    them the stated uncertainty of every coefficient, follow from it
    (:class:`~.probes.NoiseFloor`).
:func:`linearity_range`
    probes at amplitudes from :data:`SWEEP_TOP` halving down to 10⁻⁶: the odd
    part ``(F(σx) − F(−σx))/2σ`` and the even part
    ``(F(σx) + F(−σx) − 2F(0))/2σ²`` of a smooth integrator change by a power
    of σ from one amplitude to the next, by a factor 4 (or 16) per halving,
    until round-off; a saturation, a clip, a dead band or a wrap breaks that
    law.  The range is the largest amplitude below which the law holds at
    every amplitude; probes above it give wrong coefficients.
:func:`memory_length`
    random samples added one at a time before the probed window, from K + 1
    samples back to the longest probed, then all samples up to twice as far,
    each window a record of its own (a record starts from rest, so nothing can
    leak in from before it): the sample at ``1 − m`` changes the output only if
    the integrator reads m samples back; a sample it does not read leaves the
    output bit for bit as it was, whatever the code's precision.  The memory needed is the farthest m that changes it; an
    integrator that still depends on the farthest sample, or on those beyond,
    has a memory longer than the longest probed (a filter, an accumulator that
    is never reset, or just a longer memory: raise the limit).
:class:`TimeInvarianceRun`
    the same blocks (each after enough zeros to clear twice the longest memory
    probed) in one record, again in reversed order with one, two or three extra
    zero steps between them (another position, another step parity), and the
    first record of the run again as its last call (after every other call,
    and after every reset of a stateful object): a time-invariant integrator
    gives the same outputs every time.

Public API
----------
:data:`SWEEP_TOP`, :data:`SWEEP_LEVELS`, :data:`LONGEST_MEMORY`, :data:`PRECISION_THRESHOLD`,
:class:`Precision`, :class:`Linearity`, :class:`Memory`, :class:`TimeInvariance`,
:func:`precision`, :func:`linearity_range`, :func:`memory_length`, :class:`TimeInvarianceRun`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.validation import as_int, positive
from .defaults import LONGEST_MEMORY
from .interface import Integrator
from .probes import FLOAT64_NOISE, NoiseFloor, Prober

__all__ = [
    "SWEEP_TOP",
    "SWEEP_LEVELS",
    "LONGEST_MEMORY",
    "PRECISION_THRESHOLD",
    "Precision",
    "Linearity",
    "Memory",
    "TimeInvariance",
    "precision",
    "linearity_range",
    "memory_length",
    "TimeInvarianceRun",
]

#: Largest amplitude of the linearity sweep (largest sample norm) [rad, m/s].
SWEEP_TOP = 0.32
#: Amplitudes of the sweep: SWEEP_TOP / 2^k, k = 0 … SWEEP_LEVELS − 1 (down to 2.4·10⁻⁶).
SWEEP_LEVELS = 18
#: Random windows of the sweep and of the precision rays.
_PATTERNS = 2
#: Largest ratio of successive differences of the sweep still taken as a power law (16 is ε⁴).
_LAW_RATIO = 64.0
#: Noise relative to the outputs above which the code is not taken as float64 [dimensionless].
PRECISION_THRESHOLD = 1e-13
#: Points per precision ray, and their spacing relative to the window.
_RAY_POINTS, _RAY_STEP = 9, 2.0**-18
#: The measured noise is multiplied by this to bound the round-off of one output.
_NOISE_FACTOR = 8.0
#: An output differs when it departs by more than this many times its noise floor.
_RESOLVED = 10.0


def _random_window(rng, patterns: int, width: int) -> np.ndarray:
    """Random windows (patterns, width, 3) in which every sample's largest component is 1 (as large as a probe along one axis).

    Every sample reaches the amplitude: an integrator that reads only some of the window still sees it.
    """
    base = rng.standard_normal((patterns, width, 3))
    return base / np.abs(base).max(axis=-1, keepdims=True)


# --------------------------------------------------------------------------- precision
@dataclass(frozen=True)
class Precision:
    """The code's measured noise floor.

    Attributes
    ----------
    measured : float
        Root-mean-square round-off along the rays, relative to the size of the
        outputs and inputs [dimensionless].
    noise : NoiseFloor
        The floor the identification uses: :data:`~.probes.FLOAT64_NOISE`, or
        eight times the measured noise where that is larger.
    threshold : float
        :data:`PRECISION_THRESHOLD`.
    decided : bool
        False when the integrator is not time invariant: the rays' points come
        from different positions, and their scatter may be the integrator's drift.
    """

    measured: float
    noise: NoiseFloor
    threshold: float = PRECISION_THRESHOLD
    decided: bool = True

    @property
    def holds(self) -> bool:
        """The code computes in double precision (its noise at most :attr:`threshold`)."""
        return self.decided and self.measured <= self.threshold

    def summary(self) -> str:
        """One line.

        Returns
        -------
        str
        """
        eps = float(np.finfo(float).eps)
        if not self.decided:
            return f"not decided: the integrator is not time invariant (the rays' scatter, {self.measured:.1e} relative, may be its drift)"
        if self.holds:
            return f"double precision: noise {self.measured:.1e} relative to the outputs (float64 round-off {eps:.1e})"
        return (
            f"noise {self.measured:.1e} relative to the outputs, {self.measured / eps:.1e} times float64 round-off "
            f"(single precision or coarser): every uncertainty is set from it"
        )

    def as_dict(self) -> dict:
        """JSON-able verdict.

        Returns
        -------
        dict
        """
        return {"holds": self.holds, "decided": self.decided, "measured_relative_noise": self.measured, "noise_floor": self.noise.relative, "threshold": self.threshold, "summary": self.summary()}


def precision(integrator: Integrator, samples_per_step, *, reach: int, amplitude: float, guard: int | None = None, rng=None) -> Precision:
    """Measure the code's round-off along short rays through random windows (module docstring).

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    reach : int
        Samples before the step in the random windows.
    amplitude : float
        Largest component of the windows [rad, m/s]; a second set at an eighth of it.
    guard : int, optional
        Zeros before each window clear this many samples of memory (default ``reach``).
    rng : numpy.random.Generator, int or None
        Random windows.

    Returns
    -------
    Precision
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    amp = positive(amplitude, "amplitude")
    rng = np.random.default_rng(rng)
    prober = Prober(integrator, n, max(reach, guard or 0))
    width = reach + n
    first = prober.row(1 - reach)
    scales = (amp, amp / 8)
    k = np.arange(_RAY_POINTS)
    gyro = prober.zeros(len(scales) * _PATTERNS * _RAY_POINTS)
    accel = np.zeros_like(gyro) if integrator.velocity else None
    for target in (gyro, accel) if integrator.velocity else (gyro,):
        base = _random_window(rng, _PATTERNS, width)
        for a, scale in enumerate(scales):
            for b in range(_PATTERNS):
                rows = slice((a * _PATTERNS + b) * _RAY_POINTS, (a * _PATTERNS + b + 1) * _RAY_POINTS)
                target[rows, first : first + width] = scale * base[b][None] * (1.0 + _RAY_STEP * k)[:, None, None]
    rot, vel = prober.last_steps(gyro, accel)
    v = np.vander(k.astype(float), 4)
    project = np.eye(_RAY_POINTS) - v @ np.linalg.pinv(v)
    worst = 0.0
    attitude = 1.0 if integrator.output != "rotation_vector" else 0.0
    for out in (rot, vel) if vel is not None else (rot,):
        rays = out.reshape(len(scales), _PATTERNS, _RAY_POINTS, 3)
        resid = np.einsum("pk,abkw->abpw", project, rays)
        dof = (_RAY_POINTS - 4) * 3
        rms = np.sqrt((resid**2).sum(axis=(2, 3)) / dof)
        size = np.abs(rays).max(axis=(2, 3)) + np.array(scales)[:, None] + attitude
        worst = max(worst, float((rms / size).max()))
    floor = NoiseFloor(max(FLOAT64_NOISE, _NOISE_FACTOR * worst), attitude=bool(attitude))
    return Precision(worst, floor)


# --------------------------------------------------------------------------- linearity
@dataclass(frozen=True)
class Linearity:
    """Where the integrator is smooth enough for the probes: its linearity range.

    Attributes
    ----------
    amplitudes : tuple of float
        The sweep's amplitudes σ_k, largest first [rad, m/s].
    departures : tuple of float
        At each σ_k (but the last two): how far the change from σ_k to σ_(k+1)
        exceeds the power law set by the smaller amplitudes, relative to the
        noise floor (≤ 1: the law holds).
    range : float
        The largest σ_k below which the law holds at every amplitude [rad, m/s]
        (the smallest amplitude when it never holds).
    probe_amplitude : float
        ε_0, the largest probe amplitude used [rad, m/s].
    chosen : bool
        ε_0 was chosen from the range (no amplitude was given).
    """

    amplitudes: tuple
    departures: tuple
    range: float
    probe_amplitude: float
    chosen: bool

    @property
    def saturates(self) -> bool:
        """The law breaks somewhere in the sweep: a saturation, clip, dead band or wrap."""
        return self.range < self.amplitudes[0]

    @property
    def holds(self) -> bool:
        """The probes lie in the linearity range."""
        return self.probe_amplitude <= self.range * (1 + 1e-12)

    def summary(self) -> str:
        """One line.

        Returns
        -------
        str
        """
        where = f"saturation or a non-smooth response above {self.range:.3g} rad" if self.saturates else f"smooth up to {self.amplitudes[0]:g} rad, the largest amplitude tried"
        if self.holds:
            how = "chosen within it" if self.chosen else "given"
            return f"{where}; probes at {self.probe_amplitude:.3g} rad ({how}) lie within it"
        return f"{where}; the probes at {self.probe_amplitude:.3g} rad do NOT (lower --probe-amplitude-rad to {self.range / 2:.3g} or less)"

    def as_dict(self) -> dict:
        """JSON-able verdict.

        Returns
        -------
        dict
        """
        return {
            "holds": self.holds,
            "range": self.range,
            "saturates": self.saturates,
            "probe_amplitude": self.probe_amplitude,
            "probe_amplitude_chosen": self.chosen,
            "amplitudes": list(self.amplitudes),
            "departures": list(self.departures),
            "summary": self.summary(),
        }


def linearity_range(
    integrator: Integrator, samples_per_step, *, reach: int, noise: NoiseFloor, amplitude: float | None = None, default: float = 0.02, guard: int | None = None, rng=None
) -> Linearity:
    """The sweep of the module docstring, and the probe amplitude it allows.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    reach : int
        Samples before the step in the random windows.
    noise : NoiseFloor
        The code's noise floor (:func:`precision`).
    amplitude : float, optional
        ε_0 given by the user [rad, m/s]; None: the default, lowered to half
        the range where the range is smaller.
    default : float
        The default ε_0 [rad, m/s].
    guard : int, optional
        Zeros before each window clear this many samples of memory (default ``reach``).
    rng : numpy.random.Generator, int or None
        Random windows.

    Returns
    -------
    Linearity
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    rng = np.random.default_rng(rng)
    prober = Prober(integrator, n, max(reach, guard or 0))
    width = reach + n
    first = prober.row(1 - reach)
    sig = SWEEP_TOP / 2.0 ** np.arange(SWEEP_LEVELS)
    gyro = prober.zeros(1 + SWEEP_LEVELS * _PATTERNS * 2)
    accel = np.zeros_like(gyro) if integrator.velocity else None
    for target in (gyro, accel) if integrator.velocity else (gyro,):
        base = _random_window(rng, _PATTERNS, width)
        for lv, s in enumerate(sig):
            for b in range(_PATTERNS):
                row = 1 + (lv * _PATTERNS + b) * 2
                target[row, first : first + width] = s * base[b]
                target[row + 1, first : first + width] = -s * base[b]
    rot, vel = prober.last_steps(gyro, accel)
    in_scale = np.concatenate([[0.0], np.repeat(sig, _PATTERNS * 2)])
    departures = np.zeros(SWEEP_LEVELS - 2)
    for out in (rot, vel) if vel is not None else (rot,):
        fl = noise.floor(out, in_scale)
        f0, fl0 = out[0], fl[0]
        pp = out[1:].reshape(SWEEP_LEVELS, _PATTERNS, 2, 3)
        fp = fl[1:].reshape(SWEEP_LEVELS, _PATTERNS, 2)
        s = sig[:, None, None]
        odd = (pp[:, :, 0] - pp[:, :, 1]) / (2 * s)
        odd_fl = (fp[:, :, 0] + fp[:, :, 1]) / (2 * sig[:, None])
        even = (pp[:, :, 0] + pp[:, :, 1] - 2 * f0) / (2 * s**2)
        even_fl = (fp[:, :, 0] + fp[:, :, 1] + 2 * fl0) / (2 * sig[:, None] ** 2)
        for part, part_fl in ((odd, odd_fl), (even, even_fl)):
            d = np.linalg.norm(part[:-1] - part[1:], axis=-1)  # (levels − 1, patterns)
            dfl = _RESOLVED * (part_fl[:-1] + part_fl[1:])
            allowed = _LAW_RATIO * d[1:] + dfl[:-1] + _LAW_RATIO * dfl[1:]
            departures = np.maximum(departures, (d[:-1] / allowed).max(axis=-1))
    bad = np.flatnonzero(departures > 1.0)
    top = sig[bad[-1] + 1] if len(bad) else sig[0]
    if amplitude is None:
        eps0, chosen = min(default, top / 2), True
    else:
        eps0, chosen = positive(amplitude, "amplitude"), False
    return Linearity(tuple(float(x) for x in sig), tuple(float(x) for x in departures), float(top), float(eps0), chosen)


# --------------------------------------------------------------------------- memory
@dataclass(frozen=True)
class Memory:
    """How far back the integrator reads.

    Attributes
    ----------
    start : int
        K asked for (``max_previous``).
    longest : int
        The farthest sample probed, ``longest`` samples before the step.
    effects : tuple of float
        For m = start + 1 … longest: the largest change of the output when the
        sample ``1 − m`` is added, relative to its noise floor.
    needed : int or None
        The farthest m whose sample changes the output (at least ``start``);
        None: the farthest probed still does, the memory is longer.
    used : int
        K the identification used.
    decided : bool
        False when the integrator is not time invariant (the scan compares
        outputs at different positions, and cannot then tell memory from drift).
    """

    start: int
    longest: int
    effects: tuple
    needed: int | None
    used: int
    decided: bool = True

    @property
    def holds(self) -> bool:
        """The identification probed every sample the integrator reads."""
        return self.decided and self.needed is not None and self.needed <= self.used

    def summary(self) -> str:
        """One line.

        Returns
        -------
        str
        """
        if not self.decided:
            return "not decided: the integrator is not time invariant"
        if self.needed is None:
            return f"longer than {self.longest} samples (the farthest sample probed still changes the output): no finite K captures it"
        raised = f", raised from --max-previous {self.start}" if self.used > self.start else ""
        if self.holds:
            return f"reads {self.needed} sample(s) back (probed to {self.longest}); K = {self.used} used{raised}"
        return f"reads {self.needed} samples back (probed to {self.longest}) but K = {self.used} was used: raise --max-previous-limit"

    def as_dict(self) -> dict:
        """JSON-able verdict.

        Returns
        -------
        dict
        """
        return {
            "holds": self.holds,
            "decided": self.decided,
            "needed": self.needed,
            "used": self.used,
            "start": self.start,
            "longest_probed": self.longest,
            "effects": list(self.effects),
            "summary": self.summary(),
        }


def memory_length(integrator: Integrator, samples_per_step, *, start: int, longest: int = LONGEST_MEMORY, amplitude: float, noise: NoiseFloor, rng=None) -> Memory:
    """The scan of the module docstring: the farthest sample that changes the output.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    start : int
        K asked for: the scan starts one sample beyond it.
    longest : int
        The farthest sample probed (samples before the step).
    amplitude : float
        Largest sample norm of the random samples [rad, m/s] (within the linearity range).
    noise : NoiseFloor
        The code's noise floor.
    rng : numpy.random.Generator, int or None
        Random samples.

    Returns
    -------
    Memory
        With ``used`` = ``start`` (the caller sets what it used).
    """
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    k = as_int(start, "start", minimum=0)
    longest = max(as_int(longest, "longest", minimum=0), k)
    rng = np.random.default_rng(rng)
    if longest == k:
        return Memory(k, longest, (), k, k)
    far = 2 * longest  # the last window fills every sample up to twice the longest
    count = longest - k + 2  # the near window alone, one more earlier sample each up to `longest`, then all up to `far`
    bases = [amplitude * _random_window(rng, _PATTERNS, far + n) for _ in range(2 if integrator.velocity else 1)]  # columns: 1 − far … N
    rots, vels = [], []
    prober = Prober(integrator, n, 0)
    for b in range(_PATTERNS):
        for c in range(count):
            m = k + c if c < count - 1 else far  # samples 1 − m … N present
            # each window is a record of its own, which starts from rest: nothing before it can leak in
            length = (-(-m // n) + 1) * n
            records = [np.zeros((length, 3)) for _ in bases]
            for rec, base in zip(records, bases):
                rec[length - m - n :] = base[b, far - m : far + n]
            rot, vel = prober.record(records[0], records[1] if integrator.velocity else None)
            rots.append(rot[-1])
            if vel is not None:
                vels.append(vel[-1])
    rot, vel = np.array(rots), (np.array(vels) if vels else None)
    effects = np.zeros(count - 1)
    for out in (rot, vel) if vel is not None else (rot,):
        fl = noise.floor(out, amplitude).reshape(_PATTERNS, count)
        o = out.reshape(_PATTERNS, count, 3)
        change = np.linalg.norm(o[:, 1:] - o[:, :-1], axis=-1) / (fl[:, 1:] + fl[:, :-1])
        effects = np.maximum(effects, change.max(axis=0))
    reads = np.flatnonzero(effects > _RESOLVED)
    if len(reads) and reads[-1] >= count - 3:  # the farthest single sample, or anything beyond `longest`
        needed = None
    else:
        needed = k + 1 + int(reads[-1]) if len(reads) else k
    return Memory(k, longest, tuple(float(e) for e in effects[:-1]), needed, k)


# --------------------------------------------------------------------------- time invariance
@dataclass(frozen=True)
class TimeInvariance:
    """Whether the same input gives the same output wherever and whenever it comes.

    Attributes
    ----------
    repeated : float
        Largest difference between two copies of a block in one record, over its noise floor.
    shifted : float
        Largest difference between a block in the first record and in the record that
        reorders the blocks and shifts them by one to three steps, over its noise floor.
    calls : float
        Largest difference between the first call of the run and the same record
        given as its last call, over its noise floor.
    largest : float
        Largest absolute difference of any of them [rad or m/s].
    """

    repeated: float
    shifted: float
    calls: float
    largest: float

    @property
    def holds(self) -> bool:
        """Every difference is within ten times its float64 round-off."""
        return max(self.repeated, self.shifted, self.calls) <= _RESOLVED

    def summary(self) -> str:
        """One line.

        Returns
        -------
        str
        """
        if self.holds:
            return "the same input gave the same output repeated, reordered, shifted by one to three steps, and as the run's last call"
        where = []
        if self.calls > _RESOLVED:
            where.append("the first call and the last call of the run (state kept between calls or across a reset?)")
        if self.shifted > _RESOLVED:
            where.append("shifted by one to three steps or reordered in a record (a step counter, a coefficient that alternates?)")
        if self.repeated > _RESOLVED:
            where.append("repeated within a record")
        return (
            f"NO: outputs differ by up to {self.largest:.3g} between " + "; ".join(where) + ": the coefficients describe no single integrator "
            "(or its memory is longer than twice the longest probed)"
        )

    def as_dict(self) -> dict:
        """JSON-able verdict.

        Returns
        -------
        dict
        """
        return {
            "holds": self.holds,
            "largest_difference": self.largest,
            "repeated_over_floor": self.repeated,
            "shifted_over_floor": self.shifted,
            "calls_over_floor": self.calls,
            "summary": self.summary(),
        }


class TimeInvarianceRun:
    """The time-invariance test across a whole run: :meth:`first` before any other call, :meth:`last` after all.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples_per_step : int
        N.
    reach : int
        Zeros before each block clear this many samples of memory.
    amplitude : float
        Largest component of the blocks [rad, m/s].
    rng : numpy.random.Generator, int or None
        Random blocks.

    Notes
    -----
    The blocks compare *identical* inputs, so the floor is float64's
    round-off whatever the code's precision: round-off is deterministic, and a
    float32 integrator gives the same bits for the same input.  (A code that
    sums in an order that changes from call to call, multithreaded, differs by
    float64 round-off at most.)
    """

    _BLOCKS = 4

    def __init__(self, integrator: Integrator, samples_per_step, *, reach: int, amplitude: float, rng=None):
        self.n = as_int(samples_per_step, "samples_per_step", minimum=1)
        self.prober = Prober(integrator, self.n, reach)
        rng = np.random.default_rng(rng)
        width = reach + self.n
        first = self.prober.row(1 - reach)
        self.velocity = integrator.velocity
        self.gyro = self.prober.zeros(self._BLOCKS)
        self.gyro[:, first : first + width] = amplitude * _random_window(rng, self._BLOCKS, width)
        self.accel = None
        if self.velocity:
            self.accel = self.prober.zeros(self._BLOCKS)
            self.accel[:, first : first + width] = amplitude * _random_window(rng, self._BLOCKS, width)
        self.amplitude = amplitude
        self.noise = NoiseFloor(attitude=integrator.output != "rotation_vector")
        self._first = self._shifted = self._last = None

    def _outputs(self, rot, vel):
        return rot if vel is None else np.concatenate([rot, vel], axis=-1)

    def first(self) -> None:
        """The first record: the blocks in order (make it the first call of the run)."""
        self._first = self._outputs(*self.prober.last_steps(self.gyro, self.accel))

    def shifted(self) -> None:
        """The blocks reversed, each twice, with 1, 2 or 3 extra zero steps before each."""
        n, length = self.n, self.prober.length
        order = [b for b in reversed(range(self._BLOCKS)) for _ in range(2)]
        gaps = [1 + (i % 3) for i in range(len(order))]
        total = sum(g * n + length for g in gaps)
        g = np.zeros((total, 3))
        a = np.zeros((total, 3)) if self.velocity else None
        ends, pos = [], 0
        for b, gap in zip(order, gaps):
            pos += gap * n
            g[pos : pos + length] = self.gyro[b]
            if a is not None:
                a[pos : pos + length] = self.accel[b]
            pos += length
            ends.append(pos // n - 1)
        rot, vel = self.prober.record(g, a)
        out = self._outputs(rot, vel)[ends]
        self._shifted = (np.array(order), out)

    def last(self) -> None:
        """The first record again (make it the last call of the run)."""
        self._last = self._outputs(*self.prober.last_steps(self.gyro, self.accel))

    def verdict(self) -> TimeInvariance:
        """The verdict of the three records.

        Returns
        -------
        TimeInvariance

        Raises
        ------
        RuntimeError
            If a record was not run.
        """
        if self._first is None or self._shifted is None or self._last is None:
            raise RuntimeError("Expected first(), shifted() and last() before verdict()")
        ref = self._first
        floor = np.maximum(self.noise.floor(ref[:, :3], self.amplitude), self.noise.floor(ref[:, 3:], self.amplitude) if ref.shape[1] > 3 else 0.0)
        order, out = self._shifted
        pairs = out.reshape(self._BLOCKS, 2, -1)
        blocks = order.reshape(self._BLOCKS, 2)[:, 0]
        rep = np.abs(pairs[:, 0] - pairs[:, 1]).max(axis=-1)
        shift = np.abs(pairs - ref[blocks][:, None]).max(axis=(1, 2))
        calls = np.abs(self._last - ref).max(axis=-1)
        f = 2 * floor
        largest = float(max(rep.max(), shift.max(), calls.max()))
        return TimeInvariance(float((rep / f[blocks]).max()), float((shift / f[blocks]).max()), float((calls / f).max()), largest)
