"""Uniform gravity in the brute-force reference, against closed-form results.

Every expected contact time is computed here from its own formula (a square root for a
fall, the quadratic formula for a parabola meeting a line, ``scipy.optimize.brentq`` on
the distance function for a parabola meeting a circle), never from the reference's own
root finder.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import edmd2d as ed
from conftest import min_image, random_system, segment_distance
from edmd2d.reference import ReferenceSimulation

G = 9.81
WALLED = ed.Box(10.0, 10.0, periodic=False)
SHELF = ed.Wall((2.0, 5.0), (6.0, 5.0))


def _times(ref, kind=None):
    return [e[0] for e in ref.events if kind is None or e[1] == kind]


def _rise_time(height, g):
    """Time for a thrown body to rise ``height`` from a speed that takes it exactly there."""
    return math.sqrt(2.0 * height / g)


# -- box walls ---------------------------------------------------------------------------

def test_drop_onto_floor_elastic_bounces_keep_period_and_apex():
    # Dropped from 3 above the floor: impact at t1 = sqrt(2h/g) with speed sqrt(2gh),
    # then the same flight up and down: impacts at t1 + k T, T = 2 v / g = 2 t1.
    h, r = 3.0, 0.5
    ref = ReferenceSimulation([[5.0, r + h]], [[0.0, 0.0]], radii=r, box=WALLED,
                              gravity=(0.0, -G))
    e0 = ref.total_energy()
    t1 = _rise_time(h, G)
    v = math.sqrt(2.0 * G * h)
    period = 2.0 * v / G
    ref.advance(collisions=None, until=t1 + 0.5 * period)
    assert ref.events == [(pytest.approx(t1, rel=1e-14), "box", 0, 2)]
    # At the apex the disk is back at its height, at rest, and touches nothing.
    np.testing.assert_allclose(ref.positions, [[5.0, r + h]], rtol=0, atol=1e-13)
    np.testing.assert_allclose(ref.velocities, [[0.0, 0.0]], rtol=0, atol=1e-13)
    n = 100
    ref.advance(until=t1 + (n - 0.5) * period)
    times = _times(ref)
    assert len(times) == n and all(e[1:] == ("box", 0, 2) for e in ref.events)
    want = t1 + period * np.arange(n)
    np.testing.assert_allclose(times, want, rtol=1e-13, atol=0)  # no drift of the period
    np.testing.assert_allclose(ref.positions, [[5.0, r + h]], rtol=0, atol=1e-11)
    assert ref.total_energy() == pytest.approx(e0, rel=1e-13)
    assert ref.kinetic_energy() == pytest.approx(0.0, abs=1e-20 + 1e-11 * e0)


@pytest.mark.parametrize("axis, sign, side", [(1, -1, 2), (1, 1, 3), (0, -1, 0), (0, 1, 1)])
def test_fall_towards_each_box_wall(axis, sign, side):
    # Gravity pointing at each of the four walls in turn; the disk starts 2.5 away from
    # that wall with a speed 1.5 across the fall: impact at sqrt(2 * 2.5 / g).
    g, gap, r = 4.0, 2.5, 0.5
    pos = [5.0, 5.0]
    pos[axis] = r + gap if sign < 0 else 10.0 - r - gap
    vel = [0.0, 0.0]
    vel[1 - axis] = 1.5
    grav = [0.0, 0.0]
    grav[axis] = sign * g
    ref = ReferenceSimulation([pos], [vel], radii=r, box=WALLED, gravity=grav)
    ref.advance(until=1.2)
    t = _rise_time(gap, g)
    assert ref.events == [(pytest.approx(t, rel=1e-14), "box", 0, side)]
    # After the bounce: the normal speed reversed, the other component untouched.
    want = [0.0, 0.0]
    want[1 - axis] = 1.5
    want[axis] = -sign * g * t + sign * g * (1.2 - t)
    np.testing.assert_allclose(ref.velocities, [want], rtol=0, atol=1e-13)


def test_thrown_up_to_the_ceiling():
    # y(t) = y0 + vy t - g t^2 / 2 reaches H - r at the smaller root of a quadratic.
    y0, vy, r = 2.0, 13.0, 0.5
    ref = ReferenceSimulation([[5.0, y0]], [[0.3, vy]], radii=r, box=WALLED,
                              gravity=(0.0, -G))
    ref.advance(collisions=None, until=0.9)
    c = 10.0 - r - y0
    t = 2.0 * c / (vy + math.sqrt(vy * vy - 2.0 * G * c))  # smaller root, no cancellation
    assert ref.events == [(pytest.approx(t, rel=1e-14), "box", 0, 3)]
    assert ref.velocities[0, 1] == pytest.approx(-(vy - G * t) - G * (0.9 - t), rel=1e-13)


def test_inelastic_floor_apex_heights_scale_with_e_squared():
    # After the k-th impact the speed is e^k v0: the flight lasts 2 e^k v0 / g and the
    # apex is h e^(2k) above the floor; what is lost is m g h (1 - e^(2k)).
    h, r, e, m = 2.0, 0.5, 0.8, 1.5
    ref = ReferenceSimulation([[5.0, r + h]], [[0.0, 0.0]], radii=r, masses=m, box=WALLED,
                              wall_restitution=e, gravity=(0.0, -G))
    e0 = ref.total_energy()
    v0 = math.sqrt(2.0 * G * h)
    t_hit = _rise_time(h, G)
    for k in range(1, 11):
        speed = e**k * v0
        apex_time = t_hit + speed / G
        ref.advance(until=apex_time)
        assert len(ref.events) == k
        assert ref.events[-1][0] == pytest.approx(t_hit, rel=1e-13)
        assert ref.positions[0, 1] - r == pytest.approx(h * e ** (2 * k), rel=1e-12)
        assert ref.dissipated == pytest.approx(m * G * h * (1.0 - e ** (2 * k)), rel=1e-13)
        assert ref.total_energy() + ref.dissipated == pytest.approx(e0, rel=1e-14)
        t_hit += 2.0 * speed / G


def test_touching_and_approaching_is_a_contact_now():
    # Gravity across the motion: the gap to the left wall is linear and already zero
    # (or overlapping by rounding), the disk moving into it: the contact is at t = 0.
    for dx in (0.0, -1e-15):
        ref = ReferenceSimulation([[0.5 + dx, 5.0]], [[-1.0, 0.0]], radii=0.5, box=WALLED,
                                  gravity=(0.0, -1.0))
        ref.advance(until=0.5)
        assert ref.events == [(0.0, "box", 0, 0)], dx
        assert ref.velocities[0, 0] == 1.0
    # The same against the floor, falling onto it.
    ref = ReferenceSimulation([[5.0, 0.5]], [[0.0, -1.0]], radii=0.5, box=WALLED,
                              gravity=(0.0, -1.0))
    ref.advance(until=0.5)
    assert ref.events[0] == (0.0, "box", 0, 2)


def test_disk_leaving_the_floor_is_not_hit_again_at_once():
    # On the floor (exactly, or overlapping or apart by rounding) and moving up at 2:
    # the next contact is the return, y - r = 2 t - t^2 / 2 = 0 at t = 4.
    r = 0.5
    for dy in (0.0, -1e-15, 1e-15, -3e-16):
        ref = ReferenceSimulation([[3.0, r + dy]], [[0.5, 2.0]], radii=r, box=WALLED,
                                  gravity=(0.0, -1.0))
        ref.advance(until=4.5)
        assert ref.events == [(pytest.approx(4.0, rel=1e-13), "box", 0, 2)], dy


# -- disks -----------------------------------------------------------------------------

def test_two_falling_disks_meet_as_in_straight_flight():
    # Both accelerate alike: the relative motion is straight, gap 1 at speed 2.
    ref = ReferenceSimulation([[3.0, 8.0], [6.0, 8.0]], [[1.0, 0.0], [-1.0, 0.0]],
                              radii=1.0, box=WALLED, gravity=(0.0, -G))
    ref.advance(collisions=1)
    assert ref.events == [(pytest.approx(0.5, rel=1e-14), "disk", 0, 1)]
    np.testing.assert_allclose(ref.velocities, [[-1.0, -0.5 * G], [1.0, -0.5 * G]],
                               rtol=0, atol=1e-14)


def test_bouncing_on_top_of_an_immovable_disk():
    # Dropped straight over a peg's centre from 1.5 above contact: it bounces back up to
    # where it started, over and over, with impacts at (2k + 1) sqrt(2 * 1.5 / g).
    ref = ReferenceSimulation([[5.0, 6.0], [5.0, 3.0]], [[0.0, 0.0], [0.0, 0.0]],
                              radii=[0.5, 1.0], masses=[1.0, math.inf], box=WALLED,
                              gravity=(0.0, -G))
    e0 = ref.total_energy()
    t1 = _rise_time(1.5, G)
    n = 40
    ref.advance(until=(2 * n) * t1)
    assert all(e[1:] == ("disk", 0, 1) for e in ref.events) and len(ref.events) == n
    np.testing.assert_allclose(_times(ref), t1 * (2 * np.arange(n) + 1), rtol=1e-13, atol=0)
    np.testing.assert_allclose(ref.positions, [[5.0, 6.0], [5.0, 3.0]], rtol=0, atol=1e-11)
    assert ref.total_energy() == pytest.approx(e0, rel=1e-13)


def test_oblique_hit_on_an_immovable_disk_matches_brentq():
    # Off-centre: f(t) = |p + v t + g t^2/2 - c|^2 - D^2 is a quartic; its first root from
    # a scan plus brentq, and the reflection v' = v - 2 (v.n) n at that moment.
    p0, v0, c, big_r, r = np.array([3.2, 6.5]), np.array([1.0, 0.5]), np.array([5.0, 3.0]), 1.2, 0.5
    g = np.array([0.0, -G])
    d = big_r + r

    def f(t):
        s = p0 + v0 * t + 0.5 * g * t * t - c
        return s @ s - d * d

    grid = np.linspace(0.0, 2.0, 20001)
    k = next(i for i in range(len(grid)) if f(grid[i]) <= 0.0)
    t_hit = brentq(f, grid[k - 1], grid[k], xtol=1e-16, rtol=4 * np.finfo(float).eps)
    ref = ReferenceSimulation([p0, c], [v0, [0.0, 0.0]], radii=[r, big_r],
                              masses=[1.0, math.inf], box=WALLED, gravity=g)
    ref.advance(collisions=1)
    assert ref.events == [(pytest.approx(t_hit, rel=1e-13), "disk", 0, 1)]
    x = p0 + v0 * t_hit + 0.5 * g * t_hit**2
    n = (x - c) / d
    v = v0 + g * t_hit
    np.testing.assert_allclose(ref.positions[0], x, rtol=0, atol=1e-13)
    np.testing.assert_allclose(ref.velocities[0], v - 2 * (v @ n) * n, rtol=0, atol=1e-12)


def test_leaving_an_immovable_disk_it_comes_back():
    # Exactly on top of a peg, moving up at 2: no event now; back after 4 (g = 1).
    for dy in (0.0, -1e-15, 1e-15):
        ref = ReferenceSimulation([[5.0, 4.5 + dy], [5.0, 3.0]], [[0.0, 2.0], [0.0, 0.0]],
                                  radii=[0.5, 1.0], masses=[1.0, math.inf], box=WALLED,
                                  gravity=(0.0, -1.0))
        ref.advance(until=4.5)
        assert ref.events == [(pytest.approx(4.0, rel=1e-13), "disk", 0, 1)], dy


@pytest.mark.parametrize("eps", [1e-9, 1e-12, 0.0])
def test_grazing_miss_over_an_immovable_disk(eps):
    # Apex at t = 1 right above the peg (5, 3), 1.5 + eps from its centre; with
    # tau = t - 1 the squared distance minus D^2 is
    #   tau^4 / 4 + (7.5 - eps) tau^2 + 3 eps + eps^2,
    # positive for eps > 0 and with a double root at tau = 0 for eps = 0 (a tangential
    # touch): no event either way.
    ref = ReferenceSimulation([[2.0, 4.0 + eps], [5.0, 3.0]], [[3.0, 1.0], [0.0, 0.0]],
                              radii=[0.5, 1.0], masses=[1.0, math.inf], box=WALLED,
                              gravity=(0.0, -1.0))
    ref.advance(until=2.0)
    assert ref.events == []
    np.testing.assert_allclose(ref.velocities, [[3.0, -1.0], [0.0, 0.0]], rtol=0, atol=1e-14)


@pytest.mark.parametrize("eps", [-1e-12, -1e-9, -1e-7])
def test_grazing_hit_over_an_immovable_disk(eps):
    # The same with the apex 1.5 - |eps| from the centre: contact at tau^2 =
    # -2 (3 eps + eps^2) / ((7.5 - eps) + sqrt((7.5 - eps)^2 - (3 eps + eps^2))).
    ref = ReferenceSimulation([[2.0, 4.0 + eps], [5.0, 3.0]], [[3.0, 1.0], [0.0, 0.0]],
                              radii=[0.5, 1.0], masses=[1.0, math.inf], box=WALLED,
                              gravity=(0.0, -1.0))
    ref.advance(until=2.0)
    eps = (4.0 + eps) - 4.0  # the start as stored (exact, by Sterbenz's lemma)
    b, c = 7.5 - eps, 3 * eps + eps * eps
    tau = math.sqrt(-2.0 * c / (b + math.sqrt(b * b - c)))
    assert [e[1:] for e in ref.events] == [("disk", 0, 1)]
    # A graze: the contact function's slope is 15 tau there, so its rounding (~1e-15)
    # moves the time by ~1e-15 / (15 tau): 1e-10 for eps = -1e-12.
    assert ref.events[0][0] == pytest.approx(1.0 - tau, abs=1e-9)


# -- wall segments -------------------------------------------------------------------------

def test_projectile_hits_a_slanted_segment_side():
    # The signed distance from the line, n.(x(t) - a), is a parabola: it reaches r at the
    # smaller root of (n.g / 2) t^2 + (n.v) t + (n.(x0 - a) - r) = 0.
    a, b = np.array([5.2, 0.2]), np.array([8.0, 8.0])
    x0, v0, r = np.array([1.0, 2.0]), np.array([4.0, 5.0]), 0.4
    g = np.array([0.0, -G])
    u = b - a
    n = np.array([-u[1], u[0]]) / np.hypot(*u)  # pointing to the disk's side
    qa, qb, qc = 0.5 * (n @ g), n @ v0, n @ (x0 - a) - r
    assert qc > 0 and qb < 0
    t_hit = (-qb - math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa)
    x = x0 + v0 * t_hit + 0.5 * g * t_hit**2
    s = (x - a) @ u / (u @ u)
    assert 0.1 < s < 0.9
    ref = ReferenceSimulation([x0], [v0], radii=r, box=WALLED, walls=[ed.Wall(a, b)],
                              gravity=g)
    ref.advance(collisions=None, until=t_hit * (1 + 1e-9))
    assert ref.events == [(pytest.approx(t_hit, rel=1e-13), "wall", 0, 0)]
    v = v0 + g * t_hit
    after = v - 2 * (v @ n) * n
    late = ref.time - t_hit  # the run went on a little past the contact
    np.testing.assert_allclose(ref.positions[0], x + after * late + 0.5 * g * late**2,
                               rtol=0, atol=1e-13)
    np.testing.assert_allclose(ref.velocities[0], after + g * late, rtol=0, atol=1e-13)


def test_thrown_past_the_end_of_a_shelf_falls_onto_it():
    # Thrown up beside the shelf's end (x = 7 - t > 6 + r while it rises through the
    # shelf's height) and back over it: the second crossing of y = 5 + r, on the way
    # down, is on the shelf.  It then hops along the shelf with the impact speed w,
    # once every 2 w / g, until it runs off the far end.
    x0, y0, vx, vy, r = 7.0, 3.0, -1.0, 8.0, 0.25
    c = 5.0 + r - y0  # rise to the level of contact from above
    rise = 2 * c / (vy + math.sqrt(vy * vy - 2 * G * c))  # through y = 5 + r, going up
    assert x0 + vx * rise > 6.0 + r  # beside the shelf, not over it
    t_hit = (vy + math.sqrt(vy * vy - 2 * G * c)) / G  # through y = 5 + r, coming down
    assert 2.0 < x0 + vx * t_hit < 6.0
    ref = ReferenceSimulation([[x0, y0]], [[vx, vy]], radii=r, box=WALLED, walls=[SHELF],
                              gravity=(0.0, -G))
    w = G * t_hit - vy
    hop = 2 * w / G
    hops = [t_hit + k * hop for k in range(5) if 2.0 <= x0 + vx * (t_hit + k * hop) <= 6.0]
    assert len(hops) == 5
    ref.advance(until=hops[-1] + 0.5 * hop)
    assert [e[1:] for e in ref.events] == [("wall", 0, 0)] * len(hops)
    np.testing.assert_allclose(_times(ref), hops, rtol=1e-13, atol=0)
    np.testing.assert_allclose(ref.positions, [[x0 + vx * ref.time, 5.0 + r + w * w / (2 * G)]],
                               rtol=0, atol=1e-11)


def test_thrown_up_into_the_underside_of_a_shelf():
    # From below: y + r reaches 5 at the smaller root, moving up.
    y0, vy, r = 2.0, 9.0, 0.25
    c = 5.0 - r - y0
    t_hit = 2 * c / (vy + math.sqrt(vy * vy - 2 * G * c))
    ref = ReferenceSimulation([[4.0, y0]], [[0.5, vy]], radii=r, box=WALLED, walls=[SHELF],
                              gravity=(0.0, -G))
    ref.advance(collisions=None, until=t_hit * (1 + 1e-9))
    assert ref.events == [(pytest.approx(t_hit, rel=1e-14), "wall", 0, 0)]
    assert ref.velocities[0, 1] == pytest.approx(-(vy - G * t_hit) - G * (ref.time - t_hit),
                                                 rel=1e-13)


def test_drop_onto_the_end_of_a_shelf():
    # 0.2 beside the shelf's end (6, 5), radius 0.5: contact when the centre is
    # sqrt(0.25 - 0.04) above it, after falling 3 - that.  Normal (0.2, that) / 0.5.
    dx, r = 0.2, 0.5
    dz = math.sqrt(r * r - dx * dx)
    t_hit = math.sqrt(2 * (3.0 - dz) / G)
    ref = ReferenceSimulation([[6.0 + dx, 8.0]], [[0.0, 0.0]], radii=r, box=WALLED,
                              walls=[SHELF], gravity=(0.0, -G))
    ref.advance(collisions=None, until=t_hit * (1 + 1e-9))
    assert ref.events == [(pytest.approx(t_hit, rel=1e-13), "wall", 0, 0)]
    v = np.array([0.0, -G * t_hit])
    n = np.array([dx, dz]) / r
    after = v - 2 * (v @ n) * n + [0.0, -G * (ref.time - t_hit)]
    np.testing.assert_allclose(ref.velocities[0], after, rtol=0, atol=1e-12)


def test_leaving_a_shelf_top_it_comes_back():
    for dy in (0.0, -1e-15, 1e-15):
        ref = ReferenceSimulation([[4.0, 5.25 + dy]], [[0.1, 2.0]], radii=0.25, box=WALLED,
                                  walls=[SHELF], gravity=(0.0, -1.0))
        ref.advance(until=4.5)
        assert ref.events == [(pytest.approx(4.0, rel=1e-13), "wall", 0, 0)], dy


# -- whole runs ------------------------------------------------------------------------------

def _system(seed, n, box, walls, peg=True):
    rng = np.random.default_rng(seed)
    pos, vel, rad, mass = random_system(rng, n, box, walls)
    if peg:
        mass[0], vel[0] = math.inf, 0.0
    return pos, vel, rad, mass


BOX = ed.Box(6.0, 5.0, periodic=False)
DIVIDER = [ed.Wall((3.0, 1.0), (3.0, 4.0)), ed.Wall((0.5, 2.5), (2.0, 2.0))]


@pytest.mark.parametrize("seed", [0, 1, 3])
def test_total_energy_conserved_in_an_elastic_walled_run(seed):
    pos, vel, rad, mass = _system(seed, 8, BOX, DIVIDER)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=BOX, walls=DIVIDER,
                              gravity=(0.2, -1.5))
    e0 = ref.total_energy()
    p0 = ref.potential_energy()
    ref.advance(collisions=300)
    kinds = {e[1] for e in ref.events}
    assert kinds == {"disk", "wall", "box"}
    assert any(e[1] == "disk" and 0 in e[2:] for e in ref.events)  # the peg
    assert ref.total_energy() == pytest.approx(e0, rel=1e-12)
    assert ref.potential_energy() != pytest.approx(p0, rel=1e-3)  # energy did move around
    assert ref.dissipated == 0.0


@pytest.mark.parametrize("periodic, g", [((True, False), (0.4, -1.0)),
                                         ((False, True), (-1.0, 0.3))])
def test_total_energy_conserved_falling_through_a_periodic_axis(periodic, g):
    # Gravity along a periodic axis: the disks gain speed for ever while the potential
    # energy, taken at the unwrapped positions, falls by as much.
    box = ed.Box(6.0, 5.0, periodic=periodic)
    pos, vel, rad, mass = _system(3, 8, box, DIVIDER[:1])
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=DIVIDER[:1], gravity=g)
    e0 = ref.total_energy()
    ref.advance(until=6.0)
    assert max(max(abs(k) for k in im) for im in ref.images) >= 1  # wrapped
    assert ref.collisions > 20
    assert ref.total_energy() == pytest.approx(e0, rel=1e-12)


def test_potential_energy_of_a_disk_falling_through_a_periodic_box():
    # No walls across the fall: x(t) = x0 + v t + g t^2 / 2 unwrapped, many lengths on.
    box = ed.Box(4.0, 4.0, periodic=(False, True))
    ref = ReferenceSimulation([[2.0, 1.0]], [[0.0, 3.0]], radii=0.5, masses=2.0, box=box,
                              gravity=(0.0, -2.5))
    ref.advance(until=7.0)
    y = 1.0 + 3.0 * 7.0 - 0.5 * 2.5 * 49.0
    assert ref.potential_energy() == pytest.approx(2.0 * 2.5 * y, rel=1e-13)
    assert ref.positions[0, 1] == pytest.approx(y % 4.0, rel=1e-12)
    assert ref.images[0][1] == math.floor(y / 4.0)
    assert ref.total_energy() == pytest.approx(0.5 * 2.0 * 9.0 + 2.0 * 2.5 * 1.0, rel=1e-13)


def test_energy_balance_in_an_inelastic_run():
    pos, vel, rad, mass = _system(5, 8, BOX, DIVIDER)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=BOX, walls=DIVIDER, restitution=0.8,
                              wall_restitution=0.9, tc=1e-3, gravity=(0.0, -1.0))
    e0 = ref.total_energy()
    ref.advance(collisions=50)
    assert ref.wall_collisions > 100
    assert ref.dissipated > 0.2 * abs(e0)
    assert ref.total_energy() + ref.dissipated == pytest.approx(e0, rel=1e-12)


@pytest.mark.parametrize("periodic", [(False, False), (True, False), (True, True)])
def test_no_overlap_between_events(periodic):
    # A missed contact would leave two bodies overlapping: look at many moments.
    box = ed.Box(6.0, 5.0, periodic=periodic)
    walls = DIVIDER
    pos, vel, rad, mass = _system(7, 9, box, walls)
    g = (0.0, -2.0) if not periodic[1] else (0.3, -0.5)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, gravity=g)
    shifts = [np.array([sx * box.width, sy * box.height])
              for sx in ((-1, 0, 1) if periodic[0] else (0,))
              for sy in ((-1, 0, 1) if periodic[1] else (0,))]
    worst = -np.inf
    for k in range(1, 151):
        ref.advance(until=0.02 * k)
        p = ref.positions
        for i in range(len(p)):
            for j in range(i + 1, len(p)):
                worst = max(worst, rad[i] + rad[j] - np.hypot(*min_image(p[i] - p[j], box)))
            for w in walls:
                for s in shifts:
                    worst = max(worst, rad[i] - segment_distance(p[i] + s, w))
            for axis in range(2):
                if not periodic[axis]:
                    worst = max(worst, rad[i] - p[i, axis],
                                p[i, axis] + rad[i] - box.size[axis])
    assert len(ref.events) > 30
    assert worst < 1e-12


def test_horizon_bounds_the_displacement():
    # A disk displaced by at most |v| h + |g| h^2 / 2 in the window h: a quarter length.
    box = ed.Box(8.0, 6.0, periodic=True)
    ref = ReferenceSimulation([[1.0, 1.0], [4.0, 4.0]], [[3.0, 4.0], [1.0, 0.0]], radii=0.5,
                              box=box, gravity=(0.6, -0.8))
    h = ref._horizon()
    assert 5.0 * h + 0.5 * h * h == pytest.approx(6.0 / 4.0, rel=1e-14)


# -- zero gravity ------------------------------------------------------------------------------

@pytest.mark.parametrize("periodic", [(False, False), (True, True), (True, False)])
def test_zero_gravity_is_straight_flight_to_the_bit(periodic):
    box = ed.Box(6.0, 5.0, periodic=periodic)
    pos, vel, rad, mass = _system(11, 9, box, DIVIDER)
    a = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=DIVIDER).advance(until=3.0)
    b = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=DIVIDER,
                            gravity=(0.0, 0.0)).advance(until=3.0)
    assert len(a.events) > 10
    assert a.events == b.events and a.p == b.p and a.v == b.v and a.time == b.time
    assert b.potential_energy() == 0.0
    assert b.total_energy() == b.kinetic_energy()
