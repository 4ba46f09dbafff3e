"""The task of a sweep for the common case: the equation of state of a gas."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from .. import checkpoint as _checkpoint
from .. import config as _config
from .._runs import FAILED, INTERRUPTED, RunProtocol
from .._version import __version__
from ..analysis import hexatic_order
from ._store import _json_default

__all__ = ["eos_task"]

# The checkpoint of eos_task in its workdir, and the kind of its metadata.
_EOS_CHECKPOINT = "checkpoint.edmd2d"
_EOS_FORMAT = "edmd2d-eos-task"
_EOS_VERSION = 2


def eos_task(parameters: dict, seed: np.random.SeedSequence | int | None,
             workdir: str | os.PathLike[str]) -> dict:
    """A task of :func:`sweep`: the equation of state of a gas, with checkpoints.

    The gas is built from ``parameters`` as ``edmd2d run`` builds the ``[gas]`` of a
    configuration (:func:`edmd2d.config.task_config`, then
    :func:`edmd2d.config.build`: ``make_gas``, or ``random_gas`` with
    ``start="random"``), run for ``equilibrate`` of simulated time or
    ``equilibrate_collisions`` collisions per disk, then measured over ``duration``
    in ``blocks`` (an :class:`~edmd2d.operations.Measure`), by the protocol that
    ``edmd2d run`` follows too.  A checkpoint
    (:class:`~edmd2d.operations.Checkpoint`) in ``workdir`` is written at the end of
    the equilibration, at the end of each block and every ``checkpoint_every`` of
    simulated time if given; it holds the state of the measurement, and a call that
    finds one continues from it, to the same numbers to the last bit as a run that
    never stopped.

    Parameters
    ----------
    parameters : dict
        The keys of :data:`edmd2d.config.SWEEP_KEYS`: ``n``, ``packing_fraction`` and
        ``duration`` (required), ``temperature``, ``radius``, ``mass``, ``species``
        (a list of dicts as the ``[[gas.species]]`` tables: ``radius``, ``mass``,
        ``count`` or ``fraction``), ``aspect``, ``periodic``, ``start``
        (``"lattice"`` or ``"random"``), ``equilibrate``, ``equilibrate_collisions``,
        ``blocks`` and ``checkpoint_every``.
    seed : numpy.random.SeedSequence, int or None
        The seed of the start (positions, velocities).
    workdir : str or os.PathLike
        An existing directory for the checkpoint.

    Returns
    -------
    dict
        ``Z`` (the compressibility factor), ``pressure``, ``temperature`` and
        ``collision_rate`` (per disk), each with ``*_error``, its standard error over
        the blocks; ``psi6``, the global ``|psi_6|`` of the last configuration
        (:func:`edmd2d.hexatic_order`); ``collisions`` in the window; ``time``, the
        end of the run.

    Raises
    ------
    edmd2d.config.ConfigError
        For parameters that cannot be used (naming the key).
    ValueError
        If ``workdir`` holds a checkpoint of other parameters, or of another version
        of the task.
    RuntimeError
        If the simulation fails (an inelastic collapse, say); the checkpoint then
        holds the state before the failure, and a later call raises again.
    """
    cfg = _config.task_config(parameters)
    path = Path(workdir) / _EOS_CHECKPOINT
    given = json.loads(json.dumps(parameters, default=_json_default))
    if path.exists():
        meta = _checkpoint.read_metadata(path)
        if meta.get("format") != _EOS_FORMAT or meta.get("parameters") != given:
            raise ValueError(f"{path} is the checkpoint of another run (parameters "
                             f"{meta.get('parameters')}); remove it to start afresh")
        if meta.get("version") != _EOS_VERSION:
            raise ValueError(f"{path} holds a task of format version {meta.get('version')}; "
                             f"this edmd2d {__version__} continues version {_EOS_VERSION} "
                             "(remove it to start afresh)")
        sim = _checkpoint.load(path)
    else:
        sim, _ = _config.build(cfg, seed)
        meta = RunProtocol.start(sim, {"format": _EOS_FORMAT, "version": _EOS_VERSION,
                                       "parameters": given}, cfg.data["run"])
    failure = meta.get("failure")
    if failure is not None:
        raise RuntimeError(f"this task failed at t={failure['time']:g}: {failure['error']} "
                           f"(its state is in {path})")
    protocol = RunProtocol(sim, meta, path, run=cfg.data["run"], output=cfg.data["output"],
                           block_checkpoints=True)
    status = protocol.execute()
    if status == INTERRUPTED:
        raise KeyboardInterrupt
    if status == FAILED:
        raise RuntimeError(meta["failure"]["error"])
    m = protocol.result()
    psi, _ = hexatic_order(sim)
    return {
        "Z": m.compressibility_factor, "Z_error": m.compressibility_factor_error,
        "pressure": m.pressure, "pressure_error": m.pressure_error,
        "temperature": m.temperature, "temperature_error": m.temperature_error,
        "collision_rate": m.collision_rate, "collision_rate_error": m.collision_rate_error,
        "psi6": abs(psi), "collisions": m.collisions, "time": sim.time,
    }
