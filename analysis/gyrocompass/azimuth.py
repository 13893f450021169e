"""Azimuth error of analytical gyrocompassing on a rocking base.

The azimuth from two horizontal gyros is ``α = −arctan(f2/f1) + σ`` with the
tilt correction ``σ = arctan(B/A)``, ``A = cos φ cos γ + sin φ cos β sin γ``,
``B = sin φ sin β`` (Hrechka & Koroliov, eq. (2)).  On a rocking base
``β = β0 + ξ``, ``γ = γ0 + η`` (4); the estimate ``α*`` uses σ at the stable
tilts (11), so the azimuth error is ``α − α* = σ(β0 + ξ, γ0 + η) − σ(β0, γ0)``.

This module evaluates that error (vectorised, as the angle of
``(A + iB)/(A* + iB*)``, which is the difference of the arctangents for
``A, A* > 0`` and the wrapped angle difference otherwise), the bounds (14) and
(15), and the second-order theory of :mod:`strapdown.derivations.gyrocompass.azimuth_error`
(lambdified), and runs the Monte Carlo of the error through
:mod:`strapdown.analysis.core.montecarlo`, either plain or with the monomials
of the rocking as control variates (:class:`TaylorControls`).

References
----------
Hrechka & Koroliov, eqs. (2), (4), (11)–(16).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from ..core import budget, montecarlo
from ..core.cache import compiled
from ..core.validation import as_float, as_int, in_open_interval, levels, nonnegative
from .rocking import GaussianRocking, NarrowbandRocking, SineRocking

__all__ = [
    "tilt_correction",
    "tilt_components",
    "relative_angle",
    "azimuth_error",
    "bound14",
    "bound15",
    "bound14_squared",
    "SecondOrderTheory",
    "second_order_theory",
    "TiltSensitivity",
    "gradient",
    "TaylorControls",
    "AzimuthErrorKernel",
    "ControlVariateSummary",
    "AzimuthMonteCarlo",
    "far_rocking_probability",
    "azimuth_monte_carlo",
    "check_latitude",
]


def check_latitude(latitude) -> float:
    """Return ``latitude`` [rad] if ``|φ|`` < π/2, else raise ValueError naming it.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].

    Returns
    -------
    float

    Raises
    ------
    ValueError
        If ``|latitude|`` ≥ π/2 or it is not finite.
    """
    return in_open_interval(latitude, "latitude", -math.pi / 2, math.pi / 2, text="(-π/2, π/2) rad, i.e. |latitude| < 90°")


_QUARTER_PI = 0.25 * math.pi


def _cos_from_sin(angle, sine):
    """``cos(angle)`` as ``√(1 − sin²)`` (one transcendental call instead of two on the hot path).

    Used for ``|angle|`` ≤ π/4, where the cosine is at least 1/√2 and the square
    root adds no cancellation (error ≤ 2 ulp); larger tilts, rare under
    rocking, fall back to ``np.cos``.
    """
    if not isinstance(sine, np.ndarray) or sine.ndim == 0:
        return np.cos(angle)
    c = sine * sine
    np.subtract(1.0, c, out=c)
    np.sqrt(c, out=c)
    # two reductions decide the common case (no wide tilt) without a mask; a NaN makes the test
    # fail and takes the masked path, where it is not wide
    if angle.size and not (-_QUARTER_PI <= angle.min() and angle.max() <= _QUARTER_PI):
        wide = np.abs(angle) > _QUARTER_PI
        c[wide] = np.cos(angle[wide])
    return c


def tilt_components(beta, gamma, sin_latitude: float, cos_latitude: float):
    """``(A, B)`` of the tilt correction ``σ = arg(A + iB)``, vectorised (the Monte Carlo hot path).

    Parameters
    ----------
    beta, gamma : ndarray or float
        Tilts β, γ [rad] (not modified).
    sin_latitude, cos_latitude : float
        ``sin φ`` and ``cos φ`` of the latitude.

    Returns
    -------
    A, B : ndarray or float
        ``A = cos φ cos γ + sin φ cos β sin γ``, ``B = sin φ sin β`` (new arrays).

    References
    ----------
    Hrechka & Koroliov, the lines after eq. (2) (with ``cos γ`` in the first term of A).

    >>> A, B = tilt_components(0.0, 0.0, 0.5, math.sqrt(0.75))
    >>> float(B), round(float(A), 12)
    (0.0, 0.866025403784)
    """
    sg = np.sin(gamma)
    A = _cos_from_sin(gamma, sg)
    A *= cos_latitude
    B = np.sin(beta)
    cb = _cos_from_sin(beta, B)
    cb *= sg
    cb *= sin_latitude
    A += cb
    B *= sin_latitude
    return A, B


def relative_angle(A, B, A_ref, B_ref):
    """``arg((A + iB)(A_ref − iB_ref))`` [rad]: the angle of ``A + iB`` relative to ``A_ref + iB_ref``.

    This is ``arctan(B/A) − arctan(B_ref/A_ref)`` when both A are positive, and
    the wrapped angle difference in (−π, π] otherwise.

    Parameters
    ----------
    A, B : ndarray or float
        Components (from :func:`tilt_components`); arrays are overwritten.
    A_ref, B_ref : ndarray or float
        Reference components (broadcast against A, B).

    Returns
    -------
    ndarray or float
        The angle [rad] (in the memory of ``B``'s product when arrays are given).
    """
    num = B * A_ref
    num -= A * B_ref
    A *= A_ref
    B *= B_ref
    A += B
    if isinstance(num, np.ndarray):
        return np.arctan2(num, A, out=num)
    return np.arctan2(num, A)


def tilt_correction(beta, gamma, latitude):
    """Tilt correction ``σ = arg(A + iB)`` [rad] (= ``arctan(B/A)`` for A > 0).

    Parameters
    ----------
    beta : array_like
        Tilt β [rad].
    gamma : array_like
        Tilt γ [rad].
    latitude : float
        Latitude φ [rad], ``|φ|`` < π/2.

    Returns
    -------
    ndarray

    References
    ----------
    Hrechka & Koroliov, eq. (2).

    >>> round(float(tilt_correction(0.01, 0.0, math.radians(45.0))), 6)
    0.01
    """
    latitude = check_latitude(latitude)
    A, B = tilt_components(np.asarray(beta, dtype=float), np.asarray(gamma, dtype=float), math.sin(latitude), math.cos(latitude))
    return np.arctan2(B, A)


def azimuth_error(xi, eta, *, latitude, beta0, gamma0, beta_ref=None, gamma_ref=None):
    """Azimuth error ``σ(β0 + ξ, γ0 + η) − σ(β_ref, γ_ref)`` [rad], wrapped to (−π, π].

    Parameters
    ----------
    xi, eta : array_like
        Rocking ξ, η [rad].
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : float
        Stable tilts β0, γ0 [rad].
    beta_ref, gamma_ref : array_like, optional
        Tilts used by the estimate [rad] (default β0, γ0: the estimate (11);
        sample means give (16)).

    Returns
    -------
    ndarray

    References
    ----------
    Hrechka & Koroliov, eqs. (11), (12), (16).

    >>> e = azimuth_error([0.01, -0.01], [0.0, 0.0], latitude=math.radians(45), beta0=0.0, gamma0=0.0)
    >>> np.round(e, 6)
    array([ 0.01, -0.01])
    """
    latitude = check_latitude(latitude)
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    sphi, cphi = math.sin(latitude), math.cos(latitude)
    xi, eta = np.asarray(xi, dtype=float), np.asarray(eta, dtype=float)
    beta_ref = beta0 if beta_ref is None else np.asarray(beta_ref, dtype=float)
    gamma_ref = gamma0 if gamma_ref is None else np.asarray(gamma_ref, dtype=float)
    A_ref, B_ref = tilt_components(np.asarray(beta_ref, dtype=float), np.asarray(gamma_ref, dtype=float), sphi, cphi)
    A, B = tilt_components(xi + beta0, eta + gamma0, sphi, cphi)
    return relative_angle(A, B, A_ref, B_ref)


# --------------------------------------------------------------------- theory
def _coefficients():
    """Taylor coefficients of A, B at (φ, β0, γ0): generated once, cached on disk."""

    def build():
        from ...derivations.gyrocompass.azimuth_error import coefficient_expressions

        return coefficient_expressions(3)

    return compiled("gyrocompass:taylor-coefficients:order-3:v1", build)


def _moments():
    """Generic moments of the error (first-order mse, bias, fourth-order mse)."""

    def build():
        from ...derivations.gyrocompass.azimuth_error import moment_expressions

        args, m = moment_expressions()
        return args, tuple(m)

    return compiled("gyrocompass:error-moments:v1", build)


def _scalar_moments(args) -> tuple:
    """``(m1, bias, m4)`` of :func:`_moments` at scalar arguments, as Python floats.

    The generated code is scalar arithmetic and integer powers: with Python
    floats it takes the same IEEE operations (and the same ``pow``) as with
    NumPy scalars, without NumPy's scalar dispatch, a third of the time.  Where
    Python raises instead of returning ``inf`` or ``nan`` (a zero to a negative
    power, an overflowing power) the NumPy scalars give NumPy's values.
    """
    try:
        return tuple(float(v) for v in _moments()(*(float(a) for a in args)))
    except (ZeroDivisionError, OverflowError):
        return tuple(float(v) for v in _moments()(*(np.float64(a) for a in args)))


def _bound14_squared():
    """Bound (14) on δ² as a function of (φ, β0, γ0, Dξ, Dη)."""

    def build():
        from ...derivations.gyrocompass.azimuth_error import SYMBOLS, bound14_rocking

        s = SYMBOLS
        return (s.phi, s.beta0, s.gamma0, s.D_xi, s.D_eta), bound14_rocking()

    return compiled("gyrocompass:bound14-rocking:v1", build)


def bound14_squared(latitude, beta0, gamma0, var_xi, var_eta):
    """Bound (14) on δ² [rad²], vectorised (no validation: the hot path of the sample-mean kernel).

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : array_like
        Stable tilts (or their estimates) [rad].
    var_xi, var_eta : array_like
        Variances Dξ, Dη (or their estimates) [rad²].

    Returns
    -------
    ndarray
    """
    return np.asarray(_bound14_squared()(latitude, beta0, gamma0, var_xi, var_eta), dtype=float)


def _sigmas(sigma_xi, sigma_eta):
    return nonnegative(sigma_xi, "sigma_xi"), nonnegative(sigma_eta, "sigma_eta")


def bound14(latitude, beta0, gamma0, sigma_xi, sigma_eta) -> float:
    """Bound (14) on the rms azimuth error δ [rad], with ξ, η independent.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : float
        Stable tilts [rad].
    sigma_xi, sigma_eta : float
        Standard deviations of ξ, η [rad].

    Returns
    -------
    float

    Raises
    ------
    ValueError
        For ``|latitude|`` ≥ π/2, a negative sigma or non-finite input.

    References
    ----------
    Hrechka & Koroliov, eq. (14) (Dζ1, Dζ2 from (7), (10) as derived).

    >>> round(bound14(math.radians(45), 0.0, 0.0, 0.01, 0.02), 12)
    0.01
    """
    latitude = check_latitude(latitude)
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    sx, se = _sigmas(sigma_xi, sigma_eta)
    return math.sqrt(float(bound14_squared(latitude, beta0, gamma0, sx * sx, se * se)))


def bound15(latitude, sigma_xi) -> float:
    """Bound (15): ``δ ≤ tan φ √Dξ`` [rad].

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    sigma_xi : float
        Standard deviation of ξ [rad].

    Returns
    -------
    float

    References
    ----------
    Hrechka & Koroliov, eq. (15).

    >>> round(bound15(math.radians(45), 0.01), 12)
    0.01
    """
    latitude = check_latitude(latitude)
    return abs(math.tan(latitude)) * nonnegative(sigma_xi, "sigma_xi")


@dataclass(frozen=True)
class SecondOrderTheory:
    """Moments of the azimuth error ``σ − σ*`` from the Taylor series of σ [rad, rad²].

    Attributes
    ----------
    rms_first_order : float
        ``√E L²`` of the linear error (exact to second order in the rocking).
    bias : float
        ``E(σ − σ*)`` to second order.
    rms : float
        ``√E(σ − σ*)²`` with the mean square to fourth order.
    mse_first_order : float
        ``E L²``.
    mse : float
        ``E(σ − σ*)²`` to fourth order.
    """

    rms_first_order: float
    bias: float
    rms: float
    mse_first_order: float
    mse: float


def second_order_theory(latitude, beta0, gamma0, sigma_xi, sigma_eta, *, kappa_xi: float = 3.0, kappa_eta: float = 3.0) -> SecondOrderTheory:
    """Moments of the azimuth error from the Taylor series of σ (not in the paper).

    The series comes from :mod:`strapdown.derivations.gyrocompass.azimuth_error`;
    its numerical code is generated once and cached on disk
    (:func:`strapdown.analysis.core.cache.compiled`), so a call does not import SymPy.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : float
        Stable tilts [rad].
    sigma_xi, sigma_eta : float
        Standard deviations of ξ, η [rad].
    kappa_xi, kappa_eta : float
        ``E ξ⁴/(E ξ²)²`` and likewise for η (3 Gaussian, 1.5 sinusoid).

    Returns
    -------
    SecondOrderTheory

    Raises
    ------
    ValueError
        For ``|latitude|`` ≥ π/2, a negative sigma or non-finite input.

    >>> t = second_order_theory(math.radians(45), 0.0, 0.0, 0.01, 0.0)
    >>> round(t.rms_first_order, 12), t.bias
    (0.01, 0.0)
    """
    latitude = check_latitude(latitude)
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    sx, se = _sigmas(sigma_xi, sigma_eta)
    coefficients = _coefficients()(latitude, beta0, gamma0)
    args = (*coefficients, sx * sx, se * se, as_float(kappa_xi, "kappa_xi"), as_float(kappa_eta, "kappa_eta"))
    m1, bias, m4 = _scalar_moments(args)
    return SecondOrderTheory(math.sqrt(max(m1, 0.0)), bias, math.sqrt(max(m4, 0.0)), m1, m4)


class TiltSensitivity(NamedTuple):
    """First-order sensitivity of the azimuth to the tilts at (β0, γ0) [rad/rad].

    Attributes
    ----------
    d_beta : float
        ``∂σ/∂β``.
    d_gamma : float
        ``∂σ/∂γ``.
    """

    d_beta: float
    d_gamma: float


def gradient(latitude, beta0, gamma0) -> TiltSensitivity:
    """``(∂σ/∂β, ∂σ/∂γ)`` at (β0, γ0) [rad/rad]: the first-order sensitivity of the azimuth.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : float
        Stable tilts [rad].

    Returns
    -------
    TiltSensitivity

    >>> g = gradient(math.radians(45), 0.0, 0.0)
    >>> round(g.d_beta, 12), round(g.d_gamma, 12)
    (1.0, 0.0)
    """
    latitude = check_latitude(latitude)
    c = _coefficients()(latitude, as_float(beta0, "beta0"), as_float(gamma0, "gamma0"))
    As, Bs, a10, a01, b10, b01 = (float(c[i]) for i in (0, 1, 2, 3, 2 + 9, 3 + 9))
    r2 = As * As + Bs * Bs
    return TiltSensitivity((As * b10 - Bs * a10) / r2, (As * b01 - Bs * a01) / r2)


# ---------------------------------------------------------------- Monte Carlo
_ESTIMATES = ("known", "sample-mean")


@dataclass(frozen=True)
class TaylorControls:
    """Control variates of the azimuth error: the monomials of the standardised rocking.

    The error ``e(ξ, η)`` and its square are smooth in the rocking, so their
    Taylor polynomials are combinations of the monomials ``u^i v^j``
    (``u = ξ/σξ``, ``v = η/ση``, ``1 ≤ i + j ≤ degree``), whose means
    ``E u^i · E v^j`` are exact (ξ and η are independent; the moments are those
    of the rocking law).  ``e − c₁·m`` and ``e² − c₂·m``, with the monomials
    ``m`` centred at their means and coefficients fixed in advance, have the
    means of ``e`` and ``e²`` and only the variance of what the polynomial
    misses: for small rocking almost none.

    Parameters
    ----------
    degree : int
        Highest total degree of the monomials, ≥ 1.
    sigma_xi, sigma_eta : float
        Standard deviations of ξ, η [rad]; an axis with zero spread has no monomials.
    moments_xi, moments_eta : tuple of float
        ``E u^k`` and ``E v^k`` for ``k = 0 … degree`` [dimensionless].
    coefficients : tuple of tuple of float
        For the error [rad] and the squared error [rad²], the coefficient of every
        monomial (in the order of :attr:`exponents`); empty: not fitted yet.
    offsets : tuple of float
        Constants subtracted from the two controlled quantities (the pilot's
        estimates of ``E e`` [rad] and ``E e²`` [rad²]), so that their sums of
        squares carry no cancellation.
    variance_ratios : tuple of float
        The pilot's fraction of the variance of ``e`` and of ``e²`` that the
        fitted controls leave [dimensionless]; empty: not fitted yet.

    References
    ----------
    Lavenberg & Welch (1981), *Management Science* 27(3), 322–335 (control
    variables); Hrechka & Koroliov, eq. (12) (the error).
    """

    degree: int
    sigma_xi: float
    sigma_eta: float
    moments_xi: tuple
    moments_eta: tuple
    coefficients: tuple = ()
    offsets: tuple = (0.0, 0.0)
    variance_ratios: tuple = ()

    def __post_init__(self):
        object.__setattr__(self, "degree", as_int(self.degree, "degree", minimum=1))
        object.__setattr__(self, "sigma_xi", nonnegative(self.sigma_xi, "sigma_xi"))
        object.__setattr__(self, "sigma_eta", nonnegative(self.sigma_eta, "sigma_eta"))
        for name in ("moments_xi", "moments_eta"):
            if len(getattr(self, name)) != self.degree + 1:
                raise ValueError(f"Expected `{name}` of length degree + 1 = {self.degree + 1}, got {len(getattr(self, name))}")
        if self.coefficients and (len(self.coefficients) != 2 or any(len(c) != len(self.exponents) for c in self.coefficients)):
            raise ValueError(f"Expected `coefficients` as two rows of {len(self.exponents)}, got {self.coefficients!r}")

    @classmethod
    def for_rocking(cls, rocking, degree: int) -> TaylorControls:
        """The unfitted controls of a rocking model (its standard deviations and moments).

        Parameters
        ----------
        rocking : GaussianRocking | SineRocking | NarrowbandRocking
            The rocking at independent instants.
        degree : int
            Highest total degree, ≥ 1.

        Returns
        -------
        TaylorControls

        >>> from strapdown.analysis.gyrocompass.rocking import GaussianRocking
        >>> TaylorControls.for_rocking(GaussianRocking(0.01, 0.02), 2).exponents
        ((1, 0), (0, 1), (2, 0), (1, 1), (0, 2))
        """
        degree = as_int(degree, "degree", minimum=1)
        moments = tuple(rocking.standard_moment(k) for k in range(degree + 1))
        return cls(degree, rocking.sigma_xi, rocking.sigma_eta, moments, moments)

    def fitted(self, xi, eta, errors) -> TaylorControls:
        """These controls with coefficients fitted on pilot draws (:func:`strapdown.analysis.core.montecarlo.fit_controls`).

        Parameters
        ----------
        xi, eta : array_like
            Pilot rocking samples [rad].
        errors : array_like
            Their azimuth errors [rad].

        Returns
        -------
        TaylorControls

        Raises
        ------
        ValueError
            If the pilot has fewer than ``2p + 4`` draws (p monomials).
        """
        e = np.ravel(errors)
        fit = montecarlo.fit_controls(np.stack([e, e * e], axis=1), self.monomials(xi, eta))
        return replace(self, coefficients=fit.coefficients, offsets=fit.intercepts, variance_ratios=fit.variance_ratios)

    @property
    def variance_ratio(self) -> float:
        """The larger of :attr:`variance_ratios` (1 when not fitted) [dimensionless]."""
        return max(self.variance_ratios) if self.variance_ratios else 1.0

    @property
    def exponents(self) -> tuple:
        """``(i, j)`` of the monomials ``u^i v^j``, by total degree."""
        out = []
        for d in range(1, self.degree + 1):
            for i in range(d, -1, -1):
                j = d - i
                if (i == 0 or self.sigma_xi > 0.0) and (j == 0 or self.sigma_eta > 0.0):
                    out.append((i, j))
        return tuple(out)

    def monomials(self, xi, eta) -> np.ndarray:
        """The monomials minus their exact means, shape ``(n, p)``.

        Parameters
        ----------
        xi, eta : array_like
            Rocking samples [rad] (flattened).

        Returns
        -------
        ndarray
        """
        exps = self.exponents
        xi, eta = np.ravel(xi), np.ravel(eta)
        out = np.empty((xi.size, len(exps)))
        powers = {}
        for axis, values, sigma in (("u", xi, self.sigma_xi), ("v", eta, self.sigma_eta)):
            if sigma > 0.0:
                base = values / sigma
                powers[axis, 1] = base
                for k in range(2, self.degree + 1):
                    powers[axis, k] = powers[axis, k - 1] * base
        # a column of ``out`` is strided: each is written once, centred on the way from a contiguous
        # power or product (a mixed product goes through one reused contiguous buffer)
        product = np.empty(xi.size)
        for col, (i, j) in enumerate(exps):
            if i and j:
                value = np.multiply(powers["u", i], powers["v", j], out=product)
            else:
                value = powers["u", i] if i else powers["v", j]
            np.subtract(value, self.moments_xi[i] * self.moments_eta[j], out=out[:, col])
        return out

    def residuals(self, errors, monomials) -> np.ndarray:
        """``(e − c₁·m − o₁, e² − c₂·m − o₂)`` per sample, shape ``(n, 2)``.

        Parameters
        ----------
        errors : array_like
            Azimuth errors e [rad] (flattened).
        monomials : ndarray
            Their :meth:`monomials`.

        Returns
        -------
        ndarray

        Raises
        ------
        ValueError
            If the coefficients have not been fitted.
        """
        if not self.coefficients:
            raise ValueError("Expected fitted `coefficients`, got none")
        e = np.ravel(errors)
        out = np.stack([e, e * e], axis=1)
        out -= montecarlo.combine(monomials, np.array(self.coefficients).T)
        out -= np.array(self.offsets)
        return out


@dataclass(frozen=True)
class AzimuthErrorKernel:
    """Monte Carlo kernel: azimuth errors of ``n_trials`` rocking records.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    beta0, gamma0 : float
        Stable tilts [rad].
    rocking : GaussianRocking | SineRocking | NarrowbandRocking
        Rocking model.
    n_steps : int
        Samples per trial.
    dt : float or None
        Sample interval [s]; None for independent instants.
    estimate : str
        ``"known"``: the error ``σ(β0 + ξ, γ0 + η) − σ*`` of (12) at every
        sample (α* from the true β0, γ0, eq. (11));
        ``"sample-mean"``: the alignment error ``σ(β̂0, γ̂0) − σ*`` of the
        estimate (16) from the ``n_steps`` samples of a trial (one error per
        trial).  With one sample it is the error of (12).
    controls : TaylorControls or None
        Fitted control variates (``estimate="known"`` only): the kernel then also
        returns, per trial, the means of the two :meth:`TaylorControls.residuals`.

    Notes
    -----
    With ``estimate="sample-mean"`` the kernel also returns, per trial, the
    squares of the bounds (14) and (15) evaluated as the paper prescribes after
    (16): with the sample means and the sample variances of the trial.
    """

    latitude: float
    beta0: float
    gamma0: float
    rocking: object
    n_steps: int = 1024
    dt: float | None = None
    estimate: str = "known"
    controls: TaylorControls | None = None

    def __post_init__(self):
        object.__setattr__(self, "latitude", check_latitude(self.latitude))
        object.__setattr__(self, "beta0", as_float(self.beta0, "beta0"))
        object.__setattr__(self, "gamma0", as_float(self.gamma0, "gamma0"))
        object.__setattr__(self, "n_steps", as_int(self.n_steps, "n_steps", minimum=1))
        if not isinstance(self.rocking, (GaussianRocking, SineRocking, NarrowbandRocking)):
            raise TypeError(f"Expected `rocking` to be a rocking model, got {type(self.rocking).__name__}")
        if self.estimate not in _ESTIMATES:
            raise ValueError(f"Expected `estimate` in {_ESTIMATES}, got {self.estimate!r}")
        if self.estimate == "sample-mean" and self.n_steps < 2:
            raise ValueError(f"Expected `n_steps` >= 2 for sample-mean estimates, got {self.n_steps}")
        if self.controls is not None:
            if not isinstance(self.controls, TaylorControls):
                raise TypeError(f"Expected `controls` to be TaylorControls or None, got {type(self.controls).__name__}")
            if self.estimate != "known":
                raise ValueError(f"Expected `controls` only with estimate='known', got estimate={self.estimate!r}")
            if not self.controls.coefficients:
                raise ValueError("Expected fitted `controls` (coefficients), got none")

    def __call__(self, n_trials: int, rng):
        xi, eta = self.rocking.sample(rng, n_trials, self.n_steps, self.dt)
        monomials = None if self.controls is None else self.controls.monomials(xi, eta)
        sphi, cphi = math.sin(self.latitude), math.cos(self.latitude)
        xi += self.beta0
        eta += self.gamma0
        A_ref, B_ref = tilt_components(np.float64(self.beta0), np.float64(self.gamma0), sphi, cphi)
        if self.estimate == "known":
            A, B = tilt_components(xi, eta, sphi, cphi)
            errors = relative_angle(A, B, A_ref, B_ref)
            if monomials is None:
                return errors
            aux = self.controls.residuals(errors, monomials).reshape(errors.shape[0], errors.shape[1], 2).mean(axis=1)
            return errors, aux
        b_hat, g_hat = xi.mean(axis=1), eta.mean(axis=1)
        dxi = xi.var(axis=1)  # 1/n normalisation, as in (16)
        deta = eta.var(axis=1)
        A, B = tilt_components(b_hat, g_hat, sphi, cphi)
        errors = relative_angle(A, B, A_ref, B_ref)[:, None]
        b14sq = np.broadcast_to(bound14_squared(self.latitude, b_hat, g_hat, dxi, deta), dxi.shape)
        b15sq = math.tan(self.latitude) ** 2 * dxi
        return errors, np.stack([b14sq, b15sq], axis=-1)


@dataclass(frozen=True)
class ControlVariateSummary:
    """How a control-variate Monte Carlo was sized, and what its intervals are worth.

    Attributes
    ----------
    degree : int
        Highest total degree of the controls (:class:`TaylorControls`; 1 for
        linear controls); 0: the run is a plain Monte Carlo.
    pilot_samples : int
        Draws of the pilots that fitted and sized the run (0: none, coefficients fixed in advance or no controls) [count].
    samples : int
        Draws of the run whose statistics are reported [count].
    reference_samples : int
        The plain Monte Carlo whose precision was the target [count].
    plain_equivalent : float
        Draws a plain Monte Carlo would need for standard errors as small as
        these, the smaller over the mean and the mean square (estimated from
        the same run; ``inf`` when the controlled error has no spread) [count].
    """

    degree: int
    pilot_samples: int
    samples: int
    reference_samples: int
    plain_equivalent: float


@dataclass(frozen=True)
class AzimuthMonteCarlo:
    """Monte Carlo of the azimuth error with the bounds and the theory of the same case [rad].

    Attributes
    ----------
    result : MonteCarloResult
        Statistics of the error.
    bound14, bound15 : float
        Bounds (14), (15) at the true variances [rad].
    theory : SecondOrderTheory
        Second-order theory of the case.
    controls : ControlVariateSummary or None
        The control variates behind the mean and rms of ``result`` (None: plain Monte Carlo).
    """

    result: montecarlo.MonteCarloResult
    bound14: float
    bound15: float
    theory: SecondOrderTheory
    controls: ControlVariateSummary | None = None


#: main-run size over (variance ratio × reference size): a margin for the pilot's estimate of the ratio
_SIZE_MARGIN = 1.5
#: draws per block of a control-variate run (the unit of randomness)
_CONTROL_BLOCK = 8192
#: the Taylor controls are trusted for tilts within this fraction of the distance to the horizon of the tilt correction
_TRUSTED_FRACTION = 0.9
#: a plain run of the reference size expecting fewer excursions beyond it than ``_RARE_VISITS`` is not changed by
#: them; otherwise the controlled run contains at least ``_FAR_VISITS`` of them, or, if even the plain run would
#: expect fewer, it is the plain run
_RARE_VISITS = 0.05
_FAR_VISITS = 100
#: a run longer than this many pilots is fitted and sized on a second pilot of a quarter of its length
_LONG_RUN = 16
#: longer runs allowed when a run still falls short of the reference precision
_EXTENSIONS = 2
#: a controlled run planned at least this fraction of a plain one longer than ``_SHORT_RUN`` draws is the plain one
#: (a controlled draw costs about 1.4 plain ones; shorter runs cost little either way, and the controlled one is tighter)
_NOT_SHORTER = 0.5
_SHORT_RUN = 8192
#: highest degree of the controls of unbounded (Gaussian) rocking: the residual of degree-4 controls of Gaussian
#: draws has a skewness of 10-40, too much for the normal interval of a run of a few thousand draws
_UNBOUNDED_DEGREE = 2


def azimuth_monte_carlo(
    latitude,
    beta0,
    gamma0,
    rocking,
    n_samples,
    *,
    rng=None,
    steps_per_trial: int = 1024,
    executor=None,
    progress: bool = False,
    blocks_per_chunk: int = 16,
    control_degree: int = 0,
    pilot_samples: int = 1024,
    min_samples: int = 4096,
    quantiles=montecarlo.QUANTILES,
    limits: budget.Limits | None = None,
) -> AzimuthMonteCarlo:
    """Monte Carlo of ``α − α*`` at independent instants, with bounds (14), (15) and theory.

    With ``control_degree = 0`` it draws ``n_samples`` rocking samples and
    reports their statistics (standard errors from batch means of
    ``steps_per_trial`` samples).  With ``control_degree ≥ 1`` the mean and the
    mean square are control-variate estimates (:class:`TaylorControls` of that
    degree): a pilot of ``pilot_samples`` draws (its own stream) fits the
    coefficients and the fraction of the variance they leave (out of sample);
    the run then draws that fraction of ``n_samples`` (with a margin of 1.5, at
    least ``min_samples``), so that its standard errors are at most those of a
    plain run of ``n_samples``.  When that run is long, a second independent
    pilot of a quarter of its length refits and resizes it (heavy tails show
    only in larger samples).  The estimates are unbiased (the coefficients do
    not depend on the run) and their intervals are the ordinary ones of
    independent draws.  A run that still shows less precision than the
    reference is extended, at most twice.  Where the rocking reaches towards
    the horizon of the tilt correction (:func:`far_rocking_probability`) often
    enough for a plain run of ``n_samples`` to meet it, the controls cannot
    follow the error, and the large errors there would dominate what they
    leave: the controlled run then contains at least 100 such excursions in
    expectation, and where even the plain run would expect fewer, it is the
    plain run of ``n_samples`` (degree 0 in :attr:`AzimuthMonteCarlo.controls`),
    as it is where the pilots plan a controlled run of at least half its length
    and that is more than 8192 draws (a controlled draw costs about 1.4 plain
    ones).

    Parameters
    ----------
    latitude : float
        Latitude φ [rad], ``|φ|`` < π/2.
    beta0, gamma0 : float
        Stable tilts [rad].
    rocking : rocking model
        From :mod:`strapdown.analysis.gyrocompass.rocking`.
    n_samples : int
        Rocking samples (rounded up to whole trials), at least 2; with control
        variates, the plain run whose precision is to be matched [count].
    rng : Generator | SeedSequence | int | None
        Random streams.
    steps_per_trial : int
        Samples per trial (batch size of the standard error; plain runs).
    executor : Executor | dask Client | None
        Where chunks run (the result does not depend on it).
    progress : bool
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    blocks_per_chunk : int
        Blocks per work item (the result does not depend on it).
    control_degree : int
        0 for a plain Monte Carlo, else the highest total degree of the control
        monomials; at most 2 for unbounded (Gaussian) rocking, whose residuals
        after higher-degree controls are too heavy-tailed for the interval of
        a short run (a sinusoid is bounded: any degree).
    pilot_samples : int
        Draws of the pilot (control variates) [count].
    min_samples : int
        Fewest draws of the run (control variates) [count].
    quantiles : sequence of float
        Levels in (0, 1) of the sample quantiles of the result (default
        :data:`strapdown.analysis.core.montecarlo.QUANTILES`); an empty sequence
        skips their order statistics, for a caller that uses the moments only.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s; the time
        of a plain run of ``n_samples`` on one core); a request beyond them
        raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    AzimuthMonteCarlo

    Raises
    ------
    ValueError
        For ``|latitude|`` ≥ 90°, negative sigmas, ``n_samples < 2``, a negative
        ``control_degree``, too small a pilot, non-finite input, or a run whose
        estimate exceeds ``limits`` (naming ``n_samples``).

    References
    ----------
    Hrechka & Koroliov, eqs. (12), (14), (15); Lavenberg & Welch (1981),
    *Management Science* 27(3), 322–335 (control variables).

    Examples
    --------
    >>> from strapdown.analysis.gyrocompass.rocking import GaussianRocking
    >>> mc = azimuth_monte_carlo(math.radians(45), 0.0, 0.0, GaussianRocking(1e-3, 1e-3), 4096, rng=1, steps_per_trial=64)
    >>> lo, hi = mc.result.rms_ci
    >>> bool(lo < mc.theory.rms < hi)
    True
    >>> cv = azimuth_monte_carlo(math.radians(45), 0.0, 0.0, GaussianRocking(1e-3, 1e-3), 10**6, rng=1, control_degree=4)
    >>> cv.controls.samples, cv.controls.plain_equivalent > 10**6
    (4096, True)
    """
    latitude = check_latitude(latitude)
    n_samples = as_int(n_samples, "n_samples", minimum=2)
    budget.check(budget.monte_carlo(n_samples, what=f"`n_samples` = {n_samples:.3g} rocking samples"), limits)
    control_degree = as_int(control_degree, "control_degree", minimum=0)
    steps = min(as_int(steps_per_trial, "steps_per_trial", minimum=1), max(1, n_samples // 2))
    kernel = AzimuthErrorKernel(latitude, beta0, gamma0, rocking, n_steps=steps)
    theory = second_order_theory(latitude, kernel.beta0, kernel.gamma0, rocking.sigma_xi, rocking.sigma_eta, kappa_xi=rocking.kappa, kappa_eta=rocking.kappa)
    scale = theory.rms_first_order if theory.rms_first_order > 0 else 1e-12
    bounds = bound14(latitude, kernel.beta0, kernel.gamma0, rocking.sigma_xi, rocking.sigma_eta), bound15(latitude, rocking.sigma_xi)
    options = dict(blocks_per_chunk=blocks_per_chunk, executor=executor, scale=scale, progress=progress, quantiles=levels(quantiles, "quantiles"))
    if control_degree == 0:
        n_trials = max(2, -(-n_samples // steps))
        result = montecarlo.run(kernel, n_trials, rng=rng, trials_per_block=max(1, 65536 // steps), **options)
        return AzimuthMonteCarlo(result, *bounds, theory)
    pilot_samples = as_int(pilot_samples, "pilot_samples", minimum=2)
    min_samples = as_int(min_samples, "min_samples", minimum=2)
    root = montecarlo.root_seed_sequence(rng)
    degree = control_degree if isinstance(rocking, SineRocking) else min(control_degree, _UNBOUNDED_DEGREE)
    p = len(TaylorControls.for_rocking(rocking, degree).exponents)
    if pilot_samples < 2 * p + 4:
        raise ValueError(f"Expected `pilot_samples` >= {2 * p + 4} for degree {degree}, got {pilot_samples}")
    far = far_rocking_probability(latitude, kernel.beta0, kernel.gamma0, rocking)

    def plain(pilots):  # the plain run, with at least 512 batches for its standard errors
        n_steps = max(1, min(steps, n_samples // 512))
        n_trials = max(2, -(-n_samples // n_steps))
        result = montecarlo.run(replace(kernel, n_steps=n_steps), n_trials, rng=montecarlo.block_seed(root, 1), trials_per_block=max(1, 65536 // n_steps), **options)
        return AzimuthMonteCarlo(result, *bounds, theory, ControlVariateSummary(0, pilots, result.n_samples, n_samples, float(result.n_samples)))

    if _RARE_VISITS <= n_samples * far < _FAR_VISITS:
        # excursions towards the horizon that a plain run would meet, too rare for 100 of them in a shorter
        # run: their large errors would dominate the variance the controls leave, unseen
        return plain(0)
    pilot_kernel = replace(kernel, n_steps=1)

    def sized(controls):
        size = max(min_samples, math.ceil(_SIZE_MARGIN * controls.variance_ratio * n_samples))
        return max(size, math.ceil(_FAR_VISITS / far)) if n_samples * far >= _FAR_VISITS else size

    controls = _fit_controls(pilot_kernel, degree, pilot_samples, montecarlo.block_seed(root, 0))
    size, pilots = sized(controls), pilot_samples
    if size >= _NOT_SHORTER * n_samples > _SHORT_RUN:  # the controls would save little on a long run: the plain run
        return plain(pilots)
    if size > _LONG_RUN * pilot_samples:  # a long run: fit and size it on a larger, independent pilot
        second = math.ceil(size / 4)
        controls = _fit_controls(pilot_kernel, degree, second, montecarlo.block_seed(root, 2))
        size, pilots = max(size, sized(controls)), pilots + second
        if size >= _NOT_SHORTER * n_samples > _SHORT_RUN:
            return plain(pilots)
    kernel = replace(kernel, n_steps=1, controls=controls)
    for attempt in range(_EXTENSIONS + 1):  # blocks are prefix-stable: a longer run extends the shorter one
        raw = montecarlo.run(kernel, size, rng=montecarlo.block_seed(root, 1), trials_per_block=_CONTROL_BLOCK, **options)
        result = montecarlo.controlled(raw, offsets=controls.offsets)
        worth = _plain_equivalent(raw, result)
        if worth >= n_samples or attempt == _EXTENSIONS:
            break
        size = math.ceil(size * _SIZE_MARGIN * n_samples / worth)
    summary = ControlVariateSummary(degree, pilots, size, n_samples, worth)
    return AzimuthMonteCarlo(result, *bounds, theory, summary)


def far_rocking_probability(latitude, beta0, gamma0, rocking) -> float:
    """Probability that the rocking leaves the tilts where Taylor controls of the error can be trusted.

    The tilt correction ``σ = arg(A + iB)`` is singular where ``A + iB = 0``:
    at ``β = 0``, ``γ = φ − π/2`` (for φ > 0), a tilt ``π/2 − |φ|`` from level
    and at least ``d = π/2 − |φ| − |β0| − |γ0|`` from the stable tilts.  Near it
    the error turns fast and wraps, which no polynomial follows.  This is
    ``P(|ξ| > ρ or |η| > ρ)`` with ``ρ = 0.9 d`` (1 when ``d ≤ 0``), exact for
    the rocking law (ξ, η independent).

    Parameters
    ----------
    latitude : float
        Latitude φ [rad], ``|φ|`` < π/2.
    beta0, gamma0 : float
        Stable tilts [rad].
    rocking : GaussianRocking | SineRocking | NarrowbandRocking
        The rocking at independent instants.

    Returns
    -------
    float
        In [0, 1] [dimensionless].

    References
    ----------
    Hrechka & Koroliov, eq. (2) (A, B).

    >>> from strapdown.analysis.gyrocompass.rocking import SineRocking
    >>> far_rocking_probability(math.radians(80), 0.0, 0.0, SineRocking(math.radians(1), math.radians(1)))
    0.0
    """
    latitude = check_latitude(latitude)
    d = 0.5 * math.pi - abs(latitude) - abs(as_float(beta0, "beta0")) - abs(as_float(gamma0, "gamma0"))
    if d <= 0.0:
        return 1.0
    rho = _TRUSTED_FRACTION * d
    inside = 1.0
    for sigma in (rocking.sigma_xi, rocking.sigma_eta):
        if sigma > 0.0:
            inside *= rocking.standard_moment(0, rho / sigma)
    return max(0.0, 1.0 - inside)


def _fit_controls(kernel: AzimuthErrorKernel, degree: int, n: int, seed) -> TaylorControls:
    """Fit :class:`TaylorControls` of ``degree`` on ``n`` pilot draws of the kernel's error (one block, stream ``seed``)."""
    basis = TaylorControls.for_rocking(kernel.rocking, degree)
    p = len(basis.exponents)
    if n < 2 * p + 4:
        raise ValueError(f"Expected `pilot_samples` >= {2 * p + 4} for degree {degree}, got {n}")
    xi, eta = kernel.rocking.sample(np.random.default_rng(seed), n, 1, None)
    return basis.fitted(xi, eta, azimuth_error(xi.ravel(), eta.ravel(), latitude=kernel.latitude, beta0=kernel.beta0, gamma0=kernel.gamma0))


def _plain_equivalent(raw: montecarlo.MonteCarloResult, controlled: montecarlo.MonteCarloResult) -> float:
    """Draws a plain run needs for the controlled standard errors (the smaller over mean and mean square)."""
    plain_mean = (raw.mean_ci[1] - raw.mean) / montecarlo.Z95
    out = math.inf
    for plain, cv in ((plain_mean, controlled.aux_std_error[0]), (raw.mse_std_error, controlled.mse_std_error)):
        if cv > 0.0:
            out = min(out, raw.n_samples * (plain / cv) ** 2)
    return out
