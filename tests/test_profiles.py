"""Profiles along an axis (edmd2d.measurements.profiles, operations.Profile)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

import edmd2d as ed
from edmd2d import measurements, theory
from edmd2d import operations as op

G = 0.05
KT = 1.0


def barometric_density(y, n_total, width, lo, hi, radius, kt, mg):
    """The local-density prediction of the density under gravity: ``ln n + mu_ex(n) /
    kT + m g y / kT`` constant over the centres' range ``[lo, hi]``, normalised to
    ``n_total`` disks in a box ``width`` wide; ``mu_ex / kT = int_0^eta (Z - 1) / e de
    + Z - 1`` from Henderson's equation of state (``(Z - 1) / eta -> 2`` at 0)."""
    area = math.pi * radius**2
    eta = np.linspace(0.0, 0.6, 6001)
    slope = np.concatenate([[2.0], (theory.henderson_z(eta[1:]) - 1.0) / eta[1:]])
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (slope[1:] + slope[:-1])
                                                * np.diff(eta))])
    mu_ex = integral + np.concatenate([[0.0], theory.henderson_z(eta[1:]) - 1.0])
    ln_n = np.log(eta[1:] / area)
    f = ln_n + mu_ex[1:]  # (increasing in n)
    grid = np.linspace(lo, hi, 2001)

    def density(c, y):
        return np.exp(np.interp(c - mg * np.asarray(y) / kt, f, ln_n))

    c = brentq(lambda c: np.trapezoid(density(c, grid), grid) * width - n_total,
               f[0] + mg * hi / kt, f[-1])
    y = np.asarray(y)
    return np.where((y >= lo) & (y <= hi), density(c, y), 0.0)


@pytest.fixture(scope="module")
def column():
    """A gas of 200 disks under gravity, periodic across, held at ``kT = 1`` by an
    Andersen thermostat (so that its heights follow the canonical law, without the
    corrections of order 1/N of a column at fixed energy), settled into its barometric
    column and sampled over a long window."""
    sim = ed.make_gas(200, 0.02, periodic=(True, False), aspect=2.0, seed=3,
                      gravity=(0.0, -G), thermostat=(KT, 0.01))
    sim.advance(until=5000.0)
    prof = measurements.profiles(sim, 40000.0, samples=4000, blocks=20, bins=16)
    return sim, prof


def test_a_gas_under_gravity_has_the_barometric_density_profile(column):
    sim, prof = column
    counts = prof.counts
    r = float(sim.radii[0])
    width, height = sim.box.size
    # The mean density over each slab: the prediction averaged over its centres.
    predicted = []
    for a, b in zip(prof.edges[:-1], prof.edges[1:]):
        y = np.linspace(a, b, 41)
        predicted.append(np.trapezoid(barometric_density(
            y, len(sim), width, r, height - r, r, KT, G), y) / (b - a))
    predicted = np.array(predicted)
    # Slabs the gas reaches, clear of the floor by two diameters: at a hard wall the
    # density is raised within a diameter or so (the contact value), which a local
    # density cannot follow.
    use = (counts > 1000) & (prof.edges[:-1] >= 4.0 * r)
    assert use.sum() >= 10
    # (The prediction normalised over these slabs: the disks held at the floor beyond
    # the local density's share would otherwise lower it everywhere else.)
    predicted = predicted * prof.density[use].sum() / predicted[use].sum()
    z = (prof.density[use] - predicted[use]) / prof.density_error[use]
    # Errors from 20 blocks are themselves uncertain by 16 %; over seeds 1-6 the mean
    # z^2 of this comparison ranged from 0.5 to 2.8 and max |z| up to 3.1.
    assert np.abs(z).max() < 6.0, z
    assert np.mean(z**2) < 4.0, z
    # The whole profile holds every disk in every sample.
    slab_area = np.diff(prof.edges) * width
    assert np.sum(prof.density * slab_area) == pytest.approx(len(sim), rel=1e-12)


def test_the_temperature_of_a_gas_in_equilibrium_is_its_temperature_at_every_height(column):
    _, prof = column
    use = prof.counts > 1000
    z = (prof.temperature[use] - KT) / prof.temperature_error[use]
    # (Over seeds 1-6: mean z^2 0.6 to 2.7, max |z| up to 3.4; the flow velocity's
    # mean z^2 up to 3.)
    assert np.abs(z).max() < 6.0, z
    assert np.mean(z**2) < 4.0, z
    zv = prof.velocity[use] / prof.velocity_error[use]
    assert np.mean(zv**2) < 4.0, zv


