"""Report section ``alignment.md``: self-alignment of the whole system on a rocking base.

The rocking in the gyros and the accelerometers, sensor errors, three
methods, the admissible rocking.  :func:`alignment_lines` returns the Markdown
(and writes the figures); :func:`alignment_errata` the interpretations it
finds.  Formatting only:
every number and curve comes from :mod:`strapdown.analysis.gyrocompass` (the
studies of :mod:`strapdown.analysis.alignment.studies`, the design
of :mod:`strapdown.analysis.alignment.design`).
"""

from __future__ import annotations

import math

import numpy as np

from ..core.units import DEG_PER_RAD as D
from ..core.units import deg_per_h, rad
from ..core.verdicts import all_of
from . import Erratum, Section
from .rendering import at_round_off, fixed_layout

__all__ = ["SECTION", "build", "errata", "alignment_lines", "alignment_errata", "TITLE"]

#: Heading of the page.
TITLE = "Self-alignment on a rocking base: the whole system"

SECTION = Section(
    "alignment",
    TITLE,
    order=55,
    summary="Rocking in the gyros and accelerometers, sensor errors, analytic, inertial-frame and Kalman alignment checked against "
    "their theory by Monte Carlo; NEES/NIS; the admissible rocking for an azimuth budget, per method.",
)

METHOD_NAMES = {"analytic": "analytic (2)+(16)", "inertial": "inertial frame", "kalman": "Kalman"}


def _seed(ctx, *key):
    return np.random.SeedSequence(ctx.seed, spawn_key=(51, *key))


def _ci(r, digits=4, scale=D) -> str:
    return f"{r.mean * scale:.{digits}g} ({r.mean_ci[0] * scale:.{digits}g} … {r.mean_ci[1] * scale:.{digits}g})"


def _rms(r, digits=4, scale=D) -> str:
    return f"{r.rms * scale:.{digits}g} ({r.rms_ci[0] * scale:.{digits}g} … {r.rms_ci[1] * scale:.{digits}g})"


# ---------------------------------------------------------------- 1. model
def _model_lines() -> list:
    return [
        "## 1. The model",
        "",
        "- **Attitude.** $C_b^n = R_z(\\psi) R_x(-\\beta) R_y(\\gamma)$ in NED: heading ψ, then β about the first gyro's axis x, then γ",
        "  of that axis out of the horizontal. At rest with ψ = 0 the body axes are x north, y east, z down, and the two horizontal gyros",
        "  read $\\Omega(A, B)$ with exactly the A, B of Hrechka & Koroliov (after (2)): their σ is the tilt correction of this attitude.",
        "- **Rocking** in three axes (yaw ψ_r, β_r = ξ, γ_r = η), as smooth functions of time: a sinusoid per axis with independent",
        "  phases, a sum of sines, narrow-band Gaussian rocking with the spectrum of the shaping filter of the paper's narrow-band model",
        "  (cut off at 4ω0, so that the angular acceleration is finite), or band-limited white rocking. A Gaussian model is its",
        "  continuous spectral density. Its realisations are spectral syntheses on an FFT grid with trapezoidal weights, zero frequency",
        "  included, so that their covariance is the continuous autocovariance folded with the grid's period (many correlation times",
        "  beyond the record): the variance of a mean is right at every averaging time. The theory integrates the density itself, not",
        "  the grid; both are checked against the closed forms of the second-order process and of white samples",
        "  (`tests/test_base_motion.py`).",
        "- **Sensors.** Gyros measure $\\omega_{ib}^b = \\omega_{nb}^b + C_n^b\\omega_{ie}^n$, accelerometers the specific force of a block at the lever",
        "  arm r from the rocking centre, $\\dot\\omega\\times r + \\omega\\times(\\omega\\times r) + 2(C_n^b\\omega_{ie}^n)\\times(\\omega\\times r) - C_n^b g^n$; both deliver",
        "  increments (two-point Gauss quadrature of the exact rates), with scale factors, biases (fixed and random turn-on), white noise",
        "  (ARW, VRW) and quantisation of the accumulated output. Integrating the increments back reproduces the true attitude to 1e-9 rad",
        "  and the velocity to 1e-6 m/s over 20 s of rocking (`tests/test_alignment.py`).",
        "- **Methods.** *Analytic*: formula (2) with the averaged gyro outputs and the tilt estimates (16) (`paper`; exact at ψ = 0",
        "  only), or the mean rate levelled by the estimated tilts (`levelled`, any heading); it estimates the stable attitude.",
        "  *Inertial frame*: the body attitude integrated in its own initial inertial frame, the specific force accumulated there and",
        "  integrated once more, fitted to the gravity turning with the Earth (Wahba's problem, batched SVD) after removing the constant",
        "  and linear parts the lever-arm motion can add. *Kalman*: a closed-loop error-state filter (tilt and azimuth errors, velocity",
        "  error, gyro and accelerometer biases, and optionally the rocking angles and rates of an assumed shaping filter, which the",
        "  velocity measurement sees through the lever arm), gains computed once by filterpy and applied to all trials. The inertial",
        "  and Kalman methods estimate the attitude at the end of the alignment.",
        "",
    ]


