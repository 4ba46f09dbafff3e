"""Wide disks (``Simulation(grid=...)``, ``_engine/wide.py``): disks far wider than
the grid's cells, listed in every cell near them.  The engine on that grid against
the brute-force reference event for event, with every physics family it runs (heated
walls and a thermostat, restitution, rough disks, gravity, growth, shear; disks at rest
in ``test_reference_resting.py``); against
the uniform grid over longer runs; the automatic choice; continuations; refusals."""

from __future__ import annotations

import copy
import warnings

import numpy as np
import pytest

import edmd2d as ed
from conftest import continuations, overlaps, seed_of, sheared_gap, worst_gap
from edmd2d.reference import ReferenceSimulation

BOX_KINDS = [(True, True), (False, False), (True, False), (False, True)]


def _canonical(events):
    return [(t, k, min(i, j), max(i, j)) if k == "disk" else (t, k, i, j)
            for t, k, i, j in events]


def _assert_as_reference(sim, ref):
    """The same events (times to 1e-8) and final velocities as the reference; returns
    the events."""
    got, want = _canonical(sim._recorded_events()), _canonical(ref.events)
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0, atol=1e-8)
    np.testing.assert_allclose(sim.velocities, ref.velocities, rtol=0, atol=1e-8)
    return got


def _mixture(seed, n=40, big=3, ratio=5.0, packing=0.35, periodic=True, walls=None,
             aspect=1.0):
    """A disordered gas of ``n`` disks, ``big`` of them ``ratio`` times wider (up to
    20 % narrower at random), from ``random_gas``."""
    rng = np.random.default_rng(seed)
    rad = np.full(n, 0.5)
    rad[:big] = 0.5 * ratio * rng.uniform(0.8, 1.0, big)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (disks that the segments cross left out)
        return ed.random_gas(n, packing, radii=rad, periodic=periodic, walls=walls,
                             aspect=aspect, seed=int(rng.integers(1 << 30)))


def _walls(kind, box):
    w, h = box.width, box.height
    if kind == "divider":
        return [ed.Wall((0.5 * w, 0.2 * h), (0.5 * w, 0.7 * h))]
    if kind == "slant":
        return [ed.Wall((0.1 * w, 0.8 * h), (0.6 * w, 0.95 * h))]
    return []


def _physics(seed, periodic):
    kinds = [{}, dict(restitution=0.85, tc=1e-3), dict(tangential_restitution=0.5),
             dict(thermostat=(1.0, 0.5), seed=seed)]
    out = dict(kinds[seed % 4])
    if not periodic[1] and seed % 8 == 5:  # (a heated floor)
        out.update(wall_temperatures={"bottom": 2.0}, seed=seed)
    if not all(periodic) and seed % 3 == 0:
        out["gravity"] = (0.3, -1.0)
        if "restitution" in out:
            out["resting"] = False
    return out


CASES = [(seed, BOX_KINDS[seed % 4], ("none", "divider", "slant")[seed % 3])
         for seed in range(24)]


