"""The C function of hang_c.c, built next to this file by the test (libhang_c.so)."""

from pathlib import Path

from strapdown.analysis.coning.integrators.adapters import compiled

integrate = compiled(Path(__file__).with_name("libhang_c.so"), "integrate")
