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
def cross(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@numba.njit(cache=True)
def cross_rows(A, i, B, j, out):
    """``out = A[i] × B[j]`` for rows of ``(W, 3)`` arrays, without making views of the rows."""
    out[0] = A[i, 1] * B[j, 2] - A[i, 2] * B[j, 1]
    out[1] = A[i, 2] * B[j, 0] - A[i, 0] * B[j, 2]
    out[2] = A[i, 0] * B[j, 1] - A[i, 1] * B[j, 0]


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
    eg = np.zeros(3)
    ea = np.zeros(3)
    tmp = np.zeros(3)
    tmp2 = np.zeros(3)
    phi = np.zeros(3)
    phid = np.zeros(3)
    S = np.zeros(3)
    D = np.zeros(3)
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
    dV = np.zeros(3)
    dR = np.zeros(3)
    # whole quanta counted so far per axis (the floor of the residue), carried from sample to sample
    gfl = np.zeros(3)
    afl = np.zeros(3)
    for k in range(3):
        if gq[k] > 0.0:
            gfl[k] = math.floor(gres[k] / gq[k])
        if aq[k] > 0.0:
            afl[k] = math.floor(ares[k] / aq[k])
    for step in range(steps):
        if step % block == 0:  # the errors of a block of steps, shared evenly among its steps
            draw_step(g, N, H * block, gwhite, gphi, gc, gL, gx, egb)
            draw_step(g, N, H * block, awhite, aphi, ac, aL, ax, eab)
            for k in range(3):
                eg[k] = egb[k] / block
                ea[k] = eab[k] / block
        # shift the history
        for i in range(hist):
            for k in range(3):
                P[i, k] = P[i + N, k]
                B[i, k] = B[i + N, k]
        for j in range(N):
            for k in range(3):
                pv = p0[k] + (gconst[k] * H + eg[k]) / N
                bv = b0[k] + (aconst[k] * H + ea[k]) / N
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
        for k in range(3):
            phi[k] = 0.0
            phid[k] = 0.0
            S[k] = 0.0
            D[k] = 0.0
        for j in range(N):
            for k in range(3):
                phi[k] += P[hist + j, k]
                phid[k] += B[hist + j, k]
                S[k] += h * sw[j] * B[hist + j, k]
        for m in range(pi.shape[0]):
            cross_rows(P, pi[m], P, pj[m], tmp)
            for k in range(3):
                phi[k] += pc[m] * tmp[k]
            cross_rows(P, pi[m], B, pj[m], tmp)
            cross_rows(B, pi[m], P, pj[m], tmp2)
            for k in range(3):
                phid[k] += pc[m] * (tmp[k] + tmp2[k])
        for i in range(N):
            for k in range(3):
                tmp2[k] = 0.0
            for j in range(N):
                for k in range(3):
                    tmp2[k] += dw[i, j] * B[hist + j, k]
            tmp[0] = P[hist + i, 1] * tmp2[2] - P[hist + i, 2] * tmp2[1]
            tmp[1] = P[hist + i, 2] * tmp2[0] - P[hist + i, 0] * tmp2[2]
            tmp[2] = P[hist + i, 0] * tmp2[1] - P[hist + i, 1] * tmp2[0]
            for k in range(3):
                D[k] += h * tmp[k]
        t2 = phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]
        if t2 < 0.1:  # the series, five terms (integration.jacobian_terms)
            ja = 1.0 / 2.0 - t2 * (1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 / 3628800.0)))
            jb = 1.0 / 6.0 - t2 * (1.0 / 120.0 - t2 * (1.0 / 5040.0 - t2 * (1.0 / 362880.0 - t2 / 39916800.0)))
            jc = 1.0 / 24.0 - t2 * (1.0 / 720.0 - t2 * (1.0 / 40320.0 - t2 * (1.0 / 3628800.0 - t2 / 479001600.0)))
        else:
            th = math.sqrt(t2)
            ja = (1.0 - math.cos(th)) / t2
            jb = (th - math.sin(th)) / (t2 * th)
            jc = (0.5 * t2 + math.cos(th) - 1.0) / (t2 * t2)
        cross(phi, phid, tmp)
        cross(phi, tmp, tmp2)
        for k in range(3):
            dV[k] = phid[k] + ja * tmp[k] + jb * tmp2[k]
        cross(phi, S, tmp)
        cross(phi, tmp, tmp2)
        for k in range(3):
            dR[k] = S[k] + 2.0 * jb * tmp[k] + 2.0 * jc * tmp2[k] + D[k] + prate[k] * H
        # to frame I with the attitude at the start of the step
        q0, q1, q2, q3 = lam[0], lam[1], lam[2], lam[3]
        c00 = q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3
        c01 = 2.0 * (q1 * q2 - q0 * q3)
        c02 = 2.0 * (q1 * q3 + q0 * q2)
        c10 = 2.0 * (q1 * q2 + q0 * q3)
        c11 = q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3
        c12 = 2.0 * (q2 * q3 - q0 * q1)
        c20 = 2.0 * (q1 * q3 - q0 * q2)
        c21 = 2.0 * (q2 * q3 + q0 * q1)
        c22 = q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3
        dVi0 = c00 * dV[0] + c01 * dV[1] + c02 * dV[2]
        dVi1 = c10 * dV[0] + c11 * dV[1] + c12 * dV[2]
        dVi2 = c20 * dV[0] + c21 * dV[1] + c22 * dV[2]
        dRi0 = c00 * dR[0] + c01 * dR[1] + c02 * dR[2]
        dRi1 = c10 * dR[0] + c11 * dR[1] + c12 * dR[2]
        dRi2 = c20 * dR[0] + c21 * dR[1] + c22 * dR[2]
        # gravitation, trapezoid with a predicted end point
        rho = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
        k0 = -g0 * R * R / (rho * rho * rho)
        G00, G01, G02 = k0 * r[0] - Om * Om * r[0], k0 * r[1] - Om * Om * r[1], k0 * r[2]
        x0 = r[0] + v[0] * H + dRi0 + 0.5 * G00 * H * H
        x1 = r[1] + v[1] * H + dRi1 + 0.5 * G01 * H * H
        x2 = r[2] + v[2] * H + dRi2 + 0.5 * G02 * H * H
        rho = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
        k1 = -g0 * R * R / (rho * rho * rho)
        G10, G11, G12 = k1 * x0 - Om * Om * x0, k1 * x1 - Om * Om * x1, k1 * x2
        r[0] += v[0] * H + dRi0 + H * H * (G00 / 3.0 + G10 / 6.0)
        r[1] += v[1] * H + dRi1 + H * H * (G01 / 3.0 + G11 / 6.0)
        r[2] += v[2] * H + dRi2 + H * H * (G02 / 3.0 + G12 / 6.0)
        v[0] += dVi0 + 0.5 * H * (G00 + G10)
        v[1] += dVi1 + 0.5 * H * (G01 + G11)
        v[2] += dVi2 + 0.5 * H * (G02 + G12)
        # attitude: Λ ← Λ ∘ exp(φ/2)
        th = math.sqrt(t2)
        if th < 1e-8:
            s0, sv = 1.0 - t2 / 8.0, 0.5 - t2 / 48.0
        else:
            s0, sv = math.cos(0.5 * th), math.sin(0.5 * th) / th
        u0, u1, u2, u3 = s0, sv * phi[0], sv * phi[1], sv * phi[2]
        n0 = q0 * u0 - q1 * u1 - q2 * u2 - q3 * u3
        n1 = q0 * u1 + q1 * u0 + q2 * u3 - q3 * u2
        n2 = q0 * u2 - q1 * u3 + q2 * u0 + q3 * u1
        n3 = q0 * u3 + q1 * u2 - q2 * u1 + q3 * u0
        nn = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2 + n3 * n3)
        lam[0], lam[1], lam[2], lam[3] = n0 / nn, n1 / nn, n2 / nn, n3 / nn
        # vertical channel held: back on the sphere, no radial velocity over the Earth
        rho = math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2])
        for k in range(3):
            r[k] *= R / rho
        w0, w1 = v[0] + Om * r[1], v[1] - Om * r[0]  # v − Ω × r
        w2 = v[2]
        radial = (w0 * r[0] + w1 * r[1] + w2 * r[2]) / R
        w0 -= radial * r[0] / R
        w1 -= radial * r[1] / R
        w2 -= radial * r[2] / R
        v[0], v[1], v[2] = w0 - Om * r[1], w1 + Om * r[0], w2
        while rec < nrec and record[rec] == step + 1:
            for k in range(4):
                out_lam[rec, k] = lam[k]
            for k in range(3):
                out_v[rec, k] = v[k]
                out_r[rec, k] = r[k]
            rec += 1
