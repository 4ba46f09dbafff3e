"""Rough disks in the engine (``_engine/rough.py``, the family ``physics.Rough``):
event for event with the reference, the energy books, smooth disks unchanged, and
the refusals.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import edmd2d as ed
from conftest import seed_of
from edmd2d.reference import ReferenceSimulation


def _canonical(events):
    """Disk pairs unordered: the engine logs the disk whose prediction fired first."""
    return [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
            for t, k, i, j in events]


def _assert_as_reference(sim, ref):
    """The same events (times to 1e-6), velocities, spins and angles as the reference."""
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0, atol=1e-6)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-6)
    np.testing.assert_allclose(sim.angular_velocities, ref.angular_velocities, rtol=0,
                               atol=1e-6)
    np.testing.assert_allclose(sim.angles, ref.angles, rtol=0, atol=1e-6)


def _case(seed):
    """A small system, periodic or walled (with a wall segment), of disks of two
    sizes and masses spinning at random, and rough coefficients at random."""
    rng = np.random.default_rng(seed_of(900) + seed)
    periodic = seed % 3 != 2
    n = int(rng.integers(8, 20))
    phi = rng.uniform(0.2, 0.45)
    gas = ed.make_gas(n, phi, periodic=periodic, seed=int(rng.integers(1 << 30)))
    walls = []
    if not periodic:  # (a diagonal segment across a corner; the disks it crosses left out)
        walls = [ed.Wall((0.0, 0.5 * gas.box.height), (0.5 * gas.box.width, 0.0))]
        gas = ed.make_gas(n, phi, periodic=False, walls=walls,
                          seed=int(rng.integers(1 << 30)))
    n = gas.n
    big = rng.random(n) < 0.3
    rad = np.where(big, 0.5, 0.38)  # (no bigger than make_gas's, which clear the walls)
    mass = np.where(big, 2.0, 1.0)
    pos = gas.positions
    rough = dict(tangential_restitution=float(rng.choice([1.0, 0.4, -0.5, 0.0])),
                 friction=float(rng.choice([math.inf, 0.3])),
                 wall_tangential_restitution=float(rng.choice([1.0, 0.5])),
                 inertia=float(rng.choice([0.5, 0.4, 1.0])),
                 angular_velocities=rng.normal(size=n))
    model = dict(restitution=0.8, wall_restitution=0.9, tc=0.02) if seed % 4 == 3 else {}
    return gas.box, walls, pos, gas.velocities, rad, mass, rough, model


@pytest.mark.filterwarnings("ignore:make_gas. the wall segments crossed")
@pytest.mark.parametrize("seed", range(24))
def test_same_events_and_final_state_as_reference(seed):
    box, walls, pos, vel, rad, mass, rough, model = _case(seed)
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, **rough, **model)
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, **rough, **model)
    # As for smooth disks: rounding differences grow chaotically; 15 collisions keep
    # them far below the tolerances, and a wrong rule shows as another sequence or
    # a difference of order 1.
    sim.advance(until=5.0, collisions=15)
    ref.advance(until=5.0, collisions=15)
    _assert_as_reference(sim, ref)
    assert sim.dissipated_energy() == pytest.approx(ref.dissipated, abs=1e-9)
    assert sim.counts.collisions == ref.collisions


@pytest.mark.filterwarnings("ignore:make_gas. the wall segments crossed")
@pytest.mark.parametrize("seed", range(8))
def test_rough_segments_as_the_reference(seed):
    # A dilute walled gas around a wall segment: its sides and end points, and the
    # box walls, with their own coefficients.
    rng = np.random.default_rng(seed_of(950) + seed)
    walls = [ed.Wall((2.0, 3.0), (7.0, 6.0))]
    gas = ed.make_gas(10, 0.08, periodic=False, walls=walls, seed=int(rng.integers(1 << 30)))
    rough = dict(tangential_restitution=0.6, wall_tangential_restitution=float(
        rng.choice([1.0, 0.2, -0.4])), wall_friction=float(rng.choice([math.inf, 0.2])),
        angular_velocities=3.0 * rng.normal(size=gas.n))
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box, walls=walls,
                        **rough)
    sim._record_events(10_000)
    ref = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                              walls=walls, **rough)
    sim.advance(until=12.0, collisions=15)
    ref.advance(until=12.0, collisions=15)
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    assert sum(e[1] == "wall" for e in got) >= 1  # (a segment's events)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-6)
    np.testing.assert_allclose(sim.angular_velocities, ref.angular_velocities, rtol=0,
                               atol=1e-6)
    assert sim.dissipated_energy() == pytest.approx(ref.dissipated, abs=1e-9)


@pytest.mark.filterwarnings("ignore:make_gas. the wall segments crossed")
@pytest.mark.parametrize("seed", range(8))
def test_rough_disks_under_gravity_as_the_reference(seed):
    # Parabolic flights between rough contacts: a walled box, gravity straight down or
    # tilted, a wall segment, an immovable peg in half the cases; elastic, or
    # inelastic with the TC model (resting off: rough disks do not come to rest).
    rng = np.random.default_rng(seed_of(970) + seed)
    walls = [ed.Wall((1.0, 2.0), (4.0, 1.0))]
    gas = ed.make_gas(12, 0.2, periodic=False, walls=walls, aspect=0.8,
                      seed=int(rng.integers(1 << 30)))
    mass = np.ones(gas.n)
    vel = gas.velocities.copy()
    if seed % 2:
        mass[0] = np.inf
        vel[0] = 0.0
    rough = dict(tangential_restitution=float(rng.choice([1.0, 0.3, -0.5])),
                 friction=float(rng.choice([math.inf, 0.25])),
                 wall_tangential_restitution=float(rng.choice([0.8, 0.0])),
                 angular_velocities=2.0 * rng.normal(size=gas.n))
    model = dict(gravity=(0.0, -1.0) if seed < 4 else (0.3, -1.0))
    off = {}
    if seed % 4 >= 2:
        model.update(restitution=0.85, wall_restitution=0.9, tc=0.02)
        off = dict(resting=False)  # (the reference has no resting unless given one)
    sim = ed.Simulation(gas.positions, vel, gas.radii, mass, box=gas.box,
                        walls=walls, **rough, **model, **off)
    sim._record_events(10_000)
    ref = ReferenceSimulation(gas.positions, vel, gas.radii, mass, box=gas.box,
                              walls=walls, **rough, **model)
    start = sim.total_energy()
    sim.advance(until=8.0, collisions=15)
    ref.advance(until=8.0, collisions=15)
    _assert_as_reference(sim, ref)
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(start, rel=1e-11)
    assert sim.dissipated_energy() == pytest.approx(ref.dissipated, abs=1e-9)


@pytest.mark.parametrize("seed", range(6))
def test_thermostat_draws_the_spins_as_the_reference(seed):
    # Andersen redraws of velocity and spin, from one seeded stream in the same order,
    # and heated box walls that leave the spin.
    gas = ed.make_gas(12, 0.3, periodic=seed % 2 == 0, seed=seed_of(960) + seed)
    heated = {} if seed % 2 == 0 else {"left": 1.5, "top": 0.8}
    options = dict(thermostat=(1.2, 0.8), seed=seed, wall_temperatures=heated,
                   tangential_restitution=0.5, inertia=0.4,
                   angular_velocities=np.linspace(-1.0, 1.0, gas.n))
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box, **options)
    sim._record_events(10_000)
    ref = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                              **options)
    sim.advance(until=2.0)
    ref.advance(until=2.0)
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    assert sim.counts.redraws == ref.redraws > 0
    np.testing.assert_allclose(sim.angular_velocities, ref.angular_velocities, rtol=0,
                               atol=1e-6)
    assert sim.thermostat_energy() == pytest.approx(ref.thermostat_energy, rel=1e-9)


@pytest.mark.filterwarnings("ignore:make_gas. the wall segments crossed")
def test_the_cases_spin_and_exchange():
    # (The comparison above has something to compare: collisions that change spins.)
    changed = 0
    for seed in range(6):
        box, walls, pos, vel, rad, mass, rough, model = _case(seed)
        sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, **rough, **model)
        w0 = sim.angular_velocities.copy()
        sim.advance(until=5.0, collisions=15)
        changed += int(np.sum(sim.angular_velocities != w0))
    assert changed > 20


def test_energy_books_and_equipartition_of_a_rough_gas():
    # 2000 elastic, perfectly rough disks from spins at rest: energy kept to rounding,
    # rotation and translation at one temperature after ~50 collisions per disk.
    sim = ed.make_gas(2000, 0.3, seed=seed_of(44), tangential_restitution=1.0)
    start = sim.total_energy()
    sim.advance(collisions=100_000)
    assert sim.total_energy() == pytest.approx(start, rel=1e-11)
    t_tr = 2.0 * sim.kinetic_energy() / (2 * 2000 - 2)
    t_rot = 2.0 * sim.rotational_energy() / 2000
    # (4000 degrees of freedom: one sample of the ratio scatters by ~4 %.)
    assert t_rot / t_tr == pytest.approx(1.0, abs=0.12)
    inelastic = ed.make_gas(500, 0.3, seed=seed_of(45), restitution=0.9,
                            tangential_restitution=0.3, friction=0.5)
    start = inelastic.total_energy()
    inelastic.advance(collisions=20_000)
    assert inelastic.dissipated_energy() > 0.3 * start
    assert inelastic.total_energy() + inelastic.dissipated_energy() == pytest.approx(
        start, rel=1e-11)


def test_smooth_disks_are_left_as_they_were():
    plain = ed.make_gas(300, 0.4, seed=seed_of(46))
    assert "rough" not in plain.families
    assert np.array_equal(plain.angular_velocities, np.zeros(300))
    assert plain.rotational_energy() == 0.0
    with pytest.raises(ValueError, match="friction needs tangential_restitution"):
        ed.make_gas(30, 0.4, seed=1, friction=0.5)


@pytest.mark.parametrize("kwargs, match", [
    (dict(tangential_restitution=1.5), "tangential_restitution"),
    (dict(tangential_restitution=0.5, wall_tangential_restitution=-1.5),
     "wall_tangential_restitution"),
    (dict(tangential_restitution=0.5, friction=-0.1), "friction"),
    (dict(tangential_restitution=0.5, inertia=0.0), "inertia"),
    (dict(tangential_restitution=0.5, inertia=1.2), "inertia"),
    (dict(tangential_restitution=0.5, angular_velocities=[1.0, 2.0]), "angular_velocities"),
    (dict(tangential_restitution=0.5, gravity=(0.0, -1.0), periodic=False,
          restitution=0.9), "resting=False"),
    (dict(tangential_restitution=0.5, shear_rate=0.1), "shear"),
])
def test_bad_rough_input_is_refused(kwargs, match):
    with pytest.raises(ValueError, match=match):
        ed.make_gas(30, 0.3, seed=1, **kwargs)


def test_checkpoints_and_gsd_frames_carry_the_spins(tmp_path):
    from edmd2d import checkpoint
    from edmd2d import operations as op
    from edmd2d.io import gsd as gsd_io

    sim = ed.make_gas(60, 0.3, seed=seed_of(47), tangential_restitution=0.5, inertia=0.4,
                      friction=0.3, angular_velocities=np.linspace(-1.0, 1.0, 60))
    sim.advance(until=2.0)
    checkpoint.save(sim, tmp_path / "c.edmd2d")
    again = checkpoint.load(tmp_path / "c.edmd2d")
    sim.advance(until=5.0)
    again.advance(until=5.0)
    assert np.array_equal(again.positions, sim.positions)
    assert np.array_equal(again.angular_velocities, sim.angular_velocities)
    assert np.array_equal(again.angles, sim.angles)
    path = tmp_path / "t.gsd"
    sim.run(until=6.0, operations=[op.WriteGSD(path, op.Every(dt=1.0))])
    read = gsd_io.read(path)
    assert read.families["rough"].beta == 0.5 and read.families["rough"].friction == 0.3
    np.testing.assert_allclose(read.families["rough"].inertia, 0.4)
    np.testing.assert_array_equal(read.angular_velocities, sim.angular_velocities)
    import gsd.hoomd

    with gsd.hoomd.open(path) as frames:
        frame = frames[-1]
        half = 0.5 * sim.angles
        np.testing.assert_allclose(frame.particles.orientation[:, 0], np.cos(half), atol=1e-6)
        np.testing.assert_allclose(frame.particles.orientation[:, 3], np.sin(half), atol=1e-6)
        np.testing.assert_allclose(frame.particles.moment_inertia[:, 2],
                                   0.4 * sim.masses * sim.radii ** 2, rtol=1e-6)


def test_a_heavy_disk_and_a_grazing_pair_in_a_fast_frame_as_the_reference():
    # The normal comes from the separation, the normal impulse from the change of the
    # relative normal velocity: exact whichever disk is heavy, and in a moving frame.
    for mass, offset, u in ((1e12, 0.3, 0.0), (1.0, 0.99, 1e4)):
        pos = [[2.0, 5.0], [4.0, 5.0 + offset]]
        vel = [[1.0 + u, 0.0], [-1.0 + u, 0.0]]
        common = dict(box=ed.Box(1e7, 20.0, periodic=(True, False)),
                      tangential_restitution=1.0, angular_velocities=[0.5, -2.0])
        sim = ed.Simulation(pos, vel, 0.5, [mass, 1.0], **common)
        ref = ReferenceSimulation(pos, vel, 0.5, [mass, 1.0], **common)
        sim.advance(collisions=1)
        ref.advance(collisions=1)
        np.testing.assert_allclose(sim.angular_velocities, ref.angular_velocities,
                                   rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=1e-12, atol=1e-9)


def test_the_segment_feels_the_tangential_impulse():
    sim = ed.Simulation([[5.0, 3.0]], [[0.0, -1.0]], 0.5, box=ed.Box(10.0, 10.0,
                        periodic=False), walls=[ed.Wall((2.0, 1.0), (8.0, 1.0))],
                        tangential_restitution=1.0, angular_velocities=4.0)
    before = sim.velocities[0].copy()
    sim.advance(until=2.0)
    after = sim.velocities[0]
    np.testing.assert_allclose(sim._state.wacc[0, :2], -(after - before), rtol=1e-12)
    assert after[0] != 0.0


def test_growth_is_refused_for_rough_disks():
    sim = ed.make_gas(50, 0.3, seed=1, tangential_restitution=0.5)
    with pytest.raises(ValueError, match="growth does not combine with rough"):
        sim.set_growth(0.01)
    with pytest.raises(ValueError, match="growth does not combine with rough"):
        ed.compress(sim, 0.4)
