"""Deterministic lines in a record (rotor and engine harmonics), told apart from a random band by a test that can say no.

A *line* is a sinusoid whose amplitude and phase stay the same over the whole
record; a *band* is random vibration, whose Fourier coefficient at a frequency
changes its phase and size from one stretch of time to the next, however
narrow and tall its peak in a spectrum.  The search has two stages.

1. **Candidates**: bins of a Welch auto-spectrum
   (:mod:`strapdown.analysis.logs.cross_spectra`) that are local maxima and
   stand above their neighbourhood (the running median of the surrounding
   bins, corrected by the median of ``χ²_ν/ν``) by more than the
   ``χ²_ν/ν`` distribution of a band allows, at a lenient level.  A tall band
   peak passes this stage too: it only selects where to look.
2. **The test**: the record is cut into M blocks of the Welch segment length
   (never across a gap), each block is tapered (Hann) and demodulated at the
   candidate's frequency, giving the complex amplitudes ``Z_m`` of each
   channel.  For a band they are independent complex Gaussian numbers of mean
   zero; for a line they share the line's amplitude.  Thomson's statistic
   (Thomson 1982, sec. XIII, with blocks in place of tapers)::

       F = M (M − 1) |Z̄|² / Σ_m |Z_m − Z̄|²

   is then distributed as F(2, 2M − 2) under a band.  Candidates are tested
   the tallest first, and a line found is removed from the blocks before the
   next is tested, so that its leakage does not pass for a line of its own.  The candidate's
   frequency is first refined from the phase advance of ``Z_m`` from block to
   block (a search over about M frequencies of the record's resolution), and
   the level of each test is the family-wise ``false_alarm`` divided by the
   number of bins searched, channels and those M frequencies (Bonferroni), so
   that pure band noise yields a line with probability at most
   ``false_alarm``, whatever passed the first stage.

A line found has, per channel, the complex amplitude ``Z̄`` of the sequence
(``x_n ≈ Re(Z e^{i 2π f t_n})``) and its standard error from the scatter of
the blocks.  :func:`line_signal` evaluates the lines at the samples, to
remove them before the band is estimated.

Public API
----------
.. autosummary::

   Line
   LineSearch
   find_lines
   line_signal
   CANDIDATE_LEVEL
   MAX_CANDIDATES
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.validation import as_array, in_open_interval, positive
from .cross_spectra import CrossSpectra

__all__ = ["Line", "LineSearch", "find_lines", "line_signal", "CANDIDATE_LEVEL", "MAX_CANDIDATES"]

#: Probability that a band bin is taken as a candidate, over every bin and channel searched (stage 1).
CANDIDATE_LEVEL = 0.05
#: Candidates tested, the tallest first [count].
MAX_CANDIDATES = 64
#: Bins on each side of a bin whose running median is its neighbourhood's level (the two nearest excluded).
_NEIGHBOURS = 16


@dataclass(frozen=True)
class Line:
    """A deterministic line found in a record.

    Attributes
    ----------
    frequency : float
        f [Hz].
    amplitude : ndarray of complex, shape (C,)
        ``Z_c``: channel c of the record is ``Re(Z_c e^{i 2π f t})`` at the
        sample times (as recorded: increments, not rates) [unit].
    sigma : ndarray, shape (C,)
        Standard error of each ``Z_c``, ``√(E|Ẑ − Z|²)`` [unit].
    statistic : ndarray, shape (C,)
        Thomson's F of each channel.
    significant : ndarray of bool, shape (C,)
        Channels whose F exceeds the threshold.
    """

    frequency: float
    amplitude: np.ndarray
    sigma: np.ndarray
    statistic: np.ndarray
    significant: np.ndarray


@dataclass(frozen=True)
class LineSearch:
    """What :func:`find_lines` found and how it looked.

    Attributes
    ----------
    lines : tuple of Line
        The lines, by frequency.
    candidates : int
        Candidates tested [count].
    blocks : int
        Blocks M of the test [count] (0: the record was too short for one).
    threshold : float
        F above which a channel holds a line.
    false_alarm : float
        Probability that pure band noise yields a line.
    band : tuple of float
        Frequencies searched [Hz].
    """

    lines: tuple
    candidates: int
    blocks: int
    threshold: float
    false_alarm: float
    band: tuple


def _running_level(g: np.ndarray, dof: float) -> np.ndarray:
    """The neighbourhood level of each bin of ``g`` (F, C): median of the bins 3 … 16 away on either side, over the median of χ²_ν/ν."""
    from scipy.stats import chi2

    f = g.shape[0]
    offsets = np.concatenate([np.arange(-_NEIGHBOURS, -2), np.arange(3, _NEIGHBOURS + 1)])
    idx = np.clip(np.arange(f)[:, None] + offsets[None, :], 0, f - 1)  # (F, 28)
    level = np.median(g[idx], axis=1)
    return level / (chi2.ppf(0.5, dof) / dof)


def _candidates(spectra: CrossSpectra, lo: int, hi: int, level: float, silent: np.ndarray) -> list:
    """Bins in [lo, hi) standing out of their neighbourhood (stage 1), tallest first: refined frequency, 1/level of each channel."""
    from scipy.stats import chi2

    g = np.real(np.diagonal(spectra.density, axis1=1, axis2=2))  # (F, C)
    band = np.maximum(_running_level(g, spectra.dof), np.finfo(float).tiny)
    ratio = np.where(silent, 0.0, g / band)  # a channel holding only round-off (a constant) is left out
    bins = hi - lo
    cut = chi2.ppf(1.0 - level / (bins * g.shape[1]), spectra.dof) / spectra.dof
    score = ratio.max(axis=1)
    found = []
    for k in range(max(lo, 2), min(hi, g.shape[0] - 2)):
        if score[k] > cut and score[k] >= score[k - 2 : k + 3].max():
            c = int(np.argmax(ratio[k]))
            a, b, d = (math.log(max(g[k + j, c], np.finfo(float).tiny)) for j in (-1, 0, 1))
            den = a - 2.0 * b + d
            shift = 0.5 * (a - d) / den if den < 0 else 0.0
            found.append((float(score[k]), (k + max(-0.5, min(0.5, shift))) * spectra.resolution, np.where(silent, 0.0, 1.0 / band[k])))
    found.sort(key=lambda item: -item[0])
    return [(f, w) for _, f, w in found[:MAX_CANDIDATES]]


class _Blocks:
    """The record cut into tapered blocks of L samples (never across a gap), for demodulation at any frequency.

    Held as one ``(M, C, L)`` array (block, channel, sample), each block's mean
    removed; demodulation is then two real matrix-vector products per block.
    """

    def __init__(self, stretches, times, length: int):
        from scipy.signal import get_window

        self.length = length
        self.taper = get_window("hann", length)
        self.gain = 2.0 / float(self.taper.sum())
        channels = stretches[0].shape[1]
        counts = [x.shape[0] // length for x in stretches]
        self.data = np.empty((sum(counts), channels, length))
        starts, row = [], 0
        for x, t, m in zip(stretches, times, counts):
            if m:
                self.data[row : row + m] = x[: m * length].reshape(m, length, channels).transpose(0, 2, 1)
                starts.append(t[: m * length : length])
                row += m
        scale = np.abs(self.data).max(axis=(0, 2)) if self.data.size else np.zeros(channels)
        self.scale = scale
        self.data -= self.data.mean(axis=2, keepdims=True)
        # the round-off of a constant channel (gravity on z at rest): block scatter below it is no noise at all
        self.floor = (1e-12 * scale) ** 2 * max(1, self.data.shape[0])
        self.start = np.concatenate(starts) if starts else np.zeros(0)
        # consecutive blocks of one stretch: the pairs of the block-to-block phase advance
        self.pair = np.concatenate([np.r_[np.ones(m - 1, bool), False] for m in counts if m]) if any(counts) else np.zeros(0, bool)
        self.h = float(np.median(np.diff(times[0]))) if times[0].size > 1 else 1.0

    @property
    def count(self) -> int:
        return self.data.shape[0]

    def subtract(self, line: Line) -> None:
        """Remove ``line`` from the blocks (then their means again), so that its leakage does not reach weaker candidates."""
        w = 2.0 * math.pi * line.frequency
        phase = np.exp(1j * w * self.start)[:, None] * np.exp(1j * w * self.h * np.arange(self.length))[None, :]  # (M, L)
        re, im = phase.real, phase.imag
        for c, a in enumerate(line.amplitude):
            self.data[:, c, :] -= re * a.real - im * a.imag
        self.data -= self.data.mean(axis=2, keepdims=True)

    def amplitudes(self, freq: float) -> np.ndarray:
        """``Z_{m,c}`` at ``freq`` [Hz], shape (M, C): the tapered block's demodulated mean, scaled to the amplitude."""
        w = 2.0 * math.pi * freq
        inside = self.taper * np.exp(-1j * w * self.h * np.arange(self.length))
        z = np.matmul(self.data, inside.real) + 1j * np.matmul(self.data, inside.imag)
        return self.gain * z * np.exp(-1j * w * self.start)[:, None]


