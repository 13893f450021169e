"""The defaults of identification in one light module, for the library and for the command line that starts before it.

``strapdown identify`` starts the child process that runs the user's code
before it imports the analysis (SymPy, SciPy): the options' defaults come from
here, where nothing heavy is imported, and the library modules take them from
here too.

Public API
----------
:data:`TOLERANCE`, :data:`DEFAULT_MAX_PREVIOUS`, :data:`LONGEST_MEMORY`, :data:`PROBE_AMPLITUDE`,
:data:`DRIFT_TOLERANCE`, :data:`OMEGA_H`.
"""

from __future__ import annotations

__all__ = ["TOLERANCE", "DEFAULT_MAX_PREVIOUS", "LONGEST_MEMORY", "PROBE_AMPLITUDE", "DRIFT_TOLERANCE", "OMEGA_H"]

#: Largest tolerance of the rational reconstruction [dimensionless]: ``|c − p/q| ≤ 1e-9``, q ≤ 22 360 at most.
TOLERANCE = 1e-9
#: Default number of earlier samples probed.
DEFAULT_MAX_PREVIOUS = 4
#: Longest memory probed by default [samples].
LONGEST_MEMORY = 64
#: Default probe amplitude ε_0 [rad, and m/s for accelerometer probes].
PROBE_AMPLITUDE = 2e-2
#: Relative tolerance of the simulated against the closed-form drift [dimensionless].
DRIFT_TOLERANCE = 1e-6
#: ωh of the coning check [rad].
OMEGA_H = (0.25, 0.5, 1.0, 2.0)
