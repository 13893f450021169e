"""
Error budget of an IMU at rest
==============================

The sources of the example tactical-grade and MEMS data sheets
(:func:`~strapdown.analysis.navigation.imu_file.example_imu`) through the
linear navigation error model
(:func:`~strapdown.analysis.navigation.error_budget.error_budget`; ``strapdown
budget``), at rest and level at 45° N, stacked in root sum square against
time over ten minutes, as in the quick report: the tactical IMU after 120 s of
analytic self-alignment, the MEMS IMU with its heading given (its gyro cannot
find north).

Report figure ``error-budget-tactical.png`` and
Report figure ``error-budget-mems.png`` (ten minutes, as in the quick report).
"""

import math

import matplotlib.pyplot as plt

from strapdown.analysis.navigation.error_budget import error_budget
from strapdown.analysis.navigation.error_model import Site
from strapdown.analysis.navigation.imu_file import example_imu
from strapdown.analysis.report.error_budget import draw_budget

site = Site(math.radians(45.0), 0.0)
for name, alignment in (("tactical", "analytic"), ("mems", "none")):
    r = error_budget(example_imu(name), site, 600.0, alignment=alignment, alignment_time=120.0, report_times=(60.0, 600.0))
    print(f"{r.imu}: total horizontal position error {r.total.position[-1]:.4g} m at 10 min; dominant source {r.dominant('position')}")
    fig = plt.figure(figsize=(13.0, 4.2))
    draw_budget(fig, r)
plt.show()
