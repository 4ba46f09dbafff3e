"""Where the tasks of a sweep run: a call that turns a task into its record, the
Dask cluster that runs the calls, and :func:`warm`, which loads the compiled engine
on each worker."""

from __future__ import annotations

import itertools
import json
import os
import socket
import time as _time
import traceback
from dataclasses import dataclass
from importlib.metadata import version as _installed_version
from pathlib import Path

import numpy as np

from ..analysis import hexatic_order
from ..builders import make_gas
from ._store import TASKS_DIR, _json_default


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


def _version(module: str) -> str | None:
    try:
        return _installed_version(module)
    except Exception:  # (not installed, or no metadata)
        return None
