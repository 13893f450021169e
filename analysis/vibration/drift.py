"""Mean coning drift and sculling rectification of an algorithm in a vibration environment, in closed form.

Derivation (second order in the vibration amplitude, exact in ωh)
------------------------------------------------------------------
Let the body rate and specific force of one line be ``Re(Z e^{iωt})``,
``Z = (A, B)``, A the rate and B the specific-force amplitude, and let the
sensor chain of :mod:`strapdown.analysis.vibration.sensor_dynamics` have the
equivalent responses ``H_c(ω)`` per channel: the algorithm receives exactly
the increments of ``Re(H A e^{iωt})`` (and of ``Re(H B e^{iωt})``).

*Truth.*  To second order the attitude's rotation vector grows at the mean
non-commutativity rate ``⟨½ θ × ω⟩`` (θ = ∫ω), plus the constant second-order
body rate; with ``⟨Re(a e^{iωt}) × Re(b e^{iωt})⟩ = ½ Re(a × b̄)`` this is
``q/(2ω)`` with the *coning vector*

    q = ½ Im(A × Ā) = −Im w(P_ωω),     P_ab = ½ conj(Z_a) Z_b,

``w(M) = (M_yz − M_zy, M_zx − M_xz, M_xy − M_yx)``.

*Algorithm.*  The computed attitude grows at the mean rate of its step
composition (``½ Θ_n × P_n``, a geometric series in the step phase) plus its
terms ``c_ij p_i × p_j``; both are means of products of sinusoids sampled at
the steps, hence exact.  Written with the sensed amplitudes ``Ã = H A`` the
algorithm's mean rate differs from the truth *of the sensed motion*
``q̃/(2ω)`` (``q̃ = ½ Im(Ã × conj Ã)``) by exactly the classical coning drift
of the algorithm,

    u_algorithm = q̃ · D(ωh) / ω,      D(x) = [E(Nx) − Σ_l k_l R_l(x)] / (N x),

the closed form of :func:`strapdown.derivations.coning.drift.coning_drift`
(derived from the exact one-step formula; for classical coning q = α²ω²
gives u = α² ω D).  Only the pairwise terms act, through their lag sums
``k_l`` (cross-step pairs included); nested and dot terms are of higher order.
The constant second-order body rate passes the sensors (unit gain at zero
frequency) and cancels between truth and algorithm.

*Drift* (exact minus algorithm, package convention) is then the sum of

* the **sensor part** (pseudo-coning) ``u_sensor = (q − q̃)/(2ω)``: what even
  an exact integration of the sensed motion would miss.  Identical filters on
  the three axes give ``q̃ = |H|² q``; filters that differ between axes mix the
  in-phase part of A into q̃, so in-phase vibration on two axes then cones
  too;
* the **algorithm part** ``u_algorithm`` above, the algorithm's own residual
  on the motion it is given.

*Sculling.*  By the transfer principle (ω → ω + s a, Lebedev & Panov 1989,
eq. (2.5)) the velocity algorithm is the algorithm's dual extension and the
rectification error is the dual part of the same formulas, with the
*sculling vector* ``q_s = Im(A × B̄) = −2 Im w(P_ωa)`` in place of q and the
gyro and accelerometer responses on A and B: sensor part
``(q_s − q̃_s)/(2ω)`` (pseudo-sculling, including a phase mismatch between
gyro and accelerometer filters) and algorithm part ``q̃_s D(ωh)/ω``, both the
rate of ``ΔW_I = W_I,true − W_I,computed`` [m/s²] (positive: the algorithm
under-rectifies).

*Lines of one frequency* are coherent (one rotor): their amplitudes add
before the bilinear forms are taken, and they make one part
(:func:`coherent_groups`).

*Spectra.*  Each band of a spectrum adds incoherent lines, ``P = G(f) df``:
the drift is ``∫ u(f) df`` with the same integrand, taken by composite
Gauss–Legendre quadrature in log f, every table frequency a break point
(:func:`strapdown.analysis.core.quadrature.integrate`, to
:data:`QUADRATURE_RTOL` of the integral of the integrand's magnitude).

*Lines of different frequencies* add their drifts only where no pair of them
aliases: the cross terms of two lines oscillate at ``f₁ ± f₂``, and where the
sum or the difference is a multiple of the step rate 1/H the algorithm samples
them at one phase and they leave a phase-locked mean.  Such a pair adds a part
of kind ``"alias"`` (:mod:`strapdown.analysis.vibration.aliasing`, with its
derivation); a pair near an alias is listed in
:attr:`EnvironmentDrift.near_aliases` with its beat period (its mean over many
beats is zero, so it is not in the total).  Components of a stationary spectrum
at different frequencies are uncorrelated and add no such mean.

The quoted quantity: the drift is a vector in the body axes (frame I to this
order), :attr:`EnvironmentDrift.total_vector`, and its magnitude
:attr:`EnvironmentDrift.magnitude`.  A signed value is a *projection*, on an
axis that is named with it: :attr:`EnvironmentDrift.total` is the component
along the environment's *coning axis*, the direction of the true coning rate
Σ q/(2ω) (for a coning line, its axis), so that ``u > 0`` means the computed
attitude lags about that axis; drift about other axes (a tail rotor coning
about y when the main rotor cones about z) is in the vector and the magnitude,
not in that projection.

Public API
----------
.. autosummary::

   DriftPart
   EnvironmentDrift
   environment_drift
   response_integrals
   coherent_groups
   line_response
   QUADRATURE_RTOL

References
----------
Lebedev & Panov (1989), eq. (2.5) (transfer principle); Ignagni (1990, 1998);
Savage (1998), parts 1–2 (pseudo-coning, pseudo-sculling); Mark & Tazartes
(1996) (algorithms and gyro frequency response).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..coning.drift_theory import coning_drift_function
from ..core.quadrature import integrate
from ..core.validation import positive
from .aliasing import NEAR_ALIAS_BEAT, alias_pairs
from .environment import Environment, Spectrum, VibrationLine

__all__ = ["DriftPart", "EnvironmentDrift", "environment_drift", "response_integrals", "coherent_groups", "line_response", "coning_vector", "sculling_vector", "QUADRATURE_RTOL", "ResponseIntegrals"]

#: Relative tolerance of the spectrum quadrature (against the integral of the magnitude).
QUADRATURE_RTOL = 1e-10
#: Gauss–Legendre nodes per table interval of the estimate of the integrand's scale [count].
QUADRATURE_NODES = 16


def _w(m: np.ndarray) -> np.ndarray:
    """``(M_yz − M_zy, M_zx − M_xz, M_xy − M_yx)`` of the 3×3 blocks ``m[..., 3, 3]``."""
    return np.stack([m[..., 1, 2] - m[..., 2, 1], m[..., 2, 0] - m[..., 0, 2], m[..., 0, 1] - m[..., 1, 0]], axis=-1)


def coning_vector(power: np.ndarray) -> np.ndarray:
    """Coning vector ``q = −Im w(P_ωω)`` of cross-power matrices ``P`` (..., 6, 6) [(rad/s)²].

    Parameters
    ----------
    power : ndarray, shape (..., 6, 6)
        ``P_ab = ½ conj(Z_a) Z_b`` of a line, or ``G(f) df`` of a band.

    Returns
    -------
    ndarray, shape (..., 3)
    """
    return -np.imag(_w(power[..., :3, :3]))


def sculling_vector(power: np.ndarray) -> np.ndarray:
    """Sculling vector ``q_s = −2 Im w(P_ωa)`` of cross-power matrices (..., 6, 6) [(rad/s)(m/s²)].

    Parameters
    ----------
    power : ndarray, shape (..., 6, 6)
        Cross-power matrices.

    Returns
    -------
    ndarray, shape (..., 3)
    """
    return -2.0 * np.imag(_w(power[..., :3, 3:]))


def _sensed(power: np.ndarray, response: np.ndarray) -> np.ndarray:
    """``conj(H_a) H_b P_ab``."""
    return np.conj(response)[..., :, None] * response[..., None, :] * power


class ResponseIntegrals:
    """Integrals of the drift integrand against a set of algorithm response functions.

    For response functions ``φ_j(x)`` of x = ωh, the totals over the lines and
    spectra of an environment of

    * ``true``: ``q/(2ω)`` and ``q_s/(2ω)``,
    * ``sensed``: ``q̃/(2ω)`` and ``q̃_s/(2ω)``,
    * ``algorithm[j]``: ``q̃ φ_j(ωh)/ω`` and ``q̃_s φ_j(ωh)/ω``,

    each as a pair of vectors (coning [rad/s], sculling [m/s²]), per part
    (line or spectrum).  With ``φ = D`` of an algorithm this is its drift; with
    the lag responses it is the linear model of the tuning
    (:mod:`strapdown.analysis.vibration.tuning`).

    Attributes
    ----------
    parts : list of (kind, label, band)
        One entry per line or spectrum.
    true, sensed : ndarray, shape (parts, 2, 3)
    algorithm : ndarray, shape (functions, parts, 2, 3)
    """

    def __init__(self, parts, true, sensed, algorithm):
        self.parts, self.true, self.sensed, self.algorithm = parts, true, sensed, algorithm


def _integrand(environment: Environment, sample_interval: float, functions, freq: np.ndarray, power: np.ndarray) -> np.ndarray:
    """Columns (true c, true s, sensed c, sensed s, alg_j c, alg_j s …), shape (n, 2 + 2 + 2J, 3)."""
    omega = 2.0 * math.pi * freq
    response = environment.response(omega, sample_interval)
    sensed = _sensed(power, response)
    q, qs = coning_vector(power), sculling_vector(power)
    qt, qts = coning_vector(sensed), sculling_vector(sensed)
    inv = (1.0 / omega)[:, None]
    cols = [0.5 * q * inv, 0.5 * qs * inv, 0.5 * qt * inv, 0.5 * qts * inv]
    x = omega * sample_interval
    for phi in functions:
        v = np.asarray(phi(x), dtype=float).reshape(-1)[:, None] * inv
        cols += [qt * v, qts * v]
    return np.stack(cols, axis=1)


def _spectrum_integral(environment, sample_interval, functions, spectrum: Spectrum, rtol: float) -> np.ndarray:
    """∫ integrand df over the spectrum's table, in u = ln f (:func:`strapdown.analysis.core.quadrature.integrate`)."""

    def g(u):
        f = np.exp(u)
        vals = _integrand(environment, sample_interval, functions, f, spectrum.at(f)) * f[:, None, None]
        return np.moveaxis(vals, 0, -1)

    edges = np.log(spectrum.frequency)
    nodes, weights = np.polynomial.legendre.leggauss(QUADRATURE_NODES)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    u = (mid[:, None] + half[:, None] * nodes[None, :]).ravel()
    w = (half[:, None] * weights[None, :]).ravel()
    scale = np.abs(g(u)) @ w  # ∫|integrand|, the scale of the absolute tolerance of each element
    return integrate(g, edges, rtol=rtol, atol=rtol * float(np.max(scale)), panels=1)


