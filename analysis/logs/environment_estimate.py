"""The vibration environment estimated from a recorded log, and its environment file.

What the estimate is
--------------------
The six channels of a log, the angle and velocity increments of the three body
axes, are the increments of the body rate ω and the specific force a over each
sample interval.  :func:`estimate_environment` finds the deterministic lines
in them (rotor and engine harmonics, :mod:`strapdown.analysis.logs.lines`,
each confirmed by a test that a random band fails), removes them, and takes
the Welch cross-spectral density matrix of what is left
(:mod:`strapdown.analysis.logs.cross_spectra`).  Both are then turned from
increments into the continuous rate and specific force whose increments they
are: a sinusoid ``Re(A e^{iωt})`` has the increments
``Re(A (1 − e^{−iωh})/(iω) e^{iωt_n})`` (t_n the end of each interval), so
a line's amplitude is ``A = Z iω/(1 − e^{−iωh})`` and a density is divided by
``|1 − e^{−iωh}|²/ω² = (2 sin(ωh/2)/ω)²``.  The result is an
:class:`~strapdown.analysis.vibration.environment.Environment` of
``[[vibration_line]]`` entries and one ``[[spectrum]]`` over all six channels.

The motion as the logged samples see it.  Whatever filtered the signal before
it was logged (analog anti-aliasing filters, the IMU's digital low-pass
filters, decimation) is already in the samples, so the environment carries no
sensor of its own: its ``[gyro]`` and ``[accelerometer]`` filters are
``"none"`` and its decimation is 1, and a designer who feeds the file to
``environment-drift``, ``design-coning``, ``design-sculling`` or
``environment-rates`` applies none of those filters a second time.  (To
study another filter, edit those tables; the lines and spectrum then stand for
the motion as the *logged* samples saw it, not the motion of the airframe.)

The log's bandwidth.  Nothing above the Nyquist frequency ``1/(2h)`` can be
seen: vibration there reaches the log only through what the filters ahead of
it let through, folded (aliased) onto ``|f − k/h|``, and the estimate
attributes it to that alias.  The environment stops at the Nyquist frequency;
motion beyond it is missing from the estimate, and so is any drift it causes
at a faster sample rate.

Confidence intervals: each auto-spectrum value has the χ² interval of its
equivalent degrees of freedom, each cross-spectrum's real and imaginary parts
their standard deviations, and each line's amplitude the standard error from
the scatter of its blocks.

Public API
----------
.. autosummary::

   EstimatedLine
   EnvironmentEstimate
   estimate_environment
   environment_file_text
   write_environment
   DEFAULT_RESOLUTION
   MAX_ROWS
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core import budget
from ..core.atomic import replaced_atomically
from ..core.units import DEG_PER_RAD
from ..core.validation import as_int, in_open_interval, positive
from ..vibration.environment import CHANNELS, ENVIRONMENT_LIMITS, Environment, Spectrum, VibrationLine, load_environment
from .cross_spectra import CrossSpectra, welch_cross_spectra
from .lines import LineSearch, find_lines, line_signal
from .segments import as_segments, sample_interval

__all__ = ["EstimatedLine", "EnvironmentEstimate", "estimate_environment", "environment_file_text", "write_environment", "DEFAULT_RESOLUTION", "MAX_ROWS"]

#: Default bin width of the Welch estimate [Hz] (coarser for a log too short for 16 segments).
DEFAULT_RESOLUTION = 0.5
#: Default largest number of rows of the spectrum table [count]: finer estimates are averaged over adjacent bins.
MAX_ROWS = 1500


@dataclass(frozen=True)
class EstimatedLine:
    """A line of the log, as the continuous motion whose increments it is.

    Attributes
    ----------
    frequency : float
        f [Hz].
    amplitude : ndarray of complex, shape (6,)
        ``(ωx, ωy, ωz)`` [rad/s] and ``(ax, ay, az)`` [m/s²]: channel c is
        ``Re(amplitude[c] e^{i 2π f t})``; the phases are relative to the
        channel of :attr:`reference` (phase 0).
    sigma : ndarray, shape (6,)
        Standard error of each complex amplitude (``√(E|Â − A|²)``), same units.
    significant : ndarray of bool, shape (6,)
        Channels in which the line passed the test.
    reference : int
        The channel whose phase is zero (the largest significant rate channel,
        or specific-force channel if no rate channel is significant).
    """

    frequency: float
    amplitude: np.ndarray
    sigma: np.ndarray
    significant: np.ndarray
    reference: int

    def interval(self, level: float = 0.95) -> tuple:
        """``(low, high)`` of each channel's amplitude ``|A_c|`` at ``level`` (normal parts), shape (6,) each.

        Parameters
        ----------
        level : float
            Coverage, in (0, 1).

        Returns
        -------
        tuple of ndarray
        """
        from scipy.stats import norm

        z = float(norm.isf((1.0 - in_open_interval(level, "level", 0.0, 1.0)) / 2.0))
        half = z * self.sigma / math.sqrt(2.0)
        mag = np.abs(self.amplitude)
        return np.maximum(mag - half, 0.0), mag + half


@dataclass(frozen=True)
class EnvironmentEstimate:
    """The vibration environment of a log (module docstring).

    Attributes
    ----------
    environment : Environment
        Lines and one spectrum, sensors ``"none"``: what the environment file holds.
    lines : tuple of EstimatedLine
        The lines, with their uncertainties.
    search : LineSearch
        How the lines were searched (candidates, blocks, threshold).
    frequency : ndarray, shape (K,)
        The spectrum's table frequencies [Hz].
    density : ndarray of complex, shape (K, 6, 6)
        Its rate and specific-force cross-spectral densities (lines removed)
        [(rad/s)²/Hz, (rad/s)(m/s²)/Hz, (m/s²)²/Hz].
    dof : float
        Equivalent degrees of freedom of each auto-spectrum value of the table.
    quadrature_sigma : ndarray, shape (K, 6, 6)
        Standard deviation of the imaginary part of each table entry (the
        part that cones and sculls).
    sample_interval : float
        h [s].
    duration : float
        Time covered by the log's segments [s].
    segments : int
        Gap-free segments [count].
    resolution : float
        Bin width of the Welch estimate [Hz] (the table averages ``merged`` bins).
    merged : int
        Welch bins averaged into one table row [count].
    welch_segments : int
        Welch segments averaged [count].
    """

    environment: Environment
    lines: tuple
    search: LineSearch
    frequency: np.ndarray
    density: np.ndarray
    dof: float
    quadrature_sigma: np.ndarray
    sample_interval: float
    duration: float
    segments: int
    resolution: float
    merged: int
    welch_segments: int

    @property
    def nyquist(self) -> float:
        """Nyquist frequency ``1/(2h)`` [Hz]: the highest frequency the log can show."""
        return 0.5 / self.sample_interval

    def auto_factors(self, level: float = 0.95) -> tuple:
        """Multipliers ``(lo, hi)`` of an auto-spectrum value of the table giving its interval of coverage ``level``.

        Parameters
        ----------
        level : float
            Coverage, in (0, 1).

        Returns
        -------
        tuple of float
        """
        from scipy.stats import chi2

        beta = 1.0 - in_open_interval(level, "level", 0.0, 1.0)
        return float(self.dof / chi2.ppf(1.0 - beta / 2.0, self.dof)), float(self.dof / chi2.ppf(beta / 2.0, self.dof))

    def band_rms(self) -> np.ndarray:
        """Root mean square of each channel over the table (lines removed), shape (6,) [rad/s, m/s²]."""
        from scipy.integrate import trapezoid

        auto = np.real(np.diagonal(self.density, axis1=1, axis2=2))
        return np.sqrt(np.maximum(trapezoid(auto, self.frequency, axis=0), 0.0))


def _increment_response(freq: np.ndarray, h: float) -> np.ndarray:
    """``(1 − e^{−iωh})/(iω)``: the increments over h of ``e^{iωt}``, per unit, at the end of the interval."""
    w = 2.0 * math.pi * np.asarray(freq, dtype=float)
    return (1.0 - np.exp(-1j * w * h)) / (1j * w)


def _bin_correlations(window: np.ndarray, count: int) -> np.ndarray:
    """Correlation of the Welch power estimates of bins 1 … count − 1 apart (white noise), ``|Σ w² e^{−2πi jn/N}|² / (Σ w²)²``."""
    w2 = window * window
    n = np.arange(w2.size)
    return np.array([abs(np.sum(w2 * np.exp(-2j * math.pi * j * n / w2.size))) ** 2 for j in range(1, count)]) / float(w2.sum()) ** 2


def _reference(amplitude: np.ndarray, significant: np.ndarray) -> int:
    rate = [c for c in range(3) if significant[c]]
    pool = rate or [c for c in range(3, 6) if significant[c]] or list(range(6))
    return max(pool, key=lambda c: abs(amplitude[c]))


def estimate_environment(segments, *, resolution: float | None = None, min_frequency: float | None = None, false_alarm: float = 1e-3, max_rows: int = MAX_ROWS,
                         name: str = "estimated from a log", limits: budget.Limits | None = None, progress: bool = False) -> EnvironmentEstimate:  # fmt: skip
    """The vibration environment of a log: lines with amplitudes and relative phases, and the cross-spectra of the rest (module docstring).

    Parameters
    ----------
    segments : ImuLog or sequence of ImuLog
        The gap-free segments of the log (one sample interval).
    resolution : float, optional, keyword-only
        Bin width of the Welch estimate [Hz] (default :data:`DEFAULT_RESOLUTION`,
        coarser if the longest segment holds fewer than 16 segments at it).
    min_frequency : float, optional, keyword-only
        Lowest frequency of the spectrum table and of the line search [Hz]
        (default: two bins; the slow motion of a flight below it is not vibration).
    false_alarm : float, keyword-only
        Probability that pure band noise yields a line, in (0, 1).
    max_rows : int, keyword-only
        Largest number of rows of the spectrum table [count]; adjacent bins are
        averaged to keep within it (and within the environment file's limits).
    name : str, keyword-only
        The environment's name.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.
    progress : bool, keyword-only
        Show progress on stderr.

    Returns
    -------
    EnvironmentEstimate

    Raises
    ------
    TypeError
        If ``segments`` holds something else than ImuLog.
    ValueError
        A resolution finer than the longest segment allows, a minimum frequency
        at or above the Nyquist frequency, or work beyond ``limits``.

    References
    ----------
    Welch (1967); Thomson (1982), sec. XIII; Bendat & Piersol (2010), ch. 9 and 11.
    """
    segs = as_segments(segments)
    samples = float(sum(s.n_samples for s in segs))
    budget.check(budget.arrays(samples * 6.0, what=f"`segments` = {samples:.3g} samples", copies=3.0), limits)
    h = sample_interval(segs)
    longest = max(s.n_samples for s in segs)
    if resolution is None:
        length = min(int(round(1.0 / (DEFAULT_RESOLUTION * h))), max(8, longest // 16))
    else:
        length = int(round(1.0 / (positive(resolution, "resolution") * h)))
        if length > longest:
            raise ValueError(f"Expected `resolution` of at least 1/(longest segment) = {1.0 / (longest * h):.4g} Hz, got {resolution:g} Hz")
    if length < 8:
        raise ValueError(f"Expected `segments` of at least 8 samples at the resolution asked, got a bin width of {1.0 / (length * h):.4g} Hz")
    rows = as_int(max_rows, "max_rows", minimum=2)
    nyquist = 0.5 / h
    res = 1.0 / (length * h)
    f_lo = 2.0 * res if min_frequency is None else positive(min_frequency, "min_frequency")
    if f_lo >= nyquist - res:
        raise ValueError(f"Expected `min_frequency` below the Nyquist frequency {nyquist:g} Hz less one bin, got {f_lo:g} Hz")
    x = [np.concatenate([s.dtheta, s.dv], axis=1) for s in segs]
    t = [s.time for s in segs]
    spectra = welch_cross_spectra(x, h, length, limits=limits, progress=progress)
    search = find_lines(x, t, spectra, false_alarm=false_alarm, min_frequency=f_lo, max_frequency=nyquist - res)
    found = search.lines
    if found:

        def remove(index, first, count):
            return line_signal(found, t[index][first : first + count])

        spectra = welch_cross_spectra(x, h, length, subtract=remove, limits=limits, progress=progress)
    del x
    return _assemble(segs, spectra, search, h, f_lo, rows, name)


def _assemble(segs, spectra: CrossSpectra, search: LineSearch, h: float, f_lo: float, rows: int, name: str) -> EnvironmentEstimate:
    from scipy.signal import get_window

    f = spectra.frequency
    keep = np.nonzero((f >= f_lo * (1.0 - 1e-12)) & (f < 0.5 / h * (1.0 - 1e-9)))[0]
    g = spectra.density[keep] / (np.abs(_increment_response(f[keep], h)) ** 2)[:, None, None]
    freq = f[keep]
    merged = max(1, math.ceil(keep.size / rows))
    dof = spectra.dof
    if merged > 1:
        k = keep.size // merged
        freq = freq[: k * merged].reshape(k, merged).mean(axis=1)
        g = g[: k * merged].reshape(k, merged, 6, 6).mean(axis=1)
        rho = _bin_correlations(get_window("hann", spectra.segment_length), merged)
        dof = dof * merged / (1.0 + 2.0 * float(np.sum((1.0 - np.arange(1, merged) / merged) * rho)))
    g = 0.5 * (g + np.conj(np.swapaxes(g, 1, 2)))
    auto = np.real(np.diagonal(g, axis1=1, axis2=2))
    prod = auto[:, :, None] * auto[:, None, :]
    q_sigma = np.sqrt(np.maximum(prod + np.imag(g) ** 2 - np.real(g) ** 2, 0.0) / dof)
    lines = []
    vib = []
    for ln in search.lines:
        scale = 1.0 / _increment_response(np.array([ln.frequency]), h)[0]
        amp = ln.amplitude * scale
        ref = _reference(amp, ln.significant)
        amp = amp * np.exp(-1j * np.angle(amp[ref]))
        lines.append(EstimatedLine(ln.frequency, amp, ln.sigma * abs(scale), ln.significant, ref))
        vib.append(VibrationLine(ln.frequency, amp, f"line {ln.frequency:.6g} Hz"))
    spectrum = Spectrum(freq, g, "band (lines removed)")
    duration = float(sum(s.n_samples for s in segs)) * h
    description = (
        f"estimated from a log of {duration:.6g} s at {1.0 / h:.6g} Hz ({len(segs)} segment(s)): the motion as the logged samples see it, "
        f"filters ahead of the log included; nothing above the Nyquist frequency {0.5 / h:.6g} Hz is seen (it is folded below it)"
    )
    env = Environment(tuple(vib), (spectrum,), name=name, description=description)
    return EnvironmentEstimate(env, tuple(lines), search, freq, g, float(dof), q_sigma, h, duration, len(segs), spectra.resolution, merged, spectra.segments)


def _num(x: float) -> str:
    return repr(float(x))


def _list(values) -> str:
    return "[" + ", ".join(_num(v) for v in values) + "]"


def environment_file_text(estimate: EnvironmentEstimate) -> str:
    """The environment file (``docs/environment-files.md``) of an estimate.

    Lines become ``[[vibration_line]]`` (amplitudes in deg/s and m/s², phases
    in degrees, relative to the reference channel), the band one
    ``[[spectrum]]`` of the six channels in rad/s and m/s² (``[re, im]`` pairs
    for the fifteen cross-spectra), and the sensors are ``"none"``: the filters
    ahead of the log are already in it (module docstring).  Numbers are written
    with every digit (``repr``), so the file reads back exactly.

    Parameters
    ----------
    estimate : EnvironmentEstimate
        The estimate.

    Returns
    -------
    str
    """
    if not isinstance(estimate, EnvironmentEstimate):
        raise TypeError(f"Expected `estimate` to be an EnvironmentEstimate, got {type(estimate).__name__}")
    env = estimate.environment
    out = [
        "# Vibration environment estimated from a recorded log (strapdown log environment).",
        "# The motion as the logged samples see it: the filters ahead of the log (anti-aliasing,",
        "# digital low-pass, decimation) are already in it, so [gyro] and [accelerometer] are \"none\"",
        "# and must not be set to those filters again.",
        f"# Nyquist frequency {estimate.nyquist:.6g} Hz: nothing above it is seen; vibration there is folded",
        "# onto its alias below it and counted there.",
        f"# Welch: bins of {estimate.resolution:.6g} Hz ({estimate.merged} per table row), {estimate.welch_segments} segments,"
        f" {estimate.dof:.4g} degrees of freedom per auto-spectrum value.",
        f"# Lines: Thomson F-test over {estimate.search.blocks} blocks, false-alarm probability {estimate.search.false_alarm:g}.",
        f"name = {_quote(env.name)}",
        f"description = {_quote(env.description)}",
        "",
    ]
    for ln in estimate.lines:
        a = ln.amplitude
        out += [
            "[[vibration_line]]",
            f"freq_hz = {_num(ln.frequency)}",
            f"rate_amplitude_deg_s = {_list(np.abs(a[:3]) * DEG_PER_RAD)}",
            f"rate_phase_deg = {_list(np.angle(a[:3]) * DEG_PER_RAD)}",
            f"accel_amplitude_m_s2 = {_list(np.abs(a[3:]))}",
            f"accel_phase_deg = {_list(np.angle(a[3:]) * DEG_PER_RAD)}",
            f"label = {_quote(f'line {ln.frequency:.6g} Hz')}",
            "",
        ]
    g = estimate.density
    out += ["[[spectrum]]", f"label = {_quote('band (lines removed)')}", 'rate_unit = "rad/s"', 'accel_unit = "m/s2"', f"freq_hz = {_list(estimate.frequency)}"]
    for i, c in enumerate(CHANNELS):
        out.append(f"{c} = {_list(np.real(g[:, i, i]))}")
    for i, a in enumerate(CHANNELS):
        for j in range(i + 1, 6):
            pairs = ", ".join(f"[{_num(v.real)}, {_num(v.imag)}]" for v in g[:, i, j])
            out.append(f"{a}_{CHANNELS[j]} = [{pairs}]")
    out += ["", "[gyro]", 'filter = "none"', 'digital = "none"', "", "[accelerometer]", 'filter = "none"', 'digital = "none"', "", "[sampling]", "decimation = 1", ""]
    return "\n".join(out)


def _quote(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def write_environment(path, estimate: EnvironmentEstimate) -> Path:
    """Write the environment file of ``estimate`` atomically, after reading it back with the package's reader.

    The text goes to a temporary file in the target's directory, which
    :func:`~strapdown.analysis.vibration.environment.load_environment` must
    accept (within its limits) before it replaces ``path``; a refused or
    interrupted write leaves ``path`` as it was.

    Parameters
    ----------
    path : str or Path
        The file.
    estimate : EnvironmentEstimate
        The estimate.

    Returns
    -------
    Path

    Raises
    ------
    ValueError
        A text beyond the environment file's size limit (lower ``max_rows``).
    OSError
        A directory that cannot be written.
    """
    p = Path(path)
    text = environment_file_text(estimate)
    size = len(text.encode("utf-8"))
    if size > ENVIRONMENT_LIMITS.file_bytes:
        raise ValueError(f"Expected an environment file within {ENVIRONMENT_LIMITS.file_bytes} bytes, got {size} bytes: lower `max_rows` ({estimate.frequency.size} rows)")
    with replaced_atomically(p) as tmp:
        tmp.write_text(text, encoding="utf-8", newline="\n")
        load_environment(tmp)
    return p
