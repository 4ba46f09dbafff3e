"""Bad input raises a clear error naming the argument, and leaves the simulation usable."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import edmd2d as ed

BOX = ed.Box(10.0, 10.0, periodic=False)
POS = [[2.0, 2.0], [5.0, 5.0], [8.0, 8.0]]
VEL = [[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]


def make(**overrides):
    kwargs = dict(positions=POS, velocities=VEL, radii=0.5, masses=1.0, box=BOX)
    kwargs.update(overrides)
    return ed.Simulation(**kwargs)


@pytest.mark.parametrize(
    "overrides, error, pattern",
    [
        (dict(positions=[[1.0, 2.0, 3.0]] * 3), ValueError, r"positions must have shape \(N, 2\)"),
        (dict(positions=np.zeros((0, 2)), velocities=np.zeros((0, 2))), ValueError,
         "at least one disk"),
        (dict(velocities=[[1.0, 0.0]] * 2), ValueError, r"velocities must have shape \(3, 2\)"),
        (dict(positions=[[2.0, 2.0], [np.nan, 5.0], [8.0, 8.0]]), ValueError,
         r"positions contains NaN or infinite values at indices \[1\]"),
        (dict(velocities=[[1.0, 0.0], [0.0, 1.0], [np.inf, 0.0]]), ValueError,
         r"velocities contains NaN or infinite values at indices \[2\]"),
        (dict(radii=[0.5, 0.0, 0.5]), ValueError, r"radii must be > 0; disks \[1\]"),
        (dict(radii=[0.5, 0.5]), ValueError, r"radii must have shape \(3,\)"),
        (dict(radii=np.nan), ValueError, "radii contains NaN"),
        (dict(masses=[1.0, -2.0, 1.0]), ValueError, r"masses must be > 0; disks \[1\]"),
        (dict(masses=[1.0, np.nan, 1.0]), ValueError, r"masses contains NaN"),
        (dict(radii="big"), TypeError, "radii must be numeric"),
        (dict(positions=[[2.0, 2.0], [2.5, 2.0], [8.0, 8.0]]), ValueError,
         r"disk 0 overlaps disk 1"),
        (dict(positions=[[2.0, 2.0], [5.0, 5.0], [12.0, 8.0]]), ValueError,
         r"disks \[2\] lie outside the box"),
        (dict(positions=[[0.2, 2.0], [5.0, 5.0], [8.0, 8.0]]), ValueError,
         r"disks \[0\] overlap the box wall on the x axis"),
        (dict(walls=[ed.Wall((2.0, 0.0), (2.0, 3.0))]), ValueError,
         r"disk 0 overlaps walls\[0\]"),
        (dict(walls=[ed.Wall((2.0, 0.0), (12.0, 3.0))]), ValueError,
         r"walls\[0\] has an end point .* outside the box"),
        (dict(walls=[((1, 1), (2, 2))]), TypeError, r"walls\[0\] must be an edmd2d.Wall"),
        (dict(box=None), TypeError, "box is required"),
        (dict(box=(10, 10)), TypeError, "box must be an edmd2d.Box"),
        (dict(box=ed.Box(0.8, 10.0, periodic=True), positions=[[0.4, 2.0]],
              velocities=[[0.0, 0.0]]), ValueError, "smaller than the largest disk diameter"),
        (dict(cell_size=0.5), ValueError, "cell_size must be at least"),
        # (1 / m overflows for a subnormal mass, and the velocities would become NaN)
        (dict(masses=[1e-310, 1.0, 1.0]), ValueError, r"masses must be at least .* \[0\]"),
        (dict(positions=np.array(POS) + 0j), TypeError, "positions must be real"),
        (dict(positions=np.ones((3, 2), bool)), TypeError, "positions must be numbers, got "
         "booleans"),
        (dict(radii=[True, True, True]), TypeError, "radii must be numbers, got booleans"),
        (dict(masses=np.True_), TypeError, "masses must be numbers, got booleans"),
        (dict(thermostat=(1.0, 1.0), seed="seven"), TypeError, "seed must be None, an int"),
        (dict(thermostat=(1.0, 1.0), seed=-1), ValueError, "seed must be None, an int"),
    ],
)
def test_constructor_rejects(overrides, error, pattern):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # (a clear error, and no warning before it)
        with pytest.raises(error, match=pattern):
            make(**overrides)


def test_overlap_with_periodic_image_is_found():
    box = ed.Box(10.0, 10.0, periodic=True)
    with pytest.raises(ValueError, match="disk 0 overlaps disk 1"):
        ed.Simulation([[0.2, 5.0], [9.8, 5.0]], np.zeros((2, 2)), 0.5, box=box)


def test_touching_disks_are_accepted():
    # Exactly touching (to rounding) is allowed; the pair separates without an event.
    sim = make(positions=[[2.0, 2.0], [3.0, 2.0], [8.0, 8.0]],
               velocities=[[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])
    sim.advance(until=1.0)
    assert sim.counts.collisions == 0


@pytest.mark.parametrize(
    "box_args, pattern",
    [((0.0, 1.0), "Box width must be > 0"), ((1.0, -2.0), "Box height must be > 0"),
     ((1.0, np.inf), "Box height must be finite"),
     ((1.0, 1.0, "yes"), "periodic must be a bool or a pair"),
     ((1.0, 1.0, (True,)), "pair of bools"),
     ((1e200, 1.0), "Box width must be at most 1e[+]150")],
)
def test_bad_box(box_args, pattern):
    with pytest.raises((TypeError, ValueError), match=pattern):
        ed.Box(*box_args)


def test_degenerate_wall():
    with pytest.raises(ValueError, match="Wall is degenerate"):
        ed.Wall((1.0, 1.0), (1.0, 1.0))
    with pytest.raises(ValueError, match=r"Wall start must have shape \(2,\)"):
        ed.Wall((1.0, 1.0, 1.0), (2.0, 2.0))


@pytest.mark.parametrize(
    "kwargs, error, pattern",
    [
        (dict(), TypeError, "needs until= .* or collisions="),
        (dict(until=0.5), ValueError, "earlier than the current time"),
        (dict(until=np.nan), ValueError, "until contains NaN"),
        (dict(collisions=-1), ValueError, "collisions must be >= 0"),
        (dict(collisions=2.5), TypeError, "collisions must be an integer"),
        (dict(until="soon"), TypeError, "until must be numeric"),
        (dict(collisions=2 ** 70), ValueError, "collisions must be at most 2[*][*]63 - 1"),
    ],
)
def test_bad_advance_leaves_state_unchanged(kwargs, error, pattern):
    sim = make()
    sim.advance(until=1.0)
    before = (sim.time, sim.positions, sim.velocities, sim.counts)
    with pytest.raises(error, match=pattern):
        sim.advance(**kwargs)
    assert sim.time == before[0]
    np.testing.assert_array_equal(sim.positions, before[1])
    np.testing.assert_array_equal(sim.velocities, before[2])
    assert sim.counts == before[3]
    # The next valid call works and agrees with an untouched twin.
    twin = make().advance(until=1.0)
    sim.advance(until=7.0)
    twin.advance(until=7.0)
    np.testing.assert_array_equal(sim.positions, twin.positions)


def test_collisions_zero_is_a_no_op():
    sim = make()
    sim.advance(collisions=0)
    assert sim.time == 0.0 and sim.counts.events == 0


def test_collisions_that_can_never_happen():
    sim = ed.Simulation([[5.0, 5.0]], [[0.0, 0.0]], 0.5, box=BOX)
    with pytest.raises(RuntimeError, match="no further event can ever happen"):
        sim.advance(collisions=1)
    sim.advance(until=3.0)  # still usable
    assert sim.time == 3.0


def test_set_velocities_validates_and_repredicts():
    sim = make()
    with pytest.raises(ValueError, match=r"velocities must have shape \(3, 2\)"):
        sim.set_velocities(np.zeros((2, 2)))
    sim.advance(until=0.5)
    sim.set_velocities(np.zeros((3, 2)))
    p = sim.positions
    sim.advance(until=5.0)
    np.testing.assert_array_equal(sim.positions, p)


def test_returned_arrays_are_read_only_copies():
    # An edit of a returned array could not reach the simulation: it fails loudly, and
    # a copy of it is an ordinary array that leaves the simulation alone.
    sim = make()
    for name in ("positions", "velocities", "radii", "masses"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(sim, name)[:] = 0.0
        edited = getattr(sim, name).copy()
        edited[:] = 0.0
    assert sim.positions[0, 0] == 2.0 and sim.velocities[0, 0] == 1.0
    assert sim.radii[0] == 0.5 and sim.masses[0] == 1.0


def test_inputs_are_not_aliased():
    pos = np.array(POS)
    sim = make(positions=pos)
    pos[:] = 0.0
    assert sim.positions[0, 0] == 2.0


def test_scalar_and_array_radii_masses():
    sim = make(radii=[0.5, 0.6, 0.7], masses=math.inf)
    assert sim.radii.tolist() == [0.5, 0.6, 0.7]
    assert np.isinf(sim.masses).all()
    assert sim.kinetic_energy() == 0.0


@pytest.mark.parametrize("case", ["ring", "three", "filled", "peg", "segments"])
def test_wedged_elastic_disks_end_in_an_error_not_a_hang(case):
    """Elastic disks that touch with no room to move collide forever at one instant:
    the run stops with an error naming them after a bounded number of events that took
    no time (2^20 here, under a second), the state stays usable, and velocities that
    free them let it go on."""
    periodic, box = ed.Box(2.0, 5.0, periodic=True), ed.Box(5.0, 5.0, periodic=False)
    systems = {  # positions, velocities, masses, box, walls
        "ring": ([[0.5, 2.5], [1.5, 2.5]], [[1.0, 0.0], [0.0, 0.0]], 1.0, periodic, []),
        "three": ([[0.5, 1.5], [1.5, 1.5], [2.5, 1.5]], [[1.0, 0.0], [0.0, 0.0], [0.0, 0.0]],
                  1.0, ed.Box(3.0, 3.0), []),
        "filled": ([[0.5, 2.5], [1.5, 2.5]], [[1.0, 0.3], [0.0, 0.0]], 1.0,
                   ed.Box(2.0, 5.0, periodic=False), []),
        "peg": ([[0.5, 2.5], [1.5, 2.5]], [[1.0, 0.0], [0.0, 0.0]], [1.0, np.inf], box, []),
        "segments": ([[2.5, 2.5]], [[1.0, 0.0]], 1.0, box,
                     [ed.Wall((2.0, 1.0), (2.0, 4.0)), ed.Wall((3.0, 1.0), (3.0, 4.0))]),
    }
    pos, vel, mass, where, walls = systems[case]
    sim = ed.Simulation(pos, vel, 0.5, mass, box=where, walls=walls)
    with pytest.raises(RuntimeError, match=r"disks wedged at t=0.0: 1048576 or more events "
                       r"in a row at this one time, the next of disk \d+ with "
                       r"(disk \d+|walls\[[01]\]|the box wall .*), and the clock"):
        sim.advance(until=1.0)
    assert sim.time == 0.0 and sim.counts.events >= 1 << 20
    with pytest.raises(RuntimeError, match="wedged"):  # (collisions= too: it counts
        sim.advance(collisions=10 ** 7)  # disk-disk collisions, which may never come)
    sim.set_velocities(np.zeros((len(pos), 2)))
    assert sim.advance(until=1.0).time == 1.0


def test_runs_the_clock_or_the_arithmetic_cannot_follow_are_refused():
    """A thermostat that redraws faster than the clock resolves, and speeds whose
    product with the box's size would overflow a contact time's discriminant, are
    refused before the run, leaving the simulation as it was."""
    sim = ed.Simulation(POS, VEL, 0.5, box=BOX, thermostat=(1.0, 1e17), seed=1)
    with pytest.raises(ValueError, match="thermostat redraws a velocity every .* cannot "
                       "resolve"):
        sim.advance(until=1.0)
    assert sim.time == 0.0
    sim = ed.Simulation([[1e140, 1e140]], [[1e12, 0.0]], 1e139, box=ed.Box(1e141, 1e141))
    with pytest.raises(ValueError, match="must be at most 1e[+]150"):
        sim.advance(until=1.0)
    assert sim.time == 0.0
