"""A short tour of edmd2d: 10 000 hard disks at packing fraction 0.5 in a periodic box.

Hard disks fly on straight lines and bounce elastically; edmd2d finds every collision at
its exact time.  This demo builds the gas, runs half a million collisions, and prints
what happened: event counts, speed, and the conservation checks that tell the numbers
can be trusted.

    python examples/demo.py [N] [packing_fraction]
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from scipy.spatial import cKDTree

import edmd2d as ed


def main(n: int = 10_000, phi: float = 0.5) -> None:
    t0 = time.perf_counter()
    sim = ed.make_gas(n, phi, seed=2026)
    sim.advance(collisions=1)  # compiles the engine on first use (cached afterwards)
    print(f"built {n} disks at packing fraction {phi} in a {sim.box.width:.1f} x "
          f"{sim.box.height:.1f} periodic box, engine ready in {time.perf_counter() - t0:.1f} s")

    e0, p0 = sim.kinetic_energy(), sim.momentum()
    c0 = sim.counts
    t0 = time.perf_counter()
    sim.advance(collisions=50 * n)
    wall = time.perf_counter() - t0
    c = sim.counts
    coll = c.collisions - c0.collisions
    print(f"ran to t = {sim.time:.3f}: {coll} collisions, {c.cell_crossings - c0.cell_crossings} "
          f"cell crossings in {wall:.2f} s = {coll / wall / 1e6:.2f} million collisions/s")
    print(f"collisions per disk per unit time: {2 * coll / n / (sim.time):.3f}")
    print(f"relative energy change: {sim.kinetic_energy() / e0 - 1:+.1e}, "
          f"momentum change: {np.abs(sim.momentum() - p0).max():.1e}")
    tree = cKDTree(sim.positions % sim.box.size, boxsize=sim.box.size)
    close = tree.query_pairs(2 * 0.5 * (1 - 1e-9))
    print(f"overlapping pairs at the end: {len(close)}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("n", nargs="?", type=int, default=10_000,
                        help="number of disks (default 10000)")
    parser.add_argument("packing_fraction", nargs="?", type=float, default=0.5,
                        help="area covered by the disks (default 0.5)")
    args = parser.parse_args()
    if args.n < 1 or not 0.0 < args.packing_fraction < ed.lattice_packing_limit(args.n):
        parser.error("N must be >= 1 and the packing fraction in (0, the lattice limit)")
    main(args.n, args.packing_fraction)
