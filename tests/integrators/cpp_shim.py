"""docs/integrator_example.cpp (a C++ class behind an extern "C" shim), built next to this file by the test."""

from pathlib import Path

from strapdown.analysis.coning.integrators.adapters import per_sample_library

integrate = per_sample_library(Path(__file__).with_name("libintegrator_cpp.so"), "integrator_", handle=True, name="C++ ConingIntegrator")
