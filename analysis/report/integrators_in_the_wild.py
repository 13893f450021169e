"""Report section ``integrators-in-the-wild.md``: integrators as code, identified as exact algorithms.

Formatting only: every number comes from
:mod:`strapdown.analysis.coning.integrators.studies` (which assesses each
integrator with :func:`~strapdown.analysis.coning.integrators.assessment.assess`).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from ...derivations.coning.registry import get
from ..coning.drift_theory import coning_drift_function
from ..coning.integrators.identification import max_denominator
from ..coning.integrators.studies import CONING, RECURSIONS, SAMPLE_INTERVAL, SCULLING, composition_study, peer_study, recursion_study
from ..coning.integrators.verification import CONE_ANGLES, DRIFT_TOLERANCE
from ..core.units import RAD_PER_S_TO_DEG_PER_H
from . import Section
from .rendering import fixed_layout

SECTION = Section(
    "integrators-in-the-wild",
    "Integrators in the wild: code identified as exact algorithms",
    order=24,
    summary="pyins comes out exactly as Savage's 1 + 1; the autopilots' per-sample recursion for N = 1…8, and with its previous α one sample older; a quaternion per sample; peers like for like.",
)

#: N of the recursion tables (full report, quick report).
SAMPLES = {False: tuple(range(1, 9)), True: (1, 2, 3, 4)}
#: The N also run against the exact solution, per study (full report, quick report).
VERIFIED = {
    "savage": {False: (1, 2, 4, 8), True: (1, 4)},
    "one-accumulator": {False: (4,), True: ()},
    "previous-alpha-older": {False: (2, 4, 8), True: (4,)},
    "previous-increment-overwritten": {False: (4,), True: ()},
    "composition": {False: (1, 2, 4, 8), True: (4,)},
}
#: Studies whose sculling part is tabulated (the others are identified for coning only).
WITH_SCULLING = ("savage", "composition")


def _frac(f: Fraction) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def _terms(a, limit: int = 6) -> str:
    terms = a.identification.terms
    if not terms:
        return "none"
    items = [f"{c} p{k.split(',')[0]}×p{k.split(',')[1]}" for k, c in terms.items()]
    return ", ".join(items) if len(items) <= limit else ", ".join(items[:limit]) + f", … ({len(items)} terms)"


def _drift(a) -> str:
    if a.coning is None:
        return "no α² closed form"
    return f"{_frac(a.coning.coefficient)} α²ω(ωh)^{a.coning.order}"


def _check(check) -> str:
    if check is None:
        return "–"
    if check.holds is None:
        return "no point resolved"
    verdict = "holds" if check.holds else "FAILS"
    return f"{verdict}: {check.largest_difference:.0e} at {len(check.resolved)} of {len(check.points)} ωh"


def _remainder(r) -> str:
    if not r.above_roundoff:
        return "round-off only"
    if r.degree is not None:
        return f"degree {r.degree}, {r.coefficient:.3g}·\\|p\\|^{r.degree}"
    return f"slope {r.slope:.2f}" if r.slope is not None else f"{r.sizes[0]:.2g}"


def _exponent(a) -> str:
    return "–" if a.local_error_exponent is None else f"{a.local_error_exponent:.2f}"


def _tex(f: Fraction) -> str:
    sign = "-" if f < 0 else ""
    f = abs(f)
    return f"{sign}{f.numerator}" if f.denominator == 1 else f"{sign}\\frac{{{f.numerator}}}{{{f.denominator}}}"


def _series(a) -> str:
    """The leading local error ``δ h^(ρ+1) (Σ k_w x_w)`` as LaTeX."""
    e = a.local_error
    if e is None:
        return "–"
    parts = []
    for w, c in e.coefficients.items():
        if c:
            word = f"x_{{{''.join(str(k) for k in w)}}}"
            parts.append(word if c == 1 else "-" + word if c == -1 else f"{_tex(c)}\\,{word}")
    delta = "" if e.delta == 1 else f"{_tex(e.delta)}\\,"
    return f"${delta}h^{{{e.order + 1}}}({' + '.join(parts).replace('+ -', '- ')})$"


def _recursion_table(rows) -> list:
    out = [
        "| N | terms c_ij p_i×p_j | Σ c_ij (j − i) | N³/12 | accuracy order ρ | local error, exact − integrator | coning drift | remainder | measured exponent | simulated vs closed form |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for a in rows:
        c = a.consistency
        out.append(
            f"| {a.identification.samples} | {_terms(a)} | {_frac(c.second_order_sum)} | {_frac(c.second_order_expected)} | {a.order} | {_series(a)} | {_drift(a)} | "
            f"{_remainder(a.identification.remainder)} | {_exponent(a)} | {_check(a.check)} |"
        )
    return out


def _sculling_table(rows) -> list:
    out = ["| N | dual extension of the coning part | departs at | remainder of Δv | simulated vs closed-form rectification |", "|---|---|---|---|---|"]
    for a in rows:
        sc = a.sculling
        departs = ", ".join(f"m_{key[0]}{key[1]} by {_frac(d)}" if kind == "bilinear" else f"a°_{key[0]} by {_frac(d)}" for kind, key, d in sc.defect) or "–"
        out.append(f"| {a.identification.samples} | {'yes' if sc.dual_extension else 'no'} | {departs} | {_remainder(sc.remainder)} | {_check(sc.check)} |")
    return out


def build(ctx) -> None:
    """Write ``integrators-in-the-wild.md`` and its figure.

    Parameters
    ----------
    ctx : Context
        Where to write, and the run mode.
    """
    import matplotlib.pyplot as plt

    samples = SAMPLES[ctx.quick]
    studies = {
        v: recursion_study(v, samples, velocity=v in WITH_SCULLING, verify=VERIFIED[v][ctx.quick]) for v in ctx.progress(list(RECURSIONS), "integrators: recursions")
    }
    composition = composition_study(samples, verify=VERIFIED["composition"][ctx.quick])
    peers = peer_study()
    savage = get("savage-1+1")
    x0 = CONING.nu * SAMPLE_INTERVAL
    lines = [
        "# Integrators in the wild",
        "",
        "A designer's algorithm is code: an autopilot's per-sample recursion, a DCM integrator, a peer library. `strapdown identify`",
        "takes such an integrator as it is — a Python function or object, a compiled C function, a peer's class",
        "(`docs/integrators.md`) — and says what it computes. Designed probes (one or two nonzero increments in a window of",
        "zeros, four signs, amplitudes halving from 0.02 rad and extrapolated to zero) give the coefficients of its linear part",
        "$\\sum_j a_j p_j$ and of its bilinear part $\\sum_{i<j} c_{ij}\\,p_i\\times p_j$ over the current step and the samples",
        "before it (indices ≤ 0), and, for integrators that take accelerometer increments, of $\\sum_{i,j} m_{ij}\\,p_i\\times b_j$ in",
        "the velocity increment. Each is reconstructed as the exact fraction within four times its uncertainty (at most",
        f"{peers[0].assessment.identification.tolerance:g}), the one fraction there among denominators up to $(2t)^{{-1/2}}$ (at least",
        f"{max_denominator(peers[0].assessment.identification.tolerance)}). What the bilinear model leaves, the remainder, is measured on random",
        "windows: its size and its degree in the increments. The identified algorithm then goes through the package: the",
        "second-order condition $\\sum c_{ij}(j-i) = N^3/12$, the exact local-error series (accuracy order ρ: error $O(h^{\\rho+1})$), the coning",
        "drift in closed form $u = c\\,\\alpha^2\\omega(\\omega h)^m$ (exact minus integrator, along the cone axis, as",
        "`strapdown derive coning-drift`). Last, the integrator itself — not its model — runs on the exact increments of",
        f"classical coning at several ωh and cone angles α = {', '.join(f'{a:g}' for a in CONE_ANGLES)} rad, its simulated drift is extrapolated",
        f"to α → 0 and compared with the closed form of what it was identified to be (tolerance {DRIFT_TOLERANCE:g} relative, at the ωh",
        "where the round-off floor and the extrapolation allow it to decide). The measured exponent of its own one-step error",
        "on a tumbling motion is set beside ρ + 1: the remainder changes the order only if they part.",
        "",
        "## pyins: Savage's 1 + 1, exactly",
        "",
        "pyins (`python-ins` on the package index) forms $\\theta_k = p_k + \\frac{1}{12}p_{k-1}\\times p_k$ and the matching sculling",
        "term in `compute_increments_from_imu`, and multiplies direction-cosine matrices in its compiled `Integrator` loop",
        "(run with the Earth rate set to zero at rest, so that its navigation frame is inertial). Both were identified as black",
        "boxes, the loop from the matrices it outputs:",
        "",
        "| integrator | terms | equal to the registry's savage-1+1 | sculling: dual extension | remainder | accuracy order ρ | coning drift | simulated vs closed form |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for p in peers[:2]:
        a = p.assessment
        same = a.algorithm.pairwise == savage.pairwise and a.consistency.first_order
        scull = "–" if a.sculling is None else ("yes" if a.sculling.dual_extension else "no")
        lines.append(f"| {p.label} | {_terms(a)} | {'yes' if same else 'no'} | {scull} | {_remainder(a.identification.remainder)} | {a.order} | {_drift(a)} | {_check(a.check)} |")
    lines += [
        "",
        "## Savage's recursion, as autopilots write it",
        "",
        "Flight code forms the coning term one gyro sample at a time (Savage 1998, part 1, section 7.1.2): with $\\Delta\\alpha_m$ the",
        "m-th increment of the step and $\\alpha_m$ the angle accumulated through it,",
        "",
        "$$\\beta_m = \\beta_{m-1} + \\frac{1}{2}\\left(\\alpha_{m-1} + \\frac{1}{6}\\Delta\\alpha_{m-1}\\right)\\times\\Delta\\alpha_m,\\qquad \\Delta\\varphi = \\alpha_N + \\beta_N,$$",
        "",
        "with $\\Delta\\alpha_0$ the last increment of the previous step, and the sculling recursion its dual extension. ArduPilot",
        "(`AP_InertialSensor_Backend`) writes it with α and β summed in one accumulator that the update reads; PX4",
        "(`IntegratorConing` in `src/modules/sensors/vehicle_imu/Integrator.hpp`, the same update since pull request #4645 of",
        "2016) stores the accumulated angle before adding each sample and crosses that stored value with the next increment.",
        "The recursion was written as a Python integrator (`strapdown.analysis.coning.integrators.recursions`) and identified",
        f"for N = {samples[0]} … {samples[-1]}, and run against the exact solution for the N whose last columns are filled.",
        "",
        f"**{RECURSIONS['savage'][0]}.**",
        "",
        *_recursion_table(studies["savage"]),
        "",
        "Expanded, $c_{ij} = \\frac{1}{2}$ for every pair of the step plus $\\frac{1}{12}$ for each adjacent pair, $p_0\\times p_1$ included:",
        "the second-order condition holds for every N, the order is 3 in a general motion, and under coning the drift is",
        "$\\frac{1}{60}\\alpha^2\\omega(\\omega h)^4$ whatever N — the same, per sample, as Savage's 1 + 1.",
        "",
        f"**{RECURSIONS['one-accumulator'][0]}.** The same bilinear part; the coning corrections read back from the accumulator add",
        "terms of degree three, which the remainder shows and the coning drift does not (they enter at α⁴):",
        "",
        *_recursion_table(studies["one-accumulator"]),
        "",
        "Sculling, the dual recursion (Savage's form):",
        "",
        *_sculling_table(studies["savage"]),
        "",
        "## The previous α one sample older",
        "",
        "If the β update reads the accumulated angle stored at the previous sample before that sample was added —",
        "$\\alpha_{m-2}$ where Savage's recursion has $\\alpha_{m-1}$, as PX4's `IntegratorConing` stores it — the adjacent pairs lose",
        "their ½:",
        "",
        f"**{RECURSIONS['previous-alpha-older'][0]}.**",
        "",
        *_recursion_table(studies["previous-alpha-older"]),
        "",
    ]
    older = studies["previous-alpha-older"]
    defects = ", ".join(f"{_frac(a.consistency.second_order_sum - a.consistency.second_order_expected)} (N = {a.identification.samples})" for a in older[1:])
    lines += [
        f"At N = 1 nothing changes ($\\alpha_{{-1}} = \\alpha_0 = 0$). From N = 2 on the second-order condition fails by {defects}",
        "(that is, −(N − 1)/2), the order drops from 3 to 2 and the coning drift from (ωh)⁴ to (ωh)²: at the like-for-like",
        f"conditions below (ωh = {x0:.3g}) the shifted recursion at N = 4 drifts",
        f"{_ratio(peers, 'previous α one sample older, N = 4', 'Savage')} times as fast as Savage's. The identification shows it from",
        "the code alone, and the integrator's own simulation agrees with the closed form of the shifted algorithm.",
        "",
        f"**{RECURSIONS['previous-increment-overwritten'][0]}.** The slip of the EKFs' 1 + 1 term in PX4 (issue #2663) and",
        "ArduPilot (pull request #1480) in 2014–2015: the stored previous increment was overwritten by the current one before",
        "the cross product read it, so the term was $\\Delta\\alpha_m\\times\\Delta\\alpha_m = 0$. In the recursion every",
        "$\\frac{1}{12}$ vanishes and what is left is the composition of the samples with no coning term (next section):",
        "",
        *_recursion_table(studies["previous-increment-overwritten"]),
        "",
        "## A quaternion per sample, no coning term",
        "",
        "The exact rotation of every sample composed, $\\Lambda(p_1)\\circ\\dots\\circ\\Lambda(p_N)$, each velocity increment rotated by",
        "the attitude at the start of its sample. Its bilinear part is ½ for every pair (the Baker–Campbell–Hausdorff",
        "formula's), short of the second-order condition by N/12; the rest of the composition is a remainder of degree three.",
        "",
        *_recursion_table(composition),
        "",
        "Its sculling part is not the dual extension of its coning part: the rotation term $\\frac{1}{2} p_j\\times b_j$ within each",
        "sample is missing.",
        "",
        *_sculling_table(composition),
        "",
        "## Peers like for like",
        "",
        f"Every integrator gets the same increments: classical coning at {CONING.nu / (2 * math.pi):g} Hz with half-cone angle",
        f"{math.degrees(CONING.nutation):g}° (Budennyi, Kalinovsky, Panov et al., Table 3), and classical sculling at {SCULLING.nu / (2 * math.pi):g} Hz",
        f"(θ₀ = {SCULLING.angle_amplitude:g} rad, A = {SCULLING.accel_amplitude:g} m/s², in phase), both sampled at {1 / SAMPLE_INTERVAL:g} Hz",
        f"(ωh = {x0:.4g} rad), with the samples before t = 0 from the same motion; every attitude and velocity is measured against the",
        "same exact solution. Beside each simulated figure: the closed form of what the integrator was identified to be (α² term",
        "for coning, first order in θ₀A for sculling).",
        "",
        "| integrator | source | N | identified terms | coning drift simulated [deg/h] | closed form [deg/h] | sculling rate simulated [m/s²] | closed form [m/s²] |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for p in peers:
        cf = "–" if p.drift_closed_form is None else f"{p.drift_closed_form * RAD_PER_S_TO_DEG_PER_H:.4g}"
        sc = "–" if p.sculling is None else f"{p.sculling:.4g}"
        sc_cf = "–" if p.sculling_closed_form is None else f"{p.sculling_closed_form:.4g}"
        lines.append(f"| {p.label} | {p.source} | {p.samples} | {_terms(p.assessment, 3)} | {p.drift * RAD_PER_S_TO_DEG_PER_H:.4g} | {cf} | {sc} | {sc_cf} |")
    lines += [
        "",
        "pyins's two entry points and the registry's savage-1+1 run from its own terms are one algorithm, and drift alike. smsfusion",
        "(1.9) updates its quaternion to first order and normalises it, with no coning or sculling term: identified, that is the",
        "one-sample algorithm, whose drift is (ωh)² — the composition of four samples per step drifts as much per unit time.",
        "For a high-order algorithm such as compressed-4 at 1° the simulated drift is its α⁴ term, not the α² closed form",
        "(frequency-response section); at small angles the two agree (the checks above).",
        "",
        "![coning drift of identified integrators against ωh](figures/integrators-in-the-wild.png)",
        "",
        "Lines: the closed form |D(ωh)| of each identified algorithm ($u = \\alpha^2\\omega D$); markers: the integrator's own simulated",
        "drift extrapolated to α → 0, at the points the round-off floor resolves. pyins falls on Savage's recursion (dashed on solid),",
        "smsfusion on the composition without coning term: per sample they are the same algorithms.",
        "",
    ]
    curves = [
        ("Savage's recursion, N = 4", studies["savage"][samples.index(4)]),
        ("previous α older, N = 4", studies["previous-alpha-older"][samples.index(4)]),
        ("quaternion composition, N = 4", composition[samples.index(4)]),
        ("pyins (Savage's 1 + 1)", peers[0].assessment),
        ("smsfusion StrapdownINS", peers[2].assessment),
    ]
    ctx.savefig(_figure(plt, curves), "figures/integrators-in-the-wild.png")
    ctx.write_text("integrators-in-the-wild.md", "\n".join(lines))


def warm_up() -> None:
    """Compile the peers' numba code into its disk cache (:mod:`strapdown.analysis.coning.integrators.peers`): pyins's loop and smsfusion's helpers."""
    from ..coning.integrators.interface import step_increments
    from ..coning.integrators.peers import pyins_integrator, smsfusion_ins

    pyins_integrator(sample_interval=SAMPLE_INTERVAL)  # runs its loop at rest: compiled
    step_increments(smsfusion_ins(sample_interval=SAMPLE_INTERVAL), np.zeros((2, 3)), 1, np.zeros((2, 3)))