def _refine(blocks: _Blocks, freq: float, weights: np.ndarray) -> float:
    """The candidate's frequency refined from the phase advance of its block amplitudes (two passes), within half a bin.

    The channels are weighted by the inverse of their band level at the
    candidate, so that a line in a quiet channel is not drowned by the band of
    a loud one; a refinement that leaves the candidate's bin is not taken.
    """
    start, half = freq, 0.5 / (blocks.length * blocks.h)
    z = blocks.amplitudes(freq)
    r = np.sum(np.conj(z[:-1][blocks.pair[:-1]]) * z[1:][blocks.pair[:-1]] * weights)
    if r != 0:
        freq += np.angle(r) / (2.0 * math.pi * blocks.length * blocks.h)
    z = blocks.amplitudes(freq)
    u = z @ (np.conj(z.mean(axis=0)) * weights)  # one phasor per block, every channel by its weight
    weight = np.abs(u)
    if weight.sum() > 0:
        phase = np.unwrap(np.angle(u))
        t = blocks.start - np.average(blocks.start, weights=weight)
        slope = float(np.sum(weight * t * (phase - np.average(phase, weights=weight))) / max(np.sum(weight * t * t), np.finfo(float).tiny))
        freq += slope / (2.0 * math.pi)
    return freq if abs(freq - start) <= half else start


