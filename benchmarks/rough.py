"""The cost of rough disks: a gas that spins against the same gas smooth.

Rough disks (``edmd2d.physics.Rough``) add a tangential impulse to every contact and
keep an angular velocity, an angle and a moment of inertia per disk beside the state
rows; contact times do not change.  This script times the plain engine and rough
ones on the same system, alternating them in one process so that the machine's
drift hits all alike:

    python benchmarks/rough.py --n 10000 --reps 7

The systems: ``make_gas(N, 0.5, seed=1)``, smooth; with ``tangential_restitution=1``
(elastic, perfectly rough); and with ``restitution=0.95, tangential_restitution=0.5,
friction=0.3`` besides an inelastic smooth gas of the same ``restitution`` (the TC
model's bookkeeping is the same in both).  Each is run ``advance(collisions=3 N)``
untimed, then they take turns at ``advance(collisions=k N)``, timed in process CPU
time.  Prints the median and range of collisions/s of each and of each one's ratio to
its smooth counterpart, and the extra bytes per disk.
"""

from __future__ import annotations

from timing import alternating_rates, print_rates, turns_parser

import edmd2d as ed


def main() -> None:
    parser = turns_parser(__doc__)
    args = parser.parse_args()
    n = args.n
    elastic = {"smooth": ed.make_gas(n, 0.5, seed=1),
               "rough": ed.make_gas(n, 0.5, seed=1, tangential_restitution=1.0)}
    inelastic = {"smooth, e=0.95": ed.make_gas(n, 0.5, seed=1, restitution=0.95),
                 "rough, e=0.95": ed.make_gas(n, 0.5, seed=1, restitution=0.95,
                                              tangential_restitution=0.5, friction=0.3)}
    for name, systems in (("elastic", elastic), ("inelastic", inelastic)):
        rates, per_turn = alternating_rates(systems, n, args.k, args.reps)
        print(f"{name}: N = {n}, packing 0.5, {args.reps} turns of {per_turn} "
              f"collisions each")
        print_rates(rates, next(iter(systems)), width=15)
    state = elastic["rough"]._state
    extra = sum(getattr(state, name).nbytes for name in
                ("rough_w", "rough_angle", "rough_t", "rough_inv_inertia")) / n
    print(f"memory: {extra:.0f} more bytes per disk")


if __name__ == "__main__":
    main()
