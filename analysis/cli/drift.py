"""``strapdown drift``: constant drift rate of an algorithm under regular precession."""

from __future__ import annotations

import math

from ..coning.drift_theory import asymptotic_drift
from ..coning.precession import RegularPrecession
from ..coning.simulator import RAD_PER_S_TO_DEG_PER_H, simulate
from . import Result
from ._options import add_algorithm, add_motion, algorithm_from, motion_parameters, run_summary


def _run(args) -> Result:
    alg = algorithm_from(args)
    params = motion_parameters(args, alg)
    motion = RegularPrecession(params["eps"], params["nu"], params["nutation"])
    r = simulate(alg, motion, args.sample_interval, args.duration)
    data, header = run_summary(alg, r, params)
    data |= {
        "eps": params["eps"],
        "nutation_deg": args.nutation_deg,
        "freq_hz": args.freq_hz,
        "simulated_drift_deg_per_h": float(r.drift_deg_per_h),
        "drift_vector_deg_per_h": (r.drift * RAD_PER_S_TO_DEG_PER_H).tolist(),
        "asymptotic_drift_deg_per_h": _finite_or_none(float(asymptotic_drift(alg, eps=params["eps"], nu=abs(params["nu"]), nutation=params["nutation"], step=r.step)) * RAD_PER_S_TO_DEG_PER_H),
        "final_error_rad": float((r.attitude_error[-1] ** 2).sum() ** 0.5),
    }
    text = (
        f"{header}\n"
        f"constant drift rate (frame I): {data['simulated_drift_deg_per_h']:.6g} deg/h\n"
        + (f"asymptotic drift rate u_a: {data['asymptotic_drift_deg_per_h']:.6g} deg/h" if data["asymptotic_drift_deg_per_h"] is not None else "asymptotic drift rate u_a: none (zero through h^7)")
    )
    return Result(data, text)


def _finite_or_none(x: float):
    return x if math.isfinite(x) else None


def register(commands) -> None:
    p = commands.add(
        "drift",
        _run,
        "constant drift rate of an algorithm under regular precession (parallel computation)",
    )
    add_algorithm(p)
    add_motion(p)
