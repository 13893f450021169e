"""The dot-product term of the sixth-order algorithm (2.2) of Lebedev & Panov (1989), as printed.

The last term of (2.2), ``−64/45 (1 − p2·p3) p2 × p3``, carries a dot product.
Regular precession has ``|ω|`` constant, which hides errors of dot-product terms,
so :func:`dot_term_study` measures the local-error exponents on the tumbling
motion (:class:`strapdown.analysis.coning.local_error.TumblingMotion`,
:func:`strapdown.analysis.coning.order_study.local_error_exponents`) for
(2.2) at orders 2, 4 and 6, and for order 6 without the ``(p2·p3)`` part:
the printed form is the sixth-order one when its exponent is 7.

References
----------
Lebedev & Panov (1989), eq. (2.2).
"""

from __future__ import annotations

from typing import NamedTuple

from ....derivations.coning.algorithms import Algorithm
from ....derivations.coning.registry import get
from ..order_study import LocalErrorExponents, local_error_exponents

__all__ = ["DotTermStudy", "dot_term_study"]


class DotTermStudy(NamedTuple):
    """Local-error exponents of (2.2) at orders 2, 4, 6, and of order 6 without its dot-product term.

    Attributes
    ----------
    rows : tuple of LocalErrorExponents
        ``lebedev-panov-2``, ``-4``, ``-6`` and ``lebedev-panov-6 without (p2·p3) term``.
    """

    rows: tuple

    @property
    def printed(self) -> LocalErrorExponents:
        """(2.2) of order 6 as printed, with its dot-product term."""
        return self.rows[2]

    @property
    def without_dot(self) -> LocalErrorExponents:
        """(2.2) of order 6 without the ``(p2·p3)`` part of its last term."""
        return self.rows[3]

    @property
    def printed_is_sixth_order(self) -> bool:
        """True when the printed form has a local error O(H⁷): the order the paper states."""
        return self.printed.accuracy_order == 6

def dot_term_study(**kwargs) -> DotTermStudy:
    """Local-error exponents of (2.2) at orders 2, 4, 6, and of order 6 without its dot-product term.

    The last term of (2.2), ``−64/45 (1 − p2·p3) p2 × p3``, carries a dot
    product; removing its ``(p2·p3)`` part tests whether the printed form is
    the sixth-order one.

    Parameters
    ----------
    **kwargs
        Passed to :func:`local_error_exponents` (``motion``, ``times``, ``steps``).

    Returns
    -------
    DotTermStudy

    References
    ----------
    Lebedev & Panov (1989), eq. (2.2).
    """
    printed = get("lebedev-panov-6")
    no_dot = Algorithm("lebedev-panov-6 without (p2·p3) term", 4, tuple(t for t in printed.terms if not t.dots))
    return DotTermStudy(tuple(local_error_exponents(alg, **kwargs) for alg in (get("lebedev-panov-2"), get("lebedev-panov-4"), printed, no_dot)))
