"""``strapdown multistage``: the section-5 scenario of Plotnikov (1999), peak errors per stage.

The default run is the package's reading of section 5 with the consistent
truth model (a body over the rotating Earth); every reading the text leaves
open is an option.  The JSON keeps the list ``stages`` with
``peak_yaw_error_rad``, ``peak_pitch_error_rad``, ``peak_roll_error_rad`` and
``peak_tilt_error_rad``.
"""

from __future__ import annotations

from ..core import budget
from . import Result
from ._options import add_limits, check_work, count, limits_from


def _scenario(args):
    from ..core import units
    from ..core.validation import as_float, as_int, in_open_interval, positive
    from ..multistage.trajectory import Scenario

    # degrees, and t_d (the library's `rocking_decay_origin`), are checked here; the rest by Scenario
    lat = units.rad(in_open_interval(args.lat_deg, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))
    kw = dict(duration=args.duration, accel=args.accel_m_s2, accel_duration=args.accel_duration, latitude=lat, truth=args.truth, rocking_decay=args.rocking_decay_per_s)
    if args.rocking_origin is not None:
        kw["rocking_decay_origin"] = as_float(args.rocking_origin, "--rocking-origin")
    scenario = Scenario(**kw)
    as_int(args.seed, "--seed", minimum=0)
    steps = scenario.duration / positive(args.step, "--step")
    check_work(args, budget.multistage(steps, what=f"{steps:.3g} integration steps (--duration / --step)"))
    return scenario


def _run(args) -> Result:
    from ..core.validation import positive
    from ..multistage.stages import plotnikov_1999_stages, simulate

    scenario = _scenario(args)
    c = None if args.stage1_c is None else positive(args.stage1_c, "--stage1-c")
    components = (1, 3) if args.stage1_components == "horizontal" else (0, 1, 2, 3)
    stages = plotnikov_1999_stages(scenario.gravity, scenario.earth_radius, stage1_reference=args.stage1_reference, stage1_c=c, stage1_components=components, switch=args.switch)
    result = simulate(scenario, stages, step=args.step, rng=args.seed, limits=limits_from(args))
    peaks = result.peaks()
    data = {
        "duration_s": scenario.duration,
        "step_s": float(args.step),
        "g_m_s2": scenario.gravity,
        "R_m": scenario.earth_radius,
        "stages": [
            {"stage": j + 1, "peak_yaw_error_rad": p.yaw, "peak_pitch_error_rad": p.pitch, "peak_roll_error_rad": p.roll, "peak_tilt_error_rad": p.tilt}
            for j, p in enumerate(peaks)
        ],
        "tilt_reduction": peaks[0].tilt / peaks[-1].tilt if peaks[-1].tilt > 0 else None,
        "readings": {
            "truth": scenario.truth,
            "stage1_reference": args.stage1_reference,
            "stage1_c": stages[0].c,
            "stage1_components": list(stages[0].components),
            "switch": args.switch,
            "rocking_decay_per_s": scenario.rocking_decay,
            "rocking_origin_s": scenario.rocking_start if scenario.rocking_decay_origin is None else scenario.rocking_decay_origin,
            "accel_m_s2": scenario.accel,
        },
    }
    lines = [f"Plotnikov (1999) section-5 scenario, {scenario.duration:g} s, step {args.step:g} s, truth model {scenario.truth}"]
    for row in data["stages"]:
        lines.append(
            f"after stage {row['stage']}: peak |Δψ| = {row['peak_yaw_error_rad']:.3e}, |Δθ| = {row['peak_pitch_error_rad']:.3e}, "
            f"|Δγ| = {row['peak_roll_error_rad']:.3e}, tilt = {row['peak_tilt_error_rad']:.3e} rad"
        )
    if data["tilt_reduction"] is not None:
        lines.append(f"tilt error reduced {data['tilt_reduction']:.1f}x by the second stage")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``strapdown multistage``.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    from ...derivations.multistage.published import SECTION5 as S5

    p = commands.add("multistage", _run, "simulate the two-stage corrected attitude system of Plotnikov (1999), section 5")
    p.add_argument("--duration", type=float, default=S5.duration, help=f"length of the run [s] (default {S5.duration:g})")
    p.add_argument("--step", type=float, default=0.02, help="integration step [s] (default 0.02)")
    p.add_argument("--accel-m-s2", type=float, default=S5.accel, help=f"northward acceleration [m/s²] (default {S5.accel:g}, as printed)")
    p.add_argument("--accel-duration", type=float, default=S5.accel_duration, help=f"its duration [s] (default {S5.accel_duration:g})")
    p.add_argument("--lat-deg", type=float, default=S5.latitude_deg, help=f"initial latitude [deg] (default {S5.latitude_deg:g})")
    p.add_argument(
        "--truth",
        choices=("rotating-earth", "no-coriolis"),
        default="rotating-earth",
        help="truth model: consistent motion over the rotating Earth, or the earlier one without Coriolis and V²/R (default: rotating-earth)",
    )
    p.add_argument("--rocking-decay-per-s", type=float, default=S5.envelope_decay, help=f"decay rate d of the rocking envelope exp(-d(t - t_d)) [1/s] (default {S5.envelope_decay:g}, as printed)")
    p.add_argument("--rocking-origin", type=float, default=None, help=f"t_d of the envelope [s] (default: the start of rocking, {S5.rest_end:g}; printed: {S5.envelope_origin:g})")
    p.add_argument("--stage1-reference", choices=("tilt", "pure"), default="tilt", help="accelerometer quaternion of stage 1: (1.10) 'tilt' or (1.4) 'pure' (default: tilt)")
    p.add_argument("--stage1-c", type=float, default=None, help="factor c of stage 1 [dimensionless] (default: 1 for tilt, 2 for pure; printed: 2)")
    p.add_argument("--stage1-components", choices=("horizontal", "all"), default="horizontal", help="components of ν corrected by stage 1: 1 and 3, or all four (default: horizontal)")
    p.add_argument(
        "--switch",
        choices=("carry", "rescale", "bumpless"),
        default="carry",
        help="integral state of stage 2 at its gain switch: kept, rescaled by l_new/l_old, or bumpless (default: carry)",
    )
    p.add_argument("--seed", type=count, default=0, help="seed of the sensor noise [count] (default 0)")
    add_limits(p)
