"""Template of the vibration Monte Carlo kernel: plain Python that numba compiles.

:mod:`strapdown.analysis.coning.vibration_monte_carlo` copies these
functions below a generated ``increment`` of one algorithm
(:func:`strapdown.analysis.coning.kernels.increment_source`) and compiles
them with ``numba.njit(cache=True)``.  Read here the module is ordinary
Python with a two-sample placeholder, so it can be run without numba, slowly.

Per realisation, per sensor sample ``[t_j, t_j + h_s]``:

1. the exact motion at the Gauss–Legendre nodes of the sample: the rotation
   vector ``θ(t) = Σ_k Re(Θ_k e^{iω_k t})`` and ``θ̇``, the body rate
   ``ω = J_r(θ) θ̇`` (right Jacobian, exact), the inertial acceleration
   ``a_I = Σ_k Re(B_k e^{iω_k t})`` and the body specific force
   ``f = R(θ)ᵀ a_I``.  The truth is ``Λ = exp(θ)``, ``W_I = v_I(t) − v_I(t₀)``
   with ``v_I = Σ Re(B_k/(iω_k) e^{iω_k t})``: exact at any time, no
   linearisation;
2. each analog filter in continuous time: its state-space solution over the
   sample (variation of constants, matrices from the matrix exponential)
   with the input integrated by the Gauss–Legendre rule, and the increment
   ``∫ y dt`` likewise;
3. the digital filter on the increments (direct form II transposed);
4. decimation: M increments summed into one algorithm sample;
5. every N samples the algorithm's step (its dual extension for the
   velocity), the attitude and velocity products, and the errors
   ``rotvec(Λ_true ∘ Λ̄)`` and ``W_I,true − W_I`` (exact minus algorithm),
   turned into a slope by a smooth weight: ``Σ k(t) e(t) / Σ k(t) t`` with
   ``k = −g'``, ``g = sin⁴(πt/T)`` over the run T.  A constant offset has no
   weight (k is antisymmetric about T/2) and a bounded oscillation of
   angular frequency Ω biases the slope by ``O((ΩT)⁻⁵)`` of its amplitude
   over T, where a least-squares line leaves ``O((ΩT)⁻¹)``.

Phases ``e^{iω_k t}`` come from an anchor computed directly at every
multiple of :data:`REANCHOR` samples times a table of offsets (no rounding
carried from sample to sample).
"""

import math

import numpy as np

__all__: list = []  # a template: vibration_monte_carlo.py copies its functions

SAMPLES = 2
HISTORY = 0
WINDOW = 2
DUAL = False
#: Phases are computed directly at every multiple of this many sensor samples.
REANCHOR = 32


def increment(w, wd):
    """Placeholder for the generated increment: the two-sample algorithm, real part only."""
    c = 2.0 / 3.0
    return (
        w[0, 0] + w[1, 0] + c * (w[0, 1] * w[1, 2] - w[0, 2] * w[1, 1]),
        w[0, 1] + w[1, 1] + c * (w[0, 2] * w[1, 0] - w[0, 0] * w[1, 2]),
        w[0, 2] + w[1, 2] + c * (w[0, 0] * w[1, 1] - w[0, 1] * w[1, 0]),
        0.0,
        0.0,
        0.0,
    )


def so3_coefficients(x2):
    """``sin x / x``, ``(1 − cos x)/x²``, ``(x − sin x)/x³`` of x = √x2 (Taylor through x⁸ below x = 0.1: error < 1e-17)."""
    if x2 < 1e-2:
        a = 1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0)))
        b = 0.5 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0))))
        c = (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0 * (1.0 - x2 / 110.0)))) / 6.0
        return a, b, c
    x = math.sqrt(x2)
    s, c = math.sin(x), math.cos(x)
    return s / x, (1.0 - c) / x2, (x - s) / (x2 * x)


def cross(ax, ay, az, bx, by, bz):
    """a × b."""
    return ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx


def quat_of(tx, ty, tz):
    """exp(θ) as a unit quaternion."""
    x2 = tx * tx + ty * ty + tz * tz
    if x2 < 1e-12:
        c = 1.0 - x2 / 8.0
        s = 0.5 - x2 / 48.0
    else:
        x = math.sqrt(x2)
        c = math.cos(0.5 * x)
        s = math.sin(0.5 * x) / x
    return c, s * tx, s * ty, s * tz


