"""``strapdown observability``: which alignment errors the measurements can tell apart, and how well.

The stationary model (twelve states, zero-velocity measurements), the rocking
model of the fine-alignment filter (rocking states seen through the lever arm),
multi-position alignment (rotations of the block about its axes at given
times) or the motion of a recorded IMU log.  Degrees, deg/h and deg/√h at the
edge, SI inside (:mod:`strapdown.analysis.core.units`).  Library imports are lazy.
"""

from __future__ import annotations

from ..core import budget
from . import Result, UsageError
from ._options import add_limits, check_work

__all__ = ["register"]

MODELS = ("stationary", "rocking", "multi-position")
_ROCKING_OPTIONS = ("--rocking", "--amplitude-deg", "--period", "--damping", "--lever-arm")
_POSITION_OPTIONS = ("--rotation-times", "--rotation-axes", "--rotation-angles-deg")

#: Degree of observability at or above which a state is reported as little learned within the horizon.
LITTLE_LEARNED = 0.9
#: States of the largest model (the rocking model), for the estimate made before the model is built.
_MOST_STATES = 18


def _tuning(args):
    from ..alignment.fine import FilterTuning
    from ..core import units
    from ..core.validation import nonnegative, positive

    return FilterTuning(
        epoch=positive(args.epoch, "--epoch"),
        prior_tilt=units.rad(positive(args.prior_tilt_deg, "--prior-tilt-deg")),
        prior_heading=units.rad(positive(args.prior_heading_deg, "--prior-heading-deg")),
        gyro_bias=units.rad_per_s(positive(args.gyro_bias_sigma_deg_per_h, "--gyro-bias-sigma-deg-per-h")),
        accel_bias=positive(args.accel_bias_sigma_m_s2, "--accel-bias-sigma-m-s2"),
        gyro_noise=nonnegative(args.arw_deg_per_rt_h, "--arw-deg-per-rt-h") * units.DEG_PER_RT_H_TO_RAD_PER_RT_S,
        accel_noise=nonnegative(args.vrw_m_s_per_rt_h, "--vrw-m-s-per-rt-h") * units.M_S_PER_RT_H_TO_M_S_PER_RT_S,
        measurement_noise=positive(args.velocity_noise_m_s, "--velocity-noise-m-s"),
    )


def _list(text):
    return [p.strip() for p in str(text).split(",") if p.strip()]


def _rotations(args, duration):
    import math

    from ..alignment.observability import BodyRotation
    from ._options import floats

    times = args.rotation_times
    if times is None:
        times = f"{duration / 2:g}"
    n = len(_list(times))
    t = floats(times, "--rotation-times", n)
    axes = _list(args.rotation_axes)
    if len(axes) == 1:
        axes = axes * n
    angles = floats(args.rotation_angles_deg, "--rotation-angles-deg", len(_list(args.rotation_angles_deg)))
    if angles.size == 1:
        angles = angles.repeat(n)
    if len(axes) != n or angles.size != n:
        raise UsageError(f"Expected one axis (--rotation-axes) and one angle (--rotation-angles-deg) per rotation time (--rotation-times, {n}), got {len(axes)} and {angles.size}")
    for a in axes:
        if a not in ("x", "y", "z"):
            raise UsageError(f"Expected --rotation-axes among x, y, z, got {a!r}")
    if any(not 0.0 < x < duration for x in t) or list(t) != sorted(set(t)):
        raise UsageError(f"Expected --rotation-times increasing inside (0, --duration = {duration:g}) s, got {times}")
    return [BodyRotation(float(x), a, math.radians(float(d))) for x, a, d in zip(t, axes, angles)]


