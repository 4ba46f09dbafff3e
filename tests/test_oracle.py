"""The compiled engine against the brute-force reference on many random small systems."""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed
from conftest import overlaps, random_system, seed_of
from edmd2d.reference import ReferenceSimulation

BOX_KINDS = [(True, True), (False, False), (True, False), (False, True)]


def _canonical(events):
    """Disk pairs unordered: the engine logs the disk whose prediction fired first."""
    return [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
            for t, k, i, j in events]


def _walls(kind, box):
    w, h = box.width, box.height
    if kind == "none":
        return []
    if kind == "divider":  # a wall with a gap: sides and both end points get hit
        return [ed.Wall((0.5 * w, 0.25 * h), (0.5 * w, 0.75 * h))]
    if kind == "polygon":  # a triangle obstacle plus a slanted segment
        return ed.Wall.polygon([(0.2 * w, 0.2 * h), (0.45 * w, 0.25 * h), (0.3 * w, 0.45 * h)]) + [
            ed.Wall((0.6 * w, 0.9 * h), (0.95 * w, 0.6 * h))]
    raise ValueError(kind)


def _system(seed, periodic, walls_kind, peg_every, smallest=2.5, most=9):
    """A random small system of box kind ``periodic`` (sides from ``smallest`` to 7)
    with walls of ``walls_kind`` and 2 to ``most`` disks, with a fixed peg (disk 0) for
    every ``peg_every``-th seed."""
    rng = np.random.default_rng(seed)
    box = ed.Box(rng.uniform(smallest, 7.0), rng.uniform(smallest, 7.0), periodic=periodic)
    walls = _walls(walls_kind, box)
    pos, vel, rad, mass = random_system(rng, int(rng.integers(2, most + 1)), box, walls)
    if seed % peg_every == 0 and len(pos) > 2:
        mass[0] = np.inf
        vel[0] = 0.0
    return box, walls, (pos, vel, rad, mass)


def _assert_same_run(sim, ref, box):
    """The engine's recorded events and final state against the oracle's: events in
    the same order, times and state to 1e-9."""
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0, atol=1e-9)
    assert sim.time == ref.time
    d = sim.positions - ref.positions
    for axis in range(2):
        if box.periodic[axis]:
            d[:, axis] -= box.size[axis] * np.round(d[:, axis] / box.size[axis])
    np.testing.assert_allclose(d, 0.0, atol=1e-9)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-9)


CASES = [(seed, BOX_KINDS[seed % 4], ("none", "divider", "polygon")[seed % 3])
         for seed in range(48)]


@pytest.mark.parametrize("seed, periodic, walls_kind", CASES)
def test_same_events_and_final_state_as_reference(seed, periodic, walls_kind):
    box, walls, (pos, vel, rad, mass) = _system(seed, periodic, walls_kind, 5)
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls)
    # The horizon keeps the chaotic growth of rounding differences (a factor ~2-10 per
    # collision) far below the tolerance: over 200 such systems the largest difference
    # seen was 1e-11, and every event sequence was identical.
    t_end = 1.5
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    _assert_same_run(sim, ref, box)
    assert sim.time == t_end
    assert sim.counts.collisions == ref.collisions
    assert sim.counts.wall_collisions == ref.wall_collisions


@pytest.mark.parametrize("seed", range(6))
def test_collision_count_mode_matches_reference(seed):
    rng = np.random.default_rng(seed_of(100) + seed)
    box = ed.Box(6.0, 5.0, periodic=BOX_KINDS[seed % 4])
    pos, vel, rad, mass = random_system(rng, 8, box)
    sim = ed.Simulation(pos, vel, rad, mass, box=box).advance(collisions=12)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box).advance(collisions=12)
    assert sim.counts.collisions == ref.collisions == 12
    assert sim.time == pytest.approx(ref.time, abs=1e-9)
    np.testing.assert_allclose(sim.velocities, ref.velocities, atol=1e-9)


GRAVITY = [(0.0, -1.0), (0.7, -2.5), (-1.5, 0.4), (0.0, 3.0)]
GRAVITY_CASES = [(seed, BOX_KINDS[seed % 4], ("none", "divider", "polygon")[seed % 3],
                  GRAVITY[seed % 4], seed % 2 == 1) for seed in range(24)]


