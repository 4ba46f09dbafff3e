"""Timing helpers shared by the benchmark scripts (no edmd2d internals).

The engine is timed through its public API only: ``sim.advance(collisions=k)`` and the
event counters in ``sim.counts``.  Slow peers are timed with a wall-clock budget instead
of a fixed amount of work, so that a benchmark point costs about the same time whatever
the speed of the code under test.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np


def stats(values) -> dict:
    """Median, min and max of a list of rates (the median is the headline number)."""
    values = list(values)
    return {
        "median": statistics.median(values),
        "min": min(values),
        "max": max(values),
    }


def engine_array_bytes(sim) -> int:
    """Bytes held by the Simulation's numpy arrays (state, grid, event queue, counters).

    This reads the *private* attributes through ``vars(sim._state)``: a measurement, not an
    API.  Everything the engine needs between events lives in these arrays, so their
    total is the engine's memory footprint.  Several per-disk columns are views into
    the two row tables: each buffer is counted once.
    """
    owners = {}
    values = list(vars(sim._state).values())
    if sim._state.wide is not None:  # (the wide disks' lists: arrays in a named tuple)
        values += list(sim._state.wide)
    for value in values:
        if isinstance(value, np.ndarray):
            v = value
            while isinstance(v.base, np.ndarray):  # (a view: count its owner, once)
                v = v.base
            owners[id(v)] = v
    return int(sum(v.nbytes for v in owners.values()))


def count_delta(before, after) -> dict:
    """Differences of two ``sim.counts`` snapshots, as a plain dict."""
    names = ("collisions", "wall_collisions", "cell_crossings", "events", "stale")
    return {name: getattr(after, name) - getattr(before, name) for name in names}


def collision_rate(sim, collisions: int) -> float:
    """Collisions per second of process CPU time of ``sim.advance(collisions=...)``
    (CPU time: another process on the machine does not count against the run)."""
    c0 = sim.counts.collisions
    t0 = time.process_time()
    sim.advance(collisions=collisions)
    return (sim.counts.collisions - c0) / (time.process_time() - t0)


def time_advance(sim, collisions: int) -> dict:
    """Run ``sim.advance(collisions=collisions)`` once; seconds, counts and physical time."""
    c0, t_phys0 = sim.counts, sim.time
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    sim.advance(collisions=collisions)
    seconds = time.perf_counter() - t0
    cpu = time.process_time() - cpu0
    run = count_delta(c0, sim.counts)
    run["seconds"] = seconds
    # CPU time / wall time < 1 means the process was descheduled (a busy machine).
    run["cpu_share"] = cpu / seconds if seconds > 0 else 1.0
    run["physical_time"] = sim.time - t_phys0
    return run


# A timed run during which the process had less than this share of a core (CPU time /
# wall time) was slowed by another process; it is run again, within a budget.
BUSY_SHARE = 0.9


def time_engine(sim, *, seconds: float, repeats: int, rate_guess: float,
                retries: int = 0) -> tuple[list[dict], int]:
    """``repeats`` timed runs of about ``seconds`` each, continuing the same simulation.

    ``rate_guess`` (collisions per second, e.g. from an untimed equilibration run) sets
    the number of collisions per run; at least 1000 so that the call overhead of
    ``advance`` stays negligible.  Up to ``retries`` runs in all are done again when the
    process waited for a core (CPU share below ``BUSY_SHARE``); the last attempt is
    kept either way.  Returns the runs and the number of runs redone.
    """
    per_run = max(1000, int(rate_guess * seconds))
    runs, redone = [], 0
    for _ in range(repeats):
        run = time_advance(sim, per_run)
        while run["cpu_share"] < BUSY_SHARE and redone < retries:
            redone += 1
            run = time_advance(sim, per_run)
        runs.append(run)
    return runs, redone


def summarize_runs(runs: list[dict], n: int) -> dict:
    """Collision and event rates (median, min, max) over timed runs of ``n`` disks."""
    return {
        "collisions_per_s": stats(r["collisions"] / r["seconds"] for r in runs),
        "events_per_s": stats(r["events"] / r["seconds"] for r in runs),
        "physical_time_per_s": stats(r["physical_time"] / r["seconds"] for r in runs),
        "collisions_per_disk_per_run": runs[0]["collisions"] / n,
        "cpu_share_min": min(r["cpu_share"] for r in runs),
        "stale_per_collision": sum(r["stale"] for r in runs)
        / max(1, sum(r["collisions"] for r in runs)),
    }


def run_for(step, seconds: float) -> tuple[int, float]:
    """Call ``step()`` until ``seconds`` of wall time have passed (at least once).

    Returns the summed return values of ``step`` (e.g. collisions done) and the time.
    """
    done = 0
    t0 = time.perf_counter()
    while True:
        done += step()
        elapsed = time.perf_counter() - t0
        if elapsed >= seconds:
            return done, elapsed


def alternating_rates(systems: dict, n: int, k: float, reps: int) -> tuple[dict, int]:
    """Warm each simulation of ``systems`` (by name) up for ``3 n`` collisions, then
    let them take ``reps`` turns at ``k n`` collisions each, one after another so that
    the machine's drift hits all alike; returns each one's collisions/s per turn
    (:func:`collision_rate`) and the collisions of a turn."""
    for sim in systems.values():
        sim.advance(collisions=3 * n)
    per_turn = max(1, int(k * n))
    rates: dict[str, list[float]] = {name: [] for name in systems}
    for _ in range(reps):
        for name, sim in systems.items():
            rates[name].append(collision_rate(sim, per_turn))
    return rates, per_turn


def print_rates(rates: dict, baseline: str, width: int = 10) -> None:
    """Print the median and range of each entry of ``rates`` (collisions/s per
    turn), and of the ratio of each other entry's turns to those of ``baseline``."""
    for name, values in rates.items():
        print(f"  {name:>{width}}: median {statistics.median(values) / 1e6:.3f} M coll/s "
              f"(range {min(values) / 1e6:.3f}-{max(values) / 1e6:.3f})")
    for name in rates:
        if name == baseline:
            continue
        ratios = [b / a for a, b in zip(rates[baseline], rates[name])]
        print(f"  {name} / {baseline}: median {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.3f}-{max(ratios):.3f})")


def turns_parser(doc: str, reps: int = 7, reps_help: str | None = None) -> argparse.ArgumentParser:
    """The command line of a benchmark that times systems in turns: ``--n`` disks,
    ``--k`` collisions per disk a turn, ``--reps`` turns (the description: the first
    paragraph of ``doc``)."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=10_000)
    parser.add_argument("--k", type=float, default=10.0, help="collisions per disk a turn")
    parser.add_argument("--reps", type=int, default=reps, help=reps_help)
    return parser
