"""``strapdown budget``: the error budget of an IMU at rest over its mission, source by source.

The IMU is a TOML file (:mod:`strapdown.analysis.navigation.imu_file`); an
environment file (``docs/environment-files.md``) adds the algorithms' residuals.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..core.atomic import replaced_atomically
from ..core.units import DEG, DEG_PER_RAD
from ..core.validation import in_open_interval
from . import Result
from ._options import add_limits, count, limits_from, number

_QUANTITIES = (("horizontal_position_error_m", "position", 1.0), ("velocity_error_m_s", "velocity", 1.0), ("attitude_error_deg", "attitude", DEG_PER_RAD))


def _times(text: str) -> list:
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"Expected `--times` as comma-separated seconds such as 60,600,3600, got {text[:40]!r}") from None
    if not values or not all(math.isfinite(v) and v > 0 for v in values):
        raise ValueError(f"Expected `--times` as positive finite seconds, got {text[:40]!r}")
    return values


def _line(ln, i: int) -> dict:
    out = {key: float(getattr(ln, attr)[i] * k) for key, attr, k in _QUANTITIES}
    out["tilt_error_deg"] = float(ln.tilt[i] * DEG_PER_RAD)
    out["heading_error_deg"] = float(ln.heading[i] * DEG_PER_RAD)
    return out


def _save_figure(r, path) -> None:
    """The sources stacked in root sum square against time (the report's figure), written atomically."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..report.error_budget import draw_budget

    fig = plt.figure(figsize=(13.0, 4.2))
    try:
        draw_budget(fig, r)
        with replaced_atomically(path) as tmp:
            fig.savefig(tmp, format=Path(path).suffix.lstrip(".") or "png")
    finally:
        plt.close(fig)


def budget_command(args) -> Result:
    """Run ``strapdown budget``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    from ..navigation.error_budget import error_budget
    from ..navigation.error_model import Site
    from ..navigation.imu_file import load_imu

    lat = in_open_interval(args.lat_deg, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees")
    report = _times(args.times)
    imu = load_imu(args.imu)
    env = alg = None
    if args.environment is not None:
        from ..vibration.environment import load_environment

        env = load_environment(args.environment)
    if args.algorithm is not None or env is not None:
        from ...derivations.coning.registry import get

        alg = get("two-sample" if args.algorithm is None else args.algorithm)
    r = error_budget(
        imu, Site(lat * DEG, args.heading_deg * DEG), args.duration, environment=env, algorithm=alg,
        alignment=args.alignment, alignment_time=args.alignment_time, report_times=report, points=args.points,
        progress=args.progress, limits=limits_from(args),
    )  # fmt: skip
    end = len(r.times) - 1
    sources = {}
    for ln in r.lines:
        entry = _line(ln, end)
        entry["kind"] = "deterministic" if ln.deterministic else "random (1 sigma)"
        entry["at_times"] = {f"{t:g}": _line(ln, r.index(t)) for t in r.report_times}
        entry["series"] = {key: (getattr(ln, attr) * k).tolist() for key, attr, k in _QUANTITIES}
        entry["north_east_position_m"] = [float(ln.mean[end, 6]), float(ln.mean[end, 7])] if ln.deterministic else [float(ln.sigma()[end, 6]), float(ln.sigma()[end, 7])]
        sources[ln.name] = entry
    total = {key: float(getattr(r.total, attr)[end] * k) for key, attr, k in _QUANTITIES}
    total["at_times"] = {f"{t:g}": {key: float(getattr(r.total, attr)[r.index(t)] * k) for key, attr, k in _QUANTITIES} for t in r.report_times}
    total["series"] = {key: (getattr(r.total, attr) * k).tolist() for key, attr, k in _QUANTITIES}
    data = {
        "imu": r.imu,
        "lat_deg": lat,
        "heading_deg": args.heading_deg,
        "duration_s": r.duration,
        "alignment": r.alignment,
        "alignment_time_s": r.alignment_time,
        "algorithm": r.algorithm,
        "environment": r.environment,
        "times_s": r.times.tolist(),
        "report_times_s": r.report_times.tolist(),
        "sources": sources,
        "total": total,
        "dominant": {q: r.dominant(q) for q in ("position", "velocity", "attitude")},
    }
    if args.figure:
        _save_figure(r, args.figure)
        data["figure"] = str(args.figure)
    lines = [f"{r.imu}: at rest, latitude {lat:g}°, heading {args.heading_deg:g}°, alignment {r.alignment}" + (f" ({r.alignment_time:g} s)" if r.alignment_time else "")]
    if r.environment:
        lines.append(f"environment {r.environment}, algorithm {r.algorithm}")
    lines.append("horizontal position error [m] (fixed sources: signed error's size; random: 1σ; total: root sum square)")
    head = f"{'source':<28}" + "".join(f"{t:>14g} s" for t in r.report_times)
    lines.append(head)
    for ln in list(r.lines) + [r.total]:
        lines.append(f"{ln.name:<28}" + "".join(f"{float(ln.position[r.index(t)]):>16.4g}" for t in r.report_times))
    lines.append(f"dominant at {r.duration:g} s: position {data['dominant']['position']}, velocity {data['dominant']['velocity']}, attitude {data['dominant']['attitude']}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``budget``.

    Parameters
    ----------
    commands : Commands
        The command registry.
    """
    p = commands.add(
        "budget", budget_command,
        "error budget of an IMU at rest over its mission: attitude, velocity and horizontal position error per source, the total, the dominant source",
        progress="own",
    )  # fmt: skip
    p.add_argument("--imu", required=True, metavar="FILE", help="TOML IMU file [path] (keys in the docs: [gyro] bias_deg_per_h, arw_deg_per_rt_h, ...; required)")
    p.add_argument("--environment", default=None, metavar="FILE", help="TOML vibration environment file [path]: adds the coning, sculling and scrolling lines (default: none)")
    p.add_argument("--algorithm", default=None, metavar="NAME", help="coning algorithm of the environment lines [name], see `strapdown algorithms list` (default: two-sample with an environment)")
    p.add_argument("--lat-deg", type=number, required=True, metavar="L", help="latitude [deg], in (-90, 90) (required)")
    p.add_argument("--heading-deg", type=number, default=0.0, metavar="H", help="heading of body x [deg] (default 0)")
    p.add_argument("--duration", "--duration-s", type=number, required=True, metavar="T", help="mission length [s], up to 30 days (required)")
    p.add_argument("--alignment", choices=("none", "analytic"), default="none", help="initial attitude error: none, or the analytic alignment on the same sensors (default none)")
    p.add_argument("--alignment-time", type=number, default=300.0, metavar="T", help="window of the analytic alignment [s] (default 300)")
    commands.only_with(p, "--alignment-time", "--alignment", ("analytic",))
    p.add_argument("--times", default="60,600,3600", metavar="T1,T2", help="times of the table [s], comma-separated; those past the end dropped, the end added (default: 60,600,3600)")
    p.add_argument("--points", type=count, default=241, metavar="N", help="times of the series, evenly spaced [count] (default 241)")
    p.add_argument("--figure", default=None, metavar="FILE", help="also draw the stacked figure of the sources against time here [path] (default: none)")
    p.add_argument("--progress", action="store_true", help="progress bars even when stderr is not a terminal")
    add_limits(p)