def test_a_gas_moving_as_a_whole_has_its_velocity_in_every_slab_and_the_same_temperature():
    sim = ed.make_gas(400, 0.2, seed=5)
    kt = measurements.kinetic_temperature(sim)
    u = np.array([0.7, -0.3])
    sim.set_velocities(sim.velocities + u)
    p = op.Profile(op.Every(dt=0.5), axis="x", bins=4)
    sim.run(until=100.0, operations=[p])
    prof = p.result(blocks=10)
    # Momentum is conserved: the mass-weighted mean over all slabs is u exactly.
    weights = prof.counts[:, None]
    assert np.sum(prof.velocity * weights, axis=0) / prof.counts.sum() == pytest.approx(u)
    assert np.abs((prof.velocity - u) / prof.velocity_error).max() < 5.0
    # Galilean invariance: the granular temperature is the temperature at rest.
    assert np.abs((prof.temperature - kt) / prof.temperature_error).max() < 5.0
    assert prof.samples == 200


def test_a_settled_bed_is_dense_and_still():
    sim = ed.make_gas(60, 0.15, periodic=False, aspect=0.5, seed=1, restitution=0.9,
                      wall_restitution=0.9, gravity=(0.0, -1.0))
    sim.advance(until=100.0)
    assert sim.resting.all()
    # Slabs one diameter thick, each holding about one row of the bed.
    prof = measurements.profiles(sim, 2.0, samples=4, blocks=2, bins=3, span=(0.0, 3.0))
    assert (prof.velocity == 0.0).all() and (prof.temperature == 0.0).all()
    assert (prof.density_error == 0.0).all()  # (nothing moves)
    # Rows of unit disks a triangular crystal's row spacing apart, nearly filling the
    # width: some 0.75, and at most the crystal's 0.9069 (to the granularity of rows).
    assert 0.6 < prof.packing_fraction.mean() < math.pi / (2.0 * math.sqrt(3.0))


@pytest.mark.parametrize("kwargs, word", [
    (dict(duration=0.0), "duration"),
    (dict(duration=1.0, axis="z"), "axis"),
    (dict(duration=1.0, bins=0), "bins"),
    (dict(duration=1.0, span=(3.0, 1.0)), "span"),
    (dict(duration=1.0, samples=5, blocks=10), "samples"),
])
def test_bad_profile_arguments_are_refused_by_name(kwargs, word):
    sim = ed.make_gas(20, 0.1, seed=1)
    with pytest.raises(ValueError, match=word):
        measurements.profiles(sim, **kwargs)
    assert sim.time == 0.0  # nothing run


def test_asking_for_more_blocks_than_samples_taken_is_refused():
    sim = ed.make_gas(20, 0.1, seed=1)
    p = op.Profile(op.Every(dt=1.0))
    sim.run(until=3.0, operations=[p])
    with pytest.raises(ValueError, match="blocks"):
        p.result(blocks=5)


def triangular_bed(rows, cols=10, flip=False):
    """``rows`` rows of ``cols`` unit disks, a triangular crystal standing on the floor
    of a box 20 high, periodic across (every other row shifted by a radius); ``flip``:
    upside down, under gravity pointing up.  Returns positions, box and gravity."""
    y = 0.5 + np.arange(rows) * np.sqrt(3.0) / 2.0
    pos = np.array([[c + 0.5 + 0.5 * (r % 2), y[r]] for r in range(rows)
                    for c in range(cols)])
    pos[:, 0] %= cols  # (wrapped into the box, as a simulation's positions are)
    if flip:
        pos[:, 1] = 20.0 - pos[:, 1]
    return pos, ed.Box(cols, 20.0, periodic=(True, False)), np.array([0.0, 1.0 if flip
                                                                        else -1.0])


