"""Operations with triggers: several things driven by one run, at exact times."""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import _operations
from edmd2d import operations as op


def test_time_triggers_fire_at_exact_times_and_change_nothing():
    sim = ed.make_gas(300, 0.4, seed=seed_of(2))
    plain = ed.make_gas(300, 0.4, seed=seed_of(2))
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
    sim = ed.make_gas(300, 0.4, seed=seed_of(2))
    counts = []
    op.run(sim, collisions=1000, operations=[
        op.Callback(lambda s: counts.append(s.counts.collisions), op.Every(collisions=250))])
    assert counts == [250, 500, 750, 1000]


def test_a_gsd_trajectory_and_checkpoints_from_one_run(tmp_path):
    gsd = pytest.importorskip("gsd.hoomd")
    sim = ed.make_gas(200, 0.3, seed=seed_of(4))
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
    monkeypatch.setattr(_operations._time, "monotonic", lambda: float(next(clock)))
    monkeypatch.setattr(_operations, "WALL_CLOCK_SLICE", 100)
    sim = ed.make_gas(200, 0.4, seed=seed_of(1))
    fired = []
    op.run(sim, collisions=1000, operations=[
        op.Callback(lambda s: fired.append(s.counts.collisions), op.Every(seconds=2.0))])
    assert fired and fired == sorted(fired) and fired[-1] <= 1000
    assert len(fired) >= 4


@pytest.mark.parametrize("make, error, match", [
    (op.Every, TypeError, "exactly one of"),
    (lambda: op.Every(dt=1.0, collisions=5), TypeError, "exactly one of"),
    (lambda: op.Every(dt=-1.0), ValueError, "dt"),
    (lambda: op.Every(collisions=0), ValueError, "collisions"),
    (lambda: op.Callback(print, "every second"), TypeError, "Trigger"),
    (lambda: op.Callback("print", op.Every(dt=1.0)), TypeError, "callable"),
    (lambda: op.run(ed.make_gas(20, 0.2, seed=seed_of(1)), until=1.0, operations=[print]),
     TypeError, r"operations\[0\]"),
    (lambda: op.run(ed.make_gas(20, 0.2, seed=seed_of(1))), TypeError, "until="),
])
def test_bad_operations_are_refused(make, error, match):
    with pytest.raises(error, match=match):
        make()


# ----------------------------------------------------------------- measure, record, frames
def _same_measurement(a, b):
    """Two Measurements equal field by field, bit for bit (NaN equal to NaN)."""
    import dataclasses

    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, (float, np.ndarray, tuple)):
            assert np.array_equal(np.asarray(x), np.asarray(y), equal_nan=True), f.name
        else:
            assert x == y, f.name


def test_measure_record_and_gsd_in_one_run_equal_separate_runs(tmp_path):
    gsd = pytest.importorskip("gsd.hoomd")
    combined = ed.make_gas(300, 0.35, seed=seed_of(7))
    window = op.Measure(op.Blocks(duration=3.0, blocks=6))
    path = op.RecordTrajectory(op.Every(dt=0.5), include_start=True)
    combined.run(until=3.0, operations=[
        window, path, op.WriteGSD(tmp_path / "one.gsd", op.Every(dt=0.75))])

    _same_measurement(window.result(),
                      ed.make_gas(300, 0.35, seed=seed_of(7)).measure(3.0, blocks=6))
    times, positions = ed.trajectory(ed.make_gas(300, 0.35, seed=seed_of(7)), 0.5, 7)
    assert np.array_equal(path.times, times)
    assert np.array_equal(path.positions, positions)
    alone = ed.make_gas(300, 0.35, seed=seed_of(7))
    from edmd2d.io import gsd as edgsd

    edgsd.record(alone, tmp_path / "alone.gsd", [0.75, 1.5, 2.25, 3.0])
    with gsd.open(str(tmp_path / "one.gsd")) as a, gsd.open(str(tmp_path / "alone.gsd")) as b:
        assert len(a) == len(b) == 4
        for fa, fb in zip(a, b):
            assert np.array_equal(fa.particles.position, fb.particles.position)
            assert np.array_equal(fa.particles.velocity, fb.particles.velocity)
            assert fa.log.keys() == fb.log.keys()
            for key in fa.log:
                assert np.array_equal(fa.log[key], fb.log[key], equal_nan=True), key
    assert np.array_equal(combined.positions, alone.positions)
    assert combined.counts == alone.counts


