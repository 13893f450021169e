"""Recorded IMU logs: the designer's own data, read, checked and analysed.

Built on the other domains (the alignment toolkit, the coning and vibration
tools); none of them imports this one.

Modules
-------
imu_log
    A recorded IMU log: increments at a constant rate, in body axes.
native
    The package's own ``.npz`` and ``.csv`` formats.
alignment
    Alignment and observability of a recorded log.
examples
    The example log shipped with the docs.
"""
