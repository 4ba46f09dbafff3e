"""Newton's cradle: one in, one out; two in, two out.

Physics: in each row five equal disks touch in a line.  In the top row one disk strikes
the line, in the bottom row two touching disks strike together.  An elastic head-on
collision of equal masses simply swaps their velocities, so the moving state is handed
along the row contact by contact and exactly as many disks leave at the far end as came
in -- the only outcome that conserves both momentum and kinetic energy with every disk
leaving at the striking speed.  Here each contact is its own instantaneous collision at
the exact same time, processed one after another (the idealization in which the cradle
is exact; real steel balls touch simultaneously and show a small spread).  The leaving
disks bounce off the side wall, come back, and the process runs in reverse, for ever.
There is no gravity: the walls of the box play the part of the strings.

Writes an animation (``.gif``, or ``.mp4`` if you name one) and a still of the first
moment after the impact (``.png``) beside it::

    python examples/newtons_cradle.py [examples/output/newtons_cradle.gif]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

R, SPEED = 1.0, 2.0
ROW = [11.0, 13.0, 15.0, 17.0, 19.0]  # five touching disks (spacing = one diameter)
DURATION, FPS, TIME_PER_SECOND = 40.0, 20, 4.0  # two full periods, 10 s, 201 frames


def build() -> ed.Simulation:
    top = [(x, 6.0) for x in [3.0, *ROW]]  # one striker
    bottom = [(x, 2.0) for x in [3.0, 5.0, *ROW]]  # two touching strikers
    pos = np.array(top + bottom)
    vel = np.zeros_like(pos)
    vel[[0, 6, 7], 0] = SPEED
    return ed.Simulation(pos, vel, radii=R, box=ed.Box(30.0, 8.0, periodic=False))


def moving(sim: ed.Simulation) -> tuple[list[int], list[int]]:
    """Indices within each row (0 = leftmost) of the disks that move."""
    fast = np.abs(sim.velocities[:, 0]) > 0.5 * SPEED
    return np.flatnonzero(fast[:6]).tolist(), np.flatnonzero(fast[6:]).tolist()


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    # A look just after the impact (t = 4: both rows have been struck by t = 3).
    check = build().advance(until=4.0)
    top, bottom = moving(check)
    ax = viz.draw(check, color_by="speed", vmax=SPEED, show_time=True, figsize=(6.4, 2.0))
    still = out.with_suffix(".png")
    ax.figure.savefig(still, dpi=100)
    plt.close(ax.figure)

    sim = build()
    anim = viz.animate(sim, DURATION, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by="speed", vmax=SPEED, figsize=(6.4, 2.0))
    viz.save(anim, out, dpi=80)
    plt.close(anim.ax.figure)
    print(f"wrote {out} and {still}: after the impact the moving disks are {top} in the top "
          f"row and {bottom} in the bottom row (of 6 and 7); {sim.counts.collisions} "
          f"collisions in t = {sim.time:g}, energy {sim.kinetic_energy():.12g} "
          f"(start {build().kinetic_energy():.12g})")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "newtons_cradle.gif")
