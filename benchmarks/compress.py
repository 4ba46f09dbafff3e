"""The cost of compression: collisions per second while the disks grow, and the time
to jam.

Growing disks have a contact distance that grows in time: every pair's contact time
is a quadratic whose leading coefficient can have either sign, and the grid is
rebuilt each time the disks have grown by 10%.  Two measurements:

1. **Collisions per second while growing**, against the same gas with fixed radii,
   in alternating turns in one process (the machine's drift hits both alike): a gas
   of ``N`` equal disks at packing fraction 0.5, one copy growing at ``rate`` 1e-3
   (:func:`edmd2d.compress`'s unit: its packing fraction rises by about 1% over
   the five turns, and its temperature is rescaled after each), the other not.

Measured (``--n 10000,100000 --reps 5``, with the other core busy): growing at 0.909
(0.901-0.926) of the speed of fixed radii at 10^4 (1.66 against 1.84 M coll/s) and
1.09 (0.92-1.11) at 10^5; jamming 10^4 disks took 25 s, 10^5 disks 298 s (2240
collisions per disk, 0.75-0.89 M coll/s including the rescaling every two
collisions per disk), both at packing fraction 0.8451.
2. **Time to jam** ``N`` disks of the 50:50 mixture of diameter ratio 1.4 from a
   random start at 0.4 at ``rate`` 1e-2, until ``Z`` passes 1e9 (the compression of
   ``examples/jammed_packing.py``): wall-clock seconds, collisions, and the packing
   fraction reached.

::

    python benchmarks/compress.py --n 10000,100000 --reps 5
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np
from timing import collision_rate as rate

import edmd2d as ed


def growing_rates(n: int, reps: int, k: float) -> dict:
    fixed = ed.make_gas(n, 0.5, seed=1)
    fixed.advance(collisions=5 * n)
    growing = fixed.__copy__()
    # compress()'s rate 1e-3: the diameter 1 grows at 1e-3 of the thermal speed 1.
    growing.set_growth(1e-3)
    per_turn = max(1, int(k * n))
    out = {"fixed radii": [], "growing": []}
    for _ in range(reps):
        out["fixed radii"].append(rate(fixed, per_turn))
        out["growing"].append(rate(growing, per_turn))
        growing.rescale_temperature(1.0)
    return out


def time_to_jam(n: int) -> tuple[float, int, float]:
    radii = np.where(np.arange(n) % 2, 0.5, 0.7)
    gas = ed.random_gas(n, 0.4, radii=radii, seed=1)
    t0 = time.perf_counter()
    result = ed.compress(gas, rate=1e-2, max_pressure=1e9)
    return time.perf_counter() - t0, int(result.collisions[-1]), result.packing_fraction


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", default="10000,100000", help="comma-separated sizes")
    parser.add_argument("--k", type=float, default=5.0, help="collisions per disk a turn")
    parser.add_argument("--reps", type=int, default=5)
    parser.add_argument("--no-jam", action="store_true", help="skip the time to jam")
    args = parser.parse_args()
    ed.compress(ed.random_gas(100, 0.4, seed=0), 0.5)  # (compile before timing)
    for n in (int(s) for s in args.n.split(",")):
        rates = growing_rates(n, args.reps, args.k)
        print(f"N = {n}, packing fraction 0.5, {args.reps} turns of {args.k:g} N collisions")
        for name, values in rates.items():
            print(f"  {name:>11}: median {statistics.median(values) / 1e6:.3f} M coll/s "
                  f"(range {min(values) / 1e6:.3f}-{max(values) / 1e6:.3f})")
        ratios = [b / a for a, b in zip(rates["fixed radii"], rates["growing"])]
        print(f"  growing / fixed: median {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.3f}-{max(ratios):.3f})")
        if not args.no_jam:
            seconds, collisions, phi = time_to_jam(n)
            print(f"  jam {n} disks (50:50, ratio 1.4, rate 1e-2, Z > 1e9): {seconds:.1f} s, "
                  f"{collisions / n:.0f} collisions per disk "
                  f"({collisions / seconds / 1e6:.2f} M coll/s), packing fraction {phi:.4f}")


if __name__ == "__main__":
    main()