def find_lines(stretches, times, spectra: CrossSpectra, *, false_alarm: float = 1e-3, min_frequency: float | None = None, max_frequency: float | None = None) -> LineSearch:
    """Lines of the record, each confirmed by Thomson's F-test against a band (module docstring).

    Parameters
    ----------
    stretches : sequence of ndarray
        ``(N_s, C)`` samples of each gap-free stretch [unit].
    times : sequence of ndarray
        ``(N_s,)`` the time of each sample [s].
    spectra : CrossSpectra
        Welch estimate of the same record: its auto-spectra give the candidates
        and its segment length the blocks.
    false_alarm : float, keyword-only
        Probability that pure band noise yields a line, in (0, 1).
    min_frequency, max_frequency : float, optional, keyword-only
        Frequencies searched [Hz] (default: the third bin to the last but two).

    Returns
    -------
    LineSearch

    Raises
    ------
    ValueError
        Stretches and times that do not match, or a search band that is empty.

    References
    ----------
    Thomson, D. J. (1982), "Spectrum estimation and harmonic analysis",
    Proc. IEEE 70(9), 1055–1096, sec. XIII (the F-test for a line in coloured noise).
    """
    from scipy.stats import f as f_dist

    if not isinstance(spectra, CrossSpectra):
        raise TypeError(f"Expected `spectra` to be a CrossSpectra, got {type(spectra).__name__}")
    xs = [as_array(x, "stretches") for x in stretches]
    ts = [as_array(t, "times").ravel() for t in times]
    if len(xs) != len(ts) or any(x.ndim != 2 or x.shape[0] != t.size for x, t in zip(xs, ts)):
        raise ValueError("Expected `stretches` (N_s, C) and `times` (N_s,) of matching lengths, one pair per stretch")
    p = in_open_interval(false_alarm, "false_alarm", 0.0, 1.0)
    res = spectra.resolution
    nbins = spectra.frequency.size
    lo = 2 if min_frequency is None else max(2, int(math.ceil(positive(min_frequency, "min_frequency") / res)))
    hi = nbins - 2 if max_frequency is None else min(nbins - 2, int(math.floor(positive(max_frequency, "max_frequency") / res)) + 1)
    if hi <= lo:
        raise ValueError(f"Expected a search band of at least one bin, got `min_frequency` {lo * res:g} Hz and `max_frequency` {hi * res:g} Hz")
    band = (lo * res, (hi - 1) * res)
    blocks = _Blocks(xs, ts, spectra.segment_length)
    m = blocks.count
    if m < 3:
        return LineSearch((), 0, m, math.inf, p, band)
    channels = xs[0].shape[1]
    tests = (hi - lo) * channels * (m + 1)
    threshold = float(f_dist.isf(p / tests, 2, 2 * m - 2))
    lines = []
    g = np.real(np.diagonal(spectra.density, axis1=1, axis2=2))
    silent = np.median(g[lo:hi], axis=0) <= 2.0 * spectra.sample_interval * (1e-10 * blocks.scale) ** 2  # round-off of a constant channel
    candidates = _candidates(spectra, lo, hi, CANDIDATE_LEVEL, silent)
    for f0, weights in candidates:
        f1 = _refine(blocks, f0, weights)
        if not band[0] - res <= f1 <= band[1] + res:
            continue
        z = blocks.amplitudes(f1)
        mean = z.mean(axis=0)
        scatter = np.sum(np.abs(z - mean) ** 2, axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            # a mean at the round-off of a constant channel (gravity at rest) is no evidence; a line without noise is (capped)
            stat = np.where(np.abs(mean) ** 2 > blocks.floor, np.minimum(m * (m - 1) * np.abs(mean) ** 2 / np.maximum(scatter, blocks.floor), 1e300), 0.0)
        if np.any(stat > threshold) and not any(abs(f1 - ln.frequency) < res for ln in lines):
            line = Line(float(f1), mean, np.sqrt(scatter / (m * (m - 1))), stat, stat > threshold)
            lines.append(line)
            blocks.subtract(line)
    return LineSearch(tuple(sorted(lines, key=lambda ln: ln.frequency)), len(candidates), m, threshold, p, band)


def line_signal(lines, t) -> np.ndarray:
    """The lines at the times ``t``: ``Σ Re(Z e^{i 2π f t})``, shape ``t.shape + (C,)`` [unit].

    Parameters
    ----------
    lines : sequence of Line
        The lines (one C).
    t : array_like
        Times [s].

    Returns
    -------
    ndarray
    """
    t = np.asarray(t, dtype=float)
    out = None
    for ln in lines:
        v = np.real(np.exp(2j * math.pi * ln.frequency * t)[..., None] * ln.amplitude)
        out = v if out is None else out + v
    return np.zeros(t.shape + (0,)) if out is None else out
