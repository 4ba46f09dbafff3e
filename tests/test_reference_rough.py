"""Rough disks in the reference engine (``reference/_rough.py``): the collision rule,
its conservation laws and energy books, Coulomb's limit, rough walls, equipartition,
and smooth disks left exactly as they were.

The reference is the oracle the compiled engine will be checked against, event for
event; these tests check the oracle itself against the laws it must obey.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d.reference import ReferenceSimulation


def contact_velocities(ref, i, j):
    """``(g_n, g_t)`` of the contact points of ``i`` and ``j`` (normal from ``j`` to
    ``i``, nearest image)."""
    d = ref.positions[i] - ref.positions[j]
    size = np.array([ref.box.width, ref.box.height])
    d -= size * np.round(d / size) * np.array(ref.box.periodic)
    n = d / np.hypot(*d)
    t = np.array([-n[1], n[0]])
    w = ref.angular_velocities
    g = ref.velocities[i] - ref.velocities[j]
    return g @ n, g @ t - (ref.r[i] * w[i] + ref.r[j] * w[j])


def two_disks(beta=0.4, e=0.8, friction=math.inf, spins=(1.5, -0.7)):
    """Disk 0 (radius 0.5, mass 1) flying at disk 1 (radius 0.8, mass 2.5) off
    centre, both spinning, in a box too big to reach."""
    return ReferenceSimulation(
        [[2.0, 5.1], [4.0, 4.6]], [[1.0, 0.2], [-0.3, 0.1]], [0.5, 0.8], [1.0, 2.5],
        box=ed.Box(20.0, 20.0, periodic=False), restitution=e,
        tangential_restitution=beta, friction=friction, inertia=[0.5, 0.4],
        angular_velocities=list(spins))


@pytest.mark.parametrize("beta, e", [(0.4, 0.8), (1.0, 1.0), (-0.3, 1.0), (0.0, 0.5)])
def test_a_collision_reverses_the_contact_velocity_and_conserves_momenta(beta, e):
    ref = two_disks(beta, e)
    ref.advance(collisions=1)
    assert ref.collisions == 1
    # (advance stops right after the collision: the contact state before it is
    # that of a copy run just short of it.)
    t_hit = ref.events[-1][0]
    before = two_disks(beta, e).advance(until=t_hit * (1 - 1e-15))
    gn0, gt0 = contact_velocities(before, 0, 1)
    gn1, gt1 = contact_velocities(ref, 0, 1)
    assert gn0 < 0
    assert gn1 == pytest.approx(-e * gn0, rel=1e-9)
    assert gt1 == pytest.approx(-beta * gt0, rel=1e-9, abs=1e-12)
    np.testing.assert_allclose(ref.momentum(), before.momentum(), rtol=1e-13)
    assert ref.angular_momentum(ref.positions) == pytest.approx(
        before.angular_momentum(before.positions), rel=1e-12)
    total = ref.kinetic_energy() + ref.rotational_energy() + ref.dissipated
    assert total == pytest.approx(before.kinetic_energy() + before.rotational_energy(),
                                  rel=1e-13)
    if e == 1.0 and abs(beta) == 1.0:
        assert abs(ref.dissipated) < 1e-14


def test_coulomb_friction_caps_the_tangential_impulse():
    slide = two_disks(beta=1.0, e=0.8, friction=0.05)
    slide.advance(collisions=1)
    t_hit = slide.events[-1][0]
    before = two_disks(beta=1.0, e=0.8, friction=0.05).advance(until=t_hit * (1 - 1e-15))
    gn0, gt0 = contact_velocities(before, 0, 1)
    gn1, gt1 = contact_velocities(slide, 0, 1)
    # The normal impulse on disk 0 is (1 + e) mu |g_n|; its tangential one mu_f times it,
    # against g_t: the tangential momentum change of disk 0 says which.
    mu = 1.0 * 2.5 / 3.5
    jn = (1.0 + 0.8) * mu * abs(gn0)
    n = before.positions[0] - before.positions[1]
    n /= np.hypot(*n)
    t = np.array([-n[1], n[0]])
    jt = (slide.velocities[0] - before.velocities[0]) @ t * 1.0
    assert jt == pytest.approx(-math.copysign(0.05 * jn, gt0), rel=1e-9)
    assert abs(gt1) < abs(gt0) and gt1 * gt0 > 0  # slowed, still sliding the same way
    total = slide.kinetic_energy() + slide.rotational_energy() + slide.dissipated
    assert total == pytest.approx(before.kinetic_energy() + before.rotational_energy(),
                                  rel=1e-13)


def test_a_spinning_disk_on_a_rough_floor():
    # A disk dropped spinning on a floor (elastic, perfectly rough): its contact point's
    # tangential velocity reverses, energy is kept, and it leaves sideways.
    for beta, e in ((1.0, 1.0), (0.2, 0.7)):
        ref = ReferenceSimulation([[5.0, 3.0]], [[0.0, -1.0]], 0.5, 1.0,
                                  box=ed.Box(10.0, 10.0, periodic=False), restitution=e,
                                  wall_restitution=e, tangential_restitution=beta,
                                  angular_velocities=4.0)
        ref.advance(until=2.45)  # the bounce is at t = 2.5
        v0, w0 = ref.velocities[0].copy(), ref.angular_velocities[0]
        ref.advance(until=2.55)
        assert ref.wall_collisions == 1
        v1, w1 = ref.velocities[0], ref.angular_velocities[0]
        # Floor normal (0, 1), tangent (-1, 0): g_t = -v_x - r w.
        assert -v1[0] - 0.5 * w1 == pytest.approx(-beta * (-v0[0] - 0.5 * w0), rel=1e-12)
        assert v1[1] == pytest.approx(-e * v0[1], rel=1e-12)
        assert v1[0] != 0.0
        total = ref.kinetic_energy() + ref.rotational_energy() + ref.dissipated
        assert total == pytest.approx(0.5 + 0.5 * 0.5 * 0.25 * 16.0, rel=1e-13)


@pytest.mark.parametrize("a, b", [((2.0, 1.0), (8.0, 1.0)), ((8.0, 1.0), (2.0, 1.0))])
def test_a_spinning_disk_on_a_rough_segment_either_way_round(a, b):
    # The same bounce on a wall segment at y = 1 (given in either direction: its
    # normal is taken towards the disk), and on the segment's end point.
    ref = ReferenceSimulation([[5.0, 3.0]], [[0.0, -1.0]], 0.5, 1.0,
                              box=ed.Box(10.0, 10.0, periodic=False),
                              walls=[ed.Wall(a, b)], tangential_restitution=1.0,
                              angular_velocities=4.0)
    ref.advance(until=1.45)  # the bounce is at t = 1.5
    v0, w0 = ref.velocities[0].copy(), ref.angular_velocities[0]
    ref.advance(until=1.55)
    assert ref.wall_collisions == 1
    v1, w1 = ref.velocities[0], ref.angular_velocities[0]
    assert -v1[0] - 0.5 * w1 == pytest.approx(-(-v0[0] - 0.5 * w0), rel=1e-12)
    assert v1[1] == pytest.approx(-v0[1], rel=1e-12)
    assert ref.kinetic_energy() + ref.rotational_energy() == pytest.approx(
        0.5 + 0.5 * 0.5 * 0.25 * 16.0, rel=1e-13)
    end = ReferenceSimulation([[1.8, 3.0]], [[0.0, -1.0]], 0.5, 1.0,
                              box=ed.Box(10.0, 10.0, periodic=False), walls=[ed.Wall(a, b)],
                              tangential_restitution=1.0, angular_velocities=4.0)
    end.advance(until=1.4)
    v0, w0 = end.velocities[0].copy(), end.angular_velocities[0]
    end.advance(until=1.6)
    v1, w1 = end.velocities[0], end.angular_velocities[0]
    assert end.wall_collisions == 1
    t_hit = end.events[-1][0]
    centre = end.positions[0] - v1 * (1.6 - t_hit)
    n = (centre - np.array([2.0, 1.0])) / 0.5  # (from the end point, at contact)
    assert np.hypot(*n) == pytest.approx(1.0, rel=1e-9) and abs(n[0]) > 0.3
    t = np.array([-n[1], n[0]])
    assert v1 @ t - 0.5 * w1 == pytest.approx(-(v0 @ t - 0.5 * w0), rel=1e-9)
    assert v1 @ n == pytest.approx(-(v0 @ n), rel=1e-9)


def test_spins_alone_leave_a_smooth_gas_as_it_was():
    # Smooth (beta = -1) but spinning: the translation is bit for bit the smooth run's,
    # each angle turns at its own rate.
    gas = ed.make_gas(30, 0.4, seed=seed_of(40))
    spins = np.linspace(-2.0, 2.0, 30)
    smooth = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box)
    spun = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                               angular_velocities=spins)
    smooth.advance(until=3.0)
    spun.advance(until=3.0)
    assert smooth.collisions > 50
    assert np.array_equal(smooth.positions, spun.positions)
    assert np.array_equal(smooth.velocities, spun.velocities)
    np.testing.assert_allclose(spun.angles, spins * 3.0, rtol=1e-12)
    np.testing.assert_array_equal(spun.angular_velocities, spins)


def test_energy_books_of_an_inelastic_rough_gas_with_rough_walls():
    gas = ed.make_gas(30, 0.35, periodic=False, seed=seed_of(41))
    ref = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                              restitution=0.9, wall_restitution=0.95,
                              tangential_restitution=0.3, friction=0.4,
                              wall_tangential_restitution=0.6, wall_friction=0.2)
    start = ref.kinetic_energy()
    ref.advance(until=6.0)
    assert ref.collisions > 100 and ref.wall_collisions > 10
    assert ref.rotational_energy() > 0.01 * ref.kinetic_energy()
    total = ref.kinetic_energy() + ref.rotational_energy() + ref.dissipated
    assert total == pytest.approx(start, rel=1e-12)


def test_angular_momentum_is_conserved_between_disks():
    # Disks converging in the middle of a big walled box, collide among themselves
    # and do not reach a wall: sum m r x v + sum I w stays.
    rng = np.random.default_rng(seed_of(42))
    pos = np.array([[20.0 + 1.3 * (k % 5), 20.0 + 1.3 * (k // 5)] for k in range(20)])
    vel = rng.normal(size=(20, 2)) + 0.3 * (np.array([22.6, 22.0]) - pos)
    ref = ReferenceSimulation(pos, vel, 0.5, 1.0, box=ed.Box(45.0, 45.0, periodic=False),
                              restitution=0.85, tangential_restitution=0.5,
                              angular_velocities=rng.normal(size=20))
    before = ref.angular_momentum(ref.positions)
    ref.advance(until=4.0)
    assert ref.collisions > 20 and ref.wall_collisions == 0
    assert ref.angular_momentum(ref.positions) == pytest.approx(before, abs=1e-11)


def test_a_perfectly_rough_elastic_gas_shares_its_energy_equally():
    # Equipartition (e = 1, beta = 1): the rotational temperature I <w^2> reaches the
    # translational one m <v_x^2>, from all spins at rest.  20 disks (20 rotational and
    # 38 translational degrees of freedom, momentum being conserved): the ratio of the
    # mean energies per degree of freedom has expectation 1 exactly; over 120 time
    # units (some 250 collisions per disk) it scattered by 0.045 over six seeds, and
    # 0.15 is 3.3 of that.
    gas = ed.make_gas(20, 0.3, seed=seed_of(43))
    ref = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                              tangential_restitution=1.0)
    start = ref.total_energy()
    ref.advance(until=20.0)
    spin, move = [], []
    for k in range(1, 121):
        ref.advance(until=20.0 + k)
        spin.append(ref.rotational_energy())
        move.append(ref.kinetic_energy())
    ratio = (np.mean(spin) / 20) / (np.mean(move) / 38)
    assert ratio == pytest.approx(1.0, abs=0.15)
    assert ref.total_energy() == pytest.approx(start, rel=1e-12)
    assert abs(ref.dissipated) < 1e-12


@pytest.mark.parametrize("kwargs, match", [
    (dict(tangential_restitution=1.5), "tangential_restitution"),
    (dict(wall_tangential_restitution=-2.0), "wall_tangential_restitution"),
    (dict(friction=-0.1), "friction"),
    (dict(inertia=0.0), "inertia"),
    (dict(inertia=1.5), "inertia"),
    (dict(tangential_restitution=0.5, growth=0.1), "rough"),
])
def test_bad_rough_input_is_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ReferenceSimulation([[5.0, 5.0]], [[1.0, 0.0]], 0.5, box=ed.Box(10.0, 10.0),
                            **kwargs)
