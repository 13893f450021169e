"""Linear random-vibration profiles: breakpoint tables with dB/octave slopes, and the base excitation they make.

A random-vibration specification (MIL-STD-810 Method 514, RTCA DO-160
Section 8 and their like) gives the acceleration spectral density of the
structure an equipment is mounted on as a table of breakpoints: a level at
some frequencies, and between them straight lines on log–log axes, stated as
slopes in dB per octave.  A :class:`Profile` holds such a table with every
level resolved; between breakpoints its density is the power law

    ``G(f) = G_j (f / f_j)^k_j``,  ``k_j = s_j / (10 log₁₀ 2)``,

exactly, with s_j the slope of the segment in dB/octave
(``10 log₁₀(G_{j+1}/G_j) = s_j log₂(f_{j+1}/f_j)``), and zero outside the
first and last breakpoints.  Its mean square is the exact integral of the
power laws (:meth:`Profile.mean_square`), the grms of the specification when
the profile is in g²/Hz.

A :class:`BaseExcitation` gathers the profiles of the three linear axes and,
if given, of the three angular axes of the base (the structure the IMU mount
stands on), in the six channels of :mod:`strapdown.analysis.vibration.environment`:
base angular rate ``(Ωx, Ωy, Ωz)`` [rad/s] and base acceleration
``(Ax, Ay, Az)`` [m/s²], one-sided densities in the convention of that
module.  A specification states no phase between axes, so the axes are
uncorrelated: the excitation's cross-spectral density matrix is diagonal.

Levels resolve from the table as a designer writes it: a breakpoint may give
its level, the slope of the segment that ends at it, or both; each level
follows from a neighbour's along a segment with a slope, in both directions.
Where two given levels and a slope meet on one segment, the levels define
the segment and the slope must agree with them within
:data:`SLOPE_TOLERANCE_DB` (a printed table rounds its levels); a larger
difference is refused as a typing error.

The package ships an illustrative profile file (:data:`strapdown.analysis.vibration.examples.AIRFRAME_PROFILE`);
its numbers are an example of the format, not a standard's.

Public API
----------
.. autosummary::

   Profile
   profile_from_breakpoints
   BaseExcitation
   load_profile
   SLOPE_TOLERANCE_DB
   DB_PER_OCTAVE
   PROFILE_LIMITS
   ProfileLimits

References
----------
MIL-STD-810H (2019), Method 514.8, random vibration test profiles; RTCA
DO-160G (2010), Section 8, random vibration test curves; Bendat & Piersol
(2010), *Random Data*, 4th ed., section 5.2 (one-sided spectral densities).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...derivations.toml_files import read_toml
from ..core.units import DEG, STANDARD_GRAVITY
from ..core.validation import as_array
from ._file_tables import Table, show

__all__ = ["Profile", "profile_from_breakpoints", "BaseExcitation", "load_profile", "SLOPE_TOLERANCE_DB", "ProfileLimits", "PROFILE_LIMITS", "DB_PER_OCTAVE"]

#: dB per octave of a unit power-law exponent, ``10 log₁₀ 2`` (≈ 3.0103): G ∝ f^k rises k·3.0103 dB per octave.
DB_PER_OCTAVE = 10.0 * math.log10(2.0)
#: Largest difference between a slope and the two levels of its segment [dB] before the table is refused.
SLOPE_TOLERANCE_DB = 0.5
#: What each kind of profile measures: the SI unit of the channel and the unit names a file may use.
_KINDS = {"linear": ("m/s²", {"g": STANDARD_GRAVITY, "m/s2": 1.0}), "angular": ("rad/s", {"deg/s": DEG, "rad/s": 1.0})}


def _expm1_over(a: np.ndarray) -> np.ndarray:
    """``(e^a − 1)/a``, 1 at a = 0, without cancellation."""
    a = np.asarray(a, dtype=float)
    small = np.abs(a) < 1e-8
    safe = np.where(small, 1.0, a)
    return np.where(small, 1.0 + 0.5 * a, np.expm1(safe) / safe)


@dataclass(frozen=True, eq=False)
class Profile:
    """A spectral density given at breakpoints, a power law between them, zero outside.

    Attributes
    ----------
    frequency : ndarray, shape (K,)
        Breakpoints [Hz], positive, strictly increasing, K ≥ 2.
    level : ndarray, shape (K,)
        Density at the breakpoints [unit²/Hz] in SI units (``(m/s²)²/Hz`` for
        a linear profile, ``(rad/s)²/Hz`` for an angular one), positive.
    kind : str
        ``"linear"`` (acceleration) or ``"angular"`` (angular rate).
    label : str
        Name for listings.

    Raises
    ------
    ValueError
        Breakpoints not positive or not increasing, levels not positive and
        finite, or an unknown kind.
    """

    frequency: np.ndarray
    level: np.ndarray
    kind: str = "linear"
    label: str = ""

    def __post_init__(self):
        f = as_array(self.frequency, "frequency")
        g = as_array(self.level, "level")
        if f.ndim != 1 or f.size < 2:
            raise ValueError(f"Expected `frequency` with at least two breakpoints, got shape {f.shape}")
        if np.any(f <= 0) or np.any(np.diff(f) <= 0):
            raise ValueError(f"Expected `frequency` positive and strictly increasing, got {show(f.tolist())}")
        if g.shape != f.shape or np.any(g <= 0):
            raise ValueError(f"Expected `level` as {f.size} positive densities, got {show(g.tolist())}")
        if self.kind not in _KINDS:
            raise ValueError(f"Expected `kind` one of {', '.join(repr(k) for k in _KINDS)}, got {self.kind!r}")
        f, g = f.copy(), g.copy()
        f.setflags(write=False)
        g.setflags(write=False)
        object.__setattr__(self, "frequency", f)
        object.__setattr__(self, "level", g)

    @property
    def unit(self) -> str:
        """SI unit of the channel (``"m/s²"`` or ``"rad/s"``); the density is in unit²/Hz."""
        return _KINDS[self.kind][0]

    @property
    def band(self) -> tuple:
        """``(f_min, f_max)`` [Hz]."""
        return float(self.frequency[0]), float(self.frequency[-1])

    @property
    def exponent(self) -> np.ndarray:
        """Power-law exponent k_j of each segment, shape (K − 1,) [dimensionless]."""
        return np.log(self.level[1:] / self.level[:-1]) / np.log(self.frequency[1:] / self.frequency[:-1])

    @property
    def slope_db_per_octave(self) -> np.ndarray:
        """Slope of each segment [dB/octave], shape (K − 1,)."""
        return self.exponent * DB_PER_OCTAVE

    def at(self, freq) -> np.ndarray:
        """``G(f)``: the power law of the segment holding f, zero outside the band [unit²/Hz].

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz].

        Returns
        -------
        ndarray
            Same shape as ``freq``.
        """
        f = np.asarray(freq, dtype=float)
        table = self.frequency
        inside = (f >= table[0]) & (f <= table[-1])
        j = np.clip(np.searchsorted(table, f, side="right") - 1, 0, table.size - 2)
        safe = np.where(inside, f, table[0])
        value = self.level[j] * np.exp(self.exponent[j] * np.log(safe / table[j]))
        return np.where(inside, value, 0.0)

    def mean_square(self) -> float:
        """``∫ G(f) df`` over the band, exact: ``Σ_j G_j f_j ((f_{j+1}/f_j)^(k_j+1) − 1)/(k_j + 1)`` [unit²].

        Returns
        -------
        float
            The square of the rms (the grms² of a profile in g²/Hz, in (m/s²)² here).

        Examples
        --------
        >>> p = Profile([20.0, 2000.0], [1e-2, 1e-2])
        >>> round(p.mean_square(), 12)
        19.8
        """
        f, g = self.frequency, self.level
        span = np.log(f[1:] / f[:-1])
        a = (self.exponent + 1.0) * span
        return float(np.sum(g[:-1] * f[:-1] * span * _expm1_over(a)))

    @property
    def rms(self) -> float:
        """Root mean square of the channel [unit] (the grms times g₀ for a linear profile)."""
        return math.sqrt(self.mean_square())


def profile_from_breakpoints(freq_hz, levels, slopes_db_per_octave=None, *, kind: str = "linear", label: str = "") -> Profile:
    """A :class:`Profile` from a specification's table: levels where given, slopes between (module docstring).

    Parameters
    ----------
    freq_hz : sequence of float
        Breakpoints [Hz], positive and strictly increasing (at least two).
    levels : sequence of (float or None)
        Density at each breakpoint [unit²/Hz, SI], or None where the table
        gives a slope instead.
    slopes_db_per_octave : sequence of (float or None), optional
        Entry i is the slope of the segment that ends at breakpoint i
        [dB/octave]; entry 0 must be None (no segment ends at the first
        breakpoint).  Default: no slopes.
    kind : {"linear", "angular"}, keyword-only
        What the profile measures.
    label : str, keyword-only
        Name for listings.

    Returns
    -------
    Profile

    Raises
    ------
    ValueError
        A level that no given level and slope determine, a slope on the first
        breakpoint, a slope that disagrees with the two given levels of its
        segment by more than :data:`SLOPE_TOLERANCE_DB`, or bad numbers; the
        message names the breakpoint by its frequency.

    Examples
    --------
    A plateau with a +3 dB/octave ramp before it and a −6 dB/octave roll-off after:

    >>> p = profile_from_breakpoints([20.0, 80.0, 350.0, 2000.0], [None, 0.04, 0.04, None], [None, 3.0, None, -6.0])
    >>> [round(float(x), 5) for x in p.level]
    [0.01005, 0.04, 0.04, 0.00124]
    """
    f = as_array(freq_hz, "freq_hz")
    if f.ndim != 1 or f.size < 2 or np.any(f <= 0) or np.any(np.diff(f) <= 0):
        raise ValueError(f"Expected `freq_hz` as at least two positive, strictly increasing breakpoints, got {show(np.ravel(f).tolist())}")
    n = f.size
    lv = list(levels)
    sl = [None] * n if slopes_db_per_octave is None else list(slopes_db_per_octave)
    if len(lv) != n or len(sl) != n:
        raise ValueError(f"Expected `levels` and `slopes_db_per_octave` with one entry per breakpoint ({n}), got {len(lv)} and {len(sl)}")
    if sl[0] is not None:
        raise ValueError(f"Expected no slope at the first breakpoint ({f[0]:g} Hz): a slope belongs to the segment that ends at its breakpoint")
    for name, values in (("levels", lv), ("slopes_db_per_octave", sl)):
        for i, v in enumerate(values):
            if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not math.isfinite(float(v))):
                raise ValueError(f"Expected `{name}` entry at {f[i]:g} Hz to be a finite number or None, got {show(v)}")
    for i, v in enumerate(lv):
        if v is not None and v <= 0:
            raise ValueError(f"Expected the level at {f[i]:g} Hz to be positive, got {v:g}")
    known = [None if v is None else math.log10(float(v)) for v in lv]  # log10 of the levels
    octaves = np.log2(f[1:] / f[:-1])
    changed = True
    while changed:
        changed = False
        for j in range(1, n):
            s = sl[j]
            if s is None:
                continue
            step = float(s) / 10.0 * octaves[j - 1]  # log10 of the level ratio across the segment
            if known[j - 1] is not None and known[j] is None:
                known[j], changed = known[j - 1] + step, True
            elif known[j] is not None and known[j - 1] is None:
                known[j - 1], changed = known[j] - step, True
    missing = [f"{f[i]:g} Hz" for i, v in enumerate(known) if v is None]
    if missing:
        raise ValueError(f"Expected every level to follow from a given level and the slopes, got none for the breakpoint(s) at {', '.join(missing)}")
    for j in range(1, n):
        if sl[j] is not None and lv[j] is not None and lv[j - 1] is not None:
            implied = 10.0 * (known[j] - known[j - 1]) / octaves[j - 1]
            if abs(implied - float(sl[j])) * octaves[j - 1] > SLOPE_TOLERANCE_DB:
                raise ValueError(
                    f"Expected the slope of the segment {f[j - 1]:g}–{f[j]:g} Hz to agree with its two levels within {SLOPE_TOLERANCE_DB:g} dB, "
                    f"got {float(sl[j]):g} dB/octave against {implied:.4g} dB/octave from the levels"
                )
    return Profile(f, 10.0 ** np.array(known), kind, label)


@dataclass(frozen=True, eq=False)
class BaseExcitation:
    """Uncorrelated profiles of the base's six channels: angular rate (x, y, z) and acceleration (x, y, z).

    Attributes
    ----------
    angular : tuple of three (Profile or None)
        Base angular-rate profiles per axis [(rad/s)²/Hz] (None: no angular vibration on that axis).
    linear : tuple of three (Profile or None)
        Base acceleration profiles per axis [(m/s²)²/Hz].
    name : str
        Name for listings.
    description : str
        One line.

    Raises
    ------
    TypeError
        An entry that is neither a :class:`Profile` nor None.
    ValueError
        A profile of the wrong kind on a channel, or no profile at all.
    """

    angular: tuple = (None, None, None)
    linear: tuple = (None, None, None)
    name: str = "base excitation"
    description: str = ""

    def __post_init__(self):
        for attr, kind in (("angular", "angular"), ("linear", "linear")):
            value = tuple(getattr(self, attr))
            if len(value) != 3:
                raise ValueError(f"Expected `{attr}` as three entries (x, y, z), got {len(value)}")
            for axis, p in zip("xyz", value):
                if p is not None and not isinstance(p, Profile):
                    raise TypeError(f"Expected `{attr}` entries to be Profile or None, got {type(p).__name__} on {axis}")
                if p is not None and p.kind != kind:
                    raise ValueError(f"Expected a {kind} profile on the {attr} {axis} axis, got a {p.kind} one")
            object.__setattr__(self, attr, value)
        if not any(self.profiles):
            raise ValueError("Expected at least one profile in the base excitation, got none")

    @property
    def profiles(self) -> tuple:
        """The six channels' profiles (or None), in the order of :data:`~strapdown.analysis.vibration.environment.CHANNELS`."""
        return self.angular + self.linear

    @property
    def band(self) -> tuple:
        """Lowest and highest frequency of any profile [Hz]."""
        bands = [p.band for p in self.profiles if p is not None]
        return min(b[0] for b in bands), max(b[1] for b in bands)

    @property
    def breakpoints(self) -> np.ndarray:
        """Every breakpoint of every profile, sorted, without repeats [Hz]."""
        return np.unique(np.concatenate([p.frequency for p in self.profiles if p is not None]))

    @property
    def edges(self) -> np.ndarray:
        """The frequencies where a profile starts or ends, sorted [Hz]: the density may jump there."""
        return np.unique([x for p in self.profiles if p is not None for x in p.band])

    def at(self, freq) -> np.ndarray:
        """The diagonal cross-spectral density of the six base channels, shape ``freq.shape + (6, 6)``.

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz].

        Returns
        -------
        ndarray of complex
        """
        f = np.asarray(freq, dtype=float)
        out = np.zeros(f.shape + (6, 6), dtype=complex)
        for c, p in enumerate(self.profiles):
            if p is not None:
                out[..., c, c] = p.at(f)
        return out

    def rms(self) -> np.ndarray:
        """Root mean square of each channel, shape (6,) [rad/s ×3, m/s² ×3] (0 where no profile)."""
        return np.array([0.0 if p is None else p.rms for p in self.profiles])


