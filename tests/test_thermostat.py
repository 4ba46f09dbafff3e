"""Thermostats and heated walls, against statistical mechanics and kinetic theory.

The Andersen thermostat redraws velocities from the Maxwell-Boltzmann distribution;
a heated wall returns disks with velocities drawn from its temperature.  A gas held by
either must show that temperature and those velocities; a gas between a hot and a cold
wall carries a steady heat flux, with equal pressure across it.
"""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest
from scipy import stats

import edmd2d as ed
from conftest import seed_of
from edmd2d.measurements import degrees_of_freedom


def thermostatted(n=400, kt=2.0, rate=0.2, seed=None):
    seed = seed_of(1) if seed is None else seed
    gas = ed.make_gas(n, 0.3, temperature=1.0, seed=seed)
    return ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                         thermostat=(kt, rate), seed=seed)


def test_thermostat_holds_its_temperature_with_maxwell_boltzmann_velocities():
    """After ~10 redraw times the gas is at the thermostat's kT: the time average of
    the kinetic temperature equals kT within its error, and the velocity components
    pooled over snapshots 2 redraw times apart (nearly independent: 86 % of the disks
    redrawn in between) pass a Kolmogorov-Smirnov test against the Gaussian of
    variance kT / m (threshold p > 1e-4: a false alarm once in 10^4 seeds)."""
    kt, rate = 2.0, 0.2
    sim = thermostatted(kt=kt, rate=rate)
    sim.advance(until=50.0)
    temps, comps = [], []
    for _ in range(200):
        sim.advance(until=sim.time + 1.0)
        temps.append(ed.kinetic_temperature(sim))
        if len(temps) % 10 == 0:
            comps.append(sim.velocities.ravel())
    # One sample has relative spread sqrt(2 / f) (f = 2N degrees of freedom); samples
    # decorrelate over ~1 / rate = 5 time units: about 40 independent ones.
    sigma = kt * math.sqrt(2.0 / (2 * 400)) / math.sqrt(200 / 5)
    assert abs(np.mean(temps) - kt) < 4.0 * sigma
    assert stats.kstest(np.concatenate(comps) / math.sqrt(kt), "norm").pvalue > 1e-4


def test_thermostat_redraws_come_at_the_poisson_rate():
    """N disks at rate nu for time t: N nu t redraws, Poisson distributed."""
    sim = thermostatted(n=400, rate=0.5)
    sim.advance(until=40.0)
    expected = 400 * 0.5 * 40.0
    assert abs(sim.counts.redraws - expected) < 4.0 * math.sqrt(expected)
    assert sim.counts.events == (sim.counts.collisions + sim.counts.wall_collisions
                                 + sim.counts.cell_crossings + sim.counts.redraws)
    assert sim.thermostat == (2.0, 0.5)
    assert degrees_of_freedom(sim) == (800, (False, False))  # (momentum not conserved)


def test_energy_balance_closes_with_thermostat_heated_walls_and_restitution():
    gas = ed.make_gas(300, 0.2, periodic=(True, False), seed=seed_of(4))
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                        restitution=0.8, gravity=(0.0, -0.2), thermostat=(1.0, 0.05),
                        wall_temperatures={"bottom": 3.0}, seed=seed_of(2))
    e0 = sim.total_energy()
    sim.advance(until=60.0)
    balance = (sim.total_energy() + sim.dissipated_energy() - sim.wall_heat().sum()
               - sim.thermostat_energy())
    assert balance == pytest.approx(e0, rel=1e-11)
    assert sim.dissipated_energy() > 0 and sim.wall_heat()[2] > 0


def test_a_seed_gives_one_run_whatever_the_splits_copies_and_pickles():
    def run(seed):
        return thermostatted(n=300, seed=seed)

    whole = run(7).advance(until=30.0)
    split = run(7)
    for t in (3.0, 11.0, 20.0):
        split.advance(until=t)
        split = pickle.loads(pickle.dumps(copy.deepcopy(split)))
    split.advance(until=30.0)
    assert np.array_equal(whole.positions, split.positions)
    assert np.array_equal(whole.velocities, split.velocities)
    assert whole.counts == split.counts
    other = run(7)
    other2 = ed.Simulation(other.positions, other.velocities, other.radii, box=other.box,
                           thermostat=(2.0, 0.2), seed=seed_of(8)).advance(until=30.0)
    assert not np.array_equal(whole.velocities, other2.velocities)


