"""The edmd2d benchmark suite: speed against N and density, compile time, memory, peers.

Run from the repository root::

    python benchmarks/scaling.py --quick     # about 1 minute: N up to 10^5
    python benchmarks/scaling.py             # about 10 minutes: N up to 10^6

Options narrow a run while developing, e.g.
``--sizes 10000 --packings 0.5 --no-peers --no-memory --no-compile``.

What it measures (details in benchmarks/README.md):

- for every N and packing fraction, in a periodic box: a gas from ``make_gas``,
  equilibrated for a few collisions per disk (not timed), then timed runs of
  ``advance(collisions=k)`` continuing the same simulation, with ``k`` chosen from the
  equilibration speed so that each run lasts about ``--seconds``; disk-disk collisions
  per second and events per second (median, min, max of ``--repeats`` runs);
- JIT compile time, cold (numba cache off) and warm, each in a fresh process;
- memory per disk, each N in a fresh process;
- the same state run by the brute-force reference engine, by python-billiards and by
  pymunk, where installed.

Writes ``<out>/scaling-<mode>.json`` (everything), ``.png`` (log-log plot) and ``.md``
(the README tables).  Progress goes to standard output.  JIT compilation of the main
process is done before any timing.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numba
import numpy as np
import peers
import probes
import report
from timing import engine_array_bytes, summarize_runs, time_advance, time_engine

import edmd2d as ed

HERE = Path(__file__).resolve().parent

MODES = {
    "quick": {
        "sizes": [100, 1_000, 10_000, 100_000],
        "packings": [0.1, 0.3, 0.5, 0.7],
        "repeats": 3,
        "seconds": 0.25,
        "retries": 3,
        "equilibrate": 5,
        "memory_sizes": [10_000, 100_000],
        "reference_sizes": [50, 100],
        "billiards_sizes": [100, 200],
        "pymunk_sizes": [1_000],
        "pymunk_steps": [10],
        "peer_seconds": 3.0,
    },
    "full": {
        "sizes": [100, 300, 1_000, 3_000, 10_000, 30_000, 100_000, 300_000, 1_000_000],
        "packings": [0.1, 0.3, 0.5, 0.7],
        "repeats": 5,
        "seconds": 2.0,
        "retries": 5,
        "equilibrate": 5,
        "memory_sizes": [10_000, 100_000, 1_000_000],
        "reference_sizes": [50, 100, 200, 400],
        "billiards_sizes": [100, 300, 1_000],
        "pymunk_sizes": [1_000, 10_000],
        "pymunk_steps": [10, 100],
        "peer_seconds": 8.0,
    },
}
PEER_PACKING = 0.5
SEED = 1
# Refuse a point whose arrays would not fit comfortably (generous: ~1 kB per disk is
# several times what the engine and make_gas need).
BYTES_PER_DISK_BUDGET = 1024


def main(argv=None) -> int:
    args = _parse(argv)
    cfg = dict(MODES[args.mode])
    for key in ("sizes", "packings", "repeats", "seconds", "retries", "equilibrate"):
        value = getattr(args, key)
        if value is not None:
            cfg[key] = value
    out_dir = Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    stem = out_dir / f"scaling-{args.tag or args.mode}"

    results = {"meta": _machine(argv), "config": cfg}
    t_start = time.perf_counter()

    _warm_up()
    results["scaling"] = sweep(cfg)
    if not args.no_compile:
        print("compile time (fresh processes) ...", flush=True)
        results["compile"] = probes.compile_times()
        c = results["compile"]
        print(f"  cold {c['cold']['total_s']:.2f} s, warm {c['warm']['total_s']:.2f} s",
              flush=True)
    if not args.no_memory:
        results["memory"] = memory(cfg)
    if not args.no_peers:
        results["peers"] = compare(cfg)

    results["meta"]["load_after"] = os.getloadavg()[0]
    # Others may commit engine changes while the suite runs: the sweep and the peers
    # use the code imported at the start, the fresh-process probes the code of their time.
    results["meta"]["commit_end"] = _git("rev-parse", "--short", "HEAD")
    results["meta"]["uncommitted_end"] = _git("status", "--porcelain", "--",
                                              "../src/edmd2d").splitlines()
    results["meta"]["suite_seconds"] = time.perf_counter() - t_start
    report.write_json(results, stem.with_suffix(".json"))
    report.plot(results, stem.with_suffix(".png"))
    table = report.markdown(results)
    stem.with_suffix(".md").write_text(table)
    print()
    print(table)
    print(f"wrote {stem}.json, .png, .md in {results['meta']['suite_seconds']:.0f} s")
    return 0


def _parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", dest="mode", action="store_const", const="quick",
                    default="full", help="small sizes and short runs (~1 min)")
    ap.add_argument("--sizes", type=_ints, help="comma-separated N, e.g. 1000,10000")
    ap.add_argument("--packings", type=_floats, help="comma-separated packing fractions")
    ap.add_argument("--repeats", type=int, help="timed runs per point")
    ap.add_argument("--seconds", type=float, help="target seconds per timed run")
    ap.add_argument("--retries", type=int,
                    help="timed runs per point that may be redone when the process "
                         "waited for a core")
    ap.add_argument("--equilibrate", type=float, help="untimed collisions per disk first")
    ap.add_argument("--no-peers", action="store_true", help="skip the peer comparisons")
    ap.add_argument("--no-memory", action="store_true", help="skip the memory probes")
    ap.add_argument("--no-compile", action="store_true", help="skip the compile probes")
    ap.add_argument("--out", default=str(HERE / "results"), help="output directory")
    ap.add_argument("--tag", help="output file stem suffix (default: the mode)")
    return ap.parse_args(argv)


def _ints(text: str) -> list[int]:
    return [int(float(x)) for x in text.split(",") if x]


def _floats(text: str) -> list[float]:
    return [float(x) for x in text.split(",") if x]


# ---------------------------------------------------------------------- the sweep
def _warm_up() -> None:
    """Compile (or load from cache) every kernel before anything is timed."""
    t0 = time.perf_counter()
    for periodic in (True, False):
        sim = ed.make_gas(200, 0.5, periodic=periodic, seed=SEED)
        sim.advance(collisions=400)
        sim.advance(until=sim.time + 0.1)
    print(f"warm-up (JIT or cache load) {time.perf_counter() - t0:.2f} s", flush=True)


def measure_point(n: int, packing: float, cfg: dict) -> dict:
    """Build, equilibrate (untimed) and time one (N, packing fraction) point."""
    t0 = time.perf_counter()
    sim = ed.make_gas(n, packing, seed=SEED)
    build_s = time.perf_counter() - t0
    eq = time_advance(sim, max(1, int(cfg["equilibrate"] * n)))
    rate_guess = eq["collisions"] / eq["seconds"]
    runs, redone = time_engine(sim, seconds=cfg["seconds"], repeats=cfg["repeats"],
                               rate_guess=rate_guess, retries=cfg["retries"])
    point = {"n": n, "packing": packing, "build_s": build_s, "equilibration": eq}
    point.update(summarize_runs(runs, n))
    point["runs_redone_busy"] = redone
    point["engine_array_bytes_per_disk"] = engine_array_bytes(sim) / n
    point["runs"] = runs
    return point


def sweep(cfg: dict) -> list[dict]:
    points = []
    avail = _available_bytes()
    for n in cfg["sizes"]:
        if avail is not None and n * BYTES_PER_DISK_BUDGET > avail:
            print(f"N={n:>9,}: skipped, needs ~{n * BYTES_PER_DISK_BUDGET / 2**30:.1f} GiB "
                  f"of the {avail / 2**30:.1f} GiB available", flush=True)
            continue
        for phi in cfg["packings"]:
            p = measure_point(n, phi, cfg)
            c, e = p["collisions_per_s"], p["events_per_s"]
            print(f"N={n:>9,} phi={phi:<4g} {c['median'] / 1e6:6.3f} M coll/s "
                  f"({c['min'] / 1e6:.3f}-{c['max'] / 1e6:.3f})  "
                  f"{e['median'] / 1e6:6.3f} M events/s  "
                  f"{p['engine_array_bytes_per_disk']:5.0f} B/disk  "
                  f"[build {p['build_s']:.2f} s, equilibrate {p['equilibration']['seconds']:.2f}"
                  f" s, {p['collisions_per_disk_per_run']:.3g} coll/disk per run]"
                  + (f"  cpu share {p['cpu_share_min']:.2f}" if p["cpu_share_min"] < 0.95 else "")
                  + (f", {p['runs_redone_busy']} redone" if p["runs_redone_busy"] else ""),
                  flush=True)
            points.append(p)
    return points


def memory(cfg: dict) -> list[dict]:
    rows = []
    for n in cfg["memory_sizes"]:
        print(f"memory N={n:,} (fresh process) ...", flush=True)
        m = probes.memory(n, PEER_PACKING)
        print(f"  engine arrays {m['engine_array_bytes_per_disk']:.0f} B/disk, traced held "
              f"{m['traced_held_bytes_per_disk']:.0f}, peak RSS growth "
              f"{m['peak_rss_growth_bytes_per_disk']:.0f} B/disk", flush=True)
        rows.append(m)
    return rows


def compare(cfg: dict) -> dict:
    out = {"reference": [], "billiards": [], "pymunk": []}
    sec = cfg["peer_seconds"]
    for n in cfg["reference_sizes"]:
        r = peers.vs_reference(n, PEER_PACKING, seconds=sec, seed=SEED)
        print(f"reference N={n}: {r['reference_collisions_per_s']:.3g} coll/s "
              f"({r['reference_collisions']} collisions), edmd2d x{r['ratio']:,.0f}", flush=True)
        out["reference"].append(r)
    for name, sizes, fn in (("billiards", cfg["billiards_sizes"], peers.vs_billiards),
                            ("pymunk", cfg["pymunk_sizes"], peers.vs_pymunk)):
        steps = cfg["pymunk_steps"] if name == "pymunk" else [None]
        for n in sizes:
            for k in steps:
                kw = {"steps_per_free_time": k} if k else {}
                r = fn(n, PEER_PACKING, seconds=sec, seed=SEED, **kw)
                if "skipped" in r:
                    print(f"{name}: skipped: {r['skipped']}", flush=True)
                    out[name] = r
                    break
                if "error" in r:
                    print(f"{name} N={n}: {r['error']}", flush=True)
                elif name == "billiards":
                    print(f"billiards N={n}: {r['billiards_collisions_per_s']:.3g} coll/s, "
                          f"edmd2d x{r['ratio']:,.0f}", flush=True)
                else:
                    print(f"pymunk N={n} dt=tau/{k}: {r['pymunk_physical_time_per_s']:.3g} "
                          f"time units/s, edmd2d x{r['ratio']:.3g}; "
                          f"{r['overlapping_pairs_mean']:.3g} overlapping pairs", flush=True)
                out[name].append(r)
            if isinstance(out[name], dict):
                break
    return out


# ---------------------------------------------------------------------- the machine
def _available_bytes():
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def _cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return " ".join(line.split(":", 1)[1].split())
    except OSError:
        pass
    return platform.processor() or platform.machine()


def _git(*args: str) -> str:
    try:
        return subprocess.run(["git", *args], cwd=HERE, check=False, capture_output=True, text=True,
                              timeout=10).stdout.rstrip()
    except (OSError, subprocess.SubprocessError):
        return ""


def _machine(argv) -> dict:
    mem = None
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError):
        pass
    cmd = "python benchmarks/scaling.py " + " ".join(sys.argv[1:] if argv is None else argv)
    return {
        "command": cmd.strip(),
        "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
        "cpu": _cpu_name(),
        "cores": os.cpu_count(),
        "memory_gib": mem,
        "platform": platform.platform(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "numba": numba.__version__,
        "edmd2d": getattr(ed, "__version__", "?"),
        "commit": _git("rev-parse", "--short", "HEAD"),
        # The engine is being optimized concurrently: record uncommitted changes.
        "uncommitted": _git("status", "--porcelain", "--", "../src/edmd2d").splitlines(),
        "load_before": os.getloadavg()[0],
    }


if __name__ == "__main__":
    sys.exit(main())
