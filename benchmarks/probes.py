"""Measurements that need a fresh Python process: JIT compile time and memory.

Each probe runs this file as a subprocess and reads one JSON line from its output, so
that neither numba's in-memory compilation results nor the parent's allocations can
leak into the numbers.  Run directly (for debugging)::

    python benchmarks/probes.py compile           # one import + build + first advance
    python benchmarks/probes.py compile gravity   # the same for another kind of physics
    python benchmarks/probes.py memory 100000 0.5 # memory of one system of N disks

Compile time
    ``cold``: ``EDMD2D_NUMBA_CACHE=0`` (numba's on-disk cache off), so everything is
    compiled: the time to ``import edmd2d``, build a 200-disk gas and run its first
    200 collisions.  ``warm``: the same with the cache on, after one run that fills it.
    Each kind of physics compiles an event loop of its own: ``compile FAMILY`` builds
    the gas of one of :data:`FAMILIES` instead of the elastic one.
Memory
    After importing edmd2d and running a 100-disk system (so that the JIT and the
    interpreter are warm: this is the baseline), a gas of N disks is built and run for
    N collisions.  Reported per disk: the engine's numpy arrays (``vars(sim._state)``, private
    attributes read for the measurement only), the bytes traced by ``tracemalloc``
    (numpy reports its array allocations to it) while held after the build, at the
    peak of the build and at the peak of the run, and the growth of the process's peak
    resident set size (``VmHWM``, reset to the current size after the baseline by
    writing 5 to ``/proc/self/clear_refs``; where that is impossible, ``ru_maxrss``,
    whose baseline may then hide the growth) and of its current resident set size
    (``VmRSS``) over the baseline.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
COMPILE_N = 200


def _run_probe(args: list[str], env_extra: dict | None = None, timeout: float = 900) -> dict:
    env = dict(os.environ)
    env.update(env_extra or {})
    t0 = time.perf_counter()
    proc = subprocess.run(
        [sys.executable, os.path.join(HERE, "probes.py"), *args],
        env=env, check=False, capture_output=True, text=True, timeout=timeout,
    )
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"probe {args} failed:\n{proc.stderr[-2000:]}")
    result = json.loads(proc.stdout.strip().splitlines()[-1])
    result["process_s"] = wall
    return result


def compile_times() -> dict:
    """Cold (cache off) and warm (cache filled) first-run times, each in a new process."""
    cold = _run_probe(["compile"], {"EDMD2D_NUMBA_CACHE": "0"})
    fill = _run_probe(["compile"], {"EDMD2D_NUMBA_CACHE": "1"})
    warm = _run_probe(["compile"], {"EDMD2D_NUMBA_CACHE": "1"})
    return {"n": COMPILE_N, "cold": cold, "cache_fill": fill, "warm": warm}


def memory(n: int, packing: float) -> dict:
    """Memory measurements of one gas of ``n`` disks, in a new process."""
    return _run_probe(["memory", str(n), str(packing)])


# ---------------------------------------------------------------------- in the child
# The keyword arguments of make_gas for each kind of physics (growth is set on the
# Simulation itself; see _compile_child).
WALLED = {"periodic": (True, False), "gravity": (0.0, -1.0)}
FAMILIES = {
    "elastic": {},
    "restitution": {"restitution": 0.9},
    "gravity": WALLED,
    "gravity+restitution": {**WALLED, "restitution": 0.9},
    "thermostat": {"thermostat": (1.0, 0.1)},
    "growth": {},
}


def _compile_child(family: str = "elastic") -> dict:
    t0 = time.perf_counter()
    import edmd2d as ed

    t1 = time.perf_counter()
    if family == "growth":
        # Built with growth from the start, so that only the growth loop is compiled
        # (make_gas would compile the elastic one for its first prediction).
        positions, velocities, box = _lattice_gas(COMPILE_N, 0.5)
        sim = ed.Simulation(positions, velocities, 0.5, box=box, growth=0.01, seed=1)
    else:
        sim = ed.make_gas(COMPILE_N, 0.5, seed=1, **FAMILIES[family])
    t2 = time.perf_counter()
    sim.advance(collisions=COMPILE_N)
    t3 = time.perf_counter()
    return {
        "family": family,
        "cache": os.environ.get("EDMD2D_NUMBA_CACHE", "1"),
        "import_s": t1 - t0,
        "build_s": t2 - t1,
        "first_advance_s": t3 - t2,
        "total_s": t3 - t0,
        # (the CPU time of the whole process: on a shared machine the wall times above
        # include the time waiting for a core, while compiling is single-threaded)
        "process_cpu_s": time.process_time(),
    }


def _lattice_gas(n: int, packing: float):
    """Positions, velocities and the periodic box of ``n`` disks of radius 0.5 on a
    square lattice at ``packing``, with Gaussian velocities (numpy only)."""
    import numpy as np

    import edmd2d as ed

    side = int(np.ceil(np.sqrt(n)))
    length = np.sqrt(n * np.pi * 0.25 / packing)
    ij = np.stack(np.divmod(np.arange(n), side), axis=1)
    positions = (ij + 0.5) * (length / side)
    velocities = np.random.default_rng(1).normal(size=(n, 2))
    return positions, velocities, ed.Box(length, length, periodic=True)


def _status_bytes(key: str) -> int:
    """A size from /proc/self/status (``VmRSS``, ``VmHWM``) in bytes (Linux), or -1."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return -1


