"""``strapdown log coning``: coning algorithms replayed on a recorded log.

The oracle of the correction rates is a plain loop over the steps with the published
formulas (or, for the algorithms with many terms, the terms of the algorithm's data
evaluated by ``numpy.cross`` one step at a time), never the library's evaluation.
The drift differences are checked against the package's parallel-computation simulator.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from log_synthetic import cone, cone_log, write_px4_ulog

from strapdown.analysis import cli
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core.units import RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.logs.imu_log import ImuLog
from strapdown.analysis.logs.native import write_log
from strapdown.analysis.logs.replay import replay
from strapdown.derivations.coning.registry import get

H = 1.0 / 200.0  # 20 samples per cone period
N = 2041  # after one sample of history, 2040 samples: 102 cone periods of 20 samples, whole steps of 2 and 3 samples, the pattern of 60 samples 34 times
NAMES = ["two-sample", "miller-3", "ignagni-1996-5", "savage-1+1", "lebedev-panov-6"]


def _published(name, p, k):
    """The correction of step k by the published formula; p[k0 + j − 1] is p_j of the step (p_0: the sample before)."""
    if name == "two-sample":  # Miller (1983): (2/3) p1 × p2
        a = 2 * k
        return 2.0 / 3.0 * np.cross(p[a], p[a + 1])
    if name == "miller-3":  # Miller (1983): (9/20) p1 × p3 + (27/40) p2 × (p3 − p1)
        a = 3 * k
        p1, p2, p3 = p[a], p[a + 1], p[a + 2]
        return 9.0 / 20.0 * np.cross(p1, p3) + 27.0 / 40.0 * np.cross(p2, p3 - p1)
    if name == "savage-1+1":  # Savage (1998): (1/12) p0 × p1, one sample per step after one of history
        return np.cross(p[k], p[k + 1]) / 12.0
    raise KeyError(name)


def _term_value(cross, step):
    if isinstance(cross, int):
        return step(cross)
    return np.cross(_term_value(cross[0], step), _term_value(cross[1], step))


def _from_terms(alg, p, k):
    """The correction of step k from the algorithm's terms, one numpy.cross at a time."""
    base = alg.history + k * alg.samples

    def step(j):
        return p[base + j - 1]

    total = np.zeros(3)
    for t in alg.terms:
        factor = float(t.coefficient)
        for i, j in t.dots:
            factor *= float(np.dot(step(i), step(j)))
        total += factor * _term_value(t.cross, step)
    return total


def _oracle(name, p):
    alg = get(name)
    steps = (p.shape[0] - alg.history) // alg.samples
    f = (lambda k: _published(name, p, k)) if name in ("two-sample", "miller-3", "savage-1+1") else (lambda k: _from_terms(alg, p, k))
    return sum(f(k) for k in range(steps)) / (steps * alg.samples * H), steps


@pytest.fixture(scope="module")
def cone_npz(tmp_path_factory):
    path = tmp_path_factory.mktemp("cone") / "cone.npz"
    write_log(path, cone_log(N, H))
    return path


@pytest.fixture(scope="module")
def cone_json(cone_npz):
    import contextlib
    import io

    out = io.StringIO()
    argv = ["log", "coning", str(cone_npz), "--json", "--quiet", "--prediction", "none"] + [x for n in NAMES for x in ("--algorithm", n)]
    with contextlib.redirect_stdout(out):
        assert cli.main(argv) == 0
    return json.loads(out.getvalue())


def test_the_published_formulas_are_the_registry_terms():
    """The oracle's formulas and the registry's data name the same algorithms (else the check below would be void)."""
    rng = np.random.default_rng(3)
    p = rng.standard_normal((13, 3))
    for name in ("two-sample", "miller-3", "savage-1+1"):
        alg = get(name)
        for k in range(2):
            np.testing.assert_allclose(_published(name, p, k), _from_terms(alg, p, k), rtol=1e-13, atol=1e-15)