# --------------------------------------------------------------------------- files
@dataclass(frozen=True)
class ProfileLimits:
    """Limits of a profile file, checked before any arithmetic.

    Attributes
    ----------
    file_bytes : int
        Largest file size [bytes].
    tables : int
        Most ``[[linear]]`` or ``[[angular]]`` tables of each kind [count].
    breakpoints : int
        Most breakpoints of one table [count].
    """

    file_bytes: int = 1024 * 1024
    tables: int = 3
    breakpoints: int = 1000


#: The limits :func:`load_profile` applies by default.
PROFILE_LIMITS = ProfileLimits()
_TOP = {"name", "description", "linear", "angular"}
_TABLE = {"axes", "unit", "label", "breakpoints"}
_POINT = {"freq_hz", "psd", "slope_db_per_octave"}
#: Deepest nesting of a profile file: [[linear]] → breakpoints = [{...}, ...].
_MAX_DEPTH = 5


def _profile_table(path: Path, kind: str, index: int, table, limits: ProfileLimits):
    where = f"[[{kind}]] #{index + 1}"
    r = Table(path, where, table, _TABLE)
    axes = r.text("axes", "xyz")
    if not axes or len(set(axes)) != len(axes) or set(axes) - set("xyz"):
        raise r.fail("axes", "some of the letters x, y, z, each at most once (e.g. \"xyz\" or \"z\")", axes)
    units = _KINDS[kind][1]
    unit = r.choice("unit", tuple(units))
    points = r.tables("breakpoints", limit=limits.breakpoints)
    if len(points) < 2:
        raise r.fail("breakpoints", "at least two breakpoints", table.get("breakpoints"))
    freq, levels, slopes = [], [], []
    for i, point in enumerate(points):
        p = Table(path, f"{where} breakpoint #{i + 1}", point, _POINT)
        freq.append(p.number("freq_hz", low=0.0, open_low=True, required=True))
        level = p.number("psd", low=0.0, open_low=True)
        slope = p.number("slope_db_per_octave")
        levels.append(None if level is None else level * units[unit] ** 2)
        slopes.append(slope)
    if np.any(np.diff(freq) <= 0):
        raise r.fail("breakpoints", "frequencies strictly increasing", freq)
    try:
        profile = profile_from_breakpoints(freq, levels, slopes, kind=kind, label=r.text("label", f"{kind} {axes}"))
    except ValueError as exc:
        raise ValueError(f"{path}: {where}: {exc}") from None
    return axes, profile


