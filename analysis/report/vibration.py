"""Report section ``vibration.md``: coning and sculling in a vibration environment.

Formatting only: the numbers come from
:mod:`strapdown.analysis.vibration.drift` (closed form),
:mod:`~strapdown.analysis.vibration.simulation` (DOP853),
:mod:`~strapdown.analysis.vibration.monte_carlo`,
:mod:`~strapdown.analysis.vibration.tuning` and
:mod:`~strapdown.analysis.vibration.rate_design`, on the example environment
the package's example environment
:data:`strapdown.analysis.vibration.examples.QUALIFICATION`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ...derivations.coning.drift import X
from ...derivations.coning.registry import get
from ...derivations.coning.tuned import RHO, lowpass_null_coefficient, two_sample_null_coefficient
from ..coning.drift_theory import optimal_coning_algorithm
from ..core.cache import derived
from ..core.units import DEG, DEG_PER_RT_H_TO_RAD_PER_RT_S, RAD_PER_S_TO_DEG_PER_H
from ..vibration.drift import environment_drift
from ..vibration.environment import Environment, VibrationLine, coning_line, load_environment
from ..vibration.examples import QUALIFICATION
from ..vibration.noise import SensorNoise, noise_through_algorithm
from ..vibration.rate_design import rate_design
from ..vibration.sensor_dynamics import ChannelFilter, Sensor, analog_filter, digital_filter
from ..vibration.simulation import filtered_coning_check, line_drift_check
from ..vibration.tuning import drift_across_band, tune
from . import Section
from .rendering import fixed_layout

SECTION = Section(
    "vibration",
    "Coning and sculling in a vibration environment",
    order=37,
    summary=(
        "Mean coning drift and sculling rectification through the sensors' filters, in closed form: pseudo-coning of MEMS filter "
        "settings, a qualification-PSD example, algorithms tuned to it, rate and load design, DOP853 and Monte Carlo checks."
    ),
)

#: Sample interval of the examples [s] (1 kHz algorithm rate).
H = 1e-3
#: Half-cone angle of the coning line of the DOP853 and tuning checks [rad].
ALPHA = 1.0 * DEG
#: Rate amplitude of the swept coning line of the MEMS settings [rad/s] (a fixed half-cone angle of 1° would be
#: 63 deg/s of rate at 10 Hz and 314 deg/s at 50 Hz: extreme motion, not a common one).
RATE = 1.0 * DEG
#: Gyro noise of the noise table: angle random walk [deg/√h] and increment quantum [rad] (a MEMS gyro).
ARW_DEG_PER_RT_H, QUANTUM = 0.3, 1e-6
#: Drift budget of the rate design [deg/h].
BUDGET_DEG_PER_H = 0.5
#: Algorithms of the examples and checks.
CLASSICAL = ("two-sample", "optimal-3", "ignagni-1996-5")
K = RAD_PER_S_TO_DEG_PER_H


def _settings():
    """Common MEMS gyro filter settings: name → gyro Sensor (configuration of this report)."""

    def same(channel, decimation=1):
        return Sensor((channel,) * 3, decimation)

    lp = lambda fc: ChannelFilter(analog_filter("lowpass1", cutoff_hz=fc))  # noqa: E731
    return {
        "first-order 50 Hz": same(lp(50.0)),
        "first-order 100 Hz": same(lp(100.0)),
        "first-order 200 Hz": same(lp(200.0)),
        "Butterworth-2 100 Hz": same(ChannelFilter(analog_filter("butterworth", cutoff_hz=100.0, order=2))),
        "Bessel-2 100 Hz": same(ChannelFilter(analog_filter("bessel", cutoff_hz=100.0, order=2))),
        "DLPF: digital Butterworth-2 92 Hz at 1 kHz": same(ChannelFilter(digital=digital_filter("butterworth", cutoff_hz=92.0, order=2))),
        "moving average of 4 at 4 kHz, decimated by 4": same(ChannelFilter(digital=digital_filter("moving_average", taps=4)), 4),
        "first-order 100 Hz on x, 110 Hz on y": Sensor((lp(100.0), lp(110.0), lp(100.0))),
    }


def _seed(ctx, *key):
    return np.random.SeedSequence(ctx.seed, spawn_key=(37, *key))


def _vector(v, scale: float = K, *, reference: float = 0.0) -> str:
    """A body-axes vector, ``(x, y, z)`` with 3 significant digits (deg/h by default).

    Components below 1e-9 of the vector's largest (or of ``reference``, a sum's largest term) are round-off, whose digits
    depend on the instruction set: they print as 0, and a vector that is all round-off as ``0 (round-off)``.
    """
    v = np.asarray(v, dtype=float)
    top = max(float(np.max(np.abs(v))), abs(reference))
    if reference and float(np.max(np.abs(v))) <= 1e-9 * abs(reference):
        return "0 (round-off)"
    return "(" + ", ".join("0" if abs(x) <= 1e-9 * top else f"{x * scale:+.3g}" for x in v) + ")"


def _null_coefficient_formulas() -> tuple:
    """LaTeX of the two-sample null coefficient k(x, ρ), of its limit at x → 0 for ρ = 1, and of that behind a first-order low-pass."""
    k2 = two_sample_null_coefficient()
    c2 = lowpass_null_coefficient()
    return sp.latex(k2), sp.latex(sp.limit(k2.subs(RHO, 1), X, 0)), sp.latex(sp.expand(sp.limit(c2, X, 0)))


def warm_up() -> None:
    """Derive the null coefficients' formulas and compile the Monte Carlo kernels :func:`build` runs (one per classical algorithm, the first with its velocity part)."""
    from ..vibration.monte_carlo import monte_carlo_drift

    derived("vibration-report:null-coefficient-formulas:v1", _null_coefficient_formulas)
    env = load_environment(QUALIFICATION)
    for i, name in enumerate(CLASSICAL):
        monte_carlo_drift(get(name), env, H, pairs=2, duration=0.01, rng=0, velocity=(i == 0))


