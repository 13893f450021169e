"""``strapdown derive coning-drift``: the coning drift of an algorithm in closed form, its next term and where it holds.

Classical coning: half-cone angle α, coning rate ω, sample interval h (the
regular precession of Lebedev & Panov (1989), eq. (4.1), with ε = −1, ϑ = α,
ν = ω).  What is printed is the constant rate u [rad/s] of the attitude error
along the cone axis, exact minus algorithm (the error rotation
``Λ_true ∘ Λ̄_computed`` in the reference frame), to leading order in α and ωh:

    u = coefficient · α² · ω · (ωh)^m,        m the coning-drift order,

with the cone axis oriented along the mean inertial angular velocity of the
body (so u > 0: the computed attitude lags the coning rotation; u < 0: it
leads).  The error does not grow across the axis.  Beside it:

* the exact α²-coefficient as a function of ωh, ``D(x)`` with
  ``u = α² ω D(ωh) + O(α⁴)``, evaluated at the ``--omega-h-rad`` values asked for
  (:func:`strapdown.derivations.coning.drift.coning_drift`,
  :func:`strapdown.analysis.coning.drift_theory.coning_drift_function`);
* the next term in α, ``c₄ α⁴ ω (ωh)^k`` (:func:`strapdown.analysis.coning.coning_validity.next_coning_term`);
* the range of α and ωh where the leading term is within ``--tolerance`` of
  the exact drift, found against the exact drift from one step in extended
  precision (:func:`strapdown.analysis.coning.coning_validity.leading_term_range`);
* for a case given by ``--half-angle-deg --freq-hz --sample-interval``, the
  leading term, the α² part exact in ωh, the next term and the exact drift,
  with a warning when the case lies outside that range
  (:func:`strapdown.analysis.coning.coning_validity.coning_case`).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...derivations.coning.drift import X, coning_drift
from ..coning.coning_validity import (
    CONE_ANGLE_FLOOR,
    DEFAULT_OMEGA_H,
    DEFAULT_TOLERANCE,
    MAX_CONE_ANGLE,
    MAX_OMEGA_H,
    OMEGA_H_FLOOR,
    TOLERANCE_RANGE,
    coning_case,
    leading_term_range,
)
from ..coning.drift_theory import coning_drift_function
from ..core.units import RAD_PER_DEG, deg_per_h
from ..core.validation import in_closed_interval, positive
from . import Result, UsageError
from ._options import add_algorithm, algorithm_from, number

__all__ = ["coning_drift_command", "register"]

QUANTITY = (
    "constant drift rate u [rad/s] of the attitude error (exact minus algorithm) along the cone axis under classical coning "
    "(half-cone angle alpha [rad], coning rate omega [rad/s], sample interval h [s]): u = coefficient * alpha^2 * omega * (omega*h)^m "
    "to leading order in alpha and omega*h, m the coning-drift order; the cone axis points along the mean inertial angular velocity, so u > 0 means "
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
        if not OMEGA_H_FLOOR <= v <= MAX_OMEGA_H:
            raise UsageError(f"Expected --omega-h-rad values in [{OMEGA_H_FLOOR:g}, {MAX_OMEGA_H:g}] (radians), got {part.strip()!r}")
        values.append(v)
    return values


def _case(args):
    """``(α [rad], ω [rad/s], h [s])`` of the case asked for, or None; all three options or none."""
    given = {flag: getattr(args, key) for key, flag in (("half_angle_deg", "--half-angle-deg"), ("freq_hz", "--freq-hz"), ("sample_interval", "--sample-interval"))}
    present = [f for f, v in given.items() if v is not None]
    if not present:
        return None
    if len(present) < 3:
        missing = ", ".join(f for f, v in given.items() if v is None)
        raise UsageError(f"Expected --half-angle-deg, --freq-hz and --sample-interval together (a case of classical coning), got no {missing}")
    low, high = math.degrees(CONE_ANGLE_FLOOR), math.degrees(MAX_CONE_ANGLE)
    alpha = in_closed_interval(given["--half-angle-deg"], "--half-angle-deg", low, high, text=f"[{low:.2g}, {high:g}] degrees")
    nu = 2.0 * math.pi * positive(given["--freq-hz"], "--freq-hz")
    h = positive(given["--sample-interval"], "--sample-interval")
    if not OMEGA_H_FLOOR <= nu * h <= MAX_OMEGA_H:
        raise UsageError(
            f"Expected the coning rate to turn {OMEGA_H_FLOOR:g} to {MAX_OMEGA_H:g} rad per sample, got ωh = {nu * h:.3g} rad "
            f"(--freq-hz {args.freq_hz:g}, --sample-interval {h:g})"
        )
    return alpha * RAD_PER_DEG, nu, h


def _degrees(angle: float) -> float | None:
    return math.degrees(angle) if math.isfinite(angle) else None


def _angle_text(angle: float, x: float, limit: float) -> str:
    if angle == 0.0:
        return f"never (ωh beyond {limit:.3g} rad)"
    if not math.isfinite(angle):
        return f"α up to {math.degrees(MAX_CONE_ANGLE):g} deg at least"
    return f"α ≤ {math.degrees(angle):.3g} deg"


def _fraction(c) -> str:
    return f"{c.numerator}/{c.denominator}"


def coning_drift_command(args) -> Result:
    """Run ``strapdown derive coning-drift``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options: ``algorithm`` or ``algorithm_file``, ``allow_inconsistent``, ``omega_h_rad``,
        ``half_angle_deg``, ``freq_hz``, ``sample_interval``, ``tolerance``.

    Returns
    -------
    Result
        JSON data and text.

    Raises
    ------
    UsageError
        For bad ``--omega-h-rad`` values or an incomplete case.
    ValueError
        For an unknown algorithm, a malformed algorithm file, or a value out of range.
    """
    xs = _omega_h(args.omega_h_rad) if args.omega_h_rad is not None else []
    tolerance = in_closed_interval(args.tolerance, "--tolerance", *TOLERANCE_RANGE)
    case_args = _case(args)
    alg = algorithm_from(args)
    d = coning_drift(alg)
    N = alg.samples
    c, cH, m = d.coefficient, d.step_coefficient, d.order
    grid = sorted(set(xs or DEFAULT_OMEGA_H) | ({case_args[1] * case_args[2]} if case_args else set()))
    rng = leading_term_range(alg, omega_h=grid, tolerance=tolerance)
    nxt = rng.next_term
    data = {
        "algorithm": alg.name,
        "samples": N,
        "history": alg.history,
        "quantity": QUANTITY,
        "coning_drift_order": m,
        "coefficient": _fraction(c),
        "coefficient_float": float(c),
        "step_coefficient": _fraction(cH),
        "step_coefficient_note": "u = step_coefficient * alpha^2 * omega * (omega*H)^m, H = N h the algorithm step",
        "lag_sums": [str(k) for k in d.lag_sums],
        "exact_function": str(d.function),
        "exact_function_latex": sp.latex(d.function, symbol_names={X: "x"}),
        "exact_function_note": "u = alpha^2 * omega * D(x) + O(alpha^4), x = omega*h, exact in x",
        "latex": d.latex(),
        "next_term": {
            "note": "the leading alpha^4 term of the drift series: u4 = coefficient * alpha^4 * omega * (omega*h)^power",
            "power": nxt.order,
            "coefficient": _fraction(nxt.coefficient) if nxt.order is not None else None,
            "coefficient_float": float(nxt.coefficient) if nxt.order is not None else None,
            "series": [{"power": k, "coefficient": _fraction(v)} for k, v in nxt.series],
            "max_weight": nxt.max_weight,
        },
        "leading_term_range": {
            "tolerance": tolerance,
            "reference": "exact drift from one step in extended precision, every order in alpha and omega*h",
            "omega_h_limit_rad": rng.omega_h_limit if math.isfinite(rng.omega_h_limit) else None,
            "omega_h_searched_rad": [1e-3, MAX_OMEGA_H],
            "half_angle_limits": [{"omega_h_rad": x, "half_angle_limit_deg": _degrees(a)} for x, a in zip(rng.omega_h, rng.half_angle_limits)],
            "half_angle_searched_deg": math.degrees(MAX_CONE_ANGLE),
            "law": {"factor_rad": rng.law[0], "power": rng.law[1]} if rng.law else None,
            "note": "each limit ends the range that starts at 0; null: no limit up to the end of the search",
        },
        "warnings": [],
    }
    if xs:
        f = coning_drift_function(alg)
        values = np.asarray(f(np.asarray(xs)), dtype=float)
        data["values"] = [{"omega_h_rad": x, "D": float(v), "leading": float(c) * x**m} for x, v in zip(xs, values)]
    sign = "lags" if c > 0 else "leads"
    lines = [
        f"{alg.name}: coning drift u = {c} · α² ω (ωh)^{m}  (= {cH} · α² ω (ωH)^{m}, H = {N}h); coning-drift order {m}",
        f"along the cone axis, exact - algorithm: the computed attitude {sign} the coning rotation",
        f"exact in ωh at order α²: u = α² ω D(ωh), D(x) = {d.function}",
    ]
    for row in data.get("values", []):
        lines.append(f"  ωh = {row['omega_h_rad']:g} rad: D = {row['D']:.6g} (leading term {row['leading']:.6g})")
    if nxt.order is not None:
        more = " + …" if len(nxt.series) > 1 else ""
        lines.append(f"next term in α: {nxt.coefficient} · α⁴ ω (ωh)^{nxt.order}{more} (the α⁴ part of the drift series through h^{nxt.max_weight})")
    else:
        lines.append(f"next term in α: none through h^{nxt.max_weight}")
    limit = rng.omega_h_limit
    lines.append(f"the leading term is within {tolerance:.0%} of the exact drift (one step in extended precision, every order in α and ωh):")
    lines.append(f"  as α → 0: for ωh ≤ {limit:.3g} rad" if math.isfinite(limit) else f"  as α → 0: for ωh up to {MAX_OMEGA_H:g} rad at least")
    lines.append("  " + "; ".join(f"at ωh = {x:g} rad: {_angle_text(a, x, limit)}" for x, a in zip(rng.omega_h, rng.half_angle_limits)))
    if rng.law:
        factor, power = rng.law
        law = f"α ≲ {factor:.3g} rad" if power == 0 else f"α ≲ {factor:.3g} · (ωh)^{power:g} rad"
        lines.append(f"  from the two leading terms alone (where the α⁴ term reaches {tolerance:.0%} of the α² one; the exact limits above decide): {law}")
    if case_args:
        alpha, nu, h = case_args
        case = coning_case(alg, cone_angle=alpha, nu=nu, sample_interval=h, tolerance=tolerance)
        x = case.omega_h
        part2 = float(alpha**2 * nu * np.asarray(coning_drift_function(alg)(x), dtype=float))
        angle = case.range.half_angle_limits[0]
        data["case"] = {
            "half_angle_deg": args.half_angle_deg,
            "freq_hz": args.freq_hz,
            "sample_interval": h,
            "omega_h_rad": x,
            "leading_term_deg_per_h": float(deg_per_h(case.leading)),
            "alpha2_part_deg_per_h": float(deg_per_h(part2)),
            "next_term_deg_per_h": float(deg_per_h(case.next_term)) if case.next_term is not None else None,
            "exact_drift_deg_per_h": float(deg_per_h(case.exact)),
            "leading_over_exact": case.ratio if math.isfinite(case.ratio) else None,
            "within_range": case.within,
            "half_angle_limit_deg": _degrees(angle),
        }
        nt = f"{data['case']['next_term_deg_per_h']:.3g} deg/h" if case.next_term is not None else "none"
        lines += [
            f"case α = {args.half_angle_deg:g} deg, f = {args.freq_hz:g} Hz, h = {h:g} s (ωh = {x:.4g} rad), drift along the cone axis:",
            f"  leading term {data['case']['leading_term_deg_per_h']:.4g} deg/h; α² part exact in ωh {data['case']['alpha2_part_deg_per_h']:.4g} deg/h; "
            f"next term in α {nt}; exact drift {data['case']['exact_drift_deg_per_h']:.4g} deg/h",
        ]
        if not case.within:
            ratio = f"{case.ratio:.3g}× the exact drift" if math.isfinite(case.ratio) else "finite where the exact drift vanishes"
            where = f"{_angle_text(angle, x, limit)} at ωh = {x:.4g} rad"
            warning = f"the leading term is {ratio} here: the case lies outside the range where it holds ({where}); quote the exact drift"
            data["warnings"].append(warning)
            lines.append(f"warning: {warning}")
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
        "coning drift of an algorithm in closed form: coefficient · α² ω (ωh)^m, the next term in α and where the leading term holds",
        group="derive",
        description=QUANTITY + ". The exact α²-coefficient D(ωh), the next term in α and the range of α and ωh where the leading "
        "term is within --tolerance of the exact drift are printed as well, and a case given by --half-angle-deg, --freq-hz and "
        "--sample-interval is set against that range.",
    )
    add_algorithm(p)
    p.add_argument(
        "--omega-h-rad",
        metavar="X[,X...]",
        default=None,
        help="also evaluate the exact D(ωh) at these values of ωh, the angle the coning rate turns through in one sample interval [rad], "
        f"comma-separated, each in [{OMEGA_H_FLOOR:g}, {MAX_OMEGA_H:g}]; the range of α is given at them (default: none; the range at "
        f"{', '.join(f'{x:g}' for x in DEFAULT_OMEGA_H)})",
    )
    g = p.add_argument_group("a case of classical coning (all three together)")
    g.add_argument("--half-angle-deg", type=number, default=None, help=f"half-cone angle α [deg], in [{math.degrees(CONE_ANGLE_FLOOR):.2g}, {math.degrees(MAX_CONE_ANGLE):g}] (default: none)")
    g.add_argument("--freq-hz", type=number, default=None, help="coning frequency f [Hz], > 0, ω = 2πf (default: none)")
    g.add_argument("--sample-interval", type=number, default=None, metavar="H", help="gyro sample interval h [s], > 0 (default: none)")
    p.add_argument(
        "--tolerance",
        type=number,
        default=DEFAULT_TOLERANCE,
        metavar="R",
        help="relative difference from the exact drift within which the leading term is said to hold [dimensionless], "
        f"in [{TOLERANCE_RANGE[0]:g}, {TOLERANCE_RANGE[1]:g}] (default {DEFAULT_TOLERANCE:g})",
    )
