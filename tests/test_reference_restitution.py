"""Inelastic collisions and the TC model in the brute-force reference, against hand values.

Most set-ups use dyadic numbers, so contact times and velocities are exact in float64;
the tolerances are at rounding level all the same.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import random_system, seed_of
from edmd2d.reference import ReferenceSimulation

WALLED = ed.Box(20.0, 20.0, periodic=False)
WALL_BOX = ed.Box(10.0, 10.0, periodic=False)
DIVIDER = ed.Wall((5.0, 0.0), (5.0, 5.0))


def test_head_on_equal_masses():
    # Relative speed 2 along n = (-1, 0): vn = -2, each disk gets (1+e)/2 vn = -1.5 of
    # it, so 1 -> -0.5 and -1 -> 0.5.  Lost: (1 - e^2)/2 mu vn^2 = 0.375 * 0.5 * 4.
    ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
                              radii=1.0, box=WALLED, restitution=0.5)
    p0 = ref.momentum()
    ref.advance(collisions=1)
    assert ref.time == pytest.approx(0.5, abs=1e-15)
    np.testing.assert_allclose(ref.velocities, [[-0.5, 0.0], [0.5, 0.0]], rtol=0, atol=1e-15)
    assert ref.dissipated == pytest.approx(0.75, rel=1e-15)
    assert ref.kinetic_energy() == pytest.approx(0.25, rel=1e-15)
    np.testing.assert_allclose(ref.momentum(), p0, rtol=0, atol=1e-15)
    assert ref.t_last == [0.5, 0.5]


def test_head_on_unequal_masses():
    # m = 1, 3; vn = -2.  v1' = 1 - 1.5 * 3/4 * 2 = -1.25, v2' = -1 + 1.5 * 1/4 * 2 = -0.25:
    # momentum -2 kept, relative velocity -1 = -e * 2.  KE 2 -> 0.875, lost 1.125 =
    # (1 - 1/4)/2 * (3/4) * 4.
    ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
                              radii=1.0, masses=[1.0, 3.0], box=WALLED, restitution=0.5)
    ref.advance(collisions=1)
    np.testing.assert_allclose(ref.velocities, [[-1.25, 0.0], [-0.25, 0.0]], rtol=0,
                               atol=1e-15)
    np.testing.assert_allclose(ref.momentum(), [-2.0, 0.0], rtol=0, atol=1e-15)
    assert ref.kinetic_energy() == pytest.approx(0.875, rel=1e-15)
    assert ref.dissipated == pytest.approx(1.125, rel=1e-15)


def test_oblique_unequal_masses_conserves_momentum_and_energy_balance():
    # A glancing hit: the tangential relative velocity is kept, the normal one becomes -e
    # times itself, and the energy lost is (1 - e^2)/2 mu vn^2.
    m = [2.0, 0.5]
    ref = ReferenceSimulation([[1.0, 5.0], [6.0, 6.2]], [[1.5, 0.1], [-0.2, 0.0]],
                              radii=[1.0, 0.8], masses=m, box=WALLED, restitution=0.3)
    p0, e0 = ref.momentum(), ref.kinetic_energy()
    ref.advance(collisions=1)
    before = np.array([[1.5, 0.1], [-0.2, 0.0]])
    n = ref.positions[0] - ref.positions[1]
    assert np.hypot(*n) == pytest.approx(1.8, rel=1e-14)  # touching at the event
    n /= np.hypot(*n)
    t = np.array([-n[1], n[0]])
    dv0, dv1 = before[0] - before[1], ref.velocities[0] - ref.velocities[1]
    assert dv1 @ n == pytest.approx(-0.3 * (dv0 @ n), rel=1e-13)
    assert dv1 @ t == pytest.approx(dv0 @ t, rel=1e-13)
    np.testing.assert_allclose(ref.momentum(), p0, rtol=0, atol=1e-15)
    mu = m[0] * m[1] / (m[0] + m[1])
    assert ref.dissipated == pytest.approx((1 - 0.3**2) / 2 * mu * (dv0 @ n) ** 2, rel=1e-13)
    assert ref.kinetic_energy() + ref.dissipated == pytest.approx(e0, rel=1e-15)


@pytest.mark.parametrize("vel, after", [
    ([-1.0, 0.5], [0.7, 0.5]),     # wall x = 0 at t = 1
    ([1.0, 0.5], [-0.7, 0.5]),     # x = width
    ([0.5, -1.0], [0.5, 0.7]),     # y = 0
    ([0.5, 1.0], [0.5, -0.7]),     # y = height
])
def test_box_wall(vel, after):
    # The normal component 1 becomes -0.7; m = 2 loses (1 - 0.49)/2 * 2 * 1 = 0.51.
    start = [2.0 if vel[0] < 0 else 8.0, 2.0 if vel[1] < 0 else 8.0]
    ref = ReferenceSimulation([start], [vel], radii=1.0, masses=2.0, box=WALL_BOX,
                              wall_restitution=0.7)
    ref.advance(until=1.5)
    assert ref.wall_collisions == 1
    assert ref.events[0][0] == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(ref.velocities, [after], rtol=0, atol=1e-15)
    assert ref.dissipated == pytest.approx(0.51, rel=1e-15)
    assert ref.t_last == [ref.events[0][0]]


def test_segment_side():
    # Reaches the divider's side (x = 4.5) at t = 2.5, y = 3.125: vx 1 -> -0.7, vy kept.
    ref = ReferenceSimulation([[2.0, 2.5]], [[1.0, 0.25]], radii=0.5, box=WALL_BOX,
                              walls=[DIVIDER], wall_restitution=0.7)
    ref.advance(until=3.0)
    assert [e[1:] for e in ref.events] == [("wall", 0, 0)]
    assert ref.events[0][0] == pytest.approx(2.5, rel=1e-15)
    np.testing.assert_allclose(ref.velocities, [[-0.7, 0.25]], rtol=0, atol=1e-15)
    np.testing.assert_allclose(ref.positions, [[4.5 - 0.35, 3.25]], rtol=0, atol=1e-14)
    assert ref.dissipated == pytest.approx(0.5 * 0.51, rel=1e-15)


def test_segment_end_point_head_on():
    # Aimed straight at the end point (5, 5): the whole velocity is normal, -> -0.7 u.
    u = np.array([3.0, -2.0]) / math.sqrt(13.0)
    ref = ReferenceSimulation([[2.0, 7.0]], [u], radii=0.5, box=WALL_BOX, walls=[DIVIDER],
                              wall_restitution=0.7)
    t_hit = math.sqrt(13.0) - 0.5
    ref.advance(until=t_hit + 1.0)
    # The contact point, hence the normal, carries the rounding of coordinates ~5.
    np.testing.assert_allclose(ref.velocities, [-0.7 * u], rtol=0, atol=1e-14)
    np.testing.assert_allclose(ref.positions, [[5.0, 5.0] - u * (0.5 + 0.7)], atol=1e-13)
    assert ref.dissipated == pytest.approx(0.5 * 0.51, rel=1e-14)


def test_segment_end_point_glancing():
    # 0.3 above the end point: normal (-0.8, 0.6), v.n = -0.8, so
    # v' = (1, 0) - 1.7 (-0.8) (-0.8, 0.6) = (-0.088, 0.816); lost 0.5 * 0.51 * 0.64.
    ref = ReferenceSimulation([[1.0, 5.3]], [[1.0, 0.0]], radii=0.5, box=WALL_BOX,
                              walls=[DIVIDER], wall_restitution=0.7)
    ref.advance(until=3.6 + 1.0)
    np.testing.assert_allclose(ref.velocities, [[-0.088, 0.816]], rtol=0, atol=1e-14)
    assert ref.dissipated == pytest.approx(0.1632, rel=1e-14)
    assert ref.kinetic_energy() == pytest.approx(0.5 - 0.1632, rel=1e-14)


def test_species_table_picks_each_pairs_coefficient():
    # Five lanes, in each a disk at speed 1 hits an equal one at rest at t = 1:
    # afterwards (1 - e)/2 and (1 + e)/2.  Every entry of the table differs, and the
    # (2, 0) lane reads the table the other way round from (0, 2).
    table = [[0.9, 0.6, 0.3],
             [0.6, 0.8, 0.5],
             [0.3, 0.5, 0.4]]
    pairs = [(0, 0), (0, 1), (1, 2), (2, 0), (2, 2)]
    pos, vel, species = [], [], []
    for lane, (a, b) in enumerate(pairs):
        y = 2.0 + 3.0 * lane
        pos += [[2.0, y], [5.0, y]]
        vel += [[1.0, 0.0], [0.0, 0.0]]
        species += [a, b]
    ref = ReferenceSimulation(pos, vel, radii=1.0, box=WALLED, species=species,
                              restitution=np.array(table))
    ref.advance(until=1.5)
    assert ref.collisions == len(pairs)
    want = []
    for a, b in pairs:
        e = table[a][b]
        want += [[(1 - e) / 2, 0.0], [(1 + e) / 2, 0.0]]
    np.testing.assert_allclose(ref.velocities, want, rtol=0, atol=1e-15)
    lost = sum((1 - table[a][b] ** 2) / 2 * 0.5 * 1.0 for a, b in pairs)
    assert ref.dissipated == pytest.approx(lost, rel=1e-14)


def _chain(tc, reverse=False):
    # A (x = 2, speed 1) hits B at rest (x = 5) at t = 1: A 0.25, B 0.75.  B then closes
    # the gap of 0.375 to C (x = 7.375) in 0.5: the second collision is at t = 1.5.
    # ``reverse`` numbers the disks C, B, A, so that B is the second disk of that pair.
    # Returns the simulation and the order A, B, C of its rows.
    pos = [[2.0, 5.0], [5.0, 5.0], [7.375, 5.0]]
    vel = [[1.0, 0.0], [0.0, 0.0], [0.0, 0.0]]
    order = [2, 1, 0] if reverse else [0, 1, 2]
    ref = ReferenceSimulation([pos[k] for k in order], [vel[k] for k in order], radii=1.0,
                              box=WALLED, restitution=0.5, tc=tc).advance(collisions=2)
    return ref, order


@pytest.mark.parametrize("reverse", [False, True])
def test_tc_rule_second_collision_within_tc_is_elastic(reverse):
    ref, order = _chain(tc=0.75, reverse=reverse)  # 1.5 - 1.0 < 0.75: B, C swap velocities
    assert [e[0] for e in ref.events] == [1.0, 1.5]
    np.testing.assert_allclose(ref.velocities[order], [[0.25, 0.0], [0.0, 0.0], [0.75, 0.0]],
                               rtol=0, atol=1e-15)
    assert ref.dissipated == pytest.approx(0.1875, rel=1e-15)  # the first collision only
    assert [ref.t_last[k] for k in order] == [1.0, 1.5, 1.5]


@pytest.mark.parametrize("reverse", [False, True])
@pytest.mark.parametrize("tc", [0.0, 0.25, 0.5])  # 0.5: the rule is strict, 0.5 < 0.5 fails
def test_tc_rule_second_collision_after_tc_is_inelastic(tc, reverse):
    ref, order = _chain(tc=tc, reverse=reverse)
    # B 0.75 -> 0.75 * 0.25, C -> 0.75 * 0.75; lost 0.1875 + 0.375 * 0.5 * 0.5625.
    np.testing.assert_allclose(ref.velocities[order],
                               [[0.25, 0.0], [0.1875, 0.0], [0.5625, 0.0]], rtol=0, atol=1e-15)
    assert ref.dissipated == pytest.approx(0.1875 + 0.10546875, rel=1e-15)


def test_tc_rule_counts_wall_collisions():
    # A (x = 2, speed -1) hits the wall x = 0 at t = 1 (-> 0.5), then B at rest at
    # x = 3.25 at t = 1.5: elastic for tc = 0.75 (A stops), inelastic for tc = 0.25.
    def run(tc):
        return ReferenceSimulation([[2.0, 5.0], [3.25, 5.0]], [[-1.0, 0.0], [0.0, 0.0]],
                                   radii=1.0, box=WALLED, restitution=0.5,
                                   wall_restitution=0.5, tc=tc).advance(collisions=1)
    elastic, inelastic = run(0.75), run(0.25)
    assert [e[:2] for e in elastic.events] == [(1.0, "box"), (1.5, "disk")]
    np.testing.assert_allclose(elastic.velocities, [[0.0, 0.0], [0.5, 0.0]], rtol=0,
                               atol=1e-15)
    np.testing.assert_allclose(inelastic.velocities, [[0.125, 0.0], [0.375, 0.0]], rtol=0,
                               atol=1e-15)
    # The wall collision itself, 0.75/2 * 1 * 1, is inelastic in both runs.
    assert elastic.dissipated == pytest.approx(0.375, rel=1e-15)


def test_tc_rule_a_wall_collision_within_tc_is_elastic():
    # B leaves the collision with A at t = 1 at speed 0.75 and reaches the box wall
    # (centre at x = 19) after 14 / 0.75: within tc it bounces back at full speed.
    def run(tc):
        return ReferenceSimulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [0.0, 0.0]],
                                   radii=1.0, box=WALLED, restitution=0.5,
                                   wall_restitution=0.5, tc=tc).advance(until=20.0)
    within, after = run(20.0), run(15.0)
    assert [e[1] for e in within.events] == ["disk", "box"]
    assert within.velocities[1, 0] == pytest.approx(-0.75, rel=1e-15)
    assert after.velocities[1, 0] == pytest.approx(-0.375, rel=1e-15)


def test_immovable_disk_does_not_trigger_the_tc_rule():
    # A peg at x = 5 is hit by A from the left at t = 1 and by B from the right at
    # t = 1.5, within tc of the first hit: both hits are inelastic (the peg keeps no
    # collision time), each losing (1 - e^2)/2 * m * vn^2 = 0.375.
    ref = ReferenceSimulation([[2.0, 5.0], [5.0, 5.0], [8.5, 5.0]],
                              [[1.0, 0.0], [0.0, 0.0], [-1.0, 0.0]], radii=1.0,
                              masses=[1.0, math.inf, 1.0], box=WALLED, restitution=0.5,
                              tc=1.0)
    ref.advance(collisions=2)
    assert [e[0] for e in ref.events] == [1.0, 1.5]
    np.testing.assert_allclose(ref.velocities, [[-0.5, 0.0], [0.0, 0.0], [0.5, 0.0]],
                               rtol=0, atol=1e-15)
    assert ref.dissipated == pytest.approx(0.75, rel=1e-15)
    assert ref.t_last == [1.0, -math.inf, 1.5]


def test_immovable_disk_and_the_tc_rule_of_its_partner():
    # A disk that has just hit a peg hits another disk within tc: elastic (its own
    # collision time counts, whoever the partner was).  A (x = 5, speed 1) reflects from
    # the peg at x = 8 at t = 1 with speed 0.5 and meets B (x = 3.75) at t = 1.5.
    ref = ReferenceSimulation([[5.0, 5.0], [8.0, 5.0], [3.75, 5.0]],
                              [[1.0, 0.0], [0.0, 0.0], [0.0, 0.0]], radii=1.0,
                              masses=[1.0, math.inf, 1.0], box=WALLED,
                              restitution=0.5, tc=1.0)
    ref.advance(collisions=2)
    assert [e[0] for e in ref.events] == [1.0, 1.5]
    np.testing.assert_allclose(ref.velocities, [[0.0, 0.0], [0.0, 0.0], [-0.5, 0.0]],
                               rtol=0, atol=1e-15)


def test_e_one_is_the_elastic_collision():
    # Oblique, unequal masses, e = 1 given explicitly with tc > 0 and a table of ones:
    # the textbook v_i' = v_i - 2 m_j/(m_i+m_j) (dv.n) n, nothing dissipated, and the
    # same bits as with the defaults.
    args = ([[1.0, 5.0], [6.0, 6.2]], [[1.5, 0.1], [-0.2, 0.0]])
    kw = dict(radii=[1.0, 0.8], masses=[2.0, 0.5], box=WALLED)
    ref = ReferenceSimulation(*args, **kw, species=[0, 1], restitution=np.ones((2, 2)),
                              tc=0.5).advance(collisions=1)
    n = ref.positions[0] - ref.positions[1]
    n /= np.hypot(*n)
    v0, v1 = np.array(args[1])
    vn = (v0 - v1) @ n
    want = [v0 - 2 * 0.5 / 2.5 * vn * n, v1 + 2 * 2.0 / 2.5 * vn * n]
    np.testing.assert_allclose(ref.velocities, want, rtol=0, atol=1e-15)
    assert ref.dissipated == 0.0
    default = ReferenceSimulation(*args, **kw).advance(collisions=1)
    assert ref.v == default.v and ref.p == default.p and ref.events == default.events


def test_e_one_same_bits_as_defaults_over_a_random_run():
    # Elastic coefficients given explicitly (with the TC rule switched on) change nothing.
    rng = np.random.default_rng(seed_of(7))
    box = ed.Box(6.0, 5.0, periodic=False)
    walls = [ed.Wall((3.0, 1.0), (3.0, 4.0))]
    pos, vel, rad, mass = random_system(rng, 8, box, walls)
    a = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls).advance(until=3.0)
    b = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, species=[1] * len(pos),
                            restitution=[[0.1, 0.2], [0.2, 1.0]], wall_restitution=1.0,
                            tc=0.05).advance(until=3.0)
    assert len(a.events) > 20
    assert a.events == b.events and a.p == b.p and a.v == b.v
    assert b.dissipated == 0.0


@pytest.mark.parametrize("seed", range(4))
def test_energy_balance_over_a_random_inelastic_run(seed):
    # A walled box with a divider, a fixed peg at rest, two species: the kinetic energy
    # plus what was dissipated stays put (an immovable disk at rest does no work).
    rng = np.random.default_rng(seed)
    box = ed.Box(6.0, 5.0, periodic=False)
    walls = [ed.Wall((3.0, 1.0), (3.0, 4.0))]
    pos, vel, rad, mass = random_system(rng, 14, box, walls)
    mass[0], vel[0] = math.inf, 0.0
    species = np.arange(len(pos)) % 2
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, species=species,
                              restitution=[[0.9, 0.6], [0.6, 0.75]], wall_restitution=0.8,
                              tc=1e-3)
    e0 = ref.kinetic_energy()
    for t in (0.5, 1.5, 3.0):
        ref.advance(until=t)
        assert ref.kinetic_energy() + ref.dissipated == pytest.approx(e0, rel=1e-13)
    assert ref.collisions > 20 and ref.wall_collisions > 20
    assert any(kind == "disk" and 0 in (i, j) for _, kind, i, j in ref.events)  # the peg
    assert ref.dissipated > 0.5 * e0


def test_momentum_kept_in_a_random_inelastic_periodic_run():
    rng = np.random.default_rng(seed_of(11))
    box = ed.Box(5.0, 5.0, periodic=True)
    pos, vel, rad, mass = random_system(rng, 8, box)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, restitution=0.6, tc=1e-3)
    p0, e0 = ref.momentum(), ref.kinetic_energy()
    while ref.collisions <= 10 and ref.time < 100.0:  # (a run of at least 11 collisions)
        ref.advance(until=ref.time + 1.0)
    assert ref.collisions > 10
    np.testing.assert_allclose(ref.momentum(), p0, rtol=0, atol=1e-13)
    assert ref.kinetic_energy() + ref.dissipated == pytest.approx(e0, rel=1e-13)
    assert ref.dissipated > 0.1 * e0
