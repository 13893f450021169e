"""Dual numbers ``x + s x°`` (``s² = 0``) as a numpy-compatible array type.

A :class:`Dual` holds a real part and a dual part of the same shape.  numpy
ufuncs and the array functions used by this package (``stack``, ``where``,
``sum``, …) act on it through ``__array_ufunc__`` / ``__array_function__``, so a
routine written with ordinary numpy operations evaluates its own *dual
extension* when handed a :class:`Dual`:

``f(x + s x°) = f(x) + s f'(x) x°``            (transfer principle)

This is how the package obtains velocity (sculling) algorithms from attitude
(coning) ones, the biquaternion map (1.12) of Lebedev & Panov (1989) from the
real rotation-vector map, and the dual regular precession (4.2)–(4.7) from the
real one: by evaluation, never by a second hand-written formula.

Examples
--------
>>> import numpy as np
>>> x = Dual(0.5, 1.0)
>>> y = np.sin(x) * x
>>> bool(np.isclose(y.du, np.cos(0.5) * 0.5 + np.sin(0.5)))   # d/dx (x sin x)
True
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["Dual", "dual_extend", "real_part", "dual_part", "is_dual"]


def _re(x):
    return x.re if isinstance(x, Dual) else x


def _du(x):
    return x.du if isinstance(x, Dual) else 0.0


class Dual(np.lib.mixins.NDArrayOperatorsMixin):
    """Array of dual numbers ``re + s du`` with ``s² = 0``.

    Parts are float arrays (complex parts are kept, which lets tests take a
    complex-step derivative through dual code).

    Parameters
    ----------
    re : array_like
        Real part.
    du : array_like, optional
        Dual part, broadcast against ``re``; zero if omitted.
    """

    __slots__ = ("re", "du")
    __array_priority__ = 100

    def __init__(self, re, du=None):
        re = np.asarray(re)
        re = re.astype(np.result_type(re.dtype, float), copy=False)
        du = np.zeros_like(re) if du is None else np.asarray(du)
        du = du.astype(np.result_type(du.dtype, float), copy=False)
        if re.shape != du.shape:
            re, du = np.broadcast_arrays(re, du)
            re, du = re.copy(), du.copy()
        self.re = re
        self.du = du

    # ------------------------------------------------------------ container
    @property
    def shape(self):
        return self.re.shape

    @property
    def ndim(self):
        return self.re.ndim

    def __len__(self):
        return len(self.re)

    def __getitem__(self, index):
        return Dual(self.re[index], self.du[index])

    def __repr__(self):
        return f"Dual(re={self.re!r}, du={self.du!r})"

    def __iter__(self):
        for a, b in zip(self.re, self.du):
            yield Dual(a, b)

    # Comparisons look at the real part only (branch selection in series code).
    def __lt__(self, other):
        return self.re < _re(other)

    def __le__(self, other):
        return self.re <= _re(other)

    def __gt__(self, other):
        return self.re > _re(other)

    def __ge__(self, other):
        return self.re >= _re(other)

    # ------------------------------------------------------------ numpy protocol
    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        if method != "__call__" or kwargs.get("out") is not None:
            return NotImplemented
        rule = _UFUNC_RULES.get(ufunc)
        if rule is None:
            return NotImplemented
        return rule(*inputs)

    def __array_function__(self, func, types, args, kwargs):
        rule = _FUNCTION_RULES.get(func)
        if rule is None:
            return NotImplemented
        return rule(*args, **kwargs)


def is_dual(x) -> bool:
    """True when ``x`` is a :class:`Dual`.

    Parameters
    ----------
    x : object
        Anything.

    Returns
    -------
    bool
    """
    return isinstance(x, Dual)


def real_part(x):
    """Real part of ``x`` (``x`` itself when it is not dual).

    Parameters
    ----------
    x : Dual or array_like
        A dual or real value.

    Returns
    -------
    ndarray or scalar
    """
    return _re(x)


def dual_part(x):
    """Dual part of ``x`` (zeros when it is not dual).

    Parameters
    ----------
    x : Dual or array_like
        A dual or real value.

    Returns
    -------
    ndarray
    """
    return x.du if isinstance(x, Dual) else np.zeros_like(np.asarray(x, dtype=float))


def dual_extend(f: Callable, df: Callable) -> Callable:
    """Dual extension of an elementwise function with known derivative.

    Parameters
    ----------
    f, df : callable
        The real function and its derivative, both elementwise.

    Returns
    -------
    callable
        ``g`` with ``g(x) = f(x)`` for real ``x`` and
        ``g(x + s x°) = f(x) + s f'(x) x°`` for :class:`Dual` ``x``.

    Examples
    --------
    >>> cube = dual_extend(lambda x: x**3, lambda x: 3 * x**2)
    >>> float(cube(Dual(2.0, 1.0)).du)
    12.0
    """

    def g(x):
        if isinstance(x, Dual):
            return Dual(f(x.re), df(x.re) * x.du)
        return f(x)

    g.__name__ = getattr(f, "__name__", "dual_extension")
    return g


# ---------------------------------------------------------------- ufunc rules
def _add(a, b):
    return Dual(_re(a) + _re(b), _du(a) + _du(b))


def _sub(a, b):
    return Dual(_re(a) - _re(b), _du(a) - _du(b))


def _mul(a, b):
    return Dual(_re(a) * _re(b), _re(a) * _du(b) + _du(a) * _re(b))


def _div(a, b):
    rb = _re(b)
    return Dual(_re(a) / rb, (_du(a) * rb - _re(a) * _du(b)) / (rb * rb))


def _unary(f, df):
    def rule(a):
        return Dual(f(a.re), df(a.re) * a.du)

    return rule


def _power(a, b):
    if isinstance(b, Dual):
        raise TypeError("Dual exponents are not supported; use exp/log")
    ra = _re(a)
    return Dual(ra**b, b * ra ** (b - 1) * _du(a))


def _arctan2(y, x):
    ry, rx = _re(y), _re(x)
    r2 = rx * rx + ry * ry
    return Dual(np.arctan2(ry, rx), (rx * _du(y) - ry * _du(x)) / r2)


def _hypot(a, b):
    ra, rb = _re(a), _re(b)
    h = np.hypot(ra, rb)
    return Dual(h, (ra * _du(a) + rb * _du(b)) / h)


_UFUNC_RULES = {
    np.add: _add,
    np.subtract: _sub,
    np.multiply: _mul,
    np.true_divide: _div,
    np.negative: lambda a: Dual(-a.re, -a.du),
    np.positive: lambda a: Dual(a.re, a.du),
    np.power: _power,
    np.square: lambda a: Dual(a.re * a.re, 2.0 * a.re * a.du),
    np.sqrt: _unary(np.sqrt, lambda x: 0.5 / np.sqrt(x)),
    np.sin: _unary(np.sin, np.cos),
    np.cos: _unary(np.cos, lambda x: -np.sin(x)),
    np.tan: _unary(np.tan, lambda x: 1.0 / np.cos(x) ** 2),
    np.arctan: _unary(np.arctan, lambda x: 1.0 / (1.0 + x * x)),
    np.arcsin: _unary(np.arcsin, lambda x: 1.0 / np.sqrt(1.0 - x * x)),
    np.arccos: _unary(np.arccos, lambda x: -1.0 / np.sqrt(1.0 - x * x)),
    np.exp: _unary(np.exp, np.exp),
    np.log: _unary(np.log, lambda x: 1.0 / x),
    np.arctan2: _arctan2,
    np.hypot: _hypot,
    np.isfinite: lambda a: np.isfinite(a.re) & np.isfinite(a.du),
}


# ---------------------------------------------------------------- function rules
def _as_dual(x):
    return x if isinstance(x, Dual) else Dual(x)


def _stack(arrays, axis=0, **kw):
    arrays = [_as_dual(a) for a in arrays]
    return Dual(np.stack([a.re for a in arrays], axis=axis), np.stack([a.du for a in arrays], axis=axis))


def _concatenate(arrays, axis=0, **kw):
    arrays = [_as_dual(a) for a in arrays]
    return Dual(np.concatenate([a.re for a in arrays], axis=axis), np.concatenate([a.du for a in arrays], axis=axis))


def _where(cond, a, b):
    cond = _re(cond)
    return Dual(np.where(cond, _re(a), _re(b)), np.where(cond, _du(a), _du(b)))


def _sum(a, axis=None, keepdims=False, **kw):
    return Dual(np.sum(a.re, axis=axis, keepdims=keepdims), np.sum(a.du, axis=axis, keepdims=keepdims))


def _broadcast_to(a, shape, **kw):
    a = _as_dual(a)
    return Dual(np.broadcast_to(a.re, shape), np.broadcast_to(a.du, shape))


def _expand_dims(a, axis):
    return Dual(np.expand_dims(a.re, axis), np.expand_dims(a.du, axis))


def _moveaxis(a, source, destination):
    return Dual(np.moveaxis(a.re, source, destination), np.moveaxis(a.du, source, destination))


def _zeros_like(a, **kw):
    return Dual(np.zeros_like(a.re), np.zeros_like(a.du))


def _ones_like(a, **kw):
    return Dual(np.ones_like(a.re), np.zeros_like(a.du))


def _cumsum(a, axis=None, **kw):
    return Dual(np.cumsum(a.re, axis=axis), np.cumsum(a.du, axis=axis))


def _reshape(a, shape, **kw):
    return Dual(np.reshape(a.re, shape), np.reshape(a.du, shape))


_FUNCTION_RULES = {
    np.stack: _stack,
    np.concatenate: _concatenate,
    np.where: _where,
    np.sum: _sum,
    np.broadcast_to: _broadcast_to,
    np.expand_dims: _expand_dims,
    np.moveaxis: _moveaxis,
    np.zeros_like: _zeros_like,
    np.ones_like: _ones_like,
    np.cumsum: _cumsum,
    np.reshape: _reshape,
}

