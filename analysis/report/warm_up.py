"""The caches a cold report needs, filled on the second core while the report is written.

The first ``strapdown report`` after an install compiles its numba kernels and
runs its SymPy derivations; both are cached on disk (numba's cache,
:mod:`strapdown.analysis.core.cache`), so later runs only load them.  While the
report writes its sections one by one, :func:`start` runs, in a second
process, the ``warm_up()`` of the sections that have one, in report order, so
that it runs ahead of the report: each compiles and derives what its
``build`` will need (the first section only what it needs after its start),
and writes nothing else.  When the report reaches a section, its kernels and
derivations are usually in the cache already; where they are not, the report
does the work itself (a derivation another process is building is waited for,
not repeated: :func:`strapdown.analysis.core.cache.derived`).  The results are
the same either way: a cache holds what the same code computes.

Once a warm-up has finished, it leaves a marker in the cache directory, and
later reports start none.

Public API: :func:`start`, :func:`stop`, :func:`main`.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import subprocess
import sys

__all__ = ["start", "stop", "main"]

_MARKER = "report-warm-up-{}.done"


def _marker(names) -> str:
    import hashlib

    from ..core.cache import cache_directory

    return str(cache_directory() / _MARKER.format(hashlib.sha256(" ".join(names).encode()).hexdigest()[:16]))


def start(modules):
    """Start the warm-up of ``modules`` (section modules, in report order) in a background process.

    Parameters
    ----------
    modules : sequence of module
        The sections of the run, in report order; those with a ``warm_up``
        function are warmed.

    Returns
    -------
    subprocess.Popen or None
        The process, or None when there is nothing to warm (no section has a
        ``warm_up``, or an earlier warm-up of the same sections finished).
    """
    names = [m.__name__ for m in modules if callable(getattr(m, "warm_up", None))]
    if not names or os.path.exists(_marker(names)):
        return None
    code = "import sys; from strapdown.analysis.report import warm_up; warm_up.main(sys.argv[1:])"
    try:
        return subprocess.Popen([sys.executable, "-c", code, *names], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except OSError:  # no second process: the report does the work itself
        return None


def stop(process) -> None:
    """End the warm-up ``process`` if it still runs (its cache files are written atomically).

    Parameters
    ----------
    process : subprocess.Popen or None
        From :func:`start`.
    """
    if process is None or process.poll() is not None:
        return
    process.terminate()
    try:
        process.wait(timeout=10)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def main(names) -> None:
    """Run the ``warm_up()`` of the section modules ``names``, in that order (the body of the background process).

    A warm-up that fails is skipped: the report does that work itself.

    Parameters
    ----------
    names : sequence of str
        Fully qualified section module names.
    """
    from .rendering import configure_matplotlib

    configure_matplotlib()
    for name in names:
        try:
            importlib.import_module(name).warm_up()
        except Exception:  # noqa: BLE001 - the report repeats whatever failed here, and reports its errors itself
            continue
    with contextlib.suppress(OSError):
        marker = _marker(list(names))
        os.makedirs(os.path.dirname(marker), exist_ok=True)
        with open(marker, "w", encoding="utf-8") as handle:
            handle.write("\n".join(names) + "\n")
