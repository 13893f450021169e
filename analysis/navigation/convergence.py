"""The strapdown integration against exact motions: errors at the end of a run and observed orders as h halves.

The reference is independent of the algorithms: DOP853 (rtol 1e-13) on the
kinematics ``2Λ' = Λ ∘ ω``, ``W' = Λ ∘ a ∘ Λ̄``, ``R' = W`` of a motion with a
closed-form body rate and specific force — the dual regular precession
(Lebedev & Panov 1989, eqs. (4.1)–(4.3)), a spin about a tilted axis that
also accelerates (``nu_dual``, ``nutation_dual``), or the classical sculling
motion — fed by the motion's exact increments.  The errors are
estimate minus truth (the navigator is an estimator): the angle of
``Λ_computed ∘ Λ̄_true``, ``|W_computed − W_true|`` and ``|R_computed − R_true|``
at the end of the run.

Halving h divides an error of order k by 2^k; the *observed* order between
two intervals is ``log2(e(h)/e(h/2))``.  Attitude and velocity are of the
coning algorithm's accuracy order ρ (the velocity algorithm is its dual
extension); the position algorithm is exact to second order in the motion for
rates polynomial of degree N − 1 and keeps the rotation compensation exact
for constant rates, so its error is of order ``min(ρ, 4)``: its third-order terms
are exact only for constant rates, which leaves a local error of ``O(H⁵)``.

Public API
----------
.. autosummary::

   ConvergenceStudy
   reference_solution
   convergence_study
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..coning.simulator import sample_increments, step_count
from ..core import budget
from ..core import quaternion as quat
from ..core.validation import as_int, positive
from .integration import integrate

__all__ = ["ConvergenceStudy", "reference_solution", "convergence_study"]

#: Relative tolerance of the DOP853 reference.
REFERENCE_RTOL = 1e-13


def reference_solution(motion, duration: float):
    """``(Λ, W, R)`` at ``duration`` by DOP853 on the kinematics, from Λ = 1, W = 0, R = 0.

    Parameters
    ----------
    motion : RegularPrecession or ScullingMotion
        With ``omega(t)`` [rad/s] and ``accel(t)`` [m/s²] in body axes.
    duration : float
        [s].

    Returns
    -------
    tuple of ndarray
        ``(4,)``, ``(3,)``, ``(3,)``.
    """
    from scipy.integrate import solve_ivp

    T = positive(duration, "duration")

    def rhs(t, y):
        q0, q1, q2, q3 = y[0], y[1], y[2], y[3]
        w0, w1, w2 = (float(c) for c in motion.omega(t))
        a = np.asarray(motion.accel(t), dtype=float)
        # ½ Λ ∘ (0, ω) and the rotation matrix of Λ, written out (the reference runs many small steps)
        dq = 0.5 * np.array([-q1 * w0 - q2 * w1 - q3 * w2, q0 * w0 + q2 * w2 - q3 * w1, q0 * w1 - q1 * w2 + q3 * w0, q0 * w2 + q1 * w1 - q2 * w0])
        C = np.array([
            [q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
            [2 * (q1 * q2 + q0 * q3), q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3, 2 * (q2 * q3 - q0 * q1)],
            [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3],
        ])  # fmt: skip
        return np.concatenate([dq, C @ a, y[4:7]])

    y0 = np.zeros(10)
    y0[0] = 1.0
    sol = solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=REFERENCE_RTOL, atol=1e-15)
    y = sol.y[:, -1]
    return y[0:4] / np.linalg.norm(y[0:4]), y[4:7], y[7:10]


@dataclass(frozen=True)
class ConvergenceStudy:
    """Errors of the integration at the end of a run, for a sequence of halved intervals.

    Attributes
    ----------
    algorithm : str
        Its name.
    intervals : ndarray
        ``(K,)`` h [s], each half the one before.
    attitude, velocity, position : ndarray
        ``(K,)`` errors at the end [rad, m/s, m].
    """

    algorithm: str
    intervals: np.ndarray
    attitude: np.ndarray
    velocity: np.ndarray
    position: np.ndarray

    def observed_orders(self, quantity: str) -> np.ndarray:
        """``log2(e(h)/e(h/2))`` between successive intervals of ``quantity``.

        Parameters
        ----------
        quantity : str
            ``"attitude"``, ``"velocity"`` or ``"position"``.

        Returns
        -------
        ndarray
            ``(K − 1,)``.
        """
        if quantity not in ("attitude", "velocity", "position"):
            raise ValueError(f"Expected `quantity` in ('attitude', 'velocity', 'position'), got {quantity!r}")
        e = getattr(self, quantity)
        return np.log2(e[:-1] / e[1:])


def convergence_study(algorithm: Algorithm, motion, duration: float, sample_interval: float, *, halvings: int = 3, limits: budget.Limits | None = None) -> ConvergenceStudy:
    """The integration of ``motion`` over ``duration`` at h, h/2, …, against the DOP853 reference.

    Parameters
    ----------
    algorithm : Algorithm
        The coning algorithm (velocity: its dual extension; position: the N-sample position algorithm).
    motion : RegularPrecession or ScullingMotion
        A motion with exact increments (``grid_increments``) and rates.
    duration : float
        Run length [s]; each run covers whole steps and ends at its own last
        step (the reference is taken there).
    sample_interval : float
        The largest h [s].
    halvings : int, keyword-only
        How many times h is halved [count].
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s).

    Returns
    -------
    ConvergenceStudy

    Raises
    ------
    ValueError
        Bad sizes, or runs beyond ``limits`` (naming ``duration``).

    References
    ----------
    Lebedev & Panov (1989), eqs. (4.1)–(4.3) (the motion); Savage (1998), part 2.
    """
    h0 = positive(sample_interval, "sample_interval")
    k = as_int(halvings, "halvings", minimum=1)
    T = positive(duration, "duration")
    n = algorithm.samples
    total = sum(step_count(h0 / 2**i, T, n) for i in range(k + 1))
    what = f"`duration` = {T:.3g} s at `sample_interval` = {h0:g} s halved {k} times ({total:.3g} steps)"
    budget.check(budget.arrays(60.0 * total * algorithm.window, what=what), limits)
    hs, ea, ev, ep = [], [], [], []
    references = {}
    for i in range(k + 1):
        h = h0 / 2**i
        steps = step_count(h, T, n)
        q = sample_increments(motion, h, steps, n, dual=True, history=algorithm.history, limits=limits)
        run = integrate(algorithm, np.asarray(q.re), np.asarray(q.du), h)
        t_end = steps * n * h
        key = round(t_end, 12)
        if key not in references:
            references[key] = reference_solution(motion, t_end)
        lam, W, R = references[key]
        err = quat.quat_to_rotvec(quat.multiply(run.attitude[-1], quat.conjugate(lam)), canonical=True, validate=False)
        hs.append(h)
        ea.append(float(np.linalg.norm(err)))
        ev.append(float(np.linalg.norm(run.velocity[-1] - W)))
        ep.append(float(np.linalg.norm(run.position[-1] - R)))
    return ConvergenceStudy(algorithm.name, np.array(hs), np.array(ea), np.array(ev), np.array(ep))


