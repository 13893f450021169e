"""px4_integrator_coning.c through its per-sample C API (libpx4.so, built next to this file by the test), taking rates."""

import dataclasses
from pathlib import Path

from strapdown.analysis.coning.integrators.adapters import per_sample_library

integrate = dataclasses.replace(per_sample_library(Path(__file__).with_name("libpx4.so"), "px4_", name="PX4 IntegratorConing in C"), input="rate", sample_interval=0.001)