def _problem(args):
    import numpy as np

    from ..alignment import observability as obs
    from ..core.units import rad
    from ..core.validation import in_open_interval, positive

    lat = rad(in_open_interval(args.lat_deg, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))
    b0 = in_open_interval(args.beta0_deg, "--beta0-deg", -90.0, 90.0, text="(-90, 90) degrees")
    g0 = in_open_interval(args.gamma0_deg, "--gamma0-deg", -90.0, 90.0, text="(-90, 90) degrees")
    attitude = np.array([rad(args.heading_deg), rad(b0), rad(g0)])
    duration = positive(args.duration, "--duration")
    tuning = _tuning(args)
    if tuning.epoch > duration:
        raise UsageError(f"Expected --epoch at most --duration = {duration:g} s (at least one measurement inside the horizon), got {args.epoch:g} s")
    steps = duration / tuning.epoch
    gramian = duration / 5.0  # sub-intervals of the Gramian (observability.GRAMIAN_STEP), without importing it
    check_work(args, budget.observability(steps, steps, gramian, states=_MOST_STATES, measurements=3, what=f"{steps:.3g} filter epochs (--duration / --epoch)"))
    for flag, value in (("--topic", args.topic), ("--segment", args.segment)):
        if value is not None and args.log is None:
            raise UsageError(f"{flag} applies to a recorded log (--log)")
    if args.log is not None:
        if args.model != "stationary":
            raise UsageError(f"--model {args.model} does not apply to a recorded log (--log): its positions come from its motion")
        from ..logs.alignment import recorded_problem
        from ._logs import load_log

        log = load_log(args).longest  # the positions are tracked through one gap-free segment
        return recorded_problem(log, lat, tuning=tuning), log
    if args.model == "stationary":
        return obs.stationary_problem(lat, attitude=attitude, tuning=tuning, duration=duration), None
    if args.model == "multi-position":
        return obs.multi_position_problem(lat, _rotations(args, duration), duration, attitude=attitude, tuning=tuning), None
    from ..alignment.base_motion import motion_model
    from ..alignment.imu import Scenario
    from ._options import floats

    amp = str(args.amplitude_deg)
    amplitude = floats(amp if "," in amp else f"{amp},{amp},{amp}", "--amplitude-deg", 3)
    if np.any(amplitude < 0) or not np.any(amplitude > 0):
        raise UsageError(f"Expected --amplitude-deg >= 0 and not all zero, got {args.amplitude_deg}")
    period = positive(args.period, "--period")
    if not 0.0 < args.damping < 1.0:
        raise UsageError(f"Expected --damping in (0, 1), got {args.damping:g}")
    lever = floats(args.lever_arm, "--lever-arm", 3)
    if not np.any(lever):
        raise UsageError("Expected a non-zero --lever-arm with --model rocking (the rocking reaches the velocity through it)")
    motion = motion_model(args.rocking, rad(amplitude), period=period, damping=args.damping)
    sc = Scenario(lat, attitude[0], attitude[1], attitude[2], motion, lever, 10.0, duration)
    return obs.rocking_problem(sc, tuning), None


