"""make_gas: the box, the lattice start and the Maxwell-Boltzmann velocities."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

import edmd2d as ed


@pytest.mark.parametrize("periodic", [True, False, (True, False)])
@pytest.mark.parametrize("phi", [0.05, 0.5, 0.72])
def test_packing_fraction_temperature_momentum(periodic, phi):
    sim = ed.make_gas(1000, phi, periodic=periodic, temperature=2.5, seed=1)
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
    sim = ed.make_gas(20_000, 0.3, masses=np.linspace(1, 4, 20_000), temperature=0.7, seed=2)
    u = (sim.velocities * np.sqrt(sim.masses)[:, None] / np.sqrt(0.7)).ravel()
    assert stats.kstest(u, "norm").pvalue > 1e-3


def test_mixture_and_aspect():
    rng = np.random.default_rng(0)
    radii = np.where(rng.random(999) < 0.5, 0.5, 0.7)
    sim = ed.make_gas(999, 0.6, radii=radii, aspect=2.0, seed=4)
    assert sim.box.width == pytest.approx(2 * sim.box.height)
    assert sorted(sim.radii) == sorted(radii)  # same species, shuffled over the sites
    assert np.pi * np.sum(sim.radii**2) / sim.box.area == pytest.approx(0.6)


def test_a_lattice_start_melts():
    # At packing fraction 0.5 the fluid forgets the lattice: the bond-orientational
    # order of the start (|psi6| = 1 on a perfect triangular lattice) decays.
    sim = ed.make_gas(900, 0.5, seed=8)
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
