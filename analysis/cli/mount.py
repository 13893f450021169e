"""``strapdown mount-environment``: a vibration profile through an IMU mount, as an environment file.

``--profile FILE`` is a linear (and angular) random-vibration profile of the
base, ``--mount FILE`` the IMU block on its isolators (``docs/mount-files.md``).
The command prints the mount's modes, the rms of the base and of the IMU,
and writes with ``--out FILE`` an environment file (``docs/environment-files.md``)
whose spectrum is the IMU's six-channel cross-spectral density, for
``environment-drift``, ``design-coning``, ``environment-rates``.  ``--sensors
FILE`` takes the ``[gyro]``, ``[accelerometer]`` and ``[sampling]`` tables of
an environment file into the one written.  With ``--sample-interval`` it also
gives the coning drift and sculling rectification of ``--algorithms`` per mode
band: vectors in the body axes and their magnitudes.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

from ...derivations.toml_files import read_toml
from ..core.units import RAD_PER_S_TO_DEG_PER_H, STANDARD_GRAVITY, deg
from ..core.validation import positive
from ..vibration.environment import load_environment
from ..vibration.mount import COORDINATES, load_mount
from ..vibration.mount_response import MAX_TABLE_POINTS, TABLE_TOLERANCE, environment_toml, mount_drift, mount_environment
from ..vibration.profile import load_profile
from . import Result, UsageError
from ._options import add_limits, count, limits_from, number

__all__ = ["mount_command", "register"]

#: Algorithms of the drift table by default.
DEFAULT_ALGORITHMS = "two-sample,optimal-3,ignagni-1996-5"
#: The sensor tables ``--sensors`` takes from an environment file.
_SENSOR_TABLES = ("gyro", "accelerometer", "sampling")


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    return "[" + ", ".join(_toml_value(x) for x in v) + "]"


def _sensor_text(path: Path) -> tuple:
    """The sensors of an environment file and the TOML text of its sensor tables (checked by ``load_environment``)."""
    env = load_environment(path)
    if env.lines or env.spectra:
        raise ValueError(f"{path}: holds lines or spectra; --sensors takes a file with only [gyro], [accelerometer] and [sampling] tables")
    data = read_toml(path, max_bytes=4 * 1024 * 1024, max_depth=8, kind="environment file")
    out = []
    for name in _SENSOR_TABLES:
        table = data.get(name)
        if not table:
            continue
        out.append(f"[{name}]")
        out += [f"{key} = {_toml_value(v)}" for key, v in table.items() if not isinstance(v, dict)]
        for key, v in table.items():
            if isinstance(v, dict):
                out += ["", f"[{name}.{key}]"] + [f"{k} = {_toml_value(x)}" for k, x in v.items()]
        out.append("")
    return env, "\n".join(out)


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


def _vec(v) -> list:
    return [float(x) for x in v]


def _norm(v) -> float:
    return float(np.linalg.norm(v))


def mount_command(args) -> Result:
    """Run ``strapdown mount-environment``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.

    Returns
    -------
    Result
    """
    if args.algorithms is not None and args.sample_interval is None:
        raise UsageError("--algorithms applies with --sample-interval (the drift table)")
    excitation = load_profile(args.profile)
    mount = load_mount(args.mount)
    sensors, sensor_text = (None, "") if args.sensors is None else _sensor_text(Path(args.sensors))
    tolerance = positive(args.tolerance, "--tolerance")
    gyro = None if sensors is None else sensors.gyro
    accel = None if sensors is None else sensors.accelerometer
    r = mount_environment(mount, excitation, gyro=gyro, accelerometer=accel, tolerance=tolerance, max_points=args.max_points, limits=limits_from(args))
    written = None
    if args.out:
        written = str(args.out)
        _write(Path(args.out), environment_toml(r.environment, sensors=sensor_text))
    base_rms, imu_rms = excitation.rms(), r.output_rms()
    modes = [
        {"frequency_hz": md.frequency, "damping_ratio": md.damping_ratio, "damped_frequency_hz": md.damped_frequency,
         "energy": dict(zip(COORDINATES, md.energy)), "motion": md.description}
        for md in r.modes
    ]  # fmt: skip
    data = {
        "profile": str(args.profile),
        "mount": str(args.mount),
        "environment": r.environment.name,
        "written": written,
        "table": {"points": r.points, "spectra": len(r.environment.spectra), "interpolation_error": r.table_error, "tolerance": r.tolerance, "converged": r.converged},
        "base_rms": {"angular_rad_s": _vec(base_rms[:3]), "linear_m_s2": _vec(base_rms[3:])},
        "imu_rms": {"rate_rad_s": _vec(imu_rms[:3]), "specific_force_m_s2": _vec(imu_rms[3:])},
        "modes": modes,
        "drift": None,
    }
    g = STANDARD_GRAVITY
    k = RAD_PER_S_TO_DEG_PER_H
    text = [
        f"{r.environment.name}: {r.points}-point table in {len(r.environment.spectra)} {'spectrum' if len(r.environment.spectra) == 1 else 'spectra'}, "
        f"interpolation error {r.table_error:.2g} ({'within' if r.converged else 'ABOVE'} the tolerance {r.tolerance:g})"
        + (f"; written to {written}" if written else "; not written (give --out FILE)"),
        f"base rms: angular rate {np.round(deg(base_rms[:3]), 4).tolist()} deg/s, acceleration {np.round(base_rms[3:] / g, 4).tolist()} g",
        f"IMU rms:  angular rate {np.round(deg(imu_rms[:3]), 4).tolist()} deg/s, specific force {np.round(imu_rms[3:] / g, 4).tolist()} g",
        "",
        f"{'mode':>4} {'f [Hz]':>9} {'damping':>8}  motion (share of kinetic energy)",
    ]
    text += [f"{i + 1:>4} {md.frequency:>9.3f} {md.damping_ratio:>8.4f}  {md.description}" for i, md in enumerate(r.modes)]
    if not r.converged:
        text.append(f"warning: the table stopped at --max-points {args.max_points}; its interpolation error {r.table_error:.2g} exceeds --tolerance {tolerance:g}")
    if args.sample_interval is not None:
        from ...derivations.coning.registry import get

        h = positive(args.sample_interval, "--sample-interval")
        names = [n.strip() for n in (args.algorithms or DEFAULT_ALGORITHMS).split(",") if n.strip()]
        if not names:
            raise UsageError("--algorithms: expected at least one algorithm name")
        algorithms = [get(n) for n in names]
        d = mount_drift(algorithms, r, h)
        rows = []
        for a, coning, scull, total, total_s in zip(algorithms, d.coning, d.sculling, d.total_coning, d.total_sculling):
            bands = [
                {"low_hz": b.low, "high_hz": b.high, "modes": [i + 1 for i in b.modes],
                 "drift_vector_rad_s": _vec(c), "drift_magnitude_rad_s": _norm(c), "rectification_vector_m_s2": _vec(s), "rectification_magnitude_m_s2": _norm(s)}
                for b, c, s in zip(d.bands, coning, scull)
            ]  # fmt: skip
            rows.append({
                "algorithm": a.name, "total_drift_vector_rad_s": _vec(total), "total_drift_magnitude_rad_s": _norm(total),
                "total_drift_magnitude_deg_per_h": _norm(total) * k, "total_rectification_vector_m_s2": _vec(total_s),
                "total_rectification_magnitude_m_s2": _norm(total_s), "bands": bands,
            })  # fmt: skip
        sensor = d.sensor.sum(axis=0)
        data["drift"] = {"sample_interval": h, "sensor_drift_vector_rad_s": _vec(sensor), "sensor_drift_magnitude_rad_s": _norm(sensor), "algorithms": rows}
        text += [
            "",
            f"mean coning drift and sculling rectification at h = {h:g} s: vectors in the body axes (x, y, z), exact minus algorithm",
            f"sensor part (pseudo-coning, every algorithm): {np.round(sensor * k, 6).tolist()} deg/h, magnitude {_norm(sensor) * k:.4g} deg/h",
        ]
        for row in rows:
            text += [
                "",
                f"{row['algorithm']}: drift {np.round(np.array(row['total_drift_vector_rad_s']) * k, 6).tolist()} deg/h, magnitude {row['total_drift_magnitude_deg_per_h']:.4g} deg/h; "
                f"rectification magnitude {row['total_rectification_magnitude_m_s2']:.3g} m/s²",
                f"  {'band [Hz]':>15} {'modes':>7} {'drift vector [deg/h]':>40} {'|drift| [deg/h]':>16} {'|rectification| [m/s²]':>23}",
            ]
            for b in row["bands"]:
                vec = "(" + ", ".join(f"{x * k:+.3e}" for x in b["drift_vector_rad_s"]) + ")"
                modes_text = ",".join(str(i) for i in b["modes"])
                text.append(f"  {b['low_hz']:>7.4g}–{b['high_hz']:<7.4g} {modes_text:>7} {vec:>40} {b['drift_magnitude_rad_s'] * k:>16.4g} {b['rectification_magnitude_m_s2']:>23.4g}")
    return Result(data, "\n".join(text))


def register(commands) -> None:
    """Add ``mount-environment`` to the command line.

    Parameters
    ----------
    commands : strapdown.analysis.cli.Commands
        The command registry.
    """
    p = commands.add(
        "mount-environment",
        mount_command,
        "a base vibration profile through an IMU mount: modes, rms, and the IMU's cross-spectra as an environment file",
    )
    p.add_argument("--profile", required=True, metavar="FILE", help="TOML profile of the base's random vibration [path] (docs/mount-files.md; required)")
    p.add_argument("--mount", required=True, metavar="FILE", help="TOML mount file: the IMU block and its isolators [path] (docs/mount-files.md; required)")
    p.add_argument("--out", default=None, metavar="FILE", help="write the environment file here [path] (default: not written)")
    p.add_argument("--sensors", default=None, metavar="FILE",
                   help="environment file whose [gyro], [accelerometer] and [sampling] tables to use and write [path] (default: ideal sensors)")  # fmt: skip
    p.add_argument("--tolerance", type=number, default=TABLE_TOLERANCE, metavar="E",
                   help=f"largest interpolation error of the spectrum table [dimensionless], in (0, 0.5) (default {TABLE_TOLERANCE:g})")  # fmt: skip
    p.add_argument("--max-points", type=count, default=MAX_TABLE_POINTS, metavar="N", help=f"most frequencies of the spectrum table [count] (default {MAX_TABLE_POINTS})")
    p.add_argument("--sample-interval", type=number, default=None, metavar="H",
                   help="algorithm sample interval h for the drift table [s], > 0 (default: no drift table)")  # fmt: skip
    p.add_argument("--algorithms", default=None, metavar="NAMES",
                   help=f"comma-separated registry algorithms of the drift table [name] (`strapdown algorithms list`) (default {DEFAULT_ALGORITHMS})")  # fmt: skip
    add_limits(p)

