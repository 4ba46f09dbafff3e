"""Wall segments that move (``wall_motions``) in the brute-force reference.

Every expected contact time and velocity is derived here by hand (a gap closing at a
constant speed, a quadratic, an ``asin``), or found independently of the reference's
search (dense sampling of the gap and ``scipy.optimize.brentq``).  A wall of velocity
``u`` reflects the velocity relative to it: ``v' = v - (1 + e) ((v - u).n) n``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import edmd2d as ed
from edmd2d.physics import Resting
from edmd2d.reference import ReferenceSimulation, _times

WIDE = ed.Box(40.0, 10.0, periodic=False)
WALLED = ed.Box(10.0, 10.0, periodic=False)
PISTON = ((10.0, 2.0), (10.0, 8.0))  # a vertical segment at x = 10
FLOOR = ((0.0, 1.0), (10.0, 1.0))  # a floor segment across the whole width at y = 1


def _piston_run(x, v, u, e=1.0, distance=20.0, begin=None, piston=PISTON):
    """A disk of radius 1 at (x, 5) with velocity (v, 0), and the vertical segment
    ``piston`` moving at (u, 0) for ``distance``."""
    return ReferenceSimulation([[x, 5.0]], [[v, 0.0]], radii=1.0, box=WIDE,
                               walls=[piston], wall_restitution=e,
                               wall_motions={0: ed.Translation((u, 0.0), distance, begin)})


def _books(ref):
    """kinetic + potential + dissipated - work of the walls: constant."""
    return ref.total_energy() + ref.dissipated - sum(ref.wall_work)


# -- translations --------------------------------------------------------------------------

def test_head_on_piston_elastic():
    # Disk front at 6 + t, piston at 10 - t: contact at t = 2 (disk at 7, piston at 8).
    # Relative velocity v - u = 2 reverses: 2u - v = -3.  Work J.u = (-4)(-1) = 4.
    ref = _piston_run(5.0, 1.0, -1.0)
    ref.advance(until=2.5)
    assert ref.events == [(2.0, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[-3.0, 0.0]]
    assert ref.wall_work == [4.0]
    assert ref.dissipated == 0.0
    assert ref.wall_positions().tolist() == [[[7.5, 2.0], [7.5, 8.0]]]
    assert ref.kinetic_energy() == 0.5 + 4.0


def test_head_on_piston_inelastic():
    # e = 1/2: the relative velocity 2 becomes -1, so v' = u - 1 = -2; the impulse is
    # -3 and its work (-3)(-1) = 3; lost (1 - e^2)/2 m 2^2 = 1.5.  K: 0.5 -> 2.
    ref = _piston_run(5.0, 1.0, -1.0, e=0.5)
    ref.advance(until=2.5)
    assert ref.events == [(2.0, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[-2.0, 0.0]]
    assert ref.wall_work == [3.0]
    assert ref.dissipated == 1.5
    assert ref.kinetic_energy() == 2.0


def test_disk_catches_a_piston_moving_away_slower():
    # Gap 10 - 6 = 4 closing at 1 - 0.5: contact at t = 8 (piston at 14).  Relative
    # velocity 0.5 reverses: v' = 2u - v = 0, the work -0.5 took all the kinetic energy.
    ref = _piston_run(5.0, 1.0, 0.5)
    ref.advance(until=9.0)
    assert ref.events == [(8.0, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[0.0, 0.0]]
    assert ref.wall_work == [-0.5]
    assert ref.kinetic_energy() == 0.0


def test_piston_overtakes_a_slower_disk():
    # The piston at x = 2 moves right at 2, the disk ahead (centre 5, back at 4) at 1:
    # the gap 2 closes at 1, contact at t = 2 (piston at 6).  v' = 2u - v = 3, and the
    # work J.u = 2 * 2 = 4 = 4.5 - 0.5.
    ref = _piston_run(5.0, 1.0, 2.0, piston=((2.0, 2.0), (2.0, 8.0)))
    ref.advance(until=2.5)
    assert ref.events == [(2.0, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[3.0, 0.0]]
    assert ref.wall_work == [4.0]


def test_faster_disk_is_never_overtaken():
    # The disk (back at 4, speed 2) outruns the piston (at 3, speed 1): it reaches the
    # right box wall (40) at t = (39 - 5) / 2 = 17, comes back at -2 and meets the
    # piston (at 3 + t until it stops at 3 + 30) when its back, 38 - 2 (t - 17), is at
    # 3 + t: t = 23, piston at 26.  v' = 2u - v = 4, work (4 + 2) * 1.
    ref = _piston_run(5.0, 2.0, 1.0, distance=30.0, piston=((3.0, 2.0), (3.0, 8.0)))
    ref.advance(until=25.0)
    assert ref.events == [(17.0, "box", 0, 1), (23.0, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[4.0, 0.0]]
    assert ref.wall_work == [6.0]


def test_piston_that_stops_is_then_a_fixed_wall():
    # It moves left at 1 from x = 10 over 2, stopping at 8 at t = 2.  The disk (front
    # at 3 + t) reaches it at t = 5: a fixed wall, v' = -v, no work.
    ref = _piston_run(2.0, 1.0, -1.0, distance=2.0)
    ref.advance(until=6.0)
    assert ref.events == [(5.0, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[-1.0, 0.0]]
    assert ref.wall_work == [0.0]
    assert ref.wall_positions().tolist() == [[[8.0, 2.0], [8.0, 8.0]]]


@pytest.mark.parametrize(("v", "t", "after", "work"), [
    # Front at 3 + t: too slow to meet it while it moves (3 + t = 11 - t gives t = 4,
    # after the stop at 3): at the stopped piston, 3 + t = 8, t = 5.
    (1.0, 5.0, -1.0, 0.0),
    # Front at 3 + 3t: at rest until t = 1 (10 not reached), then 3 + 3t = 11 - t at
    # t = 2 while it moves: v' = 2u - v = -5, work (-8)(-1) = 8.
    (3.0, 2.0, -5.0, 8.0),
])
def test_piston_starting_later(v, t, after, work):
    # At rest at x = 10 until begin = 1, then left at 1 over 2, at rest at 8 from t = 3.
    ref = _piston_run(2.0, v, -1.0, distance=2.0, begin=1.0)
    ref.advance(until=t + 0.25)
    assert ref.events == [(t, "wall", 0, 0)]
    assert ref.velocities.tolist() == [[after, 0.0]]
    assert ref.wall_work == [work]


def test_piston_floor_rising_under_gravity():
    # A floor at y = 1 rises at 1 (over 3); the disk (r = 0.5) falls from y = 5 with
    # g = 1: its gap 3.5 - t - t^2/2 closes at t = 2 sqrt(2) - 1 (before the stop),
    # with v = -t; elastic: v' = 2u - v = 1 + 2 sqrt(2).
    ref = ReferenceSimulation([[5.0, 5.0]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                              walls=[FLOOR], gravity=(0.0, -1.0),
                              wall_motions={0: ed.Translation((0.0, 1.0), 3.0)})
    e0 = _books(ref)
    t = 2.0 * math.sqrt(2.0) - 1.0
    ref.advance(until=t + 0.01)
    assert [e[0] for e in ref.events] == [pytest.approx(t, rel=1e-15)]
    assert ref.velocities[0, 1] == pytest.approx(1.0 + 2.0 * math.sqrt(2.0) - 0.01,
                                                 rel=1e-14)
    assert _books(ref) == pytest.approx(e0, rel=1e-14)


def test_end_point_of_a_moving_segment():
    # A vertical segment (5, 2)-(5, 4) rising at 1 meets a disk at rest at (5.6, 8),
    # r = 1, with its upper end: 0.6^2 + (4 - t)^2 = 1 at t = 3.2, along n = (0.6, 0.8).
    # (v - u).n = -0.8, so v' = 1.6 n = (0.96, 1.28); work J.u = 1.28 = m v'^2 / 2.
    ref = ReferenceSimulation([[5.6, 8.0]], [[0.0, 0.0]], radii=1.0, box=WALLED,
                              walls=[((5.0, 2.0), (5.0, 4.0))],
                              wall_motions={0: ed.Translation((0.0, 1.0), 5.0)})
    dt, kind, i, k, detail = ref.next_event()
    assert (kind, i, k, detail[0]) == ("wall", 0, 0, "end")
    assert dt == pytest.approx(3.2, rel=1e-15)
    ref.advance(until=3.25)
    np.testing.assert_allclose(ref.velocities, [[0.96, 1.28]], rtol=1e-14)
    assert ref.wall_work[0] == pytest.approx(1.28, rel=1e-14)
    assert ref.kinetic_energy() == pytest.approx(ref.wall_work[0], rel=1e-14)


# -- oscillations --------------------------------------------------------------------------

@pytest.mark.parametrize("e", [1.0, 0.5])
def test_still_disk_hit_by_an_oscillating_floor(e):
    # The floor at 1 + 0.5 sin(t) reaches the disk (r = 0.5, at rest at y = 1.75) when
    # 0.5 sin(t) = 0.25: t = asin(1/2) = pi/6, going up at u = 0.5 cos(pi/6) =
    # sqrt(3)/4.  v' = u - e (0 - u) = (1 + e) u: 2u = sqrt(3)/2 when elastic.
    ref = ReferenceSimulation([[5.0, 1.75]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                              walls=[FLOOR], wall_restitution=e,
                              wall_motions={0: ed.Oscillation(0.5, omega=1.0)})
    ref.advance(until=0.6)
    assert [e[1:] for e in ref.events] == [("wall", 0, 0)]
    assert ref.events[0][0] == pytest.approx(math.pi / 6.0, rel=1e-15)
    u = math.sqrt(3.0) / 4.0
    np.testing.assert_allclose(ref.velocities, [[0.0, (1.0 + e) * u]], rtol=1e-14, atol=0)
    assert ref.dissipated == pytest.approx(0.5 * (1.0 - e * e) * u * u, rel=1e-14, abs=0)
    assert ref.wall_work[0] == pytest.approx((1.0 + e) * u * u, rel=1e-14)


def test_still_disk_out_of_reach_of_an_oscillating_floor():
    # The floor rises to 1.5 at most; the disk's bottom is at 1.6: nothing ever happens
    # (its search ends after one period).
    ref = ReferenceSimulation([[5.0, 2.1]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                              walls=[FLOOR],
                              wall_motions={0: ed.Oscillation(0.5, omega=1.0)})
    assert ref.next_event()[0] == math.inf
    ref.advance(until=20.0)
    assert ref.events == []


@pytest.mark.parametrize(("lift", "t_hit"), [
    # A hair below the floor's highest reach, 1.5: met where 0.5 sin(t) = 0.5 - 1e-9,
    # at a closing speed of only ~3e-5 (a near-double root).  A hair above: never.
    (-1e-9, math.asin(1.0 - 2e-9)),
    (1e-9, math.inf),
])
def test_near_misses_of_an_oscillating_floor(lift, t_hit):
    ref = ReferenceSimulation([[5.0, 2.0 + lift]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                              walls=[FLOOR],
                              wall_motions={0: ed.Oscillation(0.5, omega=1.0)})
    assert ref.next_event()[0] == pytest.approx(t_hit, rel=1e-9)


def test_a_search_that_does_not_converge_raises(monkeypatch):
    # (With too few steps allowed: an error, never a contact missed.)
    monkeypatch.setattr(_times, "MAX_ADVANCES", 3)
    ref = ReferenceSimulation([[5.0, 1.75]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                              walls=[FLOOR],
                              wall_motions={0: ed.Oscillation(0.5, omega=1.0)})
    with pytest.raises(RuntimeError, match="oscillating segment"):
        ref.next_event()


def test_end_point_of_an_oscillating_segment():
    # A vertical segment (5, 1)-(5, 3) shaken by 0.5 sin(t) along y; a disk at rest at
    # (5.6, 4.05), r = 1, is reached by the upper end at 3 + 0.5 sin(t): 0.6^2 + (1.05 -
    # 0.5 sin t)^2 = 1 at sin t = 1/2, t = pi/6, along n = (0.6, 0.8), the end moving
    # at u = (0, sqrt(3)/4): (v - u).n = -0.2 sqrt(3), v' = 0.4 sqrt(3) n.
    ref = ReferenceSimulation([[5.6, 4.05]], [[0.0, 0.0]], radii=1.0, box=WALLED,
                              walls=[((5.0, 1.0), (5.0, 3.0))],
                              wall_motions={0: ed.Oscillation(0.5, omega=1.0)})
    dt, kind, _, _, detail = ref.next_event()
    assert (kind, detail[0]) == ("wall", "end")
    # (The distance is 1 to rounding of 4.05: the time to a few units of rounding.)
    assert dt == pytest.approx(math.pi / 6.0, rel=1e-13)
    ref.advance(until=0.6)
    np.testing.assert_allclose(ref.velocities, [0.4 * math.sqrt(3.0) * np.array([0.6, 0.8])],
                               rtol=1e-12)


@pytest.mark.parametrize("e", [1.0, 0.8])
def test_drop_onto_an_oscillating_floor_matches_brentq(e):
    # The floor at 1 + A sin(w t + phi), the disk falling from rest at y = 4 (r = 0.5)
    # under g: its gap 2.5 - g t^2 / 2 - A sin(w t + phi), first root by sampling then
    # brentq.  Periodic along x: the search also ends at the look-ahead window.
    amp, omega, phase, g = 0.3, 5.0, 0.7, 9.81
    box = ed.Box(10.0, 10.0, periodic=(True, False))
    ref = ReferenceSimulation([[5.0, 4.0]], [[0.0, 0.0]], radii=0.5, box=box,
                              walls=[FLOOR], gravity=(0.0, -g), wall_restitution=e,
                              wall_motions={0: ed.Oscillation(amp, omega, phase=phase)})

    def gap(t):
        return 2.5 - 0.5 * g * t * t - amp * math.sin(omega * t + phase)

    grid = np.linspace(0.0, 2.0, 20001)
    first = int(np.argmax([gap(t) <= 0.0 for t in grid]))
    t_hit = brentq(gap, grid[first - 1], grid[first], xtol=1e-16, rtol=4 * np.finfo(float).eps)
    e0 = _books(ref)
    ref.advance(until=t_hit + 1e-3)
    assert [ev[1:] for ev in ref.events] == [("wall", 0, 0)]
    assert ref.events[0][0] == pytest.approx(t_hit, rel=1e-13)
    u = amp * omega * math.cos(omega * t_hit + phase)
    v_after = u - e * (-g * t_hit - u)
    assert ref.velocities[0, 1] == pytest.approx(v_after - g * 1e-3, rel=1e-12)
    assert _books(ref) == pytest.approx(e0, rel=1e-13)


def test_bouncing_on_a_shaken_floor_keeps_the_books():
    # A disk bouncing on a shaken floor (many closing contacts and openings right after
    # a bounce): the energy it gains or loses is the floor's work.
    ref = ReferenceSimulation([[5.0, 3.0]], [[0.3, 0.0]], radii=0.5, box=WALLED,
                              walls=[FLOOR], gravity=(0.0, -1.0), wall_restitution=0.9,
                              wall_motions={0: ed.Oscillation(0.2, omega=4.0)})
    e0 = _books(ref)
    ref.advance(until=60.0)
    assert sum(ev[1] == "wall" for ev in ref.events) >= 8
    assert _books(ref) == pytest.approx(e0, rel=1e-12)
    # Never below the floor (within rounding).
    floor_y = ref.wall_positions()[0, 0, 1]
    assert ref.positions[0, 1] - 0.5 >= floor_y - 1e-12


# -- many disks ----------------------------------------------------------------------------

def test_energy_books_of_a_box_with_a_piston_and_a_shaken_floor():
    rng = np.random.default_rng(7)
    grid = [(x, y) for y in (2.5, 4.5, 6.5) for x in (1.5, 3.5, 5.5, 7.5)]
    pos = np.array(grid[:10]) + rng.uniform(-0.3, 0.3, (10, 2))
    ref = ReferenceSimulation(
        pos, rng.normal(size=(10, 2)), radii=rng.uniform(0.3, 0.5, 10),
        masses=rng.uniform(0.5, 2.0, 10), box=WALLED,
        walls=[FLOOR, ((9.5, 1.3), (9.5, 9.6)), ((3.0, 8.0), (5.0, 8.5))],
        gravity=(0.0, -1.0), restitution=0.95, wall_restitution=0.9,
        wall_motions={0: ed.Oscillation(0.2, omega=4.0),
                      1: ed.Translation((-0.5, 0.0), 2.0, begin=0.5)})
    e0 = _books(ref)
    scale = abs(ref.kinetic_energy()) + abs(ref.potential_energy())
    t = 0.0
    while len(ref.events) < 300:
        t += 0.25
        ref.advance(until=t)
        assert abs(_books(ref) - e0) <= 1e-12 * scale
    kinds = {(ev[1], ev[3]) for ev in ref.events if ev[1] == "wall"}
    assert {("wall", 0), ("wall", 1)} <= kinds  # both moving segments were hit
    assert ref.wall_work[2] == 0.0 and ref.wall_work[0] != 0.0 and ref.wall_work[1] != 0.0
    assert ref.dissipated > 0.0


def test_wall_positions_of_fixed_and_moving_segments():
    walls = [((1.0, 1.0), (2.0, 3.0)), ((4.0, 4.0), (6.0, 4.0))]
    ref = ReferenceSimulation([[8.0, 8.0]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                              walls=walls, time=2.0,
                              wall_motions={1: ed.Translation((0.0, 1.0), 1.5)})
    assert ref.motions[1].begin == 2.0  # (begin: the clock at the start)
    assert ref.wall_positions().shape == (2, 2, 2)
    ref.advance(until=3.0)
    assert ref.wall_positions().tolist() == [[[1.0, 1.0], [2.0, 3.0]],
                                             [[4.0, 5.0], [6.0, 5.0]]]
    ref.advance(until=10.0)
    assert ref.wall_positions()[1].tolist() == [[4.0, 5.5], [6.0, 5.5]]
    assert ref.wall_work == [0.0, 0.0]


def test_no_motions_is_the_run_without_them():
    # An empty dict runs the code of fixed walls, bit for bit.
    rng = np.random.default_rng(3)
    pos = np.array([(x, y) for y in (3.0, 5.0, 7.0) for x in (2.0, 5.0, 8.0)])
    vel = rng.normal(size=(9, 2))
    kw = dict(radii=0.4, box=WALLED, walls=[((0.0, 1.0), (10.0, 1.5))],
              gravity=(0.0, -1.0), wall_restitution=0.9)
    a = ReferenceSimulation(pos, vel, **kw).advance(until=5.0)
    b = ReferenceSimulation(pos, vel, wall_motions={}, **kw).advance(until=5.0)
    assert a.events == b.events
    assert a.positions.tolist() == b.positions.tolist()


# -- refusals ------------------------------------------------------------------------------

@pytest.mark.parametrize(("kwargs", "motions", "words"), [
    (dict(gravity=(0.0, -1.0), resting=Resting.of(1e-3, 1.0, 0.5)), None, "resting"),
    (dict(growth=0.1), None, "growth"),
    (dict(box=ed.Box(10.0, 10.0), shear_rate=0.1), None, "shear_rate"),
    (dict(wall_temperatures={0: 1.0}), None, "heated"),
    ({}, {1: ed.Oscillation(0.1, 1.0)}, "index"),
    ({}, {-1: ed.Oscillation(0.1, 1.0)}, "index"),
    ({}, {"0": ed.Oscillation(0.1, 1.0)}, "index"),
    ({}, {0: (0.0, 1.0)}, "Translation or an Oscillation"),
    ({}, [ed.Oscillation(0.1, 1.0)], "dict"),
])
def test_refusals(kwargs, motions, words):
    motions = {0: ed.Oscillation(0.1, 1.0)} if motions is None else motions
    settings = dict(radii=0.5, box=WALLED, walls=[FLOOR]) | kwargs
    with pytest.raises(ValueError, match="wall_motions") as info:
        ReferenceSimulation([[5.0, 5.0]], [[0.0, 0.0]], wall_motions=motions, **settings)
    assert words in str(info.value)
