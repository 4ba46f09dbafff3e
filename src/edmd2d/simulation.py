"""The :class:`Simulation`: the public facade that checks input, builds the engine's
state (``edmd2d._state.EngineState``), advances it and reads it."""

from __future__ import annotations

import copy
import dataclasses
import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from . import _checks, _gaps, _operations, _state
from . import measurements as _measurements
from . import models as _models
from . import physics as _physics
from . import progress as _progress
from ._engine import layout as _layout
from ._facade import SimulationBase
from ._sums import dot, weighted_sum
from ._validate import about, as_count, as_float_array, indices_where, per_disk
from .geometry import BOX_WALLS, Box, Wall, as_walls

__all__ = ["Simulation", "Counts"]

#: The names of the streamed event kinds (:meth:`Simulation.stream_events`).
EVENT_KINDS = _state.EVENT_KINDS
#: The fields of a streamed batch of events.
EVENT_DTYPE = _state.EVENT_DTYPE


@dataclass(frozen=True)
class Counts:
    """Event counts since the simulation was created.

    Attributes
    ----------
    collisions : int
        Disk-disk collisions.
    wall_collisions : int
        Collisions of disks with box walls and wall segments (sides and end points).
    cell_crossings : int
        Grid bookkeeping events: a disk centre moved into another cell (or, on a grid
        with wide disks, a wide disk's footprint gained or lost a row of cells).
    events : int
        All processed events: the sum of the three above and of ``redraws``.
    stale : int
        Predictions found invalid when they came due (the partner had changed course)
        and recomputed; not physical events, not included in ``events``.
    redraws : int
        Velocities redrawn by the thermostat.
    rests : int
        Disks put to rest (see :class:`edmd2d.physics.Resting`).
    wakes : int
        Disks at rest woken.
    """

    collisions: int
    wall_collisions: int
    cell_crossings: int
    events: int
    stale: int
    redraws: int = 0
    rests: int = 0
    wakes: int = 0


