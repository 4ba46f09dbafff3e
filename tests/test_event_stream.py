"""The event stream: every processed event delivered, in order, without loss, with
its impulse; no effect on the run; nothing to pay when no one listens."""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of


def gas():
    base = ed.make_gas(300, 0.4, periodic=(True, False), seed=seed_of(6))
    return ed.Simulation(base.positions, base.velocities, base.radii, box=base.box,
                         thermostat=(1.0, 0.05), seed=seed_of(2))


def test_every_event_is_streamed_in_order_in_small_batches():
    sim = gas()
    batches = []
    sim.stream_events(batches.append, capacity=37)
    sim.advance(until=10.0)
    sim.advance(collisions=500)
    events = np.concatenate(batches)
    assert max(len(b) for b in batches) <= 37 and len(batches) > 10
    assert (np.diff(events["time"]) >= 0).all()
    kinds = events["kind"].tolist()
    c = sim.counts
    assert kinds.count("disk") == c.collisions
    assert kinds.count("box") == c.wall_collisions
    assert kinds.count("thermostat") == c.redraws > 0
    assert events["time"][-1] <= sim.time
    # The impulses of the box walls add up to the walls' tallies.
    box = events[events["kind"] == "box"]
    for side in (2, 3):
        assert box["impulse"][box["partner"] == side].sum() == pytest.approx(
            sim._accumulators()["box_impulse"][side], rel=1e-12)


def test_impulses_of_a_head_on_collision_and_a_wall_bounce():
    box = ed.Box(10.0, 10.0, periodic=False)
    sim = ed.Simulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]], 1.0,
                        masses=[2.0, 2.0], box=box)
    batches = []
    sim.stream_events(batches.append)
    sim.advance(until=3.0)
    events = np.concatenate(batches)
    assert events[0]["kind"] == "disk" and events[0]["impulse"] == pytest.approx(4.0)
    assert events[1]["kind"] == "box" and events[1]["impulse"] == pytest.approx(4.0)


def test_the_stream_changes_nothing_and_stops():
    plain, streamed = gas(), gas()
    seen = []
    streamed.stream_events(seen.append, capacity=5)
    plain.advance(until=8.0)
    streamed.advance(until=8.0)
    assert np.array_equal(plain.positions, streamed.positions)
    assert plain.counts == streamed.counts
    streamed.stream_events(None)
    n = sum(len(b) for b in seen)
    streamed.advance(until=10.0)
    assert sum(len(b) for b in seen) == n


def test_copies_and_pickles_do_not_stream():
    sim = gas()
    seen = []
    sim.stream_events(seen.append)
    sim.advance(until=2.0)
    for other in (copy.deepcopy(sim), pickle.loads(pickle.dumps(sim))):
        before = sum(len(b) for b in seen)
        other.advance(until=4.0)
        assert sum(len(b) for b in seen) == before


def test_a_callback_that_fails_stops_the_run_with_its_error():
    sim = gas()

    def fail(batch):
        raise RuntimeError("disk full")

    sim.stream_events(fail, capacity=10)
    with pytest.raises(RuntimeError, match="disk full"):
        sim.advance(until=5.0)
    sim.stream_events(None)
    sim.advance(until=6.0)  # (the state is consistent: the run goes on)


def test_bad_stream_arguments():
    sim = gas()
    with pytest.raises(TypeError, match="callable"):
        sim.stream_events("log.txt")
    with pytest.raises(ValueError, match="capacity"):
        sim.stream_events(print, capacity=0)


def test_events_written_to_a_file_read_back_exactly(tmp_path):
    from edmd2d.io.events import EventWriter, read

    sim = gas()
    batches = []
    path = tmp_path / "events.csv"
    with EventWriter(path) as out:
        sim.stream_events(lambda b: (batches.append(b), out(b)), capacity=64)
        sim.advance(until=5.0)
        sim.stream_events(None)
    events = read(path)
    assert np.array_equal(events, np.concatenate(batches))
    (tmp_path / "other.csv").write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match="not an edmd2d event file"):
        read(tmp_path / "other.csv")


