"""Where a command's Monte Carlo runs: here, on worker processes (``--workers``) or on a dask cluster (``--dask``).

The library's Monte Carlos take an ``executor``
(:func:`strapdown.analysis.core.montecarlo.map_tasks`): None, a
:class:`concurrent.futures.Executor`, or a ``dask.distributed`` ``Client``.
Their randomness is tied to blocks of trials, not to workers, so the result
is the same bits on any of them.  These helpers give every Monte Carlo command
the same two options:

``--workers N``
    N worker processes on this machine (a process pool).
``--dask SCHEDULER_ADDRESS``
    a running dask.distributed scheduler (``tcp://host:8786``, as started by
    ``dask scheduler``, dask-jobqueue or a Kubernetes deployment), or
    ``local:N`` for a local cluster of N worker processes started for the
    command.  dask is the optional extra ``distributed``; without it the
    option is refused in one line.

A worker lost mid-run costs time, not bits: the scheduler runs its tasks
again elsewhere, and each task draws from its own block seeds.
"""

from __future__ import annotations

import re
from contextlib import contextmanager

from ..core.validation import as_int
from . import UsageError

#: ``local:N``: a local cluster of N worker processes.
_LOCAL = re.compile(r"^local:(.*)$")
#: A scheduler address: an optional protocol, then host[:port] (no spaces).
_ADDRESS = re.compile(r"^(?:(tcp|tls|ucx|ws|wss|inproc)://)?[^\s/:]+(?::\d{1,5})?/?$")
#: Seconds to wait for a scheduler before giving up.
CONNECT_TIMEOUT = 10.0
#: Most local workers ``--dask local:N`` starts.
MAX_LOCAL_WORKERS = 256


def add_executor(parser) -> None:
    """Add ``--workers`` and ``--dask`` to a Monte Carlo command.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    """
    from ._options import count

    parser.add_argument("--workers", type=count, default=1, help="worker processes on this machine [count] (default 1; the result does not depend on it)")
    parser.add_argument(
        "--dask",
        default=None,
        metavar="SCHEDULER_ADDRESS",
        help="run the trials on a dask.distributed cluster: the scheduler's address (tcp://host:8786) or local:N for N local worker "
        "processes [name] (default: none; needs the 'distributed' extra; the result does not depend on it; docs/cluster.md)",
    )


def parse_dask(value: str | None):
    """The cluster ``--dask`` asks for: None, ``("local", N)`` or ``("address", text)``.

    Parameters
    ----------
    value : str or None
        The value typed.

    Returns
    -------
    tuple or None

    Raises
    ------
    UsageError
        A value that is neither ``local:N`` (N a whole number 1 … 256) nor a scheduler address.
    """
    if value is None:
        return None
    text = str(value).strip()
    local = _LOCAL.match(text)
    if local:
        digits = local.group(1).strip()
        if not digits.isdigit() or int(digits) < 1:
            raise UsageError(f"Expected --dask local:N with N a whole number of workers >= 1, got {value!r}")
        n = int(digits)
        if n > MAX_LOCAL_WORKERS:
            raise UsageError(f"Expected --dask local:N with N <= {MAX_LOCAL_WORKERS} local workers, got {n}")
        return ("local", n)
    if not _ADDRESS.match(text):
        raise UsageError(f"Expected --dask as a scheduler address (tcp://host:8786) or local:N, got {value!r}")
    return ("address", text)


def workers(args) -> int:
    """Worker processes on this machine that the command's memory estimate must count.

    ``--workers N`` and ``--dask local:N`` run N processes here; a remote
    scheduler's workers use their own machines' memory, so they count as one
    (the results gathered here).  Validates both options, which exclude each other.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options (``workers`` and ``dask``).

    Returns
    -------
    int

    Raises
    ------
    UsageError
        Bad values, or ``--workers`` above 1 together with ``--dask``.
    """
    n = as_int(args.workers, "--workers", minimum=1)
    cluster = parse_dask(getattr(args, "dask", None))
    if cluster is None:
        return n
    if n > 1:
        raise UsageError(f"--workers {n} and --dask exclude each other: the cluster's workers run the trials")
    return cluster[1] if cluster[0] == "local" else 1


def _distributed():
    try:
        import distributed
    except ImportError:
        raise UsageError("--dask needs dask.distributed, which is not installed: pip install 'strapdown-analysis[distributed]'") from None
    return distributed


@contextmanager
def executor(args):
    """The executor the options ask for, open for the ``with`` block and closed after it.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed options (``workers`` and ``dask``), checked by :func:`workers`.

    Yields
    ------
    None, concurrent.futures.ProcessPoolExecutor or distributed.Client

    Raises
    ------
    UsageError
        ``--dask`` without dask.distributed installed, or a scheduler that cannot be reached.
    """
    n = workers(args)
    cluster = parse_dask(getattr(args, "dask", None))
    if cluster is None:
        if n == 1:
            yield None
            return
        from ..core.montecarlo import process_pool

        pool = process_pool(n)
        try:
            yield pool
        finally:
            pool.shutdown()
        return
    distributed = _distributed()
    import logging

    if cluster[0] == "local":
        with (
            distributed.LocalCluster(n_workers=cluster[1], threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=logging.ERROR) as local,
            distributed.Client(local) as client,
        ):
            yield client
        return
    try:
        client = distributed.Client(cluster[1], timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError) as exc:
        detail = " ".join(str(exc).split()) or type(exc).__name__
        raise UsageError(f"--dask {cluster[1]}: could not reach a dask scheduler within {CONNECT_TIMEOUT:g} s ({detail[:200]})") from None
    with client:
        yield client