@pytest.mark.parametrize("seed, periodic, walls_kind", CASES)
def test_same_events_and_final_state_as_reference(seed, periodic, walls_kind):
    rng = np.random.default_rng(seed_of(980) + seed)
    shape = dict(n=int(rng.integers(30, 60)), big=int(rng.integers(1, 4)),
                 ratio=float(rng.choice([3.0, 4.0, 6.0])), packing=0.3, periodic=periodic,
                 aspect=float(rng.choice([1.0, 0.6])))
    for attempt in range(20):  # (until the segment leaves a wide disk in the box)
        probe = _mixture(seed_of(981) + 100 * attempt + seed, **shape)
        walls = _walls(walls_kind, probe.box)
        gas = _mixture(seed_of(981) + 100 * attempt + seed, walls=walls,
                       **shape) if walls else probe
        if gas.radii.max() > 0.5:
            break
    pos, vel, rad = gas.positions, gas.velocities.copy(), gas.radii
    mass = np.ones(len(pos))
    if seed % 5 == 0:  # (an immovable disk: the first, a wide one)
        mass[0] = np.inf
        vel[0] = 0.0
    options = _physics(seed, periodic)
    sim = ed.Simulation(pos, vel, rad, mass, box=gas.box, walls=walls, grid="wide",
                        **options)
    assert sim._state.wide is not None
    sim._record_events(10_000)
    ref_options = {k: v for k, v in options.items() if k != "resting"}
    ref = ReferenceSimulation(pos, vel, rad, mass, box=gas.box, walls=walls, **ref_options)
    # (Rounding differences grow chaotically: 20 collisions keep them far below the
    # tolerances, and a missed contact shows as another sequence.)
    sim.advance(until=30.0, collisions=20)
    ref.advance(until=30.0, collisions=20)
    got = _assert_as_reference(sim, ref)
    assert any(e[1] == "disk" and (e[2] < 3 or e[3] < 3) for e in got) or seed % 5 == 0


@pytest.mark.parametrize("seed", range(8))
def test_the_same_run_as_the_uniform_grid(seed):
    # Over hundreds of collisions (wide disks crossing cells, footprints growing and
    # shrinking, wrapping round periodic boxes) the two grids give the same events,
    # until rounding, which differs between them, has grown.
    periodic = BOX_KINDS[seed % 4]
    gas = _mixture(seed_of(982) + seed, n=150, big=4, ratio=(4.0, 10.0)[seed % 2],
                   periodic=periodic)
    runs = []
    for grid in ("wide", "uniform"):
        sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box, grid=grid)
        sim._record_events(1 << 16)
        sim.advance(collisions=300)
        runs.append(sim)
    wide, uniform = runs
    assert wide._state.wide is not None and uniform._state.wide is None
    got, want = _canonical(wide._recorded_events()), _canonical(uniform._recorded_events())
    assert [e[1:] for e in got] == [e[1:] for e in want]
    np.testing.assert_allclose([e[0] for e in got], [e[0] for e in want], rtol=0, atol=1e-7)
    assert wide.counts.cell_crossings > 0


def test_a_fast_wide_disk_round_a_small_periodic_box():
    # One wide disk flying fast through a dilute gas, across both periodic edges many
    # times: no contact missed (the reference agrees), no overlap after many wraps,
    # the energy kept.
    gas = _mixture(seed_of(983), n=30, big=1, ratio=4.0, packing=0.2)
    vel = gas.velocities.copy()
    vel[0] = [17.0, 9.0]
    sim = ed.Simulation(gas.positions, vel, gas.radii, box=gas.box, grid="wide")
    assert sim._state.wide is not None
    sim._record_events(10_000)
    ref = ReferenceSimulation(gas.positions, vel, gas.radii, box=gas.box)
    sim.advance(collisions=25)
    ref.advance(collisions=25)
    assert [e[1:] for e in _canonical(sim._recorded_events())] == \
        [e[1:] for e in _canonical(ref.events)]
    start = sim.total_energy()
    sim.advance(collisions=20_000)
    wraps = np.round((sim.unwrapped_positions - sim.positions) / gas.box.size)
    assert np.abs(wraps).sum() > 100  # (the disks went round the box many times)
    p = sim.positions
    d = p[:, None] - p[None]
    d -= gas.box.size * np.round(d / gas.box.size)
    gap = np.hypot(d[..., 0], d[..., 1]) - (sim.radii[:, None] + sim.radii[None])
    np.fill_diagonal(gap, np.inf)
    assert gap.min() > -1e-10
    assert sim.total_energy() == pytest.approx(start, rel=1e-12)


