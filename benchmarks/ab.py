"""Compare the speed of two (or more) versions of edmd2d in alternating runs.

On a shared or virtual machine the speed drifts by tens of percent over minutes, so two
versions measured one after the other can differ by more than any change between them.
This script alternates them instead: every round runs each version once, in a fresh
process with its own numba cache, and reports the maximum and median collisions per
second over that process's timed calls.  Compare versions round by round.

Each version is a git revision, exported into a temporary directory::

    python benchmarks/ab.py --n 10000 --k 10 --reps 7 --rounds 5 db56a69 main
    python benchmarks/ab.py --n 1000000 --k 2 --reps 4 --rounds 3 HEAD~1 HEAD

The timed call is ``advance(collisions=k * N)`` on ``make_gas(N, 0.5, seed=1)`` after
``advance(collisions=3 N)`` to equilibrate (process CPU time, one core).

Several sizes (with one ``k`` each, or one for all) alternate too, inside each round;
the summary then gives, per version, how many times slower a collision is at each size
than at the first, from the two sizes' maxima *of the same round* (the drift between
rounds cancels), with the median and range over the rounds.  For the cost of a
collision at N = 10^6 against N = 10^4::

    python benchmarks/ab.py --n 10000,1000000 --k 10,2 --reps 4 --rounds 5 main
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

_CHILD = r"""
import json, sys, time
import numpy as np
import edmd2d as ed
n, k, reps = int(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3])
sim = ed.make_gas(n, 0.5, seed=1)
sim.advance(collisions=3 * n)
rates = []
for _ in range(reps):
    c0 = sim.counts.collisions
    t0 = time.process_time()
    sim.advance(collisions=max(1, int(k * n)))
    rates.append((sim.counts.collisions - c0) / (time.process_time() - t0))
print(json.dumps({"max": max(rates), "median": float(np.median(rates))}))
"""


def export(rev: str, root: Path) -> Path:
    """The ``src`` tree of git revision ``rev``, written under ``root``."""
    dest = root / rev.replace("/", "_").replace("~", "-").replace("^", "-")
    dest.mkdir()
    data = subprocess.run(["git", "archive", rev, "src"], check=True,
                          capture_output=True).stdout
    tar_path = dest / "src.tar"
    tar_path.write_bytes(data)
    with tarfile.open(tar_path) as tar:
        tar.extractall(dest, filter="data")
    return dest


def run_once(tree: Path, n: int, k: float, reps: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(tree / "src"), NUMBA_CACHE_DIR=str(tree / "nc"))
    out = subprocess.run([sys.executable, "-c", _CHILD, str(n), str(k), str(reps)],
                         env=env, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def _number_list(text: str, kind):
    return [kind(v) for v in text.split(",") if v.strip()]


def summarize(maxima: dict, sizes: list[int]) -> list[str]:
    """Lines of the summary: per version and size, the median and range over rounds of
    the per-round maximum rate; with several sizes, the per-round slowdown of each size
    against the first (``maxima[rev][n]`` lists one maximum per round)."""
    lines = []
    for rev, by_n in maxima.items():
        for n in sizes:
            rates = sorted(by_n[n])
            lines.append(f"{rev:>12}  N={n:<8}  max per round: median "
                         f"{statistics.median(rates) / 1e6:.3f}  range "
                         f"{rates[0] / 1e6:.3f}-{rates[-1] / 1e6:.3f} M collisions/s")
        for n in sizes[1:]:
            slow = sorted(a / b for a, b in zip(by_n[sizes[0]], by_n[n]))
            lines.append(f"{rev:>12}  cost per collision at N={n} / N={sizes[0]}, same "
                         f"round: median {statistics.median(slow):.2f}  range "
                         f"{slow[0]:.2f}-{slow[-1]:.2f}")
    return lines


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("revisions", nargs="+", help="git revisions to compare")
    ap.add_argument("--n", default="10000",
                    help="disks (packing 0.5); several sizes comma-separated")
    ap.add_argument("--k", default="10",
                    help="collisions per disk per call: one value, or one per size")
    ap.add_argument("--reps", type=int, default=7, help="timed calls per process")
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds")
    args = ap.parse_args(argv)
    try:
        sizes = _number_list(args.n, int)
        ks = _number_list(args.k, float)
    except ValueError:
        ap.error("--n takes integers and --k numbers, comma-separated")
    if len(ks) == 1:
        ks = ks * len(sizes)
    if not sizes or len(ks) != len(sizes):
        ap.error("give one --k, or one per size in --n")
    if (min(sizes) < 1 or min(ks) <= 0 or args.reps < 1 or args.rounds < 1
            or len(set(sizes)) != len(sizes)):
        ap.error("--n must be distinct sizes >= 1, --reps and --rounds >= 1, --k > 0")
    maxima = {rev: {n: [] for n in sizes} for rev in args.revisions}
    with tempfile.TemporaryDirectory() as tmp:
        trees = {rev: export(rev, Path(tmp)) for rev in args.revisions}
        for tree in trees.values():  # compile (untimed) before the first round
            run_once(tree, 200, 1.0, 1)
        for r in range(args.rounds):
            for rev, tree in trees.items():
                for n, k in zip(sizes, ks):
                    res = run_once(tree, n, k, args.reps)
                    maxima[rev][n].append(res["max"])
                    print(f"round {r + 1}  {rev:>12}  N={n}  "
                          f"max {res['max'] / 1e6:.3f}  median {res['median'] / 1e6:.3f} "
                          "M collisions/s", flush=True)
    print("\n".join(["", "summary (over rounds):"] + summarize(maxima, sizes)))


if __name__ == "__main__":
    main()
