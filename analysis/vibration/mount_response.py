"""The IMU's vibration through its mount: cross-spectra, the environment they make, and the drift per mode.

:func:`output_density` is the cross-spectral density of the IMU's six
channels (body rate, specific force) under a base excitation, exactly at any
frequency: with the transfer matrix H of
:meth:`strapdown.analysis.vibration.mount.Mount.transfer`,

    ``G_out(f) = conj(H) G_in Hᵀ``

in the package's convention ``G_ab = ½ conj(Z_a) Z_b`` (Bendat & Piersol's
``S_out = H S_in Hᴴ`` written for ``S_ab ∝ Z_a conj(Z_b)``).

:func:`mount_environment` tabulates it as an
:class:`~strapdown.analysis.vibration.environment.Environment` whose spectra
any function of the vibration domain takes as they are
(:func:`strapdown.analysis.vibration.drift.environment_drift` among them).  A
spectrum table is interpolated log–log in the auto-spectra and linearly in
log f in the coherences (:class:`~strapdown.analysis.vibration.environment.Spectrum`),
so the table is refined until that interpolation reproduces the exact
density: starting from the profiles' breakpoints, a logarithmic grid and
each mode's natural and half-power frequencies, every interval whose
geometric midpoint the interpolation misses by more than ``tolerance`` is
halved.  The error of a midpoint is ``max_ab |ΔG_ab| / √((G_aa + ε_a)(G_bb + ε_b))``,
an error of coherence (relative, for an auto-spectrum), with ``ε_a`` a
millionth of the channel's peak so that negligible levels do not drive the
refinement.  Where a profile starts or ends inside the band the density
jumps; the table is then split there into several spectra, so that no
interpolation crosses a jump.

:func:`mount_drift` gives the mean coning drift and sculling rectification of
several algorithms at once (one quadrature for them all), in total and per
mode band: the band of a mode reaches from the geometric mean of its natural
frequency and the one below to that with the one above (modes closer than
:data:`MODE_MERGE` are one band).  A band's share is that of its part of the
spectrum; the modes overlap, so it is an attribution, not a decomposition of
the physics.

Public API
----------
.. autosummary::

   output_density
   MountResponse
   mount_environment
   restrict
   ModeBand
   MountDrift
   mount_drift
   environment_toml
   TABLE_TOLERANCE
   MAX_TABLE_POINTS
   MODE_MERGE

References
----------
Bendat & Piersol (2010), *Random Data*, 4th ed., eq. (6.11); Harris & Piersol
(2002), *Shock and Vibration Handbook*, ch. 3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import trapezoid

from ...derivations.coning.algorithms import Algorithm
from ..coning.drift_theory import coning_drift_function
from ..core import budget
from ..core.validation import as_int, in_open_interval, positive
from .drift import response_integrals
from .environment import CHANNELS, Environment, Spectrum
from .mount import Mount
from .profile import BaseExcitation
from .sensor_dynamics import Sensor

__all__ = [
    "output_density",
    "MountResponse",
    "mount_environment",
    "restrict",
    "ModeBand",
    "MountDrift",
    "mount_drift",
    "environment_toml",
    "TABLE_TOLERANCE",
    "MAX_TABLE_POINTS",
    "MODE_MERGE",
]

#: Default largest interpolation error of the table (module docstring) [dimensionless].
TABLE_TOLERANCE = 1e-3
#: Default largest number of table frequencies [count].
MAX_TABLE_POINTS = 4000
#: Modes whose natural frequencies differ by less than this fraction share one band [dimensionless].
MODE_MERGE = 0.02
#: Logarithmic grid of the first table, per decade [count].
_PER_DECADE = 24
#: A refinement pass evaluates the density at most at this many frequencies at once (memory of a pass, 6×6 complex each).
_CHUNK = 20000
#: Time of one table frequency (transfer matrix, density, interpolation check) [s], measured and rounded up.
_SECONDS_PER_POINT = 5e-5


def output_density(mount: Mount, excitation: BaseExcitation, freq) -> np.ndarray:
    """``G_out(f) = conj(H) G_in Hᵀ``: the IMU's cross-spectral density, shape ``freq.shape + (6, 6)``.

    Parameters
    ----------
    mount : Mount
        The mount.
    excitation : BaseExcitation
        The base's profiles.
    freq : array_like
        Frequencies [Hz], > 0.

    Returns
    -------
    ndarray of complex
        One-sided density of ``(ωx, ωy, ωz, fx, fy, fz)`` [(rad/s)²/Hz,
        (rad/s)(m/s²)/Hz, (m/s²)²/Hz], Hermitian.

    Raises
    ------
    TypeError
        If ``mount`` or ``excitation`` has the wrong type.

    References
    ----------
    Bendat & Piersol (2010), eq. (6.11).
    """
    if not isinstance(mount, Mount):
        raise TypeError(f"Expected `mount` to be a Mount, got {type(mount).__name__}")
    if not isinstance(excitation, BaseExcitation):
        raise TypeError(f"Expected `excitation` to be a BaseExcitation, got {type(excitation).__name__}")
    f = np.asarray(freq, dtype=float)
    h = mount.transfer(f)
    g = np.conj(h) @ excitation.at(f) @ np.swapaxes(h, -1, -2)
    return 0.5 * (g + np.conj(np.swapaxes(g, -1, -2)))


def _pieces(excitation: BaseExcitation) -> list:
    """Intervals of the band where the set of nonzero channels is constant, each with the excitation of its channels only.

    A profile is nonzero at its band's ends; the excitation of a piece keeps
    only the profiles that cover the whole piece, so that its density has no
    jump at the piece's ends.
    """
    edges = excitation.edges
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        mid = math.sqrt(lo * hi)
        keep = [p if p is not None and p.band[0] <= mid <= p.band[1] else None for p in excitation.profiles]
        if any(p is not None for p in keep):
            out.append((float(lo), float(hi), BaseExcitation(tuple(keep[:3]), tuple(keep[3:]), excitation.name, excitation.description)))
    return out


def _midpoint_error(spectrum: Spectrum, exact_mid: np.ndarray, mid: np.ndarray, floor: np.ndarray) -> np.ndarray:
    """Interpolation error of each interval at its geometric midpoint (module docstring)."""
    approx = spectrum.at(mid)
    auto = np.real(np.diagonal(exact_mid, axis1=-2, axis2=-1)) + floor
    scale = np.sqrt(auto[:, :, None] * auto[:, None, :])
    return np.max(np.abs(approx - exact_mid) / scale, axis=(1, 2))


def _table(mount, excitation, lo, hi, modes, tolerance, max_points):
    """Refined table of one piece: frequencies, densities, the largest midpoint error, points left."""
    inside = lambda x: x[(x > lo * (1 + 1e-9)) & (x < hi * (1 - 1e-9))]  # noqa: E731 - the ends are added exactly
    start = [np.geomspace(lo, hi, max(2, int(math.ceil(_PER_DECADE * math.log10(hi / lo))) + 1)), inside(excitation.breakpoints)]
    for md in modes:
        z = min(md.damping_ratio, 0.5)
        start.append(inside(np.array([md.frequency * (1 - z), md.frequency, md.frequency * (1 + z)])))
    f = np.unique(np.concatenate([inside(x) for x in start] + [[lo, hi]]))
    f = f[np.concatenate([[True], np.diff(f) > 1e-9 * f[1:]])]  # no two frequencies that round to one logarithm
    g = output_density(mount, excitation, f)
    peak = np.max(np.real(np.diagonal(g, axis1=-2, axis2=-1)), axis=0)
    floor = 1e-6 * np.where(peak > 0, peak, 1.0)
    worst = math.inf
    while True:
        mid = np.sqrt(f[1:] * f[:-1])
        gm = output_density(mount, excitation, mid)
        err = _midpoint_error(Spectrum(f, g), gm, mid, floor)
        worst = float(np.max(err))
        bad = err > tolerance
        if not np.any(bad) or f.size + int(np.count_nonzero(bad)) > max_points:
            return f, g, worst
        f = np.concatenate([f, mid[bad]])
        g = np.concatenate([g, gm[bad]])
        order = np.argsort(f)
        f, g = f[order], g[order]


@dataclass(frozen=True, eq=False)
class MountResponse:
    """The IMU's vibration through a mount, tabulated as an environment.

    Attributes
    ----------
    mount : Mount
    excitation : BaseExcitation
    environment : Environment
        One spectrum per piece of the band (module docstring; usually one),
        with the sensors given to :func:`mount_environment`.
    modes : tuple of Mode
        The mount's modes.
    table_error : float
        Largest interpolation error left at a midpoint of the table (module docstring) [dimensionless].
    tolerance : float
        The tolerance asked for [dimensionless].
    """

    mount: Mount
    excitation: BaseExcitation
    environment: Environment
    modes: tuple
    table_error: float
    tolerance: float

    @property
    def points(self) -> int:
        """Table frequencies of all the spectra [count]."""
        return sum(s.frequency.size for s in self.environment.spectra)

    @property
    def converged(self) -> bool:
        """Whether the table reached the tolerance within the allowed points."""
        return self.table_error <= self.tolerance

    def output_rms(self) -> np.ndarray:
        """Root mean square of the IMU's six channels from the table (trapezoids in log f on the interpolated density, 64 per interval), shape (6,)."""
        total = np.zeros(6)
        for s in self.environment.spectra:
            u = np.log(s.frequency)
            fine = np.exp(np.concatenate([np.linspace(a, b, 65)[:-1] for a, b in zip(u[:-1], u[1:])] + [u[-1:]]))
            auto = np.real(np.diagonal(s.at(fine), axis1=-2, axis2=-1))
            total += trapezoid(auto * fine[:, None], np.log(fine), axis=0)
        return np.sqrt(total)