def coherent_groups(lines) -> list:
    """Lines grouped by frequency, in order of first appearance: lines of one frequency are coherent.

    Two lines of the same frequency (a coning and a sculling line of one rotor)
    have a fixed relative phase, so their cross terms do not average out: the
    closed form takes their sum as one line.

    Parameters
    ----------
    lines : sequence of VibrationLine
        The lines.

    Returns
    -------
    list of list of VibrationLine
    """
    groups: dict = {}
    for ln in lines:
        groups.setdefault(ln.frequency, []).append(ln)
    return list(groups.values())


def response_integrals(environment: Environment, sample_interval: float, functions, *, rtol: float = QUADRATURE_RTOL) -> ResponseIntegrals:
    """Truth, sensed truth and algorithm responses of every line and spectrum (:class:`ResponseIntegrals`).

    Parameters
    ----------
    environment : Environment
        Lines, spectra and sensors.
    sample_interval : float
        Algorithm sample interval h [s], > 0.
    functions : sequence of callable
        Response functions ``φ_j(x)`` of x = ωh (vectorised).
    rtol : float, keyword-only
        Relative tolerance of the spectrum quadrature.

    Returns
    -------
    ResponseIntegrals

    Raises
    ------
    TypeError
        If ``environment`` is not an :class:`Environment`.
    ValueError
        For a non-positive sample interval, a digital filter whose cut-off
        lies above the sensor's Nyquist frequency at this interval, or an
        interval at which a spectrum's integral does not converge (naming
        ``sample_interval``).
    """
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    h = positive(sample_interval, "sample_interval")
    functions = tuple(functions)
    parts, values = [], []
    if environment.lines:
        groups = coherent_groups(environment.lines)
        freq = np.array([g[0].frequency for g in groups])
        power = np.stack([VibrationLine(g[0].frequency, sum(ln.amplitude for ln in g)).power for g in groups])
        values.extend(_integrand(environment, h, functions, freq, power))
        parts.extend(("line", " + ".join(ln.label for ln in g), (g[0].frequency, g[0].frequency)) for g in groups)
    for s in environment.spectra:
        try:
            values.append(_spectrum_integral(environment, h, functions, s, rtol))
        except ValueError as exc:
            raise ValueError(
                f"Expected `sample_interval` = {h:g} s to give a response integral over spectrum {s.label!r} that converges; "
                f"it does not ({exc}): the sensors' and the algorithm's responses are not resolved at this interval"
            ) from None
        parts.append(("spectrum", s.label, s.band))
    n = len(parts)
    arr = np.zeros((n, 4 + 2 * len(functions), 3)) if not values else np.stack(values)
    true = arr[:, 0:2]
    sensed = arr[:, 2:4]
    alg = np.stack([arr[:, 4 + 2 * j : 6 + 2 * j] for j in range(len(functions))]) if functions else np.zeros((0, n, 2, 3))
    return ResponseIntegrals(parts, true, sensed, alg)


