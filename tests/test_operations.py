"""Operations with triggers: several things driven by one run, at exact times."""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed
from edmd2d import operations as op


def test_time_triggers_fire_at_exact_times_and_change_nothing():
    sim = ed.make_gas(300, 0.4, seed=2)
    plain = ed.make_gas(300, 0.4, seed=2)
    seen = []
    op.run(sim, until=3.0, operations=[
        op.Callback(lambda s: seen.append(("dt", s.time)), op.Every(dt=0.75)),
        op.Callback(lambda s: seen.append(("at", s.time)), op.At([0.1, 2.0, 9.0])),
    ])
    assert seen == [("at", 0.1), ("dt", 0.75), ("dt", 1.5), ("at", 2.0), ("dt", 2.25),
                    ("dt", 3.0)]
    plain.advance(until=3.0)
    assert np.array_equal(sim.positions, plain.positions)
    assert sim.counts == plain.counts


def test_collision_triggers_fire_after_every_kth_collision():
    sim = ed.make_gas(300, 0.4, seed=2)
    counts = []
    op.run(sim, collisions=1000, operations=[
        op.Callback(lambda s: counts.append(s.counts.collisions), op.Every(collisions=250))])
    assert counts == [250, 500, 750, 1000]


def test_a_gsd_trajectory_and_checkpoints_from_one_run(tmp_path):
    gsd = pytest.importorskip("gsd.hoomd")
    sim = ed.make_gas(200, 0.3, seed=4)
    op.run(sim, until=4.0, operations=[
        op.WriteGSD(tmp_path / "run.gsd", op.Every(dt=1.0)),
        op.Checkpoint(tmp_path / "run.ckpt", op.At([2.0])),
    ])
    with gsd.open(str(tmp_path / "run.gsd"), "r") as traj:
        assert [float(f.log["edmd2d/time"][0]) for f in traj] == [1.0, 2.0, 3.0, 4.0]
    resumed = ed.checkpoint.load(tmp_path / "run.ckpt")
    assert resumed.time == 2.0
    assert np.array_equal(resumed.advance(until=4.0).positions, sim.positions)


def test_wall_clock_triggers_fire_between_slices(monkeypatch):
    clock = iter(np.arange(0.0, 1e6, 1.0))  # (one "second" per stop)
    monkeypatch.setattr(op._time, "monotonic", lambda: float(next(clock)))
    monkeypatch.setattr(op, "WALL_CLOCK_SLICE", 100)
    sim = ed.make_gas(200, 0.4, seed=1)
    fired = []
    op.run(sim, collisions=1000, operations=[
        op.Callback(lambda s: fired.append(s.counts.collisions), op.Every(seconds=2.0))])
    assert fired and fired == sorted(fired) and fired[-1] <= 1000
    assert len(fired) >= 4


@pytest.mark.parametrize("make, error, match", [
    (lambda: op.Every(), TypeError, "exactly one of"),
    (lambda: op.Every(dt=1.0, collisions=5), TypeError, "exactly one of"),
    (lambda: op.Every(dt=-1.0), ValueError, "dt"),
    (lambda: op.Every(collisions=0), ValueError, "collisions"),
    (lambda: op.Callback(print, "every second"), TypeError, "Trigger"),
    (lambda: op.Callback("print", op.Every(dt=1.0)), TypeError, "callable"),
    (lambda: op.run(ed.make_gas(20, 0.2, seed=1), until=1.0, operations=[print]),
     TypeError, r"operations\[0\]"),
    (lambda: op.run(ed.make_gas(20, 0.2, seed=1)), TypeError, "until="),
])
def test_bad_operations_are_refused(make, error, match):
    with pytest.raises(error, match=match):
        make()
