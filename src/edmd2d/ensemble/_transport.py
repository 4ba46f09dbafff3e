"""The task of a sweep for transport coefficients (:mod:`edmd2d.transport`)."""

from __future__ import annotations

import os

import numpy as np

from .. import config as _config
from ..transport import transport

__all__ = ["transport_task"]

# The keys of transport_task besides those of edmd2d.config.SWEEP_KEYS.
_OWN_KEYS = ("dt", "window")


def transport_task(parameters: dict, seed: np.random.SeedSequence | int | None,
                   workdir: str | os.PathLike[str]) -> dict:
    """A task of :func:`sweep`: the transport coefficients of an elastic gas.

    The gas is built from ``parameters`` as :func:`eos_task` builds it (a periodic
    box, no model), run for ``equilibrate`` of simulated time or
    ``equilibrate_collisions`` collisions per disk, then measured by
    :func:`edmd2d.transport.transport` over ``duration`` in ``blocks`` blocks, with
    samples every ``dt`` and windows up to ``window``.  The task keeps no
    checkpoint: an interrupted task runs again from its start.

    Parameters
    ----------
    parameters : dict
        ``dt`` and ``window`` (required, as :func:`edmd2d.transport.transport` takes
        them), and the keys of :data:`edmd2d.config.SWEEP_KEYS` (``n``,
        ``packing_fraction`` and ``duration`` required).
    seed : numpy.random.SeedSequence, int or None
        The seed of the start (positions, velocities).
    workdir : str or os.PathLike
        The task's directory (unused).

    Returns
    -------
    dict
        ``shear_viscosity``, ``bulk_viscosity``, ``thermal_conductivity`` and
        ``diffusion`` (of all disks together, or of the first species in a
        mixture: ``diffusion_<k>`` for each species ``k``), each with ``*_error``;
        ``temperature``, ``pressure``, ``time`` (the end of the run) and
        ``collisions`` (in the measurement).

    Raises
    ------
    edmd2d.config.ConfigError
        For parameters that cannot be used (naming the key).
    ValueError
        For ``dt`` or ``window`` missing or refused by
        :func:`~edmd2d.transport.transport`, or a system without transport
        coefficients (walls, say).

    Examples
    --------
    >>> import tempfile
    >>> from edmd2d import ensemble
    >>> result = ensemble.sweep(
    ...     ensemble.transport_task,
    ...     {"n": [100], "packing_fraction": [0.2, 0.4], "duration": [30.0],
    ...      "blocks": [5], "dt": [0.2], "window": [2.0]},
    ...     seed=1, output=tempfile.mkdtemp(), scheduler="serial")
    >>> len(result.rows), result.complete
    (2, True)
    >>> row = result.rows[1]
    >>> row["packing_fraction"], row["shear_viscosity"] > 0, "diffusion_error" in row
    (0.4, True, True)
    """
    if not isinstance(parameters, dict):
        raise TypeError(f"parameters must be a dict, got {type(parameters).__name__}")
    missing = [key for key in _OWN_KEYS if key not in parameters]
    if missing:
        raise ValueError(f"transport_task needs {' and '.join(missing)} in its parameters")
    cfg = _config.task_config({k: v for k, v in parameters.items() if k not in _OWN_KEYS})
    run = cfg.data["run"]
    sim, _ = _config.build(cfg, seed)
    if run.get("equilibrate_collisions") is not None:
        sim.advance(collisions=int(round(run["equilibrate_collisions"] * sim.n)))
    elif run["equilibrate"] > 0:
        sim.advance(until=sim.time + run["equilibrate"])
    c0 = sim.counts.collisions
    c = transport(sim, run["duration"], dt=parameters["dt"], window=parameters["window"],
                  blocks=run["blocks"])
    out = {"shear_viscosity": c.shear_viscosity,
           "shear_viscosity_error": c.shear_viscosity_error,
           "bulk_viscosity": c.bulk_viscosity, "bulk_viscosity_error": c.bulk_viscosity_error,
           "thermal_conductivity": c.thermal_conductivity,
           "thermal_conductivity_error": c.thermal_conductivity_error,
           "diffusion": float(c.diffusion[0]), "diffusion_error": float(c.diffusion_error[0])}
    if len(c.diffusion) > 1:
        for k, (d, e) in enumerate(zip(c.diffusion, c.diffusion_error)):
            out[f"diffusion_{k}"] = float(d)
            out[f"diffusion_{k}_error"] = float(e)
    out.update({"temperature": c.temperature, "pressure": c.pressure, "time": sim.time,
                "collisions": sim.counts.collisions - c0})
    return out
