"""The vibration library's fast paths agree bit for bit with the reference computations they replace."""

from __future__ import annotations

import math

import numpy as np
import pytest

from strapdown.analysis.vibration.drift import environment_drift
from strapdown.analysis.vibration.environment import Environment, coning_line
from strapdown.analysis.vibration.sensor_dynamics import ChannelFilter, Sensor, analog_filter
from strapdown.analysis.vibration.simulation import _half_products, _qmul
from strapdown.analysis.vibration.tuning import drift_across_band
from strapdown.derivations.coning.registry import get


def test_half_products_are_the_quaternion_products_bit_for_bit():
    g = np.random.default_rng(11)
    for _ in range(200):
        q, a, b = g.standard_normal(8), g.standard_normal(3), g.standard_normal(3)
        out = np.full(10, np.nan)
        _half_products(q, a, b, out)
        ref = np.concatenate([0.5 * _qmul(q[0:4], np.concatenate([[0.0], a])), 0.5 * _qmul(q[4:8], np.concatenate([[0.0], b]))])
        assert np.array_equal(out[0:8], ref)
        assert np.isnan(out[8:]).all()  # nothing beyond the two products is written


def test_band_drift_is_each_line_of_environment_drift_bit_for_bit():
    lp = lambda fc: ChannelFilter(analog_filter("lowpass1", cutoff_hz=fc))  # noqa: E731
    gyro = Sensor((lp(100.0), lp(130.0), lp(100.0)))
    freq = np.geomspace(1.0, 400.0, 40)
    rate, h = math.radians(1.0), 1e-3
    algorithms = [get("two-sample"), get("optimal-3")]
    band = drift_across_band(algorithms, Environment(name="s").with_sensors(gyro), h, freq, rate_amplitude=rate)
    env = Environment(tuple(coning_line(f, math.asin(rate / (2.0 * math.pi * f))) for f in freq), gyro=gyro)
    for j, a in enumerate(algorithms):
        d = environment_drift(a, env, h)  # the reference: every part, aliasing pairs included
        lines = [p for p in d.parts if p.kind == "line"]
        assert np.array_equal(band.total[j], [p.total @ d.coning_axis for p in lines])
        assert np.array_equal(band.sensor, [p.sensor @ d.coning_axis for p in lines])
    assert d.near_aliases  # the sweep does hold pairs near an alias, which the band leaves out


def test_band_drift_refuses_what_is_not_an_algorithm_naming_the_argument():
    with pytest.raises(TypeError, match=r"`algorithms` of Algorithm, got a str"):
        drift_across_band([get("two-sample"), "optimal-3"], Environment(name="s"), 1e-3, [10.0], half_angle=0.01)
