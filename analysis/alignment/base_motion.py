"""Rocking of the base in three axes, as smooth random functions of time.

The rocking adds ``θ_r(t) = (ψ_r, β_r, γ_r)(t)`` to the stable attitude
``(ψ0, β0, γ0)`` of :mod:`strapdown.analysis.alignment.tilt_attitude` (ψ_r is yaw; β_r,
γ_r are the paper's ξ, η).  Every model is a sum of sinusoids per axis,

    θ_a(t) = Σ_m Re[c_am e^{iω_m t}],

so that angles, rates and angular accelerations exist at every instant and a
kinematically consistent sensor record can be integrated from them
(:mod:`strapdown.analysis.alignment.imu`).  The axes are independent.

:class:`StillBase`
    no rocking.
:class:`SineMotion`
    one sinusoid per axis, amplitude ``a_a``, common period, independent
    uniform phases: ``|c| = a``.
:class:`MultiSineMotion`
    a sum of sines (several periods, amplitudes per axis), random phases.
:class:`NarrowbandMotion`
    a stationary Gaussian process with the spectrum of the shaping filter
    ``θ'' + 2ζω0 θ' + ω0² θ = w`` (the narrow-band model of
    :class:`strapdown.analysis.gyrocompass.rocking.NarrowbandRocking`), cut off
    at ``cutoff`` times ω0 so that the angular acceleration (and the lever-arm
    acceleration) has a finite variance.
:class:`WhiteMotion`
    band-limited white rocking: a flat spectrum up to ``bandwidth``; with the
    default bandwidth, the Nyquist frequency, the samples are (nearly) independent,
    the white rocking of the paper.

The Gaussian models are defined by a continuous one-sided spectral density
``G_a(ω)`` (:meth:`NarrowbandMotion.density`, :meth:`WhiteMotion.density`),
normalised so that ``∫ G_a dω = σ_a²``.  Their realisations use the spectral
representation on the frequency grid ``ω_m = 2π m/L``, ``m = 0 … n_fft/2``,
``L = n_fft dt`` at least twice the record and forty envelope correlation
times, with independent complex Gaussian coefficients of variance
``E|c_m|² = 2 P_m`` evaluated by an inverse FFT, and the trapezoidal weights
``P_m = w_m G(ω_m) Δω`` (``w = ½`` at zero frequency and at a band edge on the
grid).  By Poisson's summation formula the covariance of that process is the
continuous autocovariance folded with period L, ``Σ_j R(τ + jL)``, which is
``R(τ)`` over the record to ``R(L/2)``: the zero-frequency bin, which carries
the variance of long averages, is kept, and the statistics are right at every
time scale of the record.  The theory (:meth:`NarrowbandMotion.covariance`)
integrates the continuous density itself
(:func:`strapdown.analysis.core.quadrature.integrate`), never the grid.

Amplitudes: ``amplitude`` is the sine amplitude; for the Gaussian models it is
``σ√2`` with σ the standard deviation, as in
:mod:`strapdown.analysis.gyrocompass.admissible_rocking`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cache

import numpy as np

from ..core import budget
from ..core.validation import as_array, as_float, as_int, positive
from ..gyrocompass.rocking import as_generator
from . import kernels

__all__ = ["Spectrum", "UnitDraw", "MotionRealisation", "StillBase", "SineMotion", "MultiSineMotion", "NarrowbandMotion", "WhiteMotion", "motion_model", "MOTIONS", "mean_transfer", "mean_variance"]

#: Trials inverse-transformed at once by the FFT form of a realisation (the work arrays of a block stay in cache).
FFT_BLOCK = 8


@dataclass(frozen=True)
class Spectrum:
    """Discrete spectrum of a rocking model: power of each axis at each frequency.

    Attributes
    ----------
    omega : ndarray
        ``(M,)`` angular frequencies [rad/s].
    power : ndarray
        ``(3, M)`` variance contributed by each frequency to each axis [rad²]
        (``Σ_m power[a, m] = σ_a²``).
    gaussian : bool
        Gaussian coefficients (narrow-band, white) or fixed amplitudes with random phases (sines).
    n_fft : int or None
        FFT length of the grid ``ω_m = 2π m/(n_fft dt)`` (Gaussian models).
    """

    omega: np.ndarray
    power: np.ndarray
    gaussian: bool
    n_fft: int | None = None

    @property
    def sigma(self) -> np.ndarray:
        """Standard deviation of each axis [rad]."""
        return np.sqrt(self.power.sum(axis=1))

    def covariance(self, transfer_a, transfer_b=None) -> np.ndarray:
        """``Cov(L_a θ, L_b θ)`` per axis for linear functionals with transfer functions ``L(e^{iωt})``.

        A linear functional L of ``θ_a(t) = Σ Re[c_m e^{iω_m t}]`` is
        ``Σ Re[c_m H(ω_m)]`` with ``H(ω) = L[e^{iωt}]``; with independent
        uniform phases its covariance with another is ``Σ_m P_m Re[H_a H_b*]``.

        Parameters
        ----------
        transfer_a : array_like
            ``(M,)`` or ``(3, M)`` complex ``H(ω_m)`` (per axis if 2-D).
        transfer_b : array_like, optional
            The other functional (default ``transfer_a``: the variance).

        Returns
        -------
        ndarray
            ``(3,)`` per axis.
        """
        ha = np.asarray(transfer_a, dtype=complex)
        hb = ha if transfer_b is None else np.asarray(transfer_b, dtype=complex)
        return np.sum(self.power * np.real(ha * np.conj(hb)), axis=-1)


class UnitDraw:
    """The random coefficients of a rocking at unit amplitude per axis, with their evaluations kept.

    A search over the rocking amplitude with common random numbers evaluates
    one draw at many amplitudes: the realisations :meth:`MotionRealisation.rescaled`
    makes share this object, so each evaluation of the record (an inverse
    FFT or a sum of sinusoids) is made once and scaled per axis after.  The kept
    evaluations live as long as the draw.

    Parameters
    ----------
    model : rocking model
        The model at unit amplitude on every axis.
    spectrum : Spectrum
        Its discrete spectrum.
    coefficients : ndarray
        ``(n_trials, 3, M)`` complex coefficients at unit amplitude [rad].
    dt : float
        Sample interval [s].
    """

    def __init__(self, model, spectrum: Spectrum, coefficients: np.ndarray, dt: float):
        self.model, self.spectrum, self.coefficients, self.dt = model, spectrum, coefficients, dt
        self._evaluations: dict = {}

    def evaluation(self, n: int, offset: float, d: int, compute, axes: tuple = (0, 1, 2)) -> np.ndarray:
        """The d-th derivative at ``offset + k dt``, ``k < n``, made by ``compute()`` once (read-only).

        Parameters
        ----------
        n : int
            Time points.
        offset : float
            Time of the first point [s].
        d : int
            Derivative.
        compute : callable
            Makes the ``(n_trials, n, 3)`` evaluation.
        axes : tuple of int
            The axes it evaluates (the others are zero: axes that a scale of zero removes).

        Returns
        -------
        ndarray
        """
        return self.kept((int(n), float(offset), int(d), tuple(axes)), compute)

    def points(self, indices: np.ndarray, d: int, compute) -> np.ndarray:
        """The d-th derivative at the sample instants of ``indices``, made by ``compute()`` once (read-only).

        Parameters
        ----------
        indices : ndarray
            ``(K,)`` integer sample indices.
        d : int
            Derivative.
        compute : callable
            Makes the ``(n_trials, K, 3)`` evaluation.

        Returns
        -------
        ndarray
        """
        return self.kept(("points", indices.dtype.str, indices.tobytes(), int(d)), compute)

    def kept(self, key: tuple, compute) -> np.ndarray:
        """The array of ``key``, made by ``compute()`` at the first call and kept read-only.

        Parameters
        ----------
        key : tuple
            Hashable identity of the evaluation.
        compute : callable
            Makes the array when ``key`` is not yet kept.

        Returns
        -------
        ndarray
            Read-only.
        """
        if key not in self._evaluations:
            x = compute()
            x.flags.writeable = False
            self._evaluations[key] = x
        return self._evaluations[key]


@dataclass(frozen=True)
class MotionRealisation:
    """Rocking of ``n`` trials: ``θ_a(t) = Σ_m Re[c[t, a, m] e^{iω_m t}]``.

    Attributes
    ----------
    spectrum : Spectrum
        The model's discrete spectrum.
    coefficients : ndarray
        ``(n_trials, 3, M)`` complex coefficients [rad].
    dt : float
        Sample interval of the FFT grid [s].
    unit : UnitDraw or None
        The draw at unit amplitude of a model whose axes are one shape scaled
        by their amplitudes (sine, narrow-band, white): ``coefficients =
        unit.coefficients · scale`` per axis.  Realisations of the same draw at
        other amplitudes (:meth:`rescaled`) share it and its evaluations.
    scale : ndarray or None
        ``(3,)`` the amplitudes per axis that scale ``unit``.
    """

    spectrum: Spectrum
    coefficients: np.ndarray
    dt: float
    unit: UnitDraw | None = field(default=None, repr=False, compare=False)
    scale: np.ndarray | None = field(default=None, repr=False, compare=False)

    @property
    def n_trials(self) -> int:
        """Trials."""
        return self.coefficients.shape[0]

    def rescaled(self, model) -> MotionRealisation:
        """The same draw (common random numbers) for ``model``, the drawn model at other amplitudes.

        Parameters
        ----------
        model : rocking model
            The model that drew this realisation, with other amplitudes.

        Returns
        -------
        MotionRealisation
            Sharing :attr:`unit` and its kept evaluations.

        Raises
        ------
        ValueError
            If this realisation has no unit draw, or ``model`` at unit amplitude is another model.
        """
        if self.unit is None:
            raise ValueError("Expected a realisation with a unit draw (a model with per-axis amplitudes), got none")
        if getattr(model, "amplitude", None) is None or not _same_model(_unit_model(model), self.unit.model):
            raise ValueError(f"Expected a model that differs from the drawn one by its amplitudes only, got {model!r}")
        a = np.asarray(model.amplitude, dtype=float)
        power = self.unit.spectrum.power * (a * a)[:, None]
        return MotionRealisation(replace(self.unit.spectrum, power=power), self.unit.coefficients * a[:, None], self.dt, self.unit, a.copy())

    @classmethod
    def concatenate(cls, realisations) -> MotionRealisation:
        """The trials of several realisations of one model as one realisation, in order.

        Every trial's evaluations are its own (the inverse FFT and the sum of
        sinusoids transform trial by trial), so the trials of the whole are
        those of the parts to the last bit; their kept unit evaluations are not
        carried over.

        Parameters
        ----------
        realisations : sequence of MotionRealisation
            Draws of one model at the same amplitudes (the same spectrum and sampling).

        Returns
        -------
        MotionRealisation

        Raises
        ------
        ValueError
            For no realisation, or realisations of different models, amplitudes or sampling.
        """
        parts = tuple(realisations)
        if not parts:
            raise ValueError("Expected at least one realisation, got none")
        first = parts[0]
        if len(parts) == 1:
            return first
        for p in parts[1:]:
            same = p.dt == first.dt and p.spectrum.gaussian == first.spectrum.gaussian and p.spectrum.n_fft == first.spectrum.n_fft
            same = same and np.array_equal(p.spectrum.omega, first.spectrum.omega) and np.array_equal(p.spectrum.power, first.spectrum.power)
            same = same and (p.unit is None) == (first.unit is None)
            if same and first.unit is not None:
                same = _same_model(p.unit.model, first.unit.model) and np.array_equal(p.scale, first.scale)
            if not same:
                raise ValueError("Expected realisations of one model at the same amplitudes and sampling, got different ones")
        coefficients = np.concatenate([p.coefficients for p in parts])
        if first.unit is None:
            return cls(first.spectrum, coefficients, first.dt)
        unit = UnitDraw(first.unit.model, first.unit.spectrum, np.concatenate([p.unit.coefficients for p in parts]), first.dt)
        return cls(first.spectrum, coefficients, first.dt, unit, first.scale.copy())

    def evaluate(self, n_samples: int, offset: float = 0.0, *, derivatives: int = 2, limits: budget.Limits | None = None):
        """Angles, rates and angular accelerations at ``t_k = offset + k dt``, ``k < n_samples``.

        Parameters
        ----------
        n_samples : int
            Time points.
        offset : float
            Time of the first point [s], in [0, dt].
        derivatives : int
            Highest derivative returned, 0 to 2 (the accelerations cost an FFT more).
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        tuple of ndarray
            ``angles, rates, accelerations`` (up to ``derivatives``), each
            ``(n_trials, n_samples, 3)`` [rad, rad/s, rad/s²].

        Raises
        ------
        ValueError
            As :meth:`unit_evaluation`.
        """
        parts, scale = self.unit_evaluation(n_samples, offset, derivatives=derivatives, limits=limits)
        if self.unit is None:
            return parts
        return tuple(scale * p for p in parts)

    def unit_evaluation(self, n_samples: int, offset: float = 0.0, *, derivatives: int = 2, limits: budget.Limits | None = None):
        """:meth:`evaluate` as arrays and a factor per axis: ``evaluate(...) = tuple(scale · p for p in parts)``.

        A scaled draw (:attr:`unit`) returns the kept evaluations of its unit
        coefficients, shared and read-only, with its amplitudes as ``scale``;
        any other returns its own evaluation with ``scale`` = 1.  A caller that
        folds the factor into its own loop saves the product over the record.

        Parameters
        ----------
        n_samples : int
            Time points.
        offset : float
            Time of the first point [s], in [0, dt].
        derivatives : int
            Highest derivative returned, 0 to 2.
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        parts : tuple of ndarray
            Up to three ``(n_trials, n_samples, 3)`` arrays [rad, rad/s, rad/s² per unit of ``scale``].
        scale : ndarray
            ``(3,)`` factors per axis (yaw, β, γ) [1].

        Raises
        ------
        ValueError
            For ``derivatives`` outside 0..2, fewer than one sample, or more
            samples than ``limits`` allow.
        """
        n = as_int(n_samples, "n_samples", minimum=1)
        k = as_int(derivatives, "derivatives", minimum=0)
        if k > 2:
            raise ValueError(f"Expected `derivatives` in 0..2, got {k}")
        what = f"`n_samples` = {n:.3g} samples of {self.n_trials} trials"
        budget.check(budget.arrays(3.0 * self.n_trials * n, what=what, copies=2.0 * (k + 1) + 4.0), limits)
        shape = (self.n_trials, n, 3)
        if self.coefficients.shape[-1] == 0:
            return tuple(np.zeros(shape) for _ in range(k + 1)), np.ones(3)
        if self.unit is not None:
            axes = (0, 1, 2)
            if self.spectrum.n_fft is not None:  # an inverse FFT per axis: not for the axes a zero scale removes
                axes = tuple(int(a) for a in np.flatnonzero(self.scale))
            return tuple(self.unit.evaluation(n, offset, d, lambda d=d: self._axes_series(axes, n, offset, d), axes) for d in range(k + 1)), self.scale
        return tuple(self._series(self.coefficients, n, offset, d) for d in range(k + 1)), np.ones(3)

    def evaluate_points(self, indices, *, derivatives: int = 2):
        """:meth:`evaluate` at the sample instants ``t_k = k dt`` of a few indices k, by the sum over frequencies.

        The Gaussian models evaluate a whole record by one inverse FFT of
        their grid, many times longer than the record; at a few instants (the
        truth at the start and the end of an alignment) the direct sum is
        cheaper.  For sinusoids it is :meth:`evaluate`'s own sum at those
        instants, value for value; for the Gaussian models it equals the FFT
        evaluation to round-off.

        Parameters
        ----------
        indices : array_like
            ``(K,)`` sample indices k ≥ 0 [count].
        derivatives : int
            Highest derivative returned, 0 to 2.

        Returns
        -------
        tuple of ndarray
            ``angles, rates, accelerations`` (up to ``derivatives``), each
            ``(n_trials, K, 3)`` [rad, rad/s, rad/s²].

        Raises
        ------
        ValueError
            For a negative or non-integer index, or ``derivatives`` outside 0..2.
        """
        k = np.asarray(indices)
        if k.ndim != 1 or not (np.issubdtype(k.dtype, np.integer) and np.all(k >= 0)):
            raise ValueError(f"Expected `indices` as a 1-D array of sample indices >= 0, got {np.asarray(indices).tolist()!r}")
        d_max = as_int(derivatives, "derivatives", minimum=0)
        if d_max > 2:
            raise ValueError(f"Expected `derivatives` in 0..2, got {d_max}")
        if self.coefficients.shape[-1] == 0:
            return tuple(np.zeros((self.n_trials, k.size, 3)) for _ in range(d_max + 1))
        c, scale = (self.unit.coefficients, self.scale) if self.unit is not None else (self.coefficients, None)
        t = k * self.dt
        w = self.spectrum.omega

        def series(d):
            cd = c * ((1j * w) ** d * np.exp(1j * w * 0.0))
            if self.spectrum.n_fft is not None:
                return np.real(np.einsum("nam,km->nka", cd, np.exp(1j * np.outer(t, w))))
            return self._sinusoids(cd, t)

        if scale is None:
            return tuple(series(d) for d in range(d_max + 1))
        # a scaled draw: the unit evaluation at these instants is kept with the draw, as the records are
        return tuple(scale * self.unit.points(k, d, lambda d=d: series(d)) for d in range(d_max + 1))

    def _axes_series(self, axes, n, offset, d):
        """:meth:`_series` of the unit coefficients on ``axes`` only, zero on the others (each axis's transform is its own)."""
        if len(axes) == 3:
            return self._series(self.unit.coefficients, n, offset, d)
        out = np.zeros((self.n_trials, n, 3))
        if axes:
            out[:, :, list(axes)] = self._series(self.unit.coefficients[:, list(axes), :], n, offset, d)
        return out

    def _series(self, c, n, offset, d):
        """The d-th derivative of ``Re Σ_m c_m e^{iω_m t}`` at ``t_k = offset + k dt``, ``(n_trials, n, 3)``."""
        w = self.spectrum.omega
        c = c * ((1j * w) ** d * np.exp(1j * w * offset))
        if self.spectrum.n_fft is not None:
            return self._fft(c, n)
        return self._sinusoids(c, np.arange(n) * self.dt)

    def _sinusoids(self, c, t, *, compiled: bool | None = None):
        """``Re Σ_m c_m e^{iω_m t}`` at the times t, ``(n_trials, len(t), 3)``, one sinusoid at a time.

        ``compiled``: the products and sums in one compiled pass
        (:func:`~strapdown.analysis.alignment.kernels.sinusoid_sum`, the same
        bits) or in numpy, kept as the reference; None: the pass when it pays off.
        """
        w = self.spectrum.omega
        if kernels.use_compiled(compiled, self.n_trials * t.size * w.size):
            cos = np.array([np.cos(w[m] * t) for m in range(w.size)]).reshape(w.size, t.size)
            sin = np.array([np.sin(w[m] * t) for m in range(w.size)]).reshape(w.size, t.size)
            return kernels.sinusoid_sum(c, cos, sin)
        out = np.zeros((self.n_trials, t.size, 3))
        for m in range(w.size):  # a few sinusoids: Re[c e^{iωt}] = Re c cos ωt − Im c sin ωt
            cos, sin = np.cos(w[m] * t)[:, None], np.sin(w[m] * t)[:, None]
            out += c[:, :, m].real[:, None, :] * cos - c[:, :, m].imag[:, None, :] * sin
        return out

    def _fft(self, c, n):
        """The first ``n`` samples of the inverse FFT of the grid coefficients ``c``, ``(n_trials, n, axes)``.

        The trials are transformed :data:`FFT_BLOCK` at a time, so that the
        spectrum and the transform (``n_fft`` points per row, of which ``n``
        are kept) stay in cache; each row's transform is its own, so the
        blocks give the bits of one call over all rows.
        """
        nfft = self.spectrum.n_fft
        trials, axes, m = c.shape  # the grid ω_m = 2π m/(n_fft dt), m = 0 … M − 1
        out = np.empty((trials, n, axes))
        X = np.zeros((min(trials, FFT_BLOCK), axes, nfft // 2 + 1), dtype=complex)
        for i in range(0, trials, FFT_BLOCK):
            k = min(FFT_BLOCK, trials - i)
            Xb = X[:k]
            np.multiply(c[i : i + k], nfft / 2.0, out=Xb[..., :m])
            Xb[..., 0] *= 2.0  # irfft halves the zero and Nyquist bins (and keeps their real parts: Re c)
            if m == nfft // 2 + 1:
                Xb[..., -1] *= 2.0
            out[i : i + k] = np.swapaxes(np.fft.irfft(Xb, n=nfft, axis=-1)[..., :n], 1, 2)
        return out


def _unit_model(model):
    """``model`` with unit amplitude on every axis."""
    return replace(model, amplitude=np.ones(3))


def _same_model(a, b) -> bool:
    """Models of one type with equal parameters (arrays compared by value)."""
    from dataclasses import fields

    if type(a) is not type(b):
        return False
    return all(np.array_equal(getattr(a, f.name), getattr(b, f.name)) for f in fields(a))


def _amplitude3(value, name) -> np.ndarray:
    a = as_array(value, name).ravel()
    if a.size == 1:
        a = np.repeat(a, 3)
    if a.size != 3:
        raise ValueError(f"Expected `{name}` as one value or three (yaw, beta, gamma), got {a.size}")
    if np.any(a < 0):
        raise ValueError(f"Expected `{name}` >= 0, got {a.tolist()}")
    return a


class _Model:
    """Common behaviour: drawing coefficients from the spectrum."""

    def spectrum(self, n_samples: int, dt: float) -> Spectrum:  # pragma: no cover - overridden
        raise NotImplementedError

    def draw(self, rng, n_trials: int, n_samples: int, dt: float, *, limits: budget.Limits | None = None) -> MotionRealisation:
        """Draw the rocking of ``n_trials`` records of ``n_samples`` samples every ``dt`` [s].

        Parameters
        ----------
        rng : Generator | SeedSequence | int | None
            Random stream.
        n_trials : int
            Trials.
        n_samples : int
            Samples per record (the realisation covers ``[0, (n_samples + 1) dt]``).
        dt : float
            Sample interval [s].
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        MotionRealisation

        Raises
        ------
        ValueError
            For counts below 1, a bad ``dt``, or a draw beyond ``limits``
            (naming ``n_trials`` and ``n_samples``).
        """
        n_trials = as_int(n_trials, "n_trials", minimum=1)
        dt = positive(dt, "dt")
        n_samples = as_int(n_samples, "n_samples", minimum=1)
        what = f"`n_trials` × `n_samples` = {n_trials:.3g} × {n_samples:.3g} samples"
        budget.check(budget.arrays(3.0 * n_trials * n_samples, what=what, copies=6.0), limits)
        s = self.spectrum(n_samples, dt)
        g = as_generator(rng)
        m = s.omega.size
        if s.gaussian:
            z = g.standard_normal((n_trials, 3, m, 2))
            draw = z[..., 0] + 1j * z[..., 1]
            factor = np.sqrt  # E|c|² = 2P
        else:
            z = g.random((n_trials, 3, m))
            draw = np.exp(1j * (z * (2.0 * math.pi)))
            factor = lambda p: np.sqrt(2.0 * p)  # noqa: E731  (|c| = a)
        if "amplitude" in getattr(self, "__dataclass_fields__", {}):  # power = amplitude² · (the unit model's power)
            unit_model = _unit_model(self)
            unit_spectrum = unit_model.spectrum(n_samples, dt)
            unit = UnitDraw(unit_model, unit_spectrum, draw * factor(unit_spectrum.power), dt)
            return MotionRealisation(s, unit.coefficients * self.amplitude[:, None], dt, unit, self.amplitude.copy())
        return MotionRealisation(s, draw * factor(s.power), dt)

    @property
    def sigma(self) -> np.ndarray:
        """Standard deviation per axis (yaw, β, γ) [rad]."""
        return self.amplitude / math.sqrt(2.0)

    def covariance(self, transfer_a, transfer_b=None, *, dt: float | None = None, rtol: float = 1e-10) -> np.ndarray:
        """``Cov(L_a θ, L_b θ)`` per axis: ``Σ_m P_m Re[H_a(ω_m) H_b(ω_m)*]`` over the lines (exact for random phases).

        Parameters
        ----------
        transfer_a : callable
            ``H(ω)`` of a linear functional, ``ω`` a 1-D array [rad/s] → ``(M,)`` or ``(3, M)`` complex.
        transfer_b : callable, optional
            The other functional (default ``transfer_a``: the variance).
        dt : float, optional
            Sample interval [s] (unused: the lines do not depend on it).
        rtol : float
            Unused (the sum is exact).

        Returns
        -------
        ndarray
            ``(3,)`` per axis.
        """
        s = self.spectrum(1, 1.0)
        if s.omega.size == 0:
            return np.zeros(3)
        return s.covariance(transfer_a(s.omega), None if transfer_b is None else transfer_b(s.omega))

    def rate_variance(self, dt: float | None = None) -> np.ndarray:
        """Variance of the angular rates per axis, ``∫ G ω² dω`` (or ``Σ P ω²``) [rad²/s²].

        Parameters
        ----------
        dt : float, optional
            Sample interval [s] (white rocking at the Nyquist frequency).

        Returns
        -------
        ndarray
            ``(3,)``.
        """
        return self.covariance(lambda w: 1j * w, dt=dt)


@dataclass(frozen=True)
class StillBase(_Model):
    """No rocking."""

    name = "none"
    kappa = 3.0

    @property
    def amplitude(self) -> np.ndarray:
        """Zero amplitudes [rad]."""
        return np.zeros(3)

    def spectrum(self, n_samples: int, dt: float) -> Spectrum:
        """The empty spectrum.

        Parameters
        ----------
        n_samples : int
            Samples per record (unused).
        dt : float
            Sample interval [s] (unused).

        Returns
        -------
        Spectrum
        """
        return Spectrum(np.zeros(0), np.zeros((3, 0)), False)


@dataclass(frozen=True)
class SineMotion(_Model):
    """One sinusoid per axis with a common period and independent uniform phases.

    Parameters
    ----------
    amplitude : array_like
        Amplitudes (yaw, β, γ) [rad]; one value for all three axes.
    period : float
        Rocking period [s].
    """

    amplitude: np.ndarray
    period: float = 8.0

    name = "sine"
    kappa = 1.5

    def __post_init__(self):
        object.__setattr__(self, "amplitude", _amplitude3(self.amplitude, "amplitude"))
        object.__setattr__(self, "period", positive(self.period, "period"))

    def spectrum(self, n_samples: int, dt: float) -> Spectrum:
        """The single line at ``2π/period``.

        Parameters
        ----------
        n_samples : int
            Samples per record (unused).
        dt : float
            Sample interval [s] (unused).

        Returns
        -------
        Spectrum
        """
        return Spectrum(np.array([2.0 * math.pi / self.period]), (self.amplitude**2 / 2.0)[:, None], False)


@dataclass(frozen=True)
class MultiSineMotion(_Model):
    """A sum of sines: ``θ_a = Σ_k a_ka sin(2π t / T_k + θ_ka)``, phases uniform and independent.

    Parameters
    ----------
    amplitudes : array_like
        ``(K, 3)`` amplitudes (yaw, β, γ) of each component [rad] (``(K,)``: the same on all axes).
    periods : array_like
        ``(K,)`` periods [s].
    """

    amplitudes: np.ndarray
    periods: np.ndarray

    name = "multisine"

    def __post_init__(self):
        p = as_array(self.periods, "periods").ravel()
        a = as_array(self.amplitudes, "amplitudes")
        if a.ndim == 1:
            a = np.repeat(a[:, None], 3, axis=1)
        if a.shape != (p.size, 3):
            raise ValueError(f"Expected `amplitudes` of shape ({p.size}, 3) for {p.size} periods, got {a.shape}")
        if np.any(p <= 0) or np.any(a < 0):
            raise ValueError("Expected `periods` > 0 and `amplitudes` >= 0")
        object.__setattr__(self, "periods", p)
        object.__setattr__(self, "amplitudes", a)

    @property
    def amplitude(self) -> np.ndarray:
        """``σ√2`` per axis [rad] (the amplitude of one sine of the same variance)."""
        return np.sqrt(np.sum(self.amplitudes**2, axis=0))

    @property
    def kappa(self) -> float:
        """``E θ⁴/(E θ²)²`` of the β axis (3/2 for one sine, towards 3 for many)."""
        a2 = self.amplitudes[:, 1] ** 2 / 2.0
        s2 = a2.sum()
        if s2 == 0:
            return 1.5
        # sum of independent sines: E x⁴ = 3 (Σ a²/2)² − (3/8) Σ a⁴
        return float(3.0 - 1.5 * np.sum(a2**2) / s2**2)

    def spectrum(self, n_samples: int, dt: float) -> Spectrum:
        """The lines at ``2π/T_k``.

        Parameters
        ----------
        n_samples : int
            Samples per record (unused).
        dt : float
            Sample interval [s] (unused).

        Returns
        -------
        Spectrum
        """
        return Spectrum(2.0 * math.pi / self.periods, (self.amplitudes**2 / 2.0).T, False)


def _grid(n_samples: int, dt: float, correlation_time: float):
    """FFT length and the frequencies ``ω_m = 2π m/(n_fft dt)``, ``m = 0 … n_fft/2``, of a record [rad/s]."""
    from scipy.fft import next_fast_len

    n_fft = next_fast_len(int(max(2 * (n_samples + 2), math.ceil(40.0 * correlation_time / dt))), real=True)
    n_fft += n_fft % 2
    return n_fft, 2.0 * math.pi * np.arange(n_fft // 2 + 1) / (n_fft * dt)


class _GaussianModel(_Model):
    """A stationary Gaussian rocking given by its continuous one-sided density on a band ``[0, top]``."""

    gaussian = True

    def density(self, omega) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def _band(self, dt: float | None) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def _correlation_time(self, dt: float) -> float:  # pragma: no cover - overridden
        raise NotImplementedError

    def _resolved(self, dt):
        """The model with every parameter that depends on the sampling stated."""
        return self

    def spectrum(self, n_samples: int, dt: float) -> Spectrum:
        """The simulation's discrete spectrum: trapezoidal weights of the density on the FFT grid.

        ``P_m = w_m G(ω_m) Δω`` for ``ω_m ≤ top``, with ``w = ½`` at ``ω = 0`` and
        at the top of the band when it falls on the grid: the covariance of the
        process is the continuous autocovariance folded with period ``n_fft dt``.

        Parameters
        ----------
        n_samples : int
            Samples per record.
        dt : float
            Sample interval [s].

        Returns
        -------
        Spectrum

        Raises
        ------
        ValueError
            If the band reaches beyond the Nyquist frequency of ``dt``.
        """
        m = self._resolved(dt)
        top = m._band(dt)[-1]
        n_fft, w = _grid(n_samples, dt, m._correlation_time(dt))
        w = w[w <= top * (1.0 + 1e-12)]
        weight = np.ones(w.size)
        weight[0] = 0.5
        if abs(w[-1] - top) <= 1e-12 * top:
            weight[-1] = 0.5
        power = m.density(w) * (weight * (2.0 * math.pi / (n_fft * dt)))[None, :]
        return Spectrum(w, power, True, n_fft)

    def covariance(self, transfer_a, transfer_b=None, *, dt: float | None = None, rtol: float = 1e-10) -> np.ndarray:
        """``Cov(L_a θ, L_b θ)`` per axis from the continuous density: ``∫ G_a(ω) Re[H_a H_b*] dω``.

        Parameters
        ----------
        transfer_a : callable
            ``H(ω)`` of a linear functional of the rocking, ``ω`` a 1-D array [rad/s]
            → ``(M,)`` or ``(3, M)`` complex (per axis).
        transfer_b : callable, optional
            The other functional (default ``transfer_a``: the variance).
        dt : float, optional
            Sample interval [s]; needed by white rocking whose band is the Nyquist frequency.
        rtol : float
            Relative tolerance of the quadrature.

        Returns
        -------
        ndarray
            ``(3,)`` per axis.
        """
        from ..core.quadrature import integrate

        m = self._resolved(dt)
        hb = transfer_a if transfer_b is None else transfer_b

        def integrand(w):
            return m.density(w) * np.real(np.asarray(transfer_a(w)) * np.conj(np.asarray(hb(w))))

        return integrate(integrand, m._band(dt), rtol=rtol, atol=1e-300)


@cache
def _narrowband_integral(damping: float, cutoff: float) -> float:
    """``∫_0^c dx / ((1 − x²)² + 4ζ²x²)``: the shaping-filter density integrated to the cut-off, in units of ω0."""
    from scipy.integrate import quad

    value, _ = quad(lambda x: 1.0 / ((1.0 - x * x) ** 2 + 4.0 * damping * damping * x * x), 0.0, cutoff, points=[1.0], epsabs=0.0, epsrel=1e-13, limit=400)
    return value


@dataclass(frozen=True)
class NarrowbandMotion(_GaussianModel):
    """Gaussian narrow-band rocking: the shaping-filter spectrum, cut off at ``cutoff·ω0``.

    The one-sided density is ``G(ω) ∝ 1/((ω0² − ω²)² + 4ζ²ω0²ω²)`` for
    ``0 ≤ ω ≤ cutoff·ω0``, normalised to ``σ²`` over that band: the
    spectrum of ``θ'' + 2ζω0 θ' + ω0² θ = w`` less its tail beyond the cut-off
    (a fraction of ``1/(3 cutoff³)`` of ``π/(4ζ)`` for small ζ: 0.07 % at 4 and
    ζ = 0.1), so that the angular acceleration has a finite variance.

    Parameters
    ----------
    amplitude : array_like
        ``σ√2`` per axis (yaw, β, γ) [rad]; one value for all three.
    period : float
        Natural period ``2π/ω0`` [s].
    damping : float
        Damping ratio ζ in (0, 1).
    cutoff : float
        Highest frequency over ω0 (default 4; the filter spectrum is 1/225 of its
        low-frequency level there for small ζ).
    """

    amplitude: np.ndarray
    period: float = 8.0
    damping: float = 0.1
    cutoff: float = 4.0

    name = "narrowband"
    kappa = 3.0

    def __post_init__(self):
        object.__setattr__(self, "amplitude", _amplitude3(self.amplitude, "amplitude"))
        object.__setattr__(self, "period", positive(self.period, "period"))
        d = as_float(self.damping, "damping")
        if not 0.0 < d < 1.0:
            raise ValueError(f"Expected `damping` in (0, 1), got {d:g}")
        object.__setattr__(self, "damping", d)
        c = positive(self.cutoff, "cutoff")
        if c <= 1.0:
            raise ValueError(f"Expected `cutoff` > 1 (a multiple of ω0), got {c:g}")
        object.__setattr__(self, "cutoff", c)

    @property
    def omega0(self) -> float:
        """Natural frequency ω0 [rad/s]."""
        return 2.0 * math.pi / self.period

    def density(self, omega) -> np.ndarray:
        """One-sided spectral density per axis, ``∫_0^{cutoff·ω0} G dω = σ²`` [rad²·s].

        Parameters
        ----------
        omega : array_like
            ``(M,)`` angular frequencies [rad/s].

        Returns
        -------
        ndarray
            ``(3, M)``; zero beyond the cut-off.
        """
        w = np.asarray(omega, dtype=float)
        x = w / self.omega0
        g = 1.0 / ((1.0 - x * x) ** 2 + 4.0 * self.damping**2 * x * x)
        g = np.where(x <= self.cutoff * (1.0 + 1e-12), g, 0.0) / (self.omega0 * _narrowband_integral(self.damping, self.cutoff))
        return (self.amplitude[:, None] ** 2 / 2.0) * g[None, :]

    def _band(self, dt):
        w0, z = self.omega0, self.damping
        if dt is not None and self.cutoff * w0 >= math.pi / dt:
            raise ValueError(f"Expected the narrow-band cut-off {self.cutoff:g}·ω0 = {self.cutoff * w0 / (2 * math.pi):g} Hz below the Nyquist frequency {0.5 / dt:g} Hz")
        inner = [w0 * (1.0 - 4.0 * z), w0 * (1.0 - z), w0, w0 * (1.0 + z), w0 * (1.0 + 4.0 * z)]  # the resonance, of half-width ζω0
        return np.array([0.0] + [x for x in inner if 0.0 < x < self.cutoff * w0] + [self.cutoff * w0])

    def _correlation_time(self, dt):
        return 1.0 / (self.damping * self.omega0)

    def autocovariance(self, lag) -> np.ndarray:
        """Autocovariance ``R(τ) = ∫ G(ω) cos ωτ dω`` per axis, from the density [rad²].

        Parameters
        ----------
        lag : array_like
            ``(K,)`` lags τ [s].

        Returns
        -------
        ndarray
            ``(3, K)``.
        """
        tau = np.atleast_1d(np.asarray(lag, dtype=float))
        return np.stack([self.covariance(lambda w, t=t: np.cos(w * t), lambda w: np.ones_like(w)) for t in tau], axis=1)


@dataclass(frozen=True)
class WhiteMotion(_GaussianModel):
    """Band-limited white Gaussian rocking: a flat density on ``[0, bandwidth]``.

    Parameters
    ----------
    amplitude : array_like
        ``σ√2`` per axis (yaw, β, γ) [rad]; one value for all three.
    bandwidth : float or None
        Highest frequency [Hz]; None: the Nyquist frequency of the sampling,
        which makes the samples independent (white): the autocovariance
        ``σ² sin(2πBτ)/(2πBτ)`` vanishes at every nonzero multiple of ``dt = 1/(2B)``.
    """

    amplitude: np.ndarray
    bandwidth: float | None = None

    name = "white"
    kappa = 3.0

    def __post_init__(self):
        object.__setattr__(self, "amplitude", _amplitude3(self.amplitude, "amplitude"))
        if self.bandwidth is not None:
            object.__setattr__(self, "bandwidth", positive(self.bandwidth, "bandwidth"))

    def _top(self, dt) -> float:
        if self.bandwidth is None:
            if dt is None:
                raise ValueError("Expected `dt` for white rocking whose bandwidth is the Nyquist frequency (bandwidth=None)")
            return math.pi / positive(dt, "dt")
        if dt is not None and self.bandwidth > 0.5 / dt * (1 + 1e-12):
            raise ValueError(f"Expected `bandwidth` <= the Nyquist frequency {0.5 / dt:g} Hz, got {self.bandwidth:g}")
        return 2.0 * math.pi * self.bandwidth

    def density(self, omega, dt: float | None = None) -> np.ndarray:
        """One-sided spectral density per axis, ``σ²/(2πB)`` on the band [rad²·s].

        Parameters
        ----------
        omega : array_like
            ``(M,)`` angular frequencies [rad/s].
        dt : float, optional
            Sample interval [s] (needed when the bandwidth is the Nyquist frequency).

        Returns
        -------
        ndarray
            ``(3, M)``; zero beyond the band.
        """
        w = np.asarray(omega, dtype=float)
        top = self._top(dt)
        g = np.where(w <= top * (1.0 + 1e-12), 1.0 / top, 0.0)
        return (self.amplitude[:, None] ** 2 / 2.0) * g[None, :]

    def _band(self, dt):
        return np.array([0.0, self._top(dt)])

    def _correlation_time(self, dt):
        return 1.0 / self._top(dt)

    def _resolved(self, dt):
        """The same rocking with its bandwidth stated (the Nyquist frequency of ``dt`` for None)."""
        return self if self.bandwidth is not None else replace(self, bandwidth=self._top(dt) / (2.0 * math.pi))


def mean_transfer(duration: float):
    """Transfer function of the mean over ``[0, T]``: ``H(ω) = (e^{iωT} − 1)/(iωT)``, 1 at ω = 0.

    Parameters
    ----------
    duration : float
        Averaging time T [s].

    Returns
    -------
    callable
        ``H(ω)`` for an array of angular frequencies [rad/s] (complex, same shape).

    Examples
    --------
    >>> H = mean_transfer(10.0)
    >>> [round(abs(complex(x)), 12) for x in H(np.array([0.0, 2 * np.pi / 10.0]))]
    [1.0, 0.0]
    """
    T = positive(duration, "duration")

    def transfer(omega):
        x = np.asarray(omega, dtype=float) * T
        small = np.abs(x) < 1e-4  # the series 1 + ix/2 − x²/6, to 1e-17
        safe = np.where(small, 1.0, x)
        return np.where(small, 1.0 + 0.5j * x - x * x / 6.0, (np.exp(1j * safe) - 1.0) / (1j * safe))

    return transfer


def mean_variance(motion, duration: float, dt: float | None = None) -> np.ndarray:
    """Variance of the mean of the rocking over ``[0, T]`` per axis, from the model's continuous spectrum [rad²].

    Parameters
    ----------
    motion : rocking model
        :class:`SineMotion`, :class:`NarrowbandMotion`, :class:`WhiteMotion`, ...
    duration : float
        Averaging time T [s].
    dt : float, optional
        Sample interval [s] (white rocking whose band is the Nyquist frequency).

    Returns
    -------
    ndarray
        ``(3,)`` (yaw, β, γ).
    """
    return motion.covariance(mean_transfer(duration), dt=dt)


#: Model names of the command line.
MOTIONS = {"none": StillBase, "sine": SineMotion, "narrowband": NarrowbandMotion, "white": WhiteMotion}


def motion_model(name: str, amplitude=0.0, *, period: float = 8.0, damping: float = 0.1, bandwidth: float | None = None):
    """A rocking model by name.

    Parameters
    ----------
    name : str
        ``none``, ``sine``, ``narrowband`` or ``white``.
    amplitude : array_like
        Amplitudes (yaw, β, γ) [rad] (``σ√2`` for the Gaussian models).
    period : float
        Period [s] (sine, narrowband).
    damping : float
        Damping ratio (narrowband).
    bandwidth : float or None
        Bandwidth [Hz] (white).

    Returns
    -------
    StillBase | SineMotion | NarrowbandMotion | WhiteMotion

    Raises
    ------
    ValueError
        For an unknown name or a bad parameter.
    """
    if name == "none":
        return StillBase()
    if name == "sine":
        return SineMotion(amplitude, period)
    if name == "narrowband":
        return NarrowbandMotion(amplitude, period, damping)
    if name == "white":
        return WhiteMotion(amplitude, bandwidth)
    raise ValueError(f"Expected `rocking` among {', '.join(MOTIONS)}, got {name!r}")
