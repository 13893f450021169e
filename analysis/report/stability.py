"""Report section ``stability.md``: corrected multistage attitude stages (Plotnikov 1999).

Formatting only: every number and curve comes from
:mod:`strapdown.analysis.multistage` and :mod:`strapdown.derivations.multistage`;
the paper's printed values come from
:mod:`strapdown.derivations.multistage.published`.
"""

from __future__ import annotations

import numpy as np

from ...derivations.multistage.published import PAPER, PRINTED_GAINS, SECTION5
from ..core import units
from . import Erratum, Section
from .rendering import at_round_off, fixed_layout

SECTION = Section(
    "stability",
    "Corrected multistage attitude stages: stability, Schuler tuning, simulation",
    order=40,
    summary=(
        "Lyapunov and LaSalle argument, linearisation and Schuler transfer function, poles and responses (python-control), gain design and "
        "Schuler error budget, the section-5 simulation of Plotnikov (1999) on a consistent truth model with its readings, the yaw through the "
        "composition, sensor-error statistics."
    ),
)


def _latex(expr) -> str:
    import sympy as sp

    return sp.latex(expr)


def _e(x, digits: int = 3) -> str:
    return f"{x:.{digits}e}" if np.isfinite(x) else "—"


def _g(x, digits: int = 3) -> str:
    return f"{x:.{digits}g}" if np.isfinite(x) else "—"


_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _times_ten(x: float) -> str:
    """A number the way the paper prints it: 1.24·10⁻³, 10⁻³, −3·10⁻²."""
    mantissa, exponent = f"{abs(x):.9e}".split("e")
    power = f"10{str(int(exponent)).translate(_SUPERSCRIPT)}"
    m = float(mantissa)
    return ("−" if x < 0 else "") + (power if m == 1.0 else f"{m:.9g}·{power}")


def _table(header, rows) -> list:
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return out + [""]


#: Streams of the section, children of the report seed: the default run, the readings, the yaw study,
#: the sensor-error Monte Carlo, the printed-formula checks (the rest unused).
SEED_STREAMS = 8
_READINGS_STREAM, _FORMULA_STREAM = 1, 4


def _seeds(ctx) -> list:
    return np.random.SeedSequence(ctx.seed).spawn(SEED_STREAMS)


class _Run:
    """What the section computes once and several parts show."""

    def __init__(self, ctx):
        from ..multistage.stages import simulate
        from ..multistage.trajectory import Scenario

        self.ctx = ctx
        self.seeds = _seeds(ctx)
        self.scenario = Scenario()
        self.step = 0.2 if ctx.quick else 0.04
        self.result = simulate(self.scenario, step=self.step, rng=self.seeds[0])
        self.peaks = self.result.peaks()


# ---------------------------------------------------------------------------
# 1. Lyapunov
# ---------------------------------------------------------------------------
def _lyapunov(ctx) -> list:
    from ...derivations.multistage.lyapunov_function import derive
    from ..core.cache import derived
    from ..multistage.decay_rates import rate_checks

    ly = derived("multistage:lyapunov:v1", derive)
    lines = [
        "## 1. Lyapunov analysis of the first variant (c = 1, exact reference)",
        "",
        "With $\\nu = \\mu + z$ and $y = l\\int z\\,d\\tau$, (1.5) gives the perturbation equations (3.1)",
        "$2\\dot z = z\\circ\\omega - kz - y$, $\\dot y = lz$ (ω pure, the body rate). SymPy quaternion algebra",
        "(`derivations/multistage/lyapunov_function.py`) builds (3.2) and differentiates it along (3.1):",
        "",
        f"$$V = l\\,z\\circ\\bar z + \\frac{{1}}{{2}}\\,y\\circ\\bar y = {_latex(ly.V)}$$",
        "",
        f"$$\\dot V = {_latex(ly.Vdot)}$$",
        "",
        f"Exact symbolic equality with $-lk\\,z\\circ\\bar z$ of (3.4): **{ly.vdot_matches}** (the vector parts of",
        f"$z\\circ\\bar z$, $y\\circ\\bar y$ vanish identically: {ly.vector_part_zero}). The body-rate terms cancel",
        "because $z\\circ(\\omega+\\bar\\omega)\\circ\\bar z = 0$ for a pure ω.",
        "",
        "**What this proves.** $\\dot V$ does not contain $y$, so it is only negative *semi*definite: by",
        "Lyapunov's theorem the motion $\\nu = \\mu$ is stable, and $z \\to 0$ in $L^2$, but (3.4) alone does",
        "not give asymptotic stability as the paper states. Two complete arguments:",
        "",
        "* *LaSalle (ω constant, autonomous system).* On the set $\\dot V = 0$, i.e. $z \\equiv 0$, equation (3.1) gives",
        f"  $\\dot z = ({', '.join(_latex(c) for c in ly.lasalle_zdot)})$, which vanishes only if $y = 0$. The largest",
        "  invariant set in $\\{\\dot V = 0\\}$ is the origin, so every solution tends to it; the system being",
        "  linear, the convergence is exponential.",
        "* *Strict Lyapunov function (any bounded $\\omega(t)$, $|\\omega| \\le \\varpi$).* $W = V + \\varepsilon\\,z\\cdot y$ has, exactly",
        f"  (verified symbolically: {ly.wdot_matches}),",
        "",
        f"$$\\dot W = {_latex(ly.Wdot_structure)}$$",
        "",
        "  With $|y\\cdot(z\\circ\\omega)| \\le \\varpi|y||z|$ the quadratic form $-\\dot W$ dominates",
        "  $\\xi^T M \\xi$, $\\xi = (|z|, |y|)$, $\\xi^T M \\xi = l(k-\\varepsilon)|z|^2 - \\frac{\\varepsilon(k+\\varpi)}{2}|z||y| + \\frac{\\varepsilon}{2}|y|^2$,",
        f"  positive definite for $\\varepsilon < {_latex(ly.eps_max)}$; $W > 0$ needs $\\varepsilon^2 < 2l$. Then",
        "  $\\dot W \\le -\\gamma W$ with γ the smallest generalised eigenvalue of $(M, P_+)$, $\\xi^T P_+ \\xi = l|z|^2 + \\varepsilon|z||y| + \\frac{1}{2}|y|^2$:",
        "  uniform exponential stability, $|x(t)| \\le C e^{-\\gamma t/2}|x(0)|$.",
        "",
        "**Rate at rest.** For ω = 0 the characteristic polynomial of the 8-dimensional system is",
        f"${_latex(ly.charpoly_rest)}$, so the rate is $-\\max\\operatorname{{Re}} s$ over $s = {', '.join(_latex(x) for x in ly.rate_roots)}$:",
        "$k/4$ when $k^2 < 8l$, $(k - \\sqrt{k^2-8l})/4$ otherwise. A body rate slows the decay (for $|\\omega| \\gg k$ the slow",
        "rate tends to $lk/(k^2+|\\omega|^2)$): the integral correction is stored in non-rotating components.",
        "",
        "Check against simulation (stage 1 fed with the exact attitude, ρ = 0, body turning at a constant ω;",
        "rate = half the slope of log V fitted over the second half of the run):",
        "",
    ]
    k1, l1 = PRINTED_GAINS.stage1
    cases = [(k1, l1, (0.0, 0.0, 0.0)), (k1, l1, (0.0, 0.01, 0.0)), (0.05, 1e-4, (0.01, 0.0, 0.02))]
    checks = rate_checks(cases[1:2] if ctx.quick else cases)
    rows = [(f"{c.k:g}", f"{c.l:g}", "(" + ", ".join(f"{w:g}" for w in c.omega) + ")", f"{c.rest:.4e}", f"{c.exact:.4e}", f"{c.simulated:.4e}", f"{c.guaranteed:.4e}") for c in checks]
    lines += _table(("k [1/s]", "l [1/s²]", "ω [rad/s]", "rest rate (roots)", "exact rate (eigenvalues)", "simulated", "strict-W guarantee"), rows)
    return lines + [
        "The simulated rate matches the eigenvalues (the small difference at rest is the ripple of the",
        "oscillatory pair in log V), and the strict-Lyapunov guarantee is always below it, as it must be.",
        "",
    ]


