"""``strapdown log inspect FILE``: what a recorded log holds, how it reads, and whether it is plausible.

Library imports are lazy.  The inventory is :class:`strapdown.analysis.logs.inventory.Inventory`,
the checks :mod:`strapdown.analysis.logs.checks`; this module only formats them.
"""

from __future__ import annotations

from . import Result
from ._logs import add_log_options, load_log
from ._options import add_limits

__all__ = ["register"]


def _inspect(args) -> Result:
    import math

    from ..core.units import DEG_PER_RAD

    log = load_log(args, refuse=False)
    inv = log.inventory
    t = inv.timing
    data = {
        "path": str(args.file),
        "format": inv.format,
        "software": inv.software,
        "topic": inv.topic,
        "held": inv.held,
        "conversion": inv.conversion,
        "units": inv.units,
        "frame": inv.frame,
        "duration": inv.duration,
        "samples": log.n_samples,
        "streams": [
            {"topic": s.topic, "samples": s.samples, "rate_hz": s.rate_hz, "start": s.start, "end": s.end, "held": s.held, "readable": s.readable, "note": s.note} for s in inv.streams
        ],
        "timing": {
            "rate_hz": t.rate_hz, "interval": t.interval, "jitter_rms": t.jitter_rms, "jitter_max": t.jitter_max, "glitches": t.glitches,
            "logger_dropouts": t.logger_dropouts, "missing_samples": t.missing,
            "integration_interval": t.integration_interval, "integration_interval_unit_in_log": t.integration_interval_unit,
        },  # fmt: skip
        "gaps": [{"start": g.start, "duration": g.duration, "missing": g.missing} for g in t.gaps],
        "segments": [{"start": float(s.time[0] - s.dt), "end": float(s.time[-1]), "samples": s.n_samples, "rate_hz": 1.0 / s.dt} for s in log.segments],
        "filters": [{"parameter": f.parameter, "value": f.value, "acts_on_samples": f.acts_on_samples, "evidence": f.evidence} for f in inv.filters],
        "gnss": None,
        "metadata": {k: v for k, v in inv.metadata.items()},
        "notes": list(inv.notes),
        "checks": [{"name": c.name, "status": c.status, "value": c.value, "message": c.message} for c in log.checks.checks],
    }
    if inv.gnss is not None:
        g = inv.gnss
        data["gnss"] = {"topic": g.topic, "fixes": int(g.time.size), "lat_deg": g.mean_latitude * DEG_PER_RAD, "lon_deg": float(g.longitude.mean()) * DEG_PER_RAD, "velocity": g.velocity is not None}
    if args.figure is not None:
        from ..logs.overview import log_overview
        from ..report.log_figures import draw_overview

        draw_overview(log_overview(log), args.figure, title=f"{log.path.name}: {inv.topic} ({inv.format}, {t.rate_hz:.4g} Hz, {len(log.segments)} segment(s))")
        data["figure"] = str(args.figure)
    lines = [
        f"{log.path.name}: {inv.format} log{', ' + inv.software if inv.software else ''}, {inv.duration:.6g} s",
        f"stream read: {inv.topic} ({inv.held}), {log.n_samples} samples in {len(log.segments)} segment(s), {t.rate_hz:.6g} Hz, jitter {t.jitter_rms * 1e6:.3g} µs rms",
        f"  increments: {inv.conversion}",
        f"  units: {inv.units}",
        f"  frame: {inv.frame}",
    ]
    if t.integration_interval is not None:
        lines.append(f"  integration interval in the log: {t.integration_interval:.6g} s (stored in {t.integration_interval_unit})")
    if t.gaps:
        lines.append(f"  gaps: {len(t.gaps)}, {t.missing} samples missing, longest {max(g.duration for g in t.gaps):.4g} s")
    lines.append("streams (* read, + readable with --topic):")
    others = 0
    for s in inv.streams:
        if not (s.readable or s.note):
            others += 1
            continue
        mark = "*" if s.topic == inv.topic else ("+" if s.readable else " ")
        lines.append(f" {mark} {s.topic:<28} {s.samples:>9} msgs {s.rate_hz:>9.4g} Hz  {s.note}")
    if others:
        lines.append(f"   and {others} other topic(s) (the JSON lists them)")
    if inv.filters:
        lines.append("sensor filters (acts on the samples read?):")
        for f in inv.filters:
            acts = {True: "yes", False: "no", None: "?"}[f.acts_on_samples]
            value = "" if f.value is None or not math.isfinite(f.value) else f" = {f.value:g}"
            lines.append(f"  {f.parameter}{value}: {acts} — {f.evidence}")
    if inv.gnss is not None:
        lines.append(f"GNSS: {data['gnss']['fixes']} fixes on {inv.gnss.topic}, latitude {data['gnss']['lat_deg']:.6g}°")
    for n in inv.notes:
        lines.append(f"note: {n}")
    lines.append("checks:")
    for c in log.checks.checks:
        lines.append(f"  {c.status:<4} {c.name}: {c.message} ({c.value})")
    if args.figure is not None:
        lines.append(f"figure: {args.figure}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``log inspect`` to the command line.

    Parameters
    ----------
    commands : Commands
        The registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add("inspect", _inspect, "what a recorded IMU log holds: streams, rate, gaps, units, frame, sensor filters, plausibility checks", group="log")
    p.add_argument("file", help="the log: .ulg, .bin, .bag, a ROS 2 bag folder, EuRoC imu0/data.csv, .npz or .csv [path]")
    add_log_options(p)
    p.add_argument("--lat-deg", type=float, default=None, help="latitude to check against the log's own position [deg] (default: none)")
    p.add_argument("--figure", default=None, help="write a PNG of the rates and specific force against time, with the gaps [path] (default: none)")
    p.add_argument("--progress", action="store_true", help="progress bar on stderr (default off)")
    add_limits(p)
