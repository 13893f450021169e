"""``strapdown algorithms list|show``: the registry of published algorithms and one algorithm in detail."""

from __future__ import annotations

from ...derivations.coning.registry import get, names
from ..coning.algorithm_summary import summarize
from . import Result, UsageError
from ._options import add_algorithm, algorithm_from


def _list(args) -> Result:
    rows = []
    for name in names(library=True):
        alg = get(name)
        s = summarize(alg)
        rows.append({"name": name, "samples": alg.samples, "history": alg.history, "accuracy_order": s.accuracy_order,
                     "local_error_order": s.local_error_order, "coning_drift_order": s.coning_drift_order,
                     "paper": name in names(), "reference": alg.reference})  # fmt: skip
    width = max(len(r["name"]) for r in rows)

    def show(value):
        return "-" if value is None else str(value)

    lines = [
        f"{'':<{width}}           orders: accuracy  local-error  coning-drift",
        f"{'name':<{width}}  N  prev          ρ          ρ+1             m  reference",
    ]
    for r in rows:
        lines.append(
            f"{r['name']:<{width}}  {r['samples']}  {r['history']:>4}  {show(r['accuracy_order']):>9}  {show(r['local_error_order']):>11}  "
            f"{show(r['coning_drift_order']):>12}  {r['reference']}"
        )
    lines.append("accuracy order ρ: local error O(h^(ρ+1)) in a general motion; local-error order ρ + 1; coning-drift order m: drift c α² ω (ωh)^m under classical coning")
    return Result({"algorithms": rows}, "\n".join(lines))


def _show(args) -> Result:
    if args.name and (args.algorithm or args.algorithm_file):
        raise UsageError("Expected either NAME or --algorithm/--algorithm-file, got both")
    if not (args.name or args.algorithm or args.algorithm_file):
        raise UsageError("Expected an algorithm NAME or --algorithm-file FILE, got neither")
    alg = get(args.name) if args.name else algorithm_from(args)
    s = summarize(alg)
    data = s.as_dict()
    prev = f" + {s.history} previous" if s.history else ""
    lines = [f"{s.name}: {s.description}", f"samples N = {s.samples}{prev} (window of {s.window} increments, p{1 - s.history} … p{s.samples})",
             "Δφ = " + " + ".join(f"p{j}" for j in range(1, s.samples + 1)) + "".join(f" {'−' if c < 0 else '+'} {abs(c)} {p}" for c, p in s.terms)]  # fmt: skip
    lines.append(f"second-order defect Σ c_ij (j − i) − N³/12 = {s.second_order_defect}")
    if s.accuracy_order is None:
        lines.append("accuracy order ρ: above 6 (no local error through h⁷)")
    else:
        lines.append(f"accuracy order ρ = {s.accuracy_order}: local error O(h^{s.local_error_order}) in a general motion (local-error order {s.local_error_order}), from the symbolic series")
    if s.coning_drift_order is not None:
        lines.append(f"coning-drift order m = {s.coning_drift_order}: drift c α² ω (ωh)^{s.coning_drift_order} under classical coning (`strapdown derive coning-drift`)")
    lines.append(f"source: {s.reference}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``algorithms list`` and ``algorithms show``.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    commands.add("list", _list, "list the registry: name, samples, previous samples read, accuracy, local-error and coning-drift orders, source", group="algorithms")
    p = commands.add("show", _show, "one algorithm: terms as exact fractions, samples, history, second-order defect, orders, source", group="algorithms")
    p.add_argument("name", nargs="?", metavar="NAME", help="registry name (see `strapdown algorithms list`)")
    add_algorithm(p, required=False)