@pytest.mark.parametrize("seed, periodic, walls_kind, gravity, inelastic", GRAVITY_CASES)
def test_same_events_under_gravity_as_reference(seed, periodic, walls_kind, gravity,
                                                inelastic):
    """Parabolic flights: walls, segments (sides and end points), pegs (quartic
    contacts), periodic wraps and, for inelastic disks with a long tc, disks that come
    to rest on a floor and are freed again, against the oracle's independent roots."""
    box, walls, (pos, vel, rad, mass) = _system(500 + seed, periodic, walls_kind, 3, 3.0, 8)
    model = dict(restitution=0.6, wall_restitution=0.3, tc=0.2) if inelastic else {}
    # (The oracle does not know disks at rest on disks: the engine runs without.)
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, gravity=gravity,
                        resting=False, **model)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, gravity=gravity,
                              **model)
    # (Inelastic runs go on to t = 3, by which time several disks have come to rest
    # on a floor, some more than once; rounding differences grow chaotically from
    # collision to collision, to ~1e-6 by t = 4 in the worst of these systems.)
    t_end = 3.0 if inelastic else 2.0
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    _assert_same_run(sim, ref, box)
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(
        ref.total_energy() + ref.dissipated, rel=1e-9)


THERMAL_CASES = [(seed, BOX_KINDS[seed % 4], ("none", "divider", "polygon")[seed % 3])
                 for seed in range(12)]


@pytest.mark.parametrize("seed, periodic, walls_kind", THERMAL_CASES)
def test_same_events_with_thermostat_and_heated_walls_as_reference(seed, periodic,
                                                                   walls_kind):
    """Andersen redraws at their exact times and heated walls (box walls and a
    segment), drawn from one seeded stream: the same events, draws and final states as
    the oracle, which takes its numbers from the same stream in the same order."""
    box, walls, (pos, vel, rad, mass) = _system(900 + seed, periodic, walls_kind, 3, 3.0, 8)
    heated = {name: 1.5 + k for k, name in enumerate(("left", "right", "bottom", "top"))
              if not box.periodic[k // 2] and k % 2 == seed % 2}
    if walls:
        heated[0] = 0.7
    options = dict(wall_temperatures=heated, thermostat=(1.2, 0.8), seed=seed,
                   gravity=(0.0, -1.0) if seed % 4 == 1 else (0.0, 0.0))
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, **options)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, **options)
    t_end = 2.0
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    _assert_same_run(sim, ref, box)
    assert sim.counts.redraws == ref.redraws > 0
    np.testing.assert_allclose(sim.wall_heat(), ref.wall_heat, rtol=1e-9, atol=1e-12)
    assert sim.thermostat_energy() == pytest.approx(ref.thermostat_energy, rel=1e-9)


GROWTH_CASES = [(seed, BOX_KINDS[seed % 4], ("none", "divider", "polygon")[seed % 3],
                 (0.04, 0.12)[seed % 2]) for seed in range(24)]


@pytest.mark.parametrize("seed, periodic, walls_kind, rate", GROWTH_CASES)
def test_same_events_with_growing_disks_as_reference(seed, periodic, walls_kind, rate):
    """Radii growing linearly in time: the contact distance grows too (quadratics of
    either curvature), rims close on walls and segments at the growth speed, and the
    impulse reverses the closing rate; grids rebuilt as the disks outgrow their cells.
    The same events and final states as the oracle's textbook roots, and no overlap."""
    box, walls, (pos, vel, rad, mass) = _system(1300 + seed, periodic, walls_kind, 4, 3.0, 8)
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, growth=rate)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, growth=rate)
    t_end = 1.0
    sim.advance(until=t_end)
    ref.advance(until=t_end)
    _assert_same_run(sim, ref, box)
    np.testing.assert_allclose(sim.radii, ref.r, rtol=1e-15)
    np.testing.assert_allclose(sim.radii, rad * (1.0 + rate * t_end), rtol=1e-15)
    assert len(overlaps(sim)) == 0
