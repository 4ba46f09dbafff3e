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

import difflib
import itertools
import math
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import builders, physics
from ._validate import argument_of, as_generator
from .builders import make_gas, random_gas
from .geometry import BOX_WALLS, Wall
from .simulation import Simulation

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = ["ConfigError", "RunConfig", "load", "loads", "build", "load_sweep",
           "loads_sweep", "task_config", "SWEEP_KEYS"]


class ConfigError(ValueError):
    """A configuration that cannot be used: what is wrong, with the key and its line.

    Parameters
    ----------
    message : str
        What is wrong.
    key : str, optional
        The dotted key (``"gas.packing_fraction"``, ``"walls[1].start"``).
    line : int, optional
        Its line in the file (1-based).
    path : str, optional
        The file.
    """

    def __init__(self, message: str, key: str | None = None, line: int | None = None,
                 path: str | None = None) -> None:
        self.message, self.key, self.line, self.path = message, key, line, path
        where = path or "<config>"
        if line is not None:
            where += f", line {line}"
        super().__init__(f"{where}: {key + ': ' if key else ''}{message}")


@dataclass
class RunConfig:
    """A checked configuration.

    Attributes
    ----------
    data : dict
        The configuration with every default filled in (plain TOML values).
    text : str
        The file's text.
    path : str
        Where it was read from (``"<config>"`` for a string).
    lines : dict
        The line of each key and table of the text (see :meth:`error`).
    """

    data: dict
    text: str
    path: str = "<config>"
    lines: dict = field(default_factory=dict, repr=False)

    def error(self, key: tuple, message: str) -> ConfigError:
        """A :class:`ConfigError` for ``key`` (a path of names and indices) with its line.

        Parameters
        ----------
        key : tuple
        message : str

        Returns
        -------
        ConfigError
        """
        return ConfigError(message, _dotted(key), _line_of(self.lines, key), self.path)


# ------------------------------------------------------------------ the schema
# Each key: (checker, default).  REQUIRED marks keys without a default; OPTIONAL keys
# stay None when absent.
REQUIRED = object()
OPTIONAL = None


def _number(lo=None, hi=None, *, lo_open=False, hi_open=False):
    def check(value):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return None, f"expected a number, got {_shown(value)}"
        value = float(value)
        if not math.isfinite(value):
            return None, f"expected a finite number, got {value}"
        if lo is not None and (value < lo or (lo_open and value == lo)):
            return None, f"must be {'>' if lo_open else '>='} {lo:g}, got {value:g}"
        if hi is not None and (value > hi or (hi_open and value == hi)):
            return None, f"must be {'<' if hi_open else '<='} {hi:g}, got {value:g}"
        return value, None
    return check


def _integer(lo=None):
    def check(value):
        if isinstance(value, bool) or not isinstance(value, int):
            return None, f"expected an integer, got {_shown(value)}"
        if lo is not None and value < lo:
            return None, f"must be >= {lo}, got {value}"
        return value, None
    return check


def _vector(length=2):
    def check(value):
        if (not isinstance(value, list) or len(value) != length
                or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in value)):
            return None, f"expected a list of {length} numbers, got {_shown(value)}"
        if not all(math.isfinite(v) for v in value):
            return None, f"expected finite numbers, got {value}"
        return [float(v) for v in value], None
    return check


def _periodic(value):
    if isinstance(value, bool):
        return value, None
    if isinstance(value, list) and len(value) == 2 and all(isinstance(v, bool) for v in value):
        return list(value), None
    return None, f"expected true, false or [true/false, true/false], got {_shown(value)}"


def _restitution(value):
    if isinstance(value, list):
        if not value or not all(isinstance(row, list) and len(row) == len(value)
                                for row in value):
            return None, "expected a number or a square table (a list of equal rows)"
        out = []
        for row in value:
            for v in row:
                if isinstance(v, bool) or not isinstance(v, (int, float)):
                    return None, f"table entries must be numbers, got {_shown(v)}"
            out.append([float(v) for v in row])
        return out, None
    return _number(0.0, 1.0, lo_open=True)(value)


