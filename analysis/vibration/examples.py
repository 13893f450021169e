"""Example environment files shipped with the package (``strapdown/analysis/vibration/environments/``).

They are the examples of ``docs/environment-files.md`` and ``docs/mount-files.md`` and of the report
sections ``vibration.md`` and ``mount.md``, and read like any user file
(:func:`strapdown.analysis.vibration.environment.load_environment`,
:func:`~strapdown.analysis.vibration.profile.load_profile`, :func:`~strapdown.analysis.vibration.mount.load_mount`).

Public API
----------
.. autosummary::

   DIRECTORY
   CONING_10HZ
   QUALIFICATION
   AIRFRAME_PROFILE
   ISOLATED_MOUNT
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["DIRECTORY", "CONING_10HZ", "QUALIFICATION", "AIRFRAME_PROFILE", "ISOLATED_MOUNT"]

#: Folder of the example files.
DIRECTORY = Path(__file__).resolve().with_name("environments")
#: One classical coning line (10 Hz, 1°) seen through a first-order 100 Hz gyro filter.
CONING_10HZ = DIRECTORY / "coning-10hz.toml"
#: A MEMS IMU in a rotorcraft bay: rotor lines over a qualification random-vibration spectrum,
#: analog anti-aliasing and digital low-pass filters, decimation by 4.
QUALIFICATION = DIRECTORY / "qualification.toml"
#: An illustrative linear random-vibration profile of an airframe rack (breakpoints and dB/octave slopes, in g²/Hz,
#: with a small angular part): a profile file (:func:`strapdown.analysis.vibration.profile.load_profile`).
AIRFRAME_PROFILE = DIRECTORY / "airframe-profile.toml"
#: A 1 kg IMU block on four elastomer isolators, its centre of mass above the isolator plane: a mount file
#: (:func:`strapdown.analysis.vibration.mount.load_mount`).
ISOLATED_MOUNT = DIRECTORY / "isolated-imu-mount.toml"
