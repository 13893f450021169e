"""``strapdown environment-drift``, ``design-coning``, ``design-sculling``, ``environment-rates``: an algorithm in a vibration environment.

The environment is a TOML file (``docs/environment-files.md``): coning and
sculling lines, spectra, the gyro's and accelerometers' filters, decimation.

Every option is checked before the vibration library is imported (it brings
scipy's filters and the coning theory), so that a bad value is refused as fast
as in any other command.
"""

from __future__ import annotations

import math
import sys
import warnings

import numpy as np

from ..core.units import DEG, DEG_PER_RT_H_TO_RAD_PER_RT_S, RAD_PER_S_TO_DEG_PER_H
from ..core.validation import nonnegative, positive
from . import Result
from ._options import add_algorithm, add_limits, algorithm_from, count, limits_from, number, write_text_atomic

#: Points of the band comparison of design-coning / design-sculling [count].
BAND_POINTS = 41
K = RAD_PER_S_TO_DEG_PER_H
#: Rate amplitude of the coning line of the band comparison [deg/s] (a fixed angle would be a rate growing with frequency).
BAND_RATE_DEG_S = 1.0
#: The search grid of environment-rates (lowest and highest rate [Hz], number of rates) and its
#: frequency margin: the library's defaults (``vibration.rate_design.DEFAULT_RATES``,
#: ``FREQUENCY_MARGIN``), restated so that parsing does not import the library
#: (``tests/test_environment_cli.py`` checks that they agree).
DEFAULT_RATE_GRID = (50.0, 20000.0, 61)
FREQUENCY_MARGIN = 0.05
#: Samples and previous samples a tuned design may have (the library's MAX_SAMPLES).
MAX_DESIGN_SAMPLES = 8


def _vec(v) -> list:
    return [float(x) for x in v]


def _environment(args):
    from ..vibration.environment import load_environment

    return load_environment(args.environment)


def _interval(args) -> float:
    return positive(args.sample_interval, "--sample-interval")


def _show(v, scale: float = K) -> str:
    """A vector in deg/h (or the unit of ``scale``), as ``(x, y, z)``."""
    return "(" + ", ".join(f"{x * scale:+.4g}" for x in v) + ")"


def _warn(warnings) -> None:
    for w in warnings:
        sys.stderr.write(f"warning: {w}\n")


def _alias_json(p) -> dict:
    return {
        "lines": list(p.labels), "freq_hz": list(p.frequencies), "kind": p.kind, "multiple_of_step_rate": p.multiple,
        "offset_hz": p.offset, "beat_period_s": None if not np.isfinite(p.beat_period) else p.beat_period,
        "drift_vector_rad_s": _vec(p.drift), "drift_magnitude_rad_s": float(np.linalg.norm(p.drift)), "drift_amplitude_rad_s": p.amplitude,
        "rectification_vector_m_s2": _vec(p.sculling), "rectification_amplitude_m_s2": p.sculling_amplitude,
    }  # fmt: skip


