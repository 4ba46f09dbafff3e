"""Gravity: exact parabolic flights, checked against closed forms and kinetic theory.

Under a uniform acceleration ``g`` every movable disk flies on a parabola between
events.  The cases here have answers in closed form (a disk bouncing on a floor, a
disk falling onto a peg or onto a shelf), or from statistical mechanics (the
barometric law); energy ``kinetic + m g h`` is conserved by elastic runs.
"""

from __future__ import annotations

import math
import pickle
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import edmd2d as ed
from conftest import seed_of
from edmd2d._engine import predict

WALLED = ed.Box(10.0, 10.0, periodic=False)


def events(sim, until):
    sim._record_events(100_000)
    sim.advance(until=until)
    return sim._recorded_events()


# ------------------------------------------------------------------ closed forms
def test_bouncing_disk_impact_times_over_thousands_of_bounces():
    """Dropped from rest at height h0 above the floor, a disk first lands at
    sqrt(2 h0 / g) with speed v = sqrt(2 g h0), and then every 2 v / g: the k-th impact
    is at t1 + 2 k v / g, with no drift over thousands of bounces."""
    g, h0 = 9.81, 4.0
    sim = ed.Simulation([[5.0, 0.5 + h0]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                        gravity=(0.0, -g))
    t1 = math.sqrt(2.0 * h0 / g)
    period = 2.0 * math.sqrt(2.0 * g * h0) / g
    n = 3000
    log = events(sim, t1 + (n - 0.5) * period)
    times = np.array([t for t, kind, _, partner in log if kind == "box" and partner == 2])
    assert len(times) == n
    expected = t1 + period * np.arange(n)
    assert np.max(np.abs(times - expected) / expected) < 1e-12
    # The apex after each bounce is back at the starting height (energy conserved).
    assert sim.total_energy() == pytest.approx(g * (0.5 + h0), rel=1e-12)


def test_restitution_on_the_floor_shrinks_apex_heights_by_e_squared():
    """With wall restitution e each rebound speed is e times the impact speed, so the
    flight times between impacts shrink by e and the apex heights by e^2."""
    g, h0, e = 2.0, 5.0, 0.8
    sim = ed.Simulation([[5.0, 0.5 + h0]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                        gravity=(0.0, -g), wall_restitution=e, tc=0.0)
    # (The bounces add up to t1 + 2 v0 e / (g (1 - e)) = 20.12: the collapse.)
    log = events(sim, 20.0)
    times = np.array([t for t, kind, _, _ in log if kind == "box"])  # (not its rest)
    v0 = math.sqrt(2.0 * g * h0)
    t_k = math.sqrt(2.0 * h0 / g) + np.concatenate(
        [[0.0], np.cumsum(2.0 * v0 * e ** np.arange(1, len(times)) / g)])
    assert len(times) > 10
    np.testing.assert_allclose(times, t_k, rtol=1e-12)
    assert sim.dissipated_energy() + sim.total_energy() == pytest.approx(g * (0.5 + h0),
                                                                        rel=1e-12)


def test_disk_falls_onto_a_peg_and_bounces_back_to_its_height():
    """A disk dropped onto an immovable disk right below it (a quartic contact)
    touches it when it has fallen the gap, and rebounds to its starting height."""
    g = 1.0
    gap = 2.0
    sim = ed.Simulation([[5.0, 2.0], [5.0, 2.0 + 1.0 + gap]], [[0.0, 0.0], [0.0, 0.0]],
                        radii=0.5, masses=[np.inf, 1.0], box=WALLED, gravity=(0.0, -g))
    log = events(sim, 10.0)
    t_hit = math.sqrt(2.0 * gap / g)
    assert [kind for _, kind, _, _ in log] == ["disk"] * len(log)
    np.testing.assert_allclose([t for t, *_ in log], t_hit * np.arange(1, 2 * len(log), 2),
                               rtol=1e-13)
    assert sim.positions[0].tolist() == [5.0, 2.0]  # the peg feels no gravity


def test_disk_thrown_past_a_shelf_end_lands_on_its_top():
    """A disk thrown up beside the end of a shelf (x in [0, 4] at y = 5), far enough
    not to touch its end, rises above it and falls onto its top: the second crossing
    of the shelf's line, a case a first-crossing solver would miss."""
    g, r = 1.0, 0.5
    shelf = ed.Wall((0.0, 5.0), (4.0, 5.0))
    x0, y0, vx, vy = 5.0, 2.0, -0.4, 4.0
    sim = ed.Simulation([[x0, y0]], [[vx, vy]], radii=r, box=ed.Box(10.0, 20.0, False),
                        walls=[shelf], gravity=(0.0, -g))
    log = events(sim, 20.0)
    t, kind, _, partner = log[0]
    # Falling through y = 5 + r: y0 + vy t - g t^2 / 2 = 5.5, the later root.
    c = y0 - (5.0 + r)
    t_land = (vy + math.sqrt(vy * vy + 2.0 * g * c)) / g
    assert (kind, partner) == ("wall", 0)
    assert t == pytest.approx(t_land, rel=1e-13)
    assert 0.0 <= x0 + vx * t_land <= 4.0


def test_apex_just_inside_a_cell_turns_back_without_crossing():
    """A disk whose apex lies a hair below a cell boundary turns back there: no
    crossing into the cell above, and it keeps bouncing on the floor exactly."""
    g = 1.0
    box = ed.Box(30.0, 30.0, periodic=False)
    sim = ed.Simulation([[15.0, 0.5]], [[0.0, 1.0]], radii=0.5, box=box,
                        gravity=(0.0, -g), cell_size=1.0)
    # (0.5 + v^2 / 2g = 1.0 is the apex: exactly the boundary between cells 0 and 1.)
    sim.set_velocities([[0.0, math.sqrt(2.0 * 0.5 * g) * (1.0 - 1e-12)]])
    sim.advance(until=100.0)
    assert sim.counts.cell_crossings == 0
    assert sim.counts.wall_collisions == pytest.approx(100.0 / (2.0 * math.sqrt(1.0)),
                                                        abs=1)


def test_fast_disk_never_tunnels_through_a_thin_segment():
    """At any speed a disk falling and thrown at a thin divider bounces off it."""
    divider = ed.Wall((5.0, 0.0), (5.0, 10.0))  # (floor to ceiling: no way round)
    for speed in (1e-3, 1.0, 1e3, 1e6):
        sim = ed.Simulation([[2.0, 5.0]], [[speed, speed / 3.0]], radii=0.25,
                            box=WALLED, walls=[divider], gravity=(0.3, -1.0))
        for _ in range(50):
            sim.advance(until=sim.time + 7.0 / speed)
            assert sim.positions[0, 0] < 5.0 - 0.25 * (1.0 - 1e-9)


# ------------------------------------------------------------------ coming to rest
def test_inelastic_bounces_end_at_rest_on_the_floor_after_finitely_many_events():
    """With wall restitution e the rebound speeds are e^k v0; once a rebound would
    bring the disk back within the TC model's tc (2 v / g < tc) the floor holds it
    (without disks coming to rest, which hold it sooner: tests/test_resting.py).
    The count of bounces follows in closed form, and no event comes after."""
    g, h0, e, tc = 1.0, 4.5, 0.5, 1e-3
    sim = ed.Simulation([[5.0, 0.5 + h0]], [[0.0, 0.0]], radii=0.5, box=WALLED,
                        gravity=(0.0, -g), wall_restitution=e, tc=tc, resting=False)
    e0 = sim.total_energy()
    sim.advance(until=100.0)
    v0 = math.sqrt(2.0 * g * h0)
    bounces = next(m for m in range(1, 100) if 2.0 * e**m * v0 / g < tc)
    assert sim.counts.wall_collisions == bounces
    sim.advance(until=1e6)
    assert sim.counts.events == bounces
    assert sim.positions[0, 1] == pytest.approx(0.5, abs=1e-12)
    assert sim.velocities.tolist() == [[0.0, 0.0]]
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e0, rel=1e-12)


def test_tilted_gravity_brings_the_disk_to_rest_in_the_corner():
    sim = ed.Simulation([[5.0, 5.0]], [[0.2, 0.0]], radii=0.5, box=WALLED,
                        gravity=(0.3, -1.0), wall_restitution=0.5, tc=1e-3)
    sim.advance(until=1e3)
    events = sim.counts.events
    sim.advance(until=1e6)
    assert sim.counts.events == events < 100
    assert sim.positions.tolist() == [[9.5, 0.5]]


def test_a_resting_disk_is_woken_by_a_collision():
    """A disk falls onto one resting on the floor: the collision sets the lower disk
    free (it is pushed into the floor, bounces, and rests again); energy is accounted
    for and nothing overlaps."""
    sim = ed.Simulation([[5.0, 0.5], [5.2, 4.0]], [[0.0, 0.0], [0.0, 0.0]], radii=0.5,
                        box=WALLED, gravity=(0.0, -1.0), restitution=0.7,
                        wall_restitution=0.7, tc=1e-4)
    e0 = sim.total_energy()
    sim.advance(until=2.0)
    assert sim.counts.collisions == 0  # (the first contact comes at t ~ 2.35)
    sim.advance(until=200.0)
    assert sim.counts.collisions >= 1
    pos = sim.positions
    assert np.hypot(*(pos[0] - pos[1])) >= 1.0 - 1e-9
    assert (pos[:, 1] >= 0.5 - 1e-12).all()
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e0, rel=1e-12)