# ---------------------------------------------------------------------------
# 2. Linearisation and Schuler tuning
# ---------------------------------------------------------------------------
def _linearisation(g, r) -> list:
    from ...derivations.multistage.schuler import derive
    from ..core.cache import derived
    from ..multistage.readings import schuler_detuning

    sch = derived("multistage:schuler:v1", derive)
    lines = [
        "## 2. Linearisation and Schuler tuning",
        "",
        "`derivations/multistage/schuler.py` writes the second stage (2.1) with ρ⁽¹⁾ = 0 in quaternions: the frame η⁽¹⁾ of",
        "stage 1 is turned from η by the small errors (α, β, χ); its rate is $\\bar\\Delta\\circ\\omega_\\eta\\circ\\Delta + 2\\bar\\Delta\\circ\\dot\\Delta$;",
        "the specific force is re-projected, $W^{(1)} = \\bar\\Delta\\circ W\\circ\\Delta$, and enters by (1.4); $\\nu_1$ is (3.6). A",
        "first-order Taylor expansion in the small quantities (angles, rates, y), with the load factors",
        "$n = W/g$ kept as they are, gives (3.7)–(3.8) — nothing typed in:",
        "",
        f"$$W^{{(1)}}_1 = {_latex(sch.W1[0])},\\quad W^{{(1)}}_3 = {_latex(sch.W1[2])}$$",
        "",
        f"$$\\omega_{{\\eta}}^{{(1)}} = ({', '.join(_latex(c) for c in sch.frame_rate)})$$",
        "",
    ]
    names = {"psi1": "\\dot\\psi_1^+", "theta1": "\\dot\\theta_1^+", "gamma1": "\\dot\\gamma_1^+", "y1": "\\dot y_1", "y3": "\\dot y_3"}
    for key, name in names.items():
        lines += [f"$${name} = {_latex(sch.rates[key])}$$", ""]
    lines += [
        "These are (3.8) with $y = l\\int(\\dots)d\\tau$. The derivation gives $W^{(1)}_3 = W_3 - g\\alpha + W_1\\beta$; the paper prints",
        "$-W_1\\beta$ (its own $M_{11} = \\alpha - n_3 - n_1\\beta$ agrees with the derivation, see the errata).",
        "",
        "With $\\dot V_1 = W_1$, $\\omega_3 = -V_1/R$ and the error $e = \\theta_1^+ - \\chi$, the Laplace transform (zero initial",
        "conditions) gives the transfer function from the horizontal acceleration to the tilt error:",
        "",
        f"$$\\frac{{E(s)}}{{A(s)}} = {_latex(sch.tf_accel)},\\qquad \\frac{{E(s)}}{{V(s)}} = {_latex(sch.tf_velocity)}$$",
        "",
        f"(roll channel: ${_latex(sch.tf_accel_roll)}$). The stage-1 error χ cancels: the second stage's",
        "total error does not depend on the first stage's, which is the mechanism behind (3.12)–(3.20). At $k = 0$,",
        f"$l = g/R$ the transfer function simplifies to **{sch.schuler_residual}** exactly (3.11); it is nonzero for",
        "any other gains, e.g.:",
        "",
    ]
    rows = [(f"{s.k:g}", f"{s.l:.6g}", f"{s.dc_gain:.4g}", f"{s.peak:.4g}") for s in schuler_detuning(g, r)]
    heading = f"peak tilt error, {SECTION5.accel:g} m/s² for {SECTION5.accel_duration:g} s [rad]"
    return lines + _table(("k [1/s]", "l [1/s²]", "E/A at s = 0 [rad per m/s²]", heading), rows)


# ---------------------------------------------------------------------------
# 3. python-control
# ---------------------------------------------------------------------------
def _loops_section(ctx, g, r, schuler_frequency) -> list:
    from ..multistage.readings import section5_loops
    from ..multistage.tilt_loop import complementary_filter

    loops = section5_loops(g, r)
    lines = [
        "## 3. The stage loop with python-control",
        "",
        "Linearised tilt channel: $\\dot e = -ke + y + d + k\\delta$, $\\dot y = -le + l\\delta$ (d: rate disturbance, δ: error of",
        "the accelerometer tilt), characteristic polynomial $s^2 + ks + l$. Stage 1 of section 5 uses the",
        "tilt quaternion (1.10) of half angles with c = 1, so it acts with $K = k/2$, $L = l/2$; the (1.4) stage with",
        "c = 2 acts with k, l. Poles, damping and natural frequency from `sys.poles()` and `control.damp`:",
        "",
    ]
    rows = []
    for named in loops:
        loop = named.loop
        wn, zeta, p = loop.damp()
        poles = ", ".join(f"{z.real:.3g}{z.imag:+.3g}j" for z in p)
        peak = loop.peak_tilt_error(SECTION5.accel, SECTION5.accel_duration)
        rows.append((named.label, f"{loop.k:g}", f"{loop.l:.4g}", poles, ", ".join(_g(z + 0.0) for z in zeta), ", ".join(_g(x) for x in wn), loop.stability, f"{peak:.4g}"))
    lines += _table(("loop", "K [1/s]", "L [1/s²]", "poles [1/s]", "ζ", "ω_n [rad/s]", "stability", f"peak tilt error, {SECTION5.accel:g} m/s² × {SECTION5.accel_duration:g} s [rad]"), rows)
    filt = complementary_filter(loops[2].loop, np.logspace(-5, 0, 200))
    lines += [
        "Schuler tuning is *marginally* stable (poles $\\pm i\\sqrt{g/R}$): errors present when the gains switch",
        "persist as undamped oscillations with the Schuler period, and slowly varying disturbances are not",
        "rejected (section 5 below). With the printed $l^{(1)} = 1.24\\cdot10^{-3}$ s⁻² (the Schuler *frequency*, not its square)",
        "the loop is far from Schuler tuning. Gains that make the loop unstable are refused by `strapdown stability`",
        "(the peak tilt error is unbounded).",
        "",
        "![Poles and root loci](figures/stability-root-locus.png)",
        "",
        "![Step and impulse responses](figures/stability-responses.png)",
        "",
        "![Bode plots: the stage as a complementary filter](figures/stability-bode.png)",
        "",
        "The Bode plots show the complementary filter: the gyro-integrated attitude passes through the high-pass",
        "$H_g = s^2/(s^2+ks+l)$, the accelerometer tilt through the low-pass $H_a = (ks+l)/(s^2+ks+l)$,",
        f"$H_g + H_a = 1$ (checked on the frequency grid: difference {at_round_off(filt.max_sum_error)}).",
        "",
    ]
    _root_locus_figure(ctx, loops, g, r)
    _responses_figure(ctx, loops)
    _bode_figure(ctx, loops, schuler_frequency)
    return lines


def _root_locus_figure(ctx, loops, g, r) -> None:
    import matplotlib.pyplot as plt

    from ..multistage.tilt_loop import StageLoop, root_locus_k, root_locus_l

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    ks = np.concatenate([[0.0], np.logspace(-4, -0.5, 120)])
    for l, col in [(PRINTED_GAINS.stage1[1], "C0"), (PRINTED_GAINS.stage2_before[1], "C1"), (StageLoop.schuler(g, r).l, "C2")]:
        loci = root_locus_k(l, ks).loci
        axes[0].plot(loci.real.ravel(), loci.imag.ravel(), ".", ms=2, color=col, label=f"l = {l:.3g} s⁻², k from 0 to 0.3")
    ls = np.concatenate([[0.0], np.logspace(-7, -3, 120)])
    for k, col in [(PRINTED_GAINS.stage1[0], "C3"), (PRINTED_GAINS.stage2_before[0], "C4")]:
        loci = root_locus_l(k, ls).loci
        axes[1].plot(loci.real.ravel(), loci.imag.ravel(), ".", ms=2, color=col, label=f"k = {k:g} s⁻¹, l from 0 to 1e-3")
    for named in loops:
        p = named.loop.poles()
        for ax in axes:
            ax.plot(p.real, p.imag, "x", ms=7, mew=1.5, color="k")
    axes[0].set_title("root locus over k (× : poles of the section-5 loops)")
    axes[1].set_title("root locus over l")
    for ax in axes:
        ax.set_xlabel("Re s [1/s]")
        ax.set_ylabel("Im s [1/s]")
        ax.legend(loc="lower left")
        ax.xaxis.set_major_locator(plt.MaxNLocator(5))
    axes[0].set_xlim(-0.03, 0.002)
    axes[0].set_ylim(-0.015, 0.015)
    axes[1].set_xlim(-0.02, 0.002)
    axes[1].set_ylim(-0.03, 0.03)
    fixed_layout(fig, left=0.85, right=0.15, bottom=0.5, top=0.3, wgap=0.85)
    ctx.savefig(fig, "figures/stability-root-locus.png")


