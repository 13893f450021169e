"""``strapdown design``: rank algorithms by computational load for a drift budget."""

from __future__ import annotations

import math
from dataclasses import asdict

from ..coning.computational_load import TIME_BASES, LoadModel, design
from ..coning.precession import RegularPrecession
from ..core.units import rad, rad_per_s
from ..core.validation import as_float, in_open_interval, nonnegative, positive
from . import Result


def design_command(args) -> Result:
    """Run ``strapdown design``: validate the options, convert them to SI and rank the registry.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of :func:`register`.

    Returns
    -------
    Result
        The ranking as JSON data and as a text table.

    Raises
    ------
    ValueError, TypeError
        For a bad option value; the message names the option as typed.
    """
    required = positive(args.required_drift_deg_per_h, "--required-drift-deg-per-h")
    eps = as_float(args.eps, "--eps")
    nutation_deg = in_open_interval(args.nutation_deg, "--nutation-deg", 0.0, 180.0, text="(0, 180) degrees")
    freq = positive(args.freq_hz, "--freq-hz")
    m = nonnegative(args.m, "--m")
    fraction = positive(args.truncation_fraction, "--truncation-fraction")
    sigma_q = None if args.quaternion_cost is None else nonnegative(args.quaternion_cost, "--quaternion-cost")
    model = LoadModel(m=m, time_base=args.time_base, truncation_fraction=fraction)
    motion = RegularPrecession(eps, 2.0 * math.pi * freq, rad(nutation_deg))
    rows = design(rad_per_s(required), motion, model=model, quaternion_cost=sigma_q)
    data = {
        "required_drift_deg_per_h": required,
        "eps": eps,
        "nutation_deg": nutation_deg,
        "freq_hz": freq,
        "m": m,
        "time_base": model.time_base,
        "truncation_fraction": model.truncation_fraction,
        "quaternion_cost": sigma_q,
        "ranking": [asdict(r) for r in rows],
    }
    lines = [
        f"time base {'h (sample)' if model.time_base == 'sample' else 'H (step)'}, series rule f = {model.truncation_fraction:g}, m = {m:g}",
        f"{'algorithm':<18} {'rho':>3} {'H_max [ms]':>11} {'rate [Hz]':>10} {'phi [rad]':>10} {'K':>2} {'cost':>6} {'load [kop/s]':>13}",
    ]
    for r in rows:
        lines.append(
            f"{r.algorithm:<18} {r.order:>3} {r.step * 1e3:>11.4g} {r.sample_rate:>10.4g} {r.angle:>10.3g} {r.series_terms:>2} {r.cost:>6g} {r.load / 1e3:>13.4g}"
        )
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``strapdown design`` to the command line.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    p = commands.add("design", design_command, "largest step and computational load of each algorithm for a drift budget")
    p.add_argument("--required-drift-deg-per-h", type=float, required=True, metavar="U", help="required drift u [deg/h], > 0 (required)")
    p.add_argument("--eps", type=float, required=True, metavar="E", help="ε = μ/ν, precession to spin rate [dimensionless] (−1: coning; required)")
    p.add_argument("--nutation-deg", type=float, required=True, metavar="D", help="nutation angle ϑ [deg], in (0, 180) (required)")
    p.add_argument("--freq-hz", type=float, required=True, metavar="F", help="spin frequency f [Hz], ν = 2πf (required)")
    p.add_argument("--m", type=float, default=5.0, help="cost of a multiplication in additions [dimensionless] (default 5)")
    p.add_argument("--time-base", choices=TIME_BASES, default="sample",
                   help="load = cost of a step per sample interval h ('sample', the peak load) or per step H ('step') (default sample)")  # fmt: skip
    p.add_argument("--truncation-fraction", type=float, default=0.1, metavar="F",
                   help="series rule: the truncation error of the quaternion update may add this fraction of u [dimensionless] (default 0.1)")  # fmt: skip
    p.add_argument("--quaternion-cost", type=float, default=None,
                   help="fixed cost of the quaternion update per step, in additions [dimensionless] (default: counted with the series rule)")  # fmt: skip
