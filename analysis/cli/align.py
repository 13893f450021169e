"""``strapdown align``: self-alignment on a rocking base by Monte Carlo, with the theory that applies.

At rest with heading 0 the body axes are x north, y east, z down; the rocking
is given per axis (yaw, β, γ) in the angles of Hrechka & Koroliov.  Degrees,
deg/h, deg/√h, ppm and arc-seconds at the edge, SI inside (converted with
:mod:`strapdown.analysis.core.units`).  Library imports are lazy.
"""

from __future__ import annotations

from ..core import budget
from . import Result, UsageError
from ._executors import add_executor
from ._executors import executor as executor_from
from ._executors import workers as local_workers
from ._options import PROGRESS_HELP, add_limits, check_work, count, limits_from

__all__ = ["register"]

#: Options that apply only with some rocking models or methods (refused with the others, :meth:`Commands.only_with`).
_ROCKING_OPTIONS = {"--amplitude-deg": ("sine", "narrowband", "white"), "--period": ("sine", "narrowband"), "--damping": ("narrowband",), "--bandwidth-hz": ("white",)}
_METHOD_OPTIONS = {
    "--formula": ("analytic",),
    "--observation": ("inertial",),
    "--epoch": ("inertial", "kalman"),
    "--prior-heading-deg": ("kalman", "aided"),
    "--prior-tilt-deg": ("kalman", "aided"),
    "--velocity-noise-m-s": ("kalman",),
    "--disturbance": ("kalman",),
    "--assumed-period": ("kalman",),
    "--assumed-damping": ("kalman",),
    "--assumed-amplitude-deg": ("kalman",),
    "--lever-arm-known": ("kalman",),
    "--imu": ("kalman", "multiposition", "aided"),
    "--figure": ("kalman", "aided"),
    "--gnss-velocity-noise-m-s": ("aided",),
    "--gnss-position-noise": ("aided",),
    "--gnss-interval": ("aided",),
}

#: Methods that run on a recorded log only (the Monte Carlo runs analytic, inertial and kalman).
LOG_ONLY_METHODS = ("compass", "multiposition", "aided")

def _check_work(args, samples: int, trials: int, workers: int) -> None:
    """Refuse a Monte Carlo whose estimate exceeds ``--time-limit`` / ``--memory-limit-mb``, before it starts."""
    from ..core.validation import positive

    where = "--dask" if args.dask is not None else "--workers"
    what = f"{trials:.3g} trials (--trials) of {float(samples):.3g} samples (--duration × --sample-rate-hz) on {workers} worker(s) ({where})"
    epochs = 0.0
    if args.method == "kalman":  # the filter runs once per epoch: short epochs cost more than the samples
        epoch = positive(0.1 if args.epoch is None else args.epoch, "--epoch")
        epochs = float(samples) // max(1.0, round(epoch * positive(args.sample_rate_hz, "--sample-rate-hz")))
    check_work(args, budget.alignment_monte_carlo(trials, samples, method=args.method, epochs=epochs, workers=workers, what=what))


def _check_options(args) -> None:
    if args.rocking != "none" and args.amplitude_deg is None:
        raise UsageError(f"--amplitude-deg is required with --rocking {args.rocking}")


def _triple(text, name):
    from ._options import floats

    parts = str(text).split(",")
    if len(parts) == 1:
        return floats(f"{text},{text},{text}", name, 3)
    return floats(text, name, 3)


def _amplitude(text, flag: str, rocking: str, b0: float, g0: float):
    """A rocking amplitude typed in degrees (one value or yaw,beta,gamma), >= 0.

    The peak (the amplitude of sine rocking, 4 sigma of the random models) stays
    below 90 - ``|tilt0|`` degrees in the tilts and below 180 degrees in yaw.
    """
    import numpy as np

    amplitude = _triple(text, flag)
    if np.any(amplitude < 0):
        raise ValueError(f"Expected `{flag}` >= 0, got {text}")
    peak = amplitude * (1.0 if rocking == "sine" else 4.0 / np.sqrt(2.0))
    kind = "the amplitude" if rocking == "sine" else "4 sigma = 2.83 x amplitude"
    limit = 90.0 - max(abs(b0), abs(g0))
    if np.any(peak[1:] >= limit):
        raise UsageError(f"Expected {flag} tilts with {kind} below 90 - |tilt0| = {limit:g} deg, got {text}")
    if not peak[0] < 180.0:
        raise UsageError(f"Expected {flag} yaw with {kind} below 180 deg, got {text}")
    return amplitude


