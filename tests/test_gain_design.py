"""Gain design of a corrected stage, Schuler tuning and the Schuler error budget (Plotnikov 1999, (3.8)-(3.12))."""

import control
import numpy as np
import pytest

from strapdown.analysis.multistage.gain_design import (
    StageGains,
    check_design,
    check_error_budget,
    design_gains,
    schuler_error_budget,
    schuler_gains,
    section5_budget,
    switched_stage,
)
from strapdown.analysis.multistage.sensors import SensorErrors
from strapdown.analysis.multistage.stages import simulate
from strapdown.analysis.multistage.trajectory import Scenario


@pytest.mark.parametrize("reference,c", [("pure", None), ("tilt", None), ("tilt", 2.0), ("external", None)])
def test_design_gives_the_requested_loop(reference, c):
    g = design_gains(4e-3, 0.6, reference=reference, c=c)
    wn, zeta, _ = g.loop().damp()
    np.testing.assert_allclose(wn, 4e-3, rtol=1e-12)
    np.testing.assert_allclose(zeta, 0.6, rtol=1e-12)
    assert g.natural_frequency == pytest.approx(4e-3) and g.damping == pytest.approx(0.6)


def _tilted(duration):
    """A body pitched by 0.01 rad since before t = 0 on a non-rotating Earth, ideal sensors."""
    return Scenario(
        duration=duration,
        rocking_start=-1.0,
        rocking_frequency=0.0,
        rocking_phase=(0.0, np.pi / 2, 0.0),
        rocking_amplitude=(0.0, 0.01, 0.0),
        rocking_decay=0.0,
        rocking_onset=0.0,
        accel=0.0,
        earth_rate=0.0,
        sensors=SensorErrors(),
    )


@pytest.mark.parametrize("reference", ["pure", "tilt"])
def test_designed_stage_responds_like_its_loop(reference):
    """Started level on a tilted body, the simulated stage (half angles, c, the reference's angle factor)
    decays like the designed loop: error = e0 × step response of H_g = s²/(s² + Ks + L)."""
    g = design_gains(1e-2, 0.5, reference=reference)
    check = check_design(g, tilt=0.01, duration=1500.0, step=0.5)
    linear = -0.01 * np.asarray(control.step_response(control.tf([1.0, 0.0, 0.0], [1.0, 1e-2, 1e-4]), T=check.time).outputs).ravel()
    assert linear.max() > 1e-3  # overshoot of the ζ = 0.5 loop
    np.testing.assert_allclose(check.simulated, linear, atol=2e-6)  # second order in the 0.01 rad tilt
    assert check.max_difference < 2e-6


def test_inconsistent_c_settles_at_a_over_c():
    g = design_gains(1e-2, 0.7, reference="tilt", c=2.0)
    res = simulate(_tilted(2000.0), (g.stage(),), step=0.5)
    assert res.errors[0, -1, 1] + 0.01 == pytest.approx(0.005, rel=1e-3)
    assert g.stage().static_gain == 0.5


def test_schuler_gains():
    pure, tilt = schuler_gains(), schuler_gains(reference="tilt")
    assert (pure.k, pure.l, pure.c) == (0.0, 9.81 / 6.371e6, 2.0)
    assert tilt.l == pytest.approx(2 * 9.81 / 6.371e6) and tilt.c == 1.0
    for gains in (pure, tilt):
        assert gains.loop_gains[1] == pytest.approx(9.81 / 6.371e6)
        assert gains.loop().peak_tilt_error(20.0, 20.0) == 0.0
    with pytest.raises(ValueError, match="reference"):
        schuler_gains(reference="external")


def test_switched_stage():
    st = switched_stage(design_gains(1e-2, 0.7), schuler_gains(), 600.0)
    assert st.switch == "bumpless" and st.schedule[1] == (600.0, 0.0, 9.81 / 6.371e6)
    with pytest.raises(ValueError, match="same reference"):
        switched_stage(design_gains(1e-2, 0.7, reference="tilt"), schuler_gains(), 600.0)
    with pytest.raises(TypeError):
        switched_stage((0.01, 1e-4), schuler_gains(), 600.0)


def test_error_budget_closed_form_against_simulation():
    budget = schuler_error_budget((1e-7, 2e-8, -1e-7), (1e-3, 0.0, -2e-3))
    check = check_error_budget(budget, duration=6000.0, step=1.0)
    assert check.scale > 4e-4
    assert check.max_difference < 1e-3 * check.scale
    d, b = budget.pitch_amplitudes
    assert d == pytest.approx(1e-7 / np.sqrt(9.81 / 6.371e6)) and b == pytest.approx(2e-3 / 9.81)


def test_section5_pitch_error_is_the_unsensed_centripetal_acceleration():
    """The two-stage pitch peak of section 5 is the Schuler response to −Ω²R sin φ cos φ (plus the sensor errors)."""
    res = simulate(Scenario(), step=0.2)
    simulated = res.peaks(since=600.0)[1].pitch
    predicted = section5_budget().peaks(5000.0).pitch
    assert predicted == pytest.approx(simulated, rel=0.01)
    without = section5_budget(include_centripetal=False).peaks(5000.0).pitch
    assert without < 0.1 * simulated


@pytest.mark.parametrize("kwargs", [dict(natural_frequency=0.0, damping=0.5), dict(natural_frequency=1e-3, damping=-0.1), dict(natural_frequency=1e-3, damping=0.5, reference="gps")])
def test_bad_design_input(kwargs):
    with pytest.raises(ValueError):
        design_gains(**kwargs)


def test_stage_gains_validation():
    with pytest.raises(ValueError, match="`c`"):
        StageGains(0.01, 1e-4, 0.0, "pure")
