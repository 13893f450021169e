"""Options shared by the simulation commands: algorithm choice and motion parameters."""

from __future__ import annotations

import math

import numpy as np

from ...derivations.coning.algorithms import load_toml
from ...derivations.coning.registry import get
from ..core.quaternion import normalize
from ..core.validation import as_float, in_open_interval, positive

RAD_PER_DEG = math.pi / 180.0


def add_algorithm(parser) -> None:
    """``--algorithm NAME | --algorithm-file FILE`` and ``--allow-inconsistent``."""
    group = parser.add_mutually_exclusive_group(required=True)
    group.add_argument("--algorithm", metavar="NAME", help="registry algorithm name (e.g. panov-4s-3, lebedev-panov-6)")
    group.add_argument("--algorithm-file", metavar="FILE", help="TOML file with a user algorithm")
    parser.add_argument("--allow-inconsistent", action="store_true", help="accept a TOML algorithm that misses the second-order condition")


def algorithm_from(args):
    """The algorithm chosen by :func:`add_algorithm` options (ValueError if unknown or malformed)."""
    if getattr(args, "algorithm_file", None):
        return load_toml(args.algorithm_file, allow_inconsistent=args.allow_inconsistent)
    return get(args.algorithm)


def add_motion(parser) -> None:
    """Regular precession (4.1) options: ``--eps --nutation-deg --freq-hz``, step and duration."""
    parser.add_argument("--eps", type=float, required=True, help="ε = μ/ν, precession to spin rate (−1 is coning)")
    parser.add_argument("--nutation-deg", type=float, required=True, help="nutation angle ϑ [deg], in (0, 180)")
    parser.add_argument("--freq-hz", type=float, required=True, help="spin frequency F [Hz]; ν = 2πF")
    parser.add_argument("--sample-interval", type=float, required=True, metavar="H", help="gyro sample interval h [s]")
    parser.add_argument("--duration", type=float, required=True, help="length of the run [s], at least one step N·h")


def motion_parameters(args) -> dict:
    """Validated ε, ν [rad/s], ϑ [rad] from the options, with messages naming the option."""
    eps = as_float(args.eps, "--eps")
    nutation_deg = in_open_interval(args.nutation_deg, "--nutation-deg", 0.0, 180.0, text="(0, 180) degrees")
    freq = positive(args.freq_hz, "--freq-hz")
    positive(args.sample_interval, "--sample-interval")
    positive(args.duration, "--duration")
    return {"eps": eps, "nu": 2.0 * math.pi * freq, "nutation": nutation_deg * RAD_PER_DEG}


def floats(text: str, name: str, count: int) -> np.ndarray:
    """Parse ``count`` comma-separated finite numbers, e.g. ``--w0 10,0,0``."""
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
    """Parse four comma-separated numbers and normalise them to a unit quaternion."""
    return normalize(floats(text, name, 4), name)


def run_summary(alg, result) -> tuple[dict, str]:
    """JSON keys and the first text line shared by the simulation commands."""
    data = {
        "algorithm": alg.name,
        "samples": alg.samples,
        "sample_interval": result.sample_interval,
        "step": result.step,
        "steps": result.steps,
        "simulated_duration": float(result.time[-1]),
    }
    line = f"{alg.name}: N = {alg.samples}, h = {result.sample_interval:g} s, H = {result.step:g} s, {result.steps} steps, t = {data['simulated_duration']:g} s"
    return data, line
