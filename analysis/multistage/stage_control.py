"""Linear analysis of a corrected attitude stage with python-control.

The tilt channel of a stage, linearised (Plotnikov 1999, eqs. (3.8)–(3.10)),
is a second-order loop.  With ``e`` the tilt error (estimate minus truth), ``y``
the integral correction, ``d`` a rate disturbance (gyro drift, uncompensated
frame rate) and ``δ`` the error of the accelerometer-indicated tilt
(``a/g`` for a horizontal acceleration a, ``b/g`` for an accelerometer bias b):

    e' = −k e + y + d + k δ,        y' = −l e + l δ.

Its characteristic polynomial is ``s² + k s + l``.  Seen as a filter the stage
is complementary: the estimate is ``H_g θ_gyro + H_a θ_acc`` with the gyro
high-pass ``H_g = s²/(s² + ks + l)`` and the accelerometer low-pass
``H_a = (ks + l)/(s² + ks + l)``, ``H_g + H_a = 1``.  On a moving base the
truth itself turns with the vertical (``ω = V/R``), and the error transfer
function from horizontal acceleration (derived in :mod:`strapdown.derivations.multistage.schuler`)
is ``(ks + l − g/R)/(g(s² + ks + l))``: zero for Schuler tuning ``k = 0``,
``l = g/R``.

The gains here are the loop gains of the (1.4) stage with c = 2; a stage with
c = 1 acts with ``k/2, l/2`` (:attr:`strapdown.analysis.multistage.stages.Stage.effective_gains`).
All linear-systems work (poles, damping, root loci, time and frequency
responses) is done by python-control.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import control
import numpy as np
import sympy as sp

from ..core.validation import as_array, as_float, positive

__all__ = ["StageLoop", "schuler_period", "classify_poles", "root_locus_k", "root_locus_l", "STABILITY_LABELS"]

#: Labels of :func:`classify_poles`.
STABILITY_LABELS = ("asymptotically stable", "marginal", "unstable")


def schuler_period(gravity: float = 9.81, earth_radius: float = 6.371e6) -> float:
    """Schuler period ``2π √(R/g)`` [s].

    >>> round(schuler_period() / 60.0, 2)
    84.39
    """
    return float(2.0 * np.pi * np.sqrt(positive(earth_radius, "earth_radius") / positive(gravity, "gravity")))


def classify_poles(poles, *, rtol: float = 1e-9) -> str:
    """Stability of a linear time-invariant system from its poles.

    "asymptotically stable" if every pole has a negative real part;
    "marginal" if none is in the right half-plane and the poles on the
    imaginary axis are simple; "unstable" otherwise (a right-half-plane pole,
    or a repeated pole on the imaginary axis, whose response grows).

    Parameters
    ----------
    poles : array_like of complex
    rtol : float
        Relative tolerance for "on the imaginary axis" (scaled by the largest |pole|).

    >>> classify_poles([-1.0, -2.0]), classify_poles([1j, -1j]), classify_poles([0.0, 0.0])
    ('asymptotically stable', 'marginal', 'unstable')
    """
    p = np.asarray(poles, dtype=complex).ravel()
    tol = rtol * max(1.0, float(np.abs(p).max(initial=0.0))) if p.size else 0.0
    tol = max(tol, 1e-300)
    if np.any(p.real > tol):
        return "unstable"
    axis = p[np.abs(p.real) <= tol]
    if axis.size == 0:
        return "asymptotically stable"
    for i in range(axis.size):
        for j in range(i + 1, axis.size):
            if abs(axis[i] - axis[j]) <= tol:
                return "unstable"
    return "marginal"


@lru_cache(maxsize=1)
def _tf_coefficients():
    """Coefficients of E(s)/A(s) lambdified from the symbolic derivation."""
    from ...derivations.multistage.schuler import accel_to_tilt_tf, derive

    sym = derive().symbols
    num, den = accel_to_tilt_tf()
    args = (sym["k"], sym["l"], sym["g"], sym["R"])
    return sp.lambdify(args, num, "math"), sp.lambdify(args, den, "math")


@dataclass(frozen=True)
class StageLoop:
    """Linearised tilt channel of a corrected stage with gains (k, l).

    Parameters
    ----------
    k : float
        Position-correction gain [1/s].  Any finite value (k < 0 is analysed, flagged unstable).
    l : float
        Integral-correction gain [1/s²].  Any finite value.
    gravity : float
        g [m/s²], > 0.
    earth_radius : float
        R [m], > 0.

    Examples
    --------
    >>> loop = StageLoop(0.01, 5e-5)
    >>> loop.stability
    'asymptotically stable'
    >>> StageLoop.schuler().stability
    'marginal'
    """

    k: float
    l: float
    gravity: float = 9.81
    earth_radius: float = 6.371e6

    def __post_init__(self):
        object.__setattr__(self, "k", as_float(self.k, "k"))
        object.__setattr__(self, "l", as_float(self.l, "l"))
        object.__setattr__(self, "gravity", positive(self.gravity, "gravity"))
        object.__setattr__(self, "earth_radius", positive(self.earth_radius, "earth_radius"))

    @classmethod
    def schuler(cls, gravity: float = 9.81, earth_radius: float = 6.371e6) -> StageLoop:
        """Schuler tuning ``k = 0``, ``l = g/R`` (Plotnikov 1999, (3.11))."""
        g, r = positive(gravity, "gravity"), positive(earth_radius, "earth_radius")
        return cls(0.0, g / r, g, r)

    # ---------------------------------------------------------------- models
    def state_space(self) -> control.StateSpace:
        """States (e, y); inputs (d [rad/s], δ [rad]); output e [rad]."""
        k, l = self.k, self.l
        a = [[-k, 1.0], [-l, 0.0]]
        b = [[1.0, k], [0.0, l]]
        return control.ss(a, b, [[1.0, 0.0]], [[0.0, 0.0]], inputs=["rate", "tilt"], outputs=["e"], states=["e", "y"])

    def error_from_accel(self) -> control.TransferFunction:
        """E(s)/A(s) [rad per m/s²] from :mod:`strapdown.derivations.multistage.schuler` (zero under Schuler tuning)."""
        fnum, fden = _tf_coefficients()
        args = (self.k, self.l, self.gravity, self.earth_radius)
        return control.tf(np.array(fnum(*args), dtype=float), np.array(fden(*args), dtype=float))

    def error_from_drift(self) -> control.TransferFunction:
        """E(s)/D(s): tilt error per rate disturbance [rad per rad/s]."""
        return control.tf([1.0, 0.0], [1.0, self.k, self.l])

    def accel_lowpass(self) -> control.TransferFunction:
        """``H_a = (ks + l)/(s² + ks + l)``: how the accelerometer tilt enters the estimate."""
        return control.tf([self.k, self.l], [1.0, self.k, self.l])

    def gyro_highpass(self) -> control.TransferFunction:
        """``H_g = s²/(s² + ks + l)``: how the gyro-integrated attitude enters the estimate."""
        return control.tf([1.0, 0.0, 0.0], [1.0, self.k, self.l])

    # ---------------------------------------------------------------- numbers
    def poles(self) -> np.ndarray:
        """Closed-loop poles [1/s] (eigenvalues of the state matrix), sorted."""
        p = self.state_space().poles()
        return np.sort_complex(np.asarray(p, dtype=complex))

    def damp(self):
        """``(natural frequency [rad/s], damping ratio [-], poles)`` per pole, from ``control.damp``."""
        with np.errstate(invalid="ignore", divide="ignore"):  # ζ is undefined for a pole at 0
            wn, zeta, p = control.damp(self.state_space(), doprint=False)
        order = np.lexsort((np.asarray(p).imag, np.asarray(p).real))
        return np.asarray(wn)[order], np.asarray(zeta)[order], np.asarray(p)[order]

    @property
    def stability(self) -> str:
        """One of :data:`STABILITY_LABELS`."""
        return classify_poles(self.poles())

    @property
    def schuler_period(self) -> float:
        """``2π√(R/g)`` [s]."""
        return schuler_period(self.gravity, self.earth_radius)

    def pulse_response(self, accel, duration, *, horizon=None, max_points: int = 20_000):
        """Tilt error for a horizontal acceleration ``accel`` held ``duration`` s from rest.

        By superposition of two step responses of :meth:`error_from_accel`
        (``control.step_response``): ``e(t) = A (s(t) − s(t − T))``.

        Parameters
        ----------
        accel : float
            Acceleration A [m/s²].
        duration : float
            T [s], > 0.
        horizon : float, optional
            End of the response [s]; default ``T`` plus two Schuler periods.
        max_points : int
            Largest number of time samples.

        Returns
        -------
        t, e : ndarray
            Times [s] and tilt error [rad].

        Raises
        ------
        ValueError
            For a non-finite acceleration, a non-positive duration or a horizon shorter than it.
        """
        a = as_float(accel, "accel")
        dur = positive(duration, "accel_duration")
        end = dur + 2.0 * self.schuler_period if horizon is None else positive(horizon, "horizon")
        if end < dur:
            raise ValueError(f"Expected `horizon` >= `accel_duration` ({dur:g} s), got {end:g} s")
        # The response is exact on any grid (zero-order hold of a piecewise-constant
        # input); the grid only has to resolve the peak.
        fastest = float(np.abs(self.poles()).max(initial=0.0))
        dt = min(dur / 20.0, 0.2 / fastest if fastest > 0 else np.inf, end / 2000.0)
        dt = max(dt, end / max_points)
        m = max(1, int(np.ceil(dur / dt)))
        dt = dur / m
        n = int(np.ceil(end / dt))
        t = np.arange(n + 1) * dt
        step = control.step_response(self.error_from_accel(), T=t).outputs
        step = np.asarray(step, dtype=float).reshape(-1)
        shifted = np.concatenate([np.zeros(m), step[:-m]])
        return t, a * (step - shifted)

    def peak_tilt_error(self, accel, duration, *, horizon=None) -> float:
        """Largest |tilt error| [rad] of :meth:`pulse_response`."""
        _, e = self.pulse_response(accel, duration, horizon=horizon)
        return float(np.abs(e).max())

    def summary(self, accel: float = 20.0, duration: float = 20.0, *, horizon=None) -> dict:
        """Poles, damping, natural frequency, stability and peak tilt error as plain data."""
        wn, zeta, p = self.damp()
        end = duration + 2.0 * self.schuler_period if horizon is None else horizon
        return {
            "k_per_s": self.k,
            "l_per_s2": self.l,
            "g_m_s2": self.gravity,
            "R_m": self.earth_radius,
            "schuler_period_s": self.schuler_period,
            "poles": [[float(z.real) + 0.0, float(z.imag) + 0.0] for z in p],
            "damping": [float(v) + 0.0 for v in zeta],
            "natural_frequency_rad_s": [float(v) for v in wn],
            "stability": self.stability,
            "accel_m_s2": as_float(accel, "accel"),
            "accel_duration_s": positive(duration, "accel_duration"),
            "horizon_s": float(end),
            "peak_tilt_error_rad": self.peak_tilt_error(accel, duration, horizon=horizon),
        }


def root_locus_k(l, ks):
    """Closed-loop poles over the position gain k at fixed l: ``1 + k s/(s² + l) = 0``.

    Parameters
    ----------
    l : float
        Integral gain [1/s²].
    ks : array_like
        Values of k [1/s].

    Returns
    -------
    ndarray, shape (len(ks), 2)
        ``control.root_locus_map(...).loci``.
    """
    l = as_float(l, "l")
    ks = as_array(ks, "ks")
    return control.root_locus_map(control.tf([1.0, 0.0], [1.0, 0.0, l]), ks).loci


def root_locus_l(k, ls):
    """Closed-loop poles over the integral gain l at fixed k: ``1 + l/(s(s + k)) = 0``."""
    k = as_float(k, "k")
    ls = as_array(ls, "ls")
    return control.root_locus_map(control.tf([1.0], [1.0, k, 0.0]), ls).loci
