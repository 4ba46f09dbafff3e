"""The benchmark suite of benchmarks/ runs end to end on a tiny system.

Only that it runs and writes its files is checked: speeds are measured by the suite
itself, never asserted in tests.
"""

from __future__ import annotations

import importlib
import json
import sys
from pathlib import Path

import pytest

from conftest import seed_of

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"
MODULES = ("scaling", "peers", "probes", "report", "timing", "ab")


@pytest.fixture
def bench_modules(monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.syspath_prepend(str(BENCH))
    yield
    for name in MODULES:  # do not leak the script's flat module names
        sys.modules.pop(name, None)


def test_scaling_suite_runs(bench_modules, tmp_path):
    scaling = importlib.import_module("scaling")
    rc = scaling.main(["--sizes", "100", "--packings", "0.5", "--repeats", "2",
                       "--seconds", "0.01", "--equilibrate", "1", "--no-peers",
                       "--no-memory", "--no-compile", "--out", str(tmp_path),
                       "--tag", "smoke"])
    assert rc == 0
    data = json.loads((tmp_path / "scaling-smoke.json").read_text())
    (point,) = data["scaling"]
    assert (point["n"], point["packing"]) == (100, 0.5)
    assert len(point["runs"]) == 2
    assert point["collisions_per_s"]["median"] > 0
    assert point["engine_array_bytes_per_disk"] > 0
    assert (tmp_path / "scaling-smoke.png").stat().st_size > 0
    assert "collisions/s" in (tmp_path / "scaling-smoke.md").read_text()


def test_reference_comparison_runs(bench_modules):
    peers = importlib.import_module("peers")
    r = peers.vs_reference(20, 0.3, seconds=0.05, seed=seed_of(1))
    assert r["reference_collisions"] >= 1
    assert r["ratio"] > 0


def test_ab_summary_pairs_the_sizes_of_each_round(bench_modules):
    # The slowdown between sizes is taken round by round: a machine that drifts 2x
    # between rounds must not show up in it.
    ab = importlib.import_module("ab")
    maxima = {"main": {10: [2.0e6, 1.0e6, 1.6e6], 1000: [1.0e6, 0.5e6, 0.4e6]}}
    lines = ab.summarize(maxima, [10, 1000])
    assert "median 1.600  range 1.000-2.000" in lines[0]
    assert "median 0.500  range 0.400-1.000" in lines[1]
    # per round: 2.0, 2.0, 4.0
    assert lines[2].endswith("median 2.00  range 2.00-4.00")
    with pytest.raises(SystemExit):
        ab.main(["--n", "100,100", "HEAD"])
    with pytest.raises(SystemExit):
        ab.main(["--n", "100,200", "--k", "1,2,3", "HEAD"])
