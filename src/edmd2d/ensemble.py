"""Ensembles of runs: one function over a grid of parameter sets and seeds, on Dask.

:func:`sweep` runs ``function(parameters, seed, workdir)`` once for every parameter
set of a grid and every replica, each call a *task* with a seed of its own, and
collects what each returns (a small dict of numbers) into a table.  The tasks run on
a `Dask <https://distributed.dask.org>`_ cluster: one made for the sweep on this
machine (a single-threaded worker process per core), an existing one, or -- for
debugging -- one after another in this process, without Dask.

Seeds.  One ``numpy.random.SeedSequence(seed)`` is the root of all: its
``spawn`` gives one child per task, in the fixed order of the tasks (parameter set
by parameter set, replica by replica), so that every task gets the same seed however
and wherever the sweep runs, and the results are the same to the last bit.  The
root's entropy is recorded in the output (also when drawn because ``seed=None``),
and each task's seed is ``SeedSequence(entropy, spawn_key=(k,))`` for its index ``k``
(the column ``seed_spawn_key`` of the table).

The output directory holds

- ``results.csv``: a tidy table, one row per finished task: its id, the index of its
  parameter set, every parameter, its replica, its seed (``seed_entropy``,
  ``seed_spawn_key``), its status (``ok`` or ``failed``, with ``error_type`` and
  ``error``) and the values it returned (a value with an error bar as ``x`` and
  ``x_error``);
- ``results.json``: the same, and the tracebacks of the failed tasks, the root's
  entropy, the parameter sets, the task function's name, the versions and the time
  and host of each task;
- ``tasks/<task-id>/``: a directory for each task (``workdir``) for the files it
  writes: trajectories, checkpoints.

Both files are rewritten (to a temporary file renamed over the old one) as each task
finishes, so that an interrupted sweep -- Ctrl-C, a lost worker, a killed process --
keeps every finished task.  Running the same sweep again with the same output
*resumes* it: the finished tasks are read back, not run again (after checking that
the directory holds this sweep: the same function, parameter sets, replicas and
seed, or else a ``ValueError``), and the others run, each able to continue from what
it left in its ``workdir``.  A task that raises is recorded as failed, with its
parameters, the error and its traceback, and the others go on; a resumed sweep runs
failed tasks again (``retry_failed``).

:func:`eos_task` is a task for the common case: the equation of state of a gas
(built as ``edmd2d run`` builds it, see :mod:`edmd2d.config`), equilibrated and
measured in blocks, with checkpoints in its ``workdir`` from which a rerun continues
bit for bit.  ``edmd2d sweep CONFIG.toml`` runs it over the grid of a TOML file
(:func:`edmd2d.config.load_sweep`).

Examples
--------
>>> import tempfile
>>> from edmd2d import ensemble
>>> result = ensemble.sweep(
...     ensemble.eos_task,
...     {"n": [64], "packing_fraction": [0.2, 0.3], "duration": [2.0], "blocks": [2]},
...     replicas=2, seed=1, output=tempfile.mkdtemp(), scheduler="serial")
>>> len(result.rows), result.complete
(4, True)
>>> [round(row["Z"], 2) for row in result.rows]  # doctest: +SKIP
[1.58, 1.6, 2.07, 2.04]
"""

from __future__ import annotations

import csv
import io
import itertools
import json
import math
import os
import platform
import socket
import sys
import time as _time
import traceback
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import _atomic
from . import checkpoint as _checkpoint
from . import config as _config
from . import progress as _progress
from ._runs import FAILED, INTERRUPTED, RunProtocol
from ._version import __version__
from .analysis import hexatic_order
from .builders import make_gas

__all__ = ["sweep", "grid", "load", "eos_task", "warm", "SweepResult", "FORMAT",
           "VERSION", "CSV_FILE", "JSON_FILE", "TASKS_DIR"]

#: The format name in ``results.json``; a directory whose file has another is refused.
FORMAT = "edmd2d-sweep"
#: The version of that format.
VERSION = 1
#: The table of results in the output directory.
CSV_FILE = "results.csv"
#: Everything the table holds and more, as JSON, in the output directory.
JSON_FILE = "results.json"
#: The folder of the tasks' work directories in the output directory.
TASKS_DIR = "tasks"

# The columns of the table before the parameters, between them and the values.
_HEAD = ("task", "point")
_MIDDLE = ("replica", "seed_entropy", "seed_spawn_key", "status", "error_type", "error")
# The checkpoint of eos_task in its workdir, and the kind of its metadata.
_EOS_CHECKPOINT = "checkpoint.edmd2d"
_EOS_FORMAT = "edmd2d-eos-task"
_EOS_VERSION = 2


