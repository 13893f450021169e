"""``strapdown log environment``, ``log coning``, ``log allan``: the analyses of a recorded IMU log.

* ``log environment`` estimates the vibration environment of the log (lines
  and cross-spectra, :mod:`strapdown.analysis.logs.environment_estimate`) and
  writes it as an environment file (``docs/environment-files.md``), with a
  figure of the spectra if asked;
* ``log coning`` replays coning algorithms on the log's increments
  (:mod:`strapdown.analysis.logs.replay`) and puts beside each the drift the
  closed form predicts in the environment estimated from the same log;
* ``log allan`` reads ARW, bias instability and RRW off the Allan deviation of
  a static stretch (:mod:`strapdown.analysis.logs.static_noise`) and writes
  them as a sensor file (:mod:`strapdown.analysis.logs.sensor_file`).

Degrees, deg/h and µg at this edge; SI inside.  Library imports are lazy.
"""

from __future__ import annotations

from . import Result, UsageError
from ._logs import add_log_options, load_log
from ._options import add_limits, count, limits_from, number

__all__ = ["register"]


# --------------------------------------------------------------------------- reading
def _read(args):
    """The log's gap-free segments, read and checked (:func:`strapdown.analysis.cli._logs.load_log`), and how its increments were formed."""
    log = load_log(args)
    note = "increments as logged" if log.held == "increments" else f"the log holds rates: {log.conversion}, so the corrections see the sampled rates"
    return log.segments, note


def _vec(v) -> list:
    return [float(x) for x in v]


def _common(p) -> None:
    p.add_argument("file", metavar="FILE", help="recorded IMU log: ULog, DataFlash, ROS bag, EuRoC CSV or the package's .npz/.csv [path] (docs/recorded-logs.md)")
    add_log_options(p)
    add_limits(p)


# --------------------------------------------------------------------------- log environment
def _environment_estimate(args, segments):
    from ..core.validation import in_open_interval, positive
    from ..logs.environment_estimate import estimate_environment

    resolution = None if args.resolution_hz is None else positive(args.resolution_hz, "--resolution-hz")
    fmin = None if args.min_freq_hz is None else positive(args.min_freq_hz, "--min-freq-hz")
    p = in_open_interval(args.false_alarm, "--false-alarm", 0.0, 1.0)
    if args.max_rows < 2:
        raise UsageError(f"Expected --max-rows ≥ 2, got {args.max_rows}")
    return estimate_environment(segments, resolution=resolution, min_frequency=fmin, false_alarm=p, max_rows=args.max_rows, name=args.name or "estimated from a log",
                                limits=limits_from(args), progress=args.progress)  # fmt: skip


def _channel_names(mask) -> list:
    from ..vibration.environment import CHANNELS

    return [c for c, m in zip(CHANNELS, mask) if m]


def _line_data(ln) -> dict:
    import numpy as np

    from ..core.units import DEG_PER_RAD
    from ..vibration.environment import CHANNELS

    lo, hi = ln.interval(0.95)
    amp = np.abs(ln.amplitude)
    phase = np.angle(ln.amplitude) * DEG_PER_RAD
    with np.errstate(divide="ignore", invalid="ignore"):
        half = np.where(amp > 0, np.minimum(1.96 * ln.sigma / np.sqrt(2.0) / np.where(amp > 0, amp, 1.0), np.pi), np.pi) * DEG_PER_RAD
    return {
        "frequency_hz": ln.frequency,
        "rate_amplitude_deg_s": _vec(amp[:3] * DEG_PER_RAD),
        "rate_amplitude_ci95_deg_s": [[float(a * DEG_PER_RAD), float(b * DEG_PER_RAD)] for a, b in zip(lo[:3], hi[:3])],
        "rate_phase_deg": _vec(phase[:3]),
        "accel_amplitude_m_s2": _vec(amp[3:]),
        "accel_amplitude_ci95_m_s2": [[float(a), float(b)] for a, b in zip(lo[3:], hi[3:])],
        "accel_phase_deg": _vec(phase[3:]),
        "phase_ci95_halfwidth_deg": _vec(half),
        "significant_channels": _channel_names(ln.significant),
        "reference_channel": CHANNELS[ln.reference],
    }


