"""Report section ``azimuth.md``: gyrocompass azimuth error under random rocking.

Formatting only: every number and curve comes from
:mod:`strapdown.analysis.gyrocompass` and :mod:`strapdown.derivations.gyrocompass`.
Parts 1–6 are the tilt channel of Hrechka & Koroliov; the whole-system
self-alignment (rocking in the gyros, sensor errors, three methods) is the page
of :mod:`strapdown.analysis.report.alignment`.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.units import DEG_PER_RAD as D
from ..core.units import rad
from . import Erratum, Section
from .rendering import at_round_off, fixed_layout

SECTION = Section(
    "azimuth",
    "Gyrocompass azimuth error under random rocking",
    order=50,
    summary=(
        "Bounds (14), (15) of Hrechka & Koroliov derived and checked by Monte Carlo; second-order theory; estimators (16) vs Kalman filter; "
        "admissible rocking in the tilt channel."
    ),
)


#: highest total degree of the Taylor control variates of the Monte Carlo runs
CONTROL_DEGREE = 4


def _seed(ctx, *key):
    return np.random.SeedSequence(ctx.seed, spawn_key=(50, *key))


#: The section prints moments, intervals of the rms and histograms, never quantiles: its Monte Carlos skip their order statistics.
_NO_QUANTILES = ()

#: Reference sizes of the violation cases (their plain-run precision) [count], quick and full.
_VIOLATION_SAMPLES = {True: 400_000, False: 4_000_000}


def _violations(ctx) -> list:
    """The violation cases of part 2, computed once per report run (the errata quote one of them)."""
    from ..gyrocompass.studies import VIOLATION_CASES, run_cases

    return ctx.shared(
        "azimuth/violation-cases",
        lambda: run_cases(VIOLATION_CASES, n_samples=_VIOLATION_SAMPLES[ctx.quick], rng=_seed(ctx, 0), control_degree=CONTROL_DEGREE, quantiles=_NO_QUANTILES),
    )


def _formula_checks() -> tuple:
    """The printed formulas against the derivation (SymPy simplification: cached with the derived results)."""
    from ..core.cache import derived
    from ..gyrocompass.formula_checks import check_printed_formulas

    return derived("gyrocompass:printed-formula-checks:v1", check_printed_formulas)


def _latex(expr) -> str:
    import sympy as sp

    return sp.latex(expr)


def _g(x, digits=4) -> str:
    return f"{x:.{digits}g}"


def _ci(r, digits=5) -> str:
    return f"{_g(r.rms * D, digits)} ({_g(r.rms_ci[0] * D, digits)}–{_g(r.rms_ci[1] * D, digits)})"


#: means below this fraction of the rms are printed as 0: far above round-off (1e-16 of the rms),
#: so that no last-bit difference of the arithmetic reaches a printed digit
_MEAN_FLOOR = 1e-9


def _mean_ci(r) -> str:
    floor = _MEAN_FLOOR * r.rms
    lo, hi = r.mean_ci
    if max(abs(lo), abs(hi)) < floor:
        return f"0 (within ±{floor * D:.0e})"

    def fmt(x):
        return "0" if abs(x) < floor else f"{x * D:.3g}"

    return f"{fmt(r.mean)} ({fmt(lo)}–{fmt(hi)})"


def _samples(mc) -> str:
    c = mc.controls
    return f"{c.samples} ({c.plain_equivalent:.2g})"


def _controls_text(n) -> list:
    return [
        "The mean and the mean square are control-variate estimates: from each error and its square the Monte Carlo subtracts",
        f"a combination of the monomials $u^i v^j$ ($u = \\xi/\\sigma_\\xi$, $v = \\eta/\\sigma_\\eta$, $1 \\le i + j \\le {CONTROL_DEGREE}$ for a sinusoid, $\\le 2$",
        "for Gaussian rocking, whose residuals after higher degrees are too heavy-tailed for the interval of a short run),",
        "whose means are exact, with coefficients fitted on an independent pilot run. The estimates stay unbiased and their",
        "95 % intervals are the ordinary ones of independent draws (their coverage is tested against exact quadrature); the",
        "Taylor part of the error no longer adds variance. Each run is sized so that",
        f"its intervals are at most as wide as those of a plain Monte Carlo of {n} samples (column 'samples': draws used and,",
        "in brackets, how many a plain Monte Carlo would need for the same intervals). Where the rocking reaches towards the",
        "horizon of the tilt correction ($A + iB = 0$, where the error wraps) often enough for a plain run to meet it, no",
        "polynomial follows the error and the large errors there would dominate what the controls leave: the run then meets",
        "that region at least 100 times, and where even a plain run would meet it fewer times, it is the plain run.",
    ]


# ---------------------------------------------------------------- 1. derivation
def _linear_parts():
    """:func:`strapdown.derivations.gyrocompass.azimuth_error.linear_parts`, kept with the derived results (SymPy)."""
    from ...derivations.gyrocompass import azimuth_error as g
    from ..core.cache import derived

    return derived("gyrocompass:linear-parts:v1", g.linear_parts)


def _derivation_lines(checks) -> list:
    from ...derivations.gyrocompass import azimuth_error as g
    from ..core.cache import derived

    p = _linear_parts()
    mse = derived("gyrocompass:mse-at-zero-tilt:v1", g.mse_at_zero_tilt)
    reduces = "reduces symbolically to (15)" if derived("gyrocompass:bound14-reduces-to-15:v1", g.bound14_reduces_to_15) else "does NOT reduce to (15)"
    lines = [
        "## 1. Derivation (SymPy, `derivations/gyrocompass/azimuth_error.py`)",
        "",
        f"- $A^* = {_latex(p.A_star)}$ (6), $B^* = {_latex(p.B_star)}$ (9)",
        f"- $\\zeta_1 = {_latex(p.zeta1)}$ (7)",
        f"- $\\zeta_2 = {_latex(p.zeta2)}$ (10)",
        "- Bound (14): $\\delta^2 \\le (B^*/A^{*2})^2 D\\zeta_1 + 2|B^*/A^{*3}|\\sqrt{D\\zeta_1 D\\zeta_2} + D\\zeta_2/A^{*2}$; at $\\beta_0=\\gamma_0=0$ it",
        f"  {reduces}, $\\delta^2 \\le \\tan^2\\varphi\\, D\\xi$ (`sympy.simplify` of the difference).",
        "- Exact first-order error: $L = (A^*\\zeta_2 - B^*\\zeta_1)/(A^{*2} + B^{*2})$. (14) bounds $E L^2$ (|arctan x − arctan y| ≤ |x − y| and",
        "  Cauchy–Schwarz), but only to first order: it is not a bound on $\\delta$ itself.",
        "- **Beyond the paper**: the series of $\\sigma - \\sigma^*$ to third order (as $\\mathrm{Im}\\log(1+w)$), the second-order bias",
        "  $E(\\sigma-\\sigma^*)$ and the mean square to fourth order, with $E\\xi^4 = \\kappa D\\xi^2$ (κ = 3 Gaussian, 3/2 sinusoid).",
        "  At zero stable tilt the bias vanishes and",
        "",
        f"  $$E(\\sigma-\\sigma^*)^2 = {_latex(mse)} + O(D^3)$$",
        "",
        "  i.e. $\\tan^2\\varphi\\,D\\xi\\,[1 + D\\eta(1 + 3\\tan^2\\varphi) - \\kappa_\\xi D\\xi(1 + 2\\tan^2\\varphi)/3]$: the rocking η *does* enter at second",
        "  order (against conclusion 2 of the paper read literally), and whenever the bracket exceeds 1 — for equal Gaussian or",
        "  sinusoidal rocking at any latitude — (15) and (14) are exceeded.",
        "",
        "### Printed formulas against the derivation",
        "",
        "| Formula | printed − derived | max residual on 200 random points |",
        "|---|---|---|",
    ]
    for c in checks:
        diff = "0" if c.agrees else f"${_latex(c.difference)}$"
        lines.append(f"| {c.label} | {diff} | {at_round_off(c.residual)} |")
    lines += [
        "",
        "(5), (7), (8), (10) are compared with the first-order Taylor part (their O(ξ², η²) remainders dropped); the rows",
        "`A`, `B (after (2))` compare the full functions. See [errata](errata.md).",
        "",
    ]
    return lines


# ---------------------------------------------------------------- 2., 3. cases
def _violation_lines(results) -> list:
    lines = [
        "## 2. Where the bounds fail: concrete cases",
        "",
        "Monte Carlo at independent instants. A bound holds ('yes') when the whole 95 % CI of the rms lies at or below it, fails",
        "('no') when the whole CI lies above it, and is not resolved otherwise (with the trials a decision needs). The paper derives (15) from (14)",
        "by dropping the terms of first order in β0, γ0, i.e. for β0 = γ0 = 0; a (15) verdict at other stable tilts (marked †) tests it",
        "outside the conditions of its derivation.",
        *_controls_text(results[0].mc.controls.reference_samples),
        "",
        "| Case | rocking | φ [°] | β0, γ0 [°] | σ [°] | samples | MC rms [°] (95 % CI) | (14) [°] | (15) [°] | 2nd-order theory [°] | (14) holds | (15) holds |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for v in results:
        c, mc, r = v.case, v.mc, v.mc.result
        lines.append(
            f"| {c.label} | {c.model} | {c.latitude * D:.4g} | {c.beta0 * D:.4g}, {c.gamma0 * D:.4g} | {c.sigma * D:.4g} | {_samples(mc)} | {_ci(r)} "
            f"| {_g(mc.bound14 * D, 5)} | {_g(mc.bound15 * D, 5)} | {_g(mc.theory.rms * D, 5)} "
            f"| {r.bound_holds(mc.bound14, what='(14)').label()} | {r.bound_holds(mc.bound15, what='(15)').label()}{_outside15(c)} |"
        )
    return lines + ["", "![MC distribution against the bounds](figures/azimuth-distribution.png)", ""]


def _outside15(case) -> str:
    """The mark of a (15) verdict at stable tilts other than β0 = γ0 = 0, outside the conditions of its derivation."""
    return " †" if case.beta0 or case.gamma0 else ""


def _distribution_figure(ctx, results) -> None:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(results), figsize=(11, 3.2))
    for ax, v in zip(axes, results):
        c, mc = v.case, v.mc
        edges, counts, _, _ = mc.result.histogram
        k = 40  # merge bins for display
        m = counts[: len(counts) // k * k].reshape(-1, k).sum(axis=1)
        e = edges[::k][: len(m) + 1] * D
        width = e[1] - e[0]
        ax.stairs(m / (m.sum() * width), e, fill=True, color="0.7", label="Monte Carlo")
        for value, style, name in ((mc.result.rms, "-", "MC rms"), (mc.bound14, "--", "bound (14)"), (mc.bound15, ":", "bound (15)")):
            ax.axvline(value * D, color="k", ls=style, label=name)
            ax.axvline(-value * D, color="k", ls=style)
        lim = 3.2 * mc.result.rms * D
        ax.set_xlim(-lim, lim)
        ax.set_title(f"{c.model}, φ={c.latitude * D:.3g}°, β0={c.beta0 * D:.3g}°, γ0={c.gamma0 * D:.3g}°, σ={c.sigma * D:.3g}°", fontsize=8)
        ax.set_xlabel("azimuth error α − α* [deg]")
    axes[0].set_ylabel("density [1/deg]")
    axes[0].legend(loc="upper left")
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.6)
    ctx.savefig(fig, "figures/azimuth-distribution.png")


def _small_rocking_lines(results) -> list:
    from ..gyrocompass.studies import THEORY_MARGIN

    lines = [
        "## 3. Small rocking: Monte Carlo against the second-order theory",
        "",
        f"Control variates as in part 2, each run at least as precise as a plain Monte Carlo of {results[0].mc.controls.reference_samples} samples.",
        "",
        f"A theory agrees when the true rms is within ±{THEORY_MARGIN:.0%} of it (TOST on the mean square at 95 %); 'in CI' says whether the Monte Carlo",
        "is too coarse to see the theory's remainder at all.",
        "",
        f"| rocking | φ [°] | β0, γ0 [°] | σ [°] | samples | MC rms [°] (95 % CI) | theory rms [°] | theory agrees (±{THEORY_MARGIN:.0%}) | in CI | MC mean [°] (95 % CI) | theory bias [°] |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for v in results:
        c, mc, r = v.case, v.mc, v.mc.result
        lines.append(
            f"| {c.model} | {c.latitude * D:.4g} | {c.beta0 * D:.4g}, {c.gamma0 * D:.4g} | {c.sigma * D:.4g} | {_samples(mc)} | {_ci(r, 6)} | {mc.theory.rms * D:.6g} "
            f"| {v.theory_agreement.label()} | {'yes' if v.theory_inside else 'no'} | {_mean_ci(r)} | {mc.theory.bias * D:.3g} |"
        )
    outside = [v for v in results if not v.theory_inside]
    biased = [v for v in results if not v.mc.result.mean_ci[0] <= v.mc.theory.bias <= v.mc.result.mean_ci[1]]
    lines += ["", f"A mean below {_MEAN_FLOOR:.0e} of the rms is printed as 0."]
    if outside:
        rows = "; ".join(
            f"{v.case.model}, φ = {v.case.latitude * D:.3g}°, σ = {v.case.sigma * D:.3g}°: |MC − theory|/theory = {abs(v.mc.result.rms / v.mc.theory.rms - 1):.1g}, "
            f"$(D\\tan^2\\varphi)^2$ = {(v.case.sigma * math.tan(v.case.latitude)) ** 4:.1g}"
            for v in outside
        )
        lines += [f"Where the theory lies outside the interval the Monte Carlo resolves its remainder, of relative order $(D\\tan^2\\varphi)^2$: {rows}."]
    if biased:
        lines += [f"The theory's bias is second order; the interval of the mean resolves its fourth-order remainder in {len(biased)} of the {len(results)} cases."]
    return lines + [""]


# ---------------------------------------------------------------- 4. validity maps
def _map_groups():
    return {
        "normal, β0=γ0=0": dict(model="normal"),
        "normal, β0=2°, γ0=−2°": dict(model="normal", beta0=rad(2.0), gamma0=rad(-2.0)),
        "sine, β0=2°, γ0=−2°": dict(model="sine", beta0=rad(2.0), gamma0=rad(-2.0)),
        "narrowband τc=6.4 s, (16) over 30 s": dict(model="narrowband", period=8.0, damping=0.2, estimate="sample-mean", averaging_time=30.0),
        "narrowband τc=64 s, (16) over 30 s": dict(model="narrowband", period=8.0, damping=0.02, estimate="sample-mean", averaging_time=30.0),
    }


def _validity_maps(ctx) -> dict:
    from ..gyrocompass.bound_sweep import validity_map

    if ctx.quick:
        lats, sigmas, n = np.array([0.0, 20.0, 45.0, 70.0, 80.0]), np.array([0.01, 0.1, 1.0, 3.0, 10.0]), 20_000
    else:
        lats, sigmas, n = np.arange(0.0, 81.0, 10.0), np.geomspace(0.01, 10.0, 13).round(4), 200_000
    groups = list(_map_groups().items())
    return {
        name: validity_map(rad(lats), rad(sigmas), n_samples=n, rng=_seed(ctx, 3, i), control_degree=CONTROL_DEGREE, **fields)
        for i, (name, fields) in enumerate(ctx.progress(groups, "azimuth maps"))
    }


def _map_panel(ax, m, ratio, holds, fails, title):
    import matplotlib.colors as mcolors

    # ±0.3 in log10 is a factor of two either way: the bounds fail by tens of per cent, not decades.
    norm = mcolors.TwoSlopeNorm(vmin=-0.3, vcenter=0.0, vmax=0.3)
    im = ax.pcolormesh(np.arange(len(m.sigmas) + 1), np.arange(len(m.latitudes) + 1), np.clip(np.log10(ratio), -0.3, 0.3), cmap="RdBu_r", norm=norm, shading="flat")
    if fails is not None:
        yy, xx = np.nonzero(fails)
        ax.plot(xx + 0.5, yy + 0.5, "kx", ms=4)
        yy, xx = np.nonzero(holds)
        ax.plot(xx + 0.5, yy + 0.5, "k.", ms=2)
    ax.set_xticks(np.arange(len(m.sigmas)) + 0.5, [f"{s * D:.3g}" for s in m.sigmas], rotation=90, fontsize=6)
    ax.set_yticks(np.arange(len(m.latitudes)) + 0.5, [f"{v * D:.3g}" for v in m.latitudes], fontsize=6)
    ax.set_title(title, fontsize=8)
    ax.set_xlabel("rocking σ [deg]")
    ax.set_ylabel("latitude [deg]")
    return im


def _label_outer(axes):
    for i, row in enumerate(axes):
        for j, ax in enumerate(row):
            if j:
                ax.set_ylabel("")
            if i < len(axes) - 1:
                ax.set_xlabel("")


def _map_grid(n_columns: int, width: float):
    """Two rows of map panels and a colour-bar axis, laid out by hand (no layout engine: one draw fewer)."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, n_columns, figsize=(width * n_columns, 7.0), squeeze=False)
    fixed_layout(fig, left=0.5, right=1.2, bottom=0.65, top=0.5, wgap=0.45, hgap=0.9)
    w = width * n_columns
    return fig, axes, fig.add_axes(((w - 1.0) / w, 0.2, 0.14 / w, 0.6))