def test_a_wide_disk_meets_a_segment_across_a_periodic_edge():
    # The segment near x = 9.5 is met through its image at x = -0.5, over cells whose
    # image shift is not 0 for the wide disk: at t = 0.8, as the reference finds.
    box = ed.Box(10.0, 10.0)
    pos = [[1.8, 5.0]] + [[x, y] for y in list(np.arange(0.2, 2.5, 0.3))
                          + list(np.arange(7.6, 9.9, 0.3)) for x in np.arange(0.15, 9.9, 0.3)]
    vel = np.zeros((len(pos), 2))
    vel[0] = [-1.0, 0.0]
    rad = np.full(len(pos), 0.1)
    rad[0] = 1.5
    walls = [ed.Wall((9.5, 4.0), (9.5, 6.0))]
    sim = ed.Simulation(pos, vel, rad, box=box, walls=walls, grid="wide")
    sim._record_events(100)
    sim.advance(until=2.0)
    ref = ReferenceSimulation(pos, vel, rad, box=box, walls=walls)
    ref.advance(until=2.0)
    assert ref.events[0][0] == pytest.approx(0.8)
    _assert_as_reference(sim, ref)


def test_the_automatic_choice():
    few_big = _mixture(seed_of(984), n=2000, big=20, ratio=10.0)
    assert few_big._state.wide is not None  # (random_gas takes the default, auto)
    assert len(few_big._state.wide.disk) == 20
    equal = ed.make_gas(400, 0.4, seed=1)
    binary = ed.random_gas(400, 0.4, radii=np.where(np.arange(400) % 2, 0.5, 0.7), seed=1)
    for sim in (equal, binary):
        assert sim._state.wide is None
    uniform = ed.Simulation(few_big.positions, few_big.velocities, few_big.radii,
                            box=few_big.box, grid="uniform")
    assert uniform._state.wide is None
    assert few_big._state.gf[2] < 0.2 * uniform._state.gf[2]


def test_checkpoints_copies_and_edits_keep_the_wide_grid(tmp_path):
    sim = _mixture(seed_of(985), n=300, big=5, ratio=8.0, periodic=(True, False))
    plain = copy.deepcopy(sim)
    sim._state.reorder_every = 500  # (the rows re-sorted often along the way)
    sim.advance(collisions=2000)
    plain.advance(collisions=2000)
    # (Re-sorting changes which disk of a pair fires first, hence rounding, as on the
    # uniform grid: the same run to rounding.)
    np.testing.assert_allclose(plain.positions, sim.positions, rtol=0, atol=1e-9)
    ed.checkpoint.save(sim, tmp_path / "c.edmd2d")
    again = ed.checkpoint.load(tmp_path / "c.edmd2d")
    twin = copy.deepcopy(sim)
    for s in (sim, again, twin):
        s.advance(collisions=3000)
    assert again._state.wide is not None
    assert np.array_equal(again.positions, sim.positions)
    assert np.array_equal(twin.velocities, sim.velocities)
    # Moving every disk rebuilds the grid, wide disks listed afresh.
    sim.set_positions(sim.positions)
    sim.advance(collisions=1000)
    assert sim._state.wide is not None


def test_overlaps_with_wide_disks_are_refused():
    box = ed.Box(20.0, 20.0)
    rad = np.array([4.0] + [0.5] * 10)
    pos = np.column_stack([np.linspace(1.0, 19.0, 11), np.full(11, 16.0)])
    pos[0] = [10.0, 8.0]
    ok = ed.Simulation(pos, np.zeros((11, 2)), rad, box=box, grid="wide")
    assert ok._state.wide is not None
    near = pos.copy()
    near[1] = [10.0 + 2.9, 8.0 + 2.9]  # (4.10 from the centre: inside 4.5, cells away)
    with pytest.raises(ValueError, match="disk 1 overlaps disk 0|disk 0 overlaps disk 1"):
        ed.Simulation(near, np.zeros((11, 2)), rad, box=box, grid="wide")
    wall = [ed.Wall((13.5, 2.0), (13.5, 14.0))]  # (3.5 from the wide disk's centre)
    with pytest.raises(ValueError, match="overlaps walls"):
        ed.Simulation(pos, np.zeros((11, 2)), rad, box=box, walls=wall, grid="wide")


