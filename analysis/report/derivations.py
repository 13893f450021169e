"""Report section ``derivations.md``: local-error series, drift theory, sampling design.

Formatting only.  The series and their checks against print come from
:mod:`strapdown.derivations.coning.series_summary`,
:mod:`strapdown.derivations.coning.printed_checks` and
:mod:`strapdown.derivations.coning.leading_drift`; Table 3 from
:mod:`strapdown.analysis.coning.papers.budennyi_table3`, the u*/u_a check from
:mod:`strapdown.analysis.coning.drift_crosscheck`, Tables 4–5 from
:mod:`strapdown.analysis.coning.papers.budennyi_loads`; the printed numbers from
:mod:`strapdown.derivations.coning.published`.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...derivations.coning import drift as D
from ...derivations.coning import published as P
from ...derivations.coning import series as S
from ...derivations.coning.algorithms import Algorithm
from ...derivations.coning.leading_drift import optimal_coning, same_transport, small_cone_limit
from ...derivations.coning.printed_checks import eq_2_4_check, structure_function_checks, table2_checks
from ...derivations.coning.registry import get, names
from ...derivations.coning.series_summary import drift_coefficients, exact_increment, local_error_summary, structure_summary
from ..coning.computational_load import quaternion_update, quaternion_update_count
from ..coning.drift_crosscheck import drift_ratios
from ..coning.drift_theory import algorithm_key
from ..coning.papers import budennyi_loads as L45
from ..coning.papers.budennyi_table3 import drift_estimates, leading_estimates, table3_agreement
from ..coning.papers.formula_one import column_2_estimates
from ..coning.precession import RegularPrecession
from ..core.cache import derived
from ..core.units import deg_per_h, rad
from . import Erratum, Section
from .rendering import fixed_layout

SECTION = Section(
    "derivations",
    "Derivations: local-error series, asymptotic drift, sampling design",
    order=30,
    summary="Series to h⁷ for every algorithm, Table 2 and eq. (2.4) derived, drift structure functions, u_a vs u*, Tables 4–5 and their extension to 4000 Hz.",
)

SIM_DURATION = 8.0  # [s] cross-check runs: 80 precession periods at ε = 0.5
#: The u*/u_a cross-check runs at f = 10 Hz, ϑ = 10°.
CROSSCHECK_MOTIONS = tuple(RegularPrecession(eps, 2 * math.pi * 10.0, rad(10.0)) for eps in (-1.0, 0.5))
EXTENSION_ALGORITHMS = tuple(f"panov-4s-{k}" for k in range(1, 6)) + ("optimal-3", "lebedev-panov-6")


def _derived(fn, *args):
    """``fn(*args)`` of a SymPy derivation, from the cache of derived results (per source version; an algorithm by its content).

    Only for results whose printed form survives pickling: SymPy rebuilds an
    unpickled product by evaluating it, so ``-(32ε² + 31ε cos ϑ − 28)/4``
    comes back distributed (the structure summaries are not cached for that).
    """
    key = ":".join([fn.__module__, fn.__qualname__, "v1", *(algorithm_key(a) if isinstance(a, Algorithm) else repr(a) for a in args)])
    return derived(key, lambda: fn(*args))


def _tex(expr) -> str:
    return sp.latex(expr, symbol_names={D.THETA_DUAL: "\\vartheta^\\circ"})


def _printed_table3(algorithm: int, eps: float):
    return next(r for r in P.BUDENNYI_TABLE_3 if r.algorithm == algorithm and r.eps == eps)


def _budget(u: float) -> str:
    """A drift budget as the paper writes it: 1e-3."""
    return f"{u:.0e}".replace("e-0", "e-")


def _signed(k) -> str:
    """An integer with a typographic minus."""
    return f"−{-k}" if k < 0 else f"{k}"


def build(ctx) -> None:
    """Write ``derivations.md`` and its figures.

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        Where to write, and whether to run the quick variant.
    """
    import matplotlib.pyplot as plt

    lines = ["# Derivations: local-error series, asymptotic drift, sampling design", ""]
    lines += [
        "All series below are derived by `strapdown.derivations.coning.series` and `strapdown.derivations.coning.drift` (SymPy, exact rationals) when",
        "this report is built. $\\omega^{(k)}$ is the k-th derivative of the body rate at the middle of the step",
        "$H = N h$, and $x_{\\alpha\\beta\\dots\\gamma\\delta} = \\omega^{(\\alpha)}\\times(\\omega^{(\\beta)}\\times\\dots\\times(\\omega^{(\\gamma)}\\times\\omega^{(\\delta)}))$",
        "(Lebedev & Panov 1989, eq. (2.4)). A product of weight $w = \\sum(k+1)$ multiplies $H^w$; everything is kept",
        "through weight 7.",
        "",
    ]
    lines += _exact_section()
    lines += _local_error_section()
    lines += _table2_section()
    lines += _eq24_section()
    lines += _structure_section()
    lines += _drift_section()
    steps = (0.02, 0.01, 0.005) if ctx.quick else (0.04, 0.02, 0.01, 0.005)
    ratios = drift_ratios(CROSSCHECK_MOTIONS, steps=steps, duration=SIM_DURATION)
    lines += _crosscheck_section(ratios)
    ctx.savefig(_crosscheck_figure(plt, ratios), "figures/derivations-ua-vs-ustar.png")
    lines += _coning_section()
    lines += _design_section()
    fig, ext = _extension(plt, ctx.quick)
    ctx.savefig(fig, "figures/derivations-load-vs-frequency.png")
    lines += ext
    ctx.write_text("derivations.md", "\n".join(lines))


def _exact_section() -> list:
    ex = exact_increment()
    return [
        "## 1. Exact rotation-vector increment",
        "",
        "With $2\\Lambda' = \\Lambda\\circ\\omega$ the step quaternion is the time-ordered exponential of $\\omega/2$; its",
        "coefficients on words in the letters $\\omega^{(k)}$ are iterated integrals of monomials (exact rationals). The",
        "logarithm of that series is $\\varphi/2$ (Magnus), and the Dynkin–Specht–Wever map turns it into nested",
        "products: a Lie word of length n with coefficient c contributes $(c/n)\\,x_w$. Reduced to an independent set",
        "of nested products of the free Lie algebra, the exact increment over $[t_m - H/2, t_m + H/2]$ is",
        "",
        f"$$\\Delta\\varphi = {S.series_latex(ex.step)}$$",
        "",
        "(each $x_w$ times $H^{w}$; the even weights vanish because the expansion point is the middle of the step).",
        "A test integrates $2\\Lambda' = \\Lambda\\circ\\omega$ with DOP853 for a polynomial ω(t): halving H divides the",
        "difference by 512, i.e. the remainder is $O(H^9)$. Over the first half step $[t_m - H/2, t_m]$ (used for the",
        "drift below):",
        "",
        f"$$\\Delta\\varphi_1 = {S.series_latex(ex.first_half)}$$",
        "",
    ]


def _local_error_section() -> list:
    lines = [
        "## 2. Local error of every registry algorithm",
        "",
        "The increments $p_j$ of the same ω(t) are linear in the 21 components of $\\omega^{(0)}\\dots\\omega^{(6)}$;",
        "each algorithm (cross, triple and dot-product terms) is evaluated component-wise in a `sympy.polys` ring",
        "with graded truncation, and the exact increment is subtracted. The leading term is written in the",
        "convention of Budennyi, Kalinovsky, Panov et al., Table 2, which this derivation identifies (section 3):",
        "",
        "$$\\Delta\\varphi_{exact} - \\Delta\\varphi_{alg} = \\delta_\\rho\\, h^{\\rho+1} \\sum_w k_w x_w + O(h^{\\rho+2}),$$",
        "",
        "h the sample interval, $\\delta_\\rho = 1/\\mathrm{lcm}$ of the denominators. Weight 5 uses the basis",
        "$x_{03}, x_{12}, x_{002}, x_{110}, x_{0001}$ (independent in R³); other weights an independent set of nested",
        "products chosen in a fixed order. Dual (velocity) part by the transfer principle: each factor",
        "$\\omega^{(k)}$ in turn replaced by $a^{(k)}$ (marked °).",
        "",
        "| algorithm | N | accuracy order ρ | nonzero weights ≤ 7 (the first: the local-error order ρ + 1) | leading local error |",
        "|---|---|---|---|---|",
    ]
    for name in names():
        s = local_error_summary(get(name))
        nz = ", ".join(str(w) for w in s.nonzero_weights)
        lines.append(f"| {s.name} | {s.samples} | {s.leading.order} | {nz} | ${s.leading.latex()}$ |")
    dual = local_error_summary(get("panov-4s-3")).leading.latex(dual=True)
    lines += ["", "Dual part, for example for panov-4s-3:", "", f"$${dual}$$", ""]
    return lines


def _table2_section() -> list:
    checks = table2_checks()
    first = checks[0]
    lines = [
        "## 3. Table 2 of Budennyi, Kalinovsky, Panov et al., derived",
        "",
        "The derived coefficients equal the printed ones with the sign **exact minus algorithm**, the power",
        "**$h^5$ of the sample interval** (not $H^5$), and $\\delta_4$ factored out; the products $\\delta_4 k$ are the",
        "invariant. $\\delta_4 = 1/\\mathrm{lcm}$(denominators) reproduces the printed $\\delta_4$ of algorithms 2–5;",
        f"for algorithm 1 the table factors a further 4 into $\\delta_4$ ({first.delta} with k03 = {_signed(first.printed[0])}).",
        "",
        "| alg. | | δ4 | k03 | k12 | k002 | k110 | k0001 |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for c in checks:
        cells = [f"**{d}**" if bad else f"{d}" for d, bad in zip(c.derived, c.differs)]
        lines.append(f"| {c.algorithm} | printed | {c.delta} | " + " | ".join(str(p) for p in c.printed) + " |")
        lines.append(f"| {c.algorithm} | derived | {c.delta} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "(derived values rescaled to the printed δ4; **bold** = differs from print.)",
        "",
    ]
    lines += _table2_commentary(checks)
    return lines


def _table2_commentary(checks) -> list:
    c4 = next(c for c in checks if c.algorithm == 4)
    c3 = next(c for c in checks if c.algorithm == 3)
    c2 = next(c for c in checks if c.algorithm == 2)
    col2 = column_2_estimates()
    t_c, t_p = _printed_table3(2, -1.0), _printed_table3(2, 0.5)
    return [
        f"Algorithm 4: the printed k002 = {c4.printed[2]}, k0001 = {_signed(c4.printed[4])} are not what the algorithm gives "
        f"({c4.derived[2]}, {_signed(c4.derived[4])}: the",
        f"terms $x_{{002}}, x_{{110}}, x_{{0001}}$ come only from the exact increment, so $\\delta_4 k_{{002}} = {c3.products[2]} "
        f"= {c4.derived[2]}/{c4.delta.denominator}$",
        "is the same for every pairwise algorithm, as the other four columns show). The printed u_a of algorithm 4",
        f"in Table 3 agrees with the derived coefficients (section 6), so {c4.printed[2]} is a misprint of {c4.derived[2]}.",
        "",
        f"Algorithm 2: with Table 1 as printed (a3 = 4/3, i.e. 4/3 (p1×p3 + p2×p4)) the derivation gives k12 = {col2.k12}, not {c2.printed[1]},",
        f"and drift rates of {deg_per_h(col2.asymptotic.coning):.3f} / {deg_per_h(col2.asymptotic.precession):.3f} deg/h against the printed "
        f"u_a = {t_c.u_a_deg_per_h:g} / {t_p.u_a_deg_per_h:.3f} and u* = {t_c.u_star_deg_per_h:g} / {t_p.u_star_deg_per_h:g} (Table 3);",
        "the algorithm 4/3 (p1×p4 + p2×p3), i.e. a1 = a2 = 4/3, reproduces Table 2, u_a and u*. The registry uses it",
        "(errata: see the algorithms section). The reconstructed formula (1) (a1 → p2×p3, a2 → p1×p4,",
        "a3 → p1×p3 + p2×p4, a4 → p1×p2 + p3×p4) is otherwise confirmed: among all assignments of sets of pair",
        "products to the four constants, it is the only one that satisfies the second-order condition for all five",
        "algorithms and matches the printed k03, k12 of four of them.",
        "",
    ]


def _eq24_section() -> list:
    check = eq_2_4_check()
    lower = list(check.lower_weights)
    return [
        "## 4. Accuracy order 6: eq. (2.4) of Lebedev & Panov (1989)",
        "",
        "The nested algorithm (2.2), registered exactly as printed including $-\\tfrac{64}{45}(1 - p_2\\cdot p_3)\\,p_2\\times p_3$,",
        f"has no local error below weight 7 (nonzero weights below 7: {lower or 'none'}): its local-error order is 7, its accuracy order 6. The dot-product",
        "term is essential: $(p_2\\cdot p_3)\\,p_2\\times p_3 = -h^5 x_{0001} + \\dots$ cancels the $x_{0001}$ term of the exact",
        "increment, and without it the algorithm drops to accuracy order 4 (tested).",
        "",
        "Its $h^7$ term, exact minus algorithm, compared with (2.4) as printed *by value* (as polynomials in the 21",
        "components of $\\omega^{(0)}\\dots\\omega^{(6)}$, i.e. for all ω-derivatives; the 20 printed products are linearly",
        f"dependent, so coefficients are not compared): **{'identical' if check.identical else 'different'}**. "
        f"Eq. (2.4) is {'correct' if check.identical else 'not correct'} as printed.",
        "In the independent basis of section 2:",
        "",
        f"$${local_error_summary(get('lebedev-panov-6')).leading.latex()}$$",
        "",
    ]


def _structure_section() -> list:
    lines = [
        "## 5. Structure functions under regular precession",
        "",
        "On the precession (4.1) every ω-derivative, hence every $x_w$ and the whole local error, turns about $e_z$ of E",
        "at the rate −ν, while the attitude turns about the fixed precession axis; so the error each step adds in",
        "frame I is one vector turned by εν t, and its constant part lies along the precession axis",
        "$n = (\\sin\\vartheta\\sin\\nu t, \\sin\\vartheta\\cos\\nu t, \\cos\\vartheta)$ (in E). With X the bracket of the leading",
        "local error at t = 0, $A_\\rho = X_z = \\varepsilon\\nu^{\\rho+1}\\sin^2\\vartheta\\,f_\\rho$ and",
        "$B_\\rho = X_y = \\varepsilon\\nu^{\\rho+1}\\sin\\vartheta\\,g_\\rho$ (Lebedev & Panov 1989, (5.3)); the dual functions are",
        "$f_\\rho^\\circ = \\vartheta^\\circ\\partial f_\\rho/\\partial\\vartheta$, $g_\\rho^\\circ = \\vartheta^\\circ\\partial g_\\rho/\\partial\\vartheta$ (transfer principle with",
        "$\\nu\\to\\nu+s\\nu^\\circ$, $\\vartheta\\to\\vartheta+s\\vartheta^\\circ$). Printed against derived for (2.2) truncated to accuracy orders 2 and 4:",
        "",
        "| accuracy order ρ | function | printed | derived | equal |",
        "|---|---|---|---|---|",
    ]
    checks = structure_function_checks()
    for c in checks:
        label = c.name.replace("_dual", "^\\circ")
        lines.append(f"| {c.order} | ${label}$ | ${_tex(c.printed)}$ | ${_tex(c.derived)}$ | {'yes' if c.equal else '**no**'} |")
    n_equal = sum(c.equal for c in checks)
    verdict = f"All {n_equal} printed functions are reproduced." if n_equal == len(checks) else f"{n_equal} of {len(checks)} printed functions are reproduced."
    lines += [
        "",
        f"with $\\delta_2 = {structure_summary(get('lebedev-panov-2')).delta}$ $(= r^3/12)$ and "
        f"$\\delta_4 = {structure_summary(get('lebedev-panov-4')).delta}$. {verdict}",
        "For the five four-sample algorithms:",
        "",
        "| algorithm | δ4 | $f_4$ | $g_4$ | $g_4 + f_4\\cos\\vartheta$ |",
        "|---|---|---|---|---|",
    ]
    for k in range(1, 6):
        s = structure_summary(get(f"panov-4s-{k}"))
        lines.append(f"| {s.name} | {s.delta} | ${_tex(s.f)}$ | ${_tex(s.g)}$ | ${_tex(s.drift_factor)}$ |")
    lines += [
        "",
        "The drift is $\\delta_4 h^4/r\\cdot\\varepsilon\\nu^5\\sin^2\\vartheta\\,(g_4 + f_4\\cos\\vartheta)$: for algorithms 3 and 5 the factor",
        "is $2(1-\\varepsilon^2)$, which vanishes for coning (ε = −1) at every ϑ, ν and h — under coning their drift order is 6",
        "(drift ∝ $H^6$), two above their accuracy order.",
        "",
    ]
    return lines


def _drift_section() -> list:
    lines = [
        "## 6. Asymptotic drift u_a, and Table 3",
        "",
        "One algorithm step from the true attitude gives $\\Lambda_n\\circ e^{\\Delta\\varphi+\\delta\\varphi} = e^{(J\\delta\\varphi)_I}\\circ\\Lambda_{n+1}$ with",
        "$J = (e^{\\mathrm{ad}\\,\\Delta\\varphi}-1)/\\mathrm{ad}\\,\\Delta\\varphi$; seen from the attitude at mid-step, $\\Lambda(t_m) = \\Lambda_n\\circ e^{\\Delta\\varphi_1}$,",
        "the error vector is $\\delta\\varphi_I = e^{-\\mathrm{ad}\\,\\Delta\\varphi_1} J\\,\\delta\\varphi$. The drift rate along the precession axis is",
        "",
        "$$u = \\frac{n\\cdot\\delta\\varphi_I}{H} = \\sum_{w\\le 7} d_w(\\varepsilon,\\vartheta)\\,\\nu^w H^{w-1},\\qquad u_a = |d_{\\rho+1}|\\,\\nu^{\\rho+1}H^{\\rho}.$$",
        "",
        "To leading order $\\delta\\varphi_I = \\delta\\varphi$ and u_a is the paper's (5.3). When the leading term cancels (coning,",
        "algorithms 3 and 5) the weight-7 drift also receives $\\tfrac{H^2}{8}\\omega'\\times\\delta\\varphi_5 + \\tfrac{H^2}{24}\\omega\\times(\\omega\\times\\delta\\varphi_5)$",
        "from the weight-5 error, whose projection on n vanishes but whose transport does not. Derived coefficients:",
        "",
        "| algorithm | $d_5$ | $d_7$ |",
        "|---|---|---|",
    ]
    for name in names():
        d = _derived(drift_coefficients, get(name))
        lines.append(f"| {d.name} | ${_tex(d.d5)}$ | ${_tex(d.d7)}$ |")
    lines += _table3_table()
    return lines


def _table3_table() -> list:
    rows = drift_estimates()
    lines = [
        "",
        "Table 3 (ϑ = 1°, f = 10 Hz, H = 0.01 s), deg/h. *u_a (paper level)* projects only $\\delta\\varphi_7$, without the",
        "transport terms; *series* keeps every term through $h^7$; *u\\* (ours)* is the simulator (20 s run).",
        "",
        "| alg. | ε | drift order (the table's ρ) | u* printed | u* ours | u_a printed | u_a derived | derived/printed | series | u_a paper level |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        p = r.printed
        ours = deg_per_h(r.asymptotic)
        ratio = "–" if p.u_a_deg_per_h is None else f"{1 + r.asymptotic_vs_printed:.4f}"
        pl = "–" if r.mid_step is None else f"{deg_per_h(r.mid_step):.4g}"
        ua = "–" if p.u_a_deg_per_h is None else f"{p.u_a_deg_per_h:.3g}"
        lines.append(
            f"| {p.algorithm} | {p.eps:g} | {r.order} | {p.u_star_deg_per_h:.3g} | {deg_per_h(r.simulated):.4g} | {ua} | {ours:.4g} | {ratio} | {deg_per_h(r.series):.4g} | {pl} |"
        )
    lines += _table3_commentary(rows)
    return lines


def _table3_commentary(rows) -> list:
    agree = table3_agreement(rows)
    rho6 = agree.order_6
    sci = lambda values: ", ".join(f"{v:.3g}" for v in values)  # noqa: E731
    lines = [
        "",
        f"Every printed u_a of drift order 4 is reproduced within {100 * agree.worst_order_4:.2g} %. For drift order 6 (coning, algorithms "
        f"{', '.join(str(r.printed.algorithm) for r in rho6)}) the derived u_a ({sci(deg_per_h(r.asymptotic) for r in rho6)}) agrees with the printed "
        f"simulation u* ({sci(r.printed.u_star_deg_per_h for r in rho6)}) and with ours within {100 * agree.worst_order_6_vs_simulated:.1f} %; the printed u_a "
        f"({sci(r.printed.u_a_deg_per_h for r in rho6)}) are compared with both estimates below.",
    ]
    lines += [f"The u_a of algorithm {r.printed.algorithm} at ε = {r.printed.eps:g}, not printed, is {deg_per_h(r.asymptotic):.4g} deg/h." for r in agree.unprinted]
    lines += [""]
    lines += _order6_section()
    return lines


def _order6_section() -> list:
    est = leading_estimates()
    lines = [
        "### The cells of drift order 6: three estimates of u_a",
        "",
        "Where the $H^4$ drift cancels, the papers' estimate (the leading local error, here of weight 7, expanded at",
        "the middle of the step and projected on the precession axis: Lebedev & Panov 1989, (5.2)–(5.3); the formula (3) of",
        "Budennyi et al. is lost in the stored text, which cites Panov (1995) for it) and the full leading term of the drift",
        "series differ by the transport of the weight-5 error. The small-angle term is the part of the full term of second",
        "order in the nutation ϑ, the classical coning drift $c\\,\\vartheta^2\\nu(\\nu h)^6$ (`derive coning-drift`); at ϑ = 1° the",
        "terms of order ϑ⁴ make up the rest. Signed rates along the precession axis (exact minus algorithm, the package's",
        "convention), deg/h; u_a is the magnitude:",
        "",
        "| alg. | u_a printed | mid-step estimate | small-angle term | full leading term | transport | u* printed | u* ours | printed / mid-step | printed / small-angle | printed / full |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for e in est:
        p = e.printed
        lines.append(
            f"| {p.algorithm} | {p.u_a_deg_per_h:.3g} | {deg_per_h(e.mid_step):.4g} | {deg_per_h(e.small_angle):.4g} | {deg_per_h(e.full):.4g} | {deg_per_h(e.transport):+.4g} | "
            f"{p.u_star_deg_per_h:.3g} | {deg_per_h(e.simulated):.4g} | {1 + e.printed_vs_mid_step:.4f} | {1 + e.printed_vs_small_angle:.4f} | {1 + e.printed_vs_full:.4f} |"
        )
    three = next(e for e in est if e.printed.algorithm == 3)
    five = next(e for e in est if e.printed.algorithm == 5)
    same = same_transport(get("panov-4s-3"), get("panov-4s-5"), 7)
    lines += [
        "",
        f"Algorithm 5: the printed u_a equals the mid-step estimate to {100 * abs(five.printed_vs_mid_step):.1f} %: it is the papers' own estimate, a",
        f"legitimate approximation, less accurate than the full term, which matches the simulation within {100 * abs(five.full_vs_simulated):.1f} %; not a misprint.",
        f"Algorithm 3: the printed u_a is {100 * three.printed_vs_mid_step:+.1f} % from the mid-step estimate and {100 * three.printed_vs_full:+.1f} % from the full term,",
        f"but {100 * three.printed_vs_small_angle:+.2f} % from the small-angle term: it is the classical small-cone-angle estimate, a third legitimate",
        f"approximation ({100 * five.printed_vs_small_angle:+.1f} % for algorithm 5). The transport term is "
        + ("the same expression for both algorithms (derived symbolically: their local errors of weight 5 are equal)" if same else "different for the two algorithms")
        + f", {deg_per_h(three.transport):.3g} deg/h here, so the two printed values come from two different",
        "estimates, each reproduced to the printed digits; the column is not computed one way, but neither value is a misprint.",
        "",
    ]
    return lines


def _crosscheck_section(ratios) -> list:
    steps = ratios[0].steps
    lines = [
        "## 7. u_a against simulated u*",
        "",
        f"Every registry algorithm, ϑ = 10°, f = 10 Hz, ε = −1 and 0.5, simulated {SIM_DURATION:g} s with `strapdown.analysis.coning.simulator`",
        "(drift = norm of the least-squares slope of the attitude error in frame I). The ratio u*/u_a tends to 1 as",
        "H → 0, and $|u^*/u_a - 1|$ falls by about 4 per halving of H (the next drift term is two weights higher).",
        "Two limits of the check: optimal-3 under coning has $d_5 \\propto 1 - \\cos\\vartheta$ (it is built to cancel coning",
        "drift), so its weight-7 term dominates down to much smaller steps and the ratio converges only there; and for",
        "the coning rows of drift order 6 the periodic error from the weight-5 part (amplitude ∝ H⁴) biases the fitted slope of a",
        "finite run once the drift (∝ H⁶) becomes small, which is why steps below 5 ms are not shown. The test suite",
        "checks the same limit without that bias with a one-step oracle (the error one step adds along the precession",
        "axis), down to ratios within 2 % and the predicted rate.",
        "",
        "| algorithm | ε | drift order | " + " | ".join(f"H = {h * 1e3:g} ms" for h in steps) + " |",
        "|---|---|---|" + "---|" * len(steps),
    ]
    for r in ratios:
        lines.append(f"| {r.algorithm} | {r.eps:g} | {r.order} | " + " | ".join(f"{x:.4f}" for x in r.ratios) + " |")
    lines += ["", "![u*/u_a](figures/derivations-ua-vs-ustar.png)", ""]
    return lines


def _crosscheck_figure(plt, ratios):
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), sharey=True)
    for ax, eps in zip(axes, (-1.0, 0.5)):
        for r in (r for r in ratios if r.eps == eps):
            ax.loglog(r.steps * 1e3, np.maximum(r.deviations, 1e-8), "o-", ms=3, label=f"{r.algorithm} ($H^{r.order}$)")
        steps = ratios[0].steps
        s = np.array([steps[0], steps[-1]])
        ax.loglog(s * 1e3, 0.3 * (s / s[0]) ** 2, "k--", lw=0.8, label="slope 2")
        ax.set_title(f"ε = {eps:g}, ϑ = 10°, f = 10 Hz")
        ax.set_xlabel("step H [ms]")
        ax.set_xticks(steps * 1e3, [f"{h * 1e3:g}" for h in steps])
        ax.xaxis.set_minor_formatter(plt.NullFormatter())
    axes[0].set_ylabel("|u*/u_a − 1|")
    axes[1].legend(fontsize=6, loc="lower right")
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.2)
    return fig


def _coning_section() -> list:
    lines = [
        "## 8. Optimal N-sample coning algorithms",
        "",
        "Under pure coning (ε = −1, cone angle α) the projection $n\\cdot(p_i\\times p_j)$ depends only on the lag $j-i$, so a",
        "pairwise algorithm acts through its lag sums $k_l = \\sum_{j-i=l} c_{ij}$. Solving for the lag sums that cancel",
        "the first N−1 terms of the exact $\\alpha^2$ drift in $x = \\nu h$ (the exact step rotation from (4.4)) gives the optimal",
        "class, and its leading remainder is the closed form $u = \\alpha^2\\Omega(\\Omega H)^{2N}/C_N$ (Ω = ν, H = N h):",
        "",
        "| N | lag sums $k_1 … k_{N-1}$ | exponent | $C_N$ |",
        "|---|---|---|---|",
    ]
    for N in (2, 3, 4):
        o = _derived(optimal_coning, N)
        lines.append(f"| {o.samples} | {', '.join(str(k) for k in o.lag_sums)} | {o.exponent} | {o.constant} |")
    l2 = _derived(small_cone_limit, get("two-sample"), 5)
    l3 = _derived(small_cone_limit, get("optimal-3"), 7)
    lines += [
        "",
        "The same constants fall out of the general series of section 6 as a special case: at ε = −1 and ϑ = α → 0,",
        f"$d_5/\\alpha^2 \\to {_tex(l2)}$ for two-sample (N = 2) and $d_7/\\alpha^2 \\to {_tex(l3)}$ for optimal-3 (N = 3), i.e. $-1/C_2$ and $-1/C_3$",
        "along the precession axis (exact minus algorithm; the cone axis is its opposite at ε = −1)",
        "(Ignagni 1990). For N = 4 the remainder is of weight 9, beyond the $h^7$ series, and comes from the closed form only.",
        "",
    ]
    return lines


def _design_section() -> list:
    rep = L45.reproduce_loads()
    lines = _load_model_text(rep.model)
    lines += _load_cells_table(rep)
    lines += _load_sensitivity(rep)
    lines += _load_misses(rep)
    lines += _load_comparison(rep)
    return lines


def _load_model_text(model) -> list:
    m = model.m
    counts = L45.operation_count_checks()
    same = all(c.equal for c in counts)
    terms = (2, 3, 4, 5)
    lines = [
        "## 9. Computational load (Tables 4–5)",
        "",
        "Every printed load is recomputed from operation counts, with one model for both motions and both budgets and",
        "no constant fitted to the printed loads (`strapdown.analysis.coning.papers.budennyi_loads.reproduce_loads`). One step is",
        "the increment algorithm followed by one quaternion update; an operation is an addition and a multiplication",
        f"counts as m = {m:g} additions, $\\sigma = s + m u$ (eq. (6)).",
        "",
        "- **Algorithm.** The operations of the increment (`strapdown.analysis.coning.computational_load.operation_count`:",
        "  P = Σp in 3(N−1) additions, terms grouped by coefficient, a group that factors by bilinearity as",
        "  $(\\sum \\pm p_i)\\times(\\sum \\pm p_j)$ counted as one cross product). The counts "
        + ("equal Table 2 for all five algorithms: " if same else "differ from Table 2: ")
        + ", ".join(f"{c.algorithm}: s = {c.counted[0]}, u = {c.counted[1]}" for c in counts)
        + ".",
        "- **Quaternion update** $\\Lambda \\leftarrow \\Lambda\\circ\\lambda(\\Delta\\varphi)$ with the half-angle series cut after K terms "
        "(`quaternion_update`): "
        + "; ".join(f"{op.name}: {op.additions}+, {op.multiplications}×" for op in quaternion_update(4))
        + " (shown for K = 4; the powers of x are shared, each series term costs one multiplication and one addition). Its cost is "
        + ", ".join(f"σ_q = {quaternion_update_count(k).cost(m):g} for K = {k}" for k in terms)
        + "; no normalisation.",
        "- **Series rule.** Cutting the series after K terms changes the rotation angle of a step by",
        "  $\\delta\\theta_K \\approx 4K(\\varphi/2)^{2K+1}/(2K+1)!$, with $\\varphi = |\\omega| H$ the angle turned in the step; K is the smallest",
        f"  number of terms with $\\delta\\theta_K / H \\le f\\,[u]$, f = {model.truncation_fraction:g}: the truncation may add at most a tenth of the",
        "  budget to the drift of the algorithm (the order-of-magnitude margin the paper asks of algorithm errors).",
        f"- **Time base.** The paper does not state it. Here β = σ/{'h' if model.time_base == 'sample' else 'H'}: "
        + (
            "the work of a step is done within one sample interval h = H/4 after its last sample (the peak, 'maximum' load)."
            if model.time_base == "sample"
            else "the work of a step spread over the step H (the average load)."
        ),
        "- **Step.** β_a: the largest step from u_a (section 6); β*: from the simulated u* at H = 0.01 s (20 s run), scaled",
        "  with the drift order at the motion (the power of H of its leading term).",
        "",
    ]
    return lines


def _load_cells_table(rep) -> list:
    lines = [
        "| alg. | ε | load | [u] deg/h | H [ms] | φ [rad] | K | σ_alg | σ_q | β model | β printed | difference |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in rep.cells:
        r = c.row
        mark = "" if abs(c.relative_difference) <= rep.tolerance else " **miss**"
        lines.append(
            f"| {c.algorithm} | {c.eps:g} | {c.column} | {_budget(deg_per_h(c.required_drift))} | {r.step * 1e3:.4g} | {r.angle:.4f} | {r.series_terms} | "
            f"{r.algorithm_cost:g} | {r.quaternion_cost:g} | {r.load / 1e3:.0f} | {c.printed} | {100 * c.relative_difference:+.1f} %{mark} |"
        )
    lines += [
        "",
        f"**The model reproduces {len(rep.hits)} of {len(rep.cells)} printed loads within {rep.tolerance:.0%}** (β in thousand operations per second).",
        "",
    ]
    return lines


def _load_sensitivity(rep) -> list:
    cells = L45.load_model_sensitivity((1.0, 0.1, 0.01), m=rep.model.m, tolerance=rep.tolerance)
    fractions = list(dict.fromkeys(c.truncation_fraction for c in cells))
    bases = list(dict.fromkeys(c.time_base for c in cells))
    by = {(c.time_base, c.truncation_fraction): c for c in cells}
    return [
        f"The two rules are parameters of `LoadModel`. Cells within {100 * rep.tolerance:g} % for other choices:",
        "",
        "| time base | " + " | ".join(f"f = {f:g}" for f in fractions) + " |",
        "|---|" + "---|" * len(fractions),
        *(f"| {'h (sample)' if tb == 'sample' else 'H (step)'} | " + " | ".join(f"{by[(tb, f)].hits} of {by[(tb, f)].cells}" for f in fractions) + " |" for tb in bases),
        "",
    ]


def _load_misses(rep) -> list:
    lines = ["**The misses.** Each missed cell also fails a check of the print against itself, by about the size of the miss:", ""]
    for m in L45.explain_misses(rep):
        c = m.cell
        causes = "; ".join(
            f"{k.cells[0]} / {k.cells[1]} = {k.printed_ratio:.3f} against {k.expected_ratio:.3f} from {k.reason} ({100 * k.deviation:+.1f} %)" for k in m.checks
        )
        head = f"- alg. {c.algorithm}, ε = {c.eps:g}, {c.column}: printed {c.printed}, model {c.row.load / 1e3:.0f} ({100 * c.relative_difference:+.1f} %)."
        lines.append(f"{head} {causes or 'No check of the print fails.'}")
    lines += [
        "",
        "A ratio of two printed loads with the same cost must equal the inverse ratio of their largest steps, whatever the cost",
        "model (`printed_consistency`; a change of the series length between the two cells, one term, moves it by a few per cent at",
        "most). The cells above break that with the paper's own Table 3 or Table 5, so their most likely cause is the printed value",
        "(a misprint, or a procedure the paper does not state), not the model.",
        "",
    ]
    return lines


def _load_comparison(rep) -> list:
    comp = L45.compare_per_sample_fit(rep, tolerance=rep.tolerance)
    lines = [
        "**Comparison: the earlier reading with fitted constants.** $\\beta = (N\\sigma_{alg} + \\sigma_q)/H_{max}$ with σ_q fitted per motion",
        "to the printed loads:",
        "",
        f"| ε | fitted σ_q per step | per sample (σ_q/N) | cells within {100 * comp.tolerance:g} % | series terms K of the model | model σ_q |",
        "|---|---|---|---|---|---|",
    ]
    for f, n, ks, costs in zip(comp.fits, comp.within, comp.series_terms, comp.model_costs):
        lines.append(
            f"| {f.eps:g} | {f.sigma_q:.0f} | {f.sigma_q_per_sample:g} | {n} of {len(f.cells)} | {', '.join(map(str, ks))} | "
            f"{', '.join(f'{c:g}' for c in costs)} |"
        )
    lines += [
        "",
        f"That reading reproduces {comp.total_within} of {comp.total_cells} loads with two fitted constants. Expressed per sample, the two constants are",
        "the cost of the model's quaternion update at the series length its rule picks for each motion (two terms under coning, where",
        f"the angle per step is small; four or five under precession, where it is ~0.3 rad), and their difference, {comp.per_sample_difference:g}, is about two series",
        f"terms ({comp.two_term_cost:g}). The ranking of the paper follows: "
        + _ranking_text(rep)
        + ".",
        "",
    ]
    return lines


def _ranking_text(rep) -> str:
    parts = []
    motions = {-1.0: "under coning", 0.5: "under precession"}
    for c in L45.cheapest_algorithms(rep):
        verdict = "as printed" if c.as_printed else f"printed: {', '.join(map(str, c.printed))}"
        parts.append(f"{motions.get(c.eps, f'at ε = {c.eps:g}')} algorithm {', '.join(map(str, c.model))} is the cheapest in both tables ({verdict})")
    return "; ".join(parts)


def _extension(plt, quick: bool):
    c = P.BUDENNYI_CONDITIONS
    nutation = rad(c.nutation_deg)
    u4, u5 = L45.required_drifts()
    freqs = np.geomspace(10, 4000, 12 if quick else 40)
    curves = L45.load_curves(freqs, eps_values=c.eps, nutation=nutation, required_drift=u4, algorithms=EXTENSION_ALGORITHMS)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), sharey=True)
    for ax, eps in zip(axes, c.eps):
        for curve in (k for k in curves if k.eps == eps):
            ax.loglog(curve.frequencies, curve.loads / 1e6, label=curve.algorithm)
        ax.set_title(f"[u] = {_budget(c.required_drift_deg_per_h[0])} deg/h, ϑ = {c.nutation_deg:g}°, ε = {eps:g}")
        ax.set_xlabel("f [Hz]")
    axes[0].set_ylabel("load β [million op/s]")
    axes[1].legend(fontsize=6)
    fixed_layout(fig, left=0.75, right=0.15, bottom=0.5, top=0.3, wgap=0.2)
    points = L45.design_points(4000.0, eps_values=c.eps, nutation=nutation, budgets=(u4, u5), algorithms=EXTENSION_ALGORITHMS)
    table = [
        f"| {p.eps:g} | {_budget(deg_per_h(p.required_drift))} | {p.row.algorithm} | {p.row.order} | {p.row.step * 1e6:.3g} | {p.row.sample_rate / 1e3:.4g} | "
        f"{p.nu_step:.2g} | {p.row.angle:.2g} | {p.row.series_terms} | {p.row.load / 1e6:.4g} |"
        for p in points
    ]
    lines = [
        "### Extension to f = 4000 Hz",
        "",
        "The paper leaves open what computer and sampling rate f = 4000 Hz (vibration at gyro mounts) requires. The same",
        "model answers it: the same counts, the same series rule and time base; since $K \\propto \\nu^{\\rho+1}$ (ρ the drift order) the step shrinks as",
        "$f^{-(\\rho+1)/\\rho}$, and the rule sets the series length from the angle per step. At f = 4000 Hz, ϑ = 1°, ranked by load:",
        "",
        "| ε | [u] deg/h | algorithm | drift order | $H_{max}$ [µs] | sampling rate [kHz] | νH [rad] | φ [rad] | K | load [million op/s] |",
        "|---|---|---|---|---|---|---|---|---|---|",
        *table,
        "",
        *_extension_commentary(points),
        "",
        "![load vs frequency](figures/derivations-load-vs-frequency.png)",
        "",
    ]
    return fig, lines


def _extension_commentary(points) -> list:
    lines = []
    motions = {-1.0: "coning", 0.5: "precession"}
    summary = L45.summarize_designs(points)
    for best in summary.cheapest:
        lines.append(
            f"Under {motions.get(best.eps, f'ε = {best.eps:g}')} at [u] = {_budget(deg_per_h(best.required_drift))} deg/h the cheapest is {best.row.algorithm}: "
            f"{best.row.sample_rate / 1e3:.3g} thousand samples/s, {best.row.load / 1e6:.3g} million operations/s, K = {best.row.series_terms}."
        )
    lines.append(f"νH stays below {summary.largest_nu_step:.2g}, where the asymptotic estimate holds to a few per cent (section 7).")
    return lines


def errata(ctx) -> list:
    """The errata this section's checks establish, with their evidence.

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        The report context.

    Returns
    -------
    list of Erratum
    """
    est = {e.printed.algorithm: e for e in leading_estimates()}
    same = same_transport(get("panov-4s-3"), get("panov-4s-5"), 7)
    return [_table3_algorithm_3(est[3], est[5], same), _table3_algorithm_5(est[5])]


def _estimates_text(e) -> str:
    return (
        f"the papers' estimate, the h⁷ error projected at the middle of the step, gives {deg_per_h(abs(e.mid_step)):.3g} deg/h "
        f"({100 * e.printed_vs_mid_step:+.1f} % from the print); the small-cone-angle term c ϑ² ν (ν h)⁶ gives "
        f"{deg_per_h(abs(e.small_angle)):.4g} deg/h ({100 * e.printed_vs_small_angle:+.2f} %); the full leading term of the drift, with the "
        f"transport of the weight-5 error and the ϑ⁴ terms, gives {deg_per_h(abs(e.full)):.3g} deg/h ({100 * e.printed_vs_full:+.1f} %)"
    )


def _table3_algorithm_3(three, five, same: bool) -> Erratum:
    return Erratum(
        "Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3, u_a of algorithm 3 under coning (drift order 6)",
        f"u_a = {three.printed.u_a_deg_per_h:.3g} deg/h",
        f"the small-cone-angle estimate c ϑ² ν (ν h)⁶ (c = 2/315): {deg_per_h(abs(three.small_angle)):.4g} deg/h, "
        f"{100 * abs(three.printed_vs_small_angle):.2f} % from the print; a legitimate approximation, not a misprint",
        f"At the Table 3 conditions {_estimates_text(three)}; the full term agrees with the printed u* = {three.printed.u_star_deg_per_h:.3g} "
        f"and with the simulator ({deg_per_h(three.simulated):.4g} deg/h) within {100 * abs(three.full_vs_simulated):.1f} %. "
        + ("The transport term is the same expression for algorithms 3 and 5 " if same else "The transport terms of algorithms 3 and 5 differ ")
        + f"({deg_per_h(three.transport):.3g} deg/h here), and algorithm 5's printed u_a is its mid-step estimate to "
        f"{100 * abs(five.printed_vs_mid_step):.1f} % (its small-angle term is {100 * five.printed_vs_small_angle:+.1f} % off), "
        "so the two printed values of the column come from two different estimates; the text, which lost formula (3), does not say which.",
        "derivations",
        kind="ambiguous",
        alternatives=f"the mid-step estimate, {deg_per_h(abs(three.mid_step)):.3g} deg/h, as for algorithm 5; the full leading term, "
        f"{deg_per_h(abs(three.full)):.3g} deg/h, the most accurate.",
    )


def _table3_algorithm_5(five) -> Erratum:
    return Erratum(
        "Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3, u_a of algorithm 5 under coning (drift order 6)",
        f"u_a = {five.printed.u_a_deg_per_h:.3g} deg/h",
        f"the papers' own estimate, the h⁷ error projected at the middle of the step: {deg_per_h(abs(five.mid_step)):.3g} deg/h, "
        f"{100 * abs(five.printed_vs_mid_step):.1f} % from the print; a legitimate, less accurate approximation, not a misprint",
        "The formula (3) behind u_a is lost in the stored text, which cites Panov (1995) for it, so the text does not decide which estimate "
        "of the leading drift is meant. "
        f"At the Table 3 conditions {_estimates_text(five)}.",
        "derivations",
        kind="ambiguous",
        alternatives=f"the full leading term, {deg_per_h(abs(five.full)):.3g} deg/h, which agrees with the printed u* = {five.printed.u_star_deg_per_h:.3g} "
        f"and the simulator ({deg_per_h(five.simulated):.4g} deg/h) within {100 * abs(five.full_vs_simulated):.1f} %: the better estimate, "
        "but not what the print uses.",
    )
