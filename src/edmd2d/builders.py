"""One-line construction of systems: :func:`make_gas` (a gas from a lattice start) and
:func:`random_packing` (disks placed at random without overlap).

Wall segments
-------------
:func:`make_gas` and :func:`random_gas` take ``walls=``: the disks of the start that a
segment crosses (its distance from the centre, through the periodic images as the
engine sees it, at most the radius times ``1 + 1e-9``) are left out, the velocities are
drawn for the others, and the segments go to the simulation.  The command line
(:func:`edmd2d.config.build`) leaves out the same disks by the same rule.
"""

from __future__ import annotations

import math
import numbers
import warnings
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import _placement
from ._gaps import _segment_distance
from ._sums import weighted_sum
from ._validate import (
    as_count,
    as_generator,
    as_positive_float,
    indices_where,
    per_disk,
    refusal,
)
from .geometry import Box, Wall, as_walls
from .simulation import Simulation

__all__ = ["make_gas", "lattice_packing_limit", "random_packing", "random_gas",
           "clear_of_walls"]

# Lattice sites (and randomly placed disks) must be this much farther apart than the
# largest diameter (their sum of radii), so that rounding never reports an overlap.
_GAP = 1e-9

# The highest packing fraction random_packing accepts.  Random sequential addition of
# equal disks saturates at 0.547 (Hinrichsen, Feder and Jossang, J. Stat. Phys. 44, 793
# (1986)), and the attempts per disk diverge on the way (the free area vanishes as the
# cube of the distance to saturation): at 0.5 the last disks take some thousands.
_RSA_LIMIT = 0.5


