"""Run SymPy with a fixed seed for its internal random choices.

SymPy's multivariate factorisation (Wang's algorithm, used by ``factor`` and,
through it, by ``simplify``) draws random evaluation points from
``sympy.core.random.rng``.  The result is canonical either way, but the run
time is not: an unlucky draw can take minutes.  Derivations run under
:func:`reproducible`, which seeds that generator and restores its state
afterwards, so each derivation takes the same path, and the same time, on
every run.
"""

from __future__ import annotations

import functools
from contextlib import contextmanager

from sympy.core import random as _sympy_random

__all__ = ["reproducible", "reproducible_sympy"]

SEED = 20261122


@contextmanager
def reproducible(seed: int = SEED):
    """Context in which SymPy's internal generator is seeded with ``seed`` (state restored on exit).

    Parameters
    ----------
    seed : int
        Seed of ``sympy.core.random.rng`` inside the block.

    Yields
    ------
    None

    Examples
    --------
    >>> from sympy.core.random import rng
    >>> with reproducible():
    ...     a = rng.random()
    >>> with reproducible():
    ...     b = rng.random()
    >>> a == b
    True
    """
    state = _sympy_random.rng.getstate()
    _sympy_random.rng.seed(seed)
    try:
        yield
    finally:
        _sympy_random.rng.setstate(state)


def reproducible_sympy(func):
    """Decorator: run ``func`` under :func:`reproducible`.

    Parameters
    ----------
    func : callable
        A derivation.

    Returns
    -------
    callable
        ``func`` wrapped, with the same name and docstring.
    """

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        with reproducible():
            return func(*args, **kwargs)

    return wrapper
