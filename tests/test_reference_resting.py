"""Disks at rest: the brute-force reference against closed-form results and the engine.

The reference's rules for disks at rest (``edmd2d/reference/_resting.py``) are written
apart from the engine's; here a bounce to rest is checked against its closed form, and
small systems that settle, are hit and settle again are run in both, event for event.

Why the comparisons stop where they do.  A threshold decides by the last bits of a
quantity within rounding of it, and two arithmetics may then branch apart, both right;
the reference notes every such close call (``close_calls``), and no comparison runs
past one.  And disks that settle together meet in quick runs of contacts (a disk
sinking between two others, a pile shifting), each of which multiplies a difference of
rounding: two exact engines part ways in the end.  Each random system below is
compared up to a time before that: over each window the largest difference of event
times measured is 1e-11, a hundred times below the tolerance of 1e-9.
"""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed
from conftest import random_system, segment_distance
from edmd2d.physics import Resting
from edmd2d.reference import ReferenceSimulation

MODEL = dict(restitution=0.6, wall_restitution=0.5)


def _canonical(events):
    """Pairs unordered; the rests (wakes) of one instant in the order of their disks:
    the engine logs a pair from the disk whose prediction fired, and a cascade or a
    group in the order it finds them."""
    out = [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
           for t, k, i, j in events]
    result = []
    k = 0
    while k < len(out):
        m = k + 1
        if out[k][1] in ("rest", "wake"):
            while m < len(out) and out[m][1] == out[k][1] and out[m][0] == out[k][0]:
                m += 1
        result.extend(sorted(out[k:m], key=lambda e: e[2]))
        k = m
    return result


def _pair(pos, vel, rad, mass, box, walls, grid="auto"):
    """The engine (on the grid ``grid``) and the reference on one system, the
    reference with the engine's criteria of rest and its TC model's ``tc``."""
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, gravity=(0.0, -1.0),
                        grid=grid, **MODEL)
    sim._record_events(100_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls,
                              gravity=(0.0, -1.0), resting=sim._state.families["resting"],
                              tc=float(sim._state.model.tc), **MODEL)
    return sim, ref


def _assert_same_run(sim, ref):
    """The same events (times to 1e-9), state, rests, wakes and dissipated energy, and
    no close call in the reference; returns the events."""
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0,
                               atol=1e-9)
    assert ref.close_calls == []
    np.testing.assert_allclose(sim.positions, ref.positions, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-9)
    np.testing.assert_array_equal(sim.resting, ref.at_rest)
    assert sim.counts.rests == ref.rests
    assert sim.counts.wakes == ref.wakes
    assert sim.dissipated_energy() == pytest.approx(ref.dissipated, rel=1e-9, abs=1e-12)
    return got


def _compare_before_the_first_close_call(system, t_max):
    """Run the reference on ``system`` (positions, velocities, radii, masses, box,
    walls) to ``t_max`` or its first close call; then the engine and a fresh reference
    to just before it (halfway from the event before), and compare them there.
    Returns the events compared."""
    _, probe = _pair(*system)
    probe.advance(until=t_max)
    t_stop = t_max
    if probe.close_calls:
        t_close = probe.close_calls[0][0]
        before = [e[0] for e in probe.events if e[0] < t_close]
        t_stop = 0.5 * ((before[-1] if before else 0.0) + t_close)
    sim, ref = _pair(*system)
    sim.advance(until=t_stop)
    ref.advance(until=t_stop)
    return _assert_same_run(sim, ref)