def _scenario(args):
    import numpy as np

    from ..alignment.base_motion import motion_model
    from ..alignment.imu import Scenario
    from ..core.units import rad
    from ..core.validation import as_float, in_open_interval, positive

    lat = rad(in_open_interval(args.lat_deg, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))
    heading = rad(as_float(args.heading_deg, "--heading-deg"))
    b0 = in_open_interval(args.beta0_deg, "--beta0-deg", -90.0, 90.0, text="(-90, 90) degrees")
    g0 = in_open_interval(args.gamma0_deg, "--gamma0-deg", -90.0, 90.0, text="(-90, 90) degrees")
    fs = positive(args.sample_rate_hz, "--sample-rate-hz")
    T = positive(args.duration, "--duration")
    if T * fs < 2:
        raise ValueError(f"Expected `--duration` >= two samples = {2 / fs:g} s (--sample-rate-hz {fs:g}), got {T:g}")
    amplitude = np.zeros(3) if args.rocking == "none" else _amplitude(args.amplitude_deg, "--amplitude-deg", args.rocking, b0, g0)
    period = positive(args.period, "--period")
    damping = as_float(args.damping, "--damping")
    if args.rocking == "narrowband" and not 0.0 < damping < 1.0:
        raise ValueError(f"Expected `--damping` in (0, 1), got {damping:g}")
    bandwidth = None if args.bandwidth_hz is None else positive(args.bandwidth_hz, "--bandwidth-hz")
    if bandwidth is not None and bandwidth > fs / 2:
        raise ValueError(f"Expected `--bandwidth-hz` <= --sample-rate-hz/2 = {fs / 2:g} Hz, got {bandwidth:g}")
    if args.rocking == "sine" and 1.0 / period >= fs / 2:
        raise ValueError(f"Expected `--period` > 2/--sample-rate-hz = {2 / fs:g} s, got {period:g}")
    if args.rocking == "narrowband" and 4.0 / period >= fs / 2:
        raise ValueError(f"Expected `--period` > 8/--sample-rate-hz = {8 / fs:g} s (the narrow-band spectrum reaches 4/period), got {period:g}")
    motion = motion_model(args.rocking, rad(amplitude), period=period, damping=damping, bandwidth=bandwidth)
    lever = _triple(args.lever_arm, "--lever-arm")
    return Scenario(lat, heading, rad(b0), rad(g0), motion, lever, fs, T, rocking_in_gyros=not args.tilt_channel_only)


def _errors(args):
    import numpy as np

    from ..alignment.imu import SensorErrors
    from ..core import units
    from ..core.validation import nonnegative

    return SensorErrors(
        gyro_bias=units.rad_per_s(_triple(args.gyro_bias_deg_per_h, "--gyro-bias-deg-per-h")),
        accel_bias=_triple(args.accel_bias_m_s2, "--accel-bias-m-s2"),
        gyro_bias_sigma=units.rad_per_s(nonnegative(args.gyro_bias_sigma_deg_per_h, "--gyro-bias-sigma-deg-per-h")),
        accel_bias_sigma=nonnegative(args.accel_bias_sigma_m_s2, "--accel-bias-sigma-m-s2"),
        gyro_noise=nonnegative(args.arw_deg_per_rt_h, "--arw-deg-per-rt-h") * units.DEG_PER_RT_H_TO_RAD_PER_RT_S,
        accel_noise=nonnegative(args.vrw_m_s_per_rt_h, "--vrw-m-s-per-rt-h") * units.M_S_PER_RT_H_TO_M_S_PER_RT_S,
        gyro_scale=np.asarray(_triple(args.gyro_scale_ppm, "--gyro-scale-ppm")) * units.PPM,
        accel_scale=np.asarray(_triple(args.accel_scale_ppm, "--accel-scale-ppm")) * units.PPM,
        gyro_quantum=nonnegative(args.gyro_quantum_arcsec, "--gyro-quantum-arcsec") * units.ARCSEC,
        accel_quantum=nonnegative(args.accel_quantum_m_s, "--accel-quantum-m-s"),
    )


