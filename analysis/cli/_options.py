"""Options shared by the commands: algorithm choice, motion parameters, counts, work limits.

Argument types for argparse (:func:`count`, :func:`number`) turn a mistyped
value into a one-line error naming the option; :func:`add_limits` and
:func:`limits_from` give a command the ``--time-limit`` / ``--memory-limit-mb``
options of :mod:`strapdown.analysis.core.budget`.  The algorithm registry (and
with it SymPy) is imported only by the commands that take an algorithm, so that
a command such as ``strapdown stability`` starts quickly.
"""

from __future__ import annotations

import argparse
import math
import re

import numpy as np

from ..core import budget
from ..core.quaternion import normalize
from ..core.roundoff import drift_floor
from ..core.units import RAD_PER_DEG, RAD_PER_S_TO_DEG_PER_H
from ..core.validation import as_float, in_open_interval, positive

__all__ = [
    "count",
    "number",
    "add_algorithm",
    "algorithm_from",
    "add_motion",
    "add_run",
    "motion_parameters",
    "check_run_work",
    "add_sculling",
    "sculling_parameters",
    "SCULLING_DEFAULTS",
    "add_limits",
    "limits_from",
    "check_work",
    "floats",
    "unit_quaternion",
    "run_summary",
    "PROGRESS_HELP",
]

_COUNT = re.compile(r"[+-]?(\d+(_\d+)*|\d*\.?\d+([eE][+-]?\d+)?|\d+\.\d*([eE][+-]?\d+)?)")


#: Help of ``--progress``, as the edge (:func:`strapdown.analysis.cli.main`) behaves: progress is shown by
#: default (bars on a terminal, plain lines otherwise); the flag only turns the lines into bars.
PROGRESS_HELP = (
    "draw progress bars on stderr even when it is not a terminal (default: off; progress is shown anyway, "
    "as bars on a terminal and as a plain line every few seconds in a log or pipe; --quiet shows none)"
)


def count(text: str) -> int:
    """Argparse type of a count: a whole number, also in scientific notation (``1e6``, ``2.5e3``).

    Parameters
    ----------
    text : str
        The value as typed.

    Returns
    -------
    int

    Raises
    ------
    argparse.ArgumentTypeError
        If ``text`` is not a whole number (``1.5``, ``abc``, ``nan``, ``1e999``).

    Examples
    --------
    >>> count("1e6"), count("2.5e3"), count("1_000")
    (1000000, 2500, 1000)
    """
    text = str(text).strip()
    if not _COUNT.fullmatch(text) or len(text) > 40:
        raise argparse.ArgumentTypeError(f"expected a whole number such as 1000 or 1e6, got {text[:40]!r}")
    if "e" not in text.lower() and "." not in text:
        return int(text)
    value = float(text)
    if not math.isfinite(value) or not value.is_integer():
        raise argparse.ArgumentTypeError(f"expected a whole number such as 1000 or 1e6, got {text!r}")
    return int(value)