@pytest.mark.parametrize("flip", [False, True])
def test_the_packing_fraction_of_a_crystal_bed_is_exact(flip):
    # (The geometry alone, on exact lattice positions: _bed is bed() past its checks.)
    rows = 6
    pos, box, g = triangular_bed(rows, flip=flip)
    h = np.sqrt(3.0) / 2.0  # (the rows' spacing)
    top = 1.0 + (rows - 1) * h
    # Ending the band on the centres of row m: half of the bottom row's disks below
    # their centres, then the crystal's own packing fraction between centre lines.
    for m in (2, 4):
        skin = top - (0.5 + m * h)
        b = measurements._bed(pos, np.full(len(pos), 0.5), box, g, skin, 1.0)
        assert b.disks == rows * 10 and b.bottom == 0.0
        assert b.height == pytest.approx(top, abs=1e-9)
        assert b.top == pytest.approx(top, abs=1e-9)
        crystal = math.pi / (2.0 * math.sqrt(3.0))
        expected = (10 * math.pi / 8 + crystal * 10 * m * h) / (10 * (0.5 + m * h))
        assert b.packing_fraction == pytest.approx(expected, rel=1e-9)


def test_a_poured_bed_is_measured():
    sim = ed.make_gas(300, 0.15, periodic=False, aspect=0.5, seed=3, restitution=0.9,
                      wall_restitution=0.9, gravity=(0.0, -1.0))
    sim.advance(until=100.0)
    b = measurements.bed(sim)
    assert b.disks == 300
    # Below its surface a poured bed of equal disks is nearly crystalline: close to
    # the triangular crystal's 0.9069, never above it.
    assert 0.8 < b.packing_fraction < math.pi / (2.0 * math.sqrt(3.0))
    # The disks' area spread over the width at that packing fills about the height.
    filled = 300 * math.pi * 0.25 / (sim.box.width * b.packing_fraction)
    assert abs(b.height - filled) < 2.0
    assert b.top >= b.height


def test_bed_refuses_what_is_not_a_bed():
    sim = ed.make_gas(20, 0.1, seed=1)
    with pytest.raises(ValueError, match="gravity"):
        measurements.bed(sim)
    tilted = ed.make_gas(20, 0.1, periodic=False, seed=1, gravity=(0.3, -1.0))
    with pytest.raises(ValueError, match="axis"):
        measurements.bed(tilted)
    falling = ed.make_gas(20, 0.1, periodic=False, seed=1, gravity=(0.0, -1.0),
                          restitution=0.9)
    b = measurements.bed(falling)
    assert b.disks == 0 and math.isnan(b.height) and math.isnan(b.packing_fraction)
    with pytest.raises(ValueError, match="skin"):
        measurements.bed(falling, skin=-1.0)


def test_discharge_of_free_flights_is_their_net_speed_over_the_period():
    # Three disks flying through a box periodic in y: each crosses a line across it
    # |v_y| / H times per unit time, so the net rate is -(sum v_y) / H exactly.
    box = ed.Box(6.0, 10.0, periodic=True)
    vel = [[0.3, -2.0], [0.0, -1.0], [-0.1, 0.5]]
    sim = ed.Simulation([[1.0, 2.0], [3.0, 5.0], [5.0, 8.0]], vel, 0.4, box=box)
    flow = measurements.discharge(sim, 25.0, blocks=5)
    assert flow.rate == pytest.approx(2.5 / 10.0, rel=1e-12)
    assert flow.block_rates == pytest.approx([0.25] * 5, rel=1e-12)
    assert flow.error == pytest.approx(0.0, abs=1e-12)
    assert sim.time == 25.0 and flow.duration == 25.0 and flow.axis == 1
    sideways = measurements.discharge(sim, 10.0, axis=0)
    assert sideways.rate == pytest.approx(-0.2 / 6.0, rel=1e-12)


@pytest.mark.parametrize("kwargs, error, word", [
    (dict(duration=0.0), ValueError, "duration"),
    (dict(duration=5.0, blocks=1), ValueError, "blocks"),
    (dict(duration=5.0, axis=2), ValueError, "axis"),
    (dict(duration=5.0, axis=True), ValueError, "axis"),
    (dict(duration=5.0, axis=1.0), ValueError, "axis"),
])
def test_bad_discharge_arguments_are_refused(kwargs, error, word):
    sim = ed.Simulation([[1.0, 2.0]], [[0.0, -1.0]], 0.4, box=ed.Box(6.0, 10.0))
    with pytest.raises(error, match=word):
        measurements.discharge(sim, **kwargs)
    assert sim.time == 0.0


def test_discharge_needs_a_periodic_axis():
    sim = ed.Simulation([[1.0, 2.0]], [[0.0, -1.0]], 0.4,
                        box=ed.Box(6.0, 10.0, periodic=(True, False)))
    with pytest.raises(ValueError, match="not periodic along axis 1"):
        measurements.discharge(sim, 5.0)
