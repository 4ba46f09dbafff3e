"""Brownian motion: a heavy disk jostled by a bath of light ones.

Physics: one large disk (radius 3, mass 25) sits in a periodic bath of ~650 small disks
(radius 0.5, mass 1) at temperature kT = 1.  Every collision kicks it a little, in a
random direction; the kicks do not average out at once, so it wanders on an irregular
path -- the motion Brown saw in pollen grains and Einstein explained in 1905 as evidence
for molecules.  Its velocity is small (equipartition: ``M <V^2> / 2 = kT`` in 2D, so
``|V| ~ 0.3`` here against ``~1.4`` for the bath) and it loses memory of its direction
only after many collisions, so its path is smooth over short times and a random walk
(mean squared displacement growing linearly in time) over long ones.  The trail shows
the whole path.

Writes an animation (``.gif``, or ``.mp4`` if you name one) and the final frame
(``.png``) beside it::

    python examples/brownian_motion.py [examples/output/brownian_motion.gif]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

SEED = 3
L, SPACING = 40.0, 1.5  # box side; bath lattice spacing (gap 0.5 between bath disks)
R_HEAVY, M_HEAVY, R_BATH, M_BATH = 3.0, 25.0, 0.5, 1.0
KT = 1.0
DURATION, FPS, TIME_PER_SECOND = 300.0, 20, 25.0  # 12 s of video, 241 frames


def build() -> ed.Simulation:
    """Heavy disk in the centre (disk 0), bath disks on a square lattice around it."""
    rng = np.random.default_rng(SEED)
    centre = np.array([L / 2, L / 2])
    grid = (np.arange(int(L / SPACING)) + 0.5) * SPACING
    bath = np.array([(x, y) for x in grid for y in grid])
    keep = np.hypot(*(bath - centre).T) > R_HEAVY + R_BATH + 0.1
    pos = np.vstack([centre, bath[keep]])
    n = len(pos)
    radii = np.full(n, R_BATH)
    masses = np.full(n, M_BATH)
    radii[0], masses[0] = R_HEAVY, M_HEAVY
    # Maxwell-Boltzmann velocities at kT, total momentum removed (the bath must not
    # carry the heavy disk along as a whole).
    vel = rng.normal(size=(n, 2)) * np.sqrt(KT / masses)[:, None]
    vel -= masses @ vel / masses.sum()
    return ed.Simulation(pos, vel, radii=radii, masses=masses, box=ed.Box(L, L))


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    start = sim.unwrapped_positions[0]
    colours = ["C1"] + ["0.82"] * (len(sim) - 1)
    heavy_energy = []
    bar = viz.TextProgress()

    def record(i, n):  # after each frame: the heavy disk's kinetic energy
        bar(i, n)
        heavy_energy.append(0.5 * M_HEAVY * np.sum(sim.velocities[0] ** 2))

    frames = round(DURATION * FPS / TIME_PER_SECOND)
    anim = viz.animate(sim, DURATION, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by=colours, trail=frames, trail_disks=[0], trail_color="C3",
                       figsize=(4.8, 4.8))
    viz.save(anim, out, dpi=80, progress=record)
    still = out.with_suffix(".png")
    anim.ax.figure.savefig(still, dpi=100)  # the last frame, with the whole path
    plt.close(anim.ax.figure)

    disp = np.hypot(*(sim.unwrapped_positions[0] - start))
    print(f"wrote {out} and {still}: {len(sim) - 1} bath disks, {sim.counts.collisions} "
          f"collisions; the heavy disk moved {disp:.1f} from its start; "
          f"time-averaged M V^2 / 2 = {np.mean(heavy_energy):.2f} (equipartition: kT = {KT})")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "brownian_motion.gif")
