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

:func:`cascade_loop` runs a whole cascade (2.1)–(2.6) in one compiled pass:
the stages step in lockstep, stage j+1 fed at each step with the frame that
stage j has just modelled, and the composite, its Krylov angles, their errors
and the peak errors are formed on the way, so that a Monte Carlo trial needs
no array per stage.  It performs the operations of the vectorised cascade
:func:`strapdown.analysis.multistage.stages.run_multistage` (engine "python",
the reference it is tested against) step by step.  When only the peaks are
kept, an angle error is not evaluated (no inverse trigonometric function) at
a step where a bound shows it :data:`BOUND_MARGIN` below its running peak:
with the matrix (1.7) of the estimate and of the true attitude, the sine and
cosine of a yaw or roll difference are the cross and dot products of two
plane vectors over their lengths, those of the pitch difference follow from
``sin θ = a12``; an angle with ``cos e > 0`` is at most q if
``sin² e <= q²(1 − q²/3) <= sin² q``, and the tilt ``√(e1² + e2²)`` is at most
``√(tan² e1 + tan² e2)``.  Such a step cannot change a peak, so the peaks are
those of the full evaluation (tested bit for bit).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.linalg import expm

from ..core.quaternion import SERIES_ANGLE as _SERIES

__all__ = ["SWITCH_MODES", "KINDS", "BOUND_MARGIN", "correction_map", "stage_loop", "stage_loop_python", "cascade_loop", "bound_terms"]

#: How the integral state crosses a change of the gain schedule (module docstring).
SWITCH_MODES = ("carry", "rescale", "bumpless")
#: How a stage of :func:`cascade_loop` forms its reference m (index = code): the
#: external attitude (with the kinematic term), the pure quaternion (1.4), the tilt quaternion (1.10).
KINDS = ("external", "pure", "tilt")
#: How far below its running peak [rad] the bound of an angle error must lie for :func:`cascade_loop`
#: to skip evaluating it (far above round-off, and above any difference between ``truth`` and ``attitude``).
BOUND_MARGIN = 1e-9


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


def _flow(v, y, mask, mp, kinematic, norm_flow, grow, s0, s1, s2, s3, t0, t1, t2, t3, b0, b1, b2, b3):
    """One splitting step of a stage (in place): ``s``/``t`` the reference at the start/end, ``b`` the increment."""
    e11, e12, e21, e22, f1, f2 = mp[0], mp[1], mp[2], mp[3], mp[4], mp[5]
    k0, k1, k2, k3 = mask[0], mask[1], mask[2], mask[3]
    a0, y0 = _correct(k0, e11, e12, e21, e22, f1, f2, v[0], y[0], s0)
    a1, y1 = _correct(k1, e11, e12, e21, e22, f1, f2, v[1], y[1], s1)
    a2, y2 = _correct(k2, e11, e12, e21, e22, f1, f2, v[2], y[2], s2)
    a3, y3 = _correct(k3, e11, e12, e21, e22, f1, f2, v[3], y[3], s3)
    if norm_flow:
        a0, a1, a2, a3 = _renormalise(a0, a1, a2, a3, grow)
    if kinematic:
        a0, a1, a2, a3 = a0 - s0, a1 - s1, a2 - s2, a3 - s3
    c0, c1, c2, c3 = _qmul(a0, a1, a2, a3, b0, b1, b2, b3)
    if kinematic:
        c0, c1, c2, c3 = c0 + t0, c1 + t1, c2 + t2, c3 + t3
    if norm_flow:
        c0, c1, c2, c3 = _renormalise(c0, c1, c2, c3, grow)
    c0, y0 = _correct(k0, e11, e12, e21, e22, f1, f2, c0, y0, t0)
    c1, y1 = _correct(k1, e11, e12, e21, e22, f1, f2, c1, y1, t1)
    c2, y2 = _correct(k2, e11, e12, e21, e22, f1, f2, c2, y2, t2)
    c3, y3 = _correct(k3, e11, e12, e21, e22, f1, f2, c3, y3, t3)
    v[0], v[1], v[2], v[3] = c0, c1, c2, c3
    y[0], y[1], y[2], y[3] = y0, y1, y2, y3


