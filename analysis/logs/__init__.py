"""Recorded IMU logs: the designer's own data, read, checked and analysed.

Built on the other domains (the alignment toolkit, the coning and vibration
tools); none of them imports this one.

Modules
-------
imu_log
    A recorded IMU log: increments at a constant rate, in body axes.
native
    The package's own ``.npz`` and ``.csv`` formats.
segments
    The gap-free segments of a log, as the analyses take them.
alignment
    Alignment and observability of a recorded log.
replay
    Coning algorithms replayed on a log: mean correction rates, exact drift differences.
cross_spectra
    Welch cross-spectral densities of several channels, with their intervals.
lines
    Deterministic lines told apart from a band by Thomson's F-test.
environment_estimate
    The vibration environment of a log, written as an environment file.
static_noise
    ARW, bias instability and RRW read off the Allan deviation of a static log.
sensor_file
    Sensor files: an IMU's noise as a data sheet gives it, in TOML.
examples
    The example log shipped with the docs.
"""