def _responses_figure(ctx, loops) -> None:
    import matplotlib.pyplot as plt

    from ..multistage.tilt_loop import responses

    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    t = np.linspace(0.0, 3000.0, 1501)
    for named in (loops[0], loops[2], loops[3]):
        resp = responses(named.loop, t)
        axes[0].plot(t, resp.accel_step, label=named.label)
        axes[1].plot(t, resp.accel_impulse, label=named.label)
        axes[2].plot(t, resp.drift_step, label=named.label)
    axes[0].set_title("tilt error, acceleration step\n[rad per m/s²]")
    axes[1].set_title("tilt error, acceleration impulse\n[rad per m/s]")
    axes[2].set_title("tilt error, drift step\n[rad per rad/s]")
    for ax in axes:
        ax.set_xlabel("t [s]")
    axes[0].legend(fontsize=6)
    fixed_layout(fig, left=0.6, right=0.15, bottom=0.5, top=0.5, wgap=0.75)
    ctx.savefig(fig, "figures/stability-responses.png")


def _bode_figure(ctx, loops, schuler_frequency) -> None:
    import matplotlib.pyplot as plt

    from ..multistage.tilt_loop import complementary_filter

    fig, axes = plt.subplots(2, 1, figsize=(7, 5.5), sharex=True)
    omega = np.logspace(-5, 0, 400)
    for named in (loops[0], loops[2]):
        f = complementary_filter(named.loop, omega)
        short = named.label.split(" (")[0]
        line = axes[0].loglog(f.omega, f.gyro_magnitude, "-", label=f"gyro high-pass H_g, {short}")[0]
        axes[1].semilogx(f.omega, units.deg(f.gyro_phase), "-", color=line.get_color())
        axes[0].loglog(f.omega, f.accel_magnitude, "--", color=line.get_color(), label=f"accelerometer low-pass H_a, {short}")
        axes[1].semilogx(f.omega, units.deg(f.accel_phase), "--", color=line.get_color())
    axes[0].axvline(schuler_frequency, color="0.5", lw=0.8)
    axes[0].set_ylim(1e-4, 3)
    axes[0].set_ylabel("|H|")
    axes[1].set_ylabel("phase [deg]")
    axes[1].set_xlabel("ω [rad/s] (grey: Schuler frequency)")
    axes[0].legend(fontsize=6)
    fixed_layout(fig, left=0.8, right=0.15, bottom=0.5, top=0.15, hgap=0.15)
    ctx.savefig(fig, "figures/stability-bode.png")


# ---------------------------------------------------------------------------
# 4. Gain design and the Schuler error budget
# ---------------------------------------------------------------------------
def _design(ctx, run) -> list:
    from ..multistage import gain_design as gd

    rows = []
    for ref in ("pure", "tilt"):
        for wn, zeta in ((5e-3, 0.7), (1.2e-2, 0.7)):
            gains = gd.design_gains(wn, zeta, reference=ref)
            wn_c, zeta_c, _ = gains.loop().damp()
            rows.append((ref, f"{wn:g}", f"{zeta:g}", f"{gains.c:g}", f"{gains.k:.5g}", f"{gains.l:.5g}", f"{wn_c[0]:.5g}", f"{zeta_c[0]:.4g}"))
    for ref in ("pure", "tilt"):
        gains = gd.schuler_gains(run.scenario.gravity, run.scenario.earth_radius, reference=ref)
        rows.append((ref, "Schuler", "0", f"{gains.c:g}", f"{gains.k:.5g}", f"{gains.l:.5g}", f"{gains.natural_frequency:.5g}", f"{gains.damping:.4g}"))
    budget = gd.schuler_error_budget((1e-7, 2e-8, -1e-7), (1e-3, 0.0, -2e-3))
    check = gd.check_error_budget(budget, duration=6000.0, step=2.0 if ctx.quick else 1.0)
    d_amp, b_amp = budget.pitch_amplitudes
    lines = [
        "## 4. Gain design and the Schuler error budget",
        "",
        "`analysis/multistage/gain_design.py`. The tilt loop of a stage is $s^2 + Ks + L$ with $K = kc/2$, $L = lc/2$ (ν carries",
        "half angles), and the estimate settles at $a/c$ times the true tilt, a = 1 for the half-angle quaternion (1.10) and",
        "a = 2 for the whole-angle (1.4). A requested $(\\omega_n, \\zeta)$ gives $k = 4\\zeta\\omega_n/c$, $l = 2\\omega_n^2/c$ with the",
        "consistent $c = a$; Schuler tuning is $k = 0$, $l = 2g/(aR)$ — $g/R$ for (1.4). The loop of each design, from",
        "`control.damp`:",
        "",
    ]
    lines += _table(("reference", "requested ω_n [rad/s]", "requested ζ", "c", "k [1/s]", "l [1/s²]", "ω_n of the loop", "ζ of the loop"), rows)
    checks = [gd.check_design(gd.design_gains(1e-2, zeta, reference=ref), duration=1500.0, step=1.0 if ctx.quick else 0.5) for ref in ("pure", "tilt") for zeta in (0.3, 0.7, 1.0)]
    worst = gd.largest_design_difference(checks)
    lines += [
        "Each design simulated — the stage started level on a body pitched by 0.01 rad (ideal sensors, Ω = 0) — decays like its",
        f"loop, the step response of $H_g = s^2/(s^2 + Ks + L)$ from python-control, to {worst:.1e} rad for ζ = 0.3, 0.7, 1 with both",
        "quaternions (second order in the tilt: the c and half-angle factors are right).",
        "",
        "![Designed stages: simulation against the loop](figures/stability-design.png)",
        "",
        "A switch between two designs is *bumpless* when the integral state takes over",
        "the position correction it loses, $y \\leftarrow y + (k_{old} - k_{new})(m - c\\nu)$, so that the whole correction is",
        "continuous (`switched_stage`, `Stage(switch=\"bumpless\")`).",
        "",
        "**Error budget of the Schuler-tuned stage.** For a constant gyro drift d, accelerometer bias b and an acceleration u",
        "that no accelerometer senses (level axes north, up, east), started level with an empty integral at $t_0$,",
        "",
        "$$\\Delta\\theta = \\frac{d_3}{\\Omega_s}\\sin\\Omega_s\\tau + \\frac{b_1 - u_1}{g}(1 - \\cos\\Omega_s\\tau),\\qquad"
        "\\Delta\\gamma = \\frac{d_1}{\\Omega_s}\\sin\\Omega_s\\tau - \\frac{b_3 - u_3}{g}(1 - \\cos\\Omega_s\\tau),\\qquad \\Delta\\psi = d_2\\tau,$$",
        "",
        "$\\Omega_s = \\sqrt{g/R}$, $\\tau = t - t_0$. Entered from a settled damped phase (tilt at the accelerometer level $b/g$, drift",
        "held by the integral) only the unsensed part oscillates: $\\Delta\\theta = b_1/g - (u_1/g)(1 - \\cos\\Omega_s\\tau)$. Simulated",
        "with d = (10⁻⁷, 2·10⁻⁸, −10⁻⁷) rad/s and b = (10⁻³, 0, −2·10⁻³) m/s² (Ω = 0, body level), the closed form is",
        f"followed to {check.max_difference:.1e} rad on errors up to {check.scale:.2e} rad (pitch amplitudes: drift {d_amp:.3e} rad,",
        f"bias {b_amp:.3e} rad).",
        "",
        "![Schuler error budget: closed form against simulation](figures/stability-budget.png)",
        "",
    ]
    _design_figure(ctx, checks)
    _budget_figure(ctx, check, run)
    return lines


def _design_figure(ctx, checks) -> None:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 3.6), sharey=True)
    for ax, ref in zip(axes, ("pure", "tilt")):
        for c in (c for c in checks if c.gains.reference == ref):
            line = ax.plot(c.time, c.simulated, lw=1.2, label=f"ζ = {c.gains.damping:.1g} simulated")[0]
            ax.plot(c.time[::40], c.predicted[::40], "o", ms=3, color=line.get_color(), label=f"ζ = {c.gains.damping:.1g} loop (H_g)")
        name = "(1.4), c = 2" if ref == "pure" else "(1.10), c = 1"
        ax.set_title(f"designed stage, ω_n = 0.01 rad/s, {name}")
        ax.set_xlabel("t [s]")
        ax.legend(fontsize=6)
    axes[0].set_ylabel("pitch error [rad]")
    fixed_layout(fig, left=0.9, right=0.15, bottom=0.5, top=0.3, wgap=0.2)
    ctx.savefig(fig, "figures/stability-design.png")


