"""``strapdown reproduce tables``: our numbers next to the printed ones."""

from __future__ import annotations

from . import Result


def _run(args) -> Result:
    from ..report import algorithms as rep

    t3 = [
        {"algorithm": f"panov-4s-{r['algorithm']}", "eps": r["eps"], "ours": r["ours"], "printed": r["printed_u_star"], "rel_diff": r["rel_diff"]}
        for r in rep.budennyi_table3_rows()
    ]
    lp = []
    for r in rep.lebedev_panov_rows():
        for v, ours in zip(r["variants"], r["ours"]):
            lp.append({"quantity": r["quantity"], "order": r["order"], "eps": r["eps"], "variant": v, "ours": ours, "printed": r["printed"], "rel_diff": ours / r["printed"] - 1.0})
    data = {"budennyi_table3_u_star": t3, "lebedev_panov_1989": lp, "tolerance": rep.TOLERANCE}
    lines = ["Budennyi, Kalinovsky, Panov et al., Table 3, u* [deg/h]", f"{'algorithm':<12} {'eps':>5} {'ours':>11} {'printed':>11} {'diff':>9}"]
    lines += [f"{r['algorithm']:<12} {r['eps']:>5g} {r['ours']:>11.4g} {r['printed']:>11.4g} {100 * r['rel_diff']:>8.2f}%" for r in t3]
    lines += ["", "Lebedev & Panov (1989), section 6 (drift deg/h, ΔW m/s at t = 100 s)", f"{'quantity':<8} {'rho':>3} {'eps':>5} {'var':>3} {'ours':>11} {'printed':>11} {'diff':>9}"]
    lines += [f"{r['quantity']:<8} {r['order']:>3} {r['eps']:>5g} {r['variant']:>3} {r['ours']:>11.4g} {r['printed']:>11.4g} {100 * r['rel_diff']:>8.2f}%" for r in lp]
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    commands.add("tables", _run, "Budennyi et al. Table 3 (u*) and the Lebedev & Panov (1989) table: ours next to the printed values", group="reproduce")