def test_a_bounce_to_rest_on_the_floor_in_closed_form():
    # Dropped from h = 2 above the floor (g = 1, e_w = 1/2): impacts at speed
    # v_k = 2^-k v_0, v_0 = 2, at t_0 = 2 and t_(k+1) = t_k + 2 v_(k+1) / g.  The
    # rebound e v_k first falls below the rest speed sqrt(2 g h_r) = sqrt(2e-3) at the
    # sixth impact (1/32 < 0.0447 < 1/16): the disk slides, with no speed left, on a flat
    # floor that holds it, and comes to rest there, at t_5 = 2 + 4 (1 - 2^-5) = 5.875.
    rest = Resting.of(1e-3, 1.0, 0.5)
    ref = ReferenceSimulation([[3.0, 2.5]], [[0.0, 0.0]], radii=0.5,
                              box=ed.Box(6.0, 6.0, periodic=False), gravity=(0.0, -1.0),
                              wall_restitution=0.5, resting=rest)
    ref.advance(until=10.0)
    times = [2.0 + 4.0 * (1.0 - 0.5 ** k) for k in range(6)]
    assert [e[1:] for e in ref.events] == [("box", 0, 2)] * 6 + [("rest", 0, -1)]
    np.testing.assert_allclose([e[0] for e in ref.events], times + [times[-1]], rtol=1e-13)
    assert ref.at_rest == [True] and ref.rests == 1
    assert ref.positions[0, 1] == pytest.approx(0.5, abs=1e-12)
    # All its potential energy m g h = 2 is dissipated; at rest it has no velocity.
    assert ref.dissipated == pytest.approx(2.0, rel=1e-12)
    assert ref.velocities.tolist() == [[0.0, 0.0]]


def test_a_disk_on_one_support_is_not_held_but_on_two_it_is():
    # Two disks settle on the floor (from 5e-4 above it) in the corners of a box 2.2
    # wide, 0.2 apart.  A third, dropped into the groove between them, meets both at one
    # instant and rests there, on both: the impact pushes each into the corner of the
    # floor and its side wall, which takes it, so they stay at rest.  Dropped onto the
    # top of one of them, a little off its centre, it does not rest there (one support
    # does not hold it without friction): it rolls off into the groove and rests there.
    rest = Resting.of(1e-3, 1.0, 0.5)
    box = ed.Box(2.2, 6.0, periodic=False)

    def dropped(x):
        ref = ReferenceSimulation([[0.5, 0.5005], [1.7, 0.5005], [x, 2.0]],
                                  [[0.0, 0.0]] * 3, radii=0.5, box=box,
                                  gravity=(0.0, -1.0), restitution=0.5,
                                  wall_restitution=0.5, resting=rest)
        return ref.advance(until=30.0)

    for x in (1.1, 1.69):
        ref = dropped(x)
        assert ref.at_rest == [True, True, True]
        assert sorted(ref.supports[2][:2]) == [0, 1]
        assert ref.positions[2].tolist() == pytest.approx([1.1, 0.5 + 0.8], abs=1e-3)
        assert [e[1] for e in ref.events].count("wake") == 0
        # (From 1.69 it bounces on the top of disk 1 before it rolls off.)
        hits = [e for e in ref.events if e[1] == "disk"]
        assert len(hits) >= (2 if x == 1.1 else 3)





def _walls(kind, box):
    w, h = box.width, box.height
    if kind == "divider":
        return [ed.Wall((0.5 * w, 0.25 * h), (0.5 * w, 0.75 * h))]
    if kind == "polygon":
        return ed.Wall.polygon([(0.2 * w, 0.2 * h), (0.45 * w, 0.25 * h),
                                (0.3 * w, 0.45 * h)]) + [
            ed.Wall((0.6 * w, 0.9 * h), (0.95 * w, 0.6 * h))]
    return []


SETTLING = [(0, "none", 9.12), (1, "none", 5.275), (3, "none", 5.94), (4, "none", 15.0),
            (6, "none", 6.68), (7, "none", 8.52), (0, "divider", 7.2), (2, "divider", 9.85),
            (4, "polygon", 6.68), (7, "polygon", 7.308)]


@pytest.mark.parametrize("seed, walls_kind, t_end", SETTLING)
def test_random_systems_settle_as_in_the_reference(seed, walls_kind, t_end):
    """Eight disks of mixed sizes fall into a walled box (with a wall segment with a
    gap, or a triangle and a slanted segment): they come to rest on the floor, on
    walls and on each other, are hit and woken, and settle again (6 to 16 rests and 5
    to 12 wakes in each window)."""
    rng = np.random.default_rng(seed)
    box = ed.Box(rng.uniform(4.0, 7.0), rng.uniform(4.0, 7.0), periodic=False)
    walls = _walls(walls_kind, box)
    pos, vel, rad, mass = random_system(rng, 8, box, walls)
    sim, ref = _pair(pos, vel, rad, mass, box, walls)
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    events = _assert_same_run(sim, ref)
    assert sum(e[1] == "rest" for e in events) >= 5
    assert sum(e[1] == "wake" for e in events) >= 4


