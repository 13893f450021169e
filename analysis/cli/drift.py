"""``strapdown drift``: constant drift rate of an algorithm under regular precession or classical coning.

The motion is a regular precession (Lebedev & Panov 1989, eq. (4.1):
``--eps --nutation-deg --freq-hz``) or classical coning (``--half-angle-deg
--freq-hz``), which is the same motion with ε = −1, ϑ = α and the coning rate
ω equal to the spin rate ν.  Any registry algorithm or TOML file runs,
cross-step ones too (indices ≤ 0: the samples before the first step come from
the exact motion).  Beside the simulated drift it prints, for any algorithm:

* the asymptotic rate u_a, the leading nonvanishing term of the series
  ``u = Σ_w d_w ν^w H^(w−1)`` (eq. (3) of Part 2, the figure the papers print);
* the series, with the drift the composition of the steps adds at second order
  in the transverse step error, summed through the lowest weight whose
  estimated truncation error (the last term kept) is within ``--series-rtol``
  of the drift, at most ``--max-order``
  (:func:`strapdown.analysis.coning.drift_theory.converged_drift_series`): at a
  large ``νH``, or where the leading terms cancel, the next terms are not
  small, and ``leading_term_dominates`` is false (with a note) when u_a and the
  series differ by more than 10 %;
* the exact drift, from one step in extended precision with no series and no
  simulation (:func:`strapdown.analysis.coning.exact_drift.exact_drift`).

The simulated drift is a least-squares slope, which a periodic error larger
than the drift accumulated over the run biases; ``simulation_matches_series``
is false (with a note) when the slope and the series differ by more than 1 %.
The run streams (:func:`strapdown.analysis.coning.long_run.simulate_long_run`):
its memory does not grow with ``--duration``, and ``periodic_error_rad`` is the
largest peak of the error about the least-squares line of a window of
``periodic_error_window_steps`` steps (the whole run when it is shorter).

Signs follow the package convention, exact minus algorithm: the drift vector
(``drift_vector_deg_per_h``, components in frame I, the run starting at
Λ(0) = 1) is the rate of the error rotation ``Λ_exact ∘ Λ̄_computed``, and
``asymptotic_drift_vector_deg_per_h`` is the theory's vector along the
precession axis, with the same sign.
"""

from __future__ import annotations

import numpy as np

from ...derivations.coning.series import WEIGHT_LIMIT
from ..coning.drift_theory import SERIES_MAX_WEIGHT, SERIES_RTOL, asymptotic_drift_vector, converged_drift_series
from ..coning.exact_drift import exact_drift
from ..coning.long_run import simulate_long_run
from ..coning.precession import RegularPrecession
from ..core.units import deg_per_h
from ..core.validation import positive
from . import Result, UsageError
from ._options import add_algorithm, add_motion, algorithm_from, count, limits_from, motion_parameters, number, run_summary

#: Smallest ``--max-order``: the drift starts at weight 3 (a first-order algorithm).
MIN_ORDER = 3
#: Relative difference of the leading term and the series above which the leading term is said not to dominate.
DOMINANCE_TOLERANCE = 0.1
#: Relative difference of the simulated slope and the series above which the run is said not to resolve the drift.
AGREEMENT_TOLERANCE = 0.01


def _finite_or_none(value) -> float | None:
    value = float(value)
    return value if np.isfinite(value) else None


