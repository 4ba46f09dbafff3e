"""Inelastic disks (restitution with the TC model): hand-computed collisions on both
backends, the engine against the reference oracle, the cooling laws of a homogeneous
granular gas, inelastic collapse, bad input, copies, pickles and re-sorts."""

from __future__ import annotations

import copy
import math
import pickle

import numpy as np
import pytest

import edmd2d as ed
from conftest import overlaps, random_system, seed_of
from edmd2d.reference import ReferenceSimulation


def _lost(sim):
    """Dissipated energy of either backend."""
    return sim.dissipated_energy() if hasattr(sim, "dissipated_energy") else sim.dissipated


# ---------------------------------------------------------------- hand-computed cases
def test_head_on_equal_masses(backend):
    # Normal relative velocity -2 becomes +2e = 1: each disk keeps 0.5 of its speed
    # 1, reversed; lost (1 - e^2)/2 * mu * vn^2 = 0.375 * 0.5 * 4 = 0.75.
    box = ed.Box(10.0, 10.0, periodic=False)
    sim = backend([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]], radii=1.0, box=box,
                  restitution=0.5, tc=0.0)
    sim.advance(collisions=1)
    assert sim.time == 0.5
    np.testing.assert_allclose(sim.velocities, [[-0.5, 0.0], [0.5, 0.0]], rtol=0, atol=1e-15)
    assert _lost(sim) == pytest.approx(0.75, rel=1e-14)
    assert sim.kinetic_energy() + _lost(sim) == pytest.approx(1.0, rel=1e-14)


def test_unequal_masses_conserve_momentum(backend):
    # m = 1 at speed 2 hits m = 3 at rest, e = 0.8: mu = 0.75, J = 1.8 * 0.75 * 2 = 2.7,
    # so v1 = 2 - 2.7 = -0.7 and v2 = 2.7 / 3 = 0.9; lost 0.18 * 0.75 * 4 = 0.54.
    box = ed.Box(20.0, 10.0, periodic=False)
    sim = backend([[2.0, 5.0], [6.0, 5.0]], [[2.0, 0.0], [0.0, 0.0]], radii=1.0,
                  masses=[1.0, 3.0], box=box, restitution=0.8, tc=0.0)
    sim.advance(collisions=1)
    np.testing.assert_allclose(sim.velocities, [[-0.7, 0.0], [0.9, 0.0]], rtol=0, atol=1e-14)
    np.testing.assert_allclose(sim.momentum(), [2.0, 0.0], rtol=0, atol=1e-14)
    assert _lost(sim) == pytest.approx(0.54, rel=1e-13)


def test_box_wall_and_segment_side_and_end(backend):
    # e_w = 0.7: the normal velocity is reversed and scaled by 0.7, the tangential one
    # kept.  Box wall x=0 at t=4; a vertical segment's side; a segment's end point hit
    # head-on along its axis.
    box = ed.Box(20.0, 10.0, periodic=False)
    side = ed.Wall((12.0, 1.0), (12.0, 9.0))
    end = ed.Wall((17.0, 2.0), (19.0, 2.0))  # its start (17, 2) faces the disk below
    sim = backend([[5.0, 5.0], [9.0, 5.0], [15.0, 2.0]],
                  [[-1.0, 0.3], [1.0, -0.2], [1.0, 0.0]], radii=1.0, box=box,
                  walls=[side, end], wall_restitution=0.7, tc=0.0)
    sim.advance(until=4.5)
    np.testing.assert_allclose(sim.velocities, [[0.7, 0.3], [-0.7, -0.2], [-0.7, 0.0]],
                               rtol=0, atol=1e-14)
    # Lost: 0.51/2 * (1 + 1 + 1) * m vn^2 with vn = 1 each.
    assert _lost(sim) == pytest.approx(3 * 0.51 / 2, rel=1e-13)


