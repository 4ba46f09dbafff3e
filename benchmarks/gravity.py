"""The cost of gravity: an elastic gas under gravity against the same gas without it.

Under gravity every flight is a parabola: positions and velocities of neighbours are
evaluated with the acceleration, cell exits and box walls are quadratics with two
boundaries each, and a disk's contacts with fixed points (segment ends, immovable
disks) are quartics.  This script times the straight-line engine and the gravity
engine on the same system, alternating them in one process so that the machine's drift
hits both alike:

    python benchmarks/gravity.py --n 10000 --reps 7

The system: ``make_gas(N, 0.3, periodic=(True, False), seed=1)`` (a channel, walled in
y), with ``gravity=(0, -g)`` chosen so that the decay length kT / (m g) is half the
box height (a gas visibly denser at the floor, but filling the box), and the same gas
with no gravity.  Each is run ``advance(collisions=3 N)`` untimed (the gas under
gravity settles), then the two take turns at ``advance(collisions=k N)``, timed in
process CPU time.  Prints the median and range of collisions/s of each, and of the
ratio of each pair of turns.
"""

from __future__ import annotations

import statistics

from timing import collision_rate as rate
from timing import turns_parser

import edmd2d as ed


def main() -> None:
    parser = turns_parser(__doc__)
    args = parser.parse_args()
    n = args.n
    flat = ed.make_gas(n, 0.3, periodic=(True, False), seed=1)
    g = 1.0 / (0.5 * flat.box.height)  # kT = 1 (make_gas), m = 1: kT / (m g) = H / 2
    falling = ed.make_gas(n, 0.3, periodic=(True, False), seed=1, gravity=(0.0, -g))
    for sim in (flat, falling):
        sim.advance(collisions=3 * n)
    per_turn = max(1, int(args.k * n))
    rates = {"no gravity": [], "gravity": []}
    for _ in range(args.reps):
        rates["no gravity"].append(rate(flat, per_turn))
        rates["gravity"].append(rate(falling, per_turn))
    print(f"N = {n}, g = {g:.4g} (decay length H/2), {args.reps} turns of {per_turn} "
          "collisions each")
    for name, values in rates.items():
        print(f"  {name:>10}: median {statistics.median(values) / 1e6:.3f} M coll/s "
              f"(range {min(values) / 1e6:.3f}-{max(values) / 1e6:.3f})")
    ratios = [b / a for a, b in zip(rates["no gravity"], rates["gravity"])]
    print(f"  gravity / no gravity: median {statistics.median(ratios):.3f} "
          f"(range {min(ratios):.3f}-{max(ratios):.3f})")


if __name__ == "__main__":
    main()
