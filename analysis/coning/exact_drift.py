"""The exact constant drift of an algorithm under regular precession, from one step in extended precision.

An independent reference for the drift series (:mod:`strapdown.analysis.coning.drift_theory`)
and the closed-form coning drift: no series, no simulation, only the closed-form
motion, its exact increments and one evaluation of the algorithm, in
:mod:`mpmath` arithmetic.

Derivation.  In the frame I of the particular solution (Lebedev & Panov 1989,
eq. (4.4)) the attitude is ``Q(t) = Z(μt) ∘ Q₀ ∘ Z(νt)``, with ``Z(θ)`` the
rotation by θ about ``e_z``, ``Q₀ = (cos ϑ/2, sin ϑ/2, 0, 0)`` and ``μ = εν``;
``e_z`` of I is the precession axis n.  A strapdown algorithm's increments
depend on the gyro samples only, so the error rotation
``E_k = Λ_true ∘ Λ̄_computed`` after step k obeys ``E_{k+1} = S_k ∘ E_k`` with
the error ``S_k`` of one step taken from the true attitude.  The motion turns
every step's samples about ``e_z`` of E by ``−νH``, hence
``S_k = R^k S_0 R^{−k}`` with ``R = Z(μH)``, and exactly

    E_K = R^K ∘ T^K,        T = R⁻¹ ∘ S_0 = Q₀ ∘ Z(νH) ∘ exp(−Δφ_alg) ∘ Q̄₀,

``Δφ_alg`` the algorithm's increment over the first step.  For an exact
algorithm ``T = R⁻¹``.  Otherwise T turns by ``θ_T`` about an axis close to n,
and ``E_K`` is a bounded periodic rotation times the rotation by
``K (θ_T + μH)`` about that axis: the constant drift rate along n, exact minus
algorithm, is

    u = (θ_T + μH) / H         [rad/s],

where ``θ_T`` is the angle of ``T' = Z(νH) ∘ exp(−Δφ_alg)`` (the same rotation
seen in the body axes) about its axis oriented along ``n₀ = (0, sin ϑ, cos ϑ)``.
The tilt δ of that axis from n changes the rate only by a factor ``cos δ``, with
δ the transverse step error over νH: below 10⁻¹⁵ relative wherever the drift
is resolvable at all.  ``θ_T + μH`` is a difference of O(νH) numbers that
cancel to the drift, so it is computed in :mod:`mpmath` at a working precision
raised until two precisions agree (:data:`RELATIVE_TOLERANCE`).

Under classical coning (ε = −1, ϑ = α, ν = ω) the drift along the cone axis
(``−n``, the direction of the mean inertial angular velocity) is ``−u``
(:func:`exact_coning_drift`).

Public API
----------
:data:`RELATIVE_TOLERANCE`, :func:`exact_drift`, :func:`exact_coning_drift`.

References
----------
Lebedev & Panov (1989), eqs. (2.1), (4.1), (4.4), (5.1)–(5.3).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import quaternion as quat
from ..core.validation import in_open_interval, positive
from .evaluation import increment
from .precession import RegularPrecession

__all__ = ["RELATIVE_TOLERANCE", "exact_drift", "exact_coning_drift"]

#: Two working precisions must agree to this fraction of the drift [-].
RELATIVE_TOLERANCE = 1e-13
#: Working precisions tried in turn [decimal digits].
_DIGITS = (30, 50, 80, 130, 210, 340, 550, 900, 1500, 2500)


def _increments(eps, sin_t, cos_t, x, first: int, count: int) -> np.ndarray:
    """Exact increments (2.1) of (4.1) at ν = 1 over ``[(j − 1)x, jx]``, j = first … first + count − 1."""
    rows = []
    for j in range(first, first + count):
        t0, t1 = (j - 1) * x, j * x
        rows.append([-eps * sin_t * (mpmath.cos(t1) - mpmath.cos(t0)), eps * sin_t * (mpmath.sin(t1) - mpmath.sin(t0)), (1 + eps * cos_t) * (t1 - t0)])
    return np.array(rows, dtype=object)


def _drift_per_step(algorithm: Algorithm, eps: float, nutation: float, x: float):
    """``θ_T + μH`` [rad] at the current :mod:`mpmath` precision (ν = 1, sample interval x = νh)."""
    eps, nutation, x = mpmath.mpf(eps), mpmath.mpf(nutation), mpmath.mpf(x)
    sin_t, cos_t = mpmath.sin(nutation), mpmath.cos(nutation)
    p = _increments(eps, sin_t, cos_t, x, algorithm.first_index, algorithm.window)
    phi = increment(algorithm, p)
    angle = mpmath.sqrt(phi[0] ** 2 + phi[1] ** 2 + phi[2] ** 2)
    half = -mpmath.sin(angle / 2) / angle if angle else mpmath.mpf(-0.5)
    step = algorithm.samples * x
    turn = (mpmath.cos(step / 2), 0, 0, mpmath.sin(step / 2))
    w, v1, v2, v3 = quat.multiply_parts(turn, (mpmath.cos(angle / 2), half * phi[0], half * phi[1], half * phi[2]))
    along = v2 * sin_t + v3 * cos_t  # vector part along n₀ = (0, sin ϑ, cos ϑ)
    theta = 2 * mpmath.atan2(mpmath.sqrt(v1**2 + v2**2 + v3**2), w)
    if along < 0:
        theta = -theta
    eta = theta + eps * step
    return eta - 2 * mpmath.pi * mpmath.floor((eta + mpmath.pi) / (2 * mpmath.pi))


def exact_drift(algorithm: Algorithm, motion: RegularPrecession, sample_interval: float) -> float:
    """Constant drift rate of ``algorithm`` under regular precession along the precession axis [rad/s], exactly.

    The rate of the error rotation ``Λ_true ∘ Λ̄_computed`` (exact minus
    algorithm, the sign of :func:`strapdown.analysis.coning.drift_theory.drift_series_terms`
    and of the simulator's drift vector) along the precession axis n, of a run
    of any length: from one step in extended precision (module docstring), with
    no series and no simulation.  Cross-step algorithms read the samples before
    the step from the same motion.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    motion : RegularPrecession
        The motion (4.1); its dual parts, if any, are ignored.
    sample_interval : float
        Sample interval h [s], > 0 (the step is H = N h).

    Returns
    -------
    float
        u [rad/s], signed, to :data:`RELATIVE_TOLERANCE`; 0.0 if it vanishes
        below 10⁻²⁴⁵⁰ of νH.

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm or ``motion`` not a RegularPrecession.
    ValueError
        For a sample interval that is not positive and finite.

    References
    ----------
    Lebedev & Panov (1989), eqs. (4.1), (4.4), (5.1)–(5.3).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> u = exact_drift(get("panov-4s-1"), RegularPrecession(-1.0, 2 * np.pi * 10, np.radians(1.0)), 0.0025)
    >>> round(u * 180 / np.pi * 3600, 3)      # deg/h, along n: under coning the cone axis is −n
    -2.471
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(motion, RegularPrecession):
        raise TypeError(f"Expected `motion` to be a RegularPrecession, got {type(motion).__name__}")
    h = positive(sample_interval, "sample_interval")
    sign = 1.0 if motion.nu > 0 else -1.0  # ν < 0 is the same motion run backwards in the spin angle
    x = abs(motion.nu) * h
    previous = None
    for digits in _DIGITS:
        with mpmath.workdps(digits):
            eta = _drift_per_step(algorithm, motion.eps, motion.nutation, x)
            if previous is not None and eta != 0 and abs(eta - previous) <= RELATIVE_TOLERANCE * abs(eta):
                return sign * float(eta) / (algorithm.samples * h)
            previous = eta
    if abs(previous) < mpmath.mpf(10) ** (-(_DIGITS[-1] - 50)) * x:
        return 0.0
    raise ValueError(f"Expected the drift of {algorithm.name!r} to settle within {_DIGITS[-1]} digits, got {mpmath.nstr(previous, 5)} rad per step")


def exact_coning_drift(algorithm: Algorithm, *, cone_angle: float, nu: float, sample_interval: float) -> float:
    """Constant drift rate under classical coning along the cone axis [rad/s], exactly, at any cone angle.

    Classical coning of half-cone angle α at the coning rate ω is the regular
    precession (4.1) with ε = −1, ϑ = α, ν = ω; the cone axis, the direction of
    the mean inertial angular velocity, is −n.  Positive: the computed attitude
    lags the coning rotation (the sign of
    :func:`strapdown.derivations.coning.drift.coning_drift`), with every order
    in α and ωh included.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (sample indices ≤ 0 allowed).
    cone_angle : float
        Half-cone angle α [rad], in (0, π/2).
    nu : float
        Coning rate ω [rad/s], > 0.
    sample_interval : float
        Sample interval h [s], > 0.

    Returns
    -------
    float
        u [rad/s], signed.

    Raises
    ------
    ValueError
        For α outside (0, π/2), or ω or h not positive.

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> u = exact_coning_drift(get("two-sample"), cone_angle=1e-3, nu=1.0, sample_interval=0.01)
    >>> round(u / (1e-6 * 0.01**4 / 60), 4)     # the leading term (1/60) α² ω (ωh)⁴
    1.0
    """
    alpha = in_open_interval(cone_angle, "cone_angle", 0.0, math.pi / 2, text="(0, π/2)")
    nu = positive(nu, "nu")
    return -exact_drift(algorithm, RegularPrecession(-1.0, nu, alpha), sample_interval)