def test_species_table_picks_each_pairs_coefficient(backend):
    # Two head-on pairs far apart: species (0, 1) with e = 0.5 and (1, 1) with e = 1.
    table = [[0.2, 0.5], [0.5, 1.0]]
    box = ed.Box(20.0, 20.0, periodic=False)
    pos = [[2.0, 5.0], [5.0, 5.0], [2.0, 15.0], [5.0, 15.0]]
    vel = [[1.0, 0.0], [-1.0, 0.0]] * 2
    sim = backend(pos, vel, radii=1.0, box=box, species=[0, 1, 1, 1], restitution=table,
                  tc=0.0)
    sim.advance(until=1.0)
    np.testing.assert_allclose(sim.velocities,
                               [[-0.5, 0.0], [0.5, 0.0], [-1.0, 0.0], [1.0, 0.0]],
                               rtol=0, atol=1e-15)


def test_tc_rule_makes_a_quick_second_collision_elastic():
    # Disk 1 is hit by disk 0 at t = 0.5 and, 1/3 later, hits disk 2: with tc = 0.4
    # that second collision is elastic, with tc = 0.3 it is not.
    box = ed.Box(30.0, 10.0, periodic=False)
    pos = [[2.0, 5.0], [5.0, 5.0], [7.5, 5.0]]
    vel = [[2.0, 0.0], [0.0, 0.0], [0.0, 0.0]]
    out = {}
    for tc in (0.4, 0.3):
        sim = ed.Simulation(pos, vel, radii=1.0, box=box, restitution=0.5, tc=tc)
        ref = ReferenceSimulation(pos, vel, radii=1.0, box=box, restitution=0.5, tc=tc)
        sim.advance(collisions=2)
        ref.advance(collisions=2)
        np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-14)
        out[tc] = sim.velocities[:, 0]
    # First collision: v0 = 0.5, v1 = 1.5 (e = 0.5).  Second (disk 1 at 1.5 on disk 2
    # at rest): elastic gives (0, 1.5), e = 0.5 gives (0.375, 1.125).
    np.testing.assert_allclose(out[0.4], [0.5, 0.0, 1.5], atol=1e-14)
    np.testing.assert_allclose(out[0.3], [0.5, 0.375, 1.125], atol=1e-14)


# ---------------------------------------------------------------- against the oracle
BOX_KINDS = [(True, True), (False, False), (True, False), (False, True)]


@pytest.mark.parametrize("seed", range(24))
def test_same_events_and_final_state_as_reference(seed):
    rng = np.random.default_rng(seed_of(500) + seed)
    box = ed.Box(rng.uniform(3.0, 7.0), rng.uniform(3.0, 7.0), periodic=BOX_KINDS[seed % 4])
    walls = ([] if seed % 3 == 0 else
             [ed.Wall((0.5 * box.width, 0.2 * box.height), (0.5 * box.width, 0.7 * box.height))])
    pos, vel, rad, mass = random_system(rng, int(rng.integers(3, 10)), box, walls)
    n = len(pos)
    species = rng.integers(0, 2, n)
    e01 = rng.uniform(0.3, 1.0)
    table = [[rng.uniform(0.3, 1.0), e01], [e01, rng.uniform(0.3, 1.0)]]
    if seed % 6 == 0 and n > 3:  # a fixed peg among them
        mass[0] = np.inf
        vel[0] = 0.0
    # tc of the order of the time between collisions: the TC rule matters here.
    kw = dict(species=species, restitution=table, wall_restitution=rng.uniform(0.3, 1.0),
              tc=(0.0, 0.02, 0.2)[seed % 3])
    sim = ed.Simulation(pos, vel, rad, mass, box=box, walls=walls, **kw)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, walls=walls, **kw)
    sim._record_events(10_000)
    # A horizon short enough that rounding differences stay far below the tolerance
    # (as in the elastic oracle test).
    sim.advance(until=1.5)
    ref.advance(until=1.5)
    got = [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
           for t, k, i, j in sim._recorded_events()]
    want = [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
            for t, k, i, j in ref.events]
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0, atol=1e-9)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-9)
    assert sim.dissipated_energy() == pytest.approx(ref.dissipated, rel=1e-9, abs=1e-12)
    assert sim.counts.collisions == ref.collisions


# ---------------------------------------------------------------- elastic default
def test_coefficients_of_one_keep_the_elastic_engine():
    g = ed.make_gas(300, 0.4, seed=seed_of(3))
    a = ed.Simulation(g.positions, g.velocities, g.radii, box=g.box)
    b = ed.Simulation(g.positions, g.velocities, g.radii, box=g.box, restitution=[[1.0]],
                      wall_restitution=1.0, tc=0.5)
    assert a._model is None and b._model is None and b.tc is None
    a.advance(collisions=3000)
    b.advance(collisions=3000)
    assert np.array_equal(a.positions, b.positions) and b.dissipated_energy() == 0.0


