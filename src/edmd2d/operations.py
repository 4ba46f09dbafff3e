"""Operations with triggers: one run that drives several things at once.

:func:`run` advances a simulation and, on the way, fires each :class:`Operation` when
its :class:`Trigger` says: every ``dt`` of simulated time, at given times, at the ends
of the equal blocks of a window, every ``k`` collisions, or every so many seconds of
wall-clock time.  A trigger in simulated time fires at exactly that time, with every
disk synchronized to it (the run stops there, the operation reads the state, the run
goes on: events are not changed by stopping); a collision trigger fires right after its
collision; a wall-clock trigger fires at the first stop after its period has passed
(the run stops at least every ``WALL_CLOCK_SLICE`` collisions while one is active).
Operations due at the same moment fire in the order given, so that one listed after
another sees what the first did (a :class:`Callback` after a :class:`Measure` with
the same trigger reads the block just ended).

Operations here:

- :class:`Measure`: pressure, temperature, collision rates and wall forces over the run,
  in blocks, as a :class:`~edmd2d.measurements.Measurement`
  (:func:`edmd2d.measurements.measure` is one run with one of them);
- :class:`Profile`: density, packing fraction, flow velocity and granular temperature
  in slabs along an axis, sampled at each firing
  (:func:`edmd2d.measurements.profiles` is one run with one of them);
- :class:`Transport`: the Einstein-Helfand moments, displacements and velocities
  every ``dt``, for the viscosities, the thermal conductivity, self-diffusion and
  the velocity autocorrelation (:func:`edmd2d.transport.transport` is one run with
  one of them);
- :class:`RecordTrajectory`: positions (and velocities) at each firing
  (:func:`edmd2d.analysis.trajectory` is one run with one of them);
- :class:`RecordFrames`: a :class:`Snapshot` of everything a picture shows at each
  firing, for :func:`edmd2d.viz.animate_frames` to replay;
- :class:`WriteGSD`: a frame of a GSD trajectory (see :mod:`edmd2d.io.gsd`);
- :class:`Checkpoint`: a restart file (see :mod:`edmd2d.checkpoint`);
- :class:`Callback`: any function of the simulation.

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

A measurement in four blocks and a trajectory from one run:

>>> sim = ed.make_gas(100, 0.3, seed=1)
>>> window = op.Measure(op.Blocks(duration=2.0, blocks=4))
>>> path = op.RecordTrajectory(op.Every(dt=0.5), include_start=True)
>>> _ = sim.run(until=2.0, operations=[window, path])
>>> window.result().blocks, path.positions.shape
(4, (5, 100, 2))
"""

from __future__ import annotations

from . import _operations
from ._operations import (
    At,
    Blocks,
    Callback,
    Every,
    Operation,
    RecordFrames,
    RecordTrajectory,
    Snapshot,
    Trigger,
    run,
)
from .checkpoint import Checkpoint
from .io.gsd import WriteGSD
from .measurements import Measure, Profile
from .transport import Transport

__all__ = ["Trigger", "Every", "At", "Blocks", "Operation", "Callback", "Measure",
           "Profile", "Transport", "RecordTrajectory", "RecordFrames", "Snapshot", "WriteGSD",
           "Checkpoint", "run", "WALL_CLOCK_SLICE"]

#: Collisions at most between two stops while a wall-clock trigger is active, so that
#: ``Every(seconds=...)`` fires within a fraction of a second of its time.
WALL_CLOCK_SLICE = _operations.WALL_CLOCK_SLICE
