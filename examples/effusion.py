"""Effusion: a gas leaking through a hole in a wall into an empty chamber.

Physics: two square chambers (20 x 20) are joined by a hole in the wall between them.
All 100 disks start in the left chamber; every disk that happens to fly through the hole
crosses over, so the populations even out.  For a dilute gas the one-way flux through an
opening of width w is ``J = n w sqrt(kT / 2 pi m)`` (n: number density), so the
difference between the two populations decays as ``exp(-t / tau)`` with
``tau = A / (2 w sqrt(kT / 2 pi m))``, A the area of one chamber -- effusion (Graham's
law) in two dimensions.  Here the hole is 4 wide but a disk centre passes only through
the middle 3 (the wall's end points are hard corners), the area open to disk centres is
19 x 19, and tau is about 150 time units at kT = 1.  The gas is not quite dilute
(packing fraction 0.2 in the left chamber at the start), and it evens out somewhat
faster than that estimate.  Disks keep a colour from their starting height, so the
mixing stays visible after the numbers have equalized.

Writes an animation (``.gif``, or ``.mp4`` if you name one) and a still (``.png``) with
the fraction of disks in the right chamber against the dilute-gas estimate::

    python examples/effusion.py [examples/output/effusion.gif]
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import edmd2d as ed  # noqa: E402
from edmd2d import viz  # noqa: E402

SEED = 11
SIDE, HOLE, R, KT = 20.0, 4.0, 0.5, 1.0
N_ROWS, N_COLS = 10, 10  # the starting lattice in the left chamber: 100 disks
DURATION, FPS, TIME_PER_SECOND = 300.0, 20, 20.0  # 15 s of video, 301 frames


def build() -> ed.Simulation:
    rng = np.random.default_rng(SEED)
    lo, hi = (SIDE - HOLE) / 2, (SIDE + HOLE) / 2
    divider = [ed.Wall((SIDE, 0.0), (SIDE, lo)), ed.Wall((SIDE, hi), (SIDE, SIDE))]
    # A lattice filling the left chamber, clear of the outer walls and of the divider.
    xs = np.linspace(R + 0.5, SIDE - R - 0.5, N_COLS)
    ys = np.linspace(R + 0.5, SIDE - R - 0.5, N_ROWS)
    pos = np.array([(x, y) for x in xs for y in ys])
    vel = rng.normal(size=pos.shape) * np.sqrt(KT)
    return ed.Simulation(pos, vel, radii=R, box=ed.Box(2 * SIDE, SIDE, periodic=False),
                         walls=divider)


def main(out: Path) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    sim = build()
    n = len(sim)
    kT = sim.kinetic_energy() / n  # the actual temperature of this sample
    start_height = sim.positions[:, 1]  # colour: where each disk started
    times, right = [], []
    bar = viz.TextProgress()

    def record(i, total):  # after each frame: count the disks in the right chamber
        bar(i, total)
        times.append(sim.time)
        right.append(np.count_nonzero(sim.positions[:, 0] > SIDE) / n)

    anim = viz.animate(sim, DURATION, fps=FPS, time_per_second=TIME_PER_SECOND,
                       color_by=start_height, cmap="coolwarm", figsize=(6.4, 3.3))
    viz.save(anim, out, dpi=80, progress=record)

    area, width = (SIDE - 2 * R) ** 2, HOLE - 2 * R
    tau = area / (2 * width * np.sqrt(kT / (2 * np.pi)))
    t = np.asarray(times)
    fig, (ax_box, ax_n) = plt.subplots(1, 2, figsize=(10.0, 3.6),
                                       gridspec_kw={"width_ratios": [1.6, 1]})
    viz.draw(sim, ax=ax_box, color_by=start_height, cmap="coolwarm", show_time=True)
    ax_n.plot(t, right, "C0", label="simulation")
    ax_n.plot(t, 0.5 * (1 - np.exp(-t / tau)), "k--",
              label=rf"dilute-gas estimate, $\tau$ = {tau:.0f}")
    ax_n.set_xlabel("time")
    ax_n.set_ylabel("fraction in the right chamber")
    ax_n.set_ylim(0, 0.6)
    ax_n.legend(frameon=False, loc="lower right")
    fig.tight_layout()
    still = out.with_suffix(".png")
    fig.savefig(still, dpi=80)
    plt.close(fig)
    plt.close(anim.ax.figure)
    estimate = 0.5 * (1 - np.exp(-sim.time / tau))
    print(f"wrote {out} and {still}: after t = {sim.time:g}, {right[-1]:.0%} of the disks "
          f"are in the right chamber (dilute-gas estimate: {estimate:.0%})")


if __name__ == "__main__":
    import _cli  # (examples/_cli.py: the gallery's shared command line)

    _cli.run(globals(), "effusion.gif")
