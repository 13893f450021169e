"""``strapdown align``: self-alignment on a rocking base by Monte Carlo, with the theory that applies.

At rest with heading 0 the body axes are x north, y east, z down; the rocking
is given per axis (yaw, β, γ) in the angles of Hrechka & Koroliov.  Degrees,
deg/h, deg/√h, ppm and arc-seconds at the edge, SI inside (converted with
:mod:`strapdown.analysis.core.units`).  Library imports are lazy.
"""

from __future__ import annotations

from . import Result, UsageError

__all__ = ["register"]

_ROCKING_OPTIONS = {"amplitude_deg": ("sine", "narrowband", "white"), "period": ("sine", "narrowband"), "damping": ("narrowband",), "bandwidth_hz": ("white",)}
_METHOD_OPTIONS = {
    "formula": ("analytic",),
    "observation": ("inertial",),
    "epoch": ("inertial", "kalman"),
    "prior_heading_deg": ("kalman",),
    "prior_tilt_deg": ("kalman",),
    "velocity_noise": ("kalman",),
    "disturbance": ("kalman",),
    "assumed_period": ("kalman",),
    "assumed_damping": ("kalman",),
    "assumed_amplitude_deg": ("kalman",),
}


def _flag(name: str) -> str:
    return "--" + name.replace("_", "-")


def _check_options(args) -> None:
    for name, models in _ROCKING_OPTIONS.items():
        if getattr(args, name) is not None and args.rocking not in models:
            raise UsageError(f"{_flag(name)} does not apply to --rocking {args.rocking} (it applies to {', '.join(models)})")
    for name, methods in _METHOD_OPTIONS.items():
        if getattr(args, name) is not None and args.method not in methods:
            raise UsageError(f"{_flag(name)} does not apply to --method {args.method} (it applies to {', '.join(methods)})")
    if args.lever_arm_known and args.method != "kalman":
        raise UsageError(f"--lever-arm-known does not apply to --method {args.method} (it applies to kalman)")
    if args.rocking != "none" and args.amplitude_deg is None:
        raise UsageError(f"--amplitude-deg is required with --rocking {args.rocking}")


def _triple(text, name):
    from ._options import floats

    parts = str(text).split(",")
    if len(parts) == 1:
        return floats(f"{text},{text},{text}", name, 3)
    return floats(text, name, 3)


def _scenario(args):
    import numpy as np

    from ..core.units import rad
    from ..core.validation import as_float, in_open_interval, positive
    from ..gyrocompass.base_motion import motion_model
    from ..gyrocompass.imu import Scenario

    lat = rad(in_open_interval(args.lat_deg, "lat-deg", -90.0, 90.0, text="(-90, 90) deg"))
    heading = rad(as_float(args.heading_deg, "heading-deg"))
    b0, g0 = as_float(args.beta0_deg, "beta0-deg"), as_float(args.gamma0_deg, "gamma0-deg")
    for name, value in (("beta0-deg", b0), ("gamma0-deg", g0)):
        if not abs(value) < 90.0:
            raise UsageError(f"Expected --{name} in (-90, 90) deg, got {value:g}")
    fs = positive(args.sample_rate_hz, "sample-rate-hz")
    T = positive(args.duration, "duration")
    if T * fs < 2:
        raise ValueError(f"Expected `duration` >= two samples = {2 / fs:g} s, got {T:g}")
    amplitude = np.zeros(3)
    if args.rocking != "none":
        amplitude = _triple(args.amplitude_deg, "amplitude-deg")
        if np.any(amplitude < 0):
            raise ValueError(f"Expected `amplitude-deg` >= 0, got {args.amplitude_deg}")
        peak = amplitude * (1.0 if args.rocking == "sine" else 4.0 / np.sqrt(2.0))
        limit = 90.0 - max(abs(b0), abs(g0))
        if np.any(peak[1:] >= limit):
            kind = "the amplitude" if args.rocking == "sine" else "4 sigma = 2.83 x amplitude"
            raise UsageError(f"Expected --amplitude-deg tilts with {kind} below 90 - |tilt0| = {limit:g} deg, got {args.amplitude_deg}")
    period = 8.0 if args.period is None else positive(args.period, "period")
    damping = 0.1 if args.damping is None else as_float(args.damping, "damping")
    if args.rocking == "narrowband" and not 0.0 < damping < 1.0:
        raise ValueError(f"Expected `damping` in (0, 1), got {damping:g}")
    bandwidth = None if args.bandwidth_hz is None else positive(args.bandwidth_hz, "bandwidth-hz")
    if bandwidth is not None and bandwidth > fs / 2:
        raise ValueError(f"Expected `bandwidth-hz` <= sample-rate-hz/2 = {fs / 2:g} Hz, got {bandwidth:g}")
    if args.rocking == "sine" and 1.0 / period >= fs / 2:
        raise ValueError(f"Expected `period` > 2/sample-rate-hz = {2 / fs:g} s, got {period:g}")
    if args.rocking == "narrowband" and 4.0 / period >= fs / 2:
        raise ValueError(f"Expected `period` > 8/sample-rate-hz = {8 / fs:g} s (the narrow-band spectrum reaches 4/period), got {period:g}")
    motion = motion_model(args.rocking, rad(amplitude), period=period, damping=damping, bandwidth=bandwidth)
    lever = _triple(args.lever_arm, "lever-arm")
    return Scenario(lat, heading, rad(b0), rad(g0), motion, lever, fs, T, rocking_in_gyros=not args.tilt_channel_only)


