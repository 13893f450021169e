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
        rows.append({"name": name, "samples": alg.samples, "history": alg.history, "order": s.order,
                     "paper": name in names(), "reference": alg.reference})
    width = max(len(r["name"]) for r in rows)
    lines = [f"{'name':<{width}}  N  prev  order  reference"]
    for r in rows:
        order = "-" if r["order"] is None else str(r["order"])
        lines.append(f"{r['name']:<{width}}  {r['samples']}  {r['history']:>4}  {order:>5}  {r['reference']}")
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
             "Δφ = " + " + ".join(f"p{j}" for j in range(1, s.samples + 1)) + "".join(f" {'−' if c < 0 else '+'} {abs(c)} {p}" for c, p in s.terms)]
    lines.append(f"second-order defect Σ c_ij (j − i) − N³/12 = {s.second_order_defect}")
    lines.append(f"order ρ = {'none through h⁷' if s.order is None else s.order} (local error O(h^(ρ+1)), from the symbolic series)")
    lines.append(f"source: {s.reference}")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``algorithms list`` and ``algorithms show``.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    commands.add("list", _list, "list the registry: name, samples, previous samples read, order, source", group="algorithms")
    p = commands.add("show", _show, "one algorithm: terms as exact fractions, samples, history, second-order defect, order, source", group="algorithms")
    p.add_argument("name", nargs="?", metavar="NAME", help="registry name (see `strapdown algorithms list`)")
    add_algorithm(p, required=False)