def _budget_figure(ctx, check, run) -> None:
    import matplotlib.pyplot as plt

    from ..multistage.gain_design import section5_budget

    fig, axes = plt.subplots(1, 2, figsize=(12, 3.8))
    for i, lab in ((1, "Δθ"), (2, "Δγ"), (0, "Δψ")):
        line = axes[0].plot(check.time, check.simulated[:, i], lw=1.2, label=f"{lab} simulated")[0]
        axes[0].plot(check.time[::50], check.predicted[::50, i], "o", ms=3, color=line.get_color(), label=f"{lab} closed form")
    axes[0].set_title("Schuler-tuned stage, constant drift and bias")
    axes[0].set_xlabel("t [s]")
    axes[0].set_ylabel("error [rad]")
    axes[0].legend(fontsize=6)
    res = run.result
    pred = section5_budget(run.scenario).errors(res.time)
    after = res.time >= PRINTED_GAINS.switch_time
    axes[1].plot(res.time, res.errors[1, :, 1], lw=0.8, label="Δθ after two stages (simulated)")
    axes[1].plot(res.time[after], pred[after, 1], "--", lw=1.2, label="budget: b₁/g − (Ω²R sin φ cos φ/g)(1 − cos Ω_s τ)")
    axes[1].set_title("section 5: two-stage pitch error")
    axes[1].set_xlabel("t [s]")
    axes[1].legend(fontsize=6, loc="upper right")  # where "best" puts it; "best" searches 10⁵ points at every draw
    fixed_layout(fig, left=0.85, right=0.15, bottom=0.5, top=0.3, wgap=0.8)
    ctx.savefig(fig, "figures/stability-budget.png")


# ---------------------------------------------------------------------------
# 5. Section 5
# ---------------------------------------------------------------------------
def _truth_model(run) -> list:
    from ..multistage import earth
    from ..multistage.trajectory import Scenario, coriolis_term, specific_force_residual

    sc = run.scenario
    good = specific_force_residual(sc)
    bad = specific_force_residual(Scenario(truth="no-coriolis"))
    cor = coriolis_term(sc)
    gh = earth.horizontal_centripetal(sc.latitude, sc.earth_rate, sc.earth_radius)
    return [
        "## 5. The example of section 5",
        "",
        "### Truth model",
        "",
        f"The body moves over a spherical Earth turning at Ω = {_times_ten(sc.earth_rate)} rad/s with plumb-bob gravity g down the radius",
        "(`analysis/multistage/earth.py`, `trajectory.py`). At rest it is fixed to the Earth; the rocking angles are Krylov angles",
        "relative to the geographic frame (north, up, east); the stages estimate the attitude relative to the azimuth-free",
        "horizontal frame η of section 1, which turns relative to the geographic frame by $-\\int\\Omega\\sin\\varphi\\,dt$ (so the true yaw",
        f"relative to η grows by Ω sin φ = {sc.vertical_earth_rate:.3e} rad/s at rest). The gyros deliver the increments of the exact",
        "inertial attitude; the accelerometers the mean specific force of the same motion,",
        "$f = \\dot V + (2\\Omega + \\rho)\\times V - g = (\\dot V,\\; g - V^2/R,\\; -2\\Omega\\sin\\varphi\\,V)$ in (north, up, east) —",
        f"Coriolis and centripetal terms included (at {cor.velocity:g} m/s the Coriolis term is {cor.acceleration:.3f} m/s²).",
        "",
        "**Residual check.** The inertial velocity of the body, from the geometry alone, must change by the integral of the",
        "specific force (rotated with the true attitude) plus the gravitation $G = -g\\,u + \\Omega\\times(\\Omega\\times r)$. Over",
        f"100 s intervals of the whole run (16-point Gauss–Legendre) the largest residual is {at_round_off(good.max_residual, 1e-11)} m/s on velocity",
        f"changes up to {good.scale:.0f} m/s. The truth model of earlier versions of this report (accelerometers without the",
        "Coriolis term and V²/R, body turning with η at rest) fails the same check by "
        f"{bad.max_residual:.2f} m/s: its gyros and accelerometers described different motions.",
        "",
        f"One term is real and no accelerometer senses it: the horizontal centripetal acceleration Ω²R sin φ cos φ = {gh:.4f} m/s²",
        "to the north, balanced by the plumb-bob gravity, turns the inertial velocity that a Schuler loop integrates.",
        "",
    ]


def _printed_envelope_at_start() -> float:
    from ..multistage.readings import printed_envelope_at_rocking_start

    return printed_envelope_at_rocking_start()


def _printed_envelope() -> str:
    """The printed envelope formula with the printed numbers."""
    return f"exp(−{SECTION5.envelope_decay:g}(t − {SECTION5.envelope_origin:g}))"


def _assumptions(run) -> list:
    sc = run.scenario
    return [
        "### Readings (every constant a parameter of `Scenario`, `plotnikov_1999_stages` and `Reading`)",
        "",
        f"* Timeline as printed: rest at φ0 = {units.deg(sc.latitude):g}°, rocking from {sc.rocking_start:g} s, northward {sc.accel:g} m/s² from",
        f"  {sc.accel_start:g} s for {sc.accel_duration:g} s then constant velocity, end at {sc.duration:g} s.",
        f"* Rocking envelope, printed $E = \\exp(-{SECTION5.envelope_decay:g}(t-{SECTION5.envelope_origin:g}))$ for t = {SECTION5.rest_end:g}…{SECTION5.duration:g} s, which is "
        f"{_printed_envelope_at_start():.1e} when rocking starts. The text cannot decide",
        f"  what was meant; the default (likely reading) puts the origin at the start of rocking, $E = \\exp(-{SECTION5.envelope_decay:g}(t - t_r))$, with a",
        f"  smooth onset $1 - e^{{-(t-t_r)/{sc.rocking_onset:g}\\,\\mathrm{{s}}}}$ (not in the paper) so that the yaw (phase π/2) does not jump by {SECTION5.rocking_amplitude[0]:g} rad.",
        f"  $\\exp(-0.001(t-{SECTION5.envelope_origin:g}))$ and the printed form are among the readings below.",
        f"* Sensor errors: scale factors {_times_ten(100 * SECTION5.scale_factor_error)} %; gyro drift {_times_ten(SECTION5.gyro_drift)} s⁻¹ and accelerometer bias "
        f"{_times_ten(SECTION5.accel_bias)} m/s² with signs (+, −, +)",
        "  (\"with different signs by component\"); no noise (none is given: the Monte Carlo below draws signs and noise).",
        "* Stage 1: variant 2 without the kinematic term, μ⁺ from (1.9)–(1.10) as section 5 says, corrected on the",
        "  components 1 and 3 with c = 1 (the tilt quaternion carries half angles; the printed c = 2 makes the stage settle at",
        f"  half the tilt — a reading below). Stage 2: (2.1)–(2.2) with (1.4) and c = 2; gains as printed; at {PRINTED_GAINS.switch_time:g} s it switches to",
        f"  k⁽¹⁾ = 0, l⁽¹⁾ = g/R (the printed {_times_ten(PRINTED_GAINS.stage2_after[1])} is √(g/R)); the integral state is carried through the switch",
        "  (rescaled and bumpless are readings below). ρ = 1 s⁻¹ (not given). ν(0) = ν₁(0) = 1 as printed.",
        "* Errors are Krylov-angle differences, estimate minus truth, after stage 1 ($\\nu$) and after two stages",
        "  ($\\nu^+ = \\nu_1\\circ\\nu$, (2.6)), as in section 5.",
        "",
    ]


