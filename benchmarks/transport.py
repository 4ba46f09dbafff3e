"""The cost of the Einstein-Helfand moments: a gas with them against the same gas without.

While a ``edmd2d.operations.Transport`` runs, the engine adds each disk's flight to
the moments as it moves it and each collision's energy transfer; otherwise it
compiles and runs as before.  This script times the engine with the moments on and
off on the same system, alternating them in one process so that the machine's drift
hits both alike:

    python benchmarks/transport.py --n 10000 --reps 7

The system: ``make_gas(N, 0.3, seed=1)``, twice.  The moments are switched on in one
copy as a ``Transport`` switches them on (``Transport.begin``), without its samples,
whose cost depends on ``dt`` and the window and is reported separately: the time
per sample of displacements and velocities at ``--lags`` windows.  Each copy is run
``advance(collisions=3 N)`` untimed, then they take turns at ``advance(collisions=k
N)``, timed in process CPU time.  Prints the median and range of collisions/s of each,
and of the ratio of each turn with the moments to the turn without before it.
"""

from __future__ import annotations

import statistics
import time

from timing import alternating_rates, print_rates, turns_parser

import edmd2d as ed
from edmd2d.transport import Transport


def main() -> None:
    parser = turns_parser(__doc__)
    parser.add_argument("--lags", type=int, default=40, help="windows per sample")
    args = parser.parse_args()
    n = args.n
    plain = ed.make_gas(n, 0.3, seed=1)
    moments = ed.make_gas(n, 0.3, seed=1)
    op = Transport(dt=1.0, window=float(args.lags), block=float(args.lags))
    op.begin(moments)  # (the engine's sums on, as during a run with op)
    rates, per_turn = alternating_rates({"without": plain, "with moments": moments}, n,
                                        args.k, args.reps)
    print(f"N = {n}, packing 0.3, {args.reps} turns of {per_turn} collisions each")
    print_rates(rates, "without", width=13)
    costs = []
    for _ in range(2 * args.lags):
        start = time.process_time()
        op(moments)
        costs.append(time.process_time() - start)
    print(f"  one sample at {args.lags} windows: median "
          f"{statistics.median(costs[args.lags:]) * 1e3:.2f} ms "
          f"({statistics.median(costs[args.lags:]) / n * 1e9:.0f} ns per disk)")
    op.close()


if __name__ == "__main__":
    main()
