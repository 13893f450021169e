"""The scrolling error of the position algorithm: closed form, in a vibration environment, and by simulation.

Under a vibration line each step of the integration, started from the exact
state, adds on average ``e_v H`` to the velocity error and ``e_r H`` to the
position error (exact minus algorithm, package docstring "Errors"): ``e_v`` is
the velocity algorithm's rectification (sculling) error, ``e_r`` the
*scrolling* error of the position algorithm, both constant vectors to second
order in the amplitudes (:mod:`strapdown.derivations.navigation.position_algorithm`
derives them)::

    e_r = (h²/2) Re((Â × conj B̂) Z(ωh)),

with the line's rate and specific-force amplitudes ``Â`` [rad/s], ``B̂`` [m/s²]
as the algorithm receives them (through the sensors' responses).  Lines of one
frequency are coherent and add before the product; a spectrum adds
``Â × conj B̂ = 2 conj w(P_ωa) df`` over its band, integrated like the coning
drift (:mod:`strapdown.analysis.vibration.drift`).

:func:`simulated_scrolling` measures ``e_v`` and ``e_r`` by parallel
computation: each step of the algorithms (:mod:`~strapdown.analysis.navigation.integration`)
on the exact increments of classical sculling
(:class:`~strapdown.analysis.coning.sculling_motion.ScullingMotion`) against the
exact velocity and position gained over that step from the exact state (the
closed-form apparent velocity, and its integral by 12-point Gauss–Legendre
quadrature over the step), averaged over the steps.

Public API
----------
.. autosummary::

   scrolling_function
   ScullingErrors
   sculling_errors
   simulated_scrolling
   environment_scrolling
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ...derivations.navigation.position_algorithm import X, scrolling_kernel
from ..coning.drift_theory import algorithm_key
from ..coning.sculling_motion import ScullingMotion
from ..coning.simulator import sample_increments, step_count
from ..core import budget
from ..core import quaternion as quat
from ..core.quadrature import integrate as quadrature
from ..core.validation import positive
from ..vibration.drift import QUADRATURE_RTOL, coherent_groups
from ..vibration.environment import Environment
from .integration import step_increments

__all__ = ["scrolling_function", "ScullingErrors", "sculling_errors", "simulated_scrolling", "environment_scrolling"]


@functools.lru_cache(maxsize=64)
def _kernel_for(key: str, algorithm: Algorithm):
    import sympy as sp

    k = scrolling_kernel(algorithm)
    closed = sp.lambdify(X, k.function, "numpy")
    re = np.array([float(c) for c in k.taylor_real][::-1])
    im = np.array([float(c) for c in k.taylor_imag][::-1])
    return closed, re, im, k.switch()


def scrolling_function(algorithm: Algorithm):
    """``Z(x)`` of the algorithm's velocity and position algorithms (complex), x = ωh > 0.

    The Taylor polynomial below the switch where the closed form cancels, the
    closed form above (:meth:`strapdown.derivations.navigation.position_algorithm.ScrollingKernel.switch`).

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm.

    Returns
    -------
    callable
        ``Z(x)`` for an array x [rad], complex.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> Z = scrolling_function(get("one-sample"))
    >>> round(float(Z(np.array([1e-3])).imag[0]) / 1e-3, 6)        # Im Z ≈ −x/12
    -0.083333
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    closed, re, im, switch = _kernel_for(algorithm_key(algorithm), algorithm)

    def Z(x):
        x = np.asarray(x, dtype=float)
        small = x < switch
        xs = np.where(small, x, 1.0)
        xl = np.where(small, 1.0, x)
        with np.errstate(all="ignore"):
            big = np.asarray(closed(xl), dtype=complex) * np.ones_like(xl)
        poly = np.polyval(re, xs) + 1j * np.polyval(im, xs)
        return np.where(small, poly, big)

    return Z


@dataclass(frozen=True)
class ScullingErrors:
    """Rectification and scrolling errors of classical sculling, along ``e_r × e_a`` (exact minus algorithm).

    Attributes
    ----------
    velocity_rate : float
        ``e_v`` [m/s²].
    position_rate : float
        ``e_r`` [m/s].
    """

    velocity_rate: float
    position_rate: float


def _classical_product(motion: ScullingMotion) -> complex:
    """``Â × conj B̂`` along ``e_r × e_a``: ``i θ₀ ν A e^{−i(φ_a − φ_θ)}``."""
    return 1j * motion.angle_amplitude * motion.nu * motion.accel_amplitude * np.exp(-1j * (motion.accel_phase - motion.angle_phase))


def sculling_errors(algorithm: Algorithm, motion: ScullingMotion, sample_interval: float) -> ScullingErrors:
    """``e_v`` and ``e_r`` of classical sculling in closed form, to first order in θ₀ A.

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm (velocity: its dual extension; position: the N-sample position algorithm).
    motion : ScullingMotion
        Classical sculling.
    sample_interval : float
        h [s].

    Returns
    -------
    ScullingErrors

    References
    ----------
    :mod:`strapdown.derivations.navigation.position_algorithm` (derivation); Savage (1998), part 2.
    """
    h = positive(sample_interval, "sample_interval")
    x = motion.nu * h
    c = _classical_product(motion)
    Zv = _velocity_kernel(algorithm, x)
    e_v = float(np.real(c * Zv)) * h / (2.0 * algorithm.samples)
    e_r = 0.5 * h * h * float(np.real(c * scrolling_function(algorithm)(np.array([x]))[0]))
    return ScullingErrors(e_v, e_r)


