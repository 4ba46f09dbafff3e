"""The :class:`Simulation`: owns the state, validates input, drives the compiled engine."""

from __future__ import annotations

import copy
import math
import time as _time
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from . import _operations
from . import measurements as _measurements
from . import models as _models
from . import physics as _physics
from . import progress as _progress
from ._engine import aligned_rows
from ._engine import flight as _flight
from ._engine import grid as _grid
from ._engine import layout as _layout
from ._engine import loop as _loop
from ._engine import overlap as _overlap
from ._engine import queue as _queue
from ._facade import SimulationBase
from ._sums import dot, weighted_sum
from ._validate import about, as_count, as_float_array, as_generator, indices_where, per_disk
from .geometry import BOX_WALL_EQUATIONS, BOX_WALLS, MAX_LENGTH, Box, Wall, as_walls

__all__ = ["Simulation", "Counts"]

# Relative tolerance for "touching is fine, overlapping is not" in the input checks:
# lattices built by arithmetic touch to within rounding, and the engine copes with a
# rounding-sized overlap (an approaching overlapped pair collides at once).
_OVERLAP_TOL = 1e-9
# Margin by which a cell exceeds the largest diameter, so that a centre that is a
# rounding error outside its logical cell is still seen by its neighbours.
_CELL_MARGIN = 1e-9
# Events per engine call; between calls Python regains control, so that Ctrl-C stops a
# run within a fraction of a second (2^18 events: 0.1-0.5 s at 0.5-2 M events/s),
# leaving it at the last event processed.
_CHUNK_EVENTS = 1 << 18
# Events in a row at one instant after which disks count as wedged (no configuration
# needs more: a row of simultaneous contacts, a lattice crossing its cells together):
# per disk, and at least as many as this minimum.
_WEDGED_EVENTS_PER_DISK = 64
_WEDGED_EVENTS_MIN = 1 << 20
# Events per engine call when a progress bar is shown (a few ms at 10^6 coll/s).
_PROGRESS_EVENTS = 1 << 16
# Systems at least this large are kept sorted in memory along a Z-order curve over the
# grid cells, re-sorted every _REORDER_EVENTS_PER_DISK * N events: disks near in space
# then sit near in memory, which matters once the state no longer fits in the caches.
_REORDER_MIN_DISKS = 1024
_REORDER_EVENTS_PER_DISK = 20
# Under growth the grid is built for a largest diameter this much above the current one,
# and rebuilt when the disks reach it (an O(N) rebuild every 10% of growth).
_GROWTH_GRID_SLACK = 1.1
# The engine's physics families of elastic disks between reflecting walls: none.
_NO_MODEL = _layout.ModelFamilies(None, None, None, None)

_KIND_NAMES = {_layout.DISK: "disk", _layout.SEGMENT: "wall", _layout.BOX: "box",
               _layout.KICK: "thermostat"}