def test_a_disk_at_rest_on_the_floor_starts_held_by_an_inelastic_wall():
    sim = ed.Simulation([[5.0, 0.5]], [[1.0, 0.0]], radii=0.5, box=WALLED,
                        gravity=(0.0, -1.0), wall_restitution=0.9, tc=1e-4)
    sim.advance(until=3.0)
    assert sim.positions.tolist() == [[8.0, 0.5]]
    assert sim.counts.events == 0


# ------------------------------------------------------------------ a gas
@pytest.mark.parametrize("collisions", [100_000, pytest.param(10_000_000,
                                                              marks=pytest.mark.slow)])
def test_elastic_gas_under_gravity_conserves_total_energy(collisions):
    """Kinetic plus potential energy to ~1e-12 relative: each drift adds rounding of
    the relative size 1e-16, a random walk over the events."""
    sim = ed.make_gas(400, 0.3, periodic=(True, False), seed=seed_of(3), gravity=(0.0, -0.5))
    e0 = sim.total_energy()
    pe0 = sim.potential_energy()
    sim.advance(collisions=collisions)
    assert abs(sim.total_energy() - e0) / abs(e0) < 1e-12
    assert sim.potential_energy() < 0.9 * pe0  # the uniform start has settled


def test_readouts_are_at_the_simulation_time():
    """Velocities change between events: the readouts give them at ``time``, and the
    positions on the parabola."""
    sim = ed.Simulation([[5.0, 8.0]], [[1.0, 0.0]], radii=0.5, box=WALLED,
                        gravity=(0.0, -2.0))
    sim.advance(until=1.0)
    assert sim.velocities.tolist() == [[1.0, -2.0]]
    assert sim.positions.tolist() == [[6.0, 7.0]]
    assert sim.kinetic_energy() == pytest.approx(2.5)
    assert sim.potential_energy() == pytest.approx(14.0)
    sim.set_velocities([[0.0, 3.0]])
    sim.advance(until=2.0)
    assert sim.velocities.tolist() == [[0.0, 1.0]]
    assert sim.positions.tolist() == [[6.0, 9.0]]
    assert sim.gravity.tolist() == [0.0, -2.0]