def make_gas(
    n: int,
    packing_fraction: float,
    *,
    radius: float = 0.5,
    radii: ArrayLike | None = None,
    masses: ArrayLike = 1.0,
    aspect: float = 1.0,
    periodic: bool | tuple[bool, bool] = True,
    temperature: float = 1.0,
    seed: int | np.random.Generator | None = None,
    gravity: ArrayLike | None = None,
    restitution: ArrayLike = 1.0,
    wall_restitution: float = 1.0,
    tc: float | None = None,
    wall_temperatures: dict | None = None,
    thermostat: tuple[float, float] | None = None,
    walls: Wall | Iterable[Wall] | None = None,
    **physics: Any,
) -> Simulation:
    """A hard-disk gas at a given packing fraction, ready to run.

    The box is sized so that the disks cover ``packing_fraction`` of its area
    (``sum(pi r^2) / (width * height)``, polydisperse radii included).  Disks start on a
    triangular lattice stretched to fill the box (a lattice start melts quickly; random
    insertion stalls long before the densest fluid), with the lattice sites left over
    chosen at random as vacancies and, for mixtures, the species shuffled over the sites.
    Velocities are drawn from the Maxwell-Boltzmann distribution, the centre-of-mass
    velocity is removed (n >= 2) and the speeds rescaled so that the temperature is
    exactly ``temperature`` (k_B = 1; ``kT = sum m v^2 / f`` with ``f = 2n`` degrees of
    freedom less one for each periodic axis, along which momentum is conserved: the
    same count as :func:`edmd2d.measurements.degrees_of_freedom`).

    With ``walls``, the lattice disks that a wall segment crosses are left out (those
    closer to a segment than their radius, periodic images included), and the
    velocities are drawn for the disks that remain, with ``f = 2n`` (segments
    conserve no momentum).  ``n`` and ``packing_fraction`` then describe the lattice
    before the walls: the gas holds at most ``n`` disks, ``len(sim)`` says how many,
    and a ``UserWarning`` says how many were left out.  The box is the one made for
    ``n`` disks at ``packing_fraction`` (``width = sqrt(sum(pi r^2) / packing_fraction
    * aspect)``, ``height = width / aspect``); the walls must lie in it.

    Parameters
    ----------
    n : int
        Number of disks, >= 1.
    packing_fraction : float
        Area fraction in (0, limit), where the limit is that of the densest lattice
        start that fits the box (about 0.9 for equal disks in a periodic box; see
        :func:`lattice_packing_limit`).  Fluids of equal disks exist up to ~0.70.
    radius : float, default 0.5
        Radius of every disk when ``radii`` is not given.
    radii : float or array_like, shape (n,), optional
        Per-disk radii (for mixtures, e.g. ``np.where(np.arange(n) % 2, 0.5, 0.7)``).
    masses : float or array_like, shape (n,), default 1.0
        Finite masses, > 0.
    aspect : float, default 1.0
        Box width / height.
    periodic : bool or (bool, bool), default True
        As for :class:`~edmd2d.Box`.  Walled axes keep every disk inside its walls.
    temperature : float, default 1.0
        k_B T of the initial velocities, >= 0.
    seed : int, numpy.random.Generator or None
        Makes the vacancies, species order and velocities reproducible, and the random
        numbers of a thermostat or heated walls (the same generator goes on).
    gravity : array_like, shape (2,), optional
        A uniform acceleration of every disk (see :class:`~edmd2d.Simulation`).  The
        start is still uniform: the gas settles into its height profile as it runs.
    restitution, wall_restitution, tc, wall_temperatures, thermostat : optional
        The physics, as for :class:`~edmd2d.Simulation` (the default ``tc`` is taken
        from the initial velocities at ``temperature``).
    walls : Wall or sequence of Wall, optional
        Wall segments inside the box (a closed container: ``Wall.polygon(vertices)``;
        several: concatenate the lists).  The disks they cross are left out.
    **physics
        The keywords of physics families registered with
        :func:`edmd2d.physics.register`, as for :class:`~edmd2d.Simulation`.  With
        ``shear_rate`` (:class:`edmd2d.physics.Shear`) the velocities drawn are the
        peculiar ones, and the flow ``(shear_rate (y - height / 2), 0)`` is added to
        them: the gas starts in its linear velocity profile.

    Returns
    -------
    Simulation
        At time 0, with ``len(sim) <= n`` disks when ``walls`` crossed some.  Above
        the melting of hard disks (packing fraction about 0.70 to
        0.72) the lattice start does not melt: the system stays a crystal (hexatic
        and solid phases), however long it runs; below it, run a few tens of
        collisions per disk before measuring, so that the lattice start has melted.

    Warns
    -----
    UserWarning
        When ``walls`` crossed some lattice disks: how many were left out of ``n``,
        and the packing fraction of those that remain.

    Raises
    ------
    TypeError, ValueError
        For n < 1, a packing fraction outside (0, limit) (the message gives the limit),
        non-positive or infinite radii or masses, and the like; for ``walls`` that are
        not :class:`~edmd2d.Wall` segments, have an end point outside the box, or
        cross every disk.

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.make_gas(400, 0.3, seed=1)
    >>> len(sim), round(sim.box.width, 3)
    (400, 32.36)
    >>> round(float(sum(3.141592653589793 * sim.radii**2) / sim.box.area), 12)
    0.3
    >>> round(sim.kinetic_energy() / (2 * 400 - 2), 12)  # E / (2N - 2) = k T / 2
    0.5

    A wall across the middle of the same box (32.36 wide), and a triangular obstacle:

    >>> import warnings
    >>> walls = [ed.Wall((16.0, 0.0), (16.0, 20.0))]
    >>> walls += ed.Wall.polygon([(5.0, 25.0), (10.0, 25.0), (7.5, 29.0)])
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     sim = ed.make_gas(400, 0.3, seed=1, walls=walls)
    >>> len(sim) < 400, len(sim.walls)
    (True, 4)
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    make_gas: the wall segments crossed ... of the 400 lattice disks, left out: ...
    """
    n = as_count("n", n, minimum=1)
    phi = as_positive_float("packing_fraction", packing_fraction)
    aspect = as_positive_float("aspect", aspect)
    temperature = as_positive_float("temperature", temperature, allow_zero=True)
    rad = _disk_radii(n, radius, radii)
    mass = per_disk("masses", masses, n)
    if (mass <= 0).any():
        raise refusal(ValueError, "masses",
                      f"masses must be > 0; disks {indices_where(mass <= 0)} are not")
    segs = as_walls(walls)
    rng = as_generator("seed", seed)

    box = _box_for(float(np.pi * np.sum(rad**2)), phi, aspect, periodic)
    _check_walls_in(segs, box, "make_gas")
    dmax = 2.0 * float(rad.max())
    sites = _triangular_sites(n, box, dmax * (1.0 + _GAP))
    if sites is None:
        limit = lattice_packing_limit(n, radii=rad, aspect=aspect, periodic=periodic)
        raise refusal(ValueError, "packing_fraction",
                      f"packing_fraction {phi} cannot be reached from a lattice start for these "
                      f"{n} disks (largest diameter {dmax:g}, aspect {aspect:g}, periodic="
                      f"{box.periodic}): the limit is about {limit:.4f}")
    pick = np.sort(rng.choice(len(sites), size=n, replace=False))
    pos = sites[pick]
    if radii is not None:
        # (Each disk's mass goes with its radius: the species are shuffled together.)
        shuffle = rng.permutation(n)
        rad = rad[shuffle]
        mass = mass[shuffle]
    pos, rad, mass = _leave_out_crossed(pos, rad, mass, segs, box, "make_gas", "lattice")
    vel = _maxwell_boltzmann(rng, mass, temperature, 0 if segs else sum(box.periodic))
    vel = _with_shear_flow(vel, pos, box, physics.get("shear_rate"))
    return Simulation(pos, vel, rad, mass, box=box, gravity=gravity, restitution=restitution,
                      wall_restitution=wall_restitution, tc=tc,
                      wall_temperatures=wall_temperatures, thermostat=thermostat, seed=rng,
                      walls=segs, **physics)


