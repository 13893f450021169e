"""Report section ``alignment-design.md``: the alignment designer's toolkit.

Observability of the alignment errors, the methods (analytic, inertial-frame,
Kalman, coarse-to-fine, compass loop) on the same trials against their trials'
floors, GNSS-aided alignment in motion, sensor models from the data sheet with
their Allan deviation, time-to-align design charts with Monte Carlo check
points, and a recorded log.  Formatting only: every number and curve comes from
:mod:`strapdown.analysis.alignment.design_studies` and the modules it calls.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.units import DEG_PER_RAD as D
from ..core.units import deg_per_h, rad
from . import Section
from .rendering import fixed_layout

__all__ = ["SECTION", "build", "TITLE"]

#: Heading of the page.
TITLE = "Alignment design: observability, methods, motion, sensors"

SECTION = Section(
    "alignment-design",
    TITLE,
    order=56,
    summary="Which alignment errors are observable (rank, unobservable pairs, degree); coarse-to-fine Kalman, compass loop and the "
    "other methods on the same trials against their bias floors; GNSS-aided alignment in motion; data-sheet sensors and their Allan "
    "deviation; time-to-align charts against grade, rocking and manoeuvre, with Monte Carlo check points; a recorded log.",
)


def _seed(ctx, *key):
    return np.random.SeedSequence(ctx.seed, spawn_key=(56, *key))


def _ci(s, scale=D, digits=3) -> str:
    return f"{s.mean * scale:.{digits}g} ({s.mean_ci[0] * scale:.{digits}g} … {s.mean_ci[1] * scale:.{digits}g})"


def _rms(s, scale=D, digits=3) -> str:
    return f"{s.rms * scale:.{digits}g} ({s.rms_ci[0] * scale:.{digits}g} … {s.rms_ci[1] * scale:.{digits}g})"


def _yes(ok) -> str:
    return "—" if ok is None else ("yes" if ok else "**no**")


def _times(k: float) -> str:
    return "" if k == 1.0 else f"{k:g} × "


def _seconds(t: float) -> str:
    return "> horizon" if math.isinf(t) else f"{t:.0f}"


# ---------------------------------------------------------------- 1. observability
def _component_text(d, labels) -> str:
    parts = []
    for name, v in d.components.items():
        if name == d.state:
            continue
        parts.append(f"{labels[name]} {v:.4g}")
    return ", ".join(parts)


def _observability_lines(study) -> list:
    rows = (
        ("at rest (12 states)", study.stationary),
        ("rocking, rocking states seen through the lever arm (18 states)", study.rocking),
        ("two positions: turned 90° about the vertical at T/2", study.multi_position),
        ("four positions: turned 90° about the vertical at T/4, T/2, 3T/4", study.four_position),
    )
    lat = study.stationary.latitude * D
    lines = [
        "## 1. Which errors can be observed",
        "",
        f"The error model of a navigator aligning on zero-velocity measurements (φ = {lat:.3g}°, `strapdown observability`): attitude, velocity,",
        "gyro and accelerometer biases, and for the rocking base the angles and rates of the shaping filter of each rocking axis,",
        "which the velocity of a block off the rocking centre shows. The rank comes from the orthogonal staircase reduction of the",
        "model, block by block; each unobservable direction is written per unit of its first state (attitude first), in SI units,",
        "its partners ranked by their size in equivalent angles (a gyro bias counts as ε/Ω, an accelerometer bias as ∇/g).",
        "",
        "| model | rank | unobservable directions (what the measurements cannot tell apart) |",
        "|---|---|---|",
    ]
    for label, r in rows:
        labels = dict(zip(r.names, r.labels))
        dirs = "; ".join(f"**{d.text}** ({_component_text(d, labels)} per unit of {labels[d.state]})" for d in r.unobservable) or "none: every state observable"
        lines.append(f"| {label} | {r.rank} of {r.dim} | {dirs} |")
    lines += [
        "",
        "At rest the three classical pairs remain (Bar-Itzhack & Berman 1988): the north tilt cannot be told from the east",
        "accelerometer bias (∇_E = g φ_N), the east tilt from the north one, and the azimuth from the east gyro bias",
        "(ε_E = Ω cos φ · φ_D): hence the floors ∇/g of the tilts and ε_E/(Ω cos φ) of the azimuth, whatever the method. Rocking",
        "adds no information about them, and one rocking mode of its own stays hidden: a rotation about the line from the rocking",
        "centre to the block does not move the block.",
        "",
        *_rank_and_degree(study),
        "",
        f"**Degree of observability** after {study.stationary.duration:.0f} s: the filter's standard deviation over its prior (1: nothing learned).",
        "",
        "| state | at rest | rocking | two positions | four positions |",
        "|---|---|---|---|---|",
    ]
    st, mp, fp, rk = study.stationary, study.multi_position, study.four_position, study.rocking
    for i in range(len(st.names)):
        body = mp.labels[i]
        label = st.labels[i] if st.labels[i] == body else f"{st.labels[i]} / {body}"
        lines.append(f"| {label} | {st.posterior_ratio[i]:.3g} | {rk.posterior_ratio[i]:.3g} | {mp.posterior_ratio[i]:.3g} | {fp.posterior_ratio[i]:.3g} |")
    lines += [
        "",
        "(The multi-position models carry the biases in body axes and start at heading 0, body x north and y east: in the first",
        "position the gyro bias y is the east gyro bias.)",
        "",
    ]
    return lines


def _rank_and_degree(study) -> list:
    """Rank (what can be told apart given time) against degree (what the horizon has taught), for the turned block."""
    out = []
    for label, r in (("two positions", study.multi_position), ("four positions", study.four_position)):
        little = [r.labels[r.names.index(n)] for n in r.little_learned(0.9)]
        rank = f"rank {r.rank} of {r.dim}" + (": every state observable, given time" if r.rank == r.dim else f", {r.dim - r.rank} direction(s) still unobservable")
        learned = (
            f"after {r.duration:.0f} s the filter has still learned little (σ over the prior ≥ 0.9) of the {', '.join(little)}"
            if little
            else f"after {r.duration:.0f} s every state is below 0.9 of its prior"
        )
        out.append(f"Turned about the vertical into {label}: {rank}; {learned}.")
    return [
        "Rank and degree are different questions. The rank says which errors the measurements can tell apart *at all*, given any",
        "time; the degree of observability (below) says how much the filter has learned of each *within the horizon*. "
        + " ".join(out)
        + " The z gyro, whose axis the turns never move, shows its bias only through the azimuth error it builds up, which the",
        "velocity sees after two more integrations: observable, but slowly.",
    ]


# ---------------------------------------------------------------- 2. methods
def _methods_lines(still, rocking) -> list:
    names = {"analytic": "analytic (2)+(16)", "inertial": "inertial frame", "kalman": "Kalman from its prior", "coarse-to-fine": "coarse-to-fine Kalman", "compass": "compass loop"}
    sc = still.scenario
    lines = [
        "## 2. The methods on the same trials",
        "",
        f"φ = {sc.latitude * D:.3g}°, heading {sc.heading * D:.3g}°, {sc.duration:.0f} s at {sc.sample_rate:g} Hz; navigation-grade sensors (random turn-on biases",
        f"σ = {deg_per_h(still.errors.gyro_bias_sigma):.3g} deg/h and {still.errors.accel_bias_sigma:.3g} m/s², angle and velocity random walks). Every method runs on the",
        "same records. The *Kalman from its prior* starts from an attitude drawn from its prior (1° in azimuth); the *coarse-to-fine*",
        "filter starts from the inertial-frame alignment of the first 60 s and its covariance (the coarse stage's response to the",
        "biases, by central differences, and its noise covariance from calibration trials), so its prior knows that the coarse",
        "azimuth error *is* the east gyro bias over Ω cos φ; the *compass loop* (levelling loop ω = 0.1 rad/s, gyrocompass loop",
        "ω = 0.02 rad/s, ζ = 0.7) starts from the same coarse result. Each trial's *floor* is the azimuth error its own biases leave,",
        "−ε_E/(Ω cos φ) + tan φ ∇_E/g at the stable attitude (the derived gains). A residual of zero *mean* proves nothing (a method",
        f"that has not begun to align has one); a method has *reached* the floor when the rms of its residual is at most {_times(still.rows[0].floor_reached.margin)}the",
        "floors' rms, so that the floor makes at least half of its mean-square error: a one-sided test on the per-trial differences",
        "(e − f)² − f² at 95 %, which says *yes*, ***no*** or *not resolved* with the further trials its interval needs at the observed",
        "spread (`strapdown.analysis.core.verdicts`). NEES (12 dof; 18 with the rocking states) and NIS (3 dof) are averaged over",
        "trials at six epochs from the filter's start, against χ² bands that hold all twelve means of a consistent filter at 95 %",
        "together (each at 1 − 0.05/12, Bonferroni).",
        "",
    ]
    for label, c in (("At rest", still), ("Rocking", rocking)):
        if c is None:
            continue
        lines += [
            f"**{label}**, {c.n_trials} trials; the floors' rms {c.floor.rms * D:.3g}°."
            + (" Narrow-band rocking (8 s, σ = 0.5°, 1°, 1°), the block 1 m from the rocking centre; the filters carry rocking states matched to its spectrum." if label == "Rocking" else ""),
            "",
            "| method | azimuth error mean [°] (95 % CI) | rms [°] (95 % CI) | minus the trial's floor: mean [°] (95 % CI) | rms [°] | floor reached | NEES (band) | NIS (band) | NEES, NIS in band |",
            "|---|---|---|---|---|---|---|---|---|",
        ]
        for r in c.rows:
            nees = "—" if r.nees is None else f"{r.nees.min():.3g} … {r.nees.max():.3g} ({r.nees_band[0]:.3g} … {r.nees_band[1]:.3g})"
            nis = "—" if r.nis is None else f"{r.nis.min():.3g} … {r.nis.max():.3g} ({r.nis_band[0]:.3g} … {r.nis_band[1]:.3g})"
            lines.append(
                f"| {names[r.method]} | {_ci(r.error)} | {_rms(r.error)} | {_ci(r.residual)} | {r.residual.rms * D:.3g} | {r.floor_reached.label()} | {nees} | {nis} | {_yes(r.consistent)} |"
            )
        lines.append("")
    lines += _floor_summary(still, rocking)
    lines += [
        "The floor is the east gyro bias over Ω cos φ, which no method at rest removes (§1); the methods differ in the noise they",
        "leave above it. The analytic method is left out under rocking: it",
        "assumes the gyros see the Earth rate only, and the angle the rocking turns the block through over the alignment time",
        "enters its mean rate. The filters' rocking states are matched to the narrow-band spectrum (`Disturbance(\"matched\")`,",
        "`fine.matched_rocking_block`): the rate predicted one epoch ahead as the band-limited rocking allows (its own covariances at",
        "lags 0 and one epoch), the angle integrated by the shaping filter, the rocking's own variances kept. A shaping filter driven",
        "by white noise, the narrow-band spectrum without its cut-off at 4ω0, predicts the rate worse than the rocking allows and",
        "expects larger innovations than it gets: its NIS falls below the band (the alignment page, §3, shows both models).",
        "",
    ]
    return lines


def _names_by_outcome(c, names) -> dict:
    out = {"yes": [], "no": [], "not resolved": []}
    for r in c.rows:
        out[r.floor_reached.outcome].append(names[r.method])
    return out


def _floor_summary(still, rocking) -> list:
    names = {"analytic": "analytic", "inertial": "inertial-frame", "kalman": "Kalman", "coarse-to-fine": "coarse-to-fine", "compass": "compass-loop"}
    parts = []
    for label, c in (("At rest", still), ("Under rocking", rocking)):
        if c is None:
            continue
        by = _names_by_outcome(c, names)
        said = []
        if by["yes"]:
            said.append(f"the {', '.join(by['yes'])} {'method reaches' if len(by['yes']) == 1 else 'methods reach'} the floor")
        if by["no"]:
            said.append(f"the {', '.join(by['no'])} {'method does' if len(by['no']) == 1 else 'methods do'} not")
        if by["not resolved"]:
            said.append(f"{c.n_trials} trials do not decide for the {', '.join(by['not resolved'])} (the table gives the trials each would need)")
        parts.append(f"{label} after {c.scenario.duration:.0f} s, {'; '.join(said)}.")
    return [" ".join(parts), ""]


def _large_heading_lines(study) -> list:
    heads = " | ".join(f"{t:.0f} s" for t in study.times)
    lines = [
        "### From a large heading error",
        "",
        f"Both filters from the same initial heading errors (σ = {np.std(study.initial) * D:.0f}° drawn, the filters' prior 40°), at rest, 1 s epochs:",
        "filterpy's unscented filter on the whole navigation state (heading on the circle) and the closed-loop error-state filter",
        "above. Heading error [°] at",
        "",
        f"| start [°] | unscented: {heads} | error-state: {heads} |",
        "|---|" + "---|" * (2 * study.times.size),
    ]
    for i in range(study.initial.size):
        u = " | ".join(f"{x * D:.3g}" for x in study.unscented[i])
        f = " | ".join(f"{x * D:.3g}" for x in study.error_state[i])
        lines.append(f"| {study.initial[i] * D:.3g} | {u} | {f} |")
    us = " | ".join(f"{x * D:.3g}" for x in study.unscented_sigma)
    fs = " | ".join(f"{x * D:.3g}" for x in study.error_state_sigma)
    lines += [
        f"| *the filter's σ* | {us} | {fs} |",
        "",
        "Both converge. The closed-loop error-state filter does so faster: its loop re-centres the error at every epoch, so its",
        "small-angle model serves it far beyond its nominal range, and its gains stay those of its large prior while the error is",
        "large; the unscented transform of the saturating sin δψ gives the unscented filter smaller gains, and it becomes",
        "confident (its σ) before its error is small. From a small error the two have the same covariance (`tests/test_unscented.py`).",
        "",
    ]
    return lines


# ---------------------------------------------------------------- 3. in motion
def _aided_figure(ctx, rows) -> str:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(8.2, 3.1))
    a = np.array([r.lateral_acceleration for r in rows])
    t = np.array([r.time_to_align for r in rows])
    s = np.array([r.sigma_end for r in rows]) * D
    finite = np.isfinite(t)
    ax[0].plot(a[finite], t[finite], "o-", color="C0")
    ax[0].set_xlabel("peak lateral acceleration of the weave [m/s²]")
    ax[0].set_ylabel("time to σ_ψ ≤ 0.5° [s]")
    ax[0].set_title("GNSS-aided alignment: time to align")
    ax[1].semilogy(a, s, "s-", color="C1")
    ax[1].set_xlabel("peak lateral acceleration [m/s²]")
    ax[1].set_ylabel("σ_ψ after 180 s [°]")
    ax[1].set_title("azimuth after 180 s")
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.8)
    path = "figures/alignment-design-motion.png"
    ctx.savefig(fig, path)
    return path


def _sensor_text(gyro, accel) -> str:
    from ..core.units import DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S, milli_g

    return (
        f"{deg_per_h(gyro.turn_on_bias):.3g} deg/h turn-on gyro bias, {gyro.random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.3g} deg/√h, "
        f"{accel.turn_on_bias:.3g} m/s² ({milli_g(accel.turn_on_bias):.2g} mg) turn-on accelerometer bias, {accel.random_walk / M_S_PER_RT_H_TO_M_S_PER_RT_S:.3g} m/s/√h"
    )


def _aided_lines(ctx, rows, checks, sensors) -> list:
    gyro, accel = sensors
    path = _aided_figure(ctx, rows)
    lines = [
        "## 3. In motion: GNSS-aided alignment",
        "",
        "A car at 10 m/s (45° N, mean heading 30°), level, its heading weaving ±A with a 40 s period; the trajectory is exact over the",
        "WGS-84 ellipsoid (position by DOP853, the sensors' rates from the navigation equations with transport rate and Coriolis,",
        f"increments by Gauss–Legendre quadrature). A tactical-grade IMU ({_sensor_text(gyro, accel)}):",
        "at rest its gyrocompass floor is several degrees, so it cannot align without motion. A closed-loop 15-state filter (attitude,",
        "velocity, NED position, body-axis biases) fuses 1 Hz GNSS velocity (0.05 m/s) and position (1 m), from a 3° azimuth prior; the",
        "error model is linearised along the true trajectory, so filterpy runs its covariances once for all trials.",
        "",
        f"![GNSS-aided alignment against manoeuvre]({path})",
        "",
        "| weave A [°] | peak lateral acceleration [m/s²] | time to σ_ψ ≤ 0.5° [s] | σ_ψ after 180 s [°] |",
        "|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r.amplitude * D:.3g} | {r.lateral_acceleration:.3g} | {_seconds(r.time_to_align)} | {r.sigma_end * D:.3g} |")
    lines += [
        "",
        "A straight drive at constant speed leaves the azimuth as unobservable as at rest; the weave's changing acceleration turns an",
        "azimuth error into a cross-track velocity error of its own sign and separates it from the accelerometer biases.",
        "",
        "**Monte Carlo check points.** The *aided floor* of a trial is the azimuth error its biases leave after the filter (the linear",
        "closed loop's response to them; at rest it is the gyro-bias floor ε_E/(Ω cos φ)); the filter has reached it when the rms",
        f"of the error above it is at most {_times(checks[0][1].floor_reached.margin)}the floors' rms (the one-sided test of §2). NEES (15 dof) and NIS (6 dof) at six fixes.",
        "",
        "| weave A [°] | trials | azimuth rms [°] (95 % CI) | filter σ_ψ [°] | aided floor rms [°] | residual mean [°] (95 % CI) | residual rms [°] | floor reached "
        "| NEES (band) | NIS (band) | in band |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for amp, mc in checks:
        lines.append(
            f"| {amp:.3g} | {mc.n_trials} | {_rms(mc.error)} | {mc.heading_sigma * D:.3g} | {mc.floor.rms * D:.3g} | {_ci(mc.residual)} | {mc.residual.rms * D:.3g} | {mc.floor_reached.label()} "
            f"| {mc.nees.min():.3g} … {mc.nees.max():.3g} ({mc.nees_band[0]:.3g} … {mc.nees_band[1]:.3g}) "
            f"| {mc.nis.min():.3g} … {mc.nis.max():.3g} ({mc.nis_band[0]:.3g} … {mc.nis_band[1]:.3g}) | {_yes(mc.consistent)} |"
        )
    said = []
    for amp, mc in checks:
        v = mc.floor_reached
        drive = "driving straight" if amp == 0 else f"weaving ±{amp:g}°"
        verb = {"yes": "reaches", "no": "does not reach", "not resolved": "may or may not reach"}[v.outcome]
        said.append(f"{drive}, the filter {verb} its aided floor in {mc.check_times[-1]:.0f} s (residual rms {mc.residual.rms * D:.3g}° against {mc.floor.rms * D:.3g}°)")
    lines += [
        "",
        "; ".join(said).capitalize() + ". Where it does not, what remains is noise and the part of the prior the manoeuvre has not",
        "yet exposed, which the filter's own σ_ψ states.",
        "",
    ]
    return lines


# ---------------------------------------------------------------- 4. sensors
def _allan_figure(ctx, study, grades) -> str:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 1, figsize=(6.4, 3.6))
    tau = np.geomspace(0.1, 1e5, 200)
    for k, g in enumerate(grades):
        ax.loglog(tau, deg_per_h(np.sqrt(g.gyro.datasheet_allan_variance(tau))), "-", lw=1.0, color=f"C{k}", label=f"{g.name} (data sheet)")
        if g.name == study.grade:
            ax.loglog(tau, deg_per_h(np.sqrt(g.gyro.allan_variance(tau))), "--", lw=1.0, color=f"C{k}", label=f"{g.name}: the simulated model")
    m = study.measured
    ax.errorbar(m.taus, deg_per_h(m.adev), yerr=[deg_per_h(m.adev - m.low), deg_per_h(m.high - m.adev)], fmt="o", ms=3, color="k", label=f"{study.grade}: simulated, 95 % CI")
    ax.set_xlabel("averaging time τ [s]")
    ax.set_ylabel("Allan deviation [deg/h]")
    ax.set_title("gyro Allan deviation: data sheet and simulated sensor")
    ax.legend(loc="lower left", fontsize=7)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3)
    path = "figures/alignment-design-allan.png"
    ctx.savefig(fig, path)
    return path


def _allan_reading(study) -> str:
    """Over which averaging times the simulated model has the data sheet's Allan deviation (to 5 %)."""
    dep = study.model_departure
    worst = int(np.argmax(np.abs(dep)))
    lo, hi = study.model_within(0.05)
    if np.all(np.abs(dep) <= 0.05):
        return (f"Its Allan deviation stays within 5 % of the data sheet's over every measured τ (at most {abs(dep[worst]):.1%} "
                f"{'below' if dep[worst] < 0 else 'above'}, at τ = {study.measured.taus[worst]:.4g} s).")  # fmt: skip
    return (
        f"Its Allan deviation stays within 5 % of the data sheet's for τ ≤ {hi:.4g} s and lies {abs(dep[worst]):.0%} {'below' if dep[worst] < 0 else 'above'} "
        f"it at τ = {study.measured.taus[worst]:.4g} s: the simulated sensor has its data sheet's Allan deviation up to about {hi:.4g} s, not beyond."
    )