def _correct(on, e11, e12, e21, e22, f1, f2, a, y, s):
    """Half a step of the correction of one component, ``(a, y) ← E (a, y) + F s`` (:func:`correction_map`), if ``on``."""
    if on:
        return e11 * a + e12 * y + f1 * s, e21 * a + e22 * y + f2 * s
    return a, y


def _renormalise(a0, a1, a2, a3, grow):
    """The norm flow of a step: the squared norm r goes to ``grow r / (1 − r + r grow)``."""
    r = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3
    f = math.sqrt(grow / (1.0 - r + r * grow))
    return a0 * f, a1 * f, a2 * f, a3 * f


def _switch(y, v, mask, gains, s, mode, c, m0, m1, m2, m3):
    """What the integral state does when segment ``s`` starts (in place), with m the reference there."""
    if mode == 1:
        ratio = gains[s, 1] / gains[s - 1, 1]
        for j in range(4):
            if mask[j]:
                y[j] *= ratio
    elif mode == 2:
        dk = gains[s - 1, 0] - gains[s, 0]
        for j in range(4):
            if mask[j]:
                mj = m0 if j == 0 else (m1 if j == 1 else (m2 if j == 2 else m3))
                y[j] += dk * (mj - c * v[j])


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
            _switch(y, v, mask, gains, s, switch, c, ref_start[i0, 0], ref_start[i0, 1], ref_start[i0, 2], ref_start[i0, 3])
        mp = maps[s]
        for n in range(i0, i1):
            s0, s1, s2, s3 = ref_start[n, 0], ref_start[n, 1], ref_start[n, 2], ref_start[n, 3]
            t0, t1, t2, t3 = ref_end[n, 0], ref_end[n, 1], ref_end[n, 2], ref_end[n, 3]
            _flow(v, y, mask, mp, kinematic, norm_flow, grow, s0, s1, s2, s3, t0, t1, t2, t3, dq[n, 0], dq[n, 1], dq[n, 2], dq[n, 3])
            for j in range(4):
                nu[n + 1, j] = v[j]
                ys[n + 1, j] = y[j]
    return nu, ys


_compiled: dict = {}

#: Functions the loops call, compiled (and swapped in for the Python ones) before the first loop.
_HELPERS = ("_flow", "_correct", "_renormalise", "_switch", "_rotvec_quat", "_tilt_quat", "_qmul", "_half_quat", "_matrix", "_clip1", "_limit", "_wrap", "_record")


def _jit(fn):
    """``fn`` compiled with numba (imported on first use; the machine code is cached on disk).

    The helpers are inlined into the loops at numba's IR level (``inline="always"``), which lets
    LLVM optimise across them (about a third faster than calls).
    """
    name = fn.__name__
    if name not in _compiled:
        import numba

        g = globals()
        for helper in _HELPERS:
            if not isinstance(g[helper], numba.core.registry.CPUDispatcher):
                g[helper] = numba.njit(cache=True, nogil=True, inline="always")(g[helper])
        _compiled[name] = numba.njit(cache=True, nogil=True)(fn)
    return _compiled[name]


def _kernel():
    """The compiled recursion of one stage."""
    return _jit(_stage_loop)


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


# ---------------------------------------------------------------------------
# The whole cascade in one pass
# ---------------------------------------------------------------------------
def _rotvec_quat(p0, p1, p2):
    """:func:`strapdown.analysis.core.quaternion.rotvec_to_quat` of one rotation vector [rad]."""
    theta2 = p0 * p0 + p1 * p1 + p2 * p2
    if theta2 < _SERIES * _SERIES:
        x2 = theta2 * 0.25
        c = 1.0 - x2 / 2.0 + x2 * x2 / 24.0 - x2 * x2 * x2 / 720.0
        s = 0.5 * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
    else:
        theta = math.sqrt(theta2)
        c = math.cos(theta * 0.5)
        s = math.sin(theta * 0.5) / theta
    return c, s * p0, s * p1, s * p2


def _half_quat(q0, q1, q2, q3):
    """Square root of a unit quaternion: half its canonical rotation vector, as a quaternion."""
    if q0 < 0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    s2 = q1 * q1 + q2 * q2 + q3 * q3
    q0_safe = q0 if q0 > 0 else 1.0
    r2 = s2 / (q0_safe * q0_safe)
    if q0 > 0 and r2 < _SERIES * _SERIES:
        f = (2.0 / q0_safe) * (1.0 - r2 / 3.0 + r2 * r2 / 5.0 - r2 * r2 * r2 / 7.0 + r2 * r2 * r2 * r2 / 9.0)
    else:
        s = math.sqrt(s2)
        f = 2.0 * math.atan2(s, q0) / s
    return _rotvec_quat(0.5 * (f * q1), 0.5 * (f * q2), 0.5 * (f * q3))


