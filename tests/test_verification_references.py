"""The one-step error exponents share their exact references across integrators, with the same bits as computing them per call.

:func:`~strapdown.analysis.coning.integrators.verification.local_error_exponent`
and :func:`~.velocity_error_exponent` compute the tumbling motion's records and
exact increments once per (N, warm-up, grid) and reuse them for every integrator.
Here the per-call loop they replaced is written out and must give the same
floats exactly; an integrator that writes into its input cannot change what
the next one is given.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from strapdown.analysis.coning.integrators.interface import Integrator, step_increments
from strapdown.analysis.coning.integrators.recursions import quaternion_composition, recursion
from strapdown.analysis.coning.integrators.verification import _gauss, _specific_force, _warmup, local_error_exponent, velocity_error_exponent
from strapdown.analysis.coning.local_error import TumblingMotion
from strapdown.analysis.core import quaternion as quat

STEPS = (0.05, 0.025, 0.0125, 0.00625)
TIMES = (0.3, 1.1, 2.4)


def _slope(steps, errs):
    keep = [k for k, e in enumerate(errs) if e > 1e-13][-3:]
    return np.polyfit(np.log(np.array(steps)[keep]), np.log(np.array(errs)[keep]), 1)[0] if len(keep) >= 2 else None


def _rotation_loop(integrator, n, history):
    """The exponent as computed before the references were shared: every record built for this call."""
    warm, motion, exps = _warmup(history, n), TumblingMotion(), []
    for t_mid in TIMES:
        errs = []
        for big_h in STEPS:
            h, t0 = big_h / n, t_mid - 0.5 * big_h
            record = motion.increments(t0 - warm * big_h, h, (warm + 1) * n)
            got = step_increments(integrator, record, n).rotation[-1]
            exact = quat.quat_to_rotvec(quat.multiply(quat.conjugate(motion.attitude(t0)), motion.attitude(t0 + big_h)), validate=False)
            errs.append(float(np.linalg.norm(exact - got)))
        s = _slope(STEPS, errs)
        if s is not None:
            exps.append(s)
    return float(np.mean(exps)) if exps else math.nan


def _velocity_loop(integrator, n, history):
    warm, motion, exps = _warmup(history, n), TumblingMotion(), []
    for t_mid in TIMES:
        errs = []
        for big_h in STEPS:
            h, t0 = big_h / n, t_mid - 0.5 * big_h
            start, count = t0 - warm * big_h, (warm + 1) * n
            gyro = motion.increments(start, h, count)
            edges = start + h * np.arange(count + 1)
            accel = _gauss(edges[:-1], edges[1:], _specific_force)
            got = step_increments(integrator, gyro, n, accel).velocity[-1]
            ref = motion.attitude(t0)

            def turned(t, ref=ref):
                return quat.rotate(quat.multiply(quat.conjugate(ref), motion.attitude(t)), _specific_force(t))

            sub = t0 + h * np.arange(n + 1)
            errs.append(float(np.linalg.norm(_gauss(sub[:-1], sub[1:], turned).sum(axis=0) - got)))
        s = _slope(STEPS, errs)
        if s is not None:
            exps.append(s)
    return float(np.mean(exps)) if exps else math.nan


@pytest.mark.parametrize("n,history", [(1, 1), (2, 1), (4, 1), (4, 9)])
def test_shared_references_give_the_same_exponents_as_the_per_call_loop(n, history):
    for integrator in (recursion(velocity=True), recursion(alpha_lag=2, velocity=True), quaternion_composition(velocity=True)):
        assert local_error_exponent(integrator, n, history=history) == _rotation_loop(integrator, n, history)
        assert velocity_error_exponent(integrator, n, history=history) == _velocity_loop(integrator, n, history)
    # the exponents tell the algorithms apart (the comparison above is not between constants)
    assert abs(local_error_exponent(recursion(), 4, history=1) - local_error_exponent(recursion(alpha_lag=2), 4, history=1)) > 0.5


def test_an_integrator_writing_into_its_input_does_not_change_the_next_ones_records():
    clean = recursion(velocity=True)
    expected = local_error_exponent(clean, 2, history=1), velocity_error_exponent(clean, 2, history=1)
    inner = recursion(velocity=True).function

    def vandal(gyro, samples_per_step, accel=None):
        out = inner(gyro.copy(), samples_per_step, None if accel is None else accel.copy())
        gyro[:] = 1.0  # scribbles over what it was given
        if accel is not None:
            accel[:] = 1.0
        return out

    rude = Integrator(vandal, velocity=True, name="writes into its input")
    assert local_error_exponent(rude, 2, history=1) == expected[0]
    assert velocity_error_exponent(rude, 2, history=1) == expected[1]
    assert (local_error_exponent(clean, 2, history=1), velocity_error_exponent(clean, 2, history=1)) == expected