# ---------------------------------------------------------------- cooling laws
def _cooling_gas(seed, e, n=2000, phi=0.05):
    g = ed.make_gas(n, phi, seed=seed)
    return ed.Simulation(g.positions, g.velocities, g.radii, box=g.box, restitution=e)


def test_temperature_against_collisions_per_disk():
    # Homogeneous cooling: each collision loses (1 - e^2) T on average, so
    # T = T0 exp(-(1 - e^2) C / 2) (docs/restitution.md).  The fitted slope of ln T
    # against C, over 8 gases of 2000 disks cooled to C = 12: per gas it scatters by
    # about 0.8 % (T from 4000 velocity components: 2 % per point); the mean of 8 by
    # 0.3 %.  The remaining systematic effects (non-Gaussian velocities, velocity
    # correlations at this size) were measured below 1 %: tolerance 3 %.
    e, n = 0.9, 2000
    slopes = []
    for seed in range(8):
        sim = _cooling_gas(seed, e, n)
        t0 = ed.kinetic_temperature(sim)
        cs, ts = [0.0], [t0]
        c_start = sim.counts.collisions
        for _ in range(12):
            sim.advance(collisions=n // 2)
            cs.append(2 * (sim.counts.collisions - c_start) / n)
            ts.append(ed.kinetic_temperature(sim))
        slopes.append(np.polyfit(cs, np.log(np.array(ts) / t0), 1)[0])
    ratio = np.mean(slopes) / (-(1 - e * e) / 2)
    assert ratio == pytest.approx(1.0, abs=0.03)


def test_haffs_law_against_time():
    # T = T0 / (1 + t / t_H)^2 with t_H = 4 / ((1 - e^2) omega0), omega0 the Enskog
    # collision rate at the start (Henderson's contact value at packing 0.05): the
    # slope of 1/sqrt(T/T0) against t, times t_H, is 1.  Over 8 gases its mean scatters
    # by 0.3 %; the Enskog rate is good to better than 1 % at this density: tol 4 %.
    e, n, phi = 0.9, 2000, 0.05
    z = ed.theory.henderson_z(phi)
    omega0 = ed.theory.enskog_collision_rate(ed.theory.number_density(phi), 1.0,
                                             ed.theory.contact_value(z, phi))
    t_h = 4.0 / ((1 - e * e) * omega0)
    ratios = []
    for seed in range(8):
        sim = _cooling_gas(seed, e, n)
        t0 = ed.kinetic_temperature(sim)
        cool = ed.cooling(sim, np.linspace(0.0, 2.0 * t_h, 13))
        assert cool.collisions_per_disk[-1] > 5  # (a real cooling run)
        slope = np.polyfit(cool.time, 1.0 / np.sqrt(cool.temperature / t0), 1)[0]
        ratios.append(slope * t_h)
        # Energy bookkeeping along the way: what is lost is what was dissipated.
        np.testing.assert_allclose(cool.kinetic_energy + cool.dissipated_energy,
                                   cool.kinetic_energy[0], rtol=1e-12)
    assert np.mean(ratios) == pytest.approx(1.0, abs=0.04)


# ---------------------------------------------------------------- inelastic collapse
def _squeezed_row(n=20):
    """A row of disks in a channel just wider than one diameter, converging on its
    middle."""
    rng = np.random.default_rng(seed_of(1))
    x = 10.0 + 2.0 * np.arange(n) + 0.3 * rng.random(n)
    pos = np.c_[x, np.full(n, 0.525)]
    vel = np.c_[np.where(x < x.mean(), 1.0, -1.0) * (1 + 0.1 * rng.random(n)), np.zeros(n)]
    return pos, vel, ed.Box(60.0, 1.05, periodic=False)


def test_collapse_without_tc_stops_with_a_clear_error_and_a_usable_state():
    pos, vel, box = _squeezed_row()
    sim = ed.Simulation(pos, vel, 0.5, box=box, restitution=0.5, tc=0.0)
    # The collision count diverges: tens of thousands of collisions while the clock
    # stands at the collapse time.
    with pytest.raises(RuntimeError, match=r"inelastic collapse .*disks involved: \[.*tc > 0"):
        sim.advance(until=100.0)
    stuck = sim.time
    assert 4.0 < stuck < 6.0 and sim.counts.collisions > 10_000
    assert len(overlaps(sim)) == 0
    # Still usable: readable, copyable, and it stops the same way again.
    twin = copy.deepcopy(sim)
    assert np.array_equal(twin.positions, sim.positions)
    with pytest.raises(RuntimeError, match="inelastic collapse"):
        twin.advance(collisions=100_000)
    assert twin.time == stuck


def test_collapse_is_ended_by_the_tc_model():
    pos, vel, box = _squeezed_row()
    sim = ed.Simulation(pos, vel, 0.5, box=box, restitution=0.5)  # default tc
    assert sim.tc == pytest.approx(1e-5 * 1.0 / math.sqrt(np.mean(np.sum(vel ** 2, 1))))
    sim.advance(until=100.0)
    assert sim.time == 100.0
    assert 0 < sim.counts.collisions < 100_000
    assert sim.dissipated_energy() > 0.9 * (0.5 * np.sum(vel ** 2))  # (it did cool)
    assert len(overlaps(sim)) == 0


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, match", [
    (dict(restitution=0.0), "restitution must lie in"),
    (dict(restitution=1.5), "restitution must lie in"),
    (dict(restitution=-0.5), "restitution must lie in"),
    (dict(restitution=[[0.5, 0.6, 0.7], [0.6, 0.5, 0.7]]), "must be a scalar or a square"),
    (dict(restitution=[0.5, 0.6]), "must be a scalar or a square"),
    (dict(species=[0, 1, 0], restitution=[[0.5, 0.6], [0.7, 0.5]]), "symmetric"),
    (dict(species=[0, 1, 0], restitution=[[0.5, 0.0], [0.0, 0.5]]), r"restitution\[0, 1\]"),
    (dict(species=[0, 2, 0], restitution=[[0.5, 0.6], [0.6, 0.5]]), "3 species"),
    (dict(wall_restitution=0.0), "wall_restitution"),
    (dict(wall_restitution=2.0), "wall_restitution"),
    (dict(restitution=0.5, tc=-1e-3), "tc must be >= 0"),
    (dict(restitution=0.5, tc=math.nan), "tc"),
    (dict(species=[0, -1, 0]), r"species must lie in 0\.\.1023; disk 1"),
    (dict(species=[0, 1]), r"species must have shape \(3,\)"),
])
def test_bad_input_names_the_argument(kwargs, match):
    pos = [[2.0, 2.0], [5.0, 2.0], [8.0, 2.0]]
    with pytest.raises(ValueError, match=match):
        ed.Simulation(pos, np.zeros((3, 2)), 0.5, box=ed.Box(10.0, 10.0), **kwargs)