@pytest.mark.parametrize("seed", range(6))
def test_growing_wide_disks_as_the_reference(seed):
    # Every radius grows at its rate (a compression): footprints grow at their edges,
    # the grid is rebuilt with room to grow; the reference agrees event for event.
    periodic = BOX_KINDS[seed % 4]
    gas = _mixture(seed_of(986) + seed, n=40, big=2, ratio=4.0, packing=0.25,
                   periodic=periodic)
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                        grid="wide", growth=0.02)
    assert sim._state.wide is not None
    sim._record_events(10_000)
    ref = ReferenceSimulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                              growth=0.02)
    sim.advance(until=30.0, collisions=25)
    ref.advance(until=30.0, collisions=25)
    _assert_as_reference(sim, ref)


def test_a_mixture_of_ratio_ten_compressed_on_the_wide_grid():
    # 2 % of the disks ten times wider, compressed from packing 0.3 to 0.6: no overlap
    # on the way (a missed contact of growing disks would show), the wide grid kept
    # through the rebuilds that growth needs.
    gas = _mixture(seed_of(987), n=1500, big=30, ratio=10.0, packing=0.3)
    assert gas._state.wide is not None
    gas = ed.compress(gas, 0.6, rate=1e-2).simulation
    assert gas._state.wide is not None
    p, r = gas.positions, gas.radii
    d = p[:, None] - p[None]
    d -= gas.box.size * np.round(d / gas.box.size)
    gap = np.hypot(d[..., 0], d[..., 1]) - (r[:, None] + r[None])
    np.fill_diagonal(gap, np.inf)
    assert gap.min() > -1e-9 * 2 * r.min()
    assert ed.packing_fraction(gas) == pytest.approx(0.6, rel=1e-6)


def test_growth_past_what_the_box_fits_falls_back_to_the_uniform_grid():
    # A wide disk growing until its footprint no longer fits the periodic box: the
    # rebuild that growth needs then makes a uniform grid, and the run goes on.
    rng = np.random.default_rng(seed_of(988))
    box = ed.Box(10.0, 10.0)
    pos = [np.array([5.0, 5.0])]
    while len(pos) < 120:
        p = rng.uniform(0.0, 10.0, 2)
        d = np.array(pos) - p
        d -= 10.0 * np.round(d / 10.0)
        need = np.full(len(pos), 0.3)
        need[0] = 2.5
        if (np.hypot(*d.T) > need).all():
            pos.append(p)
    rad = np.full(len(pos), 0.05)
    rad[0] = 1.5
    sim = ed.Simulation(np.array(pos), rng.normal(size=(len(pos), 2)), rad, box=box,
                        grid="wide", growth=0.05)
    assert sim._state.wide is not None
    sim.advance(until=40.0)
    assert sim._state.wide is None and sim.radii[0] == pytest.approx(4.5)


@pytest.mark.parametrize("kwargs, match", [
    (dict(grid="hierarchical"), "grid must be"),
    (dict(grid="wide", cell_size=20.0), "cell_size"),
])
def test_bad_grids_are_refused(kwargs, match):
    gas = _mixture(1, n=40, big=2, ratio=4.0)
    with pytest.raises(ValueError, match=match):
        ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box, **kwargs)


def test_equal_disks_have_no_wide_grid():
    with pytest.raises(ValueError, match="more than one size"):
        ed.make_gas(50, 0.3, seed=1, grid="wide")


