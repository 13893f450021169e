"""``strapdown environment-drift``, ``design-coning``, ``design-sculling``, ``environment-rates``: an algorithm in a vibration environment.

The environment is a TOML file (``docs/environment-files.md``): coning and
sculling lines, spectra, the gyro's and accelerometers' filters, decimation.

Every option is checked before the vibration library is imported (it brings
scipy's filters and the coning theory), so that a bad value is refused as fast
as in any other command.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..core.units import DEG, RAD_PER_S_TO_DEG_PER_H
from ..core.validation import positive
from . import Result
from ._options import add_algorithm, algorithm_from, count, number

#: The search grid of environment-rates (lowest and highest rate [Hz], number of rates) and its
#: frequency margin: the library's defaults (``vibration.rate_design.DEFAULT_RATES``,
#: ``FREQUENCY_MARGIN``), restated so that parsing does not import the library
#: (``tests/test_environment_cli.py`` checks that they agree).
DEFAULT_RATE_GRID = (50.0, 20000.0, 61)
FREQUENCY_MARGIN = 0.05
#: Samples and previous samples a tuned design may have (the library's MAX_SAMPLES).
MAX_DESIGN_SAMPLES = 8

#: Points of the band comparison of design-coning / design-sculling [count].
BAND_POINTS = 41


def _vec(v) -> list:
    return [float(x) for x in v]


def _environment(args):
    from ..vibration.environment import load_environment

    return load_environment(args.environment)


def _interval(args) -> float:
    return positive(args.sample_interval, "--sample-interval")


def drift_command(args) -> Result:
    """Run ``strapdown environment-drift``.

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
    env = _environment(args)
    from ..vibration.drift import environment_drift

    d = environment_drift(alg, env, h)
    k = RAD_PER_S_TO_DEG_PER_H
    parts = []
    for p in d.parts:
        parts.append({
            "kind": p.kind, "label": p.label, "band_hz": list(p.band),
            "sensor_drift_rad_s": float(p.sensor @ d.coning_axis), "algorithm_drift_rad_s": float(p.algorithm @ d.coning_axis),
            "total_drift_rad_s": float(p.total @ d.coning_axis), "total_drift_deg_per_h": float(p.total @ d.coning_axis) * k,
            "total_drift_vector_rad_s": _vec(p.total),
            "sensor_rectification_m_s2": float(p.sensor_sculling @ d.sculling_axis),
            "algorithm_rectification_m_s2": float(p.algorithm_sculling @ d.sculling_axis),
            "total_rectification_m_s2": float(p.total_sculling @ d.sculling_axis),
        })  # fmt: skip
    data = {
        "algorithm": alg.name,
        "environment": env.name,
        "sample_interval": h,
        "decimation": env.decimation,
        "total_drift_rad_s": d.total,
        "total_drift_deg_per_h": d.total * k,
        "sensor_drift_rad_s": d.sensor,
        "sensor_drift_deg_per_h": d.sensor * k,
        "algorithm_drift_rad_s": d.algorithm_part,
        "algorithm_drift_deg_per_h": d.algorithm_part * k,
        "coning_axis": _vec(d.coning_axis),
        "total_drift_vector_rad_s": _vec(d.total_vector),
        "sculling": {
            "total_rectification_m_s2": d.sculling,
            "sensor_rectification_m_s2": d.sensor_sculling,
            "algorithm_rectification_m_s2": d.algorithm_sculling,
            "axis": _vec(d.sculling_axis),
            "total_rectification_vector_m_s2": _vec(d.sculling_vector),
        },
        "parts": parts,
    }
    lines = [
        f"{alg.name} in {env.name}, h = {h:g} s (decimation {env.decimation}); signed along the coning axis {np.round(d.coning_axis, 6).tolist()}",
        f"coning drift  total {d.total * k:+.6g} deg/h = sensor (pseudo-coning) {d.sensor * k:+.6g} + algorithm {d.algorithm_part * k:+.6g}",
        f"rectification total {d.sculling:+.6g} m/s² = sensor (pseudo-sculling) {d.sensor_sculling:+.6g} + algorithm {d.algorithm_sculling:+.6g}",
        "",
        f"{'part':<28} {'band [Hz]':>19} {'sensor [deg/h]':>15} {'algorithm [deg/h]':>18} {'rectif. [m/s²]':>15}",
    ]
    for p in parts:
        band = f"{p['band_hz'][0]:g}" if p["band_hz"][0] == p["band_hz"][1] else f"{p['band_hz'][0]:g}–{p['band_hz'][1]:g}"
        lines.append(f"{p['label'][:28]:<28} {band:>19} {p['sensor_drift_rad_s'] * k:>+15.6g} {p['algorithm_drift_rad_s'] * k:>+18.6g} {p['total_rectification_m_s2']:>+15.6g}")
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
    k = RAD_PER_S_TO_DEG_PER_H
    scale = k if quantity == "coning" else 1.0
    unit = "deg_per_h" if quantity == "coning" else "m_s2"
    axis = t.classical_drift / np.linalg.norm(t.classical_drift) if np.linalg.norm(t.classical_drift) > 0 else np.array([0.0, 0.0, 1.0])
    expression = None
    if quantity == "coning" and args.samples == 2 and args.previous == 0 and len(env.lines) == 1 and not env.spectra:
        from ...derivations.coning.tuned import two_sample_null_coefficient

        expression = str(two_sample_null_coefficient())
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
        f"tuned_{unit}": float(t.drift @ axis) * scale,
        f"classical_{unit}": float(t.classical_drift @ axis) * scale,
        "classical_algorithm": t.classical.name,
        "expression": expression,
        "algorithm_file": t.toml(),
        "condition_number": t.condition_number,
        "well_conditioned": t.well_conditioned,
    }
    text = [
        f"{t.algorithm.name}: {args.samples} samples, {args.previous} previous, h = {h:g} s, tuned for {quantity} in {env.name}",
        "coefficients (algorithm-file keys): " + ", ".join(f"{key} = {v!r}" for key, v in t.coefficients.items()),
        f"{'nulled' if t.nulled else 'minimised'}: {t.conditions} drift direction(s), {t.taylor_conditions} low-frequency condition(s)",
        f"{quantity} error: tuned {float(t.drift @ axis) * scale:+.6g}, classical ({t.classical.name}) {float(t.classical_drift @ axis) * scale:+.6g} "
        + ("deg/h" if quantity == "coning" else "m/s²"),
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
        amplitude = 1.0 * DEG
        band = drift_across_band([t.algorithm, t.classical], env, h, grid, half_angle=amplitude)
        data["band"] = {
            "half_angle_deg": 1.0, "freq_hz": _vec(grid),
            "tuned_deg_per_h": _vec(band.total[0] * k), "classical_deg_per_h": _vec(band.total[1] * k), "sensor_deg_per_h": _vec(band.sensor * k),
        }  # fmt: skip
        text.append(f"band (1° coning line, {grid[0]:g}–{grid[-1]:g} Hz): worst |drift| tuned {np.max(np.abs(band.total[0])) * k:.4g}, classical {np.max(np.abs(band.total[1])) * k:.4g} deg/h")
    if args.write_algorithm:
        with open(args.write_algorithm, "w", encoding="utf-8") as handle:
            handle.write(t.toml())
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
    budget = positive(args.budget_deg_per_h, "--budget-deg-per-h") / RAD_PER_S_TO_DEG_PER_H
    from ...derivations.coning.registry import get

    algorithms = [get(n.strip()) for n in args.algorithms.split(",") if n.strip()]
    tuned = [(n, 0) for n in range(2, args.tuned_up_to + 1)]
    env = _environment(args)
    from ..vibration.rate_design import rate_design

    design = rate_design(env, budget, algorithms=algorithms, tuned=tuned, rates=np.geomspace(lo, hi, args.rates), margin=args.margin)
    rows = []
    lines = [
        f"budget {args.budget_deg_per_h:g} deg/h in {env.name} (frequency margin ±{args.margin:g})",
        f"{'algorithm':<18} {'rate [Hz]':>10} {'drift [deg/h]':>14} {'sensor [deg/h]':>15} {'load [kop/s]':>13}",
    ]
    for r in design.rows:
        rows.append({
            "algorithm": r.algorithm, "samples": r.samples, "tuned": r.tuned, "sample_rate_hz": r.sample_rate,
            "drift_deg_per_h": None if r.drift is None else r.drift * RAD_PER_S_TO_DEG_PER_H,
            "sensor_drift_deg_per_h": None if r.sensor_drift is None else r.sensor_drift * RAD_PER_S_TO_DEG_PER_H,
            "cost": r.cost, "load_per_s": r.load,
        })  # fmt: skip
        if r.sample_rate is None:
            lines.append(f"{r.algorithm:<18} {'none':>10}")
        else:
            lines.append(f"{r.algorithm:<18} {r.sample_rate:>10.4g} {r.drift * RAD_PER_S_TO_DEG_PER_H:>14.4g} {r.sensor_drift * RAD_PER_S_TO_DEG_PER_H:>15.4g} {r.load / 1e3:>13.4g}")
    return Result({"budget_deg_per_h": args.budget_deg_per_h, "environment": env.name, "margin": args.margin, "rows": rows}, "\n".join(lines))


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
                   help=f"relative frequency margin the budget must also hold at [dimensionless] (default {FREQUENCY_MARGIN:g})")  # fmt: skip

