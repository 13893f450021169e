"""The Monte Carlo commands on a dask cluster (``--dask``): the bytes of one worker, a lost worker changes nothing."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from strapdown.analysis.cli import main

ROOT = Path(__file__).resolve().parent.parent
AZIMUTH = ["azimuth", "--lat-deg", "45", "--sigma-xi-deg", "0.5", "--sigma-eta-deg", "0.5", "--rocking", "narrowband", "--period", "6", "--damping", "0.2", "--json"]
ALIGN = ["align", "--method", "analytic", "--lat-deg", "45", "--rocking", "sine", "--amplitude-deg", "1", "--duration", "20", "--trials", "24", "--gyro-bias-sigma-deg-per-h", "0.02", "--json"]


def _cli(argv, **kwargs):
    return subprocess.run([sys.executable, "-m", "strapdown.analysis", *argv], capture_output=True, text=True, cwd=ROOT, timeout=600, **kwargs)


@pytest.mark.parametrize("argv", [AZIMUTH + ["--samples", "300000"], ALIGN], ids=["azimuth", "align"])
def test_a_local_cluster_gives_the_bytes_of_one_worker(argv):
    pytest.importorskip("distributed")
    one = _cli(argv + ["--workers", "1", "--quiet"])
    cluster = _cli(argv + ["--dask", "local:2"])
    assert one.returncode == 0 and cluster.returncode == 0, (one.stderr, cluster.stderr)
    assert cluster.stdout == one.stdout and json.loads(one.stdout)  # byte for byte
    # progress went to stderr across the cluster (plain lines: stderr is a pipe), and nothing else to stdout
    assert "strapdown " + argv[0] in cluster.stderr or cluster.stderr == ""


def test_a_worker_killed_mid_run_changes_nothing():
    """One of two workers is killed (SIGKILL) while it holds tasks: the scheduler runs them again elsewhere, same bytes."""
    distributed = pytest.importorskip("distributed")
    argv = AZIMUTH + ["--samples", "12000000", "--quiet"]
    reference = _cli(argv + ["--workers", "1"])
    assert reference.returncode == 0, reference.stderr
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        pids = client.run(os.getpid)
        run = subprocess.Popen([sys.executable, "-m", "strapdown.analysis", *argv, "--dask", cluster.scheduler_address], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT)
        killed, deadline = None, time.monotonic() + 300
        while killed is None and time.monotonic() < deadline and run.poll() is None:
            busy = [w for w, tasks in client.processing().items() if tasks]
            if busy:
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed = busy[0]
            else:
                time.sleep(0.01)
        assert killed is not None and run.poll() is None, "the run ended before a worker could be killed"
        out, err = run.communicate(timeout=600)
    assert run.returncode == 0, err
    assert out == reference.stdout


def test_dask_refusals_are_one_line_naming_the_option(capsys):
    for value, word in (("local:0", "local:N"), ("local:x", "local:N"), ("not an address", "scheduler address")):
        assert main(AZIMUTH + ["--samples", "1000", "--dask", value]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--dask" in err and word in err, err
    assert main(AZIMUTH + ["--samples", "1000", "--workers", "2", "--dask", "local:2"]) == 2
    err = capsys.readouterr().err
    assert "--workers 2 and --dask exclude each other" in err and err.count("\n") == 1


def test_an_unreachable_scheduler_is_one_line():
    pytest.importorskip("distributed")
    out = _cli(AZIMUTH + ["--samples", "1000", "--quiet", "--dask", "tcp://127.0.0.1:9"])  # the discard port: nothing listens
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert "--dask tcp://127.0.0.1:9: could not reach a dask scheduler" in out.stderr and "Traceback" not in out.stderr


def test_without_dask_the_option_says_how_to_install_it():
    """dask.distributed hidden from a child process: one line naming the extra, exit 2."""
    code = (
        "import sys; sys.modules['distributed'] = None\n"
        "from strapdown.analysis.cli import main\n"
        f"sys.exit(main({AZIMUTH + ['--samples', '1000', '--quiet', '--dask', 'local:2']!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert "--dask needs dask.distributed" in out.stderr and "strapdown-analysis[distributed]" in out.stderr
