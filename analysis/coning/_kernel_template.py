"""Template of the fused simulator kernel: plain Python that numba compiles.

:mod:`strapdown.analysis.coning.kernels` copies the functions of this module,
below a generated :func:`increment` and the constants of one algorithm, into a
generated module and compiles them with ``numba.njit(cache=True)``.  Read
here, the module is ordinary Python with a placeholder increment (the
two-sample algorithm), so the template itself can be run and tested without
numba, slowly.  The algorithm's number of samples N and of earlier samples are
arguments of :func:`run`, and :func:`pairwise_increment` takes its pairwise
terms as data, so that one compiled kernel serves every pairwise algorithm.

The kernel does per step what :func:`strapdown.analysis.coning.simulator.simulate`
does with whole arrays (Lebedev & Panov 1989, eqs. (1.3), (1.5), (1.12),
(2.1)–(2.6), (4.1)–(4.5)): the exact increments (2.1) of the regular precession
over each sample, the algorithm, the step (bi)quaternion (1.12), the product,
the exact solution at the step end, and the errors, exact minus algorithm
(``δφ_I = rotvec(Λ* ∘ Λ̄)`` in frame I, ``ΔW = W* − W``).  Instead of storing the
error it accumulates the drift fit and the error statistics (full series only
on request).

Sines and cosines of the sample phase ``ν t`` and of the two step-end angles of
(4.4) come by angle addition from an anchor,

    cos(x_a + jδ) = cos x_a cos jδ − sin x_a sin jδ,   sin(x_a + jδ) = sin x_a cos jδ + cos x_a sin jδ,

with the anchor ``x_a`` computed directly at every multiple of :data:`REANCHOR`
of the global sample (or step) index and the offsets ``jδ`` tabulated once per
run.  No rounding error is carried from one value to the next (a plain
recurrence ``c' = c cos δ − s sin δ`` would let the amplitude creep by an ulp
per step, a bias the drift fit sees), and each value depends only on its
index: results do not depend on where a run is cut into chunks.
"""

import math

import numpy as np

__all__: list = []  # a template, not an API: kernels.py copies its functions

# ---------------------------------------------------------------- constants (the generated module sets them)
#: Biquaternion (velocity) run.
DUAL = False
#: Sines and cosines are computed directly at every multiple of this index (module docstring).
REANCHOR = 32
#: Partial sums are flushed into the totals after every step index that is a multiple of this
#: (time chunks are cut at such multiples, so the summation order does not depend on them).
BLOCK = 1024

#: Columns of the per-point parameter rows: ε, ν, ϑ, ν°, ϑ°, h, then the
#: constant biquaternion C = θ(0) ∘ P̄(0) of the exact solution (real part, dual part).
N_PARAMETERS = 14
#: Columns of the accumulators (:data:`strapdown.analysis.coning.streaming.N_SUMS`).
N_SUMS = 18


def increment(w, wd):
    """Placeholder for a generated straight-line increment: the two-sample algorithm, real part only."""
    p1x, p1y, p1z = w[0, 0], w[0, 1], w[0, 2]
    p2x, p2y, p2z = w[1, 0], w[1, 1], w[1, 2]
    c = 2.0 / 3.0
    return (
        p1x + p2x + c * (p1y * p2z - p1z * p2y),
        p1y + p2y + c * (p1z * p2x - p1x * p2z),
        p1z + p2z + c * (p1x * p2y - p1y * p2x),
        0.0,
        0.0,
        0.0,
    )


def step_increment(w, wd, pairs, samples, history):
    """The increment :func:`run` calls: here the straight-line :func:`increment`, which ignores the data.

    The module of the data-driven kernel defines it as :func:`pairwise_increment` instead.
    """
    return increment(w, wd)