def mount_environment(mount: Mount, excitation: BaseExcitation, *, gyro: Sensor | None = None, accelerometer: Sensor | None = None, tolerance: float = TABLE_TOLERANCE,
                      max_points: int = MAX_TABLE_POINTS, name: str | None = None, limits: budget.Limits | None = None) -> MountResponse:  # fmt: skip
    """Tabulate the IMU's cross-spectra through ``mount`` as an environment (module docstring).

    Parameters
    ----------
    mount : Mount
        The mount.
    excitation : BaseExcitation
        The base's profiles.
    gyro, accelerometer : Sensor, keyword-only, optional
        The IMU's sensors (default ideal; one decimation for both).
    tolerance : float, keyword-only
        Largest interpolation error of the table, in (0, 0.5) [dimensionless].
    max_points : int, keyword-only
        Most table frequencies of all the pieces [count], ≥ 8.
    name : str, keyword-only, optional
        Name of the environment (default: the excitation's and the mount's).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a table
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`
        (naming ``max_points``).

    Returns
    -------
    MountResponse
        Check :attr:`MountResponse.converged`: a table stopped by
        ``max_points`` keeps a larger interpolation error.

    Raises
    ------
    TypeError
        A mount, excitation or sensor of the wrong type.
    ValueError
        A tolerance or point count out of range, or a table beyond ``limits``.

    Examples
    --------
    >>> from strapdown.analysis.vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT
    >>> from strapdown.analysis.vibration.mount import load_mount
    >>> from strapdown.analysis.vibration.profile import load_profile
    >>> r = mount_environment(load_mount(ISOLATED_MOUNT), load_profile(AIRFRAME_PROFILE))
    >>> r.converged, len(r.environment.spectra)
    (True, 1)
    """
    if not isinstance(mount, Mount):
        raise TypeError(f"Expected `mount` to be a Mount, got {type(mount).__name__}")
    if not isinstance(excitation, BaseExcitation):
        raise TypeError(f"Expected `excitation` to be a BaseExcitation, got {type(excitation).__name__}")
    tolerance = in_open_interval(tolerance, "tolerance", 0.0, 0.5)
    max_points = as_int(max_points, "max_points", minimum=8)
    what = f"`max_points` = {max_points:.3g} table frequencies"
    budget.check(budget.Estimate(max_points * _SECONDS_PER_POINT * 4, 8 * 16 * 36.0 * min(max_points, _CHUNK) + 16 * 36.0 * max_points, what), limits)
    if gyro is None:
        gyro = Sensor(decimation=1 if accelerometer is None else accelerometer.decimation)
    if accelerometer is None:
        accelerometer = Sensor(decimation=gyro.decimation)
    modes = mount.modes()
    pieces = _pieces(excitation)
    spans = np.array([math.log(hi / lo) for lo, hi, _ in pieces])
    share = np.maximum(8, np.floor(max_points * spans / spans.sum())).astype(int)
    spectra, worst = [], 0.0
    for (lo, hi, part), n in zip(pieces, share):
        f, g, err = _table(mount, part, lo, hi, modes, tolerance, int(n))
        worst = max(worst, err)
        label = "IMU through the mount" if len(pieces) == 1 else f"IMU through the mount, {lo:g}–{hi:g} Hz"
        spectra.append(Spectrum(f, g, label))
    env = Environment((), tuple(spectra), gyro, accelerometer, name or f"{excitation.name} through {mount.name}",
                      f"{excitation.name} at the base of {mount.name}; IMU cross-spectra from the mount's transfer matrix")  # fmt: skip
    return MountResponse(mount, excitation, env, modes, worst, tolerance)


