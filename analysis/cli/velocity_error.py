"""``strapdown velocity-error``: apparent-velocity error of an algorithm's dual extension.

Two motions: the dual regular precession (Lebedev & Panov 1989, (4.2)–(4.3);
``--motion precession``, the default) and classical sculling (angular vibration
about one body axis with linear vibration along another, ``--motion
sculling``).  Under sculling the output adds the rectification error: the
constant rate at which the velocity error grows (simulated) and its
small-amplitude value from one step (:func:`rectification_error`).

Signs follow the package convention, exact minus algorithm: the velocity
error is ``ΔW_I = W_I* − W_I`` (components in frame I), so a positive
rectification error along ``e_r × e_a`` means the algorithm under-rectifies.
"""

from __future__ import annotations

import math

from ..coning.precession import RegularPrecession
from ..coning.sculling_motion import ScullingMotion, rectification_error
from ..coning.simulator import simulate
from ..core.units import RAD_PER_DEG, deg_per_h
from ..core.validation import as_float, in_open_interval, positive
from . import Result, UsageError
from ._options import SCULLING_DEFAULTS, add_algorithm, add_run, add_sculling, algorithm_from, check_run_work, floats, limits_from, run_summary, sculling_parameters, unit_quaternion

#: Options of one motion only (refused with the other, :meth:`Commands.only_with`).
_PRECESSION_ONLY = ("--eps", "--nutation-deg", "--nu-dual-m-s2", "--nutation-dual-m-s")
_SCULLING_ONLY = tuple("--" + key.replace("_", "-") for key in SCULLING_DEFAULTS)


def _precession(args):
    missing = [flag for key, flag in (("eps", "--eps"), ("nutation_deg", "--nutation-deg")) if getattr(args, key) is None]
    if missing:
        raise UsageError(f"Expected {' and '.join(missing)} with --motion precession, got none")
    eps = as_float(args.eps, "--eps")
    nutation = in_open_interval(args.nutation_deg, "--nutation-deg", 0.0, 180.0, text="(0, 180) degrees") * RAD_PER_DEG
    nu = 2.0 * math.pi * positive(args.freq_hz, "--freq-hz")
    nu_dual = as_float(args.nu_dual_m_s2 if args.nu_dual_m_s2 is not None else 0.0, "--nu-dual-m-s2")
    nutation_dual = as_float(args.nutation_dual_m_s if args.nutation_dual_m_s is not None else 0.0, "--nutation-dual-m-s")
    motion = RegularPrecession(eps, nu, nutation, nu_dual, nutation_dual)
    return motion, {"motion": "precession", "eps": eps, "nutation_deg": args.nutation_deg, "freq_hz": args.freq_hz, "nu_dual": nu_dual, "nutation_dual": nutation_dual}


def _sculling(args):
    params = sculling_parameters(args)
    if params["rotation_axis"] == params["accel_axis"]:
        raise UsageError(f"Expected --accel-axis different from --rotation-axis, got both {'xyz'[params['accel_axis']]}")
    motion = ScullingMotion(**params)
    shown = {k: (getattr(args, k) if getattr(args, k) is not None else d) for k, d in SCULLING_DEFAULTS.items()}
    return motion, {"motion": "sculling", "freq_hz": args.freq_hz} | shown


def _run(args) -> Result:
    alg = algorithm_from(args)
    positive(args.freq_hz, "--freq-hz")
    check_run_work(args, alg, velocity=True)
    motion, shown = _sculling(args) if args.motion == "sculling" else _precession(args)
    w0 = floats(args.w0_m_s, "--w0-m-s", 3)
    lam0 = unit_quaternion(args.attitude0, "--attitude0")
    r = simulate(alg, motion, args.sample_interval, args.duration, attitude0=lam0, w_inertial0=w0, velocity=True, limits=limits_from(args))
    params = {"eps": motion.eps, "nu": motion.nu} if args.motion == "precession" else None
    data, header = run_summary(alg, r, params)
    data |= shown | {
        "dW_E": float(r.final_dw_body),
        "dW_I": float(r.final_dw_inertial),
        "simulated_drift_deg_per_h": float(deg_per_h(r.drift_rate)),
        "attitude0": lam0.tolist(),
    }
    text = f"{header}\n|ΔW_E| = {data['dW_E']:.6g} m/s, |ΔW_I| = {data['dW_I']:.6g} m/s, drift {data['simulated_drift_deg_per_h']:.6g} deg/h"
    if args.motion == "sculling":
        rate = r.velocity_error_rate
        small = rectification_error(alg, motion, args.sample_interval)
        data |= {
            "velocity_error_rate_m_s2": rate.tolist(),
            "rectified_acceleration_m_s2": motion.rectified_acceleration().tolist(),
            "rectification_error_small_amplitude_m_s2": small.rate,
            "rectification_error_relative": small.relative if math.isfinite(small.relative) else None,
        }
        text += (
            f"\nvelocity-error rate W_I* − W_I (simulated, frame I): {', '.join(f'{x:.6g}' for x in rate)} m/s²"
            f"\nrectification error, small-amplitude theory: {small.rate:.6g} m/s² along e_r × e_a"
        )
    return Result(data, text)


def register(commands) -> None:
    """Add the ``velocity-error`` command.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add(
        "velocity-error",
        _run,
        "apparent-velocity error |ΔW_E|, |ΔW_I| of an algorithm's dual extension (dual regular precession or classical sculling)",
    )
    add_algorithm(p)
    p.add_argument("--motion", choices=("precession", "sculling"), default="precession", help="test motion: dual regular precession (4.2) or classical sculling (default precession)")
    p.add_argument("--eps", type=float, default=None, help="precession: ε = μ/ν, precession to spin rate [dimensionless] (−1 is coning) (default: none; required with --motion precession)")
    p.add_argument("--nutation-deg", type=float, default=None, help="precession: nutation angle ϑ [deg], in (0, 180) (default: none; required with --motion precession)")
    p.add_argument("--freq-hz", type=float, required=True, help="precession: spin frequency F [Hz], ν = 2πF; sculling: vibration frequency F [Hz] (required)")
    add_run(p)
    p.add_argument("--nu-dual-m-s2", type=float, default=None, help="precession: dual part ν° of the spin rate [m/s²] (default 0)")
    p.add_argument("--nutation-dual-m-s", type=float, default=None, help="precession: dual part ϑ° of the nutation [m/s] (default 0)")
    add_sculling(p)
    p.add_argument("--w0-m-s", default="0,0,0", metavar="X,Y,Z", help="initial apparent velocity W_I(0) [m/s] (default 0,0,0)")
    p.add_argument("--attitude0", default="1,0,0,0", metavar="Q0,Q1,Q2,Q3", help="initial attitude Λ(0), a quaternion, normalised [dimensionless] (default 1,0,0,0)")
    for flag in _PRECESSION_ONLY:
        commands.only_with(p, flag, "--motion", ("precession",))
    for flag in _SCULLING_ONLY:
        commands.only_with(p, flag, "--motion", ("sculling",))
