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
:mod:`strapdown.analysis.core.montecarlo`.

References
----------
Hrechka & Koroliov, eqs. (2), (4), (11)–(16).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from ..core import montecarlo
from ..core.validation import as_float, as_int, in_open_interval, nonnegative
from .rocking import GaussianRocking, NarrowbandRocking, SineRocking

__all__ = [
    "tilt_correction",
    "azimuth_error",
    "bound14",
    "bound15",
    "second_order_theory",
    "AzimuthErrorKernel",
    "AzimuthMonteCarlo",
    "azimuth_monte_carlo",
    "check_latitude",
    "gradient",
]


def check_latitude(latitude) -> float:
    """Return ``latitude`` [rad] if |φ| < π/2, else raise ValueError naming it."""
    return in_open_interval(latitude, "latitude", -math.pi / 2, math.pi / 2, text="(-π/2, π/2) rad, i.e. |latitude| < 90°")


def _cos_from_sin(angle, sine):
    """``cos(angle)`` as ``√(1 − sin²)`` (one transcendental call instead of two on the hot path).

    Used for |angle| ≤ π/4, where the cosine is at least 1/√2 and the square
    root adds no cancellation (error ≤ 2 ulp); larger tilts, rare under
    rocking, fall back to ``np.cos``.
    """
    if not isinstance(sine, np.ndarray) or sine.ndim == 0:
        return np.cos(angle)
    c = sine * sine
    np.subtract(1.0, c, out=c)
    np.sqrt(c, out=c)
    wide = np.abs(angle) > _QUARTER_PI
    if wide.any():
        c[wide] = np.cos(angle[wide])
    return c


_QUARTER_PI = 0.25 * math.pi


def _components(beta, gamma, sphi, cphi):
    sg = np.sin(gamma)
    A = _cos_from_sin(gamma, sg)
    A *= cphi
    B = np.sin(beta)
    cb = _cos_from_sin(beta, B)
    cb *= sg
    cb *= sphi
    A += cb
    B *= sphi
    return A, B


def tilt_correction(beta, gamma, latitude):
    """Tilt correction ``σ = arg(A + iB)`` [rad] (= ``arctan(B/A)`` for A > 0).

    Parameters
    ----------
    beta : array_like — tilt β [rad]
    gamma : array_like — tilt γ [rad]
    latitude : float — latitude φ [rad], |φ| < π/2

    References
    ----------
    Hrechka & Koroliov, eq. (2).

    >>> round(float(tilt_correction(0.01, 0.0, math.radians(45.0))), 6)
    0.01
    """
    latitude = check_latitude(latitude)
    A, B = _components(np.asarray(beta, dtype=float), np.asarray(gamma, dtype=float), math.sin(latitude), math.cos(latitude))
    return np.arctan2(B, A)


