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

:func:`transport_task` measures transport coefficients (:mod:`edmd2d.transport`)
over a grid of parameters the same way.

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

import itertools
import json
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Literal

import numpy as np

from .. import progress as _progress
from . import _store
from ._eos import eos_task
from ._store import (
    SweepResult,
    _check_names,
    _check_same,
    _function_name,
    _json_default,
    _read_json,
    _State,
    load,
)
from ._transport import transport_task
from ._workers import _call, _meta, _run_on_dask, _tasks, warm

__all__ = ["sweep", "grid", "load", "eos_task", "transport_task", "warm", "SweepResult", "FORMAT",
           "VERSION", "CSV_FILE", "JSON_FILE", "TASKS_DIR"]

# (The constants live with the files they name; their descriptions are here, where the
# documentation of the public module reads them.)
#: The format name in ``results.json``; a directory whose file has another is refused.
FORMAT = _store.FORMAT
#: The version of that format.
VERSION = _store.VERSION
#: The table of results in the output directory.
CSV_FILE = _store.CSV_FILE
#: Everything the table holds and more, as JSON, in the output directory.
JSON_FILE = _store.JSON_FILE
#: The folder of the tasks' work directories in the output directory.
TASKS_DIR = _store.TASKS_DIR


# ------------------------------------------------------------------ the grid
def grid(parameters: list[dict] | dict[str, list]) -> list[dict]:
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


# ------------------------------------------------------------------ the sweep
def sweep(function: Callable[[dict, np.random.SeedSequence, Path], dict],
          parameters: list[dict] | dict[str, list], *, output: str | os.PathLike[str],
          replicas: int = 1,
          seed: int | Sequence[int] | None = None, scheduler: Any = None,
          workers: int | None = None, progress: _progress.ProgressArg = False,
          retry_failed: bool = True, warmup: Callable[[], object] | Literal[False] | None = None,
          metadata: dict | None = None) -> SweepResult:
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