def qmul(a0, a1, a2, a3, b0, b1, b2, b3):
    """Hamilton product."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


def error_rotvec(q0, q1, q2, q3):
    """Rotation vector of a unit quaternion (shortest rotation)."""
    if q0 < 0.0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    v = math.sqrt(q1 * q1 + q2 * q2 + q3 * q3)
    if v < 1e-300:
        return 2.0 * q1, 2.0 * q2, 2.0 * q3
    k = 2.0 * math.atan2(v, q0) / v
    return k * q1, k * q2, k * q3


def rotate(q0, q1, q2, q3, x, y, z):
    """q ∘ v ∘ q̄ for a unit quaternion."""
    tx, ty, tz = 2.0 * (q2 * z - q3 * y), 2.0 * (q3 * x - q1 * z), 2.0 * (q1 * y - q2 * x)
    return x + q0 * tx + (q2 * tz - q3 * ty), y + q0 * ty + (q3 * tx - q1 * tz), z + q0 * tz + (q1 * ty - q2 * tx)


def motion(k_count, zr, zi, th_re, th_im, a_re, a_im, b_re, b_im, out, dual):
    """θ, θ̇ (and a_I when ``dual``) at one instant from the phases ``zr + i zi`` of the components; out[0:9]."""
    for c in range(9):
        out[c] = 0.0
    for k in range(k_count):
        r, i = zr[k], zi[k]
        for c in range(3):
            out[c] += th_re[k, c] * r - th_im[k, c] * i
            out[3 + c] += a_re[k, c] * r - a_im[k, c] * i
        if dual:
            for c in range(3):
                out[6 + c] += b_re[k, c] * r - b_im[k, c] * i


def run(freq, th_re, th_im, a_re, a_im, b_re, b_im, hs, decimation, warm_samples, steps, nodes, weights,
        phi, gam, phii, xi, cmat, dmat, order, db, da, nd, dual, out):  # fmt: skip
    """Every realisation; out[r] = slopes of the attitude error (0:3) and of the velocity error (3:6)."""
    n_real, k_count = freq.shape
    m = nodes.shape[0]
    n_state = phi.shape[1]
    channels = 6 if dual else 3
    tab_r = np.empty((k_count, REANCHOR, m))
    tab_i = np.empty((k_count, REANCHOR, m))
    step_r = np.empty((k_count, REANCHOR))
    step_i = np.empty((k_count, REANCHOR))
    zr = np.empty(k_count)
    zi = np.empty(k_count)
    ar = np.empty(k_count)
    ai = np.empty(k_count)
    val = np.empty(9)
    u = np.empty((m, 6))
    x = np.zeros((6, n_state))
    xn = np.zeros(n_state)
    dz = np.zeros((6, db.shape[1]))
    window = np.zeros((WINDOW, 3))
    windowd = np.zeros((WINDOW, 3))
    acc = np.zeros(6)
    total_samples = warm_samples + steps * SAMPLES * decimation
    span = steps * SAMPLES * decimation * hs
    for r in range(n_real):
        om = freq[r]
        tr_, ti_, ar_, ai_, br_, bi_ = th_re[r], th_im[r], a_re[r], a_im[r], b_re[r], b_im[r]
        for k in range(k_count):
            for j in range(REANCHOR):
                step_r[k, j] = math.cos(om[k] * j * hs)
                step_i[k, j] = math.sin(om[k] * j * hs)
                for q in range(m):
                    ang = om[k] * (j * hs + nodes[q])
                    tab_r[k, j, q] = math.cos(ang)
                    tab_i[k, j, q] = math.sin(ang)
        x[:, :] = 0.0
        dz[:, :] = 0.0
        for c in range(6):
            acc[c] = 0.0
        sub = 0
        sample_count = 0
        lq0, lq1, lq2, lq3 = 1.0, 0.0, 0.0, 0.0
        wc = np.zeros(3)
        v0 = np.zeros(3)
        s_kt = 0.0
        s_ke = np.zeros(6)
        t0 = warm_samples * hs
        for j in range(total_samples + 1):
            jr = j % REANCHOR
            if jr == 0:
                for k in range(k_count):
                    ang = om[k] * j * hs
                    ar[k] = math.cos(ang)
                    ai[k] = math.sin(ang)
            # ---- step boundary: truth, algorithm start, errors
            if j >= warm_samples and (j - warm_samples) % (SAMPLES * decimation) == 0:
                for k in range(k_count):
                    zr[k] = ar[k] * step_r[k, jr] - ai[k] * step_i[k, jr]
                    zi[k] = ar[k] * step_i[k, jr] + ai[k] * step_r[k, jr]
                motion(k_count, zr, zi, tr_, ti_, ar_, ai_, br_, bi_, val, dual)
                q0, q1, q2, q3 = quat_of(val[0], val[1], val[2])
                vx = vy = vz = 0.0
                for k in range(k_count):  # v_I = Re(B/(iω) z) = (Im(B z))/ω ... Re(-i B z)/ω = Im(B z)/ω
                    vx += (br_[k, 0] * zi[k] + bi_[k, 0] * zr[k]) / om[k]
                    vy += (br_[k, 1] * zi[k] + bi_[k, 1] * zr[k]) / om[k]
                    vz += (br_[k, 2] * zi[k] + bi_[k, 2] * zr[k]) / om[k]
                if j == warm_samples:
                    lq0, lq1, lq2, lq3 = q0, q1, q2, q3
                    v0[0], v0[1], v0[2] = vx, vy, vz
                    wc[:] = 0.0
                t = j * hs - t0
                e0, e1, e2, e3 = qmul(q0, q1, q2, q3, lq0, -lq1, -lq2, -lq3)
                ex, ey, ez = error_rotvec(e0, e1, e2, e3)
                sn = math.sin(math.pi * t / span)
                kw = sn * sn * sn * math.cos(math.pi * t / span)
                s_kt += kw * t
                s_ke[0] += kw * ex
                s_ke[1] += kw * ey
                s_ke[2] += kw * ez
                if dual:
                    dx = vx - v0[0] - wc[0]
                    dy = vy - v0[1] - wc[1]
                    dzv = vz - v0[2] - wc[2]
                    s_ke[3] += kw * dx
                    s_ke[4] += kw * dy
                    s_ke[5] += kw * dzv
            if j == total_samples:
                break
            # ---- the sensor sample [t_j, t_j + hs]: motion at the nodes
            for q in range(m):
                for k in range(k_count):
                    br = ar[k] * tab_r[k, jr, q] - ai[k] * tab_i[k, jr, q]
                    bi = ar[k] * tab_i[k, jr, q] + ai[k] * tab_r[k, jr, q]
                    zr[k] = br
                    zi[k] = bi
                motion(k_count, zr, zi, tr_, ti_, ar_, ai_, br_, bi_, val, dual)
                tx, ty, tz = val[0], val[1], val[2]
                sa, ca, da_ = so3_coefficients(tx * tx + ty * ty + tz * tz)
                # ω = J_r(θ) θ̇ = θ̇ − ca θ×θ̇ + da θ×(θ×θ̇)
                cx, cy, cz = cross(tx, ty, tz, val[3], val[4], val[5])
                ccx, ccy, ccz = cross(tx, ty, tz, cx, cy, cz)
                u[q, 0] = val[3] - ca * cx + da_ * ccx
                u[q, 1] = val[4] - ca * cy + da_ * ccy
                u[q, 2] = val[5] - ca * cz + da_ * ccz
                if dual:  # f = R(θ)ᵀ a = a − sa θ×a + ca θ×(θ×a)
                    fx, fy, fz = cross(tx, ty, tz, val[6], val[7], val[8])
                    ffx, ffy, ffz = cross(tx, ty, tz, fx, fy, fz)
                    u[q, 3] = val[6] - sa * fx + ca * ffx
                    u[q, 4] = val[7] - sa * fy + ca * ffy
                    u[q, 5] = val[8] - sa * fz + ca * ffz
            # ---- analog filters (exact state-space solution, Gauss–Legendre input), digital filters
            for c in range(channels):
                n = order[c]
                inc = 0.0
                for q in range(m):
                    inc += weights[q] * u[q, c]
                inc *= dmat[c]
                for a in range(n):
                    s = 0.0
                    for b in range(n):
                        s += phii[c, a, b] * x[c, b]
                    for q in range(m):
                        s += xi[c, q, a] * u[q, c]
                    inc += cmat[c, a] * s
                for a in range(n):
                    s = 0.0
                    for b in range(n):
                        s += phi[c, a, b] * x[c, b]
                    for q in range(m):
                        s += gam[c, q, a] * u[q, c]
                    xn[a] = s
                for a in range(n):
                    x[c, a] = xn[a]
                L = nd[c]
                if L > 1:
                    y = db[c, 0] * inc + dz[c, 0]
                    for a in range(L - 2):
                        dz[c, a] = db[c, a + 1] * inc + dz[c, a + 1] - da[c, a + 1] * y
                    dz[c, L - 2] = db[c, L - 1] * inc - da[c, L - 1] * y
                    inc = y
                acc[c] += inc
            sub += 1
            if sub < decimation:
                continue
            sub = 0
            # ---- one algorithm sample
            for a in range(WINDOW - 1):
                for c in range(3):
                    window[a, c] = window[a + 1, c]
                    windowd[a, c] = windowd[a + 1, c]
            for c in range(3):
                window[WINDOW - 1, c] = acc[c]
                windowd[WINDOW - 1, c] = acc[3 + c]
            for c in range(6):
                acc[c] = 0.0
            if j + 1 <= warm_samples:
                continue
            sample_count += 1
            if sample_count % SAMPLES != 0:
                continue
            px, py, pz, pdx, pdy, pdz = increment(window, windowd)
            if dual:  # velocity increment in the step's start frame: J_l(Δφ) Δφ°, rotated into I
                sa, ca, da_ = so3_coefficients(px * px + py * py + pz * pz)
                cx, cy, cz = cross(px, py, pz, pdx, pdy, pdz)
                ccx, ccy, ccz = cross(px, py, pz, cx, cy, cz)
                gx, gy, gz = rotate(lq0, lq1, lq2, lq3, pdx + ca * cx + da_ * ccx, pdy + ca * cy + da_ * ccy, pdz + ca * cz + da_ * ccz)
                wc[0] += gx
                wc[1] += gy
                wc[2] += gz
            s0, s1, s2, s3 = quat_of(px, py, pz)
            lq0, lq1, lq2, lq3 = qmul(lq0, lq1, lq2, lq3, s0, s1, s2, s3)
            norm = 1.0 / math.sqrt(lq0 * lq0 + lq1 * lq1 + lq2 * lq2 + lq3 * lq3)
            lq0 *= norm
            lq1 *= norm
            lq2 *= norm
            lq3 *= norm
        for c in range(6):
            out[r, c] = s_ke[c] / s_kt