def _default_result(ctx, run) -> list:
    p1, p2 = run.peaks
    since, until = run.scenario.accel_start, run.scenario.accel_start + 600.0  # the 10 minutes after the acceleration starts
    w1, w2 = run.result.peaks(since=since, until=until)
    ratio, window_ratio = p1.over(p2), w1.over(w2)
    lines = [f"### Result (default reading, step {run.step:g} s)", ""]
    rows = [
        ("after stage 1", _e(p1.yaw), _e(p1.pitch), _e(p1.roll), _e(p1.tilt), _e(w1.tilt)),
        ("after two stages", _e(p2.yaw), _e(p2.pitch), _e(p2.roll), _e(p2.tilt), _e(w2.tilt)),
        ("ratio", f"{ratio.yaw:.2f}", f"{ratio.pitch:.2f}", f"{ratio.roll:.2f}", f"{ratio.tilt:.2f}", f"{window_ratio.tilt:.2f}"),
        (
            "paper (section 5)",
            f"{PAPER.yaw_stage1.value:.1e} → {PAPER.yaw_two_stage.value:.1e}",
            f"{PAPER.stage1_pitch_peak.value:.1e} → ≤ {PAPER.two_stage_pitch_bound.value:.1e}",
            f"reduced {PAPER.roll_reduction.value:g}×",
            "",
            "",
        ),
    ]
    lines += _table(("", "peak \\|Δψ\\| [rad]", "peak \\|Δθ\\| [rad]", "peak \\|Δγ\\| [rad]", "peak tilt [rad]", f"peak tilt, {since:g} ≤ t ≤ {until:g} s [rad]"), rows)
    lines += ["![Angle errors after one and two stages](figures/stability-scenario.png)", ""]
    _scenario_figure(ctx, run)
    return lines


def _scenario_figure(ctx, run) -> None:
    import matplotlib.pyplot as plt

    res = run.result
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    for i, lab in enumerate(["Δψ (yaw)", "Δθ (pitch)", "Δγ (roll)"]):
        axes[i].plot(res.time, res.errors[0, :, i], lw=0.8, label="after stage 1")
        axes[i].plot(res.time, res.errors[1, :, i], lw=0.8, label="after two stages")
        axes[i].set_ylabel(f"{lab} [rad]")
        for tt in (PRINTED_GAINS.switch_time, run.scenario.accel_start):
            axes[i].axvline(tt, color="0.6", lw=0.6)
    axes[1].axhline(PAPER.stage1_pitch_peak.value, color="C0", ls=":", lw=0.8, label="paper: stage-1 peak")
    axes[1].axhline(PAPER.two_stage_pitch_bound.value, color="C1", ls=":", lw=0.8, label="paper: two-stage bound")
    axes[1].axhline(-PAPER.two_stage_pitch_bound.value, color="C1", ls=":", lw=0.8)
    axes[1].set_ylim(-0.06, 0.12)
    axes[0].legend(fontsize=7, loc="lower right")  # where "best" puts them; "best" searches 10⁵ points at every draw
    axes[1].legend(fontsize=7, loc="upper right")
    axes[2].set_xlabel("t [s] (grey: gain switch at 600 s, start of the acceleration)")
    fixed_layout(fig, left=0.9, right=0.15, bottom=0.5, top=0.15, hgap=0.15)
    ctx.savefig(fig, "figures/stability-scenario.png")


def _remaining_errors(run) -> list:
    from ..multistage import earth
    from ..multistage.gain_design import initial_rate_transient, section5_budget
    from ..multistage.tilt_loop import schuler_period

    sc = run.scenario
    res = run.result
    switch = PRINTED_GAINS.switch_time
    after = res.peaks(since=switch)[1]
    before = res.peaks(until=switch)[1]
    budget = section5_budget(sc)
    predicted = budget.peaks(sc.duration)
    without = section5_budget(sc, include_centripetal=False).peaks(sc.duration)
    gh = earth.horizontal_centripetal(sc.latitude, sc.earth_rate, sc.earth_radius)
    when = res.peak_times()[1]
    transient = initial_rate_transient(sc)
    return [
        "### What remains after two stages, quantitatively",
        "",
        f"* **Pitch** (peak {after.pitch:.3e} rad at t = {when.pitch:.0f} s, after the switch): the Schuler-tuned stage 2 answers",
        f"  the unsensed centripetal acceleration {gh:.4f} m/s² as an acceleration the accelerometers miss. Entered settled at",
        f"  {switch:g} s, its budget is $\\Delta\\theta = b_1/g - (\\Omega^2R\\sin\\varphi\\cos\\varphi/g)(1 - \\cos\\Omega_s(t - {switch:g}))$ with the",
        f"  x₁ bias $b_1$ = {sc.sensors.accel_bias[0]:g} m/s²: peak {predicted.pitch:.3e} rad, half a Schuler period ({schuler_period(sc.gravity, sc.earth_radius) / 2:.0f} s) after the",
        f"  switch — {abs(predicted.relative_to(after).pitch) * 100:.1f} % from the simulation (figure above). Without the centripetal",
        f"  term the budget gives {without.pitch:.1e} rad; with Ω = 0 (readings table) the pitch error falls to the sensor level.",
        f"* **Roll** (peak {before.roll:.3e} rad at t = {when.roll:.0f} s, before the switch): both stages start with an empty",
        f"  integral while the Earth-fixed body turns at Ω cos φ = {transient.rate:.3e} rad/s about north. The damped stage 2",
        f"  takes that rate into its integral with the drift response of its loop: linear prediction {transient.peak:.3e} rad at",
        f"  t = {transient.time:.0f} s. After the switch the two-stage roll stays below {after.roll:.1e} rad.",
        f"* **Yaw** ({run.peaks[1].yaw:.1e} rad): with stage 1 on the components 1 and 3 neither stage corrects the yaw, which",
        f"  follows the gyros (drift {abs(sc.sensors.gyro_drift[1]):g} rad/s about the vertical) and the tilt coupling of the Krylov angles. See the yaw study below for the",
        "  other reading of stage 1.",
        "",
    ]


def _all_readings(ctx) -> tuple:
    """Every standard reading of section 5, run once per report (the page and the errata quote them).

    Each reading draws the same sensor noise (:func:`strapdown.analysis.multistage.readings.run_readings`),
    so a reading's result does not depend on which others run with it.
    """
    from ..multistage.readings import run_readings, standard_readings

    return ctx.shared("stability/readings", lambda: run_readings(standard_readings(), step=0.2, rng=_seeds(ctx)[_READINGS_STREAM], progress=ctx.progress))


def _readings(ctx, run) -> tuple:
    results = _all_readings(ctx)
    if ctx.quick:
        results = (results[0], results[5], results[7])
    rows = []
    for r in results:
        p1, p2 = r.peaks
        rows.append((r.reading.label, _e(p1.yaw, 2), _e(p1.pitch, 2), _e(p1.roll, 2), _e(p2.yaw, 2), _e(p2.pitch, 2), _e(p2.roll, 2), f"{r.yaw_at_switch[0]:+.2e}", f"{r.roll_ratio:.1f}"))
    rows.append(
        (
            "**paper** (section 5)",
            f"{PAPER.yaw_stage1.value:+.1e}",
            f"{PAPER.stage1_pitch_peak.value:.1e}",
            "",
            f"{PAPER.yaw_two_stage.value:+.1e}",
            f"≤ {PAPER.two_stage_pitch_bound.value:.1e}",
            "",
            "",
            f"{PAPER.roll_reduction.value:g}",
        )
    )
    lines = [
        "### Readings the text leaves open (step 0.2 s)",
        "",
        "Each row changes the default in one place (two rows change a pair). Peaks over the whole run [rad]; the yaw of stage 1",
        f"at the gain switch ({PRINTED_GAINS.switch_time:g} s) is given because the paper's {_times_ten(PAPER.yaw_stage1.value)} reads best there (see the yaw study); the roll ratio is",
        "the stage-1 peak over the two-stage peak.",
        "",
    ]
    lines += _table(
        ("reading", "stage 1: \\|Δψ\\|", "\\|Δθ\\|", "\\|Δγ\\|", "two stages: \\|Δψ\\|", "\\|Δθ\\|", "\\|Δγ\\|", f"stage-1 Δψ at {PRINTED_GAINS.switch_time:g} s", "roll ratio"),
        rows,
    )
    return lines, results


