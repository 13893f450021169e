"""
Pseudo-coning of common MEMS filter settings
============================================

A classical coning line of 1 deg/s rate amplitude swept in frequency (a fixed
1° cone would be 63 deg/s of rate at 10 Hz: extreme motion), seen by gyros
behind common filter settings, the algorithm at h = 1 ms. The sensor part of
the mean drift (pseudo-coning: with the same filter on every axis the sensed
coning is ``|H|²`` times the true one) is the same for every algorithm; relative
to the true coning it grows as (ω/ω_c)² for the first-order and Bessel filters
and as (ω/ω_c)⁴ for the maximally flat Butterworth and the DLPF;
dashed and dotted, the algorithms' own residuals with ideal sensors
(:func:`~strapdown.analysis.vibration.tuning.drift_across_band`, closed form
through the sensors' responses). Filters that differ between axes also turn
in-phase vibration into coning (the last setting).

Report figure ``vibration-pseudo-coning.png`` (60 frequencies, as in the quick
report).
"""

import matplotlib.pyplot as plt
import numpy as np

from strapdown.analysis.core.units import DEG, RAD_PER_S_TO_DEG_PER_H
from strapdown.analysis.vibration.environment import Environment
from strapdown.analysis.vibration.sensor_dynamics import ChannelFilter, Sensor, analog_filter, digital_filter
from strapdown.analysis.vibration.tuning import drift_across_band
from strapdown.derivations.coning.registry import get


def same(channel, decimation=1):
    return Sensor((channel,) * 3, decimation)


def lowpass(cutoff_hz):
    return ChannelFilter(analog_filter("lowpass1", cutoff_hz=cutoff_hz))


settings = {
    "first-order 50 Hz": same(lowpass(50.0)),
    "first-order 100 Hz": same(lowpass(100.0)),
    "first-order 200 Hz": same(lowpass(200.0)),
    "Butterworth-2 100 Hz": same(ChannelFilter(analog_filter("butterworth", cutoff_hz=100.0, order=2))),
    "Bessel-2 100 Hz": same(ChannelFilter(analog_filter("bessel", cutoff_hz=100.0, order=2))),
    "DLPF: digital Butterworth-2 92 Hz at 1 kHz": same(ChannelFilter(digital=digital_filter("butterworth", cutoff_hz=92.0, order=2))),
    "moving average of 4 at 4 kHz, decimated by 4": same(ChannelFilter(digital=digital_filter("moving_average", taps=4)), 4),
    "first-order 100 Hz on x, 110 Hz on y": Sensor((lowpass(100.0), lowpass(110.0), lowpass(100.0))),
}
h, rate = 1e-3, 1.0 * DEG
freq = np.geomspace(1.0, 400.0, 60)
sweep = Environment(name="sweep")

fig, ax = plt.subplots(figsize=(7.2, 4.8), layout="constrained")
for name, gyro in settings.items():
    band = drift_across_band([get("two-sample")], sweep.with_sensors(gyro), h, freq, rate_amplitude=rate)
    ax.loglog(freq, np.abs(band.sensor) * RAD_PER_S_TO_DEG_PER_H, label=name)
    print(f"{name}: sensor part at 10 Hz {np.interp(10.0, freq, band.sensor) * RAD_PER_S_TO_DEG_PER_H:.4g} deg/h")
ideal = drift_across_band([get("two-sample"), get("optimal-3")], sweep, h, freq, rate_amplitude=rate)
ax.loglog(freq, np.abs(ideal.total[0]) * RAD_PER_S_TO_DEG_PER_H, "k--", label="two-sample algorithm, ideal sensors")
ax.loglog(freq, np.abs(ideal.total[1]) * RAD_PER_S_TO_DEG_PER_H, "k:", label="optimal-3 algorithm, ideal sensors")
ax.set_xlabel("coning frequency [Hz]")
ax.set_ylabel("|drift| [deg/h], coning of 1 deg/s rate")
ax.set_ylim(1e-10, 1e1)
ax.legend(loc="lower right", fontsize=6.5)
plt.show()