def drift_command(args) -> Result:
    """Run ``strapdown environment-drift``.

    Every drift it prints is the vector in body axes, its magnitude, or a
    projection named with its axis.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    h = _interval(args)
    alg = algorithm_from(args)
    noisy = bool(args.arw_deg_per_rt_h or args.quantization_rad)
    if noisy:  # checked before any import of the library
        arw = nonnegative(args.arw_deg_per_rt_h, "--arw-deg-per-rt-h")
        quantum = nonnegative(args.quantization_rad, "--quantization-rad")
        mission = positive(args.mission, "--mission")
    env = _environment(args)
    from ..vibration.aliasing import alias_pairs
    from ..vibration.drift import environment_drift

    d = environment_drift(alg, env, h)
    _warn(d.warnings)
    axis, saxis = d.coning_axis, d.sculling_axis
    parts = []
    for p in d.parts:
        parts.append({
            "kind": p.kind, "label": p.label, "band_hz": list(p.band),
            "total_drift_vector_rad_s": _vec(p.total), "total_drift_magnitude_rad_s": float(np.linalg.norm(p.total)),
            "sensor_drift_vector_rad_s": _vec(p.sensor), "algorithm_drift_vector_rad_s": _vec(p.algorithm),
            "total_drift_along_coning_axis_rad_s": float(p.total @ axis),
            "total_rectification_vector_m_s2": _vec(p.total_sculling),
            "sensor_rectification_vector_m_s2": _vec(p.sensor_sculling), "algorithm_rectification_vector_m_s2": _vec(p.algorithm_sculling),
            "total_rectification_along_sculling_axis_m_s2": float(p.total_sculling @ saxis),
        })  # fmt: skip
    data = {
        "algorithm": alg.name,
        "environment": env.name,
        "sample_interval": h,
        "decimation": env.decimation,
        "total_drift_vector_rad_s": _vec(d.total_vector),
        "total_drift_vector_deg_per_h": _vec(d.total_vector * K),
        "total_drift_magnitude_rad_s": d.magnitude,
        "total_drift_magnitude_deg_per_h": d.magnitude * K,
        "sensor_drift_vector_rad_s": _vec(d.sensor_vector),
        "algorithm_drift_vector_rad_s": _vec(d.algorithm_vector),
        "coning_axis": _vec(axis),
        "along_coning_axis": {
            "axis": _vec(axis),
            "total_rad_s": d.total,
            "total_deg_per_h": d.total * K,
            "sensor_rad_s": d.sensor,
            "sensor_deg_per_h": d.sensor * K,
            "algorithm_rad_s": d.algorithm_part,
            "algorithm_deg_per_h": d.algorithm_part * K,
        },  # fmt: skip
        "sculling": {
            "total_rectification_vector_m_s2": _vec(d.sculling_vector),
            "total_rectification_magnitude_m_s2": d.sculling_magnitude,
            "sensor_rectification_vector_m_s2": _vec(d._sum("sensor_sculling")),
            "algorithm_rectification_vector_m_s2": _vec(d._sum("algorithm_sculling")),
            "along_sculling_axis": {"axis": _vec(saxis), "total_m_s2": d.sculling, "sensor_m_s2": d.sensor_sculling, "algorithm_m_s2": d.algorithm_sculling},
        },
        "parts": parts,
        "aliasing_pairs": [_alias_json(p) for p in alias_pairs(alg, env, h) if p.exact],
        "near_aliases": [_alias_json(p) for p in d.near_aliases],
        "warnings": list(d.warnings),
    }
    ax = np.round(axis, 4).tolist()
    lines = [
        f"{alg.name} in {env.name}, h = {h:g} s (decimation {env.decimation}); vectors in body axes (x, y, z)",
        f"coning drift |u| = {d.magnitude * K:.6g} deg/h, vector {_show(d.total_vector)} deg/h = sensor (pseudo-coning) {_show(d.sensor_vector)} + algorithm {_show(d.algorithm_vector)}",
        f"  projection on the coning axis {ax}: total {d.total * K:+.6g} deg/h = sensor {d.sensor * K:+.6g} + algorithm {d.algorithm_part * K:+.6g}",
        f"rectification error |ΔẆ| = {d.sculling_magnitude:.6g} m/s², vector {_show(d.sculling_vector, 1.0)} m/s²",
        "",
        f"{'part':<34} {'band [Hz]':>15} {'|drift| [deg/h]':>16} {'drift vector [deg/h]':>34} {'rectification vector [m/s²]':>34}",
    ]
    for p in d.parts:
        band = f"{p.band[0]:g}" if p.band[0] == p.band[1] else (f"{p.band[0]:g} & {p.band[1]:g}" if p.kind == "alias" else f"{p.band[0]:g}–{p.band[1]:g}")
        lines.append(f"{p.label[:34]:<34} {band:>15} {np.linalg.norm(p.total) * K:>16.6g} {_show(p.total):>34} {_show(p.total_sculling, 1.0):>34}")
    for p in d.near_aliases:
        sign = "+" if p.kind == "sum" else "−"
        lines.append(
            f"near alias: {p.labels[0]} {sign} {p.labels[1]} ({p.frequencies[0]:g} {sign} {p.frequencies[1]:g} Hz) is {p.offset:+.4g} Hz from "
            f"{p.multiple} × the step rate: beat period {p.beat_period:.4g} s; mean 0 over many beats (not in the total), "
            f"but up to {p.amplitude * K:.4g} deg/h over a flight shorter than a beat"
        )
    if noisy:
        from ..vibration.noise import SensorNoise, noise_through_algorithm

        n = noise_through_algorithm(alg, env, h, SensorNoise(arw * DEG_PER_RT_H_TO_RAD_PER_RT_S, quantum))
        rw = math.sqrt(float(np.trace(n.random_walk)) * mission)
        residual = float(np.linalg.norm(n.residual)) * mission
        data["noise"] = {
            "variance_per_sample_rad2": n.variance, "mean_drift_vector_rad_s": _vec(n.mean),
            "random_walk_rad2_per_s": [_vec(r) for r in n.random_walk], "equivalent_random_walk_rad_per_rt_s": n.equivalent_random_walk,
            "algorithm_residual_magnitude_rad_s": float(np.linalg.norm(n.residual)), "crossover_time_s": None if math.isinf(n.crossover_time) else n.crossover_time,
            "mission_s": mission, "products_random_walk_rad": rw, "residual_accumulated_rad": residual, "products_dominate": n.products_dominate(mission),
        }  # fmt: skip
        lines += [
            "",
            f"noise through the correction terms (σ² = {n.variance:.3g} rad² per sample and axis): mean drift 0 (white noise), random walk "
            f"{n.equivalent_random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.3g} deg/√h per axis (the sensor's own ARW {args.arw_deg_per_rt_h:g} deg/√h)",
            f"over {mission:g} s: products' random walk {rw / DEG * 3600:.3g} arcsec (1σ) against the algorithm's residual {residual / DEG * 3600:.3g} arcsec: "
            + ("the noise products dominate: a higher-order algorithm buys nothing here" if n.products_dominate(mission) else "the residual dominates"),
        ]
    return Result(data, "\n".join(lines))


def _design(args, quantity: str) -> Result:
    h = _interval(args)
    for flag, value, low in (("--samples", args.samples, 1), ("--previous", args.previous, 0)):
        if not low <= value <= MAX_DESIGN_SAMPLES:
            raise ValueError(f"Expected `{flag}` in {low}..{MAX_DESIGN_SAMPLES}, got {value}")
    if args.samples + args.previous < 2:
        raise ValueError(f"Expected --samples + --previous >= 2 (one lag sum at least), got {args.samples} and {args.previous}")
    env = _environment(args)
    from ..vibration.tuning import CONDITION_LIMIT, drift_across_band, tune

    t = tune(env, args.samples, h, history=args.previous, quantity=quantity, name=args.name)
    scale = K if quantity == "coning" else 1.0
    unit = "deg_per_h" if quantity == "coning" else "m_s2"
    shown = "deg/h" if quantity == "coning" else "m/s²"
    expression = None
    if quantity == "coning" and args.samples == 2 and args.previous == 0 and len(env.lines) == 1 and not env.spectra:
        from ...derivations.coning.tuned import two_sample_null_coefficient

        expression = str(two_sample_null_coefficient())
    tuned_mag, classical_mag = float(np.linalg.norm(t.drift)), float(np.linalg.norm(t.classical_drift))
    data = {
        "quantity": quantity,
        "environment": env.name,
        "samples": args.samples,
        "previous": args.previous,
        "sample_interval": h,
        "coefficients": t.coefficients,
        "lag_sums": list(t.lag_sums),
        "nulled": t.nulled,
        "conditions": t.conditions,
        "low_frequency_conditions": t.taylor_conditions,
        f"tuned_vector_{unit}": _vec(t.drift * scale),
        f"tuned_magnitude_{unit}": tuned_mag * scale,
        f"classical_vector_{unit}": _vec(t.classical_drift * scale),
        f"classical_magnitude_{unit}": classical_mag * scale,
        "classical_algorithm": t.classical.name if t.classical_in_registry else None,
        "classical_in_registry": t.classical_in_registry,
        "classical_coefficients": {f"{i},{j}": float(c) for (i, j), c in t.classical.pairwise.items()},
        "expression": expression,
        "algorithm_file": t.toml(),
        "condition_number": t.condition_number,
        "well_conditioned": t.well_conditioned,
    }
    classical = t.classical.name if t.classical_in_registry else "optimal coning lag sums on (N − l, N), not a registry algorithm"
    what = "drift" if quantity == "coning" else "rectification error"
    text = [
        f"{t.algorithm.name}: {args.samples} samples, {args.previous} previous, h = {h:g} s, tuned for {quantity} in {env.name}",
        "coefficients (algorithm-file keys): " + ", ".join(f"{key} = {v!r}" for key, v in t.coefficients.items()),
        f"{'nulled' if t.nulled else 'minimised'}: {t.conditions} drift direction(s), {t.taylor_conditions} low-frequency condition(s)",
        f"{what} magnitude: tuned {tuned_mag * scale:.6g} {shown}, classical ({classical}) {classical_mag * scale:.6g} {shown}",
        f"  vectors in body axes: tuned {_show(t.drift, scale)}, classical {_show(t.classical_drift, scale)} {shown}",
    ]
    digits = max(0.0, 16.0 - np.log10(max(t.condition_number, 1.0)))
    text.append(f"condition number of the tuning system {t.condition_number:.3g}: the coefficients keep about {digits:.0f} of float64's 16 significant digits")
    if not t.well_conditioned:
        note = (
            f"the tuning system is ill-conditioned (condition number {t.condition_number:.2g} > {CONDITION_LIMIT:.0e}): the coefficients "
            f"(largest |c| = {max(abs(v) for v in t.coefficients.values()):.2g}) keep about {digits:.0f} significant digits and cancel each other; "
            "fewer --samples or --previous give a better-conditioned algorithm"
        )
        text.append("warning: " + note)
        warnings.warn(note, stacklevel=2)
    if expression:
        text.append(f"closed form (x = ωh, rho = sensed fraction of the coning): k = {expression}")
    if quantity == "coning":
        lo, hi = env.frequency_range
        grid = np.geomspace(lo / 2, min(hi * 2, 0.5 / h), BAND_POINTS) if lo < min(hi * 2, 0.5 / h) else np.array([lo])
        rate = min(BAND_RATE_DEG_S * DEG, 0.5 * 2.0 * np.pi * float(grid[0]))
        band = drift_across_band([t.algorithm, t.classical], env, h, grid, rate_amplitude=rate)
        data["band"] = {
            "rate_amplitude_deg_s": rate / DEG, "freq_hz": _vec(grid), "axis": [0.0, 0.0, 1.0],
            "tuned_along_axis_deg_per_h": _vec(band.total[0] * K), "classical_along_axis_deg_per_h": _vec(band.total[1] * K),
            "sensor_along_axis_deg_per_h": _vec(band.sensor * K),
        }  # fmt: skip
        text.append(
            f"band (one coning line about z of rate amplitude {rate / DEG:g} deg/s swept over {grid[0]:g}–{grid[-1]:g} Hz; along z): worst |drift| tuned "
            f"{np.max(np.abs(band.total[0])) * K:.4g}, classical {np.max(np.abs(band.total[1])) * K:.4g} deg/h"
        )
    if args.write_algorithm:
        write_text_atomic(args.write_algorithm, t.toml())
        text.append(f"algorithm file written: {args.write_algorithm}")
    text += ["", t.toml().rstrip()]
    return Result(data, "\n".join(text))


def design_coning_command(args) -> Result:
    """Run ``strapdown design-coning``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    return _design(args, "coning")


