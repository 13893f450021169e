"""The time-stepping recursion of one corrected stage: compiled, and a plain Python reference.

One step of length h of (1.5)/(2.1) of Plotnikov (1999) is a symmetric
(Strang) splitting:

1. half a step of the correction flow ``v' = ½(k(m − c v) + y)``,
   ``y' = l(m − c v)`` on each corrected component (linear with constant
   coefficients on the step, integrated exactly: :func:`correction_map`);
2. half a step of the norm flow ``ν' = ½ρ(1 − |ν|²)ν`` (closed form);
3. the kinematic flow over h: ``ν ← ν ∘ Δq``, or with the kinematic term of the
   first variant ``ν ← μ_{n+1} + (ν − μ_n) ∘ Δq``;
4. and 2., 1. again (the second correction half with the reference at the end
   of the step).

The scheme is second order in h.  At a change of the gain schedule the
integral state y is carried (``"carry"``), rescaled with the integral gain
(``"rescale"``: the reading ``l(t) ∫(μ⁺ − cν) dτ``), or shifted so that the
whole correction ``k(m − cν) + y`` is continuous (``"bumpless"``).

:func:`stage_loop` is compiled with numba (cached on disk, so the compile cost
is paid once per installation); :func:`stage_loop_python` is the same
recursion written as a plain loop over Python floats, kept as the reference
that the tests compare the compiled loop against.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.linalg import expm

__all__ = ["SWITCH_MODES", "correction_map", "stage_loop", "stage_loop_python"]

#: How the integral state crosses a change of the gain schedule (module docstring).
SWITCH_MODES = ("carry", "rescale", "bumpless")


def correction_map(k: float, l: float, c: float, tau: float) -> np.ndarray:
    """Exact flow over ``tau`` of ``v' = ½(k(m − cv) + y)``, ``y' = l(m − cv)`` with m frozen.

    Parameters
    ----------
    k : float
        Position gain [1/s].
    l : float
        Integral gain [1/s²].
    c : float
        Factor c of (1.5) [-].
    tau : float
        Time span [s].

    Returns
    -------
    ndarray, shape (6,)
        ``(e11, e12, e21, e22, f1, f2)``: ``v ← e11 v + e12 y + f1 m``,
        ``y ← e21 v + e22 y + f2 m``.

    References
    ----------
    Plotnikov (1999), eq. (1.5).

    Examples
    --------
    >>> correction_map(0.0, 0.0, 1.0, 0.5).tolist()
    [1.0, 0.25, 0.0, 1.0, 0.0, 0.0]
    """
    return np.array(_correction_map(float(k), float(l), float(c), float(tau)))


@lru_cache(maxsize=256)
def _correction_map(k, l, c, tau):
    a = np.array([[-0.5 * k * c, 0.5, 0.5 * k], [-l * c, 0.0, l], [0.0, 0.0, 0.0]])
    e = expm(a * tau)
    return (e[0, 0], e[0, 1], e[1, 0], e[1, 1], e[0, 2], e[1, 2])


def _stage_loop(nu0, dq, ref_start, ref_end, mask, kinematic, seg_start, maps, gains, switch, c, rho, step):
    n_steps = dq.shape[0]
    nu = np.empty((n_steps + 1, 4))
    ys = np.empty((n_steps + 1, 4))
    v = np.empty(4)
    y = np.zeros(4)
    for j in range(4):
        v[j] = nu0[j]
        nu[0, j] = v[j]
        ys[0, j] = 0.0
    grow = math.exp(rho * step * 0.5)
    norm_flow = rho > 0.0
    for s in range(maps.shape[0]):
        i0 = seg_start[s]
        i1 = seg_start[s + 1]
        if s > 0 and i0 < n_steps:
            if switch == 1:
                ratio = gains[s, 1] / gains[s - 1, 1]
                for j in range(4):
                    if mask[j]:
                        y[j] *= ratio
            elif switch == 2:
                dk = gains[s - 1, 0] - gains[s, 0]
                for j in range(4):
                    if mask[j]:
                        y[j] += dk * (ref_start[i0, j] - c * v[j])
        e11, e12, e21, e22, f1, f2 = maps[s, 0], maps[s, 1], maps[s, 2], maps[s, 3], maps[s, 4], maps[s, 5]
        for n in range(i0, i1):
            for j in range(4):
                if mask[j]:
                    vj, yj, mj = v[j], y[j], ref_start[n, j]
                    v[j] = e11 * vj + e12 * yj + f1 * mj
                    y[j] = e21 * vj + e22 * yj + f2 * mj
            a0, a1, a2, a3 = v[0], v[1], v[2], v[3]
            if norm_flow:
                r = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3
                f = math.sqrt(grow / (1.0 - r + r * grow))
                a0, a1, a2, a3 = a0 * f, a1 * f, a2 * f, a3 * f
            if kinematic:
                a0, a1, a2, a3 = a0 - ref_start[n, 0], a1 - ref_start[n, 1], a2 - ref_start[n, 2], a3 - ref_start[n, 3]
            b0, b1, b2, b3 = dq[n, 0], dq[n, 1], dq[n, 2], dq[n, 3]
            c0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
            c1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
            c2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
            c3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0
            if kinematic:
                c0, c1, c2, c3 = c0 + ref_end[n, 0], c1 + ref_end[n, 1], c2 + ref_end[n, 2], c3 + ref_end[n, 3]
            if norm_flow:
                r = c0 * c0 + c1 * c1 + c2 * c2 + c3 * c3
                f = math.sqrt(grow / (1.0 - r + r * grow))
                c0, c1, c2, c3 = c0 * f, c1 * f, c2 * f, c3 * f
            v[0], v[1], v[2], v[3] = c0, c1, c2, c3
            for j in range(4):
                if mask[j]:
                    vj, yj, mj = v[j], y[j], ref_end[n, j]
                    v[j] = e11 * vj + e12 * yj + f1 * mj
                    y[j] = e21 * vj + e22 * yj + f2 * mj
            for j in range(4):
                nu[n + 1, j] = v[j]
                ys[n + 1, j] = y[j]
    return nu, ys


_compiled = []


def _kernel():
    """The compiled recursion (numba is imported on first use; the machine code is cached on disk)."""
    if not _compiled:
        import numba

        _compiled.append(numba.njit(cache=True, nogil=True)(_stage_loop))
    return _compiled[0]


def stage_loop(nu0, dq, ref_start, ref_end, mask, kinematic, seg_start, maps, gains, switch, c, rho, step):
    """Run the splitting recursion of one stage (compiled with numba).

    Parameters
    ----------
    nu0 : ndarray, shape (4,)
        ν(t0).
    dq : ndarray, shape (N, 4)
        Unit quaternion increments of the input frame over each step.
    ref_start, ref_end : ndarray, shape (N, 4)
        Reference quaternion m used by the first and the second correction
        half of each step (μ at t_n and t_{n+1} for the first variant; the
        accelerometer quaternion of the step, twice, otherwise).
    mask : ndarray of bool, shape (4,)
        Corrected components.
    kinematic : bool
        Include the kinematic term ``μ⁺ ∘ (ω_μ − ω_x)`` of (1.5) (first variant).
    seg_start : ndarray of int64, shape (S+1,)
        First step of each gain segment, and N.
    maps : ndarray, shape (S, 6)
        :func:`correction_map` of each segment over h/2.
    gains : ndarray, shape (S, 2)
        (k [1/s], l [1/s²]) of each segment.
    switch : int
        Index in :data:`SWITCH_MODES`.
    c : float
        Factor c of (1.5).
    rho : float
        Norm-keeping gain ρ [1/s].
    step : float
        Step H [s] of the stage recursion (one sensor sample per step: H = h).

    Returns
    -------
    nu, y : ndarray, shape (N+1, 4)
        ν and the integral state at the grid points.

    References
    ----------
    Plotnikov (1999), eqs. (1.5), (2.1).
    """
    return _kernel()(nu0, dq, ref_start, ref_end, mask, bool(kinematic), seg_start, maps, gains, int(switch), float(c), float(rho), float(step))


def stage_loop_python(nu0, dq, ref_start, ref_end, mask, kinematic, seg_start, maps, gains, switch, c, rho, step):
    """The recursion of :func:`stage_loop` as a plain loop over Python floats (the reference).

    Parameters
    ----------
    nu0, dq, ref_start, ref_end, mask, kinematic, seg_start, maps, gains, switch, c, rho, step
        As for :func:`stage_loop`.

    Returns
    -------
    nu, y : ndarray, shape (N+1, 4)
    """
    dq = np.asarray(dq, dtype=float).tolist()
    ra = np.asarray(ref_start, dtype=float).tolist()
    rb = np.asarray(ref_end, dtype=float).tolist()
    comps = [j for j in range(4) if mask[j]]
    v = [float(x) for x in nu0]
    y = [0.0, 0.0, 0.0, 0.0]
    out_v, out_y = [tuple(v)], [tuple(y)]
    grow = math.exp(rho * step * 0.5)
    sqrt = math.sqrt
    n_steps = len(dq)
    for s in range(len(maps)):
        i0, i1 = int(seg_start[s]), int(seg_start[s + 1])
        if s > 0 and i0 < n_steps:
            if switch == 1:
                ratio = gains[s][1] / gains[s - 1][1]
                for j in comps:
                    y[j] *= ratio
            elif switch == 2:
                dk = gains[s - 1][0] - gains[s][0]
                for j in comps:
                    y[j] += dk * (ra[i0][j] - c * v[j])
        e11, e12, e21, e22, f1, f2 = (float(x) for x in maps[s])
        for n in range(i0, i1):
            m = ra[n]
            for j in comps:
                vj, yj = v[j], y[j]
                v[j] = e11 * vj + e12 * yj + f1 * m[j]
                y[j] = e21 * vj + e22 * yj + f2 * m[j]
            a0, a1, a2, a3 = v
            if rho > 0.0:
                r = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3
                f = sqrt(grow / (1.0 - r + r * grow))
                a0, a1, a2, a3 = a0 * f, a1 * f, a2 * f, a3 * f
            if kinematic:
                a0, a1, a2, a3 = a0 - m[0], a1 - m[1], a2 - m[2], a3 - m[3]
            b0, b1, b2, b3 = dq[n]
            c0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
            c1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
            c2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
            c3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0
            q = rb[n]
            if kinematic:
                c0, c1, c2, c3 = c0 + q[0], c1 + q[1], c2 + q[2], c3 + q[3]
            if rho > 0.0:
                r = c0 * c0 + c1 * c1 + c2 * c2 + c3 * c3
                f = sqrt(grow / (1.0 - r + r * grow))
                c0, c1, c2, c3 = c0 * f, c1 * f, c2 * f, c3 * f
            v = [c0, c1, c2, c3]
            for j in comps:
                vj, yj = v[j], y[j]
                v[j] = e11 * vj + e12 * yj + f1 * q[j]
                y[j] = e21 * vj + e22 * yj + f2 * q[j]
            out_v.append(tuple(v))
            out_y.append(tuple(y))
    return np.array(out_v), np.array(out_y)
