"""Reading and checking a run configuration: :func:`load` and :func:`loads`."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

from ..geometry import BOX_WALLS
from ._lines import _key_lines, _shown, _unknown
from ._schema import (
    _WALL,
    ConfigError,
    RunConfig,
    _check_species,
    _check_table,
    _model_own_checks,
    _number,
    _tables,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib


def load(path: str | os.PathLike[str]) -> RunConfig:
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


_TRANSLATION = ("velocity", "distance", "begin")
_OSCILLATION = ("amplitude", "omega", "direction", "phase")


def _check_motion(cfg, where: tuple, row: dict) -> None:
    """A [[walls]] table moves as a translation (``velocity`` and ``distance``, maybe
    ``begin``) or an oscillation (``amplitude`` and ``omega``, maybe ``direction`` and
    ``phase``), or not at all."""
    given = [key for key in _TRANSLATION + _OSCILLATION if row[key] is not None]
    if not given:
        return
    kind = _TRANSLATION if given[0] in _TRANSLATION else _OSCILLATION
    other = [key for key in given if key not in kind]
    if other:
        raise cfg.error(where + (other[0],),
                        f"a wall moves by velocity and distance (a translation) or by "
                        f"amplitude and omega (an oscillation), not both: {other[0]} with "
                        f"{given[0]}")
    for key in kind[:2]:
        if row[key] is None:
            raise cfg.error(where + (given[0],), f"{given[0]} needs {key} too")


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
        if row["open"] and row["opens_at"] is not None:
            raise cfg.error(("walls", k, "opens_at"),
                            "a wall that starts open (open = true) cannot open later")
        _check_motion(cfg, ("walls", k), row)
        rows.append(row)
    cfg.data["walls"] = rows
