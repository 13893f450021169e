"""``strapdown identify``: a user's coning and sculling code, identified as an exact algorithm.

``--integrator FILE.py:NAME`` names a Python file and the integrator defined
in it: a function ``integrate(gyro, samples_per_step)`` returning one rotation
vector per step, an :class:`~strapdown.analysis.coning.integrators.interface.Integrator`
(attitude or velocity outputs, a compiled C function through
:func:`~strapdown.analysis.coning.integrators.adapters.compiled`, a peer), or
an object or class with ``reset`` / ``update`` / ``output``
(``docs/integrators.md``).  The command probes it, prints the coefficients of
``p_i × p_j`` as exact fractions, the first- and second-order conditions
(reported, never a refusal), the order of the local error, the closed-form
coning drift of the identified algorithm (same meaning as ``derive
coning-drift``), the remainder the bilinear model leaves (size and degree),
the sculling part when the integrator takes accelerometer increments, and
the integrator's own simulated drift against the closed form at several ωh
(:func:`~strapdown.analysis.coning.integrators.assessment.assess`).
``--write-algorithm FILE.toml`` writes the identified algorithm as an
algorithm file (``docs/algorithm-files.md``).
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

from ..coning.integrators.adapters import load_integrator
from ..coning.integrators.assessment import assess, work
from ..coning.integrators.identification import DEFAULT_MAX_PREVIOUS, TOLERANCE
from ..coning.integrators.verification import DRIFT_TOLERANCE, OMEGA_H
from . import Result, UsageError
from ._options import add_limits, check_work, count, number

__all__ = ["identify_command", "register"]

#: Largest ``--samples-per-step`` and ``--max-previous`` (the limits of an algorithm file).
MAX_SAMPLES = 64
#: Most ``--omega-h-rad`` values.
MAX_POINTS = 16


def _omega_h(text: str) -> tuple:
    values = []
    for part in str(text).split(","):
        try:
            v = float(part)
        except ValueError:
            raise UsageError(f"Expected --omega-h-rad as comma-separated numbers of radians, got {text[:60]!r}") from None
        if not math.isfinite(v) or not 0 < v <= math.pi:
            raise UsageError(f"Expected --omega-h-rad values in (0, π] radians (above π per sample the samples alias the coning rate), got {part.strip()[:40]!r}")
        values.append(v)
    if len(values) > MAX_POINTS:
        raise UsageError(f"Expected at most {MAX_POINTS} --omega-h-rad values, got {len(values)}")
    return tuple(values)


def _write(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (a temporary file in the same directory, then renamed)."""
    if path.is_dir():
        raise IsADirectoryError(21, "Is a directory", str(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent if str(path.parent) else ".")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _fmt(x) -> str:
    return "—" if x is None else f"{x:.3g}"


def identify_command(args) -> Result:
    """Run ``strapdown identify``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options: ``integrator``, ``samples_per_step``, ``max_previous``,
        ``tolerance``, ``omega_h_rad``, ``skip_verification``, ``write_algorithm``,
        ``name`` and the work limits.

    Returns
    -------
    Result
        JSON data and text.

    Raises
    ------
    UsageError
        For counts or values out of range.
    ValueError
        For a file or integrator that cannot be used (the message says why),
        or work beyond the limits.
    """
    n, k = args.samples_per_step, args.max_previous
    if not 1 <= n <= MAX_SAMPLES:
        raise UsageError(f"Expected --samples-per-step in 1..{MAX_SAMPLES}, got {n}")
    if not 0 <= k <= MAX_SAMPLES:
        raise UsageError(f"Expected --max-previous in 0..{MAX_SAMPLES}, got {k}")
    if not 0 < args.tolerance <= 1e-3:
        raise UsageError(f"Expected --tolerance in (0, 1e-3], got {args.tolerance:g}")
    omega_h = _omega_h(args.omega_h_rad)
    out_path = Path(args.write_algorithm) if args.write_algorithm else None
    if out_path is not None and out_path.suffix != ".toml":
        raise UsageError(f"Expected --write-algorithm to name a .toml file, got {args.write_algorithm!r}")
    if out_path is not None and not out_path.parent.is_dir() and str(out_path.parent):
        raise UsageError(f"Expected --write-algorithm in an existing directory, got {args.write_algorithm!r}")
    integrator = load_integrator(args.integrator)
    verify = not args.skip_verification
    check_work(args, work(integrator, n, max_previous=k, verify=verify, omega_h=omega_h))
    a = assess(integrator, n, max_previous=k, tolerance=args.tolerance, verify=verify, omega_h=omega_h, name=args.name)
    data = a.as_dict()
    if out_path is not None:
        _write(out_path, a.identification.toml(args.name))
        data["algorithm_file"] = str(out_path)
    return Result(data, _text(a, data))


def _text(a, data) -> str:
    ident, con = a.identification, a.consistency
    lines = [f"{ident.name}: {ident.samples} samples per step, reads {ident.history} earlier sample(s) (probed {ident.max_previous})"]
    if ident.at_limit:
        lines.append("  a coefficient sits at the earliest index probed: the integrator may read further back (raise --max-previous)")
    lines.append("linear part: " + (", ".join(f"{a_} p{j}" for j, a_ in data["linear"].items()) or "none"))
    lines.append("terms: " + (", ".join(f"{c} p{key.replace(',', '×p')}" for key, c in data["terms"].items()) or "none"))
    lines.append(
        f"  exact fractions (each within 4 × its uncertainty, at most {ident.tolerance:g}: denominators up to {ident.max_denominator} at least): "
        f"{'yes' if ident.exact else 'no (approximate fractions used)'}; "
        f"every axis alike: {'yes' if ident.isotropic else 'no'}"
    )
    lines.append(
        f"first-order condition (linear part = p1 + … + pN): {'holds' if con.first_order else 'fails'}; "
        f"second-order condition Σ c_ij (j − i) = {data['conditions']['second_order_sum']} against N³/12 = {data['conditions']['second_order_expected']}: "
        f"{'holds' if con.second_order else 'fails'}"
    )
    lines.append(f"local error O(h^{a.order + 1}): accuracy order {a.order}, local-error order {a.order + 1}" if a.order is not None else "local error zero through h^7")
    if data["local_error"] is not None:
        words = [(c.startswith("-"), c.lstrip("-"), w) for w, c in data["local_error"]["coefficients"].items()]
        terms = " ".join(f"{'-' if neg else '+'} {'' if c == '1' else c + ' '}{w}" for neg, c, w in words).removeprefix("+ ")
        lines.append(f"  exact - integrator = {data['local_error']['delta']} h^{a.order + 1} ({terms})")
    if a.local_error_exponent is not None:
        lines.append(f"  the integrator's own one-step error on a tumbling motion: exponent {a.local_error_exponent:.2f}")
    if a.coning is not None:
        lines.append(f"coning drift u = {data['coefficient']} · α² ω (ωh)^{data['coning_drift_order']}: coning-drift order {data['coning_drift_order']} (exact minus integrator, along the cone axis)")
    else:
        lines.append("coning drift: no α² closed form (the linear part is not p1 + … + pN)")
    lines.append(f"remainder: {ident.remainder.summary()}")
    if a.check is not None:
        verdict = {True: "holds", False: "FAILS", None: "no point above the round-off floor"}[a.check.holds]
        lines.append(f"simulated against closed-form drift ({DRIFT_TOLERANCE:g} relative): {verdict}")
        for p in a.check.points:
            state = f"rel. difference {p.relative_difference:.1e}" if p.resolved else f"not resolved (uncertainty {p.uncertainty / abs(p.closed_form) if p.closed_form else math.inf:.1e} relative)"
            lines.append(f"  ωh = {p.x:g}: D = {p.closed_form:.6g} closed form, {p.simulated:.6g} simulated, {state}")
    if a.sculling is not None:
        sc = a.sculling
        lines.append("sculling: " + ", ".join(f"{c} p{key.split(',')[0]}×b{key.split(',')[1]}" for key, c in data["sculling"]["terms"].items()))
        if sc.dual_extension:
            lines.append("  the dual extension of the coning part (with the rotation term ½ P × V)")
        else:
            lines.append("  departs from the dual extension of the coning part: " + ", ".join(f"{k} by {v}" for k, v in data["sculling"]["defect"].items()))
        lines.append(f"  remainder: {sc.remainder.summary()}")
        if sc.check is not None:
            verdict = {True: "holds", False: "FAILS", None: "no point above the round-off floor"}[sc.check.holds]
            lines.append(f"  simulated against closed-form rectification error: {verdict} (largest difference {_fmt(sc.check.largest_difference)})")
    if "algorithm_file" in data:
        lines.append(f"algorithm file written: {data['algorithm_file']}")
    return "\n".join(lines)


def register(commands) -> None:
    """Add ``identify`` to the command line.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add(
        "identify",
        identify_command,
        "identify a user's coning and sculling code as an exact algorithm: terms, consistency, orders, drift, remainder, check",
        description=__doc__.split("\n\n")[1].replace("\n", " "),
    )
    p.add_argument("--integrator", required=True, metavar="FILE.py:NAME", help="Python file and the name of the integrator defined in it [path] (see docs/integrators.md)")
    p.add_argument("--samples-per-step", type=count, required=True, metavar="N", help=f"samples N per output step, 1..{MAX_SAMPLES} [count]")
    p.add_argument(
        "--max-previous",
        type=count,
        default=DEFAULT_MAX_PREVIOUS,
        metavar="K",
        help=f"how many samples before the step are probed, 0..{MAX_SAMPLES} [count] (default {DEFAULT_MAX_PREVIOUS})",
    )
    p.add_argument(
        "--tolerance",
        type=number,
        default=TOLERANCE,
        metavar="T",
        help=(
            "largest |c − p/q| accepted by the rational reconstruction (each coefficient uses 4 × its uncertainty when smaller); "
            f"denominators up to (2T)^(-1/2) are admitted [dimensionless] (default {TOLERANCE:g})"
        ),
    )
    p.add_argument(
        "--omega-h-rad",
        metavar="X[,X...]",
        default=",".join(f"{x:g}" for x in OMEGA_H),
        help=f"ωh of the simulated drift check, each in (0, π], comma-separated, at most {MAX_POINTS} [rad] (default {','.join(f'{x:g}' for x in OMEGA_H)})",
    )
    p.add_argument("--skip-verification", action="store_true", help="identify and analyse only: do not run the integrator against the exact solution")
    p.add_argument("--write-algorithm", metavar="FILE.toml", default=None, help="also write the identified algorithm as an algorithm file [path] (default: none)")
    p.add_argument("--name", metavar="NAME", default=None, help="name of the identified algorithm [name] (default: the integrator's)")
    add_limits(p)
    commands.only_with(p, "--omega-h-rad", "--skip-verification", (False,))