def test_gas_between_hot_and_cold_walls_carries_a_steady_heat_flux():
    """A dilute gas between a hot floor (kT 2) and a cold ceiling (kT 0.5) reaches a
    steady state: the temperature falls monotonically with height; the heat the
    floor gives balances what the ceiling takes, to within the fluctuation of the
    gas's own energy (about sqrt(N) kT), while some 1400 units flow through; and the
    pressure is the same at every height, n kT (1 + B2 n) with the second virial
    coefficient B2 = pi d^2 / 2 of hard disks (the next order is below 1 % here)."""
    gas = ed.make_gas(400, 0.05, periodic=(True, False), seed=seed_of(3))
    sim = ed.Simulation(gas.positions, gas.velocities, 0.5, box=gas.box,
                        wall_temperatures={"bottom": 2.0, "top": 0.5}, seed=seed_of(1))
    width, height = gas.box.width, gas.box.height
    sim.advance(until=300.0)
    q0 = sim.wall_heat()
    e0 = sim.kinetic_energy()
    slabs, blocks, per_block = 8, 20, 50
    energy = np.zeros((blocks, slabs))
    count = np.zeros((blocks, slabs))
    for b in range(blocks):
        for _ in range(per_block):
            sim.advance(until=sim.time + 1.0)
            k = np.minimum((sim.positions[:, 1] / height * slabs).astype(int), slabs - 1)
            np.add.at(energy[b], k, 0.5 * (sim.velocities ** 2).sum(axis=1))
            np.add.at(count[b], k, 1)
    heat = sim.wall_heat() - q0
    # Bookkeeping: elastic disks, so the walls' heat is the change of kinetic energy.
    assert heat.sum() == pytest.approx(sim.kinetic_energy() - e0, abs=1e-9 * heat[2])
    temperature = energy.sum(axis=0) / count.sum(axis=0)
    assert (np.diff(temperature) < 0).all()
    assert 1.0 < temperature[0] < 2.0 and 0.5 < temperature[-1] < 1.0
    fluctuation = math.sqrt(400) * float(np.mean(temperature))
    assert heat[2] > 20.0 * fluctuation
    assert abs(heat[2] + heat[3]) < 4.0 * fluctuation
    # The pressure of each slab in each block of 50 time units (longer than the ~20 a
    # slab's count takes to decorrelate); each slab's mean over the 20 blocks lies
    # within 5 standard errors of the mean over the slabs (Student's t with 19 degrees
    # of freedom: a chance of about 1e-4 per slab that a true equality fails).
    density = count / (per_block * width * height / slabs)
    pressure = energy / count * density * (1.0 + math.pi / 2.0 * density)
    mean = pressure.mean(axis=0)
    error = pressure.std(axis=0, ddof=1) / math.sqrt(blocks)
    assert (np.abs(mean - mean.mean()) < 5.0 * error).all()


def test_heated_floor_drives_an_inelastic_bed_to_a_steady_state():
    """Inelastic disks under gravity over a heated floor: the granular temperature
    of the second half of the run equals that of the first half within four standard
    errors of the block means (blocks of 20 time units, longer than its correlation
    time); and the power balances: what the floor gives, ~1500 times the spread of
    the bed's total energy, is what the collisions dissipate, to within that spread
    (the difference is the change of the bed's energy)."""
    gas = ed.make_gas(300, 0.1, periodic=(True, False), seed=seed_of(5))
    sim = ed.Simulation(gas.positions, gas.velocities, 0.5, box=gas.box,
                        gravity=(0.0, -0.5), restitution=0.9, wall_restitution=0.9,
                        wall_temperatures={"bottom": 4.0}, seed=seed_of(3))
    sim.advance(until=200.0)
    heat0, lost0 = sim.wall_heat()[2], sim.dissipated_energy()
    temps, energies = [], []
    for _ in range(400):
        sim.advance(until=sim.time + 1.0)
        temps.append(ed.kinetic_temperature(sim))
        energies.append(sim.total_energy())
    blocks = np.array(temps).reshape(20, 20).mean(axis=1)
    first, second = blocks[:10], blocks[10:]
    err = math.sqrt(first.var(ddof=1) / 10 + second.var(ddof=1) / 10)
    assert abs(first.mean() - second.mean()) < 4.0 * err
    spread = float(np.std(energies))
    given = sim.wall_heat()[2] - heat0
    lost = sim.dissipated_energy() - lost0
    assert given > 1000.0 * spread
    assert abs(given - lost) < 4.0 * math.sqrt(2.0) * spread