def _choice(*options):
    def check(value):
        if value not in options or not isinstance(value, str):
            return None, (f"expected one of {', '.join(map(repr, options))}, got "
                          f"{_shown(value)}")
        return value, None
    return check


def _polygon(value):
    if not isinstance(value, list) or len(value) < 3:
        return None, f"expected a list of at least 3 points [x, y], got {_shown(value)}"
    points = []
    for point in value:
        checked, problem = _vector()(point)
        if problem:
            return None, f"each vertex: {problem}"
        points.append(checked)
    return points, None


_GAS = {
    "n": (_integer(1), REQUIRED),
    "packing_fraction": (_number(0.0, 1.0, lo_open=True, hi_open=True), REQUIRED),
    "temperature": (_number(0.0), 1.0),
    "radius": (_number(0.0, lo_open=True), OPTIONAL),
    "mass": (_number(0.0, lo_open=True), OPTIONAL),
    "aspect": (_number(0.0, lo_open=True), 1.0),
    "periodic": (_periodic, True),
    "start": (_choice("lattice", "random"), "lattice"),
}
_SPECIES = {
    "radius": (_number(0.0, lo_open=True), REQUIRED),
    "mass": (_number(0.0, lo_open=True), 1.0),
    "count": (_integer(0), OPTIONAL),
    "fraction": (_number(0.0, 1.0), OPTIONAL),
}
# What a file's value of each kind of physics keyword (edmd2d.physics.Keyword.kind) must
# look like; the library checks the rest when it builds the system.  "walls" (heated
# walls) has a check of its own, _check_wall_temperatures.
_KINDS = {
    "coefficients": _restitution,
    "coefficient": _number(0.0, 1.0, lo_open=True),
    "duration": _number(0.0),
    "vector": _vector(),
}


def _model_schema() -> dict:
    """[model]: the keywords of every registered physics family that files take, and
    the seed (read from the registry at each use: a family registered later is in it)."""
    return {
        **{kw.name: (_KINDS[kw.kind], OPTIONAL if kw.default is None else kw.default)
           for kw in physics.KEYWORDS.values() if kw.kind in _KINDS},
        "seed": (_integer(0), OPTIONAL),
    }


def _model_own_checks() -> tuple:
    """The [model] keys with a check of their own (heated walls)."""
    return tuple(kw.name for kw in physics.KEYWORDS.values() if kw.kind == "walls")


_WALL = {
    "start": (_vector(), OPTIONAL),
    "end": (_vector(), OPTIONAL),
    "polygon": (_polygon, OPTIONAL),
}
_RUN = {
    "equilibrate": (_number(0.0), 0.0),
    "duration": (_number(0.0, lo_open=True), REQUIRED),
    "blocks": (_integer(1), 10),
}
_OUTPUT = {
    "gsd_every": (_number(0.0, lo_open=True), OPTIONAL),
    "checkpoint_every": (_number(0.0, lo_open=True), OPTIONAL),
    "checkpoint_minutes": (_number(0.0, lo_open=True), OPTIONAL),
}


def _tables() -> dict:
    return {"gas": _GAS, "model": _model_schema(), "walls": _WALL, "run": _RUN,
            "output": _OUTPUT}


def load(path) -> RunConfig:
    """Read and check the configuration file ``path``.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    RunConfig

    Raises
    ------
    ConfigError
        For a file that cannot be read, is not valid TOML, or whose keys or values are
        wrong (naming the key and its line).
    """
    return loads(*_read(path))


def _read(path) -> tuple[str, str]:
    """The text of the file ``path`` and its name, or a ConfigError saying why not."""
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8"), str(path)
    except FileNotFoundError:
        raise ConfigError("no such file", path=str(path)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"cannot be read ({exc})", path=str(path)) from None