def lattice_packing_limit(n: int, *, radius: float = 0.5, radii: ArrayLike | None = None,
                          aspect: float = 1.0, periodic: bool | tuple[bool, bool] = True) -> float:
    """The largest packing fraction :func:`make_gas` reaches for these disks (bisection).

    Parameters
    ----------
    n : int
        Number of disks, >= 1.
    radius : float, default 0.5
        Radius of every disk when ``radii`` is not given.
    radii : float or array_like, shape (n,), optional
        Per-disk radii.
    aspect : float, default 1.0
        Box width / height.
    periodic : bool or (bool, bool), default True
        As for :class:`~edmd2d.Box`.

    Returns
    -------
    float

    Examples
    --------
    A square periodic box takes a lattice of 1000 equal disks up to

    >>> round(lattice_packing_limit(1000), 3)
    0.873
    """
    n = as_count("n", n)
    rad = per_disk("radii", radii, n) if radii is not None else np.full(n, float(radius))
    box_kind = Box(1.0, 1.0, periodic=periodic).periodic
    disk_area = float(np.pi * np.sum(rad**2))
    dmax = 2.0 * float(rad.max())
    lo, hi = 1e-6, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        box = _box_for(disk_area, mid, aspect, box_kind)
        if _triangular_sites(n, box, dmax * (1.0 + _GAP)) is None:
            hi = mid
        else:
            lo = mid
    return lo


