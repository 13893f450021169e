"""Peer comparison: the compiled kernels against pyins (``python-ins`` on the package index), like for like.

pyins's strapdown integrator takes attitude increments ``θ_k`` (its
``compute_increments_from_imu`` for an increment-type IMU forms
``θ_k = p_k + (1/12) p_{k−1} × p_k``: Savage's "1 + 1" coning term, a
cross-step algorithm with one sample per step) and multiplies direction-cosine
matrices in a numba loop.  The same algorithm, written as data
(``N = 1``, ``(1/12) p_0 × p_1``), runs in this package's fused kernel.  Both
sides get the exact increments (2.1) of the coning of Budennyi, Kalinovsky,
Panov et al. (Part 2), Table 3 (ε = −1, ϑ = 1°, 10 Hz, sampled at 400 Hz),
with the sample before t = 0 that the cross-step term reads, and both are
compared with the exact solution (Lebedev & Panov 1989, (4.4)).

Like for like:

1. **Earth.** pyins integrates in a local-level frame on a rotating Earth.
   Its Earth rate ``pyins.earth.RATE`` is set to zero before its loop is
   compiled, the body is at rest (no specific force, horizontal channel only:
   ``with_altitude=False``), so the transport rate is zero and its
   navigation frame is inertial: its DCM is our Λ (body → reference), updated
   on the right by the step rotation, as ours.
2. **Same algorithm, same error.** Both error series are the package's
   ``δφ_I = rotvec(Λ_exact ∘ Λ̄_computed)`` (exact minus algorithm, frame I, as
   ``SimulationResult.attitude_error``); the two must agree to round-off, vector
   by vector, and the script prints the largest gap.
3. **Vectorised mode**: pyins's ``compute_increments_from_imu`` (numpy) plus
   one ``Integrator.integrate`` over the record, against one call of our kernel
   over the record (``simulate_batch``, statistics only, and with the error
   series).
4. **One call per step**: ``Integrator.integrate`` with one increment per call
   (its real-time use; pandas bookkeeping included, as a user pays it) against
   one kernel call per step (``kernels.advance`` over one step).

Run: ``python benchmarks/peer_pyins.py [--duration 100]``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from fractions import Fraction

import numpy as np

from strapdown.analysis.coning import kernels
from strapdown.analysis.coning.batch import simulate_batch
from strapdown.analysis.coning.precession import RegularPrecession, exact_state
from strapdown.analysis.coning.streaming import empty_sums
from strapdown.analysis.core import quaternion as quat
from strapdown.analysis.core.units import deg_per_h
from strapdown.derivations.coning.algorithms import Algorithm, Term
from strapdown.derivations.coning.registry import get

RATE = 400.0
H = 1.0 / RATE
MOTION = RegularPrecession(-1.0, 2 * math.pi * 10.0, math.radians(1.0))
SAVAGE = Algorithm("savage-1+1", 1, (Term(Fraction(1, 12), (0, 1)),), description="p_k + (1/12) p_{k-1} × p_k", reference="Savage (1998); pyins")
RAD_S_TO_DEG_H = 180.0 / math.pi * 3600.0


def best(fn, repeats=3):
    t_best, out = float("inf"), None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        t_best = min(t_best, time.perf_counter() - t)
    return t_best, out


def error_vectors(q, times):
    """``δφ_I = rotvec(Λ_exact ∘ Λ̄)`` [rad]: exact minus computed, frame I (the package convention)."""
    exact = exact_state(MOTION, times).attitude
    return quat.quat_to_rotvec(quat.multiply(exact, quat.conjugate(q)), canonical=True, validate=False)


def slope(t, y):
    tc = t - t.mean()
    return float(tc @ y / (tc @ tc))


# --------------------------------------------------------------------------- pyins
def pyins_setup():
    import pyins.earth

    pyins.earth.RATE = 0.0  # before the first call compiles its loop: an inertial navigation frame
    import pandas as pd
    from pyins import strapdown
    from scipy.spatial.transform import Rotation

    return pd, strapdown, Rotation


def pyins_imu(pd, n):
    p = MOTION.grid_increments(H, -1, n + 1)  # row 0: the sample before t = 0 ("before" sample)
    frame = pd.DataFrame(np.hstack([p, np.zeros_like(p)]), index=np.arange(n + 1) * H, columns=["gyro_x", "gyro_y", "gyro_z", "accel_x", "accel_y", "accel_z"])
    return frame


def pyins_start(pd):
    return pd.Series({"lat": 0.0, "lon": 0.0, "alt": 0.0, "VN": 0.0, "VE": 0.0, "VD": 0.0, "roll": 0.0, "pitch": 0.0, "heading": 0.0})


def to_quat(Rotation, mats):
    q = Rotation.from_matrix(mats).as_quat()  # scalar last
    return np.concatenate([q[:, 3:], q[:, :3]], axis=-1)


def run_pyins(n, repeats):
    pd, strapdown, Rotation = pyins_setup()
    imu = pyins_imu(pd, n)

    def vectorised():
        inc = strapdown.compute_increments_from_imu(imu, "increment")
        integ = strapdown.Integrator(pyins_start(pd), with_altitude=False)
        integ.integrate(inc)
        return integ.mat_nb[1 : n + 1].copy()

    vectorised()  # numba compilation, not timed
    seconds, mats = best(vectorised, repeats)
    q = to_quat(Rotation, mats)
    m = min(n, 2000)
    inc = strapdown.compute_increments_from_imu(imu.iloc[: m + 1], "increment")

    def per_step():
        integ = strapdown.Integrator(pyins_start(pd), with_altitude=False)
        for k in range(m):
            integ.integrate(inc.iloc[k : k + 1])
        return integ.mat_nb[1 : m + 1].copy()

    step_seconds, step_mats = best(per_step, 1)
    np.testing.assert_allclose(step_mats, mats[:m], rtol=0, atol=1e-15)
    return seconds, q, step_seconds / m


# --------------------------------------------------------------------------- ours
def run_ours(alg, n, repeats):
    args = (alg, MOTION.eps, MOTION.nu, MOTION.nutation, H)
    simulate_batch(*args, steps=16)  # compile or load the kernel, not timed
    stats_seconds, r = best(lambda: simulate_batch(*args, steps=n // alg.samples), repeats)
    series_seconds, rs = best(lambda: simulate_batch(*args, steps=n // alg.samples, series=True), repeats)
    run = kernels.kernel(alg, velocity=False)
    m = min(n // alg.samples, 20000)
    par, theta = kernels.parameter_rows(*(np.array([v]) for v in (MOTION.eps, MOTION.nu, MOTION.nutation, 0.0, 0.0, H)), np.array([1.0, 0, 0, 0]), np.zeros(3), velocity=False)
    steps = np.array([m])

    def per_step():
        sums, th = empty_sums(1), theta.copy()
        for k in range(m):
            kernels.advance(run, par, th, steps, sums, k, k + 1)
        return sums

    step_seconds, _ = best(per_step, 1)
    return stats_seconds, series_seconds, rs, step_seconds / m, r


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=100.0, help="simulated time [s] (default 100)")
    parser.add_argument("--repeats", type=int, default=3, help="timing repeats (best kept)")
    args = parser.parse_args(argv)
    n = int(round(args.duration * RATE))
    load = os.getloadavg()
    peer_seconds, peer_q, peer_step = run_pyins(n, args.repeats)
    times = np.arange(1, n + 1) * H
    peer_error = error_vectors(peer_q, times)
    peer_angle = np.linalg.norm(peer_error, axis=-1)
    rows = [("pyins 1.0 `Integrator` (θ = p + p_prev × p / 12, DCM)", peer_angle, n / peer_seconds, 1 / peer_step, None)]
    for alg in (SAVAGE, get("two-sample"), get("panov-4s-3")):
        stats_s, series_s, rs, step_s, r = run_ours(alg, n, args.repeats)
        t = np.arange(rs.attitude_error.shape[0]) * alg.samples * H
        angle = np.linalg.norm(rs.attitude_error, axis=-1)
        if alg is SAVAGE:
            gap = float(np.linalg.norm(rs.attitude_error[1:] - peer_error, axis=-1).max())
        rows.append((f"{alg.name} (this package, compiled)", (t, angle), n / stats_s, alg.samples / step_s, (n / series_s, float(deg_per_h(r.drift_rate)))))
    print(f"machine load (1, 5, 15 min) at start: {load[0]:.2f}, {load[1]:.2f}, {load[2]:.2f}; pinned to one core by run_all.py")
    print()
    print(f"**coning: ε = −1, ϑ = 1°, 10 Hz**, sampled at {RATE:.0f} Hz for {args.duration:g} s (attitude only)")
    print()
    print("| method | drift [deg/h] | error at end [rad] | vectorised [samples/s] | with error series [samples/s] | one call per step [samples/s] | vectorised: ours/pyins | per step: ours/pyins |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    peer_rate, peer_step_rate = rows[0][2], rows[0][3]
    for label, data, rate, step_rate, extra in rows:
        if extra is None:
            print(f"| {label} | {slope(times, data) * RAD_S_TO_DEG_H:.4g} | {data[-1]:.3e} | {rate:,.0f} | | {step_rate:,.0f} | | |")
        else:
            t, angle = data
            print(
                f"| {label} | {slope(t, angle) * RAD_S_TO_DEG_H:.4g} | {angle[-1]:.3e} | {rate:,.0f} | {extra[0]:,.0f} | {step_rate:,.0f} | "
                f"{rate / peer_rate:.1f}× | {step_rate / peer_step_rate:.0f}× |"
            )
    print()
    print(f"Same algorithm (savage-1+1 against pyins): largest gap between the two attitude-error vectors δφ_I over the run {gap:.1e} rad.")
    print("Per-step rates: pyins over 2000 calls (its integrate() appends to a pandas frame each call), ours over 20 000 kernel calls;")
    print("a 'sample' is one gyro increment (an N-sample step consumes N). Drift is the slope of the error angle.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