def _sensor_lines(ctx, study, grades) -> list:
    from ..core.units import DEG_PER_RT_H_TO_RAD_PER_RT_S, M_S_PER_RT_H_TO_M_S_PER_RT_S

    path = _allan_figure(ctx, study, grades)
    lines = [
        "## 4. Sensors as a data sheet specifies them",
        "",
        "Each axis carries a turn-on bias, a random walk N, a bias instability B (flicker noise, whose Allan deviation is the flat",
        "floor 0.664 B) and a rate random walk K. Flicker noise has no finite state model: a sum of first-order Gauss–Markov",
        "processes, three per decade of correlation time over 1–3000 s with equal variances (B²/π) ln r, has its spectrum inside",
        "that band. Every term is drawn exactly over each sample interval. The grades are illustrations from the middle of the",
        "usual ranges (Groves 2013, table 4.1), not a vendor's figures.",
        "",
        "| grade | gyro turn-on [deg/h] | ARW [deg/√h] | B [deg/h] | RRW [deg/h/√h] | accel. turn-on [m/s²] | VRW [m/s/√h] | B [m/s²] |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for g in grades:
        lines.append(
            f"| {g.name} | {deg_per_h(g.gyro.turn_on_bias):.3g} | {g.gyro.random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.3g} | {deg_per_h(g.gyro.bias_instability):.3g} "
            f"| {deg_per_h(g.gyro.rate_random_walk) * 60.0:.3g} | {g.accel.turn_on_bias:.3g} | {g.accel.random_walk / M_S_PER_RT_H_TO_M_S_PER_RT_S:.3g} | {g.accel.bias_instability:.3g} |"
        )
    f, s, mf = study.fit, study.spec, study.model_fit
    lines += [
        "",
        f"![Allan deviation]({path})",
        "",
        f"**Check.** {study.duration / 3600:.2g} h of the {study.grade} gyro simulated at 10 Hz, its overlapping Allan deviation measured by `allantools`",
        "with 95 % intervals from Greenhall's equivalent degrees of freedom, against the data sheet's curve N²/τ + (0.664 B)² + K²τ/3",
        f"(IEEE Std 952): that curve lies inside the interval at {study.inside} of {study.expected.size} averaging times (at 95 % each). The simulated",
        f"model's own curve lies inside at {study.model_inside} of {study.expected.size}; it is not the data sheet's: its Gauss–Markov sum stands for",
        f"flicker noise over its band only. {_allan_reading(study)} Read back by the three-term fit over τ ≤ {study.fit_tau:.0f} s:",
        "",
        "| coefficient | data sheet | read from the model's own curve (an endless record) | read from the simulated sensor | ratio to the data sheet |",
        "|---|---|---|---|---|",
        f"| ARW N [deg/√h] | {s.random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.4g} | {mf.random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.4g} "
        f"| {f.random_walk / DEG_PER_RT_H_TO_RAD_PER_RT_S:.4g} | {f.random_walk / s.random_walk:.3f} |",
        f"| bias instability B [deg/h] | {deg_per_h(s.bias_instability):.4g} | {deg_per_h(mf.bias_instability):.4g} | {deg_per_h(f.bias_instability):.4g} "
        f"| {f.bias_instability / s.bias_instability:.3f} |",
        f"| RRW K [deg/h/√h] | {deg_per_h(s.rate_random_walk) * 60:.4g} | "
        + (f"{deg_per_h(mf.rate_random_walk) * 60:.4g}" if mf.rate_random_walk > 0 else "not resolved")
        + " | "
        + (f"{deg_per_h(f.rate_random_walk) * 60:.4g} | {f.rate_random_walk / s.rate_random_walk:.3f} |" if f.rate_random_walk > 0 else "not resolved | — |"),
        "",
        f"N reads back exactly. B rests on the few long clusters of the floor (about {float(np.interp(study.fit_tau, study.measured.taus, study.measured.edf)):.0f} degrees of freedom",
        f"at τ = {study.fit_tau:.0f} s), so one record of {study.duration / 3600:.2g} h reads it {abs(f.bias_instability / s.bias_instability - 1.0):.0%} off here,",
        f"while the model's own curve gives it back to {abs(mf.bias_instability / s.bias_instability - 1.0):.0%}.",
        "The rate random walk of this grade rises above the flicker floor only beyond a day: a record of hours cannot read it.",
        "",
    ]
    return lines


# ---------------------------------------------------------------- 5. design charts
def _grade_figure(ctx, curves, rocking) -> str:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(8.6, 3.3))
    for k, c in enumerate(curves):
        ax[0].loglog(c.times, c.sigma * D, "-", color=f"C{k}", label=c.grade)
        ax[0].axhline(c.floor * D, color=f"C{k}", lw=0.8, ls=":")
        if math.isfinite(c.time_to_align):
            ax[0].plot([c.time_to_align], [1.1 * c.floor * D], "o", color=f"C{k}", ms=4)
    ax[0].set_xlabel("alignment time [s]")
    ax[0].set_ylabel("azimuth σ [°]")
    ax[0].set_title("Kalman alignment at rest, per grade")
    ax[0].legend(loc="upper right", fontsize=7)
    for k, kind in enumerate(("shaping", "white")):
        rows = [r for r in rocking if r.kind == kind]
        ax[1].plot([r.sigma * D for r in rows], [r.time_to_align for r in rows], "o-", color=f"C{k + 3}", label="rocking states" if kind == "shaping" else "rocking as noise")
    ax[1].set_xlabel("tilt rocking σ [°] (narrow-band, 8 s)")
    ax[1].set_ylabel("time to 1.1 × floor [s]")
    ax[1].set_title("navigation grade under rocking")
    ax[1].legend(loc="upper left", fontsize=7)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.85)
    path = "figures/alignment-design-time.png"
    ctx.savefig(fig, path)
    return path


