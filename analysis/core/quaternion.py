"""Quaternion algebra on ``(..., 4)`` arrays, scalar first, Hamilton product.

Every routine is written with plain numpy operations, so it accepts
:class:`strapdown.analysis.core.dual.Dual` arrays as well: a dual quaternion argument is a
biquaternion ``Λ + s M`` and the result is the biquaternion result (transfer
principle).  In particular :func:`rotvec_to_quat` applied to a dual vector
``Φ = φ + s φ°`` *is* the map (1.12) of Lebedev & Panov (1989).

Examples
--------
>>> import numpy as np
>>> q = rotvec_to_quat([0.0, 0.0, np.pi / 2])
>>> np.round(rotate(q, [1.0, 0.0, 0.0]), 12) + 0.0
array([0., 1., 0.])
"""

from __future__ import annotations

import numpy as np

from . import blocks
from .dual import Dual
from .validation import as_quaternion, as_vector

__all__ = [
    "multiply",
    "multiply_parts",
    "conjugate",
    "norm",
    "normalize",
    "rotate",
    "vector_to_quat",
    "vect",
    "rotvec_to_quat",
    "quat_to_rotvec",
    "cross",
    "dot",
    "identity",
    "SERIES_ANGLE",
]

#: Below this angle [rad] :func:`rotvec_to_quat` and :func:`quat_to_rotvec` use their series
#: branches; their truncation error there is below 1e-24 relative, far under round-off.
SERIES_ANGLE = 1e-2
_SMALL = SERIES_ANGLE


def _arr(x):
    if isinstance(x, Dual):
        return x
    x = np.asarray(x)
    return x if np.issubdtype(x.dtype, np.inexact) else x.astype(float)


def _blocks(a, b, a_width: int, b_width: int):
    """``(a, b, lead, slices)`` for a product of large float arrays evaluated block by block, or None.

    ``a`` and ``b`` are broadcast against each other over their leading axes
    (views, no copies) to the leading shape ``lead``; the slices cut its first axis into blocks of
    about :data:`~strapdown.analysis.core.blocks.BLOCK` elements.  Each element of a product depends on the
    same elements of its inputs only, so the blocks give the values of the
    whole-array expression bit for bit.  None (the whole-array form) for dual
    numbers, other dtypes, other widths, shapes that do not broadcast, and
    arrays small enough for the cache.
    """
    if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray) and a.dtype == np.float64 and b.dtype == np.float64):
        return None
    if a.size <= a_width * blocks.BLOCK and b.size <= b_width * blocks.BLOCK:  # small inputs (checked first: the common call is small)
        return None
    if a.ndim < 1 or b.ndim < 1 or a.shape[-1] != a_width or b.shape[-1] != b_width:
        return None
    try:
        lead = np.broadcast_shapes(a.shape[:-1], b.shape[:-1])
    except ValueError:
        return None
    slices = blocks.row_slices(lead)
    if slices is None:
        return None
    return np.broadcast_to(a, lead + (a_width,)), np.broadcast_to(b, lead + (b_width,)), lead, slices


def multiply_parts(a, b):
    """Hamilton product of quaternions given as 4-tuples of components.

    The structure-of-arrays form of :func:`multiply` (the one place the product
    is written out), for hot paths that keep ``(q0, q1, q2, q3)`` as separate
    arrays.

    Parameters
    ----------
    a, b : tuple of 4 array_like
        Components ``(q0, q1, q2, q3)`` of the left and right factors (real or
        :class:`~strapdown.analysis.core.dual.Dual`, broadcasting).

    Returns
    -------
    tuple of 4 arrays
        Components of ``a ∘ b``.

    References
    ----------
    Lebedev & Panov (1989), section 1 (quaternion product).
    """
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def multiply(a, b):
    """Hamilton product ``a ∘ b`` of ``(..., 4)`` quaternions (broadcasting).

    Parameters
    ----------
    a, b : array_like, shape (..., 4)
        Left and right factors, scalar first (real or dual).

    Returns
    -------
    ndarray or Dual, shape (..., 4)

    Examples
    --------
    >>> multiply([0, 1, 0, 0], [0, 0, 1, 0])   # i * j = k
    array([0., 0., 0., 1.])
    """
    a, b = _arr(a), _arr(b)
    blocked = _blocks(a, b, 4, 4)
    if blocked is not None:  # large arrays: the same products, block by block
        a, b, lead, slices = blocked
        out = np.empty(lead + (4,))
        for s in slices:
            x, y, o = a[s], b[s], out[s]
            for i, part in enumerate(multiply_parts(tuple(x[..., i] for i in range(4)), tuple(y[..., i] for i in range(4)))):
                o[..., i] = part
        return out
    parts = multiply_parts(tuple(a[..., i] for i in range(4)), tuple(b[..., i] for i in range(4)))
    return np.stack(parts, axis=-1)