def _tilt_quat(f0, f1, f2):
    """:func:`strapdown.analysis.multistage.stages.tilt_quaternion` of one specific force, by half-angle formulas.

    θ = atan2(n₁, h) and γ = atan2(−n₃, n₂) with h = √(n₂² + n₃²); their half
    angles come from the cosines and sines by ``cos(a/2) = √((1 + cos a)/2)``,
    ``sin(a/2) = sin a / (2 cos(a/2))`` (or the other way round where cos a < 0),
    which is exact to round-off and needs no trigonometric function.
    """
    h = math.sqrt(f1 * f1 + f2 * f2)
    n = math.sqrt(f0 * f0 + h * h)
    if not (h > 0.0 and n < math.inf):  # vertical force along the body axis 1, or none: the angles' own branches
        pitch, roll = 0.5 * math.atan2(f0, h), 0.5 * math.atan2(-f2, f1)
        ct, st, cg, sg = math.cos(pitch), math.sin(pitch), math.cos(roll), math.sin(roll)
    else:
        ct = math.sqrt(0.5 * (1.0 + h / n))  # θ in [−π/2, π/2]: cos θ >= 0
        st = f0 / n / (2.0 * ct)
        c, sn = f1 / h, -f2 / h
        if c >= 0.0:
            cg = math.sqrt(0.5 * (1.0 + c))
            sg = sn / (2.0 * cg)
        else:
            sg = math.copysign(math.sqrt(0.5 * (1.0 - c)), sn)
            cg = sn / (2.0 * sg)
    return ct * cg, ct * sg, st * sg, st * cg