def pairwise_increment(w, wd, pairs, samples, history):
    """``Δφ = P + Σ_i p_i × (Σ_j c_ij p_j)`` (and its dual part) with the algorithm's terms as data.

    ``pairs`` is a float array with one row per pairwise term ``(i, j, c_ij)``
    (window rows of ``p_i`` and ``p_j``, coefficient), grouped by ``i`` in the
    order of :func:`strapdown.analysis.coning.kernels.pairwise_data`; rows
    ``history … history + samples − 1`` of ``w`` are the step's own samples.
    The operations are those of the generated straight-line code, in the same
    order (the sum P sample by sample, each right factor term by term, then
    the cross product), so the result is the same to the last bit.
    """
    r0 = history
    sx, sy, sz = w[r0, 0], w[r0, 1], w[r0, 2]
    dsx, dsy, dsz = 0.0, 0.0, 0.0
    if DUAL:
        dsx, dsy, dsz = wd[r0, 0], wd[r0, 1], wd[r0, 2]
    for j in range(1, samples):
        sx = sx + w[r0 + j, 0]
        sy = sy + w[r0 + j, 1]
        sz = sz + w[r0 + j, 2]
        if DUAL:
            dsx = dsx + wd[r0 + j, 0]
            dsy = dsy + wd[r0 + j, 1]
            dsz = dsz + wd[r0 + j, 2]
    k = 0
    count = pairs.shape[0]
    while k < count:
        i = int(pairs[k, 0])
        j = int(pairs[k, 1])
        c = pairs[k, 2]
        rx, ry, rz = c * w[j, 0], c * w[j, 1], c * w[j, 2]
        drx, dry, drz = 0.0, 0.0, 0.0
        if DUAL:
            drx, dry, drz = c * wd[j, 0], c * wd[j, 1], c * wd[j, 2]
        k += 1
        while k < count and int(pairs[k, 0]) == i:
            j = int(pairs[k, 1])
            c = pairs[k, 2]
            rx = rx + c * w[j, 0]
            ry = ry + c * w[j, 1]
            rz = rz + c * w[j, 2]
            if DUAL:
                drx = drx + c * wd[j, 0]
                dry = dry + c * wd[j, 1]
                drz = drz + c * wd[j, 2]
            k += 1
        ax, ay, az = w[i, 0], w[i, 1], w[i, 2]
        sx = sx + (ay * rz - az * ry)
        sy = sy + (az * rx - ax * rz)
        sz = sz + (ax * ry - ay * rx)
        if DUAL:
            dax, day, daz = wd[i, 0], wd[i, 1], wd[i, 2]
            dsx = dsx + (ay * drz + day * rz - (az * dry + daz * ry))
            dsy = dsy + (az * drx + daz * rx - (ax * drz + dax * rz))
            dsz = dsz + (ax * dry + dax * ry - (ay * drx + day * rx))
    return sx, sy, sz, dsx, dsy, dsz


