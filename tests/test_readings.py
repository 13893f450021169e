"""Readings of the section-5 example (Plotnikov 1999) and the checks of the printed formulas."""

import subprocess
import sys

import numpy as np
import pytest

from strapdown.analysis.multistage.formula_checks import check_printed_formulas
from strapdown.analysis.multistage.readings import Reading, run_readings, section5_loops, standard_readings
from strapdown.analysis.multistage.step_convergence import step_convergence
from strapdown.analysis.multistage.trajectory import Scenario
from strapdown.derivations.multistage.published import PAPER, PRINTED_GAINS, SECTION5
from strapdown.derivations.multistage.tilt_quaternion import derive as derive_tilt


def test_standard_readings_are_distinct_and_start_with_the_default():
    readings = standard_readings()
    assert len({r.label for r in readings}) == len(readings)
    default = readings[0]
    assert default.scenario() == Scenario()
    assert [s.components for s in default.stages()] == [(1, 3), (1, 3)]
    envelope = readings[1].scenario()
    assert envelope.rocking_decay_origin == SECTION5.envelope_origin and envelope.rocking_decay == SECTION5.envelope_decay


def test_readings_run_and_differ_where_they_should():
    short = Scenario(duration=2000.0)
    default, all_four, rescale = run_readings(
        (Reading("default"), Reading("all four", stage1_components=(0, 1, 2, 3)), Reading("rescale", switch="rescale")), base=short, step=0.5
    )
    # All four components: stage 1 pulls the yaw to ψ = 0 of (1.10), about −Ω sin φ t by the switch; the composite does not follow.
    assert all_four.yaw_at_switch[0] < -0.02 and abs(all_four.yaw_at_switch[1]) < 1e-3
    assert abs(default.yaw_at_switch[0]) < 1e-3
    # Rescaling the integral at the switch drops the Earth rate it held: a large two-stage roll error.
    assert rescale.peaks[1].roll > 5 * default.peaks[1].roll
    assert default.peaks[0] == rescale.peaks[0]  # stage 1 is the same


def test_section5_loops_read_the_printed_gains():
    loops = section5_loops()
    assert (loops[0].loop.k, loops[0].loop.l) == (PRINTED_GAINS.stage1[0] / 2, PRINTED_GAINS.stage1[1] / 2)
    assert loops[3].loop.stability == "marginal" and loops[3].loop.l == pytest.approx(9.81 / 6.371e6)
    assert loops[4].loop.l == PRINTED_GAINS.stage2_after[1]


def test_printed_formulas_against_the_truth():
    c = check_printed_formulas(samples=300, rng=4)
    assert c.derived_1_10 < 1e-14 and c.package_tilt < 1e-14 and c.printed_1_10 > 0.05
    assert c.derived_cos_gamma < 1e-14 and c.printed_cos_gamma > 1.0
    # first order in angles of 1e-3: the derived W3 is exact to ~|W| × 1e-6, the printed one misses 2 W1 β
    assert c.derived_w3 < 1e-4 < 1e-3 < c.printed_w3 and c.printed_m11 < 1e-5


def test_tilt_quaternion_derivation():
    d = derive_tilt()
    assert d.matches_printed == (False, True, True, False)
    assert not d.cos_gamma_matches_printed


def test_integrator_is_second_order():
    study = step_convergence(Scenario(duration=1250.0), steps=(0.2, 0.1, 0.05, 0.025))
    assert all(3.0 < r < 6.0 for r in study.ratios)
    assert study.composite_difference[0] < 1e-5


def test_published_numbers_load_without_sympy():
    code = "import sys; from strapdown.derivations.multistage.published import PAPER, SECTION5; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "False"
    assert PAPER.yaw_stage1.value == -3e-2 and PAPER.stage1_pitch_peak.place.startswith("section 5")
    assert np.isclose(SECTION5.rocking_frequency, np.pi)


def test_scenario_defaults_are_the_printed_setup():
    sc = Scenario()
    assert (sc.duration, sc.rocking_start, sc.accel_start, sc.accel_duration, sc.accel) == (SECTION5.duration, SECTION5.rest_end, SECTION5.accel_start, SECTION5.accel_duration, SECTION5.accel)
    assert sc.rocking_amplitude == SECTION5.rocking_amplitude and sc.rocking_decay == SECTION5.envelope_decay
    assert sc.rocking_decay_origin is None  # a reading: the printed origin is 600 s
    assert [abs(b) for b in sc.sensors.accel_bias] == [SECTION5.accel_bias] * 3