@dataclass(frozen=True, eq=False)
class DriftPart:
    """Drift and rectification of one line or one spectrum.

    Attributes
    ----------
    kind : str
        ``"line"``, ``"spectrum"`` or ``"alias"`` (the cross terms of two lines
        whose sum or difference frequency is a multiple of the step rate: an
        algorithm part only, :mod:`strapdown.analysis.vibration.aliasing`).
    label : str
        Its name.
    band : tuple of float
        Its frequency (twice for a line), band, or the two lines' frequencies (alias) [Hz].
    true_coning : ndarray (3,)
        Mean non-commutativity rate of the true motion ``q/(2ω)`` [rad/s].
    sensor : ndarray (3,)
        Pseudo-coning drift ``(q − q̃)/(2ω)`` [rad/s].
    algorithm : ndarray (3,)
        The algorithm's residual on the sensed motion ``q̃ D(ωh)/ω`` [rad/s].
    true_rectification : ndarray (3,)
        Rectified specific force of the true motion ``q_s/(2ω)`` [m/s²].
    sensor_sculling : ndarray (3,)
        Pseudo-sculling rectification error [m/s²].
    algorithm_sculling : ndarray (3,)
        The velocity algorithm's residual [m/s²].
    """

    kind: str
    label: str
    band: tuple
    true_coning: np.ndarray
    sensor: np.ndarray
    algorithm: np.ndarray
    true_rectification: np.ndarray
    sensor_sculling: np.ndarray
    algorithm_sculling: np.ndarray

    @property
    def total(self) -> np.ndarray:
        """Coning drift vector, sensor plus algorithm [rad/s]."""
        return self.sensor + self.algorithm

    @property
    def total_sculling(self) -> np.ndarray:
        """Rectification error vector, sensor plus algorithm [m/s²]."""
        return self.sensor_sculling + self.algorithm_sculling


