"""Series graded by weight, with homogeneous parts computed on demand.

Every series of the coning derivations is a sum ``Σ_w a_w`` of parts of one
*weight* ``w``: in the local-error series the weight of ``ω^(k)`` is ``k + 1``,
and a part of weight ``w`` multiplies ``H^w`` (Lebedev & Panov 1989, eq. (2.4)).
A :class:`Graded` series holds its parts as tuples of elements of one
:mod:`sympy.polys.rings` ring (one element for a scalar, three for a vector,
four for a quaternion) and computes a part only when it is asked for, from the
parts of its operands: the weight-``w`` part of ``a × b`` is
``Σ_i a_i × b_{w−i}``.  Nothing is ever truncated, and asking for weight 7
costs only the work of weights up to 7; a later request for weight 13 reuses
it.

The ring may be the ring of components of the ω-derivatives
(:data:`strapdown.derivations.coning.series.RING`) or any other, for example
the polynomials in ``ε, sin ϑ, cos ϑ`` of a regular precession
(:mod:`strapdown.derivations.coning.drift`): the same operations serve both.

Examples
--------
>>> from math import factorial
>>> from sympy.polys.domains import QQ
>>> from sympy.polys.rings import ring
>>> R, x = ring("x", QQ)
>>> a = Graded.from_parts(R, 1, {1: (x,)})          # the series x (weight 1)
>>> e = power_series(a, lambda k: Fraction(1, factorial(k)))
>>> [e.part(w)[0] for w in range(4)]                # exp(x) by weight
[1, x, 1/2*x**2, 1/6*x**3]
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from math import factorial

__all__ = [
    "Graded",
    "coefficient",
    "combine",
    "cross",
    "dot",
    "times",
    "quaternion_product",
    "power_series",
    "components",
    "pure",
    "conjugate",
    "rotation_quaternion",
    "rotation_vector",
]


def coefficient(ring, value):
    """``value`` (int, Fraction or ring-domain element) as an element of ``ring``'s domain.

    Parameters
    ----------
    ring : sympy.polys.rings.PolyRing
        Target ring.
    value : int, Fraction or domain element
        The number.

    Returns
    -------
    domain element
    """
    if isinstance(value, Fraction):
        return ring.domain(value.numerator, value.denominator)
    return ring.domain.convert(value)


class Graded:
    """A series ``Σ_{w ≥ low} a_w`` whose homogeneous parts are computed on demand and kept.

    Parameters
    ----------
    ring : sympy.polys.rings.PolyRing
        Ring of the components.
    size : int
        Components per part (1 scalar, 3 vector, 4 quaternion).
    rule : callable
        ``rule(w) -> sequence of size ring elements``: the weight-w part, for
        ``w ≥ low``.  It is called at most once per weight.
    low : int, keyword-only
        Parts below this weight are zero (used to bound sums; default 0).

    Attributes
    ----------
    ring, size, low
        As given.
    """

    __slots__ = ("ring", "size", "low", "_rule", "_parts")

    def __init__(self, ring, size: int, rule: Callable, *, low: int = 0):
        self.ring = ring
        self.size = size
        self.low = low
        self._rule = rule
        self._parts: dict = {}

    @classmethod
    def from_parts(cls, ring, size: int, parts: dict) -> Graded:
        """A series with the given parts ``{weight: tuple}`` and zero elsewhere.

        Parameters
        ----------
        ring : sympy.polys.rings.PolyRing
            Ring of the components.
        size : int
            Components per part.
        parts : dict
            ``{w: sequence of size ring elements}``.

        Returns
        -------
        Graded
        """
        fixed = {w: tuple(ring(c) for c in v) for w, v in parts.items()}
        zero = (ring.zero,) * size
        low = min(fixed, default=0)
        return cls(ring, size, lambda w: fixed.get(w, zero), low=low)

    def zero(self) -> tuple:
        """A zero part."""
        return (self.ring.zero,) * self.size

    def part(self, weight: int) -> tuple:
        """The homogeneous part of ``weight``.

        Parameters
        ----------
        weight : int
            The weight (≥ 0).

        Returns
        -------
        tuple of ring elements
        """
        if weight < self.low:
            return self.zero()
        p = self._parts.get(weight)
        if p is None:
            p = tuple(self._rule(weight))
            self._parts[weight] = p
        return p

    def parts(self, max_weight: int) -> tuple:
        """Parts of weight ``0 … max_weight``.

        Parameters
        ----------
        max_weight : int
            Highest weight.

        Returns
        -------
        tuple of tuples
        """
        return tuple(self.part(w) for w in range(max_weight + 1))

    def total(self, max_weight: int) -> tuple:
        """Sum of the parts of weight ≤ ``max_weight``.

        Parameters
        ----------
        max_weight : int
            Highest weight kept.

        Returns
        -------
        tuple of ring elements
        """
        out = list(self.zero())
        for w in range(self.low, max_weight + 1):
            for i, c in enumerate(self.part(w)):
                if c:
                    out[i] = out[i] + c
        return tuple(out)


def combine(terms, *, ring=None, size=None) -> Graded:
    """``Σ c_k a_k`` for ``terms = [(c_k, a_k), …]`` (c_k int, Fraction or domain element).

    Parameters
    ----------
    terms : sequence of (number, Graded)
        Coefficients and series, all on one ring and of one size.
    ring : PolyRing, keyword-only
        Ring of an empty combination.
    size : int, keyword-only
        Size of an empty combination.

    Returns
    -------
    Graded
    """
    terms = list(terms)
    if not terms:
        return Graded.from_parts(ring, size, {})
    ring, size = terms[0][1].ring, terms[0][1].size
    coeffs = [(coefficient(ring, c), a) for c, a in terms if c]
    low = min((a.low for _, a in coeffs), default=0)

    def rule(w):
        out = [ring.zero] * size
        for c, a in coeffs:
            for i, x in enumerate(a.part(w)):
                if x:
                    out[i] = out[i] + x * c
        return out

    return Graded(ring, size, rule, low=low)


def _convolve(a: Graded, b: Graded, size: int, product: Callable) -> Graded:
    ring = a.ring

    def rule(w):
        out = [ring.zero] * size
        for i in range(a.low, w - b.low + 1):
            pa = a.part(i)
            if not any(pa):
                continue
            pb = b.part(w - i)
            if not any(pb):
                continue
            for k, x in enumerate(product(pa, pb)):
                if x:
                    out[k] = out[k] + x
        return out

    return Graded(ring, size, rule, low=a.low + b.low)


def _cross3(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def cross(a: Graded, b: Graded) -> Graded:
    """Cross product of two vector series (weights add).

    Parameters
    ----------
    a, b : Graded
        Vector series (size 3) on one ring.

    Returns
    -------
    Graded
    """
    return _convolve(a, b, 3, _cross3)


def dot(a: Graded, b: Graded) -> Graded:
    """Scalar product of two vector series, a scalar series (size 1).

    Parameters
    ----------
    a, b : Graded
        Vector series (size 3) on one ring.

    Returns
    -------
    Graded
    """
    return _convolve(a, b, 1, lambda x, y: (x[0] * y[0] + x[1] * y[1] + x[2] * y[2],))


def times(s: Graded, v: Graded) -> Graded:
    """Product of a scalar series ``s`` (size 1) and a series ``v`` of any size.

    Parameters
    ----------
    s : Graded
        Scalar series.
    v : Graded
        Series multiplied component by component.

    Returns
    -------
    Graded
    """
    return _convolve(s, v, v.size, lambda x, y: tuple(x[0] * c for c in y))


def _hamilton(p, q):
    a0, a1, a2, a3 = p
    b0, b1, b2, b3 = q
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def quaternion_product(p: Graded, q: Graded) -> Graded:
    """Hamilton product ``p ∘ q`` of two quaternion series (size 4, scalar first).

    Parameters
    ----------
    p, q : Graded
        Quaternion series on one ring.

    Returns
    -------
    Graded
    """
    return _convolve(p, q, 4, _hamilton)


def power_series(z: Graded, coefficients: Callable) -> Graded:
    """``f(z) = Σ_k c_k z^k`` for a scalar series ``z`` with no part below weight 1.

    Parameters
    ----------
    z : Graded
        Scalar series (size 1) with ``z.low ≥ 1``.
    coefficients : callable
        ``k -> c_k`` (int, Fraction or domain element).

    Returns
    -------
    Graded

    Raises
    ------
    ValueError
        If ``z`` is not a scalar series or may have a part of weight 0.
    """
    if z.size != 1 or z.low < 1:
        raise ValueError(f"Expected a scalar series with no part below weight 1, got size {z.size} and low {z.low}")
    ring = z.ring
    one = Graded.from_parts(ring, 1, {0: (ring.one,)})
    powers = [one]
    coeffs: dict = {}

    def power(k):
        while len(powers) <= k:
            powers.append(times(powers[-1], z))
        return powers[k]

    def c(k):
        if k not in coeffs:
            coeffs[k] = coefficient(ring, coefficients(k))
        return coeffs[k]

    def rule(w):
        total = ring.zero
        for k in range(w // z.low + 1):
            ck = c(k)
            if ck:
                x = power(k).part(w)[0]
                if x:
                    total = total + x * ck
        return (total,)

    return Graded(ring, 1, rule, low=0)


def components(a: Graded, indices) -> Graded:
    """The series of the selected components of ``a`` (e.g. the vector part of a quaternion).

    Parameters
    ----------
    a : Graded
        A series.
    indices : sequence of int
        Components kept, in order.

    Returns
    -------
    Graded
    """
    indices = tuple(indices)
    return Graded(a.ring, len(indices), lambda w: tuple(a.part(w)[i] for i in indices), low=a.low)


def pure(v: Graded) -> Graded:
    """The pure quaternion series ``(0, v)`` of a vector series.

    Parameters
    ----------
    v : Graded
        Vector series (size 3).

    Returns
    -------
    Graded
    """
    zero = v.ring.zero
    return Graded(v.ring, 4, lambda w: (zero,) + v.part(w), low=v.low)


def conjugate(q: Graded) -> Graded:
    """The conjugate quaternion series ``(q0, −q1, −q2, −q3)``.

    Parameters
    ----------
    q : Graded
        Quaternion series (size 4).

    Returns
    -------
    Graded
    """

    def rule(w):
        a, b, c, d = q.part(w)
        return (a, -b, -c, -d)

    return Graded(q.ring, 4, rule, low=q.low)


def _cos_half(k):
    return Fraction((-1) ** k, 4**k * factorial(2 * k))


def _sin_half_over(k):
    return Fraction((-1) ** k, 2 ** (2 * k + 1) * factorial(2 * k + 1))


def _asin_over(k):
    return Fraction(2 * factorial(2 * k), 4**k * factorial(k) ** 2 * (2 * k + 1))


def rotation_quaternion(v: Graded) -> Graded:
    """``(cos(|v|/2), sin(|v|/2) v/|v|)``: the quaternion of the rotation vector series ``v``.

    Parameters
    ----------
    v : Graded
        Vector series with no part below weight 1.

    Returns
    -------
    Graded
        Quaternion series (scalar first), as even series in ``|v|² = v·v``.
    """
    z = dot(v, v)
    c = power_series(z, _cos_half)
    s = times(power_series(z, _sin_half_over), v)
    return Graded(v.ring, 4, lambda w: c.part(w) + s.part(w), low=0)


def rotation_vector(q: Graded) -> Graded:
    """``2 asin(|u|) u/|u|``: the rotation vector of a unit quaternion series ``q = (q0, u)``, q0 > 0.

    Parameters
    ----------
    q : Graded
        Unit quaternion series whose vector part has no part below weight 1.

    Returns
    -------
    Graded
        Vector series.

    Raises
    ------
    ValueError
        If the vector part of ``q`` has a part of weight 0.
    """
    if any(q.part(0)[1:]):
        raise ValueError("Expected a quaternion series whose vector part starts at weight 1, got a weight-0 vector part")
    u = Graded(q.ring, 3, lambda w: q.part(w)[1:], low=max(1, q.low))
    return times(power_series(dot(u, u), _asin_over), u)
