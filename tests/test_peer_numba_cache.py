"""The peers' numba functions in numba's disk cache, in the package's own cache directory.

pyins and smsfusion compile their numba functions without ``cache=True``; the
adapters (:mod:`strapdown.analysis.coning.integrators.peers`) keep the machine
code in the package's cache directory.  Each case runs in a fresh process (the
compiled code lives for the whole process): a first process compiles and
writes the cache, a second loads it (numba counts the hits), and a process
whose cache directory cannot be written compiles in memory.  All three give
the same bits, and nothing is written into pyins's installation.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("pyins")
pytest.importorskip("smsfusion")

_SCRIPT = r"""
import json, sys
import numpy as np
from strapdown.analysis.core.cache import cache_directory
from strapdown.analysis.coning.integrators.interface import step_increments
from strapdown.analysis.coning.integrators.peers import pyins_integrator, smsfusion_ins

rng = np.random.default_rng(7)
gyro, accel = 1e-2 * rng.standard_normal((24, 3)), 1e-2 * rng.standard_normal((24, 3))
loop = step_increments(pyins_integrator(), gyro, 1).rotation
sms = step_increments(smsfusion_ins(), gyro, 1, accel)
from pyins import _numba_integrate
import smsfusion._ins as ins

stats = _numba_integrate.integrate.stats
print(json.dumps({
    "pyins": loop.tobytes().hex(),
    "smsfusion": sms.rotation.tobytes().hex() + sms.velocity.tobytes().hex(),
    "pyins_hits": sum(stats.cache_hits.values()),
    "pyins_misses": sum(stats.cache_misses.values()),
    "smsfusion_hits": sum(sum(f.stats.cache_hits.values()) for f in (ins._normalize, ins._rot_matrix_from_quaternion, ins._angular_matrix_from_quaternion)),
    "pyins_cache": getattr(_numba_integrate.integrate._cache, "cache_path", None),
    "cache_directory": str(cache_directory()),
}))
"""


def _run(cache_dir) -> dict:
    env = dict(os.environ, STRAPDOWN_CACHE_DIR=str(cache_dir))
    env.pop("NUMBA_CACHE_DIR", None)
    done = subprocess.run([sys.executable, "-c", _SCRIPT], capture_output=True, text=True, env=env, timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_peers_compiled_code_is_cached_in_the_package_cache_and_gives_the_same_bits(tmp_path):
    import pyins

    first, second = _run(tmp_path / "cache"), _run(tmp_path / "cache")
    assert first["pyins_misses"] == 1 and first["pyins_hits"] == 0  # compiled, then written
    assert second["pyins_hits"] == 1 and second["pyins_misses"] == 0  # loaded, not compiled
    assert second["smsfusion_hits"] == 3
    assert Path(second["pyins_cache"]).is_relative_to(second["cache_directory"])
    assert "numba-pyins-earth-rate-zero" in second["pyins_cache"]
    assert second["pyins"] == first["pyins"] and second["smsfusion"] == first["smsfusion"]
    # nothing written next to pyins's sources (its installation may be read-only, and other users compile their own)
    assert not list(Path(pyins.__file__).parent.glob("__pycache__/*.nb[ic]"))

    # a cache directory that cannot be created (below a regular file): compiled in memory, the same bits
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    third = _run(blocker / "cache")
    assert third["pyins_cache"] is None and third["pyins_hits"] == 0
    assert third["pyins"] == first["pyins"] and third["smsfusion"] == first["smsfusion"]


def test_smsfusion_adapter_feeds_the_same_floats_as_a_sample_by_sample_loop():
    import numpy as np
    from smsfusion import StrapdownINS

    from strapdown.analysis.coning.integrators.peers import smsfusion_ins

    h = 0.0025
    rng = np.random.default_rng(11)
    gyro, accel = 1e-2 * rng.standard_normal((40, 3)), 1e-1 * rng.standard_normal((40, 3))
    ins = StrapdownINS(1.0 / h, np.r_[np.zeros(6), 1.0, 0.0, 0.0, 0.0, np.zeros(6)], g=0.0)
    q, v = [], []
    for k in range(40):  # one update per sample, the division row by row
        ins.update(accel[k] / h, gyro[k] / h)
        if (k + 1) % 4 == 0:
            q.append(ins.quaternion())
            v.append(ins.velocity())
    got = smsfusion_ins(sample_interval=h).function(gyro, 4, accel)
    assert np.array_equal(got[0], np.array(q)) and np.array_equal(got[1], np.array(v))