# ------------------------------------------------------------------ the grid
def grid(parameters) -> list[dict]:
    """The parameter sets of a sweep: a list of dicts as given, or every combination
    of a dict of lists.

    Parameters
    ----------
    parameters : list of dict or dict of lists
        Parameter sets (each a dict of JSON values: numbers, strings, booleans,
        ``None``, lists, dicts), or ``{name: [values]}`` expanded as a product, the
        last name varying fastest.

    Returns
    -------
    list of dict

    Raises
    ------
    TypeError
        For anything else, or values JSON cannot hold.
    ValueError
        For no parameter set at all, or an empty list of values.

    Examples
    --------
    >>> grid({"packing_fraction": [0.2, 0.3], "n": [100, 400]})
    [{'packing_fraction': 0.2, 'n': 100}, {'packing_fraction': 0.2, 'n': 400}, \
{'packing_fraction': 0.3, 'n': 100}, {'packing_fraction': 0.3, 'n': 400}]
    """
    if isinstance(parameters, dict):
        for name, values in parameters.items():
            if not isinstance(name, str):
                raise TypeError(f"parameter names must be strings, got {name!r}")
            if isinstance(values, (str, bytes, dict)) or not hasattr(values, "__iter__"):
                raise TypeError(f"parameters[{name!r}] must be a list of values, got "
                                f"{values!r} (a dict of lists is expanded as a product)")
        lists = {name: list(values) for name, values in parameters.items()}
        empty = [name for name, values in lists.items() if not values]
        if empty:
            raise ValueError(f"parameters[{empty[0]!r}] is an empty list: no parameter set")
        sets = [dict(zip(lists, values)) for values in itertools.product(*lists.values())]
    elif isinstance(parameters, (list, tuple)):
        sets = list(parameters)
        for k, point in enumerate(sets):
            if not isinstance(point, dict):
                raise TypeError(f"parameters[{k}] must be a dict, got {type(point).__name__}")
    else:
        raise TypeError("parameters must be a list of dicts or a dict of lists, got "
                        f"{type(parameters).__name__}")
    if not sets:
        raise ValueError("parameters holds no parameter set")
    out = []
    for k, point in enumerate(sets):
        for name in point:
            if not isinstance(name, str):
                raise TypeError(f"parameter names must be strings, got {name!r} in set {k}")
        try:
            out.append(json.loads(json.dumps(point, default=_json_default)))
        except (TypeError, ValueError) as exc:
            raise TypeError(f"parameter set {k} holds a value JSON cannot store ({exc})"
                            ) from None
    return out


@dataclass(frozen=True)
class _Task:
    index: int
    id: str
    point: int
    replica: int
    parameters: dict
    seed: np.random.SeedSequence


def _tasks(points: list, replicas: int, root: np.random.SeedSequence) -> list[_Task]:
    """Every task in order, each with its child of ``root`` (one spawn of them all,
    so that task ``k`` has the spawn key ``(k,)`` whatever runs)."""
    seeds = root.spawn(len(points) * replicas)
    wp = max(3, len(str(len(points) - 1)))
    wr = max(2, len(str(replicas - 1)))
    out = []
    for k, (p, r) in enumerate(itertools.product(range(len(points)), range(replicas))):
        out.append(_Task(k, f"p{p:0{wp}d}-r{r:0{wr}d}", p, r, points[p], seeds[k]))
    return out


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


def load(output) -> SweepResult:
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