def _readings_discussion(results) -> list:
    from ..multistage.readings import compare_with_paper

    cmp = compare_with_paper(results)
    near = [r.reading.label for r in cmp.stage1_pitch_near]
    over = [f"{r.reading.label} ({r.peaks[1].pitch:.1e} rad)" for r in cmp.above_bound]
    low, high = cmp.roll_ratio_range
    lines = [
        "What the table decides and what it does not:",
        "",
        f"* **Stage-1 pitch.** Readings within {100 * cmp.tolerance:g} % of the printed {PAPER.stage1_pitch_peak.value:.1e} rad: " + ("; ".join(near) if near else "none") + ". Only a pair of",
        f"  changes (2 m/s² *and* (1.4) for (1.10)) comes close, so the text cannot decide; the printed {SECTION5.accel:g} m/s² with (1.10) stays the default.",
        f"* **Two-stage pitch.** Above the printed bound {PAPER.two_stage_pitch_bound.value:.1e} rad: " + ("; ".join(over) if over else "no reading") + ". Rescaling the",
        "  integral at the switch throws away the Earth rate it holds (an error of order Ω cos φ/Ω_s): the carried or bumpless",
        "  integral is the likely reading.",
        f"* **Roll.** Reduced {low:.1f}–{high:.1f}× by the second stage in the consistent readings (paper: {PAPER.roll_reduction.value:g}×).",
    ]
    if cmp.earlier_truth is not None:
        lines.append(f"  The earlier truth model's two-stage roll, {cmp.earlier_truth.peaks[1].roll:.1e} rad, came from its own missing Coriolis force, not from the Earth.")
    lines += [
        "* **c.** The printed c = 2 with (1.10) halves the static tilt estimate (below), yet the section-5 peaks hardly tell the",
        "  readings apart because the manoeuvre dominates stage 1: section 5 cannot decide c; c = 1 is the likely reading.",
        f"* **Envelope.** The printed origin ({SECTION5.envelope_origin:g} s) and the start of rocking ({SECTION5.rest_end:g} s) give the same peaks (the rocking is gone in",
        "  seconds either way); a decay of 10⁻³ s⁻¹ keeps it through the run and raises mainly the stage-1 roll.",
        "",
    ]
    return lines


def _yaw(ctx, run) -> list:
    from ...derivations.multistage.composition import derive
    from ..core.cache import derived
    from ..multistage.composition import yaw_study
    from ..multistage.trajectory import Scenario

    d = derived("multistage:composition:v1", derive)
    study = yaw_study(Scenario(duration=2000.0) if ctx.quick else run.scenario, step=0.2, rng=run.seeds[2])
    horizontal, all_four = study.readings
    rows = []
    for r in study.readings:
        name = "components 1, 3" if r.components == (1, 3) else "all four components"
        for t, a, b in zip(r.times, r.stage1_yaw, r.two_stage_yaw):
            rows.append((name, f"{t:.0f}", f"{study.true_yaw(t):.3e}", f"{a:+.3e}", f"{b:+.3e}"))
    lines = [
        "### Yaw through the composition",
        "",
        "The composite $P = \\nu_1\\circ\\nu$ of (2.6) obeys, for stage 1 $2\\dot\\nu = \\nu\\circ\\omega + C$ with *any* correction C and",
        "stage 2 driven by (2.2), $2\\dot\\nu_1 = \\nu_1\\circ\\omega_{\\eta(1)} + C_1$ (`derivations/multistage/composition.py`):",
        "",
        "$$2\\dot P = P\\circ\\omega + C_1\\circ\\nu + (|\\nu|^2 - 1)\\,P\\circ\\omega + 2(1 - |\\nu|^4)\\,\\nu_1\\circ\\dot\\nu .$$",
        "",
        f"Verified symbolically: the residual has exactly this structure ({d.cancels_unit_norm}), C is absent once $|\\nu| = 1$",
        f"({d.stage1_correction_free}), and with $\\nu^{{-1}}$ for $\\bar\\nu$ in (2.2) the cancellation is exact for any norm ({d.cancels_any_norm_with_inverse}).",
        "Every stage-1 correction cancels: the composite is the gyro-integrated attitude corrected by stage 2 only. The",
        "discrete cascade has the property exactly — with stage 2 left uncorrected, the composite equals the product of the",
        f"gyro increments (difference {at_round_off(study.identity.max_difference)}) while stage 1 (all four components) moves its own yaw by up to",
        f"{study.identity.stage1_yaw_peak:.2e} rad (tests: any stage 1, to 10⁻¹¹).",
        "",
        "So the earlier statement \"yaw is not corrected by either stage, so the second stage cannot reduce it\" was wrong as",
        "reasoning. With stage 1 correcting *all four* components toward (1.10), whose yaw is 0 by construction, stage 1 pulls",
        "its yaw toward 0 while the true yaw relative to η grows with the Earth's rotation (Ω sin φ t); the composite keeps the",
        "gyro yaw:",
        "",
    ]
    lines += _table(("stage 1 corrects", "t [s]", "true yaw Ω sin φ t [rad]", "Δψ after stage 1 [rad]", "Δψ after two stages [rad]"), rows)
    at_switch = all_four.stage1_yaw_at(PRINTED_GAINS.switch_time)
    lines += [
        f"With all four components the stage-1 yaw error at the gain switch is {at_switch:+.2e} rad — the paper's",
        f"{PAPER.yaw_stage1.value:+.0e} rad — and keeps growing ({all_four.stage1_peak:.2e} rad peak), while after two stages it stays",
        f"below {all_four.two_stage_peak:.1e} rad (paper: {PAPER.yaw_two_stage.value:+.1e}). The all-four reading explains the printed",
        "stage-1 yaw and the reduction by stage 2; it is a likely reading, not decided by the text, and it does not reproduce",
        "the printed two-stage value. With components 1, 3 (default) neither yaw error exceeds "
        f"{horizontal.peak:.1e} rad.",
        "",
        "![Yaw errors for both readings of stage 1](figures/stability-yaw.png)",
        "",
    ]
    _yaw_figure(ctx, study)
    return lines


def _yaw_figure(ctx, study) -> None:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 3.8), sharey=False)
    for ax, r in zip(axes, study.readings):
        ax.plot(r.series_time, r.series_stage1, lw=0.9, label="after stage 1")
        ax.plot(r.series_time, r.series_two_stage, lw=0.9, label="after two stages")
        ax.axhline(PAPER.yaw_stage1.value, color="C0", ls=":", lw=0.8, label="paper: stage 1")
        ax.axhline(PAPER.yaw_two_stage.value, color="C1", ls=":", lw=0.8, label="paper: two stages")
        ax.axvline(PRINTED_GAINS.switch_time, color="0.6", lw=0.6)
        ax.set_title("stage 1 corrects " + ("components 1, 3" if r.components == (1, 3) else "all four components"))
        ax.set_xlabel("t [s]")
        ax.set_ylabel("Δψ [rad]")
        ax.legend(fontsize=6)
    fixed_layout(fig, left=0.9, right=0.15, bottom=0.5, top=0.3, wgap=0.85)
    ctx.savefig(fig, "figures/stability-yaw.png")


def _sensor_statistics(ctx, run) -> list:
    from ..multistage.sensor_statistics import SensorErrorStatistics, sensor_error_monte_carlo

    stats = SensorErrorStatistics.plotnikov_1999(distribution="normal")
    n = 24 if ctx.quick else 200
    mc = sensor_error_monte_carlo(stats, n, step=0.2, rng=run.seeds[3], trials_per_block=8, progress=ctx.show_progress)
    names = ("yaw", "pitch", "roll", "tilt")
    rows = []
    for s in range(mc.peaks.shape[1]):
        for q, name in enumerate(names):
            rows.append((f"stage {s + 1}" if s == 0 else "two stages", name, _e(mc.nominal[s, q]), *(_e(mc.percentiles[i, s, q]) for i in range(len(mc.levels)))))
    lines = [
        f"### Sensor-error statistics ({n} trials, step 0.2 s)",
        "",
        "`analysis/multistage/sensor_statistics.py`. Each trial draws, per axis, the gyro drift and the accelerometer bias from",
        f"N(0, σ²) with the printed sizes as σ ({stats.gyro_drift:g} rad/s, {stats.accel_bias:g} m/s²), the scale factors likewise",
        f"(σ = {stats.gyro_scale:g}), and adds white noise: angle random walk {stats.gyro_noise:g} rad/√s "
        f"({units.deg_per_sqrt_h(stats.gyro_noise):.2g} deg/√h) and velocity",
        f"random walk {stats.accel_noise:g} m/s/√s ({units.micro_g_per_sqrt_hz(stats.accel_noise):.2g} µg/√Hz) — the paper gives no noise. Trials are seeded in blocks from the",
        "spawn keys of one root seed (`core.montecarlo.collect`, the seeding of the azimuth Monte Carlo), so the peaks are",
        "bit-identical for any chunking and number of workers (tested with two processes).",
        "",
    ]
    lines += _table(("", "peak", "no sensor errors [rad]", *(f"{lv:g} % [rad]" for lv in mc.levels)), rows)
    lines += [
        f"Sensor errors of the paper's grade move the two-stage peaks by at most {mc.spread():.1e} rad (these percentiles) around the",
        "error-free run: the two-stage pitch is set by the Earth's rotation (above), the stage-1 peaks by the manoeuvre.",
        "",
        "![Distribution of the two-stage peak errors](figures/stability-sensor-statistics.png)",
        "",
    ]
    _statistics_figure(ctx, mc)
    return lines