def test_correction_rates_of_a_pure_cone_match_an_independent_sum(cone_json):
    """Each algorithm's mean correction rate (JSON contract: name, correction_rate_deg_per_h) equals the loop over its steps."""
    log = cone_log(N, H)
    rows = {row["name"]: row for row in cone_json["algorithms"]}
    assert [row["name"] for row in cone_json["algorithms"]] == NAMES
    for name in NAMES:
        expected, steps = _oracle(name, log.dtheta)
        got = np.array(rows[name]["correction_rate_deg_per_h"]) / RAD_PER_S_TO_DEG_PER_H
        assert rows[name]["steps"] == steps
        assert len(rows[name]["correction_rate_deg_per_h"]) == 3
        np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-12 * np.linalg.norm(expected))
        assert abs(expected[2]) > 1e3 * np.hypot(expected[0], expected[1])  # about the cone's axis, as it must be


@pytest.mark.parametrize("a, b", [("miller-3", "two-sample"), ("lebedev-panov-6", "two-sample"), ("ignagni-1996-5", "miller-3"), ("savage-1+1", "miller-3")])
def test_drift_differences_are_those_of_the_simulator(cone_json, a, b):
    """The difference of two algorithms' drifts on the log is that of their simulated drifts within 1 %."""
    motion = cone()
    u = {n: simulate(get(n), motion, H, (N - 1) * H).drift for n in (a, b)}
    expected = (u[a] - u[b]) * RAD_PER_S_TO_DEG_PER_H
    first = cone_json["algorithms"][0]["name"]
    diffs = {d["a"]: np.array(d["drift_difference_deg_per_h"]) for d in cone_json["differences"]}
    diffs[first] = np.zeros(3)
    got = diffs[a] - diffs[b]
    assert np.linalg.norm(got - expected) <= 0.01 * np.linalg.norm(expected), (got, expected)
    assert np.linalg.norm(expected) > 1e-4  # deg/h: a difference well above round-off


def test_a_correction_difference_is_a_drift_difference_for_one_step_only():
    """Same N: −(c_a − c_b) is the drift difference; different N: the corrections differ by orders of magnitude more."""
    r = replay(cone_log(N, H), [get(n) for n in ("miller-3", "ignagni-1996-5", "two-sample")])
    same, exact = -(r.algorithms[1].rate - r.algorithms[0].rate), r.drift_difference(1, 0)
    assert abs(same[2] / exact[2] - 1.0) < 0.01  # along the cone's axis (the body axes turn by up to the cone angle)
    assert np.linalg.norm(same - exact) < 0.03 * np.linalg.norm(exact)  # across it, the body axes wobble by the cone angle
    other = -(r.algorithms[2].rate - r.algorithms[0].rate)
    assert np.linalg.norm(other) > 100 * np.linalg.norm(r.drift_difference(2, 0))


