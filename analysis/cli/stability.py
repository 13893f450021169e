"""``strapdown stability``: poles, damping and Schuler behaviour of a corrected stage (Plotnikov 1999).

The gains come from ``--k``/``--l`` (the loop gains of the (1.4) stage), from
``--schuler`` (k = 0, l = g/R), or from a requested loop
``--natural-frequency-rad-s``/``--damping`` (the stage gains k, l for the
chosen ``--reference`` are printed as well).  The warm path imports neither
SymPy nor the derivations: the transfer function comes from generated code
cached on disk (:mod:`strapdown.analysis.core.cache`).
"""

from __future__ import annotations

from . import Result
from ._options import add_limits, limits_from

_G, _R = 9.81, 6.371e6


def _loop(args):
    from ..multistage.tilt_loop import StageLoop

    # the values are checked by the library (its names become the options at the edge); here, which options go together
    g, r = args.gravity_m_s2, args.earth_radius
    manual = args.k is not None or args.l is not None
    design = args.natural_frequency_rad_s is not None or args.damping is not None
    if sum((bool(args.schuler), manual, design)) > 1:
        raise ValueError("Expected one of `--schuler`, `--k`/`--l` or `--natural-frequency-rad-s`/`--damping`, got more than one")
    if args.schuler:
        return StageLoop.schuler(g, r), None
    if design:
        from ..multistage.gain_design import design_gains

        if args.natural_frequency_rad_s is None or args.damping is None:
            raise ValueError("Expected both `--natural-frequency-rad-s` and `--damping`, got only one")
        gains = design_gains(args.natural_frequency_rad_s, args.damping, reference=args.reference)
        return gains.loop(g, r), gains
    if args.k is None or args.l is None:
        raise ValueError("Expected `--k` and `--l` (or `--schuler`, or `--natural-frequency-rad-s` and `--damping`), got " + ("neither" if not manual else "only one"))
    loop = StageLoop(args.k, args.l, g, r)
    if loop.stability == "unstable":
        poles = ", ".join(f"{z.real:+.3g}{z.imag:+.3g}j" for z in loop.poles())
        raise ValueError(
            f"Expected `--k` and `--l` giving a stable loop (both >= 0, not both 0), got an unstable one, k = {loop.k:g} 1/s, l = {loop.l:g} 1/s²: "
            f"poles {poles}, the tilt error grows without bound"
        )
    return loop, None


def _check_response(args) -> None:
    """Refuse a response too long for the limits from the options alone, before python-control is imported."""
    import math

    from ..core import budget
    from ..multistage.response_grid import largest_sample_count

    dur, end = args.accel_duration, args.horizon
    if end is None or not (0.0 < dur <= end < math.inf):
        return  # the default horizon is bounded; bad values are the library's to name
    samples = largest_sample_count(dur, end)
    what = f"--horizon {end:.3g} s over --accel-duration {dur:.3g} s (up to {samples:.3g} time samples)"
    budget.check(budget.loop_response(samples, what=what), limits_from(args))


def _run(args) -> Result:
    _check_response(args)
    loop, gains = _loop(args)
    s = loop.summary(args.accel_m_s2, args.accel_duration, horizon=args.horizon, limits=limits_from(args))
    data = {
        "k_per_s": s.k,
        "l_per_s2": s.l,
        "g_m_s2": s.gravity,
        "R_m": s.earth_radius,
        "schuler_period_s": s.schuler_period,
        "poles": [[z.real + 0.0, z.imag + 0.0] for z in s.poles],
        "damping": list(s.damping),
        "natural_frequency_rad_s": list(s.natural_frequency),
        "stability": s.stability,
        "accel_m_s2": s.accel,
        "accel_duration_s": s.accel_duration,
        "horizon_s": s.horizon,
        "peak_tilt_error_rad": s.peak_tilt_error,
        "schuler_tuning": bool(args.schuler),
    }
    lines = [f"loop gains: K = {s.k:g} 1/s, L = {s.l:g} 1/s²  (g = {s.gravity:g} m/s², R = {s.earth_radius:g} m)"]
    if gains is not None:
        data["design"] = {"reference": gains.reference, "c": gains.c, "stage_k_per_s": gains.k, "stage_l_per_s2": gains.l}
        lines.append(f"stage gains for the reference {gains.reference!r} (c = {gains.c:g}): k = {gains.k:.6g} 1/s, l = {gains.l:.6g} 1/s²")
    poles = ", ".join(f"{z.real:+.4g}{z.imag:+.4g}j" for z in s.poles)
    lines += [
        f"poles: {poles}",
        "damping: " + ", ".join(f"{z:.4g}" for z in s.damping),
        "natural frequency: " + ", ".join(f"{w:.4g}" for w in s.natural_frequency) + " rad/s",
        f"stability: {s.stability}",
        f"Schuler period: {s.schuler_period:.1f} s ({s.schuler_period / 60:.2f} min)",
        f"peak tilt error for {s.accel:g} m/s² over {s.accel_duration:g} s (horizon {s.horizon:.0f} s): {s.peak_tilt_error:.4g} rad",
    ]
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``strapdown stability``.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    p = commands.add("stability", _run, "poles, damping, stability and peak tilt error of a corrected attitude stage (Plotnikov 1999)")
    p.add_argument("--k", type=float, help="loop position gain k [1/s] (default: none; with --l)")
    p.add_argument("--l", type=float, help="loop integral gain l [1/s²] (default: none; with --k)")
    p.add_argument("--schuler", action="store_true", help="Schuler tuning: k = 0, l = g/R (default: off)")
    p.add_argument("--natural-frequency-rad-s", type=float, help="design: natural frequency ω_n of the tilt loop [rad/s] (default: none; with --damping)")
    p.add_argument("--damping", type=float, help="design: damping ratio ζ [dimensionless] (default: none; with --natural-frequency-rad-s)")
    p.add_argument("--reference", choices=("pure", "tilt"), default="pure", help="design: accelerometer quaternion of the stage, (1.4) 'pure' (c = 2) or (1.10) 'tilt' (c = 1) (default: pure)")
    p.add_argument("--accel-m-s2", type=float, default=20.0, help="horizontal acceleration A [m/s²] (default 20)")
    p.add_argument("--accel-duration", type=float, default=20.0, help="duration T of the acceleration [s] (default 20)")
    p.add_argument("--horizon", type=float, default=None, help="end of the response [s] (default: T + 2 Schuler periods)")
    p.add_argument("--gravity-m-s2", type=float, default=_G, help=f"gravity g [m/s²] (default {_G:g})")
    p.add_argument("--earth-radius", type=float, default=_R, help=f"Earth radius R [m] (default {_R:g})")
    add_limits(p)