def restrict(spectrum: Spectrum, low: float, high: float) -> Spectrum | None:
    """The part of ``spectrum`` between ``low`` and ``high`` [Hz], exact (None if they do not overlap).

    The table keeps its frequencies inside the interval and gains the
    interpolated values at the ends; the interpolation is piecewise linear
    in the coordinates it uses, so the restricted spectrum equals the
    original inside the interval.

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum.
    low, high : float
        Ends of the interval [Hz], low < high.

    Returns
    -------
    Spectrum or None
    """
    lo, hi = max(low, spectrum.band[0]), min(high, spectrum.band[1])
    if not lo < hi:
        return None
    f = spectrum.frequency
    keep = (f > lo) & (f < hi)
    freq = np.concatenate([[lo], f[keep], [hi]])
    dens = np.concatenate([spectrum.at([lo]), spectrum.density[keep], spectrum.at([hi])])
    return Spectrum(freq, dens, spectrum.label)


@dataclass(frozen=True)
class ModeBand:
    """A band of the spectrum around one mode (or a group of close modes).

    Attributes
    ----------
    low, high : float
        Ends of the band [Hz].
    modes : tuple of int
        Indices of its modes in :attr:`MountResponse.modes`.
    """

    low: float
    high: float
    modes: tuple


def _bands(response: MountResponse) -> list:
    lo = min(s.band[0] for s in response.environment.spectra)
    hi = max(s.band[1] for s in response.environment.spectra)
    groups: list = []
    for i, md in enumerate(response.modes):
        if groups and md.frequency <= response.modes[groups[-1][-1]].frequency * (1 + MODE_MERGE):
            groups[-1].append(i)
        else:
            groups.append([i])
    centre = [math.sqrt(response.modes[g[0]].frequency * response.modes[g[-1]].frequency) for g in groups]
    cuts = [math.sqrt(a * b) for a, b in zip(centre[:-1], centre[1:])]
    edges = [min(lo, cuts[0] if cuts else lo)] + cuts + [max(hi, cuts[-1] if cuts else hi)]
    return [ModeBand(float(a), float(b), tuple(g)) for a, b, g in zip(edges[:-1], edges[1:], groups)]