def azimuth_error(xi, eta, *, latitude, beta0, gamma0, beta_ref=None, gamma_ref=None):
    """Azimuth error ``σ(β0 + ξ, γ0 + η) − σ(β_ref, γ_ref)`` [rad], wrapped to (−π, π].

    Parameters
    ----------
    xi, eta : array_like — rocking ξ, η [rad]
    latitude : float — latitude φ [rad]
    beta0, gamma0 : float — stable tilts β0, γ0 [rad]
    beta_ref, gamma_ref : array_like, optional — tilts used by the estimate [rad]
        (default β0, γ0: the estimate (11); sample means give (16))

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
    As, Bs = _components(np.asarray(beta_ref, dtype=float), np.asarray(gamma_ref, dtype=float), sphi, cphi)
    return _error(xi + beta0, eta + gamma0, sphi, cphi, As, Bs)


def _error(beta, gamma, sphi, cphi, As, Bs):
    """``arg((A + iB)(A* − iB*))`` with in-place arithmetic (the Monte Carlo hot path)."""
    A, B = _components(beta, gamma, sphi, cphi)
    num = B * As
    num -= A * Bs
    A *= As
    B *= Bs
    A += B
    if isinstance(num, np.ndarray):
        return np.arctan2(num, A, out=num)
    return np.arctan2(num, A)


# --------------------------------------------------------------------- theory
@cache
def _theory():
    """Lambdified derivations: coefficient values and the generic moments."""
    import sympy as sp

    from ...derivations.gyrocompass import azimuth_error as g

    As, Bs, a, b = g.coefficient_symbols(3)
    coeff_syms = [As, Bs, *a.values(), *b.values()]
    values = g.coefficient_values(3)
    coeff_fn = sp.lambdify((g.phi, g.beta0, g.gamma0), [values[s] for s in coeff_syms], modules="math")
    moments = (g.D_xi, g.D_eta, g.kappa_xi, g.kappa_eta)
    args = (*coeff_syms, *moments)
    first = sp.lambdify(args, g.first_order_mse(generic=True), modules="math", cse=True)
    bias = sp.lambdify(args, g.bias_second_order(generic=True), modules="math", cse=True)
    mse4 = sp.lambdify(args, g.mse_fourth_order(generic=True), modules="math", cse=True)
    # The radicand Dζ1·Dζ2 of (14) is a product of variances (≥ 0); evaluated in expanded
    # form it can round to about −1e-20 when one variance vanishes, so clip it at zero.
    sqrt_nonneg = {"sqrt": lambda x: np.sqrt(np.maximum(x, 0.0))}
    b14 = sp.lambdify((g.phi, g.beta0, g.gamma0, g.D_xi, g.D_eta), g.bound14_rocking(), modules=[sqrt_nonneg, "numpy"])
    return coeff_fn, first, bias, mse4, b14


def _sigmas(sigma_xi, sigma_eta):
    return nonnegative(sigma_xi, "sigma_xi"), nonnegative(sigma_eta, "sigma_eta")


def bound14(latitude, beta0, gamma0, sigma_xi, sigma_eta) -> float:
    """Bound (14) on the rms azimuth error δ [rad], with ξ, η independent.

    Parameters
    ----------
    latitude : float — latitude φ [rad]
    beta0, gamma0 : float — stable tilts [rad]
    sigma_xi, sigma_eta : float — standard deviations of ξ, η [rad]

    References
    ----------
    Hrechka & Koroliov, eq. (14) (Dζ1, Dζ2 from (7), (10) as derived).

    >>> round(bound14(math.radians(45), 0.0, 0.0, 0.01, 0.02), 12)
    0.01
    """
    latitude = check_latitude(latitude)
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    sx, se = _sigmas(sigma_xi, sigma_eta)
    return math.sqrt(float(_theory()[4](latitude, beta0, gamma0, sx * sx, se * se)))


def bound15(latitude, sigma_xi) -> float:
    """Bound (15): ``δ ≤ tan φ √Dξ`` [rad].

    Parameters
    ----------
    latitude : float — latitude φ [rad]
    sigma_xi : float — standard deviation of ξ [rad]

    References
    ----------
    Hrechka & Koroliov, eq. (15).

    >>> round(bound15(math.radians(45), 0.01), 12)
    0.01
    """
    latitude = check_latitude(latitude)
    return abs(math.tan(latitude)) * nonnegative(sigma_xi, "sigma_xi")


def second_order_theory(latitude, beta0, gamma0, sigma_xi, sigma_eta, *, kappa_xi: float = 3.0, kappa_eta: float = 3.0) -> dict:
    """Moments of the azimuth error from the Taylor series of σ (not in the paper).

    Parameters
    ----------
    latitude : float — latitude φ [rad]
    beta0, gamma0 : float — stable tilts [rad]
    sigma_xi, sigma_eta : float — standard deviations of ξ, η [rad]
    kappa_xi, kappa_eta : float — ``E ξ⁴/(E ξ²)²`` (3 Gaussian, 1.5 sinusoid)

    Returns
    -------
    dict
        ``rms_first_order`` (exact to second order in the rocking),
        ``bias`` (``E(σ − σ*)`` to second order), ``rms`` (``√E(σ − σ*)²``
        with the mean square to fourth order) [rad].

    >>> t = second_order_theory(math.radians(45), 0.0, 0.0, 0.01, 0.0)
    >>> round(t["rms_first_order"], 12), t["bias"]
    (0.01, 0.0)
    """
    latitude = check_latitude(latitude)
    beta0, gamma0 = as_float(beta0, "beta0"), as_float(gamma0, "gamma0")
    sx, se = _sigmas(sigma_xi, sigma_eta)
    coeff_fn, first, bias, mse4, _ = _theory()
    args = (*coeff_fn(latitude, beta0, gamma0), sx * sx, se * se, as_float(kappa_xi, "kappa_xi"), as_float(kappa_eta, "kappa_eta"))
    m1, m4 = first(*args), mse4(*args)
    return {"rms_first_order": math.sqrt(max(m1, 0.0)), "bias": float(bias(*args)), "rms": math.sqrt(max(m4, 0.0)), "mse_first_order": m1, "mse": m4}


# ---------------------------------------------------------------- Monte Carlo
@dataclass(frozen=True)
class AzimuthErrorKernel:
    """Monte Carlo kernel: azimuth errors of ``n_trials`` rocking records.

    Parameters
    ----------
    latitude : float — latitude φ [rad]
    beta0, gamma0 : float — stable tilts [rad]
    rocking : GaussianRocking | SineRocking | NarrowbandRocking — rocking model
    n_steps : int — samples per trial
    dt : float or None — sample interval [s]; None for independent instants
    estimate : str
        ``"known"``: the error ``σ(β0 + ξ, γ0 + η) − σ*`` of (12) at every
        sample (α* from the true β0, γ0, eq. (11));
        ``"sample-mean"``: the alignment error ``σ(β̂0, γ̂0) − σ*`` of the
        estimate (16) from the ``n_steps`` samples of a trial (one error per
        trial).  With one sample it is the error of (12).

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

    def __post_init__(self):
        object.__setattr__(self, "latitude", check_latitude(self.latitude))
        object.__setattr__(self, "beta0", as_float(self.beta0, "beta0"))
        object.__setattr__(self, "gamma0", as_float(self.gamma0, "gamma0"))
        object.__setattr__(self, "n_steps", as_int(self.n_steps, "n_steps", minimum=1))
        if not isinstance(self.rocking, (GaussianRocking, SineRocking, NarrowbandRocking)):
            raise TypeError(f"Expected `rocking` to be a rocking model, got {type(self.rocking).__name__}")
        if self.estimate not in ("known", "sample-mean"):
            raise ValueError(f"Expected `estimate` in ('known', 'sample-mean'), got {self.estimate!r}")
        if self.estimate == "sample-mean" and self.n_steps < 2:
            raise ValueError(f"Expected `n_steps` >= 2 for sample-mean estimates, got {self.n_steps}")

    def __call__(self, n_trials: int, rng):
        xi, eta = self.rocking.sample(rng, n_trials, self.n_steps, self.dt)
        sphi, cphi = math.sin(self.latitude), math.cos(self.latitude)
        xi += self.beta0
        eta += self.gamma0
        if self.estimate == "known":
            As, Bs = _components(np.float64(self.beta0), np.float64(self.gamma0), sphi, cphi)
            return _error(xi, eta, sphi, cphi, As, Bs)
        b_hat, g_hat = xi.mean(axis=1), eta.mean(axis=1)
        dxi = xi.var(axis=1)  # 1/n normalisation, as in (16)
        deta = eta.var(axis=1)
        As, Bs = _components(np.float64(self.beta0), np.float64(self.gamma0), sphi, cphi)
        errors = _error(b_hat, g_hat, sphi, cphi, As, Bs)[:, None]
        b14sq = np.broadcast_to(_theory()[4](self.latitude, b_hat, g_hat, dxi, deta), dxi.shape)
        b15sq = math.tan(self.latitude) ** 2 * dxi
        return errors, np.stack([b14sq, b15sq], axis=-1)


