"""``strapdown identify``: a user's coning and sculling code, identified as an exact algorithm.

``--integrator FILE.py:NAME`` names a Python file and the integrator defined
in it: a function ``integrate(gyro, samples_per_step)`` returning one rotation
vector per step, an :class:`~strapdown.analysis.coning.integrators.interface.Integrator`
(attitude or velocity outputs, rate inputs, a compiled C function through
:func:`~strapdown.analysis.coning.integrators.adapters.compiled` or a
per-sample C or C++ API through
:func:`~strapdown.analysis.coning.integrators.adapters.per_sample_library`, a
peer), or an object or class with ``reset`` / ``update`` / ``output``
(``docs/integrators.md``).  The code runs in a child process stopped at
``--time-limit``: a hang, a crash or a segmentation fault is one line on
stderr and exit status 2.  The command first tests what identification
assumes (time invariance, memory length, isotropy, linearity range, float
precision, orders decided by the coefficients) and prints each verdict; then it
probes the code, prints the coefficients of ``p_i × p_j`` as exact fractions,
the first- and second-order conditions (reported, never a refusal), the order
of the local error, the closed-form coning drift of the identified algorithm
(same meaning as ``derive coning-drift``; per axis for code that treats the
axes differently), the remainder the bilinear model leaves (size and degree),
the sculling part when the integrator takes accelerometer increments (with
its velocity accuracy order and what each departure from the dual extension
costs), and the integrator's own simulated drift against the closed form at
several ωh (:func:`~strapdown.analysis.coning.integrators.assessment.assess`).
``--record FILE`` identifies an integrator from a record of its input
increments and outputs instead, with no code
(:mod:`~strapdown.analysis.coning.integrators.records`).
``--write-algorithm FILE.toml`` writes the identified algorithm as an
algorithm file (``docs/algorithm-files.md``).
"""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

