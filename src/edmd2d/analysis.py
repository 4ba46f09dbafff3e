"""Structure and dynamics of configurations: g(r), speed statistics, MSD, hexatic order.

The functions take either a :class:`~edmd2d.Simulation` (its current state) or plain
arrays with a :class:`~edmd2d.Box`, so that stored snapshots can be analysed too.
Distances respect the box: minimum image on periodic axes, none across walls.
scipy (spatial, stats) is imported where it is used, so that ``import edmd2d`` stays
quick.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import _operations
from ._gaps import _boxsize, _min_image
from ._sums import dot
from ._validate import as_count, as_float_array, as_positive_float
from .geometry import Box
from .measurements import kinetic_temperature, rotational_temperature
from .simulation import Simulation

__all__ = [
    "radial_distribution",
    "speed_distribution",
    "maxwell_boltzmann_test",
    "angular_velocity_distribution",
    "trajectory",
    "mean_squared_displacement",
    "hexatic_order",
    "voronoi_cell_areas",
    "local_packing_fractions",
]


# --------------------------------------------------------------------------- inputs
def _positions_and_box(source, box, name="positions"):
    """``(frames (F, N, 2), box, radii or None)`` from a Simulation or arrays + Box."""
    if isinstance(source, Simulation):
        if box is not None:
            raise TypeError("box must not be given with a Simulation (it has its own box)")
        return source.positions[None], source.box, source.radii
    if box is None:
        raise TypeError(f"box is required with an array of {name}: pass box=edmd2d.Box(...)")
    if not isinstance(box, Box):
        raise TypeError(f"box must be an edmd2d.Box, got {type(box).__name__}")
    arr = np.asarray(source)
    if arr.ndim == 3:
        frames = as_float_array(name, source, (None, None, 2))
    else:
        frames = as_float_array(name, source, (None, 2))[None]
    if frames.shape[1] < 2:
        raise ValueError(f"{name} must hold at least 2 disks, got {frames.shape[1]}")
    return frames, box, None


def _wrap(pos: np.ndarray, box: Box) -> np.ndarray:
    """Positions wrapped into ``[0, L)`` on periodic axes; on walled axes they must lie
    inside the box."""
    out = pos.copy()
    for axis, length in enumerate((box.width, box.height)):
        if box.periodic[axis]:
            col = np.mod(out[:, axis], length)
            col[col >= length] = 0.0  # mod can round up to L
            out[:, axis] = col
        elif ((out[:, axis] < 0) | (out[:, axis] > length)).any():
            raise ValueError(
                f"positions lie outside the walled {'xy'[axis]} axis [0, {length}] of the box"
            )
    return out


# --------------------------------------------------------------------------- g(r)
def radial_distribution(source: Simulation | ArrayLike, box: Box | None = None, *,
                        r_max: float | None = None, bins: int = 100,
                        margin: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The radial distribution function g(r), averaged over disks (and frames).

    ``g(r)`` is the number of pairs at distance ``r`` relative to that of ideal (uniform,
    independent) points in the same box, so that an ideal gas gives ``g = 1`` exactly
    in expectation, also at finite N:

    ``g(r_k) = H_k / E_k``, where ``H_k`` counts the pairs with distance in bin ``k``
    (minimum image on periodic axes) and ``E_k = F N (N - 1) / 2 * I_k / A_c^2`` is its
    ideal value for ``F`` frames.  ``I_k`` integrates ``2 pi r gbar(r)`` over the bin,
    with ``gbar(r)`` the isotropic set covariance of the region ``A_c = X Y`` open to
    the disk centres: in a periodic box ``gbar = X Y`` (``I_k = pi X Y (r_2^2 - r_1^2)``);
    a walled axis has fewer pairs at large ``r`` and ``gbar(r) = X Y - (2r / pi)
    (Y w_x + X w_y) + (r^2 / pi) w_x w_y`` (``w_x = 1`` when x is walled), the exact
    mean over directions of the area shared by the region and its shifted copy.  On a
    walled axis the centres' region is the box less ``margin`` at each wall.

    Parameters
    ----------
    source : Simulation or array_like, shape (N, 2) or (F, N, 2)
        A simulation (its current positions) or positions, one frame or ``F`` frames of
        the same ``N`` disks.
    box : Box
        Required with arrays; not allowed with a Simulation.
    r_max : float, optional
        Largest distance, > 0; at most half the shortest periodic side and at most the
        shortest walled extent of the centres' region.  Default: five mean spacings
        ``5 sqrt(A_c / N)`` (about 6 diameters at packing fraction 0.5; the first
        few peaks of a dense fluid), or less where the limits above require.
        Memory stays linear in N for any ``r_max``: pairs are counted, not listed.
    bins : int, default 100
        Number of equal bins in ``[0, r_max]``.
    margin : float, optional
        Distance from a wall that disk centres cannot enter (used on walled axes only).
        Default: the smallest radius for a Simulation (exact for equal disks), 0 for
        arrays.

    Returns
    -------
    r : ndarray, shape (bins,)
        Bin centres.
    g : ndarray, shape (bins,)

    Raises
    ------
    TypeError, ValueError
        For bad arguments or an ``r_max`` beyond the limits above.

    Examples
    --------
    Uniform random points (an ideal gas) give ``g(r) ~ 1``:

    >>> import numpy as np, edmd2d as ed
    >>> rng = np.random.default_rng(0)
    >>> box = ed.Box(50.0, 50.0)
    >>> r, g = radial_distribution(rng.uniform(0, 50, (20, 2000, 2)), box, r_max=10, bins=20)
    >>> bool(np.all(np.abs(g[2:] - 1) < 0.05))
    True
    """
    frames, box, radii = _positions_and_box(source, box)
    bins = as_count("bins", bins, minimum=1)
    if margin is None:
        margin = float(radii.min()) if radii is not None else 0.0
    else:
        margin = as_positive_float("margin", margin, allow_zero=True)
    ext = []
    for axis, length in enumerate((box.width, box.height)):
        span = length if box.periodic[axis] else length - 2.0 * margin
        if span <= 0:
            raise ValueError(f"margin {margin} leaves no room on the walled {'xy'[axis]} axis")
        ext.append(span)
    cx, cy = ext
    wx, wy = (0.0 if p else 1.0 for p in box.periodic)
    limits = [length / 2 if p else span
              for length, span, p in zip((box.width, box.height), ext, box.periodic)]
    r_limit = min(limits)
    if r_max is None:
        r_max = min(5.0 * math.sqrt(cx * cy / frames.shape[1]), r_limit)
    else:
        r_max = as_positive_float("r_max", r_max)
        if r_max > r_limit * (1 + 1e-12):
            raise ValueError(
                f"r_max={r_max} is too large for this box: at most {r_limit:.6g} (half a "
                "periodic side, or the walled extent open to the disk centres)"
            )
    from scipy import spatial

    edges = np.linspace(0.0, r_max, bins + 1)
    hist = np.zeros(bins)
    n_frames, n = frames.shape[0], frames.shape[1]
    bsize = _boxsize(box, r_max)
    for frame in frames:
        pos = _wrap(frame, box)
        tree = spatial.cKDTree(pos, boxsize=bsize)
        # Ordered pairs (each pair twice, and every disk with itself) closer than each
        # upper edge (strictly, as the bins are [r_k, r_k+1)), minimum image on periodic
        # axes: the bins' counts without a list of the pairs, which grows as N r_max^2.
        within = tree.count_neighbors(tree, np.nextafter(edges[1:], -np.inf))
        hist += np.diff(0.5 * (within - n), prepend=0.0)

    def shell(r):  # integral of 2 pi r gbar(r) dr from 0 to r
        return (np.pi * cx * cy * r**2 - (4.0 / 3.0) * r**3 * (cy * wx + cx * wy)
                + 0.5 * r**4 * wx * wy)

    ideal = n_frames * n * (n - 1) / 2 * np.diff(shell(edges)) / (cx * cy) ** 2
    return 0.5 * (edges[1:] + edges[:-1]), hist / ideal


