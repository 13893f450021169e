"""Options shared by the simulation commands: algorithm choice and motion parameters."""

from __future__ import annotations

import math

import numpy as np

from ...derivations.coning.algorithms import load_toml
from ...derivations.coning.registry import get
from ..core.quaternion import normalize
from ..core.units import RAD_PER_DEG
from ..core.validation import as_float, in_open_interval, positive


def add_algorithm(parser, *, required: bool = True) -> None:
    """Add ``--algorithm NAME | --algorithm-file FILE`` and ``--allow-inconsistent``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    required : bool, keyword-only
        Whether one of the two must be given.
    """
    group = parser.add_mutually_exclusive_group(required=required)
    group.add_argument("--algorithm", metavar="NAME", help="registry algorithm name (e.g. panov-4s-3, savage-1+1, ignagni-1996-5; see `strapdown algorithms list`)")
    group.add_argument("--algorithm-file", metavar="FILE", help="TOML file with a user algorithm (indices <= 0: samples of earlier steps; docs/algorithm-files.md)")
    parser.add_argument("--allow-inconsistent", action="store_true", help="accept a TOML algorithm that misses the second-order condition")


def algorithm_from(args):
    """The algorithm chosen by :func:`add_algorithm` options (ValueError if unknown or malformed).

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options.
    """
    if getattr(args, "algorithm_file", None):
        return load_toml(args.algorithm_file, allow_inconsistent=args.allow_inconsistent)
    return get(args.algorithm)


def add_motion(parser) -> None:
    """Add the regular precession (4.1) options ``--eps --nutation-deg --freq-hz``, step and duration.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    parser.add_argument("--eps", type=float, required=True, help="ε = μ/ν, precession to spin rate (−1 is coning)")
    parser.add_argument("--nutation-deg", type=float, required=True, help="nutation angle ϑ [deg], in (0, 180)")
    parser.add_argument("--freq-hz", type=float, required=True, help="spin frequency F [Hz]; ν = 2πF")
    add_run(parser)


def add_run(parser) -> None:
    """Add ``--sample-interval`` and ``--duration`` (both required).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    parser.add_argument("--sample-interval", type=float, required=True, metavar="H", help="gyro sample interval h [s]")
    parser.add_argument("--duration", type=float, required=True, help="length of the run [s], at least one step N·h")


def motion_parameters(args) -> dict:
    """Validated ε, ν [rad/s], ϑ [rad] from the options, with messages naming the option.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options of :func:`add_motion`.
    """
    eps = as_float(args.eps, "--eps")
    nutation_deg = in_open_interval(args.nutation_deg, "--nutation-deg", 0.0, 180.0, text="(0, 180) degrees")
    freq = positive(args.freq_hz, "--freq-hz")
    positive(args.sample_interval, "--sample-interval")
    positive(args.duration, "--duration")
    return {"eps": eps, "nu": 2.0 * math.pi * freq, "nutation": nutation_deg * RAD_PER_DEG}


def floats(text: str, name: str, count: int) -> np.ndarray:
    """Parse ``count`` comma-separated finite numbers, e.g. ``--w0 10,0,0``.

    Parameters
    ----------
    text : str
        The option's value.
    name : str
        The option as typed, for messages.
    count : int
        How many numbers are expected.
    """
    parts = [p.strip() for p in str(text).split(",")]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise ValueError(f"Expected `{name}` as {count} comma-separated numbers, got {text!r}") from None
    if len(values) != count:
        raise ValueError(f"Expected `{name}` as {count} comma-separated numbers, got {len(values)} in {text!r}")
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"Expected `{name}` to be finite, got {text!r}")
    return np.array(values)


def unit_quaternion(text: str, name: str) -> np.ndarray:
    """Parse four comma-separated numbers and normalise them to a unit quaternion.

    Parameters
    ----------
    text : str
        The option's value.
    name : str
        The option as typed, for messages.
    """
    return normalize(floats(text, name, 4), name)


def run_summary(alg, result) -> tuple[dict, str]:
    """JSON keys and the first text line shared by the simulation commands.

    Parameters
    ----------
    alg : Algorithm
        The algorithm run.
    result : SimulationResult
        The run.
    """
    data = {
        "algorithm": alg.name,
        "samples": alg.samples,
        "history": alg.history,
        "sample_interval": result.sample_interval,
        "step": result.step,
        "steps": result.steps,
        "simulated_duration": float(result.time[-1]),
    }
    prev = f" + {alg.history} previous" if alg.history else ""
    line = f"{alg.name}: N = {alg.samples}{prev}, h = {result.sample_interval:g} s, H = {result.step:g} s, {result.steps} steps, t = {data['simulated_duration']:g} s"
    return data, line


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
    g.add_argument("--rotation-axis", choices=("x", "y", "z"), default=None, help="body axis of the angular vibration (default x)")
    g.add_argument("--accel-axis", choices=("x", "y", "z"), default=None, help="body axis of the linear vibration (default y)")


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
