"""One run of any length at constant memory: drift fit, error statistics and periodic error.

:func:`strapdown.analysis.coning.simulator.simulate` keeps the whole error
series, which a long run cannot afford (24 bytes per step for the error alone,
about 130 with its temporaries).  :func:`simulate_long_run` runs the same
parallel computation (Lebedev & Panov 1989, eqs. (1.5), (1.12), (2.1),
(4.1)–(4.4)) through the compiled kernel of
:mod:`strapdown.analysis.coning.kernels` and keeps only

* the running sums of :mod:`strapdown.analysis.coning.streaming` (the
  least-squares drift, the final, root-mean-square and largest error), and
* one window of :data:`PERIODIC_WINDOW` steps of the error series, a buffer the
  kernel refills, from which :func:`strapdown.analysis.coning.streaming.window_peak`
  (compiled beside the kernel, ``window_peak`` of its template) takes the peak
  distance of the error from the window's own least-squares line: the periodic
  error that a drift fit has to average out.

Its memory is that window and a few numbers, whatever the duration; its
estimate (:func:`strapdown.analysis.core.budget.coning_long_run`) is checked
against the measured peak by ``tests/test_long_run.py``.  A run of at most
:data:`PERIODIC_WINDOW` steps has one window, the whole run: its periodic error
is then the one of :attr:`SimulationResult.periodic_error
<strapdown.analysis.coning.simulator.SimulationResult.periodic_error>`.

Errors are exact minus algorithm (package docstring, "Errors"): ``δφ_I =
rotvec(Λ_exact ∘ Λ̄_alg)`` in frame I, and the drift is its least-squares slope.

Public API
----------
.. autosummary::

   PERIODIC_WINDOW
   LongRunResult
   simulate_long_run
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import budget
from ..core.progress import bar
from ..core.validation import as_int, positive
from . import kernels
from .precession import RegularPrecession
from .simulator import simulate, step_count
from .streaming import empty_sums, statistics, window_peak

__all__ = ["PERIODIC_WINDOW", "LongRunResult", "simulate_long_run"]

#: Steps of one window of the error series (a multiple of the kernel's block): the periodic error is
#: the largest over consecutive windows of the peak about each window's least-squares line.
PERIODIC_WINDOW = 1 << 18


@dataclass(frozen=True)
class LongRunResult:
    """Outcome of :func:`simulate_long_run`.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm run.
    sample_interval : float
        Sample interval h [s].
    step : float
        Algorithm step H = N h [s].
    steps : int
        Steps n simulated (the run covers t = 0 … n H).
    drift : ndarray, shape (3,)
        Least-squares slope of the attitude error ``δφ_I`` against time, frame I,
        exact minus algorithm [rad/s].
    final_error : ndarray, shape (3,)
        ``δφ_I`` at the end of the run [rad].
    rms_error, max_error : float
        Root mean square and largest ``|δφ_I|`` over the n + 1 step ends [rad].
    periodic_error : float
        Largest, over consecutive windows of ``window`` steps, of the peak
        distance of ``δφ_I`` from the window's least-squares line [rad].
    window : int
        Steps per window of the periodic error.
    engine : str
        ``"compiled"`` (the kernel, constant memory) or ``"numpy"`` (the
        vectorised reference, which holds the series).
    """

    algorithm: Algorithm
    sample_interval: float
    step: float
    steps: int
    drift: np.ndarray
    final_error: np.ndarray
    rms_error: float
    max_error: float
    periodic_error: float
    window: int
    engine: str

    @property
    def drift_rate(self) -> float:
        """Constant drift rate ``|drift|`` [rad/s]."""
        return float(np.linalg.norm(self.drift))

    @property
    def duration(self) -> float:
        """Simulated time n H [s]."""
        return self.steps * self.step


def simulate_long_run(
    algorithm: Algorithm,
    motion: RegularPrecession,
    sample_interval,
    duration,
    *,
    window: int = PERIODIC_WINDOW,
    engine: str = "auto",
    progress: bool = False,
    limits: budget.Limits | None = None,
) -> LongRunResult:
    """Run ``algorithm`` against the exact regular precession at memory independent of ``duration``.

    The run starts at Λ(0) = 1.  With the compiled engine it keeps the running
    sums of the drift fit and one window of the error series; with the numpy
    engine (an algorithm outside the registry on a short run, where compiling a
    kernel would not pay, or no numba) it holds the series of
    :func:`~strapdown.analysis.coning.simulator.simulate` and windows it the
    same way.  The two agree to round-off (``tests/test_long_run.py``).

    Parameters
    ----------
    algorithm : Algorithm
        The rotation-vector algorithm.
    motion : RegularPrecession
        The motion (4.1) (ε, ν, ϑ; its dual parts are not used).
    sample_interval : float
        Sample interval h [s], > 0.
    duration : float
        Length of the run [s]; the run covers ``floor(duration / H)`` whole steps.
    window : int, keyword-only
        Steps per window of the periodic error, a positive multiple of 1024
        (default :data:`PERIODIC_WINDOW`).
    engine : {"auto", "numpy", "compiled"}, keyword-only
        As :func:`strapdown.analysis.coning.kernels.use_compiled` decides.
    progress : bool, keyword-only
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a request
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    LongRunResult

    Raises
    ------
    ValueError
        Non-positive step or duration, a duration shorter than one step, a
        window that is not a positive multiple of 1024, an unknown ``engine``,
        or a run whose estimate exceeds ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration``).
    TypeError
        If ``algorithm`` is not an :class:`Algorithm` or ``motion`` not a
        :class:`RegularPrecession`.
    ImportError
        ``engine="compiled"`` without numba.

    References
    ----------
    Lebedev & Panov (1989), eqs. (1.5), (1.12), (2.1), (4.1)–(4.4);
    Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3 ("parallel computation").

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> m = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))
    >>> r = simulate_long_run(get("panov-4s-1"), m, 0.0025, 1.0)
    >>> r.steps, round(r.drift_rate * 180 / np.pi * 3600, 2)   # deg/h, as simulate()
    (100, 2.47)
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if type(motion) is not RegularPrecession:
        raise TypeError(f"Expected `motion` to be a RegularPrecession, got {type(motion).__name__}")
    window = as_int(window, "window", minimum=1)
    block = kernels.BLOCK
    if window % block:
        raise ValueError(f"Expected `window` to be a positive multiple of {block} steps, got {window}")
    h = positive(sample_interval, "sample_interval")
    steps = step_count(h, duration, algorithm.samples)
    compiled = kernels.use_compiled(engine, algorithm=algorithm, work=steps)
    degree_sum = sum(t.degree for t in algorithm.terms)
    what = f"`duration` = {float(duration):.3g} s over `sample_interval` = {h:g} s ({steps:.3g} steps of {algorithm.samples} samples)"
    budget.check(budget.coning_long_run(steps, window=min(window, steps), samples=algorithm.samples, degree_sum=degree_sum, series=not compiled, what=what), limits)
    if not compiled:
        return _numpy_run(algorithm, motion, h, steps, window)
    par, theta = kernels.parameter_rows(*(np.array([float(v)]) for v in (motion.eps, motion.nu, motion.nutation, 0.0, 0.0, h)), np.array([1.0, 0.0, 0.0, 0.0]), np.zeros(3), velocity=False)
    run = kernels.kernel(algorithm, velocity=False, specialised=None, work=float(steps))
    n_steps = np.array([steps], dtype=np.int64)
    sums = empty_sums(1)
    rows = min(window, steps) + 1
    buffer = (np.zeros((1, rows, 3)), np.zeros((1, 1, 3)), np.zeros((1, 1, 3)))
    chunk = min(window, kernels.chunk_steps(1))
    peak = 0.0
    with bar(total=steps, desc="simulation", enabled=progress, unit="step") as shown:
        for w0 in range(0, steps, window):
            w1 = min(steps, w0 + window)
            if w0:  # the window's first row is the last step of the previous (full) window
                buffer[0][:, 0] = buffer[0][:, window]
            for k0 in range(w0, w1, chunk):
                k1 = min(w1, k0 + chunk)
                kernels.advance(run, par, theta, n_steps, sums, k0, k1, buffer, origin=w0)
                shown.update(k1 - k0)
            peak = max(peak, float(run.window_peak(buffer[0], 0, w1 - w0 + 1)))
    stats = statistics(sums, n_steps, np.array([algorithm.samples * h]), velocity=False, shape=())
    return _result(algorithm, h, steps, stats.drift, stats.final_error, stats.rms_error, stats.max_error, peak, window, "compiled")


def _numpy_run(algorithm, motion, h, steps, window) -> LongRunResult:
    r = simulate(algorithm, motion, h, steps * algorithm.samples * h, engine="numpy")
    error = r.attitude_error
    if error.shape[0] != steps + 1:  # the step count is the one above, from the same duration
        raise RuntimeError(f"Expected {steps + 1} step ends from the numpy simulator, got {error.shape[0]}")
    peak = max(float(window_peak(error[None, w0 : min(steps, w0 + window) + 1])[0]) for w0 in range(0, steps, window))
    e2 = np.sum(error * error, axis=-1)
    return _result(algorithm, h, steps, r.drift, error[-1], math.sqrt(e2.mean()), math.sqrt(e2.max()), peak, window, "numpy")


def _result(algorithm, h, steps, drift, final, rms, largest, peak, window, engine) -> LongRunResult:
    vector = (np.asarray(x, dtype=float).reshape(3) for x in (drift, final))
    return LongRunResult(algorithm, h, algorithm.samples * h, int(steps), *vector, float(rms), float(largest), float(peak), int(window), engine)