def test_a_bed_with_a_wide_intruder_settles_on_the_wide_grid():
    """200 inelastic disks and one 6 times wider poured under gravity: the automatic choice
    lists the wide one in its footprint, it comes to rest on the narrow ones, the whole bed
    is at rest by t = 150 (about 100 in the runs measured: the intruder slides slowly into a
    pocket) and then costs no event, with no overlap and the energy books holding; thrown
    upwards, the intruder lands on the bed again and all settle once more."""
    rad = np.full(200, 0.5)
    rad[0] = 3.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gas = ed.random_gas(200, 0.3, radii=rad, periodic=False, aspect=2.0, seed=3)
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                        gravity=(0.0, -1.0), restitution=0.8, wall_restitution=0.8)
    assert sim._state.wide is not None and sim._state.wide.index[0] >= 0
    e0 = sim.total_energy()
    sim.advance(until=150.0)
    assert sim.resting.all()
    assert len(overlaps(sim)) == 0
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e0, abs=1e-9)
    events = sim.counts.events
    sim.advance(until=250.0)
    assert sim.counts.events == events
    # The intruder rests on narrow disks (in the footprint's cells).
    row = int(np.flatnonzero(sim._state.order == 0)[0])
    assert any(s >= 0 for s in sim._state.rest_supports[row])
    # Thrown upwards out of the bed (every disk wakes when velocities are set), the
    # intruder lands on it again, and all settle once more.
    vel = np.zeros((200, 2))
    vel[0] = (0.0, 4.0)
    sim.set_velocities(vel)
    assert not sim.resting.any()
    e1 = sim.total_energy() + sim.dissipated_energy()
    sim.advance(until=sim.time + 150.0)
    assert sim.resting.all()
    assert len(overlaps(sim)) == 0
    assert sim.total_energy() + sim.dissipated_energy() == pytest.approx(e1, abs=1e-9)


# ---------------------------------------------------------------- under shear
def _sheared(seed):
    """A sheared box 13-18 wide and 10-14 high with 25-50 disks: one to three of radius
    1.1-1.6, the others of radius 0.5 (odd seeds) or 0.3-0.5, placed where they
    overlap nothing through the sliding boundary at an offset of 0, just below the
    width or at random; the rate 0.3, -0.8, 2.5 or -6 (up to 6 cells per time unit)."""
    rng = np.random.default_rng(seed_of(990) + seed)
    box = ed.Box(rng.uniform(13.0, 18.0), rng.uniform(10.0, 14.0))
    offset = (0.0, np.nextafter(box.width, 0.0), rng.uniform(0.0, box.width))[seed % 3]
    big, n = int(rng.integers(1, 4)), int(rng.integers(25, 50))
    pos, rad = [], []
    for _ in range(50_000):
        if len(pos) == n:
            break
        r = (rng.uniform(1.1, 1.6) if len(pos) < big
             else 0.5 if seed % 2 else rng.uniform(0.3, 0.5))
        p = rng.uniform([0.0, 0.0], [box.width, box.height])
        if all(sheared_gap(p, q, box, offset) >= r + s for q, s in zip(pos, rad)):
            pos.append(p)
            rad.append(r)
    rate = (0.3, -0.8, 2.5, -6.0)[seed % 4]
    return (box, offset, rate, np.array(pos), rng.normal(size=(len(pos), 2)),
            np.array(rad), rng.uniform(0.5, 2.0, len(pos)))


@pytest.mark.parametrize("seed", range(24))
def test_sheared_mixtures_as_the_reference(seed):
    """Wide disks seen through the sliding boundary: their rows across it are listed
    in the columns where their images are, one column more for the offset's slide
    within a cell, and listed afresh at each slide.  The engine on that grid against
    the reference over 30 collisions, many of them with a wide disk or through the
    boundary, as the images slide by up to 50 cells.  (The largest difference of an
    event time measured in these runs is 2e-13.)"""
    box, offset, rate, pos, vel, rad, mass = _sheared(seed)
    model = dict(restitution=0.7, tc=0.05) if seed % 5 == 4 else {}
    sim = ed.Simulation(pos, vel, rad, mass, box=box, shear_rate=rate, shear_offset=offset,
                        grid="wide", **model)
    assert sim._state.wide is not None
    sim._record_events(10_000)
    ref = ReferenceSimulation(pos, vel, rad, mass, box=box, shear_rate=rate,
                              shear_offset=offset, **model)
    sim.advance(until=5.0, collisions=30)
    ref.advance(until=5.0, collisions=30)
    got = _assert_as_reference(sim, ref)
    assert sim.shear_offset == pytest.approx(ref.offset, abs=1e-8)
    np.testing.assert_allclose(sim.unwrapped_positions, ref.unwrapped_positions, rtol=0,
                               atol=1e-8)
    assert len(got) == 30 or sim.time == 5.0


