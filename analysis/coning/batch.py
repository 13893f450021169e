"""Batches over parameters: arrays of ε, ν, ϑ, h in one call, with no Python loop per point.

:func:`simulate_batch` runs one algorithm against the exact solution of the
regular precession (4.1) (or its dual analogue (4.2), with ν° and ϑ°) at every
point of broadcast parameter arrays (Lebedev & Panov 1989, section 4), in the
fused compiled kernel of :mod:`strapdown.analysis.coning.kernels`
(:func:`~strapdown.analysis.coning.kernels.run_batch`, the same run behind
:func:`strapdown.analysis.coning.simulator.simulate`'s compiled engine).  By
default it keeps only the streaming statistics
(:mod:`strapdown.analysis.coning.streaming`): memory is a few hundred bytes per
point whatever the number of steps; the full error series are kept on request
(``series=True``).  Its numpy engine, the slow reference, is the simulator
itself, point by point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import budget
from ..core.validation import as_array, as_int, as_quaternion, as_vector
from . import kernels
from .precession import RegularPrecession
from .simulator import simulate
from .streaming import ErrorStatistics, accumulate, empty_sums, statistics

__all__ = ["BatchResult", "simulate_batch"]


@dataclass(frozen=True)
class BatchResult:
    """Outcome of :func:`simulate_batch` (leading axes: the broadcast parameter shape).

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm run.
    sample_interval : ndarray, shape (...)
        Sample interval h of each point [s].
    statistics : ErrorStatistics
        Drift fit and error statistics of every point.
    attitude_error : ndarray, shape (..., n + 1, 3), or None
        ``δφ_I = rotvec(Λ_exact ∘ Λ̄_alg)`` (exact minus algorithm, frame I) at
        every step end [rad] (``series=True`` only).
    dw_body, dw_inertial : ndarray, shape (..., n + 1, 3), or None
        ``ΔW_E = W_E* − W_E`` (frame E), ``ΔW_I = W_I* − W_I`` (frame I) at every
        step end [m/s] (``series=True`` velocity runs only).
    """

    algorithm: Algorithm
    sample_interval: np.ndarray
    statistics: ErrorStatistics
    attitude_error: np.ndarray | None = None
    dw_body: np.ndarray | None = None
    dw_inertial: np.ndarray | None = None

    @property
    def drift_rate(self) -> np.ndarray:
        """Constant drift rate ``|slope|`` [rad/s], shape ``(...)``."""
        return self.statistics.drift_rate


def _parameters(eps, nu, nutation, sample_interval, nu_dual, nutation_dual, limits):
    arrays = {
        "eps": as_array(eps, "eps"),
        "nu": as_array(nu, "nu"),
        "nutation": as_array(nutation, "nutation"),
        "sample_interval": as_array(sample_interval, "sample_interval"),
        "nu_dual": as_array(nu_dual, "nu_dual"),
        "nutation_dual": as_array(nutation_dual, "nutation_dual"),
    }
    if np.any(arrays["nu"] == 0.0):
        raise ValueError("Expected `nu` (spin rate, rad/s) to be nonzero, got 0")
    bad = arrays["nutation"][(arrays["nutation"] <= 0.0) | (arrays["nutation"] >= math.pi)]
    if bad.size:
        raise ValueError(f"Expected `nutation` in (0, π), got {float(bad.flat[0]):g}")
    bad = arrays["sample_interval"][arrays["sample_interval"] <= 0.0]
    if bad.size:
        raise ValueError(f"Expected `sample_interval` > 0, got {float(bad.flat[0]):g}")
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{k} {a.shape}" for k, a in arrays.items())
        raise ValueError(f"Expected the parameter arrays to broadcast together, got shapes {shapes}") from None
    points = math.prod(shape)
    if points == 0:
        empty = ", ".join(f"`{k}` (shape {a.shape})" for k, a in arrays.items() if a.size == 0)
        raise ValueError(f"Expected at least one parameter point, got the empty array {empty}")
    budget.check(budget.coning_batch(points, 0, window=1, degree_sum=0, velocity=False, series=False, what=f"{_named(arrays)} broadcast to {points:.3g} points (shape {shape})"), limits)
    flat = {k: np.ascontiguousarray(np.broadcast_to(a, shape).ravel()) for k, a in arrays.items()}
    return shape, flat


def _named(arrays: dict) -> str:
    """The arguments that set the batch shape, e.g. "`eps` and `nu`"."""
    names = [f"`{k}`" for k, a in arrays.items() if a.ndim] or [f"`{k}`" for k in arrays]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _step_counts(samples: int, h, duration, steps, shape):
    if (duration is None) == (steps is None):
        raise ValueError("Expected exactly one of `duration` and `steps`, got " + ("both" if steps is not None else "neither"))
    if steps is not None:
        return np.full(h.shape, float(as_int(steps, "steps", minimum=1)))
    d = as_array(duration, "duration")
    try:
        d = np.broadcast_to(d, shape).ravel()
    except ValueError:
        raise ValueError(f"Expected `duration` to broadcast to the parameter shape {shape}, got shape {d.shape}") from None
    if np.any(d <= 0):
        raise ValueError(f"Expected `duration` > 0, got {float(d[d <= 0].flat[0]):g}")
    n = np.floor(d / (samples * h) * (1.0 + 1e-12))
    if np.any(n < 1):
        i = int(np.argmin(n))
        raise ValueError(f"Expected `duration` >= one step H = {samples} × `sample_interval` = {samples} × {h[i]:g} s = {samples * h[i]:g} s, got {d[i]:g}")
    return n


def simulate_batch(
    algorithm: Algorithm,
    eps,
    nu,
    nutation,
    sample_interval,
    duration=None,
    *,
    steps=None,
    nu_dual=0.0,
    nutation_dual=0.0,
    attitude0=(1.0, 0.0, 0.0, 0.0),
    w_inertial0=(0.0, 0.0, 0.0),
    velocity: bool = False,
    series: bool = False,
    engine: str = "auto",
    progress: bool = False,
    limits: budget.Limits | None = None,
) -> BatchResult:
    """Run ``algorithm`` at every point of broadcast arrays of ε, ν, ϑ, h (and ν°, ϑ°).

    Each point is the parallel computation of
    :func:`strapdown.analysis.coning.simulator.simulate` for the motion
    ``RegularPrecession(ε, ν, ϑ, ν°, ϑ°)`` sampled every h: the algorithm's
    attitude (and, with ``velocity``, apparent velocity) against the exact
    solution (1.5), (4.4)–(4.5), errors exact minus algorithm.  All points
    start from the same ``attitude0`` and ``w_inertial0``.

    Parameters
    ----------
    algorithm : Algorithm
        The rotation-vector algorithm (its dual extension for velocity).
    eps : array_like
        ε = μ/ν [-] (−1 is coning), eq. (4.1).
    nu : array_like
        Spin rate ν [rad/s], nonzero.
    nutation : array_like
        Nutation ϑ [rad], in (0, π).
    sample_interval : array_like
        Sample interval h [s], > 0.
    duration : float or array_like, optional
        Length of each run [s]; a run covers ``floor(duration / (N h))`` whole steps.
    steps : int, keyword-only, optional
        Steps n of every run (instead of ``duration``).
    nu_dual : array_like, keyword-only
        Dual part ν° of the spin rate [m/s²], eq. (4.2).
    nutation_dual : array_like, keyword-only
        Dual part ϑ° of the nutation [m/s].
    attitude0 : array_like, shape (4,), keyword-only
        Initial attitude Λ(0), unit quaternion (E → I).
    w_inertial0 : array_like, shape (3,), keyword-only
        Initial apparent velocity W_I(0) [m/s] (velocity runs).
    velocity : bool, keyword-only
        Also integrate the apparent velocity (biquaternion run).
    series : bool, keyword-only
        Keep the full error series (all runs must then have the same number of steps).
    engine : {"auto", "numpy", "compiled"}, keyword-only
        ``"auto"``: the compiled kernel whenever numba is available; ``"numpy"``:
        a loop over points of the numpy simulator (the reference, slow).
    progress : bool, keyword-only
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    BatchResult

    Raises
    ------
    ValueError
        Bad parameters (named), empty arrays, arrays that do not broadcast, both or neither
        of ``duration`` and ``steps``, a run shorter than one step,
        ``series`` with runs of different lengths, or a batch whose estimated
        memory or time exceeds ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration`` or ``steps``).
    TypeError
        If ``algorithm`` is not an :class:`Algorithm`.
    ImportError
        ``engine="compiled"`` without numba.

    References
    ----------
    Lebedev & Panov (1989), eqs. (1.3), (1.5), (1.12), (2.1)–(2.6), (4.1)–(4.5).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> r = simulate_batch(get("panov-4s-1"), -1.0, 2 * np.pi * 10, np.radians([0.5, 1.0]), 0.0025, 1.0)
    >>> from strapdown.analysis.core.units import deg_per_h
    >>> np.round(deg_per_h(r.drift_rate), 2)
    array([0.62, 2.47])
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    compiled = kernels.use_compiled(engine)  # the numpy path here is a slow per-point reference
    shape, p = _parameters(eps, nu, nutation, sample_interval, nu_dual, nutation_dual, limits)
    size = int(np.prod(shape, dtype=np.int64))
    n = _step_counts(algorithm.samples, p["sample_interval"], duration, steps, shape)
    if series and np.any(n != n[0]):
        raise ValueError(f"Expected runs of equal length for `series=True`, got {int(n.min())} to {int(n.max())} steps (pass `steps` instead of `duration`)")
    lam0 = as_quaternion(attitude0, "attitude0", unit=True)
    w0 = as_vector(w_inertial0, "w_inertial0")
    if lam0.shape != (4,) or w0.shape != (3,):
        raise ValueError(f"Expected `attitude0` of shape (4,) and `w_inertial0` of shape (3,), got {lam0.shape} and {w0.shape}")
    longest = float(n.max())
    asked = f"`steps` = {steps:.3g}" if steps is not None else f"`duration` up to {float(np.max(as_array(duration, 'duration'))):.3g} s"
    what = f"{asked} ({size} point{'s' if size != 1 else ''} of up to {longest:.3g} steps{', series kept' if series else ''})"
    degree_sum = sum(t.degree for t in algorithm.terms)
    budget.check(budget.coning_batch(size, longest, window=algorithm.window, degree_sum=degree_sum, velocity=velocity, series=series, what=what), limits)
    n = n.astype(np.int64)
    big_h = algorithm.samples * p["sample_interval"]
    if compiled:
        par, theta = kernels.parameter_rows(p["eps"], p["nu"], p["nutation"], p["nu_dual"], p["nutation_dual"], p["sample_interval"], lam0, w0, velocity=velocity)
        sums, keep = kernels.run_batch(algorithm, par, theta, n, velocity=velocity, series=series, progress=progress)
    else:
        sums, keep = _run_numpy(algorithm, p, n, lam0, w0, velocity=velocity, series=series)
    stats = statistics(sums, n, big_h, velocity=velocity, shape=shape)
    out = {"algorithm": algorithm, "sample_interval": np.reshape(p["sample_interval"], shape), "statistics": stats}
    if series:
        rows = int(n[0]) + 1
        out["attitude_error"] = np.reshape(keep[0], shape + (rows, 3))
        if velocity:
            out["dw_body"] = np.reshape(keep[1], shape + (rows, 3))
            out["dw_inertial"] = np.reshape(keep[2], shape + (rows, 3))
    return BatchResult(**out)


def _run_numpy(algorithm, p, n, lam0, w0, *, velocity: bool, series: bool):
    """The reference: the numpy simulator point by point (each point's series is held while it runs)."""
    size = n.shape[0]
    sums = empty_sums(size)
    keep = [[], [], []]
    for i in range(size):
        motion = RegularPrecession(p["eps"][i], p["nu"][i], p["nutation"][i], p["nu_dual"][i], p["nutation_dual"][i])
        h = float(p["sample_interval"][i])
        r = simulate(algorithm, motion, h, int(n[i]) * algorithm.samples * h, attitude0=lam0, w_inertial0=w0, velocity=velocity, engine="numpy")
        row = slice(i, i + 1)
        dwe = None if r.dw_body is None else r.dw_body[None]
        dwi = None if r.dw_inertial is None else r.dw_inertial[None]
        accumulate(sums[row], 0, n[row], r.attitude_error[None], dwe, dwi)
        if series:
            keep[0].append(r.attitude_error)
            keep[1].append(r.dw_body)
            keep[2].append(r.dw_inertial)
    if not series:
        return sums, None
    stack = [np.stack(k) if k and k[0] is not None else None for k in keep]
    return sums, tuple(stack)
