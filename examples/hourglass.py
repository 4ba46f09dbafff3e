"""An hourglass: a bed of inelastic disks runs through a neck, and is turned over.

Physics: ``N`` disks (diameter 1, mass 1, coefficient of restitution e = 0.9, also on
the walls) fill the upper chamber of a closed box ``WIDTH`` wide and ``HEIGHT`` tall
under gravity g = 1.  Two funnels of wall segments, one above and one below the middle
of the box, meet at a neck ``NECK`` wide, closed at first by a gate (a segment).  The
disks start on a lattice and fall onto the funnel; at ``OPEN`` the gate opens
(:meth:`edmd2d.Simulation.open_wall`) and the bed runs through the neck into the lower
chamber, where the disks come to rest (:class:`edmd2d.physics.Resting`).  Once every
disk has run through and come to rest, the hourglass is turned over: gravity is
reversed (:meth:`edmd2d.Simulation.set_gravity`, which wakes every disk at rest and
books the jump of the potential energy), and the disks run back.

How steady does it run?  A granular flow through an outlet is set by the free fall of
the grains through an arch of the outlet's size (Beverloo), not by the pressure of the
bed above, so the count above the neck should fall linearly in time, unlike a liquid
draining through a hole, whose outflow goes as the square root of its depth
(Torricelli).  The example fits a straight line to the count while 80 % to 20 % of the
disks are still to run, and a line to each half of that (80-50 % and 50-20 %): for
Torricelli's liquid the first half's rate would be about 1.4 times the second's.

Measured (``python examples/hourglass.py``, 300 disks, neck 3): 4.03 +- 0.04 disks
per unit time, the count within 9 disks of the line; but 4.63 +- 0.06 in the first
half and 3.57 +- 0.03 in the second (a ratio of 1.30), and after the turn 4.62 and
4.10 (1.13).  This hourglass of frictionless disks does not keep time as well as the
sand of a real one: its bed, 20 diameters deep at the start, slows its flow as it
gets shallower.  (The silo of ``examples/beverloo.py``, 36 diameters wide, showed no
trend with fill heights of 15 to 29 diameters.)  The errors are those of the fits,
from the scatter about the lines.

Writes an animation of the run and of the turn (``.gif``, or ``.mp4`` if you name one),
disks coloured by speed, and beside it (``.png``) the number of disks above the neck
against time with the fitted line; prints the rates and the energy books::

    python examples/hourglass.py [--n 300] [examples/output/hourglass.gif]
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
from edmd2d import operations as op  # noqa: E402
from edmd2d import viz  # noqa: E402

N, SEED, RESTITUTION, GRAVITY = 300, 1, 0.9, 1.0
WIDTH, HEIGHT, NECK, FUNNEL = 16.0, 64.0, 3.0, 7.0  # the box, the neck, a funnel's height
OPEN, LONGEST = 15.0, 300.0  # the gate opens; the longest run of each half
FPS, TIME_PER_SECOND = 10, 10.0  # the animation's pace
SAMPLE = TIME_PER_SECOND / FPS  # the count and a frame every SAMPLE


def walls() -> list[ed.Wall]:
    """The two funnels meeting at the neck (segments 0-3) and the gate across it (4)."""
    mid, left, right = 0.5 * HEIGHT, 0.5 * (WIDTH - NECK), 0.5 * (WIDTH + NECK)
    return [ed.Wall((0.0, mid + FUNNEL), (left, mid)), ed.Wall((right, mid), (WIDTH, mid + FUNNEL)),
            ed.Wall((0.0, mid - FUNNEL), (left, mid)), ed.Wall((right, mid), (WIDTH, mid - FUNNEL)),
            ed.Wall((left, mid), (right, mid))]


def build() -> ed.Simulation:
    """The hourglass, its gate closed, with the disks on a lattice above the funnel."""
    xs = np.arange(0.55, WIDTH - 0.54, 1.05)
    bottom = 0.5 * HEIGHT + FUNNEL + 0.6
    rows = math.ceil(N / len(xs))
    pos = np.array([(x, bottom + 1.05 * k) for k in range(rows) for x in xs])[:N]
    if pos[:, 1].max() + 0.5 > HEIGHT:
        raise ValueError(f"{N} disks do not fit in an hourglass {WIDTH} wide and "
                         f"{HEIGHT} tall")
    vel = np.random.default_rng(SEED).normal(scale=0.1, size=(N, 2))
    return ed.Simulation(pos, vel, 0.5, box=ed.Box(WIDTH, HEIGHT, periodic=False),
                         walls=walls(), gravity=(0.0, -GRAVITY), restitution=RESTITUTION,
                         wall_restitution=RESTITUTION, seed=SEED)


def run(sim: ed.Simulation, above: bool, frames: list) -> tuple[np.ndarray, np.ndarray]:
    """Run until every disk has gone through the neck and come to rest (or for
    ``LONGEST``), counting every ``SAMPLE`` the disks above (or below) the neck and
    keeping a frame of the animation."""
    times, n = [], []
    end = sim.time + LONGEST
    while sim.time < end - 1e-9:
        sim.advance(until=min(sim.time + SAMPLE, end))
        y = sim.positions[:, 1]
        times.append(sim.time)
        n.append(int(np.sum(y > 0.5 * HEIGHT) if above else np.sum(y < 0.5 * HEIGHT)))
        frames.append(op.Snapshot(sim))
        if n[-1] == 0 and sim.resting.all():
            break
    return np.array(times), np.array(n)


def _line(times: np.ndarray, n: np.ndarray, lo: float, hi: float) -> tuple:
    """The straight line through the samples with ``lo N <= n <= hi N``: its slope
    with its error (from the scatter about it), intercept, largest departure, and the
    times it spans."""
    sel = (n >= lo * N) & (n <= hi * N)
    if sel.sum() < 4:
        raise RuntimeError(f"the flow did not run steadily: {sel.sum()} samples with "
                           f"{lo:.0%} to {hi:.0%} of the disks still to run")
    (slope, intercept), cov = np.polyfit(times[sel], n[sel], 1, cov=True)
    departure = np.abs(n[sel] - (slope * times[sel] + intercept)).max()
    return (float(slope), float(math.sqrt(cov[0, 0])), float(intercept), float(departure),
            float(times[sel][0]), float(times[sel][-1]))


def steady_rate(times: np.ndarray, n: np.ndarray) -> dict:
    """The rate while 80 % to 20 % of the disks are still to run (the count ``n``):
    the straight line through it (rate, error, largest departure in disks), and the
    rates of its two halves, 80-50 % and 50-20 % (with their errors), which a flow
    that slows as the bed above the neck gets lower would tell apart."""
    slope, err, intercept, departure, start, end = _line(times, n, 0.2, 0.8)
    early, early_err = _line(times, n, 0.5, 0.8)[:2]
    late, late_err = _line(times, n, 0.2, 0.5)[:2]
    return dict(rate=-slope, error=err, departure=departure, slope=slope,
                intercept=intercept, start=start, end=end, early=-early,
                early_error=early_err, late=-late, late_error=late_err)


def main(out: Path) -> dict:
    """Fill, open, count, turn over, count, animate, plot, print; return the rates and
    the energy books (relative to the largest energy term)."""
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    clock = time.perf_counter()
    sim.advance(until=OPEN)  # the bed forms on the closed gate
    rested = int(sim.resting.sum())
    e0 = sim.total_energy() + sim.dissipated_energy()
    sim.open_wall(4)
    frames = [op.Snapshot(sim)]
    t1, n1 = run(sim, True, frames)
    first = steady_rate(t1, n1)
    left_above, flip = int(n1[-1]), sim.time
    sim.set_gravity((0.0, GRAVITY))  # turned over
    t2, n2 = run(sim, False, frames)
    second = steady_rate(t2, n2)
    books = (sim.total_energy() + sim.dissipated_energy() - sim.gravity_work() - e0) / max(
        abs(sim.potential_energy()), abs(e0))
    wall = time.perf_counter() - clock
    anim = viz.animate_frames(frames, fps=FPS, color_by="speed", vmin=0.0, vmax=6.0,
                              colorbar=True, figsize=(3.2, 8.0))
    anim.ax.figure.axes[-1].set_ylabel("speed")
    viz.save(anim, out, dpi=70, progress=viz.TextProgress())
    plt.close(anim.ax.figure)
    fig, ax = plt.subplots(figsize=(5.0, 3.4))
    ax.plot(t1, n1, ".", ms=2, label="above the neck")
    ax.plot(t2, n2, ".", ms=2, label="below the neck, turned over")
    for fit in (first, second):
        tt = np.array([fit["start"], fit["end"]])
        ax.plot(tt, fit["slope"] * tt + fit["intercept"], "k-", lw=1)
    ax.axvline(flip, color="0.6", lw=0.8)
    ax.set_xlabel("time")
    ax.set_ylabel("disks still to run through")
    ax.legend(fontsize=8)
    fig.tight_layout()
    still = out.with_suffix(".png")
    fig.savefig(still, dpi=100)
    plt.close(fig)
    print(f"{N} disks, e = {RESTITUTION}, hourglass {WIDTH:g} x {HEIGHT:g}, neck {NECK:g}, "
          f"g = {GRAVITY}; {rested} at rest on the gate when it opens at t = {OPEN:g}")
    for name, fit in (("run", first), ("after the turn", second)):
        print(f"  {name}: {fit['rate']:.3f} +- {fit['error']:.3f} disks per unit time over "
              f"t = {fit['start']:.0f} to {fit['end']:.0f}, the count at most "
              f"{fit['departure']:.1f} disks off the straight line; "
              f"{fit['early']:.3f} +- {fit['early_error']:.3f} with 80-50 % of the disks "
              f"to run, {fit['late']:.3f} +- {fit['late_error']:.3f} with 50-20 %")
    print(f"  {left_above} disks left above the neck when turned over at t = {flip:g}, "
          f"all at rest: {sim.resting.all()}; "
          f"{sim.counts.events} events, {wall:.1f} s; energy books {abs(books):.1e} of "
          "the largest energy term")
    print(f"wrote {out} and {still}")
    return dict(first=first, second=second, left_above=left_above, rested=rested,
                flip=flip, end=sim.time, at_rest=bool(sim.resting.all()), books=abs(books))


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "hourglass.gif")
