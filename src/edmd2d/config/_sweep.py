"""Sweep configurations: reading and checking them (:func:`load_sweep`), and checking
one parameter set of a sweep as a run configuration (:func:`task_config`)."""

from __future__ import annotations

import itertools
import os

from ._lines import _shown, _unknown
from ._run import _parse, _read
from ._schema import (
    _GAS,
    _RUN,
    OPTIONAL,
    ConfigError,
    RunConfig,
    _check_species,
    _check_table,
    _integer,
    _model_schema,
    _number,
)

# The tables of a sweep's parameter sets: those of a run, less the physics and the
# walls (a sweep measures the equation of state of a gas), with two more keys.
_SWEEP_RUN = {**_RUN, "equilibrate_collisions": (_number(0.0), OPTIONAL)}
_SWEEP_OUTPUT = {"checkpoint_every": (_number(0.0, lo_open=True), OPTIONAL)}
_SWEEP_TABLES: dict[str, dict] = {"gas": _GAS, "run": _SWEEP_RUN, "output": _SWEEP_OUTPUT}
_SWEEP = {"replicas": (_integer(1), 1), "seed": (_integer(0), OPTIONAL)}

# The keys of a sweep's parameter set, each with the table it belongs to
# (edmd2d.config.SWEEP_KEYS, documented where the package exports it).
SWEEP_KEYS: dict[str, str] = {
    **{key: table for table, schema in _SWEEP_TABLES.items() for key in schema},
    "species": "gas",
}


def load_sweep(path: str | os.PathLike[str]) -> RunConfig:
    """Read and check the sweep configuration file ``path`` (``edmd2d sweep``).

    A sweep configuration has the ``[gas]`` and ``[run]`` tables of a run
    configuration (``[gas]`` with its ``[[gas.species]]``, ``[run]`` with one more
    key, ``equilibrate_collisions``), an optional ``[output]`` table with
    ``checkpoint_every`` only, and a ``[sweep]`` table::

        [sweep]
        replicas = 2              # runs of each parameter set, each with its own seed
        seed = 2024               # the root of every task's seed (default: drawn, recorded)

        [sweep.grid]              # every combination of these lists (the last fastest)
        packing_fraction = [0.2, 0.3, 0.4]
        n = [100, 400]

        [[sweep.points]]          # and/or parameter sets given one by one, each
        temperature = 1.0         # combined with every combination of the grid

    The keys of ``[sweep.grid]`` and ``[[sweep.points]]`` are those of ``[gas]``,
    ``[run]`` and ``[output]`` (:data:`SWEEP_KEYS`, but not ``species``) and replace
    their values there.  ``n``, ``packing_fraction`` and ``duration`` may be given in
    the grid instead of their tables.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    RunConfig
        ``data["sweep"]`` holds ``replicas``, ``seed``, ``grid`` and ``points`` and
        ``parameters``: the list of parameter sets, flat dicts of the keys given
        (those of the tables overridden by the grid's and the point's), in the order
        of the tasks.  ``data["gas"]``, ``data["run"]`` and ``data["output"]`` hold
        the keys of the tables as given (checked, without defaults).

    Raises
    ------
    ConfigError
        For a file that cannot be read, is not valid TOML, has an unknown table or
        key, a value of the wrong type or out of range, or a parameter set that
        cannot be used (naming the key and its line).
    """
    return loads_sweep(*_read(path))


def loads_sweep(text: str, path: str = "<config>") -> RunConfig:
    """Check the sweep configuration in the TOML string ``text`` (see :func:`load_sweep`).

    Parameters
    ----------
    text : str
    path : str, default "<config>"
        The name to use in messages.

    Returns
    -------
    RunConfig
        As for :func:`load_sweep`.

    Raises
    ------
    ConfigError
        As for :func:`load_sweep`.

    Examples
    --------
    >>> cfg = loads_sweep("[sweep]\\nreplicas = 2\\n[sweep.grid]\\n"
    ...                   "packing_fraction = [0.2, 0.3]\\n[gas]\\nn = 100\\n"
    ...                   "[run]\\nduration = 5\\n")
    >>> cfg.data["sweep"]["parameters"]
    [{'n': 100, 'duration': 5.0, 'packing_fraction': 0.2}, \
{'n': 100, 'duration': 5.0, 'packing_fraction': 0.3}]
    """
    raw, cfg = _parse(text, path)
    for name in raw:
        if name not in ("sweep", *_SWEEP_TABLES):
            raise cfg.error((name,), _unknown(name, ("sweep", *_SWEEP_TABLES), "table"))
    base: dict = {}
    for name, schema in _SWEEP_TABLES.items():
        value = raw.get(name, {})
        if not isinstance(value, dict):
            raise cfg.error((name,), f"expected a table [{name}], got {_shown(value)}")
        loose = {key: (check, OPTIONAL) for key, (check, _) in schema.items()}
        checked = _check_table(cfg, (name,), value, loose,
                               skip=("species",) if name == "gas" else ())
        cfg.data[name] = {key: checked[key] for key in value if key in checked}
        if "species" in value:
            cfg.data[name]["species"] = value["species"]
        base.update(cfg.data[name])
    table = raw.get("sweep", {})
    if not isinstance(table, dict):
        raise cfg.error(("sweep",), f"expected a table [sweep], got {_shown(table)}")
    sweep = _check_table(cfg, ("sweep",), table, _SWEEP, skip=("grid", "points"))
    sweep["grid"] = _check_grid(cfg, table.get("grid", {}))
    sweep["points"] = _check_points(cfg, table.get("points", [{}]))
    cfg.data["sweep"] = sweep
    parameters = []
    for k, point in enumerate(sweep["points"]):
        for values in itertools.product(*sweep["grid"].values()):
            params = dict(base)
            params.update(point)
            params.update(zip(sweep["grid"], values))
            try:
                task_config(params)
            except ConfigError as exc:
                key = _sweep_key(exc.key, point, sweep["grid"], k)
                raise cfg.error(key, f"{exc.message} (in the parameter set "
                                     f"{_overrides(params, base)})") from None
            parameters.append(params)
    sweep["parameters"] = parameters
    return cfg