# ------------------------------------------------------------------ the sweep
def sweep(function, parameters, *, output, replicas: int = 1, seed=None, scheduler=None,
          workers: int | None = None, progress=False, retry_failed: bool = True,
          warmup=None, metadata: dict | None = None) -> SweepResult:
    """Run ``function(parameters, seed, workdir)`` for every parameter set and replica.

    Parameters
    ----------
    function : callable
        A top-level (picklable) function of ``(parameters, seed, workdir)``: the
        parameter set (a dict, a copy of the caller's), the task's
        ``numpy.random.SeedSequence`` (``numpy.random.default_rng(seed)`` turns it into
        a generator) and the task's directory (a ``pathlib.Path`` that exists), where
        it may write files and find what an earlier, interrupted call left.  It
        returns a small dict of JSON values (numbers, strings, booleans, ``None``),
        ``x`` and ``x_error`` for a value with an error bar.
    parameters : list of dict or dict of lists
        The parameter sets (see :func:`grid`).
    output : str or os.PathLike
        The output directory (made if needed).  One that holds a sweep already is
        resumed: its finished tasks are kept.
    replicas : int, default 1
        Tasks per parameter set, each with its own seed.
    seed : int, sequence of int or None
        The entropy of the root ``SeedSequence``; ``None`` draws one (recorded), or,
        when resuming, takes the one recorded.
    scheduler : None, "serial", str or distributed.Client
        ``None``: a ``dask.distributed.LocalCluster`` made for the sweep, with one
        single-threaded worker process per core (``workers`` of them) and its
        dashboard on a free port, closed at the end.  ``"serial"``: the tasks one
        after another in this process, without Dask (for debugging; a
        ``KeyboardInterrupt`` in a task stops the sweep).  An
        address (``"tcp://10.0.0.2:8786"``), a ``distributed.Client`` or a cluster
        object: that cluster (a client made here is closed at the end, one given is
        not).  The workers of a remote cluster must see ``output`` at the same path
        (a shared file system) for the tasks' work directories.
    workers : int, optional
        The number of worker processes of the cluster made for ``scheduler=None``
        (default ``os.cpu_count()``).
    progress : bool or tqdm bar, default False
        A progress bar over the tasks (:mod:`edmd2d.progress`).
    retry_failed : bool, default True
        When resuming, run the tasks that failed again (else keep their records).
    warmup : callable or False, optional
        Called once on every worker of a Dask cluster before any task is sent, so that
        the compiled engine is loaded (or compiled) once per worker and not in a task;
        default :func:`warm`, ``False`` for none.  Not called with ``"serial"``.
    metadata : dict, optional
        Stored in ``results.json`` as ``metadata`` (e.g. the configuration).

    Returns
    -------
    SweepResult
        The finished tasks (those of an earlier call included), in task order.

    Raises
    ------
    ValueError
        If ``output`` holds another sweep (another function, other parameter sets,
        replicas or seed), or an argument is out of range.
    TypeError
        If ``function`` is not callable, or for parameters :func:`grid` refuses.
    ImportError
        If a Dask scheduler is asked for and dask.distributed is not installed.
    KeyboardInterrupt
        On Ctrl-C, after the finished tasks are written (call again to resume).
    """
    if not callable(function):
        raise TypeError(f"function must be callable, got {function!r}")
    points = grid(parameters)
    if isinstance(replicas, bool) or not isinstance(replicas, (int, np.integer)) \
            or replicas < 1:
        raise ValueError(f"replicas must be an integer >= 1, got {replicas!r}")
    replicas = int(replicas)
    if workers is not None:
        if scheduler is not None:
            raise ValueError("workers= sets the size of the cluster made for "
                             "scheduler=None; it cannot be given with scheduler="
                             f"{scheduler!r}")
        if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) \
                or workers < 1:
            raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    if metadata is not None and not isinstance(metadata, dict):
        raise TypeError(f"metadata must be a dict, got {type(metadata).__name__}")
    _check_names(points)
    output = Path(output)
    name = _function_name(function)
    previous = _read_json(output)
    if previous is not None:
        seed = _check_same(output, previous, name, points, replicas, seed)
    root = np.random.SeedSequence(seed)
    tasks = _tasks(points, replicas, root)
    records: dict[int, dict] = {}
    if previous is not None:
        for record in previous["tasks"]:
            if record["status"] == "ok" or not retry_failed:
                records[record["index"]] = record
    state = _State(output, name, root, points, replicas, records, metadata)
    (output / TASKS_DIR).mkdir(parents=True, exist_ok=True)
    pending = [t for t in tasks if t.index not in records]
    for task in pending:
        (output / TASKS_DIR / task.id).mkdir(exist_ok=True)
    state.write()

    bar, owned = _progress.bar(progress, total=len(tasks), unit="task", desc="sweep",
                               unit_scale=False)
    if bar is not None and records:
        bar.update(len(records))

    def finished(record: dict) -> None:
        state.add(record)
        if bar is not None:
            bar.update(1)
            failed = sum(r["status"] == "failed" for r in state.records.values())
            if failed:
                bar.set_postfix(failed=failed)

    try:
        if scheduler == "serial":
            for task in pending:
                finished(_call(function, task.parameters, task.seed,
                               str(output / TASKS_DIR / task.id), _meta(task)))
        elif pending:
            _run_on_dask(function, pending, output, scheduler, workers,
                         warm if warmup is None else warmup, finished, state)
    finally:
        state.write()
        if owned:
            bar.close()
    return state.result()


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
        _replace(self.output / JSON_FILE, text + "\n")
        _replace(self.output / CSV_FILE, _csv_text(tasks))

    def result(self) -> SweepResult:
        return SweepResult(self.output, self.root.entropy, self.points, self.replicas,
                           self.ordered())