def _axis(primary: np.ndarray, fallback: np.ndarray) -> np.ndarray:
    for v in (primary, fallback):
        n = float(np.linalg.norm(v))
        if n > 0.0:
            return v / n
    return np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class EnvironmentDrift:
    """Mean coning drift and sculling rectification of an algorithm in an environment.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm (its dual extension is the velocity algorithm).
    sample_interval : float
        h [s].
    parts : tuple of DriftPart
        One per line frequency (coherent lines together) and spectrum, in the environment's order.
    coning_axis : ndarray (3,)
        Unit direction of the true coning rate (module docstring); signed drifts are along it.
    sculling_axis : ndarray (3,)
        Unit direction of the true rectified specific force.
    near_aliases : tuple of AliasPair
        Pairs of lines near an alias with the step rate, with their beat
        period (not in the mean: it averages out over many beats).
    """

    algorithm: Algorithm
    sample_interval: float
    parts: tuple
    coning_axis: np.ndarray
    sculling_axis: np.ndarray
    near_aliases: tuple = ()

    def _sum(self, name):
        return sum((getattr(p, name) for p in self.parts), np.zeros(3))

    @property
    def total_vector(self) -> np.ndarray:
        """Coning drift vector [rad/s] (exact minus algorithm)."""
        return self._sum("total")

    @property
    def sensor_vector(self) -> np.ndarray:
        """Pseudo-coning part [rad/s]."""
        return self._sum("sensor")

    @property
    def algorithm_vector(self) -> np.ndarray:
        """Algorithm residual [rad/s]."""
        return self._sum("algorithm")

    @property
    def magnitude(self) -> float:
        """``|total_vector|``, the drift rate [rad/s]: the one number to quote."""
        return float(np.linalg.norm(self.total_vector))

    @property
    def sculling_magnitude(self) -> float:
        """``|sculling_vector|``, the rectification-error rate [m/s²]."""
        return float(np.linalg.norm(self.sculling_vector))

    @property
    def total(self) -> float:
        """Projection of the drift on the coning axis [rad/s] (a component, not the drift rate: see :attr:`magnitude`)."""
        return float(self.total_vector @ self.coning_axis)

    @property
    def sensor(self) -> float:
        """Projection of the pseudo-coning on the coning axis [rad/s]."""
        return float(self.sensor_vector @ self.coning_axis)

    @property
    def algorithm_part(self) -> float:
        """Projection of the algorithm residual on the coning axis [rad/s]."""
        return float(self.algorithm_vector @ self.coning_axis)

    @property
    def sculling_vector(self) -> np.ndarray:
        """Rectification error vector [m/s²]."""
        return self._sum("total_sculling")

    @property
    def sculling(self) -> float:
        """Projection of the rectification error on the sculling axis [m/s²]."""
        return float(self.sculling_vector @ self.sculling_axis)

    @property
    def sensor_sculling(self) -> float:
        """Signed pseudo-sculling along the sculling axis [m/s²]."""
        return float(self._sum("sensor_sculling") @ self.sculling_axis)

    @property
    def algorithm_sculling(self) -> float:
        """Signed velocity-algorithm residual along the sculling axis [m/s²]."""
        return float(self._sum("algorithm_sculling") @ self.sculling_axis)