def test_rescale_temperature_keeps_the_momentum():
    gas = ed.make_gas(200, 0.3, periodic=(True, False), seed=seed_of(6)).advance(until=2.0)
    p0 = gas.momentum()
    gas.rescale_temperature(3.5)
    assert ed.kinetic_temperature(gas) == pytest.approx(3.5, rel=1e-12)
    np.testing.assert_allclose(gas.momentum(), p0, atol=1e-9)
    before = gas.velocities
    with pytest.raises(ValueError, match="temperature must be > 0"):
        gas.rescale_temperature(0.0)
    with pytest.raises(ValueError, match="temperature"):
        gas.rescale_temperature(np.nan)
    assert np.array_equal(gas.velocities, before)


WALLED = ed.Box(10.0, 10.0, periodic=False)
CHANNEL = ed.Box(10.0, 10.0, periodic=(True, False))


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(thermostat=(0.0, 1.0)), ValueError, "thermostat temperature kT must be > 0"),
    (dict(thermostat=(-1.0, 1.0)), ValueError, "thermostat temperature"),
    (dict(thermostat=(1.0, -0.5)), ValueError, "thermostat rate must be >= 0"),
    (dict(thermostat=(1.0, np.inf)), ValueError, "thermostat"),
    (dict(thermostat=1.0), ValueError, "thermostat must have shape"),
    (dict(wall_temperatures={"left": 1.0}, box=CHANNEL), ValueError,
     r"wall_temperatures\['left'\]: the x axis of the box is periodic"),
    (dict(wall_temperatures={"floor": 1.0}), ValueError, "no box wall is called 'floor'"),
    (dict(wall_temperatures={"bottom": 0.0}), ValueError, r"must be a temperature kT > 0"),
    (dict(wall_temperatures={0: 1.0}), ValueError, "there are 0 wall segments"),
    (dict(wall_temperatures={1.5: 1.0}), TypeError, "a box wall's name or a segment index"),
    (dict(wall_temperatures=[("bottom", 1.0)]), TypeError, "must be a dict"),
    (dict(wall_temperatures={"bottom": 1.0, "y=0": 2.0}), ValueError,
     "given a temperature already"),
])
def test_bad_thermostat_and_heated_walls_are_refused_by_name(kwargs, error, match):
    kwargs = dict(kwargs)
    box = kwargs.pop("box", WALLED)
    with pytest.raises(error, match=match):
        ed.Simulation([[5.0, 5.0]], [[1.0, 0.0]], radii=0.5, box=box, **kwargs)


def test_wall_temperatures_readout_names_the_walls():
    sim = ed.Simulation([[5.0, 5.0]], [[1.0, 0.0]], radii=0.5, box=WALLED,
                        walls=[ed.Wall((1.0, 1.0), (2.0, 2.0))],
                        wall_temperatures={"y=0": 2.0, "top": 1.0, 0: 0.5})
    assert sim.wall_temperatures == {"bottom": 2.0, "top": 1.0, 0: 0.5}
    assert sim.thermostat is None
    assert ed.Simulation([[5.0, 5.0]], [[1.0, 0.0]], radii=0.5, box=WALLED,
                         thermostat=(1.0, 0.0)).thermostat is None


def test_make_gas_builds_the_physics_and_seeds_its_random_numbers():
    def gas():
        return ed.make_gas(100, 0.2, periodic=(True, False), seed=seed_of(4), restitution=0.9,
                           gravity=(0.0, -0.5), wall_temperatures={"bottom": 3.0},
                           thermostat=(1.0, 0.1))

    a = gas().advance(until=10.0)
    b = gas().advance(until=10.0)
    assert np.array_equal(a.velocities, b.velocities)
    assert a.restitution.tolist() == [[0.9]] and a.thermostat == (1.0, 0.1)
    assert a.wall_temperatures == {"bottom": 3.0} and a.counts.redraws > 0


@pytest.mark.parametrize("physics", [{}, {"restitution": 0.9},
                                     {"wall_temperatures": {"left": 1.0}}])
def test_disks_at_rest_without_a_thermostat_have_no_further_event(physics):
    # Without a thermostat no redraw is ever due, not even at t = inf: resting disks
    # run out of events whatever else the physics holds, at the time they stand still.
    sim = ed.Simulation([[2.0, 2.0], [5.0, 5.0]], [[0.0, 0.0], [0.0, 0.0]], 0.5,
                        box=ed.Box(10.0, 10.0, periodic=False), **physics)
    with pytest.raises(RuntimeError, match="no further event can ever happen"):
        sim.advance(collisions=1)
    assert sim.time == 0.0 and sim.counts.redraws == 0