def test_a_settled_bed_hit_from_above_wakes_and_settles_again():
    """Four disks fall to the floor and settle; a fifth, released at height 17, lands
    among them at t ~ 5.6 at a speed of 4, far above the speed that wakes a disk, and
    they settle again.  The comparison runs to the reference's first close call (a disk
    meeting another side by side on the floor, their normal level to rounding: whether
    gravity presses them together), at t = 10.46."""
    pos = [[1.2, 0.9], [2.4, 1.3], [3.9, 0.7], [4.5, 2.2], [2.0, 17.0]]
    vel = [[0.3, 0.0], [-0.2, 0.1], [0.0, 0.4], [-0.5, 0.0], [0.0, 0.0]]
    system = (pos, vel, 0.5, 1.0, ed.Box(6.0, 18.0, periodic=False), [])
    events = _compare_before_the_first_close_call(system, 20.0)
    before = [e for e in events if e[0] < 5.5]
    after = [e for e in events if e[0] > 5.5]
    assert any(e[1] == "rest" for e in before)
    assert any(e[1] == "wake" for e in after) and any(e[1] == "rest" for e in after)


@pytest.mark.parametrize("angle", [0.05, np.pi / 3])
def test_a_slow_disk_leaves_a_static_body_at_the_soft_speed_times_the_pressing_share(angle):
    # A disk drops from rest onto the end point of a wall segment, meeting it at the
    # angle ``a`` above the level (normal n = (cos a, sin a)) at the speed v = sqrt(2
    # dy) = 0.0028, below the soft speed (0.0045): the impact is elastic, and the disk
    # would leave at v sin a along n.  Gravity presses that contact by the share sin a
    # of itself, so the disk leaves at soft sin a along n instead, keeping its
    # tangential velocity -v cos a: v' = (sin a cos a (soft + v), soft sin^2 a - v
    # cos^2 a).  At a = 0.05 the full soft speed would throw it sideways at 0.0046
    # instead of 0.00036.
    r, dy = 0.5, 4e-6
    end = np.array([3.0, 2.0])
    start = end + r * np.array([np.cos(angle), np.sin(angle)]) + [0.0, dy]
    system = dict(box=ed.Box(8.0, 4.0, periodic=False), walls=[ed.Wall((1.0, 2.0), tuple(end))],
                  gravity=(0.0, -1.0), **MODEL)
    sim = ed.Simulation([start], [[0.0, 0.0]], r, **system)
    sim._record_events(100)
    rest = sim._state.families["resting"]
    ref = ReferenceSimulation([start], [[0.0, 0.0]], r, resting=rest,
                              tc=float(sim._state.model.tc), **system)
    t_end = 0.004  # (the contact at t = sqrt(2 dy) = 0.00283, the next far later)
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    v = np.sqrt(2.0 * dy)
    s, c = np.sin(angle), np.cos(angle)
    after = [s * c * (rest.soft + v), rest.soft * s * s - v * c * c - (t_end - v)]
    for run in (sim, ref):
        events = run._recorded_events() if run is sim else run.events
        assert [e[1:] for e in events] == [("wall", 0, 0)]
        assert events[0][0] == pytest.approx(v, rel=1e-9)
        np.testing.assert_allclose(run.velocities[0], after, rtol=1e-9, atol=1e-15)


# ---------------------------------------------------------------- on the wide grid
def _with_a_wide_disk(seed):
    """Ten disks of radii 0.3-0.4 in a box 6-9 wide (periodic along x for odd seeds,
    a slanted segment for every third), one of them made 1.0 in radius where that
    fits: on the wide grid it is listed in the cells of its footprint."""
    rng = np.random.default_rng(1000 + seed)
    box = ed.Box(rng.uniform(6.0, 9.0), rng.uniform(5.0, 8.0),
                 periodic=(bool(seed % 2), False))
    walls = [] if seed % 3 else [ed.Wall((0.5 * box.width, 0.3 * box.height),
                                         (0.7 * box.width, 0.45 * box.height))]
    pos, vel, rad, mass = random_system(rng, 10, box, walls, rmin=0.3, rmax=0.4)
    for k, p in enumerate(pos):
        gaps = np.hypot(*(pos - p).T) - rad - 1.0
        gaps[k] = 1.0
        inside = 1.0 < p[1] < box.height - 1.0 and (box.periodic[0]
                                                   or 1.0 < p[0] < box.width - 1.0)
        if (gaps > 0).all() and inside and all(segment_distance(p, w) > 1.0
                                               for w in walls):
            rad[k] = 1.0
            return (pos, vel, rad, mass, box, walls), k
    raise AssertionError("no room for the wide disk")