def random_packing(
    n: int,
    packing_fraction: float,
    *,
    radius: float = 0.5,
    radii: ArrayLike | None = None,
    aspect: float = 1.0,
    periodic: bool | tuple[bool, bool] = True,
    seed: int | np.random.Generator | None = None,
    max_attempts: int = 1_000_000,
) -> tuple[np.ndarray, np.ndarray, Box]:
    """Disks placed uniformly at random without overlap (random sequential addition).

    The box is sized as by :func:`make_gas` (``sum(pi r^2) / (width * height)`` equals
    ``packing_fraction``, ``width / height`` equals ``aspect``).  The disks are placed
    one after the other, largest first (a mixture's large disks would find no room
    among the small ones), each at a uniformly random position that overlaps no disk
    placed before; on walled axes every centre stays at least its radius from the
    walls.  Placed disks are kept apart by a relative margin of 1e-9 beyond contact,
    so that :class:`~edmd2d.Simulation` accepts them as they are.  A cell grid makes
    each attempt cost a few distance checks: 10^5 disks at packing fraction 0.5 take
    about a second.

    This is a disordered start below the density wanted, not a dense packing: random
    sequential addition saturates at 0.547 for equal disks (Hinrichsen, Feder and
    Jossang, J. Stat. Phys. 44, 793 (1986)), and the number of attempts per disk
    diverges on the way, so packing fractions above 0.5 are refused.  Denser
    configurations are made by compressing such a start (growing the disks in a
    simulation) or from a lattice (:func:`make_gas`).  Unlike a fluid in equilibrium,
    the configuration has the correlations of random sequential addition (its
    ``g(r)`` at contact is lower than the fluid's): run a simulation before measuring.

    Parameters
    ----------
    n : int
        Number of disks, >= 1.
    packing_fraction : float
        Area fraction in (0, 0.5].
    radius : float, default 0.5
        Radius of every disk when ``radii`` is not given.
    radii : float or array_like, shape (n,), optional
        Per-disk radii (> 0), kept in the order given.
    aspect : float, default 1.0
        Box width / height.
    periodic : bool or (bool, bool), default True
        As for :class:`~edmd2d.Box`.
    seed : int, numpy.random.Generator or None
        Makes the placement reproducible.
    max_attempts : int, default 1_000_000
        Consecutive failed attempts for one disk after which the placement gives up
        (with a ``ValueError``), >= 1.

    Returns
    -------
    positions : ndarray, shape (n, 2)
        Centres inside the box (periodic axes: in ``[0, L)``).
    radii : ndarray, shape (n,)
        The radii, in the order given (disk ``i`` has ``radii[i]``).
    box : Box

    Raises
    ------
    TypeError, ValueError
        For n < 1, a packing fraction outside (0, 0.5], non-positive radii, a box too
        narrow for the largest disk (an extreme ``aspect``), or a disk that found no
        room in ``max_attempts`` attempts (the message says how far the placement got).

    Examples
    --------
    >>> import numpy as np, edmd2d as ed
    >>> pos, rad, box = ed.random_packing(1000, 0.4, seed=1)
    >>> round(float(np.pi * np.sum(rad**2) / box.area), 12)
    0.4
    >>> sim = ed.Simulation(pos, np.zeros_like(pos), rad, box=box)  # no overlap
    >>> big_small = np.where(np.arange(500) % 2, 0.5, 0.7)
    >>> pos, rad, box = ed.random_packing(500, 0.45, radii=big_small, periodic=False, seed=2)
    >>> bool(np.array_equal(rad, big_small)), bool(np.all(pos - rad[:, None] > 0))
    (True, True)
    """
    n = as_count("n", n, minimum=1)
    phi = as_positive_float("packing_fraction", packing_fraction)
    if phi > _RSA_LIMIT:
        raise refusal(ValueError, "packing_fraction",
                      f"packing_fraction {phi} is too high for random sequential addition, which "
                      f"saturates near 0.547 for equal disks (Hinrichsen, Feder and Jossang 1986) "
                      f"and slows down without bound on the way: at most {_RSA_LIMIT}.  Place the "
                      "disks at a lower packing fraction and compress them (grow the disks in a "
                      "simulation), or start from a lattice with make_gas")
    aspect = as_positive_float("aspect", aspect)
    max_attempts = as_count("max_attempts", max_attempts, minimum=1)
    rad = _disk_radii(n, radius, radii)
    rng = as_generator("seed", seed)
    box = _box_for(float(np.pi * np.sum(rad**2)), phi, aspect, periodic)

    rmax = float(rad.max())
    reach = 2.0 * rmax * (1.0 + _GAP)
    for axis, length in enumerate((box.width, box.height)):
        if length <= reach:
            raise refusal(ValueError, "aspect",
                          f"the box ({box.width:.6g} x {box.height:.6g} for aspect {aspect:g}) is "
                          f"too narrow along {'xy'[axis]} for the largest disk (diameter "
                          f"{2 * rmax:g}): make the aspect closer to 1 or use more disks")
    order = np.argsort(-rad, kind="stable")
    r_sorted = np.ascontiguousarray(rad[order])
    lo = np.zeros((n, 2))
    span = np.empty((n, 2))
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            span[:, axis] = length
        else:
            lo[:, axis] = r_sorted * (1.0 + _GAP)
            span[:, axis] = length - 2.0 * lo[:, axis]
    pos = _place(rng, r_sorted, lo, span, box, reach, max_attempts, phi)
    out = np.empty((n, 2))
    out[order] = pos
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            col = out[:, axis]
            col[col >= length] = 0.0  # lo + u * L can round up to L
    return out, rad, box