def _options(args, scenario, errors):
    import numpy as np

    from ..alignment.base_motion import motion_model
    from ..alignment.fine import Disturbance, FilterTuning, assumed_disturbance
    from ..alignment.monte_carlo import AlignmentOptions
    from ..core.units import rad
    from ..core.validation import as_float, positive

    if args.method != "kalman" or args.log is not None and args.method in LOG_ONLY_METHODS:
        return AlignmentOptions(formula=args.formula or "levelled", observation=args.observation or "position", inertial_epoch=positive(1.0 if args.epoch is None else args.epoch, "--epoch"))
    kind = args.disturbance or "auto"
    moving = args.rocking != "none" and np.any(scenario.lever_arm)
    if kind == "auto":
        kind = "shaping" if moving and not args.lever_arm_known else "none"
    assumed = scenario.motion
    if args.assumed_period is not None or args.assumed_damping is not None or args.assumed_amplitude_deg is not None:
        if args.rocking == "none":
            raise UsageError("--assumed-period, --assumed-damping and --assumed-amplitude-deg need a rocking model (--rocking)")
        name = "narrowband" if args.rocking == "white" else args.rocking
        if args.assumed_amplitude_deg is not None:
            amp = rad(_amplitude(args.assumed_amplitude_deg, "--assumed-amplitude-deg", name, args.beta0_deg, args.gamma0_deg))
        else:
            amp = scenario.motion.amplitude
        period = positive(args.assumed_period, "--assumed-period") if args.assumed_period is not None else getattr(scenario.motion, "period", 8.0)
        damping = as_float(args.assumed_damping, "--assumed-damping") if args.assumed_damping is not None else getattr(scenario.motion, "damping", 0.1)
        if name == "narrowband" and not 0.0 < damping < 1.0:
            raise ValueError(f"Expected `--assumed-damping` in (0, 1), got {damping:g}")
        assumed = motion_model(name, amp, period=period, damping=damping)
    dist = assumed_disturbance(assumed, scenario, kind=kind) if kind != "none" else Disturbance("none")
    gb = errors.gyro_bias_sigma or max(float(np.max(np.abs(errors.gyro_bias))), rad(0.01) / 3600.0)
    ab = errors.accel_bias_sigma or max(float(np.max(np.abs(errors.accel_bias))), 1e-4)
    tuning = FilterTuning(
        epoch=positive(0.1 if args.epoch is None else args.epoch, "--epoch"),
        prior_tilt=rad(positive(0.1 if args.prior_tilt_deg is None else args.prior_tilt_deg, "--prior-tilt-deg")),
        prior_heading=rad(positive(1.0 if args.prior_heading_deg is None else args.prior_heading_deg, "--prior-heading-deg")),
        gyro_bias=gb,
        accel_bias=ab,
        gyro_noise=errors.gyro_noise,
        accel_noise=errors.accel_noise,
        measurement_noise=positive(1e-3 if args.velocity_noise_m_s is None else args.velocity_noise_m_s, "--velocity-noise-m-s"),
        disturbance=dist,
        lever_arm_known=bool(args.lever_arm_known),
    )
    return AlignmentOptions(tuning=tuning)


