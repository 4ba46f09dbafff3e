"""Changing a simulation's state from outside: new positions (validated like the
constructor), read-only copies, and the clearer errors for careless input."""

from __future__ import annotations

import copy
import os
import subprocess
import sys

import numpy as np
import pytest

import edmd2d as ed
from conftest import overlaps, seed_of


@pytest.mark.parametrize("name", ["positions", "velocities", "radii", "masses",
                                  "unwrapped_positions", "species", "restitution"])
def test_copies_are_read_only(name):
    # Editing a copy could never change the simulation: it must fail, not pass silently.
    sim = ed.make_gas(50, 0.3, seed=seed_of(1))
    arr = getattr(sim, name)
    with pytest.raises(ValueError, match="read-only"):
        arr[0] = 1.0
    # (Arithmetic on them still gives ordinary arrays.)
    assert (arr * 2).flags.writeable


def test_set_positions_then_run_as_if_built_there():
    sim = ed.make_gas(200, 0.3, seed=seed_of(2))
    sim.advance(collisions=500)
    new = ed.make_gas(200, 0.3, seed=seed_of(3)).positions  # another valid configuration
    counts, t = sim.counts, sim.time
    sim.set_positions(new)
    assert np.array_equal(sim.positions, new) and sim.time == t and sim.counts == counts
    np.testing.assert_array_equal(sim.unwrapped_positions, new)  # (a fresh start)
    fresh = ed.Simulation(new, sim.velocities, sim.radii, sim.masses, box=sim.box, time=t)
    sim.advance(collisions=2000)
    fresh.advance(collisions=2000)
    assert np.array_equal(sim.positions, fresh.positions)
    assert np.array_equal(sim.velocities, fresh.velocities)
    assert len(overlaps(sim)) == 0


def test_positions_setter_walls_and_large_systems():
    # The property setter, in a walled box with a segment, and above the size at
    # which rows are kept in Z-order (the internal order differs from the user's).
    box = ed.Box(80.0, 80.0, periodic=(True, False))
    wall = ed.Wall((40.0, 10.0), (40.0, 70.0))
    g = ed.make_gas(1200, 0.2, periodic=(True, False), seed=seed_of(4))
    shift = np.array([0.0, 0.5 * (80.0 - g.box.height)])
    pos = g.positions * [80.0 / g.box.width, 1.0] + shift
    keep = np.abs(pos[:, 0] - 40.0) > 1.0
    sim = ed.Simulation(pos[keep], g.velocities[keep], 0.5, box=box, walls=[wall])
    sim.advance(collisions=3000)
    moved = sim.positions.copy()
    moved[:, 1] = 80.0 - moved[:, 1]  # mirrored: still valid
    sim.positions = moved
    np.testing.assert_array_equal(sim.positions, moved)
    sim.advance(collisions=3000)
    assert len(overlaps(sim)) == 0


@pytest.mark.parametrize("change, match", [
    (lambda p: p[:-1], r"positions must have shape"),
    (lambda p: np.vstack([p[:1], p[:1], p[2:]]), "overlaps"),
    (lambda p: p + [0.0, 1e3], "outside the box"),
    (lambda p: np.where(np.arange(len(p))[:, None] == 0, [[np.nan, 1.0]], p), "NaN"),
])
def test_bad_positions_leave_the_simulation_unchanged(change, match):
    sim = ed.make_gas(100, 0.4, seed=seed_of(5))
    sim.advance(collisions=300)
    twin = copy.deepcopy(sim)
    with pytest.raises((ValueError, TypeError), match=match):
        sim.set_positions(change(np.array(sim.positions)))
    assert np.array_equal(sim.positions, twin.positions)
    sim.advance(collisions=500)
    twin.advance(collisions=500)
    assert np.array_equal(sim.positions, twin.positions) and sim.counts == twin.counts


def test_positions_overlapping_a_wall_are_refused():
    box = ed.Box(10.0, 10.0, periodic=False)
    sim = ed.Simulation([[2.0, 2.0], [8.0, 8.0]], [[1.0, 0.0], [0.0, 1.0]], 0.5, box=box,
                        walls=[ed.Wall((5.0, 0.0), (5.0, 6.0))])
    with pytest.raises(ValueError, match=r"overlaps walls\[0\]"):
        sim.set_positions([[5.2, 2.0], [8.0, 8.0]])
    assert np.array_equal(sim.positions, [[2.0, 2.0], [8.0, 8.0]])


