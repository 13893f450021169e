"""``strapdown stability``: poles, damping and Schuler behaviour of a corrected stage."""

from __future__ import annotations

import math

from . import Result


def _run(args) -> Result:
    from ..multistage.stage_control import StageLoop

    if args.schuler:
        if args.k is not None or args.l is not None:
            raise ValueError("Expected either `--schuler` or `--k`/`--l`, got both")
        loop = StageLoop.schuler(args.g, args.R)
    else:
        if args.k is None or args.l is None:
            raise ValueError("Expected `--k` and `--l` (or `--schuler`), got " + ("neither" if args.k is None and args.l is None else "only one"))
        loop = StageLoop(args.k, args.l, args.g, args.R)
    _refuse_runaway(loop, args)
    data = loop.summary(args.accel, args.accel_duration, horizon=args.horizon)
    if data["stability"] == "unstable" and not math.isfinite(data["peak_tilt_error_rad"]):
        _refuse_runaway(loop, args, force=True)
    data["schuler_tuning"] = bool(args.schuler)
    poles = ", ".join(f"{re:+.4g}{im:+.4g}j" for re, im in data["poles"])
    text = "\n".join(
        [
            f"stage gains: k = {loop.k:g} 1/s, l = {loop.l:g} 1/s²  (g = {loop.gravity:g} m/s², R = {loop.earth_radius:g} m)",
            f"poles: {poles}",
            "damping: " + ", ".join(f"{z:.4g}" for z in data["damping"]),
            "natural frequency: " + ", ".join(f"{w:.4g}" for w in data["natural_frequency_rad_s"]) + " rad/s",
            f"stability: {data['stability']}",
            f"Schuler period: {data['schuler_period_s']:.1f} s ({data['schuler_period_s'] / 60:.2f} min)",
            f"peak tilt error for {data['accel_m_s2']:g} m/s² over {data['accel_duration_s']:g} s "
            f"(horizon {data['horizon_s']:.0f} s): {data['peak_tilt_error_rad']:.4g} rad",
        ]
    )
    return Result(data, text)


def _refuse_runaway(loop, args, *, force: bool = False) -> None:
    """Refuse gains whose tilt error grows beyond float range over the horizon (say they are unstable)."""
    _, _, poles = loop.damp()
    growth = max(float(p.real) for p in poles)
    horizon = args.horizon if args.horizon is not None else args.accel_duration + 2.0 * loop.schuler_period
    if force or (growth > 0 and growth * horizon > 700.0):  # e^700: beyond float range
        shown = ", ".join(f"{complex(p).real:+.3g}{complex(p).imag:+.3g}j" for p in poles)
        raise ValueError(
            f"Expected gains `--k`, `--l` of a stable loop, got an unstable one (k = {loop.k:g} 1/s, l = {loop.l:g} 1/s², poles {shown}): "
            f"its tilt error grows as e^({growth:.3g} t) without bound over the {horizon:.3g} s horizon"
        )


def register(commands) -> None:
    p = commands.add(
        "stability",
        _run,
        "poles, damping, stability and peak tilt error of a corrected attitude stage (Plotnikov 1999)",
    )
    p.add_argument("--k", type=float, help="position-correction gain k [1/s]")
    p.add_argument("--l", type=float, help="integral-correction gain l [1/s²]")
    p.add_argument("--schuler", action="store_true", help="Schuler tuning: k = 0, l = g/R")
    p.add_argument("--accel", type=float, default=20.0, help="horizontal acceleration A [m/s²] (default 20)")
    p.add_argument("--accel-duration", type=float, default=20.0, help="duration T of the acceleration [s] (default 20)")
    p.add_argument("--horizon", type=float, default=None, help="end of the response [s] (default T + 2 Schuler periods)")
    p.add_argument("--g", type=float, default=9.81, help="gravity g [m/s²] (default 9.81)")
    p.add_argument("--R", type=float, default=6.371e6, help="Earth radius R [m] (default 6.371e6)")