def environment_drift(algorithm: Algorithm, environment: Environment, sample_interval: float, *, rtol: float = QUADRATURE_RTOL,
                      min_beat_period: float = NEAR_ALIAS_BEAT) -> EnvironmentDrift:  # fmt: skip
    """Mean coning drift and sculling rectification of ``algorithm`` in ``environment`` (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        Registry or file algorithm (cross-step indices allowed); its dual
        extension is the velocity algorithm.
    environment : Environment
        Lines, spectra and sensors.
    sample_interval : float
        Algorithm sample interval h [s], > 0 (step H = N h).
    rtol : float, keyword-only
        Relative tolerance of the spectrum quadrature.
    min_beat_period : float, keyword-only
        Pairs of lines whose beat with the step rate is longer than this are
        listed as near an alias [s] (:func:`strapdown.analysis.vibration.aliasing.alias_pairs`).

    Returns
    -------
    EnvironmentDrift

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm or ``environment`` not an Environment.
    ValueError
        For a non-positive sample interval or a digital filter above the
        sensor's Nyquist frequency.

    References
    ----------
    Lebedev & Panov (1989), eq. (2.5); Ignagni (1990); Savage (1998).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> from strapdown.analysis.vibration.environment import coning_line
    >>> from strapdown.analysis.vibration.sensor_dynamics import Sensor, ChannelFilter, analog_filter
    >>> lp = ChannelFilter(analog_filter("lowpass1", cutoff_hz=100.0))
    >>> env = Environment((coning_line(10.0, math.radians(1.0)),), gyro=Sensor((lp, lp, lp)))
    >>> d = environment_drift(get("two-sample"), env, 1e-3)
    >>> round(d.sensor * 180 / math.pi * 3600, 2)    # pseudo-coning [deg/h]
    19.54
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    D = coning_drift_function(algorithm)
    r = response_integrals(environment, sample_interval, (D,), rtol=rtol)
    parts = []
    for i, (kind, label, band) in enumerate(r.parts):
        true, sensed, alg = r.true[i], r.sensed[i], r.algorithm[0, i]
        parts.append(DriftPart(kind, label, tuple(band), true[0], true[0] - sensed[0], alg[0], true[1], true[1] - sensed[1], alg[1]))
    pairs = alias_pairs(algorithm, environment, sample_interval, min_beat_period=min_beat_period)
    zero = np.zeros(3)
    for p in pairs:
        if p.exact:
            label = f"{p.labels[0]} × {p.labels[1]} ({p.kind} {p.multiple}/H)"
            parts.append(DriftPart("alias", label, p.frequencies, zero, zero, p.drift, zero, zero, p.sculling))
    total = sum((p.total for p in parts), np.zeros(3))
    scull = sum((p.total_sculling for p in parts), np.zeros(3))
    c_axis = _axis(r.true[:, 0].sum(axis=0) if r.parts else np.zeros(3), total)
    s_axis = _axis(r.true[:, 1].sum(axis=0) if r.parts else np.zeros(3), scull)
    return EnvironmentDrift(algorithm, float(sample_interval), tuple(parts), c_axis, s_axis, tuple(p for p in pairs if not p.exact))


def line_response(algorithm: Algorithm, line: VibrationLine, environment: Environment, sample_interval: float) -> DriftPart:
    """The drift of one line seen through the sensors of ``environment`` (its own lines and spectra ignored).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    line : VibrationLine
        The line.
    environment : Environment
        Supplies the sensors.
    sample_interval : float
        h [s].

    Returns
    -------
    DriftPart
    """
    env = Environment((line,), (), environment.gyro, environment.accelerometer)
    return environment_drift(algorithm, env, sample_interval).parts[0]