def _reset_peak_rss() -> bool:
    """Set the peak resident set size (VmHWM) to the current one (Linux >= 4.0)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        return False
    return True


def _memory_child(n: int, packing: float) -> dict:
    import gc
    import resource
    import tracemalloc

    from timing import engine_array_bytes

    import edmd2d as ed

    small = ed.make_gas(100, packing, seed=1)
    small.advance(collisions=100)
    del small
    gc.collect()
    hwm_reset = _reset_peak_rss()

    def peak_rss() -> int:
        if hwm_reset:
            return _status_bytes("VmHWM")
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # KiB on Linux

    peak0, rss0 = peak_rss(), _status_bytes("VmRSS")

    tracemalloc.start()
    sim = ed.make_gas(n, packing, seed=1)
    held, peak_build = tracemalloc.get_traced_memory()
    engine_before = engine_array_bytes(sim)
    tracemalloc.reset_peak()
    t0 = time.perf_counter()
    sim.advance(collisions=n)
    run_s = time.perf_counter() - t0
    _, peak_run = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    engine_after = engine_array_bytes(sim)
    peak1, rss1 = peak_rss(), _status_bytes("VmRSS")
    return {
        "n": n,
        "packing": packing,
        "run_collisions": n,
        "run_s": run_s,
        "engine_array_bytes_per_disk": engine_after / n,
        "engine_arrays_unchanged_by_run": engine_before == engine_after,
        "traced_held_bytes_per_disk": held / n,
        "traced_peak_build_bytes_per_disk": peak_build / n,
        "traced_peak_run_extra_bytes_per_disk": (peak_run - held) / n,
        "peak_rss_growth_bytes_per_disk": (peak1 - peak0) / n,
        "peak_rss_method": "VmHWM reset" if hwm_reset else "ru_maxrss",
        "rss_growth_bytes_per_disk": (rss1 - rss0) / n if rss0 > 0 else None,
        "baseline_rss_mib": rss0 / 2**20,
    }


if __name__ == "__main__":
    if sys.argv[1:2] == ["compile"] and len(sys.argv) <= 3 and (
            sys.argv[2:] == [] or sys.argv[2] in FAMILIES):
        out = _compile_child(*sys.argv[2:])
    elif sys.argv[1:2] == ["memory"] and len(sys.argv) == 4:
        out = _memory_child(int(sys.argv[2]), float(sys.argv[3]))
    else:
        sys.exit(f"usage: probes.py compile [{' | '.join(FAMILIES)}] | "
                 "probes.py memory N PACKING")
    print(json.dumps(out))
