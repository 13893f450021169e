"""Random rocking of the base: the tilt disturbances ξ(t), η(t).

Hrechka & Koroliov model the tilts as ``β = β0 + ξ``, ``γ = γ0 + η`` with
zero-mean random ξ, η (their eq. (4)).  Three models are provided, each a
small frozen specification with a vectorised ``sample`` method that takes an
``rng``:

:class:`GaussianRocking`
    independent Gaussian samples (white in time);
:class:`SineRocking`
    a sinusoid with a random phase, so that the value at a random instant has
    the arcsine distribution;
:class:`NarrowbandRocking`
    a ship-motion-like stationary process: the output of the second-order
    shaping filter ``ξ'' + 2ζω0 ξ' + ω0² ξ = w`` driven by white noise, with
    period ``2π/ω0`` and damping ζ.  It is generated exactly at the sample
    instants (exact discretisation, then its ARMA(2, 1) innovations form run by
    :func:`scipy.signal.lfilter`), starting in the stationary distribution.

``sigma_xi``, ``sigma_eta`` are always the standard deviations of ξ and η, so
the amplitude of :class:`SineRocking` is ``σ √2``.  ξ and η are independent.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..core import budget
from ..core.validation import as_float, as_int, nonnegative, positive

__all__ = ["GaussianRocking", "SineRocking", "NarrowbandRocking", "as_generator", "rocking_model", "mean_variance_factor", "mean_law", "tilt_domain_limit", "MODELS"]


def as_generator(rng) -> np.random.Generator:
    """Return a :class:`numpy.random.Generator` from ``rng``.

    Parameters
    ----------
    rng : Generator | SeedSequence | BitGenerator | int | None
        The source of randomness (None: fresh entropy).

    Returns
    -------
    numpy.random.Generator

    Raises
    ------
    TypeError
        For any other type.
    ValueError
        For a negative seed.
    """
    if isinstance(rng, np.random.Generator):
        return rng
    if rng is None or isinstance(rng, (np.random.SeedSequence, np.random.BitGenerator)):
        return np.random.default_rng(rng)
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool):
        if rng < 0:
            raise ValueError(f"Expected `rng` seed >= 0, got {rng}")
        return np.random.default_rng(int(rng))
    raise TypeError(f"Expected `rng` to be a numpy Generator, SeedSequence, int or None, got {type(rng).__name__}")


def _shape(n_trials, n_steps, limits=None, copies: float = 2.0) -> tuple[int, int]:
    """Validated ``(n_trials, n_steps)``; refused if ``copies`` arrays of that shape exceed ``limits``."""
    trials, steps = as_int(n_trials, "n_trials", minimum=1), as_int(n_steps, "n_steps", minimum=1)
    budget.check(budget.arrays(float(trials) * steps, what=f"`n_trials` × `n_steps` = {trials:.3g} × {steps:.3g} rocking samples", copies=copies), limits)
    return trials, steps


def _dt(dt):
    return None if dt is None else positive(dt, "dt")


def _order(k) -> int:
    return as_int(k, "k", minimum=0)


def _bound(bound) -> float:
    """A truncation bound: positive, or +inf for none."""
    if isinstance(bound, (float, np.floating)) and bound == math.inf:
        return math.inf
    return positive(bound, "bound")


def _normal_moment(k, bound=math.inf) -> float:
    """``E[u^k; |u| ≤ bound]`` of a standard normal u: 0 for odd k, ``(k − 1)!! P((k + 1)/2, bound²/2)`` for even k."""
    k = _order(k)
    if k % 2:
        return 0.0
    full = float(math.prod(range(k - 1, 0, -2)))
    if math.isinf(bound):
        return full
    from scipy.special import gammainc

    return full * float(gammainc((k + 1) / 2.0, bound * bound / 2.0))


def _arcsine_moment(k, bound=math.inf) -> float:
    """``E[u^k; |u| ≤ bound]`` of ``u = √2 sin ψ``, ψ uniform: 0 for odd k, ``2^{k/2} (2/π) ∫₀^a sin^k t dt`` (``sin a = bound/√2``)."""
    k = _order(k)
    if k % 2:
        return 0.0
    if bound >= math.sqrt(2.0):
        return math.comb(k, k // 2) * 2.0 ** (k // 2) / 2.0**k
    a = math.asin(bound / math.sqrt(2.0))
    integral = a  # ∫₀^a sin^m t dt by m ← m − 2 recursion
    for m in range(2, k + 1, 2):
        integral = -(math.sin(a) ** (m - 1)) * math.cos(a) / m + (m - 1) / m * integral
    return 2.0 ** (k // 2) * 2.0 / math.pi * integral
@dataclass(frozen=True)
class GaussianRocking:
    """Independent zero-mean Gaussian tilts.

    Parameters
    ----------
    sigma_xi : float
        Standard deviation of ξ (about the gyro sensitive axis) [rad].
    sigma_eta : float
        Standard deviation of η [rad].

    >>> xi, eta = GaussianRocking(0.01, 0.02).sample(0, 2, 3)
    >>> xi.shape, eta.shape
    ((2, 3), (2, 3))
    """

    sigma_xi: float
    sigma_eta: float

    name = "normal"
    #: fourth moment over the squared variance, E ξ⁴ / (E ξ²)²
    kappa = 3.0
    #: peak excursion in standard deviations used by the tilt-domain check (``P(|ξ| > 4σ) = 6e-5``)
    peak_factor = 4.0

    def __post_init__(self):
        object.__setattr__(self, "sigma_xi", nonnegative(self.sigma_xi, "sigma_xi"))
        object.__setattr__(self, "sigma_eta", nonnegative(self.sigma_eta, "sigma_eta"))

    def sample(self, rng, n_trials: int, n_steps: int, dt: float | None = None, *, limits: budget.Limits | None = None):
        """``(ξ, η)``, each of shape ``(n_trials, n_steps)`` [rad].

        Parameters
        ----------
        rng : Generator | SeedSequence | int | None
            Random stream.
        n_trials : int
            Independent records.
        n_steps : int
            Samples per record.
        dt : float or None
            Sample interval [s] (irrelevant for white rocking; checked if given).
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        xi, eta : ndarray

        Raises
        ------
        ValueError
            For counts below 1 or records whose memory exceeds ``limits``
            (naming ``n_trials`` and ``n_steps``).
        """
        n_trials, n_steps = _shape(n_trials, n_steps, limits)
        _dt(dt)
        g = as_generator(rng)
        z = g.standard_normal((2, n_trials, n_steps))
        z[0] *= self.sigma_xi
        z[1] *= self.sigma_eta
        return z[0], z[1]

    def standard_moment(self, k: int, bound: float = math.inf) -> float:
        """``E[(ξ/σξ)^k; |ξ/σξ| ≤ bound]`` (the same for η) [dimensionless]: the moments of the standard normal law.

        Parameters
        ----------
        k : int
            Order, ≥ 0.
        bound : float
            Truncation in standard deviations, > 0 (default none).

        Returns
        -------
        float

        >>> GaussianRocking(0.01, 0.01).standard_moment(4)
        3.0
        >>> round(GaussianRocking(0.01, 0.01).standard_moment(0, 1.959963984540054), 12)
        0.95
        """
        return _normal_moment(k, _bound(bound))

    def autocorrelation(self, lag):
        """Normalised autocorrelation ρ(τ) at lags ``lag`` [s]: 1 at 0, else 0.

        Parameters
        ----------
        lag : array_like
            Lags τ [s].

        Returns
        -------
        ndarray
        """
        lag = np.abs(np.asarray(lag, dtype=float))
        return (lag == 0).astype(float)


@dataclass(frozen=True)
class SineRocking:
    """Sinusoidal rocking with random phases: ``ξ = σξ √2 sin(2π t / Tξ + ψξ)``, ψ uniform.

    Parameters
    ----------
    sigma_xi, sigma_eta : float
        Standard deviations of ξ, η [rad] (amplitudes ``σ √2``).
    period_xi, period_eta : float
        Rocking periods [s].

    Notes
    -----
    With ``dt=None`` every sample has its own phase (independent instants);
    otherwise each trial is one time series with one phase per axis.

    >>> m = SineRocking(0.01, 0.0, 8.0, 8.0)
    >>> xi, _ = m.sample(1, 1, 4, dt=2.0)
    >>> bool(np.allclose(xi[0, 0], -xi[0, 2]))
    True
    """

    sigma_xi: float
    sigma_eta: float
    period_xi: float = 10.0
    period_eta: float = 10.0

    name = "sine"
    kappa = 1.5
    #: the peak of a sinusoid is σ√2
    peak_factor = math.sqrt(2.0)

    def __post_init__(self):
        for field in ("sigma_xi", "sigma_eta"):
            object.__setattr__(self, field, nonnegative(getattr(self, field), field))
        for field in ("period_xi", "period_eta"):
            object.__setattr__(self, field, positive(getattr(self, field), field))

    def sample(self, rng, n_trials: int, n_steps: int, dt: float | None = None, *, limits: budget.Limits | None = None):
        """``(ξ, η)``, each of shape ``(n_trials, n_steps)`` [rad], sampled every ``dt`` [s].

        Parameters
        ----------
        rng : Generator | SeedSequence | int | None
            Random stream.
        n_trials : int
            Independent records.
        n_steps : int
            Samples per record.
        dt : float or None
            Sample interval [s]; None: an independent phase for every sample.
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        xi, eta : ndarray

        Raises
        ------
        ValueError
            For counts below 1 or records whose memory exceeds ``limits``
            (naming ``n_trials`` and ``n_steps``).
        """
        n_trials, n_steps = _shape(n_trials, n_steps, limits)
        dt = _dt(dt)
        g = as_generator(rng)
        out = []
        for sigma, period in ((self.sigma_xi, self.period_xi), (self.sigma_eta, self.period_eta)):
            if dt is None:
                phase = g.random((n_trials, n_steps))
            else:
                phase = g.random((n_trials, 1)) + (np.arange(n_steps) * (dt / period))[None, :]
            phase *= 2.0 * math.pi
            np.sin(phase, out=phase)
            phase *= sigma * math.sqrt(2.0)
            out.append(phase)
        return out[0], out[1]

    def standard_moment(self, k: int, bound: float = math.inf) -> float:
        """``E[(ξ/σξ)^k; |ξ/σξ| ≤ bound]`` at a random instant (the same for η) [dimensionless]: ``ξ/σξ = √2 sin ψ``, ψ uniform.

        Parameters
        ----------
        k : int
            Order, ≥ 0.
        bound : float
            Truncation in standard deviations, > 0 (default none; none either from √2 up).

        Returns
        -------
        float

        >>> SineRocking(0.01, 0.01).standard_moment(4)
        1.5
        >>> round(SineRocking(0.01, 0.01).standard_moment(0, 1.0), 12)
        0.5
        """
        return _arcsine_moment(k, _bound(bound))

    def autocorrelation(self, lag, *, axis: str = "xi"):
        """Normalised autocorrelation ``cos(2π τ / T)`` at lags ``lag`` [s].

        Parameters
        ----------
        lag : array_like
            Lags τ [s].
        axis : str
            ``"xi"`` or ``"eta"`` (their periods may differ).

        Returns
        -------
        ndarray
        """
        period = self.period_xi if axis == "xi" else self.period_eta
        return np.cos(2.0 * math.pi * np.asarray(lag, dtype=float) / period)


@dataclass(frozen=True)
class NarrowbandRocking:
    """Stationary output of ``ξ'' + 2ζω0 ξ' + ω0² ξ = w`` with white noise w (both axes).

    Parameters
    ----------
    sigma_xi, sigma_eta : float
        Standard deviations of ξ, η [rad].
    period : float
        Natural period ``2π/ω0`` of the shaping filter [s].
    damping : float
        Damping ratio ζ, in (0, 1).

    Notes
    -----
    The autocovariance is ``σ² e^{−ζω0|τ|}(cos ωd τ + ζω0/ωd sin ωd|τ|)``,
    ``ωd = ω0 √(1 − ζ²)``; the correlation time of its envelope is
    ``1/(ζ ω0)``.  Samples every ``dt`` follow exactly from the discretised
    state ``s = (ξ, ξ')``: ``s_{k+1} = F s_k + w_k``, ``F = exp(A dt)``,
    ``Cov w_k = P∞ − F P∞ Fᵀ`` with ``P∞ = diag(σ², ω0² σ²)``.

    >>> m = NarrowbandRocking(0.01, 0.01, period=8.0, damping=0.1)
    >>> round(m.correlation_time, 4)
    12.7324
    """

    sigma_xi: float
    sigma_eta: float
    period: float = 8.0
    damping: float = 0.1

    name = "narrowband"
    kappa = 3.0
    peak_factor = 4.0

    def __post_init__(self):
        for field in ("sigma_xi", "sigma_eta"):
            object.__setattr__(self, field, nonnegative(getattr(self, field), field))
        object.__setattr__(self, "period", positive(self.period, "period"))
        damping = as_float(self.damping, "damping")
        if not 0.0 < damping < 1.0:
            raise ValueError(f"Expected `damping` in (0, 1), got {damping:g}")
        object.__setattr__(self, "damping", damping)

    def standard_moment(self, k: int, bound: float = math.inf) -> float:
        """``E[(ξ/σξ)^k; |ξ/σξ| ≤ bound]`` (the same for η) [dimensionless]: the stationary law is normal.

        Parameters
        ----------
        k : int
            Order, ≥ 0.
        bound : float
            Truncation in standard deviations, > 0 (default none).

        Returns
        -------
        float
        """
        return _normal_moment(k, _bound(bound))

    @property
    def omega0(self) -> float:
        """Natural frequency ω0 [rad/s]."""
        return 2.0 * math.pi / self.period

    @property
    def correlation_time(self) -> float:
        """Envelope correlation time ``1/(ζ ω0)`` [s]."""
        return 1.0 / (self.damping * self.omega0)

    def autocorrelation(self, lag):
        """Normalised autocorrelation ρ(τ) at lags ``lag`` [s].

        Parameters
        ----------
        lag : array_like
            Lags τ [s].

        Returns
        -------
        ndarray
        """
        tau = np.abs(np.asarray(lag, dtype=float))
        w0, z = self.omega0, self.damping
        wd = w0 * math.sqrt(1.0 - z * z)
        return np.exp(-z * w0 * tau) * (np.cos(wd * tau) + z * w0 / wd * np.sin(wd * tau))

    def discretisation(self, dt: float):
        """``(F, Qd)`` of the unit-variance state ``(ξ, ξ')`` sampled every ``dt`` [s].

        Parameters
        ----------
        dt : float
            Sample interval [s].

        Returns
        -------
        F, Qd : ndarray
            Transition and process-noise covariance (``scipy.linalg.expm``).
        """
        F, Q = _discretise(self.omega0, self.damping, positive(dt, "dt"))
        return F.copy(), Q.copy()

    def sample(self, rng, n_trials: int, n_steps: int, dt: float | None = None, *, limits: budget.Limits | None = None):
        """``(ξ, η)``, each of shape ``(n_trials, n_steps)`` [rad], sampled every ``dt`` [s].

        Parameters
        ----------
        rng : Generator | SeedSequence | int | None
            Random stream.
        n_trials : int
            Independent records.
        n_steps : int
            Samples per record.
        dt : float or None
            Sample interval [s]; None: independent draws from the stationary
            (Gaussian) distribution.
        limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
            Largest estimated memory and run time (default 2 GB, 300 s); a request
            beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

        Returns
        -------
        xi, eta : ndarray

        Raises
        ------
        ValueError
            For counts below 1 or records whose memory exceeds ``limits``
            (naming ``n_trials`` and ``n_steps``).
        """
        n_trials, n_steps = _shape(n_trials, n_steps, limits, copies=8.0)
        dt = _dt(dt)
        g = as_generator(rng)
        if dt is None:
            z = g.standard_normal((2, n_trials, n_steps))
            z[0] *= self.sigma_xi
            z[1] *= self.sigma_eta
        else:  # the filter is linear: scale its input rows, not its output
            scale = np.repeat([self.sigma_xi, self.sigma_eta], n_trials)
            z = self._unit_series(g, 2 * n_trials, n_steps, dt, scale=scale).reshape(2, n_trials, n_steps)
        return z[0], z[1]

    def innovations(self, dt: float):
        """ARMA(2, 1) form of the unit-variance series sampled every ``dt`` [s].

        With ``s_k = F s_{k−1} + w_k`` and Cayley–Hamilton (``F² − tF + dI = 0``,
        ``t = tr F``, ``d = det F``) the samples obey
        ``x_k − t x_{k−1} + d x_{k−2} = u_k``, where ``u_k`` is a moving average
        of order one of the state noise.  Its spectral factor
        ``u_k = e_k + θ e_{k−1}`` (``|θ| < 1``, ``e`` white with variance ``s²``)
        gives the same Gaussian process with one normal draw per sample instead
        of two.

        Parameters
        ----------
        dt : float
            Sample interval [s].

        Returns
        -------
        t, d, theta, s2 : float
        """
        F, Q = self.discretisation(dt)
        t, d = float(np.trace(F)), float(np.linalg.det(F))
        g2 = (F - t * np.eye(2))[0]
        c0 = float(Q[0, 0] + g2 @ Q @ g2)  # Var u_k
        c1 = float(g2 @ Q[:, 0])  # Cov(u_k, u_{k−1})
        if c1 == 0.0:
            return t, d, 0.0, c0
        r = c1 / c0
        theta = (1.0 - math.sqrt(1.0 - 4.0 * r * r)) / (2.0 * r)
        return t, d, theta, c1 / theta

    def _unit_series(self, g, n: int, n_steps: int, dt: float, *, scale=None) -> np.ndarray:
        """``n`` independent unit-variance series of ``n_steps`` samples (rows), times ``scale`` per row."""
        z0 = g.standard_normal((n, 3))
        z = g.standard_normal((n, max(n_steps - 2, 0)))
        if scale is not None:
            z0 *= scale[:, None]
            z *= scale[:, None]
        return self.series_from_normals(z0, z, n_steps, dt, overwrite=True)

    def series_from_normals(self, z0, z, n_steps: int, dt: float, *, overwrite: bool = False) -> np.ndarray:
        """Unit-variance series from standard normals (the generator is linear in them).

        Parameters
        ----------
        z0 : ndarray
            ``(n, 3)`` normals for the start.
        z : ndarray
            ``(n, n_steps − 2)`` normals after.
        n_steps : int
            Samples per series.
        dt : float
            Sample interval [s].
        overwrite : bool
            Scale ``z`` in place.

        Returns
        -------
        ndarray
            ``(n, n_steps)``.

        Notes
        -----

        ``(x_0, x_1, e_1)`` are drawn from their stationary joint law
        (``Cov(x_0, x_1) = F_00``, ``Cov(x_1, e_1) = s²``, ``Cov(x_0, e_1) = 0``),
        then the ARMA(2, 1) recursion of :meth:`innovations` runs in
        :func:`scipy.signal.lfilter`, so every sample has exactly the
        stationary law of the shaping-filter output.
        """
        from scipy import signal

        t, d, theta, s2 = self.innovations(dt)
        F, _ = self.discretisation(dt)
        cov = np.array([[1.0, F[0, 0], 0.0], [F[0, 0], 1.0, s2], [0.0, s2, s2]])
        start = z0 @ np.linalg.cholesky(cov).T
        x = np.empty((z0.shape[0], n_steps))
        x[:, : min(n_steps, 2)] = start[:, : min(n_steps, 2)]
        if n_steps <= 2:
            return x
        e1 = start[:, 2]
        # initial conditions of the transposed direct form II from x_1, x_0 and e_1
        zi = np.stack([theta * e1 + t * start[:, 1] - d * start[:, 0], -d * start[:, 1]], axis=-1)
        if overwrite:
            z *= math.sqrt(s2)
        else:
            z = math.sqrt(s2) * z
        x[:, 2:], _ = signal.lfilter([1.0, theta], [1.0, -t, d], z, axis=-1, zi=zi)
        return x


@functools.lru_cache(maxsize=64)
def _discretise(w0: float, z: float, dt: float):
    """``(F, Qd)`` of the unit-variance shaping-filter state, cached (a Monte Carlo asks for it per block)."""
    from scipy.linalg import expm

    Ac = np.array([[0.0, 1.0], [-w0 * w0, -2.0 * z * w0]])
    F = expm(Ac * dt)
    P = np.diag([1.0, w0 * w0])
    Q = P - F @ P @ F.T
    return F, 0.5 * (Q + Q.T)


MODELS = {"normal": GaussianRocking, "sine": SineRocking, "narrowband": NarrowbandRocking}


def rocking_model(name: str, sigma_xi: float, sigma_eta: float, *, period: float = 8.0, damping: float = 0.1):
    """Build a rocking model by name (``normal``, ``sine`` or ``narrowband``).

    Parameters
    ----------
    name : str
        Model name.
    sigma_xi, sigma_eta : float
        Standard deviations of ξ, η [rad].
    period : float
        Rocking period [s] (sine and narrowband).
    damping : float
        Damping ratio (narrowband).

    Returns
    -------
    GaussianRocking | SineRocking | NarrowbandRocking

    Raises
    ------
    ValueError
        For an unknown name or a bad parameter.

    >>> rocking_model("sine", 0.01, 0.0).kappa
    1.5
    """
    if name == "normal":
        return GaussianRocking(sigma_xi, sigma_eta)
    if name == "sine":
        return SineRocking(sigma_xi, sigma_eta, period, period)
    if name == "narrowband":
        return NarrowbandRocking(sigma_xi, sigma_eta, period, damping)
    raise ValueError(f"Expected `rocking` among {', '.join(MODELS)}, got {name!r}")


def mean_variance_factor(model, n_steps: int, dt: float | None, *, axis: str = "xi", limits: budget.Limits | None = None) -> float:
    """``Var(ξ̄_n) / Var ξ`` for the mean of ``n_steps`` samples taken every ``dt`` [s].

    ``(1/n) [1 + 2 Σ_{k=1}^{n−1} (1 − k/n) ρ(k dt)]`` with the model's
    autocorrelation ρ; ``1/n`` for independent samples (``dt=None``).  It sets
    how well the sample means (16) of Hrechka & Koroliov estimate β0, γ0 under
    correlated rocking.

    Parameters
    ----------
    model : rocking model
        Supplies the autocorrelation.
    n_steps : int
        Samples averaged.
    dt : float or None
        Sample interval [s]; None for independent samples.
    axis : str
        ``"xi"`` or ``"eta"``.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        For ``n_steps`` below 1, or more lags than ``limits`` allow.

    >>> round(mean_variance_factor(SineRocking(1.0, 1.0, 10.0, 10.0), 100, 0.1), 12)
    0.0
    >>> mean_variance_factor(GaussianRocking(1.0, 1.0), 4, 0.1)
    0.25
    """
    n = as_int(n_steps, "n_steps", minimum=1)
    if dt is None or isinstance(model, GaussianRocking):
        return 1.0 / n
    dt = positive(dt, "dt")
    budget.check(budget.autocorrelation_sums(1, n, what=f"`n_steps` = {n:.3g} samples averaged"), limits)
    k = np.arange(1, n, dtype=float)
    if isinstance(model, SineRocking):
        rho = model.autocorrelation(k * dt, axis=axis)
    else:
        rho = model.autocorrelation(k * dt)
    return max(float((1.0 + 2.0 * np.sum((1.0 - k / n) * rho)) / n), 0.0)


def mean_law(model, n_steps: int, dt: float | None):
    """The rocking model whose draws at independent instants have the law of one record's sample means.

    The sample means ``(ξ̄_n, η̄_n)`` of ``n_steps`` samples taken every ``dt``
    are independent, zero-mean, with variances ``v σ²``
    (:func:`mean_variance_factor`), and their law is exact:

    * Gaussian and narrow-band rocking: a linear functional of a Gaussian
      process is Gaussian, so the means are :class:`GaussianRocking` with
      standard deviations ``σ √v``;
    * a sinusoid sampled every ``dt``: the mean of ``a sin(ω k dt + ψ)`` is
      ``a |S| sin(ψ + arg S)`` with ``S = (1/n) Σ exp(iωk dt)`` and
      ``|S|² = v``, again a sinusoid with a uniform phase: :class:`SineRocking`
      with standard deviations ``σ √v``.

    Parameters
    ----------
    model : GaussianRocking | SineRocking | NarrowbandRocking
        The rocking.
    n_steps : int
        Samples averaged, ≥ 1.
    dt : float or None
        Sample interval [s]; None for independent samples (not for a sinusoid,
        whose mean of independent instants has no closed law).

    Returns
    -------
    GaussianRocking | SineRocking

    Raises
    ------
    ValueError
        For a sinusoid with ``dt=None``.
    TypeError
        For an unknown model.

    References
    ----------
    Hrechka & Koroliov, eq. (16) (the sample means); Priestley, M. B., *Spectral
    Analysis and Time Series*, Academic Press, 1981, sec. 5.3.

    >>> m = mean_law(GaussianRocking(0.02, 0.01), 4, None)
    >>> m.sigma_xi, m.sigma_eta
    (0.01, 0.005)
    """
    n = as_int(n_steps, "n_steps", minimum=1)
    if not isinstance(model, (GaussianRocking, SineRocking, NarrowbandRocking)):
        raise TypeError(f"Expected `model` to be a rocking model, got {type(model).__name__}")
    if isinstance(model, SineRocking) and dt is None:
        raise ValueError("Expected `dt` for a sinusoid (its mean over independent instants has no closed law), got None")
    sx = model.sigma_xi * math.sqrt(mean_variance_factor(model, n, dt, axis="xi"))
    se = model.sigma_eta * math.sqrt(mean_variance_factor(model, n, dt, axis="eta"))
    if isinstance(model, SineRocking):
        return SineRocking(sx, se, model.period_xi, model.period_eta)
    return GaussianRocking(sx, se)


def tilt_domain_limit(model, beta0: float, gamma0: float) -> float:
    """Largest rocking standard deviation [rad] for which the tilts stay within ±90°.

    The model is defined for tilts in (−π/2, π/2): the peak excursion
    ``|β0| + k σ`` (``k = √2`` for a sinusoid, 4 for a Gaussian process, whose
    excursions beyond 4σ have probability 6e-5) must stay below π/2 on both axes.

    Parameters
    ----------
    model : rocking model or type
        Supplies ``peak_factor``.
    beta0, gamma0 : float
        Stable tilts [rad].

    Returns
    -------
    float
        The limit [rad]; not positive when the stable tilts alone leave the domain.

    >>> round(math.degrees(tilt_domain_limit(SineRocking, 0.0, 0.0)), 3)
    63.64
    """
    worst = max(abs(as_float(beta0, "beta0")), abs(as_float(gamma0, "gamma0")))
    return (0.5 * math.pi - worst) / model.peak_factor