# ---------------------------------------------------------------- 2. theory checks
def _floor_lines(rows) -> list:
    from ..alignment.studies import THEORY_MARGIN

    lines = [
        "## 2. Theory checked by Monte Carlo",
        "",
        f"### Gyro-bias floor, east gyro bias {deg_per_h(rows[0].bias):.3g} deg/h, 60 s at rest",
        "",
        "Theory (first order, from the derived gains): $-b_E/(\\Omega\\cos\\varphi)$ for the analytic and inertial methods; the Kalman filter,",
        "which after 60 s still leans on its 1° prior at high latitude, against its own linear prediction (the noise-free error",
        "propagated through its closed loop), which tends to the floor as it converges. 'bias only': the analytic method with no other",
        "error, where every trial is the same (difference relative to the floor; the neglected term is $(b/\\Omega\\cos\\varphi)^2$); then",
        "with 0.0005 deg/√h of angle random walk, the Monte Carlo mean with its 95 % interval. A theory agrees when the true mean is",
        f"within ±{THEORY_MARGIN:.0%} of it (TOST at 95 %, `strapdown.analysis.core.verdicts`); where the trials cannot tell, the cell says how many more it needs.",
        "",
        "| φ [°] | floor [°] | bias only: analytic [°] (rel. diff.) | analytic [°] | inertial [°] | Kalman [°] | Kalman linear theory [°] | every theory agrees |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        res = r.results
        targets = {m: (res[m].kalman_theory.gyro_bias if m == "kalman" else r.floor) for m in res}
        inside = all_of([res[m].result.mean_agrees(targets[m], THEORY_MARGIN * abs(targets[m]), what="its theory") for m in res], criterion="every method's mean agrees with its theory")
        kal = res.get("kalman")
        lin = f"{kal.kalman_theory.gyro_bias * D:.5g}" if kal else "—"
        lines.append(
            f"| {r.latitude * D:.3g} | {r.floor * D:.5g} | {r.deterministic * D:.6g} ({(r.deterministic - r.floor) / r.floor:.1e}) "
            f"| {_ci(res['analytic'].result)} | {_ci(res['inertial'].result)} | {_ci(kal.result) if kal else '—'} | {lin} | {inside.label()} |"
        )
    return lines + [""]


def _accel_lines(rows, latitude) -> list:
    from ..alignment.studies import THEORY_MARGIN

    lines = [
        f"### Accelerometer biases, φ = {latitude * D:.3g}°, 30 s",
        "",
        f"A theory agrees when the true mean is within ±{THEORY_MARGIN:.0%} of it (a theory of zero: within ±{THEORY_MARGIN:.0%} of the largest theory of the table).",
        "",
        f"| bias | azimuth theory tan φ·a_E/g [°] | azimuth MC mean [°] (95 % CI) | agrees (±{THEORY_MARGIN:.0%}) | tilt theory a/g [°] | tilt MC rms (β̂, γ̂) [°] |",
        "|---|---|---|---|---|---|",
    ]
    largest = max(abs(r.azimuth_theory) for r in rows)
    for r in rows:
        res = r.mc.result
        margin = THEORY_MARGIN * (abs(r.azimuth_theory) or largest)
        lines.append(
            f"| {r.axis} {r.bias:g} m/s² | {r.azimuth_theory * D:.5g} | {_ci(res)} | {res.mean_agrees(r.azimuth_theory, margin, what='the theory').label()} "
            f"| {r.tilt_theory * D:.5g} | {r.mc.tilt_rms[0] * D:.4g}, {r.mc.tilt_rms[1] * D:.4g} |"
        )
    return lines + [""]


def _noise_lines(rows) -> list:
    from ..alignment.studies import THEORY_MARGIN

    methods = list(rows[0].results)
    kal = "kalman" in methods
    lines = [
        "### White noise against alignment time (ARW 0.003 deg/√h, VRW 0.03 m/s/√h, φ = 45°)",
        "",
        "The analytic theory is $\\sqrt{|G_\\omega|^2 N_g^2 + |G_tT_f|^2 N_a^2}/\\sqrt{T}$: the error falls as $1/\\sqrt{T}$.",
    ]
    if kal:
        lines += [
            "The Kalman filter's error is larger at short times, and its own posterior σ (last column) says so: the zero-velocity filter",
            "sees an azimuth error only through the tilt that the misresolved horizontal Earth rate, $\\Omega\\cos\\varphi\\,\\delta\\psi$, builds up,",
            "and that tilt only through the velocity it drives, integrated once more. Its information on the azimuth grows as $T^3$ (the",
            "error as $T^{-3/2}$ against the velocity noise) from its 1° prior, where the analytic method reads the Earth rate from the",
            "averaged gyros at once ($T^{-1/2}$ against the angle random walk). At 30 s the velocity record does not yet resolve the",
            "azimuth much better than the prior; by 240 s the two methods meet.",
        ]
    lines += [
        "",
        "| T [s] | analytic theory rms [°] | "
        + " | ".join(f"{METHOD_NAMES[m]} MC rms [°] (95 % CI)" for m in methods)
        + f" | theory agrees (analytic, ±{THEORY_MARGIN:.0%}) |"
        + (" Kalman filter's own σ [°] |" if kal else ""),
        "|---|---|" + "---|" * len(methods) + "---|" + ("---|" if kal else ""),
    ]
    for r in rows:
        a = r.results["analytic"].result
        row = f"| {r.duration:g} | {r.theory * D:.4g} | " + " | ".join(_rms(r.results[m].result) for m in methods) + f" | {a.rms_agrees(r.theory, THEORY_MARGIN, what='the theory').label()} |"
        if kal:
            row += f" {r.results['kalman'].kalman.heading_sigma * D:.4g} |"
        lines.append(row)
    return lines + ["", "![noise against alignment time](figures/azimuth-alignment-noise.png)", ""]


def _noise_figure(ctx, rows) -> None:
    import matplotlib.pyplot as plt

    T = np.array([r.duration for r in rows])
    fig, ax = plt.subplots(figsize=(5.6, 3.6))
    ax.loglog(T, [r.theory * D for r in rows], "k-", label="analytic theory ∝ 1/√T")
    for m, mk in zip(rows[0].results, ("o", "s", "^")):
        y = np.array([r.results[m].result.rms for r in rows]) * D
        lo = np.array([r.results[m].result.rms_ci[0] for r in rows]) * D
        hi = np.array([r.results[m].result.rms_ci[1] for r in rows]) * D
        ax.errorbar(T, y, yerr=[y - lo, hi - y], fmt=mk, ms=4, capsize=2, label=f"{METHOD_NAMES[m]} (MC)")
    ax.set_xlabel("alignment time T [s]")
    ax.set_ylabel("rms azimuth error [deg]")
    ax.legend(fontsize=7)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.15)
    ctx.savefig(fig, "figures/azimuth-alignment-noise.png")


