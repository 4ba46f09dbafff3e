"""Run configurations in TOML: reading, checking and building the simulation they describe.

A configuration (see ``examples/gas.toml``) has these tables; only ``[gas]`` with ``n``
and ``packing_fraction``, and ``[run]`` with ``duration``, are required::

    [gas]                      # a gas from a lattice start (edmd2d.make_gas)
    n = 400                    # number of disks
    packing_fraction = 0.4     # area fraction of the box
    temperature = 1.0          # kT of the Maxwell-Boltzmann start
    radius = 0.5               # equal disks ...
    mass = 1.0
    aspect = 1.0               # box width / height
    periodic = true            # or false (walled box), or [true, false] (a channel)
    start = "lattice"          # or "random" (edmd2d.random_gas: a disordered start,
                               # packing_fraction <= 0.5)

    [[gas.species]]            # ... or a mixture: one table per species, instead of
    radius = 0.5               # gas.radius and gas.mass
    mass = 1.0
    fraction = 0.5             # or count = 200 (all species alike)

    [model]                    # the physics (edmd2d.Simulation), all optional
    restitution = 0.9          # or a table per pair of species: [[1.0, 0.9], [0.9, 0.8]]
    wall_restitution = 1.0
    tc = 1e-5
    gravity = [0.0, -0.1]
    thermostat = [1.0, 0.1]    # [kT, rate per disk]
    seed = 1                   # random numbers of the start, thermostat and heated walls

    [model.wall_temperatures]  # heated walls: box walls by name, segments by index
    bottom = 2.0

    [[walls]]                  # wall segments, optional: start and end ...
    start = [10.0, 0.0]
    end = [10.0, 8.0]
    [[walls]]                  # ... or a closed polygon
    polygon = [[2.0, 2.0], [6.0, 2.0], [4.0, 5.0]]
    [[walls]]                  # a gate, closed at the start, open from t = 40 on
    start = [4.0, 6.0]         # (or open = true: open from the start, to close
    end = [6.0, 6.0]           # later from Python with Simulation.close_wall)
    opens_at = 40.0

    [run]
    equilibrate = 20.0         # simulated time run before measuring
    duration = 50.0            # the measurement window
    blocks = 10                # its blocks: one row of the table each, and the error bars

    [output]                   # optional
    gsd_every = 5.0            # a GSD frame every this much simulated time
    checkpoint_every = 25.0    # a checkpoint every this much simulated time ...
    checkpoint_minutes = 10.0  # ... and/or every this many minutes of wall-clock time

Every key is checked: a misspelt or unknown key, a value of the wrong type or out of
range is a :class:`ConfigError` that names the key and the line of the file where it
stands.  (TOML parsers give no line numbers for keys, so they are found by scanning the
text for each key within its table.)  Disks of the lattice start that a wall segment
crosses are left out (their number is reported).
"""

from __future__ import annotations

from . import _sweep
from ._build import build
from ._run import load, loads
from ._schema import ConfigError, RunConfig
from ._sweep import load_sweep, loads_sweep, task_config

__all__ = ["ConfigError", "RunConfig", "load", "loads", "build", "load_sweep",
           "loads_sweep", "task_config", "SWEEP_KEYS"]

# (Bound here, not imported by name, so that its documentation comment is read from
# this module, whose page documents it.)
#: The keys of a sweep's parameter set, each with the table it belongs to: a parameter
#: set is one flat dict (``{"n": 400, "packing_fraction": 0.3, "duration": 50.0}``).
SWEEP_KEYS: dict[str, str] = _sweep.SWEEP_KEYS

