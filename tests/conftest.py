"""Shared fixtures: the two engines (one test suite, several backends) and random systems."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

import edmd2d as ed
from edmd2d.reference import ReferenceSimulation

BACKENDS = {"engine": ed.Simulation, "reference": ReferenceSimulation}


def _seed_offset() -> int:
    text = os.environ.get("EDMD2D_TEST_SEED_OFFSET", "0")
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"EDMD2D_TEST_SEED_OFFSET must be an integer, got {text!r}") from None


# Every seed of a test's random system goes through seed_of, so that the whole suite can
# be run on other trajectories: EDMD2D_TEST_SEED_OFFSET=k shifts each seed by 1000 k.  A
# verdict that hangs on one lucky trajectory (a single seed just past a threshold) then
# fails under some offset; the suite is meant to pass with offsets 0 to 3.  Tests that
# pin a number of one trajectory (a bit-identical replay, a documented example) do not
# use it.
SEED_OFFSET = _seed_offset()


def seed_of(k: int) -> int:
    """The seed ``k`` of a test, shifted by ``1000 * EDMD2D_TEST_SEED_OFFSET``."""
    return k + 1000 * SEED_OFFSET


@pytest.fixture(params=sorted(BACKENDS))
def backend(request):
    """The compiled engine and the brute-force reference: hand-computed cases run on both."""
    return BACKENDS[request.param]


def min_image(d, box):
    """Minimum-image displacement (for tests only)."""
    d = np.array(d, dtype=float)
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            d[..., axis] -= length * np.round(d[..., axis] / length)
    return d


def random_system(rng, n, box, walls=(), rmin=0.3, rmax=0.6, max_tries=20000):
    """Up to ``n`` non-overlapping disks by random sequential insertion (small systems).

    Mixed radii and masses, Gaussian velocities.  Returns positions, velocities, radii,
    masses.
    """
    pos, rad = [], []
    for _ in range(max_tries):
        if len(pos) == n:
            break
        r = rng.uniform(rmin, rmax)
        p = rng.uniform([0.0, 0.0], [box.width, box.height])
        if any(not box.periodic[a] and not (r < p[a] < (box.width, box.height)[a] - r)
               for a in range(2)):
            continue
        if pos and (np.hypot(*min_image(np.array(pos) - p, box).T) < np.array(rad) + r).any():
            continue
        if any(segment_distance(p, w) < r for w in walls):
            continue
        pos.append(p)
        rad.append(r)
    pos = np.array(pos)
    vel = rng.normal(size=(len(pos), 2))
    mass = rng.uniform(0.5, 2.0, len(pos))
    return pos, vel, np.array(rad), mass


def segment_distance(p, wall):
    """Distance from point(s) ``p`` (shape (2,) or (N, 2)) to a wall segment."""
    a, b = np.array(wall.start), np.array(wall.end)
    u = b - a
    s = np.clip((np.asarray(p) - a) @ u / (u @ u), 0.0, 1.0)
    return np.hypot(*(np.asarray(p) - a - np.multiply.outer(s, u)).T)


def overlaps(sim, tol=1e-9):
    """Pairs of disks closer than (1 - tol) times their contact distance (brute force)."""
    p = sim.positions
    r = sim.radii
    d = min_image(p[:, None, :] - p[None, :, :], sim.box)
    dist = np.hypot(d[..., 0], d[..., 1])
    contact = r[:, None] + r[None, :]
    bad = np.triu(dist < contact * (1 - tol), k=1)
    return np.argwhere(bad)


def smallest_gap(sim) -> float:
    """The smallest gap between two disks over every pair and every image (through the
    sliding boundary at the current offset), relative to their contact distance."""
    p, r = sim.positions, sim.radii
    width, height = sim.box.width, sim.box.height
    worst = math.inf
    for sy in (-1, 0, 1):
        dx = p[:, None, 0] - p[None, :, 0] - sy * sim.shear_offset
        dx -= width * np.floor(dx / width + 0.5)
        dy = p[:, None, 1] - p[None, :, 1] - sy * height
        contact = r[:, None] + r[None, :]
        gap = (np.hypot(dx, dy) - contact) / contact
        if sy == 0:
            np.fill_diagonal(gap, np.inf)
        worst = min(worst, float(gap.min()))
    return worst


def sheared_gap(p, q, box, offset):
    """The smallest centre distance of ``p`` to the images of ``q`` in a box sheared
    at ``offset`` (the nearest image along x, one box up, none or one down)."""
    best = np.inf
    for sy in (-1, 0, 1):
        dx = p[0] - (q[0] + sy * offset)
        dx -= box.width * np.floor(dx / box.width + 0.5)
        best = min(best, np.hypot(dx, p[1] - (q[1] + sy * box.height)))
    return best


def continuations(make, t_end, pieces, t_save, path):
    """The simulation ``make()`` run to ``t_end`` in one call; and in ``pieces`` equal
    calls, and through a checkpoint saved at ``t_save`` (to ``path``) and loaded:
    ``(whole, [in_pieces, restarted])``, for comparisons bit for bit."""
    whole = make()
    whole.advance(until=t_end)
    split = make()
    for t in np.linspace(0.0, t_end, pieces + 1)[1:]:
        split.advance(until=float(t))
    restarted = make()
    restarted.advance(until=t_save)
    ed.checkpoint.save(restarted, path)
    restarted = ed.checkpoint.load(path)
    restarted.advance(until=t_end)
    return whole, [split, restarted]


def worst_gap(sim, stretches, collisions=2000):
    """The smallest gap (:func:`smallest_gap`) seen after each of ``stretches`` runs of
    ``collisions`` collisions of the sheared ``sim``."""
    worst = math.inf
    for _ in range(stretches):
        sim.advance(collisions=collisions)
        worst = min(worst, smallest_gap(sim))
    return worst
