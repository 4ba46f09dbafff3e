"""Operations with triggers: one run that drives several things at once.

:func:`run` advances a simulation and, on the way, fires each :class:`Operation` when
its :class:`Trigger` says: every ``dt`` of simulated time, at given times, every ``k``
collisions, or every so many seconds of wall-clock time.  A trigger in simulated time
fires at exactly that time, with every disk synchronized to it (the run stops there,
the operation reads the state, the run goes on: events are not changed by stopping);
a collision trigger fires right after its collision; a wall-clock trigger fires at the
first stop after its period has passed (the run stops at least every
``WALL_CLOCK_SLICE`` collisions while one is active).  Operations due at the same
moment fire in the order given.

Operations here: :class:`WriteGSD` (a frame of a GSD trajectory, see
:mod:`edmd2d.io.gsd`), :class:`Checkpoint` (a restart file, see
:mod:`edmd2d.checkpoint`), and :class:`Callback` (any function of the simulation).

Examples
--------
>>> import edmd2d as ed
>>> from edmd2d import operations as op
>>> sim = ed.make_gas(100, 0.3, seed=1)
>>> times = []
>>> _ = op.run(sim, until=2.0, operations=[op.Callback(lambda s: times.append(s.time),
...                                                  op.Every(dt=0.5))])
>>> times
[0.5, 1.0, 1.5, 2.0]
"""

from __future__ import annotations

import math
import time as _time

import numpy as np

from . import checkpoint as _checkpoint
from ._validate import as_count, as_float_array, as_positive_float

__all__ = ["Trigger", "Every", "At", "Operation", "Callback", "WriteGSD", "Checkpoint",
           "run", "WALL_CLOCK_SLICE"]

# Collisions at most between two stops while a wall-clock trigger is active.
WALL_CLOCK_SLICE = 100_000


class Trigger:
    """When an operation fires (see :class:`Every` and :class:`At`)."""

    def _start(self, sim) -> None:
        """Set the first firing from the state at the start of a run."""

    def next_time(self) -> float:
        """The next simulated time at which to fire (``inf``: none)."""
        return math.inf

    def collisions_left(self, sim) -> int | None:
        """Collisions until the next firing, or ``None``."""
        return None

    def due(self, sim, now: float) -> bool:
        """Whether to fire at this stop (and, if so, set the next firing)."""
        return False


class Every(Trigger):
    """Fire periodically: every ``dt`` of simulated time, every ``collisions``
    collisions, or every ``seconds`` of wall-clock time (exactly one of them).

    Parameters
    ----------
    dt : float, optional
        Simulated time, > 0: at ``t0 + dt, t0 + 2 dt, ...`` from the run's start.
    collisions : int, optional
        Disk-disk collisions, >= 1.
    seconds : float, optional
        Wall-clock time, > 0.
    """

    def __init__(self, dt=None, collisions=None, seconds=None) -> None:
        given = [name for name, v in (("dt", dt), ("collisions", collisions),
                                      ("seconds", seconds)) if v is not None]
        if len(given) != 1:
            raise TypeError("Every() needs exactly one of dt=, collisions=, seconds=; got "
                            f"{given or 'none'}")
        self.dt = None if dt is None else as_positive_float("dt", dt)
        self.collisions = None if collisions is None else as_count("collisions", collisions,
                                                                   minimum=1)
        self.seconds = None if seconds is None else as_positive_float("seconds", seconds)

    def _start(self, sim) -> None:
        self._t0 = sim.time
        self._k = 1
        self._c_next = sim.counts.collisions + (self.collisions or 0)
        self._clock = _time.monotonic()

    def next_time(self) -> float:
        return self._t0 + self._k * self.dt if self.dt is not None else math.inf

    def collisions_left(self, sim):
        if self.collisions is None:
            return None
        return max(self._c_next - sim.counts.collisions, 0)

    def due(self, sim, now: float) -> bool:
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

    def __init__(self, times) -> None:
        times = np.sort(np.atleast_1d(as_float_array("times", times, (None,))))
        self.times = times

    def _start(self, sim) -> None:
        self._k = int(np.searchsorted(self.times, sim.time, side="left"))

    def next_time(self) -> float:
        return float(self.times[self._k]) if self._k < len(self.times) else math.inf

    def due(self, sim, now: float) -> bool:
        fired = False
        while self._k < len(self.times) and self.times[self._k] <= sim.time:
            self._k += 1
            fired = True
        return fired