def test_steps_restart_after_a_gap():
    """Two segments: the steps of each start at its first sample (after the history), the sums add."""
    log = cone_log(1001, H)
    a = ImuLog(log.time[:500], log.dtheta[:500], log.dv[:500])
    b = ImuLog(log.time[520:], log.dtheta[520:], log.dv[520:])
    algs = [get("miller-3"), get("savage-1+1")]
    both = replay([a, b], algs)
    for i, alg in enumerate(algs):
        parts = [replay(s, [alg]).algorithms[0] for s in (a, b)]
        scale = np.linalg.norm(both.algorithms[i].correction)
        np.testing.assert_allclose(both.algorithms[i].correction, parts[0].correction + parts[1].correction, rtol=1e-12, atol=1e-13 * scale)
        assert both.algorithms[i].steps == sum(p.steps for p in parts) == sum((s.n_samples - alg.history) // alg.samples for s in (a, b))
        # the independent sum over each segment alone: no step straddles the gap
        expected = sum(_oracle(alg.name, s.dtheta)[0] * _oracle(alg.name, s.dtheta)[1] * alg.samples * H for s in (a, b))
        np.testing.assert_allclose(both.algorithms[i].correction, expected, rtol=1e-9, atol=1e-12 * scale)


def test_the_result_does_not_depend_on_the_chunks():
    log = cone_log(N, H)
    algs = [get(n) for n in NAMES]
    big, small = replay(log, algs), replay(log, algs, chunk_steps=7)
    for x, y in zip(big.algorithms, small.algorithms):
        np.testing.assert_allclose(x.correction, y.correction, rtol=1e-12, atol=1e-13 * np.linalg.norm(x.correction))
        np.testing.assert_allclose(x.attitudes[0], y.attitudes[0], rtol=0, atol=1e-14)


def test_a_rate_log_says_how_its_increments_were_formed(tmp_path, capsys):
    log = cone_log(400, H)
    np.savez(tmp_path / "rates.npz", time=log.time, gyro=log.dtheta / H, accel=log.dv / H)
    assert cli.main(["log", "coning", str(tmp_path / "rates.npz"), "--algorithm", "two-sample", "--json", "--quiet", "--prediction", "none"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert "rate × interval" in data["increments"]


def test_the_closed_form_prediction_stands_beside_the_replay(cone_npz, capsys):
    """Pure cone, no sensor: the closed form on the estimated environment gives each algorithm's drift difference."""
    argv = ["log", "coning", str(cone_npz), "--algorithm", "two-sample", "--algorithm", "miller-3", "--json", "--quiet"]
    assert cli.main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    d = data["differences"][0]
    got, predicted = np.array(d["drift_difference_deg_per_h"]), np.array(d["predicted_difference_deg_per_h"])
    assert abs(predicted[2] / got[2] - 1.0) < 0.01, (got, predicted)


def test_a_px4_ulog_of_a_cone(tmp_path, capsys):
    """A ULog of sensor_combined (float32 rates over the integral interval, timestamps in µs): the same correction rates."""
    pyulog = pytest.importorskip("pyulog")
    log = cone_log(N, H)
    dt_us = int(round(H * 1e6))
    path = tmp_path / "cone.ulg"
    gyro = (log.dtheta / H).astype(np.float32)
    write_px4_ulog(path, np.arange(1, N + 1, dtype=np.uint64) * dt_us, gyro, np.full(N, dt_us), (log.dv / H).astype(np.float32))
    data = pyulog.ULog(str(path)).get_dataset("sensor_combined").data
    t = data["timestamp"] * 1e-6
    dtheta = np.stack([data[f"gyro_rad[{i}]"] for i in range(3)], axis=1).astype(float) * (data["gyro_integral_dt"] * 1e-6)[:, None]
    np.testing.assert_allclose(dtheta, log.dtheta, rtol=1e-6, atol=1e-9)  # float32 in the file
    argv = ["log", "coning", None, "--algorithm", "two-sample", "--algorithm", "miller-3", "--json", "--quiet", "--prediction", "none"]
    argv[2] = str(path)
    if cli.main(argv) != 0:  # the package's own formats only: read the ULog's samples as the reader of ULogs would
        capsys.readouterr()
        write_log(tmp_path / "from-ulog.npz", ImuLog(t, dtheta, log.dv))
        argv[2] = str(tmp_path / "from-ulog.npz")
        assert cli.main(argv) == 0
    rows = json.loads(capsys.readouterr().out)["algorithms"]
    for row in rows:
        expected = _oracle(row["name"], dtheta)[0] * RAD_PER_S_TO_DEG_PER_H
        np.testing.assert_allclose(row["correction_rate_deg_per_h"], expected, rtol=1e-9, atol=1e-12 * np.linalg.norm(expected))
    exact = [_oracle(n, log.dtheta)[0] for n in ("two-sample", "miller-3")]
    assert abs(rows[0]["correction_rate_deg_per_h"][2] / (exact[0][2] * RAD_PER_S_TO_DEG_PER_H) - 1) < 1e-5  # float32 round-off only


def test_bad_algorithms_are_refused(cone_npz, capsys):
    assert cli.main(["log", "coning", str(cone_npz), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--algorithm" in err
    assert cli.main(["log", "coning", str(cone_npz), "--algorithm", "no-such", "--quiet"]) == 2
    assert "Traceback" not in capsys.readouterr().err
    with pytest.raises(ValueError, match="whole step"):
        replay(cone_log(2, H), [get("miller-3")])
    with pytest.raises(TypeError, match="`segments`"):
        replay([np.zeros((3, 3))], [get("two-sample")])
    with pytest.raises(TypeError, match="`algorithms`"):
        replay(cone_log(10, H), ["two-sample"])
    assert Fraction(1, 12) == get("savage-1+1").pairwise[(0, 1)]
    assert math.isclose(H, 0.005)
    assert Path(cone_npz).exists()
