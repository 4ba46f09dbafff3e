"""Long runs: no overlaps ever, conservation laws, consistent counts, consistent advancing."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

import edmd2d as ed
from conftest import seed_of, segment_distance


def assert_no_overlap(sim, tol=1e-9):
    """No pair closer than (1 - tol) x contact distance; no disk through a wall."""
    p, r = sim.positions, sim.radii
    box = sim.box
    assert np.isfinite(p).all()
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            assert (p[:, axis] >= 0).all() and (p[:, axis] <= length).all()
        else:
            assert (p[:, axis] >= r * (1 - tol)).all()
            assert (p[:, axis] <= length - r * (1 - tol)).all()
    # cKDTree wants coordinates in [0, L) on periodic axes and a box on all of them:
    # give walled axes a box twice as large so nothing wraps there.
    size = np.where(box.periodic, box.size, 2 * box.size + 1)
    q = np.where(box.periodic, np.mod(p, box.size), p)
    q[q >= size] -= size[np.nonzero(q >= size)[1]]
    tree = cKDTree(q, boxsize=size)
    pairs = tree.query_pairs(2 * r.max())
    if pairs:
        i, j = np.array(sorted(pairs)).T
        d = q[i] - q[j]
        d -= size * np.round(d / size) * np.array(box.periodic)
        dist = np.hypot(*d.T)
        bad = dist < (r[i] + r[j]) * (1 - tol)
        assert not bad.any(), f"overlapping pairs {list(zip(i[bad], j[bad]))[:5]}"
    for w in sim.walls:
        assert (segment_distance(p, w) >= r * (1 - tol)).all()


@pytest.mark.parametrize("phi", [0.3, 0.7])
def test_periodic_gas_conserves_energy_and_momentum(phi):
    sim = ed.make_gas(2000, phi, seed=seed_of(7))
    e0, p0 = sim.kinetic_energy(), sim.momentum()
    scale = float(np.sum(sim.masses * np.hypot(*sim.velocities.T)))
    for _ in range(5):
        sim.advance(collisions=20_000)
        assert_no_overlap(sim)
        # 100 000 collisions, each conserving to ~1e-16: drift well below 1e-12.
        assert abs(sim.kinetic_energy() / e0 - 1) < 1e-12
        assert np.abs(sim.momentum() - p0).max() < 1e-12 * scale
    c = sim.counts
    assert c.collisions == 100_000
    assert c.events == c.collisions + c.wall_collisions + c.cell_crossings
    assert c.wall_collisions == 0


def test_mixture_in_walled_box_with_obstacles():
    rng = np.random.default_rng(seed_of(3))
    radii = np.where(rng.random(1500) < 0.5, 0.5, 0.7)
    sim0 = ed.make_gas(1500, 0.45, radii=radii, masses=radii**2, periodic=False, seed=seed_of(3))
    w, h = sim0.box.width, sim0.box.height
    # Put obstacles in: a divider with a gap and a triangle; drop disks that overlap them.
    walls = [ed.Wall((0.5 * w, 0.0), (0.5 * w, 0.4 * h)),
             ed.Wall((0.5 * w, 0.6 * h), (0.5 * w, h))]
    walls += ed.Wall.polygon([(0.2 * w, 0.2 * h), (0.3 * w, 0.25 * h), (0.22 * w, 0.35 * h)])
    p, r = sim0.positions, sim0.radii
    keep = np.ones(len(p), bool)
    for wall in walls:
        keep &= segment_distance(p, wall) > r * 1.01
    sim = ed.Simulation(p[keep], sim0.velocities[keep], r[keep], sim0.masses[keep],
                        box=sim0.box, walls=walls)
    e0 = sim.kinetic_energy()
    for _ in range(4):
        sim.advance(collisions=15_000)
        assert_no_overlap(sim)
        assert abs(sim.kinetic_energy() / e0 - 1) < 1e-12
    assert sim.counts.wall_collisions > 1000


def test_pegs_and_channel():
    # A channel periodic in x with walls in y, and a row of fixed pegs: energy is
    # conserved, x-momentum is not (the pegs push back), nothing overlaps.
    base = ed.make_gas(800, 0.35, periodic=(True, False), seed=seed_of(5))
    p, v = base.positions.copy(), base.velocities.copy()
    mass = np.ones(len(p))
    mass[::40] = np.inf
    v[::40] = 0.0
    sim = ed.Simulation(p, v, base.radii, mass, box=base.box)
    e0 = sim.kinetic_energy()
    sim.advance(collisions=30_000)
    assert_no_overlap(sim)
    assert abs(sim.kinetic_energy() / e0 - 1) < 1e-12
    np.testing.assert_array_equal(sim.positions[::40], p[::40])


def test_one_long_advance_equals_many_short_ones():
    a = ed.make_gas(500, 0.5, seed=seed_of(11))
    b = ed.make_gas(500, 0.5, seed=seed_of(11))
    a.advance(until=10.0)
    for k in range(1, 301):
        b.advance(until=k / 30)
    assert b.time == a.time == 10.0
    assert a.counts == b.counts
    # Local clocks: drifting to a frame time does not touch the stored state, so the
    # same events happen in the same order with the same arithmetic.
    np.testing.assert_allclose(b.positions, a.positions, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.velocities, a.velocities, rtol=0, atol=1e-12)


def test_unwrapped_positions_track_crossings():
    sim = ed.make_gas(200, 0.2, seed=seed_of(2))
    e = sim.kinetic_energy()
    vmax = np.sqrt(2 * e / sim.masses.min())  # no disk can be faster than this
    prev, prev_wrapped = sim.unwrapped_positions, sim.positions
    jumps = 0
    for k in range(1, 201):
        sim.advance(until=0.05 * k)
        unwrapped, wrapped = sim.unwrapped_positions, sim.positions
        # Unwrapped trajectories are continuous: no step longer than vmax * dt ...
        assert np.hypot(*(unwrapped - prev).T).max() <= vmax * 0.05 * (1 + 1e-9)
        # ... while the wrapped ones jump by a box length at the edges.
        jumps += int((np.abs(wrapped - prev_wrapped) > 0.5 * sim.box.size).sum())
        d = np.mod(unwrapped, sim.box.size) - wrapped
        d -= sim.box.size * np.round(d / sim.box.size)
        np.testing.assert_allclose(d, 0.0, atol=1e-9)
        prev, prev_wrapped = unwrapped, wrapped
    assert jumps > 20


def test_very_fast_disks_in_a_gas_do_not_tunnel():
    sim0 = ed.make_gas(400, 0.4, periodic=False, seed=seed_of(9))
    v = sim0.velocities.copy()
    v[:5] *= 1e6
    walls = [ed.Wall((0.5 * sim0.box.width, 0.0), (0.5 * sim0.box.width, 0.01))]
    sim = ed.Simulation(sim0.positions, v, sim0.radii, box=sim0.box, walls=walls)
    for t in (1e-6, 1e-5, 1e-4):
        sim.advance(until=t)
        assert_no_overlap(sim)


def test_interrupt_as_the_engine_returns_keeps_the_clock_consistent(monkeypatch):
    # Ctrl-C lands in Python right after the compiled loop returns.  The clock must
    # follow the processed events, or positions would be extrapolated backwards.
    from edmd2d._engine import layout, loop

    sim = ed.make_gas(2000, 0.5, seed=seed_of(31))
    real_run = loop.run

    def interrupted_run(*args):
        real_run(*args)
        raise KeyboardInterrupt

    monkeypatch.setattr(loop, "run", interrupted_run)
    with pytest.raises(KeyboardInterrupt):
        sim.advance(collisions=50_000)
    monkeypatch.setattr(loop, "run", real_run)
    assert 0 < sim.counts.collisions <= 50_000  # the first engine call ran, then Ctrl-C
    assert sim.time == pytest.approx(sim._S[:, layout.T].max(), abs=0)
    assert_no_overlap(sim)
    sim.advance(until=sim.time + 1.0)
    assert_no_overlap(sim)
