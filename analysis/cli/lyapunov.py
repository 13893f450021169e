"""``strapdown derive lyapunov``: the Lyapunov function of Plotnikov (1999), (3.2)–(3.4)."""

from __future__ import annotations

from . import Result


def _run(args) -> Result:
    from ...derivations.multistage.lyapunov_function import derive

    d = derive()
    data = {
        "source": "Plotnikov (1999), eqs. (3.1)-(3.4)",
        "system": "2 z' = z o omega - k z - y,  y' = l z",
        "V": str(d.V),
        "Vdot": str(d.Vdot),
        "Vdot_expected": str(d.Vdot_expected),
        "Vdot_equals_minus_l_k_z_zbar": d.vdot_matches,
        "semidefinite": "V' does not contain y: it is only negative semidefinite",
        "lasalle_zdot_on_z_equal_0": [str(c) for c in d.lasalle_zdot],
        "W": str(d.W),
        "Wdot": str(d.Wdot_structure),
        "Wdot_verified": d.wdot_matches,
        "epsilon_max": str(d.eps_max),
        "charpoly_at_rest": str(d.charpoly_rest),
        "rate_roots": [str(r) for r in d.rate_roots],
    }
    text = "\n".join(
        [
            f"V  = {d.V}",
            f"V' = {d.Vdot}   (equals -l k z.zbar: {d.vdot_matches})",
            "V' is only negative semidefinite (no y).  On V' = 0 (z = 0): z' = "
            + ", ".join(str(c) for c in d.lasalle_zdot)
            + ", so the invariant set is z = y = 0 (LaSalle).",
            f"strict: W = V + epsilon z.y, W' = {d.Wdot_structure}  (verified: {d.wdot_matches})",
            f"epsilon < {d.eps_max} and epsilon^2 < 2 l",
            f"at rest: det(sI - A) = {d.charpoly_rest}; rates from s = {', '.join(str(r) for r in d.rate_roots)}",
        ]
    )
    return Result(data, text)


def register(commands) -> None:
    """Add ``strapdown derive lyapunov``.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    commands.add("lyapunov", _run, "Lyapunov function and its derivative for the corrected stage (Plotnikov 1999, (3.2)-(3.4))", group="derive")
