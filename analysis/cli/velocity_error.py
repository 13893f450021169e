"""``strapdown velocity-error``: apparent-velocity error of an algorithm's dual extension."""

from __future__ import annotations

from ..coning.precession import RegularPrecession
from ..coning.simulator import simulate
from ..core.validation import as_float
from . import Result
from ._options import add_algorithm, add_motion, algorithm_from, floats, motion_parameters, run_summary, unit_quaternion


def _run(args) -> Result:
    alg = algorithm_from(args)
    params = motion_parameters(args, alg, velocity=True)
    nu_dual = as_float(args.nu_dual, "--nu-dual")
    nutation_dual = as_float(args.nutation_dual, "--nutation-dual")
    w0 = floats(args.w0, "--w0", 3)
    lam0 = unit_quaternion(args.attitude0, "--attitude0")
    motion = RegularPrecession(params["eps"], params["nu"], params["nutation"], nu_dual, nutation_dual)
    r = simulate(alg, motion, args.sample_interval, args.duration, attitude0=lam0, w_inertial0=w0, velocity=True)
    data, header = run_summary(alg, r, params)
    data |= {
        "dW_E": float(r.final_dw_body),
        "dW_I": float(r.final_dw_inertial),
        "simulated_drift_deg_per_h": float(r.drift_deg_per_h),
        "attitude0": lam0.tolist(),
    }
    text = (
        f"{header}\n"
        f"|ΔW_E| = {data['dW_E']:.6g} m/s, |ΔW_I| = {data['dW_I']:.6g} m/s, drift {data['simulated_drift_deg_per_h']:.6g} deg/h"
    )
    return Result(data, text)


def register(commands) -> None:
    p = commands.add(
        "velocity-error",
        _run,
        "apparent-velocity error |ΔW_E|, |ΔW_I| of an algorithm under the dual regular precession",
    )
    add_algorithm(p)
    add_motion(p)
    p.add_argument("--nu-dual", type=float, default=0.0, help="dual part ν° of the spin rate [m/s²] (default 0)")
    p.add_argument("--nutation-dual", type=float, default=0.0, help="dual part ϑ° of the nutation [m/s] (default 0)")
    p.add_argument("--w0", default="0,0,0", metavar="X,Y,Z", help="initial apparent velocity W_I(0) [m/s] (default 0,0,0)")
    p.add_argument("--attitude0", default="1,0,0,0", metavar="Q0,Q1,Q2,Q3", help="initial attitude Λ(0), normalised (default 1,0,0,0)")
