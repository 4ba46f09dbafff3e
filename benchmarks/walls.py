"""Wall segments that move against fixed ones: what a moving segment costs.

A gas of ``N`` disks (radius 0.5, packing fraction 0.3 of the space between the
segments) in a box periodic along x, between a floor segment and a ceiling segment
across the box, under gravity ``(0, -0.2)`` (the floor is hit often):

- ``fixed``: both segments fixed (the reference);
- ``piston``: the ceiling comes down at 0.002 (a tenth of the gap in the time of the
  run, which is long: the piston keeps moving);
- ``shaken floor``: the floor oscillates with amplitude 0.5 and omega 3
  (``A omega^2 = 4.5``, 22 times gravity);
- ``both``.

    python benchmarks/walls.py --n 10000 --reps 3

``--ratio 10`` makes 1 % of the disks that many times wider (a mixture, which the
automatic choice puts on the wide grid; the packing fraction counts them).

Each system first runs ``advance(collisions=2 N)`` untimed; then, round after round,
each takes one turn of ``advance(collisions=k N)``, timed in process CPU time.  Prints
for each the median and range over the rounds of its collisions per second, of its
ratio to the fixed segments' turn of the same round, and the share of its events
that were contacts with a segment.
"""

from __future__ import annotations

import math
import statistics

import numpy as np
from timing import collision_rate as rate
from timing import turns_parser

import edmd2d as ed

PACKING = 0.3
R = 0.5


def radii(n: int, ratio: float) -> np.ndarray:
    """Radius 0.5, and ``ratio`` times that for the first 1 % (none for ratio 1)."""
    out = np.full(n, R)
    if ratio != 1.0:
        out[:max(1, n // 100)] = R * ratio
    return out


def build(n: int, motions: dict, ratio: float = 1.0) -> ed.Simulation:
    """The gas between a floor and a ceiling (a widest radius above and below its
    path), with the given motions."""
    rad = radii(n, ratio)
    width = math.sqrt(float(np.sum(math.pi * rad * rad)) / PACKING)
    # (square and periodic: rescaled below; equal disks as random_gas makes them)
    gas = ed.random_gas(n, PACKING, seed=1, **({} if ratio == 1.0 else {"radii": rad}))
    margin = max(2.0, 1.0 + float(rad.max()))
    pos = gas.positions * (width / gas.box.width) + [0.0, margin]
    height = width + 2.0 * margin
    walls = [ed.Wall((0.0, 1.0), (width, 1.0)), ed.Wall((0.0, height - 1.0),
                                                         (width, height - 1.0))]
    return ed.Simulation(pos, gas.velocities, gas.radii,
                         box=ed.Box(width, height, periodic=(True, False)),
                         walls=walls, gravity=(0.0, -0.2), wall_motions=motions)


def main() -> None:
    parser = turns_parser(__doc__, reps=3, reps_help="rounds of turns")
    parser.add_argument("--ratio", type=float, default=1.0,
                        help="1 %% of the disks this many times wider (default 1: none)")
    args = parser.parse_args()
    n = args.n
    rad = radii(n, args.ratio)
    width = math.sqrt(float(np.sum(math.pi * rad * rad)) / PACKING)
    piston = ed.Translation((0.0, -0.002), 0.1 * width)
    shaker = ed.Oscillation(0.5, 3.0)
    sims = {"fixed": build(n, {}, args.ratio), "piston": build(n, {1: piston}, args.ratio),
            "shaken floor": build(n, {0: shaker}, args.ratio),
            "both": build(n, {0: shaker, 1: piston}, args.ratio)}
    for sim in sims.values():
        sim.advance(collisions=2 * n)
    per_turn = max(1, int(args.k * n))
    rates: dict[str, list[float]] = {name: [] for name in sims}
    share: dict[str, list[float]] = {name: [] for name in sims}
    for _ in range(args.reps):
        for name, sim in sims.items():
            c0 = sim.counts
            rates[name].append(rate(sim, per_turn))
            c1 = sim.counts
            share[name].append((c1.wall_collisions - c0.wall_collisions)
                               / (c1.events - c0.events))
    grid = "wide" if sims["fixed"]._state.wide is not None else "uniform"
    print(f"N = {n}, packing fraction {PACKING}, size ratio {args.ratio:g} ({grid} grid), "
          f"{args.reps} rounds of {per_turn} collisions a turn")
    print("| segments | M collisions/s (range) | against fixed (range) | "
          "segment contacts per event |")
    print("|---|---|---|---|")
    for name, values in rates.items():
        ratios = [v / f for v, f in zip(values, rates["fixed"])]
        print(f"| {name} | {statistics.median(values) / 1e6:.3f} "
              f"({min(values) / 1e6:.3f}-{max(values) / 1e6:.3f}) | "
              f"{statistics.median(ratios):.3f} ({min(ratios):.3f}-{max(ratios):.3f}) | "
              f"{np.mean(share[name]):.4f} |")


if __name__ == "__main__":
    main()