def number(text: str) -> float:
    """Argparse type of a finite real number (``nan``, ``inf`` and overflow such as ``1e999`` are refused).

    Parameters
    ----------
    text : str
        The value as typed.

    Returns
    -------
    float

    Raises
    ------
    argparse.ArgumentTypeError
        If ``text`` is not a finite number.
    """
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {str(text)[:40]!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {str(text)[:40]!r}")
    return value


# --------------------------------------------------------------------------- algorithms
def add_algorithm(parser, *, required: bool = True) -> None:
    """``--algorithm NAME | --algorithm-file FILE`` and ``--allow-inconsistent``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    required : bool, keyword-only
        Whether one of the two must be given.
    """
    from ...derivations.coning.algorithms import TOML_LIMITS
    from ...derivations.coning.registry import names

    group = parser.add_mutually_exclusive_group(required=required)
    default = "" if required else " (default: none)"
    group.add_argument(
        "--algorithm",
        metavar="NAME",
        help=f"registry algorithm [name], one of: {', '.join(names(library=True))} (`strapdown algorithms list` shows them){default}",
    )
    group.add_argument(
        "--algorithm-file",
        metavar="FILE",
        help=f"TOML file with a user algorithm [path] (indices <= 0: samples of earlier steps; docs/algorithm-files.md; "
        f"at most {TOML_LIMITS.samples} samples, {TOML_LIMITS.terms} terms){default}",
    )
    parser.add_argument("--allow-inconsistent", action="store_true", help="accept a TOML algorithm that misses the second-order condition")


def algorithm_from(args):
    """The algorithm chosen by :func:`add_algorithm` options.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments with ``algorithm`` or ``algorithm_file``.

    Returns
    -------
    strapdown.derivations.coning.algorithms.Algorithm

    Raises
    ------
    ValueError
        An unknown name, or a file that is missing, unreadable, malformed or beyond the limits.
    """
    from ...derivations.coning.algorithms import SecondOrderConditionError, load_toml
    from ...derivations.coning.registry import get

    if getattr(args, "algorithm_file", None) is not None:
        if not str(args.algorithm_file).strip():
            raise ValueError("Expected `--algorithm-file` to name a TOML file, got an empty file name")
        try:
            return load_toml(args.algorithm_file, allow_inconsistent=args.allow_inconsistent)
        except SecondOrderConditionError as exc:
            raise ValueError(
                f"{exc.path}: algorithm misses the second-order condition: Σ c_ij (j − i) = {exc.total}, "
                f"expected N³/12 = {exc.expected} (pass --allow-inconsistent to accept it)"
            ) from None
    return get(args.algorithm)


# --------------------------------------------------------------------------- motion
def add_motion(parser) -> None:
    """Motion options: regular precession (4.1) or classical coning, ``--freq-hz``, sample interval, duration, work limits.

    Regular precession takes ``--eps --nutation-deg``; classical coning takes
    ``--half-angle-deg`` alone, the same motion with ε = −1 and ϑ = α (its
    coning rate ω is the spin rate ν = 2πF).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    g = parser.add_argument_group("motion: regular precession (--eps and --nutation-deg) or classical coning (--half-angle-deg)")
    g.add_argument("--eps", type=float, default=None, help="ε = μ/ν, precession to spin rate of a regular precession [dimensionless], −1 is coning (default: none)")
    g.add_argument("--nutation-deg", type=float, default=None, help="nutation angle ϑ of a regular precession [deg], in (0, 180) (default: none)")
    g.add_argument(
        "--half-angle-deg",
        type=float,
        default=None,
        help="half-cone angle α of classical coning [deg], in (0, 90): the regular precession with ε = −1 and ϑ = α (default: none)",
    )
    g.add_argument("--freq-hz", type=float, required=True, help="spin frequency F [Hz], > 0, ν = 2πF; under classical coning the coning frequency (required)")
    add_run(parser)


def add_run(parser) -> None:
    """``--sample-interval`` and ``--duration`` (both required), and the work limits of :func:`add_limits`.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    parser.add_argument("--sample-interval", type=float, required=True, metavar="H", help="gyro sample interval h [s] (required)")
    parser.add_argument("--duration", type=float, required=True, help="length of the run [s], at least one step N·h (required)")
    add_limits(parser)


def motion_parameters(args, algorithm=None, *, velocity: bool = False) -> dict:
    """Validated ε, ν [rad/s], ϑ [rad] from the options, with messages naming the option.

    With ``algorithm`` the work of the run is estimated too and refused if it
    exceeds the limits of :func:`add_limits` (before anything is allocated).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of :func:`add_motion`.
    algorithm : Algorithm, optional
        The algorithm to be run (for the work estimate).
    velocity : bool, keyword-only
        The run is a dual (apparent-velocity) run (about four times the work per step).

    Returns
    -------
    dict
        ``eps``, ``nu`` [rad/s], ``nutation`` [rad], ``coning`` (True for
        ``--half-angle-deg``) and ``nutation_deg`` [deg] (ϑ, or α under coning).

    Raises
    ------
    ValueError
        A value out of range (in the unit typed), both or neither of the two
        descriptions of the motion, or work beyond the limits
        (:class:`strapdown.analysis.core.budget.BudgetExceeded`).
    """
    coning = getattr(args, "half_angle_deg", None) is not None
    given = [flag for key, flag in (("eps", "--eps"), ("nutation_deg", "--nutation-deg")) if getattr(args, key) is not None]
    if coning and given:
        raise ValueError(f"Expected either --half-angle-deg (classical coning) or --eps with --nutation-deg (regular precession), got --half-angle-deg and {given[0]}")
    if not coning and len(given) < 2:
        missing = " and ".join(f for f in ("--eps", "--nutation-deg") if f not in given)
        raise ValueError(f"Expected --eps with --nutation-deg (regular precession) or --half-angle-deg (classical coning), got no {missing}")
    if coning:
        eps, nutation_deg = -1.0, in_open_interval(args.half_angle_deg, "--half-angle-deg", 0.0, 90.0, text="(0, 90) degrees")
    else:
        eps = as_float(args.eps, "--eps")
        nutation_deg = in_open_interval(args.nutation_deg, "--nutation-deg", 0.0, 180.0, text="(0, 180) degrees")
    freq = positive(args.freq_hz, "--freq-hz")
    h = positive(args.sample_interval, "--sample-interval")
    positive(args.duration, "--duration")
    nu, nutation = 2.0 * math.pi * freq, nutation_deg * RAD_PER_DEG
    with np.errstate(over="ignore", invalid="ignore"):
        rate = float(abs(nu) * np.sqrt(np.float64(1.0) + 2.0 * eps * math.cos(nutation) + np.float64(eps) ** 2))  # |ω| of (4.1), constant
    if not rate * h < math.pi:
        motion = f"--half-angle-deg {nutation_deg:g}" if coning else f"--eps {eps:g}, --nutation-deg {nutation_deg:g}"
        raise ValueError(
            f"Expected the body to turn less than π rad per sample, got |ω| h = {rate * h:.3g} rad "
            f"(|ω| = {rate:.3g} rad/s from {motion}, --freq-hz {freq:g}; --sample-interval {h:g} s): "
            "sample faster or slow the motion"
        )
    if algorithm is not None:
        check_run_work(args, algorithm, velocity=velocity)
    return {"eps": eps, "nu": nu, "nutation": nutation, "coning": coning, "nutation_deg": nutation_deg}


def check_run_work(args, algorithm, *, velocity: bool = False) -> None:
    """Estimate the work of a simulation run from ``--duration`` and ``--sample-interval``; refuse it beyond the limits.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments of :func:`add_run` (validated ``sample_interval``, ``duration``).
    algorithm : Algorithm
        The algorithm to be run.
    velocity : bool, keyword-only
        The run is a dual (apparent-velocity) run (about four times the work per step).

    Raises
    ------
    strapdown.analysis.core.budget.BudgetExceeded
        If the estimate exceeds the limits (a ValueError).
    """
    from ..coning.simulator import CHUNK_STEPS

    h = positive(args.sample_interval, "--sample-interval")
    duration = positive(args.duration, "--duration")
    steps = duration / (algorithm.samples * h)
    degree_sum = sum(t.degree for t in algorithm.terms)
    what = f"{steps:.3g} steps of {algorithm.samples} samples (--duration {duration:g} s / --sample-interval {h:g} s)"
    check_work(args, budget.coning_simulation(steps, window=algorithm.window, degree_sum=degree_sum, velocity=velocity, chunk_steps=CHUNK_STEPS, what=what))


# --------------------------------------------------------------------------- work limits
def add_limits(parser) -> None:
    """``--time-limit`` [s] and ``--memory-limit-mb``: the largest estimated work a command accepts.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    parser.add_argument(
        "--time-limit",
        type=number,
        default=budget.DEFAULT_TIME_LIMIT,
        metavar="T",
        help=f"refuse work estimated to take longer [s] (default {budget.DEFAULT_TIME_LIMIT:g})",
    )
    parser.add_argument(
        "--memory-limit-mb",
        type=number,
        default=budget.DEFAULT_MEMORY_LIMIT / 1e6,
        metavar="M",
        help=f"refuse work estimated to need more memory [MB], 1 MB = 10⁶ bytes (default {budget.DEFAULT_MEMORY_LIMIT / 1e6:g})",
    )


def limits_from(args) -> budget.Limits:
    """The :class:`~strapdown.analysis.core.budget.Limits` of the options of :func:`add_limits`.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments (defaults apply where the options are absent).

    Returns
    -------
    strapdown.analysis.core.budget.Limits

    Raises
    ------
    ValueError
        A limit that is not a positive number.
    """
    seconds = positive(getattr(args, "time_limit", budget.DEFAULT_TIME_LIMIT), "--time-limit")
    megabytes = positive(getattr(args, "memory_limit_mb", budget.DEFAULT_MEMORY_LIMIT / 1e6), "--memory-limit-mb")
    return budget.Limits(seconds=seconds, memory=megabytes * 1e6)


def check_work(args, estimate: budget.Estimate) -> budget.Estimate:
    """Refuse ``estimate`` if it exceeds the limits given on the command line.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed arguments (with the options of :func:`add_limits`, or the defaults).
    estimate : strapdown.analysis.core.budget.Estimate
        The work of the request.

    Returns
    -------
    strapdown.analysis.core.budget.Estimate
        ``estimate``.

    Raises
    ------
    strapdown.analysis.core.budget.BudgetExceeded
        If it exceeds a limit (the CLI edge prints the estimate, the limit and the option).
    """
    return budget.check(estimate, limits_from(args))


# --------------------------------------------------------------------------- vectors
def floats(text: str, name: str, count: int) -> np.ndarray:
    """Parse ``count`` comma-separated finite numbers, e.g. ``--w0 10,0,0``.

    Parameters
    ----------
    text : str
        The value as typed.
    name : str
        The option, for messages.
    count : int
        How many numbers [count].

    Returns
    -------
    ndarray, shape (count,)

    Raises
    ------
    ValueError
        Not ``count`` numbers, or a number that is not finite.
    """
    parts = [p.strip() for p in str(text).split(",")]
    shown = str(text) if len(str(text)) <= 60 else str(text)[:57] + "..."
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise ValueError(f"Expected `{name}` as {count} comma-separated numbers, got {shown!r}") from None
    if len(values) != count:
        raise ValueError(f"Expected `{name}` as {count} comma-separated numbers, got {len(values)} in {shown!r}")
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"Expected `{name}` to be finite, got {shown!r}")
    return np.array(values)


def unit_quaternion(text: str, name: str) -> np.ndarray:
    """Parse four comma-separated numbers and normalise them to a unit quaternion.

    Parameters
    ----------
    text : str
        The value as typed, e.g. ``"1,0,0,0"``.
    name : str
        The option, for messages.

    Returns
    -------
    ndarray, shape (4,)

    Raises
    ------
    ValueError
        Not four finite numbers, or all four zero.
    """
    q = floats(text, name, 4)
    norm = float(np.sqrt(np.sum(q * q)))
    if not norm > 1e-150 or not math.isfinite(norm):
        raise ValueError(f"Expected `{name}` to be a nonzero quaternion of moderate size, got {text!r}")
    return normalize(q / np.max(np.abs(q)), name)


# --------------------------------------------------------------------------- results
def run_summary(alg, result, params: dict | None = None) -> tuple[dict, str]:
    """JSON keys and the first text lines shared by the simulation commands.

    With the motion ``params`` the simulated drift is compared with the
    round-off floor of the run (:func:`strapdown.analysis.core.roundoff.drift_floor`):
    below it, the result says so (``drift_below_roundoff_floor`` and a note),
    rather than presenting round-off as a drift.

    Parameters
    ----------
    alg : Algorithm
        The algorithm run.
    result : SimulationResult or LongRunResult
        The run (:mod:`strapdown.analysis.coning.simulator`, :mod:`strapdown.analysis.coning.long_run`):
        what both have, ``sample_interval``, ``step``, ``steps``, ``duration`` and ``drift_rate``, is read.
    params : dict, optional
        ``eps``, ``nu`` [rad/s] of the motion (from :func:`motion_parameters`).

    Returns
    -------
    data : dict
        Algorithm, samples, sample interval [s], step [s], steps, simulated duration [s]
        (and, with ``params``, ``roundoff_floor_deg_per_h`` and ``drift_below_roundoff_floor``).
    text : str
        One line (two when the drift is below the floor).
    """
    data = {
        "algorithm": alg.name,
        "samples": alg.samples,
        "history": alg.history,
        "sample_interval": result.sample_interval,
        "step": result.step,
        "steps": result.steps,
        "simulated_duration": float(result.duration),
    }
    prev = f" + {alg.history} previous" if alg.history else ""
    line = f"{alg.name}: N = {alg.samples}{prev}, h = {result.sample_interval:g} s, H = {result.step:g} s, {result.steps} steps, t = {data['simulated_duration']:g} s"
    if params is not None:
        floor = drift_floor(params["nu"], params["eps"] * params["nu"]) * RAD_PER_S_TO_DEG_PER_H
        below = bool(float(result.drift_rate) * RAD_PER_S_TO_DEG_PER_H < floor)
        data["roundoff_floor_deg_per_h"] = floor
        data["drift_below_roundoff_floor"] = below
        if below:
            line += (
                f"\nnote: the simulated drift is below the float64 round-off floor of this run ({floor:.2g} deg/h): "
                "it is round-off, not the algorithm's drift (use a larger sample interval, or the asymptotic u_a)"
            )
    return data, line


# --------------------------------------------------------------------------- sculling
def add_sculling(parser) -> None:
    """Add the classical sculling options (``--motion sculling``).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    g = parser.add_argument_group("sculling motion (--motion sculling)")
    g.add_argument("--angle-amplitude-deg", type=float, default=None, help="amplitude θ0 of the angular vibration about the rotation axis [deg] (default 0.1)")
    g.add_argument("--accel-amplitude-m-s2", type=float, default=None, help="amplitude A of the linear vibration [m/s²] (default 1)")
    g.add_argument("--angle-phase-deg", type=float, default=None, help="phase φ_θ of the angular vibration [deg] (default 0)")
    g.add_argument("--accel-phase-deg", type=float, default=None, help="phase φ_a of the linear vibration [deg] (default 0: in phase)")
    g.add_argument("--rotation-axis", choices=("x", "y", "z"), default=None, help="body axis of the angular vibration: x, y or z (default x)")
    g.add_argument("--accel-axis", choices=("x", "y", "z"), default=None, help="body axis of the linear vibration: x, y or z (default y)")


SCULLING_DEFAULTS = {"angle_amplitude_deg": 0.1, "accel_amplitude_m_s2": 1.0, "angle_phase_deg": 0.0, "accel_phase_deg": 0.0, "rotation_axis": "x", "accel_axis": "y"}


def sculling_parameters(args) -> dict:
    """Validated sculling parameters (SI, radians) from :func:`add_sculling` options and ``--freq-hz``.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.
    """
    v = {k: (getattr(args, k) if getattr(args, k) is not None else d) for k, d in SCULLING_DEFAULTS.items()}
    axes = "xyz"
    return {
        "angle_amplitude": as_float(v["angle_amplitude_deg"], "--angle-amplitude-deg") * RAD_PER_DEG,
        "accel_amplitude": as_float(v["accel_amplitude_m_s2"], "--accel-amplitude-m-s2"),
        "nu": 2.0 * math.pi * positive(args.freq_hz, "--freq-hz"),
        "angle_phase": as_float(v["angle_phase_deg"], "--angle-phase-deg") * RAD_PER_DEG,
        "accel_phase": as_float(v["accel_phase_deg"], "--accel-phase-deg") * RAD_PER_DEG,
        "rotation_axis": axes.index(v["rotation_axis"]),
        "accel_axis": axes.index(v["accel_axis"]),
    }


def write_text_atomic(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically: a temporary file in the same directory, then renamed over it.

    Parameters
    ----------
    path : str or Path
        The file.
    text : str
        Its content (UTF-8, ``\\n`` line ends).
    """
    import os
    import tempfile
    from pathlib import Path

    path = Path(path)
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