# --------------------------------------------------------------------------- speeds
def _velocities_and_masses(source, masses):
    if isinstance(source, Simulation):
        if masses is not None:
            raise TypeError("masses must not be given with a Simulation (it has its own)")
        mass = source.masses
        movable = np.isfinite(mass)
        return source.velocities[movable], mass[movable]
    vel = as_float_array("velocities", source, (None, 2))
    if len(vel) == 0:
        raise ValueError("velocities must hold at least one disk, got shape (0, 2)")
    mass = np.full(len(vel), 1.0) if masses is None else masses
    if np.ndim(mass) == 0:
        mass = np.full(len(vel), float(as_positive_float("masses", mass)))
    else:
        mass = as_float_array("masses", mass, (len(vel),))
        if (mass <= 0).any():
            raise ValueError("masses must be > 0")
    return vel, mass


def speed_distribution(source: Simulation | ArrayLike, *, bins: int = 50,
                       v_max: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Histogram of the speeds ``|v|`` as a probability density.

    Compare with :func:`edmd2d.theory.maxwell_boltzmann_speed_pdf`, the 2D
    Maxwell-Boltzmann density ``f(v) = (m v / kT) exp(-m v^2 / (2 kT))``.

    Parameters
    ----------
    source : Simulation or array_like, shape (N, 2)
        A simulation (its movable disks) or velocities.
    bins : int, default 50
    v_max : float, optional
        Upper end of the histogram; default the largest speed.

    Returns
    -------
    v : ndarray, shape (bins,)
        Bin centres.
    density : ndarray, shape (bins,)
        Normalized so that ``sum(density * bin_width) == 1`` over ``[0, v_max]``.

    Examples
    --------
    >>> import numpy as np
    >>> v, f = speed_distribution(np.array([[1.0, 0.0], [0.0, 2.0]]), bins=2, v_max=2.0)
    >>> v.tolist(), f.tolist()
    ([0.5, 1.5], [0.0, 1.0])
    """
    vel, _ = _velocities_and_masses(source, None)
    bins = as_count("bins", bins, minimum=1)
    speed = np.hypot(vel[:, 0], vel[:, 1])
    if v_max is None:
        v_max = float(speed.max()) if speed.max() > 0 else 1.0
    else:
        v_max = as_positive_float("v_max", v_max)
    density, edges = np.histogram(speed, bins=bins, range=(0.0, v_max), density=True)
    return 0.5 * (edges[1:] + edges[:-1]), density


def maxwell_boltzmann_test(source: Simulation | ArrayLike, *, masses: ArrayLike | None = None,
                           temperature: float | None = None) -> Any:
    """Kolmogorov-Smirnov test of the velocities against 2D Maxwell-Boltzmann.

    In 2D the kinetic energy ``e = m v^2 / 2`` of a disk in equilibrium is exponentially
    distributed with mean ``kT`` (the 2D speed density ``(m v / kT) exp(-m v^2 / 2kT)``
    is exactly that after ``e = m v^2 / 2``), whatever the masses, so ``e / kT`` is
    tested against the unit exponential distribution.  A small p-value rejects
    Maxwell-Boltzmann.

    When ``temperature`` is not given it is estimated as the mean of ``e`` (for a
    Simulation: :func:`~edmd2d.measurements.kinetic_temperature`); estimating it from the
    same data makes the test slightly conservative (p-values biased upward).  A
    closed system also fixes the total energy, a ``1/N`` effect.

    Parameters
    ----------
    source : Simulation or array_like, shape (N, 2)
    masses : float or array_like, shape (N,), optional
        With arrays only; default 1.
    temperature : float, optional
        ``kT`` to test against, > 0.

    Returns
    -------
    scipy.stats KstestResult
        With ``statistic`` and ``pvalue``.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(1)
    >>> bool(maxwell_boltzmann_test(rng.normal(size=(5000, 2)), temperature=1.0).pvalue > 0.01)
    True
    >>> angle = rng.uniform(0, 2 * np.pi, 5000)        # all speeds equal: not MB
    >>> equal = np.column_stack([np.cos(angle), np.sin(angle)])
    >>> bool(maxwell_boltzmann_test(equal).pvalue < 1e-10)
    True
    """
    vel, mass = _velocities_and_masses(source, masses)
    energy = 0.5 * mass * np.einsum("ij,ij->i", vel, vel)
    if temperature is None:
        if isinstance(source, Simulation):
            kt = kinetic_temperature(source)
        else:
            kt = float(energy.mean())
    else:
        kt = as_positive_float("temperature", temperature)
    if not kt > 0:
        raise ValueError(f"the temperature must be > 0 for the test, got {kt}")
    from scipy import stats

    return stats.kstest(energy / kt, "expon")


def angular_velocity_distribution(sim: Simulation, *, bins: int = 50,
                                  w_max: float | None = None, scaled: bool = True
                                  ) -> tuple[np.ndarray, np.ndarray]:
    """Histogram of the angular velocities of rough disks as a probability density.

    With ``scaled`` (the default) each disk's angular velocity is measured in its own
    thermal unit, ``w sqrt(I / kT_rot)`` with ``I`` its moment of inertia and
    ``kT_rot`` the :func:`~edmd2d.measurements.rotational_temperature`: in equilibrium
    the result is the standard normal density whatever the masses, radii and
    ``inertia``; a cooling rough gas departs from it (its fourth moment differs from
    3).

    Parameters
    ----------
    sim : Simulation
        With rough disks (:class:`edmd2d.physics.Rough`); its movable disks count.
    bins : int, default 50
    w_max : float, optional
        The histogram spans ``[-w_max, w_max]``; default the largest ``|w|`` (scaled
        or not).
    scaled : bool, default True
        Scale by ``sqrt(I / kT_rot)``, or give the angular velocities as they are.

    Returns
    -------
    w : ndarray, shape (bins,)
        Bin centres.
    density : ndarray, shape (bins,)
        Normalized so that ``sum(density * bin_width) == 1`` over ``[-w_max, w_max]``.

    Raises
    ------
    ValueError
        For smooth disks, or no movable disk.

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.make_gas(4, 0.2, seed=0, tangential_restitution=1.0,
    ...                   angular_velocities=[1.0, -1.0, 1.0, 3.0])
    >>> w, f = angular_velocity_distribution(sim, bins=2, w_max=4.0, scaled=False)
    >>> w.tolist(), f.tolist()
    ([-2.0, 2.0], [0.0625, 0.1875])
    """
    kt_rot = rotational_temperature(sim)  # (refuses smooth disks)
    movable = np.isfinite(sim.masses)
    if not movable.any():
        raise ValueError("the simulation has no movable disk")
    bins = as_count("bins", bins, minimum=1)
    w = sim.angular_velocities[movable]
    if scaled:
        inertia = (sim.families["rough"].inertia * sim.masses * sim.radii ** 2)[movable]
        w = w * np.sqrt(inertia / kt_rot) if kt_rot > 0 else np.zeros_like(w)
    if w_max is None:
        top = float(np.abs(w).max())
        w_max = top if top > 0 else 1.0
    else:
        w_max = as_positive_float("w_max", w_max)
    density, edges = np.histogram(w, bins=bins, range=(-w_max, w_max), density=True)
    return 0.5 * (edges[1:] + edges[:-1]), density


# --------------------------------------------------------------------------- MSD
def trajectory(sim: Simulation, interval: float, frames: int) -> tuple[np.ndarray, np.ndarray]:
    """Advance ``sim`` and record its unwrapped positions at equal time steps.

    One run with a :class:`~edmd2d.operations.RecordTrajectory` at the frame times;
    to record while measuring or writing files, pass that operation to
    :meth:`~edmd2d.Simulation.run` with the others.

    Parameters
    ----------
    sim : Simulation
        Advanced in place by ``interval * (frames - 1)``.
    interval : float
        Time between frames, > 0.
    frames : int
        Number of frames, >= 1 (the first is the current state).

    Returns
    -------
    times : ndarray, shape (frames,)
    positions : ndarray, shape (frames, N, 2)
        Unwrapped positions (:attr:`~edmd2d.Simulation.unwrapped_positions`): periodic
        wraps undone, so that differences are true displacements.
    """
    if not isinstance(sim, Simulation):
        raise TypeError(f"trajectory() needs an edmd2d.Simulation, got {type(sim).__name__}")
    interval = as_positive_float("interval", interval)
    frames = as_count("frames", frames, minimum=1)
    times = sim.time + interval * np.arange(frames)
    record = _operations.RecordTrajectory(_operations.At(times[1:]), include_start=True)
    _operations.run(sim, until=float(times[-1]), operations=[record])
    return times, record.positions


def mean_squared_displacement(positions: ArrayLike, *,
                              max_lag: int | None = None) -> np.ndarray:
    """Mean squared displacement from unwrapped positions at equal time steps.

    ``msd[k] = < |x_i(t + k dt) - x_i(t)|^2 >`` averaged over all disks ``i`` and all
    time origins ``t`` of the series (overlapping windows).  In 2D free flight gives
    ``msd = <v^2> t^2`` and diffusion ``msd ~ 4 D t``.

    Parameters
    ----------
    positions : array_like, shape (F, N, 2)
        Unwrapped positions, e.g. from :func:`trajectory`.
    max_lag : int, optional
        Largest lag in frames, < F; default ``F - 1``.

    Returns
    -------
    ndarray, shape (max_lag + 1,)
        ``msd[0] == 0``.

    Examples
    --------
    A disk moving at unit speed: the displacement after ``k`` steps is ``k``.

    >>> import numpy as np
    >>> x = np.zeros((4, 1, 2)); x[:, 0, 0] = np.arange(4.0)
    >>> mean_squared_displacement(x).tolist()
    [0.0, 1.0, 4.0, 9.0]
    """
    pos = as_float_array("positions", positions, (None, None, 2))
    n_frames = pos.shape[0]
    if n_frames < 1 or pos.shape[1] < 1:
        raise ValueError(f"positions must hold at least one frame of one disk, got {pos.shape}")
    if max_lag is None:
        max_lag = n_frames - 1
    else:
        max_lag = as_count("max_lag", max_lag)
        if max_lag >= n_frames:
            raise ValueError(f"max_lag must be < the number of frames {n_frames}, got {max_lag}")
    msd = np.zeros(max_lag + 1)
    for k in range(1, max_lag + 1):
        d = pos[k:] - pos[:-k]
        msd[k] = float(np.mean(np.einsum("fij,fij->fi", d, d)))
    return msd


# --------------------------------------------------------------------------- psi_6
def hexatic_order(source: Simulation | ArrayLike, box: Box | None = None, *,
                  neighbors: str | float = "voronoi") -> tuple[complex, np.ndarray]:
    """The hexatic bond-orientational order parameter psi_6, per disk and global.

    ``psi_6(j) = (1 / n_j) sum_k exp(6 i theta_jk)`` over the ``n_j`` neighbours ``k`` of
    disk ``j``, ``theta_jk`` the angle of the bond from ``j`` to ``k`` (minimum image) with
    the x axis; the global value is the mean over disks, ``Psi_6 = (1/N) sum_j
    psi_6(j)``.  ``|psi_6| = 1`` for a perfect triangular lattice at any orientation and
    ``|Psi_6| ~ 1/sqrt(N)`` in an isotropic fluid.  A disk without neighbours has
    ``psi_6 = 0``.

    Parameters
    ----------
    source : Simulation or array_like, shape (N, 2)
    box : Box
        Required with an array; not allowed with a Simulation.
    neighbors : "voronoi" or float, default "voronoi"
        ``"voronoi"``: the Voronoi neighbours (the Delaunay triangulation, with periodic
        images of the disks within a band around a periodic box).  A number: every disk
        closer than this cutoff (e.g. the first minimum of g(r)).

    Returns
    -------
    psi : complex
        The global order parameter.
    psi_local : ndarray of complex, shape (N,)

    Examples
    --------
    A triangular lattice, 8 x 8 disks in a periodic box that fits it exactly:

    >>> import numpy as np, edmd2d as ed
    >>> i, j = np.meshgrid(np.arange(8), np.arange(8))
    >>> pts = np.column_stack([(i + 0.5 * (j % 2)).ravel(), (j * np.sqrt(3) / 2).ravel()])
    >>> box = ed.Box(8.0, 8 * np.sqrt(3) / 2)
    >>> psi, local = hexatic_order(pts + 0.1, box)
    >>> round(abs(psi), 12), bool(np.allclose(np.abs(local), 1))
    (1.0, True)
    """
    from scipy import spatial

    frames, box, _ = _positions_and_box(source, box)
    if frames.shape[0] != 1:
        raise ValueError("hexatic_order takes one configuration of shape (N, 2)")
    pos = _wrap(frames[0], box)
    n = len(pos)
    if isinstance(neighbors, str):
        if neighbors != "voronoi":
            raise ValueError(f'neighbors must be "voronoi" or a cutoff distance, got {neighbors!r}')
        i, j = _voronoi_pairs(pos, box)
    else:
        cutoff = as_positive_float("neighbors (cutoff)", neighbors)
        limit = min([length / 2 for length, p in zip((box.width, box.height), box.periodic)
                     if p] or [math.inf])
        if cutoff >= limit:
            raise ValueError(f"the cutoff {cutoff} must be below half the periodic side {limit}")
        pairs = spatial.cKDTree(pos, boxsize=_boxsize(box, cutoff)).query_pairs(
            cutoff, output_type="ndarray")
        i, j = pairs[:, 0], pairs[:, 1]
    d = _min_image(pos[j] - pos[i], box)
    bond = np.exp(6j * np.arctan2(d[:, 1], d[:, 0]))  # the j->i bond has the same phase
    total = np.zeros(n, complex)
    np.add.at(total, i, bond)
    np.add.at(total, j, bond)
    count = np.bincount(i, minlength=n) + np.bincount(j, minlength=n)
    local = np.where(count > 0, total / np.maximum(count, 1), 0.0)
    return complex(local.mean()), local


def _voronoi_pairs(pos: np.ndarray, box: Box):
    """Unique Voronoi-neighbour pairs ``(i, j)``, ``i < j``, from a Delaunay triangulation
    of the disks and, on periodic axes, of their images within a band around the box."""
    n = len(pos)
    if n < 3:
        raise ValueError(f"Voronoi neighbours need at least 3 disks, got {n}")
    # A band a few mean spacings wide holds every Delaunay neighbour of a fluid or
    # crystal configuration (a Delaunay circle cannot be much wider than the largest
    # empty region).
    band = 4.0 * math.sqrt(box.area / n)
    images, image_of = [pos], [np.arange(n)]
    sizes = (box.width, box.height)
    for sx in (-1, 0, 1):
        for sy in (-1, 0, 1):
            if (sx, sy) == (0, 0) or (sx and not box.periodic[0]) or (sy and not box.periodic[1]):
                continue
            shifted = pos + np.array([sx * sizes[0], sy * sizes[1]])
            keep = ((shifted[:, 0] > -band) & (shifted[:, 0] < sizes[0] + band)
                    & (shifted[:, 1] > -band) & (shifted[:, 1] < sizes[1] + band))
            images.append(shifted[keep])
            image_of.append(np.flatnonzero(keep))
    from scipy import spatial

    pts = np.concatenate(images)
    idx = np.concatenate(image_of)
    tri = spatial.Delaunay(pts)
    s = tri.simplices
    edges = np.concatenate([s[:, [0, 1]], s[:, [1, 2]], s[:, [2, 0]]])
    edges = edges[(edges[:, 0] < n) | (edges[:, 1] < n)]  # at least one original disk
    a, b = idx[edges[:, 0]], idx[edges[:, 1]]
    pairs = np.unique(np.column_stack([np.minimum(a, b), np.maximum(a, b)]), axis=0)
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    return pairs[:, 0], pairs[:, 1]


# --------------------------------------------------------------------------- Voronoi cells
def voronoi_cell_areas(source: Simulation | ArrayLike, box: Box | None = None) -> np.ndarray:
    """The area of each disk's Voronoi cell (the points nearer its centre than any
    other), in the box: cells wrap around periodic axes and end at the walls.

    The tessellation of the centres together with their images (a periodic copy on a
    periodic axis, the mirror image in the wall on a walled one: a mirror image puts
    the cell's edge on the wall itself), so the areas add up to the box's.  It is the
    tessellation of points, not of disks of different sizes (a radical tessellation
    would give large disks of a mixture larger cells).

    Parameters
    ----------
    source : Simulation or array_like, shape (N, 2)
        A simulation (its positions and box) or the centres.
    box : Box
        Required with an array; not allowed with a Simulation.

    Returns
    -------
    numpy.ndarray, shape (N,)

    Raises
    ------
    TypeError, ValueError
        For fewer than 3 disks, two disks at the same point, and bad input as
        :func:`radial_distribution`.

    Examples
    --------
    A square lattice of unit spacing: every cell is a unit square.

    >>> import numpy as np, edmd2d as ed
    >>> i, j = np.meshgrid(np.arange(4), np.arange(4))
    >>> pts = np.column_stack([i.ravel() + 0.5, j.ravel() + 0.5])
    >>> np.round(voronoi_cell_areas(pts, ed.Box(4.0, 4.0, periodic=False)), 12)[:4]
    array([1., 1., 1., 1.])
    """
    from scipy import spatial

    frames, box, _ = _positions_and_box(source, box)
    pos = _wrap(frames[0], box)
    n = len(pos)
    if n < 3:
        raise ValueError(f"Voronoi cells need at least 3 disks, got {n}")
    sizes = (box.width, box.height)
    copies = []
    for kx in (-1, 0, 1):
        for ky in (-1, 0, 1):
            image = pos.copy()
            for axis, k in ((0, kx), (1, ky)):
                if k == 0:
                    continue
                if box.periodic[axis]:
                    image[:, axis] += k * sizes[axis]
                else:  # the mirror image in the wall at 0 (k = -1) or at L (k = 1)
                    image[:, axis] = (0.0 if k < 0 else 2.0 * sizes[axis]) - image[:, axis]
            copies.append(image)
    pts = np.concatenate([copies[4]] + copies[:4] + copies[5:])  # originals first
    if len(np.unique(pos, axis=0)) < n:
        raise ValueError("two disks share a centre: their Voronoi cells are not defined")
    vor = spatial.Voronoi(pts)
    areas = np.empty(n)
    for k in range(n):
        cell = vor.vertices[vor.regions[vor.point_region[k]]]
        centred = cell - pos[k]
        order = np.argsort(np.arctan2(centred[:, 1], centred[:, 0]))
        x, y = cell[order, 0], cell[order, 1]
        areas[k] = 0.5 * abs(float(dot(x, np.roll(y, -1)) - dot(y, np.roll(x, -1))))
    return areas


def local_packing_fractions(source: Simulation) -> np.ndarray:
    """Each disk's area over its Voronoi cell's (:func:`voronoi_cell_areas`): the
    packing fraction it sees around itself.  In a triangular crystal at contact every
    disk has ``pi / (2 sqrt 3) = 0.9069``; defects and gaps lower it where they are.

    Parameters
    ----------
    source : Simulation

    Returns
    -------
    numpy.ndarray, shape (N,)

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.make_gas(400, 0.5, seed=1)
    >>> round(float(sim.radii @ sim.radii * 3.141592653589793 / sim.box.area), 12)
    0.5
    >>> bool(abs(local_packing_fractions(sim).mean() - 0.5) < 0.02)
    True
    """
    if not isinstance(source, Simulation):
        raise TypeError(f"local_packing_fractions() needs an edmd2d.Simulation, got "
                        f"{type(source).__name__}")
    return np.pi * source.radii ** 2 / voronoi_cell_areas(source)