def build(ctx) -> None:
    """Write ``vibration.md`` and its figures.

    Parameters
    ----------
    ctx : Context
        Where to write, and the run mode.
    """
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    quick = ctx.quick
    lines = [
        "# Coning and sculling in a vibration environment",
        "",
        "Every other section assumes a pure cone (or classical sculling) and ideal sensors. A designer has neither: the angular",
        "vibration is a spectrum with lines from rotors and engines, and the gyro and accelerometer outputs pass through analog",
        "anti-aliasing and digital low-pass filters before the algorithm sees them. The package describes such an environment in a",
        "TOML file (`docs/environment-files.md`: coning and sculling lines, cross-spectral densities of the angular rate and the",
        "specific force, analog filters per axis, digital filters, decimation) and gives, to second order in the vibration",
        "amplitude and exactly in ωh (`strapdown.analysis.vibration.drift`), the mean drift as two parts:",
        "",
        "$$u = \\frac{q - \\tilde q}{2\\omega} + \\tilde q\\,\\frac{D(\\omega h)}{\\omega},\\qquad q = \\frac{1}{2}\\mathrm{Im}(A\\times\\bar A),\\quad "
        "\\tilde q = \\frac{1}{2}\\mathrm{Im}(\\tilde A\\times\\bar{\\tilde A}),$$",
        "",
        "the first term the sensor part (pseudo-coning), the second the algorithm part, per line of complex rate amplitude A",
        "sensed as $\\tilde A = HA$, with the sensors' equivalent responses H per axis (analog filter times digital",
        "filter; integration and decimation are exact) and D the closed-form coning drift of the algorithm (`frequency-response.md`).",
        "A spectrum integrates the same expression against its quadrature spectrum. Sculling is the dual part: the sculling vector",
        "$\\mathrm{Im}(A\\times\\bar B)$ with the accelerometers' responses on the specific force B (transfer principle).",
        "The drift is a vector in the body axes, quoted by its magnitude; a signed value is a projection and names its axis.",
        "Two lines of different frequencies add their drifts unless their sum or difference frequency is a multiple of the step",
        "rate; then their cross terms leave a phase-locked mean (`strapdown.analysis.vibration.aliasing`, checked below).",
        "",
        "CLI: `strapdown environment-drift --algorithm NAME --environment FILE --sample-interval H`, `design-coning`, `design-sculling`,",
        "`environment-rates`.",
        "",
    ]

    # ------------------------------------------------------------ 1. pseudo-coning of MEMS settings
    settings = _settings()
    freq = np.geomspace(1.0, 400.0, 60 if quick else 160)
    env0 = Environment(name="sweep")
    curves = {}
    for name, gyro in settings.items():
        band = drift_across_band([get("two-sample")], env0.with_sensors(gyro), H, freq, rate_amplitude=RATE)
        curves[name] = band.sensor
    ideal = drift_across_band([get("two-sample"), get("optimal-3")], env0, H, freq, rate_amplitude=RATE)
    fig, ax = plt.subplots(figsize=(7.2, 4.6))
    for name, v in curves.items():
        ax.loglog(freq, np.abs(v) * K, label=name)
    ax.loglog(freq, np.abs(ideal.total[0]) * K, "k--", label="two-sample algorithm, ideal sensors")
    ax.loglog(freq, np.abs(ideal.total[1]) * K, "k:", label="optimal-3 algorithm, ideal sensors")
    ax.set_xlabel("coning frequency [Hz]")
    ax.set_ylabel("|drift| [deg/h], coning of 1 deg/s rate")
    ax.set_ylim(1e-10, 1e1)
    ax.legend(loc="lower right", fontsize=6.5)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.2)
    ctx.savefig(fig, "figures/vibration-pseudo-coning.png")
    at = [10.0, 50.0]
    table_env = {f: Environment((coning_line(f, float(np.arcsin(RATE / (2 * np.pi * f)))),)) for f in at}
    lines += [
        "## Pseudo-coning of common MEMS filter settings",
        "",
        "A coning line of rate amplitude 1 deg/s (half-cone angle Ω/ω: 0.016° at 10 Hz) swept in frequency, the algorithm at",
        f"h = {H * 1e3:g} ms. With the same filter on every axis the sensed coning is |H|² times the true one: only the gain counts,",
        "not the phase, so the sensor part (the same for every algorithm, a drift even an exact algorithm would have) is (1 − |H|²)",
        "times the true coning rate. 1 − |H|² grows as (ω/ω_c)² for the first-order and Bessel filters and as (ω/ω_c)⁴ for the",
        "maximally flat Butterworth and the digital Butterworth (DLPF) — the test suite measures both slopes — and a resonant",
        "filter (|H| > 1) makes it negative. It lies orders of magnitude above the algorithms' own residual (dashed). Filters that",
        "differ between axes also turn in-phase vibration into coning (the last setting): there the phase counts.",
        "",
        "![pseudo-coning](figures/vibration-pseudo-coning.png)",
        "",
        "| gyro filters | " + " | ".join(f"sensor part at {f:g} Hz, 1 deg/s [deg/h]" for f in at) + " |",
        "|---|" + "---|" * len(at),
    ]
    for name, gyro in settings.items():
        vals = [environment_drift(get("two-sample"), table_env[f].with_sensors(gyro), H).sensor for f in at]
        lines.append(f"| {name} | " + " | ".join(f"{v * K:.4g}" for v in vals) + " |")
    alg_vals = [environment_drift(get("two-sample"), table_env[f], H).algorithm_part for f in at]
    first_order = environment_drift(get("two-sample"), table_env[at[0]].with_sensors(settings["first-order 100 Hz"]), H).sensor
    lines += [
        "| *two-sample algorithm's own residual (ideal sensors)* | " + " | ".join(f"*{v * K:.3g}*" for v in alg_vals) + " |",
        "",
        f"At {at[0]:g} Hz and 1 deg/s, a first-order 100 Hz filter costs {first_order * K:.3g} deg/h about the cone axis, {first_order / alg_vals[0]:.2g} times the",
        "two-sample algorithm's own residual.",
        "",
    ]

    # ------------------------------------------------------------ 2. the qualification example
    env = load_environment(QUALIFICATION)
    tuned2 = tune(env, 2, H, name="tuned-2")
    tuned3 = tune(env, 3, H, name="tuned-3")
    tuned_s = tune(env, 2, H, quantity="sculling", name="tuned-sculling-2")
    algorithms = [get(n) for n in CLASSICAL] + [tuned2.algorithm, tuned3.algorithm]
    drifts = {a.name: environment_drift(a, env, H) for a in algorithms}
    ref = drifts[CLASSICAL[0]]
    lines += [
        "## A qualification-PSD example",
        "",
        f"`qualification.toml` (`strapdown/analysis/vibration/environments/`): *{env.description}*. Gyro: {env.gyro.description}; accelerometers:",
        f"{env.accelerometer.description}; decimation {env.decimation} (sensors at {env.decimation / H:g} Hz, algorithm at {1 / H:g} Hz).",
        "Vectors in the body axes (x, y, z) [deg/h]; the main rotor cones about z, the tail rotor about y.",
        "",
        "| part | band [Hz] | true coning rate | sensor part | two-sample algorithm part | optimal-3 algorithm part | rectification, two-sample [m/s²] |",
        "|---|---|---|---|---|---|---|",
    ]
    for i, p in enumerate(ref.parts):
        band = f"{p.band[0]:g}" if p.band[0] == p.band[1] else f"{p.band[0]:g}–{p.band[1]:g}"
        alt = drifts["optimal-3"].parts[i]
        lines.append(f"| {p.label} | {band} | {_vector(p.true_coning)} | {_vector(p.sensor)} | {_vector(p.algorithm)} | {_vector(alt.algorithm)} | {_vector(p.total_sculling, 1.0)} |")
    lines += [
        "",
        "| algorithm | drift magnitude [deg/h] | drift vector [deg/h] | sensor part magnitude [deg/h] | algorithm part magnitude [deg/h] | rectification magnitude [m/s²] |",
        "|---|---|---|---|---|---|",
    ]
    for a in algorithms:
        d = drifts[a.name]
        ref_mag = float(np.linalg.norm(d.sensor_vector))
        magnitude = "0 (round-off)" if d.magnitude <= 1e-9 * ref_mag else f"{d.magnitude * K:.4g}"
        lines.append(f"| {a.name} | {magnitude} | {_vector(d.total_vector, reference=ref_mag)} | {ref_mag * K:.4g} | {np.linalg.norm(d.algorithm_vector) * K:.3g} | {d.sculling_magnitude:.4g} |")
    largest = max(np.linalg.norm(drifts[n].algorithm_vector) for n in CLASSICAL) / np.linalg.norm(ref.sensor_vector)
    lines += [
        "",
        "The filters, not the algorithm, set the drift here: the sensor part is the same for every algorithm, and the classical",
        f"algorithms' own parts are at most {100 * largest:.2g} % of it in magnitude. An algorithm tuned to the environment (below)",
        "includes the sensor part in what it nulls or minimises.",
        "",
    ]

    # ------------------------------------------------------------ 3. tuned against classical
    k2_latex, k2_limit_latex, c2_limit_latex = derived("vibration-report:null-coefficient-formulas:v1", _null_coefficient_formulas)
    coeff = lambda t: ", ".join(f"c{key} = {v:.8g}" for key, v in t.coefficients.items())  # noqa: E731
    lines += [
        "## Algorithms tuned to the environment",
        "",
        "The mean drift is affine in the algorithm's lag sums, the sensors included (`strapdown.analysis.vibration.tuning`):",
        "`strapdown design-coning` nulls it where the degrees of freedom allow and spends the rest on the classical low-frequency",
        "conditions (the second-order condition first). For N = 2 and one line the coefficient has a closed form",
        "(`strapdown.derivations.coning.tuned`), with ρ the fraction of the line's coning the sensors pass:",
        "",
        f"$$k(x, \\rho) = {k2_latex},\\qquad \\lim_{{x\\to0}} k(x, 1) = {k2_limit_latex},$$",
        "",
        "and behind a first-order low-pass (ρ = 1/(1 + x²/c²), c = ω_c h) it tends to "
        f"${c2_limit_latex}$ as x → 0: the tuned algorithm also compensates the filter's pseudo-coning.",
        "",
        "| tuned algorithm | coefficients | nulled | tuned error magnitude | classical error magnitude |",
        "|---|---|---|---|---|",
    ]
    for t, unit in ((tuned2, "deg/h"), (tuned3, "deg/h"), (tuned_s, "m/s²")):
        scale = K if unit == "deg/h" else 1.0
        tuned_mag, classical_mag = float(np.linalg.norm(t.drift)), float(np.linalg.norm(t.classical_drift))
        shown = "0 (round-off)" if tuned_mag <= 1e-9 * classical_mag else f"{tuned_mag * scale:.3g}"
        lines.append(f"| {t.algorithm.name} ({t.quantity}) | {coeff(t)} | {'yes' if t.nulled else 'minimised'} | {shown} {unit} | {classical_mag * scale:.4g} {unit} ({t.classical.name}) |")
    band_freq = np.geomspace(5.0, 400.0, 50 if quick else 120)
    compare = [get("two-sample"), tuned2.algorithm, optimal_coning_algorithm(3), tuned3.algorithm]
    band = drift_across_band(compare, env, H, band_freq, rate_amplitude=RATE)
    fig, ax = plt.subplots(figsize=(7.2, 4.4))
    styles = ["C0-", "C0--", "C1-", "C1--"]
    for name, v, st in zip(band.names, band.total, styles):
        ax.loglog(band_freq, np.abs(v) * K, st, label=name)
    ax.loglog(band_freq, np.abs(band.sensor) * K, "k:", label="sensor part alone")
    ax.set_xlabel("frequency of a coning line of 1 deg/s rate [Hz]")
    ax.set_ylabel("|drift| [deg/h], qualification sensors")
    ax.legend(loc="lower right", fontsize=7)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.2)
    ctx.savefig(fig, "figures/vibration-tuned-band.png")
    lines += [
        "",
        "Through the qualification environment's sensors, a coning line of 1 deg/s rate swept in frequency: the tuned algorithms (dashed) trade",
        "accuracy away from the environment's content for zero mean drift on it.",
        "",
        "![tuned against classical](figures/vibration-tuned-band.png)",
        "",
    ]

    # ------------------------------------------------------------ 4. rate and load design
    rates = np.geomspace(100.0, 5000.0, 8 if quick else 14)
    design = rate_design(env, BUDGET_DEG_PER_H / K, algorithms=[get(n) for n in CLASSICAL], tuned=((2, 0), (3, 0)), rates=rates)
    lines += [
        "## Sample rate and load for a drift budget",
        "",
        "Budennyi et al.'s Tables 4–5 in this environment (`strapdown.analysis.vibration.rate_design`, `strapdown environment-rates`): the",
        f"lowest algorithm rate from which on the drift stays within {BUDGET_DEG_PER_H:g} deg/h, for the environment and for it with every",
        f"frequency scaled by 1 ± {design.margin:g} (so that a tuning that needs the frequencies exactly is not admitted); tuned",
        "algorithms are re-tuned at every rate. The sensor part depends on the rate through the digital filter, which runs at the",
        "sensor rate (decimation × algorithm rate).",
        "",
        "| algorithm | lowest rate [Hz] | drift there [deg/h] | sensor part [deg/h] | operations per step | load [kop/s] |",
        "|---|---|---|---|---|---|",
    ]
    for r in design.rows:
        if r.sample_rate is None:
            lines.append(f"| {r.algorithm} | none in {rates[0]:g}–{rates[-1]:g} Hz | – | – | – | – |")
        else:
            lines.append(f"| {r.algorithm} | {r.sample_rate:.4g} | {r.drift * K:.3g} | {r.sensor_drift * K:.3g} | {r.cost:g} | {r.load / 1e3:.4g} |")
    fig, ax = plt.subplots(figsize=(7.2, 4.2))
    for row, curve in zip(design.rows, design.curves):
        ax.loglog(design.rates, curve * K, "--" if row.tuned else "-", marker=".", label=row.algorithm)
    ax.loglog(design.rates, design.sensor * K, "k:", label="sensor part")
    ax.axhline(BUDGET_DEG_PER_H, color="r", lw=0.8, label="budget")
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("algorithm sample rate 1/h [Hz]")
    ax.set_ylabel("worst |drift| [deg/h] (±margin)")
    ax.legend(loc="upper right", fontsize=7)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.2)
    ctx.savefig(fig, "figures/vibration-rates.png")
    lines += ["", "![drift against rate](figures/vibration-rates.png)", ""]

    # ------------------------------------------------------------ 5. checks
    lines += [
        "## Checks by simulation",
        "",
        "**DOP853.** Classical coning (1°, 10 Hz) through first-order filters, the truth, the filters in continuous time and the",
        "sensed attitude integrated together by DOP853 (rtol 1e-11 here, 1e-13 in the test suite), the algorithm run on the filtered",
        "increments",
        "(`strapdown.analysis.vibration.simulation.filtered_coning_check`; the test suite runs three bandwidths, identical",
        "and mismatched):",
        "",
        "Values about the cone axis z, the only axis of this drift (the other components are zero in both).",
        "",
        "| gyro filters | closed-form sensor part [deg/h] | DOP853 [deg/h] | relative difference | closed-form total, two-sample [deg/h] | DOP853 |",
        "|---|---|---|---|---|---|",
    ]
    lp = lambda fc: ChannelFilter(analog_filter("lowpass1", cutoff_hz=fc))  # noqa: E731
    cases = [("first-order 100 Hz", Sensor((lp(100.0),) * 3)), ("100 Hz on x and z, 130 Hz on y", Sensor((lp(100.0), lp(130.0), lp(100.0))))]
    for name, gyro in cases:
        d = environment_drift(get("two-sample"), Environment((coning_line(10.0, ALPHA),), gyro=gyro), H)
        sim = filtered_coning_check(get("two-sample"), gyro, H, freq_hz=10.0, half_angle=ALPHA, periods=1, rtol=1e-11)
        lines.append(f"| {name} | {d.sensor * K:.6g} | {sim.sensor_drift * K:.6g} | {sim.sensor_drift / d.sensor - 1:+.1e} | {d.total * K:.6g} | {sim.total_drift * K:.6g} |")
    d5 = 5.0 * DEG
    pair_env = Environment((VibrationLine(60.0, [d5, 0, 0, 0, 0, 0], "x 60 Hz"), VibrationLine(140.0, [0, 1j * d5, 0, 0, 0, 0], "y 140 Hz")))
    near_env = Environment((VibrationLine(60.0, [d5, 0, 0, 0, 0, 0], "x 60 Hz"), VibrationLine(141.0, [0, 1j * d5, 0, 0, 0, 0], "y 141 Hz")))
    closed_pair = environment_drift(get("two-sample"), pair_env, 1 / 400)
    sim_pair = line_drift_check(get("two-sample"), pair_env, 1 / 400, periods=2)
    near = environment_drift(get("two-sample"), near_env, 1 / 400).near_aliases[0]
    lines += [
        "",
        f"The closed form leaves out terms of relative order α² ≈ {ALPHA**2:.1g}; the differences are below that.",
        "",
        "**Lines that alias with the step rate.** x at 60 Hz and y at 140 Hz, 5 deg/s each, y a quarter period ahead, the",
        "two-sample algorithm at h = 1/400 s (step rate 200 Hz = 60 + 140 Hz): each line alone has no coning, but their cross",
        "terms are sampled at one phase every step (`strapdown.analysis.vibration.aliasing`). DOP853 on the kinematics",
        "(`simulation.line_drift_check`, the algorithm run on the exact increments, nothing from the closed form):",
        "",
        "| pair | closed form [deg/h] | DOP853 [deg/h] | relative difference of the vectors |",
        "|---|---|---|---|",
        f"| x 60 Hz + y 140 Hz | {_vector(closed_pair.total_vector)} | {_vector(sim_pair.drift)} | {np.linalg.norm(closed_pair.total_vector - sim_pair.drift) / np.linalg.norm(sim_pair.drift):.1e} |",
        "",
        f"With y at 141 Hz the pair is {near.offset:g} Hz off the alias: its mean over many beats is zero, the beat period is",
        f"{near.beat_period:g} s, and a flight shorter than a beat sees up to {near.amplitude * K:.3g} deg/h (`environment-drift` lists such pairs).",
    ]
    from ..vibration.monte_carlo import CLOSED_FORM_MARGIN, monte_carlo_drift

    pairs, duration = (24, 0.5) if quick else (60, 1.0)
    lines += [
        "",
        f"**Monte Carlo** (`strapdown.analysis.vibration.monte_carlo`): the qualification environment, {2 * pairs} realisations of",
        f"{duration:g} s in antithetic pairs, the spectrum as 16 random sinusoids per realisation, exact truth (attitude exp θ(t),",
        "exact body rate and specific force), analog filters in continuous time, digital filters and decimation on the samples.",
        "Components along the coning axis.",
        "",
        f"The closed form agrees when the true mean drift is within ±{CLOSED_FORM_MARGIN:.0%} of it (TOST over the antithetic pairs at 95 %);",
        "a Monte Carlo too small to tell says how many more pairs it needs.",
        "",
        f"| algorithm | closed form [deg/h] | Monte Carlo [deg/h] | standard error | 95 % interval | closed form agrees (±{CLOSED_FORM_MARGIN:.0%}) |",
        "|---|---|---|---|---|---|",
    ]

    for i, name in enumerate(CLASSICAL):
        d = drifts[name]
        mc = monte_carlo_drift(get(name), env, H, pairs=pairs, duration=duration, rng=_seed(ctx, 1, i), velocity=(i == 0))
        m, se = mc.along(d.coning_axis)
        lo, hi = mc.interval(d.coning_axis)
        lines.append(f"| {name} | {d.total * K:.5f} | {m * K:.5f} | {se * K:.5f} | {lo * K:.5f} – {hi * K:.5f} | {mc.agrees(d.coning_axis, d.total, CLOSED_FORM_MARGIN).label()} |")
        if i == 0:
            ms, ses = mc.along(d.sculling_axis, sculling=True)
            los, his = mc.interval(d.sculling_axis, sculling=True)
            scull = (d.sculling, ms, ses, los, his, mc.agrees(d.sculling_axis, d.sculling, CLOSED_FORM_MARGIN, sculling=True))
    d_s, ms, ses, los, his, v_s = scull
    lines += [
        "",
        "Here the total is dominated by the sensor part, which the Monte Carlo resolves; the differences between the algorithms are",
        "below its standard error (the test suite's spectrum example, with larger algorithm parts, resolves them as well).",
        "",
        f"Rectification error of the two-sample velocity algorithm: closed form {d_s:+.4g} m/s², Monte Carlo {ms:+.4g} ± {ses:.2g} m/s²",
        f"(95 %: {los:+.4g} – {his:+.4g}); the closed form agrees within ±{CLOSED_FORM_MARGIN:.0%}: {v_s}.",
    ]

    # ------------------------------------------------------------ 6. noise through the algorithm
    noise = SensorNoise(ARW_DEG_PER_RT_H * DEG_PER_RT_H_TO_RAD_PER_RT_S, QUANTUM)
    lines += [
        "",
        "## Sensor noise through the algorithm",
        "",
        f"Gyro white noise ({ARW_DEG_PER_RT_H:g} deg/√h) and quantization of the increments ({QUANTUM:g} rad) pass through the",
        "algorithm's correction terms as products with the vibration and with themselves (`strapdown.analysis.vibration.noise`,",
        "closed form checked against a Monte Carlo in the test suite). Their mean is zero for white noise; their random walk",
        "is set against the algorithm's own residual in the qualification environment. Over a time T the residual accumulates",
        "|u| T and the products √(tr Q T): below the crossover T* = tr Q/|u|² the products dominate, and a higher-order",
        "algorithm buys nothing the noise does not hide.",
        "",
        "| algorithm | algorithm part magnitude [deg/h] | products' random walk [deg/√h] | crossover T* [s] | over 1 min | over 1 h |",
        "|---|---|---|---|---|---|",
    ]
    hidden = {60.0: [], 3600.0: []}
    for name in CLASSICAL:
        n = noise_through_algorithm(get(name), env, H, noise)
        for t, names_hidden in hidden.items():
            if n.products_dominate(t):
                names_hidden.append(name)
        verdicts = ["noise products dominate" if n.products_dominate(t) else "residual dominates" for t in (60.0, 3600.0)]
        lines.append(f"| {name} | {np.linalg.norm(n.residual) * K:.3g} | {n.equivalent_random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.3g} | {n.crossover_time:.3g} | {verdicts[0]} | {verdicts[1]} |")
    lines += [
        "",
        f"Over a minute the products hide the residual of {', '.join(hidden[60.0]) or 'none of them'}; over an hour, of "
        f"{', '.join(hidden[3600.0]) or 'none of them'}. Where they hide it, a higher-order algorithm buys nothing the noise does not",
        "already cover. The sensor's own angle random walk",
        f"({ARW_DEG_PER_RT_H:g} deg/√h), which every algorithm integrates alike and which is not a product, is far larger than both.",
        "",
        f"Mode: {'quick' if quick else 'full'}; root seed {ctx.seed}.",
    ]
    ctx.write_text("vibration.md", "\n".join(lines))
