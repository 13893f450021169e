"""Write ``docs/examples/rocking-imu-log.npz``, the example log of ``docs/recorded-logs.md``.

The log is :func:`strapdown.analysis.logs.examples.example_log` (seed
:data:`~strapdown.analysis.logs.examples.EXAMPLE_SEED`, 20261203): four
minutes of a simulated navigation-grade IMU on a rocking base, increments
stored as float32 (about 0.3 MB).  Running this script again writes the same
arrays (the zip members' timestamps differ).

Usage: ``python tools/make_example_log.py [OUT]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from strapdown.analysis.logs.examples import example_log
from strapdown.analysis.logs.native import write_log

DEFAULT = Path(__file__).resolve().parents[1] / "docs" / "examples" / "rocking-imu-log.npz"


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    out = Path(argv[0]) if argv else DEFAULT
    out.parent.mkdir(parents=True, exist_ok=True)
    write_log(out, example_log(), dtype=np.float32)
    print(f"{out}: {out.stat().st_size / 1e6:.2f} MB")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