def _design_lines(ctx, curves, rocking, points) -> list:
    path = _grade_figure(ctx, curves, rocking)
    lines = [
        "## 5. Time to align",
        "",
        "The fine filter's own covariance (filterpy) at 45° N, heading 30°, 1 s epochs, from a prior azimuth of three floors (at",
        "least 1°): its azimuth σ against time, and the *time to align*, after which σ stays within 10 % of the bias floor σ of the",
        "grade (dotted; the filter's bias prior takes the turn-on bias and the flicker floor together). Under rocking the block is",
        "1 m from the rocking centre; the filter either carries the rocking's shaping states or adds the lever-arm velocity to its",
        "measurement noise.",
        "",
        f"![Time to align]({path})",
        "",
        "| grade | floor σ [°] | time to align [s] | σ at the horizon [°] |",
        "|---|---|---|---|",
    ]
    for c in curves:
        lines.append(f"| {c.grade} | {c.floor * D:.3g} | {_seconds(c.time_to_align)} | {c.sigma[-1] * D:.3g} |")
    lines += [
        "",
        "| tilt rocking σ [°] | filter | time to align [s] | σ at the horizon [°] |",
        "|---|---|---|---|",
    ]
    for r in rocking:
        lines.append(f"| {r.sigma * D:.3g} | {'rocking states' if r.kind == 'shaping' else 'rocking as noise'} | {_seconds(r.time_to_align)} | {r.sigma_end * D:.3g} |")
    lines += [
        "",
        "The better grades are limited by their angle random walk long after their floor is small: N/(Ω cos φ √T) falls to 10 % of",
        "the floor slowly. Rocking the filter models costs little; rocking it treats as noise costs more the larger it is.",
        "",
        "**Monte Carlo check points** on data-sheet sensors (flicker and rate random walk included, which the filter does not model):",
        f"the filter's predicted σ against the rms of the azimuth error. The prediction holds when the rms is within ±{points[0].agreement.margin / points[0].predicted:.0%} of it",
        "(TOST on the mean square at 95 %); a Monte Carlo too small to tell says how many more trials it needs.",
        "",
        "| point | time [s] | predicted σ [°] | Monte Carlo rms [°] (95 % CI) | trials | prediction holds |",
        "|---|---|---|---|---|---|",
    ]
    for p in points:
        lines.append(f"| {p.label} | {p.time:.0f} | {p.predicted * D:.3g} | {_rms(p.error)} | {p.error.n} | {p.agreement.label()} |")
    lines.append("")
    return lines


