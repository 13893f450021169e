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

import sys

from . import Result, UsageError

__all__ = ["align_recorded", "history_data", "history_table", "nis_warning", "SIMULATION_OPTIONS", "HISTORY_POINTS"]

#: Most instants of a filter's history in the JSON output (every k-th update beyond it).
HISTORY_POINTS = 1000


def _stride(n: int, points: int = HISTORY_POINTS) -> int:
    return max(1, -(-n // points))


def history_data(h) -> dict:
    """The JSON of a :class:`~strapdown.analysis.logs.filter_history.FilterHistory` (degrees, deg/h; every k-th update).

    Parameters
    ----------
    h : FilterHistory
        The filter's histories.

    Returns
    -------
    dict
    """
    from ..core.units import deg, deg_per_h

    k = _stride(h.times.size)
    sl = slice(k - 1, None, k)
    unit = "m" if any(n.startswith("p_") for n in h.innovation_names) else "m_s"
    return {
        "stride": k,
        "times": h.times[sl].tolist(),
        "sigma_north_tilt_deg": deg(h.sigma[sl, 0]).tolist(),
        "sigma_east_tilt_deg": deg(h.sigma[sl, 1]).tolist(),
        "sigma_azimuth_deg": deg(h.sigma[sl, 2]).tolist(),
        "bias_frame": h.bias_frame,
        "gyro_bias_deg_per_h": deg_per_h(h.gyro_bias[sl]).tolist(),
        "accel_bias_m_s2": h.accel_bias[sl].tolist(),
        "innovation_names": list(h.innovation_names),
        f"innovation_{unit}": h.innovation[sl].tolist(),
        "nis": h.nis[sl].tolist(),
        "nis_dof": h.dof,
        "nis_mean": h.mean_nis,
        "nis_block": h.block,
        "nis_block_times": h.block_times.tolist(),
        "nis_block_mean": h.block_nis.tolist(),
        "nis_band": list(h.band),
        "nis_consistent": h.nis_consistent,
    }


def history_table(h) -> str:
    """A compact table of a filter's history at a few instants (1/32, 1/16, ..., 1 of the run).

    Parameters
    ----------
    h : FilterHistory
        The filter's histories.

    Returns
    -------
    str
    """
    import numpy as np

    from ..core.units import deg, deg_per_h

    E = h.times.size
    rows = sorted({max(0, int(round(E * f)) - 1) for f in (1 / 32, 1 / 16, 1 / 8, 1 / 4, 1 / 2, 1.0)})
    frame = "N,E,D" if h.bias_frame == "NED" else "x,y,z"
    head = f"{'t [s]':>9} {'σ tilt N':>9} {'σ tilt E':>9} {'σ azim':>9}  {'gyro bias ' + frame + ' [deg/h]':>30}  {'accel bias ' + frame + ' [m/s²]':>33}  {'NIS':>7}"
    lines = [head]
    for j in rows:
        s = deg(h.sigma[j])
        gb = deg_per_h(h.gyro_bias[j])
        ab = h.accel_bias[j]
        lo = max(0, j - h.block + 1)
        lines.append(
            f"{h.times[j]:9.4g} {s[0]:9.3g} {s[1]:9.3g} {s[2]:9.3g}  {gb[0]:+9.3g} {gb[1]:+9.3g} {gb[2]:+9.3g}  {ab[0]:+10.3g} {ab[1]:+10.3g} {ab[2]:+10.3g}  {float(np.mean(h.nis[lo : j + 1])):7.3g}"
        )
    lines.append(
        f"(σ in deg; NIS: mean of the {h.block} updates to t, χ²({h.dof}) per update; block means against "
        f"[{h.band[0]:.3g}, {h.band[1]:.3g}]: {'all inside' if h.nis_consistent else f'{h.outside.size} of {h.block_nis.size} outside'})"
    )
    return "\n".join(lines)


def nis_warning(h) -> str | None:
    """One line when the NIS leaves its band, None when it stays inside.

    Parameters
    ----------
    h : FilterHistory
        The filter's histories.

    Returns
    -------
    str or None
    """
    if h.nis_consistent:
        return None
    i = int(h.outside[0])  # the first block outside
    m = float(h.block_nis[i])
    side = "above" if m > h.band[1] else "below"
    why = "the filter assumes less noise than the log has (or a motion it does not model)" if side == "above" else "the filter assumes more noise than the log has"
    t1 = float(h.block_times[i])
    t0 = t1 - (h.block - 1) * (float(h.times[1] - h.times[0]) if h.times.size > 1 else 0.0)
    return (
        f"the filter's NIS leaves its χ² band in {h.outside.size} of {h.block_nis.size} blocks: mean {m:.3g} over {t0:.4g}..{t1:.4g} s, "
        f"{side} [{h.band[0]:.3g}, {h.band[1]:.3g}] ({h.dof} degrees of freedom): {why}"
    )

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

    from ..core.units import DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, deg, deg_per_h, rad, rad_per_s
    from ..core.validation import in_open_interval, positive
    from ..logs.alignment import align_log
    from ._logs import load_log
    from ._options import limits_from

    parser = args.parser_
    actions = {a.option_strings[0]: a for a in parser._actions if a.option_strings}
    for flag in SIMULATION_OPTIONS:
        a = actions[flag]
        value, default = getattr(args, a.dest), getattr(a.default, "value", a.default)
        if getattr(value, "value", value) != default:
            raise UsageError(f"{flag} does not apply to a recorded log (--log): it builds the simulated trials")
    lat = rad(in_open_interval(args.lat_deg, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))
    tuning = options.tuning
    spec = None
    if args.imu is not None:
        from ..logs.sensor_file import read_sensor_file

        spec = read_sensor_file(args.imu).sheet
        if not (spec.gyro.random_walk > 0 and spec.accel.random_walk > 0):
            raise ValueError(
                f"Expected arw_deg_per_rt_h and vrw_m_s_per_rt_h > 0 in {args.imu} (zero noise makes the filter diverge on a long log), "
                f"got {spec.gyro.random_walk:g} and {spec.accel.random_walk:g} (SI)"
            )
        tuning = replace(tuning, gyro_noise=spec.gyro.random_walk, accel_noise=spec.accel.random_walk)
    else:
        tuning = replace(tuning, gyro_noise=args.arw_deg_per_rt_h * DEG_PER_RT_H_TO_RAD_PER_RT_S, accel_noise=args.vrw_m_s_per_rt_h * M_S_PER_RT_H_TO_M_S_PER_RT_S)
    if args.method in ("kalman", "aided") and not (tuning.gyro_noise > 0 and tuning.accel_noise > 0):
        raise UsageError(
            f"--method {args.method} on a recorded log needs the sensor's noise: --imu SPEC.toml (a data sheet, or the output of log allan) "
            "or --arw-deg-per-rt-h and --vrw-m-s-per-rt-h > 0 (a filter told the noise is zero diverges on a long log)"
        )
    gyro_bias = rad_per_s(args.gyro_bias_sigma_deg_per_h) if args.gyro_bias_sigma_deg_per_h > 0 else (spec.gyro.bias_instability if spec and spec.gyro.bias_instability else None)
    accel_bias = args.accel_bias_sigma_m_s2 if args.accel_bias_sigma_m_s2 > 0 else (spec.accel.bias_instability if spec and spec.accel.bias_instability else None)
    if args.method == "kalman":
        tuning = replace(tuning, **({"gyro_bias": gyro_bias} if gyro_bias else {}), **({"accel_bias": accel_bias} if accel_bias else {}))
    aided = None
    if args.method == "aided":
        from ..alignment.aided import AidedTuning

        fields = {"gyro_noise": tuning.gyro_noise, "accel_noise": tuning.accel_noise}
        fields.update({"gyro_bias": gyro_bias} if gyro_bias else {}, **({"accel_bias": accel_bias} if accel_bias else {}))
        if args.prior_heading_deg is not None:
            fields["prior_heading"] = rad(positive(args.prior_heading_deg, "--prior-heading-deg"))
        if args.prior_tilt_deg is not None:
            fields["prior_tilt"] = rad(positive(args.prior_tilt_deg, "--prior-tilt-deg"))
        if args.epoch is not None:
            fields["epoch"] = positive(args.epoch, "--epoch")
        aided = AidedTuning(
            velocity_noise=positive(args.gnss_velocity_noise_m_s, "--gnss-velocity-noise-m-s"), position_noise=positive(args.gnss_position_noise, "--gnss-position-noise"),
            gnss_interval=positive(args.gnss_interval, "--gnss-interval"), **fields,
        )  # fmt: skip
    recorded = load_log(args)
    log = recorded.longest
    if log.metadata.get("latitude") is None and recorded.inventory.metadata:
        log = replace(log, metadata=recorded.inventory.metadata)
    gnss = recorded.inventory.gnss
    if args.method == "aided" and gnss is None:
        raise UsageError(f"--method aided needs GNSS fixes in the log, and {recorded.path.name} has none (log inspect lists its topics)")
    if args.method in ("analytic", "inertial", "kalman", "compass"):  # methods that take the block for still (or rocking about one attitude)
        from ..logs.positions import find_positions

        found = find_positions(log, lat)
        if len(found) > 1:
            turns = ", ".join(f"{deg(p.angle):.3g}°" for p in found[1:])
            sys.stderr.write(
                f"strapdown align: warning: {recorded.path.name}: the block turns between {len(found)} positions (turns of {turns} from the first): "
                f"--method {args.method} takes it for one; --method multiposition uses the positions\n"
            )
            sys.stderr.flush()
    r = align_log(log, lat, method=args.method, tuning=tuning, formula=options.formula, observation=options.observation, inertial_epoch=options.inertial_epoch,
                  gnss=gnss, aided=aided, limits=limits_from(args))  # fmt: skip
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
        "reference": {"stable": "stable attitude", "end": "attitude at the end", "first position": "attitude of the first position"}[r.reference],
        "heading_deg": deg(r.heading),
        "beta_deg": deg(r.beta),
        "gamma_deg": deg(r.gamma),
        "heading_sigma_deg": None if r.heading_sigma is None else deg(r.heading_sigma),
        "tilt_sigma_deg": None if r.tilt_sigma is None else [deg(x) for x in r.tilt_sigma],
        "heading_error_deg": None if r.heading_error is None else deg(r.heading_error),
    }
    if r.gyro_bias is not None:
        data["gyro_bias_deg_per_h"] = deg_per_h(r.gyro_bias).tolist()
        data["accel_bias_m_s2"] = [float(x) for x in r.accel_bias]
        data["bias_frame"] = "body"
    if r.multiposition is not None:
        mp = r.multiposition
        from ..alignment.tilt_attitude import angles_from_matrix

        end = angles_from_matrix(mp.end_attitude)
        data["positions"] = [{"start": p.time_start, "end": p.time_end, "turn_deg": deg(p.angle)} for p in mp.positions]
        data["end_heading_deg"], data["end_beta_deg"], data["end_gamma_deg"] = deg(float(end.heading)), deg(float(end.beta)), deg(float(end.gamma))
        data["residual_rms"] = mp.residual_rms
    if r.history is not None:
        data["history"] = history_data(r.history)
    text = (
        f"{r.method} alignment of {args.log} ({recorded.format}, {recorded.topic}; {log.n_samples} samples, {r.duration:g} s"
        f"{', the longest of ' + str(len(recorded.segments)) + ' segments' if len(recorded.segments) > 1 else ''}): "
        f"heading {data['heading_deg']:.6g} deg, β {data['beta_deg']:.6g} deg, γ {data['gamma_deg']:.6g} deg ({data['reference']})"
    )
    if r.heading_sigma is not None:
        text += f"\nstandard deviations: azimuth {data['heading_sigma_deg']:.4g} deg" + (
            f", tilts {data['tilt_sigma_deg'][0]:.3g} and {data['tilt_sigma_deg'][1]:.3g} deg" if r.tilt_sigma is not None else ""
        )
    if r.heading_error is not None:
        text += f"\nazimuth error against the log's truth: {data['heading_error_deg']:.4g} deg"
    if r.multiposition is not None:
        text += "\npositions: " + "; ".join(f"{p['start']:.4g}..{p['end']:.4g} s turned {p['turn_deg']:.4g} deg" for p in data["positions"])
        text += f"\nattitude at the end (the first position's, carried by the gyros): heading {data['end_heading_deg']:.6g} deg, β {data['end_beta_deg']:.6g} deg, γ {data['end_gamma_deg']:.6g} deg"
    if r.gyro_bias is not None:
        gb, ab = data["gyro_bias_deg_per_h"], data["accel_bias_m_s2"]
        text += f"\nbias estimates (body x, y, z): gyro {gb[0]:+.4g}, {gb[1]:+.4g}, {gb[2]:+.4g} deg/h; accelerometer {ab[0]:+.4g}, {ab[1]:+.4g}, {ab[2]:+.4g} m/s²"
    if r.history is not None:
        text += "\n" + history_table(r.history)
        warning = nis_warning(r.history)
        if warning is not None:
            sys.stderr.write(f"strapdown align: warning: {warning}\n")
            sys.stderr.flush()
    if args.figure is not None:
        from ..report.log_figures import draw_alignment_history

        draw_alignment_history(r.history, args.figure, title=f"{r.method} alignment of {recorded.path.name} ({recorded.topic})")
        data["figure"] = str(args.figure)
        text += f"\nfigure: {args.figure}"
    return Result(data, text)
