"""The results of a sweep: its two files, ``results.json`` and ``results.csv``,
rewritten atomically as each task finishes, the check that a directory to resume
holds the same sweep, and :class:`SweepResult`, what :func:`~edmd2d.ensemble.load`
reads back."""

from __future__ import annotations

import csv
import io
import json
import math
import os
import platform
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _atomic
from .._version import __version__

# The format of results.json and its version; the files and the folder of the tasks in
# the output directory (described where edmd2d.ensemble exports them).
FORMAT = "edmd2d-sweep"
VERSION = 1
CSV_FILE = "results.csv"
JSON_FILE = "results.json"
TASKS_DIR = "tasks"

# The columns of the table before the parameters, between them and the values.
_HEAD = ("task", "point")
_MIDDLE = ("replica", "seed_entropy", "seed_spawn_key", "status", "error_type", "error")


# ------------------------------------------------------------------ the result
@dataclass
class SweepResult:
    """What a sweep found: the finished tasks, in the order of the tasks.

    Attributes
    ----------
    output : pathlib.Path
        The output directory.
    entropy : int
        The entropy of the root ``numpy.random.SeedSequence``.
    parameters : list of dict
        The parameter sets.
    replicas : int
        Tasks per parameter set.
    tasks : list of dict
        One record per finished task: ``task`` (its id), ``index``, ``point``,
        ``replica``, ``parameters``, ``seed`` (``entropy`` and ``spawn_key``),
        ``status`` (``"ok"`` or ``"failed"``), ``values`` (the dict returned, or
        ``None``), ``error`` (``None``, or ``type``, ``message`` and ``traceback``),
        ``seconds``, ``host`` and ``pid``.
    """

    output: Path
    entropy: int
    parameters: list
    replicas: int
    tasks: list

    @property
    def total(self) -> int:
        """The number of tasks of the sweep, finished or not."""
        return len(self.parameters) * self.replicas

    @property
    def rows(self) -> list[dict]:
        """The rows of ``results.csv``, as dicts of the columns."""
        return _rows(self.tasks)[1]

    @property
    def failed(self) -> list[dict]:
        """The records of the failed tasks."""
        return [t for t in self.tasks if t["status"] == "failed"]

    @property
    def complete(self) -> bool:
        """Whether every task has finished without error."""
        return len(self.tasks) == self.total and not self.failed

    def seed(self, task: str) -> np.random.SeedSequence:
        """The seed a task was given, made again from the record.

        Parameters
        ----------
        task : str
            The task's id (``"p002-r01"``).

        Returns
        -------
        numpy.random.SeedSequence
        """
        for record in self.tasks:
            if record["task"] == task:
                seed = record["seed"]
                return np.random.SeedSequence(seed["entropy"],
                                              spawn_key=tuple(seed["spawn_key"]))
        raise KeyError(f"no finished task {task!r} in {self.output}")


def load(output: str | os.PathLike[str]) -> SweepResult:
    """Read the results of a sweep (finished or not) from its output directory.

    Parameters
    ----------
    output : str or os.PathLike

    Returns
    -------
    SweepResult

    Raises
    ------
    FileNotFoundError
        If the directory holds no ``results.json``.
    ValueError
        If that file was not written by :func:`sweep`.
    """
    output = Path(output)
    data = _read_json(output)
    if data is None:
        raise FileNotFoundError(f"{output / JSON_FILE}: no such file")
    return SweepResult(output, data["entropy"], data["parameters"], data["replicas"],
                       data["tasks"])


class _State:
    """The records of a sweep and its two files."""

    def __init__(self, output, name, root, points, replicas, records, metadata):
        self.output, self.name, self.root = output, name, root
        self.points, self.replicas, self.records = points, replicas, records
        self.metadata = metadata
        self.versions = _versions()

    def add(self, record: dict) -> None:
        self.records[record["index"]] = record
        self.write()

    def ordered(self) -> list[dict]:
        return [self.records[k] for k in sorted(self.records)]

    def write(self) -> None:
        tasks = self.ordered()
        data = {
            "format": FORMAT, "version": VERSION, "versions": self.versions,
            "function": self.name, "entropy": self.root.entropy,
            "replicas": self.replicas, "total": len(self.points) * self.replicas,
            "finished": len(tasks),
            "failed": sum(t["status"] == "failed" for t in tasks),
            "parameters": self.points, "metadata": self.metadata, "tasks": tasks,
        }
        text = json.dumps(_strict(data), indent=1, allow_nan=False)
        _atomic.write_text(self.output / JSON_FILE, text + "\n")
        _atomic.write_text(self.output / CSV_FILE, _csv_text(tasks))

    def result(self) -> SweepResult:
        return SweepResult(self.output, self.root.entropy, self.points, self.replicas,
                           self.ordered())


