"""Bad input to ``strapdown log environment|coning|allan``: one line on stderr, exit 2, nothing half-written."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from cli_contract import run, violations
from log_synthetic import cone_log

from strapdown.analysis.logs.native import write_log

H = 1e-3


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    d = tmp_path_factory.mktemp("logs")
    write_log(d / "cone.npz", cone_log(4000, H))
    write_log(d / "short.npz", cone_log(20, H))
    data = (d / "cone.npz").read_bytes()
    (d / "truncated.npz").write_bytes(data[: len(data) // 2])
    (d / "empty.csv").write_text("")
    return d


def _refused(argv, names, tmp_path):
    before = sorted(p.name for p in tmp_path.iterdir())
    outcome = run(argv + ["--quiet"], timeout=120.0)
    problems = violations(outcome, expect="refuse", names=names, limit=60.0, argv=argv)
    assert not problems, (argv, outcome, problems)
    assert sorted(p.name for p in tmp_path.iterdir()) == before, "a file was left behind"
    return outcome


CASES = [
    ("environment", ["--out", "{tmp}/e.toml"], "{logs}/missing.npz", ()),
    ("environment", ["--out", "{tmp}/e.toml"], "{logs}/truncated.npz", ()),
    ("environment", ["--out", "{tmp}/e.toml"], "{logs}/empty.csv", ()),
    ("environment", ["--out", "{tmp}/no-such-dir/e.toml"], "{logs}/cone.npz", ()),
    ("environment", ["--out", "{tmp}"], "{logs}/cone.npz", ()),
    ("environment", ["--out", "{tmp}/e.toml", "--figure", "{tmp}/no-such-dir/e.png"], "{logs}/cone.npz", ()),
    ("environment", ["--out", "{tmp}/e.toml", "--segment", "3:1"], "{logs}/cone.npz", ("--segment",)),
    ("environment", ["--out", "{tmp}/e.toml", "--segment", "abc"], "{logs}/cone.npz", ("--segment",)),
    ("environment", ["--out", "{tmp}/e.toml", "--segment", "100:200"], "{logs}/cone.npz", ("--segment",)),
    ("environment", ["--out", "{tmp}/e.toml", "--resolution-hz", "1e-6"], "{logs}/cone.npz", ("--resolution-hz",)),
    ("environment", ["--out", "{tmp}/e.toml", "--min-freq-hz", "600"], "{logs}/cone.npz", ("--min-freq-hz",)),
    ("environment", ["--out", "{tmp}/e.toml", "--false-alarm", "2"], "{logs}/cone.npz", ("--false-alarm",)),
    ("environment", ["--out", "{tmp}/e.toml", "--max-rows", "1"], "{logs}/cone.npz", ("--max-rows",)),
    ("environment", ["--out", "{tmp}/e.toml", "--topic", "sensor_combined"], "{logs}/cone.npz", ("--topic",)),
    ("coning", ["--algorithm", "two-sample"], "{logs}/missing.npz", ()),
    ("coning", ["--algorithm", "two-sample"], "{logs}/truncated.npz", ()),
    ("coning", ["--algorithm", "no-such"], "{logs}/cone.npz", ("--algorithm",)),
    ("coning", [], "{logs}/cone.npz", ("--algorithm",)),
    ("coning", ["--algorithm-file", "{logs}/missing.toml"], "{logs}/cone.npz", ("--algorithm-file",)),
    ("coning", ["--algorithm", "ignagni-1996-4", "--segment", "0:0.004"], "{logs}/cone.npz", ()),
    ("allan", [], "{logs}/short.npz", ()),
    ("allan", ["--out", "{tmp}/no-such-dir/imu.toml"], "{logs}/cone.npz", ()),
    ("allan", ["--segment", ":-5"], "{logs}/cone.npz", ("--segment",)),
]


@pytest.mark.parametrize("command, options, log, names", CASES, ids=[f"{c[0]} {' '.join(c[1])} {Path(c[2]).name}" for c in CASES])
def test_bad_input_is_one_line_exit_2_and_nothing_written(logs, tmp_path, command, options, log, names):
    fill = {"tmp": str(tmp_path), "logs": str(logs)}
    argv = ["log", command, log.format(**fill)] + [o.format(**fill) for o in options]
    _refused(argv, names, tmp_path)


def test_a_good_run_writes_its_files(logs, tmp_path):
    argv = ["log", "environment", str(logs / "cone.npz"), "--out", str(tmp_path / "e.toml"), "--figure", str(tmp_path / "e.png"), "--json", "--quiet"]
    outcome = run(argv, timeout=120.0)
    assert outcome.code == 0, outcome.err
    data = json.loads(outcome.out)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["e.png", "e.toml"]
    assert data["lines"] and data["nyquist_hz"] == pytest.approx(500.0)
    outcome = run(["log", "allan", str(logs / "cone.npz"), "--out", str(tmp_path / "imu.toml"), "--json", "--quiet"], timeout=120.0)
    assert outcome.code == 0, outcome.err
    assert np.isfinite(json.loads(outcome.out)["gyro"]["arw_deg_per_rt_h"])
