"""Disks in a polygonal container: walls scramble an ordered flow.

Physics: about 200 disks fill an octagonal container built from wall segments
(``Wall.polygon``), with a triangular obstacle in the middle.  They all start moving in
the same direction at the same speed -- a perfectly ordered flow.  A flat wall reflects
a disk specularly (the velocity component along the wall is kept, the normal one
reversed), which by itself would only fold the flow into a few directions; but the
convex obstacle and the corners, where a disk bounces off a segment's end point as off a
disk of radius zero, scatter nearby trajectories apart (a dispersing billiard, as in
Sinai's), and disk-disk collisions do the same.  Within a few crossings of the container
the directions are spread over the full circle and the gas is isotropic: the container
has no conserved momentum, only energy.  Disks are coloured by the direction of their
velocity on a cyclic colour scale, so the start is one colour and the end a mix of all.

Writes an animation (``.gif``, or ``.mp4`` if you name one) and the final frame
(``.png``) beside it::

    python examples/polygon_container.py [examples/output/polygon_container.gif]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.path import Path as PolygonPath  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

L, R, SPACING = 30.0, 0.5, 1.55  # box side, disk radius, starting lattice spacing
DURATION, FPS, TIME_PER_SECOND = 60.0, 20, 5.0  # 12 s of video, 241 frames


def regular_polygon(k: int, centre, radius: float, phase: float = 0.0) -> np.ndarray:
    angle = phase + 2 * np.pi * np.arange(k) / k
    return np.asarray(centre) + radius * np.stack([np.cos(angle), np.sin(angle)], axis=1)


def distance_to_segments(points: np.ndarray, walls) -> np.ndarray:
    """Smallest distance from each point to any wall segment."""
    best = np.full(len(points), np.inf)
    for w in walls:
        a, b = np.array(w.start), np.array(w.end)
        s = np.clip((points - a) @ (b - a) / np.dot(b - a, b - a), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(points - a - s[:, None] * (b - a)).T))
    return best


def build() -> ed.Simulation:
    centre = (L / 2, L / 2)
    outer = regular_polygon(8, centre, 14.0, phase=np.pi / 8)
    inner = regular_polygon(3, centre, 3.5, phase=np.pi / 2)
    walls = ed.Wall.polygon(outer) + ed.Wall.polygon(inner)
    # Lattice sites inside the octagon, outside the triangle, clear of every wall.
    g = np.arange(R, L - R, SPACING)
    pts = np.array([(x, y) for x in g for y in g])
    inside = (PolygonPath(outer).contains_points(pts)
              & ~PolygonPath(inner).contains_points(pts)
              & (distance_to_segments(pts, walls) > R + 0.05))
    pos = pts[inside]
    vel = np.tile([1.0, 0.0], (len(pos), 1))  # all to the right, at speed 1
    return ed.Simulation(pos, vel, radii=R, box=ed.Box(L, L, periodic=False), walls=walls)


def direction(sim: ed.Simulation) -> np.ndarray:
    """Direction of each disk's velocity, in (-pi, pi]."""
    v = sim.velocities
    return np.arctan2(v[:, 1], v[:, 0])


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    anim = viz.animate(sim, DURATION, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by=direction, cmap="twilight", vmin=-np.pi, vmax=np.pi,
                       figsize=(4.8, 4.8))
    viz.save(anim, out, dpi=80)
    still = out.with_suffix(".png")
    anim.ax.figure.savefig(still, dpi=100)
    plt.close(anim.ax.figure)
    # Order parameter: length of the mean unit velocity, 1 at the start, ~1/sqrt(N) when
    # the directions are random.
    theta = direction(sim)
    order = np.hypot(np.mean(np.cos(theta)), np.mean(np.sin(theta)))
    print(f"wrote {out} and {still}: {len(sim)} disks, {sim.counts.collisions} disk and "
          f"{sim.counts.wall_collisions} wall collisions; |mean direction| went from 1 "
          f"to {order:.2f} (random directions: about {1 / np.sqrt(len(sim)):.2f})")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "polygon_container.gif")