# ---------------------------------------------------------------- careless input
def test_non_finite_scalars_say_so():
    box = ed.Box(10.0, 10.0)
    with pytest.raises(ValueError, match="radii contains NaN or infinite values: got nan"):
        ed.Simulation([[5.0, 5.0]], [[0.0, 0.0]], float("nan"), box=box)
    with pytest.raises(ValueError, match="time contains NaN or infinite values: got inf"):
        ed.Simulation([[5.0, 5.0]], [[0.0, 0.0]], 0.5, box=box, time=float("inf"))
    sim = ed.Simulation([[5.0, 5.0]], [[1.0, 0.0]], 0.5, box=box)
    with pytest.raises(ValueError, match="until contains NaN or infinite values: got inf"):
        sim.advance(until=float("inf"))


@pytest.mark.parametrize("kwargs", [
    dict(positions=[["5", "5"]]),
    dict(radii="0.5"),
    dict(velocities=[[0.0, "1"]]),
])
def test_strings_are_refused_everywhere(kwargs):
    args = dict(positions=[[5.0, 5.0]], velocities=[[0.0, 0.0]], radii=0.5)
    args.update(kwargs)
    with pytest.raises(TypeError, match="must be numeric, got strings"):
        ed.Simulation(box=ed.Box(10.0, 10.0), **args)


def test_wall_messages():
    with pytest.raises(ValueError, match=r"both \(1\.0, 1\.0\)$"):
        ed.Wall((1, 1), (1.0, 1.0))
    with pytest.raises(ValueError, match="closed polygon needs at least 3 vertices, got 2"):
        ed.Wall.polygon([(1, 1), (2, 2)])
    assert len(ed.Wall.polygon([(1, 1), (2, 2)], closed=False)) == 1