def test_the_sheared_mixtures_meet_wide_disks_through_the_boundary():
    """Across the systems above, wide disks collide many times, the images slide by
    hundreds of cells, and wide disks leave through the top or bottom."""
    wide_hits = slides = exits = 0
    for seed in range(24):
        box, offset, rate, pos, vel, rad, mass = _sheared(seed)
        sim = ed.Simulation(pos, vel, rad, mass, box=box, shear_rate=rate,
                            shear_offset=offset, grid="wide")
        sim._record_events(10_000)
        sim.advance(until=5.0, collisions=30)
        wide = rad > 1.0
        wide_hits += sum(1 for _, kind, i, j in sim._recorded_events()
                         if kind == "disk" and (wide[i] or wide[j]))
        slides += abs(int(sim._state.shear_slides[0]))
        exits += int(np.round(np.abs(sim.unwrapped_positions[wide, 1]
                                     - sim.positions[wide, 1]) / box.height).sum())
    assert wide_hits > 50
    assert slides > 200
    assert exits > 0


@pytest.mark.parametrize("rate", [0.5, -3.0])
def test_a_sheared_mixture_on_the_wide_grid_keeps_its_books(rate):
    """500 disks with 1 % ten times wider, sheared (the automatic choice takes the wide
    grid): no overlap through the sliding boundary at any of 40 checks over 8x10^4
    collisions, the peculiar momentum holds (the total y momentum is zero, so
    ``d/dt sum m u_x = -rate P_y`` vanishes), and the work of the shear stress is the
    change of the peculiar energy to rounding."""
    rad = np.full(500, 0.5)
    rad[:5] = 5.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gas = ed.random_gas(500, 0.35, radii=rad, seed=seed_of(991))
    sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                        shear_rate=rate)
    assert sim._state.wide is not None and len(sim._state.wide.disk) == 5
    momentum = (sim.masses[:, None] * sim.peculiar_velocities).sum(axis=0)
    assert worst_gap(sim, 40) > -1e-12
    u = sim.peculiar_velocities
    drift = (sim.masses[:, None] * u).sum(axis=0) - momentum
    assert np.abs(drift).max() < 1e-12 * float(np.abs(sim.masses[:, None] * u).sum())
    energy = 0.5 * float(np.sum(sim.masses[:, None] * u * u))
    m = sim.measure(5.0, blocks=2)
    u = sim.peculiar_velocities
    gained = 0.5 * float(np.sum(sim.masses[:, None] * u * u)) - energy
    work = -rate * sim.box.area * m.duration * m.pressure_xy
    assert abs(gained - work) <= 1e-11 * energy


def test_a_sheared_mixture_continues_bit_identically_on_the_wide_grid(tmp_path):
    """In pieces and through a checkpoint, a sheared mixture on the wide grid runs as
    in one call, bit for bit (the wide lists across the boundary are rebuilt from the
    slides saved)."""
    rad = np.full(300, 0.5)
    rad[:3] = 4.0

    def gas():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            g = ed.random_gas(300, 0.35, radii=rad, seed=seed_of(992))
        return ed.Simulation(g.positions, g.velocities, g.radii, box=g.box,
                             shear_rate=-1.3, grid="wide")

    whole, others = continuations(gas, 12.0, 13, 5.0, tmp_path / "half.edmd2d")
    for other in others:
        assert other._state.wide is not None
        assert np.array_equal(other.positions, whole.positions)
        assert np.array_equal(other.velocities, whole.velocities)
        assert other.counts.collisions == whole.counts.collisions