@dataclass(frozen=True)
class AzimuthMonteCarlo:
    """Monte Carlo of the azimuth error with the bounds and the theory of the same case [rad]."""

    result: montecarlo.MonteCarloResult
    bound14: float
    bound15: float
    theory: dict

    def as_dict(self, *, degrees: bool = True) -> dict:
        """Flat dictionary (angles in degrees with ``degrees``), as the CLI prints it."""
        k = math.degrees(1.0) if degrees else 1.0
        r = self.result
        unit = "deg" if degrees else "rad"
        q = {f"{level:g}": v * k for level, v in r.quantiles.items()}
        return {
            f"rms_error_{unit}": r.rms * k,
            f"rms_ci_{unit}": [r.rms_ci[0] * k, r.rms_ci[1] * k],
            f"mean_error_{unit}": r.mean * k,
            f"mean_ci_{unit}": [r.mean_ci[0] * k, r.mean_ci[1] * k],
            f"bound14_{unit}": self.bound14 * k,
            f"bound15_{unit}": self.bound15 * k,
            f"theory_rms_first_order_{unit}": self.theory["rms_first_order"] * k,
            f"theory_rms_second_order_{unit}": self.theory["rms"] * k,
            f"theory_bias_{unit}": self.theory["bias"] * k,
            f"quantiles_{unit}": q,
            "bound14_holds": r.covers(self.bound14),
            "bound15_holds": r.covers(self.bound15),
            "samples": r.n_samples,
            "trials": r.n_trials,
        }


