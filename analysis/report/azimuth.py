"""Report section ``azimuth.md``: gyrocompass azimuth error under random rocking.

Hrechka & Koroliov bound the rms azimuth error of analytical gyrocompassing
on a rocking base by (14) and simplify it to (15).  This section derives both,
carries the expansion one order further, checks the printed intermediate
formulas (5)–(10), and compares everything with Monte Carlo: the distribution
against the bounds, validity maps over latitude and amplitude, the tilt
estimators (16) against a Kalman filter, and the admissible-rocking design
chart.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ..core import montecarlo
from ..gyrocompass.admissible_rocking import admissible_amplitude
from ..gyrocompass.azimuth import AzimuthErrorKernel, azimuth_monte_carlo
from ..gyrocompass.bound_sweep import SweepCase, first_order_alignment_rms, grid_cases, sweep
from ..gyrocompass.rocking import GaussianRocking, NarrowbandRocking, SineRocking
from ..gyrocompass.tilt_estimation import compare_estimators
from . import Erratum, Section

SECTION = Section(
    "azimuth",
    "Gyrocompass azimuth error under random rocking",
    order=50,
    summary="Bounds (14), (15) of Hrechka & Koroliov derived and checked by Monte Carlo; second-order theory; estimators (16) vs Kalman filter; admissible rocking.",
)

D = math.degrees(1.0)
R = math.radians(1.0)

# ---------------------------------------------------------------------------
# Printed formulas of Hrechka & Koroliov, typed from the paper (reference data)
# ---------------------------------------------------------------------------


def _printed():
    from ...derivations.gyrocompass import azimuth_error as g

    phi, b0, g0, xi, eta = g.phi, g.beta0, g.gamma0, g.xi, g.eta
    beta, gamma = sp.symbols("beta gamma", real=True)
    return {
        "A (after (2))": (sp.cos(phi) * sp.sin(gamma) + sp.sin(phi) * sp.cos(beta) * sp.sin(gamma)).subs({beta: b0 + xi, gamma: g0 + eta}),
        "(5)": sp.cos(phi) * sp.cos(g0) + sp.sin(phi) * sp.cos(b0) * sp.sin(g0) - eta * sp.cos(phi) * sp.sin(g0) + sp.sin(phi) * (eta * sp.cos(b0) * sp.cos(g0) - xi * sp.sin(b0) * sp.sin(g0)),
        "(6)": sp.cos(phi) * sp.cos(g0) + sp.sin(phi) * sp.cos(b0) * sp.sin(g0),
        "(7)": eta * (sp.sin(phi) * sp.cos(b0) * sp.cos(g0) - sp.cos(phi) * sp.sin(g0)) - xi * sp.sin(phi) * sp.cos(b0) * sp.sin(g0),
        "(8)": sp.sin(phi) * sp.sin(b0) + xi * sp.sin(phi) * sp.cos(b0),
        "(9)": sp.sin(phi) * sp.sin(b0),
        "(10)": xi * sp.sin(phi) * sp.cos(b0),
    }


def formula_checks() -> list:
    """Each printed formula (5)–(10) against the derivation: symbolic difference and a numeric residual."""
    from ...derivations.gyrocompass import azimuth_error as g

    p = g.linear_parts()
    A1, B1 = g.taylor_components(1)
    derived_A = sum(c * g.xi**i * g.eta**j for (i, j), c in A1.items())
    derived_B = sum(c * g.xi**i * g.eta**j for (i, j), c in B1.items())
    printed = _printed()
    targets = {
        "A (after (2))": (sp.cos(g.phi) * sp.cos(g.gamma0 + g.eta) + sp.sin(g.phi) * sp.cos(g.beta0 + g.xi) * sp.sin(g.gamma0 + g.eta)),
        "(5)": derived_A,
        "(6)": p["A_star"],
        "(7)": p["zeta1"],
        "(8)": derived_B,
        "(9)": p["B_star"],
        "(10)": p["zeta2"],
    }
    rng = np.random.default_rng(0)
    rows = []
    for key, expr in printed.items():
        diff = sp.simplify(sp.expand(expr - targets[key]))
        f = sp.lambdify((g.phi, g.beta0, g.gamma0, g.xi, g.eta), expr - targets[key], modules="numpy")
        pts = rng.uniform(-0.5, 0.5, size=(5, 200))
        pts[0] = rng.uniform(0.1, 1.4, size=200)
        resid = float(np.max(np.abs(np.broadcast_to(f(*pts), (200,)))))
        rows.append({"formula": key, "difference": diff, "residual": resid})
    return rows


# ---------------------------------------------------------------------------
# Monte Carlo cases
# ---------------------------------------------------------------------------


def _seeds(ctx, n):
    return np.random.SeedSequence(ctx.seed, spawn_key=(50,)).spawn(n)


def violation_cases(ctx) -> list:
    """Concrete cases for the violation table (deg in, rad out)."""
    n = 400_000 if ctx.quick else 4_000_000
    specs = [
        ("(15) drops β0, γ0", 70.0, 3.0, -3.0, 2.0, "normal"),
        ("(15) drops β0, γ0", 70.0, 3.0, -3.0, 2.0, "sine"),
        ("second order, zero tilt", 80.0, 0.0, 0.0, 1.0, "normal"),
        ("second order, zero tilt", 60.0, 0.0, 0.0, 3.0, "sine"),
        ("large amplitude", 80.0, 2.0, 2.0, 5.0, "normal"),
        ("large amplitude", 75.0, 0.0, 0.0, 10.0, "sine"),
        ("large amplitude", 45.0, 0.0, 0.0, 10.0, "normal"),
    ]
    out = []
    for seed, (label, lat, b0, g0, s, model) in zip(_seeds(ctx, len(specs)), specs):
        m = GaussianRocking(s * R, s * R) if model == "normal" else SineRocking(s * R, s * R)
        mc = azimuth_monte_carlo(lat * R, b0 * R, g0 * R, m, n, rng=seed)
        out.append(dict(label=label, lat=lat, beta0=b0, gamma0=g0, sigma=s, model=model, mc=mc))
    return out


def small_rocking_cases(ctx) -> list:
    n = 400_000 if ctx.quick else 4_000_000
    specs = [(30.0, 0.0, 0.0, 0.05, "normal"), (60.0, 2.0, 1.0, 0.1, "normal"), (75.0, 1.0, -2.0, 0.1, "sine"), (80.0, 0.0, 0.0, 0.3, "normal"), (80.0, 0.0, 0.0, 0.3, "sine")]
    out = []
    seeds = np.random.SeedSequence(ctx.seed, spawn_key=(51,)).spawn(len(specs))
    for seed, (lat, b0, g0, s, model) in zip(seeds, specs):
        m = GaussianRocking(s * R, s * R) if model == "normal" else SineRocking(s * R, s * R)
        mc = azimuth_monte_carlo(lat * R, b0 * R, g0 * R, m, n, rng=seed)
        out.append(dict(lat=lat, beta0=b0, gamma0=g0, sigma=s, model=model, mc=mc))
    return out


def _fmt(x, digits=4):
    return f"{x:.{digits}g}"


# ---------------------------------------------------------------------------
# Figures
# ---------------------------------------------------------------------------


def _distribution_figure(ctx):
    import matplotlib.pyplot as plt

    n = 200_000 if ctx.quick else 2_000_000
    specs = [(80.0, 0.0, 0.0, 3.0, "normal"), (80.0, 0.0, 0.0, 3.0, "sine"), (70.0, 3.0, -3.0, 2.0, "normal")]
    seeds = np.random.SeedSequence(ctx.seed, spawn_key=(52,)).spawn(len(specs))
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.2))
    for ax, seed, (lat, b0, g0, s, model) in zip(axes, seeds, specs):
        m = GaussianRocking(s * R, s * R) if model == "normal" else SineRocking(s * R, s * R)
        mc = azimuth_monte_carlo(lat * R, b0 * R, g0 * R, m, n, rng=seed)
        edges, counts, _, _ = mc.result.histogram
        k = 40  # merge bins for display
        c = counts[: len(counts) // k * k].reshape(-1, k).sum(axis=1)
        e = edges[:: k][: len(c) + 1] * D
        width = e[1] - e[0]
        ax.bar(e[:-1], c / (c.sum() * width), width=width, align="edge", color="0.7", label="Monte Carlo")
        for value, style, name in ((mc.result.rms, "-", "MC rms"), (mc.bound14, "--", "bound (14)"), (mc.bound15, ":", "bound (15)")):
            ax.axvline(value * D, color="k", ls=style, label=name)
            ax.axvline(-value * D, color="k", ls=style)
        lim = 3.2 * mc.result.rms * D
        ax.set_xlim(-lim, lim)
        ax.set_title(f"{model}, φ={lat:g}°, β0={b0:g}°, γ0={g0:g}°, σ={s:g}°")
        ax.set_xlabel("azimuth error α − α* [deg]")
    axes[0].set_ylabel("density [1/deg]")
    axes[0].legend(loc="upper left")
    ctx.savefig(fig, "figures/azimuth-distribution.png")


def _map_panel(ax, rows, lats, sigmas, key, title):
    import matplotlib.colors as mcolors

    ratio = np.array([r["rms"] / r[key] if r[key] > 0 else np.nan for r in rows]).reshape(len(lats), len(sigmas))
    fails = np.array([r["rms_lo"] > r[key] for r in rows]).reshape(ratio.shape)
    holds = np.array([r["rms_hi"] <= r[key] for r in rows]).reshape(ratio.shape)
    # ±0.3 in log10 is a factor of two either way: the bounds fail by tens of per cent, not decades.
    norm = mcolors.TwoSlopeNorm(vmin=-0.3, vcenter=0.0, vmax=0.3)
    im = ax.pcolormesh(np.arange(len(sigmas) + 1), np.arange(len(lats) + 1), np.clip(np.log10(ratio), -0.3, 0.3), cmap="RdBu_r", norm=norm, shading="flat")
    yy, xx = np.nonzero(fails)
    ax.plot(xx + 0.5, yy + 0.5, "kx", ms=4)
    yy, xx = np.nonzero(holds)
    ax.plot(xx + 0.5, yy + 0.5, "k.", ms=2)
    ax.set_xticks(np.arange(len(sigmas)) + 0.5, [f"{s:g}" for s in sigmas], rotation=90, fontsize=6)
    ax.set_yticks(np.arange(len(lats)) + 0.5, [f"{v:g}" for v in lats], fontsize=6)
    ax.set_title(title, fontsize=8)
    ax.set_xlabel("rocking σ [deg]")
    ax.set_ylabel("latitude [deg]")
    return im, fails, holds


def _label_outer(axes):
    """Keep axis labels on the left column and the bottom row only."""
    for i, row in enumerate(axes):
        for j, ax in enumerate(row):
            if j:
                ax.set_ylabel("")
            if i < len(axes) - 1:
                ax.set_xlabel("")


def _grids(ctx):
    if ctx.quick:
        return np.array([0.0, 20.0, 45.0, 70.0, 80.0]), np.array([0.01, 0.1, 1.0, 3.0, 10.0]), 20_000
    return np.arange(0.0, 81.0, 10.0), np.geomspace(0.01, 10.0, 13).round(4), 200_000


def validity_maps(ctx) -> dict:
    lats, sigmas, n = _grids(ctx)
    groups = {
        "normal, β0=γ0=0": dict(model="normal"),
        "normal, β0=2°, γ0=−2°": dict(model="normal", beta0_deg=2.0, gamma0_deg=-2.0),
        "sine, β0=2°, γ0=−2°": dict(model="sine", beta0_deg=2.0, gamma0_deg=-2.0),
        "narrowband τc=6.4 s, (16) over 30 s": dict(model="narrowband", period=8.0, damping=0.2, estimate="sample-mean", averaging_time=30.0),
        "narrowband τc=64 s, (16) over 30 s": dict(model="narrowband", period=8.0, damping=0.02, estimate="sample-mean", averaging_time=30.0),
    }
    out = {}
    for i, (name, fields) in enumerate(ctx.progress(list(groups.items()), "azimuth maps")):
        cases = grid_cases(lats, sigmas, **fields)
        out[name] = sweep(cases, n_samples=n, rng=np.random.SeedSequence(ctx.seed, spawn_key=(53, i)))
    return {"lats": lats, "sigmas": sigmas, "n": n, "maps": out}


def _validity_figures(ctx, maps):
    import matplotlib.pyplot as plt

    lats, sigmas = maps["lats"], maps["sigmas"]
    known = [k for k in maps["maps"] if "narrowband" not in k]
    fig, axes = plt.subplots(2, len(known), figsize=(3.9 * len(known), 7.0), squeeze=False, layout="constrained")
    im = None
    for j, name in enumerate(known):
        rows = maps["maps"][name]
        im, _, _ = _map_panel(axes[0, j], rows, lats, sigmas, "bound14", f"{name}:\nMC rms / (14)")
        _map_panel(axes[1, j], rows, lats, sigmas, "bound15", f"{name}:\nMC rms / (15)")
    _label_outer(axes)
    fig.colorbar(im, ax=axes, label="log10(MC rms / bound); x: fails (CI above), ·: holds", shrink=0.8)
    ctx.savefig(fig, "figures/azimuth-validity-known.png")
    corr = [k for k in maps["maps"] if "narrowband" in k]
    fig, axes = plt.subplots(2, len(corr), figsize=(4.2 * len(corr), 7.0), squeeze=False, layout="constrained")
    for j, name in enumerate(corr):
        rows = maps["maps"][name]
        for r in rows:
            r["plugin14_sq"] = r["plugin14"]
        im, _, _ = _map_panel(axes[0, j], rows, lats, sigmas, "plugin14", f"{name}:\nrms Δ / (14) with (16) estimates")
        _map_panel(axes[1, j], rows, lats, sigmas, "bound15", f"{name}:\nrms Δ / (15)")
    _label_outer(axes)
    fig.colorbar(im, ax=axes, label="log10(rms alignment error / bound)", shrink=0.8)
    ctx.savefig(fig, "figures/azimuth-validity-correlation.png")


def _estimators(ctx):
    import matplotlib.pyplot as plt

    n_trials = 150 if ctx.quick else 600
    times = np.array([0.1, 0.5, 1.0, 2.0, 4.0, 8.0, 15.0, 30.0, 60.0, 120.0])
    s = 1.0 * R
    models = {"sine (period 8 s)": SineRocking(s, s, 8.0, 8.0), "narrowband (8 s, ζ=0.1)": NarrowbandRocking(s, s, 8.0, 0.1), "normal (white)": GaussianRocking(s, s)}
    seeds = np.random.SeedSequence(ctx.seed, spawn_key=(54,)).spawn(len(models))
    results = {name: compare_estimators(60.0 * R, m, dt=0.1, averaging_times=times, n_trials=n_trials, rng=np.random.default_rng(seed)) for (name, m), seed in zip(models.items(), seeds)}
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
    ctx.savefig(fig, "figures/azimuth-estimators.png")
    return results, times


def _design(ctx):
    import matplotlib.pyplot as plt

    lat, T = 60.0 * R, 60.0
    freqs = np.geomspace(0.02, 1.0, 16 if ctx.quick else 40)
    budgets = (0.05, 0.1, 0.5)
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6))
    curves = {}
    for ax, kind in zip(axes, ("narrowband", "sine")):
        for b in budgets:
            d = admissible_amplitude(b * R, lat, T, freqs, rocking=kind, damping=0.1)
            curves[(kind, b)] = d
            ax.loglog(freqs, d["amplitude"] * D, label=f"budget {b:g}°")
        ax.set_xlabel("rocking frequency [Hz]")
        ax.set_ylabel("admissible amplitude [deg]")
        ax.set_title(f"{kind}: φ = 60°, T = {T:g} s, 10 Hz" + (", ζ = 0.1" if kind == "narrowband" else ""))
        ax.legend()
    # Monte Carlo check of the chart: at a_max the rms alignment error should equal the budget
    checks = []
    n_trials = 400 if ctx.quick else 3000
    pick = [0, len(freqs) // 2, len(freqs) - 1]
    seeds = np.random.SeedSequence(ctx.seed, spawn_key=(55,)).spawn(len(pick))
    d = curves[("narrowband", 0.1)]
    for seed, i in zip(seeds, pick):
        a = float(d["amplitude"][i])
        m = NarrowbandRocking(a / math.sqrt(2), a / math.sqrt(2), 1.0 / freqs[i], 0.1)
        kernel = AzimuthErrorKernel(lat, 0.0, 0.0, m, n_steps=int(d["samples"]), dt=0.1, estimate="sample-mean")
        r = montecarlo.run(kernel, n_trials, rng=seed, trials_per_block=50, scale=0.1 * R)
        checks.append((freqs[i], a, r))
        axes[0].plot(freqs[i], a * D, "ko", ms=4)
    ctx.savefig(fig, "figures/azimuth-design.png")
    return curves, checks, freqs


# ---------------------------------------------------------------------------
# Build
# ---------------------------------------------------------------------------


def _latex(expr) -> str:
    return sp.latex(expr).replace("varphi", "varphi")


def build(ctx) -> None:
    from ...derivations.gyrocompass import azimuth_error as g

    p = g.linear_parts()
    mse0 = sp.factor(sp.simplify(g.mse_fourth_order().subs({g.beta0: 0, g.gamma0: 0})))
    checks = formula_checks()
    lines = [
        f"# {SECTION.title}",
        "",
        "Source: Hrechka & Koroliov, eqs. (2), (4)–(16). The azimuth error on a rocking base is",
        "$\\alpha - \\alpha^* = \\sigma(\\beta_0+\\xi, \\gamma_0+\\eta) - \\sigma(\\beta_0, \\gamma_0)$ with",
        "$\\sigma = \\arctan(B/A)$, $A = \\cos\\varphi\\cos\\gamma + \\sin\\varphi\\cos\\beta\\sin\\gamma$, $B = \\sin\\varphi\\sin\\beta$.",
        "The package evaluates it as the angle of $(A + iB)/(A^* + iB^*)$ (the arctangent difference for $A, A^* > 0$,",
        "the wrapped angle otherwise). ξ and η are independent and zero-mean; $\\sigma_\\xi, \\sigma_\\eta$ are their standard",
        "deviations (a sinusoid has amplitude $\\sigma\\sqrt{2}$).",
        "",
        "## 1. Derivation (SymPy, `derivations/gyrocompass.py`)",
        "",
        f"- $A^* = {_latex(p['A_star'])}$ (6), $B^* = {_latex(p['B_star'])}$ (9)",
        f"- $\\zeta_1 = {_latex(p['zeta1'])}$ (7)",
        f"- $\\zeta_2 = {_latex(p['zeta2'])}$ (10)",
        "- Bound (14): $\\delta^2 \\le (B^*/A^{*2})^2 D\\zeta_1 + 2|B^*/A^{*3}|\\sqrt{D\\zeta_1 D\\zeta_2} + D\\zeta_2/A^{*2}$; at $\\beta_0=\\gamma_0=0$ it reduces",
        "  symbolically to (15), $\\delta^2 \\le \\tan^2\\varphi\\, D\\xi$ (checked by `sympy.simplify`, difference 0).",
        "- Exact first-order error: $L = (A^*\\zeta_2 - B^*\\zeta_1)/(A^{*2} + B^{*2})$. (14) bounds $E L^2$ (|arctan x − arctan y| ≤ |x − y| and",
        "  Cauchy–Schwarz), but only to first order: it is not a bound on $\\delta$ itself.",
        "- **Beyond the paper**: the series of $\\sigma - \\sigma^*$ to third order (as $\\mathrm{Im}\\log(1+w)$), the second-order bias",
        "  $E(\\sigma-\\sigma^*)$ and the mean square to fourth order, with $E\\xi^4 = \\kappa D\\xi^2$ (κ = 3 Gaussian, 3/2 sinusoid).",
        "  At zero stable tilt the bias vanishes and",
        "",
        f"  $$E(\\sigma-\\sigma^*)^2 = {_latex(mse0)} + O(D^3)$$",
        "",
        "  i.e. $\\tan^2\\varphi\\,D\\xi\\,[1 + D\\eta(1 + 3\\tan^2\\varphi) - \\kappa_\\xi D\\xi(1 + 2\\tan^2\\varphi)/3]$: the rocking η *does* enter at second",
        "  order (against conclusion 2 of the paper), and whenever the bracket exceeds 1 — for equal Gaussian or sinusoidal",
        "  rocking at any latitude — (15) and (14) are violated.",
        "",
        "### Printed formulas (5)–(10) against the derivation",
        "",
        "| Formula | printed − derived | max residual on 200 random points |",
        "|---|---|---|",
    ]
    for row in checks:
        diff = "0" if row["difference"] == 0 else f"${_latex(row['difference'])}$"
        lines.append(f"| {row['formula']} | {diff} | {row['residual']:.2e} |")
    lines += [
        "",
        "(5) and (8) are compared to first order (their O(ξ², η²) remainders dropped); the residual of `A (after (2))`",
        "is the full function. See [errata](errata.md).",
        "",
    ]

    # --- violations
    viol = violation_cases(ctx)
    lines += [
        "## 2. Where the bounds fail: concrete cases",
        "",
        f"Monte Carlo at independent instants, {viol[0]['mc'].result.n_samples} samples each, 95 % CI from the batch-means",
        "standard error. 'fails' means the whole CI lies above the bound.",
        "",
        "| Case | rocking | φ [°] | β0, γ0 [°] | σ [°] | MC rms [°] (95 % CI) | (14) [°] | (15) [°] | 2nd-order theory [°] | (14) | (15) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for v in viol:
        mc = v["mc"]
        r = mc.result
        lines.append(
            f"| {v['label']} | {v['model']} | {v['lat']:g} | {v['beta0']:g}, {v['gamma0']:g} | {v['sigma']:g} | {_fmt(r.rms * D, 5)} ({_fmt(r.rms_ci[0] * D, 5)}–{_fmt(r.rms_ci[1] * D, 5)}) "
            f"| {_fmt(mc.bound14 * D, 5)} | {_fmt(mc.bound15 * D, 5)} | {_fmt(mc.theory['rms'] * D, 5)} | {r.covers(mc.bound14)} | {r.covers(mc.bound15)} |"
        )
    lines += [
        "",
        "![MC distribution against the bounds](figures/azimuth-distribution.png)",
        "",
    ]
    _distribution_figure(ctx)

    # --- small rocking agreement
    small = small_rocking_cases(ctx)
    lines += [
        "## 3. Small rocking: Monte Carlo against the second-order theory",
        "",
        "| rocking | φ [°] | β0, γ0 [°] | σ [°] | MC rms [°] (95 % CI) | theory rms [°] | inside CI | MC mean [°] (95 % CI) | theory bias [°] |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for v in small:
        mc = v["mc"]
        r = mc.result
        inside = "yes" if r.rms_ci[0] <= mc.theory["rms"] <= r.rms_ci[1] else "no"
        lines.append(
            f"| {v['model']} | {v['lat']:g} | {v['beta0']:g}, {v['gamma0']:g} | {v['sigma']:g} | {r.rms * D:.6g} ({r.rms_ci[0] * D:.6g}–{r.rms_ci[1] * D:.6g}) | {mc.theory['rms'] * D:.6g} | {inside} "
            f"| {r.mean * D:.3g} ({r.mean_ci[0] * D:.3g}–{r.mean_ci[1] * D:.3g}) | {mc.theory['bias'] * D:.3g} |"
        )
    lines.append("")

    # --- validity maps
    maps = validity_maps(ctx)
    _validity_figures(ctx, maps)
    lines += [
        "## 4. Validity maps",
        "",
        f"Latitude × rocking standard deviation (both axes equal), {maps['n']} samples per cell. Colour: log10(MC rms / bound);",
        "x: the bound fails (CI entirely above it), dot: it holds (CI entirely below), blank: undecided.",
        "",
        "![validity maps, known stable tilts](figures/azimuth-validity-known.png)",
        "",
        "| Map | cells | (14) holds | (14) fails | (15) holds | (15) fails | worst MC rms / (14) | worst MC rms / (15) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, rows in maps["maps"].items():
        k14 = "plugin14" if "narrowband" in name else "bound14"
        c = len(rows)
        h14 = sum(r["rms_hi"] <= r[k14] for r in rows)
        f14 = sum(r["rms_lo"] > r[k14] for r in rows)
        h15 = sum(r["rms_hi"] <= r["bound15"] for r in rows)
        f15 = sum(r["rms_lo"] > r["bound15"] for r in rows)
        w14 = max((r["rms"] / r[k14] for r in rows if r[k14] > 0), default=float("nan"))
        w15 = max((r["rms"] / r["bound15"] for r in rows if r["bound15"] > 0), default=float("nan"))
        lines.append(f"| {name} | {c} | {h14} | {f14} | {h15} | {f15} | {w14:.3g} | {w15:.3g} |")
    lines += [
        "",
        "Coverage of a bound = fraction of cells where it holds. At latitude 0° error and bounds are exactly zero (holds with",
        "equality). Each cell is a 95 % decision, so where a bound is tight (zero stable tilt, small rocking) about 2.5 % of",
        "cells are flagged 'fails' by chance; the systematic failures are the blocks at large rocking and high latitude, and",
        "the whole (15) map once the stable tilts are not zero. For the narrow-band maps the error is the alignment error Δ = σ(β̂0, γ̂0) − σ(β0, γ0) of the sample",
        "means (16) over 30 s at 10 Hz, compared with (14) evaluated with the estimates of (16) as the paper prescribes,",
        "and with (15) at the true variance. The variance of a 30 s mean is about $4\\zeta\\sigma^2/(\\omega_0 T)$ (the spectral density",
        "at zero frequency grows with the damping ζ), so the strongly damped, short-correlation rocking (τc = 6.4 s) leaves",
        "more of itself in the means than the nearly periodic τc = 64 s rocking of the same period.",
        "",
        "![validity maps, correlated rocking](figures/azimuth-validity-correlation.png)",
        "",
    ]
    nb = maps["maps"]["narrowband τc=64 s, (16) over 30 s"]
    r0 = next(r for r in nb if r["latitude_deg"] == maps["lats"][len(maps["lats"]) // 2] and r["sigma_deg"] == maps["sigmas"][len(maps["sigmas"]) // 2])
    case = SweepCase(**{k: r0[k] for k in SweepCase.__dataclass_fields__})
    lines += [
        f"Check of one narrow-band cell (φ = {r0['latitude_deg']:g}°, σ = {r0['sigma_deg']:g}°, τc = 64 s): MC rms Δ = {r0['rms'] * D:.4g}° "
        f"(CI {r0['rms_lo'] * D:.4g}–{r0['rms_hi'] * D:.4g}), first-order theory with the variance factor of the mean "
        f"{first_order_alignment_rms(case) * D:.4g}°, second-order theory {r0['theory_rms'] * D:.4g}°.",
        "",
    ]

    # --- estimators
    results, times = _estimators(ctx)
    lines += [
        "## 5. Estimating β0, γ0: sample mean (16) against a Kalman filter",
        "",
        "The Kalman filter (filterpy, through `analysis/kalman.py`) estimates $(\\beta_0, \\xi, \\dot\\xi)$ per axis with the",
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
    lines += [
        "",
        "The filter helps most for a sinusoid (three unknowns, no process noise); for narrow-band rocking it gains at short",
        "times and both converge to the same rate later (the sample mean is asymptotically efficient for a constant in",
        "noise with a continuous spectrum at zero frequency); for white rocking the two coincide.",
        "",
        "![estimators](figures/azimuth-estimators.png)",
        "",
    ]

    # --- design
    curves, mc_checks, freqs = _design(ctx)
    lines += [
        "## 6. Admissible rocking (conclusion 4 of the paper)",
        "",
        "Largest rocking amplitude against frequency such that the rms alignment error of the estimate (16) over T = 60 s",
        "stays within the budget, at latitude 60° (`analysis/azimuth_design.py`, second-order theory with the variance factor",
        "of the mean). Sine rocking is admissible without limit where T holds a whole number of periods (the chart is capped",
        "at 20°); narrow-band rocking gives a smooth limit that grows with frequency.",
        "",
        "![design chart](figures/azimuth-design.png)",
        "",
        "Monte Carlo check of the narrow-band 0.1° curve (dots in the chart):",
        "",
        "| f [Hz] | admissible amplitude [°] | MC rms Δ [°] (95 % CI) |",
        "|---|---|---|",
    ]
    for f, a, r in mc_checks:
        lines.append(f"| {f:.4g} | {a * D:.4g} | {r.rms * D:.4g} ({r.rms_ci[0] * D:.4g}–{r.rms_ci[1] * D:.4g}) |")
    d = curves[("narrowband", 0.1)]
    lines += [
        "",
        "| f [Hz] | " + " | ".join(f"{f:.3g}" for f in d["frequency"][:: max(1, len(freqs) // 8)]) + " |",
        "|---|" + "---|" * len(d["frequency"][:: max(1, len(freqs) // 8)]),
        "| a_max [°], budget 0.1° | " + " | ".join(f"{a * D:.3g}" for a in d["amplitude"][:: max(1, len(freqs) // 8)]) + " |",
        "",
        f"Mode: {'quick' if ctx.quick else 'full'}; root seed {ctx.seed}.",
    ]
    ctx.write_text("azimuth.md", "\n".join(lines))


def errata(ctx) -> list:
    from ...derivations.gyrocompass import azimuth_error as g

    rows = {r["formula"]: r for r in formula_checks()}
    p = g.linear_parts()
    out = [
        Erratum(
            "Hrechka & Koroliov, definition of A after eq. (2)",
            "A = cos φ sin γ + sin φ cos β sin γ",
            "A = cos φ cos γ + sin φ cos β sin γ",
            f"The printed A differs from the paper's own expansion (5)–(6) by up to {rows['A (after (2))']['residual']:.2f} on random points "
            f"(printed (5), (6) agree with the cos γ form to {max(rows['(5)']['residual'], rows['(6)']['residual']):.1e}); with sin γ, A = 0 at zero tilt and σ would be undefined.",
            "azimuth",
        ),
        Erratum(
            "Hrechka & Koroliov, eq. (7), ξ term of ζ1",
            "− ξ sin φ cos β0 sin γ0",
            "− ξ sin φ sin β0 sin γ0 (as in (5): ∂A/∂β = −sin φ sin β sin γ)",
            f"SymPy: printed (7) − derived = ${sp.latex(rows['(7)']['difference'])}$, max residual {rows['(7)']['residual']:.2f} on random points; "
            f"the derived ζ1 = ${sp.latex(p['zeta1'])}$ also equals the first-order part of the printed (5) (residual {rows['(5)']['residual']:.1e}).",
            "azimuth",
        ),
    ]
    lat, s = 80.0 * R, 1.0 * R
    n = 400_000 if ctx.quick else 4_000_000
    mc = azimuth_monte_carlo(lat, 0.0, 0.0, GaussianRocking(s, s), n, rng=np.random.SeedSequence(ctx.seed, spawn_key=(56,)))
    r = mc.result
    out.append(
        Erratum(
            "Hrechka & Koroliov, eq. (15) and conclusion 2",
            "δ ≤ tg φ √Dξ, practically independent of the rocking in other planes",
            "δ² = tg²φ Dξ [1 + Dη(1 + 3 tg²φ) − κ Dξ (1 + 2 tg²φ)/3] + O(D³): (14)/(15) hold only to first order, and η enters at second order",
            f"Monte Carlo ({r.n_samples} samples, φ = 80°, β0 = γ0 = 0, Gaussian σξ = ση = 1°): rms {r.rms * D:.5f}° "
            f"(95 % CI {r.rms_ci[0] * D:.5f}–{r.rms_ci[1] * D:.5f}°) > (15) = {mc.bound15 * D:.5f}°; the fourth-order theory gives {mc.theory['rms'] * D:.5f}°.",
            "azimuth",
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
