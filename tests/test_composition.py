"""The composite ν₁∘ν of two stages: the stage-1 corrections cancel (Plotnikov 1999, (2.2), (2.6))."""

import numpy as np
import pytest

from strapdown.analysis.multistage.composition import composite_identity, yaw_study
from strapdown.analysis.multistage.sensors import SensorErrors
from strapdown.analysis.multistage.stages import Stage
from strapdown.analysis.multistage.trajectory import Scenario, sample
from strapdown.derivations.multistage.composition import derive


@pytest.fixture(scope="module")
def d():
    return derive()


def test_symbolic_cancellation(d):
    assert d.cancels_unit_norm and d.stage1_correction_free and d.cancels_any_norm_with_inverse
    # The printed form (ν̄ in (2.2)) leaves a residual off the unit sphere: the check is not vacuous.
    assert any(c != 0 for c in d.residual)


@pytest.mark.parametrize(
    "stage1",
    [
        Stage.constant(0.05, 1e-3, "tilt", components=(0, 1, 2, 3)),
        Stage(((0.0, 0.2, 1e-2), (300.0, 0.01, 1e-5)), "tilt", c=2.0, components=(0, 2), switch="bumpless"),
        Stage.constant(0.3, 1e-2, "pure"),
    ],
    ids=["all-four", "yaw-only-c2", "pure"],
)
def test_numerical_cancellation(stage1):
    """Any stage 1, an uncorrected stage 2: the composite is the gyro-integrated attitude to round-off."""
    data = sample(Scenario(duration=1300.0, sensors=SensorErrors.plotnikov_1999()), 0.1)
    ident = composite_identity(data, stage1)
    assert ident.stage1_yaw_peak > 1e-4  # stage 1 did change the attitude …
    assert ident.max_difference < 1e-11  # … and the composite does not see it


def test_yaw_all_four_reading():
    """Stage 1 on all four components pulls the yaw to the ψ = 0 of (1.10); the composite keeps the gyro yaw."""
    study = yaw_study(Scenario(duration=2000.0), step=0.2, times=(600.0, 2000.0))
    horizontal, all_four = study.readings
    assert horizontal.components == (1, 3) and all_four.components == (0, 1, 2, 3)
    # (1, 3): no yaw correction, stage 1 and the composite both follow the gyros.
    assert horizontal.stage1_peak < 2e-3 and horizontal.two_stage_peak < 2e-3
    # all four: stage-1 yaw error of the order of the true yaw Ω sin φ t (0.1 rad at 2000 s), negative
    true_yaw = study.yaw_rate * all_four.times
    assert np.all(all_four.stage1_yaw < 0) and np.all(-all_four.stage1_yaw > 0.5 * true_yaw - 0.01)
    assert all_four.two_stage_peak < 0.05 * all_four.stage1_peak
    assert study.identity.max_difference < 1e-11
