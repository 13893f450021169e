"""Identification from recorded input/output: a registry algorithm recovered exactly; the terms a poor record leaves unidentified."""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest
from cli_contract import run, violations

from strapdown.analysis.coning.integrators.adapters import algorithm_integrator
from strapdown.analysis.coning.integrators.interface import step_increments
from strapdown.analysis.coning.integrators.records import Record, identify_record, read_record
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.derivations.coning.registry import get


def _record(name, steps=500, scale=0.01, seed=3, velocity=False):
    alg = get(name)
    n = alg.samples
    rng = np.random.default_rng(seed)
    g = scale * rng.standard_normal((steps * n, 3))
    a = scale * rng.standard_normal((steps * n, 3)) if velocity else None
    out = step_increments(algorithm_integrator(alg, velocity=velocity), g, n, a)
    return alg, Record(g, out.rotation, np.arange(n - 1, steps * n, n), a, out.velocity)


def _write_csv(path, rec):
    with path.open("w") as f:
        cols = ["gyro_x", "gyro_y", "gyro_z", "rotation_x", "rotation_y", "rotation_z"]
        f.write(",".join(cols) + "\n")
        ends = {int(e): k for k, e in enumerate(rec.step_end)}
        for i, row in enumerate(rec.gyro):
            out = [repr(float(x)) for x in rec.rotation[ends[i]]] if i in ends else ["", "", ""]
            f.write(",".join([repr(float(x)) for x in row] + out) + "\n")


@pytest.mark.parametrize("name", ["two-sample", "miller-3", "ignagni-1996-2", "ignagni-1996-4", "panov-4s-3", "polynomial-4"])
def test_a_rich_synthetic_record_recovers_a_registry_algorithm_exactly(name, tmp_path):
    alg, rec = _record(name)
    path = tmp_path / "record.csv"
    _write_csv(path, rec)  # through the file, as a flight computer's log would come
    r = identify_record(read_record(path), alg.samples, max_previous=max(alg.history, 1))
    assert r.identified and r.exact
    assert {k: c.fraction for k, c in r.pairwise.items() if c.fraction} == alg.pairwise
    assert {j: c.fraction for j, c in r.linear.items() if c.fraction} == {j: Fraction(1) for j in range(1, alg.samples + 1)}
    json.dumps(r.as_dict(), allow_nan=False)


def test_sculling_from_a_record_is_the_dual_extension(tmp_path):
    """Savage's 1 + 1 with its sculling term written out (exactly bilinear), recorded to an .npz file."""
    rng = np.random.default_rng(4)
    g, a = 0.01 * rng.standard_normal((500, 3)), 0.01 * rng.standard_normal((500, 3))
    gp, ap = np.vstack([np.zeros((1, 3)), g[:-1]]), np.vstack([np.zeros((1, 3)), a[:-1]])
    rotation = g + np.cross(gp, g) / 12
    velocity = a + 0.5 * np.cross(g, a) + (np.cross(gp, a) + np.cross(ap, g)) / 12
    np.savez(tmp_path / "r.npz", gyro=g, rotation=rotation, accel=a, velocity=velocity)
    r = identify_record(read_record(tmp_path / "r.npz"), 1, max_previous=1)
    assert r.exact and r.terms == {"0,1": "1/12"}
    bil = {k: c.fraction for k, c in r.sculling["bilinear"].items() if c.fraction}
    assert bil == {(0, 1): Fraction(1, 12), (1, 0): Fraction(-1, 12), (1, 1): Fraction(1, 2)}


def test_a_rotation_about_one_axis_leaves_every_cross_term_unidentified():
    """All increments along z: every cross product vanishes, the linear part is still determined (a random rate)."""
    rng = np.random.default_rng(1)
    g = np.zeros((600, 3))
    g[:, 2] = 0.01 * rng.standard_normal(600)
    out = step_increments(algorithm_integrator(get("two-sample"), velocity=False), g, 2).rotation
    r = identify_record(Record(g, out, np.arange(1, 600, 2)), 2, max_previous=1)
    assert set(r.unidentified) == {"p0×p1", "p0×p2", "p1×p2"}
    assert {j: c.fraction for j, c in r.linear.items() if c is not None} == {0: 0, 1: 1, 2: 1}
    assert not r.identified and "NOT identified" in r.text()


