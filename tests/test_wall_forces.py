"""Forces on wall segments and gases in polygon containers.

Per-segment tallies: exact hand-computed cases (one disk bouncing between two parallel
segments, an end point, an inelastic wall), exact sums (the segments' impulses add up
to the total, and with the box walls' they balance the gas's change of momentum), the
virial theorem with the walls of a polygon (exact to rounding, boundary term
included), and old pickles.  The container's area: closed polygons found among the
walls, nested, crossing or open.  And a gas in an octagonal container against the
hard-disk equation of state, both through the force per length on the walls and
through the virial pressure with the container's area.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d import geometry, measurements, theory

# As in test_measure.py: tolerance in block-average standard errors, and the allowance
# for the O(1/N) shift of a finite system.
K_SIGMA = 4.0
FINITE_SIZE = 1.0
A = 0.5  # the disks' radius


def regular_polygon(k, rc, centre, phase=None):
    """Vertices (counterclockwise) of a regular k-gon of circumradius rc."""
    phase = math.pi / k if phase is None else phase
    angle = phase + 2 * np.pi * np.arange(k) / k
    return np.asarray(centre) + rc * np.stack([np.cos(angle), np.sin(angle)], axis=1)


def gas_in_polygon(vertices, eta, seed, pieces=1, box_margin=1.0):
    """Equal disks (radius A, kT = 1) at packing ``eta`` of the convex polygon
    ``vertices`` (either orientation), which stands inside a closed box ``box_margin``
    wider on every side; each side is cut into ``pieces`` collinear segments.  The
    disks start on a triangular lattice clear of the walls, at random sites."""
    v = np.asarray(vertices, float)
    lo = v.min(axis=0) - box_margin
    v = v - lo
    w, h = v.max(axis=0) + box_margin
    area = abs(geometry._shoelace(v))
    n = int(round(eta * area / (math.pi * A * A)))
    edges = np.roll(v, -1, axis=0) - v
    inward = np.stack([-edges[:, 1], edges[:, 0]], axis=1)
    inward *= np.sign(geometry._shoelace(v)) / np.hypot(*inward.T)[:, None]
    spacing = 1.02 * 2 * A
    xs = np.arange(0.0, w, spacing)
    ys = np.arange(0.0, h, spacing * math.sqrt(3) / 2)
    sites = np.array([(x + (0.5 * spacing if j % 2 else 0.0), y)
                      for j, y in enumerate(ys) for x in xs])
    clear = (((sites[:, None, :] - v[None]) * inward[None]).sum(axis=-1) > A + 0.05).all(axis=1)
    sites = sites[clear]
    assert len(sites) >= n
    rng = np.random.default_rng(seed)
    pos = sites[rng.choice(len(sites), n, replace=False)]
    vel = rng.normal(size=(n, 2))
    vel *= math.sqrt(2 * n / (vel**2).sum())  # kT = sum m v^2 / (2N) = 1 exactly
    walls = []
    for a, b in zip(v, np.roll(v, -1, axis=0)):
        cuts = [a + (b - a) * s for s in np.linspace(0.0, 1.0, pieces + 1)[1:-1]]
        pts = [a, *cuts, b]
        walls += [ed.Wall(p, q) for p, q in zip(pts[:-1], pts[1:])]
    sim = ed.Simulation(pos, vel, A, box=ed.Box(w, h, periodic=False), walls=walls)
    return sim, v


def virial_of_positions(sim):
    """``G = sum m r . v`` of the movable disks (positions unwrapped)."""
    movable = np.isfinite(sim.masses)
    r = sim.unwrapped_positions[movable]
    v = sim.velocities[movable]
    return float((sim.masses[movable][:, None] * r * v).sum())


def momentum(sim):
    movable = np.isfinite(sim.masses)
    return sim.masses[movable] @ sim.velocities[movable]


def box_impulse_vector(box_impulse):
    """The impulse vector the four box walls received (x=0 is pushed towards -x, ...)."""
    j = np.asarray(box_impulse)
    return np.array([j[1] - j[0], j[3] - j[2]])


# --------------------------------------------------------------------------- exact cases
def test_disk_between_two_parallel_segments_exact():
    # Disk 0 (radius 0.5, mass 1, speed v = 2 along x) flies between the vertical
    # segments x = 2 (walls[0], from y = 3 up to 9) and x = 8 (walls[1], from (8, 3) up
    # to (8, 9)); its centre turns at x = 2.5 and 7.5, a flight of L = 5: each segment
    # gets the impulse 2 m v = 4 every 2 L / v = 5, a mean force m v^2 / L = 0.8, and
    # a pressure 0.8 / 6 on the side it faces (walls[1]'s left side, since going up
    # along it the left is -x; walls[0]'s right side).
    # Disk 1 (speed 1 along y) flies between the box wall y = 0 and the end point
    # (8, 3) of walls[1] at x = 8: its centre turns at y = 0.5 and y = 2.5, and each
    # gets the impulse 2 every 4: the end point pushes walls[1] up by a mean 0.5,
    # which is in its force but not on either side's pressure.
    box = ed.Box(10.0, 10.0, periodic=False)
    walls = [ed.Wall((2.0, 3.0), (2.0, 9.0)), ed.Wall((8.0, 3.0), (8.0, 9.0))]
    sim = ed.Simulation([[5.0, 5.0], [8.0, 1.5]], [[2.0, 0.0], [0.0, 1.0]], radii=0.5,
                        box=box, walls=walls)
    # 10 blocks of 20 (a multiple of both periods 5 and 4), no event on a boundary:
    # each block holds the same contacts, so the block errors vanish.
    m = sim.measure(duration=200.0, blocks=10)
    assert m.collisions == 0
    assert m.wall_collisions == 2 * 40 + 2 * 50
    np.testing.assert_array_equal(m.segment_contacts, [40, 40 + 50])
    np.testing.assert_allclose(m.segment_forces, [[-0.8, 0.0], [0.8, 0.5]], rtol=1e-12,
                               atol=1e-15)
    np.testing.assert_allclose(m.segment_pressures, [[0.0, 0.8 / 6], [0.8 / 6, 0.0]],
                               rtol=1e-12)
    np.testing.assert_allclose(m.segment_pressures_error, 0.0, atol=1e-12)
    np.testing.assert_allclose(m.segment_forces_error, 0.0, atol=1e-12)
    assert m.segment_pressure == pytest.approx(2 * 0.8 / 12, rel=1e-12)
    assert m.segment_force == pytest.approx(0.8 + 0.8 + 0.5, rel=1e-12)
    assert m.box_wall_pressures == pytest.approx((0.0, 0.0, 0.5 / 10, 0.0), abs=1e-15)
    # Two open segments close no container: the box's area.
    assert m.area == box.area and m.area_source == "box"
    acc = sim._accumulators()
    np.testing.assert_allclose(acc["segment_end_impulses"], [0.0, 2.0 * 50], rtol=1e-12)
    text = m.summary()
    assert "segment pressure" in text and "walls[1] left" in text
    assert "box wall pressure" in text  # (the box wall y = 0 is hit)


def test_inelastic_wall_segments_tally_the_impulse_delivered():
    # Restitution e = 0.5 at the walls: a disk of speed v0 = 1 between the segments of
    # the case above leaves its k-th contact at speed e^k, so the k-th impulse is
    # (1 + e) e^(k-1) and the segments together receive (1 + e)(1 - e^K) / (1 - e)
    # after K contacts.  (The contacts are far apart: the TC model keeps them
    # inelastic.)
    box = ed.Box(10.0, 10.0, periodic=False)
    walls = [ed.Wall((2.0, 3.0), (2.0, 9.0)), ed.Wall((8.0, 3.0), (8.0, 9.0))]
    sim = ed.Simulation([[5.0, 5.0]], [[1.0, 0.0]], radii=0.5, box=box, walls=walls,
                        wall_restitution=0.5)
    sim.advance(until=73.0)  # contacts at 2.5, then 10, 20 and 40 later: 72.5
    e, k = 0.5, 4
    acc = sim._accumulators()
    total = (1 + e) * (1 - e**k) / (1 - e)
    assert acc["segment_impulse"] == pytest.approx(total, rel=1e-14)
    # walls[1] (right) gets contacts 1 and 3, walls[0] contacts 2 and 4.
    right = (1 + e) * (1 + e**2)
    left = (1 + e) * (e + e**3)
    np.testing.assert_allclose(acc["segment_side_impulses"], [[0.0, left], [right, 0.0]],
                               rtol=1e-14)
    np.testing.assert_allclose(acc["segment_impulses"], [[-left, 0.0], [right, 0.0]],
                               rtol=1e-14, atol=1e-15)
    np.testing.assert_array_equal(acc["segment_contacts"], [2, 2])
    assert sim.dissipated_energy() == pytest.approx(0.5 * (1 - e ** (2 * k)), rel=1e-14)


def test_polygon_orientation_chooses_the_side():
    # The inside of a counterclockwise polygon is the left side of its segments, that
    # of a clockwise one the right side; a gas around a closed obstacle touches the
    # outside.
    ccw = regular_polygon(6, 8.0, (10.0, 10.0))
    for vertices, side in ((ccw, 0), (ccw[::-1], 1)):
        sim, _ = gas_in_polygon(vertices, 0.2, seed=seed_of(1))
        m = sim.measure(duration=20.0)
        assert (m.segment_pressures[:, side] > 0).all()
        assert (m.segment_pressures[:, 1 - side] == 0).all()
        assert m.area == pytest.approx(abs(geometry._shoelace(vertices)), rel=1e-12)


# --------------------------------------------------------------------------- exact sums
def test_segment_impulses_sum_to_the_total_and_balance_the_momentum():
    # Sides and end points of every segment add up to the engine's total over all
    # segments; the impulse vectors of the segments and of the box walls are what the
    # gas's momentum lost (disk-disk collisions conserve it), to rounding.  Two
    # systems: a walled box with a closed triangle (its corners are end points the gas
    # hits from outside), an open polyline and a thin wall; a periodic box with a wall
    # that crosses the periodic edge (hit through its image as well).
    g = ed.make_gas(150, 0.25, periodic=False, seed=seed_of(3))
    w, h = g.box.width, g.box.height
    walls = (ed.Wall.polygon([(0.45 * w, 0.45 * h), (0.6 * w, 0.45 * h), (0.5 * w, 0.6 * h)])
             + ed.Wall.polygon([(0.1 * w, 0.8 * h), (0.2 * w, 0.9 * h), (0.3 * w, 0.8 * h)],
                               closed=False)
             + [ed.Wall((0.8 * w, 0.1 * h), (0.8 * w, 0.3 * h))])
    clear = np.ones(len(g), bool)
    for wall in walls:
        a, b = np.array(wall.start), np.array(wall.end)
        s = np.clip((g.positions - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
        clear &= np.hypot(*(g.positions - a - s[:, None] * (b - a)).T) > A + 0.01
    inside = geometry._inside_polygon(g.positions, np.array([w.start for w in walls[:3]]))
    keep = clear & ~inside
    walled = ed.Simulation(g.positions[keep], g.velocities[keep], A, box=g.box, walls=walls)

    g = ed.make_gas(150, 0.25, seed=seed_of(4))
    w, h = g.box.width, g.box.height
    walls = [ed.Wall((0.0, 0.5 * h), (0.3 * w, 0.5 * h)), ed.Wall((0.8 * w, 0.5 * h), (w, 0.5 * h))]
    keep = np.abs(g.positions[:, 1] - 0.5 * h) > A + 0.01
    periodic = ed.Simulation(g.positions[keep], g.velocities[keep], A, box=g.box, walls=walls)

    for sim in (walled, periodic):
        p0 = momentum(sim)
        contacts0 = sim.counts.wall_collisions
        sim.advance(until=60.0)
        acc = sim._accumulators()
        assert acc["segment_contacts"].sum() > 100
        per_segment = acc["segment_side_impulses"].sum(axis=1) + acc["segment_end_impulses"]
        assert per_segment.sum() == pytest.approx(acc["segment_impulse"], rel=1e-12)
        received = acc["segment_impulses"].sum(axis=0) + box_impulse_vector(acc["box_impulse"])
        np.testing.assert_allclose(received, p0 - momentum(sim),
                                   atol=1e-10 * acc["segment_impulse"])
        # Each segment's impulse vector is at most its sum of magnitudes.
        assert (np.hypot(*acc["segment_impulses"].T) <= per_segment * (1 + 1e-12)).all()
        box_contacts = sim.counts.wall_collisions - contacts0 - acc["segment_contacts"].sum()
        assert box_contacts >= 0
        if sim is periodic:
            assert box_contacts == 0
    acc = walled._accumulators()
    assert acc["segment_end_impulses"][:3].sum() > 0  # the triangle's corners
    assert (acc["segment_side_impulses"][:3, 0] == 0).all()  # never from inside


def test_virial_theorem_with_the_walls_of_a_polygon_is_exact():
    # d/dt sum m r.v = 2K + sum r.F.  A disk-disk collision adds J |r_ij| to
    # sum r.p, a contact on a side J n . r = J (n . s + a) (n: the side's unit normal
    # towards the disk, s: any point of the side, the centre lying a from its line).
    # Integrated over a window of length t (K constant):
    #   G(t) - G(0) = 2 K t + sum J |r_ij| + sum_sides J_side (n . s + a)
    # exactly, with no statistics: a check of each side's tally and orientation.
    # Convex containers (never touched at their corners from inside), one clockwise.
    pentagon = [(1.0, 1.0), (15.0, 2.0), (18.0, 11.0), (9.0, 17.0), (2.0, 12.0)]
    hexagon = regular_polygon(6, 9.0, (10.0, 10.0))[::-1]
    for vertices in (pentagon, hexagon):
        sim, _ = gas_in_polygon(vertices, 0.3, seed=seed_of(5), pieces=2)
        sim.advance(collisions=5000)
        acc0, g0, t0 = sim._accumulators(), virial_of_positions(sim), sim.time
        kinetic = sim.kinetic_energy()
        sim.advance(until=t0 + 100.0)
        acc1, g1 = sim._accumulators(), virial_of_positions(sim)
        sides = acc1["segment_side_impulses"] - acc0["segment_side_impulses"]
        assert (acc1["segment_end_impulses"] == 0).all()
        assert (acc1["box_impulse"] == 0).all()
        wall_term = 0.0
        for wall, (j_left, j_right) in zip(sim.walls, sides):
            s, e = np.array(wall.start), np.array(wall.end)
            left = np.array([s[1] - e[1], e[0] - s[0]]) / wall.length
            wall_term += j_left * (left @ s + A) + j_right * (-(left @ s) + A)
        pair = acc1["virial"] - acc0["virial"]
        rhs = 2 * kinetic * (sim.time - t0) + pair + wall_term
        assert g1 - g0 == pytest.approx(rhs, abs=1e-9 * pair)
        # (G is stationary: its change over the window is a fluctuation of order
        # sqrt(N) |r| m v, about 1 % of the pair term here, not a systematic part.)
        assert abs(g1 - g0) < 0.05 * pair


def test_pickles_keep_the_per_segment_tallies_and_old_ones_are_refused():
    # A pickle holds the per-segment tallies and runs on exactly like the original; a
    # pickle of the format that held the Simulation's attributes (version 1, which
    # could lack the tallies) is refused with a message that names its version.
    sim, _ = gas_in_polygon(regular_polygon(8, 8.0, (10.0, 10.0)), 0.3, seed=seed_of(6))
    sim.advance(collisions=2000)
    twin = pickle.loads(pickle.dumps(sim))
    sim.advance(collisions=3000)
    twin.advance(collisions=3000)
    assert np.array_equal(sim.positions, twin.positions) and sim.counts == twin.counts
    after, got = sim._accumulators(), twin._accumulators()
    assert got["segment_impulses"].shape == (8, 2) and got["segment_contacts"].sum() > 0
    for key in after:
        np.testing.assert_array_equal(got[key], after[key])
    old = {"_" + key: value for key, value in twin._state.__getstate__().items()
           if key != "wacc"}
    with pytest.raises(ValueError, match="format version 1"):
        ed.Simulation.__new__(ed.Simulation).__setstate__(old)


def test_no_segments_no_segment_values():
    m = ed.make_gas(60, 0.3, seed=seed_of(2)).measure(duration=5.0)
    assert m.segment_forces.shape == (0, 2) and m.segment_pressures.shape == (0, 2)
    assert m.segment_contacts.shape == (0,) and math.isnan(m.segment_pressure)
    assert "segment" not in m.summary() and m.area_source == "box"


# --------------------------------------------------------------------------- container area
def two_disks(box, walls, positions=((3.0, 3.0), (4.5, 3.0)), masses=1.0):
    return ed.Simulation(list(positions), [[1.0, 0.0]] + [[0.0, 1.0]] * (len(positions) - 1),
                         radii=0.25, masses=masses, box=box, walls=walls)


def test_container_area_of_closed_polygons():
    box = ed.Box(20.0, 20.0, periodic=False)
    square = ed.Wall.polygon([(1, 1), (11, 1), (11, 11), (1, 11)])
    inner = ed.Wall.polygon([(5, 5), (8, 5), (8, 8), (5, 8)])
    area = measurements.container_area
    assert area(two_disks(box, square)) == pytest.approx(100.0, rel=1e-14)
    # Clockwise: the same area.
    assert area(two_disks(box, ed.Wall.polygon([(1, 1), (1, 11), (11, 11), (11, 1)]))) == 100.0
    # The disks between the square and an obstacle inside it: the area between them.
    assert area(two_disks(box, square + inner)) == pytest.approx(91.0, rel=1e-14)
    # Disks in the obstacle too: both regions.
    assert area(two_disks(box, square + inner, ((3, 3), (6.5, 6.5)))) == pytest.approx(100.0)
    # Outside every polygon: the box less the outermost polygon.
    assert area(two_disks(box, square + inner, ((15, 15), (15, 17)))) == pytest.approx(300.0)
    # Two separate containers, each holding a disk: the sum.
    other = ed.Wall.polygon([(13, 13), (19, 13), (16, 19)])
    assert area(two_disks(box, square + other, ((3, 3), (16, 15)))) == pytest.approx(118.0)
    # Immovable disks do not count: the movable one is inside the square.
    assert area(two_disks(box, square, ((3, 3), (15, 15)), [1.0, np.inf])) == 100.0
    # End points that differ by rounding still close the polygon.
    nudged = [ed.Wall((1, 1), (11, 1)), ed.Wall((11, 1 + 1e-13), (11, 11)),
              ed.Wall((11, 11), (1, 11)), ed.Wall((1, 11), (1 + 1e-13, 1))]
    assert area(two_disks(box, nudged)) == pytest.approx(100.0, rel=1e-12)
    # A polygon of collinear pieces is a polygon.
    pieces = [ed.Wall((1, 1), (6, 1)), ed.Wall((6, 1), (11, 1)), *square[1:]]
    assert area(two_disks(box, pieces)) == pytest.approx(100.0, rel=1e-14)


def test_container_area_falls_back_to_the_box():
    box = ed.Box(20.0, 20.0, periodic=False)
    square = [(1, 1), (11, 1), (11, 11), (1, 11)]
    cases = {
        "open polyline": ed.Wall.polygon(square, closed=False),
        "a gap": ed.Wall.polygon(square)[:3] + [ed.Wall((1, 11), (1, 1.5))],
        # Two squares sharing a side: its end points join three segments.
        "branching": ed.Wall.polygon(square) + ed.Wall.polygon([(11, 1), (17, 1), (17, 11),
                                                               (11, 11)])[:3],
        "crossing": ed.Wall.polygon(square) + ed.Wall.polygon([(6, 6), (16, 6), (16, 16),
                                                              (6, 16)]),
        "self-crossing": ed.Wall.polygon([(1, 1), (11, 11), (11, 1), (1, 11)]),
    }
    for name, walls in cases.items():
        positions = ((3.0, 5.0), (3.0, 6.5))
        sim = two_disks(box, walls, positions)
        if "crossing" in name:  # (closed loops that cross: said, not silent)
            with pytest.warns(UserWarning, match="cross or touch"):
                assert measurements.container_area(sim) == box.area, name
        else:
            assert measurements.container_area(sim) == box.area, name
        assert sim.measure(duration=1.0).area_source == "box", name


def test_measure_takes_the_area():
    sim, v = gas_in_polygon(regular_polygon(8, 8.0, (10.0, 10.0)), 0.3, seed=seed_of(7))
    sim.advance(collisions=3000)
    twin = pickle.loads(pickle.dumps(sim))
    m = sim.measure(duration=10.0)
    given = twin.measure(duration=10.0, area=2 * m.area)
    assert m.area_source == "walls" and given.area_source == "given"
    assert given.area == 2 * m.area
    assert given.pressure == pytest.approx(m.pressure / 2, rel=1e-12)
    assert given.compressibility_factor == pytest.approx(m.compressibility_factor, rel=1e-12)
    assert "area" in m.summary() and "given" in given.summary()
    with pytest.raises(ValueError, match="area"):
        sim.measure(duration=1.0, area=0.0)
    with pytest.raises(ValueError, match="area"):
        sim.measure(duration=1.0, area=math.inf)
    with pytest.raises(TypeError, match="area"):
        sim.measure(duration=1.0, area="100")


def test_summary_of_a_gas_in_a_polygon_container():
    # The report that motivated the per-segment tallies: the box walls are never
    # touched, so the summary gives the segments' pressure, not "wall pressure 0 +- 0".
    sim, _ = gas_in_polygon(regular_polygon(8, 8.0, (10.0, 10.0)), 0.3, seed=seed_of(8))
    m = sim.measure(duration=20.0)
    text = m.summary()
    assert "wall pressure" not in text
    assert "segment pressure" in text and "8 sides touched" in text
    assert text.count("walls[") == 8
    assert m.segment_pressure > 0 and 0 < m.segment_pressure_error < 0.2 * m.segment_pressure


# --------------------------------------------------------------------------- equation of state
def test_gas_in_an_octagon_reproduces_the_equation_of_state():
    # 563 disks at packing 0.25 of an octagon of circumradius 25 (sides 19.1 long, cut
    # in thirds), standing in a box of twice its area, run for 2000 time units (1.6e6
    # collisions) in frames of 2.
    #
    # Walls: mechanical equilibrium makes the force per length on a flat wall, far
    # from corners, the bulk pressure at the density of the bulk (the contact
    # theorem).  The middle thirds of the sides (6 diameters from the corners) must
    # give P_EOS(n_bulk) = n_bulk kT Z(eta_bulk), with n_bulk counted in a circle 4
    # diameters clear of the walls (0.327, against the container's mean 0.318: the
    # layer of higher density at the walls is fed from the bulk), within the run's
    # error (0.3% here) and the O(1/N) finite-size shift.  The whole sides give less:
    # within a cot(theta / 2) of a corner (theta = 135 degrees) no centre touches the
    # side, a share 2 a cot(theta / 2) / side = 2.2% of its length (measured: -1.9%).
    #
    # Virial: with the container's area A the virial pressure obeys (for a regular
    # polygon, exactly: see the test above) P A = p_wall (A - a L / 2), L the
    # perimeter; the relative surface term a L / (2 A) = 2.2% bounds how far P may lie
    # from the equation of state at the mean density N / A (measured: +0.6%).  With
    # the box's area it would be 50% off.
    k, rc = 8, 25.0
    vertices = regular_polygon(k, rc, (0.0, 0.0))
    sim, v = gas_in_polygon(vertices, 0.25, seed=seed_of(11), pieces=3, box_margin=7.0)
    n = len(sim)
    centre = v.mean(axis=0)
    r_in = rc * math.cos(math.pi / k)
    side = 2 * rc * math.sin(math.pi / k)
    area = 0.5 * k * rc * rc * math.sin(2 * math.pi / k)
    perimeter = k * side
    r_bulk = r_in - 4.0
    middle = np.arange(1, 3 * k, 3)
    sim.advance(collisions=200 * n // 2)

    blocks, frames, dt = 20, 50, 2.0
    rows = []
    for _ in range(blocks):
        frame = []
        for _ in range(frames):
            m = sim.measure(duration=dt, blocks=1)
            inside = np.hypot(*(sim.positions - centre).T) < r_bulk
            frame.append((m.segment_pressures[middle, 0].mean(), m.segment_pressure,
                          m.compressibility_factor, np.count_nonzero(inside)))
        rows.append(np.mean(frame, axis=0))
    rows = np.array(rows)
    mean = rows.mean(axis=0)
    err = rows.std(axis=0, ddof=1) / math.sqrt(blocks)
    p_middle, p_walls, z_virial, count = mean
    assert m.area_source == "walls" and m.area == pytest.approx(area, rel=1e-12)
    assert (m.segment_pressures[:, 1] == 0).all()
    kt = ed.kinetic_temperature(sim)
    assert kt == pytest.approx(1.0, rel=1e-12)

    n_bulk = count / (math.pi * r_bulk**2)
    n_bulk_err = err[3] / (math.pi * r_bulk**2)
    eta_bulk = n_bulk * math.pi * A * A

    def p_eos(density):
        return density * kt * theory.henderson_z(density * math.pi * A * A)

    h = 1e-5
    dp_dn = (p_eos(n_bulk + h) - p_eos(n_bulk - h)) / (2 * h)
    p_bulk = p_eos(n_bulk)
    assert n_bulk > n / area  # (the walls' layer is fed from the bulk)
    # Middle thirds: the bulk pressure.
    sigma = math.hypot(err[0], dp_dn * n_bulk_err)
    assert 0 < sigma < 0.01 * p_bulk
    assert abs(p_middle - p_bulk) < K_SIGMA * sigma + FINITE_SIZE * p_bulk / n, \
        (p_middle, p_bulk, sigma, eta_bulk)
    # Whole sides: the bulk pressure less at most the corners' share.
    corners = 2 * A / math.tan(0.5 * (math.pi - 2 * math.pi / k)) / side
    sigma = math.hypot(err[1], dp_dn * n_bulk_err)
    assert p_bulk * (1 - corners) - K_SIGMA * sigma < p_walls < p_bulk + K_SIGMA * sigma
    # Virial pressure with the container's area.
    z_eos = theory.henderson_z(n * math.pi * A * A / area)
    surface = A * perimeter / (2 * area)
    assert 0 < err[2] < 0.01 * z_eos
    assert abs(z_virial - z_eos) < surface * z_eos + K_SIGMA * err[2], (z_virial, z_eos)
    assert sim.box.area > 2 * area
    assert abs(z_virial * area / sim.box.area - z_eos) > 0.4 * z_eos


def test_container_area_edge_cases_warn_or_fall_back():
    import warnings as _warnings

    box = ed.Box(10.0, 10.0, periodic=False)
    square = ed.Wall.polygon([(1.0, 1.0), (9.0, 1.0), (9.0, 9.0), (1.0, 9.0)])
    a = ed.Wall.polygon([(3.0, 3.0), (5.0, 3.0), (5.0, 5.0), (3.0, 5.0)])
    b = ed.Wall.polygon([(4.0, 4.0), (6.0, 4.0), (6.0, 6.0), (4.0, 6.0)])  # crosses a
    sim = ed.Simulation([[2.0, 2.0]], [[1.0, 0.3]], 0.5, box=box, walls=square + a + b)
    with pytest.warns(UserWarning, match="cross or touch"):
        assert measurements.container_area(sim) == 100.0
    # No movable disk: nothing to hold, the box's area (and measure does not divide by 0).
    peg = ed.Simulation([[5.0, 5.0]], [[0.0, 0.0]], 0.5, masses=np.inf, box=box,
                        walls=square)
    with _warnings.catch_warnings():
        _warnings.simplefilter("error")
        assert measurements.container_area(peg) == 100.0