def _statistics_figure(ctx, mc) -> None:
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(12, 3.4))
    for ax, q, name in zip(axes, (0, 1, 2), ("yaw", "pitch", "roll")):
        ax.hist(mc.peaks[:, 1, q], bins=25, color="C1", alpha=0.8)
        ax.axvline(mc.nominal[1, q], color="k", lw=1.0, label="no sensor errors")
        ax.set_title(f"two stages: peak |Δ{name}|")
        ax.set_xlabel("[rad]")
        ax.legend(fontsize=6)
    axes[0].set_ylabel("trials")
    fixed_layout(fig, left=0.7, right=0.2, bottom=0.5, top=0.3, wgap=0.65)
    ctx.savefig(fig, "figures/stability-sensor-statistics.png")


def _static_tilt() -> list:
    from ..multistage.gain_design import static_tilt_estimate
    from ..multistage.stages import Stage

    k, l = PRINTED_GAINS.stage1
    rows = []
    for ref, c in (("tilt", 1.0), ("tilt", 2.0), ("pure", 2.0), ("pure", 1.0)):
        st = Stage.constant(k, l, ref, c=c)
        rows.append((f"({'1.10' if ref == 'tilt' else '1.4'})", f"{c:g}", f"{st.static_gain:g}", f"{static_tilt_estimate(st, 0.1):.4f}"))
    return [
        "### The factor c",
        "",
        "A single stage with the stage-1 gains on a body statically pitched by 0.1 rad (ideal sensors, Ω = 0), started level:",
        "",
        *_table(("quaternion", "c", "a/c", "pitch estimate after 6000 s [rad]"), rows),
        "c must match the quaternion: c = 2 for the whole-angle (1.4), c = 1 for the half-angle (1.10) (the (1.4) stage settles at",
        "2 arcsin(sin θ/2), (1.4) being linear in the load factors). The paper prints c = 2 for the second variant without saying",
        "which quaternion; with (1.10) it halves the tilt.",
        "",
    ]


def _convergence(ctx) -> list:
    from ..multistage.step_convergence import step_convergence

    steps = (0.2, 0.1, 0.05) if ctx.quick else (0.08, 0.04, 0.02, 0.01)
    study = step_convergence(steps=steps)
    rows = []
    for i, (h, dq, de) in enumerate(zip(study.steps, study.composite_difference, study.angle_difference)):
        rows.append((f"{h:g}", f"{dq:.2e}", f"{de:.2e}", f"{study.ratios[i]:.2f}" if i < len(study.ratios) else "—"))
    return [
        "### Convergence of the integrator",
        "",
        "Strang splitting (exact correction flow, exact norm flow, exact kinematic step; compiled with numba, checked against",
        f"the plain-Python reference to round-off). Difference from the run with h = {study.steps[-1]:g} s over the first 1250 s",
        "(rocking and acceleration included):",
        "",
        *_table(("step h [s]", "max \\|Δν⁺\\|", "max \\|angle-error difference\\| [rad]", "ratio to the next step"), rows),
        "Halving the step divides the difference by about 4 (the last ratio is inflated by the reference's own error):",
        "second order, with errors far below the angles reported above.",
        "",
    ]


# ---------------------------------------------------------------------------
def warm_up() -> None:
    """Derive and compile what :func:`build` needs into the caches: (3.2)–(3.4), the Schuler linearisation, the composition, the tilt quaternion (1.10), the stage loops."""
    from ...derivations.multistage import composition, lyapunov_function, schuler, tilt_quaternion
    from ..core.cache import derived
    from ..multistage.decay_rates import simulated_rate
    from ..multistage.stages import simulate
    from ..multistage.tilt_loop import StageLoop
    from ..multistage.trajectory import Scenario

    derived("multistage:schuler:v1", schuler.derive)
    simulate(Scenario(duration=20.0), step=0.2, rng=0)  # the compiled cascade
    simulated_rate(1.0, 1.0, step=0.05, duration=1.0)  # the compiled single stage
    StageLoop(0.01, 5e-5).summary()
    derived("multistage:lyapunov:v1", lyapunov_function.derive)
    derived("multistage:composition:v1", composition.derive)
    derived("multistage:tilt-quaternion:v1", tilt_quaternion.derive)


def build(ctx) -> None:
    """Write ``stability.md`` and its figures.

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        Where to write, and how big to run.
    """
    from ..multistage.tilt_loop import schuler_period

    run = _Run(ctx)
    g, r = run.scenario.gravity, run.scenario.earth_radius
    tsch = schuler_period(g, r)
    lines = [
        f"# {SECTION.title}",
        "",
        "Source: Plotnikov (1999), sections 1–5. Every number below is computed by the package when this report is built;",
        "the paper's values appear only as reference data (`derivations/multistage/published.py`), with their place in the paper.",
        "",
        f"Constants: g = {g} m/s², R = {r:.0f} m, Schuler frequency √(g/R) = {run.scenario.schuler_frequency:.6e} rad/s, "
        f"Schuler period 2π√(R/g) = {tsch:.1f} s ({tsch / 60:.2f} min). Latitude {units.deg(run.scenario.latitude):g}°.",
        "",
    ]
    lines += _lyapunov(ctx)
    lines += _linearisation(g, r)
    lines += _loops_section(ctx, g, r, run.scenario.schuler_frequency)
    lines += _design(ctx, run)
    lines += _truth_model(run)
    lines += _assumptions(run)
    lines += _default_result(ctx, run)
    lines += _remaining_errors(run)
    table, results = _readings(ctx, run)
    lines += table + _readings_discussion(results)
    lines += _yaw(ctx, run)
    lines += _sensor_statistics(ctx, run)
    lines += _static_tilt()
    lines += _convergence(ctx)
    ctx.write_text("stability.md", "\n".join(lines))