def azimuth_monte_carlo(latitude, beta0, gamma0, rocking, n_samples, *, rng=None, steps_per_trial: int = 1024, executor=None, progress: bool = False, blocks_per_chunk: int = 16) -> AzimuthMonteCarlo:
    """Monte Carlo of ``α − α*`` at independent instants, with bounds (14), (15) and theory.

    Parameters
    ----------
    latitude : float — latitude φ [rad], |φ| < π/2
    beta0, gamma0 : float — stable tilts [rad]
    rocking : rocking model (:mod:`strapdown.analysis.gyrocompass.rocking`)
    n_samples : int — rocking samples (rounded up to whole trials), at least 2
    rng : Generator | SeedSequence | int | None — random streams
    steps_per_trial : int — samples per trial (batch size of the standard error)
    executor : Executor | dask Client | None — where chunks run (the result does not depend on it)
    progress : bool — tqdm progress bar on stderr
    blocks_per_chunk : int — blocks per work item (the result does not depend on it)

    Returns
    -------
    AzimuthMonteCarlo

    Raises
    ------
    ValueError
        For |latitude| ≥ 90°, negative sigmas, ``n_samples < 2`` or non-finite input.

    Examples
    --------
    >>> from strapdown.analysis.gyrocompass.rocking import GaussianRocking
    >>> mc = azimuth_monte_carlo(math.radians(45), 0.0, 0.0, GaussianRocking(1e-3, 1e-3), 4096, rng=1, steps_per_trial=64)
    >>> lo, hi = mc.result.rms_ci
    >>> bool(lo < mc.theory["rms"] < hi)
    True
    """
    latitude = check_latitude(latitude)
    n_samples = as_int(n_samples, "n_samples", minimum=2)
    steps = min(as_int(steps_per_trial, "steps_per_trial", minimum=1), max(1, n_samples // 2))
    kernel = AzimuthErrorKernel(latitude, beta0, gamma0, rocking, n_steps=steps)
    theory = second_order_theory(latitude, kernel.beta0, kernel.gamma0, rocking.sigma_xi, rocking.sigma_eta, kappa_xi=rocking.kappa, kappa_eta=rocking.kappa)
    n_trials = max(2, -(-n_samples // steps))
    scale = theory["rms_first_order"] if theory["rms_first_order"] > 0 else 1e-12
    result = montecarlo.run(kernel, n_trials, rng=rng, trials_per_block=max(1, 65536 // steps), blocks_per_chunk=blocks_per_chunk, executor=executor, scale=scale, progress=progress)
    return AzimuthMonteCarlo(result, bound14(latitude, kernel.beta0, kernel.gamma0, rocking.sigma_xi, rocking.sigma_eta), bound15(latitude, rocking.sigma_xi), theory)


def gradient(latitude, beta0, gamma0) -> tuple:
    """``(∂σ/∂β, ∂σ/∂γ)`` at (β0, γ0) [rad/rad]: the first-order sensitivity of the azimuth.

    >>> g = gradient(math.radians(45), 0.0, 0.0)
    >>> round(g[0], 12), round(g[1], 12)
    (1.0, 0.0)
    """
    latitude = check_latitude(latitude)
    c = _theory()[0](latitude, as_float(beta0, "beta0"), as_float(gamma0, "gamma0"))
    As, Bs, a10, a01, b10, b01 = c[0], c[1], c[2], c[3], c[2 + 9], c[3 + 9]
    r2 = As * As + Bs * Bs
    return (As * b10 - Bs * a10) / r2, (As * b01 - Bs * a01) / r2
