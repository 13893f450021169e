"""Plausibility of a recorded log before it is analysed.

A log in the wrong units or axes is read without complaint and gives answers
wrong by tens of degrees; these checks look at what the samples themselves say.
They work on one-second windows (means of the rates and the specific force over
each window), so their cost is one pass over the samples:

``time base``
    The sample rate is an IMU's (above 1 Hz); the integration interval the log
    states matches the time between samples (no increments dropped by logging below
    the integration rate); a specific force of g/1000 means a time column in
    milliseconds; the jitter is small.
``increments or rates``
    Velocity increments averaging g per sample are rates in the increment columns;
    specific forces averaging g × interval are increments in the rate columns.
``gravity magnitude``
    The median of the windows' mean specific force is g (normal gravity at the
    latitude given, or at 45°) within 2 % (fail beyond 10 %: m/s² against g units).
``gravity direction``
    Gravity reads about −g on z (FRD: z down); +g on z is a log with z up (FLU, ENU).
``gyro scale``
    Where the body turns across gravity, the accelerometers see gravity turn in the body axes:
    ``Δf ≈ −Δθ × f`` (skipped in a drive, GNSS speed above 1 m/s, whose accelerations
    change the specific force too).  The least-squares factor k between the gyros' turn and the
    accelerometers' is 1; k = π/180 means degrees logged as radians, k = interval means
    rates in the increment columns.
``Earth rate``
    At rest, a gyro good enough to see the Earth's rate reads ``|ω| = Ω`` = 15.04 °/h; the
    angle of ω above the horizontal is the latitude.  A gyro whose bias hides Ω is
    skipped, not failed.
``gaps``
    A gap longer than 60 s fails (pick a stretch with ``segment``); shorter gaps and
    the logger's own dropouts warn.
``latitude``
    A latitude given is compared with the log's own: its GNSS fixes, its metadata, or
    (warning only) the gyros' Earth rate.

Public API
----------
.. autosummary::

   Check
   LogChecks
   check_log
   GAP_LIMIT
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..alignment.earth import EARTH_RATE, normal_gravity

__all__ = ["Check", "LogChecks", "check_log", "GAP_LIMIT"]

#: A gap longer than this fails the ``gaps`` check [s].
GAP_LIMIT = 60.0

_WINDOW = 1.0  # averaging window of the checks [s]


@dataclass(frozen=True)
class Check:
    """One plausibility check.

    Attributes
    ----------
    name : str
        ``"time base"``, ``"gravity magnitude"`` ...
    status : str
        ``"pass"``, ``"warn"`` (usable, but look), ``"fail"`` (refused) or ``"skip"`` (the log cannot tell).
    value : str
        The value seen, with its unit.
    message : str
        What it means.
    """

    name: str
    status: str
    value: str
    message: str

    def line(self) -> str:
        """One line: ``log check 'gravity direction' failed: ... (value seen: ...)``.

        Returns
        -------
        str
        """
        verb = {"fail": "failed", "warn": "warns", "pass": "passed", "skip": "skipped"}[self.status]
        return f"log check '{self.name}' {verb}: {self.message} (value seen: {self.value})"


@dataclass(frozen=True)
class LogChecks:
    """The checks of one log.

    Attributes
    ----------
    checks : tuple of Check
        In the order they ran.
    """

    checks: tuple

    @property
    def failures(self) -> tuple:
        """The failed checks."""
        return tuple(c for c in self.checks if c.status == "fail")

    @property
    def warnings(self) -> tuple:
        """The checks that warn."""
        return tuple(c for c in self.checks if c.status == "warn")

    @property
    def passed(self) -> bool:
        """No check failed."""
        return not self.failures

    def by_name(self, name: str) -> Check:
        """The check called ``name``.

        Parameters
        ----------
        name : str
            Its name.

        Returns
        -------
        Check

        Raises
        ------
        KeyError
            If no check has that name.
        """
        for c in self.checks:
            if c.name == name:
                return c
        raise KeyError(name)


def _windows(segments):
    """Per one-second window: mean rate (W, 3) [rad/s], mean specific force (W, 3) [m/s²], rate spread [rad/s], interval [s], segment index."""
    rates, forces, spread, h_all, ids = [], [], [], [], []
    for seg in segments:
        h = seg.dt
        w = max(1, int(round(_WINDOW / h)))
        m = seg.n_samples // w
        if m == 0:
            continue
        dth = seg.dtheta[: m * w].reshape(m, w, 3)
        dv = seg.dv[: m * w].reshape(m, w, 3)
        s_th = dth.sum(axis=1)
        rates.append(s_th / (w * h))
        forces.append(dv.sum(axis=1) / (w * h))
        # rms deviation of the increments from the window's mean, as mean square less squared mean (no temporary of the samples' size)
        ms = np.einsum("mwi,mwi->m", dth, dth) / w - np.einsum("mi,mi->m", s_th, s_th) / (w * w)
        spread.append(np.sqrt(np.maximum(ms, 0.0)) / h)
        h_all.append(np.full(m, h))
        ids.append(np.full(m, len(ids)))
    if not rates:
        return None
    return np.concatenate(rates), np.concatenate(forces), np.concatenate(spread), np.concatenate(h_all), np.concatenate(ids)


_MOVING = 1.0  # GNSS speed above which the log is a drive, not a block at rest or rocking [m/s]


def _gnss_speed(gnss) -> float:
    """Largest horizontal GNSS speed of the log [m/s] (0 without GNSS velocity)."""
    if gnss is None or gnss.velocity is None or not np.size(gnss.velocity):
        return 0.0
    v = np.asarray(gnss.velocity, dtype=float)
    return float(np.max(np.hypot(v[:, 0], v[:, 1])))


def _near(x, target, tol=0.2) -> bool:
    return target > 0 and abs(x / target - 1.0) < tol


def check_log(segments, inventory, *, latitude: float | None = None) -> LogChecks:
    """Run the plausibility checks on a log's segments.

    Parameters
    ----------
    segments : sequence of ImuLog
        The gap-free segments (increments, body axes).
    inventory : Inventory
        What the reader found (format, timing, GNSS, metadata).
    latitude : float, optional, keyword-only
        The latitude the analysis will use [rad] (checked against the log's own).

    Returns
    -------
    LogChecks

    References
    ----------
    Savage, P. G. (2000), *Strapdown Analytics*, §7 (the rotation of the specific force in body
    axes, ``ḟ_b = −ω × f_b`` at rest in translation); Groves, P. D. (2013), *Principles of GNSS,
    Inertial, and Multisensor Integrated Navigation Systems*, §2.4.4 (Earth rate, Ω = 7.292115e-5 rad/s).
    """
    out = []
    timing = inventory.timing
    h = timing.interval
    own_time = inventory.format in ("npz", "csv", "euroc")
    g0 = float(normal_gravity(latitude if latitude is not None else math.radians(45.0)))
    win = _windows(segments)
    if win is None:
        longest = max((s.n_samples * s.dt for s in segments), default=0.0)
        out.append(
            Check("time base", "fail", f"{len(segments)} segment(s), the longest {longest:.3g} s", f"no gap-free stretch lasts one {_WINDOW:g} s window: nothing to check or analyse")
        )
        return LogChecks(tuple(out))
    rate, force, spread, hw, seg_id = win
    fmag = np.linalg.norm(force, axis=1)
    f_med = float(np.median(fmag))
    ratio = f_med / g0

    # time base
    tb = None
    if h >= 1.0:
        tb = Check("time base", "fail" if own_time else "warn", f"{h:.6g} s between samples ({1 / h:.3g} Hz)", "not an IMU's sample rate: is the time column in milliseconds?")
    elif inventory.held == "increments" and _near(ratio, 1e-3, 0.3):
        tb = Check("time base", "fail", f"specific force {f_med:.4g} m/s² = g/{1 / ratio:.4g}", "the increments give g/1000: the time column is in milliseconds, not seconds")
    elif timing.integration_interval is not None and not 0.8 < timing.integration_interval / h < 1.25:
        r = timing.integration_interval / h
        tb = Check(
            "time base", "fail" if r < 0.5 else "warn", f"integration interval {timing.integration_interval:.6g} s, {h:.6g} s between samples",
            f"the increments cover {r:.2g} of the time between samples: the stream is logged below its integration rate and increments are missing",
        )  # fmt: skip
    elif timing.jitter_rms > 0.05 * h:
        tb = Check("time base", "warn", f"jitter {timing.jitter_rms * 1e6:.4g} µs rms, {h * 1e6:.4g} µs interval", "the sample times jitter by more than 5 % of the interval")
    else:
        tb = Check("time base", "pass", f"{1 / h:.6g} Hz, jitter {timing.jitter_rms * 1e6:.3g} µs rms", "a regular IMU time base")
    out.append(tb)

    # increments or rates (the accelerometers)
    if inventory.held == "increments" and _near(ratio * h, 1.0, 0.25) and h < 0.5:
        msg = "they average g per sample: the increment columns hold rates (specific force [m/s²]), not increments"
        out.append(Check("increments or rates", "fail", f"velocity increments of {f_med * h:.4g} m/s per {h:.4g} s sample", msg))
    elif inventory.held == "rates" and _near(ratio / h, 1.0, 0.25) and h < 0.5:
        out.append(Check("increments or rates", "fail", f"specific force {f_med:.4g} m/s²", f"it averages g × {h:.4g} s: the rate columns hold increments, not rates"))
    else:
        out.append(Check("increments or rates", "pass", f"|f| = {f_med:.5g} m/s²", f"the samples read as {inventory.held}"))
    bad_units = any(c.status == "fail" for c in out)

    # gravity magnitude
    if bad_units:
        out.append(Check("gravity magnitude", "skip", f"{f_med:.5g} m/s²", "not checked: the time base or the columns are wrong"))
    elif abs(ratio - 1.0) > 0.10:
        hint = " (an accelerometer in g, not m/s²?)" if _near(ratio, 1 / 9.80665, 0.1) else ""
        out.append(Check("gravity magnitude", "fail", f"{f_med:.5g} m/s² against g = {g0:.5g}", f"the specific force is not gravity{hint}"))
    elif abs(ratio - 1.0) > 0.02:
        out.append(Check("gravity magnitude", "warn", f"{f_med:.5g} m/s² against g = {g0:.5g}", "more than 2 % from gravity: accelerometer scale or bias, or a log mostly in manoeuvre"))
    else:
        out.append(Check("gravity magnitude", "pass", f"{f_med:.5g} m/s²", f"gravity within {abs(ratio - 1) * 100:.2g} %"))

    # gravity direction
    with np.errstate(invalid="ignore", divide="ignore"):
        fz = float(np.median(force[:, 2] / np.where(fmag > 0, fmag, np.nan)))
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, -fz)))) if math.isfinite(fz) else float("nan")
    if not math.isfinite(fz):
        out.append(Check("gravity direction", "skip", "no specific force", "not checked"))
    elif fz > 0.8:
        out.append(Check("gravity direction", "fail", f"f_z/|f| = {fz:+.3f}", "gravity reads +g on z: the log's z axis points up (FLU, ENU); the package's body axes are x forward, y right, z down"))
    elif fz > -0.5:
        out.append(Check("gravity direction", "warn", f"z {tilt:.3g}° from the vertical", "the body z axis is far from down: a log mounted otherwise, or in manoeuvre"))
    else:
        out.append(Check("gravity direction", "pass", f"z {tilt:.3g}° from the vertical", "z points down"))

    # gyro scale against the accelerometers' view of gravity turning in the body axes
    turn = rate * (hw * np.maximum(1, np.round(_WINDOW / hw)))[:, None]  # the angle each window turns through [rad]
    same = seg_id[1:] == seg_id[:-1]
    dth = (0.5 * (turn[1:] + turn[:-1]))[same]  # from one window's centre to the next one's
    pred = -np.cross(dth, (0.5 * (force[1:] + force[:-1]))[same])
    df = np.diff(force, axis=0)[same]
    den = float(np.sum(pred * pred))
    # a turn about gravity does not move it in the body axes: only the part across it can be compared
    across = np.cross(dth, (0.5 * (force[1:] + force[:-1]))[same]) / max(float(np.median(fmag)), 1e-12) if dth.size else dth
    moved = math.degrees(float(np.sqrt(np.mean(np.sum(across * across, axis=1))))) if dth.size else 0.0
    speed = _gnss_speed(inventory.gnss)
    if speed > _MOVING:
        out.append(Check("gyro scale", "skip", f"GNSS speed up to {speed:.3g} m/s", "a drive: its accelerations change the specific force as much as its turns, the two cannot be compared"))
    elif den > 0 and moved > 0.5 and dth.shape[0] >= 5:
        k = float(np.sum(df * pred) / den)
        if 0.7 < k < 1.4:
            out.append(Check("gyro scale", "pass", f"k = {k:.3g}", "the gyros' turns match gravity turning in the accelerometers"))
        elif _near(k, math.pi / 180.0, 0.3):
            out.append(Check("gyro scale", "fail", f"k = {k:.4g} = π/180 × {k * 180 / math.pi:.3g}", "the gyros turn 57.3 times what the accelerometers see: angles in degrees, not radians"))
        elif _near(k, hw[0], 0.3):
            out.append(Check("gyro scale", "fail", f"k = {k:.4g} ≈ the interval {hw[0]:.4g} s", "the gyro columns hold rates where increments were expected"))
        elif _near(k, 1.0 / hw[0], 0.3):
            out.append(Check("gyro scale", "fail", f"k = {k:.4g} ≈ 1/interval", "the gyro columns hold increments where rates were expected"))
        elif 0.5 < k < 2.0:
            out.append(Check("gyro scale", "warn", f"k = {k:.3g}", "the gyros' turns and the accelerometers' disagree by more than 30 % (manoeuvres, or a scale error)"))
        else:
            out.append(Check("gyro scale", "fail", f"k = {k:.3g}", "the gyros' turns and gravity's turn in the accelerometers disagree (units, sign or axes of the gyros)"))
    else:
        out.append(
            Check(
                "gyro scale", "skip", f"{moved:.2g}° rms turn about the horizontal between windows",
                "the body hardly tilts (a turn about gravity leaves the accelerometers unchanged): the gyros' units cannot be compared with them",
            )  # fmt: skip
        )

    # Earth rate at rest
    rest = (np.abs(fmag / g0 - 1.0) < 0.02) & (np.linalg.norm(rate, axis=1) < math.radians(0.5)) & (spread < math.radians(5.0))
    phi_gyro = None
    if np.count_nonzero(rest) * _WINDOW >= 10.0 and not bad_units:
        w_rest = rate[rest].mean(axis=0)
        f_rest = force[rest].mean(axis=0)
        s = float(np.linalg.norm(w_rest) / EARTH_RATE)
        up = f_rest / np.linalg.norm(f_rest)
        sin_phi = float(np.dot(w_rest, up) / np.linalg.norm(w_rest)) if s > 0 else 0.0
        if 0.7 < s < 1.3:
            phi_gyro = math.asin(max(-1.0, min(1.0, sin_phi)))
            out.append(Check("Earth rate", "pass", f"|ω| = {s:.3g} Ω at rest, latitude {math.degrees(phi_gyro):+.3g}°", "the gyros see the Earth's rate"))
        elif _near(s, 180.0 / math.pi, 0.15) and latitude is not None and abs(sin_phi - math.sin(latitude)) < 0.1:
            out.append(Check("Earth rate", "fail", f"|ω| = {s:.4g} Ω at rest, along the Earth's axis", "the gyros read the Earth's rate × 57.3: angles in degrees, not radians"))
        else:
            out.append(Check("Earth rate", "skip", f"|ω| = {s:.3g} Ω at rest ({math.degrees(np.linalg.norm(w_rest)) * 3600:.3g} °/h)", "the gyro's bias hides the Earth's rate: not checked"))
    else:
        out.append(Check("Earth rate", "skip", f"{np.count_nonzero(rest) * _WINDOW:.3g} s at rest", "less than 10 s at rest: not checked"))

    # gaps
    gaps = timing.gaps
    longest = max((g.duration for g in gaps), default=0.0)
    if longest > GAP_LIMIT:
        g = max(gaps, key=lambda g: g.duration)
        out.append(Check("gaps", "fail", f"{g.duration:.4g} s at t = {g.start:.4g} s", f"the samples stop for more than {GAP_LIMIT:g} s: pick a stretch without it (segment)"))
    elif gaps or timing.logger_dropouts > 0:
        lost = f", the logger reports {timing.logger_dropouts * 1e3:.4g} ms dropped" if timing.logger_dropouts > 0 else ""
        out.append(Check("gaps", "warn", f"{len(gaps)} gap(s), {timing.missing} samples missing, longest {longest:.3g} s{lost}", f"the log splits into {len(segments)} segments"))
    else:
        out.append(Check("gaps", "pass", "no gap", "one segment"))

    # latitude
    own = []
    if inventory.gnss is not None:
        own.append(("its GNSS fixes", inventory.gnss.mean_latitude, 0.5))
    if "latitude" in inventory.metadata:
        own.append(("its metadata", float(inventory.metadata["latitude"]), 0.5))
    if latitude is None:
        seen = ", ".join(f"{math.degrees(v):+.5g}° from {w}" for w, v, _ in own) or "none in the log"
        out.append(Check("latitude", "skip", seen, "no latitude given to compare"))
    elif own:
        w, v, tol = own[0]
        d = math.degrees(abs(latitude - v))
        status = "fail" if d > tol else ("warn" if d > 0.05 else "pass")
        out.append(Check("latitude", status, f"given {math.degrees(latitude):+.5g}°, {w} {math.degrees(v):+.5g}°", f"{d:.3g}° apart"))
    elif phi_gyro is not None:
        d = math.degrees(abs(latitude - phi_gyro))
        seen = f"given {math.degrees(latitude):+.5g}°, the gyros {math.degrees(phi_gyro):+.4g}°"
        out.append(Check("latitude", "warn" if d > 10.0 else "pass", seen, f"{d:.3g}° apart (the gyros' bias limits this)"))
    else:
        out.append(Check("latitude", "skip", f"given {math.degrees(latitude):+.5g}°", "the log holds no position to compare"))
    return LogChecks(tuple(out))