def _observability(args) -> Result:
    from ..alignment.observability import observability
    from ..core.units import deg
    from ._options import limits_from

    problem, log = _problem(args)
    r = observability(problem, limits=limits_from(args))
    directions = [
        {"state": d.state, "label": r.labels[r.names.index(d.state)], "partners": list(d.partners), "components": d.components, "text": d.text} for d in r.unobservable
    ]
    data = {
        "model": r.kind,
        "lat_deg": deg(r.latitude),
        "duration": r.duration,
        "segments": len(problem.durations),
        "dim": r.dim,
        "rank": r.rank,
        "states": list(r.names),
        "labels": list(r.labels),
        "unobservable": directions,
        "pairs": [list(p) for p in r.pairs],
        "posterior_ratio": {n: float(x) for n, x in zip(r.names, r.posterior_ratio)},
        "little_learned": list(r.little_learned(LITTLE_LEARNED)),
        "little_learned_threshold": LITTLE_LEARNED,
        "gramian_eigenvalues": [float(x) for x in r.gramian_eigenvalues],
    }
    if log is not None:
        data["log"] = str(args.log)
    lines = [f"{r.kind} model, φ = {data['lat_deg']:g}°, {r.dim} states, {len(problem.durations)} segment(s) over {r.duration:g} s: rank {r.rank} of {r.dim}"]
    if r.unobservable:
        lines.append("rank: unobservable directions, whatever the time (per unit of the first state):")
        for d in r.unobservable:
            parts = ", ".join(f"{k} {v:.4g}" for k, v in d.components.items() if k != d.state)
            lines.append(f"  {d.text}: {parts}")
    else:
        lines.append("rank: every state is observable, given time")
    lines.append(f"degree of observability: standard deviation after {r.duration:g} s over the prior (1: nothing learned):")
    for label, x in zip(r.labels, r.posterior_ratio):
        lines.append(f"  {label:<28} {x:.3g}")
    little = [r.labels[r.names.index(n)] for n in r.little_learned(LITTLE_LEARNED)]
    if little:
        lines.append(f"learned little within {r.duration:g} s (ratio ≥ {LITTLE_LEARNED:g}): {', '.join(little)}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``observability`` to the command line.

    Parameters
    ----------
    commands : Commands
        The registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add("observability", _observability, "rank, unobservable directions and degree of observability of the alignment error states")
    p.add_argument(
        "--model",
        choices=MODELS,
        default="stationary",
        help="stationary (twelve states at rest), rocking (with rocking states seen through the lever arm) or multi-position (default stationary)",
    )
    p.add_argument(
        "--log", default=None, help="recorded IMU log, any format of docs/recorded-logs.md: the positions of its motion (the Earth's rate taken out) instead of --model [path] (default: none)"
    )
    p.add_argument("--topic", default=None, help="with --log: the stream to read [name] (default: the stream of highest rate that covers the log)")
    p.add_argument("--segment", default=None, metavar="START:END", help="with --log: the stretch to read, seconds from the log's start [s] (default: the whole log)")
    p.add_argument("--lat-deg", type=float, default=45.0, help="latitude φ [deg], |φ| < 90 (default 45)")
    p.add_argument("--heading-deg", type=float, default=0.0, help="initial heading ψ0 [deg] (default 0)")
    p.add_argument("--beta0-deg", type=float, default=0.0, help="initial tilt β0 [deg], |β0| < 90 (default 0)")
    p.add_argument("--gamma0-deg", type=float, default=0.0, help="initial tilt γ0 [deg], |γ0| < 90 (default 0)")
    p.add_argument("--duration", type=float, default=300.0, help="horizon of the degree of observability [s] (default 300)")
    p.add_argument("--epoch", type=float, default=0.1, help="measurement interval [s] (default 0.1)")
    p.add_argument("--rotation-times", default=None, help="multi-position: times of the rotations, comma-separated [s] (default: one, at half the duration)")
    p.add_argument("--rotation-axes", default="z", help="multi-position: body axis of each rotation, x, y or z, comma-separated [name] (default z)")
    p.add_argument("--rotation-angles-deg", default="90", help="multi-position: angle of each rotation, comma-separated [deg] (default 90)")
    p.add_argument("--rocking", choices=["sine", "narrowband", "white"], default="narrowband", help="rocking only: rocking model, sine, narrowband or white (default narrowband)")
    p.add_argument("--amplitude-deg", default="1,2,2", help="rocking only: amplitude [deg], one value or yaw,beta,gamma (default 1,2,2)")
    p.add_argument("--period", type=float, default=8.0, help="rocking only: rocking period [s] (default 8)")
    p.add_argument("--damping", type=float, default=0.1, help="rocking only: damping ratio of the shaping filter [dimensionless] (default 0.1)")
    p.add_argument("--lever-arm", default="0.5,0.3,1.0", help="rocking only: sensor block from the rocking centre, body x,y,z [m] (default 0.5,0.3,1.0)")
    p.add_argument("--prior-heading-deg", type=float, default=1.0, help="prior azimuth standard deviation [deg] (default 1)")
    p.add_argument("--prior-tilt-deg", type=float, default=0.1, help="prior tilt standard deviation [deg] (default 0.1)")
    p.add_argument("--gyro-bias-sigma-deg-per-h", type=float, default=0.01, help="prior gyro bias standard deviation [deg/h] (default 0.01)")
    p.add_argument("--accel-bias-sigma-m-s2", type=float, default=1e-3, help="prior accelerometer bias standard deviation [m/s²] (default 0.001)")
    p.add_argument("--arw-deg-per-rt-h", type=float, default=0.0, help="gyro angle random walk [deg/√h] (default 0)")
    p.add_argument("--vrw-m-s-per-rt-h", type=float, default=0.0, help="accelerometer velocity random walk [m/s/√h] (default 0)")
    p.add_argument("--velocity-noise-m-s", type=float, default=1e-3, help="noise of the velocity measurement [m/s] (default 0.001)")
    add_limits(p)
    for option in _ROCKING_OPTIONS:
        commands.only_with(p, option, "--model", ["rocking"])
    for option in _POSITION_OPTIONS:
        commands.only_with(p, option, "--model", ["multi-position"])