def _qmul(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product ``a ∘ b`` of two quaternions given by components."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def _matrix(q0, q1, q2, q3):
    """Entries a11, a12, a13, a22, a32 of the matrix (1.7) of a quaternion (normalised first), and its norm."""
    n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    q0, q1, q2, q3 = q0 / n, q1 / n, q2 / n, q3 / n
    a11 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
    a12 = 2.0 * (q1 * q2 + q0 * q3)
    a13 = 2.0 * (q1 * q3 - q0 * q2)
    a22 = q0 * q0 + q2 * q2 - q1 * q1 - q3 * q3
    a32 = 2.0 * (q2 * q3 - q0 * q1)
    return a11, a12, a13, a22, a32, n


def _clip1(x):
    return min(max(x, -1.0), 1.0)


def _wrap(a):
    """:func:`strapdown.analysis.multistage.ship_angles.wrap_angle`: ``π − ((π − a) mod 2π)``, the same operations [rad]."""
    x = math.pi - a
    if not (0.0 <= x < 2.0 * math.pi):  # otherwise x mod 2π is x itself
        x = x % (2.0 * math.pi)
    return math.pi - x


def _limit(peak):
    """Largest squared sine of an angle (with cos > 0) that is certainly at most ``peak − BOUND_MARGIN``: q²(1 − q²/3) <= sin² q; −1 if none."""
    q = peak - BOUND_MARGIN
    if q > 0.0 and q < 1.0:
        return q * q * (1.0 - q * q / 3.0)
    return -1.0


def _true_terms(attitude, out):
    """:func:`bound_terms` into ``out``: per grid point a11, a13, a22, a32 of the true attitude, sin θ, cos θ and the squared radii of the yaw and roll."""
    for i in range(attitude.shape[0]):
        t11, t12, t13, t22, t32, _ = _matrix(attitude[i, 0], attitude[i, 1], attitude[i, 2], attitude[i, 3])
        xt = _clip1(t12)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = t11, t13, t22, t32
        out[i, 4], out[i, 5] = xt, math.sqrt(1.0 - xt * xt)
        out[i, 6], out[i, 7] = t11 * t11 + t13 * t13, t22 * t22 + t32 * t32
    return out


def _record(i, prev, truth, terms, bounds, peaks, limits, nus, comps, errors, store):
    """Composite (2.6), angle errors and running peaks at grid point ``i``; False if the composite is not finite or zero.

    With ``bounds`` an error whose bound from the true attitude (:data:`BOUND_MARGIN` below
    its running peak) shows it cannot raise the peak is not evaluated (module docstring);
    ``terms`` holds the true attitude's terms of the bounds (:func:`bound_terms`), ``limits``
    the squared-sine bounds of the yaw, pitch and roll peaks (:func:`_limit`).
    """
    m = prev.shape[0]
    p0, p1, p2, p3 = prev[0, 0], prev[0, 1], prev[0, 2], prev[0, 3]
    ok = True
    t11 = t13 = t22 = t32 = xt = ct = yaw_t = roll_t = 0.0
    if bounds:
        t11, t13, t22, t32 = terms[i, 0], terms[i, 1], terms[i, 2], terms[i, 3]
        xt, ct, yaw_t, roll_t = terms[i, 4], terms[i, 5], terms[i, 6], terms[i, 7]
    for j in range(m):
        if j > 0:
            p0, p1, p2, p3 = _qmul(prev[j, 0], prev[j, 1], prev[j, 2], prev[j, 3], p0, p1, p2, p3)
        a11, a12, a13, a22, a32, n = _matrix(p0, p1, p2, p3)
        if not (n > 0.0 and n < math.inf):
            ok = False
        yaw_exact = pr_exact = True
        e0 = e1 = e2 = 0.0
        if bounds:
            # yaw and roll: sin and cos of the difference of two plane angles, scaled by both radii (sin² = cross²/rr)
            rr = (a11 * a11 + a13 * a13) * yaw_t
            cross = t13 * a11 - a13 * t11
            yaw_exact = not (rr > 0.01 and a11 * t11 + a13 * t13 > 0.0 and cross * cross <= limits[j, 0] * rr)
            x = _clip1(a12)
            if abs(x) <= 0.9 and abs(xt) <= 0.9:
                cx = math.sqrt(1.0 - x * x)
                s1 = x * ct - cx * xt
                q = peaks[j, 3] - BOUND_MARGIN
                if q > 0.0 and cx * ct + x * xt > 0.0 and s1 * s1 <= limits[j, 1]:
                    rr = (a22 * a22 + a32 * a32) * roll_t
                    cross = t32 * a22 - a32 * t22
                    if rr > 0.01 and a22 * t22 + a32 * t32 > 0.0 and cross * cross <= limits[j, 2] * rr:
                        # |e| <= tan|e| = |sin e|/√(1 − sin² e) for |e| < π/2
                        s2 = cross * cross / rr
                        pr_exact = s1 * s1 / (1.0 - s1 * s1) + s2 / (1.0 - s2) > q * q
        if yaw_exact or store:
            e0 = _wrap(math.atan2(-a13, a11) - truth[i, 0])
            if abs(e0) > peaks[j, 0]:
                peaks[j, 0] = abs(e0)
                limits[j, 0] = _limit(peaks[j, 0])
        if pr_exact or store:
            e1 = _wrap(math.asin(_clip1(a12)) - truth[i, 1])
            e2 = _wrap(math.atan2(-a32, a22) - truth[i, 2])
            if abs(e1) > peaks[j, 1]:
                peaks[j, 1] = abs(e1)
                limits[j, 1] = _limit(peaks[j, 1])
            if abs(e2) > peaks[j, 2]:
                peaks[j, 2] = abs(e2)
                limits[j, 2] = _limit(peaks[j, 2])
            peaks[j, 3] = max(peaks[j, 3], math.sqrt(e1 * e1 + e2 * e2))
        if store:
            nus[j, i, 0], nus[j, i, 1], nus[j, i, 2], nus[j, i, 3] = prev[j, 0], prev[j, 1], prev[j, 2], prev[j, 3]
            comps[j, i, 0], comps[j, i, 1], comps[j, i, 2], comps[j, i, 3] = p0, p1, p2, p3
            errors[j, i, 0], errors[j, i, 1], errors[j, i, 2] = e0, e1, e2
    return ok


def _cascade_loop(gyro, accel, attitude, truth, terms, gravity, step, kinds, masks, cs, rhos, switches, seg_start, n_seg, maps, gains, nu0, store, bounds, peaks, nus, comps, errors):
    n_steps = gyro.shape[0]
    m = kinds.shape[0]
    v = np.empty((m, 4))
    y = np.zeros((m, 4))
    prev = np.empty((m, 4))
    seg = np.zeros(m, dtype=np.int64)
    grow = np.empty(m)
    limits = np.full((m, 3), -1.0)
    for j in range(m):
        grow[j] = math.exp(rhos[j] * step * 0.5)
        n = math.sqrt(nu0[j, 0] * nu0[j, 0] + nu0[j, 1] * nu0[j, 1] + nu0[j, 2] * nu0[j, 2] + nu0[j, 3] * nu0[j, 3])
        for k in range(4):
            v[j, k] = nu0[j, k]
            prev[j, k] = nu0[j, k] / n
    ok = _record(0, prev, truth, terms, bounds, peaks, limits, nus, comps, errors, store)
    for i in range(n_steps):
        b0, b1, b2, b3 = _rotvec_quat(gyro[i, 0], gyro[i, 1], gyro[i, 2])
        f0, f1, f2 = accel[i, 0], accel[i, 1], accel[i, 2]
        for j in range(m):
            kind = kinds[j]
            if kind == 0:
                s0, s1, s2, s3 = attitude[i, 0], attitude[i, 1], attitude[i, 2], attitude[i, 3]
                t0, t1, t2, t3 = attitude[i + 1, 0], attitude[i + 1, 1], attitude[i + 1, 2], attitude[i + 1, 3]
            elif kind == 1:
                s0, s1, s2, s3 = 0.0, -f2 / gravity, 0.0, f0 / gravity
                t0, t1, t2, t3 = s0, s1, s2, s3
            else:
                s0, s1, s2, s3 = _tilt_quat(f0, f1, f2)
                t0, t1, t2, t3 = s0, s1, s2, s3
            while seg[j] + 1 < n_seg[j] and seg_start[j, seg[j] + 1] <= i:
                seg[j] += 1
                _switch(y[j], v[j], masks[j], gains[j], seg[j], switches[j], cs[j], s0, s1, s2, s3)
            _flow(v[j], y[j], masks[j], maps[j, seg[j]], kind == 0, rhos[j] > 0.0, grow[j], s0, s1, s2, s3, t0, t1, t2, t3, b0, b1, b2, b3)
            n = math.sqrt(v[j, 0] * v[j, 0] + v[j, 1] * v[j, 1] + v[j, 2] * v[j, 2] + v[j, 3] * v[j, 3])
            c0, c1, c2, c3 = v[j, 0] / n, v[j, 1] / n, v[j, 2] / n, v[j, 3] / n
            if j + 1 < m:
                # input of the next stage, (2.2): the frame this stage models, and the force re-projected at mid-step
                p0, p1, p2, p3 = prev[j, 0], prev[j, 1], prev[j, 2], prev[j, 3]
                h0, h1, h2, h3 = _half_quat(b0, b1, b2, b3)
                u0, u1, u2, u3 = _qmul(p0, p1, p2, p3, h0, h1, h2, h3)
                w0, w1, w2, w3 = _qmul(c0, c1, c2, c3, h0, -h1, -h2, -h3)
                u0, u1, u2, u3 = u0 + w0, u1 + w1, u2 + w2, u3 + w3
                n = math.sqrt(u0 * u0 + u1 * u1 + u2 * u2 + u3 * u3)
                u0, u1, u2, u3 = u0 / n, u1 / n, u2 / n, u3 / n
                w0, w1, w2, w3 = _qmul(u0, u1, u2, u3, f0 * 0.0, f0, f1, f2)
                _, f0, f1, f2 = _qmul(w0, w1, w2, w3, u0, -u1, -u2, -u3)
                w0, w1, w2, w3 = _qmul(p0, p1, p2, p3, b0, b1, b2, b3)
                b0, b1, b2, b3 = _qmul(w0, w1, w2, w3, c0, -c1, -c2, -c3)
            prev[j, 0], prev[j, 1], prev[j, 2], prev[j, 3] = c0, c1, c2, c3
        if not _record(i + 1, prev, truth, terms, bounds, peaks, limits, nus, comps, errors, store):
            ok = False
    return ok


def cascade_loop(gyro, accel, attitude, truth, gravity, step, kinds, masks, cs, rhos, switches, seg_start, n_seg, maps, gains, nu0, store=True, bounds=True, terms=None):
    """Run a cascade of stages in one compiled pass: estimates, composite (2.6), angle errors and their peaks.

    Parameters
    ----------
    gyro : ndarray, shape (N, 3)
        Gyro rotation-vector increments of the body over each step [rad].
    accel : ndarray, shape (N, 3)
        Mean specific force in the body frame over each step [m/s²].
    attitude : ndarray, shape (N+1, 4)
        True attitude μ at the grid points (the reference of an "external" stage 1).
    truth : ndarray, shape (N+1, 3)
        True Krylov angles (ψ, θ, γ) at the grid points [rad].
    gravity : float
        g [m/s²] of (1.4).
    step : float
        Step H [s] of the stage recursion.
    kinds : ndarray of int64, shape (m,)
        Index in :data:`KINDS` of each stage (only stage 1 may be "external").
    masks : ndarray of bool, shape (m, 4)
        Corrected components of each stage.
    cs, rhos : ndarray, shape (m,)
        Factor c [-] and norm-keeping gain ρ [1/s] of each stage.
    switches : ndarray of int64, shape (m,)
        Index in :data:`SWITCH_MODES` of each stage.
    seg_start : ndarray of int64, shape (m, S+1)
        First step of each gain segment of each stage, then N (padded with N).
    n_seg : ndarray of int64, shape (m,)
        Number of segments of each stage, 1 ≤ n_seg ≤ S.
    maps : ndarray, shape (m, S, 6)
        :func:`correction_map` of each segment over h/2.
    gains : ndarray, shape (m, S, 2)
        (k [1/s], l [1/s²]) of each segment.
    nu0 : ndarray, shape (m, 4)
        Initial estimate of each stage (nonzero).
    store : bool
        Keep the series (False: the peaks only).
    bounds : bool
        Without ``store``: skip the inverse trigonometric functions of an
        angle error wherever a bound from ``attitude`` shows that it stays
        :data:`BOUND_MARGIN` below its running peak (the peaks are the same).
        Used only if ``truth`` holds the Krylov angles of ``attitude``
        (checked at 17 grid points).
    terms : ndarray, shape (N+1, 8), optional
        :func:`bound_terms` of ``attitude`` and ``truth``, for many records on
        one truth (a Monte Carlo): formed once instead of at every call (and
        the check of ``truth`` with it); None: formed here when ``bounds`` is used.

    Returns
    -------
    peaks : ndarray, shape (m, 4)
        Largest ``|Δψ|``, ``|Δθ|``, ``|Δγ|`` and √(Δθ² + Δγ²) after 1, …, m stages [rad].
    nus, composite : ndarray, shape (m, N+1, 4)
        Normalised stage estimates and composites (shape (m, 0, 4) without ``store``).
    errors : ndarray, shape (m, N+1, 3)
        Angle errors, estimate minus truth, wrapped to (−π, π] [rad] (shape (m, 0, 3) without ``store``).

    Raises
    ------
    ValueError
        For inputs of inconsistent shapes, or a composite that is not finite or zero.

    References
    ----------
    Plotnikov (1999), eqs. (1.5), (2.1)–(2.6).
    """
    gyro = _shaped(gyro, "gyro", (None, 3))
    n_steps = gyro.shape[0]
    accel = _shaped(accel, "accel", (n_steps, 3))
    attitude = _shaped(attitude, "attitude", (n_steps + 1, 4))
    truth = _shaped(truth, "truth", (n_steps + 1, 3))
    kinds = np.ascontiguousarray(kinds, dtype=np.int64)
    m = kinds.shape[0] if kinds.ndim == 1 else 0
    if m < 1 or np.any((kinds < 0) | (kinds >= len(KINDS))) or np.any(kinds[1:] == 0):
        raise ValueError(f"Expected `kinds` of shape (m,) with codes in 0..{len(KINDS) - 1}, 0 (external) on stage 1 only, got {kinds!r}")
    masks = np.ascontiguousarray(masks, dtype=np.bool_)
    if masks.shape != (m, 4):
        raise ValueError(f"Expected `masks` with shape ({m}, 4), got shape {masks.shape}")
    cs, rhos = _shaped(cs, "cs", (m,)), _shaped(rhos, "rhos", (m,))
    switches = np.ascontiguousarray(switches, dtype=np.int64)
    if switches.shape != (m,) or np.any((switches < 0) | (switches >= len(SWITCH_MODES))):
        raise ValueError(f"Expected `switches` of shape ({m},) with codes in 0..{len(SWITCH_MODES) - 1}, got {switches!r}")
    maps = _shaped(maps, "maps", (m, None, 6))
    n_max = maps.shape[1]
    gains = _shaped(gains, "gains", (m, n_max, 2))
    seg_start = np.ascontiguousarray(seg_start, dtype=np.int64)
    n_seg = np.ascontiguousarray(n_seg, dtype=np.int64)
    if seg_start.shape != (m, n_max + 1) or n_seg.shape != (m,) or np.any((n_seg < 1) | (n_seg > n_max)):
        raise ValueError(f"Expected `seg_start` of shape ({m}, {n_max + 1}) and `n_seg` of shape ({m},) in 1..{n_max}, got shapes {seg_start.shape}, {n_seg.shape}")
    nu0 = _shaped(nu0, "nu0", (m, 4))
    rows = max(n_steps + 1, 1) if store else 0
    peaks = np.zeros((m, 4))
    nus, comps, errors = np.empty((m, rows, 4)), np.empty((m, rows, 4)), np.empty((m, rows, 3))
    if bool(bounds) and not store:
        terms = bound_terms(attitude, truth) if terms is None else _shaped(terms, "terms", (n_steps + 1, 8))
    else:
        terms = None
    bounds = terms is not None
    loop = _jit(_cascade_loop)
    terms = np.empty((0, 8)) if terms is None else terms
    ok = loop(gyro, accel, attitude, truth, terms, float(gravity), float(step), kinds, masks, cs, rhos, switches, seg_start, n_seg, maps, gains, nu0, bool(store), bounds, peaks, nus, comps, errors)
    if not ok:
        raise ValueError("Expected a finite, nonzero composite attitude, got one that is not (unstable gains or non-finite inputs?)")
    return peaks, nus, comps, errors


def bound_terms(attitude, truth):
    """The true attitude's terms of the bounds of :func:`cascade_loop` at every grid point, or None where they do not apply.

    Parameters
    ----------
    attitude : array_like, shape (N+1, 4)
        True attitude μ at the grid points.
    truth : array_like, shape (N+1, 3)
        True Krylov angles (ψ, θ, γ) at the grid points [rad].

    Returns
    -------
    ndarray, shape (N+1, 8), or None
        Per grid point a11, a13, a22, a32 of the matrix (1.7) of μ, sin θ and
        cos θ, ``a11² + a13²`` and ``a22² + a32²`` (read-only); None if
        ``truth`` does not hold the Krylov angles of ``attitude`` (checked at
        17 grid points), where the bounds are not used.
    """
    attitude = _shaped(attitude, "attitude", (None, 4))
    truth = _shaped(truth, "truth", (attitude.shape[0], 3))
    if not _consistent(attitude, truth):
        return None
    out = _jit(_true_terms)(attitude, np.empty((attitude.shape[0], 8)))
    out.setflags(write=False)
    return out


def _shaped(x, name: str, shape: tuple) -> np.ndarray:
    """``x`` as a C-contiguous float array of ``shape`` (None: any length): the loops index without bounds checks."""
    a = np.ascontiguousarray(x, dtype=float)
    if a.ndim != len(shape) or any(want is not None and got != want for got, want in zip(a.shape, shape)):
        text = ", ".join("…" if want is None else str(want) for want in shape)
        raise ValueError(f"Expected `{name}` with shape ({text}), got shape {a.shape}")
    return a


def _consistent(attitude, truth) -> bool:
    """Whether ``truth`` holds the Krylov angles of ``attitude`` (checked at 17 grid points, to 1e-10 rad)."""
    from .ship_angles import quat_to_angles, wrap_angle

    rows = np.unique(np.linspace(0, attitude.shape[0] - 1, 17).astype(np.int64))
    if not (np.all(np.isfinite(attitude[rows])) and np.all(np.isfinite(truth[rows]))) or np.any(np.linalg.norm(attitude[rows], axis=-1) == 0.0):
        return False
    return bool(np.abs(wrap_angle(quat_to_angles(attitude[rows]) - truth[rows])).max() < 1e-10)
