"""Identification: designed probes recover an integrator's bilinear part as exact fractions.

Model.  An integrator over a step of N samples that reads ``K`` samples
before the step is, for small increments,

    Δφ = Σ_j a_j p_j + Σ_{i<j} c_ij p_i × p_j + R(p),

with ``j`` over the window ``1 − K … N`` (indices ≤ 0: samples of earlier
steps), and, for sculling,

    Δv = Σ_j a°_j b_j + Σ_{i,j} m_ij p_i × b_j + R°(p, b).

A rotation-equivariant map has no other linear or bilinear part (the cross
product is the only equivariant bilinear map R³ × R³ → R³); the probes check
that (:attr:`Coefficient.spread`), and what they cannot capture shows in the
remainder.

Probes.  Each probe is a block of ``B = ⌈K/N⌉ + 1`` steps of zeros with the
probe increments in its last step's window; the output of that last step is
read.  The blocks go to the integrator one after the other, in records of at
most :data:`RECORD_SAMPLES` samples; a block is long enough that an integrator
reading at most ``K`` samples back cannot see the block before it.

* Linear: ``p_j = ±ε e`` gives ``a_j = (F(ε) − F(−ε)) / 2ε + O(ε²)``.
* Bilinear: ``p_i = ±ε u``, ``p_j = ±ε v`` (u ⟂ v) and the four signs,
  ``Σ s_i s_j F(s_i ε u, s_j ε v) = 4 c_ij ε² (u × v) + O(ε⁴)``: every term odd
  in either increment cancels (the linear part, the degree-three terms).
* Accelerometer probes ``b_j = ±ε v`` do the same for ``a°_j`` and ``m_ij``.

Each coefficient is measured at the amplitudes ``ε_k = ε_0 / 2^k``,
k = 0 … 3 (:data:`PROBE_AMPLITUDES`), and extrapolated to ε → 0 by Richardson's
scheme in ε² (the error terms are even in ε); its uncertainty is the
difference of the last two extrapolations plus the round-off propagated from
the outputs.  Two more orientations of the probe (u, v cycled) at one
amplitude check that the integrator treats every axis alike.

Rational reconstruction.  A value known within ``t`` is the exact fraction
``p/q`` returned by ``Fraction(value).limit_denominator(Q)`` with
``Q = ⌊(2t)^(−1/2)⌋``, verified to lie within ``t`` of the value.  Two distinct
fractions of denominators at most Q differ by at least ``1/Q² > 2t``, so at
most one fraction can pass: the reconstruction is unique.  Each coefficient's
own ``t`` is :data:`UNCERTAINTY_FACTOR` times its uncertainty, no smaller than
:data:`TOLERANCE_FLOOR` and no larger than the stated ``tolerance``
(:data:`TOLERANCE` = 1e-9 by default, which admits denominators up to 22 360): a
coefficient measured to 1e-12 is reconstructed among denominators up to about
3·10⁵ (the polynomial-fit algorithms of the registry need 145 152), one
measured only to 1e-10 among denominators up to 35 000.  A value whose
uncertainty exceeds the stated tolerance is not reconstructed: it is reported
with its uncertainty, and the analyses use the nearest fraction of
denominator at most Q, marked approximate.  A wrong fraction would leave a
bilinear (degree-two) remainder, which the remainder measurement shows.

Remainder.  On random windows (seeded, ``rng``) at decreasing scales
(:data:`REMAINDER_SCALES`), reaching N samples further back than the probes,
the remainder ``R = F − model`` of the identified model (its exact fractions)
is measured: its size at each scale, the round-off floor there, and the slope
of ``log |R|`` against ``log scale`` at the smallest resolved scales, which is
its degree in the increments
(3 for a composition of exact rotations, none above round-off for an
integrator that is exactly bilinear; 2 or less means the model misses part
of the integrator: a longer memory than ``max_previous``, an axis treated
differently, a bias).  It is reported, never dropped.

A first record of random windows, fed twice, must give the same outputs: an
integrator that keeps state between calls or draws random numbers is refused.

Public API
----------
:data:`TOLERANCE`, :data:`DEFAULT_MAX_PREVIOUS`, :data:`PROBE_AMPLITUDES`, :data:`REMAINDER_SCALES`,
:func:`max_denominator`, :func:`rational`, :class:`Coefficient`,
:class:`Remainder`, :class:`ScullingIdentification`, :class:`Identification`,
:func:`probe_samples`, :func:`identify`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ....derivations.coning.algorithms import MAX_HISTORY, Algorithm, Term, second_order_defect
from ...core.validation import as_float, as_int
from .interface import Integrator, IntegratorError, step_increments
from .sculling_terms import ScullingTerms

__all__ = [
    "TOLERANCE",
    "DEFAULT_MAX_PREVIOUS",
    "PROBE_AMPLITUDES",
    "REMAINDER_SCALES",
    "max_denominator",
    "rational",
    "Coefficient",
    "Remainder",
    "ScullingIdentification",
    "Identification",
    "probe_samples",
    "identify",
]

#: Largest tolerance of the rational reconstruction [dimensionless]: ``|c − p/q| ≤ 1e-9``, q ≤ 22 360 at most.
TOLERANCE = 1e-9
#: A coefficient's own tolerance is this many times its uncertainty (when smaller than the largest tolerance).
UNCERTAINTY_FACTOR = 4.0
#: Smallest tolerance of a coefficient [dimensionless] (denominators up to 7·10⁶).
TOLERANCE_FLOOR = 1e-14
#: Default number of earlier samples probed.
DEFAULT_MAX_PREVIOUS = 4
#: Probe amplitudes ε_k [rad, and m/s for accelerometer probes].
PROBE_AMPLITUDES = (2e-2, 1e-2, 5e-3, 2.5e-3)
#: Scales of the random windows on which the remainder is measured (largest sample norm) [rad].
REMAINDER_SCALES = (0.08, 0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625)
#: Random windows per scale.
REMAINDER_WINDOWS = 8
#: Seed of the random windows when no ``rng`` is given.
DEFAULT_SEED = 20260101
#: Largest record handed to the integrator in one call [samples] (the probes are cut into records of whole blocks).
RECORD_SAMPLES = 1 << 18
#: Round-off of one output relative to its size, times a safety factor.
_ROUNDOFF = 8 * float(np.finfo(float).eps)
#: The (u, v) orientations of a bilinear probe; the first gives the value, the others the isotropy check.
_ORIENTATIONS = ((0, 1, 2), (1, 2, 0), (2, 0, 1))


def max_denominator(tolerance: float) -> int:
    """Largest denominator Q for which a fraction within ``tolerance`` of a value is unique: ``⌊(2 tolerance)^(−1/2)⌋``.

    Parameters
    ----------
    tolerance : float
        Reconstruction tolerance [dimensionless], in (0, 0.125].

    Returns
    -------
    int

    Raises
    ------
    ValueError
        For a tolerance outside (0, 0.125].

    Examples
    --------
    >>> max_denominator(1e-9)
    22360
    """
    tol = as_float(tolerance, "tolerance")
    if not 0 < tol <= 0.125:
        raise ValueError(f"Expected `tolerance` in (0, 0.125], got {tol:g}")
    return math.isqrt(int(1 / (2 * tol)))


def rational(value: float, tolerance: float = TOLERANCE) -> Fraction | None:
    """The unique fraction within ``tolerance`` of ``value`` with denominator at most :func:`max_denominator`, or None.

    Parameters
    ----------
    value : float
        The measured coefficient [dimensionless].
    tolerance : float
        Largest ``|value − p/q|`` accepted [dimensionless].

    Returns
    -------
    Fraction or None
        ``Fraction(value).limit_denominator(Q)`` when it lies within the tolerance (verified).

    Examples
    --------
    >>> rational(0.5833333333341)
    Fraction(7, 12)
    >>> rational(0.58334) is None
    True
    """
    q = max_denominator(tolerance)
    f = Fraction(as_float(value, "value")).limit_denominator(q)
    return f if abs(float(f) - value) <= tolerance else None


@dataclass(frozen=True)
class Coefficient:
    """One identified coefficient.

    Attributes
    ----------
    value : float
        Extrapolated to zero probe amplitude [dimensionless].
    uncertainty : float
        Estimated error of ``value``: extrapolation plus round-off [dimensionless].
    tolerance : float
        The tolerance of its reconstruction: :data:`UNCERTAINTY_FACTOR` times
        its uncertainty, within [:data:`TOLERANCE_FLOOR`, the identification's
        tolerance] [dimensionless]; it admits denominators up to
        :func:`max_denominator` of it.
    exact : Fraction or None
        The reconstructed fraction (None: ``uncertainty`` above the tolerance,
        or no fraction within it).
    approximant : Fraction
        ``exact``, or the nearest fraction of denominator at most Q (used by the analyses, marked approximate).
    spread : float
        Largest difference between the probe orientations at one amplitude
        [dimensionless]: zero to round-off for an integrator that treats every
        axis alike.
    """

    value: float
    uncertainty: float
    tolerance: float
    exact: Fraction | None
    approximant: Fraction
    spread: float

    @property
    def fraction(self) -> Fraction:
        """The fraction the analyses use (:attr:`exact` when reconstructed)."""
        return self.exact if self.exact is not None else self.approximant


@dataclass(frozen=True)
class Remainder:
    """What the identified linear and bilinear model leaves of the integrator.

    Attributes
    ----------
    scales : tuple of float
        Largest sample norm of the random windows at each scale [rad].
    sizes : tuple of float
        Largest ``|R|`` over the windows at each scale [rad, or m/s].
    floors : tuple of float
        Round-off floor of ``|R|`` at each scale (same unit).
    constant : float
        ``|F(0)|``: the output for a window of zeros.
    slope : float or None
        ``d log|R| / d log scale`` over the three smallest scales where ``|R|``
        is above ten times its floor, where the lowest degree leads (None:
        fewer than two such scales).
    degree : int or None
        The slope rounded, when it is within 0.25 of an integer (a power law).
    coefficient : float or None
        ``|R| ≈ coefficient · scale^degree`` (median over the scales of the slope).
    """

    scales: tuple
    sizes: tuple
    floors: tuple
    constant: float
    slope: float | None
    degree: int | None
    coefficient: float | None

    @property
    def above_roundoff(self) -> bool:
        """Whether any measured remainder is above ten times its floor."""
        return any(s > 10 * f for s, f in zip(self.sizes, self.floors)) or self.constant > 10 * _ROUNDOFF

    def summary(self) -> str:
        """One line: degree and size, or "none above round-off".

        Returns
        -------
        str
        """
        if not self.above_roundoff:
            return f"none above round-off (|R| ≤ {max(self.sizes):.1e} at scales down from {self.scales[0]:g} rad)"
        if self.degree is not None and self.coefficient is not None:
            return f"degree {self.degree} (slope {self.slope:.2f}): |R| ≈ {self.coefficient:.3g} · |p|^{self.degree}"
        if self.slope is not None:
            return f"not a power law (slope {self.slope:.2f}; |R| = {self.sizes[0]:.3g} at |p| = {self.scales[0]:g})"
        return f"|R| = {self.sizes[0]:.3g} at |p| = {self.scales[0]:g} (constant part {self.constant:.3g})"


@dataclass(frozen=True)
class ScullingIdentification:
    """The identified sculling part of an integrator.

    Attributes
    ----------
    linear : dict
        ``{j: Coefficient}``, coefficient of ``b_j``.
    bilinear : dict
        ``{(i, j): Coefficient}``, coefficient of ``p_i × b_j``, every (i, j) of the window.
    remainder : Remainder
        Of ``Δv`` against the identified model.
    """

    linear: dict
    bilinear: dict
    remainder: Remainder

    @property
    def coefficients(self) -> tuple:
        """Every coefficient, linear first."""
        return tuple(self.linear.values()) + tuple(self.bilinear.values())

    def terms(self, samples: int) -> ScullingTerms:
        """The identified sculling part as data (:class:`~.sculling_terms.ScullingTerms`, the fractions of :attr:`Coefficient.fraction`).

        Parameters
        ----------
        samples : int
            N, samples per step.

        Returns
        -------
        ScullingTerms
        """
        return ScullingTerms(samples, {j: c.fraction for j, c in self.linear.items() if c.fraction}, {k: c.fraction for k, c in self.bilinear.items() if c.fraction})


@dataclass(frozen=True)
class Identification:
    """The identified linear and bilinear part of an integrator, and what it leaves.

    Attributes
    ----------
    name : str
        The integrator's name.
    samples : int
        N, samples per step.
    max_previous : int
        K, earlier samples probed.
    tolerance : float
        Reconstruction tolerance [dimensionless].
    linear : dict
        ``{j: Coefficient}`` for every index j of the window ``1 − K … N``.
    pairwise : dict
        ``{(i, j): Coefficient}`` for every i < j of the window.
    remainder : Remainder
        Of ``Δφ`` against the identified model.
    sculling : ScullingIdentification or None
        For integrators that take accelerometer increments.
    probe_samples : int
        Samples fed to the integrator in all.
    """

    name: str
    samples: int
    max_previous: int
    tolerance: float
    linear: dict
    pairwise: dict
    remainder: Remainder
    sculling: ScullingIdentification | None
    probe_samples: int

    @property
    def max_denominator(self) -> int:
        """Denominators every coefficient's reconstruction admits: :func:`max_denominator` of the stated tolerance (a coefficient measured more precisely admits larger ones)."""
        return max_denominator(self.tolerance)

    def _all(self) -> tuple:
        out = tuple(self.linear.values()) + tuple(self.pairwise.values())
        return out + (self.sculling.coefficients if self.sculling is not None else ())

    @property
    def exact(self) -> bool:
        """Every coefficient (sculling included) reconstructed within the tolerance."""
        return all(c.exact is not None for c in self._all())

    @property
    def isotropic(self) -> bool:
        """Every probe orientation gave the same coefficient within the tolerance."""
        return all(c.spread <= self.tolerance for c in self._all())

    @property
    def history(self) -> int:
        """Earlier samples the identified model reads (linear, coning or sculling coefficient nonzero)."""
        indices = [j for j, c in self.linear.items() if c.fraction] + [i for (i, _), c in self.pairwise.items() if c.fraction]
        if self.sculling is not None:
            indices += [j for j, c in self.sculling.linear.items() if c.fraction]
            indices += [min(k) for k, c in self.sculling.bilinear.items() if c.fraction]
        return max([0] + [1 - j for j in indices])

    @property
    def at_limit(self) -> bool:
        """Whether a nonzero coefficient sits at the earliest probed index ``1 − K`` (the integrator may read further back)."""
        return self.max_previous > 0 and self.history >= self.max_previous

    @property
    def linear_part(self) -> dict:
        """``{j: a_j}`` as fractions, nonzero entries."""
        return {j: c.fraction for j, c in self.linear.items() if c.fraction}

    @property
    def linear_is_sum(self) -> bool:
        """Whether the linear part is ``P = p_1 + … + p_N`` exactly (the first-order condition of the package's algorithms)."""
        return self.linear_part == {j: Fraction(1) for j in range(1, self.samples + 1)}

    @property
    def terms(self) -> dict:
        """``{"i,j": "p/q"}``: the nonzero coefficients of ``p_i × p_j``, i < j."""
        return {f"{i},{j}": _text(c.fraction) for (i, j), c in self.pairwise.items() if c.fraction}

    def algorithm(self, name: str | None = None) -> Algorithm:
        """The identified bilinear part as an :class:`Algorithm` (``P`` plus the terms ``c_ij p_i × p_j``).

        The linear part of an :class:`Algorithm` is ``P`` by definition: when
        :attr:`linear_is_sum` is False the linear part differs, and the
        algorithm describes the bilinear part only (reported by the assessment).

        Parameters
        ----------
        name : str, optional
            Name of the algorithm (default: the integrator's).

        Returns
        -------
        Algorithm
        """
        terms = tuple(Term(c.fraction, (i, j)) for (i, j), c in self.pairwise.items() if c.fraction)
        return Algorithm(
            name or self.name,
            self.samples,
            terms,
            description=f"identified from the integrator {self.name!r} ({self.samples} samples per step)",
            reference="identified by strapdown identify (designed probes, exact fractions)",
        )

    def toml(self, name: str | None = None) -> str:
        """The identified algorithm in the algorithm-file syntax (``docs/algorithm-files.md``).

        Parameters
        ----------
        name : str, optional
            ``name`` key (default: the integrator's name).

        Returns
        -------
        str
            TOML text: ``name``, ``samples``, ``description``, ``reference`` and the ``[cross]`` table.
        """
        alg = self.algorithm(name)
        defect = second_order_defect(alg)
        lines = [
            f"name = {_toml_string(alg.name)}",
            f"samples = {alg.samples}",
            f"description = {_toml_string(alg.description)}",
            f"reference = {_toml_string(alg.reference)}",
        ]
        if not self.exact:
            lines.append("# some coefficients were not reconstructed within the tolerance: nearest fractions written")
        if not self.linear_is_sum:
            lines.append(f"# the integrator's linear part is not p_1 + ... + p_N: {', '.join(f'a_{j} = {_text(a)}' for j, a in sorted(self.linear_part.items()))}")
        if defect:
            lines.append(f"# second-order condition missed: sum c_ij (j - i) - N^3/12 = {_text(defect)} (load with allow_inconsistent)")
        lines.append("[cross]")
        lines += [f'"{i},{j}" = "{_text(c)}"' for (i, j), c in alg.pairwise.items()]
        return "\n".join(lines) + "\n"


