"""Disks that come to rest under gravity (edmd2d.physics.Resting, _engine/resting.py)."""

import copy

import numpy as np
import pytest

import edmd2d
from edmd2d import Box, Simulation, make_gas, physics

G = (0.0, -1.0)
INELASTIC = dict(restitution=0.9, wall_restitution=0.9, gravity=G)


def books(sim, e0):
    """Kinetic + potential + dissipated energy less its start (0 to rounding)."""
    return sim.total_energy() + sim.dissipated_energy() - e0


def held_by_statics(sim, i, gap):
    """An independent check that resting disk ``i`` is held: the direction against
    gravity lies strictly inside the cone of the normals of the static bodies within
    ``gap`` of it (resting disks, immovable disks, box walls), or one is a box wall
    whose normal points against gravity."""
    pos = sim.positions
    rad = sim.radii
    up = -np.asarray(G) / np.hypot(*G)
    normals = []
    for axis, inward in [(0, 1), (0, -1), (1, 1), (1, -1)]:
        c = pos[i, axis]
        g = c - rad[i] if inward > 0 else sim.box.size[axis] - rad[i] - c
        if g <= gap:
            n = np.zeros(2)
            n[axis] = inward
            if np.array_equal(n, up):
                return True
            normals.append(n)
    static = sim.resting | np.isinf(sim.masses)
    for j in np.flatnonzero(static):
        if j == i:
            continue
        d = pos[i] - pos[j]
        if np.hypot(*d) - rad[i] - rad[j] <= gap:
            normals.append(d / np.hypot(*d))
    angles = [np.arctan2(up[0] * n[1] - up[1] * n[0], up @ n) for n in normals]
    neg = [a for a in angles if a < 0]
    pos_ = [a for a in angles if a > 0]
    return bool(neg and pos_ and min(pos_) - max(neg) < np.pi)


def test_resting_is_on_by_default_only_for_inelastic_disks_under_gravity():
    gas = dict(n=20, packing_fraction=0.1, periodic=False, seed=1)
    assert "resting" in make_gas(**gas, **INELASTIC).families
    assert "resting" not in make_gas(**gas, gravity=G).families  # elastic
    assert "resting" not in make_gas(**gas, restitution=0.9).families  # no gravity
    assert "resting" not in make_gas(**gas, **INELASTIC, resting=False).families
    sim = make_gas(**gas, gravity=G, resting=True)
    rest = sim.families["resting"]
    assert rest.height == pytest.approx(1e-3 * 2.0 * sim.radii.min())
    assert rest.speed == pytest.approx(np.sqrt(2.0 * 1.0 * rest.height))
    custom = make_gas(**gas, **INELASTIC, rest_height=0.01).families["resting"]
    assert custom.height == 0.01 and custom.gap == 0.01


@pytest.mark.parametrize("kwargs, error, word", [
    (dict(resting=True), ValueError, "gravity"),
    (dict(resting="yes", gravity=G), TypeError, "resting"),
    (dict(rest_height=-1.0, **INELASTIC), ValueError, "rest_height"),
    (dict(rest_height=0.0, **INELASTIC), ValueError, "rest_height"),
    (dict(rest_height=np.nan, **INELASTIC), ValueError, "rest_height"),
])
def test_bad_resting_arguments_are_refused_by_name(kwargs, error, word):
    with pytest.raises(error, match=word):
        Simulation([[2.0, 2.0]], [[0.0, 0.0]], 0.5, box=Box(4, 4, periodic=False), **kwargs)


def drop(x, y, extra=(), **kwargs):
    """One disk dropped from ``(x, y)`` in a 6 x 20 walled box, with immovable pegs
    ``extra`` (centres, radius 0.5)."""
    pos = [[x, y], *extra]
    mass = [1.0] + [np.inf] * len(extra)
    return Simulation(pos, np.zeros((len(pos), 2)), 0.5, masses=mass,
                      box=Box(6, 20, periodic=False), **INELASTIC, **kwargs)


def test_a_dropped_disk_comes_to_rest_on_the_floor_and_then_costs_nothing():
    sim = drop(3.0, 10.0)
    e0 = sim.total_energy()
    sim.advance(until=100.0)
    assert sim.resting[0] and sim.counts.rests >= 1
    assert sim.kinetic_energy() == 0.0
    assert sim.positions[0, 1] == pytest.approx(0.5, abs=1e-3)
    assert books(sim, e0) == pytest.approx(0.0, abs=1e-12 * e0)
    events = sim.counts.events
    sim.advance(until=1000.0)
    assert sim.counts.events == events  # a disk at rest has no event


def test_a_disk_comes_to_rest_in_a_pocket_between_two_pegs():
    pegs = [(2.45, 3.0), (3.55, 3.0)]  # a gap narrower than a diameter between them
    sim = drop(3.02, 3.9, pegs)  # (too soft a landing to bounce out of the pocket)
    e0 = sim.total_energy()
    sim.advance(until=100.0)
    assert sim.resting[0]
    assert sim.positions[0, 1] > 3.0  # held by the pegs, above them
    assert held_by_statics(sim, 0, sim.families["resting"].gap)
    assert books(sim, e0) == pytest.approx(0.0, abs=1e-12 * e0)


def test_a_disk_on_a_single_peg_slides_off_it():
    sim = drop(3.3, 4.2, [(3.0, 3.0)])  # lands off-centre on one peg
    # (It then slides along the frictionless floor, slowed only by the side walls.)
    sim.advance(until=2000.0)
    assert sim.resting[0]
    assert sim.positions[0, 1] == pytest.approx(0.5, abs=1e-3)  # on the floor, not the peg


