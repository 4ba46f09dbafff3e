"""Mixtures of disks of different sizes against equal disks: the speed against the
size ratio.

The uniform grid's cell must hold the largest disk, so a few big disks make every cell
large, and each small disk's prediction scans many neighbours.  This script measures
what that costs, on gases of ``N`` disks at packing fraction 0.35 in a periodic box
(``random_gas(N, 0.35, radii=..., seed=1)``, unit masses), small disks of radius 0.5:

- ``equal``: every disk of radius 0.5 (the reference of each ratio below);
- ``few big``: 1 % of the disks ``q`` times larger (``q`` = 2, 5, 10), 0.2 % for
  ``q = 20``, 0.05 % for ``q = 50`` (at least one big disk);
- ``50:50``: half the disks (by number) ``q`` times larger, ``q`` = 2, 5, 10;
- ``decade``: radii spread log-uniformly over a decade, 0.5 to 5.

    python benchmarks/sizes.py --n 10000 --reps 3 [--grid auto,uniform]

``--grid`` runs each mixture on each of the given grids (``Simulation(grid=...)``:
``auto`` lists the wide disks in the cells near them where that pays, ``uniform``
sizes every cell for the largest disk); the equal disks run once, on the uniform grid
that ``auto`` keeps for them.

Each system is first run ``advance(collisions=2 N)`` untimed (the random start
relaxes); then, round after round, every system takes one turn of
``advance(collisions=k N)``, timed in process CPU time, so that the machine's drift
hits all alike.  Prints, for each system, the median and range over the rounds of its
collisions per second and of its ratio to the equal disks' turn of the same round,
and the bytes per disk of the engine's arrays (``timing.engine_array_bytes``).
"""

from __future__ import annotations

import statistics

import numpy as np
from timing import collision_rate as rate
from timing import engine_array_bytes, turns_parser

import edmd2d as ed

SMALL = 0.5
PACKING = 0.35


def systems(n: int, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """The radii of each system, by name."""
    out = {"equal": np.full(n, SMALL)}
    for q, share in [(2, 0.01), (5, 0.01), (10, 0.01), (20, 0.002), (50, 0.0005)]:
        radii = np.full(n, SMALL)
        radii[:max(1, round(share * n))] = q * SMALL
        out[f"few big, ratio {q} ({100 * share:g} %)"] = radii
    for q in (2, 5, 10):
        radii = np.full(n, SMALL)
        radii[: n // 2] = q * SMALL
        out[f"50:50, ratio {q}"] = radii
    out["decade, 0.5 to 5"] = SMALL * 10.0 ** rng.uniform(0.0, 1.0, n)
    return out


def main() -> None:
    parser = turns_parser(__doc__, reps=3, reps_help="rounds of turns")
    parser.add_argument("--grid", default="auto",
                        help="comma-separated grids to run each mixture on (auto, uniform)")
    args = parser.parse_args()
    n = args.n
    grids = args.grid.split(",")
    sims = {}
    for name, radii in systems(n, np.random.default_rng(1)).items():
        gas = ed.random_gas(n, PACKING, radii=radii, seed=1)
        for grid in (["uniform"] if name == "equal" else grids):
            sim = ed.Simulation(gas.positions, gas.velocities, gas.radii, box=gas.box,
                                grid=grid)
            sim.advance(collisions=2 * n)
            label = name if name == "equal" or len(grids) == 1 else f"{name}, {grid}"
            if grid == "auto" and sim._state.wide is not None:
                label += f" [{len(sim._state.wide.disk)} wide]"
            sims[label] = sim
    per_turn = max(1, int(args.k * n))
    rates: dict[str, list[float]] = {name: [] for name in sims}
    for _ in range(args.reps):
        for name, sim in sims.items():
            rates[name].append(rate(sim, per_turn))
    print(f"N = {n}, packing fraction {PACKING}, {args.reps} rounds of {per_turn} "
          "collisions a turn")
    print("| system | M collisions/s (range) | against equal disks (range) | bytes/disk |")
    print("|---|---|---|---|")
    for name, values in rates.items():
        ratios = [v / e for v, e in zip(values, rates["equal"])]
        print(f"| {name} | {statistics.median(values) / 1e6:.3f} "
              f"({min(values) / 1e6:.3f}-{max(values) / 1e6:.3f}) | "
              f"{statistics.median(ratios):.3f} ({min(ratios):.3f}-{max(ratios):.3f}) | "
              f"{engine_array_bytes(sims[name]) / len(sims[name]):.0f} |")


if __name__ == "__main__":
    main()
