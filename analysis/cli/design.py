"""``strapdown design``: rank algorithms by computational load for a drift budget."""

from __future__ import annotations

from dataclasses import asdict

from ..coning.sampling_design import design, quaternion_update_count
from . import Result


def design_command(args) -> Result:
    rows = design(args.required_drift_deg_per_h, eps=args.eps, nutation_deg=args.nutation_deg, freq_hz=args.freq_hz, m=args.m, quaternion_cost=args.quaternion_cost)
    sigma_q = quaternion_update_count().cost(args.m) if args.quaternion_cost is None else args.quaternion_cost
    data = {
        "required_drift_deg_per_h": args.required_drift_deg_per_h,
        "eps": args.eps,
        "nutation_deg": args.nutation_deg,
        "freq_hz": args.freq_hz,
        "m": args.m,
        "quaternion_update_cost": sigma_q,
        "ranking": [asdict(r) for r in rows],
    }
    lines = [f"{'algorithm':<18} {'rho':>3} {'H_max [ms]':>11} {'rate [Hz]':>10} {'load [kop/s]':>13}"]
    for r in rows:
        lines.append(f"{r.algorithm:<18} {r.order:>3} {r.step * 1e3:>11.4g} {r.sample_rate:>10.4g} {r.load / 1e3:>13.4g}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    p = commands.add("design", design_command, "largest step and computational load of each algorithm for a drift budget")
    p.add_argument("--required-drift-deg-per-h", type=float, required=True, metavar="U", help="required drift [u] [deg/h]")
    p.add_argument("--eps", type=float, required=True, metavar="E", help="ε = μ/ν (−1: coning)")
    p.add_argument("--nutation-deg", type=float, required=True, metavar="D", help="nutation angle ϑ [deg]")
    p.add_argument("--freq-hz", type=float, required=True, metavar="F", help="frequency f [Hz], ν = 2πf")
    p.add_argument("--m", type=float, default=5.0, help="cost of a multiplication in additions (default 5)")
    p.add_argument("--quaternion-cost", type=float, default=None, help="cost of the quaternion update per step (default: counted, see strapdown.analysis.coning.sampling_design)")
