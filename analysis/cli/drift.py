"""``strapdown drift``: constant drift rate of an algorithm under regular precession.

Any registry algorithm or TOML file runs, cross-step ones too (indices ≤ 0:
the samples before the first step come from the exact motion).  Beside the
simulated drift it prints two values of the symbolic drift theory (Lebedev &
Panov 1989, section 5), both for any algorithm:

* the asymptotic rate u_a, the leading nonvanishing term of the series
  ``u = Σ_w d_w ν^w H^(w−1)`` (eq. (3) of Part 2, the figure the papers print);
* the series summed through weight ``--max-order`` (default 9), which follows
  the simulation where the leading term alone does not: at a large ``νH`` the
  next terms are not small, and ``leading_term_dominates`` is false (with a
  note) when u_a and the series differ by more than 10 %.

The simulated drift is a least-squares slope, which a periodic error larger
than the drift accumulated over the run biases; ``simulation_matches_series``
is false (with a note) when the slope and the series differ by more than 1 %.

Signs follow the package convention, exact minus algorithm: the drift vector
(``drift_vector_deg_per_h``, components in frame I, the run starting at
Λ(0) = 1) is the rate of the error rotation ``Λ_exact ∘ Λ̄_computed``, and
``asymptotic_drift_vector_deg_per_h`` is the theory's vector along the
precession axis, with the same sign.
"""

from __future__ import annotations

import numpy as np

from ...derivations.coning.series import WEIGHT_LIMIT
from ..coning.drift_theory import asymptotic_drift_vector, drift_series_terms
from ..coning.precession import RegularPrecession
from ..coning.simulator import simulate
from ..core.units import deg_per_h
from . import Result, UsageError
from ._options import add_algorithm, add_motion, algorithm_from, count, motion_parameters, run_summary

#: Default weight through which the drift series is summed (``--max-order``).
SERIES_ORDER = 9
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
    alg = algorithm_from(args)
    params = motion_parameters(args, alg)
    motion = RegularPrecession(params["eps"], params["nu"], params["nutation"])
    r = simulate(alg, motion, args.sample_interval, args.duration)
    data, header = run_summary(alg, r, params)
    theory = {"eps": params["eps"], "nu": params["nu"], "nutation": params["nutation"], "step": r.step, "max_weight": K}
    terms = drift_series_terms(alg, **theory)
    asymptotic = _finite_or_none(deg_per_h(terms.asymptotic))  # None: no drift through weight K
    vector = deg_per_h(asymptotic_drift_vector(alg, **theory))
    series = float(deg_per_h(terms.total))
    dominates = terms.leading_term_dominates(DOMINANCE_TOLERANCE)
    leading, largest = terms.leading_weight, terms.largest_weight
    simulated = float(deg_per_h(r.drift_rate))
    agrees = None  # below the round-off floor the run shows round-off, not the drift (run_summary says so)
    if not data["drift_below_roundoff_floor"] and series > 0.0:
        agrees = bool(abs(simulated - series) <= AGREEMENT_TOLERANCE * series)
    data |= {
        "eps": params["eps"],
        "nutation_deg": args.nutation_deg,
        "freq_hz": args.freq_hz,
        "max_order": K,
        "simulated_drift_deg_per_h": simulated,
        "drift_vector_deg_per_h": deg_per_h(r.drift).tolist(),
        "asymptotic_drift_deg_per_h": asymptotic,
        "asymptotic_drift_vector_deg_per_h": vector.tolist() if np.all(np.isfinite(vector)) else None,
        "series_drift_deg_per_h": series,
        "leading_term_dominates": dominates,
        "leading_weight": leading if leading >= 0 else None,
        "largest_term_weight": largest if largest >= 0 else None,
        "simulation_matches_series": agrees,
        "periodic_error_rad": float(r.periodic_error),
        "final_error_rad": float((r.attitude_error[-1] ** 2).sum() ** 0.5),
    }
    u_a_text = f"{asymptotic:.6g} deg/h" if asymptotic is not None else f"zero through h^{K} (raise --max-order)"
    lines = [
        header,
        f"constant drift rate: {data['simulated_drift_deg_per_h']:.6g} deg/h, "
        f"vector (frame I, exact minus algorithm) {', '.join(f'{x:.6g}' for x in data['drift_vector_deg_per_h'])} deg/h",
        f"asymptotic drift rate u_a (leading term): {u_a_text}",
        f"drift series through h^{K}: {series:.6g} deg/h",
    ]
    if dominates is False:
        lines.append(
            f"note: u_a differs from the series by {abs(asymptotic - series) / series:.0%} (more than {DOMINANCE_TOLERANCE:.0%}): "
            f"the largest term is of weight {largest}, the leading one of weight {leading} "
            f"(νH = {params['nu'] * r.step:.3g} rad, ϑ = {args.nutation_deg:g} deg); the series is the drift to quote"
        )
    if agrees is False:
        lines.append(
            f"note: the simulated slope differs from the series by {abs(simulated - series) / series:.1%}: the periodic error "
            f"(peak {data['periodic_error_rad']:.2e} rad about the drift line) is not averaged out in {r.time[-1]:g} s; "
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
        "constant drift rate of an algorithm under regular precession (parallel computation)",
    )
    add_algorithm(p)
    add_motion(p)
    p.add_argument(
        "--max-order",
        type=count,
        default=SERIES_ORDER,
        metavar="K",
        help=f"weight through which the drift series is summed and its leading term searched, K in {MIN_ORDER}..{WEIGHT_LIMIT} "
        f"[count] (default {SERIES_ORDER})",
    )
