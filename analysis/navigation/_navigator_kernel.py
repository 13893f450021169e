"""The compiled step loop of the navigator (:func:`strapdown.analysis.navigation.mechanization.run_navigator`).

Kept at module level, apart from the rest of the mechanization, so that numba's
on-disk cache finds the machine code again in the next process (a kernel that
calls other kernels through a closure is keyed by their pickled dispatchers,
which differ between processes, and is compiled again every time); the module
is imported only when a navigator runs, so numba is not imported before.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["run"]


@numba.njit(cache=True)
def draw_step(g, N, H, white, phi, c, L, x, out):
    """Error of one step per axis (sum over its samples) of white noise and the first-order terms; updates x.

    Each first-order term's pair (level, integral) is drawn with its Cholesky
    factor ``L``: the level's innovation ``L[0, 0] z₁`` and the integral's
    ``L[1, 0] z₁ + L[1, 1] z₂``.  The parts that drive no state, the white noise
    and every ``L[1, 1] z₂``, are independent Gaussians that only add up: one
    draw of their summed variance gives the same distribution as one draw each.
    """
    var = white * white * H
    for m in range(phi.shape[0]):
        var += L[m, 1, 1] * L[m, 1, 1]
    sd = math.sqrt(var)
    for k in range(3):
        e = 0.0
        for m in range(phi.shape[0]):
            z1 = g.standard_normal()
            e += c[m] * x[m, k] + L[m, 1, 0] * z1
            x[m, k] = phi[m] * x[m, k] + L[m, 0, 0] * z1
        if sd > 0.0:
            e += sd * g.standard_normal()
        out[k] = e


@numba.njit(cache=True)
def run(g, mode, steps, block, N, hist, h, p0, b0, pi, pj, pc, sw, dw,
        gconst, aconst, prate, gwhite, awhite, gphi, gc, gL, gx, aphi, ac, aL, ax,
        gq, aq, gres, ares, lam, v, r, R, Om, g0, record, out_lam, out_v, out_r, sums):  # fmt: skip
    H = N * h
    W = N + hist
    P = np.zeros((W, 3))
    B = np.zeros((W, 3))
    # history rows start with the ideal increments (steady state before t = 0)
    for i in range(W):
        for k in range(3):
            P[i, k] = p0[k]
            B[i, k] = b0[k]
    rec = 0
    nrec = record.shape[0]
    while rec < nrec and record[rec] == 0:
        for k in range(4):
            out_lam[rec, k] = lam[k]
        for k in range(3):
            out_v[rec, k] = v[k]
            out_r[rec, k] = r[k]
        rec += 1
    egb = np.zeros(3)
    eab = np.zeros(3)
    # the ideal increment plus the block's error per sample, fixed over a block
    pinc = np.zeros(3)
    binc = np.zeros(3)
    # whole quanta counted so far per axis (the floor of the residue), carried from sample to sample
    gfl = np.zeros(3)
    afl = np.zeros(3)
    for k in range(3):
        if gq[k] > 0.0:
            gfl[k] = math.floor(gres[k] / gq[k])
        if aq[k] > 0.0:
            afl[k] = math.floor(ares[k] / aq[k])
    # the state in scalars (kept in registers across the steps), written back at the end
    q0, q1, q2, q3 = lam[0], lam[1], lam[2], lam[3]
    v0, v1, v2 = v[0], v[1], v[2]
    r0, r1, r2 = r[0], r[1], r[2]
    for step in range(steps):
        if step % block == 0:  # the errors of a block of steps, shared evenly among its steps
            draw_step(g, N, H * block, gwhite, gphi, gc, gL, gx, egb)
            draw_step(g, N, H * block, awhite, aphi, ac, aL, ax, eab)
            for k in range(3):
                pinc[k] = p0[k] + (gconst[k] * H + egb[k] / block) / N
                binc[k] = b0[k] + (aconst[k] * H + eab[k] / block) / N
        # shift the history
        for i in range(hist):
            for k in range(3):
                P[i, k] = P[i + N, k]
                B[i, k] = B[i + N, k]
        for j in range(N):
            for k in range(3):
                pv = pinc[k]
                bv = binc[k]
                if gq[k] > 0.0:
                    before = gq[k] * gfl[k]
                    gres[k] += pv
                    gfl[k] = math.floor(gres[k] / gq[k])
                    pv = gq[k] * gfl[k] - before
                if aq[k] > 0.0:
                    before = aq[k] * afl[k]
                    ares[k] += bv
                    afl[k] = math.floor(ares[k] / aq[k])
                    bv = aq[k] * afl[k] - before
                P[hist + j, k] = pv
                B[hist + j, k] = bv
        if mode == 0:  # alignment: sums of the increments only
            for j in range(N):
                for k in range(3):
                    sums[k] += P[hist + j, k]
                    sums[3 + k] += B[hist + j, k]
            continue
        # coning, sculling (dual extension), scrolling
        f0 = f1 = f2 = 0.0  # phi
        d0 = d1 = d2 = 0.0  # phi of the dual part
        s0 = s1 = s2 = 0.0  # S
        D0 = D1 = D2 = 0.0  # D
        for j in range(N):
            b_0, b_1, b_2 = B[hist + j, 0], B[hist + j, 1], B[hist + j, 2]
            f0 += P[hist + j, 0]
            f1 += P[hist + j, 1]
            f2 += P[hist + j, 2]
            d0 += b_0
            d1 += b_1
            d2 += b_2
            s0 += h * sw[j] * b_0
            s1 += h * sw[j] * b_1
            s2 += h * sw[j] * b_2
        for m in range(pi.shape[0]):
            i_, j_, c = pi[m], pj[m], pc[m]
            a0, a1, a2 = P[i_, 0], P[i_, 1], P[i_, 2]
            e0, e1, e2 = P[j_, 0], P[j_, 1], P[j_, 2]
            u0, u1, u2 = B[i_, 0], B[i_, 1], B[i_, 2]
            w0, w1, w2 = B[j_, 0], B[j_, 1], B[j_, 2]
            f0 += c * (a1 * e2 - a2 * e1)
            f1 += c * (a2 * e0 - a0 * e2)
            f2 += c * (a0 * e1 - a1 * e0)
            d0 += c * ((a1 * w2 - a2 * w1) + (u1 * e2 - u2 * e1))
            d1 += c * ((a2 * w0 - a0 * w2) + (u2 * e0 - u0 * e2))
            d2 += c * ((a0 * w1 - a1 * w0) + (u0 * e1 - u1 * e0))
        for i in range(N):
            y0 = y1 = y2 = 0.0
            for j in range(N):
                y0 += dw[i, j] * B[hist + j, 0]
                y1 += dw[i, j] * B[hist + j, 1]
                y2 += dw[i, j] * B[hist + j, 2]
            a0, a1, a2 = P[hist + i, 0], P[hist + i, 1], P[hist + i, 2]
            D0 += h * (a1 * y2 - a2 * y1)
            D1 += h * (a2 * y0 - a0 * y2)
            D2 += h * (a0 * y1 - a1 * y0)
        t2 = f0 * f0 + f1 * f1 + f2 * f2
        if t2 < 0.1:  # the series, five terms (integration.jacobian_terms)
            ja = 1.0 / 2.0 - t2 * (1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 / 3628800.0)))
            jb = 1.0 / 6.0 - t2 * (1.0 / 120.0 - t2 * (1.0 / 5040.0 - t2 * (1.0 / 362880.0 - t2 / 39916800.0)))
            jc = 1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 * (1.0 / 3628800.0 - t2 / 479001600.0)))
        else:
            th = math.sqrt(t2)
            ja = (1.0 - math.cos(th)) / t2
            jb = (th - math.sin(th)) / (t2 * th)
            jc = (0.5 * t2 + math.cos(th) - 1.0) / (t2 * t2)
        x0, x1, x2 = f1 * d2 - f2 * d1, f2 * d0 - f0 * d2, f0 * d1 - f1 * d0  # phi × phid
        z0, z1, z2 = f1 * x2 - f2 * x1, f2 * x0 - f0 * x2, f0 * x1 - f1 * x0  # phi × (phi × phid)
        dV0 = d0 + ja * x0 + jb * z0
        dV1 = d1 + ja * x1 + jb * z1
        dV2 = d2 + ja * x2 + jb * z2
        x0, x1, x2 = f1 * s2 - f2 * s1, f2 * s0 - f0 * s2, f0 * s1 - f1 * s0  # phi × S
        z0, z1, z2 = f1 * x2 - f2 * x1, f2 * x0 - f0 * x2, f0 * x1 - f1 * x0
        dR0 = s0 + 2.0 * jb * x0 + 2.0 * jc * z0 + D0 + prate[0] * H
        dR1 = s1 + 2.0 * jb * x1 + 2.0 * jc * z1 + D1 + prate[1] * H
        dR2 = s2 + 2.0 * jb * x2 + 2.0 * jc * z2 + D2 + prate[2] * H
        # to frame I with the attitude at the start of the step
        c00 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
        c01 = 2.0 * (q1 * q2 - q0 * q3)
        c02 = 2.0 * (q1 * q3 + q0 * q2)
        c10 = 2.0 * (q1 * q2 + q0 * q3)
        c11 = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3
        c12 = 2.0 * (q2 * q3 - q0 * q1)
        c20 = 2.0 * (q1 * q3 - q0 * q2)
        c21 = 2.0 * (q2 * q3 + q0 * q1)
        c22 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
        dVi0 = c00 * dV0 + c01 * dV1 + c02 * dV2
        dVi1 = c10 * dV0 + c11 * dV1 + c12 * dV2
        dVi2 = c20 * dV0 + c21 * dV1 + c22 * dV2
        dRi0 = c00 * dR0 + c01 * dR1 + c02 * dR2
        dRi1 = c10 * dR0 + c11 * dR1 + c12 * dR2
        dRi2 = c20 * dR0 + c21 * dR1 + c22 * dR2
        # gravitation, trapezoid with a predicted end point
        rho = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
        k0 = -g0 * R * R / (rho * rho * rho)
        G00, G01, G02 = k0 * r0 - Om * Om * r0, k0 * r1 - Om * Om * r1, k0 * r2
        x0 = r0 + v0 * H + dRi0 + 0.5 * G00 * H * H
        x1 = r1 + v1 * H + dRi1 + 0.5 * G01 * H * H
        x2 = r2 + v2 * H + dRi2 + 0.5 * G02 * H * H
        rho = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
        k1 = -g0 * R * R / (rho * rho * rho)
        G10, G11, G12 = k1 * x0 - Om * Om * x0, k1 * x1 - Om * Om * x1, k1 * x2
        r0 += v0 * H + dRi0 + H * H * (G00 / 3.0 + G10 / 6.0)
        r1 += v1 * H + dRi1 + H * H * (G01 / 3.0 + G11 / 6.0)
        r2 += v2 * H + dRi2 + H * H * (G02 / 3.0 + G12 / 6.0)
        v0 += dVi0 + 0.5 * H * (G00 + G10)
        v1 += dVi1 + 0.5 * H * (G01 + G11)
        v2 += dVi2 + 0.5 * H * (G02 + G12)
        # attitude: Λ ← Λ ∘ exp(φ/2)
        th = math.sqrt(t2)
        if th < 1e-8:
            e0, sv = 1.0 - t2 / 8.0, 0.5 - t2 / 48.0
        else:
            e0, sv = math.cos(0.5 * th), math.sin(0.5 * th) / th
        u0, u1, u2, u3 = e0, sv * f0, sv * f1, sv * f2
        n0 = q0 * u0 - q1 * u1 - q2 * u2 - q3 * u3
        n1 = q0 * u1 + q1 * u0 + q2 * u3 - q3 * u2
        n2 = q0 * u2 - q1 * u3 + q2 * u0 + q3 * u1
        n3 = q0 * u3 + q1 * u2 - q2 * u1 + q3 * u0
        nn = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2 + n3 * n3)
        q0, q1, q2, q3 = n0 / nn, n1 / nn, n2 / nn, n3 / nn
        # vertical channel held: back on the sphere, no radial velocity over the Earth
        rho = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
        r0 *= R / rho
        r1 *= R / rho
        r2 *= R / rho
        w0, w1 = v0 + Om * r1, v1 - Om * r0  # v − Ω × r
        w2 = v2
        radial = (w0 * r0 + w1 * r1 + w2 * r2) / R
        w0 -= radial * r0 / R
        w1 -= radial * r1 / R
        w2 -= radial * r2 / R
        v0, v1, v2 = w0 - Om * r1, w1 + Om * r0, w2
        while rec < nrec and record[rec] == step + 1:
            out_lam[rec, 0], out_lam[rec, 1], out_lam[rec, 2], out_lam[rec, 3] = q0, q1, q2, q3
            out_v[rec, 0], out_v[rec, 1], out_v[rec, 2] = v0, v1, v2
            out_r[rec, 0], out_r[rec, 1], out_r[rec, 2] = r0, r1, r2
            rec += 1
    lam[0], lam[1], lam[2], lam[3] = q0, q1, q2, q3
    v[0], v[1], v[2] = v0, v1, v2
    r[0], r[1], r[2] = r0, r1, r2