def _cone_phasors(n, k, x):
    """The three numbers a record of a pure cone (rate x per sample) gives each coefficient: its axial constant and the
    complex amplitude of its turning part, per unit radial and axial increment (independent of the package: the increments
    are p_j = a e_z + ρ (cos(φ + j x), sin(φ + j x), 0))."""
    window = list(range(1 - k, n + 1))
    cols = []
    for j in window:  # p_j: axial a (constant), radial turning: complex amplitude e^{ijx}
        cols.append((1.0, np.exp(1j * j * x)))
    pairs = [(a, b) for a in range(len(window)) for b in range(a + 1, len(window))]
    for a, b in pairs:  # p_i × p_j = ρ² sin((j − i)x) e_z + a ρ [e_z × (r_j − r_i)]: axial and turning parts
        i, j = window[a], window[b]
        cols.append((math.sin((j - i) * x), 1j * (np.exp(1j * j * x) - np.exp(1j * i * x))))
    return cols


def test_a_pure_cone_names_its_unidentified_terms_as_the_phasor_count_predicts():
    alg = get("two-sample")
    n, k = 2, 1
    motion = RegularPrecession(-1.0, 2 * math.pi, 0.02)
    h = 0.05
    g = motion.grid_increments(h, 0, 800)
    out = step_increments(algorithm_integrator(alg, velocity=False), g, n).rotation
    r = identify_record(Record(g, out, np.arange(n - 1, 800, n)), n, max_previous=k)
    # independent count: the record determines the span of the rows (axial, Re, Im) of the phasor matrix, so rank 3
    cols = _cone_phasors(n, k, motion.nu * h)
    m = np.array([[c[0] for c in cols], [c[1].real for c in cols], [c[1].imag for c in cols]])
    assert r.rank == np.linalg.matrix_rank(m) == 3
    null = np.linalg.svd(m)[2][3:]  # the coefficient directions the record cannot see
    predicted = {lab for lab, w in zip([f"p{j}" for j in range(1 - k, n + 1)] + ["p0×p1", "p0×p2", "p1×p2"], np.linalg.norm(null, axis=0)) if w > 1e-6}
    assert set(r.unidentified) == predicted == {"p0", "p1", "p2", "p0×p1", "p0×p2", "p1×p2"}
    assert len(r.free) == r.unknowns - r.rank == 3


def test_bad_records_are_refused_by_name(tmp_path):
    with pytest.raises(ValueError, match="not found"):
        read_record(tmp_path / "missing.csv")
    (tmp_path / "x.txt").write_text("a")
    with pytest.raises(ValueError, match=".csv or .npz"):
        read_record(tmp_path / "x.txt")
    (tmp_path / "h.csv").write_text("gyro_x,gyro_y\n1,2\n")
    with pytest.raises(ValueError, match="gyro_z"):
        read_record(tmp_path / "h.csv")
    alg, rec = _record("two-sample", steps=3)
    with pytest.raises(ValueError, match="window"):
        identify_record(rec, 2, max_previous=8)


def test_the_command_line_reads_a_record(tmp_path):
    alg, rec = _record("miller-3")
    path = tmp_path / "log.csv"
    _write_csv(path, rec)
    argv = ["identify", "--record", str(path), "--samples-per-step", "3", "--max-previous", "0"]
    out = run(argv + ["--json"], timeout=120.0)
    assert not violations(out, expect="accept", names=(), limit=120.0, json_out=True, argv=argv), out
    data = json.loads(out.out)
    assert data["terms"] == {"1,2": "27/40", "1,3": "9/20", "2,3": "27/40"} and data["exact"] and data["unidentified"] == []