def _rocking_lines(rows) -> list:
    from ..alignment.studies import THEORY_MARGIN

    lines = [
        "### Rocking: the paper's tilt channel as the special case, and the rocking in the gyros",
        "",
        "Analytic method with formula (2) and the estimates (16), φ = 70°, β0 = 2°, γ0 = −1°, 30 s at 10 Hz, ideal sensors. Two",
        "readings of the paper. Its error (12) compares α of (2) with α* of (11), both built from the same gyro signals f1, f2, so",
        "that it is $\\sigma(\\beta_0+\\xi,\\gamma_0+\\eta) - \\sigma(\\beta_0,\\gamma_0)$: the rocking enters through the tilts only, as if the gyros saw",
        "the stable attitude (rows 'gyros see it: no', the tilt channel of the rest of the package); its text says that each laser",
        "gyro senses the rocking as its projection on its sensitive axis (rows 'yes'). Which one the paper",
        "means the text cannot decide (errata, 'ambiguous'). With the gyros at the stable attitude the Monte Carlo matches the",
        "paper's theory (to second order, parts 1 and 3 of the azimuth report) with the variance of the mean of the rocking. With",
        "the rocking in the gyros the mean tilt the gyros see cancels, to first order, the tilt correction of (16); what remains is",
        "the body rate the gyros average, the angle the rocking gains over the window divided by T: orders of magnitude larger, so",
        "the same rockings are run a thousand times smaller there (at 1° the error is about 100°, far outside any linear range).",
        "The size of a narrow-band rocking is its standard deviation σ per rocked axis (its amplitude in the library's convention",
        "is σ√2), of a sine its amplitude.",
        "",
        f"| rocking | gyros see it | size per axis [°] | MC rms [°] (95 % CI) | first-order theory [°] | second-order tilt-channel theory [°] | theory agrees (±{THEORY_MARGIN:.0%}) "
        "| first-order rms per degree of rocking [°/°] |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        res = r.mc.result
        th = r.second_order if not r.rocking_in_gyros else r.first_order
        sec = f"{r.second_order * D:.4g}" if not math.isnan(r.second_order) else "—"
        size = ("σ = " if r.mc.scenario.motion.name != "sine" else "amplitude ") + f"{r.amplitude * D:g}"
        lines.append(
            f"| {r.label} | {'yes' if r.rocking_in_gyros else 'no'} | {size} | {_rms(res)} | {r.first_order * D:.4g} | {sec} "
            f"| {res.rms_agrees(th, THEORY_MARGIN, what='the theory').label()} | {r.per_unit:.4g} |"
        )
    return lines + [""]


def _rocking_rows(ctx):
    """The rocking-channel study, computed once per report (the page and its erratum quote it)."""
    from ..alignment import studies as st

    return ctx.shared("alignment/rocking-channel", lambda: st.rocking_channel_study(n_trials=100 if ctx.quick else 800, rng=_seed(ctx, 3)))


# ---------------------------------------------------------------- 3. Kalman
def _nis_reading(cases) -> str:
    """Where each rocking filter's NIS lies against its 95 % band, from the numbers."""
    out = []
    for label, mc in cases[1:]:
        k = mc.kalman
        lo, hi = k.nis_band
        inside, below = int(np.sum((k.nis >= lo) & (k.nis <= hi))), int(np.sum(k.nis < lo))
        mean = "inside" if lo <= k.nis_all <= hi else ("below" if k.nis_all < lo else "above")
        kind = label.split(", ")[-1]
        out.append(
            f"with {kind} the NIS lies inside its 95 % band at {inside} of {k.nis.size} epochs ({below} below it), and its mean over the run, "
            f"{k.nis_all:.3g}, {mean} the band {lo:.3g} … {hi:.3g}"
        )
    return "On the rocking base, " + "; ".join(out) + ". A filter assuming twice the true period, or no rocking at all, is inconsistent (the next table)."


def _kalman_lines(cases, mismatch) -> list:
    lines = [
        "## 3. Kalman fine alignment: consistency and a wrong rocking model",
        "",
        "NEES (the whole state, against the truth of the simulation) and NIS (innovations, $y^TS^{-1}y$, χ² bounds from `scipy.stats.chi2`;",
        "filterpy has no NIS function) averaged over trials at eight epochs, with their two-sided 95 % bands. The random biases are drawn",
        "from the filter's prior, the initial attitude error too. A filter is *consistent* when all sixteen means lie inside bands",
        "taken at 1 − 0.05/16 each, a test at 95 % for the family (Bonferroni). The rocking states either form a shaping filter driven",
        "by white noise (the narrow-band spectrum without its cut-off at 4ω0, rougher than the simulated rocking) or are matched to",
        "the rocking's own spectrum (the rate predicted one epoch ahead from its own covariances, `fine.matched_rocking_block`); both",
        "rocking rows run on the same trials.",
        "",
        "| case | dof | NEES at the epochs (band) | NIS at the epochs (band) | rms azimuth at the end [°] (95 % CI) | filter σ [°] | consistent |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, mc in cases:
        k = mc.kalman
        lines.append(
            f"| {label} | {k.dim} | {', '.join(f'{x:.3g}' for x in k.nees)} ({k.nees_band[0]:.3g}–{k.nees_band[1]:.3g}) "
            f"| {', '.join(f'{x:.3g}' for x in k.nis)} ({k.nis_band[0]:.3g}–{k.nis_band[1]:.3g}) | {_rms(mc.result)} | {k.heading_sigma * D:.4g} | {mc.consistency().label()} |"
        )
    lines += ["", _nis_reading(cases)]
    times = cases[0][1].kalman.times
    lines += [
        "",
        f"Epochs at t = {', '.join(f'{t:.3g}' for t in times)} s.",
        "",
        "![NEES and NIS](figures/azimuth-alignment-kalman.png)",
        "",
        "### Sensitivity to the rocking model the filter assumes",
        "",
        "The same trials (common random numbers) through filters that assume the true narrow-band rocking, a period off by a factor,",
        "white rocking (the lever-arm velocity as measurement noise) or no rocking.",
        "",
        "| filter assumes | rms azimuth [°] (95 % CI) | NEES at the end (band) | mean NIS over the run (band) | filter σ [°] |",
        "|---|---|---|---|---|",
    ]
    for r in mismatch:
        k = r.mc.kalman
        lines.append(
            f"| {r.label} | {_rms(r.mc.result)} | {k.nees[-1]:.3g} ({k.nees_band[0]:.3g}–{k.nees_band[1]:.3g}) "
            f"| {k.nis_all:.3g} ({k.nis_band[0]:.3g}–{k.nis_band[1]:.3g}) | {k.heading_sigma * D:.4g} |"
        )
    return lines + [""]


def _kalman_figure(ctx, cases) -> None:
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
    for (label, mc), c in zip(cases, ("C0", "C1", "C2")):
        k = mc.kalman
        a1.semilogx(k.times, k.nees / k.dim, "-o", color=c, ms=3, label=label)
        a1.axhspan(k.nees_band[0] / k.dim, k.nees_band[1] / k.dim, color=c, alpha=0.15)
        a2.semilogx(k.times, k.nis / k.meas_dim, "-o", color=c, ms=3, label=label)
        a2.axhspan(k.nis_band[0] / k.meas_dim, k.nis_band[1] / k.meas_dim, color=c, alpha=0.15)
    a1.set_ylabel("mean NEES / dof")
    a2.set_ylabel("mean NIS / dof")
    for a in (a1, a2):
        a.set_xlabel("time [s]")
    handles, labels = a1.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=7, frameon=False)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.85, top=0.15, wgap=0.75)
    ctx.savefig(fig, "figures/azimuth-alignment-kalman.png")