def random_gas(
    n: int,
    packing_fraction: float,
    *,
    radius: float = 0.5,
    radii: ArrayLike | None = None,
    masses: ArrayLike = 1.0,
    aspect: float = 1.0,
    periodic: bool | tuple[bool, bool] = True,
    temperature: float = 1.0,
    seed: int | np.random.Generator | None = None,
    walls: Wall | Iterable[Wall] | None = None,
) -> Simulation:
    """A hard-disk gas from a disordered start: :func:`random_packing` positions and
    Maxwell-Boltzmann velocities (as :func:`make_gas` draws them).

    The start for a compression (:func:`edmd2d.compress`): unlike a lattice, it has no
    order to lose, and mixtures come out well mixed.  With ``walls``, the disks a
    segment crosses are left out, as by :func:`make_gas` (``n`` is then an upper
    bound, and a ``UserWarning`` says how many were left out).

    Parameters
    ----------
    n : int
        Number of disks, >= 1.
    packing_fraction : float
        Area fraction in (0, 0.5] (see :func:`random_packing`).
    radius, radii, aspect, periodic
        As for :func:`random_packing`.
    masses : float or array_like, shape (n,), default 1.0
        Finite masses, > 0.
    temperature : float, default 1.0
        ``kT`` of the velocities, exactly (centre-of-mass motion removed), >= 0.
    seed : int, numpy.random.Generator or None
        Makes positions and velocities reproducible.
    walls : Wall or sequence of Wall, optional
        Wall segments inside the box, as for :func:`make_gas`.

    Returns
    -------
    Simulation
        At time 0, with ``len(sim) <= n`` disks when ``walls`` crossed some.

    Warns
    -----
    UserWarning
        When ``walls`` crossed some disks, as :func:`make_gas`.

    Raises
    ------
    TypeError, ValueError
        As :func:`random_packing`, and for non-positive or infinite masses, a
        negative temperature, or ``walls`` as for :func:`make_gas`.

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.random_gas(500, 0.3, seed=4)
    >>> round(ed.kinetic_temperature(sim), 12)
    1.0
    """
    temperature = as_positive_float("temperature", temperature, allow_zero=True)
    segs = as_walls(walls)
    rng = as_generator("seed", seed)
    pos, rad, box = random_packing(n, packing_fraction, radius=radius, radii=radii,
                                   aspect=aspect, periodic=periodic, seed=rng)
    mass = per_disk("masses", masses, len(pos))
    if (mass <= 0).any():
        raise refusal(ValueError, "masses",
                      f"masses must be > 0; disks {indices_where(mass <= 0)} are not")
    _check_walls_in(segs, box, "random_gas")
    pos, rad, mass = _leave_out_crossed(pos, rad, mass, segs, box, "random_gas", "placed")
    vel = _maxwell_boltzmann(rng, mass, temperature, 0 if segs else sum(box.periodic))
    return Simulation(pos, vel, rad, mass, box=box, walls=segs)


def clear_of_walls(positions: np.ndarray, radii: np.ndarray, walls: Iterable[Wall],
                   box: Box) -> np.ndarray:
    """Which disks no wall segment crosses: the rule by which :func:`make_gas`,
    :func:`random_gas` and the command line leave disks out.

    A segment crosses a disk when the distance from the disk's centre to it (the
    nearest of the centre's periodic images, as the engine sees the segment) is at
    most the radius times ``1 + 1e-9`` (a disk just touching a wall is left out too,
    so that rounding never reports an overlap).

    Parameters
    ----------
    positions : ndarray, shape (n, 2)
        Centres, inside the box.
    radii : ndarray, shape (n,)
        Radii, > 0.
    walls : sequence of Wall
        The segments.
    box : Box
        The box, whose periodic axes the distances respect.

    Returns
    -------
    ndarray of bool, shape (n,)
        ``True`` for the disks to keep.
    """
    keep = np.ones(len(positions), dtype=bool)
    for w in walls:
        dist = _segment_distance(positions, np.asarray(w.start), np.asarray(w.end), box)
        keep &= dist > radii * (1.0 + _GAP)
    return keep


