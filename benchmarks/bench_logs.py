"""Reading and checking recorded IMU logs: an hour at 1 kHz, and what real logs read as.

1. Writes a synthetic hour at 1 kHz (3.6 million samples, a rocking block with
   the package's IMU simulator tiled to an hour) as a PX4 ULog (``sensor_combined``,
   newer layout) and as the package's ``.npz``, then reads and checks each in a
   child process pinned to one core (``taskset -c 0`` where it exists), timing
   it and taking the child's peak resident memory (``resource.getrusage`` of the
   children), ``--repeat`` times each (default 5), printing the minimum and the median.
   Target: read + check in 5 s and 600 MB each (the whole target is read + check +
   replay of five algorithms in under 10 s and 1 GB; the replay has its own benchmark).
   The time is the child's whole run from before its first import of the package
   (numpy, numba's cached record walk, the reader), as a user's command pays it.
2. With ``--real DIR``, reads every log in DIR (``.ulg``, ``.bin``, ``.bag``) and
   prints what each reads as: format, software, stream, rate, segments, the
   unit of PX4's ``gyro_integral_dt``, and the checks that do not pass.

Run from the repository root::

    python benchmarks/bench_logs.py [--real DIR] [--minutes 60] [--repeat 5] [--keep DIR]

The numbers depend on the machine and its load: say which when quoting them.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
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
replayed = None
if len(sys.argv) > 2:  # then the replay of the algorithms named, on the same process's log
    from strapdown.derivations.coning.registry import get
    from strapdown.analysis.logs.replay import replay
    replay(log.segments, [get(name) for name in sys.argv[2].split(",")])
    replayed = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
print(json.dumps({"seconds": elapsed, "with_replay": replayed, "peak_bytes": peak, "samples": log.n_samples, "segments": len(log.segments),
                  "failures": [c.name for c in log.checks.failures]}))
"""

#: The five algorithms replayed after reading (``--replay``), as ``bench_log_analysis.py`` replays them.
ALGORITHMS = ("two-sample", "miller-3", "ignagni-1996-5", "ignagni-1996-4", "lebedev-panov-6")


def _hour(minutes: float):
    import numpy as np

    from strapdown.analysis.logs.synthetic import SyntheticTruth, rocking_truth

    block = rocking_truth(duration=60.0, rate=1000.0)  # one minute, tiled: the rocking's period divides it
    reps = int(round(minutes))
    n = block.time.size * reps
    t = np.arange(1, n + 1) * 1e-3
    return SyntheticTruth(t, np.tile(block.dtheta, (reps, 1)), np.tile(block.dv, (reps, 1)), block.latitude, f"{minutes:g} min at 1 kHz")


def _child(path: Path, replay: bool = False) -> dict:
    argv = [sys.executable, "-c", CHILD, str(path)] + ([",".join(ALGORITHMS)] if replay else [])
    if shutil.which("taskset"):
        argv = ["taskset", "-c", "0"] + argv
    out = subprocess.run(argv, check=True, capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _load() -> float:
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


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
    ap.add_argument("--keep", type=Path, default=None, help="write the synthetic logs here and keep them (and reuse them when they are there)")
    ap.add_argument("--repeat", type=int, default=5, help="runs of each child (default 5): the minimum and the median are printed")
    ap.add_argument("--replay", action="store_true", help="also replay the five algorithms of bench_log_analysis.py in the same child: read + check + replay")
    args = ap.parse_args(argv)
    from strapdown.analysis.logs.synthetic import write_synthetic

    folder = args.keep or Path(tempfile.mkdtemp(prefix="bench-logs-"))
    folder.mkdir(parents=True, exist_ok=True)
    try:
        t0 = time.perf_counter()
        paths = [folder / "hour.ulg", folder / "hour.npz"]
        if not all(p.exists() for p in paths):
            truth = _hour(args.minutes)
            paths = [write_synthetic(paths[0], truth), write_synthetic(paths[1], truth)]
            print(f"wrote {truth.time.size:.3g} samples as ULog and .npz in {time.perf_counter() - t0:.1f} s")
            del truth
        _child(paths[0])  # the numba cache of the record walk, compiled once per install
        print(f"{'file':<10} {'MB':>8} {'samples':>10} {'min s':>7} {'median s':>9} {'peak RSS MB':>12}  failures   (load average before each run)")
        for p in paths:
            runs, loads = [], []
            for _ in range(max(1, args.repeat)):
                loads.append(_load())
                runs.append(_child(p))
            secs = sorted(r["seconds"] for r in runs)
            peak = max(r["peak_bytes"] for r in runs)
            r = runs[0]
            print(f"{p.name:<10} {p.stat().st_size / 1e6:8.1f} {r['samples']:10d} {secs[0]:7.2f} {statistics.median(secs):9.2f} {peak / 1e6:12.0f}  "
                  f"{r['failures'] or 'none'}   ({', '.join(f'{x:.2g}' for x in loads)})")  # fmt: skip
            if args.replay:
                full = [_child(p, replay=True) for _ in range(max(1, args.repeat))]
                tot = sorted(x["with_replay"] for x in full)
                print(f"{'':<10} read + check + replay of {len(ALGORITHMS)} algorithms: min {tot[0]:.2f} s, median {statistics.median(tot):.2f} s, "
                      f"peak RSS {max(x['peak_bytes'] for x in full) / 1e6:.0f} MB")  # fmt: skip
        print("the machine's load average is that of all its cores (a shared machine runs slower)")
    finally:
        if args.keep is None:
            shutil.rmtree(folder, ignore_errors=True)
    if args.real is not None:
        _real(args.real)
    return 0


if __name__ == "__main__":
    sys.exit(main())
