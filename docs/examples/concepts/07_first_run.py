"""
The first run: compilation and caches
=====================================

The first command after installing takes longer than the next ones, and it
is worth knowing why. Two kinds of work are done once and kept:

* **Derived expressions.** A drift function, a transfer function or the
  second-order azimuth theory comes from a SymPy derivation that can take
  seconds. The first call anywhere runs the derivation, prints the result as
  plain numpy source (:func:`strapdown.analysis.core.cache.compiled`) and
  stores it; later calls, in this process or any other, load the source and
  never import the derivation. Derived results that the reports print (SymPy
  expressions, exact fractions) are pickled the same way
  (:func:`~strapdown.analysis.core.cache.derived`).
* **Compiled kernels.** The simulator runs each algorithm in a fused loop
  generated from the algorithm's own terms and compiled with numba
  (:mod:`strapdown.analysis.coning.kernels`); the multistage stages and the
  alignment Monte Carlo have compiled loops too. numba keeps the machine code
  on disk, so the compilation is paid once per install.

The cache lives in ``$STRAPDOWN_CACHE_DIR`` if set, else
``$XDG_CACHE_HOME/strapdown-analysis``, else ``~/.cache/strapdown-analysis``,
in a directory named after the package version and a fingerprint of its
source files: an edited derivation can never be served stale. Deleting the
directory is always safe.
"""

import os
import time

import numpy as np

from strapdown.analysis.coning import kernels
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core.cache import cache_directory, generate_source
from strapdown.derivations.coning.drift import X, coning_drift
from strapdown.derivations.coning.registry import get

print("cache set by STRAPDOWN_CACHE_DIR:", "yes" if os.environ.get("STRAPDOWN_CACHE_DIR") else "no (the XDG or home default)")
print("directory of this version:", cache_directory().name)

# %%
# A derived expression becomes plain numpy code
# ---------------------------------------------
# The closed-form coning drift ``D(ωh)`` of the two-sample algorithm, derived
# with SymPy, printed as the module that the cache stores (common
# subexpressions eliminated, every numpy function fully qualified):
print(generate_source((X,), coning_drift(get("two-sample")).function, key="example"))

# %%
# A kernel is generated from the algorithm's terms
# ------------------------------------------------
# The first lines of the module generated for ``miller-3``; the template
# functions that follow it are the same for every algorithm.
source = kernels.kernel_source(get("miller-3"), velocity=False)
print("\n".join(source.splitlines()[:14]))

# %%
# The cost of a first call
# ------------------------
# The first simulation of an algorithm in a process generates its kernel and
# compiles it, or loads the machine code that an earlier process left in the
# cache; the second call pays neither. The times below were measured while this
# page was built (a cold cache pays the compilation, a few seconds per
# algorithm; a warm one a fraction of a second).
coning = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))
algorithm = get("miller-3")
for attempt in ("first call", "second call"):
    start = time.perf_counter()
    compiled = simulate(algorithm, coning, sample_interval=1 / 400, duration=10.0, engine="compiled")
    print(f"{attempt}: {time.perf_counter() - start:.2f} s")

# %%
# The vectorised numpy path of the simulator (``engine="numpy"``) needs no
# compilation; it is the reference the kernels are tested against, and it is
# the right choice for a short run of an algorithm used once. The two engines
# agree to round-off:
start = time.perf_counter()
reference = simulate(algorithm, coning, sample_interval=1 / 400, duration=10.0, engine="numpy")
print(f"numpy engine: {time.perf_counter() - start:.2f} s")
print(f"drift: compiled {compiled.drift_rate:.6e}, numpy {reference.drift_rate:.6e} rad/s")
print(f"largest difference of the attitude errors: {np.abs(compiled.attitude_error - reference.attitude_error).max():.1e} rad")

# %%
# Progress and limits at the command line
# ---------------------------------------
# Long commands show a progress bar on stderr when stderr is a terminal
# (``--no-progress`` turns it off, ``--progress`` forces it); library
# functions that take long accept ``progress=True``. Every command that grows
# with its arguments estimates its memory and time before it starts and
# refuses more than ``--time-limit`` (300 s by default) or
# ``--memory-limit-mb`` (2000), naming the option to change.