def _figure(estimate, path) -> None:
    """The rate and specific-force auto-spectra with their 95 % band, the lines marked, written atomically as PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from ..core.atomic import replaced_atomically
    from ..core.units import DEG_PER_RAD
    from ..report.rendering import fixed_layout

    f = estimate.frequency
    auto = np.real(np.diagonal(estimate.density, axis1=1, axis2=2))
    lo, hi = estimate.auto_factors(0.95)
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 6.0), sharex=True)
    panels = ((axes[0], range(3), DEG_PER_RAD**2, "rate PSD [(deg/s)²/Hz]"), (axes[1], range(3, 6), 1.0, "specific-force PSD [(m/s²)²/Hz]"))
    for ax, channels, scale, label in panels:
        for c, colour in zip(channels, ("C0", "C1", "C2")):
            name = "xyz"[c % 3]
            y = auto[:, c] * scale
            if np.any(y > 0):
                ax.fill_between(f, y * lo, y * hi, color=colour, alpha=0.2, linewidth=0)
                ax.loglog(f, y, color=colour, linewidth=0.8, label=name)
        for ln in estimate.lines:
            ax.axvline(ln.frequency, color="k", linestyle=":", linewidth=0.8)
        ax.set_ylabel(label)
        ax.grid(True, which="major", alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper right", fontsize=8)
    for ln in estimate.lines:
        axes[0].annotate(f"{ln.frequency:.4g} Hz", (ln.frequency, 1.0), xycoords=("data", "axes fraction"), xytext=(2, -10), textcoords="offset points", fontsize=7)
    axes[1].set_xlabel(f"frequency [Hz] (Nyquist {estimate.nyquist:g} Hz; nothing above it is seen)")
    axes[0].set_title(f"band with the lines removed (shaded: 95 % interval), lines dotted ({len(estimate.lines)})", fontsize=9)
    fixed_layout(fig, left=1.0, right=0.2, bottom=0.6, top=0.35, hgap=0.25)
    try:
        with replaced_atomically(path) as tmp:
            fig.savefig(tmp, format="png", dpi=100)
    finally:
        plt.close(fig)


def environment_command(args) -> Result:
    """Run ``strapdown log environment``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    from ..core.units import DEG_PER_RAD
    from ..logs.environment_estimate import write_environment

    if not str(args.out).strip():
        raise UsageError("Expected --out to name the environment file to write, got an empty name")
    from contextlib import ExitStack

    from ..core.atomic import replaced_atomically

    segments, _ = _read(args)
    e = _environment_estimate(args, segments)
    with ExitStack() as stack:  # both files or neither
        env_path = stack.enter_context(replaced_atomically(args.out))
        figure_path = stack.enter_context(replaced_atomically(args.figure)) if args.figure else None
        write_environment(env_path, e)
        if figure_path is not None:
            _figure(e, figure_path)
    lo, hi = e.auto_factors(0.95)
    rms = e.band_rms()
    s = e.search
    data = {
        "log": str(args.file),
        "out": str(args.out),
        "figure": args.figure,
        "segments": e.segments,
        "duration": e.duration,
        "sample_rate_hz": 1.0 / e.sample_interval,
        "nyquist_hz": e.nyquist,
        "unseen": (
            f"nothing above the Nyquist frequency {e.nyquist:g} Hz: vibration there reaches the log only through the filters ahead of it, "
            f"folded onto its alias below {e.nyquist:g} Hz, and is counted at that alias"
        ),
        "sensors": "none: the filters ahead of the log are already in the samples and are not applied again",
        "resolution_hz": e.resolution,
        "bins_per_row": e.merged,
        "table_rows": int(e.frequency.size),
        "band_hz": [float(e.frequency[0]), float(e.frequency[-1])],
        "welch_segments": e.welch_segments,
        "dof": e.dof,
        "psd_ci95_factor": [lo, hi],
        "band_rms_deg_s": _vec(rms[:3] * DEG_PER_RAD),
        "band_rms_m_s2": _vec(rms[3:]),
        "line_search": {"candidates": s.candidates, "blocks": s.blocks, "threshold_f": None if s.blocks < 3 else s.threshold, "false_alarm": s.false_alarm},
        "lines": [_line_data(ln) for ln in e.lines],
    }
    text = [
        f"{args.file}: {e.duration:g} s at {1.0 / e.sample_interval:g} Hz in {e.segments} segment(s); Nyquist {e.nyquist:g} Hz — {data['unseen']}",
        f"Welch: bins of {e.resolution:.4g} Hz, {e.welch_segments} segments, {e.dof:.4g} degrees of freedom; a PSD value's 95 % interval is ×[{lo:.3g}, {hi:.3g}]",
        f"lines (Thomson F-test over {s.blocks} blocks, false-alarm probability {s.false_alarm:g}): {len(e.lines)} of {s.candidates} candidates",
    ]
    for d in data["lines"]:
        rate = ", ".join(f"{a:.4g}∠{p:+.1f}°" for a, p in zip(d["rate_amplitude_deg_s"], d["rate_phase_deg"]))
        accel = ", ".join(f"{a:.4g}∠{p:+.1f}°" for a, p in zip(d["accel_amplitude_m_s2"], d["accel_phase_deg"]))
        text.append(f"  {d['frequency_hz']:.6g} Hz: rate [deg/s] {rate}; specific force [m/s²] {accel} (in {', '.join(d['significant_channels'])})")
    text.append(f"band (lines removed), rms: rate [deg/s] {', '.join(f'{x:.4g}' for x in data['band_rms_deg_s'])}; specific force [m/s²] {', '.join(f'{x:.4g}' for x in data['band_rms_m_s2'])}")
    text.append(f"environment file written: {args.out} (sensors 'none': the filters ahead of the log are in the samples)")
    if args.figure:
        text.append(f"figure written: {args.figure}")
    return Result(data, "\n".join(text))


