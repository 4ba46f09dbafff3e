"""The compiled engine against the brute-force reference under Lees-Edwards shear.

Small random sheared systems, at offsets chosen to be awkward for the engine's grid
(on a cell edge, a rounding either side of one, near the width), at slow and fast
shear of either sign, with restitution and in boxes of 4 to 8 cells per side: the
same events in the same order, at the same times, and the same final state.
"""

from __future__ import annotations

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of, sheared_gap
from edmd2d.reference import ReferenceSimulation


def _canonical(events):
    """Disk pairs unordered: the engine logs the disk whose prediction fired first."""
    return [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
            for t, k, i, j in events]


def _offsets(width, ncx):
    """Offsets awkward for the grid: 0, on a cell edge, an ulp either side of one,
    just below the width, and an ordinary one."""
    w = width / ncx
    edge = 2 * w
    return [0.0, edge, np.nextafter(edge, 0.0), np.nextafter(edge, np.inf),
            np.nextafter(width, 0.0), 0.37 * width]


def _system(rng, n, box, offset):
    """Up to ``n`` disks (radii 0.3-0.5, masses 0.5-2) placed at random where they
    overlap no other disk through the sliding boundary at ``offset``, with Gaussian
    velocities."""
    pos, rad = [], []
    for _ in range(20_000):
        if len(pos) == n:
            break
        r = rng.uniform(0.3, 0.5)
        p = rng.uniform([0.0, 0.0], [box.width, box.height])
        if all(sheared_gap(p, q, box, offset) >= r + s for q, s in zip(pos, rad)):
            pos.append(p)
            rad.append(r)
    return (np.array(pos), rng.normal(size=(len(pos), 2)), np.array(rad),
            rng.uniform(0.5, 2.0, len(pos)))


def _case(seed, rate, which_offset):
    rng = np.random.default_rng(seed_of(700) + seed)
    box = ed.Box(rng.uniform(4.2, 9.0), rng.uniform(3.2, 8.0))
    probe = ed.Simulation([[1.0, 1.0]], [[0.0, 0.0]], 0.5, box=box, shear_rate=rate)
    offset = _offsets(box.width, int(probe._state.gi[0]))[which_offset]
    return box, offset, _system(rng, int(rng.integers(6, 15)), box, offset)


RATES = [0.3, -0.8, 2.5, -6.0]
CASES = [(seed, RATES[seed % 4], seed % 6, seed % 5 == 4) for seed in range(36)]


@pytest.mark.parametrize("seed, rate, which_offset, inelastic", CASES)
def test_same_events_and_final_state_as_reference(seed, rate, which_offset, inelastic):
    box, offset, (pos, vel, rad, mass) = _case(seed, rate, which_offset)
    model = dict(restitution=0.7, tc=0.05) if inelastic else {}
    sim = ed.Simulation(pos, vel, rad, mass, box=box, shear_rate=rate,
                        shear_offset=offset, **model)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, shear_rate=rate,
                              shear_offset=offset, **model)
    # Rounding differences (the reference moves every disk at every step, the engine
    # only those of an event; the offset's clock is kept differently) start at 1e-16
    # and grow chaotically, by a factor 2-5 per collision in these small, dense boxes
    # heating fast under shear (1e-12 after 10-15 collisions, 1e-3 after 50 in the
    # worst).  The runs stop at 15 collisions (or t = 5): over 200 such systems every
    # event sequence was the same, and the largest difference of an event time 7e-8.
    # A wrong image or offset shows as another sequence or a difference of order 1.
    sim.advance(until=5.0, collisions=15)
    ref.advance(until=5.0, collisions=15)
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0, atol=1e-6)
    assert sim.time == pytest.approx(ref.time, abs=1e-6)
    assert sim.shear_offset == pytest.approx(ref.offset, abs=1e-5)
    d = sim.positions - ref.positions
    d -= np.array(box.size) * np.round(d / np.array(box.size))
    np.testing.assert_allclose(d, 0.0, atol=1e-5)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-5)
    np.testing.assert_allclose(sim.unwrapped_positions, ref.unwrapped_positions, rtol=0,
                               atol=1e-5)
    assert sim.counts.collisions == ref.collisions


def test_the_cases_meet_through_the_sliding_boundary():
    """The random systems above are not all quiet at the boundary: across them, many
    collisions pair a disk of the top row with one of the bottom row (seen through
    the boundary), and the images slide by several cells in each run."""
    across = slides = 0
    for seed, rate, which_offset, _ in CASES:
        box, offset, (pos, vel, rad, mass) = _case(seed, rate, which_offset)
        sim = ed.Simulation(pos, vel, rad, mass, box=box, shear_rate=rate,
                            shear_offset=offset)
        sim._record_events(10_000)
        sim.advance(until=5.0, collisions=15)
        height = box.height
        for _, kind, i, j in sim._recorded_events():
            if kind == "disk":
                # (Rough: a pair more than half a height apart met through the boundary.)
                y = sim.positions[:, 1]
                across += abs(y[i] - y[j]) > 0.5 * height
        slides += abs(int(sim._state.shear_slides[0]))
    assert across > 10
    assert slides > 100


def _dilute(seed):
    """A dilute sheared box of three disks, run by both engines to its third
    collision (or t = 20)."""
    rng = np.random.default_rng(seed_of(800) + seed)
    box = ed.Box(rng.uniform(12.0, 16.0), rng.uniform(8.0, 12.0))
    rate = (0.5, -1.0)[seed % 2]
    offset = rng.uniform(0.0, box.width)
    pos, vel, rad, mass = _system(rng, 3, box, offset)
    vel[:, 1] *= 3.0
    sim = ed.Simulation(pos, vel, rad, mass, box=box, shear_rate=rate, shear_offset=offset)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, shear_rate=rate,
                              shear_offset=offset)
    # (Dilute: each collision multiplies a rounding difference by about the free path
    # over the radius, 10 to 100 here: 3 collisions keep it below 1e-10.)
    sim.advance(until=20.0, collisions=3)
    ref.advance(until=20.0, collisions=3)
    return box, sim, ref


@pytest.mark.parametrize("seed", range(12))
def test_few_disks_through_many_crossings_and_wraps_of_the_offset(seed):
    """A dilute sheared box run long: few collisions (so rounding stays small), but
    exits through the top and bottom and wraps of the offset past the width, where the
    unwrapped positions must follow the reference's."""
    box, sim, ref = _dilute(seed)
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    # (The reference's clock is a sum of thousands of short steps, the look-ahead
    # window being short under shear: its rounding is relative, ~1e-10 by t = 10.)
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=1e-9,
                               atol=1e-9)
    np.testing.assert_allclose(sim.unwrapped_positions, ref.unwrapped_positions, rtol=1e-9,
                               atol=1e-8)
    # (Velocities of tens after many exits: their rounding is relative.)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=1e-8, atol=1e-9)


def test_the_dilute_cases_cross_the_boundary_and_wrap_the_offset():
    """Across the twelve dilute systems above, disks leave through the top or bottom
    tens of times, and the images slide past the width many times."""
    exits = wraps = 0
    for seed in range(12):
        box, sim, _ = _dilute(seed)
        exits += int(np.round(np.abs(sim.unwrapped_positions[:, 1] - sim.positions[:, 1])
                              / box.height).sum())
        wraps += abs(int(sim._state.shear_slides[0])) // int(sim._state.gi[0])
    assert exits > 20
    assert wraps > 10