def _check_walls_in(segs, box: Box, caller: str) -> None:
    """Refuse segments with an end point outside the box made for the gas."""
    for k, w in enumerate(segs):
        for pt in (w.start, w.end):
            if not (0.0 <= pt[0] <= box.width and 0.0 <= pt[1] <= box.height):
                raise refusal(ValueError, "walls",
                              f"walls[{k}] has an end point {tuple(pt)} outside the box [0, "
                              f"{box.width:.6g}] x [0, {box.height:.6g}] that {caller} made for "
                              "these disks at this packing fraction: place the walls inside it")


def _leave_out_crossed(pos, rad, mass, segs, box: Box, caller: str, what: str):
    """The disks no segment crosses (all without segments), with a warning naming how
    many were left out."""
    if not segs:
        return pos, rad, mass
    keep = clear_of_walls(pos, rad, segs, box)
    kept = int(keep.sum())
    if kept == 0:
        raise refusal(ValueError, "walls",
                      f"walls: the wall segments cross every one of the {len(pos)} "
                      f"{what} disks; {caller} has no disk left to start from")
    if kept < len(pos):
        phi = float(np.pi * np.sum(rad[keep] ** 2)) / box.area
        warnings.warn(
            f"{caller}: the wall segments crossed {len(pos) - kept} of the {len(pos)} "
            f"{what} disks, left out: {kept} disks remain, at packing fraction "
            f"{phi:.4g} of the box", UserWarning, stacklevel=3)
    return pos[keep], rad[keep], mass[keep]