def test_species_must_be_integers():
    with pytest.raises(TypeError, match="species must be integers"):
        ed.Simulation([[2.0, 2.0], [5.0, 2.0]], np.zeros((2, 2)), 0.5,
                      box=ed.Box(10.0, 10.0), species=[0.5, 1.0])


# ---------------------------------------------------------------- copies, pickles, re-sorts
def test_copies_and_pickles_continue_bit_identically():
    g = ed.make_gas(400, 0.3, seed=seed_of(11))
    sim = ed.Simulation(g.positions, g.velocities, g.radii, box=g.box, restitution=0.7,
                        species=np.arange(400) % 2, wall_restitution=0.9)
    sim.advance(collisions=2000)
    twins = [copy.copy(sim), copy.deepcopy(sim), pickle.loads(pickle.dumps(sim))]
    sim.advance(collisions=3000)
    for twin in twins:
        twin.advance(collisions=3000)
        assert np.array_equal(twin.positions, sim.positions)
        assert np.array_equal(twin.velocities, sim.velocities)
        assert twin.dissipated_energy() == sim.dissipated_energy()


def test_resorted_rows_keep_each_disks_species_and_clock():
    # Re-sorting the rows in memory (large systems, every 20 N events) must carry the
    # model's per-disk state along (species, last collision times): frequent re-sorts
    # change no event.
    def run(reorder_every):
        g = ed.make_gas(1500, 0.4, seed=seed_of(12))
        sim = ed.Simulation(g.positions, g.velocities, g.radii, box=g.box,
                            species=np.arange(1500) % 3,
                            restitution=[[0.6, 0.8, 0.9], [0.8, 1.0, 0.7], [0.9, 0.7, 0.5]],
                            tc=0.01)
        if reorder_every:
            sim._reorder_every = reorder_every
        sim._record_events(50_000)
        sim.advance(collisions=20_000)
        return sim

    resorted, plain = run(2999), run(10 ** 12)
    def pairs(sim):  # (the log names first the disk whose prediction fired)
        return [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
                for t, k, i, j in sim._recorded_events()]

    # (The same events; a re-sort may change which disk of a pair predicts their
    # contact, and so the last bit of its time, which the following collisions amplify:
    # up to 7e-12 of the time after 20 000 collisions, over seeds.)
    a, b = pairs(resorted), pairs(plain)
    assert [e[1:] for e in a] == [e[1:] for e in b]
    np.testing.assert_allclose([e[0] for e in a], [e[0] for e in b], rtol=1e-9)
    np.testing.assert_allclose(resorted.velocities, plain.velocities, rtol=0, atol=1e-9)
    assert np.array_equal(resorted.species, np.arange(1500) % 3)
    assert resorted.dissipated_energy() == pytest.approx(plain.dissipated_energy(), rel=1e-9)
    assert resorted.dissipated_energy() > 0


