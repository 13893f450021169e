"""``strapdown reproduce tables``: our numbers next to the printed ones."""

from __future__ import annotations

from ..coning.papers.budennyi_table3 import reproduce_u_star
from ..coning.papers.lebedev_panov_table import reproduce_table
from ..core.units import deg_per_h
from . import Result

#: Relative difference accepted as reproduced.
TOLERANCE = 0.02


def tables_command(args) -> Result:
    """Run ``strapdown reproduce tables``: Table 3 (u*) of Budennyi et al. and the Lebedev & Panov (1989) table.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (only ``--json``).

    Returns
    -------
    Result
        Every printed cell with ours and the relative difference (drift in deg/h, ΔW in m/s).
    """
    t3 = [
        {"algorithm": f"panov-4s-{c.printed.algorithm}", "eps": c.printed.eps, "ours": deg_per_h(c.simulated), "printed": c.printed.u_star_deg_per_h, "rel_diff": c.relative_difference}
        for c in reproduce_u_star()
    ]
    lp = []
    for c in reproduce_table(tolerance=TOLERANCE).cells:
        p = c.printed
        for v, ours, rel in zip(p.variants, c.ours, c.relative_differences):
            shown = deg_per_h(ours) if p.quantity == "drift" else ours
            lp.append({"quantity": p.quantity, "order": p.order, "eps": p.eps, "variant": v, "ours": shown, "printed": p.value, "rel_diff": rel})
    data = {"budennyi_table3_u_star": t3, "lebedev_panov_1989": lp, "tolerance": TOLERANCE}
    lines = ["Budennyi, Kalinovsky, Panov et al., Table 3, u* [deg/h]", f"{'algorithm':<12} {'eps':>5} {'ours':>11} {'printed':>11} {'diff':>9}"]
    lines += [f"{r['algorithm']:<12} {r['eps']:>5g} {r['ours']:>11.4g} {r['printed']:>11.4g} {100 * r['rel_diff']:>8.2f}%" for r in t3]
    lines += ["", "Lebedev & Panov (1989), section 6 (drift deg/h, ΔW m/s at t = 100 s)", f"{'quantity':<8} {'rho':>3} {'eps':>5} {'var':>3} {'ours':>11} {'printed':>11} {'diff':>9}"]
    lines += [f"{r['quantity']:<8} {r['order']:>3} {r['eps']:>5g} {r['variant']:>3} {r['ours']:>11.4g} {r['printed']:>11.4g} {100 * r['rel_diff']:>8.2f}%" for r in lp]
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``strapdown reproduce tables`` to the command line.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    commands.add("tables", tables_command, "Budennyi et al. Table 3 (u*) and the Lebedev & Panov (1989) table: ours next to the printed values", group="reproduce")