def _validity_figures(ctx, maps) -> None:
    known = [k for k in maps if "narrowband" not in k]
    fig, axes, cax = _map_grid(len(known), 3.9)
    im = None
    for j, name in enumerate(known):
        m = maps[name]
        im = _map_panel(axes[0, j], m, m.ratio14, m.holds14, m.fails14, f"{name}:\nMC rms / (14)")
        _map_panel(axes[1, j], m, m.ratio15, m.holds15, m.fails15, f"{name}:\nMC rms / (15)")
    _label_outer(axes)
    fig.colorbar(im, cax=cax, label="log10(MC rms / bound); x: fails (CI above), ·: holds")
    ctx.savefig(fig, "figures/azimuth-validity-known.png")
    corr = [k for k in maps if "narrowband" in k]
    fig, axes, cax = _map_grid(len(corr), 4.2)
    for j, name in enumerate(corr):
        m = maps[name]
        im = _map_panel(axes[0, j], m, m.ratio14, m.holds14, m.fails14, f"{name}:\nrms Δ / (14) at the variance of the mean")
        _map_panel(axes[1, j], m, m.plugin_ratio14, None, None, f"{name}:\nrms Δ / (14) with the sample variances of (16)")
    _label_outer(axes)
    fig.colorbar(im, cax=cax, label="log10(rms alignment error / bound)")
    ctx.savefig(fig, "figures/azimuth-validity-correlation.png")


