"""One-line construction of gas-like systems: :func:`make_gas`."""

from __future__ import annotations

import math

import numpy as np

from ._validate import as_count, as_positive_float, indices_where, per_disk
from .geometry import Box
from .simulation import Simulation

__all__ = ["make_gas", "lattice_packing_limit"]

# Lattice sites must be this much farther apart than the largest diameter, so that
# rounding never reports an overlap.
_GAP = 1e-9


def make_gas(
    n: int,
    packing_fraction: float,
    *,
    radius: float = 0.5,
    radii=None,
    masses=1.0,
    aspect: float = 1.0,
    periodic=True,
    temperature: float = 1.0,
    seed=None,
    gravity=None,
    restitution=1.0,
    wall_restitution=1.0,
    tc=None,
    wall_temperatures=None,
    thermostat=None,
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

    Returns
    -------
    Simulation
        At time 0.  Above the melting of hard disks (packing fraction about 0.70 to
        0.72) the lattice start does not melt: the system stays a crystal (hexatic
        and solid phases), however long it runs; below it, run a few tens of
        collisions per disk before measuring, so that the lattice start has melted.

    Raises
    ------
    TypeError, ValueError
        For n < 1, a packing fraction outside (0, limit) (the message gives the limit),
        non-positive or infinite radii or masses, and the like.

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
    """
    n = as_count("n", n, minimum=1)
    phi = as_positive_float("packing_fraction", packing_fraction)
    aspect = as_positive_float("aspect", aspect)
    temperature = as_positive_float("temperature", temperature, allow_zero=True)
    if radii is None:
        rad = per_disk("radius", as_positive_float("radius", radius), n)
    else:
        rad = per_disk("radii", radii, n)
        if (rad <= 0).any():
            raise ValueError(f"radii must be > 0; disks {indices_where(rad <= 0)} are not")
    mass = per_disk("masses", masses, n)
    if (mass <= 0).any():
        raise ValueError(f"masses must be > 0; disks {indices_where(mass <= 0)} are not")
    rng = np.random.default_rng(seed)

    area = float(np.pi * np.sum(rad**2)) / phi
    width = math.sqrt(area * aspect)
    height = math.sqrt(area / aspect)
    box = Box(width, height, periodic=periodic)
    dmax = 2.0 * float(rad.max())
    sites = _triangular_sites(n, box, dmax * (1.0 + _GAP))
    if sites is None:
        limit = lattice_packing_limit(n, radii=rad, aspect=aspect, periodic=periodic)
        raise ValueError(
            f"packing_fraction {phi} cannot be reached from a lattice start for these "
            f"{n} disks (largest diameter {dmax:g}, aspect {aspect:g}, periodic="
            f"{box.periodic}): the limit is about {limit:.4f}"
        )
    pick = np.sort(rng.choice(len(sites), size=n, replace=False))
    pos = sites[pick]
    rad = rad[rng.permutation(n)] if radii is not None else rad
    vel = _maxwell_boltzmann(rng, mass, temperature, sum(box.periodic))
    return Simulation(pos, vel, rad, mass, box=box, gravity=gravity, restitution=restitution,
                      wall_restitution=wall_restitution, tc=tc,
                      wall_temperatures=wall_temperatures, thermostat=thermostat, seed=rng)


def lattice_packing_limit(n: int, *, radius=0.5, radii=None, aspect=1.0, periodic=True) -> float:
    """The largest packing fraction :func:`make_gas` reaches for these disks (bisection).

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
        area = disk_area / mid
        box = Box(math.sqrt(area * aspect), math.sqrt(area / aspect), periodic=box_kind)
        if _triangular_sites(n, box, dmax * (1.0 + _GAP)) is None:
            hi = mid
        else:
            lo = mid
    return lo


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
    i, j = np.meshgrid(np.arange(cols), np.arange(rows), indexing="xy")
    i = i.ravel().astype(float)
    j = j.ravel()
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


def _maxwell_boltzmann(rng, mass, temperature, conserved_axes):
    """Gaussian velocities with zero total momentum (n >= 2), scaled to ``temperature``
    with ``2n - conserved_axes`` degrees of freedom."""
    n = len(mass)
    vel = rng.normal(size=(n, 2)) * np.sqrt(1.0 / mass)[:, None]
    dof = 2 * n
    if n >= 2:
        vel -= (mass @ vel) / mass.sum()
        dof = 2 * n - conserved_axes
    twice_ke = float(np.sum(mass[:, None] * vel**2))
    if twice_ke > 0 and dof > 0:
        vel *= math.sqrt(temperature * dof / twice_ke)
    else:
        vel[:] = 0.0
    return vel