# ---------------------------------------------------------------- 4. design
def _design_lines(designs, checks, scenario, budget, errors, rtol) -> list:
    from ..alignment.studies import THEORY_MARGIN

    lines = [
        "## 4. The designer's answer: admissible rocking against frequency",
        "",
        f"Budget {budget * D:g}° on the azimuth error, latitude {scenario.latitude * D:g}°, heading {scenario.heading * D:g}°, T = {scenario.duration:g} s at "
        f"{scenario.sample_rate:g} Hz, the block at r = ({', '.join(f'{x:g}' for x in scenario.lever_arm)}) m from the rocking centre, navigation-grade",
        f"sensors (turn-on gyro bias {deg_per_h(errors.gyro_bias_sigma):g} deg/h, ARW {errors.gyro_noise * 60 * D:g} deg/√h, accelerometer bias {errors.accel_bias_sigma:g} m/s²,",
        f"VRW {errors.accel_noise * 60:g} m/s/√h). Rocking of amplitude a on β and γ. Solid: by the rms; dashed: 95 % of the trials within",
        "the budget. The analytic method's curve is its first-order theory (for the sine the envelope over phase: the worst alignment",
        "time of at least T); the inertial and Kalman curves are Monte Carlo root searches with common random numbers, with the",
        "interval of the rms amplitude as a band and independent Monte Carlo check points (their rms should equal the budget).",
        "The tilt-channel curve is the paper's setting (gyros at the stable attitude).",
        "",
        "![admissible rocking](figures/azimuth-alignment-design.png)",
        "",
        "| method | rocking | floor without rocking [°] | " + " | ".join(f"{f:.3g} Hz" for f in designs[0].frequency) + " |",
        "|---|---|---|" + "---|" * designs[0].frequency.size,
    ]
    for d in designs:
        cells = " | ".join(_amp(a) for a in d.amplitude)
        lines.append(f"| {METHOD_NAMES.get(d.method, d.method)} | {d.rocking} | {d.floor * D:.3g} | {cells} |")
    lines += [
        "",
        "Admissible amplitude [°] by the rms criterion ('≥ 20' where the cap was reached, 0 where the sensors alone exceed the budget).",
        "",
        "Independent Monte Carlo at the admissible amplitudes. The admissible amplitude is the root of the search's own trials (drawn once",
        f"per frequency and evaluated at every amplitude, the root bracketed in log a to ±{50 * rtol:g} % by secant steps along the power law of",
        "the error's rocking share, with bisection as the safeguard); the check draws trials",
        "of its own, so its rms scatters about the budget by the sampling error of both runs: the search's, which the interval of the",
        "amplitude maps, and the check's, which its interval shows. Where the error grows slowly with the amplitude (the Kalman filter at",
        "low frequency) the amplitude is loosely determined — its interval from the root search is wide.",
        "",
        f"| check: method, rocking | f [Hz] | amplitude [°] (95 % interval of the search) | MC rms [°] (95 % CI) | rms meets the budget (±{THEORY_MARGIN:.0%}) |",
        "|---|---|---|---|---|",
    ]
    for d, pts in checks:
        for p in pts:
            i = int(np.argmin(np.abs(d.frequency - p.frequency)))
            lo, hi = d.amplitude_ci[i] * D
            lines.append(
                f"| {METHOD_NAMES[d.method]}, {d.rocking} | {p.frequency:.3g} | {p.amplitude * D:.4g} ({lo:.3g} … {hi:.3g}) | {_rms(p.result)} "
                f"| {p.result.rms_agrees(budget, THEORY_MARGIN, what='the budget').label()} |"
            )
    return lines + [""]


