"""Peer comparison: strapdown-analysis algorithms against smsfusion's ``StrapdownINS``.

Both sides get the same ideal inertial data of the same closed-form motions
(regular precession, Lebedev & Panov 1989, section 4) and are compared with
the exact solution (:func:`strapdown.analysis.coning.precession.exact_state`):

* ``coning``: Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3 conditions:
  ε = −1, ϑ = 1°, f = 10 Hz (ν = 2π·10 s⁻¹), sampled at 400 Hz (h = 1/400 s,
  so a four-sample step is H = 0.01 s);
* ``sculling``: the same coning with a dual nutation ϑ° (Lebedev & Panov 1989,
  eq. 4.2): a specific force rotating in step with the coning, so velocity
  algorithms see sculling; W_I(t) stays bounded, so its growth is error.

Our side evaluates each registry algorithm vectorised over the record:
increments → :func:`strapdown.analysis.coning.evaluation.increment` → step (bi)quaternions by
:func:`strapdown.analysis.core.quaternion.rotvec_to_quat` → a cumulative product (a
log-depth prefix scan, no Python loop per step).  It is also timed one step
per call, as a real-time loop would run it.

smsfusion 1.9's ``StrapdownINS.update(f_imu, w_imu)`` takes one specific-force
and one rate *sample* per call and integrates them as constants over the
sample period: first-order (Euler) quaternion update with renormalisation, a
rectangular velocity update with the attitude at the start of the step, and a
constant gravity vector added in NED.  The differences are handled so:

1. Inputs.  We take increments ∫ω dt, ∫a dt.  smsfusion gets the *same* data
   as mean rate and mean specific force (increment / h), and, separately,
   point samples ω(t_k), a(t_k) at the start of each interval, as a user with
   a rate gyro would feed it.
2. Gravity and Earth.  smsfusion always adds ``g`` in NED and has no Earth
   rate; we construct it with ``g = 0`` so that its velocity is the apparent
   velocity W_I in the inertial frame, the quantity our algorithms compute.
3. Order.  smsfusion has no coning or sculling compensation: it is a
   first-order integrator, ours are fourth to sixth order.  The accuracy ratio
   therefore measures algorithm order, not implementation quality.
4. Speed.  smsfusion is a per-sample Python method (its helpers are numba
   compiled; the compilation is excluded by a warm-up call).  Our vectorised
   figure processes a stored record; the per-step figure is the like-for-like
   real-time comparison.

Run: ``python benchmarks/peer_smsfusion.py [--duration 100] [--markdown]``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from strapdown.analysis.coning.batch import simulate_batch  # noqa: E402
from strapdown.analysis.coning.evaluation import increment  # noqa: E402
from strapdown.analysis.coning.precession import RegularPrecession, exact_state, initial_biquaternion  # noqa: E402
from strapdown.analysis.core import quaternion as quat  # noqa: E402
from strapdown.analysis.core.dual import Dual  # noqa: E402
from strapdown.derivations.coning.registry import get  # noqa: E402

RAD_S_TO_DEG_H = 180.0 / math.pi * 3600.0
RATE = 400.0  # sampling rate [Hz]
NU = 2.0 * math.pi * 10.0  # 10 Hz coning [rad/s]
NUTATION = math.radians(1.0)
NUTATION_DUAL = 0.1  # ϑ° [m/s]: lateral specific force of amplitude ν ϑ° ≈ 6.3 m/s²

CASES = {
    "coning": RegularPrecession(eps=-1.0, nu=NU, nutation=NUTATION),
    "sculling": RegularPrecession(eps=-1.0, nu=NU, nutation=NUTATION, nutation_dual=NUTATION_DUAL),
}
LABELS = {
    "coning": "coning: ε = −1, ϑ = 1°, 10 Hz",
    "sculling": f"sculling: the coning with ϑ° = {NUTATION_DUAL} m/s",
}
ALGORITHMS = ("two-sample", "optimal-3", "panov-4s-3", "lebedev-panov-4", "lebedev-panov-6")


@dataclass
class Run:
    """Accuracy and speed of one method on one case."""

    method: str
    samples: int
    drift_deg_h: float  # least-squares slope of the attitude error angle
    att_err_end: float  # attitude error angle at the end [rad]
    vel_err_end: float  # |ΔW_I| at the end [m/s] (nan for attitude-only runs)
    seconds: float  # processing time (best of repeats)

    @property
    def rate(self) -> float:
        return self.samples / self.seconds


# --------------------------------------------------------------------------- errors
def attitude_error(lam, lam_exact):
    """``δφ_I = rotvec(Λ_exact ∘ Λ̄)`` [rad]: exact minus computed, frame I, as ``SimulationResult.attitude_error``."""
    return quat.quat_to_rotvec(quat.multiply(lam_exact, quat.conjugate(lam)), canonical=True, validate=False)


def attitude_error_angle(lam, lam_exact):
    """``|δφ_I|`` [rad], the angle of the error rotation."""
    return np.linalg.norm(attitude_error(lam, lam_exact), axis=-1)


def drift(t, angle) -> float:
    """Least-squares slope of the error angle against time [deg/h]."""
    slope = np.polyfit(t, angle, 1)[0]
    return float(slope * RAD_S_TO_DEG_H)


def best_time(fn, repeats: int) -> tuple:
    best, out = math.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - start)
    return best, out


# --------------------------------------------------------------------------- our side
def cumulative_product(q):
    """Prefix products ``q[0] ∘ q[1] ∘ … ∘ q[k]`` along axis 0 (Hillis–Steele scan, log₂ n passes)."""
    k = 1
    n = q.shape[0]
    while k < n:
        q = np.concatenate([q[:k], quat.multiply(q[:-k], q[k:])], axis=0)
        k *= 2
    return q


def ours_vectorised(alg, p, start):
    """Attitude (or biquaternion) after each step of ``alg`` from increments ``p`` (steps, N, 3)."""
    steps = quat.rotvec_to_quat(increment(alg, p), validate=False)
    return quat.multiply(start, cumulative_product(steps))


def ours_per_step(alg, p, start):
    """The same, one step per Python call (a real-time loop)."""
    q = start
    for j in range(p.shape[0]):
        q = quat.multiply(q, quat.rotvec_to_quat(increment(alg, p[j]), validate=False))
    return q


def run_ours(name, motion, duration, repeats):
    alg = get(name)
    n_steps = int(round(duration * RATE)) // alg.samples
    n = n_steps * alg.samples
    h = 1.0 / RATE
    edges = np.arange(n + 1) * h
    t_step = edges[alg.samples :: alg.samples]
    lam0 = motion.attitude(0.0)
    exact = exact_state(motion, t_step, attitude0=lam0)
    if motion.is_dual:
        inc = motion.increments(edges[:-1], edges[1:])
        p = Dual(inc.re.reshape(n_steps, alg.samples, 3), inc.du.reshape(n_steps, alg.samples, 3))
        start = initial_biquaternion(lam0, np.zeros(3))
    else:
        p = motion.angle_increments(edges[:-1], edges[1:]).reshape(n_steps, alg.samples, 3)
        start = lam0
    seconds, theta = best_time(lambda: ours_vectorised(alg, p, start), repeats)
    if motion.is_dual:
        lam = theta.re
        w_i = 2.0 * quat.vect(quat.multiply(theta.du, quat.conjugate(lam)))
        vel_err = float(np.linalg.norm(exact.w_inertial[-1] - w_i[-1]))  # |W_I* − W_I|
    else:
        lam, vel_err = theta, math.nan
    angle = attitude_error_angle(lam, exact.attitude)
    vec = Run(f"{name} (vectorised)", n, drift(t_step, angle), float(angle[-1]), vel_err, seconds)
    # one step per call: time a slice and check it agrees with the vectorised run
    m = max(1, min(n_steps, 2000))
    per_seconds, last = best_time(lambda: ours_per_step(alg, p[:m], start), 1)
    last_lam = last.re if motion.is_dual else last
    ref = theta.re[m - 1] if motion.is_dual else theta[m - 1]
    mismatch = float(attitude_error_angle(last_lam, ref))
    if mismatch > 1e-12:
        raise RuntimeError(f"per-step and vectorised runs of {name} disagree by {mismatch:.1e} rad")
    loop = Run(f"{name} (one step per call)", n, vec.drift_deg_h, vec.att_err_end, vec.vel_err_end, per_seconds * n_steps / m)
    # the fused compiled kernel over the record (statistics only for the timing; the series for the accuracy)
    kw = {"nu_dual": motion.nu_dual, "nutation_dual": motion.nutation_dual, "attitude0": lam0, "velocity": motion.is_dual}
    args = (alg, motion.eps, motion.nu, motion.nutation, h)
    simulate_batch(*args, steps=16, **kw)  # compile or load the kernel, not timed
    fused_seconds, _ = best_time(lambda: simulate_batch(*args, steps=n_steps, **kw), repeats)
    r = simulate_batch(*args, steps=n_steps, series=True, **kw)
    fused_angle = np.linalg.norm(r.attitude_error[1:], axis=-1)
    fused_vel = float(np.linalg.norm(r.dw_inertial[-1])) if motion.is_dual else math.nan
    fused = Run(f"{name} (compiled kernel)", n, drift(t_step, fused_angle), float(fused_angle[-1]), fused_vel, fused_seconds)
    return vec, loop, fused


# --------------------------------------------------------------------------- smsfusion
def _check_conventions(StrapdownINS):
    """smsfusion's quaternion is body→navigation and propagates as ``2q' = q ∘ ω``, like Λ."""
    q0 = quat.rotvec_to_quat(np.array([0.3, -0.2, 0.5]))
    w = np.array([0.4, -0.7, 0.2])
    dt = 1e-5
    ins = StrapdownINS(1.0 / dt, np.r_[np.zeros(6), q0, np.zeros(6)], g=0.0)
    ins.update(np.zeros(3), w)
    ours = quat.multiply(q0, quat.rotvec_to_quat(w * dt))
    gap = float(attitude_error_angle(ins.quaternion(), ours))
    if gap > 1e-9:
        raise RuntimeError(f"smsfusion's quaternion convention differs from ours (gap {gap:.1e} rad after one step)")
    f = np.array([1.0, 2.0, 3.0])
    ins = StrapdownINS(1.0, np.r_[np.zeros(6), q0, np.zeros(6)], g=0.0)
    ins.update(f, np.zeros(3))
    gap = float(np.linalg.norm(ins.velocity() - quat.rotate(q0, f)))
    if gap > 1e-12:
        raise RuntimeError(f"smsfusion's specific force is not resolved body→navigation like ours (gap {gap:.1e})")


def run_smsfusion(motion, duration, repeats, *, inputs: str):
    from smsfusion import StrapdownINS

    _check_conventions(StrapdownINS)
    n = int(round(duration * RATE))
    h = 1.0 / RATE
    edges = np.arange(n + 1) * h
    if inputs == "mean":
        inc = motion.increments(edges[:-1], edges[1:])
        w, f = inc.re / h, inc.du / h
    else:
        w, f = motion.omega(edges[:-1]), motion.accel(edges[:-1])
    lam0 = motion.attitude(0.0)
    x0 = np.r_[np.zeros(6), lam0, np.zeros(6)]
    StrapdownINS(RATE, x0, g=0.0).update(f[0], w[0])  # numba compilation, not timed

    def integrate():
        ins = StrapdownINS(RATE, x0, g=0.0)
        q = np.empty((n, 4))
        v = np.empty((n, 3))
        for k in range(n):
            ins.update(f[k], w[k])
            q[k] = ins.quaternion()
            v[k] = ins.velocity()
        return q, v

    seconds, (q, v) = best_time(integrate, repeats)
    exact = exact_state(motion, edges[1:], attitude0=lam0)
    angle = attitude_error_angle(q, exact.attitude)
    vel_err = float(np.linalg.norm(exact.w_inertial[-1] - v[-1])) if motion.is_dual else math.nan
    label = "smsfusion StrapdownINS, mean rate & force (= our increments / h)" if inputs == "mean" else "smsfusion StrapdownINS, point samples at interval starts"
    return Run(label, n, drift(edges[1:], angle), float(angle[-1]), vel_err, seconds)


# --------------------------------------------------------------------------- report
def compare(duration: float = 100.0, repeats: int = 3, algorithms=ALGORITHMS) -> dict:
    results = {}
    for case, motion in CASES.items():
        runs = [run_smsfusion(motion, duration, 1, inputs="mean"), run_smsfusion(motion, duration, 1, inputs="point")]
        for name in algorithms:
            runs.extend(run_ours(name, motion, duration, repeats))
        results[case] = runs
    return results


def table(results: dict, duration: float) -> str:
    lines = []
    for case, runs in results.items():
        peer = runs[0]
        dual = not math.isnan(peer.vel_err_end)
        lines += [
            f"**{LABELS[case]}**, sampled at {RATE:.0f} Hz for {duration:g} s",
            "",
            "| method | drift [deg/h] | attitude error at end [rad] | "
            + ("\\|ΔW_I\\| at end [m/s] | " if dual else "")
            + "samples/s | drift: smsfusion / this | "
            + ("\\|ΔW_I\\|: smsfusion / this | " if dual else "")
            + "speed: this / smsfusion |",
            "|---|---:|---:|" + ("---:|" if dual else "") + "---:|---:|" + ("---:|" if dual else "") + "---:|",
        ]
        for r in runs:
            is_peer = r.method.startswith("smsfusion")
            acc = "" if is_peer else _ratio(abs(peer.drift_deg_h) / max(abs(r.drift_deg_h), 1e-300))
            spd = "" if is_peer else _ratio(r.rate / peer.rate)
            vel = f"{r.vel_err_end:.2e} | " if dual else ""
            vel_ratio = ("| " if is_peer else f"{_ratio(peer.vel_err_end / r.vel_err_end)} | ") if dual else ""
            lines.append(f"| {r.method} | {r.drift_deg_h:.3g} | {r.att_err_end:.2e} | {vel}{r.rate:,.0f} | {acc} | {vel_ratio}{spd} |")
        lines.append("")
    return "\n".join(lines)


def _ratio(x: float) -> str:
    return f"{x:,.0f}×" if x >= 100 else f"{x:.2g}×"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=100.0, help="simulated time [s] (default 100)")
    parser.add_argument("--repeats", type=int, default=3, help="timing repeats of our vectorised runs (best is kept)")
    args = parser.parse_args(argv)
    results = compare(args.duration, args.repeats)
    print(table(results, args.duration))
    print("Ratios are against the first smsfusion row (the same data as our increments).")
    print("smsfusion is a first-order integrator with no coning/sculling compensation, fed one sample per")
    print("Python call; it was built with g = 0 so that its velocity is the inertial apparent velocity W_I.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