def _run(args) -> Result:
    K = args.max_order
    if not MIN_ORDER <= K <= WEIGHT_LIMIT:
        raise UsageError(f"Expected --max-order in {MIN_ORDER}..{WEIGHT_LIMIT}, got {K}")
    rtol = positive(args.series_rtol, "--series-rtol")
    alg = algorithm_from(args)
    params = motion_parameters(args)  # the work is estimated by the streaming run itself (constant memory)
    motion = RegularPrecession(params["eps"], params["nu"], params["nutation"])
    r = simulate_long_run(alg, motion, args.sample_interval, args.duration, progress=args.progress, limits=limits_from(args))
    data, header = run_summary(alg, r, params)
    theory = {"eps": params["eps"], "nu": params["nu"], "nutation": params["nutation"], "step": r.step}
    terms = converged_drift_series(alg, **theory, rtol=rtol, max_weight=K)
    asymptotic = _finite_or_none(deg_per_h(terms.asymptotic))  # None: no drift through weight K
    vector = deg_per_h(asymptotic_drift_vector(alg, **theory, max_weight=terms.max_weight))
    series = float(deg_per_h(terms.total))
    truncation = _finite_or_none(deg_per_h(terms.truncation_error))
    # None: nothing through weight K (no term and no composition), so nothing to converge
    converged = None if series == 0.0 else bool(truncation is not None and truncation <= rtol * series)
    try:
        exact = abs(float(deg_per_h(exact_drift(alg, motion, args.sample_interval))))
    except ValueError:  # the drift did not settle in the precisions tried (it vanishes, or nearly)
        exact = None
    dominates = terms.leading_term_dominates(DOMINANCE_TOLERANCE)
    leading, largest = terms.leading_weight, terms.largest_weight
    simulated = float(deg_per_h(r.drift_rate))
    agrees = None  # below the round-off floor the run shows round-off, not the drift (run_summary says so)
    if not data["drift_below_roundoff_floor"] and series > 0.0:
        agrees = bool(abs(simulated - series) <= AGREEMENT_TOLERANCE * series)
    data |= {
        "motion": "classical coning" if params["coning"] else "regular precession",
        "eps": params["eps"],
        "nutation_deg": params["nutation_deg"],
        "half_angle_deg": params["nutation_deg"] if params["coning"] else None,
        "freq_hz": args.freq_hz,
        "max_order": K,
        "series_rtol": rtol,
        "simulated_drift_deg_per_h": simulated,
        "drift_vector_deg_per_h": deg_per_h(r.drift).tolist(),
        "asymptotic_drift_deg_per_h": asymptotic,
        "asymptotic_drift_vector_deg_per_h": vector.tolist() if np.all(np.isfinite(vector)) else None,
        "series_drift_deg_per_h": series,
        "series_weight": terms.max_weight,
        "series_truncation_error_deg_per_h": truncation,
        "series_converged": converged,
        "composition_drift_deg_per_h": _finite_or_none(deg_per_h(terms.composition)),
        "exact_drift_deg_per_h": exact,
        "leading_term_dominates": dominates,
        "leading_weight": leading if leading >= 0 else None,
        "drift_order": leading - 1 if leading >= 0 else None,
        "largest_term_weight": largest if largest >= 0 else None,
        "simulation_matches_series": agrees,
        "periodic_error_rad": r.periodic_error,
        "periodic_error_window_steps": min(r.window, r.steps),
        "final_error_rad": float(np.linalg.norm(r.final_error)),
    }
    u_a_text = f"{asymptotic:.6g} deg/h (drift order {leading - 1}: ∝ H^{leading - 1})" if asymptotic is not None else f"zero through h^{terms.max_weight} (raise --max-order)"
    truncation_text = f"{truncation:.2g} deg/h, the last term kept" if truncation is not None else "unknown: the terms do not fall yet"
    lines = [header]
    if params["coning"]:
        lines.append(f"classical coning: α = {params['nutation_deg']:g} deg, ω = 2π·{args.freq_hz:g} rad/s (the regular precession ε = −1, ϑ = α, ν = ω)")
    lines += [
        f"constant drift rate: {data['simulated_drift_deg_per_h']:.6g} deg/h, "
        f"vector (frame I, exact minus algorithm) {', '.join(f'{x:.6g}' for x in data['drift_vector_deg_per_h'])} deg/h",
        f"asymptotic drift rate u_a (leading term): {u_a_text}",
        f"drift series through h^{terms.max_weight}: {series:.6g} deg/h (estimated truncation error {truncation_text}; "
        f"composition of the steps {data['composition_drift_deg_per_h'] or 0.0:.3g} deg/h)",
        f"exact drift (one step in extended precision, no series): {exact:.6g} deg/h" if exact is not None else "exact drift: did not settle (it vanishes or nearly)",
    ]
    if converged is None:
        lines.append(f"note: the drift series vanishes through h^{terms.max_weight} (--max-order {K})")
    elif not converged:
        lines.append(
            f"note: through h^{terms.max_weight} (--max-order {K}) the series has not reached --series-rtol {rtol:g}: "
            f"estimated truncation error {truncation_text}; raise --max-order, or quote the exact drift"
        )
    if dominates is False:
        why = (
            f"the leading term (weight {leading}) is the largest, and the later ones cancel most of it"
            if largest == leading
            else f"the largest term is of weight {largest}, the leading one of weight {leading}"
        )
        lines.append(
            f"note: u_a differs from the series by {abs(asymptotic - series) / series:.0%} (more than {DOMINANCE_TOLERANCE:.0%}): {why} "
            f"(νH = {params['nu'] * r.step:.3g} rad, ϑ = {params['nutation_deg']:g} deg); the series is the drift to quote"
        )
    if agrees is False:
        lines.append(
            f"note: the simulated slope differs from the series by {abs(simulated - series) / series:.1%}: the periodic error "
            f"(peak {data['periodic_error_rad']:.2e} rad about the drift line) is not averaged out in {r.duration:g} s; "
            "a longer --duration brings the two together"
        )
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add the ``drift`` command.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add(
        "drift",
        _run,
        "constant drift rate of an algorithm under regular precession or classical coning (parallel computation, series, exact)",
        progress="own",
    )
    add_algorithm(p)
    add_motion(p)
    p.add_argument(
        "--max-order",
        type=count,
        default=SERIES_MAX_WEIGHT,
        metavar="K",
        help=f"highest weight (power of h) the drift series may reach, K in {MIN_ORDER}..{WEIGHT_LIMIT} [count] (default {SERIES_MAX_WEIGHT}); "
        "the weight is raised 7, 9, 11, ... until --series-rtol is met",
    )
    p.add_argument(
        "--series-rtol",
        type=number,
        default=SERIES_RTOL,
        metavar="R",
        help=f"estimated truncation error of the drift series (its last term kept) the series must reach, relative to the drift "
        f"[dimensionless] (default {SERIES_RTOL:g})",
    )