def load_profile(path, *, limits: ProfileLimits = PROFILE_LIMITS) -> BaseExcitation:
    """Read a profile file (TOML; format in ``docs/mount-files.md``) into a :class:`BaseExcitation`.

    Parameters
    ----------
    path : str or Path
        The file.
    limits : ProfileLimits, keyword-only
        Limits of the file (default :data:`PROFILE_LIMITS`).

    Returns
    -------
    BaseExcitation

    Raises
    ------
    ValueError
        A file that cannot be read or is not valid TOML, an unknown or missing
        key, a value of the wrong kind, an axis given twice, levels that the
        slopes do not determine; the message names the file, the table and
        the key.
    """
    path = Path(path)
    data = read_toml(path, max_bytes=limits.file_bytes, max_depth=_MAX_DEPTH, kind="profile file")
    top = Table(path, "top level", data, _TOP)
    channels: dict = {"linear": [None] * 3, "angular": [None] * 3}
    for kind in ("linear", "angular"):
        for i, table in enumerate(top.tables(kind, limit=limits.tables)):
            axes, profile = _profile_table(path, kind, i, table, limits)
            for a in axes:
                k = "xyz".index(a)
                if channels[kind][k] is not None:
                    raise ValueError(f"{path}: [[{kind}]] #{i + 1} key 'axes': the {a} axis already has a {kind} profile")
                channels[kind][k] = profile
    if not any(channels["linear"]) and not any(channels["angular"]):
        raise ValueError(f"{path}: no profile (expected at least one [[linear]] or [[angular]] table)")
    return BaseExcitation(tuple(channels["angular"]), tuple(channels["linear"]), top.text("name", path.stem), top.text("description", ""))