def _meta(task: _Task) -> dict:
    """What a record says of its task, besides the outcome."""
    return {"task": task.id, "index": task.index, "point": task.point,
            "replica": task.replica, "parameters": task.parameters,
            "seed": {"entropy": task.seed.entropy,
                     "spawn_key": list(task.seed.spawn_key)}}


def _call(function, parameters: dict, seed, workdir: str, meta: dict) -> dict:
    """Run one task where it is sent, and its record: the values, or the error with
    its traceback.  (A ``KeyboardInterrupt`` or ``SystemExit`` goes through.)"""
    start = _time.perf_counter()
    record = dict(meta)
    record.update(status="ok", values=None, error=None)
    try:
        path = Path(workdir)
        path.mkdir(parents=True, exist_ok=True)
        values = function(json.loads(json.dumps(parameters)), seed, path)
        record["values"] = _values(values)
    except Exception as exc:
        record.update(status="failed", values=None, error={
            "type": type(exc).__name__, "message": str(exc),
            "traceback": traceback.format_exc()})
    record.update(seconds=_time.perf_counter() - start, host=socket.gethostname(),
                  pid=os.getpid())
    return record


def _values(values) -> dict:
    if not isinstance(values, dict):
        raise TypeError(f"the task function returned {type(values).__name__}, not a dict "
                        "of values")
    out = {}
    for key, value in values.items():
        if not isinstance(key, str):
            raise TypeError(f"the task function returned a value named {key!r}, not a string")
        out[key] = json.loads(json.dumps(value, default=_json_default))
    return out


def _run_on_dask(function, pending, output, scheduler, workers, warmup, finished,
                 state) -> None:
    try:
        import distributed
    except ImportError:
        raise ImportError("a sweep on Dask needs dask.distributed: pip install "
                          "'edmd2d[ensemble]' (or run it with scheduler='serial')") from None
    state.versions.update(dask=_version("dask"), distributed=distributed.__version__)
    cluster = client = None
    own_client = True
    if scheduler is None:
        cluster = distributed.LocalCluster(
            n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
            processes=True, dashboard_address=":0")
        client = distributed.Client(cluster)
    elif isinstance(scheduler, distributed.Client):
        client, own_client = scheduler, False
    elif isinstance(scheduler, str) or hasattr(scheduler, "scheduler_address"):
        client = distributed.Client(scheduler)
    else:
        raise TypeError('scheduler must be None, "serial", an address, a '
                        f"distributed.Client or a cluster, got {scheduler!r}")
    futures = []
    try:
        if warmup is not False:
            client.run(warmup)
        token = f"{os.getpid()}-{_time.time_ns()}"
        by_key = {}
        for task in pending:
            future = client.submit(_call, function, task.parameters, task.seed,
                                   str(output / TASKS_DIR / task.id), _meta(task),
                                   key=f"edmd2d-sweep-{task.id}-{token}", pure=False)
            by_key[future.key] = task
            futures.append(future)
        for future in distributed.as_completed(futures):
            task = by_key[future.key]
            try:
                record = future.result()
            except Exception as exc:  # (the task never ran to its end: a lost worker)
                record = _meta(task)
                record.update(status="failed", values=None, seconds=None, host=None,
                              pid=None, error={"type": type(exc).__name__,
                                               "message": str(exc),
                                               "traceback": "".join(
                                                   traceback.format_exception(exc))})
            finished(record)
    finally:
        if futures:
            client.cancel(futures)
        if own_client:
            client.close()
        if cluster is not None:
            cluster.close()


def warm() -> None:
    """Load (or, with an empty cache, compile) the engine in this process: build and
    advance a small elastic gas, periodic and walled, measure it and take its hexatic
    order, as :func:`eos_task` does.

    :func:`sweep` calls it on every Dask worker before sending tasks.  A sweep whose
    tasks use other physics (restitution, gravity, a thermostat) can pass its own
    ``warmup`` that runs a small system of that kind.
    """
    for periodic in (True, False):
        sim = make_gas(16, 0.3, periodic=periodic, seed=0)
        sim.advance(until=0.2)
        sim.measure(0.2, blocks=2)
        hexatic_order(sim)


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


def _replace(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file renamed over it: a reader,
    or a sweep that resumes after a crash, never sees half a file."""
    _atomic.write_text(path, text)


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


def _version(module: str) -> str | None:
    try:
        from importlib.metadata import version

        return version(module)
    except Exception:  # (not installed, or no metadata)
        return None


def _versions() -> dict:
    return {"edmd2d": __version__, "numpy": np.__version__,
            "python": platform.python_version(), "platform": sys.platform}


# ------------------------------------------------------------------ the EOS task
def eos_task(parameters: dict, seed, workdir) -> dict:
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
