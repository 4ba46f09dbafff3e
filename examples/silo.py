"""A silo: a bed of inelastic disks pours through an outlet at a steady rate.

Physics: ``N`` disks (diameter 1, mass 1, coefficient of restitution e = 0.9, also on
the walls) fill a flat-bottomed silo ``WIDTH`` wide under gravity g = 1, its outlet of
width ``OUTLET`` in the middle of the bottom closed by a gate (a wall segment).  The
box is periodic along ``y`` and walled along ``x``: a disk that leaves through the
outlet falls to the bottom of the box and re-enters at its top, falling back onto the
bed, so that the silo discharges for ever at a steady rate.  Its energy is the
potential energy of the fall: ``potential_energy()`` uses the unwrapped heights, so a
disk loses ``m g H`` at each pass through the box (``H`` its height), and kinetic +
potential + dissipated energy stays what it was at the start, to rounding.

The disks start on a lattice above the closed gate and settle into a bed; at ``OPEN``
the gate opens (:meth:`edmd2d.Simulation.open_wall`) and the bed flows.  After a
transient of ``TRANSIENT`` the discharge rate is measured over ``DURATION`` in 10
blocks (:func:`edmd2d.measurements.discharge`: the net crossings of a line across the
box, per unit time), and compared with the rate of Beverloo's law in two dimensions,
``W = C sqrt(g) (D - k d)^(3/2) / d^(3/2)`` (disks per unit time), with ``C`` and ``k``
fitted to the discharge of wider silos over five outlet widths and three fill heights
(``examples/beverloo.py``; ``docs/gravity-and-heat.md``).

Writes an animation of the filling and the first ``ANIMATE`` time units of the flow
(``.gif``, or ``.mp4`` if you name one), disks coloured by speed, and prints the rate
with its error::

    python examples/silo.py [--n 400] [--duration 100] [examples/output/silo.gif]
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import measurements, viz  # noqa: E402

N, SEED, RESTITUTION, GRAVITY = 400, 1, 0.9, 1.0
WIDTH, HEIGHT, FLOOR, OUTLET = 20.0, 50.0, 8.0, 4.0  # the silo and its outlet
OPEN, TRANSIENT, DURATION = 15.0, 30.0, 100.0  # gate opens; the flow settles; measured
ANIMATE, FPS, TIME_PER_SECOND = 40.0, 12, 4.0  # the first ANIMATE of the flow animated
# Beverloo's law as examples/beverloo.py fits it to its 15 silos (see the module notes).
BEVERLOO_C, BEVERLOO_K = 1.36, 1.27


def build() -> ed.Simulation:
    """The silo, its gate (segment 2) closed, with the disks on a lattice above it."""
    box = ed.Box(WIDTH, HEIGHT, periodic=(False, True))
    left, right = 0.5 * (WIDTH - OUTLET), 0.5 * (WIDTH + OUTLET)
    walls = [ed.Wall((0.0, FLOOR), (left, FLOOR)), ed.Wall((right, FLOOR), (WIDTH, FLOOR)),
             ed.Wall((left, FLOOR), (right, FLOOR))]
    xs = np.arange(0.55, WIDTH - 0.54, 1.05)
    rows = math.ceil(N / len(xs))
    pos = np.array([(x, FLOOR + 0.6 + 1.05 * k) for k in range(rows) for x in xs])[:N]
    if pos[:, 1].max() + 0.5 > HEIGHT:
        raise ValueError(f"{N} disks do not fit in a silo {WIDTH} wide and {HEIGHT} tall")
    vel = np.random.default_rng(SEED).normal(scale=0.1, size=(N, 2))
    return ed.Simulation(pos, vel, 0.5, box=box, walls=walls, gravity=(0.0, -GRAVITY),
                         restitution=RESTITUTION, wall_restitution=RESTITUTION, seed=SEED)


def beverloo(outlet: float) -> float:
    """Beverloo's discharge rate (disks per unit time) for an outlet of that width."""
    return BEVERLOO_C * math.sqrt(GRAVITY) * max(outlet - BEVERLOO_K, 0.0) ** 1.5


def main(out: Path) -> dict:
    """Fill, open, animate, measure, print; return the measured numbers (``rate``,
    ``error``, ``beverloo``: the rate of the fitted law; ``books``: the energy books
    relative to the largest energy term)."""
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    e0 = sim.total_energy() + sim.dissipated_energy()
    clock = time.perf_counter()
    sim.advance(until=OPEN)  # the bed forms on the closed gate
    sim.open_wall(2)
    anim = viz.animate(sim, ANIMATE, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by="speed", vmin=0.0, vmax=6.0, colorbar=True,
                       figsize=(4.2, 7.0))
    anim.ax.figure.axes[-1].set_ylabel("speed")
    viz.save(anim, out, dpi=80, progress=viz.TextProgress())
    plt.close(anim.ax.figure)
    sim.advance(until=OPEN + max(TRANSIENT, ANIMATE))
    flow = measurements.discharge(sim, DURATION, blocks=10)
    books = (sim.total_energy() + sim.dissipated_energy() - e0) / max(
        abs(sim.potential_energy()), abs(e0))
    law = beverloo(OUTLET)
    print(f"{N} disks, e = {RESTITUTION}, silo {WIDTH:g} wide, outlet {OUTLET:g}, g = "
          f"{GRAVITY}")
    print(f"  discharge over t = {sim.time - DURATION:g} to {sim.time:g}: "
          f"{flow.rate:.3f} +- {flow.error:.3f} disks per unit time (Beverloo's law as "
          f"fitted: {law:.3f})")
    print(f"  {sim.counts.events} events, {time.perf_counter() - clock:.1f} s; energy "
          f"books {abs(books):.1e} of the largest energy term")
    print(f"wrote {out}")
    return dict(rate=flow.rate, error=flow.error, beverloo=law, books=abs(books),
                blocks=flow.block_rates)


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "silo.gif")