def _validity_lines(maps) -> list:
    first = next(iter(maps.values())).rows[0].controls
    lines = [
        "## 4. Validity maps",
        "",
        "Latitude × rocking standard deviation (both axes equal). Colour: log10(MC rms / bound); x: the bound fails (CI entirely",
        "above it), dot: it holds (CI entirely below), blank: undecided. Every cell is a control-variate Monte Carlo as in part 2",
        "(or the plain one near the horizon) whose 95 % intervals are at most as wide as those of a plain Monte Carlo of",
        f"{first.reference_samples} samples (for the narrow-band maps: of as many samples in records of 30 s); the table gives the",
        "fewest plain-equivalent samples over the cells.",
        "",
        "![validity maps, known stable tilts](figures/azimuth-validity-known.png)",
        "",
        "| Map | cells | (14) holds | (14) fails | (15) holds | (15) fails | worst MC rms / (14) | worst MC rms / (15) | draws | fewest plain-equivalent |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, m in maps.items():
        draws = sum(r.controls.samples for r in m.rows)
        worth = min(r.controls.plain_equivalent * (r.case.n_steps if r.case.estimate == "sample-mean" else 1) for r in m.rows)
        lines.append(
            f"| {name} | {m.ratio14.size} | {int(m.holds14.sum())} | {int(m.fails14.sum())} | {int(m.holds15.sum())}{_outside15(m.rows[0].case)} | {int(m.fails15.sum())}{_outside15(m.rows[0].case)} "
            f"| {np.nanmax(m.ratio14):.3g} | {np.nanmax(m.ratio15):.3g}{_outside15(m.rows[0].case)} | {draws} | {worth:.2g} |"
        )
    nb_rows = [r for m in maps.values() for r in m.rows if r.case.estimate == "sample-mean"]
    nb_plain = sum(1 for r in nb_rows if r.controls.degree == 0)
    nb_controls = "with the monomials of the means as controls" + (f" (plain in {nb_plain} of the {len(nb_rows)} cells, near the horizon)" if nb_plain else "")
    zero = maps["normal, β0=γ0=0"]
    off = zero.latitudes != 0.0
    zero_cells, zero_fails, zero_holds = int(zero.fails14[off].size), int(zero.fails14[off].sum()), int(zero.holds14[off].sum())
    lines += [
        "",
        "At latitude 0° error and bounds are exactly zero. At zero stable tilt every other cell exceeds (14) = (15) by the",
        "second-order factor of part 1, $\\sqrt{1 + D\\eta(1 + 3\\tan^2\\varphi) - \\kappa_\\xi D\\xi(1 + 2\\tan^2\\varphi)/3}$ (a relative excess of",
        "about $D\\tan^2\\varphi/2$ for equal Gaussian rocking, far below a per cent for small rocking); the Monte Carlo resolves",
        f"that excess where it exceeds the interval: {zero_fails} of the {zero_cells} cells off the equator fail, {zero_holds} 'hold' (a 2.5 % chance",
        "per cell), the rest are undecided. The large failures are the blocks at large rocking and high latitude, and the",
        "whole (15) map once the stable tilts are not zero — where (15) is applied outside the conditions of its derivation",
        "(β0 = γ0 = 0, marked † in the table): those failures measure what dropping β0, γ0 costs, not a flaw of (15) where the paper",
        "derived it.",
        "",
        "For the narrow-band maps the error is the alignment error Δ = σ(β̂0, γ̂0) − σ(β0, γ0) of the sample means (16) over",
        "30 s at 10 Hz: an error of a *mean*. It is compared with (14) and (15) evaluated at the variances of the means",
        "($D\\xi \\to v D\\xi$, $v$ the variance factor of the mean of correlated samples), the bound that applies to it (top row).",
        "The paper's prescription after (16) — (14) with the sample variances — bounds the instantaneous error (12), and",
        "overstates the error of the estimate by $1/\\sqrt{v}$ (bottom row, off the colour scale). Δ depends on a record only",
        "through its two sample means, whose law is exact (independent zero-mean Gaussians of variance $v D$, the mean of a",
        f"Gaussian record): the Monte Carlo draws them from it, {nb_controls}. The plug-in bound needs",
        "the sample variances too, so for it whole records are simulated, with the sample variances (exact mean $(1 - v) D$)",
        "as controls.",
        "",
        "![validity maps, correlated rocking](figures/azimuth-validity-correlation.png)",
        "",
    ]
    nb = maps["narrowband τc=64 s, (16) over 30 s"]
    i, j = len(nb.latitudes) // 2, len(nb.sigmas) // 2
    r = nb.rows[i * len(nb.sigmas) + j]
    from ..gyrocompass.bound_sweep import first_order_alignment_rms

    lines += [
        f"Check of one narrow-band cell (φ = {r.case.latitude * D:.3g}°, σ = {r.case.sigma * D:.4g}°, τc = 64 s): MC rms Δ = {r.rms * D:.4g}° "
        f"(CI {r.rms_lo * D:.4g}–{r.rms_hi * D:.4g}), first-order theory with the variance factor of the mean "
        f"{first_order_alignment_rms(r.case) * D:.4g}°, second-order theory {r.theory_rms * D:.4g}°; (14) with the sample variances {r.plugin14 * D:.4g}°.",
        "",
    ]
    return lines


# ---------------------------------------------------------------- 5. estimators
def _estimators(ctx):
    from ..gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking
    from ..gyrocompass.tilt_estimation import compare_estimators

    n_trials = 150 if ctx.quick else 600
    times = np.array([0.1, 0.5, 1.0, 2.0, 4.0, 8.0, 15.0, 30.0, 60.0, 120.0])
    s = rad(1.0)
    models = {"sine (period 8 s)": SineRocking(s, s, 8.0, 8.0), "narrowband (8 s, ζ=0.1)": NarrowbandRocking(s, s, 8.0, 0.1), "normal (white)": GaussianRocking(s, s)}
    seeds = _seed(ctx, 4).spawn(len(models))
    return {name: compare_estimators(rad(60.0), m, dt=0.1, averaging_times=times, n_trials=n_trials, rng=np.random.default_rng(seed)) for (name, m), seed in zip(models.items(), seeds)}


def _estimator_figure(ctx, results) -> None:
    import matplotlib.pyplot as plt

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 3.6))
    for (name, c), color in zip(results.items(), ("C0", "C1", "C2")):
        ax.loglog(c.times, c.rms_mean * D, "-o", color=color, ms=3, label=f"sample mean (16), {name}")
        ax.loglog(c.times, c.rms_kalman * D, "--s", color=color, ms=3, label=f"Kalman filter, {name}")
        ax2.semilogx(c.times, c.nees_mean, "-o", color=color, ms=3, label=name)
    lo, hi = next(iter(results.values())).nees_band
    ax2.axhspan(lo, hi, color="0.85", label="95 % band (consistent)")
    ax.set_xlabel("averaging time [s]")
    ax.set_ylabel("rms alignment error Δ [deg]")
    ax.set_title("latitude 60°, σ = 1° on both axes, 10 Hz")
    ax.legend(fontsize=6)
    ax2.set_xlabel("averaging time [s]")
    ax2.set_ylabel("mean NEES of β̂0 (1 dof)")
    ax2.legend(fontsize=6)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.75)
    ctx.savefig(fig, "figures/azimuth-estimators.png")


