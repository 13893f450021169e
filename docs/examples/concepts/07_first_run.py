"""
The first run: compilation, caches and progress
===============================================

The first command after installing takes longer than the next ones, and it
is worth knowing why. Three kinds of work are done once and kept:

* **Derived expressions.** A drift function, a transfer function or the
  second-order azimuth theory comes from a SymPy derivation that can take
  seconds. The first call anywhere runs the derivation, prints the result as
  plain numpy source (:func:`strapdown.analysis.core.cache.compiled`) and
  stores it; later calls, in this process or any other, load the source and
  never import the derivation. Derived results that the reports print (SymPy
  expressions, exact fractions) are pickled the same way
  (:func:`~strapdown.analysis.core.cache.derived`); a derivation that another
  process is building is waited for, not repeated.
* **Compiled kernels.** The simulator's compiled engine runs an algorithm in a
  fused loop compiled with numba (:mod:`strapdown.analysis.coning.kernels`).
  A purely pairwise algorithm — every algorithm of the registry but one, and
  most files of users — is run by one kernel that takes its terms as data, so
  that kernel is compiled once and serves every such algorithm; an algorithm
  with nested or dot-weighted terms gets a kernel of its own. The multistage
  stages and the alignment Monte Carlo have compiled loops too. numba keeps
  the machine code on disk, so each compilation is paid once per install.
* **Rendered mathematics** of the HTML edition of the report.

The cache lives in ``$STRAPDOWN_CACHE_DIR`` if set, else
``$XDG_CACHE_HOME/strapdown-analysis``, else ``~/.cache/strapdown-analysis``,
in a directory named after the package version and a fingerprint of its
source files: an edited derivation can never be served stale. Deleting the
directory is always safe.

The first ``strapdown report`` does not wait for all of it in turn: while it
writes its sections one by one, a second process compiles the kernels and
runs the derivations of the sections still to come (each report section that
compiles or derives has a ``warm_up()``, run by
:mod:`strapdown.analysis.report.warm_up`), so that on a machine with a second
core most of that work is done before the report reaches it. The results are
the same either way: a cache holds what the same code computes.
"""

import io
import os
import subprocess
import sys
import time

import numpy as np

from strapdown.analysis.coning import kernels
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.analysis.core import budget, progress
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
# One kernel for every pairwise algorithm
# ---------------------------------------
# A pairwise algorithm reaches the kernel as a table, one row ``(i, j, c_ij)``
# per term ``c_ij p_i × p_j`` (rows of the window of increments):
miller = get("miller-3")
print("pairwise:", kernels.is_pairwise(miller))
print(kernels.pairwise_data(miller))

# %%
# and the module it runs names no algorithm:
print("\n".join(kernels.kernel_source(miller, velocity=False).splitlines()[:3]))

# %%
# An algorithm with nested terms, ``lebedev-panov-6``, gets straight-line code
# generated from its own terms instead:
nested = get("lebedev-panov-6")
print("pairwise:", kernels.is_pairwise(nested))
for line in kernels.kernel_source(nested, velocity=False).splitlines()[:3]:
    print(line if len(line) <= 100 else line[:99] + "…")

# %%
# The cost of a first call
# ------------------------
# The first compiled simulation in a process compiles the pairwise kernel, or
# loads the machine code that an earlier process left in the cache; the next
# call pays neither, and neither does the first call of *another* pairwise
# algorithm. The times below were measured while this page was built, in a
# new process (the pages of this site share one, and an earlier page may
# have run the kernel already): with a cold cache the first call pays the
# compilation, a few seconds; with a warm one (here, if an earlier page
# compiled the kernel) it loads the machine code in a fraction of a second.
first_calls = """
import time
import numpy as np
from strapdown.analysis.coning.precession import RegularPrecession
from strapdown.analysis.coning.simulator import simulate
from strapdown.derivations.coning.registry import get
coning = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))
for attempt, name in (("first call, miller-3", "miller-3"), ("second call, miller-3", "miller-3"), ("first call, two-sample", "two-sample")):
    start = time.perf_counter()
    simulate(get(name), coning, sample_interval=1 / 400, duration=10.0, engine="compiled")
    print(f"{attempt:>22}: {time.perf_counter() - start:.2f} s")
"""
print(subprocess.run([sys.executable, "-c", first_calls], capture_output=True, text=True, check=True).stdout, end="")

# %%
# The vectorised numpy path of the simulator (``engine="numpy"``) needs no
# compilation; it is the reference the kernels are tested against, and it is
# the right choice for a short run (``engine="auto"``, the default, takes it
# below about two million sample steps). The two engines agree to round-off:
coning = RegularPrecession(eps=-1.0, nu=2 * np.pi * 10, nutation=np.radians(1.0))
compiled = simulate(miller, coning, sample_interval=1 / 400, duration=10.0, engine="compiled")
start = time.perf_counter()
reference = simulate(miller, coning, sample_interval=1 / 400, duration=10.0, engine="numpy")
print(f"numpy engine: {time.perf_counter() - start:.2f} s")
print(f"drift: compiled {compiled.drift_rate:.6e}, numpy {reference.drift_rate:.6e} rad/s")
print(f"largest difference of the attitude errors: {np.abs(compiled.attitude_error - reference.attitude_error).max():.1e} rad")

# %%
# Progress, limits and the report's files at the command line
# -----------------------------------------------------------
# A command that works for long says so on stderr, in one of three ways
# chosen by :func:`~strapdown.analysis.core.progress.mode`: bars that redraw
# in place when stderr is a terminal; plain lines when it is a file, a pipe or
# a notebook (a CI log), the first after a few seconds and then every few
# seconds, each saying what runs, the fraction done and the time elapsed, such
# as ``strapdown report: 43% done, report: derivations 3/10; coning drift
# 12/28, 65 s elapsed``; and nothing with ``--quiet`` (or ``--no-progress``).
# ``--json`` output on stdout is never mixed with it.
for stream, quiet, what in ((io.StringIO(), False, "stderr a file or a pipe"), (io.StringIO(), True, "--quiet")):
    print(f"{what:>24}: {progress.mode(quiet, stream)}")

# %%
# Every command whose work grows with its arguments estimates its memory and
# time before it starts and refuses more than ``--time-limit`` (300 s by
# default) or ``--memory-limit-mb`` (2000), naming the option to change. The
# Python functions do the same before they allocate, naming the argument
# (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, a ``ValueError``),
# and take ``limits=`` (:class:`~strapdown.analysis.core.budget.Limits`) to
# allow more. A simulation of 10⁷ s by mistake:
try:
    simulate(miller, coning, sample_interval=1 / 400, duration=1e7)
except budget.BudgetExceeded as error:
    print("refused:", error)

# %%
# ``strapdown report --out DIR`` replaces DIR only if it is new, empty or holds
# nothing but an earlier report, and swaps the finished report in atomically.
# Its manifest records the SHA-256 of every file it wrote: a later run that
# would replace a generated file edited since refuses before any work, names
# the files and leaves the edits as they are, unless ``--overwrite-modified``
# is given.