# ---------------------------------------------------------------- 6. recorded log
def _log_lines(results, log) -> list:
    lines = [
        "## 6. A recorded log",
        "",
        "`strapdown align --log FILE` aligns a recorded IMU log once (format: `docs/recorded-logs.md`). The example log",
        f"`docs/examples/rocking-imu-log.npz` ({log.n_samples} samples at {1.0 / log.dt:.0f} Hz) is four minutes of a simulated navigation-grade",
        "IMU on a rocking base, its truth in its metadata:",
        "",
        "| method | heading [°] | σ (filter) [°] | error against the log's truth [°] |",
        "|---|---|---|---|",
    ]
    for r in results:
        sig = "—" if r.heading_sigma is None else f"{r.heading_sigma * D:.3g}"
        err = "—" if r.heading_error is None else f"{r.heading_error * D:.3g}"
        lines.append(f"| {r.method} | {r.heading * D:.5g} | {sig} | {err} |")
    lines += [
        "",
        "The analytic method is off by tens of degrees here: the rocking reaches the gyros, and the angle the block turned through",
        "over the log enters its mean rate (§2).",
        "",
    ]
    return lines


def build(ctx) -> None:
    """Write ``alignment-design.md`` and its figures.

    Parameters
    ----------
    ctx : Context
        Report context (output, sizes, seed).
    """
    from ..alignment import design_studies as ds
    from ..alignment.fine import FilterTuning
    from ..alignment.sensor_models import GRADES
    from ..logs.alignment import align_log
    from ..logs.examples import example_log

    q = ctx.quick
    lines = [
        f"# {TITLE}",
        "",
        "What an alignment designer asks before choosing a method: which errors the measurements can observe at all, how the",
        "methods compare on the same trials, how long a grade of IMU takes to align at rest, under rocking and in motion with GNSS,",
        "and whether the simulated sensors are those of their data sheets. Angles in degrees here, radians in the library",
        "(`strapdown.analysis.alignment`: `observability`, `coarse_to_fine`, `compass_loop`, `comparison`, `aided`, `trajectory`,",
        "`sensor_models`, `recorded`, `design_studies`).",
        "",
    ]
    lines += _observability_lines(ds.observability_study())
    still = ds.methods_study(n_trials=24 if q else 96, rng=_seed(ctx, 0))
    rocking = ds.methods_study(n_trials=16 if q else 48, rng=_seed(ctx, 1), rocking=True)
    lines += _methods_lines(still, rocking)
    lines += _large_heading_lines(ds.large_heading_study(n_trials=3 if q else 6, rng=_seed(ctx, 6)))
    amps = rad(np.array([0.0, 2.0, 5.0, 10.0, 20.0, 30.0] if not q else [0.0, 5.0, 20.0]))
    checks = ds.aided_checks(rad(np.array([0.0, 20.0])), n_trials=16 if q else 64, rng=_seed(ctx, 2))
    lines += _aided_lines(ctx, ds.manoeuvre_study(amps), list(zip([0.0, 20.0], checks)), ds.aided_sensors())
    lines += _sensor_lines(ctx, ds.allan_study(GRADES[3], n_samples=2**15 if q else 2**17, rng=_seed(ctx, 3)), GRADES)
    curves = ds.grade_study(GRADES[:3], duration=4000.0)
    rocking_rows = ds.rocking_design_study(rad(np.array([0.5, 2.0] if q else [0.5, 1.0, 2.0, 4.0])))
    nav = GRADES[1]
    t_nav = next(c.time_to_align for c in curves if c.grade == "navigation")
    cases = [("navigation, at rest, at its time to align", nav, 0.0, t_nav), ("navigation, rocking σ = 2° (rocking states), 600 s", nav, rad(2.0), 600.0)]
    if not q:
        cases.append(("intermediate, at rest, 300 s", GRADES[2], 0.0, 300.0))
    points = ds.design_check_points(cases, n_trials=16 if q else 48, rng=_seed(ctx, 4))
    lines += _design_lines(ctx, curves, rocking_rows, points)
    log = example_log()
    nav_tuning = FilterTuning(
        epoch=0.1, gyro_bias=nav.gyro.turn_on_bias, accel_bias=nav.accel.turn_on_bias, gyro_noise=nav.gyro.random_walk, accel_noise=nav.accel.random_walk, measurement_noise=0.02
    )
    results = [align_log(log, log.metadata["latitude"], method=m, tuning=nav_tuning, rng=_seed(ctx, 5)) for m in ("analytic", "inertial", "kalman", "compass")]
    lines += _log_lines(results, log)
    lines.append(f"Mode: {'quick' if ctx.quick else 'full'}; root seed {ctx.seed}.")
    ctx.write_text("alignment-design.md", "\n".join(lines))
