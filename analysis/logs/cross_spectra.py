"""Welch estimate of the cross-spectral density matrix of several channels, with its confidence intervals.

The channels of one or more gap-free stretches of a record are cut into
overlapping segments (never across a gap), each segment has its mean removed
and is tapered by a window, and the one-sided cross-spectral density matrix is
the average over the segments of ``conj(X_a) X_b`` (Welch 1967), scaled as
``scipy.signal.csd`` with ``scaling="density"`` scales it: one-sided after
Bendat & Piersol, ``G_ab = 2 S_ab``, with ``S_ab`` the transform of
``R_ab(τ) = E[x_a(t) x_b(t + τ)]`` (the convention of
:mod:`strapdown.analysis.vibration.environment`).  The segments are taken a
block at a time, so memory does not grow with the record.

Confidence intervals
--------------------
An auto-spectrum estimate is distributed as ``G χ²_ν / ν`` with the
equivalent degrees of freedom of overlapped, tapered segments (Percival &
Walden 1993, eq. (292b)), ``ν = 2 K / (1 + 2 Σ_{m≥1} (1 − m/K) ρ(m)²)``, ρ(m)
the correlation of the window with itself shifted by m segment steps; the
interval of level ``1 − β`` is ``[ν Ĝ/χ²_ν(1 − β/2), ν Ĝ/χ²_ν(β/2)]``.  The real
(co-) and imaginary (quadrature) parts ``C``, ``Q`` of a cross-spectrum have
the standard deviations ``√((G_aa G_bb + C² − Q²)/ν)`` and
``√((G_aa G_bb + Q² − C²)/ν)`` (Bendat & Piersol 2010, table 9.6, with
``n_d = ν/2`` averages), taken as normal.

Public API
----------
.. autosummary::

   CrossSpectra
   welch_cross_spectra
   equivalent_dof
   WELCH_SAMPLE
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..core import budget
from ..core.progress import bar
from ..core.validation import as_array, as_int, in_open_interval, positive

__all__ = ["CrossSpectra", "welch_cross_spectra", "equivalent_dof", "WELCH_SAMPLE"]

#: Welch estimate, per sample and per channel pair (time; the six-channel matrix has 36):
#: measured on one core by ``benchmarks/bench_log_analysis.py``, rounded up.  Memory: the blocks.
WELCH_SAMPLE = budget.CostModel(seconds_per_unit=4e-9, bytes_per_unit=0.0, fixed_seconds=0.05)
#: Bytes of the working set per frequency bin and block segment (the FFT of six channels, their products).
_BLOCK_BYTES_PER_BIN = 6 * 16 * 4


@dataclass(frozen=True)
class CrossSpectra:
    """One-sided cross-spectral density matrix of C channels, by Welch's method.

    Attributes
    ----------
    frequency : ndarray, shape (F,)
        Bin frequencies, 0 to the Nyquist frequency [Hz].
    density : ndarray of complex, shape (F, C, C)
        ``G_ab(f)`` [unit_a · unit_b / Hz], Hermitian positive semidefinite.
    segments : int
        Segments averaged [count].
    dof : float
        Equivalent degrees of freedom ν of an auto-spectrum estimate.
    segment_length : int
        Samples per segment [count].
    sample_interval : float
        h [s].
    """

    frequency: np.ndarray
    density: np.ndarray
    segments: int
    dof: float
    segment_length: int
    sample_interval: float

    @property
    def resolution(self) -> float:
        """Bin spacing ``1/(segment_length · h)`` [Hz]."""
        return 1.0 / (self.segment_length * self.sample_interval)

    def auto_factors(self, level: float = 0.95) -> tuple:
        """Multipliers ``(lo, hi)`` of an auto-spectrum estimate giving its interval of coverage ``level``.

        Parameters
        ----------
        level : float
            Coverage, in (0, 1).

        Returns
        -------
        tuple of float
            ``(ν/χ²_ν(1 − β/2), ν/χ²_ν(β/2))``, β = 1 − level.
        """
        from scipy.stats import chi2

        beta = 1.0 - in_open_interval(level, "level", 0.0, 1.0)
        nu = self.dof
        return float(nu / chi2.ppf(1.0 - beta / 2.0, nu)), float(nu / chi2.ppf(beta / 2.0, nu))

    def part_sigmas(self) -> tuple:
        """Standard deviations of the real and imaginary parts of every entry, shapes (F, C, C) (module docstring).

        Returns
        -------
        tuple of ndarray
            ``(σ_C, σ_Q)``; on the diagonal σ_C is that of the auto-spectrum, ``G √(2/ν)``.
        """
        g = self.density
        auto = np.real(np.diagonal(g, axis1=1, axis2=2))
        prod = auto[:, :, None] * auto[:, None, :]
        c2, q2 = np.real(g) ** 2, np.imag(g) ** 2
        return np.sqrt(np.maximum(prod + c2 - q2, 0.0) / self.dof), np.sqrt(np.maximum(prod + q2 - c2, 0.0) / self.dof)


def equivalent_dof(window: np.ndarray, step: int, segments: int) -> float:
    """Equivalent degrees of freedom of a Welch estimate (Percival & Walden 1993, eq. (292b)).

    Parameters
    ----------
    window : array_like
        The taper, one value per sample of a segment.
    step : int
        Samples between the starts of consecutive segments [count].
    segments : int
        Segments averaged [count].

    Returns
    -------
    float
        ν; ``2 K`` for segments that do not overlap.

    Examples
    --------
    Hann segments overlapping by half: about 1.9 K.

    >>> from scipy.signal import get_window
    >>> round(equivalent_dof(get_window("hann", 1024), 512, 100) / 100, 3)
    1.896
    """
    w = as_array(window, "window").ravel()
    d = as_int(step, "step", minimum=1)
    k = as_int(segments, "segments", minimum=1)
    energy = float(w @ w)
    total = 0.0
    for m in range(1, k):
        shift = m * d
        if shift >= w.size:
            break
        rho = float(w[:-shift] @ w[shift:]) / energy
        total += (1.0 - m / k) * rho * rho
    return 2.0 * k / (1.0 + 2.0 * total)


def _shapes(stretches, name: str) -> tuple:
    """The stretches as a tuple and their shapes (no pass over the samples), checked to be (N, C) with one C."""
    if isinstance(stretches, np.ndarray):
        stretches = (stretches,)
    if not isinstance(stretches, Sequence) or isinstance(stretches, (str, bytes)) or not stretches:
        raise ValueError(f"Expected `{name}` as one or more (N, C) arrays, got {type(stretches).__name__}")
    shapes = [np.shape(s) for s in stretches]
    if any(len(sh) != 2 or sh[1] != shapes[0][1] or sh[1] < 1 for sh in shapes):
        raise ValueError(f"Expected `{name}` as (N, C) arrays with one C, got shapes {shapes[:4]}")
    return tuple(stretches), shapes


def welch_cross_spectra(stretches, sample_interval: float, segment_length: int, *, overlap: float = 0.5, window: str = "hann", block: int = 64,
                        subtract=None, limits: budget.Limits | None = None, progress: bool = False) -> CrossSpectra:  # fmt: skip
    """Welch estimate of the cross-spectral density matrix of the channels (module docstring).

    Parameters
    ----------
    stretches : ndarray or sequence of ndarray
        ``(N_s, C)`` samples of C channels, one array per gap-free stretch
        (segments never cross from one to the next) [unit].
    sample_interval : float
        h [s].
    segment_length : int
        Samples per segment [count], at least 8; stretches shorter than one
        segment are left out.
    overlap : float, keyword-only
        Fraction of a segment shared with the next, in [0, 1).
    window : str, keyword-only
        Taper (``scipy.signal.get_window`` name).
    block : int, keyword-only
        Segments transformed at once [count] (memory; the result does not depend on it).
    subtract : callable, optional, keyword-only
        ``subtract(stretch_index, first_row, count) -> (count, C)``: a signal
        removed from the samples before they are transformed (fitted lines).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.
    progress : bool, keyword-only
        Show progress on stderr.

    Returns
    -------
    CrossSpectra

    Raises
    ------
    ValueError
        Bad arrays, a segment length below 8, no stretch as long as one
        segment, or work beyond ``limits`` (named by ``stretches`` or ``segment_length``).

    References
    ----------
    Welch, P. D. (1967), IEEE Trans. Audio Electroacoust. 15(2), 70–73;
    Percival, D. B., Walden, A. T. (1993), *Spectral Analysis for Physical
    Applications*, eq. (292b); Bendat, J. S., Piersol, A. G. (2010), *Random
    Data*, 4th ed., sec. 11.5 and table 9.6.

    Examples
    --------
    White noise of variance 1 sampled at 1 kHz has the one-sided density 2 h = 0.002 /Hz:

    >>> x = np.random.default_rng(0).standard_normal((200_000, 1))
    >>> s = welch_cross_spectra(x, 1e-3, 1000)
    >>> round(float(np.mean(s.density[1:-1, 0, 0].real)) / 0.002, 2)
    1.0
    """
    from scipy.fft import rfft
    from scipy.signal import get_window

    parts, shapes = _shapes(stretches, "stretches")
    h = positive(sample_interval, "sample_interval")
    n = as_int(segment_length, "segment_length", minimum=8)
    ov = float(overlap)
    if not 0.0 <= ov < 1.0:
        raise ValueError(f"Expected `overlap` in [0, 1), got {overlap!r}")
    b = as_int(block, "block", minimum=1)
    c = shapes[0][1]
    step = max(1, int(round(n * (1.0 - ov))))
    counts = [0 if sh[0] < n else 1 + (sh[0] - n) // step for sh in shapes]
    if sum(counts) == 0:
        raise ValueError(f"Expected at least one stretch of `stretches` as long as `segment_length` = {n} samples, got at most {max(sh[0] for sh in shapes)}")
    bins = n // 2 + 1
    samples = float(sum(sh[0] for sh in shapes))
    what = f"`stretches` = {samples:.3g} samples of {c} channels in segments of `segment_length` = {n}"
    budget.check(WELCH_SAMPLE.estimate(samples * (n / step) * c * c, what=what, extra_bytes=float(b) * bins * _BLOCK_BYTES_PER_BIN * c / 6 + 8.0 * n * c * b), limits)
    parts = tuple(as_array(x, "stretches") for x in parts)
    w = get_window(window, n)
    scale = 1.0 / (float(w @ w) / h)
    total = np.zeros((bins, c, c), dtype=complex)
    with bar(desc="cross-spectra", total=sum(counts), enabled=progress, unit="segment") as pb:
        for index, (x, k) in enumerate(zip(parts, counts)):
            for s0 in range(0, k, b):
                s1 = min(k, s0 + b)
                first, last = s0 * step, (s1 - 1) * step + n
                data = x[first:last]
                if subtract is not None:
                    data = data - subtract(index, first, last - first)
                frames = np.lib.stride_tricks.sliding_window_view(data, n, axis=0)[::step]  # (s1 − s0, C, n)
                frames = frames - frames.mean(axis=-1, keepdims=True)
                spec = np.ascontiguousarray(rfft(frames * w, axis=-1).transpose(2, 1, 0))  # (F, C, k)
                total += np.matmul(spec.conj(), spec.transpose(0, 2, 1))  # Σ_k conj(X_a) X_b, one product per bin
                pb.update(s1 - s0)
    total = 0.5 * (total + np.conj(total.transpose(0, 2, 1)))  # exactly Hermitian
    total *= scale / sum(counts)
    total[1 : bins - (1 if n % 2 == 0 else 0)] *= 2.0  # one-sided: DC and (even n) the Nyquist bin once
    dof = sum(equivalent_dof(w, step, k) for k in counts if k)
    return CrossSpectra(np.arange(bins) / (n * h), total, int(sum(counts)), float(dof), n, h)