@dataclass(frozen=True, eq=False)
class MountDrift:
    """Mean coning drift and sculling rectification of several algorithms through a mount, in total and per mode band.

    Vectors are in the body axes; drift is exact minus algorithm (package
    convention); the sensor part is the same for every algorithm.

    Attributes
    ----------
    algorithms : tuple of Algorithm
    sample_interval : float
        h [s].
    bands : tuple of ModeBand
    true_coning : ndarray (B, 3)
        Mean non-commutativity rate of the true motion per band [rad/s].
    sensor : ndarray (B, 3)
        Pseudo-coning per band [rad/s].
    algorithm : ndarray (A, B, 3)
        Each algorithm's own residual per band [rad/s].
    true_rectification : ndarray (B, 3)
        Rectified specific force of the true motion per band [m/s²].
    sensor_sculling : ndarray (B, 3)
        Pseudo-sculling per band [m/s²].
    algorithm_sculling : ndarray (A, B, 3)
        Each velocity algorithm's residual per band [m/s²].
    """

    algorithms: tuple
    sample_interval: float
    bands: tuple
    true_coning: np.ndarray
    sensor: np.ndarray
    algorithm: np.ndarray
    true_rectification: np.ndarray
    sensor_sculling: np.ndarray
    algorithm_sculling: np.ndarray

    @property
    def coning(self) -> np.ndarray:
        """Coning drift vector per algorithm and band, sensor plus algorithm, shape (A, B, 3) [rad/s]."""
        return self.sensor[None] + self.algorithm

    @property
    def sculling(self) -> np.ndarray:
        """Rectification error vector per algorithm and band, shape (A, B, 3) [m/s²]."""
        return self.sensor_sculling[None] + self.algorithm_sculling

    @property
    def total_coning(self) -> np.ndarray:
        """Coning drift vector per algorithm, all bands, shape (A, 3) [rad/s]."""
        return self.coning.sum(axis=1)

    @property
    def total_sculling(self) -> np.ndarray:
        """Rectification error vector per algorithm, all bands, shape (A, 3) [m/s²]."""
        return self.sculling.sum(axis=1)