def _errors(args):
    import numpy as np

    from ..core import units
    from ..core.validation import nonnegative
    from ..gyrocompass.imu import SensorErrors

    return SensorErrors(
        gyro_bias=units.rad_per_s(_triple(args.gyro_bias_deg_per_h, "gyro-bias-deg-per-h")),
        accel_bias=_triple(args.accel_bias_m_s2, "accel-bias-m-s2"),
        gyro_bias_sigma=units.rad_per_s(nonnegative(args.gyro_bias_sigma_deg_per_h, "gyro-bias-sigma-deg-per-h")),
        accel_bias_sigma=nonnegative(args.accel_bias_sigma_m_s2, "accel-bias-sigma-m-s2"),
        gyro_noise=nonnegative(args.arw_deg_per_rt_h, "arw-deg-per-rt-h") * units.DEG_PER_RT_H_TO_RAD_PER_RT_S,
        accel_noise=nonnegative(args.vrw_m_s_per_rt_h, "vrw-m-s-per-rt-h") * units.M_S_PER_RT_H_TO_M_S_PER_RT_S,
        gyro_scale=np.asarray(_triple(args.gyro_scale_ppm, "gyro-scale-ppm")) * units.PPM,
        accel_scale=np.asarray(_triple(args.accel_scale_ppm, "accel-scale-ppm")) * units.PPM,
        gyro_quantum=nonnegative(args.gyro_quantum_arcsec, "gyro-quantum-arcsec") * units.ARCSEC,
        accel_quantum=nonnegative(args.accel_quantum_m_s, "accel-quantum-m-s"),
    )


