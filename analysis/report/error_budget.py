"""Report section ``error-budget.md``: the error budget of an IMU at rest over a one-hour mission.

Formatting only: the numbers come from
:func:`strapdown.analysis.navigation.error_budget.error_budget` (the linear
error model, one line per source, by superposition) and
:func:`strapdown.analysis.navigation.monte_carlo.monte_carlo` (the nonlinear
navigator with the data sheet's errors drawn per trial), on the example IMU
files :func:`strapdown.analysis.navigation.imu_file.example_imu`.
:func:`draw_budget` is also the figure of ``strapdown budget --figure``.
"""

from __future__ import annotations

import math

import numpy as np

from ...derivations.coning.registry import get
from ..alignment.earth import EARTH_RATE
from ..core.units import DEG_PER_RAD
from . import Section
from .rendering import fixed_layout

__all__ = ["SECTION", "build", "draw_budget", "QUANTITIES"]

SECTION = Section(
    "error-budget",
    "Error budget of an IMU over its mission",
    order=95,
    summary=(
        "Attitude, velocity and horizontal position error of a tactical-grade and a MEMS IMU at rest over one hour, one line "
        "per data-sheet source by superposition of the linear error model, the dominant source named, and the total checked "
        "against a Monte Carlo of the nonlinear navigator."
    ),
)

#: (JSON key, attribute of a budget line, factor to the printed unit) of the three quantities.
QUANTITIES = (("horizontal_position_error_m", "position", 1.0), ("velocity_error_m_s", "velocity", 1.0), ("attitude_error_deg", "attitude", DEG_PER_RAD))
_LABELS = {"position": "horizontal position error [m]", "velocity": "horizontal velocity error [m/s]", "attitude": "attitude error [deg]"}
#: Latitude [deg] and heading [deg] of the examples.
LAT_DEG, HEADING_DEG = 45.0, 0.0
#: Window of the analytic alignment before the mission [s].
ALIGNMENT_TIME = 120.0


def draw_budget(fig, r) -> None:
    """Draw the sources of a budget stacked in root sum square against time, one panel per quantity.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        An empty figure.
    r : ErrorBudget
        The budget.
    """
    t = r.times / 60.0
    axes = fig.subplots(1, 3)
    order = sorted(r.lines, key=lambda ln: float(ln.position[-1]))
    for ax, (_, attr, k) in zip(axes, QUANTITIES):
        below = np.zeros_like(t)
        for ln in order:
            top = np.sqrt(below**2 + (getattr(ln, attr) * k) ** 2)
            ax.fill_between(t, below, top, label=ln.name, linewidth=0)
            below = top
        ax.plot(t, getattr(r.total, attr) * k, color="black", linewidth=1.0, label="total")
        ax.set_xlabel("time [min]")
        ax.set_ylabel(_LABELS[attr])
    axes[0].legend(fontsize=6, loc="upper left")
    fig.suptitle(f"{r.imu}: sources stacked in root sum square (alignment {r.alignment})", fontsize=9)
    fixed_layout(fig, left=0.8, right=0.2, bottom=0.55, top=0.4, wgap=0.9)


#: Largest half-width of the simulation's interval, relative to the budget, for a "yes".
RESOLUTION = 0.25


def _verdict(a, i: int, q: int) -> str:
    if not a.agrees[i, q]:
        return "no"
    return "yes" if (a.high[i, q] - a.low[i, q]) / 2.0 <= RESOLUTION * a.model[i, q] else "not resolved (more trials)"


def _table(r) -> list:
    times = list(r.report_times)
    head = "| source | kind | " + " | ".join(f"position at {t / 60:g} min [m]" for t in times) + f" | velocity at {times[-1] / 60:g} min [m/s] | attitude at {times[-1] / 60:g} min [deg] |"
    out = [head, "|" + "---|" * (len(times) + 4)]
    end = r.index(times[-1])
    for ln in list(r.lines) + [r.total]:
        kind = "total (RSS)" if ln is r.total else ("fixed" if ln.deterministic else "random, 1σ")
        cells = " | ".join(f"{float(ln.position[r.index(t)]):.3g}" for t in times)
        out.append(f"| {ln.name} | {kind} | {cells} | {float(ln.velocity[end]):.3g} | {float(ln.attitude[end]) * DEG_PER_RAD:.3g} |")
    return out


