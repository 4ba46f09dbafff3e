"""Thermodynamic and kinetic measurements over a time window: :func:`measure`.

Everything here is a true two-dimensional quantity with ``k_B = 1``.  The pressure comes
from the collision virial, which the engine accumulates exactly at every disk-disk
collision (no sampling of configurations), and error bars come from block averages over
equal sub-windows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._validate import as_count, as_positive_float

__all__ = ["Measurement", "measure", "kinetic_temperature", "degrees_of_freedom", "Cooling",
           "cooling"]


@dataclass(frozen=True)
class Measurement:
    """Results of :func:`measure` over one time window (``k_B = 1``, 2D).

    Each ``*_error`` is the standard error of the mean over the window's blocks
    (``std(block values, ddof=1) / sqrt(blocks)``), ``nan`` with a single block.  It is
    an honest error bar when each block is much longer than the correlation time of the
    quantity (a few mean free times for the virial of a fluid; in 2D the stress
    autocorrelation has a slow ``1/t`` tail, so very short blocks underestimate it).

    Attributes
    ----------
    duration : float
        Length of the window.
    collisions : int
        Disk-disk collisions in the window.
    wall_collisions : int
        Collisions with box walls and wall segments in the window.
    blocks : int
        Number of equal sub-windows used for the error bars.
    n : int
        Number of movable disks (``mass < inf``): the ``N`` of every formula below.
    area : float
        Box area ``A``.
    degrees_of_freedom : int
        ``f = 2N`` minus one for every Cartesian component of the total momentum that
        the dynamics conserves (see :func:`degrees_of_freedom`).
    temperature : float
        ``kT = (sum m v^2 - P_c^2 / M) / f`` averaged over the block boundaries, where
        ``P_c`` is the conserved part of the total momentum and ``M`` the total mass
        (constant in an elastic run, so this is the window's temperature).
    pressure, pressure_error : float
        Virial pressure ``P = (N kT + sum J |r_ij| / (2 t)) / A``: the sum runs over the
        disk-disk collisions of the window, ``J`` is the impulse magnitude and ``|r_ij|``
        the centre distance at contact.  (This is the 2D virial theorem: the
        ``1/(2t)`` is ``1/(d t)`` with ``d = 2`` dimensions.)  In a fully periodic box
        this is the bulk pressure.  In a box with walls it is the virial pressure of
        the whole box, which includes the walls' share (see ``wall_pressure``).
    pressure_xx, pressure_yy : float
        Diagonal of the pressure tensor, ``P_aa A = N kT_a + sum J |r_ij| n_a^2 / t``
        with ``n`` the unit contact normal and ``kT_a`` the kinetic temperature of the
        ``a`` components alone (``(sum m v_a^2 - P_a^2 / M) / (N - c_a)``, ``c_a = 1`` if
        that momentum component is conserved).  Their mean is ``pressure`` (up to the
        split of the kinetic part); they differ in anisotropic systems such as a channel.
    compressibility_factor, compressibility_factor_error : float
        ``Z = P A / (N kT) = 1 + sum J |r_ij| / (2 t N kT)``.
    collision_rate, collision_rate_error : float
        Collisions per disk per unit time, ``2 C / (N_all t)`` (every disk-disk
        collision involves two disks; ``N_all`` counts all disks).
    mean_free_time, mean_free_time_error : float
        ``1 / collision_rate`` (time between disk-disk collisions of one disk).
    mean_speed : float
        Mean of ``|v|`` over the movable disks, averaged over the block boundaries.
    mean_free_path : float
        ``mean_speed * mean_free_time``.
    wall_pressure, wall_pressure_error : float
        Impulse delivered to the box walls (on walled axes) per unit time and per unit
        wall length: a mechanical pressure.  ``nan`` in a fully periodic box.
    box_wall_pressures : tuple of 4 float
        The same for each box wall, in the order x=0, x=width, y=0, y=height (``nan``
        on periodic axes).
    segment_force : float
        Impulse delivered to all wall segments per unit time (0.0 without segments).
    """

    duration: float
    collisions: int
    wall_collisions: int
    blocks: int
    n: int
    area: float
    degrees_of_freedom: int
    temperature: float
    pressure: float
    pressure_error: float
    pressure_xx: float
    pressure_yy: float
    compressibility_factor: float
    compressibility_factor_error: float
    collision_rate: float
    collision_rate_error: float
    mean_free_time: float
    mean_free_time_error: float
    mean_speed: float
    mean_free_path: float
    wall_pressure: float
    wall_pressure_error: float
    box_wall_pressures: tuple
    segment_force: float

    def summary(self) -> str:
        """A few lines with the main values and their error bars."""

        def pm(value, err):
            return f"{value:.6g} +- {err:.2g}" if np.isfinite(err) else f"{value:.6g}"

        lines = [
            f"window {self.duration:g} ({self.blocks} blocks), N={self.n}, "
            f"{self.collisions} collisions",
            f"temperature            {self.temperature:.6g}",
            f"pressure               {pm(self.pressure, self.pressure_error)}",
            f"compressibility Z      "
            f"{pm(self.compressibility_factor, self.compressibility_factor_error)}",
            f"collision rate / disk  {pm(self.collision_rate, self.collision_rate_error)}",
            f"mean free time         {pm(self.mean_free_time, self.mean_free_time_error)}",
            f"mean free path         {self.mean_free_path:.6g}",
        ]
        if np.isfinite(self.wall_pressure):
            lines.append(f"wall pressure          "
                         f"{pm(self.wall_pressure, self.wall_pressure_error)}")
        return "\n".join(lines)


def degrees_of_freedom(sim) -> tuple[int, tuple[bool, bool]]:
    """Kinetic degrees of freedom of the movable disks and the conserved momentum axes.

    A Cartesian component of the total momentum is conserved when its axis is periodic
    and nothing external can push along it: no wall segments (a segment's end points
    push in every direction) and no immovable disks (``mass = inf``).  Each conserved
    component removes one degree of freedom: ``f = 2N - 2`` in a fully periodic box of
    free disks, ``2N - 1`` in a channel periodic along one axis, ``2N`` in a closed box.

    Returns
    -------
    f : int
        The degrees of freedom.
    conserved : (bool, bool)
        Whether the x and y components of the total momentum are conserved.

    Examples
    --------
    >>> import edmd2d as ed
    >>> degrees_of_freedom(ed.make_gas(10, 0.2, seed=0))
    (18, (True, True))
    >>> degrees_of_freedom(ed.make_gas(10, 0.2, periodic=(True, False), seed=0))
    (19, (True, False))
    """
    movable = np.isfinite(sim.masses)
    free = bool(movable.all()) and not sim.walls
    conserved = (bool(sim.box.periodic[0]) and free, bool(sim.box.periodic[1]) and free)
    return 2 * int(movable.sum()) - int(sum(conserved)), conserved


def kinetic_temperature(sim) -> float:
    """The kinetic temperature ``kT`` of the movable disks now (2D, ``k_B = 1``).

    ``kT = (sum m v^2 - sum_c P_c^2 / M) / f``: each disk has two translational degrees
    of freedom with ``<m v_a^2> = kT`` (equipartition in 2D, so the mean kinetic energy
    per disk is ``kT``, not the ``3 kT / 2`` of 3D).  ``P_c`` runs over the conserved
    components of the total momentum, ``M`` is the total mass and ``f`` comes from
    :func:`degrees_of_freedom`: the centre-of-mass motion along a conserved axis carries
    no heat.  ``nan`` when ``f <= 0`` (a single disk in a periodic box).

    Examples
    --------
    >>> import edmd2d as ed
    >>> sim = ed.make_gas(100, 0.3, temperature=2.5, seed=1)
    >>> round(kinetic_temperature(sim), 12)
    2.5
    """
    dof, conserved = degrees_of_freedom(sim)
    if dof <= 0:
        return math.nan
    mass = sim.masses
    vel = sim.velocities
    movable = np.isfinite(mass)
    m, v = mass[movable], vel[movable]
    twice_ke = float(np.dot(m, np.einsum("ij,ij->i", v, v)))
    momentum = m @ v
    total_mass = float(m.sum())
    cm = sum(float(momentum[a]) ** 2 for a in range(2) if conserved[a]) / total_mass
    return (twice_ke - cm) / dof


def measure(sim, duration: float, *, blocks: int = 10) -> Measurement:
    """Run ``sim`` for ``duration`` and measure pressure, temperature and collision rates.

    The window is cut into ``blocks`` equal sub-windows; the values returned are the
    averages over the whole window, and the errors the standard errors of the block
    values.  Equilibrate first (``sim.advance(until=...)``): every collision of the
    window counts.

    Formulas (2D, ``k_B = 1``; ``N`` movable disks, box area ``A``, window length ``t``,
    ``C`` disk-disk collisions, ``J`` impulse magnitude, ``|r_ij|`` contact distance):

    - temperature ``kT = (sum m v^2 - P_c^2 / M) / f`` with ``f = 2N - (number of
      conserved momentum components)`` (:func:`kinetic_temperature`);
    - virial pressure ``P A = N kT + (1 / (2 t)) sum J |r_ij|`` (the 2D virial theorem;
      in 3D the factor would be ``1/(3t)`` and ``P V = N kT + ...``);
    - compressibility factor ``Z = P A / (N kT)``;
    - collision rate per disk ``2 C / (N t)``; mean free time its inverse; mean free
      path ``<|v|>`` times the mean free time;
    - wall pressure: impulse on the box walls per unit time per unit wall length.

    For a walled rectangular box of equal disks of radius ``a`` the virial theorem with
    the wall forces included reads exactly (in the time average)
    ``(W - 2a) F_x + (H - 2a) F_y = 2 P A``, where ``F_x`` is the mean force on one
    x-wall (``box_wall_pressures[0] * H``) and ``F_y`` that on one y-wall: the walls
    carry the virial ``2 P A`` at the distance ``a`` at which the disk centres touch.
    So ``wall_pressure`` differs from ``pressure`` by a surface term of relative size
    ``~ 2a / L``; in a channel (periodic along the walls) ``wall_pressure`` is the bulk
    pressure normal to the walls.

    With immovable disks or wall segments ``pressure`` keeps its formula but is no
    longer a thermodynamic pressure (the obstacles' virial is not included).  A
    collision with an immovable disk adds to ``collisions`` like any other.

    Parameters
    ----------
    sim : Simulation
        Advanced in place, from ``sim.time`` to ``sim.time + duration``.
    duration : float
        Length of the window, > 0.
    blocks : int, default 10
        Number of sub-windows for the error bars, >= 1.

    Returns
    -------
    Measurement

    Raises
    ------
    TypeError, ValueError
        For a ``sim`` that is not a Simulation, a non-positive or non-finite
        ``duration``, or ``blocks < 1``.

    Examples
    --------
    A dilute gas: ``Z`` close to the hard-disk equation of state, and the temperature
    stays exactly what :func:`~edmd2d.make_gas` set:

    >>> import edmd2d as ed
    >>> from edmd2d import theory
    >>> sim = ed.make_gas(200, 0.2, seed=3)
    >>> _ = sim.advance(until=10.0)
    >>> m = sim.measure(duration=50.0)
    >>> round(m.temperature, 9)
    1.0
    >>> abs(m.compressibility_factor - theory.henderson_z(0.2)) < 0.03
    True
    >>> m.collisions == round(m.collision_rate * m.n * m.duration / 2)
    True
    """
    from .simulation import Simulation

    if not isinstance(sim, Simulation):
        raise TypeError(f"measure() needs an edmd2d.Simulation, got {type(sim).__name__}")
    duration = as_positive_float("duration", duration)
    blocks = as_count("blocks", blocks, minimum=1)

    box = sim.box
    area = box.area
    n_all = len(sim)
    movable = np.isfinite(sim.masses)
    n = int(movable.sum())
    dof, _ = degrees_of_freedom(sim)
    # Wall lengths in the order of the engine's box accumulators: x=0, x=W, y=0, y=H.
    lengths = np.array([box.height, box.height, box.width, box.width])
    walled = np.array([not box.periodic[0]] * 2 + [not box.periodic[1]] * 2)

    t0 = sim.time
    acc0 = sim._accumulators()
    counts0 = sim.counts
    edges_acc = [acc0]
    temps = [kinetic_temperature(sim)]
    axis_temps = [_axis_temperatures(sim, movable)]
    speeds = [_mean_speed(sim, movable)]
    coll = [counts0.collisions]
    for b in range(1, blocks + 1):
        t_end = t0 + duration * b / blocks if b < blocks else t0 + duration
        sim.advance(until=t_end)
        edges_acc.append(sim._accumulators())
        temps.append(kinetic_temperature(sim))
        axis_temps.append(_axis_temperatures(sim, movable))
        speeds.append(_mean_speed(sim, movable))
        coll.append(sim.counts.collisions)
    tau = duration / blocks

    virial = np.diff([a["virial"] for a in edges_acc])
    virial_axes = np.array([edges_acc[-1][k] - acc0[k] for k in ("virial_xx", "virial_yy")])
    kt_axes = np.mean(np.array(axis_temps), axis=0)
    box_imp = np.diff(np.array([a["box_impulse"] for a in edges_acc]), axis=0)
    seg_imp = edges_acc[-1]["segment_impulse"] - acc0["segment_impulse"]
    temps = np.array(temps)
    kt_block = 0.5 * (temps[1:] + temps[:-1])
    n_coll = np.diff(coll)

    kt = float(np.mean(temps))
    with np.errstate(divide="ignore", invalid="ignore"):
        p_block = (n * kt_block + virial / (2.0 * tau)) / area
        z_block = p_block * area / (n * kt_block) if kt > 0 else np.full(blocks, math.nan)
        rate_block = 2.0 * n_coll / (n_all * tau)
        pressure = (n * kt + float(virial.sum()) / (2.0 * duration)) / area
        z = pressure * area / (n * kt) if kt > 0 else math.nan
        p_axes = (n * kt_axes + virial_axes / duration) / area
        rate = 2.0 * float(n_coll.sum()) / (n_all * duration)
        rate_err = _stderr(rate_block)
        mft = 1.0 / rate if rate > 0 else math.inf
        mft_err = rate_err / rate**2 if rate > 0 else math.nan
        per_wall = box_imp.sum(axis=0) / (duration * lengths)
        if walled.any():
            wall_p = float(box_imp[:, walled].sum() / (duration * lengths[walled].sum()))
            wall_p_block = box_imp[:, walled].sum(axis=1) / (tau * lengths[walled].sum())
            wall_err = _stderr(wall_p_block)
        else:
            wall_p, wall_err = math.nan, math.nan
    mean_speed = float(np.mean(speeds))
    return Measurement(
        duration=float(duration),
        collisions=int(n_coll.sum()),
        wall_collisions=sim.counts.wall_collisions - counts0.wall_collisions,
        blocks=blocks,
        n=n,
        area=area,
        degrees_of_freedom=dof,
        temperature=kt,
        pressure=float(pressure),
        pressure_error=_stderr(p_block),
        pressure_xx=float(p_axes[0]),
        pressure_yy=float(p_axes[1]),
        compressibility_factor=float(z),
        compressibility_factor_error=_stderr(z_block),
        collision_rate=rate,
        collision_rate_error=rate_err,
        mean_free_time=mft,
        mean_free_time_error=mft_err,
        mean_speed=mean_speed,
        mean_free_path=mean_speed * mft,
        wall_pressure=wall_p,
        wall_pressure_error=wall_err,
        box_wall_pressures=tuple(float(p) if w else math.nan for p, w in zip(per_wall, walled)),
        segment_force=float(seg_imp / duration),
    )


def _axis_temperatures(sim, movable: np.ndarray) -> np.ndarray:
    """``kT_x, kT_y``: the kinetic temperature of each velocity component alone."""
    _, conserved = degrees_of_freedom(sim)
    m = sim.masses[movable]
    v = sim.velocities[movable]
    out = np.full(2, math.nan)
    for a in range(2):
        dof = len(m) - int(conserved[a])
        if dof > 0:
            p = float(m @ v[:, a])
            out[a] = (float(m @ v[:, a] ** 2) - (p * p / m.sum() if conserved[a] else 0.0)) / dof
    return out


def _mean_speed(sim, movable: np.ndarray) -> float:
    v = sim.velocities[movable]
    return float(np.mean(np.hypot(v[:, 0], v[:, 1]))) if len(v) else math.nan


def _stderr(values: np.ndarray) -> float:
    """Standard error of the mean of independent block values (nan for fewer than 2)."""
    values = np.asarray(values, dtype=float)
    if len(values) < 2:
        return math.nan
    return float(np.std(values, ddof=1) / math.sqrt(len(values)))


@dataclass(frozen=True)
class Cooling:
    """Results of :func:`cooling`: a cooling (inelastic) gas sampled at given times.

    Attributes
    ----------
    time : ndarray, shape (K,)
        The sampling times (the first is the start).
    collisions_per_disk : ndarray, shape (K,)
        Disk-disk collisions per disk since the start, ``2 C / N_all`` (every
        collision involves two disks).
    kinetic_energy : ndarray, shape (K,)
        Total kinetic energy of the movable disks.
    temperature : ndarray, shape (K,)
        Granular temperature, the kinetic temperature ``kT`` of
        :func:`kinetic_temperature` (mean kinetic energy per degree of freedom, with
        the conserved centre-of-mass motion left out).
    dissipated_energy : ndarray, shape (K,)
        Kinetic energy lost in collisions since the start.
    """

    time: np.ndarray
    collisions_per_disk: np.ndarray
    kinetic_energy: np.ndarray
    temperature: np.ndarray
    dissipated_energy: np.ndarray


def cooling(sim, times) -> Cooling:
    """Run ``sim`` through the increasing ``times`` and sample how it cools.

    Parameters
    ----------
    sim : Simulation
        Advanced in place to ``times[-1]``.
    times : array_like, shape (K,)
        Increasing sampling times, the first not before ``sim.time`` (the run goes
        there first).

    Returns
    -------
    Cooling
        Time, collisions per disk, kinetic energy, granular temperature and
        dissipated energy at each sampling time.  For a homogeneous gas of
        restitution ``e``, ``T = T0 exp(-(1 - e^2) C / 2)`` against the collisions per
        disk ``C`` and Haff's law ``T = T0 / (1 + t / t_H)^2`` against time (see
        ``docs/restitution.md``).

    Raises
    ------
    ValueError
        If ``times`` is empty, not increasing or starts before ``sim.time``.
    """
    t = np.asarray(times, dtype=float)
    if t.ndim != 1 or len(t) == 0 or not np.all(np.isfinite(t)):
        raise ValueError(f"times must be a non-empty 1-D array of finite times, got {times!r}")
    if np.any(np.diff(t) <= 0):
        raise ValueError("times must be strictly increasing")
    if t[0] < sim.time:
        raise ValueError(f"times start at {t[0]}, before the simulation's time {sim.time}")
    n_all = sim.n
    rows = []
    c0 = e0 = None
    for tk in t:
        sim.advance(until=float(tk))
        c, lost = sim.counts.collisions, sim.dissipated_energy()
        if c0 is None:
            c0, e0 = c, lost
        rows.append((2.0 * (c - c0) / n_all, sim.kinetic_energy(), kinetic_temperature(sim),
                     lost - e0))
    cols = np.array(rows).T
    return Cooling(t.copy(), cols[0], cols[1], cols[2], cols[3])