def _options(args, scenario, errors):
    import numpy as np

    from ..core.units import rad
    from ..core.validation import positive
    from ..gyrocompass.alignment_monte_carlo import AlignmentOptions
    from ..gyrocompass.base_motion import motion_model
    from ..gyrocompass.fine_alignment import Disturbance, FilterTuning, assumed_disturbance

    if args.method != "kalman":
        return AlignmentOptions(formula=args.formula or "levelled", observation=args.observation or "position", inertial_epoch=positive(args.epoch or 1.0, "epoch"))
    kind = args.disturbance or "auto"
    moving = args.rocking != "none" and np.any(scenario.lever_arm)
    if kind == "auto":
        kind = "shaping" if moving and not args.lever_arm_known else "none"
    assumed = scenario.motion
    if args.assumed_period is not None or args.assumed_damping is not None or args.assumed_amplitude_deg is not None:
        if args.rocking == "none":
            raise UsageError("--assumed-period, --assumed-damping and --assumed-amplitude-deg need a rocking model (--rocking)")
        name = "narrowband" if args.rocking == "white" else args.rocking
        amp = rad(_triple(args.assumed_amplitude_deg, "assumed-amplitude-deg")) if args.assumed_amplitude_deg is not None else scenario.motion.amplitude
        period = positive(args.assumed_period, "assumed-period") if args.assumed_period is not None else getattr(scenario.motion, "period", 8.0)
        damping = args.assumed_damping if args.assumed_damping is not None else getattr(scenario.motion, "damping", 0.1)
        assumed = motion_model(name, amp, period=period, damping=damping)
    dist = assumed_disturbance(assumed, scenario, kind=kind) if kind != "none" else Disturbance("none")
    gb = errors.gyro_bias_sigma or max(float(np.max(np.abs(errors.gyro_bias))), rad(0.01) / 3600.0)
    ab = errors.accel_bias_sigma or max(float(np.max(np.abs(errors.accel_bias))), 1e-4)
    tuning = FilterTuning(
        epoch=positive(args.epoch or 0.1, "epoch"),
        prior_tilt=rad(positive(args.prior_tilt_deg or 0.1, "prior-tilt-deg")),
        prior_heading=rad(positive(args.prior_heading_deg or 1.0, "prior-heading-deg")),
        gyro_bias=gb,
        accel_bias=ab,
        gyro_noise=errors.gyro_noise,
        accel_noise=errors.accel_noise,
        measurement_noise=positive(args.velocity_noise or 1e-3, "velocity-noise"),
        disturbance=dist,
        lever_arm_known=bool(args.lever_arm_known),
    )
    return AlignmentOptions(tuning=tuning)


def _align(args) -> Result:
    import math

    from ..core.units import deg
    from ..core.validation import as_int
    from ..gyrocompass.alignment_monte_carlo import alignment_monte_carlo

    _check_options(args)
    scenario = _scenario(args)
    errors = _errors(args)
    options = _options(args, scenario, errors)
    trials = as_int(args.trials, "trials", minimum=2)
    seed = as_int(args.seed, "seed", minimum=0)
    workers = as_int(args.workers, "workers", minimum=1)
    executor = None
    if workers > 1:
        from concurrent.futures import ProcessPoolExecutor

        executor = ProcessPoolExecutor(workers)
    try:
        mc = alignment_monte_carlo(scenario, errors, method=args.method, n_trials=trials, rng=seed, options=options, executor=executor, progress=args.progress)
    finally:
        if executor is not None:
            executor.shutdown()
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
    return Result(data, "\n".join(text))