def _velocity_kernel(algorithm: Algorithm, x: float) -> complex:
    """``K_v − K_v,alg`` at x (numerically, closed form of each kernel)."""
    n = algorithm.samples
    a = 1j * x

    def interval(lo, hi):
        return (np.exp(a * hi) - np.exp(a * lo)) / a

    def k(i, j):
        return interval(i - 1, i) * np.conj(interval(j - 1, j))

    K_v = (n - (1 - np.exp(-a * n)) / a) / a
    K_alg = sum(float(c) * (k(i, j) - k(j, i)) for (i, j), c in algorithm.pairwise.items())
    K_alg += 0.5 * sum(k(i, j) for i in range(1, n + 1) for j in range(1, n + 1))
    return complex(K_v - K_alg)


def simulated_scrolling(algorithm: Algorithm, motion: ScullingMotion, sample_interval: float, duration: float, *, limits: budget.Limits | None = None) -> ScullingErrors:
    """``e_v`` and ``e_r`` measured by running the integration on classical sculling (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm.
    motion : ScullingMotion
        Classical sculling.
    sample_interval : float
        h [s].
    duration : float
        Run length [s] (many vibration periods).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s).

    Returns
    -------
    ScullingErrors
        Means over the steps along ``e_r × e_a``.

    Raises
    ------
    ValueError
        A run beyond ``limits`` (naming ``duration``).
    """
    if not isinstance(motion, ScullingMotion):
        raise TypeError(f"Expected `motion` to be a ScullingMotion, got {type(motion).__name__}")
    h = positive(sample_interval, "sample_interval")
    n = algorithm.samples
    steps = step_count(h, duration, n)
    budget.check(budget.arrays(80.0 * steps * algorithm.window, what=f"`duration` = {float(duration):.3g} s ({steps:.3g} steps)"), limits)
    q = sample_increments(motion, h, steps, n, dual=True, history=algorithm.history, limits=limits)
    inc = step_increments(algorithm, np.asarray(q.re), np.asarray(q.du), h)
    H = n * h
    t = np.arange(steps + 1) * H
    # the exact state at the step boundaries, and the exact position gained over each step
    lam = motion.attitude(t)
    w = motion.apparent_velocity(t)
    nodes, weights = np.polynomial.legendre.leggauss(12)
    tq = t[:-1, None] + 0.5 * H * (nodes[None, :] + 1.0)
    gained = 0.5 * H * np.einsum("k,sk...->s...", weights, motion.apparent_velocity(tq))
    # exact minus algorithm, each step from the exact state (frame I)
    dW = np.diff(w, axis=0) - quat.rotate(lam[:-1], inc.velocity)
    dR = gained - H * w[:-1] - quat.rotate(lam[:-1], inc.position)
    normal = np.cross(motion.e_r, motion.e_a)
    return ScullingErrors(float(np.mean(dW @ normal)) / H, float(np.mean(dR @ normal)) / H)


def _cross_conj(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """``A × conj B`` of complex 3-vectors (..., 3)."""
    return np.cross(A, np.conj(B))


def environment_scrolling(algorithm: Algorithm, environment: Environment, sample_interval: float, *, rtol: float = QUADRATURE_RTOL) -> np.ndarray:
    """Scrolling error ``e_r`` of an environment, body axes [m/s] (exact minus algorithm).

    The lines (coherent per frequency) and spectra of ``environment`` seen
    through its sensors' responses (:meth:`strapdown.analysis.vibration.environment.Environment.response`),
    summed (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm.
    environment : Environment
        Lines, spectra and sensors.
    sample_interval : float
        Algorithm sample interval h [s].
    rtol : float, keyword-only
        Relative tolerance of the spectrum quadrature.

    Returns
    -------
    ndarray
        ``(3,)`` [m/s].

    Raises
    ------
    TypeError
        If ``environment`` is not an Environment.
    ValueError
        A non-positive ``sample_interval``.

    References
    ----------
    Savage (1998), part 2 (scrolling); :mod:`strapdown.derivations.navigation.position_algorithm`.
    """
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    h = positive(sample_interval, "sample_interval")
    Z = scrolling_function(algorithm)
    total = np.zeros(3)
    for group in coherent_groups(environment.lines):
        amp = sum(ln.amplitude for ln in group)
        omega = group[0].omega
        resp = environment.response(np.array([omega]), h)[0]
        sensed = amp * resp
        total += 0.5 * h * h * np.real(_cross_conj(sensed[:3], sensed[3:]) * Z(np.array([omega * h]))[0])
    for spectrum in environment.spectra:

        def g(u, spectrum=spectrum):
            f = np.exp(u)
            omega = 2.0 * math.pi * f
            resp = environment.response(omega, h)
            P = np.conj(resp)[..., :, None] * resp[..., None, :] * spectrum.at(f)
            Pwa = P[..., 0:3, 3:6]
            w = np.stack([Pwa[..., 1, 2] - Pwa[..., 2, 1], Pwa[..., 2, 0] - Pwa[..., 0, 2], Pwa[..., 0, 1] - Pwa[..., 1, 0]], axis=-1)
            val = 0.5 * h * h * np.real(2.0 * np.conj(w) * Z(omega * h)[:, None]) * f[:, None]
            return np.moveaxis(val, 0, -1)

        edges = np.log(spectrum.frequency)
        total += quadrature(g, edges, rtol=rtol, atol=0.0, panels=1)
    return total