def _estimator_lines(results) -> list:
    lines = [
        "## 5. Estimating β0, γ0: sample mean (16) against a Kalman filter",
        "",
        "The Kalman filter (filterpy, through `analysis/core/kalman.py`) estimates $(\\beta_0, \\xi, \\dot\\xi)$ per axis with the",
        "rocking model as its dynamics; accelerometer noise 0.001°, prior σ(β0) = 2°. Azimuth error: the alignment error",
        "$\\Delta = \\sigma(\\hat\\beta_0, \\hat\\gamma_0) - \\sigma(\\beta_0, \\gamma_0)$ (rms over trials).",
        "",
        "| rocking | T [s] | sample mean [°] | Kalman [°] | NEES (95 % band) |",
        "|---|---|---|---|---|",
    ]
    for name, c in results.items():
        lo, hi = c.nees_band
        for j in (2, 5, 8):
            lines.append(f"| {name} | {c.times[j]:g} | {c.rms_mean[j] * D:.4g} | {c.rms_kalman[j] * D:.4g} | {c.nees_mean[j]:.3f} ({lo:.3f}–{hi:.3f}) |")
    return lines + [
        "",
        "The filter helps most for a sinusoid (three unknowns, no process noise); for narrow-band rocking it gains at short",
        "times and both converge to the same rate later (the sample mean is asymptotically efficient for a constant in",
        "noise with a continuous spectrum at zero frequency); for white rocking the two coincide.",
        "",
        "![estimators](figures/azimuth-estimators.png)",
        "",
    ]


