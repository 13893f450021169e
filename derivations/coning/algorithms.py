"""Multi-sample rotation-vector (coning) algorithms as data.

An algorithm over a step ``H = N h`` takes the ``N`` gyro increments
``p_1 … p_N`` (``p_j = ∫ ω dt`` over the j-th sample interval) and returns the
rotation-vector increment

    Δφ = P + Σ c · [dot factors] · (nested cross product of the p_j),
    P = p_1 + … + p_N,

with exact rational coefficients ``c``.  Evaluated on dual vectors
``q_j = p_j + s b_j`` the same data gives the velocity (sculling) counterpart
(transfer principle, Lebedev & Panov 1989, eq. (2.5)); there is no second
definition.

Term syntax
-----------
``cross`` is a nested pair of sample indices: ``(1, 2)`` is
``p_1 × p_2`` and ``(1, (2, 4))`` is ``p_1 × (p_2 × p_4)``.  ``dots`` is a
tuple of index pairs whose dot products multiply the term: ``((2, 3),)`` with
cross ``(2, 3)`` is ``(p_2 · p_3) p_2 × p_3``.

Sample indices
--------------
With N samples per step, indices ``1 … N`` are the samples of the current step,
``0`` is the last sample of the previous step, ``−1`` the one before it, and so
on ("cross-step", or "N + previous" algorithms: Savage's ``(1/12) p_0 × p_1``
with N = 1).  :attr:`Algorithm.history` is the number of earlier samples an
algorithm reads, and :attr:`Algorithm.first_index` its lowest index
``1 − history``.  Increments are handed to an algorithm as one window
``p_{1−history} … p_N`` (:attr:`Algorithm.window` rows, oldest first).

TOML files (see :func:`load_toml`)::

    name = "my-3-sample"
    samples = 3
    description = "coning-optimal three-sample algorithm"
    [cross]            # coefficient of p_i × p_j (indices ≤ 0: earlier steps)
    "1,3" = "9/20"
    "1,2" = "27/40"
    "2,3" = "27/40"
    [triple]           # coefficient of p_i × (p_j × p_k)
    [dot_cross]        # coefficient of (p_i · p_j)(p_k × p_l), key "i,j;k,l"

The second-order condition (the sum rule that reproduces the
``H³/12 ω × ω'`` term of the exact increment) is
``Σ c_ij (j − i) = N³/12`` over the pairwise terms; it holds for cross-step
terms unchanged, since every increment is expanded about the same instant.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

from ..toml_files import read_toml

__all__ = ["Term", "Algorithm", "MAX_HISTORY", "TOML_LIMITS", "TomlLimits", "load_toml", "second_order_defect", "SecondOrderConditionError"]

Expr = int | tuple

#: How far back a cross-step term may reach, in samples before the current step.
MAX_HISTORY = 64


@dataclass(frozen=True)
class TomlLimits:
    """Limits of a TOML algorithm file, checked before any arithmetic.

    Far above any published algorithm (the largest in the sources has six
    samples and twenty terms), low enough that every file within them is read,
    checked and refused or accepted in well under a second.

    Attributes
    ----------
    file_bytes : int
        Largest file size [bytes].
    samples : int
        Largest number of samples N per step [count].
    terms : int
        Largest number of nonlinear terms [count].
    depth : int
        Deepest nesting of tables and arrays (``[cross]`` then ``key = value`` is 2) [count].
    coefficient_digits : int
        Most decimal digits in a coefficient's numerator or denominator, and
        largest decimal exponent of a coefficient such as ``"1.5e-3"`` [count].
    text : int
        Longest ``name``, ``description`` or ``reference`` [characters].
    """

    file_bytes: int = 256 * 1024
    samples: int = 64
    terms: int = 1000
    depth: int = 2
    coefficient_digits: int = 40
    text: int = 1000


#: The limits :func:`load_toml` applies by default.
TOML_LIMITS = TomlLimits()


def _leaves(expr) -> list:
    if isinstance(expr, int):
        return [expr]
    a, b = expr
    return _leaves(a) + _leaves(b)


@dataclass(frozen=True)
class Term:
    """One nonlinear term ``coefficient · Π(p_i·p_j) · cross``.

    Attributes
    ----------
    coefficient : Fraction
        Exact coefficient.
    cross : tuple
        Nested cross product of sample indices, e.g. ``(1, (2, 4))``; indices
        ``≤ 0`` are samples of earlier steps (module docstring).
    dots : tuple of (int, int)
        Dot-product factors ``(p_i · p_j)``.
    """

    coefficient: Fraction
    cross: tuple
    dots: tuple = ()

    @property
    def degree(self) -> int:
        """Degree in the increments (number of p factors)."""
        return len(_leaves(self.cross)) + 2 * len(self.dots)

    def indices(self) -> list:
        """Every sample index of the term, cross product first, then dot factors."""
        out = _leaves(self.cross)
        for i, j in self.dots:
            out += [i, j]
        return out

    def __str__(self) -> str:
        def show(e):
            if isinstance(e, int):
                return f"p{e}"
            a, b = e
            sa = show(a)
            sb = show(b) if isinstance(b, int) else f"({show(b)})"
            sa = sa if isinstance(a, int) else f"({sa})"
            return f"{sa}×{sb}"

        dots = "".join(f"(p{i}·p{j})" for i, j in self.dots)
        return f"{self.coefficient} {dots}{show(self.cross)}"


@dataclass(frozen=True)
class Algorithm:
    """An N-sample rotation-vector algorithm as exact data.

    Attributes
    ----------
    name : str
        Registry name.
    samples : int
        Number N of gyro increments per step H = N h.
    terms : tuple of Term
        Nonlinear terms added to P = p_1 + … + p_N; their indices lie in
        ``1 − MAX_HISTORY … N`` (``≤ 0``: samples of earlier steps).
    description : str
        One line for listings.
    reference : str
        Source (author, year, equation or table).
    """

    name: str
    samples: int
    terms: tuple = field(default_factory=tuple)
    description: str = ""
    reference: str = ""

    def __post_init__(self):
        if not isinstance(self.samples, int) or isinstance(self.samples, bool) or self.samples < 1:
            raise ValueError(f"Expected `samples` to be a positive integer, got {self.samples!r}")
        for term in self.terms:
            if not isinstance(term.coefficient, Fraction):
                raise TypeError(f"Expected an exact Fraction coefficient in algorithm {self.name!r}, got {term.coefficient!r}")
            if isinstance(term.cross, int):
                raise ValueError(f"Expected a cross product in every term of {self.name!r}, got the bare index {term.cross}")
            bad = [i for i in term.indices() if not (1 - MAX_HISTORY <= i <= self.samples)]
            if bad:
                raise ValueError(f"Expected sample indices in {1 - MAX_HISTORY}..{self.samples} in algorithm {self.name!r}, got {bad[0]}")

    @property
    def pairwise(self) -> dict:
        """Coefficients ``{(i, j): c}`` of the plain terms ``p_i × p_j``, folded to i < j."""
        out: dict = {}
        for t in self.terms:
            if t.dots or not (isinstance(t.cross[0], int) and isinstance(t.cross[1], int)):
                continue
            i, j = t.cross
            if i == j:
                continue
            key, sign = ((i, j), 1) if i < j else ((j, i), -1)
            out[key] = out.get(key, Fraction(0)) + sign * t.coefficient
        return {k: v for k, v in sorted(out.items()) if v != 0}

    @property
    def history(self) -> int:
        """Number of samples before the current step that the algorithm reads (0: within the step)."""
        lowest = min((i for t in self.terms for i in t.indices()), default=1)
        return max(0, 1 - lowest)

    @property
    def first_index(self) -> int:
        """Lowest sample index read, ``1 − history``."""
        return 1 - self.history

    @property
    def window(self) -> int:
        """Rows of the increment window ``p_{1−history} … p_N`` handed to the algorithm."""
        return self.samples + self.history

    @property
    def max_degree(self) -> int:
        """Highest degree of a term in the increments (1 for a linear algorithm)."""
        return max((t.degree for t in self.terms), default=1)


def second_order_defect(algorithm: Algorithm) -> Fraction:
    """``Σ c_ij (j − i) − N³/12``: zero iff the second-order condition holds.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm (cross-step indices allowed).

    Returns
    -------
    Fraction

    With ``p_j = h ω + (j − (N+1)/2) h² ω' + …`` the pairwise terms give
    ``Σ c_ij (j − i) h³ ω × ω'``, and the exact increment needs
    ``H³/12 ω × ω' = N³ h³/12 ω × ω'``.

    >>> two = Algorithm("two-sample", 2, (Term(Fraction(2, 3), (1, 2)),))
    >>> second_order_defect(two)
    Fraction(0, 1)
    """
    n = algorithm.samples
    total = sum((c * (j - i) for (i, j), c in algorithm.pairwise.items()), Fraction(0))
    return total - Fraction(n**3, 12)


# ---------------------------------------------------------------- TOML files
def _show(value, width: int = 40) -> str:
    """``repr(value)``, cut to ``width`` characters (a hostile file must not make a huge message)."""
    text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


_NUMBER = re.compile(r"\s*[+-]?(?:(?P<num>\d+)(?:/(?P<den>\d+))?|(?P<mant>\d*\.\d+|\d+\.?\d*)(?:[eE](?P<exp>[+-]?\d+))?)\s*")


def _fraction(value, where: str, limits: TomlLimits = TOML_LIMITS) -> Fraction:
    if isinstance(value, bool) or not isinstance(value, (str, int)):
        raise ValueError(f"{where}: expected an exact fraction as a string such as \"27/40\", got {_show(value)}")
    digits = limits.coefficient_digits
    if isinstance(value, int):
        if abs(value) >= 10**digits:
            raise ValueError(f"{where}: expected a coefficient of at most {digits} digits, got an integer of {len(str(abs(value)))} digits")
        return Fraction(value)
    m = _NUMBER.fullmatch(value) if len(value) <= 4 * digits else None
    if m is None:
        raise ValueError(f"{where}: expected an exact fraction such as \"27/40\" (at most {digits} digits), got {_show(value)}")
    parts = [m.group("num"), m.group("den"), (m.group("mant") or "").replace(".", "")]
    exponent = int(m.group("exp") or 0) if len(m.group("exp") or "") <= 6 else 10**6
    if max(len(p or "") for p in parts) > digits or abs(exponent) > digits:  # rejected before any arithmetic
        raise ValueError(f"{where}: expected a coefficient of at most {digits} digits and a decimal exponent of at most {digits}, got {_show(value)}")
    try:
        return Fraction(value)
    except (ValueError, ZeroDivisionError):
        raise ValueError(f"{where}: expected an exact fraction such as \"27/40\", got {_show(value)}") from None


def _indices(key: str, count: int, where: str, samples: int) -> tuple:
    """Parse ``"i,j"``; indices may be 0 or negative (earlier steps) down to ``1 − MAX_HISTORY``."""
    parts = [s.strip() for s in key.split(",")]
    try:
        idx = tuple(int(s) for s in parts)
    except ValueError:
        raise ValueError(f"{where}: expected {count} comma-separated sample indices, got {_show(key)}") from None
    if len(idx) != count:
        raise ValueError(f"{where}: expected {count} comma-separated sample indices, got {_show(key)}")
    bad = [i for i in idx if not 1 - MAX_HISTORY <= i <= samples]
    if bad:
        raise ValueError(f"{where}: expected sample indices in {1 - MAX_HISTORY}..{samples} (≤ 0: earlier steps), got {bad[0]}")
    return idx


def _parse(path: Path, limits: TomlLimits) -> dict:
    """Read and parse ``path`` within ``limits``: a regular UTF-8 file, small, shallow."""
    return read_toml(path, max_bytes=limits.file_bytes, max_depth=limits.depth, kind="algorithm file")


def _term(table: str, key: str, coefficient: Fraction, where: str, samples: int) -> Term:
    """The term a key of ``[cross]``, ``[triple]`` or ``[dot_cross]`` names; a cross product of a sample with itself is refused."""
    if table == "cross":
        i, j = _indices(key, 2, where, samples)
        cross, dots = (i, j), ()
    elif table == "triple":
        i, j, k = _indices(key, 3, where, samples)
        cross, dots = (i, (j, k)), ()
    else:
        if key.count(";") != 1:
            raise ValueError(f"{where}: expected \"i,j;k,l\" for (p_i·p_j)(p_k×p_l)")
        left, right = key.split(";")
        i, j = _indices(left, 2, where, samples)
        k, m = _indices(right, 2, where, samples)
        cross, dots = (k, m), ((i, j),)
    pair = cross if table != "triple" else cross[1]
    if pair[0] == pair[1]:
        term = Term(coefficient, cross, dots)
        raise ValueError(
            f"{where}: {_describe(term)} is zero (p_{pair[0]} × p_{pair[0]} = 0); a cross product needs two different sample indices"
        )
    return Term(coefficient, cross, dots)


def _product_key(term: Term) -> tuple:
    """What a file's term multiplies, with each pair sorted, and the sign that sorting gives.

    ``p_i × p_j``, ``p_i × (p_j × p_k)`` and ``(p_i·p_j)(p_k × p_l)``: swapping the
    factors of a cross product changes the sign, those of a dot product do not.
    """
    first, second = term.cross
    pair = term.cross if isinstance(second, int) else second
    sign = -1 if pair[0] > pair[1] else 1
    cross = tuple(sorted(pair)) if isinstance(second, int) else (first, tuple(sorted(pair)))
    return (cross, tuple(sorted(tuple(sorted(d)) for d in term.dots))), sign


def _describe(term: Term) -> str:
    """The product of a term without its coefficient, e.g. ``p1×p2``."""
    return str(term).split(" ", 1)[1]


class SecondOrderConditionError(ValueError):
    """A file's algorithm misses the second-order condition ``Σ c_ij (j − i) = N³/12``.

    Raised by :func:`load_toml` unless ``allow_inconsistent=True``; a front end can
    catch it to tell its user how to accept the algorithm in its own terms.

    Parameters
    ----------
    path : Path
        The file.
    total : Fraction
        ``Σ c_ij (j − i)`` of the algorithm.
    expected : Fraction
        ``N³/12``.
    """

    def __init__(self, path, total, expected):
        self.path, self.total, self.expected = path, total, expected
        super().__init__(
            f"{path}: algorithm misses the second-order condition: Σ c_ij (j − i) = {total}, "
            f"expected N³/12 = {expected} (load it with `allow_inconsistent=True` to accept it)"
        )


def load_toml(path, *, allow_inconsistent: bool = False, limits: TomlLimits = TOML_LIMITS) -> Algorithm:
    """Read a user algorithm from a TOML file (syntax in the module docstring).

    Everything is checked before any arithmetic, within :data:`TOML_LIMITS`
    (file size, samples, terms, nesting depth, coefficient size): a hostile
    file is refused in milliseconds and never exhausts memory or the stack.

    Parameters
    ----------
    path : str or Path
        The file (a regular file of UTF-8 text).
    allow_inconsistent : bool, keyword-only
        Accept an algorithm that violates the second-order condition.
    limits : TomlLimits, keyword-only
        Limits of the file (default :data:`TOML_LIMITS`).

    Returns
    -------
    Algorithm
        The algorithm, with exact fraction coefficients.

    Raises
    ------
    ValueError
        Malformed file (the message names the file, the key and the problem),
        a file beyond ``limits``, an empty file name, a file that cannot be read (missing, a
        directory, a device, no permission, not UTF-8).
    SecondOrderConditionError
        An algorithm that misses the second-order condition (a ``ValueError``).
    """
    if not str(path).strip():
        raise ValueError("Expected `path` to name a TOML file, got an empty file name")
    path = Path(path)
    data = _parse(path, limits)
    known = {"name", "samples", "description", "reference", "cross", "triple", "dot_cross"}
    extra = sorted(set(data) - known)
    if extra:
        raise ValueError(f"{path}: unknown key {_show(extra[0])} (expected one of {', '.join(sorted(known))})")
    if "samples" not in data:
        raise ValueError(f"{path}: key 'samples' is missing (expected N, the number of gyro increments per step, a positive integer)")
    samples = data["samples"]
    if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
        raise ValueError(f"{path}: key 'samples' must be a positive integer, got {_show(samples)}")
    if samples > limits.samples:
        raise ValueError(f"{path}: key 'samples' is {_show(samples)}, more than the limit of {limits.samples} samples per step")
    count = sum(len(v) for k, v in data.items() if k in ("cross", "triple", "dot_cross") and isinstance(v, dict))
    if count > limits.terms:
        raise ValueError(f"{path}: {count} terms, more than the limit of {limits.terms}")
    for key in ("name", "description", "reference"):
        if isinstance(data.get(key), str) and len(data[key]) > limits.text:
            raise ValueError(f"{path}: key {key!r} has {len(data[key])} characters, more than the limit of {limits.text}")
    terms = []
    for table in ("cross", "triple", "dot_cross"):
        entries = data.get(table, {})
        if not isinstance(entries, dict):
            raise ValueError(f"{path}: [{table}] must be a table, got {type(entries).__name__}")
        seen: dict = {}  # product (pairs sorted) -> (key, term, sign) of the key that named it first
        for key, value in entries.items():
            where = f"{path}: [{table}] key {_show(key)}"
            c = _fraction(value, where, limits)
            term = _term(table, key, c, where, samples)
            product, sign = _product_key(term)
            if product in seen:
                other, first, first_sign = seen[product]
                relation = "= " if sign == first_sign else "= −"
                raise ValueError(
                    f"{where}: names the same product as key {_show(other)} ({_describe(term)} {relation}{_describe(first)}); "
                    "give each product once"
                )
            seen[product] = (key, term, sign)
            terms.append(term)
    name = data.get("name", path.stem)
    if not isinstance(name, str):
        raise ValueError(f"{path}: key 'name' must be a string, got {_show(name)}")
    alg = Algorithm(name, samples, tuple(terms), str(data.get("description", "")), str(data.get("reference", str(path.name))))
    defect = second_order_defect(alg)
    if defect != 0 and not allow_inconsistent:
        raise SecondOrderConditionError(path, defect + Fraction(samples**3, 12), Fraction(samples**3, 12))
    return alg
