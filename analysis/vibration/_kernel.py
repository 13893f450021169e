"""Template of the vibration Monte Carlo kernel: plain Python that numba compiles.

:mod:`strapdown.analysis.vibration.monte_carlo` copies these
functions below a generated ``increment`` of one algorithm
(:func:`strapdown.analysis.coning.kernels.increment_source`) and the constants
of one run kind, and compiles them with ``numba.njit(cache=True)``.  Read here
the module is ordinary Python with a two-sample placeholder (attitude only), so
it can be run without numba, slowly.

The kernel runs antithetic pairs: the realisation of the amplitudes given and
the one of their negatives.  Per pair, per sensor sample ``[t_j, t_j + h_s]``:

1. the exact motion at the Gauss–Legendre nodes of the sample, once for the
   pair: the rotation vector ``θ(t) = Σ_k Re(Θ_k e^{iω_k t})``, ``θ̇`` (and the
   inertial acceleration ``a_I = Σ_k Re(B_k e^{iω_k t})``), then the body rate
   ``ω = J_r(θ) θ̇`` (right Jacobian, exact) and the specific force
   ``f = R(θ)ᵀ a_I`` of both members.  Negating the amplitudes negates θ, θ̇
   and a_I exactly in floating point, so the negative member's inputs are
   ``−θ̇ − c_a θ×θ̇ − d_a θ×(θ×θ̇)`` from the same cross products, and its truth
   is the conjugate quaternion and the negated velocity.  The truth is
   ``Λ = exp(θ)``, ``W_I = v_I(t) − v_I(t₀)`` with ``v_I = Σ Re(B_k/(iω_k) e^{iω_k t})``:
   exact at any time, no linearisation;
2. every analog filter in continuous time: over a sample its state-space
   solution is linear in the state and the node inputs,
   ``[∫ y dt; x'] = G [x; u_1 … u_m]`` (the matrix from the matrix exponential,
   :func:`strapdown.analysis.vibration.monte_carlo.sensor_matrices`),
   evaluated for all :data:`LANES` (member, channel) lanes at once;
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

The phases ``e^{iω_k(t_j + s_q)}`` at the nodes are evaluated directly (sine and
cosine) at every multiple of ``reanchor`` samples of the run, and advanced
from sample to sample in between by one complex multiplication by
``e^{iω_k h_s}``.  Between anchors a phase's modulus and argument carry at most
``reanchor`` roundings (3·10⁻¹⁴ for 256), a bounded error that repeats with the
anchors and does not grow over the run: the mean drift moves by about 10⁻⁹ of
itself, the attitude error by 10⁻¹⁵ rad (the test suite compares a run with a
direct evaluation at every sample, ``reanchor = 1``).  Each value depends only on
the sample index, so results do not depend on chunking.  The sines and cosines
of the rotations use their Taylor series below 0.1 rad (truncation below
10⁻¹⁷, under the rounding of the closed forms).
"""

import math

import numpy as np

__all__: list = []  # a template: vibration_monte_carlo.py copies its functions

# ---------------------------------------------------------------- constants (the generated module sets them)
#: Samples N per step.
SAMPLES = 2
#: Samples of earlier steps the algorithm reads.
HISTORY = 0
#: Rows of the increment window, ``HISTORY + SAMPLES``.
WINDOW = 2
#: Velocity (sculling) run: accelerometer channels, specific force, dual algorithm.
DUAL = False
#: Sensor channels per realisation: the gyro axes, and the accelerometer axes in a velocity run.
CHANNELS = 3
#: Filter lanes: (member of the pair, channel), member-major.
LANES = 2 * CHANNELS
#: Motion values at a node: θ and θ̇, and a_I in a velocity run.
OUTPUTS = 6


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
    """exp(θ) as a unit quaternion (Taylor through |θ|⁸ below |θ| = 0.1: error < 1e-19)."""
    x2 = tx * tx + ty * ty + tz * tz
    if x2 < 1e-2:  # cos(x/2) and sin(x/2)/x in y = x²/4
        y = 0.25 * x2
        c = 1.0 - y / 2.0 * (1.0 - y / 12.0 * (1.0 - y / 30.0 * (1.0 - y / 56.0)))
        s = 0.5 * (1.0 - y / 6.0 * (1.0 - y / 20.0 * (1.0 - y / 42.0 * (1.0 - y / 72.0))))
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
    """Rotation vector of a unit quaternion, the shortest rotation (Taylor of atan below 0.02 rad: error < 1e-20)."""
    if q0 < 0.0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    v2 = q1 * q1 + q2 * q2 + q3 * q3
    if v2 < 1e-4 * (q0 * q0):  # 2 atan(v/q0)/v = (2/q0)(1 − x²/3 + x⁴/5 − x⁶/7 + x⁸/9), x = v/q0 < 0.01
        iq = 1.0 / q0
        x2 = v2 * iq * iq
        k = 2.0 * iq * (1.0 - x2 * (1.0 / 3.0 - x2 * (0.2 - x2 * (1.0 / 7.0 - x2 / 9.0))))
        return k * q1, k * q2, k * q3
    v = math.sqrt(v2)
    if v < 1e-300:
        return 2.0 * q1, 2.0 * q2, 2.0 * q3
    k = 2.0 * math.atan2(v, q0) / v
    return k * q1, k * q2, k * q3