def _amp(a) -> str:
    x = a * D
    if x >= 19.999:
        return "≥ 20"
    return f"{x:.3g}"


def _design_figure(ctx, designs, checks, tilt) -> None:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), sharey=True)
    colors = {"analytic": "C3", "inertial": "C0", "kalman": "C2"}
    for ax, rock in zip(axes, ("sine", "narrowband")):
        for d in designs:
            if d.rocking != rock:
                continue
            c = colors[d.method]
            ax.loglog(d.frequency, np.where(d.amplitude > 0, d.amplitude, np.nan) * D, "-", color=c, label=f"{METHOD_NAMES[d.method]}, rms")
            ax.loglog(d.frequency, np.where(d.amplitude_percentile > 0, d.amplitude_percentile, np.nan) * D, "--", color=c, label=f"{METHOD_NAMES[d.method]}, 95 %")
            if d.n_trials:
                ax.fill_between(d.frequency, d.amplitude_ci[:, 0] * D, d.amplitude_ci[:, 1] * D, color=c, alpha=0.15, lw=0)
        t = tilt[rock]
        ax.loglog(t.frequency, t.amplitude * D, ":", color="0.4", label="tilt channel only (paper), rms")
        for d, pts in checks:
            if d.rocking == rock:
                ax.plot([p.frequency for p in pts], [p.amplitude * D for p in pts], "o", color=colors[d.method], ms=5, mfc="none")
        ax.set_title(f"{rock} rocking" + (", envelope over phase (analytic)" if rock == "sine" else ", ζ = 0.1"), fontsize=9)
        ax.set_xlabel("rocking frequency [Hz]")
        ticks = [f for f in (0.05, 0.1, 0.2, 0.4) if t.frequency.min() * 0.99 <= f <= t.frequency.max() * 1.01]
        ax.set_xticks(ticks, [f"{f:g}" for f in ticks])
        ax.xaxis.set_minor_formatter(plt.NullFormatter())
    axes[0].set_ylabel("admissible amplitude [deg]")
    axes[0].set_ylim(1e-4, 40.0)
    axes[1].legend(fontsize=6, loc="center right")
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.2)
    ctx.savefig(fig, "figures/azimuth-alignment-design.png")


