"""Reading and checking recorded IMU logs: an hour at 1 kHz, and what real logs read as.

1. Writes a synthetic hour at 1 kHz (3.6 million samples, a rocking block with
   the package's IMU simulator tiled to an hour) as a PX4 ULog (``sensor_combined``,
   newer layout) and as the package's ``.npz``, then reads and checks each in a
   child process pinned to one core (``taskset -c 0`` where it exists), timing
   it and taking the child's peak resident memory (``resource.getrusage`` of the
   children).  Target: a few seconds and well under 1 GB each (the whole issue's
   target is read + check + replay of five algorithms in under 10 s and 1 GB).
2. With ``--real DIR``, reads every log in DIR (``.ulg``, ``.bin``, ``.bag``) and
   prints what each reads as: format, software, stream, rate, segments, the
   unit of PX4's ``gyro_integral_dt``, and the checks that do not pass.

Run from the repository root::

    python benchmarks/bench_logs.py [--real DIR] [--minutes 60] [--keep DIR]

The numbers depend on the machine and its load: say which when quoting them.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

CHILD = r"""
import json, resource, sys, time
start = time.perf_counter()
from strapdown.analysis.logs.reader import read_imu_log
log = read_imu_log(sys.argv[1], latitude=0.7853981633974483)
elapsed = time.perf_counter() - start
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({"seconds": elapsed, "peak_bytes": peak, "samples": log.n_samples, "segments": len(log.segments),
                  "failures": [c.name for c in log.checks.failures]}))
"""


def _hour(minutes: float):
    import numpy as np

    from strapdown.analysis.logs.synthetic import SyntheticTruth, rocking_truth

    block = rocking_truth(duration=60.0, rate=1000.0)  # one minute, tiled: the rocking's period divides it
    reps = int(round(minutes))
    n = block.time.size * reps
    t = np.arange(1, n + 1) * 1e-3
    return SyntheticTruth(t, np.tile(block.dtheta, (reps, 1)), np.tile(block.dv, (reps, 1)), block.latitude, f"{minutes:g} min at 1 kHz")


def _child(path: Path) -> dict:
    argv = [sys.executable, "-c", CHILD, str(path)]
    if shutil.which("taskset"):
        argv = ["taskset", "-c", "0"] + argv
    out = subprocess.run(argv, check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _real(folder: Path) -> None:
    from strapdown.analysis.logs.reader import read_imu_log

    print(f"\nreal logs in {folder}:")
    for path in sorted(p for p in folder.iterdir() if p.suffix.lower() in (".ulg", ".bin", ".bag")):
        try:
            log = read_imu_log(path)
        except (ValueError, OSError) as e:
            print(f"  {path.name}: refused: {e}")
            continue
        t = log.inventory.timing
        unit = f", integral_dt in {t.integration_interval_unit}" if t.integration_interval_unit else ""
        bad = [f"{c.name} {c.status}" for c in log.checks.checks if c.status in ("fail", "warn")]
        print(
            f"  {path.name}: {log.format}, {log.inventory.software}; {log.topic} ({log.held}) {t.rate_hz:.5g} Hz, "
            f"{log.n_samples} samples in {len(log.segments)} segment(s), jitter {t.jitter_rms * 1e6:.3g} µs{unit}; "
            f"{len(log.inventory.streams)} topics; checks not passing: {', '.join(bad) or 'none'}"
        )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--real", type=Path, default=None, help="a folder of real logs to read")
    ap.add_argument("--minutes", type=float, default=60.0, help="length of the synthetic log [min] (default 60)")
    ap.add_argument("--keep", type=Path, default=None, help="write the synthetic logs here and keep them")
    args = ap.parse_args(argv)
    from strapdown.analysis.logs.synthetic import write_synthetic

    folder = args.keep or Path(tempfile.mkdtemp(prefix="bench-logs-"))
    folder.mkdir(parents=True, exist_ok=True)
    try:
        t0 = time.perf_counter()
        truth = _hour(args.minutes)
        paths = [write_synthetic(folder / "hour.ulg", truth), write_synthetic(folder / "hour.npz", truth)]
        print(f"wrote {truth.time.size:.3g} samples as ULog and .npz in {time.perf_counter() - t0:.1f} s")
        del truth
        _child(paths[0])  # the numba cache of the record walk, compiled once per install
        print(f"{'file':<10} {'MB':>8} {'samples':>10} {'seconds':>8} {'peak RSS MB':>12}  failures")
        for p in paths:
            r = _child(p)
            print(f"{p.name:<10} {p.stat().st_size / 1e6:8.1f} {r['samples']:10d} {r['seconds']:8.2f} {r['peak_bytes'] / 1e6:12.0f}  {r['failures'] or 'none'}")
        try:
            print(f"load average {os.getloadavg()[0]:.2f} (a shared machine runs slower)")
        except OSError:
            pass
    finally:
        if args.keep is None:
            shutil.rmtree(folder, ignore_errors=True)
    if args.real is not None:
        _real(args.real)
    return 0


if __name__ == "__main__":
    sys.exit(main())