def _place(rng, rad, lo, span, box: Box, reach, max_attempts, phi):
    """Random sequential addition of ``rad`` (sorted, largest first) into ``box``."""
    n = len(rad)
    ncx = max(1, int(box.width // reach))
    ncy = max(1, int(box.height // reach))
    head = np.full(ncx * ncy, -1, dtype=np.int64)
    nxt = np.full(n, -1, dtype=np.int64)
    pos = np.zeros((n, 2))
    k, fails = 0, 0
    while True:
        # Fresh random numbers for a few attempts per disk still to place; a stalled
        # placement at most uses up max_attempts of them.
        u = rng.random((min(max(4096, 8 * (n - k)), max_attempts + 1), 2))
        k, _, fails, status = _placement.place_disks(
            pos, rad, lo, span, k, fails, u, box.width, box.height, box.periodic[0],
            box.periodic[1], 1.0 + _GAP, head, nxt, ncx, ncy, max_attempts)
        if status == _placement.DONE:
            return pos
        if status == _placement.STALLED:
            placed = float(np.pi * np.sum(rad[:k] ** 2)) / box.area
            raise refusal(ValueError, "packing_fraction",
                          f"random sequential addition stalled: disk {k + 1} of {n} (radius "
                          f"{rad[k]:g}, placed largest first) found no room in {max_attempts} "
                          f"attempts at packing fraction {placed:.4f} of the {phi} asked; lower "
                          "packing_fraction and compress, or raise max_attempts")


def _disk_radii(n: int, radius, radii) -> np.ndarray:
    """The radii of ``n`` disks: ``radius`` for all, or ``radii`` per disk (> 0)."""
    if radii is None:
        return per_disk("radius", as_positive_float("radius", radius), n)
    rad = per_disk("radii", radii, n)
    if (rad <= 0).any():
        raise refusal(ValueError, "radii",
                      f"radii must be > 0; disks {indices_where(rad <= 0)} are not")
    return rad


def _box_for(disk_area: float, phi: float, aspect: float, periodic) -> Box:
    """The box of ``width / height = aspect`` in which disks of total area
    ``disk_area`` cover the fraction ``phi``."""
    area = disk_area / phi
    return Box(math.sqrt(area * aspect), math.sqrt(area / aspect), periodic=periodic)


def _triangular_sites(n: int, box: Box, spacing_min: float):
    """At least ``n`` sites of a (stretched) triangular lattice filling ``box``, all at
    least ``spacing_min`` apart (periodic images included) and, on walled axes, at least
    ``spacing_min / 2`` from the walls; ``None`` if no lattice does.

    ``ny`` rows run along x, ``nx`` sites each, odd rows shifted by half a spacing.  The
    closest sites are in-row neighbours (``ax``), neighbours in adjacent rows
    (``hypot(ax/2, ay)``) and sites two rows apart (``2 ay``), or a site's own image on
    a periodic axis with a single row or column.  On a periodic y axis ``ny`` is even (or
    1) so that the shift pattern closes on itself.  Every ``ny`` is tried and the most
    open lattice kept.
    """
    px, py = box.periodic
    half = 0.5 * spacing_min
    free_x = box.width if px else box.width - spacing_min
    free_y = box.height if py else box.height - spacing_min
    if free_x < 0 or free_y < 0:
        return None
    ny = np.arange(1, n + 1)
    if py:
        ny = ny[(ny % 2 == 0) | (ny == 1)]
    nx = -(-n // ny)  # ceil(n / ny)
    inf = np.inf
    with np.errstate(divide="ignore", invalid="ignore"):
        if px:
            ax = box.width / nx
            in_row = ax  # with nx == 1 this is the site's own image
        else:
            # Walled: the shifted rows span (nx - 1/2) spacings, a single row nx - 1.
            ax = np.where(ny > 1, free_x / (nx - 0.5), free_x / np.maximum(nx - 1, 1))
            in_row = np.where(nx > 1, ax, inf)
        if py:
            ay = box.height / ny
            stacked = np.where(ny > 1, 2 * ay, box.height)
        else:
            ay = np.where(ny > 1, free_y / (ny - 1), inf)
            stacked = np.where(ny > 2, 2 * ay, inf)
        diag = np.where(ny > 1, np.hypot(0.5 * ax, ay), inf)
    dist = np.minimum(np.minimum(in_row, diag), stacked)
    ok = dist >= spacing_min
    if not ok.any():
        return None
    k = int(np.argmax(np.where(ok, dist, -1.0)))
    rows, cols, sx, sy = int(ny[k]), int(nx[k]), float(ax[k]), float(ay[k])
    grid_i, grid_j = np.meshgrid(np.arange(cols), np.arange(rows), indexing="xy")
    i = grid_i.ravel().astype(float)
    j = grid_j.ravel()
    shift = 0.5 * (j % 2) if rows > 1 else 0.0
    if px:
        x = ((i + shift + 0.25) * sx) % box.width
    elif rows == 1 and cols == 1:
        x = np.full(len(i), 0.5 * box.width)
    else:
        x = half + (i + shift) * sx
    if py:
        y = ((j + 0.5) * sy) % box.height
    elif rows == 1:
        y = np.full(len(j), 0.5 * box.height)
    else:
        y = half + j * sy
    return np.column_stack([x, y])


def _with_shear_flow(velocities: np.ndarray, positions: np.ndarray, box: Box,
                    rate) -> np.ndarray:
    """``velocities`` taken as peculiar ones, with the flow of a box sheared at ``rate``
    added, ``(rate (y - height / 2), 0)`` (see :class:`edmd2d.physics.Shear`); as they
    are for a ``rate`` that is ``None``, zero or not a finite number (which the
    simulation then refuses, naming it)."""
    if (not isinstance(rate, numbers.Real) or isinstance(rate, (bool, np.bool_))
            or not math.isfinite(rate) or rate == 0):
        return velocities
    out = np.array(velocities, np.float64)
    out[:, 0] += float(rate) * (positions[:, 1] - 0.5 * box.height)
    return out


def _maxwell_boltzmann(rng, mass, temperature, conserved_axes):
    """Gaussian velocities with zero total momentum (n >= 2), scaled to ``temperature``
    with ``2n - conserved_axes`` degrees of freedom."""
    n = len(mass)
    vel = rng.normal(size=(n, 2)) * np.sqrt(1.0 / mass)[:, None]
    dof = 2 * n
    if n >= 2:
        vel -= weighted_sum(mass, vel) / mass.sum()
        dof = 2 * n - conserved_axes
    twice_ke = float(np.sum(mass[:, None] * vel**2))
    if twice_ke > 0 and dof > 0:
        vel *= math.sqrt(temperature * dof / twice_ke)
    else:
        vel[:] = 0.0
    return vel