def test_split_runs_and_pickles_continue_bit_identically():
    def gas():
        return ed.make_gas(300, 0.4, periodic=(True, False), seed=seed_of(5), gravity=(0.1, -1.0))

    whole = gas().advance(until=6.0)
    split = gas()
    for t in (1.0, 2.5, 4.0):
        split.advance(until=t)
    split = pickle.loads(pickle.dumps(split))
    split.advance(until=6.0)
    assert np.array_equal(whole.positions, split.positions)
    assert np.array_equal(whole.velocities, split.velocities)
    assert whole.counts == split.counts


@pytest.mark.parametrize("slow", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_dilute_gas_follows_the_barometric_law(slow):
    """An elastic gas in a tall walled box settles into the barometric profile
    ``n(y) = n0 exp(-y / L)``, ``L = kT / (m g)`` (heights ``y`` of the centres above
    ``r``), with ``kT`` the time-averaged kinetic energy per disk.

    At the floor the gas is not quite ideal (``n0 = 0.04``, packing 0.03): with the
    second virial coefficient ``B2 = pi d^2 / 2`` hydrostatics ``dp/dy = -m g n`` with
    ``p = n kT (1 + B2 n)`` gives a mean height ``L (1 + B2 n0 / 2)`` to first order in
    ``B2 n0`` (3 % above ``L``; the next order is ~0.3 %), where ``n0`` follows from
    ``L (n0 + B2 n0^2) = N / width``.  Well above the floor the profile is the
    exponential: counts in ``[2L, 3L]`` and ``[3L, 4L]`` differ by the factor ``e``.
    """
    n, g, width = 400, 0.05, 800.0
    box = ed.Box(width, 300.0, periodic=(True, False))  # (> 25 decay lengths tall)
    rng = np.random.default_rng(seed_of(11))
    xs, ys = np.meshgrid(np.arange(134) * 5.9 + 1.0, [2.0, 5.0, 8.0])
    pos = np.c_[xs.ravel(), ys.ravel()][:n]
    sim = ed.Simulation(pos, rng.normal(size=(n, 2)), radii=0.5, box=box,
                        gravity=(0.0, -g))
    sim.advance(until=1000.0)  # (about 30 collisions a disk)
    samples = 4000 if slow else 400
    heights, kinetic = [], []
    for _ in range(samples):
        sim.advance(until=sim.time + 5.0)
        heights.append(sim.positions[:, 1] - 0.5)
        kinetic.append(sim.kinetic_energy())
    y = np.concatenate(heights)
    length = np.mean(kinetic) / n / g
    b2 = math.pi / 2.0
    n0 = (-1.0 + math.sqrt(1.0 + 4.0 * b2 * n / (width * length))) / (2.0 * b2)
    expected = length * (1.0 + 0.5 * b2 * n0)
    # A disk's height decorrelates over about its fall time from L, sqrt(2 L / g)
    # (~20): about one independent height per disk per 25 time units, each with
    # standard deviation ~L.
    independent = n * samples * 5.0 / 25.0
    sigma = length / math.sqrt(independent)
    assert abs(np.mean(y) - expected) < 4.0 * sigma + 0.005 * length
    upper = np.count_nonzero((y > 2 * length) & (y < 3 * length))
    top = np.count_nonzero((y > 3 * length) & (y < 4 * length))
    # (Poisson errors of the two counts, inflated by the correlation of the samples.)
    err = math.sqrt((1.0 / upper + 1.0 / top) * len(y) / independent)
    assert math.log(upper / top) == pytest.approx(1.0, abs=4.0 * err)


# ------------------------------------------------------------------ contact times
def _first_contact_sampled(p, v, a, d, t_max):
    """The first t in (0, t_max] at which |p + v t + a t^2/2| <= d, by dense sampling
    refined with bisection (an independent brute force)."""
    ts = np.linspace(0.0, t_max, 200_001)
    x = p[0] + ts * (v[0] + 0.5 * a[0] * ts)
    y = p[1] + ts * (v[1] + 0.5 * a[1] * ts)
    inside = x * x + y * y <= d * d
    if not inside[1:].any():
        return math.inf
    k = int(np.argmax(inside[1:])) + 1
    lo, hi = ts[k - 1], ts[k]
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        xm = p[0] + mid * (v[0] + 0.5 * a[0] * mid)
        ym = p[1] + mid * (v[1] + 0.5 * a[1] * mid)
        if xm * xm + ym * ym <= d * d:
            hi = mid
        else:
            lo = mid
    return hi


coord = st.floats(-5.0, 5.0)
# (No magnitudes so small that the textbook roots of the check itself cancel.)
coarse = coord.filter(lambda x: x == 0.0 or abs(x) > 1e-3)


@settings(max_examples=300, deadline=None)
@given(px=coord, py=coord, vx=coord, vy=coord, ax=coord, ay=coord,
       d=st.floats(0.1, 2.0))
def test_point_time_finds_the_first_contact(px, py, vx, vy, ax, ay, d):
    """The quartic contact against a brute-force sampling of the flight, for a start
    outside the contact distance (a dip below d shorter than the sampling step could
    be missed by the brute force alone: those are compared loosely)."""
    if px * px + py * py <= d * d * 1.0001 or ax * ax + ay * ay < 1e-6:
        return
    t_max = 20.0
    t = predict.point_time(px, py, vx, vy, ax, ay, d, t_max)
    ref = _first_contact_sampled((px, py), (vx, vy), (ax, ay), d, t_max)
    if ref < math.inf:
        assert t == pytest.approx(ref, rel=1e-9, abs=1e-9)
    elif t < math.inf:
        # Found where sampling saw nothing: a dip narrower than the sampling step.
        x = px + t * (vx + 0.5 * ax * t)
        y = py + t * (vy + 0.5 * ay * t)
        assert math.hypot(x, y) <= d * (1.0 + 1e-12)


@settings(max_examples=300, deadline=None)
@given(c=st.floats(0.0, 10.0), b=coarse, a=coarse)
def test_descend_time_is_the_falling_root(c, b, a):
    """``descend_time`` against the textbook roots (with the discriminant's sign
    decided in exact rational arithmetic): the first t >= 0 at which the gap
    c + b t + a t^2 falls through zero."""
    t = predict.descend_time(c, b, a)
    disc = Fraction(b) ** 2 - 4 * Fraction(a) * Fraction(c)
    if a != 0.0:
        roots = [] if disc < 0 else [(-b + sgn * math.sqrt(float(disc))) / (2 * a)
                                     for sgn in (-1.0, 1.0)]
    else:
        roots = [-c / b] if b else []
    falling = sorted(r for r in roots if r >= 0.0 and 2 * a * r + b < 0)
    if c == 0.0 and (b < 0.0 or (b == 0.0 and a < 0.0)):
        assert t == 0.0
    elif falling:
        assert t == pytest.approx(falling[0], rel=1e-9, abs=1e-12)
    else:
        assert t == math.inf or abs(2 * a * t + b) < 1e-6  # (a double root: a touch)


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize("bad, error, match", [
    ((0.0, np.inf), ValueError, "gravity"),
    ((0.0, np.nan), ValueError, "gravity"),
    ((1.0, 2.0, 3.0), ValueError, "gravity must have shape"),
    ("down", TypeError, "gravity must be numeric"),
    (9.81, ValueError, "gravity must have shape"),
])
def test_bad_gravity_is_refused_by_name(bad, error, match):
    with pytest.raises(error, match=match):
        ed.Simulation([[5.0, 5.0]], [[0.0, 0.0]], radii=0.5, box=WALLED, gravity=bad)


def test_a_disk_at_rest_on_the_floor_is_refused():
    with pytest.raises(ValueError, match=r"disks \[0\] rest on the box wall at y=0"):
        ed.Simulation([[5.0, 0.5]], [[1.0, 0.0]], radii=0.5, box=WALLED,
                      gravity=(0.0, -1.0))
    sim = ed.Simulation([[5.0, 0.5]], [[1.0, 1.0]], radii=0.5, box=WALLED,
                        gravity=(0.0, -1.0))
    before = sim.velocities
    with pytest.raises(ValueError, match="velocities: disks .* rest on the box wall"):
        sim.set_velocities([[0.0, 0.0]])
    with pytest.raises(ValueError, match="rest on the box wall"):
        ed.Simulation([[5.0, 0.5]], [[1.0, 0.0]], radii=0.5, box=WALLED,
                      gravity=(0.0, -1.0), wall_restitution=0.9, tc=0.0)
    assert np.array_equal(sim.velocities, before)


def test_zero_gravity_is_the_straight_line_engine():
    sim = ed.make_gas(50, 0.3, seed=seed_of(1), gravity=(0.0, 0.0))
    ref = ed.make_gas(50, 0.3, seed=seed_of(1))
    assert sim._gravity is None
    sim.advance(until=5.0)
    ref.advance(until=5.0)
    assert np.array_equal(sim.positions, ref.positions)


def test_floor_and_ceiling_carry_the_weight_of_the_gas():
    """Momentum balance along gravity, exactly: the impulses of floor and ceiling over
    a window, less the weight's N m g t, are the change of the gas's momentum; and
    measure's floor pressure times the floor's length is the weight, to within that
    change over the window."""
    n, g = 300, 0.4
    sim = ed.make_gas(n, 0.2, periodic=(True, False), seed=seed_of(8), gravity=(0.0, -g))
    sim.advance(until=50.0)
    acc0, p0, t0 = sim._accumulators(), sim.momentum()[1], sim.time
    m = sim.measure(duration=200.0)
    acc1, p1 = sim._accumulators(), sim.momentum()[1]
    floor, ceiling = (acc1["box_impulse"] - acc0["box_impulse"])[2:]
    weight = n * 1.0 * g * (sim.time - t0)
    assert floor - ceiling - weight == pytest.approx(p1 - p0, abs=1e-9 * weight)
    assert m.box_wall_pressures[2] * sim.box.width == pytest.approx(
        n * g, abs=abs(p1 - p0) / 200.0 + m.box_wall_pressures[3] * sim.box.width + 1e-9)


# ------------------------------------------------------------------ resting on points
def test_point_contact_at_rest_under_a_pressing_acceleration_is_now():
    """Touching, no relative velocity, the acceleration pressing the bodies together:
    the contact is now (not missed: the bodies would pass through each other)."""
    assert predict.point_time(0.0, -1.0, 0.0, 0.0, 0.0, 1.0, 1.0, math.inf) == 0.0
    # A rebound too small for rounding to lift the gap above zero comes back at its
    # turning point, not never.
    t = predict.point_time(0.0, 1.0, 0.0, 1e-17, 0.0, -1.0, 1.0, math.inf)
    assert 0.0 < t < 1e-15


def test_a_disk_at_rest_on_a_held_disk_stops_with_a_clear_error_without_resting():
    """Without disks coming to rest only box walls hold disks: a disk at rest on a disk
    held by the floor would bounce at one instant without end.  The run stops with an
    error that says so and what to change; nothing interpenetrates."""
    sim = ed.Simulation([[5.0, 0.5], [5.0, 1.5]], [[0.0, 0.0], [0.0, 0.0]], 0.5,
                        box=WALLED, gravity=(0.0, -1.0), restitution=0.5,
                        wall_restitution=0.5, tc=1e-4, resting=False)
    with pytest.raises(RuntimeError, match="let disks come to rest"):
        sim.advance(until=3.0)
    pos = sim.positions
    assert np.hypot(*(pos[0] - pos[1])) >= 1.0 - 1e-9


@pytest.mark.parametrize("peg", [True, False])
def test_an_elastic_disk_at_rest_on_a_peg_or_a_shelf_is_refused(peg):
    kwargs = (dict(masses=[np.inf, 1.0]) if peg
              else dict(walls=[ed.Wall((2.0, 5.0), (8.0, 5.0))]))
    pos = [[5.0, 4.0], [5.0, 5.0]] if peg else [[1.0, 1.0], [5.0, 5.5]]
    with pytest.raises(ValueError, match="rests on a wall segment or an immovable disk"):
        ed.Simulation(pos, [[0.0, 0.0], [0.0, 0.0]], 0.5, box=WALLED,
                      gravity=(0.0, -1.0), **kwargs)


def test_changing_gravity_books_the_jump_of_the_potential_energy():
    # Elastic: total energy less the work of the changes of gravity is constant.
    sim = ed.make_gas(200, 0.2, periodic=(True, False), gravity=(0.0, -1.0), seed=3)
    sim.advance(until=2.0)
    e0 = sim.total_energy()
    for g in [(0.5, -1.0), (0.0, -3.0), (-0.2, 0.7)]:
        sim.set_gravity(g)
        assert sim.total_energy() - sim.gravity_work() == pytest.approx(e0, rel=1e-12)
        sim.advance(until=sim.time + 2.0)
        assert np.array_equal(sim.gravity, g)
    assert sim.total_energy() - sim.gravity_work() == pytest.approx(e0, rel=1e-10)
    assert sim.dissipated_energy() == 0.0