def mount_drift(algorithms, response: MountResponse, sample_interval: float) -> MountDrift:
    """Mean coning drift and sculling rectification of ``algorithms`` through the mount, per mode band (module docstring).

    One quadrature serves all the algorithms
    (:func:`strapdown.analysis.vibration.drift.response_integrals` with their
    closed-form drift functions D(ωh)); the totals equal
    :func:`strapdown.analysis.vibration.drift.environment_drift` of each
    algorithm on ``response.environment``.

    Parameters
    ----------
    algorithms : sequence of Algorithm
        The algorithms (their dual extensions are the velocity algorithms).
    response : MountResponse
        The tabulated response (:func:`mount_environment`).
    sample_interval : float
        Algorithm sample interval h [s], > 0.

    Returns
    -------
    MountDrift

    Raises
    ------
    TypeError
        An entry that is not an Algorithm, or a response of the wrong type.
    ValueError
        No algorithm, or a bad sample interval.

    References
    ----------
    Lebedev & Panov (1989), eq. (2.5); Savage (1998).
    """
    algorithms = tuple(algorithms)
    if not algorithms:
        raise ValueError("Expected at least one algorithm in `algorithms`, got none")
    for a in algorithms:
        if not isinstance(a, Algorithm):
            raise TypeError(f"Expected `algorithms` to hold Algorithm, got {type(a).__name__}")
    if not isinstance(response, MountResponse):
        raise TypeError(f"Expected `response` to be a MountResponse, got {type(response).__name__}")
    h = positive(sample_interval, "sample_interval")
    bands = _bands(response)
    spectra, owner = [], []
    for b, band in enumerate(bands):
        for s in response.environment.spectra:
            part = restrict(s, band.low, band.high)
            if part is not None:
                spectra.append(part)
                owner.append(b)
    env = Environment((), tuple(spectra), response.environment.gyro, response.environment.accelerometer, response.environment.name)
    r = response_integrals(env, h, [coning_drift_function(a) for a in algorithms])
    nb = len(bands)
    true, sensed = np.zeros((nb, 2, 3)), np.zeros((nb, 2, 3))
    alg = np.zeros((len(algorithms), nb, 2, 3))
    for i, b in enumerate(owner):
        true[b] += r.true[i]
        sensed[b] += r.sensed[i]
        alg[:, b] += r.algorithm[:, i]
    return MountDrift(algorithms, h, tuple(bands), true[:, 0], true[:, 0] - sensed[:, 0], alg[:, :, 0], true[:, 1], true[:, 1] - sensed[:, 1], alg[:, :, 1])


def environment_toml(environment: Environment, *, sensors: str = "") -> str:
    """The spectra of ``environment`` as the text of an environment file (``docs/environment-files.md``).

    Numbers are written with ``repr`` (they read back exactly); a cross
    spectrum that is zero at every frequency is left out.  Lines are not
    written (a mount environment has none).

    Parameters
    ----------
    environment : Environment
        Its name, description and spectra are written.
    sensors : str, keyword-only
        TOML text of the ``[gyro]``, ``[accelerometer]`` and ``[sampling]``
        tables to append (default: none, ideal sensors).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        An environment with lines (not written by this function).
    """
    if environment.lines:
        raise ValueError("Expected an environment without lines (environment_toml writes spectra only)")

    def q(text: str) -> str:
        return '"' + text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'

    def row(values) -> str:
        return "[" + ", ".join(repr(float(v)) for v in values) + "]"

    out = [f"name = {q(environment.name)}", f"description = {q(environment.description)}", ""]
    for s in environment.spectra:
        out += ["[[spectrum]]", f"label = {q(s.label)}", f"freq_hz = {row(s.frequency)}"]
        for i, c in enumerate(CHANNELS):
            out.append(f"{c} = {row(np.real(s.density[:, i, i]))}")
        for i, a in enumerate(CHANNELS):
            for j in range(i + 1, 6):
                v = s.density[:, i, j]
                if np.any(v != 0):
                    out.append(f"{a}_{CHANNELS[j]} = [" + ", ".join(f"[{float(z.real)!r}, {float(z.imag)!r}]" for z in v) + "]")
        out.append("")
    if sensors:
        out.append(sensors.rstrip() + "\n")
    return "\n".join(out)
