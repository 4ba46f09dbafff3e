"""The machinery of operations: triggers, the :class:`Operation` base, the run driver
and the generic recorders.

It reads only the public state of the simulation it is given, so that
:class:`~edmd2d.Simulation` can use it (``Simulation.run``) and each concrete
operation can live with its subject: ``Measure`` in :mod:`edmd2d.measurements`,
``Checkpoint`` in :mod:`edmd2d.checkpoint`, ``WriteGSD`` in :mod:`edmd2d.io.gsd`.
:mod:`edmd2d.operations` gathers them all under one public name.
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from . import progress as _progress
from ._validate import as_count, as_float_array, as_positive_float

if TYPE_CHECKING:  # (for the annotations only: simulation imports this module)
    from .simulation import Simulation

__all__ = ["Trigger", "Every", "At", "Blocks", "Operation", "Callback",
           "RecordTrajectory", "RecordFrames", "Snapshot", "run", "WALL_CLOCK_SLICE"]

# Collisions at most between two stops while a wall-clock trigger is active (the
# public name and its description: edmd2d.operations.WALL_CLOCK_SLICE).
WALL_CLOCK_SLICE = 100_000


class Trigger:
    """When an operation fires (see :class:`Every`, :class:`At` and :class:`Blocks`)."""

    def _start(self, sim) -> None:
        """Set the first firing from the state at the start of a run."""

    def next_time(self) -> float:
        """The next simulated time at which to fire (``inf``: none).

        Returns
        -------
        float
        """
        return math.inf

    def collisions_left(self, sim: Simulation) -> int | None:
        """Collisions until the next firing, or ``None``.

        Parameters
        ----------
        sim : Simulation

        Returns
        -------
        int or None
        """
        return None

    def due(self, sim: Simulation, now: float) -> bool:
        """Whether to fire at this stop (and, if so, set the next firing).

        Parameters
        ----------
        sim : Simulation
        now : float
            The wall clock (``time.monotonic()``) at this stop.

        Returns
        -------
        bool
        """
        return False


class Every(Trigger):
    """Fire periodically: every ``dt`` of simulated time, every ``collisions``
    collisions, or every ``seconds`` of wall-clock time (exactly one of them).

    Parameters
    ----------
    dt : float, optional
        Simulated time, > 0: at ``t0 + dt, t0 + 2 dt, ...`` with ``t0`` the run's start.
    collisions : int, optional
        Disk-disk collisions, >= 1.
    seconds : float, optional
        Wall-clock time, > 0.
    start : float, optional
        With ``dt`` only: the origin ``t0`` of the times instead of the run's start;
        the run fires at the times ``t0 + k dt`` (``k >= 1``) after its start.  A run
        continued from a checkpoint keeps the times of the run it continues this way.
    """

    def __init__(self, dt: float | None = None, collisions: int | None = None,
                 seconds: float | None = None, *, start: float | None = None) -> None:
        given = [name for name, v in (("dt", dt), ("collisions", collisions),
                                      ("seconds", seconds)) if v is not None]
        if len(given) != 1:
            raise TypeError("Every() needs exactly one of dt=, collisions=, seconds=; got "
                            f"{given or 'none'}")
        self.dt = None if dt is None else as_positive_float("dt", dt)
        self.collisions = None if collisions is None else as_count("collisions", collisions,
                                                                   minimum=1)
        self.seconds = None if seconds is None else as_positive_float("seconds", seconds)
        if start is not None and dt is None:
            raise TypeError("Every(start=...) goes with dt= (times of simulated time)")
        self.start = None if start is None else float(as_float_array("start", start, ()))

    def _start(self, sim) -> None:
        self._t0 = sim.time if self.start is None else self.start
        self._k = 1
        if self.start is not None:
            assert self.dt is not None  # (start goes with dt: __init__)
            # The first k >= 1 with t0 + k dt after now, computed as the times are.
            t = sim.time
            self._k = max(1, math.floor((t - self._t0) / self.dt) + 1)
            while self._k > 1 and self._t0 + (self._k - 1) * self.dt > t:
                self._k -= 1
            while self._t0 + self._k * self.dt <= t:
                self._k += 1
        self._c_next = sim.counts.collisions + (self.collisions or 0)
        self._clock = _time.monotonic()

    def next_time(self) -> float:
        return self._t0 + self._k * self.dt if self.dt is not None else math.inf

    def collisions_left(self, sim: Simulation) -> int | None:
        if self.collisions is None:
            return None
        return max(self._c_next - sim.counts.collisions, 0)

    def due(self, sim: Simulation, now: float) -> bool:
        if self.dt is not None:
            if sim.time >= self.next_time():
                self._k += 1
                return True
            return False
        if self.collisions is not None:
            if sim.counts.collisions >= self._c_next:
                self._c_next += self.collisions
                return True
            return False
        assert self.seconds is not None  # (exactly one of the three: __init__)
        if now - self._clock >= self.seconds:
            self._clock = now
            return True
        return False


class At(Trigger):
    """Fire at each of the given simulated times (those not before the run's start).

    Parameters
    ----------
    times : array_like of float
    """

    def __init__(self, times: ArrayLike) -> None:
        times = np.sort(np.atleast_1d(as_float_array("times", times, (None,))))
        self.times = times

    def _start(self, sim) -> None:
        self._k = int(np.searchsorted(self.times, sim.time, side="left"))

    def next_time(self) -> float:
        return float(self.times[self._k]) if self._k < len(self.times) else math.inf

    def due(self, sim: Simulation, now: float) -> bool:
        fired = False
        while self._k < len(self.times) and self.times[self._k] <= sim.time:
            self._k += 1
            fired = True
        return fired


class Blocks(Trigger):
    """Fire at the ends of ``blocks`` equal blocks of a window of ``duration``.

    The window starts at ``start`` (default: the start of the first run that uses the
    trigger; it stays there for later runs), and block ``b`` ends at
    ``start + duration * b / blocks`` (the last at ``start + duration`` exactly), the
    times at which :func:`edmd2d.measurements.measure` cuts its window.  If ``start``
    lies after the run's start, the trigger fires at ``start`` too (the window opens:
    a :class:`Measure` then takes its first boundary).  Two triggers made with the same
    arguments fire at the same times, so a :class:`Callback` can follow a
    :class:`Measure` block by block.

    Parameters
    ----------
    duration : float
        Length of the window, > 0.
    blocks : int, default 10
        Number of blocks, >= 1.
    start : float, optional
        Start of the window.
    count : int, optional
        Blocks to fire, default ``blocks``; more continue at the same spacing after
        the window (block ``b`` ends at ``start + duration * b / blocks``).
    """

    def __init__(self, duration: float, blocks: int = 10, *, start: float | None = None,
                 count: int | None = None) -> None:
        self.duration = as_positive_float("duration", duration)
        self.blocks = as_count("blocks", blocks, minimum=1)
        self.start = None if start is None else float(as_float_array("start", start, ()))
        self.count = self.blocks if count is None else as_count("count", count, minimum=1)
        self._t0 = self.start
        self._b = 0

    @property
    def window_start(self) -> float | None:
        """The start of the window (``None`` before a run has started the trigger)."""
        return self._t0

    def elapsed(self, b: int) -> float:
        """The window's length after ``b`` blocks: ``duration * b / blocks``
        (``duration`` exactly for ``b == blocks``).

        Parameters
        ----------
        b : int

        Returns
        -------
        float
        """
        return self.duration if b == self.blocks else self.duration * b / self.blocks

    def edge(self, b: int) -> float:
        """The end of block ``b`` (``b = 0``: the start of the window).

        Parameters
        ----------
        b : int

        Returns
        -------
        float
        """
        if self._t0 is None:
            raise ValueError("the window has no start yet: give start= or run first")
        if b == 0:
            return self._t0
        return (self._t0 + self.duration * b / self.blocks if b != self.blocks
                else self._t0 + self.duration)

    def _start(self, sim) -> None:
        if self._t0 is None:
            self._t0 = sim.time
        self._b = 0
        while self._b <= self.count and self.edge(self._b) <= sim.time:
            self._b += 1

    def next_time(self) -> float:
        return self.edge(self._b) if self._b <= self.count else math.inf

    def due(self, sim: Simulation, now: float) -> bool:
        fired = False
        while self._b <= self.count and self.edge(self._b) <= sim.time:
            self._b += 1
            fired = True
        return fired


class Operation:
    """Something done to or with the simulation when ``trigger`` fires.

    Parameters
    ----------
    trigger : Trigger
    """

    def __init__(self, trigger: Trigger) -> None:
        if not isinstance(trigger, Trigger):
            raise TypeError(f"trigger must be an edmd2d.operations.Trigger, got {trigger!r}")
        self.trigger = trigger

    def begin(self, sim: Simulation) -> None:
        """Called once when a run starts, after the triggers have started.

        Parameters
        ----------
        sim : Simulation
        """

    def __call__(self, sim) -> None:  # pragma: no cover - the subclasses' job
        raise NotImplementedError

    def close(self) -> None:
        """Release what the operation holds (at the end of the run)."""


class Callback(Operation):
    """Call ``function(sim)`` when ``trigger`` fires.

    Parameters
    ----------
    function : callable
        Called with the simulation.
    trigger : Trigger
    """

    def __init__(self, function: Callable[[Simulation], Any], trigger: Trigger) -> None:
        super().__init__(trigger)
        if not callable(function):
            raise TypeError(f"function must be callable, got {function!r}")
        self.function = function

    def __call__(self, sim) -> None:
        self.function(sim)


class RecordTrajectory(Operation):
    """Record the disks' positions (and, if asked, velocities) at each firing.

    Parameters
    ----------
    trigger : Trigger
    unwrapped : bool, default True
        Unwrapped positions (:attr:`~edmd2d.Simulation.unwrapped_positions`, periodic
        wraps undone, for displacements), else positions wrapped into the box.
    velocities : bool, default False
        Record the velocities too.
    include_start : bool, default False
        Also record the state at the run's start.

    Examples
    --------
    >>> import edmd2d as ed
    >>> from edmd2d import operations as op
    >>> rec = op.RecordTrajectory(op.Every(dt=0.5), include_start=True)
    >>> _ = ed.make_gas(50, 0.3, seed=1).run(until=1.0, operations=[rec])
    >>> rec.times.tolist(), rec.positions.shape
    ([0.0, 0.5, 1.0], (3, 50, 2))
    """

    def __init__(self, trigger: Trigger, *, unwrapped: bool = True, velocities: bool = False,
                 include_start: bool = False) -> None:
        super().__init__(trigger)
        self.unwrapped = bool(unwrapped)
        self.record_velocities = bool(velocities)
        self.include_start = bool(include_start)
        self._times: list[float] = []
        self._pos: list[np.ndarray] = []
        self._vel: list[np.ndarray] = []

    def begin(self, sim: Simulation) -> None:
        """Record the state at the run's start if ``include_start`` (and nothing was
        recorded yet).

        Parameters
        ----------
        sim : Simulation
        """
        if self.include_start and not self._times:
            self(sim)

    def __call__(self, sim) -> None:
        self._times.append(sim.time)
        self._pos.append(sim.unwrapped_positions if self.unwrapped else sim.positions)
        if self.record_velocities:
            self._vel.append(sim.velocities)

    @property
    def times(self) -> np.ndarray:
        """The times of the frames, shape (F,)."""
        return np.array(self._times, dtype=float)

    @property
    def positions(self) -> np.ndarray:
        """The positions, shape (F, N, 2)."""
        return _stack(self._pos)

    @property
    def velocities(self) -> np.ndarray | None:
        """The velocities, shape (F, N, 2), or ``None`` if not recorded."""
        return _stack(self._vel) if self.record_velocities else None


class Snapshot:
    """What a picture of a simulation shows at one time: read-only, synchronized copies.

    It has the attributes of a :class:`~edmd2d.Simulation` that :mod:`edmd2d.viz`
    reads, so that recorded frames can be drawn and animated after the run.

    Parameters
    ----------
    sim : Simulation
        Copied at its current time.

    Attributes
    ----------
    time : float
    positions, unwrapped_positions, velocities : ndarray, shape (N, 2)
    radii, masses : ndarray, shape (N,)
    species : ndarray of int, shape (N,)
    box : Box
    walls : tuple of Wall
    open_walls : ndarray of bool, shape (S,)
    counts : Counts
    shear_offset : float
        The offset of the images above a sheared box (0.0 without shear).
    families : dict
        The registered physics families (:attr:`Simulation.families
        <edmd2d.Simulation.families>`).
    angles, angular_velocities : ndarray, shape (N,)
        Rough disks: each disk's angle and angular velocity (zero for smooth disks).
    """

    __slots__ = ("time", "positions", "unwrapped_positions", "velocities", "radii",
                 "masses", "species", "box", "walls", "open_walls", "counts",
                 "shear_offset", "families", "angles", "angular_velocities")

    def __init__(self, sim: Simulation) -> None:
        self.time = sim.time
        self.positions = sim.positions
        self.unwrapped_positions = sim.unwrapped_positions
        self.velocities = sim.velocities
        self.radii = sim.radii
        self.masses = sim.masses
        self.species = sim.species
        self.box = sim.box
        self.walls = sim.walls
        self.open_walls = sim.open_walls
        self.counts = sim.counts
        self.shear_offset = sim.shear_offset
        self.families = sim.families
        self.angles = sim.angles
        self.angular_velocities = sim.angular_velocities

    def __len__(self) -> int:
        return len(self.positions)

    @property
    def n(self) -> int:
        """Number of disks."""
        return len(self.positions)

    def __repr__(self) -> str:
        return f"Snapshot(t={self.time:g}, n={self.n}, collisions={self.counts.collisions})"


class RecordFrames(Operation):
    """Keep a :class:`Snapshot` at each firing: the frames of an animation, drawn after
    the run with :func:`edmd2d.viz.animate_frames` (and as often as wanted).

    Parameters
    ----------
    trigger : Trigger
        When to take a frame, e.g. ``Every(dt=1 / 30)``.
    include_start : bool, default True
        Also take a frame at the run's start.

    Examples
    --------
    >>> import edmd2d as ed
    >>> from edmd2d import operations as op
    >>> frames = op.RecordFrames(op.Every(dt=0.25))
    >>> _ = ed.make_gas(50, 0.3, seed=1).run(until=1.0, operations=[frames])
    >>> [round(f.time, 2) for f in frames.frames]
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """

    def __init__(self, trigger: Trigger, *, include_start: bool = True) -> None:
        super().__init__(trigger)
        self.include_start = bool(include_start)
        self.frames: list[Snapshot] = []

    def begin(self, sim: Simulation) -> None:
        """Take a frame at the run's start if ``include_start`` (and none was taken
        yet).

        Parameters
        ----------
        sim : Simulation
        """
        if self.include_start and not self.frames:
            self(sim)

    def __call__(self, sim) -> None:
        self.frames.append(Snapshot(sim))

    @property
    def times(self) -> np.ndarray:
        """The times of the frames, shape (F,)."""
        return np.array([f.time for f in self.frames], dtype=float)


def run(sim: Simulation, until: float | None = None, collisions: int | None = None,
        operations: Iterable[Operation] = (),
        progress: _progress.ProgressArg = False) -> Simulation:
    """Advance ``sim`` to ``until`` (and/or by ``collisions``), firing ``operations``.

    Parameters
    ----------
    sim : Simulation
    until : float, optional
        The end time (as for :meth:`Simulation.advance`).
    collisions : int, optional
        Stop after this many further collisions (whichever of the two comes first).
    operations : sequence of Operation
    progress : bool or tqdm bar, default False
        A progress bar over the run (:mod:`edmd2d.progress`), of the simulated time
        with the collisions per second (or of the collisions, with ``collisions``
        alone); a bar passed in is advanced the same way.

    Returns
    -------
    Simulation
        ``sim``.  Every operation is closed at the end (also on an error).
    """
    if until is None and collisions is None:
        raise TypeError("run() needs until= (a time) or collisions= (a count)")
    operations = list(operations)
    for k, operation in enumerate(operations):
        if not isinstance(operation, Operation):
            raise TypeError(f"operations[{k}] must be an edmd2d.operations.Operation, got "
                            f"{type(operation).__name__}")
    t_end = math.inf if until is None else float(as_float_array("until", until, ()))
    if t_end < sim.time:
        raise ValueError(f"until={t_end} is earlier than the current time {sim.time}")
    c_end = math.inf if collisions is None else (
        sim.counts.collisions + as_count("collisions", collisions))
    by_time = until is not None
    bar, owned = _progress.bar(progress, total=(t_end - sim.time) if by_time else collisions,
                               unit="time" if by_time else "coll", desc="run")
    try:
        for operation in operations:
            operation.trigger._start(sim)
        for operation in operations:
            operation.begin(sim)
        clocked = any(isinstance(o.trigger, Every) and o.trigger.seconds is not None
                      for o in operations)
        while True:
            stop = min([t_end] + [o.trigger.next_time() for o in operations])
            left = [n_left for o in operations
                    if (n_left := o.trigger.collisions_left(sim)) is not None]
            budget = c_end - sim.counts.collisions
            if left:
                budget = min(budget, *left)
            if clocked:
                budget = min(budget, WALL_CLOCK_SLICE)
            c_before = sim.counts.collisions
            # (A stop at the current time needs no advance: its events are done.)
            if budget > 0 and not stop <= sim.time:
                # With a bar over the simulated time, advance moves it as it runs (and
                # shows the collisions per second); a bar of collisions moves here.
                sim.advance(until=None if math.isinf(stop) else stop,
                            collisions=None if math.isinf(budget) else int(budget),
                            progress=bar if bar is not None and by_time else False)
            if bar is not None and not by_time:
                bar.update(sim.counts.collisions - c_before)
            now = _time.monotonic()
            for operation in operations:
                if operation.trigger.due(sim, now):
                    operation(sim)
            if sim.time >= t_end or sim.counts.collisions >= c_end:
                return sim
    finally:
        if owned:
            bar.close()
        for operation in operations:
            operation.close()


def _stack(frames: list) -> np.ndarray:
    if not frames:
        return np.zeros((0, 0, 2))
    return np.stack(frames)