@pytest.mark.parametrize("seed, t_end", [(1, 10.0), (8, 4.49), (9, 4.5), (32, 7.78)])
def test_disks_settle_on_a_wide_disk_as_in_the_reference(seed, t_end):
    """With a disk 2.5-3.3 times wider than the others listed in its footprint, the engine
    settles, wakes and settles again as the reference does (1 to 16 rests and up to 12 wakes
    in each window), and the wide disk comes to rest itself.  (Each window ends before the
    runs part ways by rounding, which the two grids do at the same events: the largest
    difference of event times measured in them is 3e-11.)"""
    system, wide = _with_a_wide_disk(seed)
    sim, ref = _pair(*system, grid="wide")
    assert sim._state.wide is not None and sim._state.wide.index[wide] >= 0
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    events = _assert_same_run(sim, ref)
    assert any(e[1] == "rest" and e[2] == wide for e in events)


def test_a_wide_disk_woken_wakes_the_disk_it_holds():
    """A disk 1.5 in radius rests on the floor, 0.7 from the left wall; a disk 0.4 in
    radius rests in the pocket between them, held by both.  A third, sliding along
    the floor at speed 3, hits the wide disk (far above the speed that wakes it), and
    the small one, its support gone, wakes with it at that instant; both settle
    again.  On the wide grid the small disk finds the wide one, and the wide one the
    small one, through the footprint's cells."""
    pos = [[2.2, 1.5003], [0.4001, 1.5003 + np.sqrt(1.9001 ** 2 - 1.7999 ** 2)],
           [8.0, 0.4003], [9.0, 4.0]]
    vel = [[0.0, 0.0], [0.0, 0.0], [-3.0, 0.0], [0.0, 0.0]]
    system = (pos, vel, [1.5, 0.4, 0.4, 0.4], [4.0, 1.0, 1.0, 1.0],
              ed.Box(10.0, 12.0, periodic=False), [])
    sim, ref = _pair(*system, grid="wide")
    assert sim._state.wide is not None and sim._state.wide.index[0] >= 0
    sim.advance(until=12.0)
    ref.advance(until=12.0)
    events = _assert_same_run(sim, ref)
    rests = {e[2]: e[0] for e in events if e[1] == "rest" and e[0] < 0.1}
    assert sorted(rests) == [0, 1]
    woken = [e for e in events if e[1] == "wake" and 1.0 < e[0] < 2.0]
    assert [e[2] for e in woken] == [0, 1] and woken[0][0] == woken[1][0]
    assert any(e[1] == "rest" and e[2] == 0 and e[0] > 2.0 for e in events)


def test_a_wide_disk_rests_on_a_floor_across_a_periodic_edge():
    """A floor segment spans the whole period of a box periodic along x; a wide disk
    falls on it at the seam, x = 0.05, where the floor's image one period to the left
    ends.  Both images are within its gap (a rest height of 0.05), and the flat side
    under it holds it: it comes to rest as in the reference."""
    box = ed.Box(8.0, 6.0, periodic=(True, False))
    walls = [ed.Wall((0.0, 1.0), (8.0, 1.0))]
    pos = [[0.05, 2.6]] + [[x, 1.6] for x in np.linspace(2.5, 6.5, 9)]
    rad = [1.0] + [0.25] * 9
    sim = ed.Simulation(pos, np.zeros((10, 2)), rad, box=box, walls=walls,
                        gravity=(0.0, -1.0), grid="wide", rest_height=0.05, **MODEL)
    sim._record_events(100_000)
    ref = ReferenceSimulation(pos, np.zeros((10, 2)), rad, box=box, walls=walls,
                              gravity=(0.0, -1.0), resting=sim._state.families["resting"],
                              tc=float(sim._state.model.tc), **MODEL)
    assert sim._state.wide is not None and sim._state.wide.index[0] >= 0
    sim.advance(until=8.0)
    ref.advance(until=8.0)
    events = _assert_same_run(sim, ref)
    assert any(e[1] == "rest" and e[2] == 0 for e in events)
