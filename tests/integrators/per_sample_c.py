"""per_sample.c through its per-sample C API (libper_sample.so, built next to this file by the test)."""

from pathlib import Path

from strapdown.analysis.coning.integrators.adapters import per_sample_library

integrate = per_sample_library(Path(__file__).with_name("libper_sample.so"), "sav_", name="Savage per sample in C")