# ---------------------------------------------------------------- 6. design chart
def _design(ctx):
    from ..gyrocompass.admissible_rocking import admissible_amplitude
    from ..gyrocompass.studies import tilt_design_check

    lat, T = rad(60.0), 60.0
    freqs = np.geomspace(0.02, 1.0, 16 if ctx.quick else 40)
    curves = {(kind, b): admissible_amplitude(rad(b), lat, T, freqs, rocking=kind, damping=0.1) for kind in ("narrowband", "sine") for b in (0.05, 0.1, 0.5)}
    exact_sine = admissible_amplitude(rad(0.1), lat, T, freqs, rocking="sine", envelope=False)
    check = tilt_design_check(rad(0.1), lat, T, freqs, n_trials=400 if ctx.quick else 3000, check=(0, len(freqs) // 2, -1), rng=_seed(ctx, 5))
    return curves, exact_sine, check, freqs


def _design_figure(ctx, curves, exact_sine, check, freqs) -> None:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
    for ax, kind in zip(axes, ("narrowband", "sine")):
        for b, color in zip((0.05, 0.1, 0.5), ("C0", "C1", "C2")):
            d = curves[(kind, b)]
            ax.loglog(freqs, d.amplitude * D, color=color, label=f"budget {b:g}°, rms")
            ax.loglog(freqs, d.amplitude_percentile * D, color=color, ls="--", label=f"budget {b:g}°, {d.level:.0%} of |Δ|")
        ax.set_xlabel("rocking frequency [Hz]")
        ax.set_ylabel("admissible amplitude [deg]")
        ax.set_title(f"{kind}: φ = 60°, T = 60 s, 10 Hz" + (", ζ = 0.1" if kind == "narrowband" else ", envelope over phase"), fontsize=9)
    axes[1].loglog(freqs, exact_sine.amplitude * D, color="0.6", lw=0.8, label="budget 0.1°, exact phase (jagged)")
    axes[0].plot(check.frequencies, check.amplitudes * D, "ko", ms=4, label="Monte Carlo check")
    for ax in axes:
        ax.legend(fontsize=6)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.7)
    ctx.savefig(fig, "figures/azimuth-design.png")


def _design_lines(curves, check, freqs) -> list:
    lines = [
        "## 6. Admissible rocking in the tilt channel (conclusion 4 of the paper)",
        "",
        "Largest rocking amplitude against frequency such that the alignment error of the estimate (16) over T = 60 s stays",
        "within the budget, at latitude 60°, when the rocking reaches the accelerometers only (the error (12) of the paper, read as",
        "gyros at the stable attitude;",
        "`analysis/gyrocompass/admissible_rocking.py`): by the rms (second-order theory with the variance factor of the mean,",
        "solid) and by the 95th percentile of |Δ| (first order, dashed). For the sine the mean over the window keeps",
        "the Dirichlet factor $\\sin(n\\omega h/2)/(n\\sin(\\omega h/2))$, which vanishes where T holds a whole number of periods; the chart",
        "uses its envelope over that phase (the worst case over alignment times of at least T; the exact, jagged",
        "curve is drawn thin). The sine's residue is bounded, so its 95th percentile is below $1.96\\,$rms; the narrow-band",
        "residue is Gaussian. The whole system — rocking in the gyros, sensor errors, three alignment methods — is part 7.",
        "",
        "![design chart](figures/azimuth-design.png)",
        "",
        "Monte Carlo check of the narrow-band 0.1° rms curve (dots in the chart):",
        "",
        "| f [Hz] | admissible amplitude [°] | MC rms Δ [°] (95 % CI) |",
        "|---|---|---|",
    ]
    for f, a, r in zip(check.frequencies, check.amplitudes, check.results):
        lines.append(f"| {f:.4g} | {a * D:.4g} | {_ci(r, 4)} |")
    step = max(1, len(freqs) // 8)
    d, s = curves[("narrowband", 0.1)], curves[("sine", 0.1)]
    lines += [
        "",
        "| f [Hz] | " + " | ".join(f"{f:.3g}" for f in freqs[::step]) + " |",
        "|---|" + "---|" * len(freqs[::step]),
        "| narrow-band a_max [°], rms 0.1° | " + " | ".join(f"{a * D:.3g}" for a in d.amplitude[::step]) + " |",
        "| narrow-band a_max [°], 95 % of \\|Δ\\| ≤ 0.1° | " + " | ".join(f"{a * D:.3g}" for a in d.amplitude_percentile[::step]) + " |",
        "| sine a_max [°], rms 0.1° (envelope) | " + " | ".join(f"{a * D:.3g}" for a in s.amplitude[::step]) + " |",
        "| sine a_max [°], 95 % of \\|Δ\\| ≤ 0.1° (envelope) | " + " | ".join(f"{a * D:.3g}" for a in s.amplitude_percentile[::step]) + " |",
        "",
    ]
    return lines


# ---------------------------------------------------------------- build
def warm_up() -> None:
    """Derive what :func:`build` needs into the caches: the linear parts, the mean square at zero tilt, the printed-formula checks, the second-order theory."""
    from ...derivations.gyrocompass import azimuth_error as g
    from ..core.cache import derived
    from ..gyrocompass.azimuth import second_order_theory

    derived("gyrocompass:mse-at-zero-tilt:v1", g.mse_at_zero_tilt)
    derived("gyrocompass:bound14-reduces-to-15:v1", g.bound14_reduces_to_15)
    _linear_parts()
    _formula_checks()
    second_order_theory(rad(45.0), rad(1.0), rad(0.5), rad(1.0), rad(1.0))


def build(ctx) -> None:
    """Write ``azimuth.md`` and its figures.

    Parameters
    ----------
    ctx : Context
        Report context (output, sizes, seed).
    """
    from ..gyrocompass.studies import DISTRIBUTION_CASES, SMALL_ROCKING_CASES, run_cases

    big, mid = (400_000, 200_000) if ctx.quick else (4_000_000, 2_000_000)
    lines = [
        f"# {SECTION.title}",
        "",
        "Source: Hrechka & Koroliov, eqs. (2), (4)–(16). The azimuth error on a rocking base is",
        "$\\alpha - \\alpha^* = \\sigma(\\beta_0+\\xi, \\gamma_0+\\eta) - \\sigma(\\beta_0, \\gamma_0)$ with",
        "$\\sigma = \\arctan(B/A)$, $A = \\cos\\varphi\\cos\\gamma + \\sin\\varphi\\cos\\beta\\sin\\gamma$, $B = \\sin\\varphi\\sin\\beta$.",
        "The package evaluates it as the angle of $(A + iB)/(A^* + iB^*)$ (the arctangent difference for $A, A^* > 0$,",
        "the wrapped angle otherwise). ξ and η are independent and zero-mean; $\\sigma_\\xi, \\sigma_\\eta$ are their standard",
        "deviations (a sinusoid has amplitude $\\sigma\\sqrt{2}$). This section analyses the paper's error (12), in which α and α* are",
        "built from the same gyro signals: the rocking enters through the tilts the accelerometers measure, as if the gyros saw the",
        "stable attitude. That is a reading: the paper also says each laser gyro senses the rocking as its projection on its",
        "sensitive axis, which makes the error thousands of times larger (alignment report and errata, 'ambiguous').",
        "",
    ]
    lines += _derivation_lines(_formula_checks())
    lines += _violation_lines(_violations(ctx))
    _distribution_figure(ctx, run_cases(DISTRIBUTION_CASES, n_samples=mid, rng=_seed(ctx, 2), quantiles=_NO_QUANTILES))
    lines += _small_rocking_lines(run_cases(SMALL_ROCKING_CASES, n_samples=big, rng=_seed(ctx, 1), control_degree=CONTROL_DEGREE, quantiles=_NO_QUANTILES))
    maps = _validity_maps(ctx)
    _validity_figures(ctx, maps)
    lines += _validity_lines(maps)
    estimators = _estimators(ctx)
    _estimator_figure(ctx, estimators)
    lines += _estimator_lines(estimators)
    curves, exact_sine, check, freqs = _design(ctx)
    _design_figure(ctx, curves, exact_sine, check, freqs)
    lines += _design_lines(curves, check, freqs)
    lines += [
        "## 7. The whole system",
        "",
        "Self-alignment with the rocking in the gyros as well, sensor errors and three alignment methods, and the admissible",
        "rocking of each method: [alignment](alignment.md).",
        "",
    ]
    lines.append(f"Mode: {'quick' if ctx.quick else 'full'}; root seed {ctx.seed}.")
    ctx.write_text("azimuth.md", "\n".join(lines))


# ---------------------------------------------------------------- errata
def errata(ctx) -> list:
    """Errata and interpretations of Hrechka & Koroliov, with evidence computed here.

    Parameters
    ----------
    ctx : Context
        Report context (sizes and seed).

    Returns
    -------
    list of Erratum
    """

    rows = {c.label: c for c in _formula_checks()}
    p = _linear_parts()
    out = [
        Erratum(
            "Hrechka & Koroliov, definition of A after eq. (2)",
            "A = cos φ sin γ + sin φ cos β sin γ",
            "A = cos φ cos γ + sin φ cos β sin γ",
            f"The printed A differs from the paper's own expansion (5)–(6) by up to {rows['A (after (2))'].residual:.2f} on random points "
            f"(printed (5), (6) agree with the cos γ form, residual {at_round_off(max(rows['(5)'].residual, rows['(6)'].residual))}); with sin γ, A = 0 at zero tilt and σ would be undefined.",
            "azimuth",
            kind="misprint",
        ),
        Erratum(
            "Hrechka & Koroliov, eq. (7), ξ term of ζ1",
            "− ξ sin φ cos β0 sin γ0",
            "− ξ sin φ sin β0 sin γ0 (as in (5): ∂A/∂β = −sin φ sin β sin γ)",
            f"SymPy: printed (7) − derived = ${_latex(rows['(7)'].difference)}$, max residual {rows['(7)'].residual:.2f} on random points; "
            f"the derived ζ1 = ${_latex(p.zeta1)}$ also equals the first-order part of the printed (5) (residual {at_round_off(rows['(5)'].residual)}).",
            "azimuth",
            kind="misprint",
        ),
    ]
    n = _VIOLATION_SAMPLES[ctx.quick]
    v = next(v for v in _violations(ctx) if v.case.model == "normal" and v.case.latitude == rad(80.0) and v.case.beta0 == v.case.gamma0 == 0.0 and v.case.sigma == rad(1.0))
    r, mc = v.mc.result, v.mc
    out.append(
        Erratum(
            "Hrechka & Koroliov, eq. (15) and conclusion 2",
            "δ ≤ tg φ √Dξ, practically independent of the rocking in other planes",
            "A first-order estimate, δ² = tg²φ Dξ + O(D²), exact to that order (the paper drops the second-order terms before (14): "
            "'відкинувши члени другого порядку малості')",
            f"Monte Carlo with control variates ({mc.controls.samples} samples, the intervals of a plain run of at least {n}; φ = 80°, β0 = γ0 = 0, Gaussian σξ = ση = 1°): "
            f"rms {r.rms * D:.5f}° (95 % CI {r.rms_ci[0] * D:.5f}–{r.rms_ci[1] * D:.5f}°) "
            f"> (15) = {mc.bound15 * D:.5f}°; the fourth-order theory gives {mc.theory.rms * D:.5f}°.",
            "azimuth",
            kind="ambiguous",
            alternatives="Read as a bound on δ, (14)/(15) fail: δ² = tg²φ Dξ [1 + Dη(1 + 3 tg²φ) − κ Dξ (1 + 2 tg²φ)/3] + O(D³), exceeded for equal "
            "Gaussian or sinusoidal rocking at any latitude, and η, against conclusion 2, enters at second order.",
        )
    )
    out.append(
        Erratum(
            "Hrechka & Koroliov, the expression before eq. (16)",
            "α̂*ₙ = arctg [sin φ sin β*₀,ₙ / (cos φ cos γ*₀,ₙ + sin φ cos β*₀,ₙ sin γ*₀,ₙ)]",
            "σ̂*ₙ = arctg [sin φ sin β*₀,ₙ / (cos φ cos γ*₀,ₙ + sin φ cos β*₀,ₙ sin γ*₀,ₙ)]: the estimate of σ that (16) adds to −arctg(f₂/f₁)",
            "The right-hand side is σ = arctg(B/A) of (2) with A*, B* at the sample means, and (16), α̂* = −arctg(f₂/f₁) + σ̂*ₙ, uses σ̂*ₙ, "
            "which is defined nowhere else; read as α̂*ₙ, the azimuth estimate would lack the −arctg(f₂/f₁) term of (2).",
            "azimuth",
            kind="misprint",
        )
    )
    return out