# ------------------------------------------------------------------ resuming
def _read_json(output: Path) -> dict | None:
    path = output / JSON_FILE
    if not path.exists():
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise ValueError(f"{path} cannot be read as the results of a sweep ({exc})") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise ValueError(f"{path} was not written by edmd2d.ensemble.sweep: {output} holds "
                         "something else; give another output directory")
    if data.get("version") != VERSION:
        raise ValueError(f"{path} holds a sweep of format version {data.get('version')}; "
                         f"this edmd2d reads version {VERSION}")
    return data


def _check_same(output: Path, previous: dict, name: str, points: list, replicas: int,
                seed):
    """The seed to resume with, once ``output`` is known to hold this sweep."""
    def refuse(what: str):
        return ValueError(f"{output} holds another sweep ({what}); give another output "
                          "directory, or remove it to start afresh")

    if previous["function"] != name:
        raise refuse(f"of the function {previous['function']}, not {name}")
    if previous["replicas"] != replicas:
        raise refuse(f"{previous['replicas']} replicas, not {replicas}")
    old = previous["parameters"]
    if len(old) != len(points):
        raise refuse(f"{len(old)} parameter sets, not {len(points)}")
    for k, (a, b) in enumerate(zip(old, points)):
        if a != b:
            raise refuse(f"parameter set {k} is {a} there, {b} here")
    if seed is None:
        return previous["entropy"]
    if np.random.SeedSequence(seed).entropy != previous["entropy"]:
        raise refuse(f"of the seed entropy {previous['entropy']}, not that of seed={seed!r}")
    return seed


def _function_name(function) -> str:
    module = getattr(function, "__module__", None) or "?"
    qualname = getattr(function, "__qualname__", None) or type(function).__qualname__
    return f"{module}:{qualname}"


def _check_names(points: list) -> None:
    for k, point in enumerate(points):
        for name in point:
            if name in _HEAD or name in _MIDDLE:
                raise ValueError(f"parameter set {k} has a parameter named {name!r}, a "
                                 "column of the table of results: rename it")


# ------------------------------------------------------------------ the files
def _rows(tasks: list) -> tuple[list[str], list[dict]]:
    """The columns and rows of the table: ids, parameters, seed and status, values."""
    names: dict = {}
    values: dict = {}
    for t in tasks:
        names.update(dict.fromkeys(t["parameters"]))
        values.update(dict.fromkeys(t["values"] or {}))
    fixed = set(_HEAD) | set(names) | set(_MIDDLE)
    # (A value named like a parameter or a fixed column, such as the temperature a
    # run measured beside the temperature it was given, is "measured_" in the table.)
    shown = {v: (f"measured_{v}" if v in fixed else v) for v in values}
    columns = [*_HEAD, *names, *_MIDDLE, *shown.values()]
    rows = []
    for t in tasks:
        error = t["error"] or {}
        row = {"task": t["task"], "point": t["point"], **t["parameters"],
               "replica": t["replica"], "seed_entropy": t["seed"]["entropy"],
               "seed_spawn_key": t["seed"]["spawn_key"][-1],
               "status": t["status"], "error_type": error.get("type"),
               "error": error.get("message")}
        for v, column in shown.items():
            row[column] = (t["values"] or {}).get(v)
        rows.append({c: row.get(c) for c in columns})
    return columns, rows


def _csv_text(tasks: list) -> str:
    columns, rows = _rows(tasks)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([_cell(row[c]) for c in columns])
    return buf.getvalue()


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)  # (the shortest text that reads back to the same float)
    if isinstance(value, (list, dict)):
        return json.dumps(value)
    return str(value)


def _json_default(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, tuple):
        return list(value)
    raise TypeError(f"{type(value).__name__} {value!r} is not a JSON value")


def _strict(value):
    """``value`` with every float that is not finite as ``None`` (strict JSON)."""
    if isinstance(value, dict):
        return {k: _strict(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_strict(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _versions() -> dict:
    return {"edmd2d": __version__, "numpy": np.__version__,
            "python": platform.python_version(), "platform": sys.platform}
