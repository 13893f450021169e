"""Derivations the azimuth report keeps with the derived results agree exactly with a fresh derivation."""

from __future__ import annotations

import sympy as sp

from strapdown.analysis.core import cache
from strapdown.analysis.report import azimuth
from strapdown.derivations.gyrocompass import azimuth_error as g


def test_linear_parts_from_disk_equal_the_derivation(tmp_path, monkeypatch):
    monkeypatch.setenv("STRAPDOWN_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(cache, "_memory", {})
    fresh = g.linear_parts()
    first = azimuth._linear_parts()  # derived and written
    monkeypatch.setattr(cache, "_memory", {})  # a new process: memory empty, disk warm
    loaded = azimuth._linear_parts()
    assert loaded is not fresh  # a copy read back from disk, not the derivation's own object
    for a, b, c in zip(fresh, first, loaded):
        assert sp.srepr(a) == sp.srepr(b) == sp.srepr(c)
        assert sp.latex(a) == sp.latex(c)  # what the report prints