class Simulation(SimulationBase):
    """An exact event-driven simulation of hard disks in a rectangular box.

    Disks move on straight lines between collisions (on parabolas under ``gravity``).
    Every disk-disk and disk-wall contact is found at its exact time from a quadratic
    equation (a quartic, bracketed, for two bodies of different accelerations: a
    falling disk against a fixed point or a disk resting on a box wall), with no time
    step, so no collision is missed at any speed or over any interval.

    Parameters
    ----------
    positions : array_like, shape (N, 2)
        Disk centres, inside the box.  On a walled axis each disk must fit between the
        walls (``r <= x <= width - r``); on a periodic axis ``0 <= x <= width``.
    velocities : array_like, shape (N, 2)
        Disk velocities.
    radii : float or array_like, shape (N,)
        Radii, > 0.
    masses : float or array_like, shape (N,), default 1.0
        Masses, > 0; ``inf`` makes a disk immovable (a fixed peg, or a piston if it
        moves).  Two immovable disks must never meet, nor may a moving immovable disk
        reach a wall: that stops the simulation with a ``RuntimeError``.
    box : Box
        The container.  A periodic axis must be at least one largest diameter long.
    walls : iterable of Wall, optional
        Extra wall segments inside the box.
    open_walls : iterable of int, optional
        The indices of the segments that start open (see :meth:`open_wall`): a
        gate to close later.
    time : float, default 0.0
        The clock at the given state.
    cell_size : float, optional
        Side of the grid cells (advanced).  Must be at least the largest diameter;
        the default is that bound, widened in dilute systems to keep at most about
        two cells per disk.
    grid : {"auto", "uniform", "wide"}, default "auto"
        How the grid finds neighbours (advanced; see ``docs/performance-notes.md``).
        ``"uniform"``: every cell holds the largest disk.  ``"wide"``: the cells hold
        the narrow disks, and each disk wider than them is listed in every cell near
        it, so that a few large disks do not slow the many small ones.  ``"auto"``
        keeps the uniform grid unless the largest diameter is at least 2.5 times the
        smallest and an estimate of the work finds the wide grid cheaper.  Wide disks do not
        combine with a ``cell_size`` (there ``"auto"`` keeps the uniform grid); they come
        to rest, hold others and meet through a sheared boundary as narrow ones do; under
        growth, a rebuild after
        which the wide disks' footprints no longer fit a periodic box makes a uniform grid.
        Every grid gives the same dynamics; runs on different grids differ by rounding.
    species : array_like of int, shape (N,), optional
        Each disk's species (``0, 1, ...``), which selects its row of the
        ``restitution`` table; all 0 by default.
    restitution : float or array_like, shape (S, S), default 1.0
        Coefficient of normal restitution ``e`` in ``(0, 1]`` of disk-disk collisions:
        one value, or a symmetric table indexed by the two disks' species (``S`` at
        least the number of species).  ``1`` is elastic.  Below 1 each collision
        reverses the normal relative velocity and multiplies it by ``e``, with the TC
        model against inelastic collapse (see :mod:`edmd2d.models`).
    wall_restitution : float, default 1.0
        Coefficient of normal restitution against box walls and wall segments.
    tc : float, optional
        The TC model's duration (``>= 0``): a collision is elastic when a movable
        disk involved collided less than ``tc`` ago.  Default ``1e-5`` of the time a disk
        of mean diameter needs to cross it at the initial root-mean-square speed.
        Used only when some coefficient is below 1; ``0`` turns the model off, and a
        run that collapses then stops with a ``RuntimeError``.
    gravity : array_like, shape (2,), optional
        A uniform acceleration ``(gx, gy)`` of every movable disk (immovable disks and
        walls stay put): disks fly on exact parabolas between events.  Velocities then
        change between events; every readout gives them at :attr:`time`, and
        :meth:`potential_energy` and :meth:`total_energy` include ``m g.h``.  A movable
        disk may not start at rest against a wall that gravity presses it into (a
        resting contact is not an event-driven motion): lift it by a gap, or give it a
        speed.  An inelastic model (a coefficient below 1, ``tc > 0``) lets the wall
        hold such a disk, and holds a disk whose bounces on a box wall shrink until
        the next would come within ``tc``: it then slides along the wall until a
        collision lifts it.
    wall_temperatures : dict, optional
        Heated walls: ``{wall: kT}``, ``wall`` a box wall (``"left"``, ``"right"``,
        ``"bottom"``, ``"top"``, or ``"x=0"``, ``"x=width"``, ``"y=0"``,
        ``"y=height"``) or the index of a wall segment, ``kT > 0``.  A disk that hits a
        heated wall leaves it with a velocity drawn from the wall's temperature (the
        normal component from the flux-weighted distribution
        ``(m v / kT) exp(-m v^2 / 2kT)``, the tangential one Gaussian with variance
        ``kT / m``) instead of being reflected; :meth:`wall_heat` sums the energy each
        wall gives.
    thermostat : (float, float), optional
        An Andersen thermostat ``(kT, rate)``: each movable disk's velocity is redrawn
        from the Maxwell-Boltzmann distribution at ``kT`` at the events of a Poisson
        process of ``rate`` (per disk and unit time, ``>= 0``), each at its exact time
        (an event of the run, after which the disk is predicted afresh).
    seed : int or numpy.random.Generator, optional
        The random numbers of heated walls and the thermostat: a run is reproducible
        from its seed (and continues the same stream after copies and pickles).
    growth : float, optional
        Growing disks (``>= 0``, per unit time): every radius grows linearly in time at
        ``growth`` times its value at ``time``, ``r_i(t) = r_i (1 + growth (t - time))``,
        so a mixture keeps its size ratios (the Lubachevsky-Stillinger compression;
        :func:`edmd2d.compress` drives it to a packing fraction or to jamming).  A
        contact then reverses the rate at which the gap closed, which adds kinetic
        energy (the work of the compression).  For elastic disks in free flight
        (no ``gravity``, restitution, heated walls or thermostat).  See
        :meth:`set_growth`.
    **physics
        The keywords of the physics families registered with
        :func:`edmd2d.physics.register` (kept in :attr:`families`).

    Raises
    ------
    TypeError, ValueError
        For arguments of the wrong type, shape or value, with the indices of the
        offending disks, overlapping pairs, and disks overlapping a wall.

    Notes
    -----
    Event times are absolute float64 values and each disk's position is kept at its own
    last event time.  Contacts are resolved to rounding of the numbers involved, so
    exactness in practice holds while ``time * speed`` stays well below ~1e7 diameters
    (a relative precision of 1e-16 on the time, times the distance travelled, must stay
    far below the grid's 1e-9 diameter margin); an overlap that rounding might leave is
    repaired at once, since an approaching overlapped pair collides immediately.  Event
    order among exactly simultaneous events follows the engine's internal row order.

    Examples
    --------
    Two disks approaching head-on touch when their gap of 1 closes at relative speed 2:

    >>> import edmd2d as ed
    >>> sim = ed.Simulation([[2.0, 5.0], [5.0, 5.0]], [[1.0, 0.0], [-1.0, 0.0]],
    ...                     radii=1.0, box=ed.Box(10.0, 10.0, periodic=False))
    >>> sim.advance(collisions=1).time
    0.5
    >>> sim.velocities
    array([[-1.,  0.],
           [ 1.,  0.]])
    """

    def __init__(
        self,
        positions: ArrayLike,
        velocities: ArrayLike,
        radii: ArrayLike,
        masses: ArrayLike = 1.0,
        box: Box | None = None,
        walls: Iterable[Wall] = (),
        *,
        open_walls: Iterable[int] = (),
        time: float = 0.0,
        cell_size: float | None = None,
        grid: str = "auto",
        species: ArrayLike | None = None,
        restitution: ArrayLike = 1.0,
        wall_restitution: float = 1.0,
        tc: float | None = None,
        gravity: ArrayLike | None = None,
        wall_temperatures: dict | None = None,
        thermostat: tuple[float, float] | None = None,
        seed: int | np.random.Generator | None = None,
        growth: float | None = None,
        **physics: Any,
    ) -> None:
        if box is None:
            raise TypeError("box is required: pass box=edmd2d.Box(width, height, periodic=...)")
        if not isinstance(box, Box):
            raise TypeError(f"box must be an edmd2d.Box, got {type(box).__name__}")
        pos = as_float_array("positions", positions, (None, 2))
        n = len(pos)
        if n == 0:
            raise ValueError("positions must hold at least one disk, got shape (0, 2)")
        vel = as_float_array("velocities", velocities, (n, 2))
        rad = per_disk("radii", radii, n)
        if (rad <= 0).any():
            raise ValueError(f"radii must be > 0; disks {indices_where(rad <= 0)} are not")
        mass = per_disk("masses", masses, n, allow_inf=True)
        if (mass <= 0).any():
            raise ValueError(f"masses must be > 0; disks {indices_where(mass <= 0)} are not")
        tiny = mass < np.finfo(np.float64).tiny
        if tiny.any():  # (1 / m would overflow, and the velocities become NaN)
            raise ValueError(f"masses must be at least {np.finfo(np.float64).tiny:.3g} (a "
                             f"normal float64, whose inverse is finite); disks "
                             f"{indices_where(tiny)} are not")
        with about("walls"):
            wall_list = as_walls(walls)
        t0 = as_float_array("time", time, ())
        with about("species"):
            spec = _models.as_species(species, n)
        with about("open_walls"):
            wall_open = np.zeros(len(wall_list), bool)
            if isinstance(open_walls, (str, bytes)) or not isinstance(open_walls, Iterable):
                raise TypeError(f"open_walls must be an iterable of segment indices, "
                                f"got {open_walls!r}")
            for index in open_walls:
                k = as_count("open_walls", index)
                if k >= len(wall_list):
                    raise ValueError(f"open_walls must name wall segments (0 to "
                                     f"{len(wall_list) - 1}), got {k}")
                wall_open[k] = True
        system = _physics.System(box, len(wall_list), rad, vel, mass, spec, float(t0),
                                 walls=tuple(wall_list))
        gravity_family = _physics.Gravity.check(system, gravity=gravity)
        g = None if gravity_family is None else gravity_family.g
        growth_family = _physics.Growth.check(system, growth=growth)
        with about("positions"):
            pos = _checks.check_in_box(box, pos, rad)
        with about("walls"):
            _checks.check_walls_in_box(box, wall_list)
        _checks.check_room(box, vel, rad)
        _checks.check_periodic_room(box, rad)
        cell_size = _checks.as_cell_size(cell_size, rad)
        contact = _physics.Restitution.check(system, restitution=restitution,
                                             wall_restitution=wall_restitution, tc=tc)
        model = _state.build_model(
            system, seed, contact,
            _physics.HeatedWalls.check(system, wall_temperatures=wall_temperatures),
            _physics.Thermostat.check(system, thermostat=thermostat))
        if growth_family is not None:
            growth_family.check_combination(model, g)
        families = _physics.check_registered(
            dataclasses.replace(system, gravity=g, inelastic=not contact.elastic), physics)
        _checks.check_grid(grid, rad, cell_size)
        self._state = _state.EngineState(
            box, wall_list, pos, vel, rad, mass, float(t0),
            species=None if species is None else spec, model=model, gravity=g,
            growth=growth_family, cell_size=cell_size, families=families,
            wall_open=wall_open, grid=grid)

    def __len__(self) -> int:
        """The number of disks."""
        return len(self._state.S)

    def __repr__(self) -> str:
        state = self._state
        return (
            f"Simulation(n={len(self)}, time={state.time:.6g}, box={state.box!r}, "
            f"walls={len(state.walls)}, collisions={int(state.counts[_layout.C_COLLISIONS])})"
        )

    @property
    def n(self) -> int:
        """Number of disks."""
        return len(self._state.S)

    @property
    def time(self) -> float:
        """The simulation clock."""
        return self._state.time

    @property
    def positions(self) -> np.ndarray:
        """Disk centres at :attr:`time`, shape (N, 2), a copy (wrapped into the box)."""
        return self._state.to_user(self._state.positions())

    @positions.setter
    def positions(self, positions) -> None:
        self.set_positions(positions)

    @property
    def resting(self) -> np.ndarray:
        """Which disks are at rest, shape (N,), bool (a read-only copy): disks that came
        to rest under gravity (see :class:`edmd2d.physics.Resting`); all ``False``
        where disks do not come to rest."""
        support = _layout.support_view(self._state.S)
        return self._state.to_user((support & _layout.RESTING) != 0)

    @property
    def unwrapped_positions(self) -> np.ndarray:
        """Disk centres at :attr:`time` with periodic wraps undone, shape (N, 2).

        Differences of these between two times are true displacements (for diffusion
        studies); on walled axes they equal :attr:`positions`.
        """
        return self._state.to_user(self._state.unwrapped())

    @property
    def velocities(self) -> np.ndarray:
        """Disk velocities at :attr:`time`, shape (N, 2), a copy."""
        return self._state.to_user(self._state.velocities())

    @property
    def peculiar_velocities(self) -> np.ndarray:
        """Disk velocities at :attr:`time` relative to the flow of a sheared box,
        ``v - (rate (y - height / 2), 0)`` (see :class:`edmd2d.physics.Shear`), shape
        (N, 2), a copy; :attr:`velocities` without shear.  Temperatures and the kinetic
        part of the pressure are taken from them."""
        vel = self._state.velocities()
        shear = self._state.shear
        if shear is not None:
            y = self._state.positions()[:, 1]
            vel[:, 0] -= shear.rate * (y - 0.5 * self.box.height)
        return self._state.to_user(vel)

    @property
    def shear_offset(self) -> float:
        """How far the images above a sheared box are shifted along x at :attr:`time`,
        in ``[0, width)`` (0.0 without shear; see :class:`edmd2d.physics.Shear`): the
        image of a disk at ``(x, y)`` one box above is at ``(x + shear_offset, y +
        height)``, moving ``rate * height`` faster along x."""
        if self._state.shear is None:
            return 0.0
        return self._state.shear_offsets()[0] % self.box.width

    @property
    def radii(self) -> np.ndarray:
        """Disk radii at :attr:`time`, shape (N,), a copy (they change in time under
        :attr:`growth`)."""
        state = self._state
        return state.to_user(state.S[:, _layout.R] * state.growth_factor(state.time))

    @property
    def masses(self) -> np.ndarray:
        """Disk masses, shape (N,), a copy (``inf`` for immovable disks)."""
        return self._state.to_user(self._state.mass)

    @property
    def species(self) -> np.ndarray:
        """Each disk's species (int), shape (N,), a copy; all 0 unless given."""
        out = (np.zeros(len(self), np.int32) if self._state.species is None
               else self._state.species.copy())
        out.flags.writeable = False
        return out

    @property
    def restitution(self) -> np.ndarray:
        """Coefficient of normal restitution for each pair of species, shape (S, S),
        a copy: ``(1, 1)`` if one coefficient applies to every pair, all 1 for elastic
        disks."""
        if self._state.model is None:
            n_species = int(self.species.max()) + 1
            out = np.ones((n_species, n_species))
        else:
            out = self._state.model.table.copy()
        out.flags.writeable = False
        return out

    @property
    def wall_restitution(self) -> float:
        """Coefficient of normal restitution against box walls and wall segments."""
        return 1.0 if self._state.model is None else self._state.model.wall

    @property
    def tc(self) -> float | None:
        """The TC-model duration (see :mod:`edmd2d.models`); ``None`` for elastic disks."""
        return None if self._state.model is None else self._state.model.tc

    @property
    def box(self) -> Box:
        """The container."""
        return self._state.box

    @property
    def walls(self) -> tuple[Wall, ...]:
        """The wall segments."""
        return self._state.walls

    @property
    def wall_positions(self) -> np.ndarray:
        """Where the wall segments are at :attr:`time`, shape (S, 2, 2): each segment's
        start and end point (moved by its motion, if it moves: see the keyword
        ``wall_motions``)."""
        wa, wb = self._state.wall_ends()
        return np.stack([wa, wb], axis=1)

    @property
    def open_walls(self) -> np.ndarray:
        """Which wall segments are open (:meth:`open_wall`), shape (S,), a read-only
        copy."""
        out = self._state.wall_open.copy()
        out.flags.writeable = False
        return out

    def open_wall(self, k: int) -> None:
        """Open wall segment ``k`` at the current time: disks pass through it as if it
        were not there (a silo's outlet opening under a filled bed).

        Parameters
        ----------
        k : int
            The segment's index in :attr:`walls`.

        Raises
        ------
        TypeError, ValueError
            For an index that is not an integer or names no segment; the
            simulation is then left unchanged.

        Notes
        -----
        The segment keeps its index, its tallies (:meth:`wall_heat`, the forces of
        :func:`edmd2d.measurements.measure`) and its settings, and
        :meth:`close_wall` closes it again.  Every disk at rest wakes (the segment
        may have held some; the others settle again at once), and every event is
        predicted afresh.  Opening an open segment changes nothing.
        """
        k = self._wall_index(k)
        if not self._state.wall_open[k]:
            self._state.set_wall_open(k, True)

    def close_wall(self, k: int) -> None:
        """Close wall segment ``k`` again (see :meth:`open_wall`) at the current time.

        Parameters
        ----------
        k : int
            The segment's index in :attr:`walls`.

        Raises
        ------
        TypeError, ValueError
            For an index that is not an integer or names no segment, or for disks
            that overlap the segment (they would be inside a wall): the simulation is
            then left unchanged.
        """
        k = self._wall_index(k)
        state = self._state
        if not state.wall_open[k]:
            return
        start, end = self.wall_positions[k]  # (where it is now: it may move)
        dist = _gaps._segment_distance(self.positions, start, end, state.box)
        rad = self.radii
        inside = dist < rad * (1.0 - _checks.OVERLAP_TOL)
        if inside.any():
            raise ValueError(f"close_wall({k}): disks {indices_where(inside)} overlap "
                             f"walls[{k}]; close it when they have left it")
        state.set_wall_open(k, False)

    def _wall_index(self, k: int) -> int:
        """``k`` checked as the index of a wall segment."""
        k = as_count("k", k)
        if k >= len(self._state.walls):
            raise ValueError(f"k must name a wall segment (0 to "
                             f"{len(self._state.walls) - 1}), got {k}")
        return k

    @property
    def counts(self) -> Counts:
        """Event counts since creation (see :class:`Counts`)."""
        c = self._state.counts
        coll, wall, cross = (int(c[_layout.C_COLLISIONS]), int(c[_layout.C_WALL]),
                             int(c[_layout.C_CROSSINGS]))
        kicks = int(c[_layout.C_KICKS])
        return Counts(coll, wall, cross, coll + wall + cross + kicks, int(c[_layout.C_STALE]),
                      kicks, int(c[_layout.C_RESTS]), int(c[_layout.C_WAKES]))

    def kinetic_energy(self) -> float:
        """Total kinetic energy of the movable disks, ``sum m v^2 / 2``.

        Returns
        -------
        float
        """
        movable = self._state.invm > 0
        vel = self._state.velocities()[movable]
        return float(0.5 * dot(self._state.mass[movable], np.einsum("ij,ij->i", vel, vel)))

    def wall_heat(self) -> np.ndarray:
        """Kinetic energy the heated walls gave to the disks since creation (negative:
        they took it), shape (4 + S,): the box walls x=0, x=width, y=0, y=height, then
        each wall segment; 0 for walls that are not heated.

        Returns
        -------
        numpy.ndarray, shape (4 + S,)
        """
        return np.concatenate([self._state.acc[_layout.A_HEAT_BOX:_layout.A_HEAT_BOX + 4],
                               self._state.wacc[:, _layout.W_HEAT]])

    def wall_work(self) -> np.ndarray:
        """The work each wall segment has done on the disks since creation, shape (S,):
        ``J.u`` summed over its contacts (``J`` the impulse it gave, ``u`` its velocity),
        0 for a segment that never moved.  ``total_energy() + dissipated_energy()``
        minus ``wall_work().sum()`` stays constant to rounding.

        Returns
        -------
        numpy.ndarray, shape (S,)
        """
        return self._state.wacc[:, _layout.W_WORK].copy()

    def thermostat_energy(self) -> float:
        """Kinetic energy the thermostat's redraws gave to the disks since creation
        (negative: they took it).  ``total_energy() + dissipated_energy()`` minus this and
        ``wall_heat().sum()`` stays constant to rounding.

        Returns
        -------
        float
        """
        return float(self._state.acc[_layout.A_THERMOSTAT])

    @property
    def thermostat(self) -> tuple[float, float] | None:
        """The Andersen thermostat's ``(kT, rate per disk)``, or ``None``."""
        return None if self._state.model is None else self._state.model.thermostat

    @property
    def wall_temperatures(self) -> dict:
        """The heated walls, ``{wall: kT}`` (box walls by name: ``"left"``,
        ``"right"``, ``"bottom"``, ``"top"``; segments by index); empty if none."""
        if self._state.model is None:
            return {}
        return {(BOX_WALLS[k] if k < 4 else k - 4): float(t)
                for k, t in enumerate(self._state.model.wall_kt) if t > 0.0}

    def rescale_temperature(self, temperature: float) -> None:
        """Scale the velocities relative to the centre of mass so that the kinetic
        temperature (:func:`edmd2d.measurements.kinetic_temperature`) becomes
        ``temperature``; the total momentum is kept.  In a sheared box the peculiar
        velocities are scaled (:attr:`peculiar_velocities`), and the flow kept.

        The simple thermostat of compressions and equilibrations, applied at the times
        the caller chooses (between ``advance`` calls).

        Parameters
        ----------
        temperature : float
            The new ``kT``, > 0.

        Raises
        ------
        ValueError
            For a temperature that is not finite and > 0, or a state that no scaling
            brings there (every movable disk at rest relative to the centre of mass,
            or a centre-of-mass motion along an axis without momentum conservation
            that alone is hotter); the simulation is then left unchanged.

        Examples
        --------
        >>> import edmd2d as ed
        >>> sim = ed.make_gas(100, 0.3, seed=1).advance(until=1.0)
        >>> sim.rescale_temperature(2.0)
        >>> round(ed.kinetic_temperature(sim), 12)
        2.0
        """
        kt = float(as_float_array("temperature", temperature, ()))
        if not kt > 0.0:
            raise ValueError(f"temperature must be > 0, got {kt}")
        dof, conserved = _measurements.degrees_of_freedom(self)
        vel = self.peculiar_velocities
        movable = np.isfinite(self.masses)
        mass = self.masses[movable]
        centre = weighted_sum(mass, vel[movable]) / mass.sum()
        thermal = vel[movable] - centre
        twice_thermal = float(dot(mass, np.einsum("ij,ij->i", thermal, thermal)))
        # kinetic_temperature counts the centre-of-mass motion along the axes where
        # momentum is not conserved as heat: scaling the velocities about the centre
        # of mass by s gives kT = (M c_free^2 + s^2 sum m |v - c|^2) / f.
        free = mass.sum() * sum(float(centre[a]) ** 2 for a in range(2) if not conserved[a])
        if not (twice_thermal > 0.0 and dof > 0 and kt * dof > free):
            raise ValueError(
                f"no velocities about the centre of mass give kT={kt}: the thermal "
                "motion is zero, or the centre of mass alone carries more (set the "
                "velocities instead)")
        new = vel.copy()
        new[movable] = centre + thermal * math.sqrt((kt * dof - free) / twice_thermal)
        if self._state.shear is not None:
            new += self.velocities - vel  # (the flow, kept)
        self.set_velocities(new)

    def dissipated_energy(self) -> float:
        """Kinetic energy lost in inelastic collisions since creation (0 for elastic
        disks): ``kinetic_energy() + dissipated_energy()`` stays constant to rounding
        (while no immovable disk moves; under gravity ``total_energy()`` takes the place
        of ``kinetic_energy()``).  Where disks come to rest (:class:`edmd2d.physics.Resting`)
        it includes the kinetic energy of the disks at rest (given back when they
        wake) and less the small lifts that keep a disk from pressing on a body at rest.
        For rough disks it includes what their collisions take from the rotation too:
        ``total_energy()`` (with the rotational energy) plus it stays constant.

        Returns
        -------
        float
        """
        return float(self._state.acc[_layout.A_DISSIPATED])

    def momentum(self) -> np.ndarray:
        """Total momentum of the movable disks.

        Returns
        -------
        numpy.ndarray, shape (2,)
        """
        movable = self._state.invm > 0
        return weighted_sum(self._state.mass[movable], self._state.velocities()[movable])

    @property
    def families(self) -> dict:
        """The physics families registered with :func:`edmd2d.physics.register` that
        this simulation has, by name (a copy of the mapping; the families are frozen).

        Returns
        -------
        dict of str to edmd2d.physics.Family
        """
        return dict(self._state.families)

    @property
    def gravity(self) -> np.ndarray:
        """The uniform acceleration of the movable disks, shape (2,), a copy (zero
        without gravity)."""
        out = np.zeros(2) if self._state.gravity is None else self._state.gravity.copy()
        out.flags.writeable = False
        return out

    def set_gravity(self, gravity: ArrayLike) -> None:
        """Change gravity at the current time: tilt a bed, or make it heavier.

        Parameters
        ----------
        gravity : array_like, shape (2,)
            The new uniform acceleration of the movable disks: finite, not zero.

        Raises
        ------
        TypeError, ValueError
            For a gravity of the wrong shape, not finite or zero, or a simulation
            created without gravity (its engine flies disks on straight lines: create
            it with ``gravity=``); for disks that would rest on a box wall with zero
            normal velocity that the new gravity presses them into, as the constructor
            refuses them.  The simulation is then left unchanged.

        Notes
        -----
        Every disk at rest wakes (:class:`edmd2d.physics.Resting`, whose criteria
        follow the new magnitude) and every event is predicted afresh.  The
        positions and velocities do not change, so the potential energy jumps:
        :meth:`gravity_work` books the jump, and ``total_energy() +
        dissipated_energy() - gravity_work()`` stays constant to rounding.  Under
        gravity not along a box axis, a disk sliding on a box wall and one sliding on
        another can press on each other at one instant for ever, and the run then
        stops with an inelastic collapse (see ``docs/gravity-and-heat.md``).

        Examples
        --------
        Tilting a bed by 10 degrees:

        >>> import math
        >>> import edmd2d as ed
        >>> sim = ed.make_gas(100, 0.2, periodic=False, gravity=(0.0, -1.0),
        ...                   restitution=0.9, seed=1)
        >>> a = math.radians(10.0)
        >>> sim.set_gravity((math.sin(a), -math.cos(a)))
        >>> bool(sim.gravity[0] > 0.0)
        True
        """
        state = self._state
        if state.gravity is None:
            with about("gravity"):
                raise ValueError("this simulation was created without gravity (its "
                                 "engine flies disks on straight lines): create it with "
                                 "gravity=... to change gravity later")
        family = _physics.Gravity.check(gravity=gravity)
        if family is None:
            with about("gravity"):
                raise ValueError("gravity must not be zero once a simulation has it "
                                 "(set the velocities of a new simulation without "
                                 "gravity instead)")
        g = family.g
        # The velocities the disks at rest resume when they wake, for the check of the
        # disks that rest on box walls.
        vel = self.velocities.copy()
        if state.rest_frozen is not None:
            at_rest = self.resting
            vel[at_rest] = state.to_user(state.rest_frozen)[at_rest]
        rest = _checks.resting(state.box, state.walls_holding_still(), g, self.positions, vel,
                               self.radii, self.masses, state.model, "gravity")
        families = dict(state.families)
        if "resting" in families:
            old = families["resting"]
            families["resting"] = type(old).of(old.height, float(np.hypot(*g)),
                                               float(self.radii.min()))
        state.set_gravity(g, rest, families)

    def gravity_work(self) -> float:
        """Potential energy that changes of gravity (:meth:`set_gravity`) gave the
        disks since creation (negative: took from them): ``total_energy() +
        dissipated_energy()`` minus this stays constant to rounding.

        Returns
        -------
        float
        """
        return float(self._state.acc[_layout.A_GRAVITY])

    def potential_energy(self) -> float:
        """Potential energy of the movable disks in the gravity field,
        ``-sum m g.r`` (zero at the origin), with :attr:`unwrapped_positions` so that
        it stays continuous across periodic wraps; 0 without gravity.

        Returns
        -------
        float
        """
        if self._state.gravity is None:
            return 0.0
        state = self._state
        movable = state.invm > 0
        return float(-dot(state.mass[movable], dot(state.unwrapped()[movable], state.gravity)))

    def total_energy(self) -> float:
        """``kinetic_energy() + potential_energy()`` (and ``rotational_energy()`` for
        rough disks): constant to rounding for elastic disks (while no immovable disk
        moves); with inelastic collisions (or rough ones that are neither smooth nor
        perfectly rough) it decreases by :meth:`dissipated_energy`.

        Returns
        -------
        float
        """
        total = self.kinetic_energy() + self.potential_energy()
        return total + self.rotational_energy() if self._state.rough_w is not None else total

    @property
    def angular_velocities(self) -> np.ndarray:
        """Rough disks (:class:`edmd2d.physics.Rough`): each disk's angular velocity,
        counter-clockwise (zero for smooth disks), read-only.

        Returns
        -------
        numpy.ndarray, shape (N,)
        """
        state = self._state
        w = state.rough_w
        return state.to_user(np.zeros(len(state.S)) if w is None else w.copy())

    @property
    def angles(self) -> np.ndarray:
        """Rough disks: each disk's angle, turned from 0 at the start at its angular
        velocity (zero for smooth disks), read-only.

        Returns
        -------
        numpy.ndarray, shape (N,)
        """
        state = self._state
        if state.rough_w is None:
            return state.to_user(np.zeros(len(state.S)))
        return state.to_user(state.angles())

    def set_angular_velocities(self, angular_velocities: ArrayLike) -> None:
        """Rough disks: replace every angular velocity at the current time (each
        angle read forward to now first; immovable disks do not turn and keep 0).

        Parameters
        ----------
        angular_velocities : float or array_like, shape (N,)
            Counter-clockwise, in the user's disk order; one number for all.

        Raises
        ------
        ValueError
            For smooth disks, or values that are not finite or of the wrong shape.
            The simulation is left unchanged.

        Notes
        -----
        No predicted event changes: contact times do not depend on the spins.

        Examples
        --------
        >>> import edmd2d as ed
        >>> sim = ed.make_gas(4, 0.2, seed=0, tangential_restitution=1.0)
        >>> sim.set_angular_velocities([1.0, 0.0, -1.0, 2.0])
        >>> sim.angular_velocities.tolist()
        [1.0, 0.0, -1.0, 2.0]
        """
        state = self._state
        if state.rough_w is None:
            raise ValueError("the disks are smooth and do not turn: angular velocities "
                             "need rough disks (tangential_restitution)")
        state.set_angular_velocities(per_disk("angular_velocities", angular_velocities,
                                              len(self)))

    def rotational_energy(self) -> float:
        """The rotational kinetic energy ``sum I w^2 / 2`` (zero for smooth disks).

        Returns
        -------
        float
        """
        bundle = self._state.rough_bundle()
        if bundle is None:
            return 0.0
        movable = bundle.inv_inertia > 0
        return float(0.5 * np.sum(bundle.w[movable] ** 2 / bundle.inv_inertia[movable]))

    def set_positions(self, positions: ArrayLike) -> None:
        """Move every disk to new positions at the current time (``sim.positions = ...``
        does the same).

        Parameters
        ----------
        positions : array_like, shape (N, 2)
            The new centres, checked as the constructor checks them: inside the box,
            no overlap between disks, with their periodic images or with a wall.

        Raises
        ------
        TypeError, ValueError
            For bad input, naming the offending disks; the simulation is left
            unchanged.

        Notes
        -----
        Velocities, counts, accumulated impulses and the clock are kept; the grid and
        every predicted event are rebuilt, and :attr:`unwrapped_positions` start
        afresh from the new positions.
        """
        pos = np.array(as_float_array("positions", positions, (len(self), 2)))
        # The constructor's checks, on a throwaway simulation of the same disks: it
        # refuses what the constructor refuses, and nothing of self changes until
        # they have passed.
        # (Any grid serves the checks: the default one, also when the disks have grown
        # past a cell_size given at construction.)
        # (Sheared, through the sliding boundary at the present offset.)
        shear = self._state.shear
        sheared = ({} if shear is None else
                   {"shear_rate": shear.rate, "shear_offset": self.shear_offset})
        Simulation(pos, self.velocities, self.radii, self.masses, box=self._state.box,
                   walls=self._state.walls, open_walls=np.flatnonzero(self._state.wall_open),
                   time=self._state.time, **sheared)
        state = self._state
        pos = _checks.check_in_box(state.box, pos, self.radii)  # (x = width becomes 0 if periodic)
        state.place(pos, _checks.resting(state.box, state.walls_holding_still(), state.gravity, pos,
                                         self.velocities, self.radii, self.masses,
                                         state.model))

    def set_velocities(self, velocities: ArrayLike) -> None:
        """Replace all velocities at the current time (e.g. to rescale the temperature).

        Parameters
        ----------
        velocities : array_like, shape (N, 2)
            The new velocities, in the user's disk order.

        Raises
        ------
        TypeError, ValueError
            As the constructor: a wrong shape, non-finite values, a moving disk that
            fills the box between two walls.  The simulation is left unchanged.

        Notes
        -----
        Positions, counts and the clock are kept; every predicted event is recomputed.

        Examples
        --------
        Doubling the temperature (speeds times sqrt 2):

        >>> import edmd2d as ed
        >>> sim = ed.make_gas(100, 0.3, temperature=1.0, seed=1)
        >>> sim.set_velocities(sim.velocities * 2 ** 0.5)
        >>> round(ed.kinetic_temperature(sim), 12)
        2.0
        """
        vel = as_float_array("velocities", velocities, (len(self), 2))
        state = self._state
        _checks.check_room(state.box, vel, self.radii)
        state.set_velocities(vel, _checks.resting(state.box, state.walls_holding_still(),
                                                  state.gravity, self.positions, vel,
                                                  self.radii, self.masses, state.model,
                                                  "velocities"))

    def measure(self, duration: float, **kwargs: Any) -> _measurements.Measurement:
        """Run for ``duration`` and return the measurements over that window.

        Parameters
        ----------
        duration : float
            Length of the window, > 0.
        **kwargs
            The options of :func:`edmd2d.measurements.measure` (``blocks``, ``area``,
            ``progress``), which describes the quantities.

        Returns
        -------
        Measurement
        """
        return _measurements.measure(self, duration, **kwargs)

    def stream_events(self, callback: Callable[[np.ndarray], object] | None,
                      capacity: int = 1 << 16) -> None:
        """Deliver every processed event to ``callback``, in batches, without loss.

        Parameters
        ----------
        callback : callable or None
            Called as ``callback(batch)`` with a NumPy structured array of up to
            ``capacity`` events in time order, fields ``time``, ``kind`` (the names of
            :data:`EVENT_KINDS`: ``"disk"``, ``"wall"`` (a segment), ``"box"``,
            ``"thermostat"``, and where disks come to rest (:class:`edmd2d.physics.Resting`)
            ``"rest"`` and ``"wake"``), ``disk``, ``partner`` (a disk, a segment
            index, a box wall 0-3 for x=0, x=width, y=0, y=height, or -1 for a
            thermostat redraw, a rest or a wake) and ``impulse`` (the momentum change
            of a movable disk of the event; for a rest or a wake the momentum the disk
            loses or regains).  Cell crossings are bookkeeping, not streamed.
            ``None`` stops the stream.
        capacity : int, default 65536
            Events per batch: when the engine's buffer is full it returns to Python
            for ``callback``, then goes on; the last batch of a call of
            :meth:`advance` comes at its end.

        Notes
        -----
        With no stream the engine records nothing and costs nothing more.  The
        callback is not part of the state: copies, pickles and checkpoints do not
        stream.

        Rests and wakes come at the time of what caused them: the wakes an impact
        causes before the collision, the rests that follow a collision after it,
        every disk woken by :meth:`set_velocities`, :meth:`set_positions`,
        :meth:`set_gravity` or :meth:`open_wall` at that moment.  Replaying them
        gives :attr:`resting` at every event, and their numbers are
        ``counts.rests`` and ``counts.wakes``.

        Examples
        --------
        >>> import edmd2d as ed
        >>> sim = ed.make_gas(100, 0.3, seed=1)
        >>> batches = []
        >>> sim.stream_events(batches.append, capacity=50)
        >>> _ = sim.advance(collisions=120)
        >>> sum(b["kind"].tolist().count("disk") for b in batches)
        120
        """
        if callback is not None:
            if not callable(callback):
                raise TypeError(f"callback must be callable or None, got {callback!r}")
            capacity = as_count("capacity", capacity, minimum=1)
        self._state.stream(callback, capacity)

    @property
    def growth(self) -> float | None:
        """The growth rate of the radii (see :meth:`set_growth`), ``None`` if they are
        fixed."""
        growth = self._state.growth_bundle()
        return None if growth is None else growth.rate

    def set_growth(self, rate: float | None) -> None:
        """Let every radius grow linearly in time from now on, or stop it growing.

        Parameters
        ----------
        rate : float or None
            ``>= 0`` per unit time: each radius grows at ``rate`` times its present
            value, ``r_i(t) = r_i(now) (1 + rate (t - now))``.  ``None`` (or 0) keeps
            the radii fixed at their present values.

        Raises
        ------
        TypeError, ValueError
            For a rate that is negative or not finite, or a simulation whose physics
            growth does not combine with (gravity, restitution below 1, heated walls
            or a thermostat); the simulation is left unchanged.

        Notes
        -----
        The contacts of growing disks reverse the rate at which their gap closed,
        so that they part, which heats the system: rescale the temperature at
        intervals (:meth:`rescale_temperature`), as :func:`edmd2d.compress` does.
        The grid is rebuilt whenever the disks have grown by 10%; a run that would
        take the largest disk past the size of the box is refused.
        """
        growth = _physics.Growth.check(growth=rate)
        if growth is not None:
            growth.check_combination(self._state.model, self._state.gravity)
            if "rough" in self._state.families:
                with _physics.about("growth"):
                    raise ValueError("growth does not combine with rough disks (their "
                                     "moments of inertia follow their radii)")
        self._state.set_growth(growth)

    def advance(self, until: float | None = None, collisions: int | None = None,
                progress: _progress.ProgressArg = False) -> Simulation:
        """Run the simulation forward, event by event, in time order.

        Parameters
        ----------
        until : float, optional
            Process every event up to and including this time, then let all disks
            fly on to it; afterwards ``time == until``.  Must not be earlier than
            :attr:`time`.
        collisions : int, optional
            Stop right after this many further disk-disk collisions; :attr:`time` is
            then the time of the last one.  ``0`` does nothing.  With ``until`` too,
            the run stops at whichever comes first.
        progress : bool or tqdm bar, default False
            ``True`` shows a progress bar (:mod:`edmd2d.progress`) of the simulated
            time (or, with ``collisions`` alone, of the collisions) and the collisions
            per second; a tqdm bar passed in is advanced by the simulated time.

        Returns
        -------
        Simulation
            ``self``, so that calls can be chained.

        Raises
        ------
        TypeError, ValueError
            For missing or invalid arguments, or a run to a time at which the float64
            clock could no longer tell a disk's cell crossings apart (a speed far too
            large for the time scale); the simulation is left unchanged.
        RuntimeError
            If two immovable disks meet, or a moving immovable disk reaches a wall, or
            ``collisions`` is requested when no further event can ever happen, or an
            inelastic collapse that the TC model does not end.  The simulation then
            stands at the last event processed before the problem.

        Examples
        --------
        >>> import edmd2d as ed
        >>> sim = ed.make_gas(100, 0.3, seed=1)
        >>> sim.advance(until=2.0).time
        2.0
        >>> sim.advance(collisions=50).counts.collisions >= 50
        True
        """
        if until is None and collisions is None:
            raise TypeError("advance() needs until= (a time) or collisions= (a count)")
        t_end = math.inf
        if until is not None:
            t_end = float(as_float_array("until", until, ()))
            if t_end < self._state.time:
                raise ValueError(
                    f"until={t_end} is earlier than the current time {self._state.time}; "
                    "simulations only run forward"
                )
        max_coll = np.iinfo(np.int64).max
        if collisions is not None:
            max_coll = as_count("collisions", collisions)
            if max_coll == 0:
                return self
        self._state.advance(t_end, max_coll, until is not None, progress)
        return self

    def run(self, until: float | None = None, collisions: int | None = None,
            operations: Iterable[_operations.Operation] = (),
            progress: _progress.ProgressArg = False) -> Simulation:
        """Advance like :meth:`advance`, firing ``operations`` on the way, each when
        its trigger says (see :mod:`edmd2d.operations`).

        Parameters
        ----------
        until, collisions
            As for :meth:`advance`.
        operations : sequence of edmd2d.operations.Operation
        progress : bool, default False
            A progress bar over the run.

        Returns
        -------
        Simulation
            ``self``.

        Examples
        --------
        >>> import edmd2d as ed
        >>> from edmd2d.operations import Callback, Every
        >>> sim = ed.make_gas(100, 0.3, seed=1)
        >>> energies = []
        >>> _ = sim.run(until=3.0, operations=[
        ...     Callback(lambda s: energies.append(s.kinetic_energy()), Every(dt=1.0))])
        >>> len(energies)
        3
        """
        return _operations.run(self, until=until, collisions=collisions,
                               operations=operations, progress=progress)

    # ------------------------------------------------------------------ copies
    def __getstate__(self) -> dict:
        """For pickle and copies: the engine's state, which pickles itself."""
        return {"_state": self._state}

    def __setstate__(self, state: dict) -> None:
        if set(state) != {"_state"}:
            raise ValueError(
                "this Simulation was pickled by an edmd2d that kept its state in format "
                f"version 1; this edmd2d reads version {_state.VERSION}: build the "
                "simulation again, or load the pickle with the edmd2d that wrote it")
        vars(self).update(state)

    def __copy__(self) -> Simulation:
        """``copy.copy`` gives an independent copy too (as ``copy.deepcopy``): two
        simulations sharing some of their arrays would corrupt each other."""
        return copy.deepcopy(self)


def _engine_attribute(name: str) -> property:
    """A private attribute of ``Simulation`` that is the engine state's ``name``."""
    return property(lambda self: getattr(self._state, name),
                    lambda self, value: setattr(self._state, name, value),
                    doc=f"The engine state's ``{name}`` (``edmd2d._state.EngineState``).")


# The engine's tables, grid, queue and hooks, under the private names by which the
# package's other modules, the tests and the benchmarks reach them through a simulation.
for _name in ("S", "E", "stamp", "nxt", "prv", "qt", "tcand", "invm", "mass", "order",
              "image", "hv", "qhead", "qs", "qf", "gi", "gf", "head", "wstart", "counts",
              "acc", "wacc", "model", "gravity", "time", "grid_dmax", "reorder_every",
              "accumulators", "record_events", "recorded_events", "reorder", "queue_args",
              "outgrow_diameter"):
    setattr(Simulation, "_" + _name, _engine_attribute(_name))
del _name
