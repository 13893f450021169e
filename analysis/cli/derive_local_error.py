"""``strapdown derive local-error``: the local-error series of an algorithm.

The series is derived symbolically (:mod:`strapdown.derivations.coning.series`) and printed in
the convention of Budennyi, Kalinovsky, Panov et al., Table 2:
``Δφ_exact − Δφ_algorithm = δ h^(ρ+1) Σ k_w x_w``, h the sample interval.
"""

from __future__ import annotations

from ...derivations.coning.series import error_coefficients, local_error
from . import Result
from ._options import add_algorithm, algorithm_from


def _word_key(word) -> str:
    return "x" + "".join(str(k) for k in word)


def local_error_command(args) -> Result:
    alg = algorithm_from(args)
    coeffs = error_coefficients(alg)
    err = local_error(alg)
    data = {
        "algorithm": alg.name,
        "samples": alg.samples,
        "order": coeffs.order,
        "convention": "exact minus algorithm, coefficient of h^(order+1), h = sample interval, H = N h",
        "delta": str(coeffs.delta) if coeffs.order is not None else None,
        "coefficients": {_word_key(w): str(c) for w, c in coeffs.coefficients.items()},
        "latex": coeffs.latex(),
        "latex_dual": coeffs.latex(dual=True),
        "nonzero_weights": [w for w, part in enumerate(err.parts) if any(part)],
    }
    lines = [f"{alg.name}: order {coeffs.order} ({alg.samples} samples)"]
    if coeffs.order is not None:
        terms = " ".join(f"{'+' if c >= 0 else '-'} {abs(c)} {_word_key(w)}" for w, c in coeffs.coefficients.items() if c)
        lines.append(f"exact - algorithm = {coeffs.delta} h^{coeffs.order + 1} ({terms.lstrip('+ ')})")
    else:
        lines.append("the local error vanishes through h^7")
    return Result(data, "\n".join(lines))


def register(commands) -> None:
    p = commands.add("local-error", local_error_command, "local-error series of an algorithm (exact fractions, LaTeX)", group="derive")
    add_algorithm(p)