def loads(text: str, path: str = "<config>") -> RunConfig:
    """Check the configuration in the TOML string ``text``.

    Parameters
    ----------
    text : str
    path : str, default "<config>"
        The name to use in messages.

    Returns
    -------
    RunConfig

    Raises
    ------
    ConfigError
        As for :func:`load`.

    Examples
    --------
    >>> cfg = loads("[gas]\\nn = 100\\npacking_fraction = 0.3\\n[run]\\nduration = 5\\n")
    >>> cfg.data["run"]["blocks"], cfg.data["gas"]["temperature"]
    (10, 1.0)
    >>> try:
    ...     loads("[gas]\\nn = 100\\npacking_fractoin = 0.3\\n[run]\\nduration = 5\\n")
    ... except ConfigError as exc:
    ...     print(exc)
    <config>, line 3: gas.packing_fractoin: unknown key (did you mean 'packing_fraction'?)
    """
    raw, cfg = _parse(text, path)
    data = cfg.data
    tables = _tables()
    for name in raw:
        if name not in tables:
            raise cfg.error((name,), _unknown(name, tables, "table"))
    if "gas" not in raw:
        raise cfg.error(("gas",), "the table [gas] is required (n, packing_fraction)")
    if "run" not in raw:
        raise cfg.error(("run",), "the table [run] is required (duration)")
    for name, schema in tables.items():
        if name == "walls":
            continue
        value = raw.get(name, {})
        if not isinstance(value, dict):
            raise cfg.error((name,), f"expected a table [{name}], got {_shown(value)}")
        data[name] = _check_table(cfg, (name,), value, schema,
                                  skip=("species",) if name == "gas" else
                                  _model_own_checks() if name == "model" else ())
    _check_species(cfg, raw["gas"])
    _check_wall_temperatures(cfg, raw.get("model", {}))
    _check_walls(cfg, raw.get("walls", []))
    return cfg