# --------------------------------------------------------------------------- log coning
def _algorithms(args) -> list:
    from ...derivations.coning.algorithms import SecondOrderConditionError, load_toml
    from ...derivations.coning.registry import get

    algs = [get(name) for name in args.algorithm or ()]
    for path in args.algorithm_file or ():
        if not str(path).strip():
            raise ValueError("Expected `--algorithm-file` to name a TOML file, got an empty file name")
        try:
            algs.append(load_toml(path, allow_inconsistent=args.allow_inconsistent))
        except SecondOrderConditionError as exc:
            raise ValueError(f"{exc.path}: algorithm misses the second-order condition (pass --allow-inconsistent to accept it)") from None
    if not algs:
        raise UsageError("Expected at least one --algorithm NAME or --algorithm-file FILE")
    return algs


def coning_command(args) -> Result:
    """Run ``strapdown log coning``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    from ..core.units import RAD_PER_S_TO_DEG_PER_H
    from ..logs.environment_estimate import estimate_environment
    from ..logs.replay import replay
    from ..vibration.drift import environment_drift

    algs = _algorithms(args)
    segments, note = _read(args)
    limits = limits_from(args)
    r = replay(segments, algs, limits=limits, progress=args.progress)
    k = RAD_PER_S_TO_DEG_PER_H
    predicted = None
    if args.prediction == "closed-form":
        env = estimate_environment(segments, limits=limits, progress=args.progress)
        predicted = [environment_drift(a, env.environment, r.sample_interval).total_vector for a in algs]
    rows = []
    for i, a in enumerate(r.algorithms):
        row = {
            "name": a.algorithm.name,
            "correction_rate_deg_per_h": _vec(a.rate * k),
            "correction_rate_rad_s": _vec(a.rate),
            "steps": a.steps,
            "integrated_time": a.integrated_time,
        }
        if predicted is not None:
            row["predicted_drift_deg_per_h"] = _vec(predicted[i] * k)
        rows.append(row)
    diffs = []
    for j in range(1, len(algs)):
        d = {"a": algs[j].name, "b": algs[0].name, "drift_difference_deg_per_h": _vec(r.drift_difference(j, 0) * k)}
        if predicted is not None:
            d["predicted_difference_deg_per_h"] = _vec((predicted[j] - predicted[0]) * k)
        diffs.append(d)
    data = {
        "log": str(args.file),
        "segments": r.segments,
        "samples": r.samples,
        "sample_interval": r.sample_interval,
        "increments": note,
        "prediction": args.prediction,
        "algorithms": rows,
        "differences": diffs,
    }
    text = [
        f"{args.file}: {r.samples} samples at {1.0 / r.sample_interval:g} Hz in {r.segments} segment(s) (steps restart in each); {note}",
        "mean correction rate (Σ of the corrections beyond Σ Δθ over the integrated time), body axes [deg/h]"
        + ("; beside it the drift the closed form predicts in the environment estimated from this log" if predicted is not None else ""),
    ]
    for row in rows:
        c = ", ".join(f"{x:+.6g}" for x in row["correction_rate_deg_per_h"])
        line = f"  {row['name']:<18} ({row['steps']} steps, {row['integrated_time']:g} s): [{c}]"
        if predicted is not None:
            line += "  predicted drift [" + ", ".join(f"{x:+.4g}" for x in row["predicted_drift_deg_per_h"]) + "]"
        text.append(line)
    if diffs:
        text.append(f"drift of each algorithm minus that of {algs[0].name} on this log, from the attitudes they compute over {r.common_time:g} s [deg/h]:")
        for d in diffs:
            line = f"  {d['a']:<18} [" + ", ".join(f"{x:+.6g}" for x in d["drift_difference_deg_per_h"]) + "]"
            if predicted is not None:
                line += "  closed form [" + ", ".join(f"{x:+.4g}" for x in d["predicted_difference_deg_per_h"]) + "]"
            text.append(line)
    return Result(data, "\n".join(text))


# --------------------------------------------------------------------------- log allan
def allan_command(args) -> Result:
    """Run ``strapdown log allan``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    from ..logs.sensor_file import ACCEL_KEYS, GYRO_KEYS, write_sensor_file
    from ..logs.static_noise import static_noise

    segments, _ = _read(args)
    if args.out is not None and not str(args.out).strip():
        raise UsageError("Expected --out to name the sensor file to write, got an empty name")
    noise = static_noise(segments, limits=limits_from(args))
    if args.out is not None:
        write_sensor_file(args.out, noise, name=args.name or "from a static log", description=f"read off the Allan deviation of {args.file}")
    data = {"log": str(args.file), "duration": noise.duration, "sample_interval": noise.sample_interval, "level": noise.level, "out": args.out}
    text = [f"{args.file}: {noise.duration:g} s at {1.0 / noise.sample_interval:g} Hz; each value read at one averaging time τ, with its 95 % interval"]
    for table, keys, triad in (("gyro", GYRO_KEYS, noise.gyro), ("accel", ACCEL_KEYS, noise.accel)):
        entry = {}
        for key, (attr, factor, _) in keys.items():
            c = getattr(triad, attr)
            entry[key] = c.value / factor
            entry[f"{key}_ci95"] = [c.low / factor, c.high / factor]
            entry[f"{key}_tau"] = c.tau
            seen = "" if c.low > 0 else " (not seen: an upper bound)"
            text.append(f"  {table} {key:<28} {c.value / factor:.4g}  [{c.low / factor:.4g}, {c.high / factor:.4g}] at τ = {c.tau:g} s{seen}")
        entry["tau"] = _vec(triad.pooled.taus)
        entry["adev"] = _vec(triad.pooled.adev)
        data[table] = entry
    if args.out is not None:
        text.append(f"sensor file written: {args.out}")
    return Result(data, "\n".join(text))