def _align(args) -> Result:
    import math

    from ..alignment.monte_carlo import alignment_monte_carlo
    from ..core.units import deg
    from ..core.validation import as_int

    for flag, value in (("--topic", args.topic), ("--segment", args.segment), ("--imu", args.imu), ("--figure", args.figure)):
        if value is not None and args.log is None:
            raise UsageError(f"{flag} applies to a recorded log (--log)")
    if args.method in LOG_ONLY_METHODS and args.log is None:
        raise UsageError(f"--method {args.method} runs on a recorded log: give --log FILE (the Monte Carlo runs analytic, inertial and kalman)")
    if args.log is not None:  # one alignment of a recorded log, no Monte Carlo
        from ._recorded import align_recorded

        return align_recorded(args, _options(args, _scenario(args), _errors(args)))
    _check_options(args)
    scenario = _scenario(args)
    trials = as_int(args.trials, "--trials", minimum=2)
    seed = as_int(args.seed, "--seed", minimum=0)
    workers = local_workers(args)
    _check_work(args, scenario.n_samples, trials, workers)
    errors = _errors(args)
    options = _options(args, scenario, errors)
    with executor_from(args) as executor:
        mc = alignment_monte_carlo(scenario, errors, method=args.method, n_trials=trials, rng=seed, options=options, executor=executor, progress=args.progress, limits=limits_from(args))
    r = mc.result
    data = {
        "method": args.method,
        "rocking": args.rocking,
        "lat_deg": args.lat_deg,
        "heading_deg": args.heading_deg,
        "duration": scenario.n_samples * scenario.dt,
        "sample_rate_hz": scenario.sample_rate,
        "rocking_in_gyros": scenario.rocking_in_gyros,
        "reference": "stable attitude" if args.method == "analytic" else "attitude at the end",
        "trials": r.n_trials,
        "seed": seed,
        "azimuth_error_mean_deg": deg(r.mean),
        "azimuth_error_mean_ci_deg": [deg(r.mean_ci[0]), deg(r.mean_ci[1])],
        "azimuth_error_rms_deg": deg(r.rms),
        "azimuth_error_rms_ci_deg": [deg(r.rms_ci[0]), deg(r.rms_ci[1])],
        "azimuth_error_quantiles_deg": {f"{level:g}": deg(v) for level, v in r.quantiles.items()},
        # the 95 % interval of each quantile (order statistics); null where the trials do not reach
        "azimuth_error_quantile_intervals_deg": {f"{level:g}": [deg(x) if math.isfinite(x) else None for x in ci] for level, ci in r.quantile_intervals.items()},
        "tilt_error_rms_deg": [deg(x) for x in mc.tilt_rms],
        "theory_gyro_bias_floor_deg": deg(mc.bias_floor[0]),
        "theory_accel_bias_floor_deg": deg(mc.bias_floor[1]),
    }
    t = mc.theory
    if t is not None:
        data.update(
            theory_mean_deg=deg(t.mean),
            theory_rms_deg=deg(t.rms),
            theory_gyro_bias_deg=deg(t.gyro_bias),
            theory_accel_bias_deg=deg(t.accel_bias),
            theory_gyro_scale_deg=deg(t.gyro_scale),
            theory_accel_scale_deg=deg(t.accel_scale),
            theory_gyro_bias_random_rms_deg=deg(t.gyro_bias_random),
            theory_accel_bias_random_rms_deg=deg(t.accel_bias_random),
            theory_gyro_noise_rms_deg=deg(t.gyro_noise),
            theory_accel_noise_rms_deg=deg(t.accel_noise),
            theory_quantisation_rms_deg=deg(math.hypot(t.gyro_quantisation, t.accel_quantisation)),
            theory_rocking_rms_deg=deg(t.rocking),
        )
    if mc.kalman is not None:
        k, kt = mc.kalman, mc.kalman_theory
        data.update(
            theory_kalman_gyro_bias_deg=deg(kt.gyro_bias),
            theory_kalman_accel_bias_deg=deg(kt.accel_bias),
            theory_kalman_sigma_deg=deg(kt.sigma),
            nees={"times": k.times.tolist(), "mean": k.nees.tolist(), "band": list(k.nees_band), "dof": k.dim},
            nis={"times": k.times.tolist(), "mean": k.nis.tolist(), "band": list(k.nis_band), "dof": k.meas_dim, "mean_all_epochs": k.nis_all},
            consistency=mc.consistency().as_dict(),
        )
    text = [
        f"{args.method} alignment, {r.n_trials} trials, T = {data['duration']:g} s: azimuth error mean {data['azimuth_error_mean_deg']:.6g} deg "
        f"(95 % CI {data['azimuth_error_mean_ci_deg'][0]:.6g} .. {data['azimuth_error_mean_ci_deg'][1]:.6g}), rms {data['azimuth_error_rms_deg']:.6g} deg "
        f"(95 % CI {data['azimuth_error_rms_ci_deg'][0]:.6g} .. {data['azimuth_error_rms_ci_deg'][1]:.6g})",
        f"bias floors: gyro {data['theory_gyro_bias_floor_deg']:.6g} deg, accelerometer {data['theory_accel_bias_floor_deg']:.6g} deg",
    ]
    if t is not None:
        text.append(f"theory: mean {data['theory_mean_deg']:.6g} deg, rms {data['theory_rms_deg']:.6g} deg (rocking {data['theory_rocking_rms_deg']:.6g} deg)")
    if mc.kalman is not None:
        text.append(f"NEES at the end {k.nees[-1]:.3g} (95 % band {k.nees_band[0]:.3g} .. {k.nees_band[1]:.3g}), NIS {k.nis[-1]:.3g} ({k.nis_band[0]:.3g} .. {k.nis_band[1]:.3g})")
        text.append(f"consistent (every mean NEES and NIS in its band, 95 % for the family): {mc.consistency()}")
    return Result(data, "\n".join(text))