def qmul(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product of two quaternions given by components."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def rotvec_quat(x, y, z, dx, dy, dz):
    """Step (bi)quaternion of the rotation vector ``φ + s φ°``: eq. (1.12) as the dual extension of the real map.

    Near zero angle the even series of ``cos(θ/2)`` and ``sin(θ/2)/θ`` in ``θ²``
    are used, as in :func:`strapdown.analysis.core.quaternion.rotvec_to_quat`.
    Returns the real quaternion and, for a dual run, its dual part (zeros otherwise).
    """
    t2 = x * x + y * y + z * z
    dt2 = 0.0
    if DUAL:
        dt2 = 2.0 * (x * dx + y * dy + z * dz)
    if t2 < 1e-4:
        x2 = t2 * 0.25
        c = 1.0 - x2 / 2.0 + x2 * x2 / 24.0 - x2 * x2 * x2 / 720.0
        s = 0.5 * (1.0 - x2 / 6.0 + x2 * x2 / 120.0 - x2 * x2 * x2 / 5040.0)
        dc = 0.0
        ds = 0.0
        if DUAL:
            dx2 = 0.25 * dt2
            dc = (-0.5 + x2 / 12.0 - x2 * x2 / 240.0) * dx2
            ds = 0.5 * (-1.0 / 6.0 + x2 / 60.0 - x2 * x2 / 1680.0) * dx2
    else:
        t = math.sqrt(t2)
        half = 0.5 * t
        ch = math.cos(half)
        sh = math.sin(half)
        c = ch
        s = sh / t
        dc = 0.0
        ds = 0.0
        if DUAL:
            dt = 0.5 * dt2 / t
            dc = -sh * 0.5 * dt
            ds = (ch * 0.5 * dt * t - sh * dt) / t2
    if DUAL:
        return c, s * x, s * y, s * z, dc, ds * x + s * dx, ds * y + s * dy, ds * z + s * dz
    return c, s * x, s * y, s * z, 0.0, 0.0, 0.0, 0.0


def error_rotvec(q0, q1, q2, q3):
    """Shortest rotation vector of a unit quaternion (``q`` and ``−q`` identified)."""
    if q0 < 0.0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    s2 = q1 * q1 + q2 * q2 + q3 * q3
    if q0 > 0.0 and s2 < 1e-4 * q0 * q0:
        r2 = s2 / (q0 * q0)
        f = (2.0 / q0) * (1.0 - r2 / 3.0 + r2 * r2 / 5.0 - r2 * r2 * r2 / 7.0 + r2 * r2 * r2 * r2 / 9.0)
    else:
        s = math.sqrt(s2)
        f = 2.0 * math.atan2(s, q0) / s
    return f * q1, f * q2, f * q3


def fill_table(table, rate, interval, count):
    """Cosines and sines of the in-block offsets ``rate · (j · interval)``, ``j < count``."""
    for j in range(count):
        angle = rate * (j * interval)
        table[j, 0] = math.cos(angle)
        table[j, 1] = math.sin(angle)


def phase(rate, interval, offset, index, table, ca, sa):
    """Cosine and sine of ``rate · ((index + offset) · interval)`` by angle addition from the block's anchor.

    At a multiple of :data:`REANCHOR` the anchor ``(ca, sa)`` is computed
    directly; between anchors the value is the anchor rotated by the tabulated
    offset.  Returns ``(c, s, ca, sa)`` with the (possibly new) anchor.
    """
    anchor = (index // REANCHOR) * REANCHOR
    j = index - anchor
    if j == 0:
        angle = rate * ((anchor + offset) * interval)
        ca = math.cos(angle)
        sa = math.sin(angle)
    return ca * table[j, 0] - sa * table[j, 1], sa * table[j, 0] + ca * table[j, 1], ca, sa


def anchor_of(rate, interval, offset, index):
    """Cosine and sine at the anchor of ``index``'s block (what :func:`phase` carries)."""
    anchor = (index // REANCHOR) * REANCHOR
    angle = rate * ((anchor + offset) * interval)
    return math.cos(angle), math.sin(angle)


def run(par, n_steps, theta, k0, k1, sums, err, dwe, dwi, keep, origin, pairs, samples, history):
    """Advance every point from step ``k0`` to ``min(k1, n_steps)``; accumulate the statistics.

    ``par`` (P, N_PARAMETERS) parameter rows; ``n_steps`` (P,) steps of each run;
    ``theta`` (P, 8) the (bi)quaternion after step ``k0``, updated in place;
    ``sums`` (P, N_SUMS) the accumulators, updated; ``err`` (P, rows, 3) and
    ``dwe``, ``dwi`` the series, step k written at row ``k − origin`` when ``keep``
    (``origin`` 0 and ``rows`` n + 1 for a whole series; ``origin`` k0 for a
    window that holds the steps k0 … k1 only).
    Step 0 (the initial state) is compared when ``k0 == 0``.  ``samples`` (N) and
    ``history`` are the algorithm's, and ``pairs`` holds the pairwise terms of a
    data-driven increment (:func:`pairwise_increment`).
    """
    win = np.zeros((history + samples, 3))
    wind = np.zeros((history + samples, 3))
    tab_s = np.zeros((REANCHOR, 2))
    tab_a = np.zeros((REANCHOR, 2))
    tab_b = np.zeros((REANCHOR, 2))
    for i in range(par.shape[0]):
        n = n_steps[i]
        last = min(k1, n)
        if k0 > last or (k0 == last and k0 != 0):
            continue
        e, nu, nut, nud, nutd, h = par[i, 0], par[i, 1], par[i, 2], par[i, 3], par[i, 4], par[i, 5]
        k0c0, k0c1, k0c2, k0c3 = par[i, 6], par[i, 7], par[i, 8], par[i, 9]
        k0d0, k0d1, k0d2, k0d3 = par[i, 10], par[i, 11], par[i, 12], par[i, 13]
        big_h = samples * h
        half_n = 0.5 * n
        # Increments (2.1) of (4.1) about the sample midpoint t_m = (s + 1/2) h:
        # p = (a sin νt_m, a cos νt_m, p3), a = 2 ε sin ϑ sin(νh/2).
        sin_nut, cos_nut = math.sin(nut), math.cos(nut)
        g = 2.0 * math.sin(0.5 * h * nu)
        amp = e * sin_nut * g
        p3 = nu * (1.0 + e * cos_nut) * h
        damp = 0.0
        dp3 = 0.0
        if DUAL:
            damp = e * cos_nut * nutd * g + e * sin_nut * h * math.cos(0.5 * h * nu) * nud
            dp3 = (nud * (1.0 + e * cos_nut) - nu * e * sin_nut * nutd) * h
        fill_table(tab_s, nu, h, REANCHOR if history > 0 else min(REANCHOR, n * samples))
        # Exact attitude (4.4): angles a = (1 + ε)νt/2, b = (1 − ε)νt/2 at t_k = k H.
        rate_a = (1.0 + e) * nu / 2.0
        rate_b = (1.0 - e) * nu / 2.0
        fill_table(tab_a, rate_a, big_h, min(REANCHOR, n + 1))
        fill_table(tab_b, rate_b, big_h, min(REANCHOR, n + 1))
        cn, sn = math.cos(nut / 2.0), math.sin(nut / 2.0)
        dcn = -sn * nutd / 2.0
        dsn = cn * nutd / 2.0
        # The window's history rows: samples k0 N − history … k0 N − 1.
        for r in range(history):
            s_idx = k0 * samples - history + r
            sca, ssa = anchor_of(nu, h, 0.5, s_idx)
            cs, ss, sca, ssa = phase(nu, h, 0.5, s_idx, tab_s, sca, ssa)
            win[r, 0], win[r, 1], win[r, 2] = amp * ss, amp * cs, p3
            if DUAL:
                tm = (s_idx + 0.5) * h
                wind[r, 0] = damp * ss + amp * cs * nud * tm
                wind[r, 1] = damp * cs - amp * ss * nud * tm
                wind[r, 2] = dp3
        t0, t1, t2, t3 = theta[i, 0], theta[i, 1], theta[i, 2], theta[i, 3]
        d0, d1, d2, d3 = theta[i, 4], theta[i, 5], theta[i, 6], theta[i, 7]
        sca, ssa = anchor_of(nu, h, 0.5, k0 * samples)
        aca, asa = anchor_of(rate_a, big_h, 0.0, k0)
        bca, bsa = anchor_of(rate_b, big_h, 0.0, k0)
        ca, sa, aca, asa = phase(rate_a, big_h, 0.0, k0, tab_a, aca, asa)
        cb, sb, bca, bsa = phase(rate_b, big_h, 0.0, k0, tab_b, bca, bsa)
        # Partial sums of the current block, in registers (module docstring of streaming).
        a0 = a1 = a2 = a3 = a4 = 0.0
        b14 = b15 = b16 = b17 = 0.0
        k = k0
        while True:
            stepped = k > k0
            if stepped:
                # One algorithm step: the samples (k − 1) N … k N − 1.
                for j in range(samples):
                    s_idx = (k - 1) * samples + j
                    cs, ss, sca, ssa = phase(nu, h, 0.5, s_idx, tab_s, sca, ssa)
                    r = history + j
                    win[r, 0], win[r, 1], win[r, 2] = amp * ss, amp * cs, p3
                    if DUAL:
                        tm = (s_idx + 0.5) * h
                        wind[r, 0] = damp * ss + amp * cs * nud * tm
                        wind[r, 1] = damp * cs - amp * ss * nud * tm
                        wind[r, 2] = dp3
                x, y, z, dx, dy, dz = step_increment(win, wind, pairs, samples, history)
                for r in range(history):  # the next step's earlier samples
                    for c in range(3):
                        win[r, c] = win[r + samples, c]
                        wind[r, c] = wind[r + samples, c]
                q0, q1, q2, q3, e0, e1, e2, e3 = rotvec_quat(x, y, z, dx, dy, dz)
                if DUAL:
                    m0, m1, m2, m3 = qmul(t0, t1, t2, t3, e0, e1, e2, e3)
                    n0, n1, n2, n3 = qmul(d0, d1, d2, d3, q0, q1, q2, q3)
                    d0, d1, d2, d3 = m0 + n0, m1 + n1, m2 + n2, m3 + n3
                t0, t1, t2, t3 = qmul(t0, t1, t2, t3, q0, q1, q2, q3)
                ca, sa, aca, asa = phase(rate_a, big_h, 0.0, k, tab_a, aca, asa)
                cb, sb, bca, bsa = phase(rate_b, big_h, 0.0, k, tab_b, bca, bsa)
            if not (stepped or k == 0):
                k += 1  # step k0 > 0 was compared by the chunk that reached it
                continue
            # Exact solution at t_k: Λ* = C ∘ Q(t_k) (4.4), or θ* = C ∘ P(t_k) with (4.5).
            x0, x1, x2, x3 = cn * ca, sn * cb, -sn * sb, cn * sa
            l0, l1, l2, l3 = qmul(k0c0, k0c1, k0c2, k0c3, x0, x1, x2, x3)
            # Error δφ_I = rotvec(Λ* ∘ Λ̄), exact minus algorithm: Λ* ∘ Λ̄ is the conjugate of
            # Λ ∘ Λ̄*, whose rotation vector is the negated one, exactly (as in the numpy path).
            ex, ey, ez = error_rotvec(*qmul(t0, t1, t2, t3, l0, -l1, -l2, -l3))
            ex, ey, ez = -ex, -ey, -ez
            weight = k - half_n
            e2n = ex * ex + ey * ey + ez * ez
            a0 += weight * ex
            a1 += weight * ey
            a2 += weight * ez
            a3 += e2n
            a4 = max(a4, e2n)
            if keep:
                err[i, k - origin, 0], err[i, k - origin, 1], err[i, k - origin, 2] = ex, ey, ez
            if k == n:
                sums[i, 5], sums[i, 6], sums[i, 7] = ex, ey, ez
            if DUAL:
                tk = k * big_h
                da = (1.0 + e) * nud * tk / 2.0
                db = (1.0 - e) * nud * tk / 2.0
                y0 = dcn * ca - cn * sa * da
                y1 = dsn * cb - sn * sb * db
                y2 = -dsn * sb - sn * cb * db
                y3 = dcn * sa + cn * ca * da
                m0, m1, m2, m3 = qmul(k0c0, k0c1, k0c2, k0c3, y0, y1, y2, y3)
                n0, n1, n2, n3 = qmul(k0d0, k0d1, k0d2, k0d3, x0, x1, x2, x3)
                u0, u1, u2, u3 = m0 + n0, m1 + n1, m2 + n2, m3 + n3
                # W_E = 2 vect(Λ̄ ∘ M), W_I = 2 vect(M ∘ Λ̄) (1.3), computed and exact; ΔW = W* − W.
                _, wb1, wb2, wb3 = qmul(t0, -t1, -t2, -t3, d0, d1, d2, d3)
                _, wi1, wi2, wi3 = qmul(d0, d1, d2, d3, t0, -t1, -t2, -t3)
                _, vb1, vb2, vb3 = qmul(l0, -l1, -l2, -l3, u0, u1, u2, u3)
                _, vi1, vi2, vi3 = qmul(u0, u1, u2, u3, l0, -l1, -l2, -l3)
                bx, by, bz = 2.0 * vb1 - 2.0 * wb1, 2.0 * vb2 - 2.0 * wb2, 2.0 * vb3 - 2.0 * wb3
                ix, iy, iz = 2.0 * vi1 - 2.0 * wi1, 2.0 * vi2 - 2.0 * wi2, 2.0 * vi3 - 2.0 * wi3
                b2n = bx * bx + by * by + bz * bz
                i2n = ix * ix + iy * iy + iz * iz
                b14 = max(b14, b2n)
                b15 = max(b15, i2n)
                b16 += b2n
                b17 += i2n
                if keep:
                    dwe[i, k - origin, 0], dwe[i, k - origin, 1], dwe[i, k - origin, 2] = bx, by, bz
                    dwi[i, k - origin, 0], dwi[i, k - origin, 1], dwi[i, k - origin, 2] = ix, iy, iz
                if k == n:
                    sums[i, 8], sums[i, 9], sums[i, 10] = bx, by, bz
                    sums[i, 11], sums[i, 12], sums[i, 13] = ix, iy, iz
            if k % BLOCK == 0 or k == last:
                flush(sums, i, a0, a1, a2, a3, a4, b14, b15, b16, b17)
                a0 = a1 = a2 = a3 = a4 = 0.0
                b14 = b15 = b16 = b17 = 0.0
            if k == last:
                break
            k += 1
        theta[i, 0], theta[i, 1], theta[i, 2], theta[i, 3] = t0, t1, t2, t3
        theta[i, 4], theta[i, 5], theta[i, 6], theta[i, 7] = d0, d1, d2, d3


def flush(sums, i, a0, a1, a2, a3, a4, b14, b15, b16, b17):
    """Add the partial sums of one block into the totals of point ``i`` (maxima: keep the larger)."""
    sums[i, 0] += a0
    sums[i, 1] += a1
    sums[i, 2] += a2
    sums[i, 3] += a3
    sums[i, 4] = max(sums[i, 4], a4)
    sums[i, 14] = max(sums[i, 14], b14)
    sums[i, 15] = max(sums[i, 15], b15)
    sums[i, 16] += b16
    sums[i, 17] += b17


def window_peak(err, i, count):
    """Peak distance of rows ``0 … count − 1`` of ``err[i]`` from their least-squares line.

    The compiled counterpart of :func:`strapdown.analysis.coning.streaming.window_peak`
    (same definition, its sums in another order: equal to round-off): the
    line ``a + d (k − (count − 1)/2)`` from one pass, the largest distance from
    a second.
    """
    if count < 3:
        return 0.0
    mid = 0.5 * (count - 1)
    s0 = s1 = s2 = 0.0
    m0 = m1 = m2 = 0.0
    for k in range(count):
        c = k - mid
        s0 += err[i, k, 0]
        s1 += err[i, k, 1]
        s2 += err[i, k, 2]
        m0 += c * err[i, k, 0]
        m1 += c * err[i, k, 1]
        m2 += c * err[i, k, 2]
    norm = count * (count * count - 1.0) / 12.0
    a0, a1, a2 = s0 / count, s1 / count, s2 / count
    d0, d1, d2 = m0 / norm, m1 / norm, m2 / norm
    best = 0.0
    for k in range(count):
        c = k - mid
        r0 = err[i, k, 0] - a0 - c * d0
        r1 = err[i, k, 1] - a1 - c * d1
        r2 = err[i, k, 2] - a2 - c * d2
        best = max(best, r0 * r0 + r1 * r1 + r2 * r2)
    return math.sqrt(best)