_KIND_CODES = np.array(sorted(_KIND_NAMES))
#: The names of the streamed event kinds (:meth:`Simulation.stream_events`).
EVENT_KINDS = tuple(_KIND_NAMES[k] for k in _KIND_CODES)
#: The fields of a streamed batch of events.
EVENT_DTYPE = np.dtype([("time", "f8"), ("kind", "U10"), ("disk", "i8"),
                        ("partner", "i8"), ("impulse", "f8")])


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
        Grid bookkeeping events: a disk centre moved into another cell.
    events : int
        All processed events: the sum of the three above and of ``redraws``.
    stale : int
        Predictions found invalid when they came due (the partner had changed course)
        and recomputed; not physical events, not included in ``events``.
    redraws : int
        Velocities redrawn by the thermostat.
    """

    collisions: int
    wall_collisions: int
    cell_crossings: int
    events: int
    stale: int
    redraws: int = 0


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
    time : float, default 0.0
        The clock at the given state.
    cell_size : float, optional
        Side of the grid cells (advanced).  Must be at least the largest diameter;
        the default is that bound, widened in dilute systems to keep at most about
        two cells per disk.
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
        positions,
        velocities,
        radii,
        masses=1.0,
        box: Box | None = None,
        walls: Iterable[Wall] = (),
        *,
        time: float = 0.0,
        cell_size: float | None = None,
        species=None,
        restitution=1.0,
        wall_restitution=1.0,
        tc: float | None = None,
        gravity=None,
        wall_temperatures=None,
        thermostat=None,
        seed=None,
        growth=None,
        **physics,
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
        self._box = box
        self._walls = tuple(wall_list)
        with about("species"):
            spec = _models.as_species(species, n)
        system = _physics.System(box, len(wall_list), rad, vel, mass, spec, float(t0))
        g = _physics.Gravity.check(system, gravity=gravity)
        self._gravity = None if g is None else g.g
        growth = _physics.Growth.check(system, growth=growth)
        with about("positions"):
            pos = self._check_in_box(pos, rad)
        with about("walls"):
            self._check_walls_in_box()
        self._check_room(vel, rad)

        dmax = 2.0 * float(rad.max())
        for axis, length in (("width", box.width), ("height", box.height)):
            periodic = box.periodic[0 if axis == "width" else 1]
            if periodic and length < dmax:
                raise ValueError(
                    f"box {axis} {length} is smaller than the largest disk diameter {dmax}: "
                    "on a periodic axis a disk would overlap its own image"
                )
        if cell_size is not None:
            cell_size = float(as_float_array("cell_size", cell_size, ()))
            if not cell_size >= dmax:
                raise ValueError(
                    f"cell_size must be at least the largest diameter {dmax}, got {cell_size}"
                )
        model = _build_model(
            system, seed,
            _physics.Restitution.check(system, restitution=restitution,
                                       wall_restitution=wall_restitution, tc=tc),
            _physics.HeatedWalls.check(system, wall_temperatures=wall_temperatures),
            _physics.Thermostat.check(system, thermostat=thermostat))
        if growth is not None:
            growth.check_combination(model, self._gravity)
        self._families = _physics.check_registered(system, physics)

        # Per-disk state and bookkeeping, one 64-byte row each in S and E (see
        # _engine/layout.py for the columns).
        state = aligned_rows(n, _layout.N_STATE, np.float64)  # 64-byte rows, aligned
        state[:] = 0.0  # (also the spare bytes: the rows are compared bit for bit)
        state[:, _layout.X:_layout.Y + 1] = pos
        state[:, _layout.VX:_layout.VY + 1] = vel
        state[:, _layout.T] = float(t0)
        state[:, _layout.R] = rad
        # E: the bookkeeping table (cell, kept candidate, queue links and time).
        _, table, hv, qhead, qs, qf = _queue.allocate(n)
        self._mass = mass
        self._time = float(t0)
        # (The stamps start at 0.)
        vars(self).update(self._tables(state, table, hv, qhead, qs, qf))
        with np.errstate(divide="ignore"):
            self._invm[:] = np.where(np.isinf(mass), 0.0, 1.0 / mass)
        self._tcand[:] = np.inf
        # Image counters stay int64: a fast disk in a small periodic box can wrap more
        # than 2^31 times in a long run.
        self._image = np.zeros((n, 2), np.int64)
        if wall_list:
            self._wa = np.array([w.start for w in wall_list], np.float64)
            self._wb = np.array([w.end for w in wall_list], np.float64)
        else:
            self._wa = np.zeros((0, 2))
            self._wb = np.zeros((0, 2))
        # Each segment's impulses and contacts (layout.W_*), summed by the engine.
        self._wacc = np.zeros((len(wall_list), _layout.N_WACC))
        self._cell_size = cell_size
        self._growth = None if growth is None else np.array([growth.rate, float(t0)])
        self._build_grid(pos, self._grid_diameter(dmax), cell_size)
        with about("positions"):
            self._check_overlaps(pos, rad)
        _layout.support_view(state)[:] = self._resting(pos, vel, rad, mass, model)

        self._species = None if species is None else spec
        self._model = model
        self._counts = np.zeros(_layout.N_COUNTS, np.int64)
        self._acc = np.zeros(_layout.N_ACC, np.float64)
        self._set_log(0)
        self._listener = None  # (see stream_events; not part of the saved state)
        # Internal row k holds the user's disk order[k]; public getters translate.
        self._order = np.arange(n, dtype=np.int64)
        self._reorder_every = (
            _REORDER_EVENTS_PER_DISK * n if n >= _REORDER_MIN_DISKS else np.iinfo(np.int64).max
        )
        self._since_reorder = 0
        self._predict_all()
        if n >= _REORDER_MIN_DISKS:
            self._reorder()

    # ------------------------------------------------------------------ grid
    def _build_grid(self, pos: np.ndarray, dmax: float, cell_size: float | None) -> None:
        """(Re)build the grid for disks of largest diameter ``dmax`` at ``pos`` (stored
        positions, inside the box): the cell geometry, each disk's cell, the cells'
        lists and the wall segments listed per cell.  Cells are at least ``dmax`` wide
        (``cell_size``, if given, is at least that); the default widens them in dilute
        systems to keep at most about two cells per disk.  The kept candidates and the
        queue are not touched: predict every disk afresh after a rebuild.

        Under growth the grid holds until the largest diameter reaches ``dmax``
        (:meth:`_time_of_diameter` of it)."""
        self._grid_dmax = float(dmax)
        width, height = self._box.width, self._box.height
        side_min = dmax * (1.0 + _CELL_MARGIN)
        if cell_size is None:
            side = max(side_min, math.sqrt(width * height / (2.0 * len(pos))))
        else:
            side = max(cell_size, side_min)
        ncx = max(1, int(width // side))
        ncy = max(1, int(height // side))
        periodic = self._box.periodic
        self._gi = np.array([ncx, ncy, int(periodic[0]), int(periodic[1])], np.int64)
        self._gf = np.array([width, height, width / ncx, height / ncy], np.float64)
        self._head = np.empty(ncx * ncy, np.int32)
        _grid.build_cells(pos, self._gi, self._gf, self._E[:, _layout.CELL], self._head,
                          self._nxt, self._prv)
        reach = 0.5 * dmax + _CELL_MARGIN * (side + dmax)
        self._wstart, self._wwall, self._wsx, self._wsy = _grid.bucket_walls(
            self._wa, self._wb, self._gi, self._gf, reach
        )

    # ------------------------------------------------------------------ growth
    def _growth_factor(self, t: float) -> float:
        """The factor by which every radius at ``t`` exceeds its stored value (1 without
        growth; the engine's ``scan.growth_factor``)."""
        growth = self._growth_bundle()
        if growth is None:
            return 1.0
        return 1.0 + growth.rate * (t - growth.t0)

    def _grid_diameter(self, dmax: float) -> float:
        """The largest diameter to build the grid for, the current one being ``dmax``:
        that one, or under growth a margin above it (but within the box)."""
        if self._growth is None:
            return dmax
        return min(dmax * _GROWTH_GRID_SLACK, max(dmax, self._outgrow_diameter()))

    def _outgrow_diameter(self) -> float:
        """The largest diameter the box holds: a disk that wide would overlap its own
        periodic image, or fill the box between its walls."""
        return min(self._box.width, self._box.height) * (1.0 - _OVERLAP_TOL)

    def _time_of_diameter(self, diameter: float) -> float:
        """Under growth, the time at which the largest diameter reaches ``diameter``."""
        growth = self._growth_bundle()
        d0 = 2.0 * float(self._S[:, _layout.R].max())
        return growth.t0 + (diameter / d0 - 1.0) / growth.rate  # (rate > 0: _as_growth)

    def _regrid(self) -> None:
        """Under growth, once the largest diameter has reached the one the grid was
        built for: bring every disk to the current time, rebuild the grid for the
        disks' growth ahead and predict every disk afresh."""
        self._sync_all()
        dmax = 2.0 * float(self._S[:, _layout.R].max()) * self._growth_factor(self._time)
        self._build_grid(self._S[:, _layout.X:_layout.Y + 1], self._grid_diameter(dmax),
                         self._cell_size)
        self._predict_all()

    @property
    def growth(self) -> float | None:
        """The growth rate of the radii (see :meth:`set_growth`), ``None`` if they are
        fixed."""
        growth = self._growth_bundle()
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
            growth.check_combination(self._model, self._gravity)
        radii = self._S[:, _layout.R] * self._growth_factor(self._time)
        self._S[:, _layout.R] = radii
        self._growth = None if growth is None else np.array([growth.rate, self._time])
        if growth is None:
            self._predict_all()
        else:
            self._regrid()  # (a grid with room to grow)

    # ------------------------------------------------------------------ validation
    def _check_in_box(self, pos: np.ndarray, rad: np.ndarray) -> np.ndarray:
        box = self._box
        for axis, length in enumerate((box.width, box.height)):
            name = "xy"[axis]
            coord = pos[:, axis]
            outside = (coord < 0) | (coord > length)
            if outside.any():
                raise ValueError(
                    f"positions: disks {indices_where(outside)} lie outside the box "
                    f"(0 <= {name} <= {length})"
                )
            if box.periodic[axis]:
                coord[coord == length] = 0.0
            else:
                lo = coord < rad * (1 - _OVERLAP_TOL)
                hi = coord > length - rad * (1 - _OVERLAP_TOL)
                if (lo | hi).any():
                    raise ValueError(
                        f"positions: disks {indices_where(lo | hi)} overlap the box wall "
                        f"on the {name} axis (need radius <= {name} <= {length} - radius)"
                    )
        return pos

    def _check_room(self, vel: np.ndarray, rad: np.ndarray) -> None:
        """A disk as wide as the box between two walls cannot move across it: it would
        bounce from wall to wall with no time in between, without end."""
        box = self._box
        for axis, length in enumerate((box.width, box.height)):
            if box.periodic[axis]:
                continue
            stuck = (2.0 * rad >= length * (1 - _OVERLAP_TOL)) & (vel[:, axis] != 0.0)
            if stuck.any():
                name = "xy"[axis]
                raise ValueError(
                    f"velocities: disks {indices_where(stuck)} fill the box between its "
                    f"walls on the {name} axis (diameter >= {length}) and cannot move "
                    f"along {name}; their {name}-velocity must be 0"
                )

    def _resting(self, pos: np.ndarray, vel: np.ndarray, rad: np.ndarray,
                 mass: np.ndarray, model, what: str = "positions") -> np.ndarray:
        """Under gravity, the box walls each movable disk rests on (bits ``1 << side``,
        see ``layout.S_SUPPORT``): it touches the wall, with zero normal velocity, and
        gravity presses it into the wall.  An inelastic model with ``tc > 0`` holds such
        a disk on the wall (as it would put a disk to rest whose bounces shrink); any
        other model would make it bounce without end at one instant (a resting contact
        is not a motion of free flights and impulses): refused."""
        bits = np.zeros(len(pos), np.int32)
        g = self._gravity
        if g is None:
            return bits
        box = self._box
        movable = np.isfinite(mass)
        for axis, length in enumerate((box.width, box.height)):
            if box.periodic[axis] or g[axis] == 0.0:
                continue
            if g[axis] < 0.0:
                touching = pos[:, axis] - rad <= _OVERLAP_TOL * rad
            else:
                touching = length - rad - pos[:, axis] <= _OVERLAP_TOL * rad
            resting = movable & touching & (vel[:, axis] == 0.0)
            if resting.any() and (model is None or model.hold == 0.0):
                name = "xy"[axis]
                wall = f"{name}=0" if g[axis] < 0.0 else f"{name}={length}"
                raise ValueError(
                    f"{what}: disks {indices_where(resting)} rest on the box wall at "
                    f"{wall} with zero {name}-velocity while gravity presses them into "
                    "it, which would take unboundedly many bounces at one instant: "
                    "lift them by a small gap, give them a velocity, or make them "
                    "inelastic (restitution < 1 with tc > 0 lets walls hold them)"
                )
            side = 2 * axis + (0 if g[axis] < 0.0 else 1)
            bits[resting] |= 1 << side
        if model is None:
            self._check_not_resting_on_obstacles(pos, vel, rad, movable, g, what)
        return bits

    def _check_not_resting_on_obstacles(self, pos, vel, rad, movable, g, what) -> None:
        """Elastic disks under gravity: none may start at rest (no velocity along the
        contact normal) on a wall segment or an immovable disk that gravity presses it
        into; it would bounce without end at one instant.  (Only disks with a zero
        velocity component can, so only they are checked.)"""
        still = np.flatnonzero(movable & ((vel[:, 0] == 0.0) | (vel[:, 1] == 0.0)))
        if len(still) == 0:
            return
        pegs = np.flatnonzero(~movable)
        for i in still:
            normals = []
            for w in self._walls:
                a, b = np.array(w.start), np.array(w.end)
                u = b - a
                s = np.clip(dot(pos[i] - a, u) / dot(u, u), 0.0, 1.0)
                d = pos[i] - (a + s * u)
                normals.append((d, rad[i]))
            for j in pegs:
                normals.append((pos[i] - pos[j], rad[i] + rad[j]))
            for d, contact in normals:
                dist = float(np.hypot(*d))
                if (dist <= contact * (1.0 + _OVERLAP_TOL) and float(dot(vel[i], d)) == 0.0
                        and float(dot(g, d)) < 0.0):
                    raise ValueError(
                        f"{what}: disk {i} rests on a wall segment or an immovable "
                        "disk with no velocity along the contact while gravity presses "
                        "it on, which would take unboundedly many bounces at one "
                        "instant: lift it by a small gap or give it a velocity (only "
                        "box walls hold disks at rest)")

    def _check_walls_in_box(self) -> None:
        w, h = self._box.width, self._box.height
        for k, wall in enumerate(self._walls):
            for pt in (wall.start, wall.end):
                if not (0 <= pt[0] <= w and 0 <= pt[1] <= h):
                    raise ValueError(
                        f"walls[{k}] has an end point {pt} outside the box [0, {w}] x [0, {h}]"
                    )

    def _check_overlaps(self, pos: np.ndarray, rad: np.ndarray) -> None:
        i, j, dist = _overlap.first_disk_overlap(
            pos, rad, self._gi, self._gf, self._E[:, _layout.CELL], self._head, self._nxt,
            _OVERLAP_TOL,
        )
        if i >= 0:
            what = "its own periodic image" if i == j else f"disk {j}"
            contact = rad[i] + rad[j]
            raise ValueError(
                f"positions: disk {i} overlaps {what} (centre distance {dist:.17g} < "
                f"sum of radii {contact:.17g}, by {1.0 - dist / contact:.3g} of it)"
            )
        if not self._walls:
            return
        i, w, dist = _overlap.first_wall_overlap(
            pos, rad, self._gf, self._E[:, _layout.CELL], self._wa, self._wb,
            self._wstart, self._wwall, self._wsx, self._wsy, _OVERLAP_TOL,
        )
        if i >= 0:
            raise ValueError(
                f"positions: disk {i} overlaps walls[{w}] (distance {dist:.17g} < "
                f"radius {rad[i]:.17g}, by {1.0 - dist / rad[i]:.3g} of it)"
            )

    # ------------------------------------------------------------------ engine calls
    # Per-disk columns that are views into the rows of _S and _E (loop.row_views).
    _ROW_VIEWS = ("_stamp", "_nxt", "_prv", "_qt", "_tcand", "_invm")

    @classmethod
    def _tables(cls, state, table, hv, qhead, qs, qf) -> dict:
        """The attributes for the tables ``S`` and ``E``, the queue's other arrays and
        the per-disk columns that are views into ``S`` and ``E`` (the queue times among
        them): to be installed together, by one ``vars(self).update``."""
        attrs = dict(_S=state, _E=table, _hv=hv, _qhead=qhead, _qs=qs, _qf=qf)
        attrs.update(zip(cls._ROW_VIEWS, _layout.row_views(state, table)))
        return attrs

    def __getstate__(self) -> dict:
        """For pickle and ``copy.deepcopy``: without the views into ``S`` and ``E``,
        which a copy would turn into arrays of their own, detached from the copied
        tables; :meth:`__setstate__` rebuilds them."""
        state = dict(vars(self))
        for name in self._ROW_VIEWS:
            del state[name]
        # A stream's callback is not part of the state (nor what it has collected):
        # a copy does not stream, and its log is empty.
        for name in ("_listener", "_recorded"):
            state.pop(name, None)
        for name, empty in (("_log_t", np.zeros(0)), ("_log_e", np.zeros((0, 3), np.int64)),
                            ("_log_j", np.zeros(0)), ("_log_n", np.zeros(1, np.int64))):
            state[name] = empty
        return state

    def __copy__(self) -> Simulation:
        """``copy.copy`` gives an independent copy too (as ``copy.deepcopy``): two
        simulations sharing some of their arrays would corrupt each other."""
        return copy.deepcopy(self)

    def __setstate__(self, state: dict) -> None:
        state = dict(state)
        qs = state["_qs"]
        if len(qs) == _queue.FIRST:  # (pickled before the queue kept qs[FIRST], a hint)
            state["_qs"] = np.append(qs, -1)
        elif len(qs) != _queue.N_QS:
            raise ValueError(
                "this Simulation was pickled by an incompatible version of edmd2d "
                f"(queue state of {len(qs)} entries, expected {_queue.N_QS})"
            )
        tables = []
        for name in ("_S", "_E"):  # (back on 64-byte boundaries: a copy may not be)
            table = aligned_rows(*state[name].shape, state[name].dtype)
            table[:] = state.pop(name)
            tables.append(table)
        # Saved before the lookahead noted its stages, the column held -1 ("all given"):
        # none given, as after a prediction.
        staged = tables[1][:, _layout.STAGED]
        staged[staged & ~_layout.STAGE_BITS != 0] = 0
        state.update(self._tables(*tables, *(state.pop(name) for name in
                                             ("_hv", "_qhead", "_qs", "_qf"))))
        # Saved before models and species existed: elastic disks of one species, and
        # no accumulated dissipation.
        state.setdefault("_model", None)
        state.setdefault("_species", None)
        state.setdefault("_cell_size", None)
        state.setdefault("_gravity", None)
        state.setdefault("_growth", None)
        state.setdefault("_grid_dmax", 2.0 * float(state["_S"][:, _layout.R].max()))
        state.setdefault("_log_j", np.zeros(len(state.get("_log_t", ()))))
        state.setdefault("_listener", None)
        state.setdefault("_families", {})
        acc = state["_acc"]
        if len(acc) < _layout.N_ACC:
            state["_acc"] = np.concatenate([acc, np.zeros(_layout.N_ACC - len(acc))])
        # Saved before the impulses were summed per segment: none summed yet (the total
        # over all segments, acc[A_SEGMENTS], is kept).
        state.setdefault("_wacc", np.zeros((len(state["_wa"]), _layout.N_WACC)))
        wacc = state["_wacc"]
        if wacc.shape[1] < _layout.N_WACC:  # (saved before heated segments)
            state["_wacc"] = np.concatenate(
                [wacc, np.zeros((len(wacc), _layout.N_WACC - wacc.shape[1]))], axis=1)
        counts = state["_counts"]
        if len(counts) < _layout.N_COUNTS:  # (saved before thermostats)
            state["_counts"] = np.concatenate(
                [counts, np.zeros(_layout.N_COUNTS - len(counts), np.int64)])
        model = state["_model"]
        if model is not None and len(model.wall_kt) < 4 + len(state["_wa"]):
            model.wall_kt = np.zeros(4 + len(state["_wa"]))  # (saved before heated walls)
        vars(self).update(state)

    def _run(self, t_end, max_collisions, max_events, out, info, mode):
        """One call of the event loop, with the state in its bundles (see loop.py).

        The physics families not in use are ``None``; a model hands over restitution
        and the TC model always (a model of heated walls or a thermostat alone runs
        its contacts with ``e = 1`` through them), the others as it uses them."""
        families = _NO_MODEL if self._model is None else self._model.engine_families()
        return _loop.run(
            _layout.Control(t_end, max_collisions, max_events, mode, out, info),
            _layout.Particles(self._S, self._E, self._stamp, self._nxt, self._prv,
                              self._qt, self._tcand, self._invm, self._image, self._order),
            _layout.Grid(self._gi, self._gf, self._head),
            _layout.Walls(self._wa, self._wb, self._wstart, self._wwall, self._wsx,
                          self._wsy),
            _layout.Calendar(self._hv, self._qhead, self._qs, self._qf),
            _layout.Tallies(self._counts, self._acc, self._wacc),
            _layout.Log(self._log_t, self._log_e, self._log_n, self._log_j),
            families.contact, families.heated, families.thermostat, families.uniforms,
            self._gravity_bundle(), self._growth_bundle(),
        )

    def _gravity_bundle(self):
        """The engine's gravity family: ``None`` (straight-line flight) or a
        ``layout.Gravity`` holding this simulation's inverse masses and supports."""
        g = self._gravity
        return (None if g is None else
                _layout.Gravity(float(g[0]), float(g[1]), self._invm,
                                _layout.support_view(self._S)))

    def _growth_bundle(self):
        """The engine's growth family: ``None`` (fixed radii) or a ``layout.Growth``."""
        if self._growth is None:
            return None
        rate, t0 = self._growth.tolist()  # (stored as an array, which checkpoints hold)
        return _layout.Growth(rate, t0)

    def _queue_args(self):
        return (self._qt, self._E, self._hv, self._qhead, self._qs, self._qf)

    def _reorder(self) -> None:
        """Re-sort the internal rows along the Z-order of their cells (see module top).

        Every new array is built first and all are swapped in by one ``dict.update``,
        so an interrupt cannot leave them half permuted.  The queue is rebuilt rather than
        renumbered, which keeps its tie order (time, then internal index) exact.
        """
        # (The cells' Morton ranks are recomputed each time rather than held: a few
        # bytes a disk less for a small cost every 20 N events.)
        rank = _grid.morton_rank(int(self._gi[0]), int(self._gi[1]))
        perm = _grid.order_by_cell(self._E[:, _layout.CELL], rank, len(rank))
        inv = np.empty_like(perm)
        inv[perm] = np.arange(len(perm))
        # (Whole rows move: the stamps with S, the queue times, candidate times and
        # inverse masses with E.  The cell lists and the queue are rebuilt; queue
        # links left in the rows of disks that end up outside the lists go unread.)
        state = aligned_rows(len(perm), _layout.N_STATE, np.float64)
        state[:] = self._S[perm]
        _, table, hv, qhead, qs, qf = _queue.allocate(len(perm))
        qs[_queue.LOOKAHEAD] = self._qs[_queue.LOOKAHEAD]  # (forced on in tests)
        table[:] = self._E[perm]
        table[:, _layout.STAGED] = 0  # (what the lookahead fetched has moved)
        disk = table[:, _layout.KIND] & _layout.KIND_MASK == _layout.DISK
        table[disk, _layout.PARTNER] = inv[table[disk, _layout.PARTNER]]
        _, nxt, prv, times, _, _ = _layout.row_views(state, table)
        head = np.empty_like(self._head)
        _grid.build_lists(table[:, _layout.CELL], head, nxt, prv)
        # (The queue times are passed twice, as the loop does.)
        _queue.build(self._time, times, times, table, hv, qhead, qs, qf)
        model = None if self._model is None else self._model.permuted(perm)
        vars(self).update(self._tables(state, table, hv, qhead, qs, qf),
                          _mass=self._mass[perm], _order=self._order[perm],
                          _image=self._image[perm], _head=head, _model=model,
                          _since_reorder=0)

    def _to_user(self, internal: np.ndarray) -> np.ndarray:
        """Rows in the user's disk order: a new, read-only array (editing it could not
        change the simulation, so an edit fails instead of passing silently)."""
        out = np.empty_like(internal)
        out[self._order] = internal
        out.flags.writeable = False
        return out

    def _predict_all(self) -> None:
        self._run(math.inf, 0, 0, np.array([self._time]), np.full(2, -1, np.int64),
                  _layout.PREDICT_ALL)

    def advance(self, until: float | None = None, collisions: int | None = None,
                progress=False) -> Simulation:
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
            if t_end < self._time:
                raise ValueError(
                    f"until={t_end} is earlier than the current time {self._time}; "
                    "simulations only run forward"
                )
        max_coll = np.iinfo(np.int64).max
        if collisions is not None:
            max_coll = as_count("collisions", collisions)
            if max_coll == 0:
                return self

        self._check_clock_resolves_crossings(t_end)
        outgrown = math.inf
        if self._growth is not None:
            outgrown = self._time_of_diameter(self._outgrow_diameter())
            if t_end > outgrown and until is not None:
                raise ValueError(
                    f"until={t_end} is past t={outgrown:.17g}, when the largest disk "
                    f"grows as wide as the box ({min(self._box.size):.6g}); the "
                    f"simulation is left at t={self._time}")
            t_end = min(t_end, outgrown)
        by_time = until is not None
        bar, owned = _progress.bar(
            progress, total=(t_end - self._time) if by_time else max_coll,
            unit="time" if by_time else "coll", desc="advance")
        try:
            try:
                status, info, remaining = self._advance(t_end, max_coll, bar, by_time)
            finally:
                self._drain()  # (also on an error: the events up to it)
            if bar is not None and by_time and status in (_layout.REACHED_TIME,
                                                          _layout.NO_EVENTS):
                bar.update(t_end - self._time)  # (the flight after the last event)
        finally:
            if owned:
                bar.close()
        if status in (_layout.REACHED_TIME, _layout.NO_EVENTS) and until is not None:
            self._time = t_end
            return self
        if status == _layout.REACHED_COLLISIONS:
            return self
        if (self._growth is not None and t_end == outgrown
                and status in (_layout.REACHED_TIME, _layout.NO_EVENTS)):
            self._time = t_end
            raise RuntimeError(
                f"the largest disk grew as wide as the box at t={t_end} before "
                f"{remaining} of the {max_coll} requested collisions; the simulation "
                f"stands at that time")
        if status == _layout.NO_EVENTS:
            raise RuntimeError(
                f"no further event can ever happen (t={self._time}): "
                f"{remaining} of the {max_coll} requested collisions cannot occur"
            )
        raise self._engine_error(status, int(info[0]), int(info[1]))

    def _advance(self, t_end, max_coll, bar, by_time):
        """The engine calls of :meth:`advance`: ``(status, info, remaining)``, the final
        status, the disks it names and the collisions still to go.  With a progress bar
        the calls are shorter (``_PROGRESS_EVENTS``) and the bar is updated after
        each."""
        remaining = max_coll
        out = np.array([self._time])
        info = np.full(2, -1, np.int64)  # (the disks an engine error names)
        same = 0  # events in a row at the present time, over the calls so far
        limit = self._wedged_limit()
        chunk = _CHUNK_EVENTS if bar is None else _PROGRESS_EVENTS
        clock = _time.perf_counter()
        while True:
            before = int(self._counts[_layout.C_COLLISIONS])
            events_before = self.counts.events
            shown = self._time
            budget = min(chunk, self._reorder_every - self._since_reorder)
            t_run = t_end  # (under growth: no later than the grid holds)
            if self._growth is not None:
                t_run = min(t_end, self._time_of_diameter(self._grid_dmax))
            try:
                status = self._run(t_run, remaining, budget, out, info, _layout.RUN_EVENTS)
            finally:
                # Also when Ctrl-C arrives as the engine returns: the clock must follow
                # the events the engine has processed, or positions would be read at a
                # time earlier than the disks' own.
                self._time = float(out[0])
                events = self.counts.events - events_before
                self._since_reorder += events
            done = int(self._counts[_layout.C_COLLISIONS]) - before
            remaining -= done
            # Disks wedged with no room to move (a ring of touching disks around a
            # periodic axis, a disk between a wall and a peg) collide forever at one
            # instant, the clock standing still: count the events of the calls that did
            # not move it (here, between calls, it costs the event loop nothing).
            if self._time == shown:
                same += events
                if same >= limit:
                    i = int(np.argmin(self._qt))  # (the next event: one of the wedged)
                    kind = _layout.kind_of(int(self._E[i, _layout.KIND]))
                    info[0] = i
                    info[1] = (-1 - int(self._E[i, _layout.AUX]) if kind == _layout.BOX
                               else int(self._E[i, _layout.PARTNER]))
                    return _layout.ERR_WEDGED, info, remaining
            else:
                same = 0
            if bar is not None:
                now = _time.perf_counter()
                if by_time:
                    bar.update(self._time - shown)
                    rate = (max_coll - remaining) / max(now - clock, 1e-9)
                    bar.set_postfix_str(f"{rate:.3g} coll/s", refresh=False)
                else:  # (tqdm shows the rate of its own unit, collisions)
                    bar.update(done)
            if status == _layout.NEED_RANDOM:
                self._model.refill()
                continue
            if status == _layout.LOG_FULL:
                self._drain()
                continue
            if t_run < t_end and status in (_layout.REACHED_TIME, _layout.NO_EVENTS):
                # The disks have grown as large as the grid's cells allow: rebuild it.
                self._time = t_run
                out[0] = t_run
                self._regrid()
                continue
            if status != _layout.REACHED_EVENT_LIMIT:
                # (No reordering here: an error below names disks by internal index.)
                return status, info, remaining
            if self._since_reorder >= self._reorder_every:
                self._reorder()

    def run(self, until: float | None = None, collisions: int | None = None,
            operations=(), progress=False) -> Simulation:
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

    def _check_clock_resolves_crossings(self, t_end: float) -> None:
        """Refuse a run to ``t_end`` at whose end the float64 clock could no longer
        tell a disk's successive cell crossings, or the thermostat's redraws, apart
        (they are events: the clock would stop, and the run never end), and speeds
        whose product with the box's size the contact times cannot square."""
        horizon = max(abs(self._time), abs(t_end) if math.isfinite(t_end) else 0.0)
        vel = self._velocities()
        v = float(np.hypot(vel[:, 0], vel[:, 1]).max())
        if self._gravity is not None:
            # The fastest a disk can become: gravity's work over the box, if every axis
            # it acts along is walled (energy is conserved or lost), else its push for
            # the whole run.
            g = float(np.hypot(*self._gravity))
            along_periodic = any(p and gk != 0.0 for p, gk in
                                 zip(self._box.periodic, self._gravity))
            if along_periodic:
                if math.isfinite(t_end):
                    v += g * (t_end - self._time)
            else:
                v = math.sqrt(v * v + 2.0 * g * math.hypot(*self._box.size))
        if self._model is not None and self._model.thermo[1] > 0.0:
            interval = 1.0 / float(self._model.thermo[1])  # (mean time between redraws)
            if interval <= 64.0 * np.spacing(horizon):
                raise ValueError(
                    f"the thermostat redraws a velocity every {interval:.3g} on average, "
                    f"which the float64 clock cannot resolve at t={horizon:.6g} (its "
                    f"resolution there is {np.spacing(horizon):.3g}): the run could not "
                    "advance.  Use a smaller thermostat rate.")
        side = float(min(self._gf[2], self._gf[3]))
        if v > 0.0 and side / v <= 64.0 * np.spacing(horizon):
            raise ValueError(
                f"a disk at speed {v:.3g} crosses a grid cell (side {side:.3g}) "
                f"in {side / v:.3g}, which the float64 clock cannot resolve at "
                f"t={horizon:.6g} (its resolution there is {np.spacing(horizon):.3g}): "
                "the run could not advance.  Use smaller speeds (a slower unit of time) "
                "or a shorter run."
            )
        extent = max(self._box.size)
        if v * extent > MAX_LENGTH:
            raise ValueError(
                f"a disk at speed {v:.3g} in a box of side {extent:.3g}: the product, "
                f"{v * extent:.3g}, must be at most {MAX_LENGTH:g} (the contact times "
                "square it).  Use smaller speeds (a slower unit of time).")

    def _wedged_limit(self) -> int:
        """The events in a row at one time after which disks count as wedged."""
        return max(_WEDGED_EVENTS_PER_DISK * len(self), _WEDGED_EVENTS_MIN)

    def _engine_error(self, status: int, i: int, j: int) -> RuntimeError:
        """The exception for an error status of the engine, which stopped before the
        event of internal disk ``i`` with ``j`` (a disk, a wall segment ``>= 0``, or
        ``-1 - side`` for a box wall, as the event's kind says)."""
        t_bad = float(self._qt[i])
        user_i = int(self._order[i])
        stopped = f"The simulation stopped at t={self._time}."
        if status == _layout.ERR_IMMOVABLE_PAIR:
            return RuntimeError(
                f"immovable disks {user_i} and {int(self._order[j])} (mass=inf) meet at "
                f"t={t_bad}: two immovable bodies cannot collide. {stopped}"
            )
        where = (f"walls[{j}]" if j >= 0
                 else f"the box wall at {BOX_WALL_EQUATIONS[-1 - j]}")
        if status == _layout.ERR_IMMOVABLE_WALL:
            return RuntimeError(
                f"immovable disk {user_i} (mass=inf) reaches {where} at t={t_bad}: an "
                f"immovable disk cannot bounce. {stopped}"
            )
        if status == _layout.ERR_STALLED:
            kind = _layout.kind_of(int(self._E[i, _layout.KIND]))
            partner = f"disk {int(self._order[j])}" if kind == _layout.DISK else where
            streak = self._model.streak
            involved = np.sort(self._order[streak >= streak.max() // 10])
            if self._gravity is not None:
                advice = ("Under gravity this is a disk at rest on another disk, a peg or "
                          "a segment, which no tc ends: only box walls hold disks at "
                          "rest (see docs/gravity-and-heat.md).")
            elif self._model.tc > 0.0:
                advice = (f"The TC model (tc={self._model.tc}) did not end it: a larger tc "
                          "would, unless the disks are confined with no room to move.")
            else:
                advice = "Use the TC model (tc > 0) to end the collapse."
            return RuntimeError(
                f"inelastic collapse at t={t_bad}: disk {user_i} and {partner} would "
                f"collide again at the same time, after {_models.STALL_COLLISIONS} "
                f"collisions in a row that took no time (disks involved: "
                f"{indices_where(np.isin(np.arange(len(self)), involved))}); the run would "
                f"need unboundedly many events. {advice} {stopped}"
            )
        if status == _layout.ERR_WEDGED:
            kind = _layout.kind_of(int(self._E[i, _layout.KIND]))
            other = (f"disk {int(self._order[j])}" if kind == _layout.DISK else
                     where if kind in (_layout.SEGMENT, _layout.BOX) else
                     "a grid cell's edge" if kind == _layout.CROSS else "a redraw")
            return RuntimeError(
                f"disks wedged at t={self._time}: {self._wedged_limit()} or more events in "
                f"a row at this one time, the next of disk {user_i} with {other}, and the "
                "clock cannot advance: "
                "disks that touch with no room to move (a ring of touching disks around a "
                "periodic axis, a disk between a wall and a peg or between two walls) "
                "collide forever at one instant.  Give them room (a larger box, smaller "
                "or fewer disks) or set velocities that do not drive them into each "
                f"other. {stopped}"
            )
        return RuntimeError(f"internal error: engine returned status {status}")  # pragma: no cover

    # ------------------------------------------------------------------ state
    def __len__(self) -> int:
        """The number of disks."""
        return len(self._S)

    def __repr__(self) -> str:
        return (
            f"Simulation(n={len(self)}, time={self._time:.6g}, box={self._box!r}, "
            f"walls={len(self._walls)}, collisions={int(self._counts[_layout.C_COLLISIONS])})"
        )

    @property
    def n(self) -> int:
        """Number of disks."""
        return len(self._S)

    @property
    def time(self) -> float:
        """The simulation clock."""
        return self._time

    @property
    def positions(self) -> np.ndarray:
        """Disk centres at :attr:`time`, shape (N, 2), a copy (wrapped into the box)."""
        out = np.empty((len(self._S), 2))
        _flight.synchronized_positions(self._time, self._S, self._gi, self._gf, out,
                                       self._gravity_bundle())
        return self._to_user(out)

    @positions.setter
    def positions(self, positions) -> None:
        self.set_positions(positions)

    @property
    def unwrapped_positions(self) -> np.ndarray:
        """Disk centres at :attr:`time` with periodic wraps undone, shape (N, 2).

        Differences of these between two times are true displacements (for diffusion
        studies); on walled axes they equal :attr:`positions`.
        """
        return self._to_user(self._unwrapped())

    def _unwrapped(self) -> np.ndarray:
        """Unwrapped centres at :attr:`time`, in internal row order."""
        return (_flight.positions_at(self._time, self._S, self._gravity_bundle())
                + self._image * self._box.size)

    def _velocities(self) -> np.ndarray:
        """Velocities at :attr:`time`, in internal row order (a new array)."""
        return _flight.velocities_at(self._time, self._S, self._gravity_bundle())

    @property
    def velocities(self) -> np.ndarray:
        """Disk velocities at :attr:`time`, shape (N, 2), a copy."""
        return self._to_user(self._velocities())

    @property
    def radii(self) -> np.ndarray:
        """Disk radii at :attr:`time`, shape (N,), a copy (they change in time under
        :attr:`growth`)."""
        return self._to_user(self._S[:, _layout.R] * self._growth_factor(self._time))

    @property
    def masses(self) -> np.ndarray:
        """Disk masses, shape (N,), a copy (``inf`` for immovable disks)."""
        return self._to_user(self._mass)

    @property
    def species(self) -> np.ndarray:
        """Each disk's species (int), shape (N,), a copy; all 0 unless given."""
        out = (np.zeros(len(self), np.int32) if self._species is None
               else self._species.copy())
        out.flags.writeable = False
        return out

    @property
    def restitution(self) -> np.ndarray:
        """Coefficient of normal restitution for each pair of species, shape (S, S),
        a copy: ``(1, 1)`` if one coefficient applies to every pair, all 1 for elastic
        disks."""
        if self._model is None:
            n_species = int(self.species.max()) + 1
            out = np.ones((n_species, n_species))
        else:
            out = self._model.table.copy()
        out.flags.writeable = False
        return out

    @property
    def wall_restitution(self) -> float:
        """Coefficient of normal restitution against box walls and wall segments."""
        return 1.0 if self._model is None else self._model.wall

    @property
    def tc(self) -> float | None:
        """The TC-model duration (see :mod:`edmd2d.models`); ``None`` for elastic disks."""
        return None if self._model is None else self._model.tc

    @property
    def box(self) -> Box:
        """The container."""
        return self._box

    @property
    def walls(self) -> tuple[Wall, ...]:
        """The wall segments."""
        return self._walls

    @property
    def counts(self) -> Counts:
        """Event counts since creation (see :class:`Counts`)."""
        c = self._counts
        coll, wall, cross = (int(c[_layout.C_COLLISIONS]), int(c[_layout.C_WALL]),
                             int(c[_layout.C_CROSSINGS]))
        kicks = int(c[_layout.C_KICKS])
        return Counts(coll, wall, cross, coll + wall + cross + kicks, int(c[_layout.C_STALE]),
                      kicks)

    def kinetic_energy(self) -> float:
        """Total kinetic energy of the movable disks, ``sum m v^2 / 2``.

        Returns
        -------
        float
        """
        movable = self._invm > 0
        vel = self._velocities()[movable]
        return float(0.5 * dot(self._mass[movable], np.einsum("ij,ij->i", vel, vel)))

    def wall_heat(self) -> np.ndarray:
        """Kinetic energy the heated walls gave to the disks since creation (negative:
        they took it), shape (4 + S,): the box walls x=0, x=width, y=0, y=height, then
        each wall segment; 0 for walls that are not heated.

        Returns
        -------
        numpy.ndarray, shape (4 + S,)
        """
        return np.concatenate([self._acc[_layout.A_HEAT_BOX:_layout.A_HEAT_BOX + 4],
                               self._wacc[:, _layout.W_HEAT]])

    def thermostat_energy(self) -> float:
        """Kinetic energy the thermostat's redraws gave to the disks since creation
        (negative: they took it).  ``total_energy() + dissipated_energy()`` minus this and
        ``wall_heat().sum()`` stays constant to rounding.

        Returns
        -------
        float
        """
        return float(self._acc[_layout.A_THERMOSTAT])

    @property
    def thermostat(self) -> tuple[float, float] | None:
        """The Andersen thermostat's ``(kT, rate per disk)``, or ``None``."""
        return None if self._model is None else self._model.thermostat

    @property
    def wall_temperatures(self) -> dict:
        """The heated walls, ``{wall: kT}`` (box walls by name: ``"left"``,
        ``"right"``, ``"bottom"``, ``"top"``; segments by index); empty if none."""
        if self._model is None:
            return {}
        return {(BOX_WALLS[k] if k < 4 else k - 4): float(t)
                for k, t in enumerate(self._model.wall_kt) if t > 0.0}

    def rescale_temperature(self, temperature: float) -> None:
        """Scale the velocities relative to the centre of mass so that the kinetic
        temperature (:func:`edmd2d.measurements.kinetic_temperature`) becomes
        ``temperature``; the total momentum is kept.

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
        vel = self.velocities
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
        self.set_velocities(new)

    def dissipated_energy(self) -> float:
        """Kinetic energy lost in inelastic collisions since creation (0 for elastic
        disks): ``kinetic_energy() + dissipated_energy()`` stays constant to rounding
        (while no immovable disk moves).

        Returns
        -------
        float
        """
        return float(self._acc[_layout.A_DISSIPATED])

    def momentum(self) -> np.ndarray:
        """Total momentum of the movable disks.

        Returns
        -------
        numpy.ndarray, shape (2,)
        """
        movable = self._invm > 0
        return weighted_sum(self._mass[movable], self._velocities()[movable])

    @property
    def families(self) -> dict:
        """The physics families registered with :func:`edmd2d.physics.register` that
        this simulation has, by name (a copy of the mapping; the families are frozen).

        Returns
        -------
        dict of str to edmd2d.physics.Family
        """
        return dict(self._families)

    @property
    def gravity(self) -> np.ndarray:
        """The uniform acceleration of the movable disks, shape (2,), a copy (zero
        without gravity)."""
        out = np.zeros(2) if self._gravity is None else self._gravity.copy()
        out.flags.writeable = False
        return out

    def potential_energy(self) -> float:
        """Potential energy of the movable disks in the gravity field,
        ``-sum m g.r`` (zero at the origin), with :attr:`unwrapped_positions` so that
        it stays continuous across periodic wraps; 0 without gravity.

        Returns
        -------
        float
        """
        if self._gravity is None:
            return 0.0
        movable = self._invm > 0
        return float(-dot(self._mass[movable], dot(self._unwrapped()[movable], self._gravity)))

    def total_energy(self) -> float:
        """``kinetic_energy() + potential_energy()``: constant to rounding for elastic
        disks (while no immovable disk moves); with inelastic collisions it decreases
        by :meth:`dissipated_energy`.

        Returns
        -------
        float
        """
        return self.kinetic_energy() + self.potential_energy()

    def set_positions(self, positions) -> None:
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
        Simulation(pos, self.velocities, self.radii, self.masses, box=self._box,
                   walls=self._walls, time=self._time)
        pos = self._check_in_box(pos, self.radii)  # (x = width becomes 0 if periodic)
        rest = self._resting(pos, self.velocities, self.radii, self.masses, self._model)
        self._sync_all()
        self._S[:, _layout.X:_layout.Y + 1] = pos[self._order]
        _layout.support_view(self._S)[:] = rest[self._order]
        self._image[:] = 0
        dmax = 2.0 * float(self._S[:, _layout.R].max()) * self._growth_factor(self._time)
        self._build_grid(self._S[:, _layout.X:_layout.Y + 1], self._grid_diameter(dmax),
                         self._cell_size)
        self._predict_all()

    def set_velocities(self, velocities) -> None:
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
        self._check_room(vel, self.radii)
        rest = self._resting(self.positions, vel, self.radii, self.masses, self._model,
                             "velocities")
        self._sync_all()
        self._S[:, _layout.VX:_layout.VY + 1] = vel[self._order]
        _layout.support_view(self._S)[:] = rest[self._order]
        self._predict_all()  # every event and kept candidate is recomputed

    def _sync_all(self) -> None:
        """Move every stored position to the current time (local clocks all equal)."""
        _flight.drift_all(self._time, self._S, self._gravity_bundle())

    def measure(self, duration: float, **kwargs):
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

    # ------------------------------------------------------------------ hooks
    def _accumulators(self) -> dict:
        """Raw sums since creation: the collision virial ``sum J |r_ij|``, its diagonal
        components ``sum J |r_ij| n_x^2`` and ``n_y^2`` (``n`` the contact normal), and the
        impulses on the walls (``J`` the impulse magnitude of a contact):

        - ``"box_impulse"``, shape (4,): ``sum J`` on each box wall (x=0, x=width, y=0,
          y=height);
        - ``"segment_impulse"``: ``sum J`` over all wall segments;
        - ``"segment_impulses"``, shape (S, 2): the impulse vector each segment received,
          ``sum -J n`` (``n`` the unit normal from the segment to the disk);
        - ``"segment_side_impulses"``, shape (S, 2): ``sum J`` over the contacts on each
          side of each segment, left then right (the left side lies to the left going
          from ``start`` to ``end``: counterclockwise polygons have their inside there);
        - ``"segment_end_impulses"``, shape (S,): ``sum J`` at each segment's end points;
        - ``"segment_contacts"``, shape (S,): contact events of each segment (as counted
          in ``counts.wall_collisions``).

        At a heated wall ``J`` is the normal component of the momentum change (the
        tangential one is in ``"segment_impulses"`` for a segment).

        Over all segments, the side and end-point sums add up to ``"segment_impulse"``
        (to rounding)."""
        a = self._acc
        w = self._wacc
        return {
            "virial": float(a[_layout.A_VIRIAL]),
            "virial_xx": float(a[_layout.A_VIRIAL_XX]),
            "virial_yy": float(a[_layout.A_VIRIAL_YY]),
            "box_impulse": a[_layout.A_BOX:_layout.A_BOX + 4].copy(),
            "segment_impulse": float(a[_layout.A_SEGMENTS]),
            "segment_impulses": w[:, _layout.W_FX:_layout.W_FY + 1].copy(),
            "segment_side_impulses": w[:, _layout.W_LEFT:_layout.W_RIGHT + 1].copy(),
            "segment_end_impulses": w[:, _layout.W_ENDS].copy(),
            "segment_contacts": w[:, _layout.W_CONTACTS].astype(np.int64),
        }

    def stream_events(self, callback, capacity: int = 1 << 16) -> None:
        """Deliver every processed event to ``callback``, in batches, without loss.

        Parameters
        ----------
        callback : callable or None
            Called as ``callback(batch)`` with a NumPy structured array of up to
            ``capacity`` events in time order, fields ``time``, ``kind`` (the names of
            :data:`EVENT_KINDS`: ``"disk"``, ``"wall"`` (a segment), ``"box"``,
            ``"thermostat"``), ``disk``, ``partner`` (a disk, a segment index, a box
            wall 0-3 for x=0, x=width, y=0, y=height, or -1 for a thermostat redraw)
            and ``impulse`` (the momentum change of a movable disk of the event).  Cell
            crossings are bookkeeping, not streamed.  ``None`` stops the stream.
        capacity : int, default 65536
            Events per batch: when the engine's buffer is full it returns to Python
            for ``callback``, then goes on; the last batch of a call of
            :meth:`advance` comes at its end.

        Notes
        -----
        With no stream the engine records nothing and costs nothing more.  The
        callback is not part of the state: copies, pickles and checkpoints do not
        stream.

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
        if callback is None:
            self._drain()
            self._listener = None
            self._set_log(0)
            return
        if not callable(callback):
            raise TypeError(f"callback must be callable or None, got {callback!r}")
        capacity = as_count("capacity", capacity, minimum=1)
        self._drain()
        self._listener = callback
        self._set_log(capacity)

    def _set_log(self, capacity: int) -> None:
        self._log_t = np.zeros(capacity)
        self._log_e = np.zeros((capacity, 3), np.int64)
        self._log_j = np.zeros(capacity)
        self._log_n = np.zeros(1, np.int64)

    def _drain(self) -> None:
        """Hand the events in the engine's log to the listener and empty it."""
        k = int(self._log_n[0])
        if k == 0 or self._listener is None:
            return
        batch = np.empty(k, dtype=EVENT_DTYPE)
        batch["time"] = self._log_t[:k]
        batch["kind"] = np.array(EVENT_KINDS)[np.searchsorted(_KIND_CODES,
                                                              self._log_e[:k, 0])]
        batch["disk"] = self._log_e[:k, 1]
        batch["partner"] = self._log_e[:k, 2]
        batch["impulse"] = self._log_j[:k]
        self._log_n[0] = 0
        self._listener(batch)

    def _record_events(self, capacity: int = 1 << 16) -> None:
        """Record every disk, wall and thermostat event (for :meth:`_recorded_events`)."""
        self._recorded = []
        self.stream_events(self._recorded.append, capacity)

    def _recorded_events(self) -> list[tuple[float, str, int, int]]:
        """Recorded events as ``(time, kind, disk, partner)``; kind is "disk", "wall"
        (partner: wall index), "box" (partner: 0..3 for x=0, x=width, y=0, y=height) or
        "thermostat" (partner -1)."""
        self._drain()
        return [(float(e["time"]), str(e["kind"]), int(e["disk"]), int(e["partner"]))
                for batch in self._recorded for e in batch]


def _build_model(system, seed, contact, heated, thermostat):
    """The :class:`~edmd2d.models.Model` of the checked families, or ``None`` for
    elastic disks between reflecting walls without a thermostat (the engine's default
    path)."""
    if contact.elastic and not heated.active and thermostat is None:
        return None
    rng = None
    if heated.active or thermostat is not None:
        rng = as_generator("seed", seed)
    return _models.Model(
        contact.table, contact.wall, contact.tc, contact.species, heated.kt,
        None if thermostat is None else (thermostat.temperature, thermostat.rate), rng,
        system.time)
