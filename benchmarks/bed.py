"""A poured bed: the time it takes to settle, the speed while it flows, its cost at rest.

``N`` inelastic disks (``restitution = wall_restitution = 0.9``) start as a gas at
packing fraction ``--packing`` (0.15) in a walled box ``--aspect`` (2) times as wide
as tall (``make_gas(N, packing, periodic=False, aspect=aspect, seed=1, gravity=(0,
-1))``), fall, and settle into a bed, the disks coming to rest with the library's
defaults:

    python benchmarks/bed.py --n 100000

Every ``--interval`` time units it prints the disks at rest, the kinetic energy against
its start, the events of the interval and the events per second of wall time.  Once
every disk is at rest (or at ``--until``), it advances 100 more time units and reports
their events and wall time (the cost at rest), then the bed's height and packing
fraction (``edmd2d.measurements.bed``).
"""

from __future__ import annotations

import argparse
import time

import edmd2d as ed
from edmd2d import measurements


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--n", type=int, default=100_000)
    parser.add_argument("--interval", type=float, default=10.0)
    parser.add_argument("--until", type=float, default=2000.0)
    parser.add_argument("--packing", type=float, default=0.15)
    parser.add_argument("--aspect", type=float, default=2.0)
    args = parser.parse_args()
    sim = ed.make_gas(args.n, args.packing, periodic=False, aspect=args.aspect, seed=1,
                      restitution=0.9, wall_restitution=0.9, gravity=(0.0, -1.0))
    w, h = sim.box.size
    print(f"N = {args.n}, box {w:.1f} x {h:.1f}, rest search every "
          f"{sim.families['resting'].every:.3f} time units", flush=True)
    sim.advance(collisions=1)  # (compiles the engine, untimed)
    k0 = sim.kinetic_energy()
    e0 = sim.total_energy() + sim.dissipated_energy()
    start = time.perf_counter()
    events = sim.counts.events
    t = sim.time
    while t < args.until and not sim.resting.all():
        t = min(t + args.interval, args.until)
        clock = time.perf_counter()
        sim.advance(until=t)
        wall = time.perf_counter() - clock
        done = sim.counts.events - events
        events = sim.counts.events
        print(f"t = {t:8.1f}  at rest {int(sim.resting.sum()):>8d}  "
              f"KE/KE0 {sim.kinetic_energy() / k0:9.2e}  events {done:>11d}  "
              f"{done / max(wall, 1e-9) / 1e6:6.3f} M events/s  wall {wall:7.1f} s",
              flush=True)
    settled = time.perf_counter() - start
    print(f"settled: {sim.resting.all()} at t = {sim.time:.1f}, wall {settled:.1f} s, "
          f"{sim.counts.events} events ({sim.counts.events / settled / 1e6:.3f} M/s over "
          f"the whole run), energy books "
          f"{(sim.total_energy() + sim.dissipated_energy() - e0) / abs(e0):.1e} of E0")
    clock = time.perf_counter()
    before = sim.counts.events
    sim.advance(until=sim.time + 100.0)
    print(f"at rest: {sim.counts.events - before} events in 100 time units, "
          f"{time.perf_counter() - clock:.2f} s of wall time")
    b = measurements.bed(sim)
    print(f"bed: {b.disks} disks at rest, mean height {b.height:.2f}, top {b.top:.2f}, "
          f"packing fraction {b.packing_fraction:.4f} below {b.band[1]:.2f}")


if __name__ == "__main__":
    main()
