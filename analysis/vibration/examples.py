"""Example environment files shipped with the package (``strapdown/analysis/vibration/environments/``).

They are the examples of ``docs/environment-files.md`` and of the report section
``vibration.md``, and read like any user file (:func:`strapdown.analysis.vibration.environment.load_environment`).

Public API
----------
.. autosummary::

   DIRECTORY
   CONING_10HZ
   QUALIFICATION
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["DIRECTORY", "CONING_10HZ", "QUALIFICATION"]

#: Folder of the example files.
DIRECTORY = Path(__file__).resolve().with_name("environments")
#: One classical coning line (10 Hz, 1°) seen through a first-order 100 Hz gyro filter.
CONING_10HZ = DIRECTORY / "coning-10hz.toml"
#: A MEMS IMU in a rotorcraft bay: rotor lines over a qualification random-vibration spectrum,
#: analog anti-aliasing and digital low-pass filters, decimation by 4.
QUALIFICATION = DIRECTORY / "qualification.toml"