def register(commands) -> None:
    """Add ``align`` to the command line.

    Parameters
    ----------
    commands : Commands
        The registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add("align", _align, "self-alignment on a rocking base (analytic, inertial-frame or Kalman) by Monte Carlo, with its theory")
    p.add_argument(
        "--method",
        choices=["analytic", "inertial", "kalman"],
        required=True,
        help="alignment method: analytic (formula (2) on averaged outputs), inertial (inertial frame) or kalman (fine alignment) (required)",
    )
    p.add_argument("--lat-deg", type=float, required=True, help="latitude φ [deg], |φ| < 90 (required)")
    p.add_argument("--heading-deg", type=float, default=0.0, help="stable heading ψ0 [deg] (default 0: body x north, y east, z down)")
    p.add_argument("--beta0-deg", type=float, default=0.0, help="stable tilt β0 about the body x axis [deg] (default 0)")
    p.add_argument("--gamma0-deg", type=float, default=0.0, help="stable tilt γ0 of the body x axis [deg] (default 0)")
    p.add_argument("--rocking", choices=["none", "sine", "narrowband", "white"], default="none", help="rocking model: none, sine, narrowband or white (default none)")
    p.add_argument("--amplitude-deg", default=None, help="rocking amplitude [deg], one value or yaw,beta,gamma; sine amplitude, sigma·√2 for narrowband and white (required with a rocking model)")
    p.add_argument("--period", type=float, default=None, help="rocking period [s] (sine, narrowband; default 8)")
    p.add_argument("--damping", type=float, default=None, help="damping ratio of narrow-band rocking, in (0, 1) [1] (default 0.1)")
    p.add_argument("--bandwidth-hz", type=float, default=None, help="bandwidth of white rocking [Hz] (default half the sample rate)")
    p.add_argument("--lever-arm", default="0,0,0", help="sensor block from the rocking centre, body axes x,y,z [m] (default 0,0,0)")
    p.add_argument("--tilt-channel-only", action="store_true", help="the gyros see the stable attitude only, the rocking reaches the accelerometers (the paper's setting; default off)")
    p.add_argument("--gyro-bias-deg-per-h", default="0,0,0", help="fixed gyro bias bx,by,bz [deg/h] (default 0,0,0)")
    p.add_argument("--accel-bias-m-s2", default="0,0,0", help="fixed accelerometer bias ax,ay,az [m/s²] (default 0,0,0)")
    p.add_argument("--gyro-bias-sigma-deg-per-h", type=float, default=0.0, help="random turn-on gyro bias per axis, standard deviation [deg/h] (default 0)")
    p.add_argument("--accel-bias-sigma-m-s2", type=float, default=0.0, help="random turn-on accelerometer bias, standard deviation [m/s²] (default 0)")
    p.add_argument("--arw-deg-per-rt-h", type=float, default=0.0, help="gyro angle random walk [deg/√h] (default 0)")
    p.add_argument("--vrw-m-s-per-rt-h", type=float, default=0.0, help="accelerometer velocity random walk [m/s/√h] (default 0)")
    p.add_argument("--gyro-scale-ppm", default="0,0,0", help="gyro scale-factor errors sx,sy,sz [ppm] (default 0,0,0)")
    p.add_argument("--accel-scale-ppm", default="0,0,0", help="accelerometer scale-factor errors [ppm] (default 0,0,0)")
    p.add_argument("--gyro-quantum-arcsec", type=float, default=0.0, help="gyro angle quantum [arcsec] (default 0: none)")
    p.add_argument("--accel-quantum-m-s", type=float, default=0.0, help="accelerometer velocity quantum [m/s] (default 0: none)")
    p.add_argument("--sample-rate-hz", type=float, default=100.0, help="sensor sample rate [Hz] (default 100)")
    p.add_argument("--duration", type=float, default=120.0, help="alignment time T [s] (default 120)")
    p.add_argument("--trials", type=int, default=200, help="Monte Carlo trials [1] (default 200)")
    p.add_argument("--seed", type=int, default=0, help="root seed [1] (default 0)")
    p.add_argument("--workers", type=int, default=1, help="worker processes [1] (default 1; the result does not depend on it)")
    p.add_argument("--formula", choices=["levelled", "paper"], default=None, help="analytic: levelled (three gyros, any heading) or paper (eq. (2) with σ, exact at heading 0) (default levelled)")
    p.add_argument("--observation", choices=["position", "velocity"], default=None, help="inertial: integrated velocity (position) or velocity vectors (default position)")
    p.add_argument("--epoch", type=float, default=None, help="inertial: observation spacing, kalman: measurement interval [s] (default 1 and 0.1)")
    p.add_argument("--prior-heading-deg", type=float, default=None, help="kalman: prior azimuth standard deviation, the coarse alignment's [deg] (default 1)")
    p.add_argument("--prior-tilt-deg", type=float, default=None, help="kalman: prior tilt standard deviation [deg] (default 0.1)")
    p.add_argument("--velocity-noise", type=float, default=None, help="kalman: noise of the zero-velocity reference [m/s] (default 0.001)")
    p.add_argument(
        "--disturbance",
        choices=["auto", "none", "white", "shaping"],
        default=None,
        help="kalman: how the filter models the lever-arm motion: auto (shaping when there is rocking and a lever arm), none, white or shaping (default auto)",
    )
    p.add_argument("--assumed-period", type=float, default=None, help="kalman: rocking period the filter assumes [s] (default the true one)")
    p.add_argument("--assumed-damping", type=float, default=None, help="kalman: rocking damping the filter assumes [1] (default the true one)")
    p.add_argument("--assumed-amplitude-deg", default=None, help="kalman: rocking amplitude the filter assumes [deg], one value or yaw,beta,gamma (default the true one)")
    p.add_argument("--lever-arm-known", action="store_true", help="kalman: compensate the lever-arm velocity with the known lever arm (default off)")
    p.add_argument("--progress", action="store_true", help="progress bar on stderr (default off)")