def _parse(text: str, path: str):
    """The TOML of ``text`` as a dict, and an empty :class:`RunConfig` with its lines."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        found = re.search(r"line (\d+)", str(exc))
        raise ConfigError(f"not valid TOML: {exc}", line=int(found.group(1)) if found else None,
                          path=path) from None
    return raw, RunConfig({}, text, path, _key_lines(text))


def _check_table(cfg, where: tuple, value: dict, schema: dict, skip=()) -> dict:
    out = {}
    for key in value:
        if key not in schema and key not in skip:
            raise cfg.error(where + (key,), _unknown(key, list(schema) + list(skip)))
    for key, (check, default) in schema.items():
        if key not in value:
            if default is REQUIRED:
                raise cfg.error(where + (key,), "is required")
            out[key] = default
            continue
        checked, problem = check(value[key])
        if problem:
            raise cfg.error(where + (key,), problem)
        out[key] = checked
    return out


def _check_species(cfg, gas: dict) -> None:
    data = cfg.data["gas"]
    species = gas.get("species")
    data["species"] = None
    if species is None:
        data["radius"] = 0.5 if data["radius"] is None else data["radius"]
        data["mass"] = 1.0 if data["mass"] is None else data["mass"]
        return
    if not isinstance(species, list) or not species or not all(isinstance(s, dict)
                                                               for s in species):
        raise cfg.error(("gas", "species"), "expected tables [[gas.species]] (one a species)")
    for key in ("radius", "mass"):
        if data[key] is not None:
            raise cfg.error(("gas", key), "give the radius and mass of each [[gas.species]] "
                                          "instead of gas." + key)
    rows = [_check_table(cfg, ("gas", "species", k), s, _SPECIES)
            for k, s in enumerate(species)]
    kinds = {("count" if r["count"] is not None else "")
             + ("fraction" if r["fraction"] is not None else "") for r in rows}
    if len(kinds) != 1 or kinds not in ({"count"}, {"fraction"}):
        k = next((k for k, r in enumerate(rows)
                  if (r["count"] is None) == (r["fraction"] is None)), 0)
        raise cfg.error(("gas", "species", k), "give every species either a count or a "
                                                 "fraction (one of them, the same for all)")
    n = data["n"]
    if kinds == {"count"}:
        total = sum(r["count"] for r in rows)
        if total != n:
            raise cfg.error(("gas", "n"), f"is {n}, but the species' counts add up to {total}")
    else:
        fractions = np.array([r["fraction"] for r in rows])
        if abs(fractions.sum() - 1.0) > 1e-9:
            raise cfg.error(("gas", "species", len(rows) - 1, "fraction"),
                            f"the species' fractions add up to {fractions.sum():g}, not 1")
        # Largest remainders: counts that add up to n, each within one of n * fraction.
        exact = fractions * n
        counts = np.floor(exact).astype(int)
        order = np.argsort(-(exact - counts), kind="stable")
        counts[order[:n - counts.sum()]] += 1
        for r, c in zip(rows, counts):
            r["count"] = int(c)
    data["species"] = rows


def _check_wall_temperatures(cfg, model: dict) -> None:
    value = model.get("wall_temperatures")
    where = ("model", "wall_temperatures")
    out = None
    if value is not None:
        if not isinstance(value, dict):
            raise cfg.error(where, "expected a table {wall = kT} (box walls by name, "
                                   "segments by index)")
        out = {}
        for key, kt in value.items():
            if key not in BOX_WALLS and not key.isdigit():
                raise cfg.error(where + (key,), _unknown(key, BOX_WALLS, "wall")
                                + " (or a segment's index)")
            checked, problem = _number(0.0, lo_open=True)(kt)
            if problem:
                raise cfg.error(where + (key,), problem)
            out[key] = checked
    cfg.data["model"]["wall_temperatures"] = out


def _check_walls(cfg, walls) -> None:
    if not isinstance(walls, list) or not all(isinstance(w, dict) for w in walls):
        raise cfg.error(("walls",), "expected tables [[walls]] (start and end, or polygon)")
    rows = []
    for k, w in enumerate(walls):
        row = _check_table(cfg, ("walls", k), w, _WALL)
        segment = row["start"] is not None or row["end"] is not None
        if segment == (row["polygon"] is not None) or (segment and None in (row["start"],
                                                                            row["end"])):
            raise cfg.error(("walls", k), "give either start and end, or polygon")
        rows.append(row)
    cfg.data["walls"] = rows


# ------------------------------------------------------------------ sweeps
# The tables of a sweep's parameter sets: those of a run, less the physics and the
# walls (a sweep measures the equation of state of a gas), with two more keys.
_SWEEP_RUN = {**_RUN, "equilibrate_collisions": (_number(0.0), OPTIONAL)}
_SWEEP_OUTPUT = {"checkpoint_every": (_number(0.0, lo_open=True), OPTIONAL)}
_SWEEP_TABLES = {"gas": _GAS, "run": _SWEEP_RUN, "output": _SWEEP_OUTPUT}
_SWEEP = {"replicas": (_integer(1), 1), "seed": (_integer(0), OPTIONAL)}

#: The keys of a sweep's parameter set, each with the table it belongs to: a parameter
#: set is one flat dict (``{"n": 400, "packing_fraction": 0.3, "duration": 50.0}``).
SWEEP_KEYS: dict[str, str] = {
    **{key: table for table, schema in _SWEEP_TABLES.items() for key in schema},
    "species": "gas",
}


def load_sweep(path) -> RunConfig:
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
        for value in values:
            value, problem = _check_value(key, value)
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


# ------------------------------------------------------------------ building
# Keyword of make_gas or Simulation -> the key of the configuration it comes from.
_ARGUMENT_KEYS = {
    "n": ("gas", "n"), "packing_fraction": ("gas", "packing_fraction"),
    "temperature": ("gas", "temperature"), "radius": ("gas", "radius"),
    "radii": ("gas", "species"), "masses": ("gas", "mass"), "aspect": ("gas", "aspect"),
    "periodic": ("gas", "periodic"), "species": ("gas", "species"),
    "walls": ("walls",), "positions": ("walls",), "velocities": ("walls",),
    "seed": ("model", "seed"),
}


def _key_of_argument(exc: BaseException) -> tuple:
    """The configuration key of the argument a library error is about, or ``()``."""
    name = argument_of(exc)
    if name in physics.KEYWORDS and physics.KEYWORDS[name].kind:
        return ("model", name)
    return _ARGUMENT_KEYS.get(name, ())


def build(cfg: RunConfig, seed: int):
    """The simulation a configuration describes, at time 0.

    Without wall segments or a mixture of masses this is
    ``edmd2d.make_gas(n, packing_fraction, ..., seed=seed)`` with the ``[model]``
    keywords (``edmd2d.random_gas`` with ``start = "random"``).  A mixture's species
    are laid on the lattice at random (species of equal radius told apart by a further
    random draw) and, if their masses differ,
    their velocities are drawn for their masses; disks that a wall segment crosses are
    left out (by :func:`edmd2d.builders.clear_of_walls`, the rule of ``make_gas(...,
    walls=...)``).

    Parameters
    ----------
    cfg : RunConfig
    seed : int or numpy.random.SeedSequence
        The seed of all random numbers (``[model] seed``, or one drawn by the caller).

    Returns
    -------
    sim : Simulation
    removed : int
        Disks left out because a wall segment crossed them.

    Raises
    ------
    ConfigError
        If the library refuses a value (the message is the library's, with the key
        and line it comes from).
    """
    gas, model = cfg.data["gas"], cfg.data["model"]
    rng = as_generator("seed", seed)
    species = gas["species"]
    try:
        if species is None:
            radii, masses, radius = None, gas["mass"], gas["radius"]
        else:
            radii = np.repeat([s["radius"] for s in species], [s["count"] for s in species])
            species_masses = np.array([s["mass"] for s in species])
            masses = float(species_masses[0]) if (species_masses == species_masses[0]).all() \
                else 1.0
            radius = 0.5
        start = (random_gas if gas["start"] == "random" else make_gas)(
            gas["n"], gas["packing_fraction"], radius=radius, radii=radii, masses=masses,
            aspect=gas["aspect"], periodic=_box_kind(gas), temperature=gas["temperature"],
            seed=rng)
        pos, vel, rad, mass = (start.positions, start.velocities, start.radii,
                               start.masses.copy())
        labels = None
        if species is not None:
            labels = _species_labels(rad, species, rng)
            mass = species_masses[labels]
            if not (species_masses == species_masses[0]).all():
                vel = builders._maxwell_boltzmann(rng, mass, gas["temperature"],
                                                  sum(start.box.periodic))
        walls = []
        for w in cfg.data["walls"]:
            if w["polygon"] is not None:
                walls.extend(Wall.polygon(w["polygon"]))
            else:
                walls.append(Wall(tuple(w["start"]), tuple(w["end"])))
        # (The rule of make_gas(walls=...); the species are labelled before, on the
        # whole lattice, so that each keeps its count there.)
        keep = builders.clear_of_walls(pos, rad, walls, start.box)
        if not keep.any():
            raise cfg.error(("walls",), "the wall segments cross every disk of the gas")
        wall_kt = model["wall_temperatures"]
        if wall_kt is not None:
            wall_kt = {(int(k) if k.isdigit() else k): v for k, v in wall_kt.items()}
        sim = Simulation(
            pos[keep], vel[keep], rad[keep], mass[keep], box=start.box, walls=walls,
            species=None if labels is None else labels[keep],
            restitution=(model["restitution"] if not isinstance(model["restitution"], list)
                         else np.array(model["restitution"])),
            wall_restitution=model["wall_restitution"], tc=model["tc"],
            gravity=model["gravity"], wall_temperatures=wall_kt,
            thermostat=model["thermostat"], seed=rng,
            **{name: model[name] for name, kw in physics.KEYWORDS.items()
               if kw.kind in _KINDS and not physics.owner(name).built_in
               and model.get(name) is not None})
    except (TypeError, ValueError) as exc:
        if isinstance(exc, ConfigError):
            raise
        raise cfg.error(_key_of_argument(exc), str(exc)) from None
    return sim, int((~keep).sum())


def _box_kind(gas: dict):
    periodic = gas["periodic"]
    return tuple(periodic) if isinstance(periodic, list) else periodic


def _species_labels(radii: np.ndarray, species: list, rng) -> np.ndarray:
    """Each disk's species, from its radius (``make_gas`` shuffles the radii over the
    lattice); among species of equal radius, a random permutation decides."""
    labels = np.empty(len(radii), np.int64)
    species_radii = np.array([s["radius"] for s in species])
    for r in np.unique(species_radii):
        ids = np.flatnonzero(species_radii == r)
        members = np.repeat(ids, [species[k]["count"] for k in ids])
        where = np.flatnonzero(radii == r)
        labels[where] = members if len(ids) == 1 else rng.permutation(members)
    return labels



# ------------------------------------------------------------------ messages and lines
def _unknown(key: str, known, what: str = "key") -> str:
    close = difflib.get_close_matches(key, list(known), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else (
        f" (known: {', '.join(map(str, known))})")
    return f"unknown {what}{hint}"


def _shown(value) -> str:
    kind = {str: "a string", bool: "a boolean", int: "an integer", float: "a number",
            list: "a list", dict: "a table"}.get(type(value), type(value).__name__)
    return f"{kind} {value!r}" if not isinstance(value, dict) else kind


def _dotted(key: tuple) -> str:
    out = ""
    for part in key:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else part)
    return out


def _line_of(lines: dict, key: tuple) -> int | None:
    """The line of ``key``, or of the nearest enclosing table or key that has one."""
    key = tuple(key)
    while key:
        if key in lines:
            return lines[key]
        key = key[:-1]
    return None


_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*$")
_NAME = r"""(?:[A-Za-z0-9_-]+|"[^"]*"|'[^']*')"""  # (a bare or quoted key)
_KEY = re.compile(rf"^\s*({_NAME}(?:\s*\.\s*{_NAME})*)\s*=(.*)$")