def _ratio(peers, label: str, reference: str) -> str:
    a = next(p for p in peers if p.label == label)
    b = next(p for p in peers if p.label.startswith(reference))
    return f"{a.drift / b.drift:,.0f}"


def _figure(plt, curves):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    grid = np.geomspace(0.05, 2.5, 120)
    cmap = plt.get_cmap("tab10")
    styles = (("-", "o", 6), ("-", "o", 6), ("-", "o", 6), ("--", "s", 9), ("--", "s", 9))  # the peers dashed: they fall on the recursions' lines
    for k, ((label, a), (line, marker, size)) in enumerate(zip(curves, styles)):
        color = cmap(k)
        d = np.abs(np.asarray(coning_drift_function(a.algorithm)(grid), dtype=float))
        ax.loglog(grid, d, line, color=color, lw=1.3, label=f"{label}: {_drift(a)}")
        if a.check is not None:
            pts = a.check.resolved
            ax.loglog([p.x for p in pts], [abs(p.simulated) for p in pts], marker, color=color, ms=size, mfc="none")
    ax.set_xlabel("ωh: coning rate × sample interval [rad]")
    ax.set_ylabel("|D(ωh)| = |u| / (α² ω)")
    ax.set_title("Identified integrators: closed form (lines) and their own simulation (markers)", fontsize=10)
    ax.legend(fontsize=7, loc="lower right")
    fixed_layout(fig, left=0.8, right=0.15, bottom=0.5, top=0.35)
    return fig