class Operation:
    """Something done to or with the simulation when ``trigger`` fires."""

    def __init__(self, trigger: Trigger) -> None:
        if not isinstance(trigger, Trigger):
            raise TypeError(f"trigger must be an edmd2d.operations.Trigger, got {trigger!r}")
        self.trigger = trigger

    def __call__(self, sim) -> None:  # pragma: no cover - the subclasses' job
        raise NotImplementedError

    def close(self) -> None:
        """Release what the operation holds (at the end of the run)."""


class Callback(Operation):
    """Call ``function(sim)`` when ``trigger`` fires."""

    def __init__(self, function, trigger: Trigger) -> None:
        super().__init__(trigger)
        if not callable(function):
            raise TypeError(f"function must be callable, got {function!r}")
        self.function = function

    def __call__(self, sim) -> None:
        self.function(sim)


class WriteGSD(Operation):
    """Append a frame to the GSD file ``path`` when ``trigger`` fires (see
    :class:`edmd2d.io.gsd.Writer`; ``mode`` ``"w"`` or ``"a"``)."""

    def __init__(self, path, trigger: Trigger, mode: str = "w") -> None:
        super().__init__(trigger)
        from .io.gsd import Writer

        self.writer = Writer(path, mode)

    def __call__(self, sim) -> None:
        self.writer.write(sim)

    def close(self) -> None:
        self.writer.close()


class Checkpoint(Operation):
    """Write a checkpoint to ``path`` when ``trigger`` fires, replacing the previous
    one atomically (see :func:`edmd2d.checkpoint.save`)."""

    def __init__(self, path, trigger: Trigger) -> None:
        super().__init__(trigger)
        self.path = path

    def __call__(self, sim) -> None:
        _checkpoint.save(sim, self.path)


def run(sim, until=None, collisions=None, operations=(), progress=False):
    """Advance ``sim`` to ``until`` (and/or by ``collisions``), firing ``operations``.

    Parameters
    ----------
    sim : Simulation
    until : float, optional
        The end time (as for :meth:`Simulation.advance`).
    collisions : int, optional
        Stop after this many further collisions (whichever of the two comes first).
    operations : sequence of Operation
    progress : bool, default False
        A progress bar over the run (:mod:`edmd2d.progress`).

    Returns
    -------
    Simulation
        ``sim``.  Every operation is closed at the end (also on an error).
    """
    from . import progress as _progress

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
    for operation in operations:
        operation.trigger._start(sim)
    clocked = any(isinstance(o.trigger, Every) and o.trigger.seconds is not None
                  for o in operations)
    by_time = until is not None
    bar, owned = _progress.bar(progress, total=(t_end - sim.time) if by_time else collisions,
                               unit="time" if by_time else "coll", desc="run")
    try:
        while True:
            stop = min([t_end] + [o.trigger.next_time() for o in operations])
            left = [o.trigger.collisions_left(sim) for o in operations]
            left = [k for k in left if k is not None]
            budget = c_end - sim.counts.collisions
            if left:
                budget = min(budget, min(left))
            if clocked:
                budget = min(budget, WALL_CLOCK_SLICE)
            t_before, c_before = sim.time, sim.counts.collisions
            if budget > 0:
                sim.advance(until=None if math.isinf(stop) else stop,
                            collisions=None if math.isinf(budget) else int(budget))
            if bar is not None:
                bar.update((sim.time - t_before) if by_time
                           else sim.counts.collisions - c_before)
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