def test_a_measure_goes_on_over_runs_and_through_a_checkpoint(tmp_path):
    reference = ed.make_gas(200, 0.3, seed=seed_of(3)).measure(4.0, blocks=4)
    twice = ed.make_gas(200, 0.3, seed=seed_of(3))
    window = op.Measure(op.Blocks(4.0, 4))
    twice.run(until=1.5, operations=[window])
    assert window.blocks == 1 and window.result().duration == 1.0
    twice.run(until=4.0, operations=[window])
    _same_measurement(window.result(), reference)

    first = ed.make_gas(200, 0.3, seed=seed_of(3))
    window = op.Measure(op.Blocks(4.0, 4))
    first.run(until=2.5, operations=[window, op.Checkpoint(
        tmp_path / "c.ckpt", op.At([2.5]), metadata=lambda s: {"m": window.state()})])
    later = ed.checkpoint.load(tmp_path / "c.ckpt")
    again = op.Measure.from_state(ed.checkpoint.read_metadata(tmp_path / "c.ckpt")["m"])
    _same_measurement(again.result(), window.result())  # (two blocks, read back exactly)
    later.run(until=4.0, operations=[again])
    _same_measurement(again.result(), reference)


def test_a_window_that_starts_later_and_other_triggers():
    sim = ed.make_gas(200, 0.3, seed=seed_of(5))
    window = op.Measure(op.Blocks(3.0, 3, start=1.0))
    seen = []
    sim.run(until=4.0, operations=[window, op.Callback(lambda s: seen.append(window.blocks),
                                                       op.Blocks(3.0, 3, start=1.0))])
    assert seen == [0, 1, 2, 3]  # (the window opens at 1.0, then a block each)
    plain = ed.make_gas(200, 0.3, seed=seed_of(5)).advance(until=1.0)
    _same_measurement(window.result(), plain.measure(3.0, blocks=3))

    by_dt = op.Measure(op.Every(dt=0.5))
    ed.make_gas(200, 0.3, seed=seed_of(5)).run(until=2.0, operations=[by_dt])
    m = by_dt.result()
    assert m.blocks == 4 and m.duration == 2.0 and np.isfinite(m.pressure_error)
    assert m.collisions == ed.make_gas(200, 0.3, seed=seed_of(5)).measure(2.0, blocks=4).collisions
    with pytest.raises(ValueError, match="no block"):
        op.Measure(op.Every(dt=1.0)).result()
    late = ed.make_gas(50, 0.3, seed=seed_of(1)).advance(until=2.0)
    with pytest.raises(ValueError, match="before the run's start"):
        late.run(until=3.0, operations=[op.Measure(op.Blocks(2.0, 2, start=1.0))])


def test_every_with_a_start_keeps_the_grid_of_times():
    sim = ed.make_gas(50, 0.3, seed=seed_of(1)).advance(until=1.3)
    seen = []
    sim.run(until=2.5, operations=[
        op.Callback(lambda s: seen.append(s.time), op.Every(dt=0.5, start=0.0))])
    assert seen == [1.5, 2.0, 2.5]
    with pytest.raises(TypeError, match="goes with dt"):
        op.Every(collisions=3, start=0.0)


def test_recorded_frames_animate_as_the_live_animation():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from edmd2d import viz

    live = viz.animate(ed.make_gas(60, 0.3, seed=seed_of(1)), duration=1.0, fps=5, trail=3)
    frames = op.RecordFrames(op.At(live.frame_times[1:]))
    ed.make_gas(60, 0.3, seed=seed_of(1)).run(until=float(live.frame_times[-1]),
                                              operations=[frames])
    replay = viz.animate_frames(frames, fps=5, trail=3)
    assert np.array_equal(replay.frame_times, live.frame_times)

    def picture(artists):
        out = []
        for a in artists:
            if a.get_gid() == "edmd2d-disks":
                out.append(a.get_offsets().copy())
            elif a.get_gid() == "edmd2d-trails":
                out.extend(np.array(s, copy=True) for s in a.get_segments())
            else:
                out.append(a.get_text())
        return out

    shown = [picture(live.goto_frame(k)) for k in range(len(live.frame_times))]
    for _ in range(2):  # (recorded frames play again, trails and all)
        for k, expected in enumerate(shown):
            got = picture(replay.goto_frame(k))
            assert len(got) == len(expected)
            for a, b in zip(expected, got):
                assert (a == b) if isinstance(a, str) else np.array_equal(a, b, equal_nan=True)
    with pytest.raises(ValueError, match="at least one frame"):
        viz.animate_frames([])
    plt.close("all")