def test_viz_without_matplotlib_names_the_extra():
    # A child process in which matplotlib cannot be imported.
    code = ("import sys; sys.modules['matplotlib'] = None\n"
            "import edmd2d\n"
            "try:\n    edmd2d.viz\nexcept ModuleNotFoundError as e:\n    print(e)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=dict(os.environ), timeout=120, check=True).stdout
    assert "pip install 'edmd2d[viz]'" in out


def test_a_run_the_clock_cannot_resolve_is_refused():
    # At speed 1e300 a disk crosses a cell in 1e-300: from t ~ 1e-285 on, the float64
    # clock could not tell two crossings apart and would stop.
    box = ed.Box(20.0, 20.0)
    sim = ed.Simulation([[5.0, 5.0], [15.0, 15.0]], [[1e300, 0.0], [0.0, 1.0]], 0.5, box=box)
    with pytest.raises(ValueError, match="float64 clock cannot resolve"):
        sim.advance(until=1.0)
    assert sim.time == 0.0
    # A count of collisions is checked at the current time: at t = 1e17 (resolution
    # 16) a crossing every 2.5 is lost.
    late = ed.Simulation([[5.0, 5.0], [15.0, 15.0]], [[4.0, 0.0], [0.0, 0.0]], 0.5, box=box,
                         time=1e17)
    with pytest.raises(ValueError, match="float64 clock cannot resolve"):
        late.advance(collisions=1)
    # Ordinary fast disks are fine (no tunnelling at 1e12 either).
    fast = ed.Simulation([[5.0, 5.0], [15.0, 15.0]], [[1e12, 3.0], [0.0, 1.0]], 0.5, box=box)
    fast.advance(until=1e-5)
    assert fast.counts.cell_crossings > 5e5


def test_opening_a_partition_lets_a_gas_fill_the_box_uniformly():
    """Free expansion: an elastic gas in the left half of a walled box, a partition
    (wall segment 0) down the middle.  Opened, the gas fills the box; the fraction of
    disks in the right half, averaged over 40 well separated times, is 1/2 to within
    its statistics (binomial: sd sqrt(1/4N) = 0.025 per time for N = 100, so 0.004 for
    the mean of 40 nearly independent ones; 0.03 allows for their correlation)."""
    import edmd2d as ed

    rng = np.random.default_rng(5)
    pos = np.array([(x, y) for x in np.arange(0.7, 9.5, 1.25)
                    for y in np.arange(0.7, 19.5, 1.4)])[:100]
    vel = rng.normal(size=(100, 2))
    sim = ed.Simulation(pos, vel, 0.5, box=ed.Box(20.0, 20.0, periodic=False),
                        walls=[ed.Wall((10.0, 0.0), (10.0, 20.0))])
    e0 = sim.total_energy()
    sim.advance(until=20.0)
    assert (sim.positions[:, 0] < 10.0).all()  # held in the left half
    sim.open_wall(0)
    sim.advance(until=100.0)  # (a disk crosses the box in about 20)
    right = []
    for k in range(40):
        sim.advance(until=100.0 + 10.0 * (k + 1))
        right.append(float((sim.positions[:, 0] > 10.0).mean()))
    assert np.mean(right) == pytest.approx(0.5, abs=0.03)
    assert sim.total_energy() == pytest.approx(e0, rel=1e-12)
    assert sim.wall_heat().shape == (5,)  # the open segment keeps its place


def test_open_walls_survive_a_checkpoint(tmp_path):
    import edmd2d as ed
    from edmd2d import checkpoint

    sim = ed.Simulation([[2.0, 2.0], [5.0, 5.0], [3.0, 7.0]],
                        [[1.0, 0.3], [-0.4, 1.0], [0.2, -0.9]], 0.5,
                        box=ed.Box(10.0, 10.0, periodic=False),
                        walls=[ed.Wall((6.0, 1.0), (9.0, 4.0)), ed.Wall((8.0, 0.0), (8.0, 10.0))])
    sim.open_wall(1)
    checkpoint.save(sim, tmp_path / "open.edmd2d")
    again = checkpoint.load(tmp_path / "open.edmd2d")
    assert again.open_walls.tolist() == [False, True]
    again.advance(until=5.0)
    sim.advance(until=5.0)
    assert np.array_equal(again.positions, sim.positions)


@pytest.mark.parametrize("open_walls, error", [([2], ValueError), ([-1], ValueError),
                                               (1, TypeError), ("0", TypeError),
                                               ([0.5], TypeError)])
def test_bad_open_walls_are_refused_by_name(open_walls, error):
    import edmd2d as ed

    with pytest.raises(error, match="open_walls"):
        ed.Simulation([[2.0, 2.0]], [[1.0, 0.0]], 0.5, box=ed.Box(10.0, 10.0, periodic=False),
                      walls=[ed.Wall((5.0, 0.0), (5.0, 10.0)), ed.Wall((8.0, 1.0), (9.0, 2.0))],
                      open_walls=open_walls)


def test_a_disk_may_start_on_an_open_wall():
    import edmd2d as ed

    sim = ed.Simulation([[5.0, 2.0]], [[1.0, 0.0]], 0.5, box=ed.Box(10.0, 10.0, periodic=False),
                        walls=[ed.Wall((5.0, 0.0), (5.0, 10.0))], open_walls=[0])
    sim.advance(until=2.0)
    assert sim.positions[0, 0] == pytest.approx(7.0)
    with pytest.raises(ValueError, match="overlap"):
        ed.Simulation([[5.0, 2.0]], [[1.0, 0.0]], 0.5, box=ed.Box(10.0, 10.0, periodic=False),
                      walls=[ed.Wall((5.0, 0.0), (5.0, 10.0))])


def test_an_open_wall_is_no_obstacle_to_set_positions_or_to_a_disk_at_rest_on_it():
    import edmd2d as ed

    box, wall = ed.Box(10.0, 10.0, periodic=False), ed.Wall((0.0, 5.0), (10.0, 5.0))
    sim = ed.Simulation([[2.0, 5.0], [7.0, 2.0]], [[0.1, 0.0], [0.0, 0.3]], 0.5, box=box,
                        walls=[wall], open_walls=[0])
    sim.set_positions(sim.positions)  # disk 0 lies across the open wall
    assert sim.positions[0, 1] == 5.0
    # At rest on it under gravity: refused on a closed wall (it would bounce without
    # end), not on an open one, through which it falls.
    with pytest.raises(ValueError, match="segment"):
        ed.Simulation([[2.0, 5.5]], [[0.0, 0.0]], 0.5, box=box, walls=[wall],
                      gravity=(0.0, -1.0))
    falling = ed.Simulation([[2.0, 5.5]], [[0.0, 0.0]], 0.5, box=box, walls=[wall],
                            open_walls=[0], gravity=(0.0, -1.0))
    falling.advance(until=1.0)
    assert falling.positions[0, 1] == pytest.approx(5.0)