def test_species_ids_are_bounded_and_a_scalar_needs_no_table():
    pos = [[2.0, 2.0], [5.0, 2.0]]
    box = ed.Box(10.0, 10.0)
    for bad in ([0, 2 ** 31], [0, 5000]):
        with pytest.raises(ValueError, match=r"species must lie in 0\.\.1023; disk 1"):
            ed.Simulation(pos, np.zeros((2, 2)), 0.5, box=box, species=bad, restitution=0.5)
    with pytest.raises(TypeError, match="species must be integers"):
        ed.Simulation(pos, np.zeros((2, 2)), 0.5, box=box, species=[True, False])
    sim = ed.Simulation(pos, [[1.0, 0.0], [-1.0, 0.0]], 0.5, box=box, species=[0, 1000],
                        restitution=0.5)
    assert sim.restitution.shape == (1, 1) and list(sim.species) == [0, 1000]
    sim.advance(collisions=1)
    np.testing.assert_allclose(sim.velocities, [[-0.5, 0.0], [0.5, 0.0]], atol=1e-15)
    with pytest.raises(TypeError, match="restitution"):
        ed.Simulation(pos, np.zeros((2, 2)), 0.5, box=box, species=[0, 1],
                      restitution=[[0.5, 1j], [1j, 0.5]])


def test_no_false_collapse_at_a_late_clock():
    # Simultaneous means equal to a few units of rounding of the clock, however far
    # the clock has run: at t = 1e13 (rounding 0.002, mean free time 0.06) a gas that
    # barely dissipates runs on.
    g = ed.make_gas(400, 0.7, seed=seed_of(2))
    g.advance(collisions=4000)
    sim = ed.Simulation(g.positions, g.velocities, g.radii, box=g.box, restitution=0.9999,
                        time=1e13)
    sim.advance(collisions=300_000)
    assert sim.counts.collisions == 300_000


def test_a_disk_that_fills_the_box_cannot_move_across_it():
    box = ed.Box(10.0, 1.0, periodic=(True, False))
    with pytest.raises(ValueError, match="fill the box between its walls on the y axis"):
        ed.Simulation([[5.0, 0.5]], [[1.0, 0.1]], 0.5, box=box, wall_restitution=0.9)
    sim = ed.Simulation([[5.0, 0.5]], [[1.0, 0.0]], 0.5, box=box)  # along x only: fine
    with pytest.raises(ValueError, match="y-velocity must be 0"):
        sim.set_velocities([[1.0, 0.1]])
    assert sim.advance(until=20.0).counts.wall_collisions == 0
