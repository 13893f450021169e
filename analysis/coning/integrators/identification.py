"""Identification: designed probes recover an integrator's linear and bilinear part as exact fractions.

Model.  An integrator over a step of N samples that reads ``K`` samples
before the step is, for small increments, a function of the window
``x = (p_{1−K}, …, p_N)`` ∈ R^(3W), ``W = K + N``,

    Δφ = F(0) + L x + Σ_{s ≤ t} H_st x_s x_t + R(x),

with ``s, t`` over the 3W slots (sample j, axis u).  Nothing is assumed of
``L`` (3 × 3W) and ``H`` (3W × 3W slots, each a vector of R³): the probes
measure every entry, so that an integrator that treats the axes differently
(a correction applied to z only, an axis dropped) is described as it is.  A
rotation-equivariant integrator has ``L = (a_j I)`` and ``H`` of cross
products only,

    Δφ = Σ_j a_j p_j + Σ_{i<j} c_ij p_i × p_j + R(p),

(the cross product is the only equivariant bilinear map R³ × R³ → R³): the
isotropic coefficients ``a_j`` and ``c_ij`` are read from the tensors, and
how far every entry departs from them is reported
(:attr:`Coefficient.spread`, :attr:`Identification.isotropic`).  For sculling,

    Δv = Σ_j a°_j b_j + Σ_{i,j} m_ij p_i × b_j + R°(p, b),

probed along the axes in three orientations (the departure of the two others
from the first is the spread).

Probes.  Each probe is a block of ``⌈K/N⌉ + 1`` steps of zeros with the probe
increments in its last step's window (:class:`~.probes.Prober`).

* Linear and square: ``x_s = ±ε``: ``L_s = (F(ε) − F(−ε)) / 2ε + O(ε²)`` and
  ``H_ss = (F(ε) + F(−ε) − 2F(0)) / 2ε² + O(ε²)``.
* Products: ``x_s = ±ε``, ``x_t = ±ε`` and the four signs,
  ``Σ σ τ F(σε, τε) = 4ε² H_st + O(ε⁴)``: every term odd in either increment
  cancels (the linear part, the degree-three terms).
* Accelerometer probes ``b_j = ±ε v`` do the same for ``a°_j`` and ``m_ij``.

Each entry is measured at the amplitudes ``ε_k = ε_0 / 2^k``, k = 0 … 3 (ε_0
the probe amplitude, :data:`PROBE_AMPLITUDE` unless given: it must lie in the
integrator's linearity range, :func:`~.assumptions.linearity_range`), and
extrapolated to ε → 0 by Richardson's scheme in ε² (the error terms are even
in ε); its uncertainty is the difference of the last two extrapolations plus
the round-off propagated from the outputs, whose size is the code's measured
noise floor (:class:`~.probes.NoiseFloor`; float64 round-off unless given).

Rational reconstruction.  A value known within ``t`` is the exact fraction
``p/q`` returned by ``Fraction(value).limit_denominator(Q)`` with
``Q = ⌊(2t)^(−1/2)⌋``, verified to lie within ``t`` of the value.  Two distinct
fractions of denominators at most Q differ by at least ``1/Q² > 2t``, so at
most one fraction can pass: the reconstruction is unique.  Each coefficient's
own ``t`` is :data:`UNCERTAINTY_FACTOR` times its uncertainty, no smaller than
:data:`TOLERANCE_FLOOR` and no larger than the stated ``tolerance``
(:data:`TOLERANCE` = 1e-9 by default, which admits denominators up to 22 360): a
coefficient measured to 1e-12 is reconstructed among denominators up to about
3·10⁵ (the polynomial-fit algorithms of the registry need 145 152).  A value
whose uncertainty exceeds the stated tolerance, or that no such fraction fits,
is not reconstructed: it is reported with its uncertainty, and the analyses use
the simplest fraction within four times its uncertainty
(:func:`simplest_fraction`), marked approximate, never a nearby fraction that
the measurement excludes (2/3 + 10⁻⁷ measured to 10⁻¹² is not 2/3).

Remainder.  On random windows (seeded, ``rng``) at decreasing scales (from
four times the probe amplitude, :func:`remainder_scales`), reaching N samples
further back than the probes, the remainder ``R = F − model`` of the
identified model (its tensors, each entry its exact fraction where one is
reconstructed) is measured: its size at each scale, the noise floor there,
and the slope of ``log |R|`` against ``log scale`` at the smallest resolved
scales, which is its degree in the increments (3 for a composition of exact
rotations, none above round-off for an integrator that is exactly bilinear;
2 or less means the model misses part of the integrator: a longer memory than
``max_previous``, a bias).  It is reported, never dropped.

The identification assumes an integrator that is time invariant, reads at
most K samples back, and stays linear over the probes; :mod:`.assumptions`
tests each of these and :func:`~.assessment.assess` reports the verdicts.

Public API
----------
:data:`TOLERANCE`, :data:`DEFAULT_MAX_PREVIOUS`, :data:`PROBE_AMPLITUDE`, :data:`LEVELS`,
:data:`PROBE_AMPLITUDES`, :data:`REMAINDER_SCALES`,
:func:`probe_amplitudes`, :func:`remainder_scales`,
:func:`max_denominator`, :func:`rational`, :func:`simplest_fraction`, :class:`Coefficient`,
:class:`Remainder`, :class:`ScullingIdentification`, :class:`Identification`,
:func:`probe_samples`, :func:`work`, :func:`identify`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from ....derivations.coning.algorithms import MAX_HISTORY, Algorithm, Term, second_order_defect
from ...core import budget
from ...core.validation import as_float, as_int, positive
from .defaults import DEFAULT_MAX_PREVIOUS, PROBE_AMPLITUDE, TOLERANCE
from .interface import Integrator
from .probes import NoiseFloor, Prober
from .sculling_terms import ScullingTerms

__all__ = [
    "TOLERANCE",
    "DEFAULT_MAX_PREVIOUS",
    "PROBE_AMPLITUDE",
    "LEVELS",
    "PROBE_AMPLITUDES",
    "REMAINDER_SCALES",
    "probe_amplitudes",
    "remainder_scales",
    "max_denominator",
    "rational",
    "simplest_fraction",
    "Coefficient",
    "Remainder",
    "ScullingIdentification",
    "Identification",
    "probe_samples",
    "work",
    "identify",
]

#: A coefficient's own tolerance is this many times its uncertainty (when smaller than the largest tolerance).
UNCERTAINTY_FACTOR = 4.0
#: Smallest tolerance of a coefficient [dimensionless] (denominators up to 7·10⁶).
TOLERANCE_FLOOR = 1e-14
#: Amplitudes per entry: ε_0, ε_0/2, ε_0/4, ε_0/8.
LEVELS = 4
#: Random windows per scale of the remainder.
REMAINDER_WINDOWS = 8
#: Scales of the remainder per probe amplitude: 4 ε_0 / 2^k, k = 0 … 7.
REMAINDER_LEVELS = 8
#: Seed of the random windows when no ``rng`` is given.
DEFAULT_SEED = 20260101
#: The (u, v) orientations of a sculling probe; the first gives the value, the others the isotropy check.
_ORIENTATIONS = ((0, 1, 2), (1, 2, 0), (2, 0, 1))


def probe_amplitudes(amplitude: float = PROBE_AMPLITUDE) -> tuple:
    """The amplitudes ε_0 / 2^k, k = 0 … :data:`LEVELS` − 1, of every probed entry.

    Parameters
    ----------
    amplitude : float
        ε_0 [rad, m/s], > 0.

    Returns
    -------
    tuple of float

    Examples
    --------
    >>> probe_amplitudes(0.02)
    (0.02, 0.01, 0.005, 0.0025)
    """
    eps = positive(amplitude, "amplitude")
    return tuple(eps / 2**k for k in range(LEVELS))


def remainder_scales(amplitude: float = PROBE_AMPLITUDE) -> tuple:
    """Scales of the random windows of the remainder: 4 ε_0 / 2^k, k = 0 … 7 [rad].

    Parameters
    ----------
    amplitude : float
        ε_0 [rad], > 0.

    Returns
    -------
    tuple of float
    """
    eps = positive(amplitude, "amplitude")
    return tuple(4 * eps / 2**k for k in range(REMAINDER_LEVELS))


#: The default probe amplitudes [rad, m/s].
PROBE_AMPLITUDES = probe_amplitudes()
#: The default scales of the remainder [rad].
REMAINDER_SCALES = remainder_scales()


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


def simplest_fraction(low, high) -> Fraction:
    """The fraction of smallest denominator in the closed interval [low, high] (Stern–Brocot descent).

    Parameters
    ----------
    low, high : float or Fraction
        The interval, ``low ≤ high`` [dimensionless].

    Returns
    -------
    Fraction

    Raises
    ------
    ValueError
        If ``low > high`` or either is not finite.

    Examples
    --------
    >>> simplest_fraction(0.6666, 0.6667)
    Fraction(2, 3)
    >>> simplest_fraction(2 / 3 + 1e-7 - 1e-11, 2 / 3 + 1e-7 + 1e-11).denominator > 10**5
    True
    """
    lo = Fraction(low) if isinstance(low, Fraction) else Fraction(as_float(low, "low"))
    hi = Fraction(high) if isinstance(high, Fraction) else Fraction(as_float(high, "high"))
    if lo > hi:
        raise ValueError(f"Expected `low` <= `high`, got {float(lo)!r} > {float(hi)!r}")
    if lo <= 0 <= hi:
        return Fraction(0)
    if hi < 0:
        return -simplest_fraction(-hi, -lo)
    # continued fractions of both ends until they part (the simplest number between them)
    fl = math.floor(lo)
    if fl == lo or math.floor(hi) > fl or math.ceil(lo) <= hi:
        return Fraction(math.ceil(lo))
    return fl + 1 / simplest_fraction(1 / (hi - fl), 1 / (lo - fl))


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
        ``exact``, or the simplest fraction within :data:`UNCERTAINTY_FACTOR`
        times the uncertainty of ``value`` (used by the analyses, marked approximate).
    spread : float
        Largest departure of the measured entries that an isotropic integrator
        makes equal to this coefficient (or to zero) [dimensionless]: zero to
        round-off for an integrator that treats every axis alike.
    """

    value: float
    uncertainty: float
    tolerance: float
    exact: Fraction | None
    approximant: Fraction
    spread: float

    @classmethod
    def measured(cls, value: float, uncertainty: float, tolerance: float = TOLERANCE, spread: float = 0.0) -> Coefficient:
        """A coefficient from its measured value and uncertainty: reconstructed as the module docstring says.

        Parameters
        ----------
        value : float
            Measured value [dimensionless].
        uncertainty : float
            Its uncertainty [dimensionless], ≥ 0.
        tolerance : float
            Largest reconstruction tolerance [dimensionless].
        spread : float
            Departure from isotropy [dimensionless].

        Returns
        -------
        Coefficient

        Examples
        --------
        >>> Coefficient.measured(0.5833333333341, 1e-12).exact
        Fraction(7, 12)
        >>> Coefficient.measured(2 / 3 + 1e-7, 1e-12).fraction == Fraction(2, 3)
        False
        """
        return _coefficient(as_float(value, "value"), as_float(uncertainty, "uncertainty"), spread, as_float(tolerance, "tolerance"))

    @property
    def fraction(self) -> Fraction:
        """The fraction the analyses use (:attr:`exact` when reconstructed)."""
        return self.exact if self.exact is not None else self.approximant

    @property
    def bound(self) -> float:
        """Largest error of :attr:`fraction` that the measurement allows [dimensionless]: 0 when exact."""
        return 0.0 if self.exact is not None else abs(float(self.approximant) - self.value) + UNCERTAINTY_FACTOR * self.uncertainty

    @property
    def isotropic(self) -> bool:
        """Whether :attr:`spread` is within what the uncertainty explains (twice the reconstruction factor)."""
        return self.spread <= 2 * UNCERTAINTY_FACTOR * self.uncertainty + TOLERANCE_FLOOR * max(1.0, abs(self.value))


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
        Noise floor of ``|R|`` at each scale (same unit).
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
    constant_floor : float
        Noise floor of ``|F(0)|``.
    """

    scales: tuple
    sizes: tuple
    floors: tuple
    constant: float
    slope: float | None
    degree: int | None
    coefficient: float | None
    constant_floor: float = 0.0

    @property
    def above_roundoff(self) -> bool:
        """Whether any measured remainder is above ten times its floor."""
        return any(s > 10 * f for s, f in zip(self.sizes, self.floors)) or self.constant > 10 * self.constant_floor

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


@dataclass(frozen=True, eq=False)
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
        ``{j: Coefficient}`` for every index j of the window ``1 − K … N``: the
        isotropic part ``a_j`` (mean of the diagonal of ``L_j``; spread: its
        largest departure from ``a_j I``).
    pairwise : dict
        ``{(i, j): Coefficient}`` for every i < j of the window: the isotropic
        part ``c_ij`` (spread: the largest departure of the entries of ``H_ij``
        from ``c_ij`` times the cross product).
    remainder : Remainder
        Of ``Δφ`` against the identified model (its tensors).
    sculling : ScullingIdentification or None
        For integrators that take accelerometer increments.
    probe_samples : int
        Samples fed to the integrator in all.
    amplitude : float
        ε_0, the largest probe amplitude [rad, m/s].
    noise : NoiseFloor
        The round-off model of the outputs the uncertainties follow from.
    linear_tensor : dict
        ``{(j, w, u): Fraction}``: the nonzero entries of ``L``, output axis w,
        input axis u of sample j (exact where reconstructed, else approximant).
    quadratic_tensor : dict
        ``{(i, u, j, v, w): Fraction}``: the nonzero coefficients of
        ``x_(i,u) x_(j,v)`` in output w, with ``(i, u) ≤ (j, v)`` (slot order).
    self_spread : float
        Largest entry of the same-sample products (``p_j`` with itself), which
        an isotropic integrator does not have [dimensionless].
    self_uncertainty : float
        Largest uncertainty of those entries [dimensionless].
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
    amplitude: float = PROBE_AMPLITUDE
    noise: NoiseFloor = field(default_factory=NoiseFloor)
    linear_tensor: dict = field(default_factory=dict)
    quadratic_tensor: dict = field(default_factory=dict)
    self_spread: float = 0.0
    self_uncertainty: float = 0.0

    @property
    def window(self) -> tuple:
        """Indices ``1 − K … N`` of the probed window."""
        return tuple(range(1 - self.max_previous, self.samples + 1))

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
        """Every measured entry is what an integrator that treats every axis alike gives, within its uncertainty."""
        same = self.self_spread <= 2 * UNCERTAINTY_FACTOR * self.self_uncertainty + TOLERANCE_FLOOR
        return same and all(c.isotropic for c in self._all())

    @property
    def history(self) -> int:
        """Earlier samples the identified model reads (any nonzero entry of its tensors, coning or sculling)."""
        indices = [j for (j, _, _) in self.linear_tensor] + [i for (i, _, _, _, _) in self.quadratic_tensor]
        indices += [j for j, c in self.linear.items() if c.fraction] + [i for (i, _), c in self.pairwise.items() if c.fraction]
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


# --------------------------------------------------------------------------- measurement
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


def _own_tolerance(value: float, uncertainty: float, tolerance: float) -> float:
    return min(tolerance, max(UNCERTAINTY_FACTOR * uncertainty, TOLERANCE_FLOOR * max(1.0, abs(value))))


def _snap(value: float, uncertainty: float, tolerance: float) -> tuple:
    """(exact or None, approximant, own tolerance) of one measured value."""
    own = _own_tolerance(value, uncertainty, tolerance)
    exact = rational(value, own) if uncertainty <= tolerance else None
    if exact is not None:
        return exact, exact, own
    width = max(own, UNCERTAINTY_FACTOR * uncertainty)
    return None, simplest_fraction(value - width, value + width), own


def _coefficient(value, uncertainty, spread, tolerance) -> Coefficient:
    v, u = float(value), float(uncertainty)
    exact, approximant, own = _snap(v, u, tolerance)
    return Coefficient(v, u, own, exact, approximant, float(spread))


#: Levi-Civita symbol ε_uvw: the isotropic pattern of a bilinear block.
_LEVI = np.zeros((3, 3, 3))
for _u, _v, _w in _ORIENTATIONS:
    _LEVI[_u, _v, _w], _LEVI[_v, _u, _w] = 1.0, -1.0


def _slots(prober: Prober, window) -> tuple:
    rows = np.repeat([prober.row(j) for j in window], 3)
    axes = np.tile(np.arange(3), len(window))
    return rows, axes


def _channel(prober: Prober, blocks: np.ndarray, channel: str):
    """Outputs of the last step of each block: gyro probes read Δφ; accelerometer probes (with zero gyro) read Δv."""
    if channel == "gyro":
        return prober.last_steps(blocks)[0]
    return prober.last_steps(np.zeros_like(blocks), blocks)[1]


def _gyro_tensors(prober: Prober, window, amps: np.ndarray, noise: NoiseFloor) -> tuple:
    """Every entry of L and H (module docstring), extrapolated: values and uncertainties.

    Returns F(0) (3,), its floor, L (S, 3) and its uncertainty, H (S, S, 3) (upper triangle, diagonal
    included: the coefficient of x_s x_t, or of x_s² on the diagonal) and its uncertainty.
    """
    rows, axes = _slots(prober, window)
    s_count, levels = len(rows), len(amps)
    # the zero block, then ±ε at every slot and level
    nb = levels * s_count * 2
    lv = np.repeat(np.arange(levels), s_count * 2)
    sl = np.tile(np.repeat(np.arange(s_count), 2), levels)
    sg = np.tile([1.0, -1.0], levels * s_count)
    blocks = prober.zeros(1 + nb)
    blocks[1 + np.arange(nb), rows[sl], axes[sl]] = sg * amps[lv]
    out = _channel(prober, blocks, "gyro")
    fl = noise.floor(out, np.concatenate([[0.0], amps[lv]]))
    f0, fl0 = out[0], fl[0]
    fp, flp = out[1:].reshape(levels, s_count, 2, 3), fl[1:].reshape(levels, s_count, 2)
    eps = amps[:, None]
    lin = (fp[:, :, 0] - fp[:, :, 1]) / (2 * eps[..., None])
    lin_err = (flp[:, :, 0] + flp[:, :, 1]) / (2 * eps)
    sq = (fp[:, :, 0] + fp[:, :, 1] - 2 * f0) / (2 * eps[..., None] ** 2)
    sq_err = (flp[:, :, 0] + flp[:, :, 1] + 2 * fl0) / (2 * eps**2)
    l_val, l_unc = _richardson(np.moveaxis(lin, 0, -1), np.broadcast_to(np.moveaxis(lin_err, 0, -1)[:, None, :], (s_count, 3, levels)))
    q_val, q_unc = _richardson(np.moveaxis(sq, 0, -1), np.broadcast_to(np.moveaxis(sq_err, 0, -1)[:, None, :], (s_count, 3, levels)))
    h_val = np.zeros((s_count, s_count, 3))
    h_unc = np.zeros((s_count, s_count, 3))
    idx = np.arange(s_count)
    h_val[idx, idx], h_unc[idx, idx] = q_val, q_unc
    # products of two slots, the four signs at every level, in batches of whole records
    pairs = np.array([(s, t) for s in range(s_count) for t in range(s + 1, s_count)], dtype=int).reshape(-1, 2)
    per_pair = levels * 4
    batch = max(1, (1 << 18) // (per_pair * prober.length))
    sig = np.array([(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)])
    weights = sig[:, 0] * sig[:, 1]
    for start in range(0, len(pairs), batch):
        part = pairs[start : start + batch]
        c = len(part)
        b = np.arange(c * per_pair)
        pi = np.repeat(np.arange(c), per_pair)
        lvl = np.tile(np.repeat(np.arange(levels), 4), c)
        sgn = np.tile(sig, (c * levels, 1))
        s_, t_ = part[pi, 0], part[pi, 1]
        blocks = prober.zeros(c * per_pair)
        blocks[b, rows[s_], axes[s_]] = sgn[:, 0] * amps[lvl]
        blocks[b, rows[t_], axes[t_]] += sgn[:, 1] * amps[lvl]
        out = _channel(prober, blocks, "gyro")
        fl = noise.floor(out, amps[lvl]).reshape(c, levels, 4)
        out = out.reshape(c, levels, 4, 3)
        scale = 4 * amps[None, :] ** 2
        combo = np.einsum("clkw,k->clw", out, weights) / scale[..., None]
        err = fl.sum(axis=-1) / scale
        v, u = _richardson(np.moveaxis(combo, 1, -1), np.broadcast_to(err[:, None, :], (c, 3, levels)))
        h_val[part[:, 0], part[:, 1]], h_unc[part[:, 0], part[:, 1]] = v, u
    return f0, fl0, l_val, l_unc, h_val, h_unc


def _isotropic_parts(window, l_val, l_unc, h_val, h_unc, tolerance) -> tuple:
    """The isotropic coefficients a_j, c_ij read from the tensors, with their departures (spreads)."""
    linear, pairwise = {}, {}
    for p, j in enumerate(window):
        a = l_val[3 * p : 3 * p + 3, :].T  # A_j[w, u]
        diag = np.diag(a)
        value = float(diag.mean())
        unc = float(np.diag(l_unc[3 * p : 3 * p + 3, :].T).max())
        spread = float(np.abs(a - value * np.eye(3)).max())
        linear[j] = _coefficient(value, unc, spread, tolerance)
    for p, i in enumerate(window):
        for q in range(p + 1, len(window)):
            block = h_val[3 * p : 3 * p + 3, 3 * q : 3 * q + 3]  # [u, v, w]
            value = float(np.mean([(block[u, v, w] - block[v, u, w]) / 2 for u, v, w in _ORIENTATIONS]))
            unc = float(h_unc[3 * p : 3 * p + 3, 3 * q : 3 * q + 3].max())
            spread = float(np.abs(block - value * _LEVI).max())
            pairwise[(i, window[q])] = _coefficient(value, unc, spread, tolerance)
    self_spread = self_unc = 0.0
    for p in range(len(window)):
        block = np.triu(np.ones((3, 3), dtype=bool))
        vals = h_val[3 * p : 3 * p + 3, 3 * p : 3 * p + 3][block]
        uncs = h_unc[3 * p : 3 * p + 3, 3 * p : 3 * p + 3][block]
        k = int(np.argmax(np.abs(vals).max(axis=-1)))
        if np.abs(vals).max() > self_spread:
            self_spread, self_unc = float(np.abs(vals).max()), float(uncs[k].max())
    return linear, pairwise, self_spread, self_unc


def _snapped_tensors(window, l_val, l_unc, h_val, h_unc, tolerance) -> tuple:
    """Each entry as its fraction (exact or approximant): the nonzero ones as dicts, and all as float arrays."""
    s_count = l_val.shape[0]
    lin_frac, quad_frac = {}, {}
    l_model = np.zeros((s_count, 3))
    h_model = np.zeros((s_count, s_count, 3))
    for s in range(s_count):
        for w in range(3):
            f = _snap(float(l_val[s, w]), float(l_unc[s, w]), tolerance)[1]
            if f:
                lin_frac[(window[s // 3], w, s % 3)] = f
                l_model[s, w] = float(f)
    for s, t in zip(*np.triu_indices(s_count)):
        for w in range(3):
            v, u = float(h_val[s, t, w]), float(h_unc[s, t, w])
            if abs(v) <= UNCERTAINTY_FACTOR * u + TOLERANCE_FLOOR:
                continue
            f = _snap(v, u, tolerance)[1]
            if f:
                quad_frac[(window[s // 3], int(s % 3), window[t // 3], int(t % 3), w)] = f
                h_model[s, t, w] = float(f)
    return lin_frac, quad_frac, l_model, h_model


# --------------------------------------------------------------------------- sculling probes (three orientations)
def _accel_linear(prober: Prober, window, amps, noise, tolerance) -> dict:
    rows = {j: prober.row(j) for j in window}
    plan = [(j, a, lv, s) for j in window for lv in range(len(amps)) for a in ((0, 1, 2) if lv == 1 else (0,)) for s in (1.0, -1.0)]
    blocks = prober.zeros(len(plan))
    for b, (j, a, lv, s) in enumerate(plan):
        blocks[b, rows[j], a] = s * amps[lv]
    out = _channel(prober, blocks, "accel")
    fl = noise.floor(out, np.array([amps[p[2]] for p in plan]))
    index = {key: k for k, key in enumerate(plan)}
    res = {}
    for j in window:
        levels = np.array([(out[index[(j, 0, lv, 1.0)], 0] - out[index[(j, 0, lv, -1.0)], 0]) / (2 * amps[lv]) for lv in range(len(amps))])
        errs = np.array([(fl[index[(j, 0, lv, 1.0)]] + fl[index[(j, 0, lv, -1.0)]]) / (2 * amps[lv]) for lv in range(len(amps))])
        value, unc = _richardson(levels, errs)
        resp = np.array([(out[index[(j, a, 1, 1.0)]] - out[index[(j, a, 1, -1.0)]]) / (2 * amps[1]) for a in (0, 1, 2)])
        spread = float(np.abs(resp - np.diag(np.full(3, resp[0, 0]))).max())
        res[j] = _coefficient(value, unc, spread, tolerance)
    return res


def _accel_pairs(prober: Prober, pairs, amps, noise, tolerance) -> dict:
    plan = [(i, j, o, lv, si, sj) for i, j in pairs for lv in range(len(amps)) for o in (range(3) if lv == 1 else (0,)) for si in (1.0, -1.0) for sj in (1.0, -1.0)]
    gyro = prober.zeros(len(plan))
    accel = prober.zeros(len(plan))
    for b, (i, j, o, lv, si, sj) in enumerate(plan):
        gyro[b, prober.row(i), _ORIENTATIONS[o][0]] = si * amps[lv]
        accel[b, prober.row(j), _ORIENTATIONS[o][1]] = sj * amps[lv]
    out = prober.last_steps(gyro, accel)[1]
    fl = noise.floor(out, np.array([amps[p[3]] for p in plan]))
    index = {key: k for k, key in enumerate(plan)}

    def combo(i, j, o, lv):
        w = _ORIENTATIONS[o][2]
        total = sum(si * sj * out[index[(i, j, o, lv, si, sj)], w] for si in (1.0, -1.0) for sj in (1.0, -1.0))
        err = sum(fl[index[(i, j, o, lv, si, sj)]] for si in (1.0, -1.0) for sj in (1.0, -1.0))
        scale = 4 * amps[lv] ** 2
        return total / scale, err / scale

    res = {}
    for i, j in pairs:
        vals = [combo(i, j, 0, lv) for lv in range(len(amps))]
        value, unc = _richardson(np.array([v for v, _ in vals]), np.array([e for _, e in vals]))
        at = [combo(i, j, o, 1)[0] for o in range(3)]
        res[(i, j)] = _coefficient(value, unc, max(at) - min(at), tolerance)
    return res


# --------------------------------------------------------------------------- remainder
def _random_windows(prober: Prober, rng, velocity: bool, scales):
    """A block of zeros, then random windows ``1 − reach … N`` of the prober at each scale (largest sample norm = scale)."""
    w = prober.reach + prober.n
    first = prober.row(1 - prober.reach)
    gyro = prober.zeros(1 + len(scales) * REMAINDER_WINDOWS)
    accel = np.zeros_like(gyro) if velocity else None
    for target in (gyro, accel) if velocity else (gyro,):
        base = rng.standard_normal((REMAINDER_WINDOWS, w, 3))
        base /= np.linalg.norm(base, axis=-1).max(axis=-1)[:, None, None]
        for s, scale in enumerate(scales):
            target[1 + s * REMAINDER_WINDOWS : 1 + (s + 1) * REMAINDER_WINDOWS, first : first + w] = scale * base
    return gyro, accel


def _model_rotation(x: np.ndarray, l_model: np.ndarray, h_model: np.ndarray) -> np.ndarray:
    """``L x + Σ_{s ≤ t} H_st x_s x_t`` on windows ``x`` (nb, S)."""
    return x @ l_model + np.einsum("bs,bt,stw->bw", x, x, h_model)


def _model_velocity(k, gyro_window, accel_window, sculling: ScullingIdentification):
    """Σ a°_j b_j + Σ m_ij p_i × b_j on the windows (index j at column j − 1 + K)."""
    out = np.zeros((gyro_window.shape[0], 3))
    for j, c in sculling.linear.items():
        out += float(c.fraction) * accel_window[:, j - 1 + k]
    for (i, j), c in sculling.bilinear.items():
        if c.fraction:
            out += float(c.fraction) * np.cross(gyro_window[:, i - 1 + k], accel_window[:, j - 1 + k])
    return out


def _remainder(outputs, model, floors, scales, constant_floor) -> Remainder:
    resid = np.linalg.norm(outputs - model, axis=-1)
    constant = float(resid[0])
    sizes, fl = [], []
    for s in range(len(scales)):
        rows = slice(1 + s * REMAINDER_WINDOWS, 1 + (s + 1) * REMAINDER_WINDOWS)
        sizes.append(float(resid[rows].max()))
        fl.append(float(floors[rows].max()))
    scales_arr = np.array(scales)
    good = np.flatnonzero([z > 10 * f for z, f in zip(sizes, fl)])[-3:]  # the smallest resolved scales: the lowest degree leads there
    slope = degree = coefficient = None
    if len(good) >= 2:
        slope = float(np.polyfit(np.log(scales_arr[good]), np.log(np.array(sizes)[good]), 1)[0])
        if abs(slope - round(slope)) <= 0.25:
            degree = int(round(slope))
            coefficient = float(np.median(np.array(sizes)[good] / scales_arr[good] ** degree))
    return Remainder(tuple(scales), tuple(sizes), tuple(fl), constant, slope, degree, coefficient, float(constant_floor))


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
    37652
    """
    n = as_int(samples, "samples", minimum=1)
    k = as_int(max_previous, "max_previous", minimum=0)
    w = n + k
    s = 3 * w
    length = (-(-k // n) + 1) * n
    blocks = 1 + LEVELS * s * 2 + s * (s - 1) // 2 * 4 * LEVELS
    if velocity:
        blocks += w * (2 * LEVELS + 4) + w * w * 4 * (LEVELS + 2)
    remainder = (1 + REMAINDER_LEVELS * REMAINDER_WINDOWS) * (-(-(k + n) // n) + 1) * n
    return blocks * length + remainder


def work(samples, max_previous=DEFAULT_MAX_PREVIOUS, *, velocity: bool = False, seconds_per_sample: float | None = None) -> budget.Estimate:
    """Estimated time and memory of :func:`identify`.

    Parameters
    ----------
    samples : int
        N.
    max_previous : int
        K.
    velocity : bool, keyword-only
        With the sculling probes.
    seconds_per_sample : float, optional, keyword-only
        The integrator's time per sample [s] (default: that of a vectorised
        integrator, :data:`~strapdown.analysis.core.budget.INTEGRATOR_SAMPLE`).

    Returns
    -------
    strapdown.analysis.core.budget.Estimate
        Its ``what`` names ``max_previous``.
    """
    fed = probe_samples(samples, max_previous, velocity=velocity)
    per = budget.INTEGRATOR_SAMPLE.seconds_per_unit if seconds_per_sample is None else max(float(seconds_per_sample), 0.0)
    model = budget.CostModel(seconds_per_unit=1.2 * per + 2e-6, bytes_per_unit=0.0, fixed_bytes=(1 << 18) * 3 * 8 * 8)
    s = 3 * (int(samples) + int(max_previous))
    return model.estimate(fed, what=f"`max_previous` = {max_previous} ({fed:,} probe samples, {s * s * 3:,} tensor entries)")


def identify(
    integrator: Integrator,
    samples_per_step,
    *,
    max_previous=DEFAULT_MAX_PREVIOUS,
    tolerance=TOLERANCE,
    amplitude=PROBE_AMPLITUDE,
    noise: NoiseFloor | None = None,
    rng=None,
    limits: budget.Limits | None = None,
) -> Identification:
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
    amplitude : float, keyword-only
        ε_0, the largest probe amplitude [rad, and m/s for accelerometer
        probes]; the others are ε_0/2, ε_0/4, ε_0/8.
    noise : NoiseFloor, keyword-only, optional
        The round-off of the integrator's outputs (default: float64's,
        :data:`~.probes.FLOAT64_NOISE`; :func:`~.assumptions.precision` measures it).
    rng : numpy.random.Generator, int or None, keyword-only
        Random windows of the remainder measurement (default: a fixed seed).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (:func:`work`).

    Returns
    -------
    Identification

    Raises
    ------
    TypeError
        If ``integrator`` is not an :class:`~.interface.Integrator`.
    ValueError
        For N or K out of range, a non-positive amplitude, or work beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``max_previous``).
    IntegratorError
        The integrator raised, returned a wrong shape, NaN or infinity.

    Examples
    --------
    >>> from .recursions import recursion
    >>> ident = identify(recursion(), 2, max_previous=2)
    >>> ident.terms, ident.isotropic
    ({'0,1': '1/12', '1,2': '7/12'}, True)
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
    amps = np.array(probe_amplitudes(amplitude))
    noise = NoiseFloor(attitude=integrator.output != "rotation_vector") if noise is None else noise
    if not isinstance(noise, NoiseFloor):
        raise TypeError(f"Expected `noise` to be a NoiseFloor or None, got {type(noise).__name__}")
    budget.check(work(n, k, velocity=integrator.velocity), limits)
    rng = np.random.default_rng(DEFAULT_SEED if rng is None else rng)
    prober = Prober(integrator, n, k)
    window = list(range(1 - k, n + 1))

    f0, fl0, l_val, l_unc, h_val, h_unc = _gyro_tensors(prober, window, amps, noise)
    linear, pairwise, self_spread, self_unc = _isotropic_parts(window, l_val, l_unc, h_val, h_unc, tolerance)
    lin_frac, quad_frac, l_model, h_model = _snapped_tensors(window, l_val, l_unc, h_val, h_unc, tolerance)

    # the random windows reach N samples further back than the probes: a longer memory leaves a remainder
    scales = remainder_scales(amplitude)
    rprober = Prober(integrator, n, k + n)
    rgyro, raccel = _random_windows(rprober, rng, integrator.velocity, scales)
    rot, vel = rprober.last_steps(rgyro, raccel)
    first = rprober.row(1 - k)
    x = rgyro[:, first : first + n + k].reshape(rgyro.shape[0], -1)
    in_scale = np.concatenate([[0.0], np.repeat(scales, REMAINDER_WINDOWS)])
    remainder = _remainder(rot, _model_rotation(x, l_model, h_model), noise.floor(rot, in_scale), scales, fl0)

    sculling = None
    if integrator.velocity:
        s_lin = _accel_linear(prober, window, amps, noise, tolerance)
        s_bil = _accel_pairs(prober, [(i, j) for i in window for j in window], amps, noise, tolerance)
        partial = ScullingIdentification(s_lin, s_bil, remainder)
        model = _model_velocity(k, rgyro[:, first:], raccel[:, first:], partial)
        vfloor = noise.floor(vel, in_scale)
        sculling = ScullingIdentification(s_lin, s_bil, _remainder(vel, model, vfloor, scales, vfloor[0]))
    return Identification(
        integrator.name, n, k, float(tolerance), linear, pairwise, remainder, sculling, prober.fed + rprober.fed,
        float(amps[0]), noise, lin_frac, quad_frac, self_spread, self_unc,
    )  # fmt: skip