def register(commands) -> None:
    """Add ``align`` to the command line.

    Parameters
    ----------
    commands : Commands
        The registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add("align", _align, "self-alignment on a rocking base (analytic, inertial-frame or Kalman) by Monte Carlo, with its theory", progress="own")
    p.add_argument(
        "--method",
        choices=["analytic", "inertial", "kalman", "compass", "multiposition", "aided"],
        required=True,
        help="alignment method: analytic (formula (2) on averaged outputs), inertial (inertial frame), kalman (fine alignment); "
        "with --log also compass (compass loop), multiposition (still positions between turns, the biases estimated) "
        "and aided (in motion, with the log's GNSS fixes) [name] (required)",
    )
    p.add_argument("--lat-deg", type=float, required=True, help="latitude φ [deg], |φ| < 90 (required)")
    p.add_argument(
        "--log",
        default=None,
        help="recorded IMU log: .ulg, .bin, .bag, ROS 2 bag, EuRoC imu0/data.csv, .npz or .csv (docs/recorded-logs.md): align it once, no Monte Carlo [path] (default: none)",
    )
    p.add_argument("--topic", default=None, help="with --log: the stream to read [name] (default: the stream of highest rate that covers the log)")
    p.add_argument("--segment", default=None, metavar="START:END", help="with --log: the stretch to read, seconds from the log's start [s] (default: the whole log)")
    p.add_argument(
        "--imu",
        default=None,
        help="kalman with --log: sensor specification TOML, [gyro] arw_deg_per_rt_h, bias_instability_deg_per_h, [accel] vrw_m_s_per_rt_h, bias_instability_ug "
        "(a data sheet, or the output of log allan) [path] (default: none; then --arw-deg-per-rt-h and --vrw-m-s-per-rt-h are required)",
    )
    p.add_argument("--figure", default=None, help="kalman and aided with --log: a PNG of the filter's σ, bias estimates and NIS against time [path] (default: none)")
    p.add_argument("--gnss-velocity-noise-m-s", type=float, default=0.05, help="aided only: GNSS velocity noise per axis [m/s] (default 0.05)")
    p.add_argument("--gnss-position-noise", type=float, default=1.0, help="aided only: GNSS position noise per axis [m] (default 1)")
    p.add_argument("--gnss-interval", type=float, default=1.0, help="aided only: time between the filter's GNSS updates [s] (default 1)")
    p.add_argument("--heading-deg", type=float, default=0.0, help="stable heading ψ0 [deg] (default 0: body x north, y east, z down)")
    p.add_argument("--beta0-deg", type=float, default=0.0, help="stable tilt β0 about the body x axis [deg], |β0| < 90 (default 0)")
    p.add_argument("--gamma0-deg", type=float, default=0.0, help="stable tilt γ0 of the body x axis [deg], |γ0| < 90 (default 0)")
    p.add_argument("--rocking", choices=["none", "sine", "narrowband", "white"], default="none", help="rocking model: none, sine, narrowband or white (default none)")
    p.add_argument(
        "--amplitude-deg",
        default=None,
        help="rocking amplitude [deg], one value or yaw,beta,gamma; sine amplitude, sigma·√2 for narrowband and white "
        "(default: none; required with a rocking model)",
    )
    p.add_argument("--period", type=float, default=8.0, help="rocking period [s], sine and narrowband only (default 8)")
    p.add_argument("--damping", type=float, default=0.1, help="damping ratio of narrow-band rocking, in (0, 1) [dimensionless], narrowband only (default 0.1)")
    p.add_argument("--bandwidth-hz", type=float, default=None, help="bandwidth of white rocking [Hz], white only (default: half the sample rate)")
    p.add_argument("--lever-arm", default="0,0,0", help="sensor block from the rocking centre, body axes x,y,z [m] (default 0,0,0)")
    p.add_argument("--tilt-channel-only", action="store_true", help="the gyros see the stable attitude only, the rocking reaches the accelerometers (the paper's setting; default off)")
    p.add_argument("--gyro-bias-deg-per-h", default="0,0,0", help="fixed gyro bias bx,by,bz [deg/h] (default 0,0,0)")
    p.add_argument("--accel-bias-m-s2", default="0,0,0", help="fixed accelerometer bias ax,ay,az [m/s²] (default 0,0,0)")
    p.add_argument("--gyro-bias-sigma-deg-per-h", type=float, default=0.0, help="random turn-on gyro bias per axis, standard deviation [deg/h] (default 0)")
    p.add_argument("--accel-bias-sigma-m-s2", type=float, default=0.0, help="random turn-on accelerometer bias, standard deviation [m/s²] (default 0)")
    p.add_argument("--arw-deg-per-rt-h", type=float, default=0.0, help="gyro angle random walk [deg/√h] (default 0)")
    p.add_argument("--vrw-m-s-per-rt-h", type=float, default=0.0, help="accelerometer velocity random walk [m/s/√h] (default 0)")
    p.add_argument("--gyro-scale-ppm", default="0,0,0", help="gyro scale-factor errors sx,sy,sz [ppm] (default 0,0,0)")
    p.add_argument("--accel-scale-ppm", default="0,0,0", help="accelerometer scale-factor errors sx,sy,sz [ppm] (default 0,0,0)")
    p.add_argument("--gyro-quantum-arcsec", type=float, default=0.0, help="gyro angle quantum [arcsec] (default 0: none)")
    p.add_argument("--accel-quantum-m-s", type=float, default=0.0, help="accelerometer velocity quantum [m/s] (default 0: none)")
    p.add_argument("--sample-rate-hz", type=float, default=100.0, help="sensor sample rate [Hz] (default 100)")
    p.add_argument("--duration", type=float, default=120.0, help="alignment time T [s] (default 120)")
    p.add_argument("--trials", type=count, default=200, help="Monte Carlo trials [count] (default 200)")
    p.add_argument("--seed", type=count, default=0, help="root seed [count] (default 0)")
    add_executor(p)
    p.add_argument("--formula", choices=["levelled", "paper"], default=None, help="analytic only: levelled (three gyros, any heading) or paper (eq. (2) with σ, exact at heading 0) (default levelled)")
    p.add_argument("--observation", choices=["position", "velocity"], default=None, help="inertial only: integrated velocity (position) or velocity vectors (default position)")
    p.add_argument("--epoch", type=float, default=None, help="inertial: observation spacing, kalman: measurement interval [s] (default 1 for inertial, 0.1 for kalman)")
    p.add_argument("--prior-heading-deg", type=float, default=None, help="kalman only: prior azimuth standard deviation, the coarse alignment's [deg] (default 1)")
    p.add_argument("--prior-tilt-deg", type=float, default=None, help="kalman only: prior tilt standard deviation [deg] (default 0.1)")
    p.add_argument("--velocity-noise-m-s", type=float, default=None, help="kalman only: noise of the zero-velocity reference [m/s] (default 0.001)")
    p.add_argument(
        "--disturbance",
        choices=["auto", "none", "white", "shaping", "matched"],
        default=None,
        help="kalman only: how the filter models the lever-arm motion: auto (shaping when there is rocking and a lever arm), none, white, shaping "
        "(rocking states driven by white noise) or matched (rocking states matched to the rocking's spectrum) (default auto)",
    )
    p.add_argument("--assumed-period", type=float, default=None, help="kalman only: rocking period the filter assumes [s] (default: the true one)")
    p.add_argument("--assumed-damping", type=float, default=None, help="kalman only: rocking damping ratio the filter assumes [dimensionless] (default: the true one)")
    p.add_argument("--assumed-amplitude-deg", default=None, help="kalman only: rocking amplitude the filter assumes [deg], one value or yaw,beta,gamma (default: the true one)")
    p.add_argument("--lever-arm-known", action="store_true", help="kalman only: compensate the lever-arm velocity with the known lever arm (default off)")
    p.add_argument("--progress", action="store_true", help=PROGRESS_HELP)
    add_limits(p)
    for option, models in _ROCKING_OPTIONS.items():
        commands.only_with(p, option, "--rocking", models)
    for option, methods in _METHOD_OPTIONS.items():
        commands.only_with(p, option, "--method", methods)
