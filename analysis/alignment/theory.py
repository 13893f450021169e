"""Theory of the self-alignment errors, term by term, to first order.

Analytic method (:func:`analytic_theory`).  With the gains of
:mod:`strapdown.derivations.alignment.analytic_gains` (generated once into
numerical code, :func:`strapdown.analysis.core.cache.compiled`), the azimuth
error of the analytic alignment over a time T is, to first order,

* fixed gyro bias b: ``G_ω b`` (at ψ0 = β0 = γ0 = 0: ``−b_E/(Ω cos φ)``, the
  gyro-bias floor);
* fixed accelerometer bias a: ``G_t T_f a`` (``tan φ · a_E/g``);
* scale factors s: ``G_ω (s ⊙ ω0)``, ``G_t T_f (s ⊙ f0)``;
* random turn-on biases of standard deviation σ: ``|G_ω| σ_g``, ``|G_t T_f| σ_a``;
* white noise (angle and velocity random walk N): ``|G_ω| N_g/√T``, ``|G_t T_f| N_a/√T``;
* quantisation q of the accumulated outputs: the error of a sum telescopes to
  ``q (floor(u + X) − X)`` with X the true sum in quanta and u the uniform initial
  residue, a two-point error of variance ``q² f (1 − f)``, ``f = frac(X)``;
  averaged over the spread s of X (noise, rocking) it is
  ``q² [1/6 − Σ_k cos(2πkμ/q) e^{−2π²k²s²/q²}/(π²k²)]`` (1/6 when s ≫ q), and
  the azimuth error is ``G_ω`` (``G_t T_f``) times these errors over T;
* rocking: the linear functional
  ``Σ_a Re[c_a H_a(ω)]`` with ``H_a = [k_mean (e^{iωT} − 1)/(iωT) + k_inc (e^{iωT} − 1)/T + k_rate iω(e^{iωT} − 1)/T]_a``:
  the mean angle θ̄ (through the accelerometers and through the Earth rate the
  rocked gyros see), the angle gained over the window (the body rate averaged
  by the gyros) and the lever-arm acceleration averaged by the accelerometers;
  its variance is the integral of the rocking's continuous spectral density
  against ``|H_a|²`` (the models' ``covariance``; for sinusoids the sum over
  their lines), exact for the process the simulation realises.  For a sinusoid the residue of each axis is
  a sinusoid of amplitude ``a_a |H_a|``; its envelope over phase replaces
  ``|H_a(ω, T)|`` by its largest value over alignment times in ``[T, T + 2π/ω]``.

Kalman filter (:func:`kalman_theory`): the linear filter's own response to the
fixed biases (the noise-free error propagated through the closed loop,
``e⁺ = (I − K H) F e``) and its posterior standard deviation of the azimuth.

Second-order effects (the tilt-channel curvature of Hrechka & Koroliov, the
coning rectification of the rocking in the gyros, products of errors) are not
included; :mod:`strapdown.analysis.gyrocompass.azimuth` has the tilt channel to
second order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.cache import compiled
from ..gyrocompass.error_distribution import ErrorQuantile, abs_error_quantile
from .base_motion import mean_transfer
from .earth import EARTH_RATE, normal_gravity
from .imu import Scenario, SensorErrors

__all__ = ["AnalyticGainValues", "analytic_gain_values", "AnalyticTheory", "analytic_theory", "rocking_transfer", "quantisation_variance", "KalmanTheory", "kalman_theory", "bias_floor"]


@dataclass(frozen=True)
class AnalyticGainValues:
    """Numerical gains of the analytic alignment at the stable state of a scenario.

    Attributes
    ----------
    G_omega : ndarray
        ``(3,)`` ``∂ψ̂/∂ω̄`` [s].
    G_tilt : ndarray
        ``(2,)`` ``∂ψ̂/∂(β̂, γ̂)``.
    T_f : ndarray
        ``(2, 3)`` ``∂(β, γ)/∂f`` [s²/m].
    D : ndarray
        ``(3, 3)`` ``∂(C_n^b ω_ie^n)/∂θ`` [rad/s].
    J : ndarray
        ``(3, 3)`` Euler-rate matrix.
    omega0 : ndarray
        ``(3,)`` Earth rate in body axes [rad/s].
    f0 : ndarray
        ``(3,)`` specific force in body axes [m/s²].
    """

    G_omega: np.ndarray
    G_tilt: np.ndarray
    T_f: np.ndarray
    D: np.ndarray
    J: np.ndarray
    omega0: np.ndarray
    f0: np.ndarray

    @property
    def G_accel(self) -> np.ndarray:
        """``(3,)`` ``G_t T_f``: the azimuth per unit specific-force error [s²/m]."""
        return self.G_tilt @ self.T_f


def _gain_function(formula: str):
    def build():
        from ...derivations.alignment.analytic_gains import gain_expressions

        return gain_expressions(formula)

    return compiled(f"gyrocompass:analytic-alignment-gains:{formula}:v1", build)


def analytic_gain_values(scenario: Scenario, formula: str = "levelled") -> AnalyticGainValues:
    """Evaluate the derived gains at the stable state of ``scenario``.

    Parameters
    ----------
    scenario : Scenario
        Latitude and stable attitude.
    formula : str
        ``"levelled"`` or ``"paper"``.

    Returns
    -------
    AnalyticGainValues

    Raises
    ------
    ValueError
        For an unknown formula.
    """
    if formula not in ("levelled", "paper"):
        raise ValueError(f"Expected `formula` in ('levelled', 'paper'), got {formula!r}")
    sc = scenario
    v = np.array(_gain_function(formula)(sc.latitude, sc.heading, sc.beta0, sc.gamma0, EARTH_RATE, normal_gravity(sc.latitude)), dtype=float)
    sizes, shapes = (3, 2, 6, 9, 9, 3, 3), ((3,), (2,), (2, 3), (3, 3), (3, 3), (3,), (3,))
    parts, k = [], 0
    for size, shape in zip(sizes, shapes):
        parts.append(v[k : k + size].reshape(shape))
        k += size
    return AnalyticGainValues(*parts)


def rocking_transfer(gains: AnalyticGainValues, scenario: Scenario, omega, duration: float) -> np.ndarray:
    """``H_a(ω)``: the azimuth error per unit complex rocking coefficient of each axis.

    Parameters
    ----------
    gains : AnalyticGainValues
        From :func:`analytic_gain_values`.
    scenario : Scenario
        Lever arm and whether the rocking reaches the gyros.
    omega : array_like
        ``(M,)`` rocking frequencies [rad/s].
    duration : float
        Alignment time T [s].

    Returns
    -------
    ndarray
        ``(3, M)`` complex.
    """
    w = np.asarray(omega, dtype=float)
    T = float(duration)
    E = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    k_mean = gains.G_tilt @ E
    k_inc = np.zeros(3)
    if scenario.rocking_in_gyros:
        k_mean = k_mean + gains.G_omega @ gains.D
        k_inc = gains.G_omega @ gains.J
    r = scenario.lever_arm
    rx = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    k_rate = gains.G_accel @ (-rx @ gains.J)
    e = np.exp(1j * w * T) - 1.0
    mean = mean_transfer(T)(w)
    return k_mean[:, None] * mean[None, :] + (k_inc[:, None] / T) * e[None, :] + (k_rate[:, None] / T) * (1j * w * e)[None, :]


@dataclass(frozen=True)
class AnalyticTheory:
    """First-order azimuth error of the analytic alignment, term by term [rad].

    Attributes
    ----------
    gyro_bias, accel_bias, gyro_scale, accel_scale : float
        Deterministic errors of the fixed biases and scale factors.
    gyro_bias_random, accel_bias_random : float
        Standard deviations from the random turn-on biases.
    gyro_noise, accel_noise : float
        Standard deviations from the white noise.
    gyro_quantisation, accel_quantisation : float
        Standard deviations from the quantisation.
    rocking : float
        rms of the rocking term (over its random phases or amplitudes).
    rocking_sine_amplitudes : ndarray
        ``(3,)`` amplitudes of the sinusoidal residues per axis (sine rocking), else empty.
    gaussian_rocking : bool
        The rocking term is Gaussian (narrow-band, white).
    """

    gyro_bias: float
    accel_bias: float
    gyro_scale: float
    accel_scale: float
    gyro_bias_random: float
    accel_bias_random: float
    gyro_noise: float
    accel_noise: float
    gyro_quantisation: float
    accel_quantisation: float
    rocking: float
    rocking_sine_amplitudes: np.ndarray
    gaussian_rocking: bool

    @property
    def mean(self) -> float:
        """The deterministic part (biases and scale factors) [rad]."""
        return self.gyro_bias + self.accel_bias + self.gyro_scale + self.accel_scale

    @property
    def sensor_sigma(self) -> float:
        """Standard deviation of the random sensor terms [rad]."""
        return math.sqrt(sum(x * x for x in (self.gyro_bias_random, self.accel_bias_random, self.gyro_noise, self.accel_noise, self.gyro_quantisation, self.accel_quantisation)))

    @property
    def std(self) -> float:
        """Standard deviation of the azimuth error [rad]."""
        return math.hypot(self.sensor_sigma, self.rocking)

    @property
    def rms(self) -> float:
        """``√(mean² + std²)`` [rad]."""
        return math.hypot(self.mean, self.std)

    def quantile(self, level: float) -> ErrorQuantile:
        """Percentile of the absolute azimuth error (sinusoidal residues bounded, the rest Gaussian).

        Parameters
        ----------
        level : float
            Probability in (0, 1).

        Returns
        -------
        ErrorQuantile
        """
        if self.gaussian_rocking or self.rocking_sine_amplitudes.size == 0:
            return abs_error_quantile([], self.std, level, mean=self.mean)
        return abs_error_quantile(self.rocking_sine_amplitudes, self.sensor_sigma, level, mean=self.mean)


def _norm(x) -> float:
    return float(np.sqrt(np.sum(np.square(x))))


def quantisation_variance(total, spread, quantum) -> np.ndarray:
    """Variance of the quantisation error of a telescoped sum [unit of ``quantum`` squared].

    Parameters
    ----------
    total : array_like
        Mean true sum μ of the output over the record.
    spread : array_like
        Standard deviation s of that sum across trials.
    quantum : float
        Output quantum q (0: none).

    Returns
    -------
    ndarray
        ``q² E[f (1 − f)]``, ``f = frac(X/q)``, ``X ~ N(μ, s²)``.

    Examples
    --------
    >>> float(quantisation_variance(0.5, 0.0, 1.0)), round(float(quantisation_variance(0.3, 10.0, 1.0)), 12)
    (0.25, 0.166666666667)
    """
    q = float(quantum)
    mu, s = np.asarray(total, dtype=float), np.asarray(spread, dtype=float)
    if q <= 0:
        return np.zeros(np.broadcast(mu, s).shape)
    mu, s = np.broadcast_arrays(mu / q, s / q)
    f = mu - np.floor(mu)
    # narrow spread: the parabola f(1 − f) smoothed by N(0, s²) loses s² (the Fourier series converges slowly there)
    v = f * (1.0 - f) - s * s
    wide = s >= 0.01
    if np.any(wide):
        k = np.arange(1, 401)[:, None]
        terms = np.cos(2.0 * math.pi * k * mu[wide]) * np.exp(-2.0 * (math.pi * k * s[wide]) ** 2) / (math.pi * k) ** 2
        v = np.array(v, dtype=float)
        v[wide] = 1.0 / 6.0 - terms.sum(axis=0)
    return q * q * np.maximum(v, 0.0)


def analytic_theory(scenario: Scenario, errors: SensorErrors | None = None, *, formula: str = "levelled", envelope: bool = False, envelope_points: int = 64) -> AnalyticTheory:
    """First-order theory of the analytic alignment of ``scenario`` with ``errors``.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, rocking, lever arm, sampling and T.
    errors : SensorErrors, optional
        Sensor errors (default ideal).
    formula : str
        ``"levelled"`` or ``"paper"``.
    envelope : bool
        For sinusoidal rocking: the envelope over phase (worst alignment time in
        ``[T, T + period]``) instead of the value at T.
    envelope_points : int
        Alignment times tried per period for the envelope.

    Returns
    -------
    AnalyticTheory

    References
    ----------
    Hrechka & Koroliov, eqs. (2), (16) (the method); the gains are derived in
    :mod:`strapdown.derivations.alignment.analytic_gains`.

    Examples
    --------
    The gyro-bias floor at zero heading and tilt:

    >>> sc = Scenario(math.radians(60.0), duration=60.0)
    >>> b = math.radians(0.01) / 3600.0
    >>> t = analytic_theory(sc, SensorErrors(gyro_bias=[0.0, b, 0.0]))
    >>> round(t.gyro_bias / (-b / (EARTH_RATE * math.cos(math.radians(60.0)))), 12)
    1.0
    """
    e = SensorErrors() if errors is None else errors
    G = analytic_gain_values(scenario, formula)
    T = scenario.n_samples * scenario.dt
    Ga = G.G_accel
    gw, ga = _norm(G.G_omega), _norm(Ga)
    motion = scenario.motion
    gaussian = bool(getattr(motion, "gaussian", False))
    lines = None if gaussian else motion.spectrum(scenario.n_samples, scenario.dt)
    sine = np.zeros(0)
    if lines is not None and envelope and lines.omega.size == 1:
        # a sinusoid: the envelope over phase, |H| at its worst alignment time in [T, T + period]
        period = 2.0 * math.pi / lines.omega[0]
        Ts = T + period * np.arange(envelope_points) / envelope_points
        mags = np.array([np.abs(rocking_transfer(G, scenario, lines.omega, t))[:, 0] for t in Ts]).max(axis=0)
        rocking = math.sqrt(float(np.sum(lines.power[:, 0] * mags**2)))
        sine = np.sqrt(2.0 * lines.power[:, 0]) * mags
    else:
        rocking = math.sqrt(float(np.sum(motion.covariance(lambda w: rocking_transfer(G, scenario, w, T), dt=scenario.dt))))
        if lines is not None and lines.omega.size == 1:
            sine = np.sqrt(2.0 * lines.power[:, 0]) * np.abs(rocking_transfer(G, scenario, lines.omega, T)[:, 0])
    return AnalyticTheory(
        gyro_bias=float(G.G_omega @ e.gyro_bias),
        accel_bias=float(Ga @ e.accel_bias),
        gyro_scale=float(G.G_omega @ (e.gyro_scale * G.omega0)),
        accel_scale=float(Ga @ (e.accel_scale * G.f0)),
        gyro_bias_random=gw * e.gyro_bias_sigma,
        accel_bias_random=ga * e.accel_bias_sigma,
        gyro_noise=gw * e.gyro_noise / math.sqrt(T),
        accel_noise=ga * e.accel_noise / math.sqrt(T),
        gyro_quantisation=_quantised(G.G_omega, G.omega0 + e.gyro_bias, e.gyro_noise, e.gyro_quantum, T),
        accel_quantisation=_quantised(Ga, G.f0 + e.accel_bias, e.accel_noise, e.accel_quantum, T),
        rocking=rocking,
        rocking_sine_amplitudes=sine,
        gaussian_rocking=gaussian,
    )


def _quantised(gain, rate, noise, quantum, T) -> float:
    """Azimuth standard deviation from the quantisation of the sums of one sensor triad."""
    if quantum <= 0:
        return 0.0
    var = quantisation_variance(np.asarray(rate) * T, noise * math.sqrt(T), quantum)
    return math.sqrt(float(np.sum(np.asarray(gain) ** 2 * var))) / T


def bias_floor(scenario: Scenario, errors: SensorErrors) -> tuple:
    """``(gyro, accel)``: the first-order azimuth errors of the fixed biases at the stable state [rad].

    The same for every self-alignment method to first order in ``ΩT``: the
    east gyro bias cannot be told from an azimuth error, nor the horizontal
    accelerometer biases from tilts.

    Parameters
    ----------
    scenario : Scenario
        Latitude and stable attitude.
    errors : SensorErrors
        The fixed biases.

    Returns
    -------
    tuple of float
    """
    G = analytic_gain_values(scenario, "levelled")
    return float(G.G_omega @ errors.gyro_bias), float(G.G_accel @ errors.accel_bias)


@dataclass(frozen=True)
class KalmanTheory:
    """What the linear filter predicts for its own azimuth error at the end of the alignment [rad].

    Attributes
    ----------
    gyro_bias : float
        Response to the fixed gyro bias (noise-free closed loop).
    accel_bias : float
        Response to the fixed accelerometer bias.
    sigma : float
        The filter's posterior standard deviation of the azimuth error.
    """

    gyro_bias: float
    accel_bias: float
    sigma: float


def kalman_theory(scenario: Scenario, errors: SensorErrors, model, sequence) -> KalmanTheory:
    """The filter's linear prediction of its azimuth error (no simulation).

    The true error state with only the fixed biases, ``e_0 = (0, 0, C0 b_g, C0 b_a, 0)``,
    is propagated through the closed loop, ``e⁺ = (I − K_k H) F e``; the azimuth
    error is ``−φ_D``.

    Parameters
    ----------
    scenario : Scenario
        Stable attitude.
    errors : SensorErrors
        Fixed biases.
    model : FineAlignmentModel
        The filter's model.
    sequence : FilterSequence
        Its gains and covariances.

    Returns
    -------
    KalmanTheory
    """
    from .tilt_attitude import attitude_matrix

    C0 = attitude_matrix(scenario.stable_angles)
    out = []
    for part in ("gyro", "accel"):
        e = np.zeros(model.dim)
        if part == "gyro":
            e[6:9] = C0 @ errors.gyro_bias
        else:
            e[9:12] = C0 @ errors.accel_bias
        for K in sequence.gains:
            e = model.F @ e
            e = e - K @ (model.H @ e)
        out.append(-float(e[2]))
    return KalmanTheory(out[0], out[1], float(math.sqrt(sequence.posterior[-1, 2, 2])))