def test_a_sheared_box_too_narrow_for_its_widest_disk_is_refused():
    """The sliding boundary's collision takes the nearest image along x, so a sheared
    box stays more than 4 of the largest diameters wide on the wide grid too."""
    rad = np.full(60, 0.5)
    rad[0] = 2.5
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gas = ed.random_gas(60, 0.2, radii=rad, seed=1, aspect=0.8)
    assert 10.0 < gas.box.width < 20.0 < gas.box.height
    with pytest.raises(ValueError, match="more than 4 largest diameters"):
        ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                      shear_rate=0.5, grid="wide")


def test_two_wide_disks_meet_through_the_boundary_two_widths_over():
    """Near opposite corners with the offset just below the width, a wide disk meets
    the image of another one box up and (offset included) two box widths over: the
    image each finds in their shared cells.  The same events as the reference."""
    pos = [[0.1, 9.5], [15.9, 1.0]]
    vel = [[0.0, 1.0], [0.0, 0.0]]
    rad = [1.5, 1.5]
    for y in (4.0, 5.0, 6.0, 7.0):
        for x in np.linspace(1.0, 15.0, 10):
            pos.append([x, y])
            vel.append([0.0, 0.0])
            rad.append(0.3)
    box = ed.Box(16.0, 12.0)
    sim = ed.Simulation(pos, vel, rad, box=box, shear_rate=0.001, shear_offset=15.9,
                        grid="wide")
    assert list(sim._state.wide.disk) == [0, 1]
    sim._record_events(1000)
    ref = ReferenceSimulation(pos, vel, rad, box=box, shear_rate=0.001, shear_offset=15.9)
    sim.advance(until=3.0)
    ref.advance(until=3.0)
    got = _assert_as_reference(sim, ref)
    assert got[0][1:] == ("disk", 0, 1) and got[0][0] == pytest.approx(0.514, abs=1e-3)


def test_a_still_sheared_box_lists_its_wide_disks_where_the_images_are_when_it_moves():
    """Disks at rest under shear: a run to a time ends with no event, and the images'
    offset is then restarted at that time, cells away from where the last slide left
    it.  A wide disk's rows across the boundary are listed afresh there: set moving, a
    narrow disk meets the wide one's image as in a fresh simulation of the same
    state and in the reference."""
    rad = [1.5, 0.3]
    pos = [[8.0, 10.9], [11.9, 0.75]]
    for x in np.linspace(1.0, 15.0, 8):
        for y in (4.5, 6.0, 7.5):
            pos.append([x, y])
            rad.append(0.3)
    pos = np.array(pos)
    box = ed.Box(16.0, 12.0)
    rate = 0.05
    sim = ed.Simulation(pos, np.zeros_like(pos), rad, box=box, shear_rate=rate,
                        grid="wide")
    sim.advance(until=(9.0 + 7 * 16.0) / (rate * 12.0))  # (an offset of 4.5 cells)
    vel = np.zeros_like(pos)
    vel[1] = (2.0, -0.3)
    sim.set_velocities(vel)
    fresh = ed.Simulation(sim.positions, vel, rad, box=box, shear_rate=rate,
                          shear_offset=sim.shear_offset, grid="wide", time=sim.time)
    ref = ReferenceSimulation(sim.positions, vel, rad, box=box, shear_rate=rate,
                              shear_offset=sim.shear_offset, time=sim.time)
    t_end = sim.time + 2.0
    for s in (sim, fresh):
        s._record_events(1000)
        s.advance(until=t_end)
    ref.advance(until=t_end)
    for s in (sim, fresh):
        _assert_as_reference(s, ref)
    assert _canonical(sim._recorded_events())[0][1:] == ("disk", 0, 1)