def row_and_faller(n=5):
    """``n`` inelastic disks side by side just above the floor, which come to rest at
    once, and one more falling onto them from high above (it wakes the row)."""
    x = 1.0 + np.arange(n) * 1.0005
    pos = np.vstack([np.column_stack([x, np.full(n, 0.5001)]), [x[n // 2] + 0.2, 15.0]])
    return ed.Simulation(pos, np.zeros((n + 1, 2)), 0.5,
                         box=ed.Box(n + 2.0, 20.0, periodic=False), restitution=0.9,
                         wall_restitution=0.9, gravity=(0.0, -1.0))


def replay(events, n):
    """Each disk's state (at rest or not) after ``events``, checking that only a disk
    in flight comes to rest and only one at rest wakes."""
    at_rest = np.zeros(n, bool)
    for e in events:
        if e["kind"] in ("rest", "wake"):
            assert at_rest[e["disk"]] == (e["kind"] == "wake"), e
            assert e["partner"] == -1 and e["impulse"] >= 0.0
            at_rest[e["disk"]] = e["kind"] == "rest"
    return at_rest


def test_rests_and_wakes_are_streamed_as_events_in_batches_that_keep_the_capacity():
    sim = row_and_faller()
    batches = []
    sim.stream_events(batches.append, capacity=3)
    sim.advance(until=4.0)  # the row at rest; the sixth disk still falling
    events = np.concatenate(batches)
    assert (replay(events, len(sim)) == sim.resting).all() and sim.resting.sum() == 5
    sim.advance(until=200.0)  # it lands, wakes the row, and all settle again
    events = np.concatenate(batches)
    assert max(len(b) for b in batches) <= 3
    assert (np.diff(events["time"]) >= 0.0).all()
    kinds = events["kind"].tolist()
    assert kinds.count("rest") == sim.counts.rests and kinds.count("wake") == sim.counts.wakes
    assert sim.counts.wakes >= 1
    assert kinds.count("disk") == sim.counts.collisions
    assert (replay(events, len(sim)) == sim.resting).all() and sim.resting.all()
    # The first wake comes at the impact that causes it, just before that collision.
    first = kinds.index("wake")
    after = events[first:][events["kind"][first:] != "wake"][0]
    assert after["kind"] == "disk" and after["time"] == events[first]["time"]
    assert 5 in (after["disk"], after["partner"])
    # A disk at rest regains the momentum it came to rest with.
    done = len(events)
    sim.set_velocities(np.zeros((len(sim), 2)))  # (handed over at once)
    woken = np.concatenate(batches)[done:]
    assert woken["kind"].tolist() == ["wake"] * 6
    assert (woken["time"] == sim.time).all()
    assert sorted(woken["disk"].tolist()) == list(range(6))


def test_streaming_rests_and_wakes_leaves_the_run_unchanged():
    plain, streamed = row_and_faller(), row_and_faller()
    streamed.stream_events(lambda batch: None, capacity=2)
    for sim in (plain, streamed):
        sim.advance(until=200.0)
    assert (plain.positions == streamed.positions).all()
    assert plain.counts == streamed.counts


def test_a_callback_that_stops_the_stream_gets_the_rest_of_what_was_logged():
    sim = row_and_faller()
    sim.advance(until=4.0)  # five disks at rest
    seen = []

    def stop_at_first(batch):
        seen.append(batch)
        if len(seen) == 1:
            sim.stream_events(None)

    sim.stream_events(stop_at_first, capacity=3)
    sim.set_velocities(np.zeros((len(sim), 2)))  # wakes five disks: two batches
    kinds = np.concatenate(seen)["kind"].tolist()
    assert kinds == ["wake"] * 5 and [len(b) for b in seen] == [3, 2]


def test_wakes_made_from_python_are_handed_over_once_the_disks_are_awake():
    sim = row_and_faller()
    sim.advance(until=4.0)
    at_rest_when_seen = []
    sim.stream_events(lambda batch: at_rest_when_seen.append(int(sim.resting.sum())))
    sim.set_velocities(np.zeros((len(sim), 2)))
    assert at_rest_when_seen == [0]


def test_the_impulse_of_a_collision_that_ends_at_rest_is_the_collision_s_own():
    # A disk dropped 0.5 above a row of five at rest (wall to wall) bounces in a groove
    # of the row and comes to rest there after a collision, the row untouched: each
    # collision (alone in a run to the next) is logged with m |v_after - v_before|,
    # v_before from its parabola since the stop before, v_after as the collision left
    # it (the velocity it came to rest with, for the last).
    x = 0.5001 + np.arange(5) * 1.0005
    pos = np.vstack([np.column_stack([x, np.full(5, 0.5001)]), [x[2] + 0.3, 2.0]])
    sim = ed.Simulation(pos, np.zeros((6, 2)), 0.5,
                        box=ed.Box(x[-1] + 0.5006, 6.0, periodic=False), restitution=0.9,
                        wall_restitution=0.9, gravity=(0.0, -1.0))
    sim.advance(until=0.5)
    assert sim.resting[:5].all()
    batches = []
    sim.stream_events(batches.append)
    checked = rested = 0
    while not sim.resting.all():
        t0, v0 = sim.time, sim.velocities[5].copy()
        done = sum(len(b) for b in batches)
        sim.advance(until=t0 + 50.0, collisions=1)
        new = np.concatenate(batches)[done:] if batches else []
        if len(new) == 0 or new[0]["kind"] == "rest":
            break  # (at rest with the row as a group, between two collisions)
        moves = new[new["kind"] != "rest"]
        assert (moves["disk"] == 5).all()
        if len(moves) > 1:
            continue  # (wall contacts before the collision: its velocity before unknown)
        event = moves[0]
        before = v0 + np.array([0.0, -1.0]) * (event["time"] - t0)
        if sim.resting[5]:
            assert new[1]["kind"] == "rest" and new[1]["disk"] == 5
            row = int(np.flatnonzero(sim._state.order == 5)[0])
            after = sim._state.rest_frozen[row]
            rested += 1
        else:
            after = sim.velocities[5]
        assert event["impulse"] == pytest.approx(np.hypot(*(after - before)), rel=1e-9)
        checked += 1
    assert sim.resting.all() and rested == 1 and checked > 3 and sim.counts.wakes == 0