# ---------------------------------------------------------------- 5. finite samples
def _finite_lines(table, coverage, required) -> list:
    lines = [
        "## 5. Finite-sample statistics of (16)",
        "",
        "The mean of n correlated tilt samples is worth $n_{eff} = 1/v$ independent ones, $v = \\mathrm{Var}\\,\\bar x/\\sigma^2$; the variance estimate of (16)",
        "is biased, $E\\hat\\sigma^2_n = \\sigma^2(1 - v)$; the interval of independent samples is too narrow by $\\sqrt{nv/(1-v)}$; an interval that holds is",
        "$\\bar x \\pm t_\\nu \\hat\\sigma\\sqrt{v/(1-v)}$ with Bartlett's degrees of freedom ν of $\\hat\\sigma^2$. Samples at 10 Hz, σ = 1°.",
        "",
        "| rocking | T [s] | n | n_eff | bias of σ̂² | naive interval too narrow by | ν of σ̂² |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in table:
        s = r.stats
        neff = "∞ (whole periods)" if not math.isfinite(s.effective_sample_size) else f"{s.effective_sample_size:.4g}"
        lines.append(f"| {r.label} | {r.duration:g} | {s.n_samples} | {neff} | {s.variance_bias + 0.0:+.3g} | ×{s.naive_interval_ratio:.3g} | {s.variance_dof:.3g} |")
    lines += [
        "",
        f"Coverage of 95 % intervals of β0 by Monte Carlo ({coverage[0].n_trials} trials each, {coverage[0].label}; binomial SE ≈ 0.5 %):",
        "",
        "| T [s] | model (t_ν, bias corrected) | independent samples | 10 batch means |",
        "|---|---|---|---|",
    ]
    for r in coverage:
        c = r.coverage
        lines.append(f"| {r.duration:g} | {c['model']:.3f} | {c['naive']:.3f} | {c['batch-means']:.3f} |")
    lines += [
        "",
        "Averaging needed by (16) for an rms budget in the tilt channel (first order, latitude 60°, σ = 0.5° on both axes, 10 Hz):",
        "",
        "| rocking | budget [°] | n | T [s] |",
        "|---|---|---|---|",
    ]
    for label, b, r in required:
        lines.append(f"| {label} | {b * D:g} | {r.n_samples if r.n_samples else 'not within the search'} | {r.duration:.4g} |")
    return lines + [""]


# ---------------------------------------------------------------- build
def alignment_lines(ctx) -> list:
    """The Markdown lines of the page (its figures written through ``ctx``).

    Parameters
    ----------
    ctx : Context
        Report context (output, sizes, seed).

    Returns
    -------
    list of str
    """
    from ..alignment import studies as st
    from ..alignment.base_motion import NarrowbandMotion
    from ..alignment.design import admissible_rocking, design_check
    from ..alignment.fine import Disturbance, assumed_disturbance
    from ..alignment.imu import Scenario
    from ..alignment.monte_carlo import alignment_monte_carlo
    from ..gyrocompass.admissible_rocking import admissible_amplitude
    from ..gyrocompass.finite_sample import required_averaging
    from ..gyrocompass.rocking import NarrowbandRocking, SineRocking

    q = ctx.quick
    lines = [
        f"# {TITLE}",
        "",
        "Hrechka & Koroliov bound the azimuth error of a self-aligning SINS through the tilt channel only and leave open the",
        "admissible rocking (conclusion 4). This section simulates the whole system — the rocking in the gyros and the accelerometers,",
        "sensor errors, three alignment methods — checks every first-order error term against Monte Carlo, and answers the",
        "designer's question for each method. Angles in degrees here, radians in the library.",
        "",
    ]
    lines += _model_lines()
    floors = st.bias_floor_study(rad(np.array([0.0, 30.0, 60.0, 75.0])), n_trials=32 if q else 256, rng=_seed(ctx, 0))
    lines += _floor_lines(floors)
    lines += _accel_lines(st.accel_bias_study(rad(60.0), n_trials=128 if q else 400, rng=_seed(ctx, 1)), rad(60.0))
    noise = st.noise_study([30.0, 120.0] if q else [30.0, 60.0, 120.0, 240.0], n_trials=32 if q else 128, rng=_seed(ctx, 2))
    _noise_figure(ctx, noise)
    lines += _noise_lines(noise)
    lines += _rocking_lines(_rocking_rows(ctx))
    # Kalman consistency
    e = st.NAVIGATION_GRADE
    still = Scenario(rad(60.0), heading=rad(30.0), sample_rate=10.0, duration=120.0)
    rocking = Scenario(rad(60.0), heading=rad(30.0), motion=NarrowbandMotion(rad(np.array([0.5, 1.0, 1.0])), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=120.0)
    n_k = 32 if q else 256
    cases = []
    for i, (label, sc) in enumerate((("at rest", still), ("narrow-band rocking, lever arm, shaping states", rocking))):
        mc = alignment_monte_carlo(sc, e, method="kalman", n_trials=n_k, rng=_seed(ctx, 4, i), options=st.kalman_options(sc, e))
        cases.append((label, mc))
    # the same rocking trials (common random numbers) through the rocking states matched to the narrow-band spectrum
    matched = st.kalman_options(rocking, e, disturbance=assumed_disturbance(rocking.motion, rocking, kind="matched"))
    cases.append(("narrow-band rocking, lever arm, matched rocking states", alignment_monte_carlo(rocking, e, method="kalman", n_trials=n_k, rng=_seed(ctx, 4, 1), options=matched)))
    _kalman_figure(ctx, cases)
    mismatch = st.mismatch_study(rocking, e, period_ratios=(0.5, 1.0, 2.0) if q else (0.5, 0.8, 1.0, 1.25, 2.0), n_trials=32 if q else 128, rng=_seed(ctx, 5))
    lines += _kalman_lines(cases, mismatch)
    # design
    sc = st.DESIGN_SCENARIO
    budget = rad(0.3)
    freqs = np.geomspace(0.05, 0.4, 2 if q else 6)
    n_d, rtol = (16, 0.3) if q else (64, 0.1)
    n_trials = {"analytic": 0, "inertial": 2 * n_d, "kalman": n_d}
    designs, checks = [], []
    for k, (method, rock) in enumerate((("analytic", "sine"), ("analytic", "narrowband"), ("inertial", "sine"), ("inertial", "narrowband"), ("kalman", "sine"), ("kalman", "narrowband"))):
        opts = st.kalman_options(sc, e, disturbance=Disturbance("shaping", 0.01)) if method == "kalman" else None
        d = admissible_rocking(method, budget, sc, freqs, e, rocking=rock, options=opts, n_trials=max(n_trials[method], 8), rtol=rtol, rng=_seed(ctx, 6, k))
        designs.append(d)
        if method != "analytic":
            checks.append((d, design_check(d, sc, e, indices=(0, -1), options=opts, n_trials=n_d if q else 128, rng=_seed(ctx, 7, k))))
    tilt = {r: admissible_amplitude(budget, sc.latitude, sc.duration, freqs, rocking=r, sample_rate=sc.sample_rate) for r in ("sine", "narrowband")}
    _design_figure(ctx, designs, checks, tilt)
    lines += _design_lines(designs, checks, sc, budget, e, rtol)
    # finite samples
    table = st.sample_statistics_table([10.0, 30.0, 60.0, 120.0])
    coverage = st.coverage_study([10.0, 30.0, 120.0], n_trials=300 if q else 2000, rng=_seed(ctx, 8))
    s = rad(0.5)
    required = [
        (label, rad(b), required_averaging(rad(b), rad(60.0), model, 0.1, max_samples=100_000))
        for label, model in (("narrow-band 8 s, ζ = 0.1", NarrowbandRocking(s, s, 8.0, 0.1)), ("sine 8 s", SineRocking(s, s, 8.0, 8.0)))
        for b in (0.1, 0.02)
    ]
    lines += _finite_lines(table, coverage, required)
    lines += _corrections(lines, q)
    return lines


def warm_up() -> None:
    """Compile what :func:`build` runs: the IMU increments, the preintegration and the filter loop, on a short rocking record."""
    from ..alignment import studies as st
    from ..alignment.base_motion import NarrowbandMotion
    from ..alignment.imu import Scenario
    from ..alignment.monte_carlo import alignment_monte_carlo
    from ..coning.kernels import available

    if not available():
        return
    import numba  # noqa: F401 - the alignment loops run compiled once numba is loaded (as it is when the report reaches them)

    e = st.NAVIGATION_GRADE
    still = Scenario(rad(60.0), heading=rad(30.0), sample_rate=10.0, duration=10.0)
    rocking = Scenario(rad(60.0), heading=rad(30.0), motion=NarrowbandMotion(rad(np.array([0.5, 1.0, 1.0])), 8.0, 0.1), lever_arm=[0.5, 0.3, 1.0], sample_rate=10.0, duration=10.0)
    for method in ("analytic", "inertial"):
        alignment_monte_carlo(rocking, e, method=method, n_trials=2, rng=0)
    for sc in (still, rocking):
        alignment_monte_carlo(sc, e, method="kalman", n_trials=2, rng=0, options=st.kalman_options(sc, e))


#: The earlier version whose numbers the page lists where they changed.
EARLIER = "0.1.0"


def _corrections(lines, quick: bool) -> list:
    from .corrections import changed_cells, corrections_lines, earlier_page

    causes = [
        f"Version {EARLIER} of this page understated the error of every method under narrow-band and white rocking. Its Gaussian",
        "rocking was drawn on a frequency grid without the zero-frequency bin, and its theory summed the same discrete spectrum, so",
        "the two agreed with each other and both lost the lowest frequencies, which carry the variance of a long mean: for the",
        "30 s means of 8 s narrow-band rocking in the rocking table the variance was 5 % too small, for 300 s means half its value.",
        "The models are now continuous spectral densities; the simulation keeps the zero frequency and the theory integrates the",
        "density (part 1), both checked against closed forms that share nothing with them.",
        "",
        "The other changes follow from it. The Gaussian draws now hold the zero-frequency bin, so every narrow-band trial is a",
        "different draw: the Monte Carlo cells of the narrow-band rows move within their intervals. The admissible-amplitude search",
        "now evaluates trials drawn once per frequency at every amplitude (common random numbers passed explicitly) and reports the",
        "root found by Brent's method, where it reported the lower end of its last bracket: its sine rows move too, and the checks",
        "straddle the budget instead of falling below it. The sine, noise, bias and finite-sample tables did not change. The rocking",
        "table's size column said 'amplitude' where its narrow-band value is the standard deviation σ (the amplitude in the",
        "library's convention is σ√2); it now says which.",
    ]
    if quick:
        return ["## Corrections to earlier versions", "", *causes, "", "The changed numbers are listed in the full report.", ""]
    cells = changed_cells(earlier_page(f"alignment-{EARLIER}.md"), "\n".join(lines))
    return corrections_lines(cells, version=EARLIER, causes=causes)


def build(ctx) -> None:
    """Write ``alignment.md`` and its figures.

    Parameters
    ----------
    ctx : Context
        Report context (output, sizes, seed).
    """
    lines = alignment_lines(ctx)
    lines.append(f"Mode: {'quick' if ctx.quick else 'full'}; root seed {ctx.seed}.")
    ctx.write_text("alignment.md", "\n".join(lines))


def errata(ctx) -> list:
    """The interpretations of Hrechka & Koroliov that the whole-system model finds.

    Parameters
    ----------
    ctx : Context
        Report context.

    Returns
    -------
    list of Erratum
    """
    return alignment_errata(ctx)


def alignment_errata(ctx) -> list:
    """Interpretations of Hrechka & Koroliov found by the whole-system model.

    Parameters
    ----------
    ctx : Context
        Report context.

    Returns
    -------
    list of Erratum
    """
    from ..alignment.analytic import analytic_alignment
    from ..alignment.imu import Scenario, simulate_imu

    lat, b0, g0 = rad(60.0), rad(1.0), rad(-0.5)
    err = {}
    for h in (0.0, 45.0, 90.0):
        rec = simulate_imu(Scenario(lat, heading=rad(h), beta0=b0, gamma0=g0, duration=5.0, sample_rate=10.0), n_trials=1, rng=0)
        err[h] = (float(analytic_alignment(rec, formula="paper").heading_error[0]), float(analytic_alignment(rec, formula="levelled").heading_error[0]))
    rows = _rocking_rows(ctx)
    tilt = [r for r in rows if not r.rocking_in_gyros]
    gyro = [r for r in rows if r.rocking_in_gyros]
    return [
        Erratum(
            "Hrechka & Koroliov, before (4) and (11)–(12): the rocking in the gyros",
            "each laser gyro senses the rocking as its projection on its sensitive axis; the error (12) compares α and α* of (11), "
            "both built from the same gyro signals f1, f2",
            "the error the paper analyses, σ(β0 + ξ, γ0 + η) − σ(β0, γ0), is that of gyros at the stable attitude: the rocking "
            "enters through the tilts the accelerometers measure (the package's tilt channel and `--tilt-channel-only`)",
            f"Analytic alignment, φ = 70°, β0 = 2°, γ0 = −1°, 30 s at 10 Hz: with the gyros at the stable attitude the first-order "
            f"rms per degree of rocking is {min(r.per_unit for r in tilt):.3g} to {max(r.per_unit for r in tilt):.3g} °/°, and the Monte Carlo "
            "matches the paper's theory; with the rocking in the gyros it is "
            f"{min(r.per_unit for r in gyro):.4g} to {max(r.per_unit for r in gyro):.4g} °/° (rocking table of the alignment report).",
            "alignment",
            kind="ambiguous",
            alternatives="Read literally, the gyros see the rocking: then (2) averages the body rate the rocking adds, the mean tilt the gyros "
            "see cancels the tilt correction of (16) to first order, and the error is thousands of times the tilt channel's (the evidence), "
            "far beyond (14)–(15). The paper's analysis fits the first reading, its sentence the second.",
        ),
        Erratum(
            "Hrechka & Koroliov, eq. (2) with σ = arctg(B/A)",
            "α = −arctg(f2/f1) + σ, σ = arctg(B/A) with A, B independent of α",
            "(2) with this σ is the analytic gyrocompass for a near-north orientation of the two gyros (the paper takes it from "
            "its reference [5]); the tilt correction σ is the one at zero azimuth",
            f"Ideal sensors, φ = 60°, β0 = 1°, γ0 = −0.5°: error of (2) with σ {at_round_off(err[0.0][0] * D)}° at ψ = 0, {err[45.0][0] * D:.3g}° at 45°, "
            f"{err[90.0][0] * D:.3g}° at 90°; the mean rate levelled by the same tilt estimates: error {at_round_off(max(abs(v[1]) for v in err.values()) * D)}° at all three.",
            "azimuth",
            kind="ambiguous",
            alternatives="Read as a formula for any azimuth, (2) with σ is off by degrees at 45° and 90° for tilts of a degree (the evidence); the exact correction "
            "depends on the azimuth: the levelled formula ψ = atan2(−ω_h,y, ω_h,x), ω_h = R_x(−β̂) R_y(γ̂) ω̄.",
        )
    ]