def build(ctx) -> None:
    """Write ``error-budget.md`` and its figures.

    Parameters
    ----------
    ctx : Context
        Where to write, and the run mode.
    """
    import matplotlib.pyplot as plt

    from ..navigation.error_budget import error_budget
    from ..navigation.error_model import Site
    from ..navigation.imu_file import example_imu
    from ..navigation.monte_carlo import LEVEL, compare, monte_carlo

    quick = ctx.quick
    duration = 600.0 if quick else 3600.0
    report_times = (60.0, 600.0) if quick else (60.0, 600.0, 3600.0)
    trials = 8 if quick else 16
    site = Site(math.radians(LAT_DEG), math.radians(HEADING_DEG))
    lines = [
        "# Error budget of an IMU over its mission",
        "",
        "A designer's deliverable: for a given IMU, how large the attitude, velocity and horizontal position errors are after",
        "one minute, ten minutes and an hour, and which source dominates. The budget runs the linear navigation error model",
        "(nine navigation states in NED plus the sensor-error states; `strapdown.analysis.navigation.error_model`) once per",
        "source of the data sheet, so that each line is that source alone, and adds them in root sum square: fixed errors",
        "(turn-on biases drawn once, scale factor and misalignment at rest) as their size, random ones as 1σ",
        "(`strapdown budget --imu IMU.toml --lat-deg L --duration T`; the task page “An error budget for your IMU” describes the IMU file).",
        "",
        f"Both examples: at rest and level at {LAT_DEG:g}° N, heading {HEADING_DEG:g}°, {ALIGNMENT_TIME:g} s of analytic",
        f"self-alignment before the mission, {duration / 60:g} min of free-inertial navigation.",
    ]
    for k, name in enumerate(("tactical", "mems")):
        imu = example_imu(name)
        alignment = "analytic" if k == 0 else "none"
        r = error_budget(imu, site, duration, alignment=alignment, alignment_time=ALIGNMENT_TIME, report_times=report_times)
        lines += ["", f"## {r.imu}", ""]
        if alignment == "none":
            ratio = imu.gyro.turn_on_bias / (EARTH_RATE * math.cos(site.latitude))
            lines += [
                f"This gyro cannot find north: its turn-on bias is {ratio:.3g} times the horizontal Earth rate, so a gyrocompass",
                "heading would be meaningless. The heading is taken from an external source and counted exact (`--alignment none`);",
                "the budget below is the free-inertial part alone.",
                "",
            ]
        lines += [*_table(r), ""]
        lines.append(
            f"Dominant at {duration / 60:g} min: position — {r.dominant('position')}; velocity — {r.dominant('velocity')}; "
            f"attitude — {r.dominant('attitude')}."
        )
        fig = plt.figure(figsize=(13.0, 4.2))
        draw_budget(fig, r)
        ctx.savefig(fig, f"figures/error-budget-{name}.png")
        plt.close(fig)
        lines += ["", f"![{r.imu}: sources stacked against time](figures/error-budget-{name}.png)"]
        if k == 0:
            stream = np.random.SeedSequence(ctx.seed, spawn_key=(95,))
            mc = monte_carlo(imu, site, report_times, n_trials=trials, algorithm=get("two-sample"), alignment="analytic", alignment_time=ALIGNMENT_TIME, rng=stream)
            a = compare(r.total, mc)
            lines += [
                "",
                f"**The total against the nonlinear navigator.** {trials} trials of the full mechanization at "
                f"{imu.sample_rate:g} Hz with every error of the data sheet drawn per trial and the same analytic alignment "
                "(`strapdown.analysis.navigation.monte_carlo`, which shares no matrix with the linear model). The budget agrees where",
                f"it lies inside the simulation's {LEVEL:.1%} interval of the root mean square; the interval's width says how much that can tell",
                "with this many trials (the test suite runs 120 trials per source).",
                "",
                f"The verdict is \"yes\" only when the budget lies inside the interval and the interval is narrower than ±{RESOLUTION:.0%} of the",
                "budget, \"no\" when the budget lies outside, and \"not resolved\" when the interval is too wide to tell.",
                "",
                "| time [min] | quantity | budget | simulation (rms) | interval | width / value | agrees |",
                "|---|---|---|---|---|---|---|",
            ]
            for i, t in enumerate(a.times):
                for q, qname in enumerate(a.quantities):
                    f = DEG_PER_RAD if qname == "attitude" else 1.0
                    lines.append(
                        f"| {t / 60:g} | {qname} | {a.model[i, q] * f:.4g} | {a.simulated[i, q] * f:.4g} | {a.low[i, q] * f:.4g} – {a.high[i, q] * f:.4g} | "
                        f"{(a.high[i, q] - a.low[i, q]) / a.model[i, q]:.2f} | {_verdict(a, i, q)} |"
                    )
    ctx.write_text("error-budget.md", "\n".join(lines))
