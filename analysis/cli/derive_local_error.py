"""``strapdown derive local-error``: the local-error series of an algorithm, to any order.

The series is derived symbolically (:mod:`strapdown.derivations.coning.series`)
through ``h^K`` (``--max-order K``, default 7) and printed in the convention of
Budennyi, Kalinovsky, Panov et al., Table 2:
``Δφ_exact − Δφ_algorithm = δ h^(ρ+1) Σ k_w x_w + O(h^(ρ+2))``, h the sample
interval.  With the series, the coning drift it implies is printed weight by
weight (:func:`strapdown.derivations.coning.drift.coning_drift_series`): under
classical coning (half-cone angle α, rate ω) the drift along the cone axis is
``α² ω Σ_m c_m (ωh)^m + O(α⁴)``, exact minus algorithm (positive: the computed
attitude lags the coning rotation), for the powers m < K the series reaches.
"""

from __future__ import annotations

from ...derivations.coning.drift import coning_drift_series
from ...derivations.coning.series import DEFAULT_MAX_WEIGHT, WEIGHT_LIMIT, error_coefficients, local_error
from . import Result, UsageError
from ._options import add_algorithm, add_limits, algorithm_from, check_work, count

__all__ = ["local_error_command", "register"]

#: Smallest ``--max-order``: the second-order condition is a statement about h³.
MIN_ORDER = 3


def _word_key(word) -> str:
    return "x" + "".join(str(k) for k in word)


def local_error_command(args) -> Result:
    """Run ``strapdown derive local-error``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options: ``algorithm`` or ``algorithm_file``, ``allow_inconsistent``, ``max_order``.

    Returns
    -------
    Result
        JSON data and text.

    Raises
    ------
    UsageError
        For ``--max-order`` outside its range.
    strapdown.analysis.core.budget.BudgetExceeded
        For a series whose estimated time or memory exceeds ``--time-limit`` / ``--memory-limit-mb``.
    ValueError
        For an unknown algorithm or a malformed algorithm file.
    """
    from ..core import budget

    K = args.max_order
    if not MIN_ORDER <= K <= WEIGHT_LIMIT:
        raise UsageError(f"Expected --max-order in {MIN_ORDER}..{WEIGHT_LIMIT}, got {K}")
    check_work(args, budget.series_derivation(K, what=f"the series through h^{K} (--max-order {K})"))
    alg = algorithm_from(args)
    coeffs = error_coefficients(alg, K)
    err = local_error(alg, K)
    N = alg.samples
    coning = {w - 1: c * N ** (w - 1) for w, c in enumerate(coning_drift_series(alg, K)) if c}
    data = {
        "algorithm": alg.name,
        "samples": N,
        "history": alg.history,
        "max_order": K,
        "order": coeffs.order,
        "convention": "exact minus algorithm, coefficient of h^(order+1), h = sample interval, H = N h",
        "delta": str(coeffs.delta) if coeffs.order is not None else None,
        "coefficients": {_word_key(w): str(c) for w, c in coeffs.coefficients.items()},
        "latex": coeffs.latex(),
        "latex_dual": coeffs.latex(dual=True),
        "nonzero_weights": [w for w, part in enumerate(err.parts) if any(part)],
        "coning_drift_convention": "drift along the cone axis = alpha^2 * omega * sum_m c_m (omega h)^m + O(alpha^4), exact minus algorithm (positive: the computed attitude lags the coning rotation)",
        "coning_drift_series": {str(m): str(c) for m, c in sorted(coning.items())},
    }
    lines = [f"{alg.name}: order {coeffs.order} ({N} samples{f', {alg.history} earlier' if alg.history else ''}), series through h^{K}"]
    if coeffs.order is not None:
        terms = " ".join(f"{'+' if c >= 0 else '-'} {abs(c)} {_word_key(w)}" for w, c in coeffs.coefficients.items() if c)
        lines.append(f"exact - algorithm = {coeffs.delta} h^{coeffs.order + 1} ({terms.lstrip('+ ')})")
    else:
        lines.append(f"the local error vanishes through h^{K}")
    lines.append(f"nonzero weights: {data['nonzero_weights']}")
    if coning:
        series = " ".join(f"{'+' if c >= 0 else '-'} {abs(c)} (ωh)^{m}" for m, c in sorted(coning.items())).lstrip("+ ")
        lines.append(f"coning drift / (α² ω) = {series} + O((ωh)^{K})  (exact - algorithm, along the cone axis)")
    else:
        lines.append(f"coning drift: zero through (ωh)^{K - 1}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``derive local-error`` to the command line.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add("local-error", local_error_command, "local-error series of an algorithm (exact fractions, LaTeX) to any order", group="derive")
    add_algorithm(p)
    p.add_argument(
        "--max-order",
        type=count,
        default=DEFAULT_MAX_WEIGHT,
        metavar="K",
        help=f"keep the series through h^K, K in {MIN_ORDER}..{WEIGHT_LIMIT} [count] (default {DEFAULT_MAX_WEIGHT}); "
        "6-sample algorithms need K = 13 to reach their coning term; the work about triples with each order (K = 16: about a minute)",
    )
    add_limits(p)
