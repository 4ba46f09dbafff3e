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

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"
MODULES = ("scaling", "peers", "probes", "report", "timing")


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
    r = peers.vs_reference(20, 0.3, seconds=0.05, seed=1)
    assert r["reference_collisions"] >= 1
    assert r["ratio"] > 0
