"""Groups of slow disks that hold one another up (edmd2d._balance): balanced by
non-negative contact forces, and stable."""

import numpy as np
import pytest

from edmd2d import Box, _balance

G = np.array([0.0, -1.0])
SPEED, GAP = 0.05, 1e-3


def groups(pos, box, vel=None, static=None, ends=(), mass=None):
    pos = np.asarray(pos, float)
    n = len(pos)
    vel = np.zeros((n, 2)) if vel is None else np.asarray(vel, float)
    static = np.zeros(n, bool) if static is None else np.asarray(static)
    mass = np.ones(n) if mass is None else np.asarray(mass, float)
    return _balance.held_groups(pos, vel, np.full(n, 0.5), mass, static, ~static, box,
                                [tuple(map(np.asarray, e)) for e in ends], np.ones(4, bool),
                                np.ones(len(ends), bool), G, SPEED, GAP, _balance.TOL)


def crystal(cols, rows, width):
    """A triangular crystal of unit disks on the floor of a walled box ``width`` wide:
    rows of ``cols`` disks from x = 0.5, every other row one fewer and offset by 0.5."""
    pos = []
    for r in range(rows):
        k = cols - (r % 2)
        pos += [[0.5 + 0.5 * (r % 2) + c, 0.5 + r * np.sqrt(3.0) / 2.0] for c in range(k)]
    return np.array(pos), Box(width, rows + 2.0, periodic=False)


@pytest.mark.parametrize("cols, rows", [(6, 5), (20, 40)])
def test_a_crystal_between_walls_is_held_as_one_group(cols, rows):
    pos, box = crystal(cols, rows, float(cols))
    held, supports = groups(pos, box)
    assert sorted(held.tolist()) == list(range(len(pos)))
    assert (supports[:, 0] != -1).all()  # each has a support carrying force
    bottom = np.flatnonzero(pos[:, 1] == 0.5)
    assert np.isin(supports[np.searchsorted(held, bottom)], [-2 - 2]).any(axis=1).all()


def test_a_crystal_free_to_slide_along_the_floor_is_held_and_a_loose_pair_is_not():
    # Without friction the whole crystal can slide along the floor, but that lowers
    # nothing (a neutral motion): it is held, as a disk on a floor is.
    pos = np.array([[0.5 * (r % 2) + c + 0.25, 0.5 + r * np.sqrt(3.0) / 2.0]
                    for r in range(5) for c in range(6)])
    held, _ = groups(pos, Box(6.0, 8.0, periodic=(True, False)))
    assert len(held) == len(pos)
    # (The same crystal between walls a little too far apart: its edge disks, each on
    # one disk below, fall off.)
    pos, box = crystal(6, 5, 6.01)
    held, _ = groups(pos + [0.005, 0.0], box)
    assert len(held) == 0
    # Two disks side by side leaning on two pegs balance, but swing down together.
    pegs = [[1.9, 3.0], [4.1, 3.0]]
    pair = [[2.5, 3.8], [3.5, 3.8]]
    static = np.array([False, False, True, True])
    held, _ = groups(pair + pegs, Box(6, 20, periodic=False), static=static)
    assert len(held) == 0
    # Pinned by two more pegs above and outside them, they are held.
    pins = [[1.9, 4.6], [4.1, 4.6]]
    static = np.array([False, False, True, True, True, True])
    held, _ = groups(pair + pegs + pins, Box(6, 20, periodic=False), static=static)
    assert sorted(held.tolist()) == [0, 1]


def test_the_disks_of_a_crystal_too_fast_or_on_a_slope_are_not_held():
    pos, box = crystal(6, 5, 6.0)
    vel = np.zeros_like(pos)
    vel[-1] = [0.0, 2 * SPEED]  # the top disk is too fast to take part
    held, _ = groups(pos, box, vel)
    assert len(held) == len(pos) - 1 and len(pos) - 1 not in held
    # Two touching disks on a frictionless incline slide down it.
    a, b = np.array([1.0, 1.0]), np.array([9.0, 3.0])
    n = np.array([-(b - a)[1], (b - a)[0]]) / np.hypot(*(b - a))
    u = (b - a) / np.hypot(*(b - a))
    pair = [a + 3 * u + 0.5 * n, a + 4 * u + 0.5 * n]
    held, _ = groups(pair, Box(10, 10, periodic=False), ends=[(a, b)])
    assert len(held) == 0


def test_a_disk_in_a_v_of_segments_and_one_on_a_static_disk_are_held():
    # One disk touching both sides of a V (segments), one in the notch of two static
    # disks: each a group of one.
    v = [((2.0, 4.0), (3.0, 2.0)), ((3.0, 2.0), (4.0, 4.0))]
    r = 0.5
    # (The disk's centre above the V's tip at the distance r / sin(half-angle).)
    half = np.arctan2(1.0, 2.0)
    disk = [3.0, 2.0 + r / np.sin(half)]
    pos = [disk, [7.0, 1.0], [8.0, 1.0], [7.5, 1.0 + np.sqrt(3.0) / 2.0]]
    static = [False, True, True, False]
    held, supports = groups(pos, Box(10, 10, periodic=False), static=static, ends=v)
    assert sorted(held.tolist()) == [0, 3]
    assert sorted(supports[list(held).index(0), :2].tolist()) == [-7, -6]
    assert sorted(supports[list(held).index(3), :2].tolist()) == [1, 2]


def test_the_supports_kept_are_the_disks_under_each_disk_first():
    pos, box = crystal(8, 8, 8.0)
    held, supports = groups(pos, box)
    assert len(held) == len(pos)
    for k, i in enumerate(held):
        below = [j for j in range(len(pos)) if pos[j, 1] < pos[i, 1] - 0.1
                 and np.hypot(*(pos[j] - pos[i])) < 1.0 + 1e-9]
        if pos[i, 1] == 0.5:
            assert supports[k, 0] == -2 - 2  # (the floor)
        else:
            assert sorted(supports[k, :len(below)].tolist()) == sorted(below), (i, below)


def test_a_member_that_cannot_be_held_is_peeled_off_and_the_rest_is_held():
    # A and B stand on the floor in the corners of a box 2.8 wide, C in the groove
    # between them, and D leans on C alone, its contact 30 degrees off the vertical:
    # nothing balances D, so the group of four is not held; without D, the three hold
    # one another (A and B pinned by the side walls) and come to rest.
    c = np.array([1.4, 0.5 + np.sqrt(1.0 - 0.9 ** 2)])
    pos = np.array([[0.5, 0.5], [2.3, 0.5], c, c + [-0.5, np.sqrt(0.75)]])
    rows, supports = groups(pos, Box(2.8, 10.0, periodic=False))
    assert sorted(rows.tolist()) == [0, 1, 2]
    assert sorted(supports[list(rows).index(2)][:2].tolist()) == [0, 1]
    # Peeling off stops there: D alone is in no group held.
    old = _balance.PEELS
    try:
        _balance.PEELS = 1  # (the group itself only)
        assert len(groups(pos, Box(2.8, 10.0, periodic=False))[0]) == 0
    finally:
        _balance.PEELS = old
