"""``strapdown multistage``: the section-5 scenario of Plotnikov (1999), peak errors per stage."""

from __future__ import annotations

import numpy as np

from ..core import budget
from ..core.validation import as_int, in_open_interval, positive
from . import Result
from ._options import add_limits, check_work, count


def _run(args) -> Result:
    from ..multistage.stages import plotnikov_1999_stages, simulate
    from ..multistage.trajectory import Scenario

    latitude = in_open_interval(args.latitude, "--latitude", -90.0, 90.0, text="(-90, 90) degrees")
    scenario = Scenario(duration=args.duration, accel=args.accel, accel_duration=args.accel_duration, latitude=np.radians(latitude))
    steps = scenario.duration / positive(args.step, "step")
    check_work(args, budget.multistage(steps, what=f"{steps:.3g} integration steps (--duration / --step)"))
    stages = plotnikov_1999_stages(scenario.gravity, scenario.earth_radius)
    result = simulate(scenario, stages, step=args.step, rng=as_int(args.seed, "seed", minimum=0))
    peak = result.peak()
    tilt = result.tilt().max(axis=1)
    data = {
        "duration_s": scenario.duration,
        "step_s": float(args.step),
        "g_m_s2": scenario.gravity,
        "R_m": scenario.earth_radius,
        "stages": [
            {
                "stage": j + 1,
                "peak_yaw_error_rad": float(peak[j, 0]),
                "peak_pitch_error_rad": float(peak[j, 1]),
                "peak_roll_error_rad": float(peak[j, 2]),
                "peak_tilt_error_rad": float(tilt[j]),
            }
            for j in range(peak.shape[0])
        ],
        "tilt_reduction": float(tilt[0] / tilt[-1]) if tilt[-1] > 0 else None,
    }
    lines = [f"Plotnikov (1999) section-5 scenario, {scenario.duration:g} s, step {args.step:g} s"]
    for row in data["stages"]:
        lines.append(
            f"after stage {row['stage']}: peak |Δψ| = {row['peak_yaw_error_rad']:.3e}, |Δθ| = {row['peak_pitch_error_rad']:.3e}, "
            f"|Δγ| = {row['peak_roll_error_rad']:.3e}, tilt = {row['peak_tilt_error_rad']:.3e} rad"
        )
    if data["tilt_reduction"] is not None:
        lines.append(f"tilt error reduced {data['tilt_reduction']:.1f}x by the second stage")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    p = commands.add("multistage", _run, "simulate the two-stage corrected attitude system of Plotnikov (1999), section 5")
    p.add_argument("--duration", type=float, default=5000.0, help="length of the run [s] (default 5000)")
    p.add_argument("--step", type=float, default=0.02, help="integration step [s] (default 0.02)")
    p.add_argument("--accel", type=float, default=20.0, help="northward acceleration [m/s²] (default 20)")
    p.add_argument("--accel-duration", type=float, default=20.0, help="its duration [s] (default 20)")
    p.add_argument("--latitude", type=float, default=45.0, help="initial latitude [deg] (default 45)")
    p.add_argument("--seed", type=count, default=0, help="seed of the sensor noise (default 0)")
    add_limits(p)
