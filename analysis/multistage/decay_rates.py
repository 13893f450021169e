"""Exponential rates of the first-variant stage, checked against simulation.

The perturbation equations (3.1) of Plotnikov (1999), ``2z' = z∘ω − kz − y``,
``y' = lz``, are linear in ``x = (z, y) ∈ R⁸``.  This module gives

* the state matrix for a constant body rate ω, and the exact exponential rate
  (slowest real part) from its eigenvalues;
* the rate at rest in closed form, from the roots of ``2s² + ks + l``
  (:mod:`strapdown.derivations.multistage.lyapunov_function`): ``k/4`` when ``k² < 8l``;
* a guaranteed rate for any time-varying rate with ``|ω(t)| ≤ ϖ``, from the
  strict Lyapunov function ``W = V + ε z·y`` (:mod:`strapdown.derivations.multistage.lyapunov_function`);
* the rate measured on a simulation of the stage (:func:`strapdown.analysis.multistage.stages.run_stage`
  with the external reference), to check the three.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from ..core import budget
from ..core import quaternion as quat
from ..core.cache import compiled
from ..core.validation import as_float, as_vector, positive
from .stages import Stage, run_stage

__all__ = ["perturbation_matrix", "exact_rate", "rest_rate", "strict_rate_bound", "simulated_rate", "RateCheck", "rate_checks"]


def perturbation_matrix(k, l, omega=(0.0, 0.0, 0.0)) -> np.ndarray:
    """State matrix A of (3.1) for a constant body rate: ``x' = A x``, ``x = (z, y)``.

    Parameters
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    omega : array_like, shape (3,)
        Body rate ω [rad/s].

    Returns
    -------
    ndarray, shape (8, 8)

    References
    ----------
    Plotnikov (1999), eq. (3.1).
    """
    k, l = as_float(k, "k"), as_float(l, "l")
    w = quat.vector_to_quat(as_vector(omega, "omega"))
    right = quat.multiply(np.eye(4), w).T  # column i: e_i ∘ ω
    a = np.zeros((8, 8))
    a[:4, :4] = 0.5 * (right - k * np.eye(4))
    a[:4, 4:] = -0.5 * np.eye(4)
    a[4:, :4] = l * np.eye(4)
    return a


def exact_rate(k, l, omega=(0.0, 0.0, 0.0)) -> float:
    """Exponential decay rate ``−max Re λ(A)`` [1/s] for a constant body rate.

    Parameters
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    omega : array_like, shape (3,)
        Body rate ω [rad/s].

    Returns
    -------
    float
    """
    return float(-np.linalg.eigvals(perturbation_matrix(k, l, omega)).real.max())


def _rest_roots_build():
    from ...derivations.multistage.lyapunov_function import SYMBOLS, derive

    return (SYMBOLS.k, SYMBOLS.l), tuple(derive().rate_roots)


def rest_rate(k, l) -> float:
    """Rate at rest from the roots of ``2s² + ks + l`` [1/s]: ``k/4`` if ``k² < 8l``.

    The roots come from the symbolic derivation
    (:func:`strapdown.analysis.core.cache.compiled`: derived once, then served
    from the cache).

    Parameters
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].

    Returns
    -------
    float

    Examples
    --------
    >>> rest_rate(0.01, 5e-5)
    0.0025
    """
    k, l = as_float(k, "k"), as_float(l, "l")
    roots = compiled("multistage:lyapunov:rest-roots:v1", _rest_roots_build)(k + 0j, l + 0j)
    return float(-np.asarray(roots, dtype=complex).real.max())


def _strict_build():
    from ...derivations.multistage.lyapunov_function import SYMBOLS, strict_bound_matrices

    s = SYMBOLS
    m, p_plus, p_minus = strict_bound_matrices(s.k, s.l, s.epsilon, s.varpi)
    return (s.k, s.l, s.epsilon, s.varpi), tuple(m) + tuple(p_plus) + tuple(p_minus)


def strict_rate_bound(k, l, omega_max, *, samples: int = 400) -> tuple:
    """Guaranteed decay rate of ``|x|`` for any body rate with ``|ω(t)| ≤ ϖ``.

    With ``W = V + εz·y`` and ``ξ = (|z|, |y|)``: ``−W' ≥ ξᵀMξ`` and
    ``W ≤ ξᵀP₊ξ``.  If ``P₋ > 0`` (so W is positive definite) and γ is the
    smallest generalised eigenvalue of ``(M, P₊)``, then ``M − γP₊ ⪰ 0``,
    ``W' ≤ −γW`` and ``|x(t)| ≤ C e^{−γt/2}``.  ε is chosen on a grid to
    maximise γ.

    Parameters
    ----------
    k : float
        Position gain [1/s], > 0.
    l : float
        Integral gain [1/s²], > 0.
    omega_max : float
        Bound ϖ on ``|ω|`` [rad/s], >= 0.
    samples : int
        Grid size for ε.

    Returns
    -------
    rate : float
        γ/2 [1/s] (a lower bound of the true rate).
    eps : float
        The ε that attains it.
    """
    k, l = positive(k, "k"), positive(l, "l")
    wbar = as_float(omega_max, "omega_max")
    if wbar < 0:
        raise ValueError(f"Expected `omega_max` >= 0, got {wbar:g}")
    f = compiled("multistage:lyapunov:strict-bound-matrices:v1", _strict_build)
    eps_hi = min(8 * k * l / (8 * l + (k + wbar) ** 2), np.sqrt(2 * l), k)
    best = (0.0, 0.0)
    for eps in np.linspace(0.0, eps_hi, samples + 2)[1:-1]:
        parts = np.array(f(k, l, eps, wbar), dtype=float)
        m, p_plus, p_minus = parts[0:4].reshape(2, 2), parts[4:8].reshape(2, 2), parts[8:12].reshape(2, 2)
        if np.linalg.eigvalsh(p_minus).min() <= 0:
            continue
        gamma = float(eigh(m, p_plus, eigvals_only=True).min())
        if gamma > 0 and gamma / 2 > best[0]:
            best = (gamma / 2, float(eps))
    return float(best[0]), best[1]


def simulated_rate(k, l, omega=(0.0, 0.0, 0.0), *, step: float = 0.05, duration=None, z0=(0.0, 0.02, -0.01, 0.015), limits: budget.Limits | None = None) -> float:
    """Decay rate of ``V = l|z|² + ½|y|²`` measured on a simulation of the stage [1/s].

    The body turns at the constant rate ω relative to a fixed frame; stage 1 is
    fed with the exact attitude as external reference (c = 1, ρ = 0) and starts
    from ``ν(0) = μ(0) + z0``.  The rate is half the slope of ``log V`` fitted by
    least squares over the second half of the run.

    Parameters
    ----------
    k : float
        Position gain [1/s], > 0.
    l : float
        Integral gain [1/s²], > 0.
    omega : array_like, shape (3,)
        Body rate [rad/s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    duration : float, optional
        Run length [s]; default ``14 / rest_rate``.
    z0 : array_like, shape (4,)
        Initial perturbation.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        For bad arguments, or a run whose estimated memory or time exceeds ``limits``
        (naming ``duration`` and ``step``).
    """
    k, l = positive(k, "k"), positive(l, "l")
    w = as_vector(omega, "omega")
    h = positive(step, "step")
    end = 14.0 / rest_rate(k, l) if duration is None else positive(duration, "duration")
    steps = np.ceil(end / h)
    budget.check(budget.multistage(steps, what=f"`duration` = {end:.3g} s over `step` = {h:g} s ({steps:.3g} steps)"), limits)
    n = int(steps)
    t = np.arange(n + 1) * h
    mu = quat.rotvec_to_quat(t[:, None] * w)
    dq = np.broadcast_to(quat.rotvec_to_quat(w * h), (n, 4))
    stage = Stage.constant(k, l, "external", rho=0.0)
    nu, y = run_stage(stage, h, dq, reference=mu, initial=mu[0] + np.asarray(z0, dtype=float))
    z = nu - mu
    v = l * np.sum(z * z, axis=1) + 0.5 * np.sum(y * y, axis=1)
    sel = t >= 0.5 * t[-1]
    slope = np.polyfit(t[sel], np.log(v[sel]), 1)[0]
    return float(-slope / 2.0)


@dataclass(frozen=True)
class RateCheck:
    """The four rates of one case (:func:`rate_checks`) [1/s].

    Attributes
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    omega : tuple
        Body rate [rad/s].
    rest : float
        :func:`rest_rate`.
    exact : float
        :func:`exact_rate`.
    simulated : float
        :func:`simulated_rate`.
    guaranteed : float
        :func:`strict_rate_bound`.
    """

    k: float
    l: float
    omega: tuple
    rest: float
    exact: float
    simulated: float
    guaranteed: float


def rate_checks(cases, *, step: float = 0.5, periods: float = 14.0) -> tuple:
    """Rest, exact, simulated and guaranteed rates for each ``(k, l, omega)``.

    Parameters
    ----------
    cases : sequence of (k, l, omega)
        Gains [1/s], [1/s²] and body rate [rad/s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).
    periods : float
        Length of the simulation in units of ``1/exact rate``.

    Returns
    -------
    tuple of RateCheck
    """
    out = []
    for k, l, w in cases:
        ex = exact_rate(k, l, w)
        sim = simulated_rate(k, l, w, step=step, duration=periods / ex)
        bound, _ = strict_rate_bound(k, l, float(np.linalg.norm(w)))
        out.append(RateCheck(float(k), float(l), tuple(float(x) for x in w), rest_rate(k, l), ex, sim, bound))
    return tuple(out)
