"""make_gas: the box, the lattice start and the Maxwell-Boltzmann velocities."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

import edmd2d as ed
from conftest import seed_of, segment_distance


@pytest.mark.parametrize("periodic", [True, False, (True, False)])
@pytest.mark.parametrize("phi", [0.05, 0.5, 0.72])
def test_packing_fraction_temperature_momentum(periodic, phi):
    sim = ed.make_gas(1000, phi, periodic=periodic, temperature=2.5, seed=seed_of(1))
    assert np.pi * np.sum(sim.radii**2) / sim.box.area == pytest.approx(phi, rel=1e-12)
    assert sim.box.periodic == ed.Box(1, 1, periodic=periodic).periodic
    dof = 2 * 1000 - sum(sim.box.periodic)  # momentum is conserved along periodic axes
    assert 2 * sim.kinetic_energy() / dof == pytest.approx(2.5, rel=1e-12)
    assert ed.kinetic_temperature(sim) == pytest.approx(2.5, rel=1e-9)
    np.testing.assert_allclose(sim.momentum(), 0.0, atol=1e-10)


def test_reproducible_and_seed_dependent():
    a, b, c = (ed.make_gas(300, 0.4, seed=s) for s in (5, 5, 6))
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.velocities, b.velocities)
    assert not np.array_equal(a.velocities, c.velocities)


def test_velocities_are_maxwell_boltzmann():
    # Each component of m^(1/2) v is normal with variance kT (up to the tiny rescaling).
    sim = ed.make_gas(20_000, 0.3, masses=np.linspace(1, 4, 20_000), temperature=0.7,
                      seed=seed_of(2))
    u = (sim.velocities * np.sqrt(sim.masses)[:, None] / np.sqrt(0.7)).ravel()
    assert stats.kstest(u, "norm").pvalue > 1e-3


def test_mixture_and_aspect():
    rng = np.random.default_rng(seed_of(0))
    radii = np.where(rng.random(999) < 0.5, 0.5, 0.7)
    sim = ed.make_gas(999, 0.6, radii=radii, aspect=2.0, seed=seed_of(4))
    assert sim.box.width == pytest.approx(2 * sim.box.height)
    assert sorted(sim.radii) == sorted(radii)  # same species, shuffled over the sites
    assert np.pi * np.sum(sim.radii**2) / sim.box.area == pytest.approx(0.6)


def test_a_lattice_start_melts():
    # At packing fraction 0.5 the fluid forgets the lattice: the bond-orientational
    # order of the start (|psi6| = 1 on a perfect triangular lattice) decays.
    sim = ed.make_gas(900, 0.5, seed=seed_of(8))
    p0 = sim.unwrapped_positions
    sim.advance(collisions=900 * 50)
    msd = np.mean(np.sum((sim.unwrapped_positions - p0) ** 2, axis=1))
    assert msd > 1.0  # disks left their sites by more than a diameter on average


@pytest.mark.parametrize(
    "args, kwargs, pattern",
    [
        ((0, 0.3), {}, "n must be >= 1"),
        ((-5, 0.3), {}, "n must be >= 1, got -5"),
        ((10.5, 0.3), {}, "n must be an integer"),
        ((100, 0.0), {}, "packing_fraction must be > 0"),
        ((100, 0.95), {}, r"cannot be reached .* the limit is about 0\.\d+"),
        ((100, 0.3), {"radius": -1}, "radius must be > 0"),
        ((100, 0.3), {"radii": np.ones(5)}, r"radii must have shape \(100,\)"),
        ((100, 0.3), {"masses": np.inf}, "masses contains NaN or infinite"),
        ((100, 0.3), {"temperature": -1}, "temperature must be >= 0"),
        ((100, 0.3), {"aspect": 0}, "aspect must be > 0"),
    ],
)
def test_bad_arguments(args, kwargs, pattern):
    with pytest.raises((TypeError, ValueError), match=pattern):
        ed.make_gas(*args, **kwargs)


def test_limit_is_consistent_with_make_gas():
    limit = ed.lattice_packing_limit(500, periodic=False)
    ed.make_gas(500, 0.999 * limit, periodic=False)
    with pytest.raises(ValueError, match="cannot be reached"):
        ed.make_gas(500, 1.001 * limit, periodic=False)


# --------------------------------------------------------------------------- random_packing
def assert_no_overlap(pos, rad, box):
    from scipy import spatial

    bsize = [length if p else 2 * length for length, p in zip(box.size, box.periodic)]
    pairs = spatial.cKDTree(pos, boxsize=bsize).query_pairs(2 * rad.max(), output_type="ndarray")
    d = pos[pairs[:, 1]] - pos[pairs[:, 0]]
    for axis, length in enumerate(box.size):
        if box.periodic[axis]:
            d[:, axis] -= length * np.round(d[:, axis] / length)
    dist = np.hypot(d[:, 0], d[:, 1])
    assert (dist >= (rad[pairs[:, 0]] + rad[pairs[:, 1]]) * (1 + 1e-10)).all()


@pytest.mark.parametrize("periodic", [True, False, (True, False)])
@pytest.mark.parametrize("phi", [0.05, 0.3, 0.5])
def test_random_packing_fraction_no_overlap_inside(periodic, phi):
    pos, rad, box = ed.random_packing(2000, phi, periodic=periodic, aspect=1.5, seed=seed_of(1))
    assert pos.shape == (2000, 2) and rad.shape == (2000,)
    assert box.periodic == ed.Box(1, 1, periodic=periodic).periodic
    assert np.pi * np.sum(rad**2) / box.area == pytest.approx(phi, rel=1e-12)
    assert box.width == pytest.approx(1.5 * box.height)
    assert_no_overlap(pos, rad, box)
    for axis, length in enumerate(box.size):
        if box.periodic[axis]:
            assert ((pos[:, axis] >= 0) & (pos[:, axis] < length)).all()
        else:  # at least one radius from the walls
            assert (pos[:, axis] - rad > 0).all() and (length - pos[:, axis] - rad > 0).all()


def test_random_packing_is_uniform():
    pos, rad, box = ed.random_packing(20_000, 0.3, seed=seed_of(2))
    for axis, length in enumerate(box.size):
        assert stats.kstest(pos[:, axis] / length, "uniform").pvalue > 1e-3


def test_random_packing_reproducible_and_seed_dependent():
    a, b, c = (ed.random_packing(500, 0.45, seed=seed_of(s)) for s in (5, 5, 6))
    np.testing.assert_array_equal(a[0], b[0])
    assert not np.array_equal(a[0], c[0])
    rng = np.random.default_rng(seed_of(5))
    d = ed.random_packing(500, 0.45, seed=rng)
    np.testing.assert_array_equal(a[0], d[0])  # a Generator with that seed: the same


def test_random_packing_keeps_a_mixture_in_order():
    rng = np.random.default_rng(seed_of(0))
    radii = np.where(rng.random(3000) < 0.5, 0.5, 0.7)
    pos, rad, box = ed.random_packing(3000, 0.5, radii=radii, periodic=False, seed=seed_of(4))
    np.testing.assert_array_equal(rad, radii)
    assert np.pi * np.sum(radii**2) / box.area == pytest.approx(0.5, rel=1e-12)
    assert_no_overlap(pos, rad, box)
    assert (pos - rad[:, None] > 0).all() and (box.size - pos - rad[:, None] > 0).all()


def test_random_packing_runs_a_simulation():
    pos, rad, box = ed.random_packing(300, 0.5, radii=np.linspace(0.4, 0.6, 300),
                                      periodic=(False, True), seed=seed_of(3))
    sim = ed.Simulation(pos, np.random.default_rng(seed_of(1)).normal(size=(300, 2)), rad, box=box)
    sim.advance(collisions=3000)
    assert sim.counts.collisions == 3000


def test_random_packing_of_many_disks_is_quick():
    import time

    ed.random_packing(10, 0.1, seed=seed_of(0))  # compiled (or loaded from the cache) first
    start = time.perf_counter()
    pos, rad, box = ed.random_packing(50_000, 0.5, seed=seed_of(1))
    assert time.perf_counter() - start < 5.0  # (about 0.3 s; generous on a shared machine)
    assert len(pos) == 50_000


def test_random_packing_reports_a_stall():
    with pytest.raises(ValueError, match=r"stalled: disk \d+ of 2000 .* in 3 attempts at "
                                         r"packing fraction 0\.\d+ of the 0\.5 asked"):
        ed.random_packing(2000, 0.5, seed=seed_of(1), max_attempts=3)


@pytest.mark.parametrize(
    "args, kwargs, pattern",
    [
        ((0, 0.3), {}, "n must be >= 1"),
        ((10.5, 0.3), {}, "n must be an integer"),
        ((100, 0.0), {}, "packing_fraction must be > 0"),
        ((100, 0.55), {}, r"packing_fraction 0\.55 is too high .* 0\.547 .* compress"),
        ((100, 0.3), {"radius": -1}, "radius must be > 0"),
        ((100, 0.3), {"radii": np.ones(5)}, r"radii must have shape \(100,\)"),
        ((100, 0.3), {"radii": np.r_[np.ones(99), 0.0]}, r"radii must be > 0; disks \[99\]"),
        ((100, 0.3), {"aspect": 0}, "aspect must be > 0"),
        ((100, 0.3), {"aspect": 1e4}, "too narrow along y"),
        ((100, 0.3), {"max_attempts": 0}, "max_attempts must be >= 1"),
    ],
)
def test_random_packing_bad_arguments(args, kwargs, pattern):
    with pytest.raises((TypeError, ValueError), match=pattern):
        ed.random_packing(*args, **kwargs)


def test_make_gas_box_unchanged():
    # make_gas and random_packing size their boxes alike (one geometry helper).
    sim = ed.make_gas(400, 0.3, seed=seed_of(1))
    _, _, box = ed.random_packing(400, 0.3, seed=seed_of(1))
    assert (sim.box.width, sim.box.height) == (box.width, box.height)
    assert round(sim.box.width, 3) == 32.36


def test_make_gas_shuffles_masses_with_their_radii():
    """A mixture's disks keep their own masses when the species are shuffled over the
    lattice: disk i of the input radii and masses is one disk of the gas."""
    n = 200
    radii = np.where(np.arange(n) % 2, 0.5, 0.7)
    masses = np.where(np.arange(n) % 2, 1.0, 4.0)
    sim = ed.make_gas(n, 0.4, radii=radii, masses=masses, seed=seed_of(5))
    pairs = set(zip(sim.radii.tolist(), sim.masses.tolist()))
    assert pairs == {(0.5, 1.0), (0.7, 4.0)}
    assert not np.array_equal(sim.radii, radii)  # (shuffled)


# --------------------------------------------------------------------------- walls
def crossed(pos, rad, walls, box):
    """Disks that a segment crosses, brute force: the distance of every periodic image
    of the centre (3 x 3 on a periodic box) to each segment, against the radius."""
    out = np.zeros(len(pos), bool)
    for w in walls:
        for sx in (-1, 0, 1) if box.periodic[0] else (0,):
            for sy in (-1, 0, 1) if box.periodic[1] else (0,):
                p = pos + [sx * box.width, sy * box.height]
                out |= segment_distance(p, w) <= rad * (1 + 1e-9)
    return out


def test_walls_leave_out_the_lattice_disks_they_cross():
    # 400 disks at 0.3: a 32.36-wide square periodic box.  A wall across the middle,
    # a triangle, and a wall 0.05 from the edge x = 0, which crosses the disks near
    # x = width through their periodic images.
    walls = [ed.Wall((16.0, 0.0), (16.0, 20.0)), ed.Wall((0.05, 5.0), (0.05, 25.0))]
    walls += ed.Wall.polygon([(5.0, 25.0), (10.0, 25.0), (7.5, 29.0)])
    free = ed.make_gas(400, 0.3, seed=seed_of(40))
    cut = crossed(free.positions, free.radii, walls, free.box)
    assert 10 < cut.sum() < 100
    through_image = free.positions[:, 0] > free.box.width - 0.8
    assert (cut & through_image).any()  # (only through the image)
    with pytest.warns(UserWarning, match=rf"crossed {cut.sum()} of the 400 lattice disks"):
        sim = ed.make_gas(400, 0.3, seed=seed_of(40), walls=walls)
    # The same lattice, the crossed disks left out, in order.
    np.testing.assert_array_equal(sim.positions, free.positions[~cut])
    np.testing.assert_array_equal(sim.radii, free.radii[~cut])
    assert sim.walls == tuple(walls) and sim.box == free.box
    # Velocities for the disks that remain: segments conserve no momentum, f = 2n.
    n = len(sim)
    assert n == 400 - cut.sum()
    assert 2 * sim.kinetic_energy() / (2 * n) == pytest.approx(1.0, rel=1e-12)
    assert ed.kinetic_temperature(sim) == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(sim.momentum(), 0.0, atol=1e-10)
    sim.advance(collisions=2000)  # runs, the walls in place
    assert sim.counts.collisions >= 2000


def test_walls_in_a_mixture_and_a_random_start():
    radii = np.where(np.arange(300) % 2, 0.5, 0.7)
    masses = np.where(np.arange(300) % 2, 1.0, 2.0)
    walls = [ed.Wall((3.0, 3.0), (20.0, 12.0))]
    for build in (ed.make_gas, ed.random_gas):
        free = build(300, 0.4, radii=radii, masses=masses, periodic=False, seed=seed_of(41))
        cut = crossed(free.positions, free.radii, walls, free.box)
        with pytest.warns(UserWarning, match=rf"crossed {cut.sum()} of the 300"):
            sim = build(300, 0.4, radii=radii, masses=masses, periodic=False,
                        seed=seed_of(41), walls=walls)
        np.testing.assert_array_equal(sim.positions, free.positions[~cut])
        np.testing.assert_array_equal(sim.masses, free.masses[~cut])  # (with their radii)
        assert len(sim.walls) == 1 and 0 < cut.sum() < 60


def test_walls_that_cross_nothing_and_no_walls():
    import warnings

    free = ed.make_gas(100, 0.2, seed=seed_of(42))
    for none in (None, []):
        same = ed.make_gas(100, 0.2, seed=seed_of(42), walls=none)
        np.testing.assert_array_equal(same.velocities, free.velocities)
        assert same.walls == ()
    # A short wall in a gap of the lattice: every disk stays, no warning.
    x, y = free.positions[0]
    gap = (x + 0.5 * (free.positions[1, 0] - x), y)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sim = ed.make_gas(100, 0.2, seed=seed_of(42), walls=ed.Wall(gap, (gap[0], y + 0.1)))
    assert len(sim) == 100 and len(sim.walls) == 1
    np.testing.assert_array_equal(sim.positions, free.positions)


@pytest.mark.parametrize(
    "walls, error, pattern",
    [
        ("walls", TypeError, "walls must be an edmd2d.Wall or a sequence of them, got str"),
        (np.array([[1.0, 1.0], [5.0, 5.0]]), TypeError, r"Wall\.polygon\(vertices\)"),
        ([((1.0, 1.0), (5.0, 5.0))], TypeError, r"walls\[0\] must be an edmd2d.Wall, got tuple"),
        ([ed.Wall((1.0, 1.0), (5.0, 5.0)), ed.Wall((1.0, 1.0), (50.0, 5.0))], ValueError,
         r"walls\[1\] has an end point \(50\.0, 5\.0\) outside the box \[0, 12\.53\d*\] x"),
        # Walls 0.32 apart over the whole box: every disk is crossed.
        ([ed.Wall((0.0, y), (12.5, y)) for y in np.linspace(0.0, 12.5, 40)], ValueError,
         "the wall segments cross every one of the 100 lattice disks"),
    ],
)
def test_bad_walls(walls, error, pattern):
    with pytest.raises(error, match=pattern):
        ed.make_gas(100, 0.5, walls=walls)