def _split_key(key: str) -> tuple:
    parts = re.findall(_NAME, key)
    return tuple(p[1:-1] if p[:1] in "\"'" else p for p in parts)


def _strip_comment(line: str) -> str:
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch == "#":
            return line[:i]
    return line


def _key_lines(text: str) -> dict:
    """Where each key and table of a TOML text is: ``{path: line}``, a path being the
    tuple of names (and indices of arrays of tables, ``("walls", 1, "start")``).

    A scan of the text, table header by table header: keys (also dotted and quoted)
    at the start of a line; the keys of an inline table ``{a = 1, b = 2}`` on the line
    of its key; the lines inside a value that spans several lines are skipped.
    """
    lines: dict = {}
    arrays: dict = {}
    table: tuple = ()
    depth = 0
    for number, raw in enumerate(text.splitlines(), start=1):
        line = _strip_comment(raw)
        if depth > 0:  # (inside a value of several lines: an array)
            depth += line.count("[") + line.count("{") - line.count("]") - line.count("}")
            continue
        header = _HEADER.match(line)
        if header:
            path = _split_key(header.group(2))
            if header.group(1) == "[[":
                k = arrays.get(path, 0)
                arrays[path] = k + 1
                lines.setdefault(path, number)
                path = path + (k,)
            else:
                # (a sub-table of the last element of an array of tables)
                for n in range(len(path) - 1, 0, -1):
                    if path[:n] in arrays:
                        path = path[:n] + (arrays[path[:n]] - 1,) + path[n:]
                        break
            table = path
            lines.setdefault(path, number)
            continue
        found = _KEY.match(line)
        if not found:
            continue
        path = table + _split_key(found.group(1))
        lines.setdefault(path, number)
        value = found.group(2)
        depth = value.count("[") + value.count("{") - value.count("]") - value.count("}")
        inline = value.strip()
        if inline.startswith("{"):
            for inner in re.finditer(r"([A-Za-z0-9_-]+)\s*=", inline):
                lines.setdefault(path + (inner.group(1),), number)
    return lines
