"""``strapdown derive local-error``: the local-error series of an algorithm, to any order.

The series is derived symbolically (:mod:`strapdown.derivations.coning.series`)
through ``h^K`` (``--max-order K``, default 7) and printed weight by weight, every
nonzero weight computed, in the convention of Budennyi, Kalinovsky, Panov et al.,
Table 2: ``Δφ_exact − Δφ_algorithm = Σ_w δ_w h^w Σ k_x x + O(h^(K+1))``, h the
sample interval (:func:`strapdown.derivations.coning.series.error_series`).  The
first weight is ρ + 1: ρ is the accuracy order, ρ + 1 the local-error order.
With the series, the coning drift it implies is printed weight by weight
(:func:`strapdown.derivations.coning.drift.coning_drift_series`): under
classical coning (half-cone angle α, rate ω) the drift along the cone axis is
``α² ω Σ_m c_m (ωh)^m + O(α⁴)``, exact minus algorithm (positive: the computed
attitude lags the coning rotation), for the powers m < K the series reaches.
"""

from __future__ import annotations

from ...derivations.coning.drift import coning_drift_series
from ...derivations.coning.series import DEFAULT_MAX_WEIGHT, WEIGHT_LIMIT, error_coefficients, error_series, local_error
from . import Result, UsageError
from ._options import add_algorithm, add_limits, algorithm_from, check_work, count

__all__ = ["local_error_command", "register"]

#: Smallest ``--max-order``: the second-order condition is a statement about h³.
MIN_ORDER = 3


def _word_key(word) -> str:
    """``x02`` for ``x_{02}``; with a letter of two digits the letters are comma-separated, ``x0,10``."""
    return "x" + ("".join if max(word) < 10 else ",".join)(str(k) for k in word)


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
    series = error_series(alg, K)
    N = alg.samples
    coning = {w - 1: c * N ** (w - 1) for w, c in enumerate(coning_drift_series(alg, K)) if c}
    rho = coeffs.order
    data = {
        "algorithm": alg.name,
        "samples": N,
        "history": alg.history,
        "max_order": K,
        "accuracy_order": rho,
        "local_error_order": rho + 1 if rho is not None else None,
        "convention": "exact minus algorithm = sum over weights w of delta_w h^w sum_x k_x x, h = sample interval, H = N h; "
        "the first weight is the local-error order, accuracy order + 1",
        "delta": str(coeffs.delta) if rho is not None else None,
        "coefficients": {_word_key(w): str(c) for w, c in coeffs.coefficients.items()},
        "latex": coeffs.latex(),
        "latex_dual": coeffs.latex(dual=True),
        "series": [
            {"weight": t.weight, "delta": str(t.delta), "coefficients": {_word_key(w): str(c) for w, c in t.coefficients.items() if c}, "latex": t.latex()}
            for t in series
        ],
        "nonzero_weights": [w for w, part in enumerate(err.parts) if any(part)],
        "coning_drift_convention": "drift along the cone axis = alpha^2 * omega * sum_m c_m (omega h)^m + O(alpha^4), exact minus algorithm (positive: the computed attitude lags the coning rotation)",
        "coning_drift_series": {str(m): str(c) for m, c in sorted(coning.items())},
    }
    history = f", {alg.history} earlier" if alg.history else ""
    if rho is not None:
        lines = [f"{alg.name}: accuracy order {rho}, local-error order {rho + 1} ({N} samples{history}), series through h^{K}"]
        lines.append("exact - algorithm, weight by weight (h the sample interval):")
        for t in series:
            terms = " ".join(f"{'+' if c >= 0 else '-'} {abs(c)} {_word_key(w)}" for w, c in t.coefficients.items() if c)
            lines.append(f"  h^{t.weight}: {t.delta} ({terms.lstrip('+ ')})")
    else:
        lines = [f"{alg.name}: accuracy order above {K - 1} ({N} samples{history}), series through h^{K}", f"the local error vanishes through h^{K}"]
    lines.append(f"nonzero weights: {data['nonzero_weights']}")
    if coning:
        text = " ".join(f"{'+' if c >= 0 else '-'} {abs(c)} (ωh)^{m}" for m, c in sorted(coning.items())).lstrip("+ ")
        lines.append(f"coning drift / (α² ω) = {text} + O((ωh)^{K})  (exact - algorithm, along the cone axis)")
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
    p = commands.add("local-error", local_error_command, "local-error series of an algorithm, every weight through h^K (exact fractions, LaTeX)", group="derive")
    add_algorithm(p)
    p.add_argument(
        "--max-order",
        type=count,
        default=DEFAULT_MAX_WEIGHT,
        metavar="K",
        help=f"keep the series through h^K and print every weight, K in {MIN_ORDER}..{WEIGHT_LIMIT} [count] (default {DEFAULT_MAX_WEIGHT}); "
        "6-sample algorithms need K = 13 to reach their coning term; the work about triples with each order (K = 16: about a minute)",
    )
    add_limits(p)