def _check_value(key: str, value):
    """``value`` checked as the sweep key ``key``: (checked, problem)."""
    table = SWEEP_KEYS[key]
    return _SWEEP_TABLES[table][key][0](value)


def _check_grid(cfg, grid) -> dict:
    where = ("sweep", "grid")
    if not isinstance(grid, dict):
        raise cfg.error(where, "expected a table [sweep.grid] of lists of values")
    out = {}
    for key, values in grid.items():
        _known_sweep_key(cfg, where + (key,), key)
        if not isinstance(values, list) or not values:
            raise cfg.error(where + (key,), f"expected a list of values, got {_shown(values)}")
        checked = []
        for given in values:
            value, problem = _check_value(key, given)
            if problem:
                raise cfg.error(where + (key,), f"each value: {problem}")
            checked.append(value)
        out[key] = checked
    return out


def _check_points(cfg, points) -> list:
    where = ("sweep", "points")
    if not isinstance(points, list) or not points or not all(isinstance(p, dict)
                                                             for p in points):
        raise cfg.error(where, "expected tables [[sweep.points]] (one a parameter set)")
    out = []
    for k, point in enumerate(points):
        row = {}
        for key, value in point.items():
            _known_sweep_key(cfg, where + (k, key), key)
            checked, problem = _check_value(key, value)
            if problem:
                raise cfg.error(where + (k, key), problem)
            row[key] = checked
        out.append(row)
    return out


def _known_sweep_key(cfg, where: tuple, key: str) -> None:
    if key == "species":
        raise cfg.error(where, "a mixture is given in [[gas.species]], not swept over")
    if key not in SWEEP_KEYS:
        raise cfg.error(where, _unknown(key, [k for k in SWEEP_KEYS if k != "species"]))


def _sweep_key(dotted: str | None, point: dict, grid: dict, k: int) -> tuple:
    """The key of a sweep configuration behind an error in a parameter set."""
    parts = tuple(dotted.split(".")) if dotted else ()
    name = parts[1] if len(parts) > 1 else None
    if name in grid:
        return ("sweep", "grid", name)
    if name in point:
        return ("sweep", "points", k, name)
    return parts


def _overrides(params: dict, base: dict) -> str:
    changed = {k: v for k, v in params.items() if base.get(k, _MISSING) != v}
    return "{" + ", ".join(f"{k} = {v!r}" for k, v in changed.items()) + "}" if changed \
        else "of the tables"


_MISSING = object()


def task_config(parameters: dict, path: str = "<parameters>") -> RunConfig:
    """Check a sweep's parameter set: a flat dict of the keys of :data:`SWEEP_KEYS`.

    Parameters
    ----------
    parameters : dict
        ``n``, ``packing_fraction`` and ``duration`` are required; every other key
        takes its default (as in a run configuration).  ``species`` is a list of
        dicts as the ``[[gas.species]]`` tables.
    path : str, default "<parameters>"
        The name to use in messages.

    Returns
    -------
    RunConfig
        With the tables ``gas``, ``run`` and ``output`` filled in with their defaults,
        and ``model`` (the defaults: an elastic gas) and ``walls`` (none), ready for
        :func:`build`.

    Raises
    ------
    ConfigError
        For an unknown key, a missing one, or a value of the wrong type or out of
        range (naming the key as ``table.key``).
    TypeError
        If ``parameters`` is not a dict.

    Examples
    --------
    >>> cfg = task_config({"n": 100, "packing_fraction": 0.3, "duration": 5})
    >>> cfg.data["gas"]["start"], cfg.data["run"]["blocks"]
    ('lattice', 10)
    """
    if not isinstance(parameters, dict):
        raise TypeError(f"a parameter set must be a dict, got {type(parameters).__name__}")
    cfg = RunConfig({}, "", path)
    raw: dict = {name: {} for name in _SWEEP_TABLES}
    for key, value in parameters.items():
        if key not in SWEEP_KEYS:
            raise ConfigError(_unknown(key, SWEEP_KEYS), str(key), path=path)
        raw[SWEEP_KEYS[key]][key] = value
    for name, schema in _SWEEP_TABLES.items():
        cfg.data[name] = _check_table(cfg, (name,), raw[name], schema,
                                      skip=("species",) if name == "gas" else ())
    _check_species(cfg, raw["gas"])
    run = cfg.data["run"]
    if run["equilibrate_collisions"] is not None and "equilibrate" in raw["run"]:
        raise cfg.error(("run", "equilibrate_collisions"),
                        "give either equilibrate (a time) or equilibrate_collisions "
                        "(collisions per disk), not both")
    cfg.data["model"] = _check_table(cfg, ("model",), {}, _model_schema())
    cfg.data["model"]["wall_temperatures"] = None
    cfg.data["walls"] = []
    return cfg
