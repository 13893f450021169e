"""Recorded IMU logs: the designer's own data, read, checked and analysed.

Built on the other domains (the alignment toolkit, the coning and vibration
tools); none of them imports this one.

Modules
-------
reader
    :func:`~strapdown.analysis.logs.reader.read_imu_log`: any format, its inventory, segments and checks.
imu_log
    A recorded IMU log: increments at a constant rate, in body axes.
inventory
    What a log holds: streams, timing, units, frame, filters, GNSS.
streams
    From one stream's samples to gap-free constant-rate segments.
checks
    Plausibility before analysis.
ulog, dataflash, rosbag, euroc, native
    One module per format (PX4, ArduPilot, ROS 1/2, EuRoC/TUM-VI, the package's own).
framing
    The record walk of the binary formats.
synthetic
    Synthetic logs with a known truth in every format.
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
