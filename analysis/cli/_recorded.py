"""``strapdown align --log``: one alignment of a recorded IMU log (the Monte Carlo options do not apply).

The log is read and checked by :func:`strapdown.analysis.cli._logs.load_log`
(any format of ``docs/recorded-logs.md``; the longest gap-free segment is aligned).
The sensor options describe what the filter assumes about the IMU (its noise and
bias priors); ``kalman`` takes its noise from ``--imu`` (a data sheet or the
output of ``log allan``) or from ``--arw-deg-per-rt-h`` and ``--vrw-m-s-per-rt-h``,
never a silent zero.  Nothing random is added to the recorded data, so
``--seed`` is refused with the other options that build a simulation.
"""

from __future__ import annotations

from . import Result, UsageError

__all__ = ["align_recorded", "SIMULATION_OPTIONS"]

#: Options of ``align`` that build the simulated trials, refused with ``--log``.
SIMULATION_OPTIONS = (
    "--heading-deg", "--beta0-deg", "--gamma0-deg", "--rocking", "--amplitude-deg", "--period", "--damping", "--bandwidth-hz", "--lever-arm",
    "--tilt-channel-only", "--gyro-bias-deg-per-h", "--accel-bias-m-s2", "--gyro-scale-ppm", "--accel-scale-ppm", "--gyro-quantum-arcsec",
    "--accel-quantum-m-s", "--sample-rate-hz", "--duration", "--trials", "--workers", "--disturbance", "--assumed-period", "--assumed-damping",
    "--assumed-amplitude-deg", "--lever-arm-known", "--seed",
)  # fmt: skip


def align_recorded(args, options) -> Result:
    """Align the log ``args.log`` once with ``args.method``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``align``.
    options : AlignmentOptions
        The method options built from them (the filter's tuning for ``kalman``).

    Returns
    -------
    Result

    Raises
    ------
    UsageError
        If a simulation option was given.
    """
    from dataclasses import replace

    from ..core.units import deg, rad
    from ..core.validation import in_open_interval
    from ..logs.alignment import align_log
    from ._logs import load_log

    parser = args.parser_
    actions = {a.option_strings[0]: a for a in parser._actions if a.option_strings}
    for flag in SIMULATION_OPTIONS:
        a = actions[flag]
        value, default = getattr(args, a.dest), getattr(a.default, "value", a.default)
        if getattr(value, "value", value) != default:
            raise UsageError(f"{flag} does not apply to a recorded log (--log): it builds the simulated trials")
    lat = rad(in_open_interval(args.lat_deg, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))
    tuning = options.tuning
    if args.method == "kalman":
        if args.imu is not None:
            from ..logs.sensor_spec import read_sensor_spec

            spec = read_sensor_spec(args.imu)
            tuning = replace(tuning, gyro_noise=spec.arw, accel_noise=spec.vrw)
            if spec.gyro_bias_instability and args.gyro_bias_sigma_deg_per_h == 0:
                tuning = replace(tuning, gyro_bias=spec.gyro_bias_instability)
            if spec.accel_bias_instability and args.accel_bias_sigma_m_s2 == 0:
                tuning = replace(tuning, accel_bias=spec.accel_bias_instability)
        elif not (tuning.gyro_noise > 0 and tuning.accel_noise > 0):
            raise UsageError(
                "--method kalman on a recorded log needs the sensor's noise: --imu SPEC.toml (a data sheet, or the output of log allan) "
                "or --arw-deg-per-rt-h and --vrw-m-s-per-rt-h > 0 (a filter told the noise is zero diverges on a long log)"
            )
    elif args.imu is not None:
        raise UsageError(f"--imu does not apply to --method {args.method} (it sets the noise of the kalman filter)")
    recorded = load_log(args)
    log = recorded.longest
    if log.metadata.get("latitude") is None and recorded.inventory.metadata:
        log = replace(log, metadata=recorded.inventory.metadata)
    r = align_log(log, lat, method=args.method, tuning=tuning, formula=options.formula, observation=options.observation, inertial_epoch=options.inertial_epoch)
    data = {
        "log": str(args.log),
        "format": recorded.format,
        "topic": recorded.topic,
        "segments": len(recorded.segments),
        "checks": {c.name: c.status for c in recorded.checks.checks},
        "method": r.method,
        "lat_deg": args.lat_deg,
        "samples": log.n_samples,
        "sample_rate_hz": 1.0 / log.dt,
        "duration": r.duration,
        "reference": "stable attitude" if r.reference == "stable" else "attitude at the end",
        "heading_deg": deg(r.heading),
        "beta_deg": deg(r.beta),
        "gamma_deg": deg(r.gamma),
        "heading_sigma_deg": None if r.heading_sigma is None else deg(r.heading_sigma),
        "heading_error_deg": None if r.heading_error is None else deg(r.heading_error),
    }
    text = (
        f"{r.method} alignment of {args.log} ({recorded.format}, {recorded.topic}; {log.n_samples} samples, {r.duration:g} s"
        f"{', the longest of ' + str(len(recorded.segments)) + ' segments' if len(recorded.segments) > 1 else ''}): "
        f"heading {data['heading_deg']:.6g} deg, β {data['beta_deg']:.6g} deg, γ {data['gamma_deg']:.6g} deg ({data['reference']})"
    )
    if r.heading_sigma is not None:
        text += f"\nthe filter's azimuth standard deviation: {data['heading_sigma_deg']:.4g} deg"
    if r.heading_error is not None:
        text += f"\nazimuth error against the log's truth: {data['heading_error_deg']:.4g} deg"
    return Result(data, text)