def design_sculling_command(args) -> Result:
    """Run ``strapdown design-sculling``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    return _design(args, "sculling")


def rates_command(args) -> Result:
    """Run ``strapdown environment-rates``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    if not 1 <= args.tuned_up_to <= 4:
        raise ValueError(f"Expected `--tuned-up-to` in 1..4 (1: no tuned algorithm), got {args.tuned_up_to}")
    if not 2 <= args.rates <= 400:
        raise ValueError(f"Expected `--rates` in 2..400, got {args.rates}")
    lo, hi = positive(args.min_rate_hz, "--min-rate-hz"), positive(args.max_rate_hz, "--max-rate-hz")
    if hi <= lo:
        raise ValueError(f"Expected `--max-rate-hz` above `--min-rate-hz`, got {hi:g} and {lo:g}")
    budget = positive(args.budget_deg_per_h, "--budget-deg-per-h") / K
    if not 0.0 <= args.margin < 1.0:  # checked again by rate_design; here before the heavy imports
        raise ValueError(f"Expected `--margin` in [0, 1) (the frequencies are scaled by 1 ± margin), got {args.margin:g}")
    env = _environment(args)
    from ...derivations.coning.registry import get

    algorithms = [get(n.strip()) for n in args.algorithms.split(",") if n.strip()]
    tuned = [(n, 0) for n in range(2, args.tuned_up_to + 1)]
    from ..vibration.drift import theory_warnings
    from ..vibration.rate_design import rate_design

    design = rate_design(env, budget, algorithms=algorithms, tuned=tuned, rates=np.geomspace(lo, hi, args.rates), margin=args.margin, limits=limits_from(args))
    _warn(theory_warnings(env, 1.0 / hi))
    rows = []
    lines = [
        f"budget {args.budget_deg_per_h:g} deg/h on the drift magnitude |u| in {env.name} (frequency margin ±{args.margin:g})",
        *(f"note: {n}" for n in design.notes),
        f"{'algorithm':<18} {'rate [Hz]':>10} {'|drift| [deg/h]':>16} {'|sensor| [deg/h]':>17} {'load [kop/s]':>13}",
    ]
    for r in design.rows:
        rows.append({
            "algorithm": r.algorithm, "samples": r.samples, "tuned": r.tuned, "sample_rate_hz": r.sample_rate,
            "drift_magnitude_deg_per_h": None if r.drift is None else r.drift * K,
            "sensor_drift_magnitude_deg_per_h": None if r.sensor_drift is None else r.sensor_drift * K,
            "cost": r.cost, "load_per_s": r.load, "note": r.note,
        })  # fmt: skip
        if r.sample_rate is None:
            lines.append(f"{r.algorithm:<18} {'none':>10}  ({r.note})")
        else:
            lines.append(f"{r.algorithm:<18} {r.sample_rate:>10.4g} {r.drift * K:>16.4g} {r.sensor_drift * K:>17.4g} {r.load / 1e3:>13.4g}" + (f"  ({r.note})" if r.note else ""))
    return Result({"budget_deg_per_h": args.budget_deg_per_h, "environment": env.name, "margin": args.margin, "notes": list(design.notes), "rows": rows}, "\n".join(lines))