def settled_row(n=5, **kwargs):
    """``n`` disks side by side just above the floor of a walled box, and one more
    falling from high above onto the middle of the row."""
    x = 1.0 + np.arange(n) * 1.0005
    pos = np.column_stack([x, np.full(n, 0.5001)])
    pos = np.vstack([pos, [x[n // 2] + 0.2, 15.0]])
    return Simulation(pos, np.zeros((n + 1, 2)), 0.5, box=Box(n + 2.0, 20.0, periodic=False),
                      **INELASTIC, **kwargs)


def test_an_impact_wakes_the_disks_at_rest_and_they_settle_again():
    sim = settled_row()
    e0 = sim.total_energy()
    sim.advance(until=4.0)  # the row is at rest before the falling disk arrives
    assert sim.resting[:-1].all() and not sim.resting[-1]
    sim.advance(until=200.0)
    assert sim.counts.wakes >= 1  # the impact woke the row
    assert sim.resting.all()
    assert sim.kinetic_energy() == 0.0
    assert books(sim, e0) == pytest.approx(0.0, abs=1e-12 * e0)
    for i in range(len(sim)):
        assert held_by_statics(sim, i, sim.families["resting"].gap)


def test_without_resting_the_same_row_stops_with_an_inelastic_collapse():
    sim = settled_row(resting=False, tc=0.0)
    with pytest.raises(RuntimeError, match="inelastic collapse"):
        sim.advance(until=200.0)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_poured_bed_settles_with_the_energy_books_holding(seed):
    sim = make_gas(60, 0.15, periodic=False, aspect=0.5, seed=seed, **INELASTIC)
    e0 = sim.total_energy()
    k0 = sim.kinetic_energy()
    sim.advance(until=100.0)
    assert sim.kinetic_energy() < 1e-4 * k0
    assert sim.resting.mean() > 0.9
    assert books(sim, e0) == pytest.approx(0.0, abs=1e-12 * abs(e0))
    gap = sim.families["resting"].gap
    d = np.hypot(*(sim.positions[:, None] - sim.positions[None]).transpose(2, 0, 1))
    np.fill_diagonal(d, np.inf)
    assert d.min() >= 1.0 - 1e-9  # no overlap
    for i in np.flatnonzero(sim.resting):
        assert held_by_statics(sim, i, gap), i


def test_a_copy_made_while_settling_continues_bit_identically():
    sim = make_gas(60, 0.15, periodic=False, aspect=0.5, seed=4, **INELASTIC)
    sim.advance(until=20.0)  # settling: some at rest, some in flight
    assert 0 < sim.resting.sum() < len(sim)
    twin = copy.deepcopy(sim)
    sim.advance(until=40.0)
    twin.advance(until=22.5)
    twin.advance(until=40.0)
    assert np.array_equal(sim.positions, twin.positions)
    assert np.array_equal(sim.velocities, twin.velocities)
    assert np.array_equal(sim.resting, twin.resting)
    assert sim.counts == twin.counts


def test_setting_velocities_wakes_the_bed():
    sim = settled_row()
    sim.advance(until=4.0)
    assert sim.resting.sum() == 5
    sim.set_velocities(np.zeros((len(sim), 2)))
    assert not sim.resting.any()
    assert sim.counts.wakes >= 5
    e1 = sim.total_energy() + sim.dissipated_energy()
    sim.advance(until=200.0)
    assert sim.resting.all()
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e1, abs=1e-9)


def test_a_bounce_on_the_floor_slower_than_the_rest_speed_ends_at_rest():
    """With wall restitution e the rebound speeds are e^k v0; the first rebound slower
    than sqrt(2 g h) leaves the disk on the floor, at rest: the count of bounces
    follows in closed form, and no event comes after."""
    g, h0, e = 1.0, 4.5, 0.5
    sim = Simulation([[5.0, 0.5 + h0]], [[0.0, 0.0]], 0.5, box=Box(10, 10, periodic=False),
                     gravity=(0.0, -g), wall_restitution=e)
    v_rest = sim.families["resting"].speed
    e0 = sim.total_energy()
    sim.advance(until=100.0)
    v0 = np.sqrt(2.0 * g * h0)
    bounces = next(m for m in range(1, 100) if e**m * v0 < v_rest)
    assert sim.counts.wall_collisions == bounces
    assert sim.resting[0] and sim.counts.rests == 1
    sim.advance(until=1e6)
    assert sim.counts.events == bounces
    assert sim.positions[0, 1] == pytest.approx(0.5, abs=1e-12)
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e0, rel=1e-12)


def test_a_disk_on_a_disk_on_the_floor_comes_to_rest_where_it_once_collapsed():
    """The stack that stops with an inelastic collapse without resting
    (tests/test_gravity.py), the upper disk a thousandth of a diameter off the top
    (exactly above, it would balance for ever): the lower disk rests on the floor; the
    upper one, with a single support, slides off it in soft bounces and comes to rest
    on the floor beside it."""
    sim = Simulation([[5.0, 0.5], [5.001, 1.5]], [[0.0, 0.0], [0.0, 0.0]], 0.5,
                     box=Box(10, 10, periodic=False), gravity=G, restitution=0.5,
                     wall_restitution=0.5, tc=1e-4)
    e0 = sim.total_energy()
    sim.advance(until=1000.0)
    assert sim.resting.all()
    assert sim.positions[1, 1] == pytest.approx(0.5, abs=1e-3)
    assert books(sim, e0) == pytest.approx(0.0, abs=1e-12)
    assert np.hypot(*(sim.positions[0] - sim.positions[1])) >= 1.0 - 1e-9


def test_the_physics_module_lists_resting():
    assert physics.FAMILIES["resting"] is physics.Resting
    assert edmd2d.physics.KEYWORDS["rest_height"].kind == "length"
