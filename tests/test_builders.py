"""make_gas: the box, the lattice start and the Maxwell-Boltzmann velocities."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

import edmd2d as ed
from conftest import seed_of


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