def _common(p) -> None:
    p.add_argument("--environment", required=True, metavar="FILE", help="TOML environment file [path] (docs/environment-files.md; required)")
    p.add_argument("--sample-interval", type=number, required=True, metavar="H", help="algorithm sample interval h [s], > 0 (required)")


def _design_options(p) -> None:
    p.add_argument("--samples", type=count, required=True, metavar="N", help="samples per step N [count], 1 … 8 (required)")
    p.add_argument("--previous", type=count, default=0, metavar="K", help="samples of earlier steps the algorithm may read [count], 0 … 8 (default 0)")
    _common(p)
    p.add_argument("--name", default=None, metavar="NAME", help="name of the tuned algorithm [name] (default: tuned-<quantity>-N)")
    p.add_argument("--write-algorithm", default=None, metavar="FILE", help="also write the tuned algorithm file here [path] (default: not written)")


def register(commands) -> None:
    """Add the environment commands to the command line.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    p = commands.add("environment-drift", drift_command, "mean coning drift and sculling rectification of an algorithm in a vibration environment (closed form)")
    add_algorithm(p)
    _common(p)
    p.add_argument("--arw-deg-per-rt-h", type=number, default=0.0, metavar="N",
                   help="gyro angle random walk, passed through the correction terms [deg/√h] (default 0: no noise section)")  # fmt: skip
    p.add_argument("--quantization-rad", type=number, default=0.0, metavar="Q",
                   help="quantum of the gyro increments, rounding error q²/12 [rad] (default 0)")  # fmt: skip
    p.add_argument("--mission", type=number, default=3600.0, metavar="T",
                   help="time over which the noise products' random walk is set against the residual [s] (default 3600)")  # fmt: skip
    p = commands.add("design-coning", design_coning_command, "coning algorithm tuned to a vibration environment: coefficients, algorithm file, drift across the band")
    _design_options(p)
    p = commands.add("design-sculling", design_sculling_command, "sculling (velocity) algorithm tuned to a vibration environment: coefficients and algorithm file")
    _design_options(p)
    p = commands.add("environment-rates", rates_command, "lowest sample rate and load of each algorithm, classical and tuned, for a drift budget in an environment")
    p.add_argument("--environment", required=True, metavar="FILE", help="TOML environment file [path] (docs/environment-files.md; required)")
    p.add_argument("--budget-deg-per-h", type=number, required=True, metavar="U", help="drift budget [deg/h], > 0 (required)")
    p.add_argument("--algorithms", default="two-sample,optimal-3,ignagni-1996-5", metavar="NAMES",
                   help="comma-separated registry algorithms [name] (`strapdown algorithms list`) (default two-sample,optimal-3,ignagni-1996-5)")  # fmt: skip
    p.add_argument("--tuned-up-to", type=count, default=3, metavar="N", help="also tuned algorithms of 2 … N samples [count], 1 … 4 (default 3)")
    lo, hi, rates = DEFAULT_RATE_GRID
    p.add_argument("--min-rate-hz", type=number, default=lo, metavar="F", help=f"lowest sample rate searched [Hz] (default {lo:g})")
    p.add_argument("--max-rate-hz", type=number, default=hi, metavar="F", help=f"highest sample rate searched [Hz] (default {hi:g})")
    p.add_argument("--rates", type=count, default=rates, metavar="R", help=f"sample rates on the search grid [count] (default {rates})")
    p.add_argument("--margin", type=number, default=FREQUENCY_MARGIN, metavar="D",
                   help=f"relative frequency margin the budget must also hold at [dimensionless], 0 ≤ D < 1 (default {FREQUENCY_MARGIN:g})")  # fmt: skip
    add_limits(p)