def rotate(q0, q1, q2, q3, x, y, z):
    """q ∘ v ∘ q̄ for a unit quaternion."""
    tx, ty, tz = 2.0 * (q2 * z - q3 * y), 2.0 * (q3 * x - q1 * z), 2.0 * (q1 * y - q2 * x)
    return x + q0 * tx + (q2 * tz - q3 * ty), y + q0 * ty + (q3 * tx - q1 * tz), z + q0 * tz + (q1 * ty - q2 * tx)


def phases(om, t, nodes, zr, zi):
    """``zr + i zi = e^{iω_k (t + s_q)}`` at the nodes ``s_q`` of the sample that starts at t, directly."""
    for q in range(nodes.shape[0]):
        for k in range(om.shape[0]):
            ang = om[k] * (t + nodes[q])
            zr[q, k] = math.cos(ang)
            zi[q, k] = math.sin(ang)


def advance(zr, zi, rot_r, rot_i):
    """Every phase times ``e^{iω_k h_s}``: the nodes of the next sample."""
    for q in range(zr.shape[0]):
        for k in range(zr.shape[1]):
            r = zr[q, k]
            zr[q, k] = r * rot_r[k] - zi[q, k] * rot_i[k]
            zi[q, k] = r * rot_i[k] + zi[q, k] * rot_r[k]


def motion(zr, zi, q, cr, ci, out):
    """``out[c] = Re Σ_k (cr + i ci)[k, c] (zr + i zi)[q, k]``, c < OUTPUTS: θ, θ̇ (and a_I) at node q."""
    s0 = s1 = s2 = s3 = s4 = s5 = s6 = s7 = s8 = 0.0
    for k in range(zr.shape[1]):
        r = zr[q, k]
        i = zi[q, k]
        s0 += cr[k, 0] * r - ci[k, 0] * i
        s1 += cr[k, 1] * r - ci[k, 1] * i
        s2 += cr[k, 2] * r - ci[k, 2] * i
        s3 += cr[k, 3] * r - ci[k, 3] * i
        s4 += cr[k, 4] * r - ci[k, 4] * i
        s5 += cr[k, 5] * r - ci[k, 5] * i
        if DUAL:
            s6 += cr[k, 6] * r - ci[k, 6] * i
            s7 += cr[k, 7] * r - ci[k, 7] * i
            s8 += cr[k, 8] * r - ci[k, 8] * i
    out[0], out[1], out[2], out[3], out[4], out[5] = s0, s1, s2, s3, s4, s5
    out[6], out[7], out[8] = s6, s7, s8


