"""A poured bed: inelastic disks fall, settle and come to rest, are kicked, settle again.

Physics: 300 disks (diameter 1, mass 1) with a coefficient of restitution e = 0.9 (and
0.9 on the walls) start as a gas at packing fraction 0.15 in a closed box twice as
tall as wide and fall under gravity g = 1.  Each collision loses the fraction 1 - e^2
of the normal relative motion's energy; within some 30 time units the disks have
formed a bed.  A disk that is slow (its kinetic energy could lift it by at most a
thousandth of a diameter) and held (by the disks at rest and the walls under it, or
with a group of slow disks that hold one another up) comes to rest: it stops being
simulated, so a settled bed costs nothing (:class:`edmd2d.physics.Resting`, on by
default for inelastic disks under gravity).  Without it the bounces of disks on disks
would shrink without end, an inelastic collapse, and the run would stop.

At ``KICK`` the disks of the lowest row are sent upwards at ``KICK_SPEED``: they wake
the bed above them as they hit it, the bed is thrown up, falls back and settles again.
Throughout, kinetic + potential + dissipated energy stays what it was at the start, to
rounding (the energy of a disk put to rest counts as dissipated, and is given back if
it wakes).

Writes an animation of the pour (``.gif``, or ``.mp4`` if you name one) and, beside it
(``_kick`` added to its name), one of the kick, disks coloured by speed; prints when
the bed came to rest, its height and packing fraction
(:func:`edmd2d.measurements.bed`), the events while it settled and once at rest, and
the energy books::

    python examples/poured_bed.py [--n 300] [--seed 1] [examples/output/poured_bed.gif]
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import measurements, viz  # noqa: E402

N, PACKING, SEED, RESTITUTION, GRAVITY = 300, 0.15, 1, 0.9, 1.0
KICK, KICK_SPEED, END = 100.0, 6.0, 200.0  # kick the lowest row at KICK, run to END
ANIMATE, FPS, TIME_PER_SECOND = 40.0, 12, 4.0  # the first ANIMATE of the pour and kick


def build() -> ed.Simulation:
    """The gas of the pour, in a walled box twice as tall as wide."""
    return ed.make_gas(N, PACKING, periodic=False, aspect=0.5, seed=SEED,
                       restitution=RESTITUTION, wall_restitution=RESTITUTION,
                       gravity=(0.0, -GRAVITY))


def settle(sim: ed.Simulation, until: float, step: float = 5.0):
    """Advance ``sim`` in steps to ``until``: the first step's end at which every disk
    was at rest (``None``: not by then), and the events processed after it."""
    at_rest, events = None, sim.counts.events
    while sim.time < until:
        sim.advance(until=min(sim.time + step, until))
        if at_rest is None and sim.resting.all():
            at_rest, events = sim.time, sim.counts.events
    return at_rest, sim.counts.events - events


def animate(sim: ed.Simulation, out: Path, duration: float) -> None:
    anim = viz.animate(sim, duration, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by="speed", vmin=0.0, vmax=KICK_SPEED, colorbar=True,
                       figsize=(3.6, 6.0))
    anim.ax.figure.axes[-1].set_ylabel("speed")
    viz.save(anim, out, dpi=80, progress=viz.TextProgress())
    plt.close(anim.ax.figure)


def main(out: Path) -> dict:
    """Pour, settle, kick, settle again; animate, print; return the measured numbers
    (``rest_1``, ``rest_2``: when every disk was at rest before and after the kick;
    ``bed_1``, ``bed_2``: the beds then; ``quiet_1``, ``quiet_2``: the events after
    that; ``woken``: wakes after the kick; ``books``: the worst energy books, relative to
    the energy)."""
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    e0 = sim.total_energy() + sim.dissipated_energy()
    books = []
    clock = time.perf_counter()
    animate(sim, out, min(ANIMATE, KICK))
    rest_1, quiet_1 = settle(sim, KICK)
    bed_1 = measurements.bed(sim)
    events = sim.counts.events
    books.append(sim.total_energy() + sim.dissipated_energy() - e0)
    # The kick: the lowest row upwards.
    vel = np.array(sim.velocities)
    lowest = sim.positions[:, 1] < 2.0 * sim.radii
    vel[lowest] = [0.0, KICK_SPEED]
    sim.set_velocities(vel)
    e1 = sim.total_energy() + sim.dissipated_energy()
    wakes = sim.counts.wakes
    animate(sim, out.with_name(out.stem + "_kick" + out.suffix), min(ANIMATE, END - KICK))
    rest_2, quiet_2 = settle(sim, END)
    bed_2 = measurements.bed(sim)
    books.append(sim.total_energy() + sim.dissipated_energy() - e1)
    seconds = time.perf_counter() - clock
    print(f"{N} disks, e = {RESTITUTION}, box {sim.box.width:.2f} x {sim.box.height:.2f}, "
          f"g = {GRAVITY}")
    for name, rest, bed in (("poured", rest_1, bed_1), ("kicked", rest_2, bed_2)):
        print(f"  {name}: every disk at rest by t = {rest}; bed height {bed.height:.2f}, "
              f"packing fraction {bed.packing_fraction:.3f} below {bed.band[1]:.2f}")
    print(f"  the pour: {events} events, then {quiet_1} at rest in the "
          f"{KICK - (rest_1 or KICK):.0f} time units before the kick; the kick: "
          f"{sim.counts.events - events} events, then {quiet_2} at rest to t = {END:g}")
    print(f"  the kick woke {sim.counts.wakes - wakes} disks at rest (some several "
          f"times); {sim.counts.events} events in all, {seconds:.1f} s")
    print(f"  energy books: {max(abs(b) for b in books) / abs(e0):.1e} of the energy")
    print(f"wrote {out} (the pour) and {out.with_name(out.stem + '_kick' + out.suffix)} "
          "(the kick)")
    return dict(rest_1=rest_1, rest_2=rest_2, bed_1=bed_1, bed_2=bed_2, quiet_1=quiet_1,
                quiet_2=quiet_2, woken=sim.counts.wakes - wakes,
                books=max(abs(b) for b in books) / abs(e0), e0=e0)


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "poured_bed.gif")
