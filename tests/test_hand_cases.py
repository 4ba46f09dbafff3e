"""Collisions computed by hand, run on both the compiled engine and the reference."""

from __future__ import annotations

import math

import numpy as np
import pytest

import edmd2d as ed

WALLED = ed.Box(20.0, 20.0, periodic=False)


def test_head_on_equal_masses(backend):
    # Gap 3 - 2 = 1 closes at relative speed 2: contact at t = 0.5, velocities swap.
    sim = backend([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]], radii=1.0, box=WALLED)
    sim.advance(collisions=1)
    assert sim.time == pytest.approx(0.5, abs=1e-15)
    np.testing.assert_allclose(sim.velocities, [[-1.0, 0.0], [1.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(sim.positions, [[2.5, 5.0], [4.5, 5.0]], atol=1e-15)


def test_head_on_unequal_masses(backend):
    # 1D elastic collision: v1' = ((m1-m2) v1 + 2 m2 v2)/(m1+m2) = -2, v2' = 0.
    sim = backend([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]], radii=1.0,
                  masses=[1.0, 3.0], box=WALLED)
    sim.advance(until=1.0)
    np.testing.assert_allclose(sim.velocities, [[-2.0, 0.0], [0.0, 0.0]], atol=1e-14)
    # After contact at 0.5 disk 0 moves back by 2 * 0.5; disk 1 rests at 4.5.
    np.testing.assert_allclose(sim.positions, [[1.5, 5.0], [4.5, 5.0]], atol=1e-14)
    assert sim.kinetic_energy() == pytest.approx(0.5 * 1 + 0.5 * 3, rel=1e-14)


def test_glancing_collision_at_sixty_degrees(backend):
    # Impact parameter 1 with contact distance 2: contact when x = 5 - sqrt(3); the
    # normal is (-sqrt3, -1)/2, so the moving disk leaves at (1/4, -sqrt3/4) and the
    # target at (3/4, sqrt3/4): 90 degrees apart, as for equal masses.
    sim = backend([[1.0, 5.0], [6.0, 6.0]], [[1.0, 0.0], [0.0, 0.0]], radii=1.0, box=WALLED)
    sim.advance(collisions=1)
    s3 = math.sqrt(3.0)
    assert sim.time == pytest.approx(5.0 - s3, rel=1e-14)
    np.testing.assert_allclose(sim.velocities, [[0.25, -s3 / 4], [0.75, s3 / 4]], atol=1e-14)


@pytest.mark.parametrize("offset, hits", [(2.0 + 1e-9, False), (2.0 - 1e-9, True)])
def test_grazing(backend, offset, hits):
    # Impact parameter just above / below the contact distance 2.
    sim = backend([[1.0, 5.0], [8.0, 5.0 + offset]], [[1.0, 0.0], [0.0, 0.0]], radii=1.0,
                  box=WALLED)
    sim.advance(until=15.0)  # the moving disk reaches the wall at x = 19 at t = 18
    collided = not np.allclose(sim.velocities[1], 0.0)
    assert collided is hits
    if hits:
        # A near-tangential hit transfers almost nothing: |dv| = |v.n| ~ sqrt(1 - (b/2)^2).
        transfer = math.sqrt(1.0 - (offset / 2.0) ** 2)
        assert np.hypot(*sim.velocities[1]) == pytest.approx(transfer, rel=1e-4)


def test_newtons_cradle(backend):
    # A striker hits a row of four touching disks at rest: the momentum travels through
    # the row in zero-time contacts and only the last disk leaves, with the striker's speed.
    pos = [[3.0, 5.0], [6.0, 5.0], [8.0, 5.0], [10.0, 5.0], [12.0, 5.0]]
    vel = [[1.0, 0.0]] + [[0.0, 0.0]] * 4
    sim = backend(pos, vel, radii=1.0, box=WALLED)
    sim.advance(until=2.0)
    expected_v = np.zeros((5, 2))
    expected_v[4, 0] = 1.0
    np.testing.assert_allclose(sim.velocities, expected_v, atol=1e-14)
    np.testing.assert_allclose(sim.positions[4], [13.0, 5.0], atol=1e-14)
    np.testing.assert_allclose(sim.positions[0], [4.0, 5.0], atol=1e-14)


WALL_BOX = ed.Box(10.0, 10.0, periodic=False)
DIVIDER = ed.Wall((5.0, 0.0), (5.0, 5.0))


def test_wall_side_hit(backend):
    sim = backend([[2.0, 2.5]], [[1.0, 0.0]], radii=0.5, box=WALL_BOX, walls=[DIVIDER])
    sim.advance(until=3.0)
    # Reaches x = 4.5 at t = 2.5, back by 0.5.
    np.testing.assert_allclose(sim.positions, [[4.0, 2.5]], atol=1e-14)
    np.testing.assert_allclose(sim.velocities, [[-1.0, 0.0]], atol=1e-15)


def test_end_point_head_on(backend):
    # Aimed straight at the end point (5, 5): contact after sqrt(13) - 0.5, reversed.
    u = np.array([3.0, -2.0]) / math.sqrt(13.0)
    sim = backend([[2.0, 7.0]], [u], radii=0.5, box=WALL_BOX, walls=[DIVIDER])
    sim.advance(collisions=0)
    t_hit = math.sqrt(13.0) - 0.5
    sim.advance(until=t_hit + 1.0)
    np.testing.assert_allclose(sim.velocities, [-u], atol=1e-14)
    np.testing.assert_allclose(sim.positions, [[5.0, 5.0] - u * 1.5], atol=1e-13)


def test_end_point_glancing(backend):
    # Passing 0.3 above the end point with radius 0.5: contact at x = 5 - 0.4, normal
    # (-0.8, 0.6), so v = (1, 0) becomes (1, 0) - 2(-0.8)(-0.8, 0.6) = (-0.28, 0.96).
    sim = backend([[1.0, 5.3]], [[1.0, 0.0]], radii=0.5, box=WALL_BOX, walls=[DIVIDER])
    sim.advance(until=3.6 + 1.0)
    np.testing.assert_allclose(sim.velocities, [[-0.28, 0.96]], atol=1e-14)
    np.testing.assert_allclose(sim.positions, [[4.6 - 0.28, 5.3 + 0.96]], atol=1e-13)


def test_inner_corner(backend):
    # Into an inner right-angle corner along the diagonal: both sides at t = 2.5.
    walls = [ed.Wall((6.0, 1.0), (6.0, 6.0)), ed.Wall((1.0, 6.0), (6.0, 6.0))]
    sim = backend([[3.0, 3.0]], [[1.0, 1.0]], radii=0.5, box=WALL_BOX, walls=walls)
    sim.advance(until=5.0)
    np.testing.assert_allclose(sim.velocities, [[-1.0, -1.0]], atol=1e-14)
    np.testing.assert_allclose(sim.positions, [[3.0, 3.0]], atol=1e-13)


def test_outer_corner_of_a_square(backend):
    # A square obstacle; a disk aimed along the diagonal at its corner (6, 6) bounces
    # straight back from the corner point.
    square = ed.Wall.polygon([(6.0, 6.0), (8.0, 6.0), (8.0, 8.0), (6.0, 8.0)])
    v = np.array([1.0, 1.0]) / math.sqrt(2.0)
    sim = backend([[3.0, 3.0]], [v], radii=0.5, box=WALL_BOX, walls=square)
    t_hit = 3.0 * math.sqrt(2.0) - 0.5
    sim.advance(until=t_hit + 1.0)
    np.testing.assert_allclose(sim.velocities, [-v], atol=1e-14)
    np.testing.assert_allclose(sim.positions, [np.array([6.0, 6.0]) - 1.5 * v], atol=1e-13)
    assert sim.wall_collisions == 1 if hasattr(sim, "wall_collisions") else (
        sim.counts.wall_collisions == 1)


def _bounce_position(x0, lo, hi, distance):
    """Where a point starting at x0 moving right ends after ``distance`` between lo and hi."""
    period = 2.0 * (hi - lo)
    u = (x0 - lo + distance) % period
    return lo + u if u <= hi - lo else lo + period - u


@pytest.mark.parametrize("speed", [1e4, 1e6])
def test_fast_disk_never_tunnels_through_a_thin_wall(backend, speed):
    if backend.__name__ == "ReferenceSimulation" and speed > 1e4:
        pytest.skip("250 000 bounces are for the compiled engine")
    # Between the box wall (centre stops at 0.5) and the divider (centre stops at 4.5).
    thin = ed.Wall((5.0, 1.0), (5.0, 9.0))
    sim = backend([[1.0, 5.0]], [[speed, 0.0]], radii=0.5, box=WALL_BOX, walls=[thin])
    for t in (1e-7, 0.3, 0.7, 1.0):
        sim.advance(until=t)
        x = sim.positions[0, 0]
        assert 0.5 - 1e-9 <= x <= 4.5 + 1e-9
        # Distance scaled by speed: rounding grows with the number of bounces.
        assert x == pytest.approx(_bounce_position(1.0, 0.5, 4.5, speed * t), abs=1e-12 * speed)
    # Bounces off the divider at (3.5 + 8k)/speed, off the box wall at (7.5 + 8k)/speed.
    n_walls = sim.counts.wall_collisions if hasattr(sim, "counts") else sim.wall_collisions
    expected = math.floor((speed - 3.5) / 8) + 1 + math.floor((speed - 7.5) / 8) + 1
    assert n_walls == expected


def test_piston_pushes_and_keeps_its_speed(backend):
    # An immovable disk moving at 1 hits a light disk at rest: elastic collision with an
    # infinite mass gives the light disk 2V - v = 2, the piston is unaffected.
    sim = backend([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]], radii=1.0,
                  masses=[math.inf, 1.0], box=WALLED)
    sim.advance(until=2.0)
    np.testing.assert_allclose(sim.velocities, [[1.0, 0.0], [2.0, 0.0]], atol=1e-15)
    # Contact at t = 1 (gap 1 at speed 1); the light disk then runs at 2 for 1.
    np.testing.assert_allclose(sim.positions, [[4.0, 5.0], [7.0, 5.0]], atol=1e-14)


def test_fixed_peg_reflects(backend):
    sim = backend([[2.0, 5.0], [6.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]], radii=1.0,
                  masses=[1.0, math.inf], box=WALLED)
    sim.advance(until=4.0)
    np.testing.assert_allclose(sim.velocities, [[-1.0, 0.0], [0.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(sim.positions[0], [2.0, 5.0], atol=1e-14)
    assert sim.kinetic_energy() == pytest.approx(0.5)


def test_two_immovable_disks_meeting_is_an_error(backend):
    sim = backend([[2.0, 5.0], [6.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]], radii=1.0,
                  masses=math.inf, box=WALLED)
    with pytest.raises(RuntimeError, match="immovable disks 0 and 1"):
        sim.advance(until=10.0)


def test_immovable_disk_reaching_a_wall_is_an_error():
    sim = ed.Simulation([[2.0, 5.0]], [[1.0, 0.0]], radii=1.0, masses=math.inf, box=WALLED)
    with pytest.raises(RuntimeError, match=r"immovable disk 0 .* box wall at x=width"):
        sim.advance(until=100.0)
    # It stopped before the contact, at its last processed event (a cell crossing).
    assert sim.time < 17.0
    assert sim.positions[0, 0] <= 19.0


@pytest.mark.parametrize("width", [1.2, 2.5, 3.5])
def test_small_periodic_boxes(backend, width):
    # 1, 2 and 3 cells on the periodic x axis.  Two disks moving apart along x meet again
    # through the boundary: the gap across it is width - 1 - ... closed at speed 2.
    box = ed.Box(width, 10.0, periodic=(True, False))
    sim = backend([[0.3, 5.0], [0.3 + 0.55, 5.0]], [[-1.0, 0.0], [1.0, 0.0]], radii=0.25,
                  box=box)
    sim.advance(collisions=1)
    gap = width - 0.55 - 0.5
    assert sim.time == pytest.approx(gap / 2.0, rel=1e-13)
    np.testing.assert_allclose(sim.velocities, [[1.0, 0.0], [-1.0, 0.0]], atol=1e-15)


@pytest.mark.parametrize("cell_size", [None, 1.65])
def test_tiny_periodic_box_matches_reference(cell_size):
    # A 1.7 x 1.9 periodic box (1 x 1 or 1 x 2 cells): every image is a neighbour, and
    # the pair meets through the boundaries many times.  Same events as the reference.
    from edmd2d.reference import ReferenceSimulation

    box = ed.Box(1.7, 1.9, periodic=True)
    args = ([[0.2, 0.3], [1.1, 1.2]], [[0.31, -0.7], [-0.4, 0.25]], [0.3, 0.2])
    sim = ed.Simulation(*args, box=box, cell_size=cell_size)
    if cell_size is not None:
        assert tuple(sim._gi[:2]) == (1, 1)
    sim._record_events(1000)
    ref = ReferenceSimulation(*args, box=box)
    # Rounding differences grow ~10x per collision in so tight a box (chaos): after 7
    # collisions they are still ~1e-11, after 11 about 1e-6.
    sim.advance(until=10.0)
    ref.advance(until=10.0)
    assert sim.counts.collisions == ref.collisions >= 7
    assert [e[1:] for e in _canonical(sim._recorded_events())] == [
        e[1:] for e in _canonical(ref.events)]
    np.testing.assert_allclose(sim.velocities, ref.velocities, atol=1e-9)


def _canonical(events):
    return [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
            for t, k, i, j in events]