def run(freq, coef_re, coef_im, vel_re, vel_im, hs, decimation, warm_samples, steps, nodes, gmat, db, da, reanchor, out):  # fmt: skip
    """Every pair p: ``out[2p]`` for the amplitudes given, ``out[2p + 1]`` for their negatives.

    ``freq[p, k]`` are the angular frequencies [rad/s]; ``coef[p, k]`` the
    complex amplitudes of θ (0:3), θ̇ (3:6) and a_I (6:9); ``vel[p, k]`` those of
    v_I.  ``out[r]`` receives the slopes of the attitude error (0:3) and of the
    velocity error (3:6), frame I.
    """
    n_pair, k_count = freq.shape
    m = nodes.shape[0]
    n_state = gmat.shape[0] - 1
    n_dig = db.shape[0]
    if gmat.shape[1] != n_state + m or gmat.shape[2] != LANES or db.shape[1] != LANES or da.shape != db.shape:
        raise ValueError("Expected filter matrices G of shape (n + 1, n + nodes, LANES) and digital coefficients of shape (L, LANES)")
    zr = np.empty((m, k_count))
    zi = np.empty((m, k_count))
    rot_r = np.empty(k_count)
    rot_i = np.empty(k_count)
    back_r = np.empty(k_count)
    back_i = np.empty(k_count)
    cr = np.empty((k_count, 9))
    ci = np.empty((k_count, 9))
    val = np.empty(9)
    vv = np.zeros((n_state + m, LANES))  # [x; u_1 … u_m] of every lane
    yy = np.zeros((n_state + 1, LANES))
    tt = np.zeros(LANES)
    inc = np.zeros(LANES)
    dz = np.zeros((n_dig, LANES))
    acc = np.zeros(LANES)
    window = np.zeros((2, WINDOW, 3))
    windowd = np.zeros((2, WINDOW, 3))
    lq = np.zeros((2, 4))
    wc = np.zeros((2, 3))
    v0 = np.zeros(3)
    s_ke = np.zeros((2, 6))
    per_step = SAMPLES * decimation
    total_samples = warm_samples + steps * per_step
    span = steps * per_step * hs
    t0 = warm_samples * hs
    weight = np.empty(steps + 1)  # k(t) at the step boundaries, the same for every realisation
    s_kt = 0.0
    for i in range(steps + 1):
        t = (warm_samples + i * per_step) * hs - t0
        sn = math.sin(math.pi * t / span)
        weight[i] = sn * sn * sn * math.cos(math.pi * t / span)
        s_kt += weight[i] * t
    for p in range(n_pair):
        om = freq[p]
        for k in range(k_count):
            rot_r[k] = math.cos(om[k] * hs)
            rot_i[k] = math.sin(om[k] * hs)
            back_r[k] = math.cos(om[k] * nodes[0])  # from the first node back to the sample's start
            back_i[k] = -math.sin(om[k] * nodes[0])
            for c in range(9):
                cr[k, c] = coef_re[p, k, c]
                ci[k, c] = coef_im[p, k, c]
        vv[:, :] = 0.0
        dz[:, :] = 0.0
        acc[:] = 0.0
        s_ke[:, :] = 0.0
        window[:, :, :] = 0.0
        windowd[:, :, :] = 0.0
        sub = 0
        sample_count = 0
        for j in range(total_samples + 1):
            if j % reanchor == 0:
                phases(om, j * hs, nodes, zr, zi)
            # ---- step boundary: the truth (the negative member's is the conjugate), the errors of both members
            if j >= warm_samples and (j - warm_samples) % per_step == 0:
                bx = by = bz = vx = vy = vz = 0.0
                for k in range(k_count):
                    r = zr[0, k] * back_r[k] - zi[0, k] * back_i[k]
                    i = zr[0, k] * back_i[k] + zi[0, k] * back_r[k]
                    bx += cr[k, 0] * r - ci[k, 0] * i
                    by += cr[k, 1] * r - ci[k, 1] * i
                    bz += cr[k, 2] * r - ci[k, 2] * i
                    if DUAL:
                        vx += vel_re[p, k, 0] * r - vel_im[p, k, 0] * i
                        vy += vel_re[p, k, 1] * r - vel_im[p, k, 1] * i
                        vz += vel_re[p, k, 2] * r - vel_im[p, k, 2] * i
                q0, q1, q2, q3 = quat_of(bx, by, bz)
                if j == warm_samples:
                    lq[0, 0], lq[0, 1], lq[0, 2], lq[0, 3] = q0, q1, q2, q3
                    lq[1, 0], lq[1, 1], lq[1, 2], lq[1, 3] = q0, -q1, -q2, -q3
                    v0[0], v0[1], v0[2] = vx, vy, vz
                    wc[:, :] = 0.0
                kw = weight[(j - warm_samples) // per_step]
                for s in range(2):
                    sg = 1.0 - 2.0 * s
                    e0, e1, e2, e3 = qmul(q0, sg * q1, sg * q2, sg * q3, lq[s, 0], -lq[s, 1], -lq[s, 2], -lq[s, 3])
                    ex, ey, ez = error_rotvec(e0, e1, e2, e3)
                    s_ke[s, 0] += kw * ex
                    s_ke[s, 1] += kw * ey
                    s_ke[s, 2] += kw * ez
                    if DUAL:
                        s_ke[s, 3] += kw * (sg * (vx - v0[0]) - wc[s, 0])
                        s_ke[s, 4] += kw * (sg * (vy - v0[1]) - wc[s, 1])
                        s_ke[s, 5] += kw * (sg * (vz - v0[2]) - wc[s, 2])
            if j == total_samples:
                break
            # ---- the sensor sample [t_j, t_j + hs]: the motion at the nodes, once for the pair
            for q in range(m):
                motion(zr, zi, q, cr, ci, val)
                tx, ty, tz = val[0], val[1], val[2]
                sa, ca, da_ = so3_coefficients(tx * tx + ty * ty + tz * tz)
                # ω = J_r(θ) θ̇ = θ̇ − ca θ×θ̇ + da θ×(θ×θ̇); for (−θ, −θ̇): −θ̇ − ca θ×θ̇ − da θ×(θ×θ̇)
                cx, cy, cz = cross(tx, ty, tz, val[3], val[4], val[5])
                ccx, ccy, ccz = cross(tx, ty, tz, cx, cy, cz)
                cx, cy, cz = ca * cx, ca * cy, ca * cz
                ccx, ccy, ccz = da_ * ccx, da_ * ccy, da_ * ccz
                row = n_state + q
                vv[row, 0] = val[3] - cx + ccx
                vv[row, 1] = val[4] - cy + ccy
                vv[row, 2] = val[5] - cz + ccz
                vv[row, CHANNELS] = -val[3] - cx - ccx
                vv[row, CHANNELS + 1] = -val[4] - cy - ccy
                vv[row, CHANNELS + 2] = -val[5] - cz - ccz
                if DUAL:  # f = R(θ)ᵀ a = a − sa θ×a + ca θ×(θ×a); for (−θ, −a): −a − sa θ×a − ca θ×(θ×a)
                    fx, fy, fz = cross(tx, ty, tz, val[6], val[7], val[8])
                    ffx, ffy, ffz = cross(tx, ty, tz, fx, fy, fz)
                    fx, fy, fz = sa * fx, sa * fy, sa * fz
                    ffx, ffy, ffz = ca * ffx, ca * ffy, ca * ffz
                    vv[row, 3] = val[6] - fx + ffx
                    vv[row, 4] = val[7] - fy + ffy
                    vv[row, 5] = val[8] - fz + ffz
                    vv[row, CHANNELS + 3] = -val[6] - fx - ffx
                    vv[row, CHANNELS + 4] = -val[7] - fy - ffy
                    vv[row, CHANNELS + 5] = -val[8] - fz - ffz
            advance(zr, zi, rot_r, rot_i)
            # ---- analog filters, [∫y dt; x'] = G [x; u], and digital filters, lane by lane
            for r in range(n_state + 1):
                for l in range(LANES):
                    tt[l] = 0.0
                for b in range(n_state + m):
                    for l in range(LANES):
                        tt[l] += gmat[r, b, l] * vv[b, l]
                for l in range(LANES):
                    yy[r, l] = tt[l]
            for r in range(n_state):
                for l in range(LANES):
                    vv[r, l] = yy[r + 1, l]
            for l in range(LANES):
                inc[l] = yy[0, l]
            if n_dig > 1:
                for l in range(LANES):
                    y = db[0, l] * inc[l] + dz[0, l]
                    for a in range(n_dig - 2):
                        dz[a, l] = db[a + 1, l] * inc[l] + dz[a + 1, l] - da[a + 1, l] * y
                    dz[n_dig - 2, l] = db[n_dig - 1, l] * inc[l] - da[n_dig - 1, l] * y
                    inc[l] = y
            for l in range(LANES):
                acc[l] += inc[l]
            sub += 1
            if sub < decimation:
                continue
            sub = 0
            # ---- one algorithm sample for each member
            for s in range(2):
                for a in range(WINDOW - 1):
                    for c in range(3):
                        window[s, a, c] = window[s, a + 1, c]
                        windowd[s, a, c] = windowd[s, a + 1, c]
                for c in range(3):
                    window[s, WINDOW - 1, c] = acc[s * CHANNELS + c]
                    if DUAL:
                        windowd[s, WINDOW - 1, c] = acc[s * CHANNELS + 3 + c]
            acc[:] = 0.0
            if j + 1 <= warm_samples:
                continue
            sample_count += 1
            if sample_count % SAMPLES != 0:
                continue
            for s in range(2):
                px, py, pz, pdx, pdy, pdz = increment(window[s], windowd[s])
                l0, l1, l2, l3 = lq[s, 0], lq[s, 1], lq[s, 2], lq[s, 3]
                if DUAL:  # velocity increment in the step's start frame: J_l(Δφ) Δφ°, rotated into I
                    sa, ca, da_ = so3_coefficients(px * px + py * py + pz * pz)
                    cx, cy, cz = cross(px, py, pz, pdx, pdy, pdz)
                    ccx, ccy, ccz = cross(px, py, pz, cx, cy, cz)
                    gx, gy, gz = rotate(l0, l1, l2, l3, pdx + ca * cx + da_ * ccx, pdy + ca * cy + da_ * ccy, pdz + ca * cz + da_ * ccz)
                    wc[s, 0] += gx
                    wc[s, 1] += gy
                    wc[s, 2] += gz
                s0, s1, s2, s3 = quat_of(px, py, pz)
                l0, l1, l2, l3 = qmul(l0, l1, l2, l3, s0, s1, s2, s3)
                norm = 1.0 / math.sqrt(l0 * l0 + l1 * l1 + l2 * l2 + l3 * l3)
                lq[s, 0], lq[s, 1], lq[s, 2], lq[s, 3] = l0 * norm, l1 * norm, l2 * norm, l3 * norm
        for s in range(2):
            for c in range(6):
                out[2 * p + s, c] = s_ke[s, c] / s_kt
