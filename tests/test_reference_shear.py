"""Lees-Edwards (sliding-brick) boundaries in the brute-force reference, checked by hand.

A box sheared at rate ``gamma`` has its images above sliding along x at ``U = gamma Ly``
(those below at ``-U``), offset by ``delta(t) = U (t - t0) mod Lx``.  Every expected
number here comes from its own formula: a contact time from the straight lines of a
disk and a sliding image, a collision from the textbook impulse, a free disk's path in
the infinite sheared system, a redraw from the documented random stream.  The long runs
check two exact identities of the sheared dynamics: the balance of the peculiar
kinetic energy against the shear stress, and the conservation of the peculiar momentum.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import random_system, seed_of
from edmd2d.physics import Resting
from edmd2d.reference import ReferenceSimulation

BOX = ed.Box(10.0, 10.0)


def _peculiar(ref):
    """The peculiar velocities ``v - (gamma (y - Ly/2), 0)``, computed here."""
    u = ref.velocities
    u[:, 0] -= ref.shear_rate * (ref.positions[:, 1] - 0.5 * ref.box.height)
    return u


def _closest_approach(ref):
    """The smallest distance between two disks over the sheared images, divided by
    their contact distance (>= 1 where no two overlap)."""
    p, r = ref.positions, np.array(ref.r)
    w, h = ref.box.width, ref.box.height
    worst = math.inf
    for i in range(len(p)):
        for j in range(i + 1, len(p)):
            for sy in (-1, 0, 1):
                dx = p[i, 0] - p[j, 0] - sy * ref.offset
                dx -= w * round(dx / w)
                dy = p[i, 1] - p[j, 1] - sy * h
                worst = min(worst, math.hypot(dx, dy) / (r[i] + r[j]))
    return worst


# -- 1. two disks meeting through the boundary --------------------------------------------

@pytest.mark.parametrize("gamma", [0.5, -0.5])
def test_disks_at_rest_meet_through_the_sliding_image_and_collide_elastically(gamma):
    # Disk 0 at (5, 9.6), disk 1 at (x1, 0.2), both at rest, radii 0.5, masses 1 and 3.
    # Disk 1's image above is at (x1 + U t, 10.2) with velocity (U, 0), U = 10 gamma = +-5:
    # from x1 = 1 (U > 0) or x1 = 9 (U < 0) it closes in on disk 0 along x, 0.6 above it.
    # They touch when |x0 - x_image| = sqrt(1 - 0.6^2) = 0.8: after 3.2 / 5 = 0.64.
    u = gamma * BOX.height
    x1 = 1.0 if u > 0 else 9.0
    ref = ReferenceSimulation([[5.0, 9.6], [x1, 0.2]], [[0.0, 0.0], [0.0, 0.0]],
                              radii=0.5, masses=[1.0, 3.0], box=BOX, shear_rate=gamma)
    k0 = ref.peculiar_kinetic_energy()
    ref.advance(collisions=1)
    t = 3.2 / 5.0
    assert len(ref.events) == 1 and ref.events[0][1:] == ("disk", 0, 1)
    assert ref.events[0][0] == pytest.approx(t, rel=1e-12)
    assert ref.offset == pytest.approx(u * t % 10.0, rel=1e-12)
    # Neither disk moved.  At contact r = p_0 - image = (+-0.8, -0.6), the unit normal
    # n = r / 1, the relative velocity v_0 - (v_1 + (U, 0)) = (-U, 0), so vn = -4 either
    # way.  Elastic, masses 1 and 3: v_0' = -2 (3/4) vn n = 6 n, v_1' = 2 (1/4) vn n = -2 n.
    np.testing.assert_allclose(ref.positions, [[5.0, 9.6], [x1, 0.2]], rtol=0, atol=1e-15)
    n = np.array([math.copysign(0.8, u), -0.6])
    np.testing.assert_allclose(ref.velocities, [6.0 * n, -2.0 * n], rtol=0, atol=1e-12)
    # The virial r_a J_b with J = m_0 v_0' = 6 n on disk 0.
    assert ref.virial_xx == pytest.approx(6.0 * n[0] * n[0], rel=1e-12)
    assert ref.virial_yy == pytest.approx(6.0 * n[1] * n[1], rel=1e-12)
    assert ref.virial_xy == pytest.approx(6.0 * n[0] * n[1], rel=1e-12)
    # The peculiar energy gained, -gamma r_y J_x (no flight stress: the disks stood still
    # in the box, u_y = 0 before the collision).
    assert ref.kinetic_stress_integral()[2] == 0.0
    gained = -gamma * (-0.6) * (6.0 * n[0])
    assert ref.peculiar_kinetic_energy() - k0 == pytest.approx(gained, rel=1e-12)
    # Momentum in the frame of the image is kept: (0, 0) + 3 (U, 0) before.
    total = 1.0 * ref.velocities[0] + 3.0 * (ref.velocities[1] + [u, 0.0])
    np.testing.assert_allclose(total, [3.0 * u, 0.0], rtol=0, atol=1e-12)


# -- 2. a disk crossing the top and the bottom --------------------------------------------

def test_a_disk_leaving_through_the_top_comes_back_shifted_by_the_offset():
    # x0 = (2, 9), v = (0.7, 2), gamma = 0.3, U = 3: it leaves through the top at t = 0.5.
    # At t = 0.6 it is 0.2 above the bottom, its x shifted by -delta(0.6) = -1.8 from
    # 2 + 0.7 * 0.6 = 2.42, its vx by -U.
    ref = ReferenceSimulation([[2.0, 9.0]], [[0.7, 2.0]], radii=0.4, box=BOX,
                              shear_rate=0.3)
    ref.advance(until=0.6)
    assert ref.offset == pytest.approx(1.8, rel=1e-14)
    np.testing.assert_allclose(ref.positions, [[0.62, 0.2]], rtol=0, atol=1e-14)
    np.testing.assert_allclose(ref.velocities, [[0.7 - 3.0, 2.0]], rtol=0, atol=1e-14)
    # Unwrapped: on the straight line of the infinite sheared system.
    np.testing.assert_allclose(ref.unwrapped_positions, [[2.42, 10.2]], rtol=0, atol=1e-14)
    assert ref.images == [[0, 1]]


def test_a_disk_leaving_through_the_bottom_comes_back_shifted_the_other_way():
    # x0 = (2, 1), v = (0.7, -2), gamma = -0.3, U = -3: out through the bottom at 0.5; at
    # t = 0.6, delta = -1.8 mod 10 = 8.2, x = 2.42 + 8.2 - 10 = 0.62, vx = 0.7 - 3.
    ref = ReferenceSimulation([[2.0, 1.0]], [[0.7, -2.0]], radii=0.4, box=BOX,
                              shear_rate=-0.3)
    ref.advance(until=0.6)
    assert ref.offset == pytest.approx(8.2, rel=1e-14)
    np.testing.assert_allclose(ref.positions, [[0.62, 9.8]], rtol=0, atol=1e-13)
    np.testing.assert_allclose(ref.velocities, [[0.7 - 3.0, -2.0]], rtol=0, atol=1e-14)
    np.testing.assert_allclose(ref.unwrapped_positions, [[2.42, -0.2]], rtol=0, atol=1e-13)


@pytest.mark.parametrize("gamma, v, t0", [(0.3, (0.7, 2.0), 0.0), (-0.45, (-1.3, 1.1), 3.0),
                                          (1.7, (0.4, -2.3), -2.5)])
def test_a_free_disk_follows_its_straight_line_through_many_crossings(gamma, v, t0):
    # Alone, a disk flies straight in the infinite sheared system: unwrapped
    # x0 + v (t - t0), however often it crosses the top or the bottom and however often
    # the offset wraps past the width.  Its stored state follows from that path: k =
    # floor(y_unwrapped / Ly) boxes up, y = y_unwrapped - k Ly, x = x_unwrapped -
    # k D(t) mod Lx (D = U (t - t0) not reduced) and vx = v_x - k U.  Its peculiar
    # velocity changes at -gamma vy in flight, continuously across the crossings,
    # which the exact integrals of the kinetic stress must follow too.
    # (Rounding: k boxes up, the disk moves at vx - k U in the box, up to ~1600 here,
    # so the look-ahead window is short and the run takes up to ~10^5 steps.  The clock,
    # a sum of their durations rounded at each, strays from the flights' total by up to
    # ~1e-10 (3e-10 seen), which that speed turns into an error of x: tolerance
    # 1e-9 (1 + |k U|).  vx takes the rounding of k subtractions of U.)
    x0, m = np.array([3.0, 4.0]), 1.5
    ref = ReferenceSimulation([x0], [v], radii=0.4, masses=m, box=BOX, time=t0,
                              shear_rate=gamma)
    assert ref.t0 == t0 and ref.offset == 0.0
    u_speed = gamma * BOX.height
    ux0 = v[0] - gamma * (x0[1] - 5.0)
    crossings = 0
    for t in t0 + np.linspace(0.37, 400.0, 60):
        ref.advance(until=t)
        tau = t - t0
        path = x0 + np.array(v) * tau
        k = math.floor(path[1] / 10.0)
        tol = 1e-9 * (1.0 + abs(k * u_speed))
        np.testing.assert_allclose(ref.unwrapped_positions[0], path, rtol=0, atol=tol)
        slide = u_speed * tau
        assert ref.images[0][1] == k
        assert ref.offset == pytest.approx(slide % 10.0, rel=1e-12, abs=1e-12)
        assert 0.0 <= ref.offset < 10.0
        x, y = ref.positions[0]
        assert 0.0 <= x < 10.0 and 0.0 <= y < 10.0
        assert y == pytest.approx(path[1] - 10.0 * k, abs=tol)
        dx = x - (path[0] - k * slide)
        assert abs(dx - 10.0 * round(dx / 10.0)) < tol
        v_tol = 1e-13 * (1.0 + abs(k * u_speed))
        np.testing.assert_allclose(ref.velocities[0], [v[0] - k * u_speed, v[1]], rtol=0,
                                   atol=v_tol)
        np.testing.assert_allclose(_peculiar(ref)[0], [ux0 - gamma * v[1] * tau, v[1]],
                                   rtol=0, atol=v_tol + abs(gamma) * tol)
        want = (m * (ux0 ** 2 * tau - gamma * v[1] * ux0 * tau ** 2
                     + gamma ** 2 * v[1] ** 2 * tau ** 3 / 3.0),
                m * v[1] ** 2 * tau,
                m * v[1] * (ux0 * tau - gamma * v[1] * tau ** 2 / 2.0))
        np.testing.assert_allclose(ref.kinetic_stress_integral(), want, rtol=1e-11)
        crossings = max(crossings, abs(k))
    # Many crossings, and the offset many widths on.
    assert crossings >= 40
    assert abs(u_speed) * 400.0 >= 40 * 10.0


# -- the images tried under shear ---------------------------------------------------------

class _EveryNearImage(ReferenceSimulation):
    """The reference trying far more images than its six shifts per row: sx from -10
    to 10 and sy from -3 to 3 around the offset."""

    def _sheared_shifts(self):
        w, h = self.box.width, self.box.height
        delta, speed = self.offset, self.shear_rate * h
        return [(sx * w + sy * delta, sy * h, sy * speed)
                for sy in range(-3, 4) for sx in range(-10, 11)]


@pytest.mark.parametrize("k, gamma", [(7, 3.0), (8, -4.0)])
def test_the_images_tried_are_all_that_can_touch_within_the_window(k, gamma):
    # A small dense box sheared fast (images sliding a width in ~0.1): with far more
    # images tried, the same collisions come in the same order at the same times (the
    # same images give the same arithmetic): none that could come first was left out.
    rng = np.random.default_rng(seed_of(k))
    box = ed.Box(4.0, 3.5)
    pos, vel, rad, mass = random_system(rng, 8, box)
    runs = [cls(pos, vel, rad, mass, box=box, shear_rate=gamma)
            for cls in (ReferenceSimulation, _EveryNearImage)]
    for ref in runs:
        ref.advance(collisions=200)
    assert runs[0].events == runs[1].events
    assert runs[0].p == runs[1].p and runs[0].v == runs[1].v


# -- 3. the identities of the sheared dynamics --------------------------------------------

def _sheared_gas(seed, n, side):
    """About ``n`` disks (mixed radii and masses) in a ``side`` square, packing ~0.3-0.4,
    with no y momentum in total (so that the peculiar momentum stays put)."""
    rng = np.random.default_rng(seed)
    box = ed.Box(side, side)
    pos, vel, rad, mass = random_system(rng, n, box)
    vel[:, 1] -= mass @ vel[:, 1] / mass.sum()
    return box, pos, vel, rad, mass


IDENTITY_RUNS = [(1, 0.5, 20, 5.6, 2000), (2, -1.5, 20, 5.4, 2000), (3, 2.0, 24, 6.0, 2000),
                 pytest.param(9, -1.0, 40, 7.6, 5000, marks=pytest.mark.slow)]


@pytest.mark.parametrize("k, gamma, n, side, collisions", IDENTITY_RUNS)
def test_peculiar_energy_balances_the_shear_stress_and_peculiar_momentum_is_kept(
        k, gamma, n, side, collisions):
    # Elastic, no thermostat: K(t) - K(0) = -gamma (int sum m u_x u_y dt + sum r_y J_x),
    # exact (see ReferenceSimulation's notes), so to rounding over thousands of
    # collisions through the sliding images.
    box, pos, vel, rad, mass = _sheared_gas(seed_of(k), n, side)
    assert 0.3 <= np.pi * np.sum(rad ** 2) / box.area <= 0.5
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, shear_rate=gamma)
    k0 = ref.peculiar_kinetic_energy()
    p0 = mass @ _peculiar(ref)
    scale_p = mass @ np.abs(_peculiar(ref)).sum(axis=1)
    ref.advance(collisions=collisions)
    assert ref.collisions == collisions
    # Collisions through the boundaries above and below, with the offset a width on.
    assert max(abs(i[1]) for i in ref.images) >= 1
    assert abs(gamma * side * ref.time) > side
    k1 = ref.peculiar_kinetic_energy()
    flight_xy = ref.kinetic_stress_integral()[2]
    balance = -gamma * (flight_xy + ref.virial_xy)
    scale = k0 + k1 + abs(gamma) * (abs(flight_xy) + abs(ref.virial_xy))
    assert abs((k1 - k0) - balance) <= 1e-12 * scale
    assert k1 > k0  # (viscous heating: the shear does work on the disks)
    # The peculiar momentum: no change in flight (no y momentum), at collisions or
    # through the boundaries.
    np.testing.assert_allclose(mass @ _peculiar(ref), p0, rtol=0, atol=1e-12 * scale_p)
    assert _closest_approach(ref) > 1.0 - 1e-9


def test_dissipation_and_redraws_enter_the_balance_of_peculiar_energy():
    # Inelastic collisions take `dissipated` off the peculiar energy, redraws add
    # `thermostat_energy` (their change of it): K(t) - K(0) = -gamma (I_xy + W_xy)
    # - dissipated + thermostat_energy.
    box, pos, vel, rad, mass = _sheared_gas(seed_of(4), 16, 5.0)
    gamma = 1.2
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, shear_rate=gamma,
                              restitution=0.8, thermostat=(1.0, 0.3), seed=seed_of(4))
    k0 = ref.peculiar_kinetic_energy()
    ref.advance(collisions=1000)
    assert ref.redraws > 10 and ref.dissipated > 0.0
    k1 = ref.peculiar_kinetic_energy()
    flight_xy = ref.kinetic_stress_integral()[2]
    balance = (-gamma * (flight_xy + ref.virial_xy) - ref.dissipated
               + ref.thermostat_energy)
    scale = (k0 + k1 + abs(gamma) * (abs(flight_xy) + abs(ref.virial_xy))
             + ref.dissipated + abs(ref.thermostat_energy))
    assert abs((k1 - k0) - balance) <= 1e-12 * scale


# -- 4. no shear: everything as before ----------------------------------------------------

@pytest.mark.parametrize("periodic, gravity, thermostat", [
    (True, (0.0, 0.0), (1.0, 0.5)), (False, (0.0, -2.0), None), ((True, False), (0.0, -1.0),
                                                                 None)])
def test_a_zero_shear_rate_runs_exactly_as_without_it(periodic, gravity, thermostat):
    rng = np.random.default_rng(seed_of(5))
    box = ed.Box(6.0, 5.0, periodic=periodic)
    pos, vel, rad, mass = random_system(rng, 8, box)
    common = dict(box=box, gravity=gravity, thermostat=thermostat, seed=7,
                  restitution=0.9)
    plain = ReferenceSimulation(pos, vel, rad, mass, **common)
    zero = ReferenceSimulation(pos, vel, rad, mass, shear_rate=0.0, **common)
    plain.advance(until=6.0)
    zero.advance(until=6.0)
    assert len(plain.events) >= 20
    assert zero.events == plain.events
    assert zero.p == plain.p and zero.v == plain.v and zero.images == plain.images
    assert zero.offset == 0.0
    assert zero.peculiar_kinetic_energy() == zero.kinetic_energy()
    assert zero.thermostat_energy == plain.thermostat_energy
    np.testing.assert_array_equal(zero.unwrapped_positions,
                                  np.array(plain.p) + np.array(plain.images) * box.size)


# -- 5. what shear does not combine with --------------------------------------------------

@pytest.mark.parametrize("change", [
    dict(box=ed.Box(10.0, 10.0, periodic=False)),
    dict(box=ed.Box(10.0, 10.0, periodic=(True, False))),
    dict(box=ed.Box(10.0, 10.0, periodic=(False, True))),
    dict(walls=[ed.Wall((1.0, 1.0), (3.0, 1.0))]),
    dict(gravity=(0.0, -1.0)),
    dict(growth=0.1),
    dict(resting=Resting.of(1e-3, 1.0, 0.5)),
])
def test_shear_is_refused_where_the_sliding_images_make_no_sense(change):
    args = dict(box=BOX, shear_rate=0.5) | change
    with pytest.raises(ValueError, match="shear_rate"):
        ReferenceSimulation([[5.0, 5.0]], [[0.0, 0.0]], radii=0.5, **args)
    # (With no shear, the same system is fine.)
    ReferenceSimulation([[5.0, 5.0]], [[0.0, 0.0]], radii=0.5, **(args | {"shear_rate": 0.0}))


# -- 6. the thermostat draws peculiar velocities ------------------------------------------

def test_a_redraw_under_shear_adds_the_flow_velocity_at_the_disk():
    # One disk at rest at height 8 in the box: u = (-gamma * 3, 0).  The documented
    # stream: the first waiting time, then the disk, the next waiting time and two
    # Gaussians sqrt(-2 ln(1 - u1)) cos(2 pi u2).
    gamma, kt, rate, m, seed = 0.7, 2.0, 0.5, 1.5, 11
    ref = ReferenceSimulation([[3.0, 8.0]], [[0.0, 0.0]], radii=0.5, masses=m, box=BOX,
                              shear_rate=gamma, thermostat=(kt, rate), seed=seed)
    stream = np.random.default_rng(seed)

    def gauss():
        r = math.sqrt(-2.0 * math.log(1.0 - stream.random()))
        return r * math.cos(2.0 * math.pi * stream.random())

    t_redraw = -math.log(1.0 - stream.random()) / rate
    assert ref.next_redraw == t_redraw
    stream.random()  # (the disk: the only one)
    stream.random()  # (the next waiting time)
    s = math.sqrt(kt / m)
    g1, g2 = gauss(), gauss()
    ref.advance(until=t_redraw)
    assert ref.redraws == 1
    want = [s * g1 + gamma * (8.0 - 5.0), s * g2]
    np.testing.assert_allclose(ref.velocities, [want], rtol=1e-14, atol=0)
    # Its energy: that of the peculiar velocity, from (-2.1, 0) to (s g1, s g2).
    gained = 0.5 * m * ((s * g1) ** 2 + (s * g2) ** 2 - (gamma * 3.0) ** 2)
    assert ref.thermostat_energy == pytest.approx(gained, rel=1e-13)


def test_redraws_are_centred_on_the_flow_velocity_at_each_height():
    # One disk wandering across the box, redrawn 3000 times: each vx is gamma (y - 5)
    # plus a Gaussian of variance kT/m = 1 drawn afresh, independent of y.  So the
    # residuals have mean 0 (standard error 1/sqrt(3000) = 0.018) and the least-squares
    # slope of vx against y is gamma (standard error 1/(sqrt(3000) sd(y)), about 0.007
    # for y spread over the box); both checked to 5 standard errors.
    gamma = -0.8
    ref = ReferenceSimulation([[3.0, 8.0]], [[0.5, 1.3]], radii=0.5, box=BOX,
                              shear_rate=gamma, thermostat=(1.0, 1.0), seed=seed_of(6))
    ys, vxs = [], []
    for _ in range(3000):
        ref.advance(until=ref.next_redraw)
        ys.append(ref.positions[0, 1])
        vxs.append(ref.velocities[0, 0])
    ys, vxs = np.array(ys), np.array(vxs)
    residual = vxs - gamma * (ys - 5.0)
    n = len(ys)
    assert abs(residual.mean()) < 5.0 / math.sqrt(n)
    assert residual.std() == pytest.approx(1.0, abs=5.0 / math.sqrt(2.0 * n))
    slope = np.polyfit(ys, vxs, 1)[0]
    assert abs(slope - gamma) < 5.0 / (math.sqrt(n) * ys.std())