def conjugate(q):
    """Conjugate ``q̄ = (q0, -q1, -q2, -q3)``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternion(s), scalar first.

    Returns
    -------
    ndarray or Dual, shape (..., 4)
    """
    q = _arr(q)
    return np.stack([q[..., 0], -q[..., 1], -q[..., 2], -q[..., 3]], axis=-1)


def norm(q):
    """Euclidean norm over the last axis.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternion(s).

    Returns
    -------
    ndarray or Dual, shape (...)
    """
    q = _arr(q)
    return np.sqrt(np.sum(q * q, axis=-1))


def normalize(q, name: str = "q"):
    """Return ``q / |q|``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Nonzero quaternion(s).
    name : str
        Argument name for error messages.

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternion(s).

    Raises
    ------
    ValueError
        For a zero quaternion, or one that is not finite or not of shape (..., 4).
    """
    q = as_quaternion(q, name)
    n = np.linalg.norm(q, axis=-1, keepdims=True)
    if np.any(n == 0):
        raise ValueError(f"Expected `{name}` to be a nonzero quaternion, got a zero quaternion")
    return q / n


def identity(shape=()):
    """Identity quaternions of the given batch shape.

    Parameters
    ----------
    shape : int or tuple of int
        Batch shape (``()`` for one quaternion).

    Returns
    -------
    ndarray, shape ``(*shape, 4)``
        ``(1, 0, 0, 0)`` everywhere.
    """
    q = np.zeros(tuple(np.atleast_1d(shape)) + (4,) if shape != () else (4,))
    q[..., 0] = 1.0
    return q


def vector_to_quat(v):
    """Pure quaternion ``{0, v}`` from a ``(..., 3)`` vector.

    Parameters
    ----------
    v : array_like, shape (..., 3)
        Vector(s) (real or dual).

    Returns
    -------
    ndarray or Dual, shape (..., 4)
    """
    v = _arr(v)
    return np.stack([v[..., 0] * 0.0, v[..., 0], v[..., 1], v[..., 2]], axis=-1)


def vect(q):
    """Vector part of ``(..., 4)`` quaternions.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Quaternion(s).

    Returns
    -------
    ndarray or Dual, shape (..., 3)
    """
    return _arr(q)[..., 1:]


def rotate(q, v):
    """Rotate vectors: ``vect(q ∘ {0, v} ∘ q̄)``; maps E to I when ``q = Λ``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternion(s).
    v : array_like, shape (..., 3)
        Vector(s), broadcast against ``q``.

    Returns
    -------
    ndarray or Dual, shape (..., 3)
        The rotated vector(s).

    References
    ----------
    Lebedev & Panov (1989), section 1 (``v_I = Λ ∘ v_E ∘ Λ̄``).
    """
    q, v = _arr(q), _arr(v)
    blocked = _blocks(q, v, 4, 3)
    if blocked is not None:  # large arrays: the same products, block by block
        q, v, lead, slices = blocked
        out = np.empty(lead + (3,))
        for s in slices:
            for i, part in enumerate(_rotate_parts(q[s], v[s])):
                out[s][..., i] = part
        return out
    return np.stack(_rotate_parts(q, v), axis=-1)


def _rotate_parts(q, v):
    """The three components of :func:`rotate` (arrays broadcast against each other)."""
    q0, q1, q2, q3 = (q[..., i] for i in range(4))
    v0, v1, v2 = v[..., 0], v[..., 1], v[..., 2]
    # the products of multiply(multiply(q, vector_to_quat(v)), conjugate(q)), component by component
    w0, w1, w2, w3 = multiply_parts((q0, q1, q2, q3), (v0 * 0.0, v0, v1, v2))
    c1, c2, c3 = -q1, -q2, -q3
    return (
        w0 * c1 + w1 * q0 + w2 * c3 - w3 * c2,
        w0 * c2 - w1 * c3 + w2 * q0 + w3 * c1,
        w0 * c3 + w1 * c2 - w2 * c1 + w3 * q0,
    )


def cross(a, b):
    """Cross product of ``(..., 3)`` vectors (real or dual).

    Parameters
    ----------
    a, b : array_like, shape (..., 3)
        Left and right factors (broadcasting).

    Returns
    -------
    ndarray or Dual, shape (..., 3)
    """
    if isinstance(a, Dual) or isinstance(b, Dual):
        a, b = _arr(a), _arr(b)
        a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
        b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
        return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)
    return np.cross(a, b)


