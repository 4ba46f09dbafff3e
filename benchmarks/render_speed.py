"""Seconds per frame of edmd2d.viz for gases of 1 000 and 10 000 disks.

Three numbers per size, each the median over the frames of one run:

- ``advance``: ``sim.advance(until=t_k)`` between two frames (the physics, not drawing);
- ``draw``: updating the artists and rendering the figure with Agg (``canvas.draw()``),
  i.e. the cost of one frame without a screen and without encoding;
- ``gif`` / ``mp4``: the wall time between successive frames while ``viz.save`` writes
  the file, i.e. advance + draw + encode.

JIT compilation is warmed up first and not counted.  Run::

    python benchmarks/render_speed.py            # 1000 and 10000 disks, 30 frames each
    python benchmarks/render_speed.py --n 1000 --frames 10
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

PACKING = 0.4
FPS = 30


def make(n: int) -> ed.Simulation:
    return ed.make_gas(n, PACKING, seed=1)


def time_draw(n: int, frames: int) -> tuple[float, float]:
    """Median seconds per frame for advance, and for artist update + Agg render."""
    sim = make(n)
    # blit=False: with blitting the moving artists are "animated" and a plain
    # canvas.draw() would skip them.
    anim = viz.animate(sim, duration=frames / FPS, fps=FPS, blit=False)
    canvas = anim.ax.figure.canvas
    t_adv, t_draw = [], []
    for k in range(len(anim.frame_times)):
        t0 = time.perf_counter()
        sim.advance(until=anim.frame_times[k])
        t1 = time.perf_counter()
        anim.goto_frame(k)  # the simulation is already there: this only updates artists
        canvas.draw()
        t2 = time.perf_counter()
        t_adv.append(t1 - t0)
        t_draw.append(t2 - t1)
    anim._draw_was_started = True  # drawn by hand; silence matplotlib's unused warning
    plt.close(anim.ax.figure)
    return float(np.median(t_adv[1:])), float(np.median(t_draw[1:]))


def time_save(n: int, frames: int, suffix: str) -> tuple[float, float]:
    """Median seconds between frames while saving, and total seconds per frame."""
    sim = make(n)
    anim = viz.animate(sim, duration=frames / FPS, fps=FPS)
    stamps = []
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        viz.save(anim, Path(tmp) / f"bench{suffix}",
                 progress=lambda i, total: stamps.append(time.perf_counter()))
        total = time.perf_counter() - t0
    plt.close(anim.ax.figure)
    return float(np.median(np.diff(stamps))), total / len(anim.frame_times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="+", default=[1000, 10000])
    parser.add_argument("--frames", type=int, default=30)
    args = parser.parse_args()

    t0 = time.perf_counter()
    make(50).advance(until=1.0)  # compile (or load the cached) engine
    print(f"warm-up (JIT compile or cache load): {time.perf_counter() - t0:.1f} s")
    print(f"gas at packing fraction {PACKING}, {FPS} frames per unit time, "
          f"{args.frames} frames, figure 640x640 px (GIFs at their default 480 px), "
          f"matplotlib {matplotlib.__version__}")
    print(f"{'N':>6} {'advance':>9} {'draw':>9} {'gif':>9} {'gif tot':>9} "
          f"{'mp4':>9} {'mp4 tot':>9}   (seconds per frame, median)")
    for n in args.n:
        adv, drw = time_draw(n, args.frames)
        gif, gif_tot = time_save(n, args.frames, ".gif")
        mp4, mp4_tot = time_save(n, args.frames, ".mp4")
        print(f"{n:>6} {adv:>9.4f} {drw:>9.4f} {gif:>9.4f} {gif_tot:>9.4f} "
              f"{mp4:>9.4f} {mp4_tot:>9.4f}")


if __name__ == "__main__":
    main()