# --------------------------------------------------------------------------- registration
def register(commands) -> None:
    """Add ``log environment``, ``log coning`` and ``log allan`` to the command line.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    from ..logs.environment_estimate import DEFAULT_RESOLUTION, MAX_ROWS

    p = commands.add("environment", environment_command, "vibration environment of a log: lines and cross-spectra with intervals, written as an environment file", group="log")
    _common(p)
    p.add_argument("--out", required=True, metavar="ENV.toml", help="environment file to write [path] (docs/environment-files.md; required)")
    p.add_argument("--figure", default=None, metavar="PNG", help="also draw the spectra with the lines marked into this PNG file [path] (default: none)")
    p.add_argument("--resolution-hz", type=number, default=None, metavar="R",
                   help=f"bin width of the Welch estimate [Hz] (default {DEFAULT_RESOLUTION:g}, coarser for a short log)")  # fmt: skip
    p.add_argument("--min-freq-hz", type=number, default=None, metavar="F", help="lowest frequency of the estimate [Hz] (default: two bins)")
    p.add_argument("--false-alarm", type=number, default=1e-3, metavar="P", help="probability that pure band noise yields a line [dimensionless] (default 0.001)")
    p.add_argument("--max-rows", type=count, default=MAX_ROWS, metavar="N", help=f"largest number of rows of the spectrum table [count] (default {MAX_ROWS})")
    p.add_argument("--name", default=None, metavar="NAME", help="name of the environment [name] (default: estimated from a log)")
    p = commands.add("coning", coning_command, "replay coning algorithms on a log: mean correction rate of each, their exact drift differences, the closed form beside", group="log")
    _common(p)
    from ...derivations.coning.registry import names

    p.add_argument("--algorithm", action="append", metavar="NAME",
                   help=f"registry algorithm [name], repeatable, one of: {', '.join(names(library=True))} (`strapdown algorithms list`) (default: none)")  # fmt: skip
    p.add_argument("--algorithm-file", action="append", metavar="FILE", help="TOML file with a user algorithm [path], repeatable (docs/algorithm-files.md) (default: none)")
    p.add_argument("--allow-inconsistent", action="store_true", help="accept a TOML algorithm that misses the second-order condition")
    p.add_argument("--prediction", choices=["closed-form", "none"], default="closed-form",
                   help="closed-form: also the drift predicted in the environment estimated from the log; none: the replay alone (default closed-form)")  # fmt: skip
    p = commands.add("allan", allan_command, "Allan deviation of a static log: ARW, bias instability and RRW with intervals, written as a sensor file", group="log")
    _common(p)
    p.add_argument("--out", default=None, metavar="SENSOR.toml", help="sensor file to write [path] (docs/recorded-logs.md) (default: none)")
    p.add_argument("--name", default=None, metavar="NAME", help="name of the IMU in the sensor file [name] (default: from a static log)")