def dot(a, b):
    """Dot product over the last axis (real or dual).

    Parameters
    ----------
    a, b : array_like, shape (..., n)
        Factors (broadcasting).

    Returns
    -------
    ndarray or Dual, shape (...)
    """
    return np.sum(_arr(a) * _arr(b), axis=-1)


def rotvec_to_quat(phi, *, validate: bool = True):
    """Unit quaternion of the rotation vector ``φ``: ``(cos(|φ|/2), sin(|φ|/2) φ/|φ|)``.

    Near zero angle the even series of ``cos(θ/2)`` and ``sin(θ/2)/θ`` in ``θ²``
    are used, so that ``|φ| = 1e-300`` and ``1e-8`` are exact to machine
    precision and the dual extension has no ``0/0``.  For a dual vector
    ``Φ = φ + s φ°`` the result is the unit biquaternion ``Λ + s M`` of
    Lebedev & Panov (1989), eq. (1.12), obtained as the dual extension of this
    real map.

    Parameters
    ----------
    phi : array_like or Dual, shape (..., 3)
        Rotation vector(s) [rad].
    validate : bool, keyword-only
        Check shape and finiteness of real input.

    Returns
    -------
    ndarray or Dual, shape (..., 4)

    Raises
    ------
    ValueError
        If ``phi`` is not ``(..., 3)`` or not finite.
    """
    if not isinstance(phi, Dual) and validate:
        phi = as_vector(phi, "phi")
    phi = _arr(phi)
    theta2 = np.sum(phi * phi, axis=-1)
    small = theta2 < _SMALL * _SMALL
    # Safe argument for the closed form where the series branch is taken.
    theta = np.sqrt(np.where(small, 1.0, theta2))
    half = theta * 0.5
    c_big = np.cos(half)
    s_big = np.sin(half) / theta
    x2 = theta2 * 0.25  # (θ/2)²
    c_small = 1.0 - x2 / 2.0 + x2 * x2 / 24.0 - x2 * x2 * x2 / 720.0
    s_small = 0.5 * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
    c = np.where(small, c_small, c_big)
    s = np.where(small, s_small, s_big)
    return np.stack([c, s * phi[..., 0], s * phi[..., 1], s * phi[..., 2]], axis=-1)


def quat_to_rotvec(q, *, canonical: bool = False, validate: bool = True):
    """Rotation vector of a unit quaternion, inverse of :func:`rotvec_to_quat`.

    Parameters
    ----------
    q : array_like or Dual, shape (..., 4)
        Unit quaternion(s).
    canonical : bool, keyword-only
        If False (default) the angle ``2 atan2(|vect q|, q0)`` lies in
        ``[0, 2π]``, so the map inverts :func:`rotvec_to_quat` for every
        ``|φ| < 2π``.  If True, ``q`` and ``-q`` are identified and the
        shortest rotation vector (``|φ| ≤ π``) is returned.
    validate : bool, keyword-only
        Check shape, finiteness and unit norm (to 1e-6) of real input.

    Returns
    -------
    ndarray or Dual, shape (..., 3)
    """
    if not isinstance(q, Dual) and validate:
        q = as_quaternion(q, "q", unit=True, atol=1e-6)
    q = _arr(q)
    if canonical:
        flip = q[..., 0] < 0
        sign = np.where(flip, -1.0, 1.0)
        q = q * (sign[..., None] if not isinstance(sign, Dual) else sign)
    q0 = q[..., 0]
    v = q[..., 1:]
    s2 = np.sum(v * v, axis=-1)
    q0_safe = np.where(q0 > 0, q0, 1.0)
    r2 = s2 / (q0_safe * q0_safe)
    small = (q0 > 0) & (r2 < _SMALL * _SMALL)
    # atan(r)/r = 1 - r²/3 + r⁴/5 - r⁶/7 + r⁸/9
    f_small = (2.0 / q0_safe) * (1.0 - r2 / 3.0 + r2 * r2 / 5.0 - r2 * r2 * r2 / 7.0 + r2 * r2 * r2 * r2 / 9.0)
    s = np.sqrt(np.where(small, 1.0, s2))
    f_big = 2.0 * np.arctan2(s, q0) / s
    f = np.where(small, f_small, f_big)
    return np.stack([f * v[..., 0], f * v[..., 1], f * v[..., 2]], axis=-1)
