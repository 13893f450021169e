"""``strapdown derive coning-drift``: the coning drift of an algorithm in closed form.

Classical coning: half-cone angle α, coning rate ω, sample interval h (the
regular precession of Lebedev & Panov (1989), eq. (4.1), with ε = −1, ϑ = α,
ν = ω).  What is printed is the constant rate u [rad/s] of the attitude error
along the cone axis, exact minus algorithm (the error rotation
``Λ_true ∘ Λ̄_computed`` in the reference frame), to leading order in α and ωh:

    u = coefficient · α² · ω · (ωh)^order,

with the cone axis oriented along the mean inertial angular velocity of the
body (so u > 0: the computed attitude lags the coning rotation; u < 0: it
leads).  The error does not grow across the axis.  The exact α²-coefficient as
a function of ωh, ``D(x)`` with ``u = α² ω D(ωh) + O(α⁴)``, is printed too, and
evaluated at the ``--omega-h-rad`` values asked for
(:func:`strapdown.derivations.coning.drift.coning_drift`,
:func:`strapdown.analysis.coning.drift_theory.coning_drift_function`).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...derivations.coning.drift import X, coning_drift
from ..coning.drift_theory import coning_drift_function
from . import Result, UsageError
from ._options import add_algorithm, algorithm_from

__all__ = ["coning_drift_command", "register"]

QUANTITY = (
    "constant drift rate u [rad/s] of the attitude error (exact minus algorithm) along the cone axis under classical coning "
    "(half-cone angle alpha [rad], coning rate omega [rad/s], sample interval h [s]): u = coefficient * alpha^2 * omega * (omega*h)^order "
    "to leading order in alpha and omega*h; the cone axis points along the mean inertial angular velocity, so u > 0 means "
    "the computed attitude lags the coning rotation"
)


def _omega_h(text: str) -> list:
    values = []
    if not str(text).strip():
        raise UsageError("Expected --omega-h-rad as comma-separated numbers of radians, got an empty value")
    for part in str(text).split(","):
        try:
            v = float(part)
        except ValueError:
            raise UsageError(f"Expected --omega-h-rad as comma-separated numbers of radians, got {text!r}") from None
        if not math.isfinite(v):
            raise UsageError(f"Expected --omega-h-rad values to be finite numbers of radians, got {part.strip()!r} in {text!r}")
        if v <= 0:
            raise UsageError(f"Expected --omega-h-rad values > 0 (radians), got {part.strip()!r}")
        values.append(v)
    return values


def coning_drift_command(args) -> Result:
    """Run ``strapdown derive coning-drift``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options: ``algorithm`` or ``algorithm_file``, ``allow_inconsistent``, ``omega_h_rad``.

    Returns
    -------
    Result
        JSON data and text.

    Raises
    ------
    UsageError
        For bad ``--omega-h-rad`` values.
    ValueError
        For an unknown algorithm or a malformed algorithm file.
    """
    xs = _omega_h(args.omega_h_rad) if args.omega_h_rad is not None else []
    alg = algorithm_from(args)
    d = coning_drift(alg)
    N = alg.samples
    c, cH = d.coefficient, d.step_coefficient
    data = {
        "algorithm": alg.name,
        "samples": N,
        "history": alg.history,
        "quantity": QUANTITY,
        "order": d.order,
        "coefficient": f"{c.numerator}/{c.denominator}",
        "coefficient_float": float(c),
        "step_coefficient": f"{cH.numerator}/{cH.denominator}",
        "step_coefficient_note": "u = step_coefficient * alpha^2 * omega * (omega*H)^order, H = N h the algorithm step",
        "lag_sums": [str(k) for k in d.lag_sums],
        "exact_function": str(d.function),
        "exact_function_latex": sp.latex(d.function, symbol_names={X: "x"}),
        "exact_function_note": "u = alpha^2 * omega * D(x) + O(alpha^4), x = omega*h, exact in x",
        "latex": d.latex(),
    }
    if xs:
        f = coning_drift_function(alg)
        values = np.asarray(f(np.asarray(xs)), dtype=float)
        data["values"] = [{"omega_h_rad": x, "D": float(v), "leading": float(c) * x**d.order} for x, v in zip(xs, values)]
    sign = "lags" if c > 0 else "leads"
    lines = [
        f"{alg.name}: coning drift u = {c} · α² ω (ωh)^{d.order}  (= {cH} · α² ω (ωH)^{d.order}, H = {N}h)",
        f"along the cone axis, exact - algorithm: the computed attitude {sign} the coning rotation",
        f"exact in ωh at order α²: u = α² ω D(ωh), D(x) = {d.function}",
    ]
    for row in data.get("values", []):
        lines.append(f"  ωh = {row['omega_h_rad']:g} rad: D = {row['D']:.6g} (leading term {row['leading']:.6g})")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    """Add ``derive coning-drift`` to the command line.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add(
        "coning-drift",
        coning_drift_command,
        "coning drift of an algorithm in closed form: coefficient · α² ω (ωh)^order, exact fraction",
        group="derive",
        description=QUANTITY + ". The exact α²-coefficient D(ωh) is printed as well.",
    )
    add_algorithm(p)
    p.add_argument(
        "--omega-h-rad",
        metavar="X[,X...]",
        default=None,
        help="also evaluate the exact D(ωh) at these values of ωh, the angle the coning rate turns through in one sample interval [rad], comma-separated (default: none)",
    )
