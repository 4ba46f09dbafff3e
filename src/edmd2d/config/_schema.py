"""What a configuration may hold: its error, the checked configuration, and the
schema of each table (keys, checks of their values, defaults) with the checks of a
table against its schema.

The keys of ``[model]`` are read from the physics registry (:mod:`edmd2d.physics`) at
each use, so that a family registered later takes part.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import physics
from ._lines import _dotted, _line_of, _shown, _unknown


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


def _switch(value):
    if isinstance(value, bool):
        return value, None
    return None, f"expected true or false, got {_shown(value)}"


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
    "temperature": (_number(0.0, lo_open=True), 1.0),
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
    "switch": _switch,
    "length": _number(0.0, lo_open=True),
    "nonnegative": _number(0.0),
    "rate": _number(),
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
    "open": (_switch, False),
    "opens_at": (_number(0.0), OPTIONAL),
    # A motion (edmd2d.Translation with velocity and distance, or edmd2d.Oscillation
    # with amplitude and omega); a polygon's sides move together.
    "velocity": (_vector(), OPTIONAL),
    "distance": (_number(0.0, lo_open=True), OPTIONAL),
    "begin": (_number(), OPTIONAL),
    "amplitude": (_number(0.0, lo_open=True), OPTIONAL),
    "omega": (_number(0.0, lo_open=True), OPTIONAL),
    "direction": (_vector(), OPTIONAL),
    "phase": (_number(), OPTIONAL),
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


# ------------------------------------------------------------------ checking
# A table against its schema, and the species of [gas] (a run and a sweep's
# parameter set alike).
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