def _text(f: Fraction) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def _toml_string(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


# --------------------------------------------------------------------------- probes
class _Prober:
    """Blocks of probe increments, one record per call, the last step of each block read."""

    def __init__(self, integrator: Integrator, samples: int, max_previous: int):
        self.integrator = integrator
        self.n = samples
        self.k = max_previous
        self.blocks = -(-max_previous // samples) + 1
        self.length = self.blocks * samples
        self.fed = 0

    def row(self, index: int) -> int:
        """Row of window index ``index`` (``1 − K … N``) in a block."""
        return (self.blocks - 1) * self.n + index - 1

    def last_steps(self, gyro, accel=None):
        """Outputs of the last step of every block: rotation (nb, 3) and velocity (nb, 3) or None.

        The blocks go to the integrator in records of at most :data:`RECORD_SAMPLES` samples.
        """
        per_call = max(1, RECORD_SAMPLES // self.length)
        rots, vels = [], []
        for start in range(0, gyro.shape[0], per_call):
            g = gyro[start : start + per_call]
            a = None if accel is None else accel[start : start + per_call]
            out = step_increments(self.integrator, g.reshape(-1, 3), self.n, None if a is None else a.reshape(-1, 3))
            self.fed += g.shape[0] * g.shape[1]
            rots.append(out.rotation.reshape(g.shape[0], self.blocks, 3)[:, -1])
            if out.velocity is not None:
                vels.append(out.velocity.reshape(g.shape[0], self.blocks, 3)[:, -1])
        return np.concatenate(rots), (np.concatenate(vels) if vels else None)


def _floor(values: np.ndarray, attitude_output: bool) -> np.ndarray:
    """Round-off of outputs ``values`` (n, 3): relative to their size, and absolute for attitudes (O(1) state)."""
    return _ROUNDOFF * (np.abs(values).max(axis=-1) + (1.0 if attitude_output else 0.0))


def _richardson(levels: np.ndarray, errors: np.ndarray) -> tuple:
    """Extrapolate ``levels[..., k]`` at amplitudes halving with k to zero amplitude (errors even in ε).

    Returns (value, uncertainty): the last diagonal entry, and its difference
    with the one before plus the round-off propagated through the weights.
    """
    table = [levels[..., k] for k in range(levels.shape[-1])]
    err = [errors[..., k] for k in range(errors.shape[-1])]
    previous = table[-1]
    m = 1
    while len(table) > 1:
        f = 4.0**m
        previous = table[-1]
        table = [(f * table[k + 1] - table[k]) / (f - 1) for k in range(len(table) - 1)]
        err = [(f * err[k + 1] + err[k]) / (f - 1) for k in range(len(err) - 1)]
        m += 1
    return table[0], np.abs(table[0] - previous) + err[0]


def _coefficients(value, uncertainty, spread, tolerance) -> list:
    out = []
    for v, u, s in zip(np.atleast_1d(value), np.atleast_1d(uncertainty), np.atleast_1d(spread)):
        v, u, s = float(v), float(u), float(s)
        own = min(tolerance, max(UNCERTAINTY_FACTOR * u, TOLERANCE_FLOOR))
        exact = rational(v, own) if u <= tolerance else None
        approximant = exact if exact is not None else Fraction(v).limit_denominator(max_denominator(own))
        out.append(Coefficient(v, u, own, exact, approximant, s))
    return out


def _unit(axis: int) -> np.ndarray:
    e = np.zeros(3)
    e[axis] = 1.0
    return e


def _linear_blocks(prober: _Prober, indices, channel: str):
    """Blocks probing the linear coefficients of ``indices``: axis x at every amplitude, y and z at the second.

    Returns gyro and accel blocks and the plan (index, axis, amplitude, sign) of each.
    """
    plan = []
    for j in indices:
        for level in range(len(PROBE_AMPLITUDES)):
            for axis in (0, 1, 2) if level == 1 else (0,):
                for sign in (1.0, -1.0):
                    plan.append((j, axis, level, sign))
    nb = len(plan)
    blocks = np.zeros((nb, prober.length, 3))
    rows = np.array([prober.row(j) for j, _, _, _ in plan])
    vec = np.array([s * PROBE_AMPLITUDES[lv] * _unit(a) for _, a, lv, s in plan])
    blocks[np.arange(nb), rows] = vec
    if channel == "gyro":
        return blocks, None, plan
    return np.zeros_like(blocks), blocks, plan


def _linear_values(plan, outputs, floors, indices, tolerance) -> dict:
    n_levels = len(PROBE_AMPLITUDES)
    index = {key: k for k, key in enumerate(plan)}
    out = {}
    for j in indices:
        levels, errors = np.zeros(n_levels), np.zeros(n_levels)
        for lv, eps in enumerate(PROBE_AMPLITUDES):
            plus, minus = index[(j, 0, lv, 1.0)], index[(j, 0, lv, -1.0)]
            levels[lv] = (outputs[plus, 0] - outputs[minus, 0]) / (2 * eps)
            errors[lv] = (floors[plus] + floors[minus]) / (2 * eps)
        value, unc = _richardson(levels, errors)
        eps = PROBE_AMPLITUDES[1]
        resp = np.array([(outputs[index[(j, a, 1, 1.0)]] - outputs[index[(j, a, 1, -1.0)]]) / (2 * eps) for a in (0, 1, 2)])
        spread = float(np.abs(resp - np.diag(np.full(3, resp[0, 0]))).max())  # equal diagonal, no cross-talk
        out[j] = _coefficients(value, unc, spread, tolerance)[0]
    return out


def _pair_blocks(prober: _Prober, pairs, channel: str):
    """Blocks probing ``p_i × p_j`` (channel "gyro") or ``p_i × b_j`` ("accel") for each (i, j) of ``pairs``."""
    plan = []
    for i, j in pairs:
        for level in range(len(PROBE_AMPLITUDES)):
            for orient in range(3) if level == 1 else (0,):
                for si in (1.0, -1.0):
                    for sj in (1.0, -1.0):
                        plan.append((i, j, orient, level, si, sj))
    nb = len(plan)
    gyro = np.zeros((nb, prober.length, 3))
    accel = np.zeros_like(gyro) if channel == "accel" else None
    ar = np.arange(nb)
    ri = np.array([prober.row(p[0]) for p in plan])
    rj = np.array([prober.row(p[1]) for p in plan])
    vi = np.array([p[4] * PROBE_AMPLITUDES[p[3]] * _unit(_ORIENTATIONS[p[2]][0]) for p in plan])
    vj = np.array([p[5] * PROBE_AMPLITUDES[p[3]] * _unit(_ORIENTATIONS[p[2]][1]) for p in plan])
    gyro[ar, ri] = vi
    if accel is None:
        gyro[ar, rj] += vj
    else:
        accel[ar, rj] = vj
    return gyro, accel, plan


def _pair_values(plan, outputs, floors, pairs, tolerance) -> dict:
    n_levels = len(PROBE_AMPLITUDES)
    index = {key: k for k, key in enumerate(plan)}

    def combo(i, j, orient, lv):
        w = _ORIENTATIONS[orient][2]
        total, err = 0.0, 0.0
        for si in (1.0, -1.0):
            for sj in (1.0, -1.0):
                k = index[(i, j, orient, lv, si, sj)]
                total += si * sj * outputs[k, w]
                err += floors[k]
        scale = 4 * PROBE_AMPLITUDES[lv] ** 2
        return total / scale, err / scale

    out = {}
    for i, j in pairs:
        levels, errors = np.zeros(n_levels), np.zeros(n_levels)
        for lv in range(n_levels):
            levels[lv], errors[lv] = combo(i, j, 0, lv)
        value, unc = _richardson(levels, errors)
        at = [combo(i, j, o, 1)[0] for o in range(3)]
        spread = float(max(at) - min(at))
        out[(i, j)] = _coefficients(value, unc, spread, tolerance)[0]
    return out


def _measure(prober: _Prober, keys, channel: str, kind: str, attitude: bool, tolerance: float) -> dict:
    """Coefficients of ``keys`` (indices for "linear", index pairs for "pairs"), probed in batches of whole records."""
    blocks_per_key = (2 * len(PROBE_AMPLITUDES) + 4) if kind == "linear" else 4 * (len(PROBE_AMPLITUDES) + 2)
    batch = max(1, RECORD_SAMPLES // (blocks_per_key * prober.length))
    out: dict = {}
    for start in range(0, len(keys), batch):
        part = keys[start : start + batch]
        if kind == "linear":
            gyro, accel, plan = _linear_blocks(prober, part, channel)
        else:
            gyro, accel, plan = _pair_blocks(prober, part, channel)
        rot, vel = prober.last_steps(gyro, accel)
        values = rot if channel == "gyro" else vel
        floors = _floor(values, attitude)
        out.update(_linear_values(plan, values, floors, part, tolerance) if kind == "linear" else _pair_values(plan, values, floors, part, tolerance))
    return out


# --------------------------------------------------------------------------- remainder
def _random_windows(prober: _Prober, rng, velocity: bool):
    """A block of zeros, then random windows ``1 − K … N`` of the prober at each scale (largest sample norm = scale)."""
    w = prober.k + prober.n
    first = prober.row(1 - prober.k)
    gyro = np.zeros((1 + len(REMAINDER_SCALES) * REMAINDER_WINDOWS, prober.length, 3))
    accel = np.zeros_like(gyro) if velocity else None
    for target in (gyro, accel) if velocity else (gyro,):
        base = rng.standard_normal((REMAINDER_WINDOWS, w, 3))
        base /= np.linalg.norm(base, axis=-1).max(axis=-1)[:, None, None]
        for s, scale in enumerate(REMAINDER_SCALES):
            target[1 + s * REMAINDER_WINDOWS : 1 + (s + 1) * REMAINDER_WINDOWS, first : first + w] = scale * base
    return gyro, accel


def _model_rotation(k, gyro_window, linear, pairwise):
    """Σ a_j p_j + Σ c_ij p_i × p_j on the windows (nb, W, 3) (index j at column j − 1 + K)."""
    out = np.zeros((gyro_window.shape[0], 3))
    for j, c in linear.items():
        out += float(c.fraction) * gyro_window[:, j - 1 + k]
    for (i, j), c in pairwise.items():
        if c.fraction:
            out += float(c.fraction) * np.cross(gyro_window[:, i - 1 + k], gyro_window[:, j - 1 + k])
    return out


def _model_velocity(k, gyro_window, accel_window, sculling: ScullingIdentification):
    """Σ a°_j b_j + Σ m_ij p_i × b_j on the windows (index j at column j − 1 + K)."""
    out = np.zeros((gyro_window.shape[0], 3))
    for j, c in sculling.linear.items():
        out += float(c.fraction) * accel_window[:, j - 1 + k]
    for (i, j), c in sculling.bilinear.items():
        if c.fraction:
            out += float(c.fraction) * np.cross(gyro_window[:, i - 1 + k], accel_window[:, j - 1 + k])
    return out


def _remainder(outputs, model, floors) -> Remainder:
    resid = np.linalg.norm(outputs - model, axis=-1)
    constant = float(resid[0])
    sizes, fl = [], []
    for s in range(len(REMAINDER_SCALES)):
        rows = slice(1 + s * REMAINDER_WINDOWS, 1 + (s + 1) * REMAINDER_WINDOWS)
        sizes.append(float(resid[rows].max()))
        fl.append(float(floors[rows].max()))
    scales = np.array(REMAINDER_SCALES)
    good = np.flatnonzero([z > 10 * f for z, f in zip(sizes, fl)])[-3:]  # the smallest resolved scales: the lowest degree leads there
    slope = degree = coefficient = None
    if len(good) >= 2:
        slope = float(np.polyfit(np.log(scales[good]), np.log(np.array(sizes)[good]), 1)[0])
        if abs(slope - round(slope)) <= 0.25:
            degree = int(round(slope))
            coefficient = float(np.median(np.array(sizes)[good] / scales[good] ** degree))
    return Remainder(tuple(REMAINDER_SCALES), tuple(sizes), tuple(fl), constant, slope, degree, coefficient)


def _deterministic(prober: _Prober, gyro, accel, first) -> None:
    again = prober.last_steps(gyro, accel)
    for a, b, what in ((first[0], again[0], "rotation vectors"), (first[1], again[1], "velocity increments")):
        if a is None:
            continue
        gap = float(np.abs(a - b).max())
        if gap > _ROUNDOFF * (float(np.abs(a).max()) + 1e-300):
            step = int(np.argmax(np.abs(a - b).max(axis=-1)))
            raise IntegratorError(
                f"integrator {prober.integrator.name!r} is not deterministic: two calls on the same increments gave {what} differing by {gap:.3g} "
                f"(block {step}); identification needs a function of its arguments alone (state left over from an earlier call? random numbers?)"
            )


# --------------------------------------------------------------------------- entry points
def probe_samples(samples: int, max_previous: int = DEFAULT_MAX_PREVIOUS, *, velocity: bool = False) -> int:
    """Number of samples :func:`identify` feeds an integrator (for work estimates).

    Parameters
    ----------
    samples : int
        N, samples per step.
    max_previous : int
        K, earlier samples probed.
    velocity : bool, keyword-only
        The sculling probes too.

    Returns
    -------
    int

    Examples
    --------
    >>> probe_samples(4, 4)
    7704
    """
    n = as_int(samples, "samples", minimum=1)
    k = as_int(max_previous, "max_previous", minimum=0)
    w = n + k
    length = (-(-k // n) + 1) * n
    levels = len(PROBE_AMPLITUDES)
    linear = w * (2 * levels + 4)
    pairs = w * (w - 1) // 2 * 4 * (levels + 2)
    blocks = linear + pairs
    if velocity:
        blocks += w * (2 * levels + 4) + w * w * 4 * (levels + 2)
    remainder = 2 * (1 + len(REMAINDER_SCALES) * REMAINDER_WINDOWS) * (-(-(k + n) // n) + 1) * n
    return blocks * length + remainder


def identify(integrator: Integrator, samples_per_step, *, max_previous=DEFAULT_MAX_PREVIOUS, tolerance=TOLERANCE, rng=None) -> Identification:
    """Identify the linear and bilinear part of ``integrator`` as exact fractions, and measure the remainder.

    Parameters
    ----------
    integrator : Integrator
        The black box (:mod:`.interface`); with ``velocity`` its sculling part is identified too.
    samples_per_step : int
        N, samples per output step, 1 … 64.
    max_previous : int, keyword-only
        K, how many samples before the step are probed, 0 … 64.
    tolerance : float, keyword-only
        Reconstruction tolerance [dimensionless] (module docstring).
    rng : numpy.random.Generator, int or None, keyword-only
        Random windows of the remainder measurement (default: a fixed seed).

    Returns
    -------
    Identification

    Raises
    ------
    TypeError
        If ``integrator`` is not an :class:`~.interface.Integrator`.
    ValueError
        For N or K out of range.
    IntegratorError
        The integrator raised, returned a wrong shape, NaN or infinity, or is
        not deterministic.

    Examples
    --------
    >>> from .recursions import recursion
    >>> ident = identify(recursion(), 2, max_previous=2)
    >>> ident.terms
    {'0,1': '1/12', '1,2': '7/12'}
    """
    if not isinstance(integrator, Integrator):
        raise TypeError(f"Expected `integrator` to be an Integrator, got {type(integrator).__name__}")
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    if n > 64:
        raise ValueError(f"Expected `samples_per_step` in 1..64, got {n}")
    k = as_int(max_previous, "max_previous", minimum=0)
    if k > MAX_HISTORY:
        raise ValueError(f"Expected `max_previous` in 0..{MAX_HISTORY}, got {k}")
    max_denominator(tolerance)
    rng = np.random.default_rng(DEFAULT_SEED if rng is None else rng)
    prober = _Prober(integrator, n, k)
    attitude = integrator.output != "rotation_vector"
    window = list(range(1 - k, n + 1))
    pairs = [(i, j) for a, i in enumerate(window) for j in window[a + 1 :]]

    # the random windows first: a small record that also checks determinism; they reach N samples
    # further back than the probes, so that an integrator with a longer memory leaves a bilinear remainder
    rprober = _Prober(integrator, n, k + n)
    rgyro, raccel = _random_windows(rprober, rng, integrator.velocity)
    rand = rprober.last_steps(rgyro, raccel)
    _deterministic(rprober, rgyro, raccel, rand)
    first = rprober.row(1 - k)

    linear = _measure(prober, window, "gyro", "linear", attitude, tolerance)
    pairwise = _measure(prober, pairs, "gyro", "pairs", attitude, tolerance)
    remainder = _remainder(rand[0], _model_rotation(k, rgyro[:, first:], linear, pairwise), _floor(rand[0], attitude))

    sculling = None
    if integrator.velocity:
        s_lin = _measure(prober, window, "accel", "linear", attitude, tolerance)
        s_bil = _measure(prober, [(i, j) for i in window for j in window], "accel", "pairs", attitude, tolerance)
        model = _model_velocity(k, rgyro[:, first:], raccel[:, first:], ScullingIdentification(s_lin, s_bil, remainder))
        sculling = ScullingIdentification(s_lin, s_bil, _remainder(rand[1], model, _floor(rand[1], attitude)))
    return Identification(integrator.name, n, k, float(tolerance), linear, pairwise, remainder, sculling, prober.fed + rprober.fed)
