"""``strapdown derive local-error``: the local-error series of an algorithm.

The series is derived symbolically (:mod:`derivations.series`) and printed in
the convention of Budennyi, Kalinovsky, Panov et al., Table 2:
``Δφ_exact − Δφ_algorithm = δ h^(ρ+1) Σ k_w x_w``, h the sample interval.
"""

from __future__ import annotations

from derivations import algorithms
from derivations.series import error_coefficients, local_error

from . import Result, UsageError


def _word_key(word) -> str:
    return "x" + "".join(str(k) for k in word)


def resolve_algorithm(args):
    """The algorithm named by ``--algorithm`` or read from ``--algorithm-file``."""
    if (args.algorithm is None) == (args.algorithm_file is None):
        raise UsageError("Expected exactly one of --algorithm NAME or --algorithm-file FILE")
    if args.algorithm is not None:
        return algorithms.get(args.algorithm)
    return algorithms.load_toml(args.algorithm_file, allow_inconsistent=args.allow_inconsistent)


def local_error_command(args) -> Result:
    alg = resolve_algorithm(args)
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
    p.add_argument("--algorithm", metavar="NAME", help=f"registry algorithm ({', '.join(algorithms.names())})")
    p.add_argument("--algorithm-file", metavar="FILE", help="TOML file describing a user algorithm")
    p.add_argument("--allow-inconsistent", action="store_true", help="accept a file algorithm that misses the second-order condition")