from ..coning.integrators.defaults import DEFAULT_MAX_PREVIOUS, DRIFT_TOLERANCE, LONGEST_MEMORY, OMEGA_H, PROBE_AMPLITUDE, TOLERANCE
from . import Result, UsageError
from ._options import add_limits, check_work, count, limits_from, number

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
        Parsed options: ``integrator`` or ``record``, ``samples_per_step``,
        ``max_previous``, ``max_previous_limit``, ``tolerance``,
        ``probe_amplitude_rad``, ``omega_h_rad``, ``skip_verification``,
        ``write_algorithm``, ``name`` and the work limits.

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
        an integrator stopped at the time limit or whose process died, or
        work beyond the limits.
    """
    n, k = args.samples_per_step, args.max_previous
    if not 1 <= n <= MAX_SAMPLES:
        raise UsageError(f"Expected --samples-per-step in 1..{MAX_SAMPLES}, got {n}")
    if not 0 <= k <= MAX_SAMPLES:
        raise UsageError(f"Expected --max-previous in 0..{MAX_SAMPLES}, got {k}")
    if not k <= args.max_previous_limit <= MAX_SAMPLES:
        raise UsageError(f"Expected --max-previous-limit in --max-previous ({k})..{MAX_SAMPLES}, got {args.max_previous_limit}")
    if not 0 < args.tolerance <= 1e-3:
        raise UsageError(f"Expected --tolerance in (0, 1e-3], got {args.tolerance:g}")
    amplitude = args.probe_amplitude_rad
    if amplitude is not None and not 0 < amplitude <= 0.32:
        raise UsageError(f"Expected --probe-amplitude-rad in (0, 0.32] radians, got {amplitude:g}")
    omega_h = _omega_h(args.omega_h_rad)
    out_path = Path(args.write_algorithm) if args.write_algorithm else None
    if out_path is not None and out_path.suffix != ".toml":
        raise UsageError(f"Expected --write-algorithm to name a .toml file, got {args.write_algorithm!r}")
    if out_path is not None and not out_path.parent.is_dir() and str(out_path.parent):
        raise UsageError(f"Expected --write-algorithm in an existing directory, got {args.write_algorithm!r}")
    if args.record is not None:
        return _record_command(args, n, k, out_path)
    from ..coning.integrators.isolation import Isolated

    with Isolated(args.integrator, time_limit=args.time_limit) as child:  # the child loads the file while the analysis imports
        from ..coning.integrators.assessment import assess, work

        integrator = child.integrator
        verify = not args.skip_verification
        check_work(args, work(integrator, n, max_previous=k, verify=verify, omega_h=omega_h, max_previous_limit=args.max_previous_limit))
        a = assess(
            integrator, n, max_previous=k, max_previous_limit=args.max_previous_limit, tolerance=args.tolerance, amplitude=amplitude,
            verify=verify, omega_h=omega_h, name=args.name, limits=limits_from(args),
        )  # fmt: skip
    data = a.as_dict()
    if out_path is not None:
        _write(out_path, a.identification.toml(args.name))
        data["algorithm_file"] = str(out_path)
    return Result(data, _text(a, data))


def _record_command(args, n, k, out_path) -> Result:
    from ..coning.integrators.records import identify_record, read_record

    record = read_record(args.record)
    ident = identify_record(record, n, max_previous=k, tolerance=args.tolerance, name=args.name)
    data = ident.as_dict()
    if out_path is not None:
        _write(out_path, ident.toml(args.name))
        data["algorithm_file"] = str(out_path)
    return Result(data, ident.text() + (f"\nalgorithm file written: {out_path}" if out_path is not None else ""))


def _verdict(v) -> str:
    return "holds" if v.holds else "NO"


_NAMES = {
    "time_invariance": "time invariance",
    "memory": "memory length",
    "isotropy": "isotropy",
    "linearity": "linearity range",
    "precision": "float precision",
    "drift_order": "orders from the coefficients",
}


def _text(a, data) -> str:
    ident, con = a.identification, a.consistency
    lines = [f"{ident.name}: {ident.samples} samples per step, reads {ident.history} earlier sample(s) (probed {ident.max_previous})"]
    if a.assumptions is not None:
        lines.append("what the identification assumes, tested on the code:")
        for key, verdict in a.assumptions.items():
            lines.append(f"  {_NAMES[key]}: {_verdict(verdict)} — {verdict.summary()}")
        if not a.assumptions.trusted:
            lines.append("  the coefficients below do NOT describe the integrator reliably (see the verdicts above)")
    if ident.at_limit:
        lines.append("  a coefficient sits at the earliest index probed: the integrator may read further back (raise --max-previous)")
    lines.append("linear part: " + (", ".join(f"{a_} p{j}" for j, a_ in data["linear"].items()) or "none") + ("" if con.linear_tensor_is_sum or not ident.isotropic else " (not on every axis alike)"))
    lines.append("terms: " + (", ".join(f"{c} p{key.replace(',', '×p')}" for key, c in data["terms"].items()) or "none") + ("" if ident.isotropic else " (the isotropic part only: per axis below)"))
    lines.append(
        f"  exact fractions (each within 4 × its uncertainty, at most {ident.tolerance:g}: denominators up to {ident.max_denominator} at least): "
        f"{'yes' if ident.exact else 'no (the simplest fractions within the uncertainties used)'}; probes at {ident.amplitude:.3g} rad"
    )
    bound = f" ± {con.second_order_bound:.1e}" if con.second_order_bound else ""
    lines.append(
        f"first-order condition (linear part = p1 + … + pN on every axis): {'holds' if con.first_order else 'fails'}; "
        f"second-order condition Σ c_ij (j − i) = {data['conditions']['second_order_sum']}{bound} against N³/12 = {data['conditions']['second_order_expected']}: "
        f"{'holds' if con.second_order else 'fails'}"
    )
    lines.append(f"local error O(h^{a.order + 1}): accuracy order {a.order}, local-error order {a.order + 1}" if a.order is not None else "local error zero through h^7")
    if data["local_error"] is not None:
        words = [(c.startswith("-"), c.lstrip("-"), w) for w, c in data["local_error"]["coefficients"].items()]
        terms = " ".join(f"{'-' if neg else '+'} {'' if c == '1' else c + ' '}{w}" for neg, c, w in words).removeprefix("+ ")
        lines.append(f"  exact - integrator = {data['local_error']['delta']} h^{a.order + 1} ({terms})")
    if a.local_error_exponent is not None and math.isfinite(a.local_error_exponent):
        lines.append(f"  the integrator's own one-step error on a tumbling motion: exponent {a.local_error_exponent:.2f}")
    if a.coning is not None:
        lines.append(f"coning drift u = {data['coefficient']} · α² ω (ωh)^{data['coning_drift_order']}: coning-drift order {data['coning_drift_order']} (exact minus integrator, along the cone axis)")
    elif ident.isotropic:
        lines.append("coning drift: no α² closed form (the linear part is not p1 + … + pN)")
    if a.assumptions is not None and a.assumptions.isotropy.corrections:
        lines += _per_axis(a)
    lines.append(f"remainder: {ident.remainder.summary()}")
    if a.check is not None:
        lines += _check_lines(a.check, a.cone_angles)
    if a.sculling is not None:
        lines += _sculling_lines(a.sculling, data)
    if "algorithm_file" in data:
        lines.append(f"algorithm file written: {data['algorithm_file']}")
    return "\n".join(lines)


def _check_lines(check, angles, indent="") -> list:
    if check.holds is None:
        verdict = f"no point resolved at {DRIFT_TOLERANCE:g} (round-off or extrapolation); within its uncertainty: {'agrees' if check.consistent else 'DISAGREES'}"
    else:
        verdict = "holds" if check.holds else "FAILS"
    out = [f"{indent}simulated against closed-form drift ({DRIFT_TOLERANCE:g} relative, cone angles {angles[0]:.3g} … {angles[-1]:.3g} rad): {verdict}"]
    for p in check.points:
        state = f"rel. difference {p.relative_difference:.1e}" if p.resolved else f"not resolved (uncertainty {p.uncertainty / abs(p.closed_form) if p.closed_form else math.inf:.1e} relative)"
        out.append(f"{indent}  ωh = {p.x:g}: D = {p.closed_form:.6g} closed form, {p.simulated:.6g} simulated, {state}")
    return out


def _per_axis(a) -> list:
    iso = a.assumptions.isotropy
    out = ["per axis (the integrator treats the axes differently; a cone about each body axis):"]
    for k, c in enumerate(iso.corrections):
        terms = ", ".join(f"{v} p{key.replace(',', '×p')}" for key, v in c.terms.items()) or "none"
        sym = ", ".join(f"{v} (p{i}·p{j} radial)" for (i, j), v in ((key, _frac(s)) for key, s in c.symmetric.items()))
        axial = ", ".join(f"{_frac(v)} p{j}" for j, v in c.linear.items()) or "nothing"
        line = f"  {c.name}: coning term {terms}" + (f", symmetric {sym}" if sym else "") + f"; the axial increment counted as {axial}"
        drift = c.drift()
        if drift is not None:
            line += f"; drift u = {_frac(drift.coefficient)} · α² ω (ωh)^{drift.order}"
        elif c.drift_function() is None:
            line += "; no α² closed form (the linear part is not p1 + … + pN on every axis)"
        out.append(line)
        check = iso.checks[k] if k < len(iso.checks) else None
        sim = iso.simulated[k] if k < len(iso.simulated) else None
        if check is not None:
            out += _check_lines(check, a.cone_angles, indent="    ")
        elif sim:
            out.append("    simulated D = u/(α² ω): " + ", ".join(f"{d:.6g} at ωh = {x:g}" for x, d in sim))
    return out


def _frac(f) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def _sculling_lines(sc, data) -> list:
    d = data["sculling"]
    out = ["sculling: " + ", ".join(f"{c} p{key.split(',')[0]}×b{key.split(',')[1]}" for key, c in d["terms"].items())]
    if sc.dual_extension:
        out.append("  the dual extension of the coning part (with the rotation term ½ P × V)")
    else:
        out.append("  departs from the dual extension of the coning part: " + ", ".join(f"{k} by {v}" for k, v in d["defect"].items()))
        for c in d["consequences"]:
            w = c["velocity_error_weight"]
            out.append(f"    {c['departure']} by {c['difference']}: alone, a velocity error {'O(h^' + str(w) + ')' if w else 'beyond h^8'}")
        cw = sc.corrected_weight
        corrected = f"O(h^{cw})" if cw is not None else "none through h^8"
        out.append(
            f"    all of them: velocity error {'O(h^' + str(sc.departures_weight) + ')' if sc.departures_weight else 'beyond h^8'}; "
            f"corrected (the dual extension), the linear and bilinear part errs at {corrected}"
        )
    order = sc.velocity_order
    exponent = "" if sc.velocity_exponent is None or not math.isfinite(sc.velocity_exponent) else f"; the integrator's own one-step velocity error: exponent {sc.velocity_exponent:.2f}"
    if order is not None:
        out.append(f"  velocity: local error O(h^{order + 1}), accuracy order {order} (decided by the {sc.decided_by}){exponent}")
    else:
        weight = f"O(h^{sc.error_weight})" if sc.error_weight else "none through h^8"
        out.append(f"  velocity: the linear and bilinear part errs at {weight}; the terms of degree three decide from h³ (not measured){exponent}")
    out.append(f"  remainder: {sc.remainder.summary()}")
    if sc.check is not None:
        verdict = {True: "holds", False: "FAILS", None: "no point resolved"}[sc.check.holds]
        ld = sc.check.largest_difference
        out.append(f"  simulated against closed-form rectification error: {verdict} (largest difference {'—' if ld is None else f'{ld:.3g}'})")
    return out


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
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument(
        "--integrator", metavar="FILE.py:NAME", default=None, help="Python file and the name of the integrator defined in it [path] (see docs/integrators.md; run in a child process) (default: none)"
    )
    source.add_argument(
        "--record",
        metavar="FILE",
        default=None,
        help="a record of input increments and the integrator's outputs, .csv or .npz, to identify with no code [path] (see docs/integrators.md) (default: none)",
    )
    p.add_argument("--samples-per-step", type=count, required=True, metavar="N", help=f"samples N per output step, 1..{MAX_SAMPLES} [count]")
    p.add_argument(
        "--max-previous",
        type=count,
        default=DEFAULT_MAX_PREVIOUS,
        metavar="K",
        help=f"how many samples before the step are probed, 0..{MAX_SAMPLES} [count] (default {DEFAULT_MAX_PREVIOUS})",
    )
    p.add_argument(
        "--max-previous-limit",
        type=count,
        default=LONGEST_MEMORY,
        metavar="K",
        help=f"the farthest sample the memory test probes, and the largest K it raises --max-previous to, up to {MAX_SAMPLES} [count] (default {LONGEST_MEMORY})",
    )
    p.add_argument(
        "--probe-amplitude-rad",
        type=number,
        default=None,
        metavar="E",
        help=f"largest probe amplitude ε_0 (then ε_0/2, /4, /8), in (0, 0.32] [rad] (default {PROBE_AMPLITUDE:g}, lowered to half the measured linearity range when that is smaller)",
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
    commands.only_with(p, "--probe-amplitude-rad", "--record", (None,))
