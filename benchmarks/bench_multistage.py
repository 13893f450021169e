"""Benchmark: the stage recursion of Plotnikov (1999), compiled against plain Python.

Three implementations run side by side on the same inputs (the two stages of
section 5, 5000 s at h = 0.02 s), timing the recursion alone:

* "previous": the loop over Python floats that the package used before the
  recursion was compiled (copied below, components 1 and 3 only);
* "reference": :func:`strapdown.analysis.multistage.stage_recursion.stage_loop_python`,
  the plain-Python reference the tests compare the compiled loop against
  (it also handles all four components and the switch modes);
* "compiled": :func:`strapdown.analysis.multistage.stage_recursion.stage_loop` (numba).

Target: the compiled loop at least 50 times the previous one's rate.  The
whole pipeline (sampling the truth and sensors, both stages, composition) is
timed too.  Run from the repository root:

    python benchmarks/bench_multistage.py
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from strapdown.analysis.core import quaternion as quat  # noqa: E402
from strapdown.analysis.multistage import stage_recursion  # noqa: E402
from strapdown.analysis.multistage.stages import multistage_peaks, plotnikov_1999_stages, recursion_inputs, run_multistage  # noqa: E402
from strapdown.analysis.multistage.trajectory import Scenario, sample  # noqa: E402


def previous_loop(nu, dq, target, segments, maps, rho, step):
    """The stage loop as it was before compilation (components 1 and 3; lists of floats)."""
    n0, n1, n2, n3 = nu
    y1 = y3 = 0.0
    out = [(n0, n1, n2, n3)]
    outy = [(0.0, 0.0)]
    grow = math.exp(rho * step * 0.5)
    sqrt = math.sqrt
    norm_flow = rho > 0.0
    for (i0, i1), (e11, e12, e21, e22, f1, f2) in zip(segments, maps):
        for n in range(i0, i1):
            m1, m3 = target[n]
            a1 = e11 * n1 + e12 * y1 + f1 * m1
            y1 = e21 * n1 + e22 * y1 + f2 * m1
            a3 = e11 * n3 + e12 * y3 + f1 * m3
            y3 = e21 * n3 + e22 * y3 + f2 * m3
            a0, a2 = n0, n2
            if norm_flow:
                r = a0 * a0 + a1 * a1 + a2 * a2 + a3 * a3
                f = sqrt(grow / (1.0 - r + r * grow))  # exact norm flow over h/2
                a0, a1, a2, a3 = a0 * f, a1 * f, a2 * f, a3 * f
            b0, b1, b2, b3 = dq[n]
            c0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
            c1 = a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
            c2 = a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
            c3 = a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0
            if norm_flow:
                r = c0 * c0 + c1 * c1 + c2 * c2 + c3 * c3
                f = sqrt(grow / (1.0 - r + r * grow))  # exact norm flow over h/2
                c0, c1, c2, c3 = c0 * f, c1 * f, c2 * f, c3 * f
            n0, n2 = c0, c2
            n1 = e11 * c1 + e12 * y1 + f1 * m1
            y1 = e21 * c1 + e22 * y1 + f2 * m1
            n3 = e11 * c3 + e12 * y3 + f1 * m3
            y3 = e21 * c3 + e22 * y3 + f2 * m3
            out.append((n0, n1, n2, n3))
            outy.append((y1, y3))
    nu_out = np.array(out)
    y_out = np.zeros_like(nu_out)
    y_out[:, [1, 3]] = np.array(outy)
    return nu_out, y_out



def _previous(args):
    nu0, dq, ref_start, _, _, _, seg_start, maps, _, _, _, rho, h = args
    segments = list(zip(seg_start[:-1].tolist(), seg_start[1:].tolist()))
    return previous_loop(tuple(nu0), dq.tolist(), ref_start[:, [1, 3]].tolist(), segments, [tuple(m) for m in maps], rho, h)


def _best(fn, repeats):
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main(repeats: int = 5) -> None:
    scenario = Scenario()
    stages = plotnikov_1999_stages()
    step = 0.02
    data = sample(scenario, step, rng=0)
    dq = quat.rotvec_to_quat(data.gyro)
    n = dq.shape[0]
    print(f"stage recursion alone, {scenario.duration:g} s at h = {step:g} s ({n} steps)")
    print(f"{'stage':>26} {'previous [us/step]':>19} {'reference [us/step]':>20} {'compiled [us/step]':>19} {'compiled/previous':>18} {'target':>7}")
    for name, st in (("1: tilt quaternion (1.10)", stages[0]), ("2: (1.4), Schuler switch", stages[1])):
        args = recursion_inputs(st, step, dq, data.accel)
        stage_recursion.stage_loop(*args)  # load the compiled code (cached on disk)
        nu_prev, _ = _previous(args)
        nu_comp, _ = stage_recursion.stage_loop(*args)
        assert np.abs(nu_prev - nu_comp).max() < 1e-12
        t_prev = _best(lambda args=args: _previous(args), 1)
        t_ref = _best(lambda args=args: stage_recursion.stage_loop_python(*args), 1)
        t_comp = _best(lambda args=args: stage_recursion.stage_loop(*args), repeats)
        print(f"{name:>26} {1e6 * t_prev / n:19.3f} {1e6 * t_ref / n:20.3f} {1e6 * t_comp / n:19.4f} {t_prev / t_comp:17.0f}x {'>= 50x':>7}")
    print()
    print("whole pipeline (sampling, both stages, composition)")
    print(f"{'step [s]':>9} {'steps':>8} {'sample [s]':>11} {'2 stages, compiled [s]':>23} {'peaks only [s]':>15} {'2 stages, reference [s]':>24}")
    for h in (0.04, 0.02):
        t_sample = _best(lambda h=h: sample(scenario, h, rng=0), 3)
        d = sample(scenario, h, rng=0)
        t_c = _best(lambda d=d: run_multistage(d, stages), 3)
        t_k = _best(lambda d=d: multistage_peaks(d, stages), 3)
        t_p = _best(lambda d=d: run_multistage(d, stages, engine="python"), 1)
        print(f"{h:9g} {int(round(scenario.duration / h)):8d} {t_sample:11.2f} {t_c:23.3f} {t_k:15.3f} {t_p:24.2f}")


if __name__ == "__main__":
    main()