def errata(ctx) -> list:
    """Errata and readings of Plotnikov (1999) with their evidence.

    Each entry says in its evidence whether a check decides it ("Misprint") or
    the text admits several readings ("Ambiguous", with the likely reading).

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        The report context (its seed draws the samples of the checks).

    Returns
    -------
    list of Erratum
    """
    from ...derivations.multistage.tilt_quaternion import derive as derive_tilt
    from ..core.cache import derived
    from ..multistage.formula_checks import check_printed_formulas
    from ..multistage.gain_design import static_tilt_estimate
    from ..multistage.stages import Stage
    from ..multistage.tilt_loop import StageLoop
    from ..multistage.trajectory import Scenario

    seeds = _seeds(ctx)
    c = check_printed_formulas(rng=seeds[_FORMULA_STREAM])
    every = _all_readings(ctx)
    default, printed_env, slow_env, accel2, accel2_pure, printed_c, all_four, rescale, bumpless = (every[i] for i in (0, 1, 2, 3, 5, 6, 7, 9, 10))
    tilt = derived("multistage:tilt-quaternion:v1", derive_tilt)  # (1.10) simplified once, as the other derivations
    sc = Scenario()
    g, r = sc.gravity, sc.earth_radius
    schuler_l = StageLoop.schuler(g, r).l
    printed_l = PRINTED_GAINS.stage2_after[1]
    peak_printed = StageLoop(*PRINTED_GAINS.stage2_after, g, r).peak_tilt_error(SECTION5.accel, SECTION5.accel_duration)
    switch = PRINTED_GAINS.switch_time
    k1, l1 = PRINTED_GAINS.stage1
    half = static_tilt_estimate(Stage.constant(k1, l1, "tilt", c=2.0), 0.1)
    whole = static_tilt_estimate(Stage.constant(k1, l1, "tilt", c=1.0), 0.1)
    return [
        Erratum(
            "Plotnikov (1999), eq. (3.7), W₃⁽¹⁾",
            "W₃⁽¹⁾ = W₃ − gα − W₁β",
            "W₃⁽¹⁾ = W₃ − gα + W₁β (then M₁₁ = −W₃⁽¹⁾/g = α − n₃ − n₁β, as printed in (3.7)–(3.8))",
            f"Decided by the symbolic first-order expansion of Δ̄∘W∘Δ (derivations/multistage/schuler.py): for {c.samples} random "
            f"small rotations (|α|, |β|, |χ| ≤ {c.small_angle:g} rad) and |W₁| ≤ 20 m/s², the derived form differs from the exact rotation by at most "
            f"{c.derived_w3:.1e} m/s², the printed one by {c.printed_w3:.1e} m/s²; the printed M₁₁ agrees with the derived sign ({c.printed_m11:.1e}).",
            "stability",
            kind="misprint",
        ),
        Erratum(
            f"Plotnikov (1999), section 5, l⁽¹⁾ after {switch:g} s",
            f"l⁽¹⁾ = ({_times_ten(printed_l)}) s⁻²",
            f"l⁽¹⁾ = ({_times_ten(printed_l)})² = g/R = {schuler_l:.4e} s⁻² (the square was lost)",
            f"Decided by the paper's own condition: the text says the Schuler conditions hold, which (3.11) makes l = g/R; "
            f"√(g/R) = {sc.schuler_frequency:.5e} s⁻¹ is the printed number. With the printed value the linearised stage's peak tilt error "
            f"for {SECTION5.accel:g} m/s² over {SECTION5.accel_duration:g} s is {peak_printed:.3g} rad instead of 0.",
            "stability",
            kind="misprint",
        ),
        Erratum(
            "Plotnikov (1999), section 5, rocking envelope",
            f"E = {_printed_envelope()} for t = {SECTION5.rest_end:g}…{SECTION5.duration:g} s",
            f"likely reading: E = exp(−{SECTION5.envelope_decay:g}(t − {SECTION5.rest_end:g})), the origin at the start of rocking (default)",
            f"The text cannot decide: as printed E({SECTION5.rest_end:g} s) = {_printed_envelope_at_start():.1e}, i.e. no rocking at all. Against the default, the "
            f"two-stage peak errors change by at most {100 * default.peak_change(printed_env):.1f} % with the printed form and "
            f"{100 * default.peak_change(slow_env):.1f} % with exp(−0.001(t − {SECTION5.envelope_origin:g})) (readings table of the stability report).",
            "stability",
            kind="ambiguous",
            alternatives=(
                f"{_printed_envelope()} as printed (stage-1 roll peak {printed_env.peaks[0].roll:.2e} rad); exp(−0.001(t − {SECTION5.envelope_origin:g})), rocking through the run "
                f"(stage-1 roll peak {slow_env.peaks[0].roll:.2e} rad against {default.peaks[0].roll:.2e})"
            ),
        ),
        Erratum(
            "Plotnikov (1999), eq. (1.9), cos γ",
            "cos γ = −n_x2/h",
            "cos γ = n_x2/h (from W_x2 = g cos θ cos γ in (1.8))",
            f"Decided by (1.8) (derivations/multistage/tilt_quaternion.py: matches print = {tilt.cos_gamma_matches_printed}); on {c.samples} random "
            f"attitudes the printed form misses cos γ by up to {c.printed_cos_gamma:.2f}, the derived one by {at_round_off(c.derived_cos_gamma)}.",
            "stability",
            kind="misprint",
        ),
        Erratum(
            "Plotnikov (1999), eq. (1.10), μ0 and μ3",
            "μ0 = ½(h/n + n_x2/n + n_x3/h + 1)^½,  μ3 = (n_x1 n_x2 + n_x1)/(4μ0 n h)",
            "μ0 = ½(h/n + n_x2/n + n_x2/h + 1)^½,  μ3 = n_x1(n_x2 + h)/(4μ0 n h)",
            "Decided by substituting (1.9) into (1.7) with ψ = 0 (derivations/multistage/tilt_quaternion.py; components that match the print: "
            f"{', '.join(f'μ{i}' for i, m in enumerate(tilt.matches_printed) if m)}). On {c.samples} random attitudes (ψ = 0, |θ|, |γ| ≤ 0.6 rad) the printed "
            f"(1.10) differs from the true quaternion by up to {c.printed_1_10:.2f}, the derived one by {at_round_off(c.derived_1_10)} "
            f"(the package's tilt quaternion: {at_round_off(c.package_tilt)}).",
            "stability",
            kind="misprint",
        ),
        Erratum(
            "Plotnikov (1999), section 1 after (1.6), c for the accelerometer quaternion",
            "c = 2 (second variant, μ⁺ from the accelerometers)",
            "likely reading: c = 2 for the whole-angle (1.4), c = 1 for the half-angle (1.10) used by stage 1 in section 5 (default)",
            f"The text cannot decide which quaternion c = 2 was meant for. A stage with the stage-1 gains on a body pitched by 0.1 rad settles "
            f"at {whole:.4f} rad with (1.10) and c = 1, at {half:.4f} rad with (1.10) and c = 2. Section 5 does not decide it either: neither reading "
            f"brings the stage-1 pitch near the printed {PAPER.stage1_pitch_peak.value:.1e} rad (readings table).",
            "stability",
            kind="ambiguous",
            alternatives=(
                f"c = 2 with (1.10) as printed: the static tilt is halved; in section 5 the stage-1 pitch peak is {printed_c.peaks[0].pitch:.3f} rad "
                f"(default {default.peaks[0].pitch:.3f}) and the two-stage pitch peak {printed_c.peaks[1].pitch:.2e} rad (default {default.peaks[1].pitch:.2e})"
            ),
        ),
        Erratum(
            "Plotnikov (1999), section 5, acceleration",
            f"V̇ζ₁ = {SECTION5.accel:g} m/s² for t = {SECTION5.accel_start:g}…{SECTION5.accel_start + SECTION5.accel_duration:g} s",
            f"likely reading: {SECTION5.accel:g} m/s² as printed (default)",
            f"The text cannot decide: with (1.10) and {SECTION5.accel:g} m/s² the stage-1 pitch peak is {default.peaks[0].pitch:.3f} rad against the printed "
            f"{PAPER.stage1_pitch_peak.value:.1e}; no single change of the reading matches the print (readings table of the stability report).",
            "stability",
            kind="ambiguous",
            alternatives=(
                f"2 m/s²: stage-1 pitch peak {accel2.peaks[0].pitch:.3f} rad; 2 m/s² together with stage 1 on (1.4), c = 2 (a second change): "
                f"{accel2_pure.peaks[0].pitch:.3f} rad, two-stage {accel2_pure.peaks[1].pitch:.2e} rad"
            ),
        ),
        Erratum(
            "Plotnikov (1999), sections 1 and 5, components corrected by stage 1",
            "\"asymptotic stability only for the part of the components where correction is introduced\"; section 5 gives no list",
            "likely reading for the printed yaw: all four components of (1.10); the package's default stays 1, 3 (the reading whose errors the stability report explains)",
            "The text cannot decide. (1.4) has only the components 1 and 3; (1.10) has all four, and correcting them all pulls the stage-1 yaw to "
            "the ψ = 0 of (1.10) — the stage-1 yaw error β of (3.8), ψ₁⁺ = β + const, that stage 2 takes up — which the composite (2.6) undoes "
            f"(every stage-1 correction cancels in ν₁∘ν, derived symbolically). With all four components the stage-1 yaw error at the {switch:g} s switch is "
            f"{all_four.yaw_at_switch[0]:+.2e} rad (printed {PAPER.yaw_stage1.value:+.0e}), growing to {all_four.peaks[0].yaw:.2e} rad by the end; after two "
            f"stages its peak is {all_four.peaks[1].yaw:.1e} rad (printed {PAPER.yaw_two_stage.value:+.1e}).",
            "stability",
            kind="ambiguous",
            alternatives=(
                f"components 1, 3 (default): stage-1 yaw error at {switch:g} s {default.yaw_at_switch[0]:+.1e} rad, peaks {default.peaks[0].yaw:.1e} (stage 1) and "
                f"{default.peaks[1].yaw:.1e} rad (two stages) — it cannot give the printed yaw numbers"
            ),
        ),
        Erratum(
            "Plotnikov (1999), section 5, the integral at the gain switch of stage 2",
            f"\"from t = {switch:g} s only integral correction with the Schuler conditions\"",
            "likely reading: the integral state carried through the switch (default)",
            "The text cannot decide. Rescaling the integral by l_new/l_old discards the Earth rate it holds; carrying it, or a bumpless switch, "
            f"keeps the two-stage pitch below the printed bound {PAPER.two_stage_pitch_bound.value:.1e} rad (readings table).",
            "stability",
            kind="ambiguous",
            alternatives=(
                f"bumpless: two-stage pitch peak {bumpless.peaks[1].pitch:.2e} rad (carried: {default.peaks[1].pitch:.2e}); l(t)∫(μ⁺ − 2ν)dτ rescaled with "
                f"the new l: two-stage roll {rescale.peaks[1].roll:.1e} rad, pitch {rescale.peaks[1].pitch:.1e} rad"
            ),
        ),
    ]
