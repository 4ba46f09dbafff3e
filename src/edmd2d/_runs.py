"""One run of a configured system: equilibrate, measure in blocks, checkpoint, continue.

``edmd2d run`` and ``edmd2d resume`` (:mod:`edmd2d.cli`) and the task of a sweep
(:func:`edmd2d.ensemble.eos_task`) run a system the same way, through
:class:`RunProtocol`:

1. equilibrate: run for ``equilibrate`` of simulated time after the start, or for
   ``equilibrate_collisions`` collisions per disk since the system was built;
2. measure: a :class:`~edmd2d.operations.Measure` over a window of ``duration`` cut
   into ``blocks`` equal blocks, starting where the equilibration ends, and going on
   block after block past the window's end when the run is asked to go further;
3. checkpoint: every ``checkpoint_every`` of simulated time (counted from the start),
   every ``checkpoint_minutes`` of wall-clock time, optionally at the end of each
   block, and always at the end of the equilibration and of the run; a checkpoint's
   metadata holds the run's dict, in which the protocol keeps the start
   (``t_start``), the window's start (``window_start``, ``None`` until the
   equilibration has ended) and the state of the measurement (``measure``), so that
   a run continued from it gives the same numbers, to the last bit, as a run that
   never stopped;
4. optionally, a GSD frame every ``gsd_every`` of simulated time.

A run stopped by Ctrl-C or failed with a :class:`RuntimeError` of the simulation (an
inelastic collapse, say) saves the state it stands in, with the failure in the
metadata, and says so in its status; what it measured before is kept.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from . import checkpoint as _checkpoint
from . import operations as _op
from .io import gsd as _gsd

__all__ = ["RunProtocol", "DONE", "INTERRUPTED", "FAILED"]

#: The statuses of :meth:`RunProtocol.execute`.
DONE, INTERRUPTED, FAILED = "done", "interrupted", "failed"


class RunProtocol:
    """Equilibrate, measure in blocks and checkpoint one simulation.

    Parameters
    ----------
    sim : Simulation
        The system, new or loaded from the protocol's checkpoint.
    meta : dict
        The run's metadata, saved with every checkpoint (it must be JSON-able); the
        protocol keeps ``t_start``, ``window_start``, ``measure`` and, after a
        failure, ``failure`` in it (see :meth:`start`).
    checkpoint : str or os.PathLike
        The checkpoint file, replaced atomically at each save.
    run : dict
        ``equilibrate`` (simulated time), ``equilibrate_collisions`` (per disk;
        ``None`` or absent to equilibrate by time), ``duration`` and ``blocks``.
    output : dict
        ``checkpoint_every`` (simulated time), ``checkpoint_minutes`` and
        ``gsd_every`` (simulated time), each ``None`` or absent for none.
    gsd : str or os.PathLike, optional
        The GSD file of the frames (with ``gsd_every``).  A new run (``resumed``
        false) writes it afresh, with the start as its first frame; a continued run
        appends to it.
    resumed : bool, default False
        Whether ``sim`` was loaded from a checkpoint of this run.
    block_checkpoints : bool, default False
        Save a checkpoint at the end of every block too.
    on_block : callable, optional
        Called as ``on_block(sim, measure)`` at the window's start and at the end of
        every block (after the measure has taken its boundary).
    annotate : callable, optional
        Called with ``meta`` before every save, to add what the caller keeps there.
    """

    def __init__(self, sim, meta: dict, checkpoint, *, run: dict, output: dict, gsd=None,
                 resumed: bool = False, block_checkpoints: bool = False, on_block=None,
                 annotate=None) -> None:
        self.sim, self.meta, self.path = sim, meta, Path(checkpoint)
        self.run, self.output = run, output
        self.gsd, self.resumed = gsd, resumed
        self.block_checkpoints = block_checkpoints
        self.on_block, self.annotate = on_block, annotate
        self.measure = None
        if meta["measure"] is not None:
            self.measure = _op.Measure.from_state(meta["measure"])

    @staticmethod
    def start(sim, meta: dict, run: dict) -> dict:
        """Set the protocol's keys of ``meta`` for a run that starts now.

        With equilibration by time the window's start is known at once
        (``t_start + equilibrate``); with equilibration by collisions it is set when
        the equilibration ends.

        Parameters
        ----------
        sim : Simulation
        meta : dict
        run : dict
            As for :class:`RunProtocol`.

        Returns
        -------
        dict
            ``meta``.
        """
        t0 = sim.time
        by_time = run.get("equilibrate_collisions") is None
        meta.update({"t_start": t0, "window_start": t0 + run["equilibrate"] if by_time
                     else None, "measure": None})
        return meta

    # ------------------------------------------------------------------ the window
    def _blocks(self, count: int | None = None) -> _op.Blocks:
        return _op.Blocks(self.run["duration"], self.run["blocks"],
                          start=self.meta["window_start"], count=count)

    @property
    def window_end(self) -> float | None:
        """The end of the measurement window (``None`` before its start is known)."""
        if self.meta["window_start"] is None:
            return None
        return self.block_edge(self.run["blocks"])

    def block_edge(self, b: int) -> float:
        """The end of block ``b`` of the measurement (``b = 0``: its start).

        Parameters
        ----------
        b : int

        Returns
        -------
        float
        """
        return self._blocks().edge(b)

    def blocks_until(self, until: float) -> int:
        """How many blocks end by ``until``: the window's own, or more of the same
        length when the run goes on past the window's end.

        Parameters
        ----------
        until : float

        Returns
        -------
        int
        """
        trigger = self._blocks()
        count = self.run["blocks"]
        while trigger.edge(count + 1) <= until:
            count += 1
        return count

    @property
    def equilibrated(self) -> bool:
        """Whether the equilibration has ended (the window's start is reached)."""
        start = self.meta["window_start"]
        return start is not None and self.sim.time >= start

    # ------------------------------------------------------------------ the run
    def execute(self, until: float | None = None, *, progress=False) -> str:
        """Run to ``until`` (default: the end of the window) and save a checkpoint.

        Parameters
        ----------
        until : float, optional
            Not before the simulation's time.
        progress : bool or tqdm bar, default False
            As for :meth:`~edmd2d.Simulation.run`.

        Returns
        -------
        str
            :data:`DONE` (``until`` reached), :data:`INTERRUPTED` (Ctrl-C) or
            :data:`FAILED` (the simulation raised a :class:`RuntimeError`; its
            message and time are in ``meta["failure"]``).
        """
        sim = self.sim
        status = DONE
        writer = None
        try:
            writer = self._open_gsd()
            periodic = self._periodic(writer)
            if not self.equilibrated:
                self._equilibrate(until, periodic, progress)
            if self.equilibrated:
                end = self.window_end if until is None else until
                assert end is not None  # (the window's start, so its end, is known)
                if sim.time < end or self.measure is None:
                    self._measure(end, periodic, progress)
        except KeyboardInterrupt:
            status = INTERRUPTED
        except RuntimeError as exc:
            # (The simulation stands at the last event before the problem: keep it
            # and what was measured up to it.)
            status = FAILED
            self.meta["failure"] = {"time": sim.time, "error": str(exc)}
        finally:
            if writer is not None:
                writer.close()
        self.save()
        return status

    def _equilibrate(self, until: float | None, periodic: Callable[[], list[_op.Operation]],
                     progress) -> None:
        sim, run, meta = self.sim, self.run, self.meta
        if run.get("equilibrate_collisions") is not None:
            left = round(run["equilibrate_collisions"] * len(sim)) - sim.counts.collisions
            if left > 0:
                sim.run(until=until, collisions=left, operations=periodic(),
                        progress=progress)
            if round(run["equilibrate_collisions"] * len(sim)) <= sim.counts.collisions:
                meta["window_start"] = sim.time
        else:
            stop = meta["window_start"] if until is None else min(until,
                                                                    meta["window_start"])
            if sim.time < stop:
                sim.run(until=stop, operations=periodic(), progress=progress)
        if self.equilibrated:
            self.save()

    def _measure(self, until: float, periodic: Callable[[], list[_op.Operation]],
                 progress) -> None:
        sim = self.sim
        count = self.blocks_until(until)
        if self.measure is None:
            self.measure = _op.Measure(self._blocks(count))
        else:
            self.measure = _op.Measure.from_state(self.meta["measure"], count=count)
        operations: list[_op.Operation] = [self.measure]
        if self.on_block is not None:
            if self.measure.blocks == 0 and sim.time == self.meta["window_start"]:
                self.on_block(sim, self.measure)  # (the window opens now)
            operations.append(_op.Callback(lambda s: self.on_block(s, self.measure),
                                           self._blocks(count)))
        if self.block_checkpoints:
            operations.append(_op.Checkpoint(self.path, self._blocks(count),
                                             metadata=self._metadata))
        if sim.time < until:
            sim.run(until=until, operations=operations + periodic(), progress=progress)

    def _periodic(self, writer) -> Callable[[], list[_op.Operation]]:
        """A maker of the operations of the whole run (made anew for each
        :meth:`~edmd2d.Simulation.run`, since a run closes its operations; the GSD
        writer stays open across them)."""
        out, t0 = self.output, self.meta["t_start"]

        def make() -> list[_op.Operation]:
            ops: list[_op.Operation] = []
            if writer is not None:
                ops.append(_op.Callback(writer.write, _op.Every(dt=out["gsd_every"],
                                                                start=t0)))
            if out.get("checkpoint_every") is not None:
                ops.append(_op.Checkpoint(self.path, _op.Every(dt=out["checkpoint_every"],
                                                               start=t0),
                                          metadata=self._metadata))
            for time, segments in self.meta.get("wall_openings", []):
                # (A gate opening during the run: opening an open segment changes
                # nothing, so a run resumed after it is left as it was.)
                ops.append(_op.Callback(_opener(segments), _op.At([time])))
            if out.get("checkpoint_minutes") is not None:
                ops.append(_op.Checkpoint(
                    self.path, _op.Every(seconds=60.0 * out["checkpoint_minutes"]),
                    metadata=self._metadata))
            return ops

        return make

    def _open_gsd(self):
        if self.gsd is None or self.output.get("gsd_every") is None:
            return None
        writer = _gsd.Writer(self.gsd, "a" if self.resumed else "w")
        if not self.resumed:
            writer.write(self.sim)  # (the first frame: the start)
            self.resumed = True  # (a second execute appends)
        return writer

    # ------------------------------------------------------------------ the files
    def _metadata(self, sim) -> dict:
        meta = self.meta
        meta["measure"] = None if self.measure is None else self.measure.state()
        if self.annotate is not None:
            self.annotate(meta)
        return meta

    def save(self) -> None:
        """Save the simulation and the run's metadata to the checkpoint."""
        _checkpoint.save(self.sim, self.path, metadata=self._metadata(self.sim))

    def result(self):
        """The measurement over the blocks ended so far, or ``None`` before the first.

        Returns
        -------
        Measurement or None
        """
        if self.measure is None or self.measure.blocks == 0:
            return None
        return self.measure.result()


def _opener(segments: list[int]) -> Callable:
    """A callback that opens the wall ``segments`` of the simulation it is given."""
    def open_them(sim) -> None:
        for k in segments:
            sim.open_wall(k)
    return open_them
