"""The cost of shear: a gas between Lees-Edwards boundaries against the same gas at rest.

Under shear the disks of the top and bottom rows of cells meet their neighbours through
the sliding boundary (four columns instead of three), are predicted afresh each time
the images slide by a cell (a slide), and every flight adds to the integrals of the
kinetic stress.  This script times the plain engine and the sheared one on the same
system, alternating them in one process so that the machine's drift hits both alike:

    python benchmarks/shear.py --n 10000 --reps 7

The system: ``make_gas(N, 0.5, seed=1, thermostat=(1, 0.1))`` with no shear, and the
same gas at the shear rates ``--rates`` (default 0.1 and 1, in units of
``sqrt(kT / m) / d``; the thermostat keeps ``kT`` near 1, a little above it at the
higher rate).  Each is run ``advance(collisions=3 N)`` untimed, then they take turns at
``advance(collisions=k N)``, timed in process CPU time.  Prints the median and range of
collisions/s of each, and of the ratio of each sheared turn to the plain turn before it.
"""

from __future__ import annotations

from timing import alternating_rates, print_rates, turns_parser

import edmd2d as ed


def main() -> None:
    parser = turns_parser(__doc__)
    parser.add_argument("--rates", type=str, default="0.1,1",
                        help="comma-separated shear rates")
    args = parser.parse_args()
    n = args.n
    shear_rates = [float(r) for r in args.rates.split(",")]
    systems = {"no shear": ed.make_gas(n, 0.5, seed=1, thermostat=(1.0, 0.1))}
    for r in shear_rates:
        systems[f"rate {r:g}"] = ed.make_gas(n, 0.5, seed=1, thermostat=(1.0, 0.1),
                                             shear_rate=r)
    rates, per_turn = alternating_rates(systems, n, args.k, args.reps)
    print(f"N = {n}, packing 0.5, thermostat kT = 1 at 0.1 redraws per disk per unit "
          f"time, {args.reps} turns of {per_turn} collisions each")
    print_rates(rates, "no shear")
    for name, sim in systems.items():
        print(f"  {name:>10}: kT = {ed.kinetic_temperature(sim):.4f} at t = {sim.time:.1f}")


if __name__ == "__main__":
    main()
